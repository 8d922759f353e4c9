!> Interface node insertion of TYPE=SURFACE TO SURFACE contact pairs.
!>
!> Each slave corner is projected onto the master surface (closest point) and each
!> master corner onto the slave face (along the master's normal at the node), in the
!> reference configuration; where a projection falls inside a side (not on one of its
!> end nodes), a new node is inserted there, as one more vertex of that side's
!> polygon, on the side itself: the straight chord of a first-order side, the
!> quadratic curve of a second-order one (split into pieces, each with its own side
!> node on the same curve).  The element sides are the bodies' boundaries, so the
!> insertion changes neither body's geometry (no smoothing at kinks, no curve guessed
!> from neighbouring sides).  A virtual element takes any number of vertices, so the
!> meshes stay valid and the interface becomes node to node: every interface node has a
!> partner on the other side at the same tangential position, and where the two faces
!> are the same curve (straight faces, kinks at vertices of both meshes) the contact
!> patch test is passed exactly for any mesh on either side (Wriggers, Rust, Reddy
!> 2016; docs/contact-formulation.md).  The pairs found here are stored in the model
!> (contact_pair_t%partner) and kept for the whole analysis: small sliding, consistent
!> with small strain.
!>
!> Only virtual elements can take the extra nodes: a side of a FEM element (CPE4,
!> CPE3, CPE8, CPE6 with FORMULATION=FEM) on a surface of such a pair is an error
!> naming it, and so is a pair of a first-order and a second-order face.
module vemcontact_contact_insertion
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, fatal_error, append_message, err_input
   use vemcontact_model, only: model_t, surface_t, dload_t, step_t, source_loc_t, location_string, &
                               surface_element, surface_node, form_fem, etype_polygon, etype_polygon2, dload_pressure, &
                               dload_hydrostatic, pair_surface_to_surface, element_order, element_side
   use vemcontact_model, only: contact_pair_t
   use vemcontact_contact_surfaces, only: master_segments, slave_edges
   use vemcontact_text, only: int_text
   use vemcontact_contact_search, only: segment_grid_t, build_segment_grid, closest_segments, end_tol
   use vemcontact_contact_geometry, only: length2
   implicit none
   private

   public :: insert_interface_nodes, project_onto_sides, on_face
   public :: insert_tie_nodes

   !> A projection within snap_rel of a side's length from one of its end nodes is
   !> that node: nodes that coincide in the mesh (matching faces of a joint) do so up
   !> to the rounding of their coordinates, about 1e-16 of the coordinates, and 1e-10
   !> leaves room for coordinates 1e6 times the side length.  A larger snap would move
   !> the partner tangentially, which changes the gap by the tangential strain times
   !> the offset and spoils the patch test with stiff penalties.
   real(wp), parameter, public :: snap_rel = 1.0e-10_wp

   !> One node to insert: on side `side` of element `elem` at parameter xi (0 at the
   !> side's start node, 1 at its end node).
   type :: insertion_t
      integer(ip) :: elem = 0
      integer :: side = 0
      real(wp) :: xi = 0.0_wp
      integer(ip) :: ends(2) = 0   !< the side's start and end node
      integer(ip) :: mid = 0       !< its side node (second order; 0 for first order)
      integer(ip) :: node = 0      !< the new node
   end type insertion_t

   ! entities listed in one message before "... and N more"
   integer, parameter :: max_listed = 20

   !> The work of apply_insertions: the insertions in element, side and xi order
   !> (order; those of element e are order(eptr(e):eptr(e+1)-1), nins(e) of them),
   !> the node counts (n0 before, ncorner inserted corners, nmid new side nodes), the
   !> undeformed coordinates and the new connectivity being built.
   type :: splice_t
      integer(ip), allocatable :: order(:), eptr(:), nins(:), new_ptr(:), new_conn(:)
      real(wp), allocatable :: x0(:, :)
      integer(ip) :: n0 = 0, ncorner = 0, nmid = 0
      type(insertion_t), allocatable :: mids(:)
   end type splice_t

contains

   !> Insert the interface nodes of every SURFACE TO SURFACE pair into the model and
   !> record each pair's node partners; `added(p)` is the number of nodes inserted
   !> for pair p.
   subroutine insert_interface_nodes(model, added, error)
      type(model_t), intent(inout) :: model
      integer(ip), allocatable, intent(out) :: added(:)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      integer :: p
      if (.not. allocated(model%pairs)) then
         allocate (added(0))
         return
      end if
      allocate (added(size(model%pairs)), source=0_ip)
      do p = 1, size(model%pairs)
         if (model%pairs(p)%formulation /= pair_surface_to_surface) cycle
         call insert_pair(model, p, added(p), err)
         if (allocated(err)) then
            call append_message(error, location_string(model, model%pairs(p)%loc)//': '//err%message, err%code)
            return
         end if
      end do
   end subroutine insert_interface_nodes

   !> The insertion of a SURFACE TO SURFACE pair for every *TIE: the corners of each
   !> face are inserted into the other face's sides, so that the tied interface is node
   !> to node and tying the pairs (vemcontact_driver_tie) makes the two traces one
   !> field, piecewise linear (or quadratic) on the union of both faces' nodes.  The
   !> pairs are stored in model%ties(t)%partner.  When only one face is of virtual
   !> elements, the FEM face's corners are inserted into it (insert_fem_corners) and
   !> its nodes are then tied to the FEM face by closest points.  A tie whose insertion
   !> is refused (two FEM faces, first- and second-order sides together, a split side
   !> held by a *BOUNDARY, a face that is not on the outer boundary) keeps no partners
   !> and is tied by closest points; the refusals are checks made before anything is
   !> inserted, so the model is then unchanged.  `added(t)`: the nodes inserted for tie
   !> t, -1 for a tie left to closest points.  insert_pair reads the two surfaces from
   !> model%pairs, so each tie runs as a pair appended there for the time of its
   !> insertion.
   subroutine insert_tie_nodes(model, added)
      type(model_t), intent(inout) :: model
      integer(ip), allocatable, intent(out) :: added(:)
      type(contact_pair_t), allocatable :: kept(:)
      type(contact_pair_t) :: pair
      type(error_t), allocatable :: err
      integer :: t, n
      if (.not. allocated(model%ties)) then
         allocate (added(0))
         return
      end if
      allocate (added(size(model%ties)), source=-1_ip)
      do t = 1, size(model%ties)
         if (model%ties(t)%slave == 0 .or. model%ties(t)%master == 0) cycle
         pair%slave = model%ties(t)%slave
         pair%master = model%ties(t)%master
         pair%formulation = pair_surface_to_surface
         pair%loc = model%ties(t)%loc
         if (allocated(model%pairs)) then
            kept = model%pairs
            model%pairs = [kept, pair]
         else
            model%pairs = [pair]
         end if
         n = size(model%pairs)
         call insert_pair(model, n, added(t), err)
         if (allocated(err)) then
            deallocate (err)
            call insert_fem_corners(model, n, added(t), model%ties(t)%reverse, err)
            if (allocated(err)) then
               added(t) = -1
               model%ties(t)%reverse = .false.
               deallocate (err)
            end if
         else
            call move_alloc(model%pairs(n)%partner, model%ties(t)%partner)
         end if
         if (allocated(kept)) then
            model%pairs = kept
            deallocate (kept)
         else
            deallocate (model%pairs)
         end if
      end do
   end subroutine insert_tie_nodes

   !> One way, for a *TIE (pair p) of a face of virtual elements and a face of FEM
   !> elements: the FEM face's corners are inserted into the virtual face's sides where
   !> they project onto them (closest points), so that every node of the FEM face is a
   !> node of the virtual face too; tied to the FEM face at their closest points, the
   !> virtual face's nodes then make its trace the FEM face's (vemcontact_driver_tie).
   !> `reverse`: the virtual face is the master (its nodes are to be tied to the slave
   !> face's sides, slave_edges').  An error, with the model unchanged, when neither or
   !> both faces are of virtual elements or the orders differ.
   subroutine insert_fem_corners(model, p, nadded, reverse, error)
      type(model_t), intent(inout) :: model
      integer, intent(in) :: p
      integer(ip), intent(out) :: nadded
      logical, intent(out) :: reverse
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err_m, err_s
      integer(ip), allocatable :: mseg(:, :), melem(:), sseg(:, :), selem(:), vface(:, :), fface(:, :), fnode(:)
      integer(ip), allocatable :: vnode(:), on(:), partner(:), velem(:)
      integer, allocatable :: mside(:), sside(:), vside(:)
      real(wp), allocatable :: xi(:)
      type(insertion_t), allocatable :: ins(:), mids(:)
      logical, allocatable :: on_slave(:)
      integer :: order, m
      nadded = 0
      reverse = .false.
      call master_segments(model, model%pairs(p), mseg, melem, mside, error)
      if (allocated(error)) return
      melem = model%surfaces(model%pairs(p)%master)%elem
      mside = model%surfaces(model%pairs(p)%master)%side
      call slave_edges(model, model%pairs(p), sseg, selem, sside, error)
      if (allocated(error)) return
      call check_orders(model, [melem, selem], order, error)
      if (allocated(error)) return
      call check_virtual(model, melem, err_m)
      call check_virtual(model, selem, err_s)
      if (allocated(err_m) .eqv. allocated(err_s)) then
         call fatal_error(error, 'error: one face of virtual elements, one of FEM elements expected', err_input)
         return
      end if
      reverse = .not. allocated(err_m)
      if (reverse) then
         vface = face_sides(model, melem, mside)
         fface = face_sides(model, selem, sside)
         velem = melem
         vside = mside
      else
         vface = face_sides(model, selem, sside)
         fface = face_sides(model, melem, mside)
         velem = selem
         vside = sside
      end if
      ! the FEM corners that are not nodes of the virtual face already
      vnode = unique_nodes(vface(1:2, :), model%nnode)
      fnode = unique_nodes(fface(1:2, :), model%nnode)
      fnode = pack(fnode, .not. is_in(fnode, vnode, model%nnode))
      call project_onto_face(model%x, vface, fnode, 2.0_wp*max(longest_side(model%x, vface), &
                             longest_side(model%x, fface)), on, xi, error)
      if (allocated(error)) return
      allocate (ins(count(on > 0)))
      m = 0
      call partners(vface, velem, vside, on, xi, ins, m, partner)
      ins = ins(:m)
      call check_constrained_sides(model, ins, error)
      if (allocated(error)) return
      call apply_insertions(model, ins, nadded, mids)
      allocate (on_slave(model%nelem), source=.false.)
      if (.not. reverse) on_slave(selem) = .true.
      call add_to_sets(model, [ins, mids], model%pairs(p)%slave, on_slave)
   end subroutine insert_fem_corners

   !> Insertion and partners of pair p.  Each face is a list of sides (a, b, m): the
   !> corners a -> b in element orientation and the side node m of a second-order side
   !> (0 for first order).  The corners of each face are projected onto the other face
   !> and inserted where they fall inside a side; a second-order side that takes
   !> corners is split into sides with their own side nodes (split_quadratic_sides), and
   !> the side nodes of facing sides, which then span the same stretch, become partners.
   subroutine insert_pair(model, p, nadded, error)
      type(model_t), intent(inout) :: model
      integer, intent(in) :: p
      integer(ip), intent(out) :: nadded
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: mseg(:, :), melem(:), sseg(:, :), selem(:), snode(:), mnode(:), sall(:)
      integer(ip), allocatable :: s_on(:), m_on(:), s_partner(:), m_partner(:), pairs(:, :), mface(:, :), sface(:, :)
      integer, allocatable :: mside(:), sside(:)
      real(wp), allocatable :: s_xi(:), m_xi(:)
      type(insertion_t), allocatable :: ins(:), mids(:)
      logical, allocatable :: on_slave(:)
      real(wp) :: radius
      integer :: k, m, order

      nadded = 0
      ! master_segments validates the master surface (outer boundary, no zero-length side)
      call master_segments(model, model%pairs(p), mseg, melem, mside, error)
      if (allocated(error)) return
      melem = model%surfaces(model%pairs(p)%master)%elem
      mside = model%surfaces(model%pairs(p)%master)%side
      call slave_edges(model, model%pairs(p), sseg, selem, sside, error)
      if (allocated(error)) return
      call check_virtual(model, [melem, selem], error)
      if (allocated(error)) return
      call check_orders(model, [melem, selem], order, error)
      if (allocated(error)) return
      mface = face_sides(model, melem, mside)
      sface = face_sides(model, selem, sside)
      ! the corners of each face; a node of both (a joint tip) is no one's partner
      sall = unique_nodes(sface(1:2, :), model%nnode)
      mnode = unique_nodes(mface(1:2, :), model%nnode)
      snode = pack(sall, .not. is_in(sall, mnode, model%nnode))
      mnode = pack(mnode, .not. is_in(mnode, sall, model%nnode))
      radius = 2.0_wp*max(longest_side(model%x, mface), longest_side(model%x, sface))
      call project_onto_face(model%x, mface, snode, radius, s_on, s_xi, error)
      if (allocated(error)) return
      call project_onto_face(model%x, sface, mnode, radius, m_on, m_xi, error)
      if (allocated(error)) return
      call cast_along_normals(model%x, sface, mnode, node_normals(model%x, mseg, mnode), m_on, m_xi)

      ! partners: an end node of the side, or a node inserted into it
      allocate (ins(count(s_on > 0) + count(m_on > 0)))
      m = 0
      call partners(mface, melem, mside, s_on, s_xi, ins, m, s_partner)
      call partners(sface, selem, sside, m_on, m_xi, ins, m, m_partner)
      ins = ins(:m)
      call check_constrained_sides(model, ins, error)
      if (allocated(error)) return
      call apply_insertions(model, ins, nadded, mids)
      do k = 1, size(s_partner)
         if (s_partner(k) < 0) s_partner(k) = ins(-s_partner(k))%node
      end do
      do k = 1, size(m_partner)
         if (m_partner(k) < 0) m_partner(k) = ins(-m_partner(k))%node
      end do
      ! (slave, master) node pairs, each slave node once
      allocate (pairs(2, count(s_partner > 0) + count(m_partner > 0)))
      m = 0
      do k = 1, size(snode)
         if (s_partner(k) <= 0) cycle
         m = m + 1
         pairs(:, m) = [snode(k), s_partner(k)]
      end do
      do k = 1, size(mnode)
         if (m_partner(k) <= 0) cycle
         m = m + 1
         pairs(:, m) = [m_partner(k), mnode(k)]
      end do
      ! the nodes inserted into the slave face are slave nodes
      allocate (on_slave(model%nelem), source=.false.)
      on_slave(selem) = .true.
      call add_to_sets(model, [ins, mids], model%pairs(p)%slave, on_slave)
      if (order == 2) then
         ! the faces after the insertion: their side nodes face each other in pairs
         call slave_edges(model, model%pairs(p), sseg, selem, sside, error)
         if (allocated(error)) return
         sface = face_sides(model, selem, sside)
         mface = face_sides(model, model%surfaces(model%pairs(p)%master)%elem, &
                            model%surfaces(model%pairs(p)%master)%side)
         pairs = side_node_pairs(model%nnode, sface, mface, pairs)
      end if
      model%pairs(p)%partner = unique_pairs(pairs, model%nnode)
   end subroutine insert_pair

   !> The sides (a, b, m) of the element sides (elem(k), side(k)): corners in element
   !> orientation and the side node (0 for a first-order side).
   pure function face_sides(model, elem, side) result(face)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: elem(:)
      integer, intent(in) :: side(:)
      integer(ip), allocatable :: face(:, :)
      integer :: k, ns
      allocate (face(3, size(elem)))
      do k = 1, size(elem)
         call element_side(model, elem(k), side(k), face(:, k), ns)
      end do
   end function face_sides

   !> The corner pairs `pairs` (slave, master) followed by the pairs of side nodes:
   !> a slave side whose corners face the corners of one master side (partners, or the
   !> same node at a joint tip) faces that side, and its side node faces the master's.
   pure function side_node_pairs(n, sface, mface, pairs) result(all)
      integer(ip), intent(in) :: n, sface(:, :), mface(:, :), pairs(:, :)
      integer(ip), allocatable :: all(:, :)
      integer(ip), allocatable :: mate(:), from(:), extra(:, :)
      integer(ip) :: pa, pb
      integer :: k, j, m
      allocate (mate(n), from(n), source=0_ip)
      do k = 1, size(mface, 2)
         from(mface(1, k)) = int(k, ip)
         ! a corner of both faces (a joint tip) faces itself
         mate(mface(1:2, k)) = mface(1:2, k)
      end do
      do k = 1, size(pairs, 2)
         mate(pairs(1, k)) = pairs(2, k)
      end do
      allocate (extra(2, size(sface, 2)))
      m = 0
      do k = 1, size(sface, 2)
         pa = mate(sface(1, k))
         pb = mate(sface(2, k))
         if (pa == 0 .or. pb == 0 .or. sface(3, k) == 0) cycle
         ! facing sides run in opposite directions
         j = 0
         if (from(pb) > 0) then
            if (mface(2, from(pb)) == pa) j = int(from(pb))
         end if
         if (j == 0 .and. from(pa) > 0) then
            if (mface(2, from(pa)) == pb) j = int(from(pa))
         end if
         if (j == 0) cycle
         if (mface(3, j) == 0) cycle
         m = m + 1
         extra(:, m) = [sface(3, k), mface(3, j)]
      end do
      all = reshape([pairs, extra(:, :m)], [2, size(pairs, 2) + m])
   end function side_node_pairs

   !> Refuse a pair whose faces mix first- and second-order sides: the node-to-node
   !> interface needs the same nodal weights of a pressure on both (l/2 at the ends of
   !> a first-order side, l/6, 4l/6, l/6 on a second-order one).  `order`: the faces'.
   subroutine check_orders(model, elems, order, error)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: elems(:)
      integer, intent(out) :: order
      type(error_t), allocatable, intent(out) :: error
      integer :: k
      order = 1
      if (size(elems) == 0) return
      order = element_order(model%elem_type(elems(1)))
      do k = 2, size(elems)
         if (element_order(model%elem_type(elems(k))) == order) cycle
         call fatal_error(error, 'error: the surfaces of this TYPE=SURFACE TO SURFACE pair have first- and '// &
                          'second-order sides (elements '//int_text(model%elem_id(elems(1)))//' and '// &
                          int_text(model%elem_id(elems(k)))//', the second defined at '// &
                          location_string(model, model%elem_loc(elems(k)))//')'//new_line('a')// &
                          '  = help: mesh both bodies along the interface with the same order (VPE/VPS or '// &
                          'VPE2/VPS2), or use TYPE=NODE TO SURFACE', err_input)
         return
      end do
   end subroutine check_orders

   !> The longest of the sides seg(:, k) = (a, b), 0 for none.
   pure real(wp) function longest_side(x, seg) result(l)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :)
      integer :: k
      l = 0.0_wp
      do k = 1, size(seg, 2)
         l = max(l, length2(x(:, seg(2, k)) - x(:, seg(1, k))))
      end do
   end function longest_side

   !> Side and parameter of the projection of each node of `query` onto the sides
   !> seg(:, k) = (a, b) of a surface: on(i) = 0 when no side is within `radius` or
   !> the node lies past an open end of the surface (the contact search's rules).
   pure subroutine project_onto_sides(x, seg, query, radius, on, xi, error)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :), query(:)
      real(wp), intent(in) :: radius
      integer(ip), allocatable, intent(out) :: on(:)
      real(wp), allocatable, intent(out) :: xi(:)
      type(error_t), allocatable, intent(out) :: error
      type(segment_grid_t) :: grid
      real(wp), allocatable :: gap(:), normal(:, :)
      allocate (on(size(query)), xi(size(query)), gap(size(query)), normal(2, size(query)))
      on = 0
      xi = 0.0_wp
      if (size(seg, 2) == 0 .or. size(query) == 0) return
      call build_segment_grid(x, seg, radius, grid, error)
      if (allocated(error)) return
      call closest_segments(grid, x, seg, query, radius, on, xi, gap, normal)
   end subroutine project_onto_sides

   !> Side and parameter t of the projection of each node of `query` onto the sides
   !> face(:, k) = (a, b, m) of a face (t = 0 at a, 1 at b; on(i) = 0 as in
   !> project_onto_sides).  A second-order side is searched as its two halves a -> m,
   !> m -> b, then t is refined to the closest point of the side's quadratic curve
   !> (exact in one step on a straight side).
   pure subroutine project_onto_face(x, face, query, radius, on, t, error)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: face(:, :), query(:)
      real(wp), intent(in) :: radius
      integer(ip), allocatable, intent(out) :: on(:)
      real(wp), allocatable, intent(out) :: t(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: half(:, :), hon(:)
      integer :: k, i
      if (all(face(3, :) == 0)) then
         call project_onto_sides(x, face(1:2, :), query, radius, on, t, error)
         return
      end if
      allocate (half(2, 2*size(face, 2)))
      do k = 1, size(face, 2)
         half(:, 2*k - 1) = [face(1, k), face(3, k)]
         half(:, 2*k) = [face(3, k), face(2, k)]
      end do
      call project_onto_sides(x, half, query, radius, hon, t, error)
      if (allocated(error)) return
      allocate (on(size(query)), source=0_ip)
      do i = 1, size(query)
         if (hon(i) == 0) cycle
         k = int((hon(i) + 1)/2)
         on(i) = int(k, ip)
         t(i) = 0.5_wp*t(i)
         if (mod(hon(i), 2_ip) == 0) t(i) = t(i) + 0.5_wp
         t(i) = closest_on_quadratic(x(:, face(1, k)), x(:, face(2, k)), x(:, face(3, k)), x(:, query(i)), t(i))
      end do
   end subroutine project_onto_face

   !> The direction of the master's mean normal (node_partners in active_set.f90) at
   !> each node of `query`: the sum of (t_y, -t_x) over the segments seg(:, k) = (a, b)
   !> that meet there, normalized.
   pure function node_normals(x, seg, query) result(nq)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :), query(:)
      real(wp), allocatable :: nq(:, :)
      real(wp), allocatable :: vn(:, :)
      real(wp) :: t(2)
      integer :: k, i
      allocate (vn(2, size(x, 2)), source=0.0_wp)
      do k = 1, size(seg, 2)
         t = x(:, seg(2, k)) - x(:, seg(1, k))
         vn(:, seg(1, k)) = vn(:, seg(1, k)) + [t(2), -t(1)]
         vn(:, seg(2, k)) = vn(:, seg(2, k)) + [t(2), -t(1)]
      end do
      allocate (nq(2, size(query)))
      do i = 1, size(query)
         nq(:, i) = vn(:, query(i))/max(length2(vn(:, query(i))), tiny(1.0_wp))
      end do
   end function node_normals

   !> Move each master node's point on the slave face (on, t: the closest point, from
   !> project_onto_face) to where the master's normal through the node meets the face,
   !> walking from side to side along the face; on(i) = 0 when the normal passes an open
   !> end of the face (beyond end_tol of a side).  The pair's gap is measured along this
   !> normal (node_partners), so the partner then lies straight across the gap, as the
   !> slave nodes' partners do (their closest points on the master sides); with closest
   !> points on a curved slave face a master node's partner lay off its normal by the
   !> gap times the face's tilt, and a slave corner and a master node closer than that
   !> came in opposite orders along the two faces (the Hertz disc of k = 2 on a fine
   !> mesh: a piece of 5e-4 between them and a peak of 224 instead of 84).
   pure subroutine cast_along_normals(x, face, query, nq, on, t)
      real(wp), intent(in) :: x(:, :), nq(:, :)
      integer(ip), intent(in) :: face(:, :), query(:)
      integer(ip), intent(inout) :: on(:)
      real(wp), intent(inout) :: t(:)
      integer(ip), allocatable :: from(:), into(:)
      integer(ip) :: k
      integer :: i, step
      real(wp) :: tt
      logical :: ok
      allocate (from(size(x, 2)), into(size(x, 2)), source=0_ip)
      do k = 1, size(face, 2)
         from(face(1, k)) = k
         into(face(2, k)) = k
      end do
      do i = 1, size(query)
         k = on(i)
         if (k == 0) cycle
         ! a few sides at most: the closest point and the normal's point are a gap times a tilt apart
         do step = 1, 8
            call ray_side(x, face(:, k), x(:, query(i)), nq(:, i), t(i), tt, ok)
            if (.not. ok) exit
            if (tt < -end_tol) then
               k = into(face(1, k))
            else if (tt > 1.0_wp + end_tol) then
               k = from(face(2, k))
            else
               on(i) = k
               t(i) = tt
               exit
            end if
            if (k == 0) then
               on(i) = 0
               exit
            end if
         end do
      end do
   end subroutine cast_along_normals

   !> Parameter tt where the line through xq along nq meets the side f = (a, b, m)
   !> (m = 0: the chord; else the side's quadratic, by Newton's method from t0);
   !> ok = .false. when the line runs along the side.
   pure subroutine ray_side(x, f, xq, nq, t0, tt, ok)
      real(wp), intent(in) :: x(:, :), xq(2), nq(2), t0
      integer(ip), intent(in) :: f(3)
      real(wp), intent(out) :: tt
      logical, intent(out) :: ok
      real(wp) :: a(2), b(2), d(2), g, dg, dt
      integer :: it
      a = x(:, f(1))
      b = x(:, f(2))
      d = 0.0_wp
      if (f(3) > 0) d = x(:, f(3)) - 0.5_wp*(a + b)
      tt = min(max(t0, 0.0_wp), 1.0_wp)
      ok = .false.
      do it = 1, 30
         ! cross(x(t) - xq, nq) = 0
         g = cross(a + tt*(b - a) + 4.0_wp*tt*(1.0_wp - tt)*d - xq, nq)
         dg = cross((b - a) + 4.0_wp*(1.0_wp - 2.0_wp*tt)*d, nq)
         if (.not. (abs(dg) > 1.0e-12_wp*length2(b - a))) return
         dt = g/dg
         tt = tt - dt
         if (abs(dt) <= 4.0_wp*epsilon(tt)*max(1.0_wp, abs(tt))) exit
      end do
      ok = .true.
   contains
      pure real(wp) function cross(u, v)
         real(wp), intent(in) :: u(2), v(2)
         cross = u(1)*v(2) - u(2)*v(1)
      end function cross
   end subroutine ray_side

   !> The parameter of the point of the quadratic side through a (t = 0), m (1/2) and
   !> b (1) closest to q, by Newton's method on (x(t) - q) . x'(t) = 0 from t0 (the
   !> projection onto the half a -> m or m -> b, within O(sagitta) of it).
   pure real(wp) function closest_on_quadratic(a, b, m, q, t0) result(t)
      real(wp), intent(in) :: a(2), b(2), m(2), q(2), t0
      real(wp) :: d(2), r(2), dx(2), f, df, dt
      integer :: it
      d = m - 0.5_wp*(a + b)
      t = t0
      do it = 1, 20
         r = quadratic_point(a, b, m, t) - q
         dx = (b - a) + 4.0_wp*(1.0_wp - 2.0_wp*t)*d
         f = dot_product(r, dx)
         df = dot_product(dx, dx) - 8.0_wp*dot_product(r, d)
         if (.not. (df > 0.0_wp)) exit
         dt = f/df
         t = t - dt
         ! a step below the rounding of t: converged
         if (abs(dt) <= 4.0_wp*epsilon(t)) exit
      end do
   end function closest_on_quadratic

   !> The point at parameter t of the quadratic side through a (t = 0), m (1/2), b (1):
   !> the second-order element's own side curve (docs/vem-formulation.md).
   pure function quadratic_point(a, b, m, t) result(xp)
      real(wp), intent(in) :: a(2), b(2), m(2), t
      real(wp) :: xp(2)
      xp = a + t*(b - a) + 4.0_wp*t*(1.0_wp - t)*(m - 0.5_wp*(a + b))
   end function quadratic_point

   !> The partner of each projected node on the sides seg(:, k) = (a, b, m): the end
   !> node of the side when the projection is within snap_rel of it, else -(index into
   !> ins) of the node to insert (appended to ins(m+1:)), 0 without a side.
   pure subroutine partners(seg, elem, side, on, xi, ins, m, partner)
      integer(ip), intent(in) :: seg(:, :), elem(:), on(:)
      integer, intent(in) :: side(:)
      real(wp), intent(in) :: xi(:)
      type(insertion_t), intent(inout) :: ins(:)
      integer, intent(inout) :: m
      integer(ip), allocatable, intent(out) :: partner(:)
      integer :: i
      allocate (partner(size(on)), source=0_ip)
      do i = 1, size(on)
         if (on(i) == 0) cycle
         if (xi(i) <= snap_rel) then
            partner(i) = seg(1, on(i))
         else if (xi(i) >= 1.0_wp - snap_rel) then
            partner(i) = seg(2, on(i))
         else
            m = m + 1
            ins(m) = insertion_t(elem(on(i)), side(on(i)), xi(i), seg(1:2, on(i)), seg(3, on(i)), 0_ip)
            partner(i) = -m
         end if
      end do
   end subroutine partners

   !> The point at parameter xi of the straight side xa -> xb: exactly xa at 0 and xb
   !> at 1, and on the line through them (to the rounding of one multiply-add).
   pure function on_face(xa, xb, xi) result(xp)
      real(wp), intent(in) :: xa(2), xb(2), xi
      real(wp) :: xp(2)
      xp = xa + xi*(xb - xa)
   end function on_face

   !> Refuse sides of FEM elements: they cannot take extra nodes.  One message that
   !> names the first few elements and where the first is defined.
   subroutine check_virtual(model, elems, error)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: elems(:)
      type(error_t), allocatable, intent(out) :: error
      logical, allocatable :: seen(:)
      character(len=:), allocatable :: list, first
      integer :: k, nbad
      allocate (seen(model%nelem), source=.false.)
      nbad = 0
      list = ''
      do k = 1, size(elems)
         if (model%elem_form(elems(k)) /= form_fem .or. seen(elems(k))) cycle
         seen(elems(k)) = .true.
         nbad = nbad + 1
         if (nbad == 1) first = location_string(model, model%elem_loc(elems(k)))
         if (nbad <= max_listed) list = list//', '//int_text(model%elem_id(elems(k)))
      end do
      if (nbad == 0) return
      if (nbad > max_listed) list = list//' and '//int_text(int(nbad - max_listed, ip))//' more'
      call fatal_error(error, 'error: '//int_text(int(nbad, ip))//' FEM elements have sides on the surfaces of '// &
                       'this TYPE=SURFACE TO SURFACE pair (the first defined at '//first//'): '//list(3:)// &
                       new_line('a')//'  = help: this contact inserts nodes into the sides of both surfaces, '// &
                       'which only virtual elements take: use polygon elements (VPE/VPS) or FORMULATION=VEM '// &
                       'on *SOLID SECTION for both bodies, or TYPE=NODE TO SURFACE', err_input)
   end subroutine check_virtual

   !> Refuse to split a side whose two end nodes carry a *BOUNDARY condition on the
   !> same dof (before the steps or in the same step): the boundary conditions of node
   !> sets were resolved to nodes when the deck was read, so the inserted node would be
   !> free where the user meant the whole side to be held.
   subroutine check_constrained_sides(model, ins, error)
      type(model_t), intent(in) :: model
      type(insertion_t), intent(in) :: ins(:)
      type(error_t), allocatable, intent(out) :: error
      integer :: i
      if (size(ins) == 0) return
      call check_list(model%initial)
      if (allocated(error) .or. .not. allocated(model%steps)) return
      do i = 1, size(model%steps)
         call check_list(model%steps(i))
         if (allocated(error)) return
      end do
   contains
      subroutine check_list(st)
         type(step_t), intent(in) :: st
         logical, allocatable :: held(:, :)
         integer :: k
         if (.not. allocated(st%boundary)) return
         if (size(st%boundary) == 0) return
         allocate (held(2, model%nnode), source=.false.)
         do k = 1, size(st%boundary)
            held(st%boundary(k)%dof, st%boundary(k)%node) = .true.
         end do
         do k = 1, size(ins)
            if (ins(k)%mid > 0) then
               if (any(held(:, ins(k)%mid))) then
                  call fatal_error(error, 'error: a node would be inserted into side '//int_text(int(ins(k)%side, ip))// &
                                   ' of element '//int_text(model%elem_id(ins(k)%elem))//', whose side node '// &
                                   int_text(model%node_id(ins(k)%mid))//' carries a *BOUNDARY condition: the side '// &
                                   'is split into sides with new side nodes'//new_line('a')// &
                                   '  = help: hold the body through other nodes, or use TYPE=NODE TO SURFACE', &
                                   err_input)
                  return
               end if
            end if
            if (any(held(:, ins(k)%ends(1)) .and. held(:, ins(k)%ends(2)))) then
               call fatal_error(error, 'error: a node would be inserted between nodes '// &
                                int_text(model%node_id(ins(k)%ends(1)))//' and '//int_text(model%node_id(ins(k)%ends(2)))// &
                                ' (side '//int_text(int(ins(k)%side, ip))//' of element '// &
                                int_text(model%elem_id(ins(k)%elem))//'), which both carry a *BOUNDARY condition on '// &
                                'the same dof: the inserted node would be free'//new_line('a')// &
                                '  = help: hold the side through other nodes, or use TYPE=NODE TO SURFACE', err_input)
               return
            end if
         end do
      end subroutine check_list
   end subroutine check_constrained_sides

   !> Create the nodes of `ins` (ins%node set; insertions at the same point of a side,
   !> within snap_rel, share one node), put them into their elements between the
   !> side's end nodes in order of xi, and renumber the sides that element surfaces
   !> and distributed loads refer to (a split side becomes its pieces).  A node lies on
   !> the side it splits: on the chord of a first-order side, on the quadratic of a
   !> second-order one, whose pieces get side nodes at their middles on the same curve
   !> (the side's own node moved to the middle of the piece that holds it, new nodes
   !> for the others, returned in `mids` with the piece's ends), so that every side
   !> keeps its curve.  `nadded`: the nodes created.
   subroutine apply_insertions(model, ins, nadded, mids)
      type(model_t), intent(inout) :: model
      type(insertion_t), intent(inout) :: ins(:)
      integer(ip), intent(out) :: nadded
      type(insertion_t), allocatable, intent(out) :: mids(:)
      type(splice_t) :: sp
      integer(ip) :: e, k, idmax
      allocate (mids(0))
      nadded = 0
      if (size(ins) == 0) return
      sp%n0 = model%nnode
      call number_insertions(ins, sp)
      call count_insertions(model, ins, sp)
      idmax = maxval(model%node_id)
      sp%x0 = model%x
      call grow_nodes(model, sp%ncorner + sp%nmid)
      call place_inserted(model, ins, sp)
      call splice_connectivity(model, ins, sp)
      do k = sp%n0 + 1, model%nnode
         model%node_id(k) = idmax + (k - sp%n0)
      end do
      do k = 1, size(ins)
         model%node_loc(ins(k)%node) = model%elem_loc(ins(k)%elem)
      end do
      do k = 1, size(sp%mids)
         model%node_loc(sp%mids(k)%node) = model%elem_loc(sp%mids(k)%elem)
      end do
      nadded = sp%ncorner + sp%nmid
      call renumber_sides(model, ins, sp%order, sp%eptr)
      call move_alloc(sp%new_ptr, model%elem_ptr)
      call move_alloc(sp%new_conn, model%elem_conn)
      do e = 1, model%nelem
         if (sp%nins(e) == 0) cycle
         if (element_order(model%elem_type(e)) == 2) then
            model%elem_type(e) = etype_polygon2
         else
            model%elem_type(e) = etype_polygon
         end if
      end do
      call move_alloc(sp%mids, mids)
   end subroutine apply_insertions

   !> One node per distinct point, numbered after the existing nodes (ins%node);
   !> sp%order: the insertions in element, side and xi order.
   subroutine number_insertions(ins, sp)
      type(insertion_t), intent(inout) :: ins(:)
      type(splice_t), intent(inout) :: sp
      integer(ip) :: j, k
      sp%order = sorted_order(ins)
      sp%ncorner = 0
      do j = 1, size(sp%order)
         k = sp%order(j)
         if (j > 1) then
            associate (q => ins(sp%order(j - 1)))
               if (q%elem == ins(k)%elem .and. q%side == ins(k)%side .and. &
                   ins(k)%xi - q%xi <= snap_rel) then
                  ins(k)%node = q%node
                  cycle
               end if
            end associate
         end if
         sp%ncorner = sp%ncorner + 1
         ins(k)%node = sp%n0 + sp%ncorner
      end do
   end subroutine number_insertions

   !> The distinct insertions of each element, in side and xi order:
   !> ins(order(eptr(e):eptr(e+1)-1)), nins(e) of them; a second-order element
   !> gains a side node per inserted corner (sp%nmid in all).
   subroutine count_insertions(model, ins, sp)
      type(model_t), intent(in) :: model
      type(insertion_t), intent(in) :: ins(:)
      type(splice_t), intent(inout) :: sp
      integer(ip) :: e, j
      sp%order = pack(sp%order, [.true., (ins(sp%order(j))%node /= ins(sp%order(j - 1))%node, &
                                          j=2, size(sp%order))])
      allocate (sp%nins(model%nelem), source=0_ip)
      do j = 1, size(sp%order)
         sp%nins(ins(sp%order(j))%elem) = sp%nins(ins(sp%order(j))%elem) + 1
      end do
      sp%nmid = 0
      do e = 1, model%nelem
         if (sp%nins(e) > 0 .and. element_order(model%elem_type(e)) == 2) sp%nmid = sp%nmid + sp%nins(e)
      end do
      allocate (sp%eptr(model%nelem + 1))
      sp%eptr(1) = 1
      do e = 1, model%nelem
         sp%eptr(e + 1) = sp%eptr(e) + sp%nins(e)
      end do
   end subroutine count_insertions

   !> The inserted nodes' coordinates: on the chord of a first-order side, on the
   !> quadratic of a second-order one (the undeformed sides of sp%x0).
   subroutine place_inserted(model, ins, sp)
      type(model_t), intent(inout) :: model
      type(insertion_t), intent(in) :: ins(:)
      type(splice_t), intent(in) :: sp
      integer(ip) :: j
      do j = 1, size(sp%order)
         associate (q => ins(sp%order(j)), x0 => sp%x0)
            if (q%mid > 0) then
               model%x(:, q%node) = quadratic_point(x0(:, q%ends(1)), x0(:, q%ends(2)), x0(:, q%mid), q%xi)
            else
               model%x(:, q%node) = on_face(x0(:, q%ends(1)), x0(:, q%ends(2)), q%xi)
            end if
         end associate
      end do
   end subroutine place_inserted

   !> The new connectivity (sp%new_ptr, sp%new_conn) with the inserted nodes, and
   !> the side nodes of split second-order sides (sp%mids).
   subroutine splice_connectivity(model, ins, sp)
      type(model_t), intent(inout) :: model
      type(insertion_t), intent(in) :: ins(:)
      type(splice_t), intent(inout) :: sp
      integer(ip) :: e
      allocate (sp%new_ptr(model%nelem + 1))
      sp%new_ptr(1) = 1
      do e = 1, model%nelem
         sp%new_ptr(e + 1) = sp%new_ptr(e) + (model%elem_ptr(e + 1) - model%elem_ptr(e)) + &
                             element_order(model%elem_type(e))*sp%nins(e)
      end do
      allocate (sp%new_conn(sp%new_ptr(model%nelem + 1) - 1))
      allocate (sp%mids(sp%nmid))
      sp%nmid = 0
      do e = 1, model%nelem
         if (element_order(model%elem_type(e)) == 2 .and. sp%nins(e) > 0) then
            call connect_quadratic(model, ins, sp, e)
         else
            call connect_linear(model, ins, sp, e)
         end if
      end do
   end subroutine splice_connectivity

   !> Element e's nodes with the inserted ones after the start node of their side.
   subroutine connect_linear(model, ins, sp, e)
      type(model_t), intent(in) :: model
      type(insertion_t), intent(in) :: ins(:)
      type(splice_t), intent(inout) :: sp
      integer(ip), intent(in) :: e
      integer(ip) :: p0, nn, m, jj
      integer :: sd
      p0 = model%elem_ptr(e)
      nn = model%elem_ptr(e + 1) - p0
      m = sp%new_ptr(e)
      jj = sp%eptr(e)
      do sd = 1, int(nn)
         sp%new_conn(m) = model%elem_conn(p0 + sd - 1)
         m = m + 1
         do while (jj < sp%eptr(e + 1))
            if (ins(sp%order(jj))%side /= sd) exit
            sp%new_conn(m) = ins(sp%order(jj))%node
            m = m + 1
            jj = jj + 1
         end do
      end do
   end subroutine connect_linear

   !> Second-order element e: its corners with the inserted ones, then one side node
   !> per piece of every side (the old one moved to the middle of the piece holding
   !> t = 1/2 of its side, new ones for the other pieces).
   subroutine connect_quadratic(model, ins, sp, e)
      type(model_t), intent(inout) :: model
      type(insertion_t), intent(in) :: ins(:)
      type(splice_t), intent(inout) :: sp
      integer(ip), intent(in) :: e
      integer(ip) :: p0, nc, mc, mm, jj, j0, a, b, mid, ends(2)
      integer :: sd, i, np
      real(wp) :: t0, t1
      real(wp), allocatable :: tv(:)
      p0 = model%elem_ptr(e)
      nc = (model%elem_ptr(e + 1) - p0)/2
      mc = sp%new_ptr(e)
      mm = sp%new_ptr(e) + nc + sp%nins(e)
      jj = sp%eptr(e)
      do sd = 1, int(nc)
         a = model%elem_conn(p0 + sd - 1)
         b = model%elem_conn(p0 + mod(sd, int(nc)))
         mid = model%elem_conn(p0 + nc + sd - 1)
         sp%new_conn(mc) = a
         mc = mc + 1
         j0 = jj
         do while (jj < sp%eptr(e + 1))
            if (ins(sp%order(jj))%side /= sd) exit
            sp%new_conn(mc) = ins(sp%order(jj))%node
            mc = mc + 1
            jj = jj + 1
         end do
         np = int(jj - j0)
         if (np == 0) then
            sp%new_conn(mm) = mid
            mm = mm + 1
            cycle
         end if
         tv = [0.0_wp, (ins(sp%order(j0 + i - 1))%xi, i=1, np), 1.0_wp]
         do i = 1, np + 1
            t0 = tv(i)
            t1 = tv(i + 1)
            ends(1) = a
            if (i > 1) ends(1) = ins(sp%order(j0 + i - 2))%node
            ends(2) = b
            if (i <= np) ends(2) = ins(sp%order(j0 + i - 1))%node
            if (t0 <= 0.5_wp .and. 0.5_wp < t1) then
               sp%new_conn(mm) = mid
            else
               sp%nmid = sp%nmid + 1
               sp%new_conn(mm) = sp%n0 + sp%ncorner + sp%nmid
               sp%mids(sp%nmid) = insertion_t(e, sd, 0.5_wp*(t0 + t1), ends, 0_ip, sp%new_conn(mm))
            end if
            model%x(:, sp%new_conn(mm)) = quadratic_point(sp%x0(:, a), sp%x0(:, b), sp%x0(:, mid), &
                                                          0.5_wp*(t0 + t1))
            mm = mm + 1
         end do
      end do
   end subroutine connect_quadratic

   !> Element surfaces and the pressure loads of every step: side k of an element
   !> with insertions becomes sides first .. first + (nodes inserted into side k).
   subroutine renumber_sides(model, ins, order, eptr)
      type(model_t), intent(inout) :: model
      type(insertion_t), intent(in) :: ins(:)
      integer(ip), intent(in) :: order(:), eptr(:)
      integer :: i
      if (allocated(model%surfaces)) then
         do i = 1, size(model%surfaces)
            if (model%surfaces(i)%kind /= surface_element) cycle
            call split_facets(model%surfaces(i))
         end do
      end if
      call split_dloads(model%initial)
      if (allocated(model%steps)) then
         do i = 1, size(model%steps)
            call split_dloads(model%steps(i))
         end do
      end if
   contains
      !> Pieces of side k of element e: first new side and count.
      pure subroutine pieces(e, k, first, count_)
         integer(ip), intent(in) :: e
         integer, intent(in) :: k
         integer, intent(out) :: first, count_
         integer(ip) :: j
         first = k
         count_ = 1
         do j = eptr(e), eptr(e + 1) - 1
            if (ins(order(j))%side < k) first = first + 1
            if (ins(order(j))%side == k) count_ = count_ + 1
         end do
      end subroutine pieces

      subroutine split_facets(surf)
         type(surface_t), intent(inout) :: surf
         integer(ip), allocatable :: el(:)
         integer, allocatable :: sd(:)
         integer :: f, first, c, j, m
         if (.not. allocated(surf%elem)) return
         if (size(surf%elem) == 0) return
         if (.not. any(eptr(surf%elem + 1) > eptr(surf%elem))) return
         allocate (el(size(surf%elem) + size(order)), sd(size(surf%elem) + size(order)))
         m = 0
         do f = 1, size(surf%elem)
            call pieces(surf%elem(f), surf%side(f), first, c)
            do j = 0, c - 1
               m = m + 1
               el(m) = surf%elem(f)
               sd(m) = first + j
            end do
         end do
         surf%elem = el(:m)
         surf%side = sd(:m)
      end subroutine split_facets

      subroutine split_dloads(st)
         type(step_t), intent(inout) :: st
         type(dload_t), allocatable :: out(:)
         integer :: k, first, c, j, m
         if (.not. allocated(st%dload)) return
         allocate (out(size(st%dload) + size(order)))
         m = 0
         do k = 1, size(st%dload)
            associate (d => st%dload(k))
               if ((d%kind /= dload_pressure .and. d%kind /= dload_hydrostatic) .or. &
                   d%elem < 1 .or. d%elem > size(eptr) - 1) then
                  m = m + 1
                  out(m) = d
                  cycle
               end if
               call pieces(d%elem, d%side, first, c)
               do j = 0, c - 1
                  m = m + 1
                  out(m) = d
                  out(m)%side = first + j
               end do
            end associate
         end do
         st%dload = out(:m)
      end subroutine split_dloads
   end subroutine renumber_sides

   !> Every node set and TYPE=NODE surface that holds both end nodes of a side gets
   !> the nodes inserted into it; the slave surface `islave`, when of TYPE=NODE, also
   !> gets every node inserted into a side of its face (elements `on_slave`), as on the
   !> side that runs to a joint tip, which the set leaves out.
   subroutine add_to_sets(model, ins, islave, on_slave)
      type(model_t), intent(inout) :: model
      type(insertion_t), intent(in) :: ins(:)
      integer, intent(in) :: islave
      logical, intent(in) :: on_slave(:)
      logical, allocatable :: mark(:)
      integer :: i
      if (size(ins) == 0) return
      allocate (mark(model%nnode))
      if (allocated(model%nsets)) then
         do i = 1, size(model%nsets)
            call extend(model%nsets(i)%items, .false.)
         end do
      end if
      if (allocated(model%surfaces)) then
         do i = 1, size(model%surfaces)
            if (model%surfaces(i)%kind /= surface_node .or. .not. allocated(model%surfaces(i)%nodes)) cycle
            call extend(model%surfaces(i)%nodes, i == islave)
         end do
      end if
   contains
      subroutine extend(items, slave)
         integer(ip), allocatable, intent(inout) :: items(:)
         logical, intent(in) :: slave
         integer :: k
         logical :: grew
         if (.not. allocated(items)) return
         mark = .false.
         mark(items) = .true.
         grew = .false.
         do k = 1, size(ins)
            if ((mark(ins(k)%ends(1)) .and. mark(ins(k)%ends(2))) .or. (slave .and. on_slave(ins(k)%elem))) then
               grew = grew .or. .not. mark(ins(k)%node)
               mark(ins(k)%node) = .true.
            end if
         end do
         if (grew) items = pack([(int(k, ip), k=1, size(mark))], mark)
      end subroutine extend
   end subroutine add_to_sets

   !> Extend the node arrays by n entries.
   subroutine grow_nodes(model, n)
      type(model_t), intent(inout) :: model
      integer(ip), intent(in) :: n
      real(wp), allocatable :: x(:, :)
      integer(ip), allocatable :: id(:)
      type(source_loc_t), allocatable :: loc(:)
      integer(ip) :: n0
      n0 = model%nnode
      allocate (x(2, n0 + n), id(n0 + n), loc(n0 + n))
      x(:, :n0) = model%x(:, :n0)
      id(:n0) = model%node_id(:n0)
      loc(:n0) = model%node_loc(:n0)
      call move_alloc(x, model%x)
      call move_alloc(id, model%node_id)
      call move_alloc(loc, model%node_loc)
      model%nnode = n0 + n
   end subroutine grow_nodes

   !> Order of the insertions by element, side and xi (a stable merge sort).
   pure function sorted_order(ins) result(order)
      type(insertion_t), intent(in) :: ins(:)
      integer(ip), allocatable :: order(:)
      integer(ip) :: i
      order = [(i, i=1, size(ins))]
      call merge_sort(order)
   contains
      pure recursive subroutine merge_sort(a)
         integer(ip), intent(inout) :: a(:)
         integer(ip), allocatable :: l(:), r(:)
         integer :: n, m, il, ir, k
         n = size(a)
         if (n < 2) return
         m = n/2
         l = a(:m)
         r = a(m + 1:)
         call merge_sort(l)
         call merge_sort(r)
         il = 1
         ir = 1
         do k = 1, n
            if (ir > size(r)) then
               a(k) = l(il); il = il + 1
            else if (il > size(l)) then
               a(k) = r(ir); ir = ir + 1
            else if (before(l(il), r(ir))) then
               a(k) = l(il); il = il + 1
            else
               a(k) = r(ir); ir = ir + 1
            end if
         end do
      end subroutine merge_sort

      pure logical function before(a, b)
         integer(ip), intent(in) :: a, b
         if (ins(a)%elem /= ins(b)%elem) then
            before = ins(a)%elem < ins(b)%elem
         else if (ins(a)%side /= ins(b)%side) then
            before = ins(a)%side < ins(b)%side
         else
            before = ins(a)%xi <= ins(b)%xi
         end if
      end function before
   end function sorted_order

   !> Sorted unique entries of an index array (given as rank 2) of nodes 1..n.
   pure function unique_nodes(a, n) result(u)
      integer(ip), intent(in) :: a(:, :)
      integer(ip), intent(in) :: n
      integer(ip), allocatable :: u(:)
      logical, allocatable :: seen(:)
      integer(ip) :: i
      allocate (seen(n), source=.false.)
      seen(pack(a, .true.)) = .true.
      u = pack([(i, i=1, n)], seen)
   end function unique_nodes

   !> Whether each entry of a (nodes 1..n) is in b.
   pure function is_in(a, b, n) result(yes)
      integer(ip), intent(in) :: a(:), b(:)
      integer(ip), intent(in) :: n
      logical, allocatable :: yes(:)
      logical, allocatable :: mark(:)
      allocate (mark(n), source=.false.)
      mark(b) = .true.
      yes = mark(a)
   end function is_in

   !> The (slave, master) pairs with each slave node once (its first pair).
   pure function unique_pairs(pairs, n) result(u)
      integer(ip), intent(in) :: pairs(:, :)
      integer(ip), intent(in) :: n
      integer(ip), allocatable :: u(:, :)
      logical, allocatable :: keep(:), seen(:)
      integer :: k
      allocate (keep(size(pairs, 2)), source=.false.)
      allocate (seen(n), source=.false.)
      do k = 1, size(pairs, 2)
         keep(k) = .not. seen(pairs(1, k))
         seen(pairs(1, k)) = .true.
      end do
      u = reshape(pack(pairs, spread(keep, 1, 2)), [2, count(keep)])
   end function unique_pairs

end module vemcontact_contact_insertion
