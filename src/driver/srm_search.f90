!> The search of a strength reduction step for the largest factor F at which
!> equilibrium still exists, as pure rules on a small state (unit-tested by
!> tests/unit/driver/test_srm_search.f90), apart from the solves that answer them
!> (vemcontact_driver_strength_reduction).
!>
!> The first trial is F = 1, the strengths as given: if it fails the bodies slide
!> and the search ends.  Then the bracket: the first trial factor, then twice the
!> last converged factor (never beyond the largest factor) until a trial fails; then
!> bisection of [F_ok, F_fail] until (F_fail - F_ok)/F_ok <= tolerance.  The midpoint
!> is arithmetic, so each bisection halves the bracket and the final bracket lies in
!> (tolerance/2, tolerance] of F_ok (a bracket already within the tolerance ends the
!> search at once).  Whether equilibrium exists is taken as monotone in F: every
!> trial converged below F_ok and failed above F_fail.
module vemcontact_driver_srm_search
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: srm_search_t

   !> Search phases
   integer, parameter, public :: srm_at_one = 0     !< the trial at F = 1 is next
   integer, parameter, public :: srm_bracket = 1    !< growing F until a trial fails
   integer, parameter, public :: srm_bisect = 2     !< halving [F_ok, F_fail]
   integer, parameter, public :: srm_found = 3      !< F_ok and F_fail within the tolerance
   integer, parameter, public :: srm_slides = 4     !< no equilibrium at F = 1
   integer, parameter, public :: srm_unbounded = 5  !< equilibrium up to the largest factor
   !> the bracket's growth factor: doubling reaches any factor up to 100 from 1.5 in
   !> at most 7 trials and leaves a bracket of relative width 1, 10 bisections from 1e-3
   real(wp), parameter, public :: srm_growth = 2.0_wp

   type :: srm_search_t
      real(wp) :: tolerance = 1.0e-3_wp
      real(wp) :: f_first = 1.5_wp
      real(wp) :: f_max = 100.0_wp
      integer :: phase = srm_at_one
      real(wp) :: f_ok = 0.0_wp      !< the largest factor that converged (0: none yet)
      real(wp) :: f_fail = 0.0_wp    !< the smallest factor that failed (0: none yet)
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
      if (self%f_fail > 0.0_wp) then
         self%phase = srm_bisect
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
