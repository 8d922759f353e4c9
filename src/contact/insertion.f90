!> Interface node insertion of TYPE=SURFACE TO SURFACE contact pairs.
!>
!> Each slave node is projected onto the master surface and each master node onto
!> the slave face, in the reference configuration; where a projection falls inside
!> a side (not on one of its end nodes), a new node is inserted there, as one more
!> vertex of that side's polygon, on the side itself: a first-order side is the
!> straight chord between its end nodes, and that chord is the body's boundary, so
!> the inserted node changes neither body's geometry (no smoothing at kinks, no
!> curve guessed from neighbouring sides).  A virtual element takes any number of
!> vertices, so the meshes stay valid and the interface becomes node to node: every
!> interface node has a partner on the other side at the same tangential position,
!> and where the two faces are the same polyline (straight faces, kinks at vertices
!> of both meshes) the contact patch test is passed exactly for any mesh on either
!> side (Wriggers, Rust, Reddy 2016; docs/contact-formulation.md).  The pairs found
!> here are stored in the model (contact_pair_t%partner) and kept for the whole
!> analysis: small sliding, consistent with small strain.
!>
!> Only virtual elements can take the extra nodes: a side of a FEM element (CPE4,
!> CPE3, FORMULATION=FEM) on a surface of such a pair is an error naming it.
module vemcontact_contact_insertion
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, fatal_error, append_message, err_input
   use vemcontact_model, only: model_t, surface_t, dload_t, step_t, source_loc_t, location_string, &
                               surface_element, surface_node, form_fem, etype_polygon, dload_pressure, &
                               dload_hydrostatic, pair_surface_to_surface, element_order
   use vemcontact_contact_surfaces, only: master_segments, slave_edges
   use vemcontact_contact_search, only: segment_grid_t, build_segment_grid, closest_segments
   use vemcontact_contact_geometry, only: length2
   implicit none
   private

   public :: insert_interface_nodes, project_onto_sides, on_face

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
      integer(ip) :: node = 0      !< the new node
   end type insertion_t

   ! entities listed in one message before "... and N more"
   integer, parameter :: max_listed = 20

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
         ! these messages name the surface's own file:line
         call check_first_order(model, model%pairs(p)%slave, error)
         if (allocated(error)) return
         call check_first_order(model, model%pairs(p)%master, error)
         if (allocated(error)) return
         call insert_pair(model, p, added(p), err)
         if (allocated(err)) then
            call append_message(error, location_string(model, model%pairs(p)%loc)//': '//err%message, err%code)
            return
         end if
      end do
   end subroutine insert_interface_nodes

   !> Insertion and partners of pair p.
   subroutine insert_pair(model, p, nadded, error)
      type(model_t), intent(inout) :: model
      integer, intent(in) :: p
      integer(ip), intent(out) :: nadded
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: mseg(:, :), melem(:), sseg(:, :), selem(:), snode(:), mnode(:), sall(:)
      integer(ip), allocatable :: s_on(:), m_on(:), s_partner(:), m_partner(:), pairs(:, :)
      integer, allocatable :: mside(:), sside(:)
      real(wp), allocatable :: s_xi(:), m_xi(:)
      type(insertion_t), allocatable :: ins(:)
      logical, allocatable :: on_slave(:)
      real(wp) :: radius
      integer :: k, m

      nadded = 0
      call master_segments(model, model%pairs(p), mseg, melem, mside, error)
      if (allocated(error)) return
      call slave_edges(model, model%pairs(p), sseg, selem, sside, error)
      if (allocated(error)) return
      call check_virtual(model, [melem, selem], error)
      if (allocated(error)) return
      ! the interface nodes of each side; a node of both (a joint tip) is no one's partner
      sall = unique_nodes(sseg, model%nnode)
      mnode = unique_nodes(mseg, model%nnode)
      snode = pack(sall, .not. is_in(sall, mnode, model%nnode))
      mnode = pack(mnode, .not. is_in(mnode, sall, model%nnode))
      radius = 2.0_wp*max(longest_side(model%x, mseg), longest_side(model%x, sseg))
      call project_onto_sides(model%x, mseg, snode, radius, s_on, s_xi, error)
      if (allocated(error)) return
      call project_onto_sides(model%x, sseg, mnode, radius, m_on, m_xi, error)
      if (allocated(error)) return

      ! partners: an end node of the side, or a node inserted into it
      allocate (ins(count(s_on > 0) + count(m_on > 0)))
      m = 0
      call partners(mseg, melem, mside, s_on, s_xi, ins, m, s_partner)
      call partners(sseg, selem, sside, m_on, m_xi, ins, m, m_partner)
      ins = ins(:m)
      call check_constrained_sides(model, ins, error)
      if (allocated(error)) return
      call apply_insertions(model, ins, nadded)
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
      model%pairs(p)%partner = unique_pairs(pairs, model%nnode)
      ! the nodes inserted into the slave face are slave nodes
      allocate (on_slave(model%nelem), source=.false.)
      on_slave(selem) = .true.
      call add_to_sets(model, ins, model%pairs(p)%slave, on_slave)
   end subroutine insert_pair

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

   !> The partner of each projected node: the end node of the side when the
   !> projection is within snap_rel of it, else -(index into ins) of the node to
   !> insert (appended to ins(m+1:)), 0 without a side.
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
            ins(m) = insertion_t(elem(on(i)), side(on(i)), xi(i), seg(:, on(i)), 0_ip)
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

   !> Refuse a surface on second-order elements (VPE2/VPS2, CPE8, CPE6): a node
   !> inserted into a side with a middle node would need new side nodes for the two
   !> new sides, which the insertion does not make.  The message names the surface's
   !> file:line and one element (or, for a node surface, one node of such an element).
   subroutine check_first_order(model, isurf, error)
      type(model_t), intent(in) :: model
      integer, intent(in) :: isurf
      type(error_t), allocatable, intent(out) :: error
      logical, allocatable :: second(:)
      character(len=:), allocatable :: what
      integer(ip) :: e
      integer :: k
      if (.not. allocated(model%surfaces)) return
      if (isurf < 1 .or. isurf > size(model%surfaces)) return
      what = ''
      associate (s => model%surfaces(isurf))
         if (s%kind == surface_element .and. allocated(s%elem)) then
            do k = 1, size(s%elem)
               if (element_order(model%elem_type(s%elem(k))) == 2) then
                  what = 'element '//itoa(model%elem_id(s%elem(k)))
                  exit
               end if
            end do
         else if (allocated(s%nodes)) then
            allocate (second(model%nnode), source=.false.)
            do e = 1, model%nelem
               if (element_order(model%elem_type(e)) == 2) &
                  second(model%elem_conn(model%elem_ptr(e):model%elem_ptr(e + 1) - 1)) = .true.
            end do
            do k = 1, size(s%nodes)
               if (second(s%nodes(k))) then
                  what = 'node '//itoa(model%node_id(s%nodes(k)))
                  exit
               end if
            end do
         end if
         if (len(what) == 0) return
         call fatal_error(error, location_string(model, s%loc)//': error: contact surface '//s%name// &
                          ' is on a second-order element ('//what//'): TYPE=SURFACE TO SURFACE contact on '// &
                          'sides with a middle node is not supported'//new_line('a')//'  = help: use TYPE=NODE '// &
                          'TO SURFACE, or first-order elements (VPE/VPS) along the contact surfaces', err_input)
      end associate
   end subroutine check_first_order

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
         if (nbad <= max_listed) list = list//', '//itoa(model%elem_id(elems(k)))
      end do
      if (nbad == 0) return
      if (nbad > max_listed) list = list//' and '//itoa(int(nbad - max_listed, ip))//' more'
      call fatal_error(error, 'error: '//itoa(int(nbad, ip))//' FEM elements have sides on the surfaces of '// &
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
            if (any(held(:, ins(k)%ends(1)) .and. held(:, ins(k)%ends(2)))) then
               call fatal_error(error, 'error: a node would be inserted between nodes '// &
                                itoa(model%node_id(ins(k)%ends(1)))//' and '//itoa(model%node_id(ins(k)%ends(2)))// &
                                ' (side '//itoa(int(ins(k)%side, ip))//' of element '// &
                                itoa(model%elem_id(ins(k)%elem))//'), which both carry a *BOUNDARY condition on '// &
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
   !> and distributed loads refer to (a split side becomes its pieces).
   subroutine apply_insertions(model, ins, nadded)
      type(model_t), intent(inout) :: model
      type(insertion_t), intent(inout) :: ins(:)
      integer(ip), intent(out) :: nadded
      integer(ip), allocatable :: order(:), new_ptr(:), new_conn(:), nins(:), eptr(:)
      integer(ip) :: e, n0, k, m, j, p0, nn, idmax
      integer :: s
      nadded = 0
      if (size(ins) == 0) return
      order = sorted_order(ins)
      ! one node per distinct point, numbered after the existing nodes
      n0 = model%nnode
      do j = 1, size(order)
         k = order(j)
         if (j > 1) then
            associate (q => ins(order(j - 1)))
               if (q%elem == ins(k)%elem .and. q%side == ins(k)%side .and. &
                   ins(k)%xi - q%xi <= snap_rel) then
                  ins(k)%node = q%node
                  cycle
               end if
            end associate
         end if
         nadded = nadded + 1
         ins(k)%node = n0 + nadded
      end do
      idmax = maxval(model%node_id)
      call grow_nodes(model, nadded)
      do k = 1, size(ins)
         associate (i => ins(k)%node)
            model%x(:, i) = on_face(model%x(:, ins(k)%ends(1)), model%x(:, ins(k)%ends(2)), ins(k)%xi)
            model%node_loc(i) = model%elem_loc(ins(k)%elem)
            model%node_id(i) = idmax + (i - n0)
         end associate
      end do
      ! the distinct insertions of each element, in side and xi order: ins(order(eptr(e):eptr(e+1)-1))
      order = pack(order, [.true., (ins(order(j))%node /= ins(order(j - 1))%node, j=2, size(order))])
      allocate (nins(model%nelem), source=0_ip)
      do j = 1, size(order)
         nins(ins(order(j))%elem) = nins(ins(order(j))%elem) + 1
      end do
      allocate (eptr(model%nelem + 1))
      eptr(1) = 1
      do e = 1, model%nelem
         eptr(e + 1) = eptr(e) + nins(e)
      end do
      allocate (new_ptr(model%nelem + 1))
      new_ptr(1) = 1
      do e = 1, model%nelem
         new_ptr(e + 1) = new_ptr(e) + (model%elem_ptr(e + 1) - model%elem_ptr(e)) + nins(e)
      end do
      allocate (new_conn(new_ptr(model%nelem + 1) - 1))
      do e = 1, model%nelem
         p0 = model%elem_ptr(e)
         nn = model%elem_ptr(e + 1) - p0
         m = new_ptr(e)
         j = eptr(e)
         do s = 1, int(nn)
            new_conn(m) = model%elem_conn(p0 + s - 1)
            m = m + 1
            do while (j < eptr(e + 1))
               if (ins(order(j))%side /= s) exit
               new_conn(m) = ins(order(j))%node
               m = m + 1
               j = j + 1
            end do
         end do
      end do
      call renumber_sides(model, ins, order, eptr)
      call move_alloc(new_ptr, model%elem_ptr)
      call move_alloc(new_conn, model%elem_conn)
      where (nins > 0) model%elem_type = etype_polygon
   end subroutine apply_insertions

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

   pure function itoa(i) result(s)
      integer(ip), intent(in) :: i
      character(len=:), allocatable :: s
      character(len=16) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function itoa
end module vemcontact_contact_insertion
