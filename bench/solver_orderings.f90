!> Benchmark of the Cholesky orderings on a 2-dof-per-node grid matrix:
!> CHOLMOD's default analysis versus nodal METIS + given-permutation analysis,
!> then factorize and solve with each.
!>
!>   bench_solver_orderings [m [stencil [matrix.mtx]]]
!>
!> m x m nodes (default 708: 1,002,528 unknowns); stencil 9 couples the nodes of
!> Q4 elements (as the FE/VEM matrix does), 5 only grid neighbours; a third
!> argument writes the matrix in Matrix Market format for bench/cholmod_ref.
program bench_solver_orderings
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_mmio, only: write_matrix_market
   use vemcontact_solver_cholmod, only: cholmod_solver_t
   use vemcontact_solver_ordering, only: nodal_metis_ordering, node_graph_from_elements
   implicit none

   integer :: m, stencil
   character(len=256) :: arg, mtx
   type(sym_csc_t) :: a
   type(cholmod_solver_t) :: s
   type(error_t), allocatable :: error
   integer(i8), allocatable :: adj_ptr(:)
   integer(ip), allocatable :: adj(:), perm(:)
   real(wp), allocatable :: b(:), x(:)
   real(wp) :: t0, t_graph, t_metis, t_an, t_fac, t_sol

   m = 708
   stencil = 9
   mtx = ''
   if (command_argument_count() >= 1) then
      call get_command_argument(1, arg)
      read (arg, *) m
   end if
   if (command_argument_count() >= 2) then
      call get_command_argument(2, arg)
      read (arg, *) stencil
   end if
   if (command_argument_count() >= 3) call get_command_argument(3, mtx)

   t0 = wtime()
   call grid_graph(m, stencil, adj_ptr, adj)
   t_graph = wtime() - t0
   call block_matrix(adj_ptr, adj, m, a)
   allocate (b(a%n), x(a%n))
   b = 1.0_wp
   write (*, '(a,i0,a,i0,a,i0,a,i0,a,i0)') 'grid ', m, 'x', m, ', stencil ', stencil, ', n = ', a%n, &
      ', nnz(triu A) = ', a%col_ptr(a%n + 1) - 1
   write (*, '(a,f8.3,a)') 'node graph from elements  ', t_graph, ' s'
   if (len_trim(mtx) > 0) then
      call write_matrix_market(trim(mtx), a, error)
      call check('write_matrix_market')
      write (*, '(a)') 'wrote '//trim(mtx)
   end if

   ! CHOLMOD's default ordering strategy
   t0 = wtime()
   call s%analyze(a, error)
   t_an = wtime() - t0
   call check('analyze (default)')
   call factor_and_solve()
   call line('cholmod default ('//s%ordering//')', 0.0_wp)

   ! nodal METIS ordering, given to CHOLMOD
   allocate (perm(a%n))
   t0 = wtime()
   call nodal_metis_ordering(m*m, adj_ptr, adj, perm, error)
   t_metis = wtime() - t0
   call check('nodal_metis_ordering')
   t0 = wtime()
   call s%analyze(a, error, perm)
   t_an = wtime() - t0
   call check('analyze (nodal metis)')
   call factor_and_solve()
   call line('nodal metis + given', t_metis)
   call s%release()

contains

   ! Factorize twice (as the contact iterations refactorize) and keep the faster.
   subroutine factor_and_solve()
      integer :: rep
      t_fac = huge(1.0_wp)
      do rep = 1, 2
         t0 = wtime()
         call s%factorize(a, error)
         t_fac = min(t_fac, wtime() - t0)
         call check('factorize')
      end do
      t0 = wtime()
      call s%solve(b, x, error)
      t_sol = wtime() - t0
      call check('solve')
   end subroutine factor_and_solve

   subroutine line(what, t_order)
      character(len=*), intent(in) :: what
      real(wp), intent(in) :: t_order
      write (*, '(a)') what
      if (t_order > 0.0_wp) write (*, '(a,f8.3,a)') '  metis (node graph)      ', t_order, ' s'
      write (*, '(a,f8.3,a)') '  analyze                 ', t_an, ' s'
      write (*, '(a,f8.3,a)') '  factorize (best of 2)   ', t_fac, ' s'
      write (*, '(a,f8.3,a)') '  solve                   ', t_sol, ' s'
      write (*, '(a,f8.3,a)') '  total                   ', t_order + t_an + t_fac + t_sol, ' s'
      write (*, '(a,i0,a,es10.3)') '  nnz(L) ', s%nnz_factor, ', flops ', s%flops
   end subroutine line

   subroutine check(what)
      character(len=*), intent(in) :: what
      if (allocated(error)) then
         write (*, '(a)') what//': '//error%message
         error stop 1
      end if
   end subroutine check

   real(wp) function wtime()
      integer(i8) :: count, rate
      call system_clock(count, rate)
      wtime = real(count, wp)/real(rate, wp)
   end function wtime

   ! Node graph of an m x m grid: Q4 elements (9-point) or grid edges as
   ! 2-node elements (5-point).
   subroutine grid_graph(m, stencil, adj_ptr, adj)
      integer, intent(in) :: m, stencil
      integer(i8), allocatable, intent(out) :: adj_ptr(:)
      integer(ip), allocatable, intent(out) :: adj(:)
      integer(ip), allocatable :: elem_ptr(:), elem_conn(:)
      integer :: ix, iy, e, n1, k

      if (stencil == 9) then
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
      else
         allocate (elem_ptr(2*m*(m - 1) + 1), elem_conn(4*m*(m - 1)))
         k = 0
         do iy = 1, m
            do ix = 1, m
               n1 = ix + (iy - 1)*m
               if (ix < m) then
                  elem_conn(k + 1:k + 2) = [n1, n1 + 1]
                  k = k + 2
               end if
               if (iy < m) then
                  elem_conn(k + 1:k + 2) = [n1, n1 + m]
                  k = k + 2
               end if
            end do
         end do
         elem_ptr = [(2*e - 1, e=1, k/2 + 1)]
      end if
      call node_graph_from_elements(m*m, elem_ptr, elem_conn, adj_ptr, adj, error)
      call check('node_graph_from_elements')
   end subroutine grid_graph

   ! kron(G + C, B): G graph Laplacian, C = 1 on the first grid column, B SPD 2x2.
   subroutine block_matrix(adj_ptr, adj, m, a)
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      integer, intent(in) :: m
      type(sym_csc_t), intent(out) :: a
      real(wp), parameter :: blk(2, 2) = reshape([2.0_wp, 0.5_wp, 0.5_wp, 1.0_wp], [2, 2])
      integer(ip) :: nnode, j, i, cj, ci
      integer(i8) :: p, q
      real(wp) :: diag

      nnode = size(adj_ptr) - 1
      a%n = 2*nnode
      allocate (a%col_ptr(a%n + 1), a%row_idx(2*size(adj) + 3*nnode), a%val(2*size(adj) + 3*nnode))
      q = 1
      do j = 1, nnode
         diag = real(adj_ptr(j + 1) - adj_ptr(j), wp)
         if (mod(j - 1, m) == 0) diag = diag + 1.0_wp
         do cj = 1, 2
            a%col_ptr(2*j - 2 + cj) = q
            do p = adj_ptr(j), adj_ptr(j + 1) - 1
               i = adj(p)
               if (i > j) exit
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
   end subroutine block_matrix
end program bench_solver_orderings
