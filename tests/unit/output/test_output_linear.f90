!> The cost of a run's output is linear in its number of steps (issue 25): the driver
!> rewrites the .pvd (and flushes JOB.h5), each costing O(entries so far), only when
!> pvd_rewrite_due says so.  Counted here, not timed: over N steps the entries
!> written in all stay below 2N (a rewrite after every step wrote N(N+1)/2: 2 001 000
!> for N = 2000), and the number of rewrites grows like log2 N.
program test_output_linear
   use vemcontact_testing, only: checker_t
   use vemcontact_output_pvd, only: pvd_rewrite_due
   implicit none
   type(checker_t) :: t
   integer, parameter :: sizes(3) = [200, 2000, 100000]
   integer :: k, n, i, rewrites
   integer(8) :: written
   do k = 1, size(sizes)
      n = sizes(k)
      written = 0
      rewrites = 0
      do i = 1, n
         ! the driver writes when due and after the last step
         if (pvd_rewrite_due(i) .or. i == n) then
            written = written + i
            rewrites = rewrites + 1
         end if
      end do
      call t%check(written < 3_8*n, 'entries written over the run below 3 N (linear)')
      call t%check(rewrites <= ceiling(log(real(n))/log(2.0)) + 2, 'rewrites grow like log2 N')
      print '(a,i0,a,i0,a,i0,a)', 'N = ', n, ': ', written, ' entries written in ', rewrites, ' rewrites'
   end do
   call t%check(pvd_rewrite_due(1) .and. pvd_rewrite_due(2) .and. pvd_rewrite_due(1024), 'due at powers of two')
   call t%check(.not. (pvd_rewrite_due(0) .or. pvd_rewrite_due(3) .or. pvd_rewrite_due(1000)), &
                'not due between them')
   call t%finish()
end program test_output_linear
