!> Sparsity pattern of the global stiffness matrix, built once from the node
!> graph, and the scatter of element matrices into it.
!>
!> Two dofs per node.  Column j of the upper-triangle CSC matrix holds the rows of
!> all dofs of the nodes I <= J adjacent to node J (J the node of dof j), so the
!> pattern is the node graph expanded to 2x2 blocks.  Entries of a node block are
!> found with one binary search per node pair, not per dof pair.
module vemcontact_sparse_pattern
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_sparse_matrix, only: sym_csc_t
   implicit none
   private

   public :: build_pattern, add_element_matrix, block_offset

contains

   !> Build the dof pattern (values zeroed) from a node adjacency graph.
   !> adj_ptr/adj: CSR node graph, 1-based, symmetric, sorted neighbours, no self loops.
   subroutine build_pattern(nnode, adj_ptr, adj, a)
      integer(ip), intent(in) :: nnode
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      type(sym_csc_t), intent(out) :: a
      integer(ip) :: jn, in, nlow
      integer(i8) :: k, pos
      a%n = 2*nnode
      allocate (a%col_ptr(a%n + 1))
      a%col_ptr(1) = 1
      do jn = 1, nnode
         nlow = count_lower(jn)
         a%col_ptr(2*jn) = a%col_ptr(2*jn - 1) + 2*nlow + 1
         a%col_ptr(2*jn + 1) = a%col_ptr(2*jn) + 2*nlow + 2
      end do
      allocate (a%row_idx(a%col_ptr(a%n + 1) - 1))
      allocate (a%val(size(a%row_idx)), source=0.0_wp)
      do jn = 1, nnode
         ! column 2J-1: both dofs of lower neighbours, then 2J-1 itself
         pos = a%col_ptr(2*jn - 1)
         do k = adj_ptr(jn), adj_ptr(jn + 1) - 1
            in = adj(k)
            if (in >= jn) exit
            a%row_idx(pos) = 2*in - 1
            a%row_idx(pos + 1) = 2*in
            pos = pos + 2
         end do
         a%row_idx(pos) = 2*jn - 1
         ! column 2J: the same plus 2J-1 and 2J
         pos = a%col_ptr(2*jn)
         do k = adj_ptr(jn), adj_ptr(jn + 1) - 1
            in = adj(k)
            if (in >= jn) exit
            a%row_idx(pos) = 2*in - 1
            a%row_idx(pos + 1) = 2*in
            pos = pos + 2
         end do
         a%row_idx(pos) = 2*jn - 1
         a%row_idx(pos + 1) = 2*jn
      end do
   contains
      pure integer(ip) function count_lower(j) result(c)
         integer(ip), intent(in) :: j
         integer(i8) :: kk
         c = 0
         do kk = adj_ptr(j), adj_ptr(j + 1) - 1
            if (adj(kk) < j) c = c + 1
         end do
      end function count_lower
   end subroutine build_pattern

   !> Offset of the x-dof row of node `in` within the columns of node `jn` (in <= jn),
   !> i.e. a%val(a%col_ptr(2*jn-1) + off) is entry (2*in-1, 2*jn-1); -1 if absent.
   pure function block_offset(a, in, jn) result(off)
      type(sym_csc_t), intent(in) :: a
      integer(ip), intent(in) :: in, jn
      integer(i8) :: off
      integer(i8) :: lo, hi, mid, first
      integer(ip) :: target, r
      first = a%col_ptr(2*jn - 1)
      target = 2*in - 1
      lo = first
      hi = a%col_ptr(2*jn) - 1     ! last entry of column 2J-1 is the diagonal
      do while (lo <= hi)
         mid = (lo + hi)/2
         r = a%row_idx(mid)
         if (r == target) then
            off = mid - first
            return
         else if (r < target) then
            lo = mid + 1
         else
            hi = mid - 1
         end if
      end do
      off = -1
   end function block_offset

   !> Add a dense element matrix ke (dof order u1x,u1y,u2x,...) of the nodes
   !> `nodes` into a.  Only the upper triangle of the global matrix is touched;
   !> ke must be symmetric.  `ok` is false if a node pair is missing from the pattern.
   pure subroutine add_element_matrix(a, nodes, ke, ok)
      type(sym_csc_t), intent(inout) :: a
      integer(ip), intent(in) :: nodes(:)
      real(wp), intent(in) :: ke(:, :)
      logical, intent(out) :: ok
      integer :: p, q, lp, lq
      integer(ip) :: ni, nj
      integer(i8) :: off, c1, c2
      ok = .true.
      do q = 1, size(nodes)
         nj = nodes(q)
         lq = 2*q - 1
         c1 = a%col_ptr(2*nj - 1)
         c2 = a%col_ptr(2*nj)
         do p = 1, size(nodes)
            ni = nodes(p)
            lp = 2*p - 1
            if (ni < nj) then
               off = block_offset(a, ni, nj)
               if (off < 0) then
                  ok = .false.
                  return
               end if
               ! rows 2I-1, 2I of columns 2J-1 and 2J
               a%val(c1 + off) = a%val(c1 + off) + ke(lp, lq)
               a%val(c1 + off + 1) = a%val(c1 + off + 1) + ke(lp + 1, lq)
               a%val(c2 + off) = a%val(c2 + off) + ke(lp, lq + 1)
               a%val(c2 + off + 1) = a%val(c2 + off + 1) + ke(lp + 1, lq + 1)
            else if (ni == nj) then
               ! diagonal block: last entry of column 2J-1, last two of column 2J.
               ! p == q here unless an element repeats a node (rejected upstream).
               a%val(c2 - 1) = a%val(c2 - 1) + ke(lp, lq)
               a%val(a%col_ptr(2*nj + 1) - 2) = a%val(a%col_ptr(2*nj + 1) - 2) + ke(lp, lq + 1)
               a%val(a%col_ptr(2*nj + 1) - 1) = a%val(a%col_ptr(2*nj + 1) - 1) + ke(lp + 1, lq + 1)
            end if
         end do
      end do
   end subroutine add_element_matrix
end module vemcontact_sparse_pattern
