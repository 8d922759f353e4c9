!> The partition of a mesh over the MPI processes of a distributed run: METIS's
!> k-way partition of the node graph (nodes adjacent when they share an element)
!> gives each node, and so its two rows of the matrix, to one process; each
!> element goes to the process that owns most of its nodes (the lowest such rank
!> on a tie), which assembles it.  Every process computes the same partition from
!> the same mesh (METIS is deterministic), so nothing is communicated.
!>
!> The nodes rather than the elements are partitioned because the rows decide the
!> balance of the solver, the dominant cost; the elements follow them closely.
module vemcontact_driver_partition
   use vemcontact_kinds, only: ip, i8
   use vemcontact_error, only: error_t
   use vemcontact_solver_metis, only: metis_partition
   implicit none
   private

   public :: partition_t, partition_mesh

   !> A partition into `nparts` parts, numbered 0 .. nparts-1 like the MPI ranks.
   type :: partition_t
      integer :: nparts = 0
      integer(ip), allocatable :: node_part(:)     !< the part of each node
      integer(ip), allocatable :: elem_part(:)     !< the part of each element
      integer(ip), allocatable :: nodes(:)         !< nodes of part k-1 in nodes(k)
      integer(ip), allocatable :: elements(:)      !< elements of part k-1 in elements(k)
      !> the dofs in the order of the parts, 2 per node (x, y), each part's nodes in
      !> the mesh's order: `perm(k)` is the dof with the k-th row of the distributed matrix
      integer(ip), allocatable :: perm(:)
   end type partition_t

contains

   !> The partition of the mesh of `nnode` nodes and the CSR connectivity
   !> `elem_ptr`/`elem_conn` into `nparts` parts; `adj_ptr`/`adj`: its node graph
   !> (vemcontact_solver_ordering's node_graph_from_elements).
   subroutine partition_mesh(nnode, elem_ptr, elem_conn, adj_ptr, adj, nparts, p, error)
      integer(ip), intent(in) :: nnode
      integer(ip), intent(in) :: elem_ptr(:), elem_conn(:)
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      integer, intent(in) :: nparts
      type(partition_t), intent(out) :: p
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: next(:)
      integer(ip) :: nelem, e, i, j, k, best, nbest, cnt, q, node
      p%nparts = nparts
      nelem = size(elem_ptr) - 1
      allocate (p%node_part(nnode), p%elem_part(nelem))
      call metis_partition(nnode, adj_ptr, adj, nparts, p%node_part, error)
      if (allocated(error)) return
      ! each element to the part of most of its nodes (the lowest part on a tie)
      do e = 1, nelem
         best = nparts
         nbest = 0
         do i = elem_ptr(e), elem_ptr(e + 1) - 1
            q = p%node_part(elem_conn(i))
            cnt = 0
            do j = elem_ptr(e), elem_ptr(e + 1) - 1
               if (p%node_part(elem_conn(j)) == q) cnt = cnt + 1
            end do
            if (cnt > nbest .or. (cnt == nbest .and. q < best)) then
               best = q
               nbest = cnt
            end if
         end do
         p%elem_part(e) = merge(best, 0_ip, nbest > 0)
      end do
      allocate (p%nodes(nparts), p%elements(nparts), source=0_ip)
      do node = 1, nnode
         p%nodes(p%node_part(node) + 1) = p%nodes(p%node_part(node) + 1) + 1
      end do
      do e = 1, nelem
         p%elements(p%elem_part(e) + 1) = p%elements(p%elem_part(e) + 1) + 1
      end do
      ! the nodes part by part (a counting sort: each part's nodes in the mesh's order)
      allocate (next(nparts), p%perm(2*nnode))
      next(1) = 1
      do k = 2, nparts
         next(k) = next(k - 1) + p%nodes(k - 1)
      end do
      do node = 1, nnode
         q = p%node_part(node) + 1
         k = next(q)
         p%perm(2*k - 1) = 2*node - 1
         p%perm(2*k) = 2*node
         next(q) = k + 1
      end do
   end subroutine partition_mesh
end module vemcontact_driver_partition
