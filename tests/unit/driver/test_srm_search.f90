!> The search rules of a strength reduction step (vemcontact_driver_srm_search)
!> against a synthetic limit: a trial converges when F <= f_star.  The answers are
!> exact consequences of the rules (bracket by doubling or probes around an estimate,
!> galloping, arithmetic bisection).
program test_srm_search
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_driver_srm_search, only: srm_search_t, srm_found, srm_slides, srm_unbounded
   implicit none
   type(checker_t) :: t
   type(srm_search_t) :: s, a, b
   real(wp) :: w1, w2
   real(wp), parameter :: miss(4) = [0.97_wp, 1.03_wp, 0.6_wp, 1.4_wp]
   integer :: k

   ! the limit lies in every final bracket, whose relative width is within the tolerance
   s = search(1.37_wp, 1.5_wp, 100.0_wp, 1.0e-3_wp)
   call t%check(s%phase == srm_found, 'f* = 1.37: found')
   call t%check(s%f_ok <= 1.37_wp .and. s%f_fail > 1.37_wp, 'f* = 1.37 within [F_ok, F_fail)')
   call t%check((s%f_fail - s%f_ok) <= 1.0e-3_wp*s%f_ok, 'f* = 1.37: bracket within the tolerance')
   ! trials: F = 1, 1.5 (fails), then log2(0.5/1e-3) rounded up = 9 bisections
   call t%check(s%trials == 11, 'f* = 1.37: 11 trials')

   ! repeatability: another first trial and largest factor give the same factor to the tolerance
   a = search(3.21_wp, 1.5_wp, 100.0_wp, 1.0e-3_wp)
   b = search(3.21_wp, 2.7_wp, 40.0_wp, 1.0e-3_wp)
   call t%check(a%phase == srm_found .and. b%phase == srm_found, 'f* = 3.21: found from both brackets')
   call t%check(abs(a%f_ok - b%f_ok) <= 1.0e-3_wp*3.21_wp, 'f* = 3.21: same factor within the tolerance')
   call t%check(a%trials <= 30 .and. b%trials <= 30, 'at most 30 trials to 1e-3')

   ! halving the tolerance halves the final bracket: each bisection halves it, so the
   ! final relative width lies in (tol/2, tol] and the halved one in (tol/4, tol/2]
   do k = 1, 5
      a = search(1.0_wp + 0.731_wp*k, 1.5_wp, 100.0_wp, 1.0e-3_wp)
      b = search(1.0_wp + 0.731_wp*k, 1.5_wp, 100.0_wp, 0.5e-3_wp)
      w1 = (a%f_fail - a%f_ok)
      w2 = (b%f_fail - b%f_ok)
      ! the same first bracket: the halved tolerance takes exactly one bisection more
      call t%close(w2, 0.5_wp*w1, 1.0e-12_wp, 'halved tolerance, halved bracket')
      call t%check(b%trials == a%trials + 1, 'halved tolerance: one trial more')
   end do

   ! with an exact estimate: two probes close the bracket (three trials in all), within
   ! the tolerance, around the limit; halving the tolerance halves the bracket
   a = search(2.3982_wp, 1.5_wp, 100.0_wp, 1.0e-3_wp, 2.3982_wp)
   b = search(2.3982_wp, 1.5_wp, 100.0_wp, 0.5e-3_wp, 2.3982_wp)
   call t%check(a%phase == srm_found .and. a%trials == 3 .and. b%trials == 3, 'exact estimate: 3 trials')
   call t%check(a%f_ok <= 2.3982_wp .and. a%f_fail > 2.3982_wp, 'exact estimate: the limit in the bracket')
   call t%check((a%f_fail - a%f_ok) <= 1.0e-3_wp*a%f_ok, 'exact estimate: within the tolerance')
   ! widths 0.8 tol F_est: the ratio is exactly 1/2
   call t%close(b%f_fail - b%f_ok, 0.5_wp*(a%f_fail - a%f_ok), 1.0e-12_wp, 'exact estimate: halved bracket')
   ! estimates that miss by 3 % and 40 %, low and high: the same factor within the
   ! tolerance as the doubling bracket, in fewer trials than it for small misses
   s = search(2.3982_wp, 1.5_wp, 100.0_wp, 1.0e-3_wp)
   do k = 1, 4
      a = search(2.3982_wp, 1.5_wp, 100.0_wp, 1.0e-3_wp, 2.3982_wp*miss(k))
      call t%check(a%phase == srm_found .and. a%f_ok <= 2.3982_wp .and. a%f_fail > 2.3982_wp, &
                   'missed estimate: the limit in the bracket')
      call t%check((a%f_fail - a%f_ok) <= 1.0e-3_wp*a%f_ok, 'missed estimate: within the tolerance')
      call t%check(abs(a%f_ok - s%f_ok) <= 1.0e-3_wp*2.3982_wp, 'missed estimate: the factor of the bracket')
      if (k <= 2) call t%check(a%trials < s%trials, 'a 3 % miss: fewer trials than doubling')
      call t%check(a%trials <= 30, 'missed estimate: at most 30 trials')
   end do
   ! an estimate within the tolerance of 1: the probe below is skipped
   a = search(1.0002_wp, 1.5_wp, 100.0_wp, 1.0e-3_wp, 1.0002_wp)
   call t%check(a%phase == srm_found .and. a%f_ok >= 1.0_wp .and. a%f_fail > 1.0002_wp, 'estimate near 1')

   ! no equilibrium at F = 1: the bodies slide, after one trial
   s = search(0.9_wp, 1.5_wp, 100.0_wp, 1.0e-3_wp)
   call t%check(s%phase == srm_slides .and. s%trials == 1, 'f* < 1: slides after one trial')

   ! equilibrium up to the largest factor: 1, 1.5, 3, 6, 10
   s = search(50.0_wp, 1.5_wp, 10.0_wp, 1.0e-3_wp)
   call t%check(s%phase == srm_unbounded .and. s%trials == 5, 'f* > largest: unbounded after 5 trials')
   call t%close(s%f_ok, 10.0_wp, 1.0e-15_wp, 'unbounded: F_ok is the largest factor')

   ! the largest factor fails: bisection below it
   s = search(7.0_wp, 1.5_wp, 10.0_wp, 1.0e-3_wp)
   call t%check(s%phase == srm_found .and. s%f_ok <= 7.0_wp .and. s%f_fail > 7.0_wp, 'f* = 7 < largest 10')
   call t%finish()
contains
   !> The whole search against the limit f_star.
   function search(f_star, first, largest, tol, estimate) result(st)
      real(wp), intent(in) :: f_star, first, largest, tol
      real(wp), intent(in), optional :: estimate
      type(srm_search_t) :: st
      real(wp) :: f
      st = srm_search_t(tolerance=tol, f_first=first, f_max=largest)
      do while (.not. st%done())
         f = st%next_factor()
         ! the driver sets the estimate after the trial at F = 1
         if (st%trials == 0 .and. present(estimate)) st%estimate = estimate
         call st%record(f, f <= f_star)
         if (st%trials > 100) exit
      end do
   end function search
end program test_srm_search
