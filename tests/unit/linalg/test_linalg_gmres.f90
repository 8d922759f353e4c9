!> GMRES (vemcontact_linalg_gmres) on small systems with known solutions: a
!> nonsymmetric matrix preconditioned by the inverse of its diagonal part, the
!> exact preconditioner (one iteration), restarts, a stall ending the solve; the
!> norm safe from under- and overflow.
module test_gmres_operators
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t
   use vemcontact_linalg_gmres, only: linear_operator_t
   implicit none
   private
   public :: dense_t

   !> y = A x with a dense A; the preconditioner divides by d (d = diag(A): Jacobi)
   type, extends(linear_operator_t) :: dense_t
      real(wp), allocatable :: a(:, :), d(:)
   contains
      procedure :: apply => dense_apply
      procedure :: precondition => dense_precondition
   end type dense_t
contains
   subroutine dense_apply(self, x, y)
      class(dense_t), intent(inout) :: self
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      y = matmul(self%a, x)
   end subroutine dense_apply

   subroutine dense_precondition(self, x, y, error)
      class(dense_t), intent(inout) :: self
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      type(error_t), allocatable, intent(out) :: error
      y = x/self%d
   end subroutine dense_precondition
end module test_gmres_operators

program test_linalg_gmres
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t
   use vemcontact_testing, only: checker_t
   use vemcontact_linalg_gmres, only: gmres, gmres_result_t
   use vemcontact_linalg_norms, only: safe_norm2
   use test_gmres_operators, only: dense_t
   implicit none
   integer, parameter :: n = 40
   type(checker_t) :: t
   type(dense_t) :: op
   type(gmres_result_t) :: res
   type(error_t), allocatable :: error
   real(wp) :: xexact(n), b(n), x(n)
   integer :: i, j

   ! A = D + N: D = diag(1..n), N nonsymmetric with entries up to 0.3 (so that the
   ! preconditioned matrix I + D^-1 N is far from I, and GMRES needs many iterations)
   allocate (op%a(n, n), op%d(n))
   do j = 1, n
      do i = 1, n
         op%a(i, j) = 0.3_wp*sin(real(3*i + 7*j, wp))/real(1 + abs(i - j), wp)
      end do
      op%d(j) = real(j, wp)
      op%a(j, j) = op%d(j)
   end do
   do i = 1, n
      xexact(i) = cos(real(i, wp))
   end do
   b = matmul(op%a, xexact)

   ! to a residual of 1e-13 |b|: |x - x*| / |x*| within cond(A) times that, cond(A) ~ 1e2
   x = 0.0_wp
   call gmres(op, b, x, 1.0e-13_wp*norm2(b), 0.0_wp, 20, 200, 0.5_wp, res, error)
   call t%check(.not. allocated(error), 'no error')
   call t%check(res%converged, 'converged')
   call t%close(norm2(x - xexact)/norm2(xexact), 0.0_wp, 0.0_wp, 'solution', atol=1.0e-11_wp)
   call t%close(res%residual, norm2(b - matmul(op%a, x)), 1.0e-12_wp, 'reported residual is the true one')
   write (*, '(a,i0,a,es10.3)') 'restarted GMRES(20): ', res%iterations, ' iterations, error ', &
      norm2(x - xexact)/norm2(xexact)
   call t%check(res%iterations > 1, 'the Jacobi preconditioner is not exact: several iterations')

   ! a diagonal A with the exact preconditioner: one iteration, then the floor
   op%a = 0.0_wp
   do j = 1, n
      op%a(j, j) = op%d(j)
   end do
   b = matmul(op%a, xexact)
   x = 0.0_wp
   call gmres(op, b, x, 1.0e-10_wp*norm2(b), 0.0_wp, 20, 200, 0.5_wp, res, error)
   call t%check(res%converged .and. res%iterations <= 2, 'exact preconditioner: at most 2 iterations')
   call t%close(norm2(x - xexact)/norm2(xexact), 0.0_wp, 0.0_wp, 'exact preconditioner: solution', &
                atol=1.0e-15_wp)

   ! an unreachable goal (0) below a floor the start already meets: the iterations go on
   ! while they halve the residual (to the round-off), then converged by the floor
   x = 0.0_wp
   call gmres(op, b, x, 0.0_wp, 2.0_wp*norm2(b), 20, 200, 0.5_wp, res, error)
   call t%check(res%converged .and. res%iterations <= 3, 'floor: converged after the round-off is reached')
   call t%close(norm2(x - xexact)/norm2(xexact), 0.0_wp, 0.0_wp, 'floor: solution to round-off', &
                atol=1.0e-15_wp)

   ! b = 0 from x = 0: nothing to do, no iteration
   b = 0.0_wp
   x = 0.0_wp
   call gmres(op, b, x, 0.0_wp, 0.0_wp, 20, 200, 0.5_wp, res, error)
   call t%equal(res%iterations, 0, 'zero right-hand side: no iteration')
   call t%close(maxval(abs(x)), 0.0_wp, 0.0_wp, 'zero right-hand side: zero solution')

   ! restart length 1 on a matrix whose preconditioned form has eigenvalues of both
   ! signs: GMRES(1) makes no progress and stops (not converged) long before maxit
   op%a = 0.0_wp
   do j = 1, n
      op%a(j, j) = merge(1.0_wp, -1.0_wp, mod(j, 2) == 0)*op%d(j)
   end do
   op%d = abs(op%d)
   b = 1.0_wp
   x = 0.0_wp
   call gmres(op, b, x, 1.0e-10_wp, 0.0_wp, 1, 1000, 0.5_wp, res, error)
   call t%check(.not. res%converged, 'GMRES(1) on an indefinite preconditioned matrix: not converged')
   call t%check(res%iterations < 10, 'and the stall ends it early')

   ! the norm at scales where the squares under- or overflow
   call t%close(safe_norm2([3.0e-200_wp, 4.0e-200_wp]), 5.0e-200_wp, 1.0e-15_wp, 'safe_norm2 at 1e-200')
   call t%close(safe_norm2([3.0e200_wp, -4.0e200_wp]), 5.0e200_wp, 1.0e-15_wp, 'safe_norm2 at 1e200')
   call t%close(safe_norm2([0.0_wp, 0.0_wp]), 0.0_wp, 0.0_wp, 'safe_norm2 of zero')
   call t%finish()
end program test_linalg_gmres
