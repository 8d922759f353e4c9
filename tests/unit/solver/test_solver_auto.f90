!> `--solver auto` resolved by vemcontact_solver_factory's auto_solver: cholmod below
!> the measured crossover auto_gamg_unknowns on one process, gamg from it on and on
!> several processes whatever the size.
program test_solver_auto
   use vemcontact_kinds, only: i8
   use vemcontact_solver_factory, only: auto_solver, auto_gamg_unknowns, solver_cholmod, solver_gamg
   use vemcontact_testing, only: checker_t
   implicit none

   type(checker_t) :: t

   ! the threshold is the crossover measured between 1e5 and 2e5 unknowns on the
   ! peers' Voronoi cantilever (bench/results/peers_solvers_*.csv)
   call t%check(auto_gamg_unknowns > 100004_i8 .and. auto_gamg_unknowns <= 200004_i8, 'threshold in the measured range')
   call t%equal(auto_solver(2_i8, 1), solver_cholmod, 'tiny model: cholmod')
   call t%equal(auto_solver(100000_i8, 1), solver_cholmod, '1e5 unknowns: cholmod')
   call t%equal(auto_solver(auto_gamg_unknowns - 1, 1), solver_cholmod, 'just below the threshold: cholmod')
   call t%equal(auto_solver(auto_gamg_unknowns, 1), solver_gamg, 'at the threshold: gamg')
   call t%equal(auto_solver(400004_i8, 1), solver_gamg, "the peers' 4e5 unknowns: gamg")
   call t%equal(auto_solver(10000000000_i8, 1), solver_gamg, '1e10 unknowns (beyond int32): gamg')
   call t%equal(auto_solver(2_i8, 2), solver_gamg, 'two processes: gamg')
   call t%finish()
end program test_solver_auto
