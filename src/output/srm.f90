!> The trials of a strength reduction step as a CSV table, JOB_srm_NNNN.csv
!> (docs/output-format.md): trial, F, converged (0/1), u_char (the characteristic
!> displacement of a converged trial, 0 for a failed one), iterations (contact
!> iterations of the trial), reason (converged, or what ended the trial).
module vemcontact_output_srm
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t
   use vemcontact_safe_file, only: safe_file_t
   implicit none
   private

   public :: write_srm_csv

contains

   !> One line per trial, in trial order, full precision.
   subroutine write_srm_csv(path, f, converged, u_char, iterations, reason, error)
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: f(:), u_char(:)
      integer, intent(in) :: converged(:), iterations(:)
      character(len=*), intent(in) :: reason(:)
      type(error_t), allocatable, intent(out) :: error
      type(safe_file_t) :: out
      character(len=160) :: line
      integer :: k
      call out%open(path, error)
      if (allocated(error)) return
      call out%write('trial,F,converged,u_char,iterations,reason'//new_line('a'))
      do k = 1, size(f)
         write (line, '(i0,",",es24.16e3,",",i0,",",es24.16e3,",",i0,",")') k, f(k), converged(k), u_char(k), &
            iterations(k)
         call out%write(trim(line)//trim(reason(k))//new_line('a'))
      end do
      ! a failed write is reported (file and reason) by the commit
      call out%commit(error)
   end subroutine write_srm_csv
end module vemcontact_output_srm
