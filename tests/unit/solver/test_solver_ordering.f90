!> Node graph from element connectivity, and the nodal METIS dof ordering:
!> a valid permutation with each node's dofs consecutive, whose fill on a grid
!> is far below the natural ordering's and close to CHOLMOD's default (AMD).
program test_solver_ordering
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_solver_cholmod, only: cholmod_solver_t
   use vemcontact_solver_ordering, only: nodal_metis_ordering, node_graph_from_elements
   use vemcontact_solver_metis, only: metis_nodend
   use vemcontact_testing, only: checker_t
   implicit none

   type(checker_t) :: t

   call test_node_graph(t)
   call test_nodal_ordering(t)
   call test_metis_edge_cases(t)
   call t%finish()

contains

   ! Two quads and a triangle, plus node 8 in no element:
   !
   !   4---5---6
   !   |   |   | \
   !   1---2---3--7
   subroutine test_node_graph(t)
      type(checker_t), intent(inout) :: t
      integer(i8), allocatable :: adj_ptr(:)
      integer(ip), allocatable :: adj(:)
      type(error_t), allocatable :: error
      integer(ip), parameter :: elem_ptr(4) = [1, 5, 9, 12]
      integer(ip), parameter :: elem_conn(11) = [1, 2, 5, 4, 2, 3, 6, 5, 3, 7, 6]
      integer(i8), parameter :: expect_ptr(9) = [1, 4, 9, 13, 16, 21, 25, 27, 27]
      integer(ip), parameter :: expect(26) = [2, 4, 5, &
                                              1, 3, 4, 5, 6, &
                                              2, 5, 6, 7, &
                                              1, 2, 5, &
                                              1, 2, 3, 4, 6, &
                                              2, 3, 5, 7, &
                                              3, 6]

      call node_graph_from_elements(8, elem_ptr, elem_conn, adj_ptr, adj, error)
      call t%check(.not. allocated(error), 'node graph: no error')
      call t%equal(size(adj_ptr), 9, 'node graph: size of adj_ptr')
      if (size(adj_ptr) == 9) call t%check(all(adj_ptr == expect_ptr), 'node graph: adj_ptr')
      call t%equal(size(adj), 26, 'node graph: size of adj')
      if (size(adj) == 26) call t%check(all(adj == expect), 'node graph: sorted unique neighbours')

      ! A node repeated inside an element (degenerate polygon) adds no self loop.
      call node_graph_from_elements(3, [1, 5], [1, 2, 2, 3], adj_ptr, adj, error)
      call t%check(.not. allocated(error), 'node graph, repeated node: no error')
      call t%check(all(adj_ptr == [1_i8, 3_i8, 5_i8, 7_i8]) .and. all(adj == [2, 3, 1, 3, 1, 2]), &
         'node graph, repeated node: neighbours')

      call node_graph_from_elements(3, [1, 4], [1, 2, 4], adj_ptr, adj, error)
      call t%check(allocated(error), 'node graph: node index out of range is an error')
      call node_graph_from_elements(2, [1], [integer(ip) ::], adj_ptr, adj, error)
      call t%check(.not. allocated(error) .and. size(adj) == 0 .and. all(adj_ptr == 1), &
         'node graph: no elements gives isolated nodes')
   end subroutine test_node_graph

   subroutine test_nodal_ordering(t)
      type(checker_t), intent(inout) :: t
      integer, parameter :: m = 60
      integer(i8), allocatable :: adj_ptr(:)
      integer(ip), allocatable :: adj(:), perm(:), natural(:)
      type(error_t), allocatable :: error
      type(sym_csc_t) :: a
      type(cholmod_solver_t) :: s
      integer(i8) :: lnz_natural, lnz_default, lnz_nodal
      logical, allocatable :: seen(:)
      logical :: valid
      integer(ip) :: k
      character(len=:), allocatable :: default_name

      call q4_grid_graph(m, adj_ptr, adj)
      a = block_pattern(adj_ptr, adj)
      allocate (perm(a%n), seen(a%n))
      call nodal_metis_ordering(m*m, adj_ptr, adj, perm, error)
      call t%check(.not. allocated(error), 'nodal ordering: no error')

      valid = all(perm >= 1 .and. perm <= a%n)
      seen = .false.
      if (valid) then
         do k = 1, a%n
            valid = valid .and. .not. seen(perm(k))
            seen(perm(k)) = .true.
         end do
      end if
      call t%check(valid .and. all(seen), 'nodal ordering: a permutation of 1..2*nnode')
      call t%check(all(mod(perm(1::2), 2) == 1) .and. all(perm(2::2) == perm(1::2) + 1), &
         'nodal ordering: dofs 2k-1, 2k of a node consecutive')
      call t%check(any(perm(1::2) /= [(2*k - 1, k=1, m*m)]), 'nodal ordering: not the natural order')

      natural = [(k, k=1, a%n)]
      call s%analyze(a, error, natural)
      lnz_natural = s%nnz_factor
      call s%analyze(a, error)
      lnz_default = s%nnz_factor
      default_name = s%ordering
      call s%analyze(a, error, perm)
      lnz_nodal = s%nnz_factor
      write (*, '(a,i0,a,i0,a,i0,a,a,a)') '  nnz(L) on a 60x60-node grid, 2 dofs/node: natural ', &
         lnz_natural, ', nodal METIS ', lnz_nodal, ', CHOLMOD default ', lnz_default, ' (', default_name, ')'
      ! Banded natural order fills ~ n*2m; nested dissection O(n log n).
      call t%check(real(lnz_nodal, wp) < 0.5_wp*real(lnz_natural, wp), &
         'nodal METIS: less than half the fill of the natural order')
      ! AMD and nested dissection are both O(n log n) on 2D grids and within ~10% of
      ! each other at this size (observed ratio ~1.0); 1.25 flags a broken ordering.
      call t%check(real(lnz_nodal, wp) <= 1.25_wp*real(lnz_default, wp), &
         'nodal METIS: fill comparable to the default ordering')
   end subroutine test_nodal_ordering

   subroutine test_metis_edge_cases(t)
      type(checker_t), intent(inout) :: t
      integer(ip), allocatable :: perm(:)
      type(error_t), allocatable :: error

      allocate (perm(0))
      call metis_nodend(0, [1_i8], [integer(ip) ::], perm, error)
      call t%check(.not. allocated(error), 'metis: empty graph')
      deallocate (perm)
      allocate (perm(3))
      call metis_nodend(3, [1_i8, 1_i8, 1_i8, 1_i8], [integer(ip) ::], perm, error)
      call t%check(.not. allocated(error) .and. all(perm == [1, 2, 3]), 'metis: no edges gives natural order')
      call metis_nodend(3, [1_i8, 2_i8, 3_i8, 3_i8], [2, 2], perm, error)
      call t%check(allocated(error), 'metis: self loop is an error')
      call metis_nodend(3, [1_i8, 2_i8, 3_i8, 3_i8], [2, 4], perm, error)
      call t%check(allocated(error), 'metis: neighbour out of range is an error')
      ! a small connected graph (path 1-2-3) is ordered without error
      call metis_nodend(3, [1_i8, 2_i8, 4_i8, 5_i8], [2, 1, 3, 2], perm, error)
      call t%check(.not. allocated(error), 'metis: path of 3 vertices')
      call t%check(minval(perm) == 1 .and. maxval(perm) == 3 .and. perm(1) /= perm(2) .and. &
         perm(2) /= perm(3) .and. perm(1) /= perm(3), 'metis: path of 3 vertices gives a permutation')
   end subroutine test_metis_edge_cases

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

   ! Upper-triangle pattern with 2 dofs per node and full 2x2 node blocks
   ! (values are not needed for the analysis).
   function block_pattern(adj_ptr, adj) result(a)
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      type(sym_csc_t) :: a
      integer(ip) :: nnode, j, i, cj, ci
      integer(i8) :: p, q

      nnode = size(adj_ptr) - 1
      a%n = 2*nnode
      allocate (a%col_ptr(a%n + 1), a%row_idx(4*size(adj) + 3*nnode))
      q = 1
      do j = 1, nnode
         do cj = 1, 2
            a%col_ptr(2*j - 2 + cj) = q
            do p = adj_ptr(j), adj_ptr(j + 1) - 1
               i = adj(p)
               if (i > j) exit
               do ci = 1, 2
                  a%row_idx(q) = 2*i - 2 + ci
                  q = q + 1
               end do
            end do
            do ci = 1, cj
               a%row_idx(q) = 2*j - 2 + ci
               q = q + 1
            end do
         end do
      end do
      a%col_ptr(a%n + 1) = q
      a%row_idx = a%row_idx(:q - 1)
   end function block_pattern
end program test_solver_ordering
