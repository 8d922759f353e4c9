!> CHOLMOD solver object: solutions of SPD systems (natural, default and nodal
!> METIS orderings), refactorization without re-analysis, not positive definite
!> matrices (error and failing dof), rcond, calls out of order, and the solve on
!> the dofs ordered last from the factor's trailing block.
program test_solver_cholmod
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, err_solver, err_internal
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_solver_cholmod, only: cholmod_solver_t
   use vemcontact_solver_ordering, only: nodal_metis_ordering, nodal_metis_ordering_last, node_graph_from_elements
   use vemcontact_testing, only: checker_t
   implicit none

   ! Cholesky is backward stable: ||A x - b|| <= c n eps ||A|| ||x||.  With b = A x_true
   ! for an oscillating x_true, ||b|| ~ ||A|| ||x||, so 1e-12 leaves a margin of ~1e3
   ! over eps for n = 5000 (observed residuals are ~1e-16 to 1e-15).
   real(wp), parameter :: res_tol = 1.0e-12_wp
   type(checker_t) :: t

   call test_laplacian(t)
   call test_block(t)
   call test_not_posdef(t)
   call test_rcond(t)
   call test_out_of_order(t)
   call test_trailing(t)
   call t%finish()

contains

   subroutine test_laplacian(t)
      type(checker_t), intent(inout) :: t
      type(sym_csc_t) :: a
      type(cholmod_solver_t) :: s
      type(error_t), allocatable :: error
      real(wp), allocatable :: b(:), x(:)

      a = laplacian5(50)
      call rhs_of(a, b)
      allocate (x(a%n))
      call s%analyze(a, error)
      call t%check(.not. allocated(error), 'laplacian: analyze')
      call s%factorize(a, error)
      call t%check(.not. allocated(error), 'laplacian: factorize')
      call s%solve(b, x, error)
      call t%check(.not. allocated(error), 'laplacian: solve')
      call report('laplacian 50x50 default ordering '//s%ordering, residual(a, x, b), s%nnz_factor)
      call t%check(residual(a, x, b) < res_tol, 'laplacian: residual')
      call t%check(s%supernodal, 'laplacian: supernodal factor')
      call t%check(s%ordering == 'amd' .or. s%ordering == 'metis' .or. s%ordering == 'nesdis', &
         'laplacian: default ordering is a fill-reducing one')
      ! nnz(L) lies between nnz(triu(A)) and the dense triangle
      call t%check(s%nnz_factor >= a%col_ptr(a%n + 1) - 1 .and. &
         s%nnz_factor <= int(a%n, i8)*(a%n + 1)/2, 'laplacian: nnz(L) plausible')
      call t%check(s%flops > 0.0_wp, 'laplacian: flop count')
   end subroutine test_laplacian

   subroutine test_block(t)
      type(checker_t), intent(inout) :: t
      type(sym_csc_t) :: a, a2
      type(cholmod_solver_t) :: s(2)
      type(error_t), allocatable :: error
      real(wp), allocatable :: b(:), x(:), x_old(:), b3(:, :), x3(:, :)
      integer(i8), allocatable :: adj_ptr(:)
      integer(ip), allocatable :: adj(:), perm(:)
      integer :: k, m
      character(len=*), parameter :: name(2) = ['default    ', 'nodal metis']

      call q4_grid_graph(50, adj_ptr, adj)
      a = block_matrix(adj_ptr, adj, 50)
      call rhs_of(a, b)
      allocate (x(a%n), perm(a%n))
      call nodal_metis_ordering(a%n/2, adj_ptr, adj, perm, error)
      call t%check(.not. allocated(error), 'block: nodal ordering')
      do k = 1, 2
         if (k == 1) then
            call s(k)%analyze(a, error)
         else
            call s(k)%analyze(a, error, perm)
         end if
         call t%check(.not. allocated(error), 'block: analyze '//trim(name(k)))
         call s(k)%factorize(a, error)
         call t%check(.not. allocated(error), 'block: factorize '//trim(name(k)))
         call s(k)%solve(b, x, error)
         call t%check(.not. allocated(error), 'block: solve '//trim(name(k)))
         call report('block 2x2500 dofs '//trim(name(k))//' ('//s(k)%ordering//')', residual(a, x, b), &
            s(k)%nnz_factor)
         call t%check(residual(a, x, b) < res_tol, 'block: residual '//trim(name(k)))
      end do
      call t%check(s(2)%ordering == 'given', 'block: perm given is used')

      ! New values on the same pattern: only factorize again.
      allocate (x_old(a%n))
      x_old(:) = x
      a2 = a
      do m = 1, a2%n
         a2%val(a2%col_ptr(m + 1) - 1) = 2.0_wp*a2%val(a2%col_ptr(m + 1) - 1)
      end do
      do k = 1, 2
         call s(k)%factorize(a2, error)
         call t%check(.not. allocated(error), 'block: refactorize '//trim(name(k)))
         call s(k)%solve(b, x, error)
         call report('block refactorized, scaled diagonal, '//trim(name(k)), residual(a2, x, b), &
            s(k)%nnz_factor)
         call t%check(residual(a2, x, b) < res_tol, 'block: residual after refactorization '//trim(name(k)))
         ! the old factor would not solve the new system
         call t%check(residual(a, x, b) > 1.0e-3_wp, 'block: refactorization used the new values '// &
            trim(name(k)))
      end do
      call t%check(norm2(x - x_old) > 1.0e-3_wp*norm2(x_old), 'block: solution changed')

      ! Several right-hand sides at once.
      allocate (b3(a2%n, 3), x3(a2%n, 3))
      do k = 1, 3
         b3(:, k) = real(k, wp)*b
         if (k == 3) b3(:, k) = 1.0_wp
      end do
      call s(2)%solve(b3, x3, error)
      call t%check(.not. allocated(error), 'block: solve with 3 right-hand sides')
      do k = 1, 3
         call t%check(residual(a2, x3(:, k), b3(:, k)) < res_tol, 'block: residual of several rhs')
      end do
      call t%check(maxval(abs(x3(:, 1) - x)) <= 1.0e-14_wp*maxval(abs(x)), &
         'block: several rhs agree with one rhs')
      ! gfortran 12 does not finalize local arrays of derived type
      call s(1)%release()
      call s(2)%release()
   end subroutine test_block

   subroutine test_not_posdef(t)
      type(checker_t), intent(inout) :: t
      type(sym_csc_t) :: a, bad
      type(cholmod_solver_t) :: s
      type(error_t), allocatable :: error
      real(wp), allocatable :: b(:), x(:)
      integer(i8), allocatable :: adj_ptr(:)
      integer(ip), allocatable :: adj(:), perm(:)
      integer(ip), parameter :: d_neg = 1555, node_zero = 1234
      integer :: k, j
      integer(i8) :: p
      character(len=*), parameter :: name(2) = ['default    ', 'nodal metis']

      call q4_grid_graph(50, adj_ptr, adj)
      a = block_matrix(adj_ptr, adj, 50)
      call rhs_of(a, b)
      allocate (x(a%n), perm(a%n))
      call nodal_metis_ordering(a%n/2, adj_ptr, adj, perm, error)
      do k = 1, 2
         if (k == 1) then
            call s%analyze(a, error)
         else
            call s%analyze(a, error, perm)
         end if
         call t%check(.not. allocated(error), 'not posdef: analyze '//trim(name(k)))

         ! Negative diagonal at one dof: every pivot before it belongs to a principal
         ! submatrix of the SPD matrix, its own pivot is <= -1, so exactly it fails.
         bad = a
         bad%val(bad%col_ptr(d_neg + 1) - 1) = -1.0_wp
         call s%factorize(bad, error)
         call t%check(allocated(error), 'negative diagonal: error '//trim(name(k)))
         if (allocated(error)) then
            call t%equal(error%code, err_solver, 'negative diagonal: err_solver '//trim(name(k)))
            write (*, '(a)') '  message: '//error%message
         end if
         call t%equal(s%failed_column, d_neg, 'negative diagonal: failed dof '//trim(name(k)))
         call s%solve(b, x, error)
         call t%check(allocated(error), 'negative diagonal: solve refused '//trim(name(k)))
         call t%check(s%rcond() < 0.0_wp, 'negative diagonal: no rcond '//trim(name(k)))

         ! A node with no stiffness at all (zero rows and columns, diagonal stored as 0).
         bad = a
         do j = 1, bad%n
            do p = bad%col_ptr(j), bad%col_ptr(j + 1) - 1
               if ((j + 1)/2 == node_zero .or. (bad%row_idx(p) + 1)/2 == node_zero) bad%val(p) = 0.0_wp
            end do
         end do
         call s%factorize(bad, error)
         call t%check(allocated(error), 'zero block: error '//trim(name(k)))
         write (*, '(a,i0,a,i0)') '  zero block at node ', node_zero, ': failed dof ', s%failed_column
         call t%equal((s%failed_column + 1)/2, node_zero, 'zero block: failed dof is on the node '// &
            trim(name(k)))

         ! The same analysis still serves a good matrix afterwards.
         call s%factorize(a, error)
         call t%check(.not. allocated(error), 'refactorize after failure '//trim(name(k)))
         call t%equal(s%failed_column, 0, 'failed_column reset '//trim(name(k)))
         call s%solve(b, x, error)
         call t%check(.not. allocated(error), 'solve after failure '//trim(name(k)))
         call t%check(residual(a, x, b) < res_tol, 'residual after failure '//trim(name(k)))
      end do
   end subroutine test_not_posdef

   subroutine test_rcond(t)
      type(checker_t), intent(inout) :: t
      type(sym_csc_t) :: a
      type(cholmod_solver_t) :: s
      type(error_t), allocatable :: error
      integer(ip), parameter :: n = 10
      integer(ip) :: j

      a%n = n
      a%col_ptr = [(int(j, i8), j=1, n + 1)]
      a%row_idx = [(j, j=1, n)]
      allocate (a%val(n))
      a%val = 1.0_wp
      a%val(n) = 1.0e-6_wp
      call s%analyze(a, error)
      call t%check(s%rcond() < 0.0_wp, 'rcond before factorize is -1')
      call s%factorize(a, error)
      call t%check(.not. allocated(error), 'rcond: factorize diagonal')
      ! For LL' CHOLMOD returns (min diag L / max diag L)**2 = (sqrt(1e-6)/1)**2: exact
      ! for a diagonal matrix up to the rounding of one sqrt and one square (a few ulp).
      write (*, '(a,es24.16)') '  rcond(diag(1,...,1e-6)) = ', s%rcond()
      call t%close(s%rcond(), 1.0e-6_wp, 1.0e-14_wp, 'rcond of diag(1,...,1e-6)')
      a = laplacian5(20)
      call s%analyze(a, error)
      call s%factorize(a, error)
      write (*, '(a,es12.4)') '  rcond(laplacian 20x20) = ', s%rcond()
      call t%check(s%rcond() > 0.0_wp .and. s%rcond() <= 1.0_wp, 'rcond of laplacian in (0, 1]')
   end subroutine test_rcond

   subroutine test_out_of_order(t)
      type(checker_t), intent(inout) :: t
      type(sym_csc_t) :: a, other
      type(cholmod_solver_t) :: s
      type(error_t), allocatable :: error
      real(wp), allocatable :: b(:), x(:)
      integer(ip), allocatable :: perm(:)
      integer(ip) :: j

      a = laplacian5(10)
      call rhs_of(a, b)
      allocate (x(a%n))
      call s%factorize(a, error)
      call t%check(allocated(error), 'factorize before analyze is an error')
      if (allocated(error)) call t%equal(error%code, err_internal, 'factorize before analyze: err_internal')
      call s%solve(b, x, error)
      call t%check(allocated(error), 'solve before analyze is an error')
      call s%analyze(a, error)
      call s%solve(b, x, error)
      call t%check(allocated(error), 'solve before factorize is an error')

      ! a different pattern than the analysed one
      other = laplacian5(10)
      other%row_idx(2) = 2
      call s%factorize(other, error)
      call t%check(allocated(error), 'factorize with another pattern is an error')
      other = laplacian5(9)
      call s%factorize(other, error)
      call t%check(allocated(error), 'factorize with another size is an error')

      ! invalid input to analyze: not a permutation, lower-triangle entry
      perm = [(j, j=1, a%n)]
      perm(5) = 4
      call s%analyze(a, error, perm)
      call t%check(allocated(error), 'analyze with a repeated index in perm is an error')
      other = laplacian5(10)
      other%row_idx(2) = 3   ! row 3 in column 2: below the diagonal
      call s%analyze(other, error)
      call t%check(allocated(error), 'analyze with a lower-triangle entry is an error')
      call s%factorize(a, error)
      call t%check(allocated(error), 'a failed analysis leaves nothing to factorize')

      call s%release()
      call s%release()
      call t%check(.true., 'release twice')
      call s%factorize(a, error)
      call t%check(allocated(error), 'factorize after release is an error')
      call s%analyze(a, error)
      call s%factorize(a, error)
      call s%solve(b, x, error)
      call t%check(.not. allocated(error), 'analyze/factorize/solve after release')
      call t%check(residual(a, x, b) < res_tol, 'residual after release and reuse')
   end subroutine test_out_of_order

   ! 5-point Laplacian on an m x m grid with Dirichlet boundary, upper triangle.
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

   ! A^-1 b on a set of dofs for b supported on them (the contact compliance's
   ! columns), read from the factor's trailing block when the ordering puts the
   ! set last, against the full solve with the same factor.  The sets: a grid row
   ! (a separator, as a joint between two bodies) and two rows apart (not one).
   subroutine test_trailing(t)
      type(checker_t), intent(inout) :: t
      integer, parameter :: m = 50, ncol = 40
      type(sym_csc_t) :: a
      type(cholmod_solver_t) :: s
      type(error_t), allocatable :: error
      integer(i8), allocatable :: adj_ptr(:)
      integer(ip), allocatable :: adj(:), perm(:), last(:), dofs(:)
      real(wp), allocatable :: b(:, :), x(:, :), xf(:, :)
      logical :: done
      integer :: k, c, set
      character(len=*), parameter :: name(2) = ['one row ', 'two rows']

      call q4_grid_graph(m, adj_ptr, adj)
      a = block_matrix(adj_ptr, adj, m)
      allocate (perm(a%n))
      do set = 1, 2
         if (set == 1) then
            last = [(int(k + 24*m, ip), k=1, m)]
         else
            last = [(int(k + 9*m, ip), k=1, m), (int(k + 39*m, ip), k=1, m)]
         end if
         dofs = [(2*last(k) - 1, 2*last(k), k=1, size(last))]
         call nodal_metis_ordering_last(int(m*m, ip), adj_ptr, adj, last, perm, error)
         call t%check(.not. allocated(error), 'trailing: ordering '//trim(name(set)))
         call t%check(all(perm(a%n - size(dofs) + 1:) == dofs), 'trailing: the set''s dofs last, '//trim(name(set)))
         call s%analyze(a, error, perm)
         call t%check(.not. allocated(error), 'trailing: analyze '//trim(name(set)))
         call s%factorize(a, error)
         call t%check(.not. allocated(error), 'trailing: factorize '//trim(name(set)))
         allocate (b(a%n, ncol), x(a%n, ncol), xf(a%n, ncol), source=0.0_wp)
         do c = 1, ncol
            do k = 1, size(dofs)
               b(dofs(k), c) = sin(real(c*k, wp)) + merge(1.0_wp, 0.0_wp, k == c)
            end do
         end do
         call s%solve_trailing(dofs, b, x, done, error)
         call t%check(.not. allocated(error) .and. done, 'trailing: solved from the trailing block, '//trim(name(set)))
         call s%solve(b, xf, error)
         call t%check(.not. allocated(error), 'trailing: full solve '//trim(name(set)))
         ! the same factor in both: the trailing rows of the forward substitution and
         ! the back substitution there are the same arithmetic in another order, so
         ! they differ by round-off amplified by the block's condition (~1e3 here):
         ! 1e-12 leaves a margin of 10 (observed ~1e-15)
         write (*, '(2x,a,": max |x_trailing - x_full| / max |x_full| = ",es10.3)') 'trailing '//trim(name(set)), &
            maxval(abs(x(dofs, :) - xf(dofs, :)))/maxval(abs(xf(dofs, :)))
         call t%check(maxval(abs(x(dofs, :) - xf(dofs, :))) <= 1.0e-12_wp*maxval(abs(xf(dofs, :))), &
                      'trailing: equals the full solve on the set, '//trim(name(set)))
         deallocate (b, x, xf)
      end do
      ! the plain nodal ordering eliminates a row of the grid anywhere: the block
      ! from its first dof to the end is then too large to read, and the caller
      ! solves in full
      call nodal_metis_ordering(int(m*m, ip), adj_ptr, adj, perm, error)
      last = [(int(k, ip), k=1, m)]
      dofs = [(2*last(k) - 1, 2*last(k), k=1, size(last))]
      call s%analyze(a, error, perm)
      call s%factorize(a, error)
      allocate (b(a%n, 1), x(a%n, 1), source=0.0_wp)
      b(dofs, 1) = 1.0_wp
      call s%solve_trailing(dofs, b, x, done, error)
      call t%check(.not. allocated(error) .and. .not. done, 'trailing: a set not ordered last is declined')
   end subroutine test_trailing

   ! Node graph of an m x m grid of Q4 elements (9-point stencil).
   subroutine q4_grid_graph(m, adj_ptr, adj)
      integer, intent(in) :: m
      integer(i8), allocatable, intent(out) :: adj_ptr(:)
      integer(ip), allocatable, intent(out) :: adj(:)
      integer(ip), allocatable :: elem_ptr(:), elem_conn(:)
      type(error_t), allocatable :: error
      integer :: ix, iy, e, n1

      allocate (elem_ptr((m - 1)**2 + 1), elem_conn(4*(m - 1)**2))
      e = 0
      do iy = 1, m - 1
         do ix = 1, m - 1
            e = e + 1
            n1 = ix + (iy - 1)*m
            elem_ptr(e) = 4*e - 3
            elem_conn(4*e - 3:4*e) = [n1, n1 + 1, n1 + 1 + m, n1 + m]
         end do
      end do
      elem_ptr(e + 1) = 4*e + 1
      call node_graph_from_elements(m*m, elem_ptr, elem_conn, adj_ptr, adj, error)
      if (allocated(error)) then
         write (*, '(a)') 'q4_grid_graph: '//error%message
         error stop 1
      end if
   end subroutine q4_grid_graph

   ! Elasticity-like matrix with 2 dofs per node: kron(G + C, B), G the graph
   ! Laplacian of the node graph, C = 1 on the nodes of the first grid column
   ! (clamped edge; nodes 1, 1+m, ...), B = [2 0.5; 0.5 1].  SPD as a Kronecker
   ! product of SPD matrices.
   function block_matrix(adj_ptr, adj, m) result(a)
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      integer, intent(in) :: m
      type(sym_csc_t) :: a
      real(wp), parameter :: blk(2, 2) = reshape([2.0_wp, 0.5_wp, 0.5_wp, 1.0_wp], [2, 2])
      integer(ip) :: nnode, j, i, cj, ci
      integer(i8) :: p, q
      real(wp) :: diag

      nnode = size(adj_ptr) - 1
      a%n = 2*nnode
      allocate (a%col_ptr(a%n + 1), a%row_idx(4*size(adj) + 3*nnode), a%val(4*size(adj) + 3*nnode))
      q = 1
      do j = 1, nnode
         diag = real(adj_ptr(j + 1) - adj_ptr(j), wp)
         if (mod(j - 1, m) == 0) diag = diag + 1.0_wp
         do cj = 1, 2
            a%col_ptr(2*j - 2 + cj) = q
            do p = adj_ptr(j), adj_ptr(j + 1) - 1
               i = adj(p)
               if (i > j) exit   ! neighbours are sorted
               do ci = 1, 2
                  a%row_idx(q) = 2*i - 2 + ci
                  a%val(q) = -blk(ci, cj)
                  q = q + 1
               end do
            end do
            do ci = 1, cj
               a%row_idx(q) = 2*j - 2 + ci
               a%val(q) = diag*blk(ci, cj)
               q = q + 1
            end do
         end do
      end do
      a%col_ptr(a%n + 1) = q
      a%row_idx = a%row_idx(:q - 1)
      a%val = a%val(:q - 1)
   end function block_matrix

   ! y = A x for the symmetric matrix stored as its upper triangle.
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

   ! b = A x_true with an oscillating x_true, so that ||b|| ~ ||A|| ||x||.
   subroutine rhs_of(a, b)
      type(sym_csc_t), intent(in) :: a
      real(wp), allocatable, intent(out) :: b(:)
      real(wp), allocatable :: x_true(:)
      integer :: i
      allocate (x_true(a%n))
      do i = 1, a%n
         x_true(i) = 1.0_wp + sin(real(i, wp))
      end do
      b = matvec(a, x_true)
   end subroutine rhs_of

   real(wp) function residual(a, x, b)
      type(sym_csc_t), intent(in) :: a
      real(wp), intent(in) :: x(:), b(:)
      residual = norm2(matvec(a, x) - b)/norm2(b)
   end function residual

   subroutine report(what, res, lnz)
      character(len=*), intent(in) :: what
      real(wp), intent(in) :: res
      integer(i8), intent(in) :: lnz
      write (*, '(2x,a,": ||Ax-b||/||b|| = ",es10.3,", nnz(L) = ",i0)') what, res, lnz
   end subroutine report
end program test_solver_cholmod
