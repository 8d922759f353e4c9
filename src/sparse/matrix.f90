!> Symmetric sparse matrix stored as its upper triangle in compressed sparse
!> column form (1-based), the layout CHOLMOD takes with stype = +1.  Row indices
!> within a column are sorted and the diagonal is always present (it is the last
!> entry of its column), so a Dirichlet row can always be replaced by its diagonal.
module vemcontact_sparse_matrix
   use vemcontact_kinds, only: wp, ip, i8
   implicit none
   private

   public :: sym_csc_t

   type :: sym_csc_t
      integer(ip) :: n = 0
      integer(i8), allocatable :: col_ptr(:)   !< (n+1), 1-based offsets into row_idx/val
      integer(ip), allocatable :: row_idx(:)   !< (nnz), row of each entry, row <= column
      real(wp), allocatable :: val(:)          !< (nnz)
   end type sym_csc_t
end module vemcontact_sparse_matrix
