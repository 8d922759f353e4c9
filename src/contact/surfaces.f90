!> Slave nodes and master segments of a *CONTACT PAIR, from the model's surfaces.
!>
!> Master segments are the sides of a TYPE=ELEMENT surface in the orientation of
!> their counter-clockwise element (side k from node k to node k+1), so the
!> outward normal of the master body is (t_y, -t_x)/l.  Each slave node carries
!> its undeformed tributary length L_s and a thickness, so that the penalty
!> k_s = K * L_s * thickness turns the pressure slope K into a nodal spring.
!> Everything here is set-up work done once per pair, O(connectivity).
module vemcontact_contact_surfaces
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, fatal_error, append_message, err_input, err_internal
   use vemcontact_model, only: model_t, contact_pair_t, surface_t, location_string, &
                               surface_element, surface_node
   use vemcontact_contact_geometry, only: segment_is_degenerate, length2
   implicit none
   private

   public :: master_segments, slave_nodes, slave_edges

   ! A pair lists at most this many offending entities before "... and N more".
   integer, parameter :: max_listed = 20

contains

   !> Master segments of `pair`: seg(:, k) = (a, b) node indices of the k-th
   !> facet of the master surface in element orientation, seg_elem(k) its element,
   !> seg_side(k) its side.  Errors (all listed): a master surface that is not of
   !> TYPE=ELEMENT, an element side shared with another element (not on the mesh
   !> boundary), a zero-length side.
   pure subroutine master_segments(model, pair, seg, seg_elem, seg_side, error)
      type(model_t), intent(in) :: model
      type(contact_pair_t), intent(in) :: pair
      integer(ip), allocatable, intent(out) :: seg(:, :)
      integer(ip), allocatable, intent(out) :: seg_elem(:)
      integer, allocatable, intent(out) :: seg_side(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: node_ptr(:), node_elem(:)
      integer(ip) :: e, other
      integer :: k, nfac, nbad
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
         allocate (seg(2, nfac), seg_elem(nfac), seg_side(nfac))
         call node_elements(model, node_ptr, node_elem)
         nbad = 0
         do k = 1, nfac
            e = surf%elem(k)
            seg(:, k) = side_nodes(model, e, surf%side(k))
            seg_elem(k) = e
            seg_side(k) = surf%side(k)
            other = other_element(model, node_ptr, node_elem, e, seg(1, k), seg(2, k))
            if (other /= 0) then
               nbad = nbad + 1
               if (nbad <= max_listed) call append_message(error, where//': element '// &
                  itoa(model%elem_id(e))//' side '//itoa(surf%side(k))//' is shared with element '// &
                  itoa(model%elem_id(other))//', not on the mesh boundary: a master surface must be '// &
                  'an outer boundary', err_input)
            else if (segment_is_degenerate(model%x(:, seg(1, k)), model%x(:, seg(2, k)))) then
               nbad = nbad + 1
               if (nbad <= max_listed) call append_message(error, where//': element '// &
                  itoa(model%elem_id(e))//' side '//itoa(surf%side(k))//' has zero length (nodes '// &
                  itoa(node_user(model, seg(1, k)))//' and '//itoa(node_user(model, seg(2, k)))// &
                  ' coincide)', err_input)
            end if
         end do
         if (nbad > max_listed) call append_message(error, '... and '//itoa(nbad - max_listed)//' more')
      end associate
   end subroutine master_segments

   !> Slave nodes of `pair`, sorted, with their undeformed tributary length
   !> `length` and thickness `thick` (k_s = K * length * thick).
   !> Element surface: the facets' end nodes, each facet giving half its length
   !> to each end.  Node surface: the mesh boundary edges (used by one element)
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
      integer :: k, j
      integer(ip) :: ab(2)
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
               ab = side_nodes(model, ms%elem(k), ms%side(k))
               in_master(ab) = .true.
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
               ab = side_nodes(model, e, surf%side(k))
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
                  itoa(node_user(model, i))//' has no tributary length (no mesh boundary edge to '// &
                  'another node of the surface, or only zero-length facets): it would get no contact spring', &
                  err_input)
            else
               m = m + 1
            end if
         end do
         if (nbad > max_listed) call append_message(error, '... and '//itoa(nbad - max_listed)//' more')
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
      integer(ip) :: e, p, q, p0, nn, m
      integer :: k, j
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
               edge(:, k) = side_nodes(model, surf%elem(k), surf%side(k))
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
               in_master(side_nodes(model, ms%elem(k), ms%side(k))) = .true.
            end do
         end if
         call node_elements(model, node_ptr, node_elem)
         allocate (be(2, 16), bel(16), bside(16))
         m = 0
         ! every side of an element that touches the set, once: from its start node
         do e = 1, model%nelem
            p0 = model%elem_ptr(e)
            nn = model%elem_ptr(e + 1) - p0
            do j = 0, int(nn) - 1
               p = model%elem_conn(p0 + j)
               q = model%elem_conn(p0 + mod(j + 1, int(nn)))
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
      if (bad) call fatal_error(error, 'contact pair: '//role//' surface index '//itoa(isurf)// &
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
            call fatal_error(error, where//': element index '//itoa(e)//' out of range', err_internal)
            return
         end if
         if (surf%side(k) < 1 .or. surf%side(k) > model%elem_ptr(e + 1) - model%elem_ptr(e)) then
            call fatal_error(error, where//': element '//itoa(model%elem_id(e))//' has no side '// &
                             itoa(surf%side(k)), err_input)
            return
         end if
      end do
   end subroutine check_facets

   !> (node k, node k+1) of element e, side k.
   pure function side_nodes(model, e, k) result(ab)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: e
      integer, intent(in) :: k
      integer(ip) :: ab(2)
      integer(ip) :: p0, n
      p0 = model%elem_ptr(e)
      n = model%elem_ptr(e + 1) - p0
      ab(1) = model%elem_conn(p0 + k - 1)
      ab(2) = model%elem_conn(p0 + mod(k, n))
   end function side_nodes

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

   !> An element other than e with a side joining p and q, 0 if there is none.
   pure integer(ip) function other_element(model, node_ptr, node_elem, e, p, q) result(f)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: node_ptr(:), node_elem(:), e, p, q
      integer(ip) :: j, p0, n, k, c1, c2
      do j = node_ptr(p), node_ptr(p + 1) - 1
         f = node_elem(j)
         if (f == e) cycle
         p0 = model%elem_ptr(f)
         n = model%elem_ptr(f + 1) - p0
         do k = 0, n - 1
            c1 = model%elem_conn(p0 + k)
            c2 = model%elem_conn(p0 + mod(k + 1, n))
            if ((c1 == p .and. c2 == q) .or. (c1 == q .and. c2 == p)) return
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

   pure function itoa(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=16) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function itoa
end module vemcontact_contact_surfaces
