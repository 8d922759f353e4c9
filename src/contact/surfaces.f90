!> Slave nodes and master segments of a *CONTACT PAIR, from the model's surfaces.
!>
!> Master segments are the sides of a TYPE=ELEMENT surface in the orientation of
!> their counter-clockwise element (side k from node k to node k+1), so the
!> outward normal of the master body is (t_y, -t_x)/l.  Each slave node carries
!> its undeformed tributary length L_s and a thickness, so that the penalty
!> k_s = K * L_s * thickness turns the pressure slope K into a nodal spring.
!> Everything here is set-up work done once per pair, O(connectivity).
!>
!> Second-order sides (corner a, corner b, side node m of a VPE2/VPS2, CPE8/CPS8
!> or CPE6/CPS6 element): the master side gives two straight segments a -> m and
!> m -> b (exact for the straight sides of the k = 2 virtual element, a chord
!> approximation of a curved FEM side), and the slave points are all three nodes
!> with the consistent tributary lengths of a uniform pressure on a quadratic
!> side, l/6 at each corner and 4l/6 at the side node (l = |b - a|).
module vemcontact_contact_surfaces
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, fatal_error, append_message, err_input, err_internal
   use vemcontact_model, only: model_t, contact_pair_t, surface_t, location_string, &
                               surface_element, surface_node, element_side, element_order
   use vemcontact_contact_geometry, only: segment_is_degenerate, length2
   use vemcontact_text, only: int_text
   implicit none
   private

   public :: master_segments, slave_nodes, slave_edges

   ! A pair lists at most this many offending entities before "... and N more".
   integer, parameter :: max_listed = 20

contains

   !> Master segments of `pair`: seg(:, k) = (a, b) node indices of the k-th
   !> segment of the master surface in element orientation, seg_elem(k) its element,
   !> seg_side(k) its side.  A first-order side is one segment; a second-order
   !> side (a, b, side node m) is two, a -> m and m -> b, in this order.  Errors
   !> (all listed): a master surface that is not of TYPE=ELEMENT, an element side
   !> shared with another element (not on the mesh boundary), a zero-length side.
   pure subroutine master_segments(model, pair, seg, seg_elem, seg_side, error)
      type(model_t), intent(in) :: model
      type(contact_pair_t), intent(in) :: pair
      integer(ip), allocatable, intent(out) :: seg(:, :)
      integer(ip), allocatable, intent(out) :: seg_elem(:)
      integer, allocatable, intent(out) :: seg_side(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: node_ptr(:), node_elem(:)
      integer(ip) :: e, other, abc(3)
      integer :: k, nfac, nbad, nseg, ns
      character(len=:), allocatable :: where

      call check_surface_index(model, pair%master, 'master', error)
      if (allocated(error)) return
      associate (surf => model%surfaces(pair%master))
         where = surface_where(model, surf)
         if (surf%kind /= surface_element) then
            call fatal_error(error, where//': a master surface must be of TYPE=ELEMENT', err_input)
            return
         end if
         call check_facets(model, surf, where, error)
         if (allocated(error)) return
         nfac = size(surf%elem)
         nseg = 0
         do k = 1, nfac
            nseg = nseg + facet_order(model, surf%elem(k))
         end do
         allocate (seg(2, nseg), seg_elem(nseg), seg_side(nseg))
         call node_elements(model, node_ptr, node_elem)
         nbad = 0
         nseg = 0
         do k = 1, nfac
            e = surf%elem(k)
            call element_side(model, e, surf%side(k), abc, ns)
            if (abc(3) == 0) then
               seg(:, nseg + 1) = abc(1:2)
               seg_elem(nseg + 1) = e
               seg_side(nseg + 1) = surf%side(k)
               nseg = nseg + 1
            else
               seg(:, nseg + 1) = [abc(1), abc(3)]
               seg(:, nseg + 2) = [abc(3), abc(2)]
               seg_elem(nseg + 1:nseg + 2) = e
               seg_side(nseg + 1:nseg + 2) = surf%side(k)
               nseg = nseg + 2
            end if
            other = other_element(model, node_ptr, node_elem, e, abc(1), abc(2))
            if (other /= 0) then
               nbad = nbad + 1
               if (nbad <= max_listed) call append_message(error, where//': element '// &
                  int_text(model%elem_id(e))//' side '//int_text(surf%side(k))//' is shared with element '// &
                  int_text(model%elem_id(other))//', not on the mesh boundary: a master surface must be '// &
                  'an outer boundary', err_input)
            else if (segment_is_degenerate(model%x(:, abc(1)), model%x(:, abc(2)))) then
               nbad = nbad + 1
               if (nbad <= max_listed) call append_message(error, where//': element '// &
                  int_text(model%elem_id(e))//' side '//int_text(surf%side(k))//' has zero length (nodes '// &
                  int_text(node_user(model, abc(1)))//' and '//int_text(node_user(model, abc(2)))// &
                  ' coincide)', err_input)
            end if
         end do
         if (nbad > max_listed) call append_message(error, '... and '//int_text(nbad - max_listed)//' more')
      end associate
   end subroutine master_segments

   !> Slave nodes of `pair`, sorted, with their undeformed tributary length
   !> `length` and thickness `thick` (k_s = K * length * thick).
   !> Element surface: the facets' end nodes, each facet giving half its length
   !> to each end; a second-order facet (a, b, side node m) gives all three
   !> nodes, l/6 to a and b and 4l/6 to m, l = |m - a| + |b - m| (the consistent
   !> nodal forces of a uniform pressure on a quadratic side, so that equal
   !> pressures at the three nodes transmit exactly that pressure).  The same
   !> holds for the boundary sides of a node surface, whose side nodes belong
   !> to the face whether the set lists them or not.  Node surface: the mesh boundary edges (used by one element)
   !> with both ends in the set, or one end in the set and the other a node of
   !> the master surface outside the set (the tip shared by the faces of a
   !> joint, which a mesher leaves out), half to each end, thickness from that
   !> edge's element.  A node fed by elements of different thickness gets the
   !> length-weighted mean, so that length*thick = sum of (l/2)*t_e exactly.
   !> Nodes that are also nodes of the master surface (a joint tip, nodes shared
   !> by bonded bodies) are dropped and counted in `nexcluded`: a node cannot
   !> penetrate a segment it belongs to.  A remaining node with zero tributary
   !> length would get no spring: an error naming it.
   pure subroutine slave_nodes(model, pair, node, length, thick, nexcluded, error)
      type(model_t), intent(in) :: model
      type(contact_pair_t), intent(in) :: pair
      integer(ip), allocatable, intent(out) :: node(:)
      real(wp), allocatable, intent(out) :: length(:), thick(:)
      integer(ip), intent(out) :: nexcluded
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: node_ptr(:), node_elem(:)
      logical, allocatable :: in_slave(:), in_master(:)
      real(wp), allocatable :: lsum(:), ltsum(:)
      integer(ip) :: i, p, q, e, n, m, nbad
      integer :: k, j, ns
      integer(ip) :: ab(2), abc(3)
      real(wp) :: l
      character(len=:), allocatable :: where

      nexcluded = 0
      call check_surface_index(model, pair%slave, 'slave', error)
      if (allocated(error)) return
      call check_surface_index(model, pair%master, 'master', error)
      if (allocated(error)) return
      if (.not. allocated(model%elem_thick)) then
         call fatal_error(error, 'slave_nodes: element thicknesses not set', err_internal)
         return
      end if
      n = model%nnode
      allocate (in_slave(n), in_master(n), source=.false.)
      allocate (lsum(n), ltsum(n), source=0.0_wp)

      ! nodes of the master surface
      associate (ms => model%surfaces(pair%master))
         if (ms%kind == surface_element) then
            call check_facets(model, ms, surface_where(model, ms), error)
            if (allocated(error)) return
            do k = 1, size(ms%elem)
               call element_side(model, ms%elem(k), ms%side(k), abc, ns)
               in_master(pack(abc, abc > 0)) = .true.
            end do
         end if
      end associate

      associate (surf => model%surfaces(pair%slave))
         where = surface_where(model, surf)
         select case (surf%kind)
         case (surface_element)
            call check_facets(model, surf, where, error)
            if (allocated(error)) return
            do k = 1, size(surf%elem)
               e = surf%elem(k)
               call element_side(model, e, surf%side(k), abc, ns)
               if (abc(3) /= 0) then
                  in_slave(abc(1:2)) = .true.
                  call add_quadratic_side(model, e, abc, in_slave, lsum, ltsum)
                  cycle
               end if
               ab = abc(1:2)
               l = length2(model%x(:, ab(2)) - model%x(:, ab(1)))
               in_slave(ab) = .true.
               lsum(ab) = lsum(ab) + 0.5_wp*l
               ltsum(ab) = ltsum(ab) + 0.5_wp*l*model%elem_thick(e)
            end do
         case (surface_node)
            if (allocated(surf%nodes)) then
               if (any(surf%nodes < 1) .or. any(surf%nodes > n)) then
                  call fatal_error(error, where//': node index out of range', err_internal)
                  return
               end if
               in_slave(surf%nodes) = .true.
               call node_elements(model, node_ptr, node_elem)
               ! A boundary edge of the face joins two nodes of the set, or a node of
               ! the set and a node of the master surface left out of it (the tip
               ! shared by the two faces of a joint).  Every boundary edge is side
               ! a -> b of exactly one element: from each node p of the set, the side
               ! p -> q is taken when q is in the set or on the master, the side
               ! q -> p only when q is on the master and not in the set (otherwise it
               ! is taken from q), so each edge is counted once.
               do k = 1, size(surf%nodes)
                  p = surf%nodes(k)
                  do j = node_ptr(p), node_ptr(p + 1) - 1
                     e = node_elem(j)
                     if (facet_order(model, e) == 2) then
                        call add_quadratic_edges(model, node_ptr, node_elem, e, p, in_master, &
                                                 in_slave, lsum, ltsum)
                        cycle
                     end if
                     q = next_in_element(model, e, p)
                     if (in_slave(q) .or. in_master(q)) &
                        call add_boundary_edge(model, node_ptr, node_elem, e, p, q, lsum, ltsum)
                     q = previous_in_element(model, e, p)
                     if (in_master(q) .and. .not. in_slave(q)) &
                        call add_boundary_edge(model, node_ptr, node_elem, e, q, p, lsum, ltsum)
                  end do
               end do
            end if
         case default
            call fatal_error(error, where//': unknown surface type', err_internal)
            return
         end select

         ! drop master nodes, then every remaining node needs a spring
         m = 0
         nbad = 0
         do i = 1, n
            if (.not. in_slave(i)) cycle
            if (in_master(i)) then
               nexcluded = nexcluded + 1
               in_slave(i) = .false.
            else if (.not. (lsum(i) > 0.0_wp)) then
               nbad = nbad + 1
               if (nbad <= max_listed) call append_message(error, where//': slave node '// &
                  int_text(node_user(model, i))//' has no tributary length (no mesh boundary edge to '// &
                  'another node of the surface, or only zero-length facets): it would get no contact spring', &
                  err_input)
            else
               m = m + 1
            end if
         end do
         if (nbad > max_listed) call append_message(error, '... and '//int_text(nbad - max_listed)//' more')
         if (allocated(error)) return
      end associate

      allocate (node(m), length(m), thick(m))
      m = 0
      do i = 1, n
         if (.not. in_slave(i)) cycle
         m = m + 1
         node(m) = i
         length(m) = lsum(i)
         thick(m) = ltsum(i)/lsum(i)
      end do
   end subroutine slave_nodes

   !> Sides of the slave face of `pair` in element orientation: edge(:, k) = (a, b),
   !> the side's corners (a second-order side's middle node is element_side's third),
   !> side edge_side(k) of element edge_elem(k).  Element surface: its facets.  Node
   !> surface: the mesh boundary edges (used by one element) whose ends are both in the
   !> set, or one in the set and the other a node of the master surface (the edge to a
   !> joint tip that the set leaves out).
   pure subroutine slave_edges(model, pair, edge, edge_elem, edge_side, error)
      type(model_t), intent(in) :: model
      type(contact_pair_t), intent(in) :: pair
      integer(ip), allocatable, intent(out) :: edge(:, :), edge_elem(:)
      integer, allocatable, intent(out) :: edge_side(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: node_ptr(:), node_elem(:), be(:, :), bel(:)
      integer, allocatable :: bside(:)
      logical, allocatable :: in_slave(:), in_master(:)
      integer(ip) :: e, p, q, m, abc(3)
      integer :: k, j, ns
      call check_surface_index(model, pair%slave, 'slave', error)
      if (allocated(error)) return
      call check_surface_index(model, pair%master, 'master', error)
      if (allocated(error)) return
      associate (surf => model%surfaces(pair%slave), ms => model%surfaces(pair%master))
         if (surf%kind == surface_element) then
            call check_facets(model, surf, surface_where(model, surf), error)
            if (allocated(error)) return
            allocate (edge(2, size(surf%elem)), edge_elem(size(surf%elem)), edge_side(size(surf%elem)))
            do k = 1, size(surf%elem)
               call element_side(model, surf%elem(k), surf%side(k), abc, ns)
               edge(:, k) = abc(1:2)
            end do
            edge_elem = surf%elem
            edge_side = surf%side
            return
         end if
         allocate (in_slave(model%nnode), in_master(model%nnode), source=.false.)
         if (allocated(surf%nodes)) in_slave(surf%nodes) = .true.
         if (ms%kind == surface_element) then
            call check_facets(model, ms, surface_where(model, ms), error)
            if (allocated(error)) return
            do k = 1, size(ms%elem)
               call element_side(model, ms%elem(k), ms%side(k), abc, ns)
               in_master(abc(1:2)) = .true.
            end do
         end if
         call node_elements(model, node_ptr, node_elem)
         allocate (be(2, 16), bel(16), bside(16))
         m = 0
         ! every side of an element that touches the set, once: from its start corner
         do e = 1, model%nelem
            call element_side(model, e, 1, abc, ns)
            do j = 0, ns - 1
               call element_side(model, e, j + 1, abc, ns)
               p = abc(1)
               q = abc(2)
               if (.not. ((in_slave(p) .and. (in_slave(q) .or. in_master(q))) .or. &
                          (in_slave(q) .and. in_master(p)))) cycle
               if (other_element(model, node_ptr, node_elem, e, p, q) /= 0) cycle
               m = m + 1
               if (m > size(bel)) then
                  be = reshape([be, spread(0_ip, 1, 2*size(bel))], [2, 2*size(bel)])
                  bel = [bel, spread(0_ip, 1, size(bel))]
                  bside = [bside, spread(0, 1, size(bside))]
               end if
               be(:, m) = [p, q]
               bel(m) = e
               bside(m) = j + 1
            end do
         end do
         edge = be(:, :m)
         edge_elem = bel(:m)
         edge_side = bside(:m)
      end associate
   end subroutine slave_edges

   pure subroutine check_surface_index(model, isurf, role, error)
      type(model_t), intent(in) :: model
      integer, intent(in) :: isurf
      character(len=*), intent(in) :: role
      type(error_t), allocatable, intent(out) :: error
      logical :: bad
      bad = .not. allocated(model%surfaces)
      if (.not. bad) bad = isurf < 1 .or. isurf > size(model%surfaces)
      if (bad) call fatal_error(error, 'contact pair: '//role//' surface index '//int_text(isurf)// &
                                ' out of range', err_internal)
   end subroutine check_surface_index

   !> Facet arrays present, elements and sides in range.
   pure subroutine check_facets(model, surf, where, error)
      type(model_t), intent(in) :: model
      type(surface_t), intent(in) :: surf
      character(len=*), intent(in) :: where
      type(error_t), allocatable, intent(out) :: error
      integer :: k
      integer(ip) :: e
      if (.not. (allocated(surf%elem) .and. allocated(surf%side))) then
         call fatal_error(error, where//': element surface without facets', err_internal)
         return
      end if
      if (size(surf%elem) /= size(surf%side)) then
         call fatal_error(error, where//': facet arrays differ in size', err_internal)
         return
      end if
      do k = 1, size(surf%elem)
         e = surf%elem(k)
         if (e < 1 .or. e > model%nelem) then
            call fatal_error(error, where//': element index '//int_text(e)//' out of range', err_internal)
            return
         end if
         if (surf%side(k) < 1 .or. surf%side(k) > model%elem_ptr(e + 1) - model%elem_ptr(e)) then
            call fatal_error(error, where//': element '//int_text(model%elem_id(e))//' has no side '// &
                             int_text(surf%side(k)), err_input)
            return
         end if
      end do
   end subroutine check_facets

   !> If side a -> b of element e is a mesh boundary edge (no other element
   !> has it), half its length goes to each end, weighted by e's thickness in ltsum.
   pure subroutine add_boundary_edge(model, node_ptr, node_elem, e, a, b, lsum, ltsum)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: node_ptr(:), node_elem(:), e, a, b
      real(wp), intent(inout) :: lsum(:), ltsum(:)
      real(wp) :: l
      if (other_element(model, node_ptr, node_elem, e, a, b) /= 0) return
      l = length2(model%x(:, b) - model%x(:, a))
      lsum([a, b]) = lsum([a, b]) + 0.5_wp*l
      ltsum([a, b]) = ltsum([a, b]) + 0.5_wp*l*model%elem_thick(e)
   end subroutine add_boundary_edge

   !> Side abc = (a, b, side node m) of second-order element e: m becomes a slave
   !> node (the corners are the caller's business), l/6 of the side's length l = |m - a| + |b - m|
   !> at each corner and 4l/6 at m (weighted by e's thickness in ltsum).
   pure subroutine add_quadratic_side(model, e, abc, in_slave, lsum, ltsum)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: e, abc(3)
      logical, intent(inout) :: in_slave(:)
      real(wp), intent(inout) :: lsum(:), ltsum(:)
      real(wp) :: l, w(3)
      l = length2(model%x(:, abc(3)) - model%x(:, abc(1))) + length2(model%x(:, abc(2)) - model%x(:, abc(3)))
      w = [1.0_wp, 1.0_wp, 4.0_wp]*(l/6.0_wp)
      in_slave(abc(3)) = .true.
      lsum(abc) = lsum(abc) + w
      ltsum(abc) = ltsum(abc) + w*model%elem_thick(e)
   end subroutine add_quadratic_side

   !> Node surface, second-order element e at corner p of the set: the boundary
   !> sides of e that start at p and end at a node of the set or of the master
   !> surface, and those that end at p and start at a master node outside the set
   !> (the rule of the first-order edges, so that each side is counted once),
   !> each added by add_quadratic_side.
   pure subroutine add_quadratic_edges(model, node_ptr, node_elem, e, p, in_master, in_slave, lsum, ltsum)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: node_ptr(:), node_elem(:), e, p
      logical, intent(in) :: in_master(:)
      logical, intent(inout) :: in_slave(:)
      real(wp), intent(inout) :: lsum(:), ltsum(:)
      integer(ip) :: abc(3)
      integer :: k, ns
      logical :: take
      call element_side(model, e, 1, abc, ns)
      do k = 1, ns
         call element_side(model, e, k, abc, ns)
         take = .false.
         if (abc(1) == p) take = in_slave(abc(2)) .or. in_master(abc(2))
         if (abc(2) == p) take = in_master(abc(1)) .and. .not. in_slave(abc(1))
         if (.not. take) cycle
         if (other_element(model, node_ptr, node_elem, e, abc(1), abc(2)) /= 0) cycle
         call add_quadratic_side(model, e, abc, in_slave, lsum, ltsum)
      end do
   end subroutine add_quadratic_edges

   !> Order of element e's sides: 2 when they carry a side node.
   pure integer function facet_order(model, e)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: e
      facet_order = 1
      if (allocated(model%elem_type)) facet_order = element_order(model%elem_type(e))
   end function facet_order

   !> The node before p in element e (counter-clockwise).
   pure integer(ip) function previous_in_element(model, e, p) result(q)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: e, p
      q = neighbour_in_element(model, e, p, -1)
   end function previous_in_element

   !> The node after p in element e (counter-clockwise).
   pure integer(ip) function next_in_element(model, e, p) result(q)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: e, p
      q = neighbour_in_element(model, e, p, 1)
   end function next_in_element

   !> The node `shift` places after p in element e (counter-clockwise), 0 if p is
   !> not a node of e.
   pure integer(ip) function neighbour_in_element(model, e, p, shift) result(q)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: e, p
      integer, intent(in) :: shift
      integer(ip) :: p0, n, k
      p0 = model%elem_ptr(e)
      n = model%elem_ptr(e + 1) - p0
      q = 0
      do k = 0, n - 1
         if (model%elem_conn(p0 + k) == p) then
            q = model%elem_conn(p0 + modulo(k + shift, n))
            return
         end if
      end do
   end function neighbour_in_element

   !> An element other than e with a side joining corners p and q, 0 if there is none.
   pure integer(ip) function other_element(model, node_ptr, node_elem, e, p, q) result(f)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: node_ptr(:), node_elem(:), e, p, q
      integer(ip) :: j, abc(3)
      integer :: k, ns
      do j = node_ptr(p), node_ptr(p + 1) - 1
         f = node_elem(j)
         if (f == e) cycle
         call element_side(model, f, 1, abc, ns)
         do k = 1, ns
            call element_side(model, f, k, abc, ns)
            if ((abc(1) == p .and. abc(2) == q) .or. (abc(1) == q .and. abc(2) == p)) return
         end do
      end do
      f = 0
   end function other_element

   !> Elements of each node (transpose of the connectivity), CSR.
   pure subroutine node_elements(model, node_ptr, node_elem)
      type(model_t), intent(in) :: model
      integer(ip), allocatable, intent(out) :: node_ptr(:), node_elem(:)
      integer(ip), allocatable :: fill(:)
      integer(ip) :: e, k, i
      allocate (node_ptr(model%nnode + 1), source=0_ip)
      do k = 1, model%elem_ptr(model%nelem + 1) - 1
         i = model%elem_conn(k)
         node_ptr(i + 1) = node_ptr(i + 1) + 1
      end do
      node_ptr(1) = 1
      do i = 1, model%nnode
         node_ptr(i + 1) = node_ptr(i + 1) + node_ptr(i)
      end do
      allocate (node_elem(node_ptr(model%nnode + 1) - 1))
      fill = node_ptr(:model%nnode)
      do e = 1, model%nelem
         do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
            i = model%elem_conn(k)
            node_elem(fill(i)) = e
            fill(i) = fill(i) + 1
         end do
      end do
   end subroutine node_elements

   pure function surface_where(model, surf) result(s)
      type(model_t), intent(in) :: model
      type(surface_t), intent(in) :: surf
      character(len=:), allocatable :: s
      s = location_string(model, surf%loc)//': *SURFACE '
      if (allocated(surf%name)) s = s//surf%name
   end function surface_where

   pure integer(ip) function node_user(model, i) result(id)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: i
      id = i
      if (allocated(model%node_id)) id = model%node_id(i)
   end function node_user

end module vemcontact_contact_surfaces
