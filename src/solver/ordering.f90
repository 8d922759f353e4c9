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

   public :: nodal_metis_ordering, node_graph_from_elements

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
