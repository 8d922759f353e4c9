!> Matrix Market output of the global matrix, for debugging and for comparing
!> with reference solvers (bench/cholmod_ref reads it).
module vemcontact_sparse_mmio
   use vemcontact_kinds, only: i8
   use vemcontact_error, only: error_t, fatal_error, err_io, err_internal
   use vemcontact_sparse_matrix, only: sym_csc_t
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
      integer :: unit, ios
      integer(i8) :: nnz, p
      integer :: j
      character(len=256) :: msg

      if (.not. allocated(a%col_ptr) .or. .not. allocated(a%row_idx) .or. .not. allocated(a%val)) then
         call fatal_error(error, 'write_matrix_market: matrix not allocated', err_internal)
         return
      end if
      nnz = a%col_ptr(a%n + 1) - 1
      open (newunit=unit, file=path, status='replace', action='write', form='formatted', &
         iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, trim(path)//': cannot open for writing: '//trim(msg), err_io)
         return
      end if
      write (unit, '(a)', iostat=ios, iomsg=msg) '%%MatrixMarket matrix coordinate real symmetric'
      if (ios == 0) write (unit, '(i0,1x,i0,1x,i0)', iostat=ios, iomsg=msg) a%n, a%n, nnz
      do j = 1, a%n
         if (ios /= 0) exit
         do p = a%col_ptr(j), a%col_ptr(j + 1) - 1
            write (unit, '(i0,1x,i0,1x,es24.16e3)', iostat=ios, iomsg=msg) j, a%row_idx(p), a%val(p)
            if (ios /= 0) exit
         end do
      end do
      if (ios /= 0) then
         close (unit, iostat=ios)
         call fatal_error(error, trim(path)//': write failed: '//trim(msg), err_io)
         return
      end if
      close (unit, iostat=ios, iomsg=msg)
      if (ios /= 0) call fatal_error(error, trim(path)//': close failed: '//trim(msg), err_io)
   end subroutine write_matrix_market
end module vemcontact_sparse_mmio
