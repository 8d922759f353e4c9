!> The run's phase times as a table, JOB_phases.csv: one row per phase line of
!> the log, in the order logged, `step,phase,within,seconds`.  `step` is 0 for
!> the phases outside the steps; `within` names the phase a sub-phase is part
!> of (empty for the phases of the run's total); the row `total` is the run's
!> end-to-end wall time, which the phases with an empty `within` add up to.
module vemcontact_output_phases
   use vemcontact_error, only: error_t
   use vemcontact_log, only: logger_t
   use vemcontact_safe_file, only: safe_file_t
   implicit none
   private

   public :: write_phases

contains

   !> Write the phases recorded by `log` to `path` (through a temporary, renamed when complete).
   subroutine write_phases(path, log, error)
      character(len=*), intent(in) :: path
      type(logger_t), intent(in) :: log
      type(error_t), allocatable, intent(out) :: error
      type(safe_file_t) :: out
      character(len=40) :: buf
      integer :: k
      call out%open(path, error)
      if (allocated(error)) return
      call out%write('step,phase,within,seconds'//new_line('a'))
      do k = 1, log%nphases
         associate (r => log%phases(k))
            write (buf, '(i0,a)') r%step, ','
            call out%write(trim(buf)//r%name//','//r%within//',')
            write (buf, '(es16.9)') r%seconds
            call out%write(trim(adjustl(buf))//new_line('a'))
         end associate
      end do
      ! a failed write is reported (file and reason) by the commit
      call out%commit(error)
   end subroutine write_phases
end module vemcontact_output_phases
