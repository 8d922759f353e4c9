!> Preconditioned conjugate gradients for a symmetric positive definite A x = b, for
!> small systems whose product by A is expensive (each one a solve with a factor):
!> the multiplier step of HARD contact (vemcontact_contact_iteration), where A is the
!> condensed compliance of the contact entries and the preconditioner the inverse of
!> the springs.  Stops on a bound per component of the residual (the round-off of
!> each equation), not on a norm.  Hestenes-Stiefel with the preconditioner M^-1
!> (Saad, Iterative Methods for Sparse Linear Systems, 2nd ed., algorithm 9.1).
module vemcontact_linalg_cg
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t
   use vemcontact_linalg_gmres, only: linear_operator_t
   implicit none
   private

   public :: pcg, cg_result_t

   !> What a conjugate gradient solve did.
   type :: cg_result_t
      logical :: converged = .false.   !< every |b - A x|_i <= tol_i
      integer :: iterations = 0        !< products by A
   end type cg_result_t

contains

   !> Solve A x = b from x = 0 until every component of the residual is within its
   !> bound, |b - A x|_i <= tol_i (then x = 0 when b already is), until the search
   !> direction has no positive curvature left (p.A p <= 0: round-off, A being
   !> positive definite), or after `maxit` products by A.  The first iterate is the
   !> preconditioned Richardson step M^-1 b at its best length, and every further
   !> iterate lowers the A-norm of the error; x is the last iterate.
   subroutine pcg(op, b, tol, maxit, x, res, error)
      class(linear_operator_t), intent(inout) :: op
      real(wp), intent(in) :: b(:), tol(:)
      integer, intent(in) :: maxit
      real(wp), intent(out) :: x(:)
      type(cg_result_t), intent(out) :: res
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: r(:), z(:), p(:), q(:)
      real(wp) :: rz, rz_new, pq, alpha
      x = 0.0_wp
      r = b
      res%converged = all(abs(r) <= tol)
      if (res%converged) return
      allocate (z(size(b)), q(size(b)))
      call op%precondition(r, z, error)
      if (allocated(error)) return
      p = z
      rz = dot_product(r, z)
      do while (res%iterations < maxit)
         res%iterations = res%iterations + 1
         call op%apply(p, q)
         pq = dot_product(p, q)
         if (.not. (pq > 0.0_wp .and. rz > 0.0_wp)) return
         alpha = rz/pq
         x = x + alpha*p
         r = r - alpha*q
         res%converged = all(abs(r) <= tol)
         if (res%converged) return
         call op%precondition(r, z, error)
         if (allocated(error)) return
         rz_new = dot_product(r, z)
         p = z + (rz_new/rz)*p
         rz = rz_new
      end do
   end subroutine pcg
end module vemcontact_linalg_cg
