!> The partition of a mesh over processes (vemcontact_driver_partition) on a
!> 40 x 20 quad grid in 3 parts: every node and element in one part, the counts
!> adding up, each part's nodes contiguous in the order `perm` (whole nodes),
!> every element in the part of most of its nodes, a compact partition (METIS's
!> cut far below a random one's), and the same partition when computed again
!> (every process computes its own).
program test_partition
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t
   use vemcontact_testing, only: checker_t
   use vemcontact_solver_ordering, only: node_graph_from_elements
   use vemcontact_driver_partition, only: partition_t, partition_mesh
   use vemcontact_test_polymesh, only: quad_grid
   implicit none
   type(checker_t) :: t
   type(partition_t) :: p, q
   type(error_t), allocatable :: error
   real(wp), allocatable :: x(:, :)
   integer(ip), allocatable :: ptr(:), conn(:), adj(:), cnt(:)
   integer(i8), allocatable :: adj_ptr(:)
   integer(i8) :: k, cut, edges
   integer(ip) :: nnode, nelem, e, i, node
   logical :: ok
   integer, parameter :: nparts = 3

   call quad_grid(40, 20, 0.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 0.0_wp, 1, x, ptr, conn)
   nnode = size(x, 2, kind=ip)
   nelem = size(ptr, kind=ip) - 1
   call node_graph_from_elements(nnode, ptr, conn, adj_ptr, adj, error)
   call t%check(.not. allocated(error), 'node graph')
   call partition_mesh(nnode, ptr, conn, adj_ptr, adj, nparts, p, error)
   call t%check(.not. allocated(error), 'partition without error')
   if (allocated(error)) call t%finish()
   call t%check(all(p%node_part >= 0 .and. p%node_part < nparts), 'node parts in 0..nparts-1')
   call t%check(all(p%elem_part >= 0 .and. p%elem_part < nparts), 'element parts in 0..nparts-1')
   call t%equal(sum(p%nodes), nnode, 'nodes per part add up')
   call t%equal(sum(p%elements), nelem, 'elements per part add up')
   ! METIS balances the nodes within 3 %; the elements follow (a quarter of an even share at least)
   call t%check(minval(p%nodes) >= nnode/(2*nparts) .and. minval(p%elements) >= nelem/(4*nparts), &
                'every part a fair share')
   ! perm: a permutation of the dofs, node by node, the parts one after the other
   ok = all(p%perm(2::2) == p%perm(1::2) + 1) .and. all(mod(p%perm(1::2), 2) == 1)
   allocate (cnt(nnode), source=0_ip)
   do i = 1, nnode
      node = (p%perm(2*i) + 1)/2
      if (node >= 1 .and. node <= nnode) cnt(node) = cnt(node) + 1
      if (i > 1) ok = ok .and. p%node_part((p%perm(2*i) + 1)/2) >= p%node_part((p%perm(2*i - 2) + 1)/2)
   end do
   call t%check(ok .and. all(cnt == 1), 'perm: whole nodes, every node once, part after part')
   ! each element in the part that holds most of its nodes
   ok = .true.
   do e = 1, nelem
      do i = ptr(e), ptr(e + 1) - 1
         ok = ok .and. count(p%node_part(conn(ptr(e):ptr(e + 1) - 1)) == p%elem_part(e)) >= &
              count(p%node_part(conn(ptr(e):ptr(e + 1) - 1)) == p%node_part(conn(i)))
      end do
   end do
   call t%check(ok, 'elements in the part of most of their nodes')
   ! a compact partition: a random one cuts 2/3 of the edges; 3 strips of the grid
   ! cut about 2 x 21 x 3 of about 4800 (1 %); 5 % leaves room for METIS's shapes
   cut = 0
   edges = adj_ptr(nnode + 1) - 1
   do node = 1, nnode
      do k = adj_ptr(node), adj_ptr(node + 1) - 1
         if (p%node_part(adj(k)) /= p%node_part(node)) cut = cut + 1
      end do
   end do
   call t%check(real(cut, wp) < 0.05_wp*real(edges, wp), 'edge cut below 5 % of the edges')
   call partition_mesh(nnode, ptr, conn, adj_ptr, adj, nparts, q, error)
   call t%check(all(q%node_part == p%node_part) .and. all(q%elem_part == p%elem_part), &
                'the same partition computed again')
   call t%finish()
end program test_partition
