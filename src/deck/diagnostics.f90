!> Collects the error messages of a deck so that all problems are reported in one run.
!> Messages follow fpm/rustc:
!>
!>     path/deck.inp:12: error: unknown keyword *FOO
!>        12 | *FOO, BAR=1
!>        = help: did you mean *NODE?
!>
!> After `limit` messages further errors are only counted.
module vemcontact_deck_diagnostics
   use vemcontact_error, only: error_t, append_message, err_input
   use vemcontact_deck_fields, only: int_str
   implicit none
   private

   public :: diag_t

   !> Longest quoted source text; longer lines (continued polygons) are cut.
   integer, parameter :: max_quote = 160

   type :: diag_t
      type(error_t), allocatable :: error
      integer :: count = 0
      integer :: limit = 50
   contains
      procedure :: report
      procedure :: finish
   end type diag_t

contains

   !> Record one error.  `line` = 0 omits the line number; `text` is the offending
   !> source line (omitted when empty); `help` an optional hint.
   subroutine report(self, path, line, message, text, help, code)
      class(diag_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      integer, intent(in) :: line
      character(len=*), intent(in) :: message
      character(len=*), intent(in), optional :: text, help
      integer, intent(in), optional :: code
      character(len=:), allocatable :: msg, num
      integer :: icode
      self%count = self%count + 1
      if (self%count > self%limit) return
      icode = err_input
      if (present(code)) icode = code
      if (line > 0) then
         num = int_str(line)
         msg = path//':'//num//': error: '//message
         if (present(text)) then
            if (len(text) > 0) then
               if (len(text) > max_quote) then
                  msg = msg//new_line('a')//repeat(' ', max(0, 5 - len(num)))//num//' | ' &
                        //text(1:max_quote)//' ...'
               else
                  msg = msg//new_line('a')//repeat(' ', max(0, 5 - len(num)))//num//' | '//text
               end if
            end if
         end if
      else
         msg = path//': error: '//message
      end if
      if (present(help)) then
         if (len(help) > 0) msg = msg//new_line('a')//'   = help: '//help
      end if
      call append_message(self%error, msg, icode)
   end subroutine report

   !> Hand the collected messages over (with a count of those not shown); `error`
   !> stays unallocated when nothing was reported.
   subroutine finish(self, error)
      class(diag_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: error
      if (self%count == 0) return
      if (self%count > self%limit) then
         call append_message(self%error, '... and '//int_str(self%count - self%limit)// &
                             ' more errors not shown')
      end if
      if (self%count > 1) then
         call append_message(self%error, 'error: the deck has '//int_str(self%count)//' errors')
      end if
      call move_alloc(self%error, error)
   end subroutine finish
end module vemcontact_deck_diagnostics
