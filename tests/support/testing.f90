!> Minimal assertion module for vemcontact's test programs (pFUnit is not
!> available from the package registries we can reach).  A test program keeps a
!> `checker_t`, calls its checks, and ends with `call t%finish()`, which prints
!> "N passed, N failed" and stops with a non-zero status if any check failed.
module vemcontact_testing
   use vemcontact_kinds, only: wp
   use, intrinsic :: iso_fortran_env, only: output_unit
   implicit none
   private

   public :: checker_t

   type :: checker_t
      integer :: npass = 0
      integer :: nfail = 0
   contains
      procedure :: check => check_true
      procedure :: close => check_close
      procedure :: equal => check_equal_int
      procedure :: finish
   end type checker_t

contains

   !> Pass when `cond` is true.
   subroutine check_true(self, cond, what)
      class(checker_t), intent(inout) :: self
      logical, intent(in) :: cond
      character(len=*), intent(in) :: what
      if (cond) then
         self%npass = self%npass + 1
      else
         self%nfail = self%nfail + 1
         write (output_unit, '(a)') 'FAIL: '//what
      end if
   end subroutine check_true

   !> Pass when |actual - expected| <= max(atol, rtol*|expected|); NaN always fails.
   subroutine check_close(self, actual, expected, rtol, what, atol)
      class(checker_t), intent(inout) :: self
      real(wp), intent(in) :: actual, expected, rtol
      character(len=*), intent(in) :: what
      real(wp), intent(in), optional :: atol
      real(wp) :: tol
      tol = rtol*abs(expected)
      if (present(atol)) tol = max(tol, atol)
      if (abs(actual - expected) <= tol) then
         self%npass = self%npass + 1
      else
         self%nfail = self%nfail + 1
         write (output_unit, '(a,es24.16,a,es24.16,a,es10.3)') 'FAIL: '//what//': got ', actual, &
            ' expected ', expected, ' tol ', tol
      end if
   end subroutine check_close

   !> Pass when two integers are equal.
   subroutine check_equal_int(self, actual, expected, what)
      class(checker_t), intent(inout) :: self
      integer, intent(in) :: actual, expected
      character(len=*), intent(in) :: what
      if (actual == expected) then
         self%npass = self%npass + 1
      else
         self%nfail = self%nfail + 1
         write (output_unit, '(a,i0,a,i0)') 'FAIL: '//what//': got ', actual, ' expected ', expected
      end if
   end subroutine check_equal_int

   !> Print the summary line and stop non-zero on any failure (or if nothing was checked).
   subroutine finish(self)
      class(checker_t), intent(in) :: self
      write (output_unit, '(i0,a,i0,a)') self%npass, ' passed, ', self%nfail, ' failed'
      if (self%nfail > 0) error stop 1
      if (self%npass == 0) error stop 2
   end subroutine finish
end module vemcontact_testing
