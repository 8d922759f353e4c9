!> Prescribed displacements imposed on the assembled system without changing its
!> pattern: the rows and columns of a constrained dof are zeroed, its diagonal kept
!> (so the matrix stays well scaled) and its right-hand side set to diagonal * value;
!> the known values move to the right-hand side of the free rows.  The matrix
!> then depends only on which dofs are fixed, not on their values, so a step that
!> only changes values reuses the factorization (it calls constrain_rhs alone).
module vemcontact_driver_dirichlet
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_sparse_matrix, only: sym_csc_t
   implicit none
   private

   public :: apply_dirichlet, constrain_rhs, constrain_matrix, dirichlet_moves, kept_diagonal

contains

   !> Both parts; `a` is modified in place (pass a copy of the stiffness).
   pure subroutine apply_dirichlet(a, fixed, value, f)
      type(sym_csc_t), intent(inout) :: a
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: value(:)
      real(wp), intent(inout) :: f(:)
      call constrain_rhs(a, fixed, value, f)
      call constrain_matrix(a, fixed)
   end subroutine apply_dirichlet

   !> Right-hand side for the constrained system, from the unconstrained matrix `a`.
   pure subroutine constrain_rhs(a, fixed, value, f)
      type(sym_csc_t), intent(in) :: a
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: value(:)
      real(wp), intent(inout) :: f(:)
      integer(ip) :: j
      call dirichlet_moves(a, fixed, value, f)
      do j = 1, a%n
         if (fixed(j)) f(j) = kept_diagonal(a%val(a%col_ptr(j + 1) - 1))*value(j)
      end do
   end subroutine constrain_rhs

   !> The known values moved to the free rows: f(i) = f(i) - a(i, j) value(j) for
   !> free i and fixed j.  Linear in `a`: the moves of the shares of a matrix add up
   !> to those of the matrix.
   pure subroutine dirichlet_moves(a, fixed, value, f)
      type(sym_csc_t), intent(in) :: a
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: value(:)
      real(wp), intent(inout) :: f(:)
      integer(ip) :: j, i
      integer(i8) :: k
      do j = 1, a%n
         do k = a%col_ptr(j), a%col_ptr(j + 1) - 2      ! the diagonal is last: skipped
            i = a%row_idx(k)
            if (fixed(j) .and. .not. fixed(i)) then
               f(i) = f(i) - a%val(k)*value(j)
            else if (fixed(i) .and. .not. fixed(j)) then
               f(j) = f(j) - a%val(k)*value(i)
            end if
         end do
      end do
   end subroutine dirichlet_moves

   !> Zero the couplings of fixed dofs; their diagonal stays (1 where it is not positive).
   !> For one process's share `a` of a matrix (the matrix is the sum of the shares),
   !> `diag` is the whole matrix's diagonal (read at the fixed dofs): the fixed diagonal,
   !> kept from it, is held by the share with `owner` and zero in the others.
   pure subroutine constrain_matrix(a, fixed, diag, owner)
      type(sym_csc_t), intent(inout) :: a
      logical, intent(in) :: fixed(:)
      real(wp), intent(in), optional :: diag(:)
      logical, intent(in), optional :: owner
      integer(ip) :: j
      integer(i8) :: k
      do j = 1, a%n
         do k = a%col_ptr(j), a%col_ptr(j + 1) - 2
            if (fixed(j) .or. fixed(a%row_idx(k))) a%val(k) = 0.0_wp
         end do
         if (.not. fixed(j)) cycle
         k = a%col_ptr(j + 1) - 1
         if (present(diag)) then
            a%val(k) = 0.0_wp
            if (owner) a%val(k) = kept_diagonal(diag(j))
         else
            a%val(k) = kept_diagonal(a%val(k))
         end if
      end do
   end subroutine constrain_matrix

   !> The diagonal a fixed dof keeps: its own, 1 where that is not positive.
   pure real(wp) function kept_diagonal(d)
      real(wp), intent(in) :: d
      kept_diagonal = d
      if (d <= 0.0_wp) kept_diagonal = 1.0_wp
   end function kept_diagonal
end module vemcontact_driver_dirichlet
