!> Stopping a run on SIGINT (Ctrl-C) or SIGTERM: the C handler (interrupt_shim.c)
!> only records the signal; the analysis asks `stop_signal` at safe points and, when
!> a signal came, ends through its error object with `interrupt_error`, whose code
!> 128 + the signal number (130 for SIGINT, 143 for SIGTERM, the shell's convention)
!> becomes the exit status.  The results of the completed steps are then closed as
!> for a failed run, marked interrupted (docs/output-format.md).
module vemcontact_interrupt
   use, intrinsic :: iso_c_binding, only: c_int
   use vemcontact_error, only: error_t, fatal_error
   implicit none
   private

   public :: install_interrupt_handlers, stop_signal, interrupt_error, interrupt_context, is_interrupt, signal_name, &
      sigint_number, sigterm_number

   !> Error codes of an interrupted run are err_interrupt_base + the signal number.
   integer, parameter, public :: err_interrupt_base = 128

   interface
      function c_install() result(rc) bind(C, name='vc_interrupt_install')
         import :: c_int
         integer(c_int) :: rc
      end function c_install
      function c_signal() result(s) bind(C, name='vc_interrupt_signal')
         import :: c_int
         integer(c_int) :: s
      end function c_signal
      function c_sigint() result(s) bind(C, name='vc_interrupt_sigint')
         import :: c_int
         integer(c_int) :: s
      end function c_sigint
      function c_sigterm() result(s) bind(C, name='vc_interrupt_sigterm')
         import :: c_int
         integer(c_int) :: s
      end function c_sigterm
   end interface

contains

   !> Catch SIGINT and SIGTERM from now on (a second one ends the process at once).
   subroutine install_interrupt_handlers()
      integer(c_int) :: rc
      rc = c_install()
   end subroutine install_interrupt_handlers

   !> The signal that asks this process to stop (SIGINT or SIGTERM), 0 if none came.
   integer function stop_signal()
      stop_signal = int(c_signal())
   end function stop_signal

   !> The error that ends a run interrupted by `signo` at `where` ("before contact
   !> iteration 4"); the driver adds the step and what was kept (`interrupt_context`).
   subroutine interrupt_error(signo, where, error)
      integer, intent(in) :: signo
      character(len=*), intent(in) :: where
      type(error_t), allocatable, intent(out) :: error
      call fatal_error(error, 'interrupted by '//signal_name(signo)//' '//where, err_interrupt_base + signo)
   end subroutine interrupt_error

   !> Add to an interruption's message the step it came in (`step`: "in step 3
   !> (Step-3)", '' between steps) and the number `done` of steps complete in every
   !> results file.
   subroutine interrupt_context(error, step, done)
      type(error_t), intent(inout) :: error
      character(len=*), intent(in) :: step
      integer, intent(in) :: done
      character(len=24) :: b
      character(len=:), allocatable :: kept
      write (b, '(i0)') done
      if (done == 0) then
         kept = 'no step was complete'
      else if (done == 1) then
         kept = 'step 1 is complete in the results files'
      else
         kept = 'steps 1 to '//trim(b)//' are complete in the results files'
      end if
      if (len(step) > 0) error%message = error%message//' '//step
      error%message = error%message//': '//kept
   end subroutine interrupt_context

   !> Whether an error code is that of an interrupted run.
   pure logical function is_interrupt(code)
      integer, intent(in) :: code
      is_interrupt = code > err_interrupt_base .and. code < err_interrupt_base + 64
   end function is_interrupt

   !> The number of SIGINT on this system.
   integer function sigint_number()
      sigint_number = int(c_sigint())
   end function sigint_number

   !> The number of SIGTERM on this system.
   integer function sigterm_number()
      sigterm_number = int(c_sigterm())
   end function sigterm_number

   !> "SIGINT", "SIGTERM" or "signal N".
   function signal_name(signo) result(s)
      integer, intent(in) :: signo
      character(len=:), allocatable :: s
      character(len=16) :: b
      if (signo == int(c_sigint())) then
         s = 'SIGINT'
      else if (signo == int(c_sigterm())) then
         s = 'SIGTERM'
      else
         write (b, '(a,i0)') 'signal ', signo
         s = trim(b)
      end if
   end function signal_name
end module vemcontact_interrupt
