!> `--solver auto` resolved by vemcontact_solver_factory's auto_solver: on one process
!> cholmod below the measured crossover auto_gamg_unknowns or with contact pairs, gamg
!> from it on without contact; gamg on several processes whatever the size.
program test_solver_auto
   use vemcontact_kinds, only: i8
   use vemcontact_solver_factory, only: auto_solver, auto_gamg_unknowns, solver_cholmod, solver_gamg
   use vemcontact_testing, only: checker_t
   implicit none

   type(checker_t) :: t

   ! the threshold is the crossover measured between 1e5 and 2e5 unknowns on the
   ! peers' Voronoi cantilever (bench/results/peers_solvers_*.csv)
   call t%check(auto_gamg_unknowns > 100004_i8 .and. auto_gamg_unknowns <= 200004_i8, 'threshold in the measured range')
   call t%equal(auto_solver(2_i8, 1, .false.), solver_cholmod, 'tiny model: cholmod')
   call t%equal(auto_solver(100000_i8, 1, .false.), solver_cholmod, '1e5 unknowns: cholmod')
   call t%equal(auto_solver(auto_gamg_unknowns - 1, 1, .false.), solver_cholmod, 'just below the threshold: cholmod')
   call t%equal(auto_solver(auto_gamg_unknowns, 1, .false.), solver_gamg, 'at the threshold: gamg')
   call t%equal(auto_solver(400004_i8, 1, .false.), solver_gamg, "the peers' 4e5 unknowns: gamg")
   call t%equal(auto_solver(10000000000_i8, 1, .false.), solver_gamg, '1e10 unknowns (beyond int32): gamg')
   call t%equal(auto_solver(2_i8, 2, .false.), solver_gamg, 'two processes: gamg')
   ! with contact pairs one process stays cholmod at every size (the contact iteration's
   ! many solves), several processes take gamg
   call t%equal(auto_solver(auto_gamg_unknowns, 1, .true.), solver_cholmod, 'contact at the threshold: cholmod')
   call t%equal(auto_solver(10000000000_i8, 1, .true.), solver_cholmod, 'contact, 1e10 unknowns: cholmod')
   call t%equal(auto_solver(2_i8, 2, .true.), solver_gamg, 'contact, two processes: gamg')
   call t%finish()
end program test_solver_auto
