!> Products with the symmetric upper-triangle CSC matrix.
module vemcontact_sparse_matvec
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_sparse_matrix, only: sym_csc_t
   implicit none
   private

   public :: sym_matvec

contains

   !> y = A x, A symmetric and stored as its upper triangle.
   pure subroutine sym_matvec(a, x, y)
      type(sym_csc_t), intent(in) :: a
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      integer(ip) :: j, i
      integer(i8) :: k
      y = 0.0_wp
      do j = 1, a%n
         do k = a%col_ptr(j), a%col_ptr(j + 1) - 1
            i = a%row_idx(k)
            y(i) = y(i) + a%val(k)*x(j)
            if (i /= j) y(j) = y(j) + a%val(k)*x(i)
         end do
      end do
   end subroutine sym_matvec
end module vemcontact_sparse_matvec
