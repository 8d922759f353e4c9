!> Run log: every line goes to the screen and to JOB.log; phase timings use the
!> wall clock so that they add up to what the user waits for.
module vemcontact_log
   use vemcontact_kinds, only: wp
   use vemcontact_clock, only: wall_time
   use vemcontact_error, only: error_t, fatal_error, err_io
   use, intrinsic :: iso_fortran_env, only: output_unit
   implicit none
   private

   public :: logger_t, wall_time

   type :: logger_t
      integer :: unit = -1          !< newunit numbers are negative: test `opened`, not the sign
      logical :: opened = .false.
      logical :: quiet = .false.
   contains
      procedure :: open => logger_open
      procedure :: say => logger_say
      procedure :: phase => logger_phase
      procedure :: close => logger_close
   end type logger_t

contains

   subroutine logger_open(self, path, error)
      class(logger_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: error
      integer :: stat
      open (newunit=self%unit, file=path, status='replace', action='write', iostat=stat)
      self%opened = stat == 0
      if (stat /= 0) then
         self%unit = -1
         call fatal_error(error, 'error: cannot write the log file '//path, err_io)
      end if
   end subroutine logger_open

   subroutine logger_say(self, line)
      class(logger_t), intent(in) :: self
      character(len=*), intent(in) :: line
      if (.not. self%quiet) write (output_unit, '(a)') line
      if (self%opened) then
         write (self%unit, '(a)') line
         flush (self%unit)
      end if
   end subroutine logger_say

   !> One timing line: "  phase ...... 1.234 s".
   subroutine logger_phase(self, name, seconds)
      class(logger_t), intent(in) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: seconds
      character(len=80) :: buf
      write (buf, '(2x,a,t24,f10.3,a)') name, seconds, ' s'
      call self%say(trim(buf))
   end subroutine logger_phase

   subroutine logger_close(self)
      class(logger_t), intent(inout) :: self
      if (self%opened) close (self%unit)
      self%opened = .false.
      self%unit = -1
   end subroutine logger_close
end module vemcontact_log
