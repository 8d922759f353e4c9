!> The search of a strength reduction step for the largest factor F at which
!> equilibrium still exists, as pure rules on a small state (unit-tested by
!> tests/unit/driver/test_srm_search.f90), apart from the solves that answer them
!> (vemcontact_driver_strength_reduction).
!>
!> The first trial is F = 1, the strengths as given: if it fails the bodies slide and
!> the search ends.  Then, with an estimate F_est of the factor (the driver's
!> mobilized-strength ratio of the trial at F = 1, exact for one planar joint), two
!> probes F_est (1 -+ 0.4 tolerance): when the first holds and the second fails the
!> bracket is already within the tolerance.  A probe that misses gallops away from it
!> (steps 4 tolerance, doubled after each trial that does not close the bracket)
!> until a trial closes it.  Without an estimate (or with the first trial factor given
!> on the data line) the bracket grows from the first trial factor by doubling.  A
!> bracket [F_ok, F_fail] wider than the tolerance is then bisected until
!> (F_fail - F_ok)/F_ok <= tolerance; the midpoint is arithmetic, so each bisection
!> halves the bracket.  Whether equilibrium exists is taken as monotone in F: every
!> trial converges below F_ok and fails above F_fail.
module vemcontact_driver_srm_search
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: srm_search_t

   !> Search phases
   integer, parameter, public :: srm_at_one = 0      !< the trial at F = 1 is next
   integer, parameter, public :: srm_bracket = 1     !< growing F by doubling until a trial fails
   integer, parameter, public :: srm_bisect = 2      !< halving [F_ok, F_fail]
   integer, parameter, public :: srm_probe_low = 3   !< the probe just below the estimate
   integer, parameter, public :: srm_probe_high = 4  !< the probe just above it
   integer, parameter, public :: srm_gallop_up = 5   !< the estimate was low: growing steps up
   integer, parameter, public :: srm_gallop_down = 6 !< it was high: growing steps down
   integer, parameter, public :: srm_found = 7       !< F_ok and F_fail within the tolerance
   integer, parameter, public :: srm_slides = 8      !< no equilibrium at F = 1
   integer, parameter, public :: srm_unbounded = 9   !< equilibrium up to the largest factor
   !> the bracket's growth factor from the first trial: doubling reaches any factor up to
   !> 100 from 1.5 in at most 7 trials and leaves a bracket of relative width 1
   real(wp), parameter, public :: srm_growth = 2.0_wp
   !> the probes lie at F_est (1 -+ probe tolerance): their bracket, 0.8 tolerance
   !> F_est wide, is within the tolerance of the lower one for every tolerance < 0.5
   real(wp), parameter :: probe = 0.4_wp
   !> the first gallop step, in tolerances: a few probe widths
   real(wp), parameter :: gallop = 4.0_wp

   type :: srm_search_t
      real(wp) :: tolerance = 1.0e-3_wp
      real(wp) :: f_first = 1.5_wp
      real(wp) :: f_max = 100.0_wp
      !> the estimate of the factor after the trial at F = 1 (0: none, the bracket by doubling)
      real(wp) :: estimate = 0.0_wp
      integer :: phase = srm_at_one
      real(wp) :: f_ok = 0.0_wp      !< the largest factor that converged (0: none yet)
      real(wp) :: f_fail = 0.0_wp    !< the smallest factor that failed (0: none yet)
      real(wp) :: step = 0.0_wp      !< the relative gallop step
      integer :: trials = 0
   contains
      procedure :: next_factor
      procedure :: record
      procedure :: done
   end type srm_search_t

contains

   !> The factor of the next trial.
   pure real(wp) function next_factor(self) result(f)
      class(srm_search_t), intent(in) :: self
      select case (self%phase)
      case (srm_at_one)
         f = 1.0_wp
      case (srm_bracket)
         if (self%f_ok <= 1.0_wp) then
            f = self%f_first
         else
            f = min(srm_growth*self%f_ok, self%f_max)
         end if
      case (srm_probe_low)
         f = self%estimate*(1.0_wp - probe*self%tolerance)
      case (srm_probe_high)
         f = min(self%estimate*(1.0_wp + probe*self%tolerance), self%f_max)
      case (srm_gallop_up)
         f = min(self%f_ok*(1.0_wp + self%step), self%f_max)
      case (srm_gallop_down)
         f = self%f_fail/(1.0_wp + self%step)
         if (f <= self%f_ok) f = 0.5_wp*(self%f_ok + self%f_fail)
      case (srm_bisect)
         f = 0.5_wp*(self%f_ok + self%f_fail)
      case default
         f = self%f_ok
      end select
   end function next_factor

   !> The outcome of the trial at factor f.
   pure subroutine record(self, f, converged)
      class(srm_search_t), intent(inout) :: self
      real(wp), intent(in) :: f
      logical, intent(in) :: converged
      self%trials = self%trials + 1
      if (self%phase == srm_at_one) then
         if (converged) then
            self%f_ok = f
            self%phase = srm_bracket
            if (self%estimate > 1.0_wp) then
               self%phase = srm_probe_low
               ! a factor within the tolerance of 1: the probe below would repeat F = 1
               if (self%estimate*(1.0_wp - probe*self%tolerance) <= f) self%phase = srm_probe_high
            end if
         else
            self%f_fail = f
            self%phase = srm_slides
         end if
         return
      end if
      if (converged) then
         self%f_ok = max(self%f_ok, f)
      else if (self%f_fail > 0.0_wp) then
         self%f_fail = min(self%f_fail, f)
      else
         self%f_fail = f
      end if
      select case (self%phase)
      case (srm_probe_low)
         if (converged) then
            self%phase = srm_probe_high
         else
            self%phase = srm_gallop_down
            self%step = gallop*self%tolerance
         end if
      case (srm_probe_high)
         if (converged) then
            self%phase = srm_gallop_up
            self%step = gallop*self%tolerance
         else
            self%phase = srm_bisect
         end if
      case (srm_gallop_up)
         if (converged) then
            self%step = 2.0_wp*self%step
         else
            self%phase = srm_bisect
         end if
      case (srm_gallop_down)
         if (converged) then
            self%phase = srm_bisect
         else
            self%step = 2.0_wp*self%step
         end if
      case (srm_bracket)
         if (.not. converged) self%phase = srm_bisect
      end select
      if (self%f_fail > 0.0_wp) then
         if ((self%f_fail - self%f_ok) <= self%tolerance*self%f_ok) self%phase = srm_found
      else if (self%f_ok >= self%f_max) then
         self%phase = srm_unbounded
      end if
   end subroutine record

   !> Whether the search has ended (found, slides or unbounded).
   pure logical function done(self)
      class(srm_search_t), intent(in) :: self
      done = self%phase >= srm_found
   end function done
end module vemcontact_driver_srm_search
