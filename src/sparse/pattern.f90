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

   public :: build_pattern, add_element_matrix, add_element_matrix_searched, block_offset

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
   !> The nodes are put in ascending order (insertion sort of the element's few
   !> nodes), so that the rows of each node's column are found by one forward
   !> walk through that column instead of a search per node pair.  Each entry of
   !> a receives exactly one term of ke, so the result does not depend on how
   !> the entries are found.
   pure subroutine add_element_matrix(a, nodes, ke, ok)
      type(sym_csc_t), intent(inout) :: a
      integer(ip), intent(in) :: nodes(:)
      real(wp), intent(in) :: ke(:, :)
      logical, intent(out) :: ok
      integer :: s(size(nodes))
      integer :: i, j, t
      ! s: local node numbers in ascending order of the global ones
      do i = 1, size(nodes)
         t = i
         j = i - 1
         do while (j >= 1)
            if (nodes(s(j)) <= nodes(t)) exit
            s(j + 1) = s(j)
            j = j - 1
         end do
         s(j + 1) = t
      end do
      do i = 2, size(nodes)
         if (nodes(s(i)) == nodes(s(i - 1))) then
            ! a repeated node (contact springs may pair a node with a side through it)
            call add_element_matrix_searched(a, nodes, ke, ok)
            return
         end if
      end do
      ! the arrays as arguments of their own: a store into val cannot change col_ptr or row_idx
      call add_sorted(a%col_ptr, a%row_idx, a%val, nodes, s, ke, ok)
   end subroutine add_element_matrix

   !> add_element_matrix for distinct nodes, s their local numbers in ascending order.
   pure subroutine add_sorted(col_ptr, row_idx, val, nodes, s, ke, ok)
      integer(i8), intent(in) :: col_ptr(:)
      integer(ip), intent(in) :: row_idx(:)
      real(wp), intent(inout) :: val(:)
      integer(ip), intent(in) :: nodes(:)
      integer, intent(in) :: s(:)
      real(wp), intent(in) :: ke(:, :)
      logical, intent(out) :: ok
      integer :: i, j, p, q, lp, lq
      integer(ip) :: nj, target
      integer(i8) :: c1, c2, c3, pos, off
      ok = .true.
      do j = 1, size(nodes)
         q = s(j)
         nj = nodes(q)
         lq = 2*q - 1
         c1 = col_ptr(2*nj - 1)
         c2 = col_ptr(2*nj)
         c3 = col_ptr(2*nj + 1)
         ! column 2J-1 holds the x-dof rows 2I-1 of its lower neighbours at c1, c1 + 2, ...
         ! and ends with the diagonal 2J-1, which is larger than every target: the walk stops
         pos = c1
         do i = 1, j - 1
            p = s(i)
            lp = 2*p - 1
            target = 2*nodes(p) - 1
            do while (row_idx(pos) < target)
               pos = pos + 2
            end do
            if (row_idx(pos) /= target) then
               ok = .false.
               return
            end if
            off = pos - c1
            ! rows 2I-1, 2I of columns 2J-1 and 2J
            val(pos) = val(pos) + ke(lp, lq)
            val(pos + 1) = val(pos + 1) + ke(lp + 1, lq)
            val(c2 + off) = val(c2 + off) + ke(lp, lq + 1)
            val(c2 + off + 1) = val(c2 + off + 1) + ke(lp + 1, lq + 1)
         end do
         ! diagonal block: last entry of column 2J-1, last two of column 2J
         val(c2 - 1) = val(c2 - 1) + ke(lq, lq)
         val(c3 - 2) = val(c3 - 2) + ke(lq, lq + 1)
         val(c3 - 1) = val(c3 - 1) + ke(lq + 1, lq + 1)
      end do
   end subroutine add_sorted

   !> add_element_matrix by one binary search per node pair (the scatter before
   !> issue 15, kept for bench/assembly_rate.f90), for node lists with a repeated
   !> node (the diagonal block then receives every pair of its copies).
   pure subroutine add_element_matrix_searched(a, nodes, ke, ok)
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
               a%val(c2 - 1) = a%val(c2 - 1) + ke(lp, lq)
               a%val(a%col_ptr(2*nj + 1) - 2) = a%val(a%col_ptr(2*nj + 1) - 2) + ke(lp, lq + 1)
               a%val(a%col_ptr(2*nj + 1) - 1) = a%val(a%col_ptr(2*nj + 1) - 1) + ke(lp + 1, lq + 1)
            end if
         end do
      end do
   end subroutine add_element_matrix_searched
end module vemcontact_sparse_pattern
