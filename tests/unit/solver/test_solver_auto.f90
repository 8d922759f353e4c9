!> `--solver auto` resolved by vemcontact_solver_factory's auto_solver: on one process
!> cholmod below the measured crossover auto_gamg_unknowns or with contact pairs, gamg
!> from it on without contact for a compressible material; gamg on several processes
!> whatever the size.
program test_solver_auto
   use vemcontact_kinds, only: wp, i8
   use vemcontact_solver_factory, only: auto_solver, auto_gamg_unknowns, auto_gamg_poisson, solver_cholmod, solver_gamg
   use vemcontact_testing, only: checker_t
   implicit none

   type(checker_t) :: t
   real(wp), parameter :: nu = 0.3_wp

   ! the threshold is the crossover measured between 1e5 and 2e5 unknowns on the
   ! peers' Voronoi cantilever (bench/results/peers_solvers_*.csv)
   call t%check(auto_gamg_unknowns > 100004_i8 .and. auto_gamg_unknowns <= 200004_i8, 'threshold in the measured range')
   call t%equal(auto_solver(2_i8, 1, .false., nu), solver_cholmod, 'tiny model: cholmod')
   call t%equal(auto_solver(100000_i8, 1, .false., nu), solver_cholmod, '1e5 unknowns: cholmod')
   call t%equal(auto_solver(auto_gamg_unknowns - 1, 1, .false., nu), solver_cholmod, 'just below the threshold: cholmod')
   call t%equal(auto_solver(auto_gamg_unknowns, 1, .false., nu), solver_gamg, 'at the threshold: gamg')
   call t%equal(auto_solver(400004_i8, 1, .false., nu), solver_gamg, "the peers' 4e5 unknowns: gamg")
   call t%equal(auto_solver(10000000000_i8, 1, .false., nu), solver_gamg, '1e10 unknowns (beyond int32): gamg')
   call t%equal(auto_solver(2_i8, 2, .false., nu), solver_gamg, 'two processes: gamg')
   ! with contact pairs one process stays cholmod at every size (the contact iteration's
   ! many solves), several processes take gamg
   call t%equal(auto_solver(auto_gamg_unknowns, 1, .true., nu), solver_cholmod, 'contact at the threshold: cholmod')
   call t%equal(auto_solver(10000000000_i8, 1, .true., nu), solver_cholmod, 'contact, 1e10 unknowns: cholmod')
   call t%equal(auto_solver(2_i8, 2, .true., nu), solver_gamg, 'contact, two processes: gamg')
   ! nearly incompressible plane strain: CG's iterations grow (646 at nu = 0.4999 against
   ! 23 at 0.3 on the peers' cantilever), so one process stays cholmod; several take gamg
   call t%check(auto_gamg_poisson >= 0.45_wp .and. auto_gamg_poisson < 0.49_wp, 'Poisson limit in the measured range')
   call t%equal(auto_solver(400004_i8, 1, .false., auto_gamg_poisson), solver_gamg, 'at the Poisson limit: gamg')
   call t%equal(auto_solver(400004_i8, 1, .false., 0.4999_wp), solver_cholmod, 'nu = 0.4999: cholmod')
   call t%equal(auto_solver(10000000000_i8, 1, .false., 0.49_wp), solver_cholmod, 'nu = 0.49, 1e10 unknowns: cholmod')
   call t%equal(auto_solver(2_i8, 2, .false., 0.4999_wp), solver_gamg, 'nu = 0.4999, two processes: gamg')
   call t%finish()
end program test_solver_auto
