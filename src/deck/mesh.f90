!> Handlers of the mesh keywords: *NODE, *ELEMENT, *NSET and *ELSET.
!> Element connectivity is stored with user node ids while parsing and resolved
!> once at the end (see vemcontact_deck_finish); sets are resolved when read, so
!> the nodes and elements they name must be defined before them, as in CalculiX.
module vemcontact_deck_mesh
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_model, only: model_t, source_loc_t, etype_polygon, etype_quad4, etype_tri3, &
                               etype_polygon2, etype_quad8, etype_tri6, &
                               plane_strain, plane_stress
   use vemcontact_deck_state, only: deck_parser_t, item_list_t, here, err_here, refuse_here, warn_here, field, get_id, &
                                    get_int, get_real, push_item, node_index, elem_index, get_set, &
                                    set_suggestion, ref_kind, ref_id, ref_name
   use vemcontact_deck_lines, only: advance, skip_data
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: keyword_line_t, split_fields, get_param, has_param, to_upper, &
                                     squeeze, int_str
   use vemcontact_deck_numbers, only: parse_int, num_ok, number_problem
   implicit none
   private

   public :: read_nodes, read_elements, read_set

contains

   !> *NODE [, NSET=name]; data lines: id, x, y [, z = 0] [, ignored numbers].
   subroutine read_nodes(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: sname
      logical :: found, ok, warned
      integer :: kset
      integer(ip) :: id
      real(wp) :: x, y, z
      kset = 0
      warned = .false.
      call get_param(kw, 'NSET', sname, found)
      if (found) call get_set(model%nsets, p%nset_items, p%nnset, sname, here(p), .true., kset)
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (p%f%n > 4) then
            ! CalculiX reads id, x, y, z and ignores what follows (its test deck
            ! planestress.inp has a line "21, 0.75, 1.0, ,0.0": a blank z, then a stray 0)
            call check_extra_fields(p, warned, ok)
            if (.not. ok) cycle
         end if
         call get_id(p, 1, 'node id', id, ok)
         if (.not. ok) cycle
         call get_real(p, 2, 'x coordinate', x, ok)
         if (.not. ok) cycle
         call get_real(p, 3, 'y coordinate', y, ok)
         if (.not. ok) cycle
         call get_real(p, 4, 'z coordinate', z, ok)
         if (.not. ok) cycle
         if (abs(z) > 0.0_wp) then
            call err_here(p, 'node '//int_str(id)//' has z = '//field(p, 4)// &
                          ': vemcontact is two-dimensional, a third coordinate must be 0')
            cycle
         end if
         call add_node(p, model, id + p%node_offset, x, y)
         if (kset > 0) call push_item(p%nset_items(kset), model%nnode)
      end do
   end subroutine read_nodes

   !> The family of a CalculiX/Abaqus element type vemcontact does not model
   !> ('' when `tname` is none of them, e.g. a misspelt type).
   pure function element_family(tname) result(what)
      character(len=*), intent(in) :: tname
      character(len=:), allocatable :: what
      what = ''
      if (starts(tname, 'CAX') .or. starts(tname, 'CGAX')) then
         what = 'axisymmetric'
      else if (starts(tname, 'C3D')) then
         what = 'three-dimensional solid'
      else if (index(' CPE4R CPS4R CPE4I CPS4I CPE4H CPE3H CPE6H CPE8H CPE4RH CPE8RH CPE6M CPS6M CPE6MH ', &
                     ' '//tname//' ') > 0 .or. starts(tname, 'CPEG')) then
         what = 'a plane element variant vemcontact does not have'
      else if (starts(tname, 'S3') .or. starts(tname, 'S4') .or. starts(tname, 'S6') .or. &
               starts(tname, 'S8') .or. starts(tname, 'M3D')) then
         what = 'shell or membrane'
      else if (starts(tname, 'B2') .or. starts(tname, 'B3') .or. starts(tname, 'T2D') .or. &
               starts(tname, 'T3D') .or. starts(tname, 'U1')) then
         what = 'beam or truss'
      else if (starts(tname, 'SPRING') .or. starts(tname, 'DASHPOT') .or. starts(tname, 'GAP') .or. &
               tname == 'MASS' .or. starts(tname, 'DCOUP') .or. starts(tname, 'DC')) then
         what = 'spring, dashpot, gap, mass or heat transfer'
      end if
   contains
      pure logical function starts(s, prefix)
         character(len=*), intent(in) :: s, prefix
         starts = .false.
         if (len(s) >= len(prefix)) starts = s(1:len(prefix)) == prefix
      end function starts
   end function element_family

   !> Fields after the fourth of a *NODE line: numbers are ignored, as CalculiX
   !> does (one warning per *NODE block); anything else is an error.
   subroutine check_extra_fields(p, warned, ok)
      type(deck_parser_t), intent(inout) :: p
      logical, intent(inout) :: warned
      logical, intent(out) :: ok
      integer :: k
      real(wp) :: v
      do k = 5, p%f%n
         call get_real(p, k, 'field '//int_str(k)//' of a *NODE line (id, x, y, z)', v, ok)
         if (.not. ok) return
      end do
      if (.not. warned) call warn_here(p, 'fields after id, x, y, z of a *NODE line are ignored, as in '// &
                                       'CalculiX (found '//int_str(p%f%n)//')')
      warned = .true.
   end subroutine check_extra_fields

   subroutine add_node(p, model, id, x, y)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer(ip), intent(in) :: id
      real(wp), intent(in) :: x, y
      integer(ip), allocatable :: ti(:)
      real(wp), allocatable :: tx(:, :)
      type(source_loc_t), allocatable :: tl(:)
      integer(ip) :: n, cap
      n = model%nnode
      if (n == p%node_cap) then
         cap = max(1024_ip, 2*p%node_cap)
         allocate (ti(cap), tx(2, cap), tl(cap))
         if (n > 0) then
            ti(1:n) = model%node_id(1:n)
            tx(:, 1:n) = model%x(:, 1:n)
            tl(1:n) = model%node_loc(1:n)
         end if
         call move_alloc(ti, model%node_id)
         call move_alloc(tx, model%x)
         call move_alloc(tl, model%node_loc)
         p%node_cap = cap
      end if
      n = n + 1
      model%nnode = n
      model%node_id(n) = id
      model%x(1, n) = x
      model%x(2, n) = y
      model%node_loc(n) = here(p)
   end subroutine add_node

   !> *ELEMENT, TYPE=t [, ELSET=name]; data lines: id, n1, n2, ... (a line ending
   !> with a comma continues on the next line while nodes are still expected).
   subroutine read_elements(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: tname, sname
      logical :: found, ok, more, continued, reduced
      integer :: kset, etype, plane, nn, k, nnod, stat
      integer(ip) :: id, nid
      call get_param(kw, 'TYPE', tname, found)
      reduced = tname == 'CPE8R' .or. tname == 'CPS8R'
      select case (tname)
      case ('VPE')
         etype = etype_polygon; plane = plane_strain; nn = 0
      case ('VPS')
         etype = etype_polygon; plane = plane_stress; nn = 0
      case ('CPE4')
         etype = etype_quad4; plane = plane_strain; nn = 4
      case ('CPS4')
         etype = etype_quad4; plane = plane_stress; nn = 4
      case ('CPE3')
         etype = etype_tri3; plane = plane_strain; nn = 3
      case ('CPS3')
         etype = etype_tri3; plane = plane_stress; nn = 3
      case ('VPE2')
         etype = etype_polygon2; plane = plane_strain; nn = 0
      case ('VPS2')
         etype = etype_polygon2; plane = plane_stress; nn = 0
      case ('CPE8', 'CPE8R')
         etype = etype_quad8; plane = plane_strain; nn = 8
      case ('CPS8', 'CPS8R')
         etype = etype_quad8; plane = plane_stress; nn = 8
      case ('CPE6')
         etype = etype_tri6; plane = plane_strain; nn = 6
      case ('CPS6')
         etype = etype_tri6; plane = plane_stress; nn = 6
      case default
         if (len(element_family(tname)) > 0) then
            call refuse_here(p, 'element type '//tname//' ('//element_family(tname)//')', &
                             'the elements of vemcontact are VPE, VPS, VPE2, VPS2, CPE4, CPS4, CPE3, CPS3, '// &
                             'CPE8, CPS8, CPE8R, CPS8R, CPE6, CPS6')
            return
         end if
         call err_here(p, 'unsupported element type '//tname, &
                       'supported types are VPE, VPS (polygons), VPE2, VPS2 (second-order polygons), '// &
                       'CPE4, CPS4, CPE3, CPS3, CPE8, CPS8, CPE8R, CPS8R, CPE6, CPS6')
         p%element_errors = .true.
         call skip_data(p)
         return
      end select
      kset = 0
      call get_param(kw, 'ELSET', sname, found)
      if (found) call get_set(model%elsets, p%elset_items, p%nelset, sname, here(p), .true., kset)
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         ! a polygon's continued lines are split once at the end (splitting the
         ! growing line after every continuation is quadratic in its length)
         continued = .false.
         do while (p%src%text(p%src%length:p%src%length) == ',' .and. (nn == 0 .or. p%f%n < nn + 1))
            call p%src%continue_line(more)
            if (.not. more) exit
            continued = .true.
            if (nn > 0) call split_fields(p%src%text(1:p%src%length), p%f)
         end do
         if (continued .and. nn == 0) call split_fields(p%src%text(1:p%src%length), p%f)
         call get_id(p, 1, 'element id', id, ok)
         if (.not. ok) then
            p%element_errors = .true.
            cycle
         end if
         nnod = p%f%n - 1
         if (nn > 0 .and. nnod /= nn) then
            call err_here(p, 'element '//int_str(id)//' of type '//tname//' needs '//int_str(nn)// &
                          ' nodes, found '//int_str(nnod))
            p%element_errors = .true.
            cycle
         else if (nn == 0 .and. nnod < 3) then
            call err_here(p, 'element '//int_str(id)//' of type '//tname// &
                          ' needs at least 3 nodes, found '//int_str(nnod))
            p%element_errors = .true.
            cycle
         else if (etype == etype_polygon2 .and. (nnod < 6 .or. mod(nnod, 2) /= 0)) then
            call err_here(p, 'element '//int_str(id)//' of type '//tname// &
                          ' needs an even number of nodes, at least 6 (n corners, then n side nodes), found '// &
                          int_str(nnod))
            p%element_errors = .true.
            cycle
         end if
         call reserve_element(p, model, nnod)
         ok = .true.
         do k = 1, nnod
            call parse_int(p%src%text(p%f%first(k + 1):p%f%last(k + 1)), nid, stat)
            if (stat /= num_ok .or. nid <= 0) then
               if (stat == num_ok) then
                  call err_here(p, 'node id '//field(p, k + 1)//' of element '//int_str(id)// &
                                ' must be a positive integer')
               else
                  call err_here(p, number_problem(stat, field(p, k + 1), 'node id of element '//int_str(id)))
               end if
               ok = .false.
               exit
            end if
            model%elem_conn(p%nconn + k) = nid + p%node_offset
         end do
         if (.not. ok) then
            p%element_errors = .true.
            cycle
         end if
         p%nconn = p%nconn + nnod
         model%nelem = model%nelem + 1
         associate (e => model%nelem)
            model%elem_id(e) = id + p%elem_offset
            model%elem_ptr(e + 1) = p%nconn + 1
            model%elem_type(e) = etype
            model%elem_plane(e) = plane
            model%elem_loc(e) = here(p)
         end associate
         if (reduced) call push_item(p%reduced, model%nelem)
         if (kset > 0) call push_item(p%elset_items(kset), model%nelem)
      end do
   end subroutine read_elements

   !> Room for one more element with `nnod` nodes.
   subroutine reserve_element(p, model, nnod)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer, intent(in) :: nnod
      integer(ip), allocatable :: ti(:)
      integer, allocatable :: tt(:)
      type(source_loc_t), allocatable :: tl(:)
      integer(ip) :: n, cap
      n = model%nelem
      if (n == p%elem_cap) then
         cap = max(1024_ip, 2*p%elem_cap)
         allocate (ti(cap))
         if (n > 0) ti(1:n) = model%elem_id(1:n)
         call move_alloc(ti, model%elem_id)
         allocate (ti(cap + 1))
         ti(1) = 1
         if (n > 0) ti(1:n + 1) = model%elem_ptr(1:n + 1)
         call move_alloc(ti, model%elem_ptr)
         allocate (tt(cap))
         if (n > 0) tt(1:n) = model%elem_type(1:n)
         call move_alloc(tt, model%elem_type)
         allocate (tt(cap))
         if (n > 0) tt(1:n) = model%elem_plane(1:n)
         call move_alloc(tt, model%elem_plane)
         allocate (tl(cap))
         if (n > 0) tl(1:n) = model%elem_loc(1:n)
         call move_alloc(tl, model%elem_loc)
         p%elem_cap = cap
      end if
      if (p%nconn + nnod > p%conn_cap) then
         cap = max(4096_ip, 2*p%conn_cap, p%nconn + nnod)
         allocate (ti(cap))
         if (p%nconn > 0) ti(1:p%nconn) = model%elem_conn(1:p%nconn)
         call move_alloc(ti, model%elem_conn)
         p%conn_cap = cap
      end if
   end subroutine reserve_element

   !> *NSET, NSET=name [, GENERATE] (is_node) or *ELSET, ELSET=name [, GENERATE].
   !> Data lines: ids and names of existing sets, or with GENERATE first, last [, increment].
   !> A second definition with the same name appends, as in CalculiX.  A data line
   !> with an error adds nothing.
   subroutine read_set(p, model, kw, is_node)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      logical, intent(in) :: is_node
      character(len=:), allocatable :: sname, what
      logical :: found, generate, ok
      integer :: kset, k
      type(item_list_t) :: line_items
      if (is_node) then
         what = 'node'
         call get_param(kw, 'NSET', sname, found)
         call get_set(model%nsets, p%nset_items, p%nnset, sname, here(p), .true., kset)
      else
         what = 'element'
         call get_param(kw, 'ELSET', sname, found)
         call get_set(model%elsets, p%elset_items, p%nelset, sname, here(p), .true., kset)
      end if
      generate = has_param(kw, 'GENERATE')
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         line_items%n = 0
         if (generate) then
            call generate_line(p, model, is_node, what, line_items, ok)
         else
            call list_line(p, model, is_node, what, line_items, ok)
         end if
         if (.not. ok) cycle
         do k = 1, line_items%n
            if (is_node) then
               call push_item(p%nset_items(kset), line_items%a(k))
            else
               call push_item(p%elset_items(kset), line_items%a(k))
            end if
         end do
      end do
   end subroutine read_set

   !> A GENERATE data line, first, last [, increment]: the ids of the range into
   !> `items`; ok = .false. after an error (said at the line).
   subroutine generate_line(p, model, is_node, what, items, ok)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      logical, intent(in) :: is_node
      character(len=*), intent(in) :: what
      type(item_list_t), intent(inout) :: items
      logical, intent(out) :: ok
      integer(ip) :: first, last, inc, i, idx, first_missing
      integer :: nmissing
      if (p%f%n < 2 .or. p%f%n > 3) then
         call err_here(p, 'a GENERATE data line needs first, last [, increment], found '// &
                       int_str(p%f%n)//' fields')
         ok = .false.
         return
      end if
      call get_id(p, 1, 'first '//what//' id', first, ok)
      if (ok) call get_id(p, 2, 'last '//what//' id', last, ok)
      inc = 1
      if (ok .and. p%f%n == 3) call get_int(p, 3, 'increment', inc, ok)
      if (.not. ok) return
      ok = .false.
      if (inc <= 0) then
         call err_here(p, 'GENERATE increment must be positive, found '//int_str(inc))
         return
      end if
      if (last < first) then
         call err_here(p, 'GENERATE range is empty: last id '//int_str(last)// &
                       ' is smaller than first id '//int_str(first))
         return
      end if
      if (range_exceeds_model(p, model, is_node, what, first, last, inc)) return
      nmissing = 0
      first_missing = 0
      do i = first, last, inc
         idx = lookup(p, model, is_node, i)
         if (idx == 0) then
            nmissing = nmissing + 1
            if (nmissing == 1) first_missing = i
         else
            call push_item(items, idx)
         end if
         if (i > last - inc) exit   ! avoids overflow of i near huge()
      end do
      if (nmissing > 0) then
         call err_here(p, int_str(nmissing)//' of the ids '//int_str(first)//' to '//int_str(last)// &
                       ' are not defined '//what//'s (the first is '//int_str(first_missing)//')', &
                       what//'s must be defined before a set refers to them')
         return
      end if
      ok = .true.
   end subroutine generate_line

   !> Whether a GENERATE range holds more ids than the model defines (then some are
   !> missing: said at the line).  They are counted from the defined ids, never by
   !> walking a range of up to 2**31 ids.
   logical function range_exceeds_model(p, model, is_node, what, first, last, inc) result(exceeds)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      logical, intent(in) :: is_node
      character(len=*), intent(in) :: what
      integer(ip), intent(in) :: first, last, inc
      integer(i8) :: nrange, nfound
      integer(ip) :: id, first_missing
      integer :: k
      character(len=24) :: cbuf
      nrange = (int(last, i8) - first)/inc + 1
      exceeds = nrange > int(merge(model%nnode, model%nelem, is_node), i8)
      if (.not. exceeds) return
      nfound = 0
      do k = 1, merge(model%nnode, model%nelem, is_node)
         if (is_node) then
            id = model%node_id(k)
         else
            id = model%elem_id(k)
         end if
         if (id >= first .and. id <= last .and. mod(int(id, i8) - first, int(inc, i8)) == 0) &
            nfound = nfound + 1
      end do
      ! the first missing id comes after at most nfound defined ones
      first_missing = first
      do while (lookup(p, model, is_node, first_missing) /= 0)
         first_missing = first_missing + inc
      end do
      write (cbuf, '(i0)') nrange - nfound
      call err_here(p, trim(cbuf)//' of the ids '//int_str(first)//' to '//int_str(last)// &
                    ' are not defined '//what//'s (the first is '//int_str(first_missing)//')', &
                    what//'s must be defined before a set refers to them')
   end function range_exceeds_model

   !> A data line of ids and set names into `items`; ok = .false. after an error.
   subroutine list_line(p, model, is_node, what, items, ok)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      logical, intent(in) :: is_node
      character(len=*), intent(in) :: what
      type(item_list_t), intent(inout) :: items
      logical, intent(out) :: ok
      character(len=:), allocatable :: ref
      integer :: k, kind
      integer(ip) :: id, idx
      ok = .true.
      do k = 1, p%f%n
         if (p%f%last(k) < p%f%first(k)) cycle
         call ref_kind(p, k, kind, id, what)
         if (kind == ref_id) then
            idx = lookup(p, model, is_node, id)
            if (idx == 0) then
               call err_here(p, 'undefined '//what//' '//int_str(id), &
                             what//'s must be defined before a set refers to them')
               ok = .false.
               return
            end if
            call push_item(items, idx)
         else if (kind == ref_name) then
            ref = to_upper(squeeze(field(p, k)))
            call add_named(p, model, is_node, ref, items, ok)
            if (.not. ok) return
         else
            ok = .false.
            return
         end if
      end do
   end subroutine list_line

   !> The index of the node (is_node) or element with user id uid; 0 if undefined.
   function lookup(p, model, is_node, uid) result(ix)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      logical, intent(in) :: is_node
      integer(ip), intent(in) :: uid
      integer(ip) :: ix
      if (is_node) then
         ix = node_index(p, model, uid)
      else
         ix = elem_index(p, model, uid)
      end if
   end function lookup

   !> Append the items of the existing set `name` to items; ok = .false. if undefined.
   subroutine add_named(p, model, is_node, name, items, ok)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      logical, intent(in) :: is_node
      character(len=*), intent(in) :: name
      type(item_list_t), intent(inout) :: items
      logical, intent(out) :: ok
      integer :: kref
      integer(ip) :: j
      if (is_node) then
         call get_set(model%nsets, p%nset_items, p%nnset, name, here(p), .false., kref)
         ok = kref /= 0
         if (.not. ok) then
            call err_here(p, 'undefined node set '//name, set_suggestion(model%nsets, p%nnset, name))
            return
         end if
         do j = 1, p%nset_items(kref)%n
            call push_item(items, p%nset_items(kref)%a(j))
         end do
      else
         call get_set(model%elsets, p%elset_items, p%nelset, name, here(p), .false., kref)
         ok = kref /= 0
         if (.not. ok) then
            call err_here(p, 'undefined element set '//name, set_suggestion(model%elsets, p%nelset, name))
            return
         end if
         do j = 1, p%elset_items(kref)%n
            call push_item(items, p%elset_items(kref)%a(j))
         end do
      end if
   end subroutine add_named
end module vemcontact_deck_mesh
