!> The automatic BLAS thread count: the cores left idle by the load average, at
!> least one, at most the cores (docs/performance.md, "BLAS threads").
program test_blas_threads
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_app_blas_threads, only: auto_blas_threads
   implicit none
   type(checker_t) :: t
   call t%equal(auto_blas_threads(2, 0.05_wp), 2, 'idle 2-core machine: both cores')
   call t%equal(auto_blas_threads(2, 0.6_wp), 1, 'one core mostly busy: one thread')
   call t%equal(auto_blas_threads(2, 1.2_wp), 1, 'one core busy: one thread')
   call t%equal(auto_blas_threads(2, 9.0_wp), 1, 'overloaded: still one thread')
   call t%equal(auto_blas_threads(8, 2.4_wp), 6, '8 cores, load 2.4: the 6 idle ones')
   call t%equal(auto_blas_threads(8, 0.0_wp), 8, 'idle: all cores')
   call t%equal(auto_blas_threads(4, -1.0_wp), 4, 'load unknown: all cores (OpenBLAS''s own default)')
   call t%equal(auto_blas_threads(0, -1.0_wp), 1, 'at least one thread')
   call t%finish()
end program test_blas_threads
