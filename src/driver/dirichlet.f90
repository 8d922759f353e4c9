!> Prescribed displacements imposed on the assembled system without changing its
!> pattern: the rows and columns of a constrained dof are zeroed, its diagonal kept
!> (so the matrix stays well scaled) and its right-hand side set to diagonal * value;
!> the known values move to the right-hand side of the free rows.  The matrix
!> then depends only on which dofs are fixed, not on their values, so a step that
!> only changes values reuses the factorization.
module vemcontact_driver_dirichlet
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_sparse_matrix, only: sym_csc_t
   implicit none
   private

   public :: apply_dirichlet

contains

   !> `a` is modified in place (pass a copy of the stiffness); `f` becomes the right-hand side.
   pure subroutine apply_dirichlet(a, fixed, value, f)
      type(sym_csc_t), intent(inout) :: a
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: value(:)
      real(wp), intent(inout) :: f(:)
      integer(ip) :: j, i
      integer(i8) :: k
      do j = 1, a%n
         do k = a%col_ptr(j), a%col_ptr(j + 1) - 1
            i = a%row_idx(k)
            if (i == j) cycle
            if (fixed(j) .and. .not. fixed(i)) then
               f(i) = f(i) - a%val(k)*value(j)
               a%val(k) = 0.0_wp
            else if (fixed(i) .and. .not. fixed(j)) then
               f(j) = f(j) - a%val(k)*value(i)
               a%val(k) = 0.0_wp
            else if (fixed(i) .and. fixed(j)) then
               a%val(k) = 0.0_wp
            end if
         end do
      end do
      do j = 1, a%n
         if (.not. fixed(j)) cycle
         k = a%col_ptr(j + 1) - 1          ! the diagonal is the last entry of its column
         if (a%val(k) <= 0.0_wp) a%val(k) = 1.0_wp
         f(j) = a%val(k)*value(j)
      end do
   end subroutine apply_dirichlet
end module vemcontact_driver_dirichlet
