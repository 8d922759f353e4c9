!> Fill-reducing ordering of the global dofs.  The ordering is computed on the
!> node graph (nodes adjacent when they share an element), which has a quarter
!> of the non-zeros of the dof graph, and expanded so that the two dofs of a
!> node stay consecutive: the 2x2 node blocks then fall into the same
!> supernodes of the Cholesky factor.
module vemcontact_solver_ordering
   use vemcontact_kinds, only: ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_internal
   use vemcontact_solver_metis, only: metis_nodend
   implicit none
   private

   public :: nodal_metis_ordering, nodal_metis_ordering_last, node_graph_from_elements

contains

   !> Dof permutation from METIS nested dissection of the node graph.
   !> `adj_ptr(nnode+1)` (integer(i8)) and `adj` are the 1-based CSR adjacency,
   !> symmetric, without self loops (as built by `node_graph_from_elements`).
   !> On return `perm(2*k-1:2*k) = [2*v-1, 2*v]` where v is the node METIS
   !> eliminates k-th; `perm(j)` is the original dof eliminated j-th, as
   !> `cholmod_solver_t%analyze` expects.
   subroutine nodal_metis_ordering(nnode, adj_ptr, adj, perm, error)
      integer(ip), intent(in) :: nnode
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      integer(ip), intent(out) :: perm(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: node_perm(:)
      integer(ip) :: k

      if (size(perm) /= 2*nnode) then
         call fatal_error(error, 'nodal_metis_ordering: perm must have 2*nnode entries', err_internal)
         return
      end if
      allocate (node_perm(nnode))
      call metis_nodend(nnode, adj_ptr, adj, node_perm, error)
      if (allocated(error)) return
      do k = 1, nnode
         perm(2*k - 1) = 2*node_perm(k) - 1
         perm(2*k) = 2*node_perm(k)
      end do
   end subroutine nodal_metis_ordering

   !> As `nodal_metis_ordering`, with the nodes `last` (distinct, 1..nnode)
   !> eliminated last, in the order given: METIS orders the graph without them.
   !> Their dofs then hold the factor's trailing block, from which the solver reads
   !> A^-1 on them (the contact compliance) by dense solves of their size.  For a
   !> contact interface between bodies, the interface is a separator of the graph,
   !> which nested dissection would also eliminate late.
   subroutine nodal_metis_ordering_last(nnode, adj_ptr, adj, last, perm, error)
      integer(ip), intent(in) :: nnode
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      integer(ip), intent(in) :: last(:)
      integer(ip), intent(out) :: perm(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: sub(:), orig(:), node_perm(:), sadj(:)
      integer(i8), allocatable :: sptr(:)
      integer(ip) :: i, k, ns
      integer(i8) :: p

      if (size(perm) /= 2*nnode .or. any(last < 1) .or. any(last > nnode)) then
         call fatal_error(error, 'nodal_metis_ordering_last: perm must have 2*nnode entries, last within 1..nnode', &
                          err_internal)
         return
      end if
      ! sub(i): node i's index in the graph without `last` (0 for the last ones)
      allocate (sub(nnode), source=1_ip)
      sub(last) = 0
      if (count(sub == 0) /= size(last)) then
         call fatal_error(error, 'nodal_metis_ordering_last: repeated node in last', err_internal)
         return
      end if
      ns = 0
      allocate (orig(nnode - size(last)))
      do i = 1, nnode
         if (sub(i) == 0) cycle
         ns = ns + 1
         sub(i) = ns
         orig(ns) = i
      end do
      allocate (sptr(ns + 1), sadj(count(sub(adj) > 0)))
      sptr(1) = 1
      do k = 1, ns
         i = orig(k)
         sptr(k + 1) = sptr(k)
         do p = adj_ptr(i), adj_ptr(i + 1) - 1
            if (sub(adj(p)) == 0) cycle
            sadj(sptr(k + 1)) = sub(adj(p))
            sptr(k + 1) = sptr(k + 1) + 1
         end do
      end do
      allocate (node_perm(ns))
      if (ns > 0) call metis_nodend(ns, sptr, sadj, node_perm, error)
      if (allocated(error)) return
      do k = 1, ns
         perm(2*k - 1) = 2*orig(node_perm(k)) - 1
         perm(2*k) = 2*orig(node_perm(k))
      end do
      do k = 1, size(last)
         perm(2*(ns + k) - 1) = 2*last(k) - 1
         perm(2*(ns + k)) = 2*last(k)
      end do
   end subroutine nodal_metis_ordering_last

   !> Node adjacency graph of a mesh: i and j (i /= j) are neighbours when they
   !> share an element.  `elem_ptr(nelem+1)`/`elem_conn` is the model's 1-based
   !> CSR connectivity.  Returns `adj_ptr(nnode+1)` (integer(i8)) and `adj`, each
   !> node's neighbours sorted and unique.  Memory beyond the result is
   !> O(connectivity + nnode); time is O(sum over elements of size**2).
   !> A node index outside 1..nnode is an err_internal error.
   pure subroutine node_graph_from_elements(nnode, elem_ptr, elem_conn, adj_ptr, adj, error)
      integer(ip), intent(in) :: nnode
      integer(ip), intent(in) :: elem_ptr(:)
      integer(ip), intent(in) :: elem_conn(:)
      integer(i8), allocatable, intent(out) :: adj_ptr(:)
      integer(ip), allocatable, intent(out) :: adj(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: node_ptr(:), node_elem(:), mark(:), unsorted(:)
      integer(i8), allocatable :: next(:)
      integer(ip) :: nelem, e, i, j, k, m
      integer(i8) :: p

      nelem = size(elem_ptr) - 1
      if (nelem < 0) then
         call fatal_error(error, 'node_graph_from_elements: elem_ptr is empty', err_internal)
         return
      end if
      if (nelem > 0) then
         if (elem_ptr(1) /= 1 .or. elem_ptr(nelem + 1) - 1 > size(elem_conn) .or. &
            any(elem_ptr(2:) < elem_ptr(:nelem))) then
            call fatal_error(error, 'node_graph_from_elements: invalid elem_ptr', err_internal)
            return
         end if
         if (any(elem_conn(:elem_ptr(nelem + 1) - 1) < 1) .or. &
            any(elem_conn(:elem_ptr(nelem + 1) - 1) > nnode)) then
            call fatal_error(error, 'node_graph_from_elements: node index out of range', err_internal)
            return
         end if
      end if

      ! Elements of each node (transpose of the connectivity).
      allocate (node_ptr(nnode + 1))
      node_ptr = 0
      do k = 1, elem_ptr(nelem + 1) - 1
         node_ptr(elem_conn(k) + 1) = node_ptr(elem_conn(k) + 1) + 1
      end do
      node_ptr(1) = 1
      do i = 1, nnode
         node_ptr(i + 1) = node_ptr(i + 1) + node_ptr(i)
      end do
      allocate (node_elem(node_ptr(nnode + 1) - 1), mark(nnode))
      mark(:) = node_ptr(:nnode)      ! fill position per node
      do e = 1, nelem
         do k = elem_ptr(e), elem_ptr(e + 1) - 1
            i = elem_conn(k)
            node_elem(mark(i)) = e
            mark(i) = mark(i) + 1
         end do
      end do

      ! Count, then fill, the distinct neighbours of each node; mark(j) == i
      ! means j is already listed for i.
      allocate (adj_ptr(nnode + 1))
      mark = 0
      adj_ptr(1) = 1
      do i = 1, nnode
         m = 0
         mark(i) = i
         do k = node_ptr(i), node_ptr(i + 1) - 1
            e = node_elem(k)
            do p = elem_ptr(e), elem_ptr(e + 1) - 1
               j = elem_conn(p)
               if (mark(j) /= i) then
                  mark(j) = i
                  m = m + 1
               end if
            end do
         end do
         adj_ptr(i + 1) = adj_ptr(i) + m
      end do
      allocate (unsorted(adj_ptr(nnode + 1) - 1))
      mark = 0
      do i = 1, nnode
         p = adj_ptr(i)
         mark(i) = i
         do k = node_ptr(i), node_ptr(i + 1) - 1
            e = node_elem(k)
            do m = elem_ptr(e), elem_ptr(e + 1) - 1
               j = elem_conn(m)
               if (mark(j) /= i) then
                  mark(j) = i
                  unsorted(p) = j
                  p = p + 1
               end if
            end do
         end do
      end do
      deallocate (node_ptr, node_elem, mark)

      ! The graph is symmetric, so its transpose has the same pointers; building
      ! it visits rows in increasing order and so leaves every list sorted, in
      ! O(nnz) whatever the node degrees.
      allocate (adj(size(unsorted)), next(nnode))
      next(:) = adj_ptr(:nnode)
      do i = 1, nnode
         do p = adj_ptr(i), adj_ptr(i + 1) - 1
            j = unsorted(p)
            adj(next(j)) = i
            next(j) = next(j) + 1
         end do
      end do
   end subroutine node_graph_from_elements
end module vemcontact_solver_ordering
