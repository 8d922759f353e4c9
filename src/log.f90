!> Run log: every line goes to the screen and to JOB.log; phase timings use the
!> wall clock so that they add up to what the user waits for.
!>
!> JOB.log is created afresh through src/safe_file.f90 (a file or link of that
!> name is removed, never followed) and every line is written with a checked
!> write(2): the first failure is kept (`failed`, `close`) and later lines go
!> to the screen only.  Control characters (from deck text) are shown escaped.
!>
!> Every phase line is also recorded (`phases`: name, seconds, step, the phase
!> it is part of) so that the run can write its phase times as data
!> (vemcontact_output_phases).  `lap` times what has run since the previous lap
!> and was not logged as a phase of its own, so a run timed by laps from start
!> to end has phases that add up to its total.
module vemcontact_log
   use vemcontact_kinds, only: wp
   use vemcontact_clock, only: wall_time
   use vemcontact_error, only: error_t, fatal_error, err_io
   use vemcontact_safe_file, only: open_fresh, write_bytes, close_synced, io_reason
   use vemcontact_text, only: escape_controls
   use, intrinsic :: iso_fortran_env, only: output_unit
   implicit none
   private

   public :: logger_t, phase_record_t, wall_time

   !> One logged phase.
   type :: phase_record_t
      character(len=:), allocatable :: name
      !> the phase this one is part of ('' for a phase of the run's total)
      character(len=:), allocatable :: within
      integer :: step = 0          !< the step it belongs to, 0 outside the steps
      real(wp) :: seconds = 0
   end type phase_record_t

   type :: logger_t
      integer :: fd = -1            !< descriptor of JOB.log
      logical :: opened = .false.
      logical :: quiet = .false.
      integer :: errno = 0          !< first failed write to JOB.log, 0 if none
      character(len=:), allocatable :: path
      type(phase_record_t), allocatable :: phases(:)   !< (nphases used)
      integer :: nphases = 0
      integer :: step = 0           !< step of the phases logged now (0 outside the steps)
      real(wp) :: mark = 0          !< wall time of the last lap
      real(wp) :: since_mark = 0    !< seconds of the phases (not sub-phases) logged since then
   contains
      procedure :: open => logger_open
      procedure :: say => logger_say
      procedure :: phase => logger_phase
      procedure :: lap => logger_lap
      procedure :: start_clock => logger_start_clock
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

   !> One timing line: "  phase ...... 1.234 s", recorded in `phases`.
   !> `within`: the phase this one is part of (a sub-phase, not added again to the total).
   subroutine logger_phase(self, name, seconds, within)
      class(logger_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: seconds
      character(len=*), intent(in), optional :: within
      character(len=80) :: buf
      type(phase_record_t), allocatable :: grown(:)
      write (buf, '(2x,a,t24,f10.3,a)') name, seconds, ' s'
      call self%say(trim(buf))
      if (.not. allocated(self%phases)) allocate (self%phases(16))
      if (self%nphases == size(self%phases)) then
         allocate (grown(2*size(self%phases)))
         grown(:self%nphases) = self%phases
         call move_alloc(grown, self%phases)
      end if
      self%nphases = self%nphases + 1
      associate (r => self%phases(self%nphases))
         r%name = name
         r%seconds = seconds
         r%step = self%step
         if (present(within)) then
            r%within = within
         else
            r%within = ''
            self%since_mark = self%since_mark + seconds
         end if
      end associate
   end subroutine logger_phase

   !> Log as phase `name` the wall time since the last lap (or start_clock) that
   !> no phase logged in between accounts for, and start the next lap.
   subroutine logger_lap(self, name)
      class(logger_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp) :: now
      now = wall_time()
      call self%phase(name, max(0.0_wp, now - self%mark - self%since_mark))
      self%mark = now
      self%since_mark = 0
   end subroutine logger_lap

   !> Start the laps at wall time t (the start of the run).
   subroutine logger_start_clock(self, t)
      class(logger_t), intent(inout) :: self
      real(wp), intent(in) :: t
      self%mark = t
      self%since_mark = 0
   end subroutine logger_start_clock

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
