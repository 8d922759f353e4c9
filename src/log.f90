!> Run log: every line goes to the screen and to JOB.log; phase timings use the
!> wall clock so that they add up to what the user waits for.
!>
!> JOB.log is created afresh through src/safe_file.f90 (a file or link of that
!> name is removed, never followed) and every line is written with a checked
!> write(2): the first failure is kept (`failed`, `close`) and later lines go
!> to the screen only.  Control characters (from deck text) are shown escaped.
module vemcontact_log
   use vemcontact_kinds, only: wp
   use vemcontact_clock, only: wall_time
   use vemcontact_error, only: error_t, fatal_error, err_io
   use vemcontact_safe_file, only: open_fresh, write_bytes, close_synced, io_reason
   use vemcontact_text, only: escape_controls
   use, intrinsic :: iso_fortran_env, only: output_unit
   implicit none
   private

   public :: logger_t, wall_time

   type :: logger_t
      integer :: fd = -1            !< descriptor of JOB.log
      logical :: opened = .false.
      logical :: quiet = .false.
      integer :: errno = 0          !< first failed write to JOB.log, 0 if none
      character(len=:), allocatable :: path
   contains
      procedure :: open => logger_open
      procedure :: say => logger_say
      procedure :: phase => logger_phase
      procedure :: failed => logger_failed
      procedure :: close => logger_close
   end type logger_t

contains

   subroutine logger_open(self, path, error)
      class(logger_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: error
      self%path = path
      self%errno = 0
      call open_fresh(path, self%fd, error)
      self%opened = .not. allocated(error)
      if (.not. self%opened) self%fd = -1
   end subroutine logger_open

   subroutine logger_say(self, line)
      class(logger_t), intent(inout) :: self
      character(len=*), intent(in) :: line
      character(len=:), allocatable :: shown
      shown = escape_controls(line)
      if (.not. self%quiet) write (output_unit, '(a)') shown
      if (self%opened .and. self%errno == 0) self%errno = write_bytes(self%fd, shown//new_line('a'))
   end subroutine logger_say

   !> One timing line: "  phase ...... 1.234 s".
   subroutine logger_phase(self, name, seconds)
      class(logger_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: seconds
      character(len=80) :: buf
      write (buf, '(2x,a,t24,f10.3,a)') name, seconds, ' s'
      call self%say(trim(buf))
   end subroutine logger_phase

   !> The error of the first failed write to JOB.log, if any.
   subroutine logger_failed(self, error)
      class(logger_t), intent(in) :: self
      type(error_t), allocatable, intent(out) :: error
      if (self%errno /= 0) call fatal_error(error, 'error: cannot write '''//self%path//''': '// &
                                            io_reason(self%errno), err_io)
   end subroutine logger_failed

   !> Close JOB.log (fsync'ed); `error` reports a failed write or close.
   subroutine logger_close(self, error)
      class(logger_t), intent(inout) :: self
      type(error_t), allocatable, intent(out), optional :: error
      integer :: rc
      if (.not. self%opened) return
      rc = close_synced(self%fd)
      if (self%errno == 0) self%errno = rc
      self%opened = .false.
      self%fd = -1
      if (present(error)) call self%failed(error)
   end subroutine logger_close
end module vemcontact_log
