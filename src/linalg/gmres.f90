!> Restarted GMRES with right preconditioning, for systems A x = b whose matrix is a
!> small change of one with a factor at hand: the factor is the preconditioner, so
!> that GMRES needs few iterations (one when the factor is that of A itself).
!>
!> The caller extends `linear_operator_t` with the product by A and the
!> preconditioner solve.  Right preconditioning, A M^-1 y = b with x = M^-1 y,
!> minimizes the true residual |b - A x|, which is what the caller's stop tests.
!> Arnoldi with modified Gram-Schmidt, Givens rotations (Saad, Iterative Methods for
!> Sparse Linear Systems, 2nd ed., algorithms 6.9 and 9.5).
module vemcontact_linalg_gmres
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t
   use vemcontact_linalg_norms, only: safe_norm2
   implicit none
   private

   public :: linear_operator_t, gmres, gmres_result_t

   !> A linear operator with a preconditioner.
   type, abstract :: linear_operator_t
   contains
      procedure(apply_i), deferred :: apply
      procedure(precondition_i), deferred :: precondition
   end type linear_operator_t

   abstract interface
      !> y = A x
      subroutine apply_i(self, x, y)
         import :: linear_operator_t, wp
         class(linear_operator_t), intent(inout) :: self
         real(wp), intent(in) :: x(:)
         real(wp), intent(out) :: y(:)
      end subroutine apply_i
      !> y = M^-1 x
      subroutine precondition_i(self, x, y, error)
         import :: linear_operator_t, wp, error_t
         class(linear_operator_t), intent(inout) :: self
         real(wp), intent(in) :: x(:)
         real(wp), intent(out) :: y(:)
         type(error_t), allocatable, intent(out) :: error
      end subroutine precondition_i
   end interface

   !> What a GMRES solve did.
   type :: gmres_result_t
      logical :: converged = .false.   !< |b - A x| <= tol
      integer :: iterations = 0        !< products by A (and preconditioner solves)
      real(wp) :: residual = 0.0_wp    !< |b - A x| at the end
      real(wp) :: initial = 0.0_wp     !< |b - A x| at the start
   end type gmres_result_t

contains

   !> Solve A x = b from the initial x: at least one iteration (unless b - A x = 0),
   !> until |b - A x| <= tol (2-norm), or, once it is below `floor` (the round-off
   !> the caller expects), until an iteration lowers it by less than the factor
   !> `stall` (e.g. 0.5); restarts every `restart` iterations, at most `maxit`
   !> iterations in all.  A restart cycle that lowers the residual by less than
   !> `stall` ends the solve: the preconditioner is too far from A.  Converged: the
   !> residual is below max(tol, floor).  x is the last iterate.
   subroutine gmres(op, b, x, tol, floor, restart, maxit, stall, res, error)
      class(linear_operator_t), intent(inout) :: op
      real(wp), intent(in) :: b(:), tol, floor, stall
      real(wp), intent(inout) :: x(:)
      integer, intent(in) :: restart, maxit
      type(gmres_result_t), intent(out) :: res
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: v(:, :), h(:, :), cs(:), sn(:), g(:), y(:), w(:), z(:)
      real(wp) :: beta, cycle_start, t, rho, rho_prev
      integer :: n, m, j, i
      logical :: done

      n = size(b)
      m = max(1, restart)
      allocate (v(n, m + 1), h(m + 1, m), cs(m), sn(m), g(m + 1), y(m), w(n), z(n))
      call residual_of(x, w)
      beta = safe_norm2(w)
      res%initial = beta
      res%residual = beta
      do while (res%iterations < maxit)
         if (.not. beta > 0.0_wp) exit
         cycle_start = beta
         rho = beta
         done = .false.
         v(:, 1) = w/beta
         g = 0.0_wp
         g(1) = beta
         h = 0.0_wp
         j = 0
         do while (j < m .and. res%iterations < maxit)
            j = j + 1
            res%iterations = res%iterations + 1
            call op%precondition(v(:, j), z, error)
            if (allocated(error)) return
            call op%apply(z, w)
            ! modified Gram-Schmidt
            do i = 1, j
               h(i, j) = dot_product(w, v(:, i))
               w = w - h(i, j)*v(:, i)
            end do
            h(j + 1, j) = safe_norm2(w)
            if (h(j + 1, j) > 0.0_wp) v(:, j + 1) = w/h(j + 1, j)
            ! previous rotations on the new column, then a new rotation
            do i = 1, j - 1
               t = cs(i)*h(i, j) + sn(i)*h(i + 1, j)
               h(i + 1, j) = -sn(i)*h(i, j) + cs(i)*h(i + 1, j)
               h(i, j) = t
            end do
            call rotation(h(j, j), h(j + 1, j), cs(j), sn(j))
            h(j, j) = cs(j)*h(j, j) + sn(j)*h(j + 1, j)
            h(j + 1, j) = 0.0_wp
            g(j + 1) = -sn(j)*g(j)
            g(j) = cs(j)*g(j)
            rho_prev = rho
            rho = abs(g(j + 1))
            done = .not. abs(h(j, j)) > 0.0_wp .or. rho <= tol .or. (rho <= floor .and. rho > stall*rho_prev)
            if (done) exit
         end do
         ! x <- x + M^-1 V y with H y = g (upper triangular)
         do i = j, 1, -1
            y(i) = g(i)
            if (i < j) y(i) = y(i) - dot_product(h(i, i + 1:j), y(i + 1:j))
            if (abs(h(i, i)) > 0.0_wp) then
               y(i) = y(i)/h(i, i)
            else
               y(i) = 0.0_wp
            end if
         end do
         w = matmul(v(:, 1:j), y(1:j))
         call op%precondition(w, z, error)
         if (allocated(error)) return
         x = x + z
         call residual_of(x, w)
         beta = safe_norm2(w)
         res%residual = beta
         if (done .or. beta > stall*cycle_start .or. beta <= tol) exit
      end do
      res%converged = beta <= max(tol, floor)
   contains
      subroutine residual_of(xx, r)
         real(wp), intent(in) :: xx(:)
         real(wp), intent(out) :: r(:)
         call op%apply(xx, r)
         r = b - r
      end subroutine residual_of
   end subroutine gmres

   !> Givens rotation (c, s) with c a + s b = r, -s a + c b = 0.
   pure subroutine rotation(a, b, c, s)
      real(wp), intent(in) :: a, b
      real(wp), intent(out) :: c, s
      real(wp) :: r
      r = hypot(a, b)
      if (r > 0.0_wp) then
         c = a/r
         s = b/r
      else
         c = 1.0_wp
         s = 0.0_wp
      end if
   end subroutine rotation
end module vemcontact_linalg_gmres
