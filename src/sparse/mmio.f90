!> Matrix Market output of the global matrix, for debugging and for comparing
!> with reference solvers (bench/cholmod_ref reads it).  Written through
!> `safe_file_t` (checked writes, fsync, rename), like the result files.
module vemcontact_sparse_mmio
   use vemcontact_kinds, only: i8
   use vemcontact_error, only: error_t, fatal_error, err_internal
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_safe_file, only: safe_file_t
   implicit none
   private

   public :: write_matrix_market

contains

   !> Write `a` as "coordinate real symmetric".  The Matrix Market format asks
   !> for the lower triangle of a symmetric matrix, so the stored upper entry
   !> (i, j), i <= j, is written as (j, i); readers (CHOLMOD, SciPy) mirror it.
   !> Values use 17 significant digits, enough to read back every bit.
   subroutine write_matrix_market(path, a, error)
      character(len=*), intent(in) :: path
      type(sym_csc_t), intent(in) :: a
      type(error_t), allocatable, intent(out) :: error
      type(safe_file_t) :: out
      integer(i8) :: nnz, p
      integer :: j
      character(len=64) :: line

      if (.not. allocated(a%col_ptr) .or. .not. allocated(a%row_idx) .or. .not. allocated(a%val)) then
         call fatal_error(error, 'write_matrix_market: matrix not allocated', err_internal)
         return
      end if
      nnz = a%col_ptr(a%n + 1) - 1
      call out%open(path, error)
      if (allocated(error)) return
      call out%write('%%MatrixMarket matrix coordinate real symmetric'//new_line('a'))
      write (line, '(i0,1x,i0,1x,i0)') a%n, a%n, nnz
      call out%write(trim(line)//new_line('a'))
      do j = 1, a%n
         if (out%failed()) exit
         do p = a%col_ptr(j), a%col_ptr(j + 1) - 1
            write (line, '(i0,1x,i0,1x,es24.16e3)') j, a%row_idx(p), a%val(p)
            call out%write(trim(line)//new_line('a'))
         end do
      end do
      call out%commit(error)
   end subroutine write_matrix_market
end module vemcontact_sparse_mmio
