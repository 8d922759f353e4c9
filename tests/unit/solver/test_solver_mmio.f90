!> write_matrix_market (src/sparse/mmio.f90): header, size line, lower-triangle
!> coordinates and values that read back bit for bit.
program test_solver_mmio
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, err_io
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_mmio, only: write_matrix_market
   use vemcontact_testing, only: checker_t
   implicit none

   type(checker_t) :: t
   type(sym_csc_t) :: a
   type(error_t), allocatable :: error
   character(len=*), parameter :: path = 'test_solver_mmio.mtx'
   character(len=128) :: line
   integer :: unit, ios, nrow, ncol, i, j, k
   integer(i8) :: nnz
   real(wp) :: v
   logical :: ok

   ! [ 1/3   -2.5e-300   0    ]
   ! [       1e300       pi   ]
   ! [                   -0.0 ]   (upper triangle, column by column)
   a%n = 3
   a%col_ptr = [1_i8, 2_i8, 4_i8, 6_i8]
   a%row_idx = [integer(ip) :: 1, 1, 2, 2, 3]
   a%val = [1.0_wp/3.0_wp, -2.5e-300_wp, 1.0e300_wp, acos(-1.0_wp), -0.0_wp]

   call write_matrix_market(path, a, error)
   call t%check(.not. allocated(error), 'write: no error')
   open (newunit=unit, file=path, status='old', action='read', iostat=ios)
   call t%equal(ios, 0, 'file exists')
   read (unit, '(a)') line
   call t%check(line == '%%MatrixMarket matrix coordinate real symmetric', 'header line')
   read (unit, *) nrow, ncol, nnz
   call t%check(nrow == 3 .and. ncol == 3 .and. nnz == 5_i8, 'size line')
   ok = .true.
   do k = 1, 5
      read (unit, *) i, j, v
      ! written as (column, row) of the stored upper entry: the lower triangle
      ok = ok .and. i == col_of(k) .and. j == a%row_idx(k) .and. i >= j
      ok = ok .and. transfer(v, 0_i8) == transfer(a%val(k), 0_i8)   ! bit for bit, -0.0 included
   end do
   call t%check(ok, 'entries: lower-triangle coordinates and exact values')
   read (unit, *, iostat=ios) i
   call t%check(ios /= 0, 'nothing after the last entry')
   close (unit, status='delete')

   call write_matrix_market('no-such-directory/x.mtx', a, error)
   call t%check(allocated(error), 'unwritable path is an error')
   if (allocated(error)) call t%equal(error%code, err_io, 'unwritable path: err_io')
   call t%finish()

contains

   integer function col_of(k)
      integer, intent(in) :: k
      do col_of = 1, a%n
         if (a%col_ptr(col_of + 1) > k) return
      end do
   end function col_of
end program test_solver_mmio
