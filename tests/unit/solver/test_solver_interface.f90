!> Every backend of the linear solver interface (vemcontact_solver_factory), used
!> only through `linear_solver_t`: solutions of an SPD system for one and for a
!> block of right-hand sides, a second factorization with new values, calls out of
!> order, a matrix with an entry more than the analysed pattern (a pattern rebuilt
!> without a new analysis) refused, and failures reported in the error object:
!> CHOLMOD's on a negative definite matrix, CG's when it runs out of iterations.  Without PETSc
!> (the build did not find it) its backends must say so.
program test_solver_interface
   use vemcontact_kinds, only: wp, i8
   use vemcontact_error, only: error_t, err_solver, err_internal
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_solver_linear_solver, only: linear_solver_t
   use vemcontact_solver_petsc, only: petsc_solver_t, petsc_finalize
   use vemcontact_solver_factory, only: make_solver, solver_cholmod, solver_gamg, solver_hypre, solver_mumps, &
                                        uses_petsc
   use vemcontact_testing, only: checker_t
   implicit none

   ! Direct solvers (CHOLMOD, MUMPS) are backward stable: ||A x - b|| <= c n eps ||A|| ||x||,
   ! and ||b|| ~ ||A|| ||x|| for the oscillating x_true below: 1e-12 leaves ~1e3 over eps.
   real(wp), parameter :: direct_tol = 1.0e-12_wp
   ! CG stops at ||b - A x|| <= 1e-10 ||b|| (vemcontact_solver_petsc's default_rtol);
   ! twice that covers the round-off of our own evaluation of the residual.
   real(wp), parameter :: cg_tol = 2.0e-10_wp
   character(len=*), parameter :: names(4) = [character(len=7) :: 'cholmod', 'gamg', 'hypre', 'mumps']
   integer, parameter :: kinds(4) = [solver_cholmod, solver_gamg, solver_hypre, solver_mumps]
   type(checker_t) :: t
   integer :: k

   do k = 1, size(kinds)
      call check_backend(t, kinds(k), trim(names(k)))
   end do
   call petsc_finalize()
   call t%finish()

contains

   subroutine check_backend(t, kind, name)
      type(checker_t), intent(inout) :: t
      integer, intent(in) :: kind
      character(len=*), intent(in) :: name
      class(linear_solver_t), allocatable :: s
      type(error_t), allocatable :: error
      type(sym_csc_t) :: a, grown
      real(wp), allocatable :: b(:), x(:), bb(:, :), xx(:, :), xy(:, :)
      real(wp) :: tol
      integer :: j
      integer(i8) :: p

      tol = merge(cg_tol, direct_tol, kind == solver_gamg .or. kind == solver_hypre)
      a = laplacian5(20)          ! 400 unknowns: 200 "nodes" of 2 dofs
      allocate (xy(2, a%n/2))
      do j = 1, a%n/2
         xy(:, j) = [real(mod(j - 1, 10), wp), real((j - 1)/10, wp)]
      end do
      call make_solver(kind, s, error)
      call t%check(.not. allocated(error), name//': made')
      if (allocated(error)) return
      call s%analyze(a, error, coords=xy)
      if (allocated(error) .and. uses_petsc(kind)) then
         if (index(error%message, 'built without PETSc') > 0) then
            print '(a)', '  '//name//': '//error%message
            call t%check(.true., name//': says it was not built')
            return
         end if
      end if
      call t%check(.not. allocated(error), name//': analyze')
      if (allocated(error)) return

      ! a solve before any factorization is refused
      allocate (x(a%n))
      b = matvec(a, oscillating(a%n, 0))
      call s%solve(b, x, error)
      call t%check(allocated(error), name//': solve before factorize refused')
      if (allocated(error)) call t%equal(error%code, err_internal, name//': ... as an internal error')

      call s%factorize(a, error)
      call t%check(.not. allocated(error), name//': factorize')
      call s%solve(b, x, error)
      call t%check(.not. allocated(error), name//': solve')
      print '(2x,a,": ||Ax-b||/||b|| = ",es10.3)', name, residual(a, x, b)
      call t%check(residual(a, x, b) <= tol, name//': residual of one right-hand side')

      ! a block of three right-hand sides, after new values on the same pattern
      a%val = 2.0_wp*a%val
      call s%factorize(a, error)
      call t%check(.not. allocated(error), name//': second factorize')
      allocate (bb(a%n, 3), xx(a%n, 3))
      do j = 1, 3
         bb(:, j) = matvec(a, oscillating(a%n, j))
      end do
      call s%solve(bb, xx, error)
      call t%check(.not. allocated(error), name//': block solve')
      do j = 1, 3
         call t%check(residual(a, xx(:, j), bb(:, j)) <= tol, name//': residual of block column')
      end do
      call t%check(s%rcond() <= 1.0_wp, name//': rcond is an estimate or -1')

      ! the same order with one entry more (row 1 of the last column): not the analysed
      ! pattern, refused as an internal error (the driver analyses a rebuilt pattern)
      grown = a
      p = a%col_ptr(a%n)
      grown%row_idx = [a%row_idx(:p - 1), 1, a%row_idx(p:)]
      grown%val = [a%val(:p - 1), -0.1_wp, a%val(p:)]
      grown%col_ptr(a%n + 1) = a%col_ptr(a%n + 1) + 1
      call s%factorize(grown, error)
      call t%check(allocated(error), name//': factorize with an entry more than the analysed pattern refused')
      if (allocated(error)) call t%equal(error%code, err_internal, name//': ... as an internal error')

      ! failures: CHOLMOD on a negative definite matrix; CG limited to 2 iterations
      ! (MUMPS factors symmetric indefinite matrices as LDL' and solves them, and CG
      ! with a preconditioner of the same sign converges on them: not checked)
      select type (s)
      type is (petsc_solver_t)
         s%max_iterations = 2
      end select
      if (kind /= solver_mumps) then
         if (kind == solver_cholmod) a%val = -a%val
         call s%factorize(a, error)
         if (.not. allocated(error)) call s%solve(b, x, error)
         call t%check(allocated(error), name//': failure reported')
         if (allocated(error)) then
            print '(a)', '  '//name//': '//error%message
            call t%equal(error%code, err_solver, name//': ... as a solver error')
         end if
      end if
      call s%release()
   end subroutine check_backend

   pure function oscillating(n, shift) result(x)
      integer, intent(in) :: n, shift
      real(wp) :: x(n)
      integer :: i
      do i = 1, n
         x(i) = 1.0_wp + sin(real(i + 7*shift, wp))
      end do
   end function oscillating

   !> 5-point Laplacian of an m x m grid, upper triangle in CSC, diagonal last.
   function laplacian5(m) result(a)
      integer, intent(in) :: m
      type(sym_csc_t) :: a
      integer :: ix, iy, j
      integer(i8) :: p
      a%n = m*m
      allocate (a%col_ptr(a%n + 1), a%row_idx(3*a%n), a%val(3*a%n))
      p = 1
      do iy = 1, m
         do ix = 1, m
            j = ix + (iy - 1)*m
            a%col_ptr(j) = p
            if (iy > 1) then
               a%row_idx(p) = j - m
               a%val(p) = -1.0_wp
               p = p + 1
            end if
            if (ix > 1) then
               a%row_idx(p) = j - 1
               a%val(p) = -1.0_wp
               p = p + 1
            end if
            a%row_idx(p) = j
            a%val(p) = 4.0_wp
            p = p + 1
         end do
      end do
      a%col_ptr(a%n + 1) = p
      a%row_idx = a%row_idx(:p - 1)
      a%val = a%val(:p - 1)
   end function laplacian5

   !> y = A x for the symmetric A of which `a` holds the upper triangle.
   function matvec(a, x) result(y)
      type(sym_csc_t), intent(in) :: a
      real(wp), intent(in) :: x(:)
      real(wp) :: y(size(x))
      integer :: j, i
      integer(i8) :: p
      y = 0.0_wp
      do j = 1, a%n
         do p = a%col_ptr(j), a%col_ptr(j + 1) - 1
            i = a%row_idx(p)
            y(i) = y(i) + a%val(p)*x(j)
            if (i /= j) y(j) = y(j) + a%val(p)*x(i)
         end do
      end do
   end function matvec

   real(wp) function residual(a, x, b)
      type(sym_csc_t), intent(in) :: a
      real(wp), intent(in) :: x(:), b(:)
      residual = norm2(matvec(a, x) - b)/norm2(b)
   end function residual
end program test_solver_interface
