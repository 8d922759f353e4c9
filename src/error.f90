!> Error object passed back to the caller instead of stopping.
!> The convention (as in test-drive, tblite): a procedure that can fail takes
!> `type(error_t), allocatable, intent(out) :: error`; on return the error is
!> allocated exactly when something went wrong.  Only the main program stops.
module vemcontact_error
   implicit none
   private

   public :: error_t, fatal_error, append_message

   !> Error categories; the program's exit status is derived from them.
   integer, parameter, public :: err_input = 1    !< bad deck or command line
   integer, parameter, public :: err_io = 2       !< file cannot be read or written
   integer, parameter, public :: err_model = 3    !< model not solvable (floating part, ...)
   integer, parameter, public :: err_solver = 4   !< factorization / convergence failure
   integer, parameter, public :: err_internal = 5 !< a bug: should never be seen by users

   !> An error: category code and human-readable message (may hold several lines).
   type :: error_t
      integer :: code = err_internal
      character(len=:), allocatable :: message
   end type error_t

contains

   !> Allocate `error` with a message and an optional category (default err_input).
   pure subroutine fatal_error(error, message, code)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), intent(in) :: message
      integer, intent(in), optional :: code
      allocate (error)
      error%message = message
      error%code = err_input
      if (present(code)) error%code = code
   end subroutine fatal_error

   !> Add a line to an error, creating it if needed; lets a reader report all problems at once.
   pure subroutine append_message(error, message, code)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: message
      integer, intent(in), optional :: code
      if (.not. allocated(error)) then
         allocate (error)
         error%message = message
         error%code = err_input
         if (present(code)) error%code = code
      else
         error%message = error%message//new_line('a')//message
      end if
   end subroutine append_message
end module vemcontact_error
