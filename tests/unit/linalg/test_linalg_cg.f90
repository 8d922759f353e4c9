!> Preconditioned conjugate gradients (vemcontact_linalg_cg) on the structure of the
!> multiplier step of HARD contact: S = C (I + k C)^-1 with k the springs (the
!> preconditioner) and C the compliance of the pressure modes, most of them soft
!> (k c >> 1, eigenvalues of S clustered near 1/k) and a few carried by a stiffer
!> body (k c << 1).  Plain Uzawa (the preconditioned Richardson step) divides the
!> error of such a mode by 1 + k c per step; conjugate gradients end after as many
!> steps as S has distinct eigenvalues.
module test_cg_operators
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t
   use vemcontact_linalg_gmres, only: linear_operator_t
   implicit none
   private
   public :: spd_t

   !> y = A x with a dense symmetric A; the preconditioner multiplies by k
   type, extends(linear_operator_t) :: spd_t
      real(wp), allocatable :: a(:, :)
      real(wp) :: k = 1.0_wp
   contains
      procedure :: apply => spd_apply
      procedure :: precondition => spd_precondition
   end type spd_t
contains
   subroutine spd_apply(self, x, y)
      class(spd_t), intent(inout) :: self
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      y = matmul(self%a, x)
   end subroutine spd_apply

   subroutine spd_precondition(self, x, y, error)
      class(spd_t), intent(inout) :: self
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      type(error_t), allocatable, intent(out) :: error
      y = self%k*x
   end subroutine spd_precondition
end module test_cg_operators

program test_linalg_cg
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t
   use vemcontact_testing, only: checker_t
   use vemcontact_linalg_cg, only: pcg, cg_result_t
   use test_cg_operators, only: spd_t
   implicit none
   integer, parameter :: n = 12
   type(checker_t) :: t
   type(spd_t) :: op
   type(cg_result_t) :: res
   type(error_t), allocatable :: error
   real(wp) :: q(n, n), v(n), c(n), s(n), b(n), x(n), xexact(n), tol(n), kb(n), alpha
   integer :: i, j

   ! S = Q diag(s) Q^T, Q a Householder reflector, k = 1e3: nine soft modes
   ! (c = 1, k c = 1e3: one eigenvalue) and three stiff ones (k c = 1, 1e-1, 1e-3)
   op%k = 1.0e3_wp
   c = [(1.0_wp, i=1, 9), 1.0e-3_wp, 1.0e-4_wp, 1.0e-6_wp]
   s = c/(1.0_wp + op%k*c)
   v = [(sin(real(3*i, wp)) + 1.5_wp, i=1, n)]
   do j = 1, n
      do i = 1, n
         q(i, j) = merge(1.0_wp, 0.0_wp, i == j) - 2.0_wp*v(i)*v(j)/dot_product(v, v)
      end do
   end do
   op%a = matmul(q, matmul(diag(s), transpose(q)))
   xexact = [(cos(real(5*i, wp)), i=1, n)]
   b = matmul(op%a, xexact)

   ! four distinct eigenvalues: four steps (a fifth for the round-off), to the
   ! round-off of the equations (tol 1e-12 of the right-hand side)
   tol = 1.0e-12_wp*maxval(abs(b))
   call pcg(op, b, tol, 30, x, res, error)
   call t%check(.not. allocated(error), 'no error')
   call t%check(res%converged, 'converged to the bound per equation')
   call t%check(res%iterations <= 5, 'as many steps as distinct eigenvalues (4), one for round-off')
   ! the stiff mode (k c = 1e-3) amplifies the residual's round-off by 1/s = 1e6 k
   call t%close(maxval(abs(x - xexact)), 0.0_wp, 0.0_wp, 'the exact multipliers', atol=1.0e-6_wp)
   call t%check(all(abs(b - matmul(op%a, x)) <= tol), 'every residual within its bound')

   ! one step: the Richardson (plain Uzawa) step k b at its best length
   call pcg(op, b, tol, 1, x, res, error)
   kb = op%k*b
   alpha = dot_product(b, kb)/dot_product(kb, matmul(op%a, kb))
   call t%close(maxval(abs(x - alpha*kb)), 0.0_wp, 0.0_wp, 'first iterate: the Uzawa step at its best length', &
                atol=1.0e-12_wp*maxval(abs(alpha*kb)))
   call t%check(.not. res%converged .and. res%iterations == 1, 'one step, not converged')

   ! a right-hand side within its bounds: nothing to do
   call pcg(op, 0.5_wp*tol, tol, 30, x, res, error)
   call t%check(res%converged .and. res%iterations == 0 .and. maxval(abs(x)) <= 0.0_wp, 'within the bounds: x = 0')
   call t%finish()
contains
   pure function diag(d) result(m)
      real(wp), intent(in) :: d(:)
      real(wp) :: m(size(d), size(d))
      integer :: k
      m = 0.0_wp
      do k = 1, size(d)
         m(k, k) = d(k)
      end do
   end function diag
end program test_linalg_cg
