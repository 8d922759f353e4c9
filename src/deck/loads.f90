!> Handlers of the step and load keywords: *STEP, *STATIC, *GEOSTATIC, *END STEP,
!> *BOUNDARY, *CLOAD, *DLOAD, and of *HEADING.
!> Entries are kept in deck order; with OP=NEW the entries of that kind given
!> earlier in the same step are dropped and the step's `*_new` flag is set, which
!> tells the driver to drop those of earlier steps too (CalculiX semantics).
module vemcontact_deck_loads
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, step_t, dof_value_t, dload_t, dload_grav, dload_pressure, &
                               dload_hydrostatic, procedure_static, procedure_geostatic, element_order, &
                               procedure_strength_reduction
   use vemcontact_deck_state, only: deck_parser_t, item_list_t, step_acc_t, grav_ref_t, here, &
                                    err_here, refuse_here, err_at, warn_here, field, get_int, get_real, push_item, push_dof, &
                                    push_dload, node_index, elem_index, get_set, set_suggestion, &
                                    ref_kind, ref_id, ref_name, loc_str, tidy_items
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: keyword_line_t, split_fields, get_param, has_param, to_upper, &
                                     squeeze, int_str
   use vemcontact_deck_numbers, only: parse_int, num_ok
   use vemcontact_deck_outputs, only: carry_outputs
   implicit none
   private

   public :: read_heading, read_boundary, read_cload, read_dload, start_step, read_procedure, end_step
   public :: acc_to_step, field_nodes, field_elems, get_op, trim_steps

contains

   !> *HEADING: the data lines are the heading text (joined with new lines).
   subroutine read_heading(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         if (allocated(model%heading)) then
            model%heading = model%heading//new_line('a')//p%src%text(1:p%src%length)
         else
            model%heading = p%src%text(1:p%src%length)
         end if
      end do
   end subroutine read_heading

   !> Nodes named by field k (a node id or a node set) into `nodes`; ok = .false. if reported.
   subroutine field_nodes(p, model, k, nodes, ok)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer, intent(in) :: k
      type(item_list_t), intent(inout) :: nodes
      logical, intent(out) :: ok
      integer :: kind, kset
      integer(ip) :: id, idx
      character(len=:), allocatable :: name
      nodes%n = 0
      ok = .false.
      if (p%f%n < k) then
         call err_here(p, 'missing node id or node set name')
         return
      end if
      call ref_kind(p, k, kind, id, 'node')
      if (kind == ref_id) then
         idx = node_index(p, model, id)
         if (idx == 0) then
            call err_here(p, 'undefined node '//int_str(id))
            return
         end if
         call push_item(nodes, idx)
      else if (kind == ref_name) then
         name = to_upper(squeeze(field(p, k)))
         call get_set(model%nsets, p%nset_items, p%nnset, name, here(p), .false., kset)
         if (kset == 0) then
            call err_here(p, 'undefined node set '//name, set_suggestion(model%nsets, p%nnset, name))
            return
         end if
         call tidy_items(p%nset_items(kset))
         do id = 1, p%nset_items(kset)%n
            call push_item(nodes, p%nset_items(kset)%a(id))
         end do
      else
         return
      end if
      ok = .true.
   end subroutine field_nodes

   !> Elements named by field k (an element id or an element set).
   subroutine field_elems(p, model, k, elems, ok)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer, intent(in) :: k
      type(item_list_t), intent(inout) :: elems
      logical, intent(out) :: ok
      integer :: kind, kset
      integer(ip) :: id, idx
      character(len=:), allocatable :: name
      elems%n = 0
      ok = .false.
      if (p%f%n < k) then
         call err_here(p, 'missing element id or element set name')
         return
      end if
      call ref_kind(p, k, kind, id, 'element')
      if (kind == ref_id) then
         idx = elem_index(p, model, id)
         if (idx == 0) then
            call err_here(p, 'undefined element '//int_str(id))
            return
         end if
         call push_item(elems, idx)
      else if (kind == ref_name) then
         name = to_upper(squeeze(field(p, k)))
         call get_set(model%elsets, p%elset_items, p%nelset, name, here(p), .false., kset)
         if (kset == 0) then
            call err_here(p, 'undefined element set '//name, set_suggestion(model%elsets, p%nelset, name))
            return
         end if
         call tidy_items(p%elset_items(kset))
         do id = 1, p%elset_items(kset)%n
            call push_item(elems, p%elset_items(kset)%a(id))
         end do
      else
         return
      end if
      ok = .true.
   end subroutine field_elems

   !> OP=NEW/MOD of a load keyword; `is_new` true for NEW, reported outside a step.
   subroutine get_op(p, kw, kname, is_new)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t), intent(in) :: kw
      character(len=*), intent(in) :: kname
      logical, intent(out) :: is_new
      character(len=:), allocatable :: op
      logical :: found
      call get_param(kw, 'OP', op, found)
      is_new = op == 'NEW'
      if (is_new .and. .not. p%in_step) then
         call err_here(p, 'OP=NEW on '//kname//' is only meaningful inside a *STEP', &
                       'conditions given before the first *STEP hold in every step')
         is_new = .false.
      end if
   end subroutine get_op

   !> *BOUNDARY [, OP=MOD|NEW]; data lines: node or node set, first dof [, last dof [, value]].
   !> Dof 3 (z) is accepted and ignored: CalculiX decks for plane elements often fix 1 to 3.
   subroutine read_boundary(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      logical :: is_new, ok
      integer(ip) :: dof1, dof2
      integer :: i, dof
      real(wp) :: val
      type(item_list_t) :: nodes
      call get_op(p, kw, '*BOUNDARY', is_new)
      if (is_new) then
         p%cur%bnew = .true.
         p%cur%nb = 0
      end if
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (p%f%n > 4) then
            call err_here(p, 'too many fields on a *BOUNDARY data line: expected node or set, '// &
                          'first dof, last dof, value')
            cycle
         end if
         call field_nodes(p, model, 1, nodes, ok)
         if (.not. ok) cycle
         if (boundary_type(p, dof1, dof2, ok)) then
            ! Abaqus' named conditions (Abaqus/CAE writes them): zero values
            if (.not. ok) cycle
            call push_range(dof1, dof2, 0.0_wp)
            cycle
         end if
         call get_int(p, 2, 'first degree of freedom', dof1, ok)
         if (.not. ok) cycle
         dof2 = dof1
         if (p%f%n >= 3) then
            if (p%f%last(3) >= p%f%first(3)) then
               call get_int(p, 3, 'last degree of freedom', dof2, ok)
               if (.not. ok) cycle
            end if
         end if
         call get_real(p, 4, 'prescribed value', val, ok)
         if (.not. ok) cycle
         if (.not. dofs_ok(p, dof1, dof2)) cycle
         call push_range(dof1, dof2, val)
      end do
   contains
      subroutine push_range(d1, d2, v)
         integer(ip), intent(in) :: d1, d2
         real(wp), intent(in) :: v
         do i = 1, nodes%n
            do dof = int(d1), min(int(d2), 2)
               if (p%in_step) then
                  call push_dof(p%cur%boundary, p%cur%nb, dof_value_t(nodes%a(i), dof, v, p%amp))
               else
                  call push_dof(p%init%boundary, p%init%nb, dof_value_t(nodes%a(i), dof, v, p%amp))
               end if
            end do
         end do
      end subroutine push_range
   end subroutine read_boundary

   !> Whether field 2 of a *BOUNDARY line is one of Abaqus' named conditions, and the
   !> in-plane dofs it holds: ENCASTRE and PINNED 1-2, XSYMM 1 (u1 = ur2 = ur3 = 0),
   !> YSYMM 2, XASYMM 2 (u2 = u3 = ur1 = 0), YASYMM 1; ZSYMM and ZASYMM hold no
   !> in-plane dof of a 2D model (ok false, no error: nothing to hold).  Other names
   !> are errors (ok false).
   function boundary_type(p, dof1, dof2, ok) result(named)
      type(deck_parser_t), intent(inout) :: p
      integer(ip), intent(out) :: dof1, dof2
      logical, intent(out) :: ok
      logical :: named
      character(len=:), allocatable :: f
      dof1 = 1
      dof2 = 2
      ok = .true.
      named = .false.
      if (p%f%n < 2) return
      f = to_upper(squeeze(field(p, 2)))
      if (len(f) == 0) return
      if (index('ABCDEFGHIJKLMNOPQRSTUVWXYZ', f(1:1)) == 0) return
      named = .true.
      select case (f)
      case ('ENCASTRE', 'PINNED')
      case ('XSYMM', 'YASYMM')
         dof2 = 1
      case ('YSYMM', 'XASYMM')
         dof1 = 2
      case ('ZSYMM', 'ZASYMM')
         ok = .false.
      case default
         call err_here(p, 'unknown boundary type '//f//' on a *BOUNDARY line', &
                       'Abaqus'' types are ENCASTRE, PINNED, XSYMM, YSYMM, ZSYMM, XASYMM, YASYMM, ZASYMM; '// &
                       'or give first dof, last dof, value')
         ok = .false.
      end select
      if (ok .and. p%f%n > 2) then
         call err_here(p, 'a named boundary type takes no further fields')
         ok = .false.
      end if
   end function boundary_type

   !> Check a dof range; dofs are 1 (x), 2 (y) and 3 (z, ignored).
   function dofs_ok(p, dof1, dof2) result(ok)
      type(deck_parser_t), intent(inout) :: p
      integer(ip), intent(in) :: dof1, dof2
      logical :: ok
      ok = .false.
      if (dof1 < 1 .or. dof2 < 1) then
         call err_here(p, 'degrees of freedom are numbered from 1, found '//int_str(min(dof1, dof2)))
      else if (dof2 < dof1) then
         call err_here(p, 'last degree of freedom '//int_str(dof2)//' is smaller than the first '// &
                       int_str(dof1))
      else if (dof2 > 3) then
         call err_here(p, 'degree of freedom '//int_str(dof2)//' does not exist in a 2D model', &
                       'dofs are 1 (x) and 2 (y); 3 (z) is accepted and ignored')
      else
         ok = .true.
      end if
   end function dofs_ok

   !> *CLOAD [, OP=MOD|NEW]; data lines: node or node set, dof, value (at each node of a set).
   subroutine read_cload(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      logical :: is_new, ok
      integer(ip) :: dof
      integer :: i
      real(wp) :: val
      type(item_list_t) :: nodes
      call get_op(p, kw, '*CLOAD', is_new)
      if (is_new) then
         p%cur%cnew = .true.
         p%cur%nc = 0
      end if
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (p%f%n > 3) then
            call err_here(p, 'too many fields on a *CLOAD data line: expected node or set, dof, value')
            cycle
         end if
         call field_nodes(p, model, 1, nodes, ok)
         if (.not. ok) cycle
         call get_int(p, 2, 'degree of freedom', dof, ok)
         if (.not. ok) cycle
         call get_real(p, 3, 'load value', val, ok)
         if (.not. ok) cycle
         if (.not. dofs_ok(p, dof, dof)) cycle
         if (dof == 3) then
            if (abs(val) > 0.0_wp) call err_here(p, 'a force in z (dof 3) cannot be applied in a 2D model')
            cycle
         end if
         do i = 1, nodes%n
            call push_dof(p%cur%cload, p%cur%nc, dof_value_t(nodes%a(i), int(dof), val, p%amp))
         end do
      end do
   end subroutine read_cload

   !> *DLOAD [, OP=MOD|NEW]; data lines: element or element set, GRAV, g, dx, dy [, dz = 0],
   !> element or element set, P<k>, p (pressure on side k), or element or element set,
   !> HP<k>, p, y_zero, y_ref (Abaqus' hydrostatic pressure on side k: p at height y_ref,
   !> falling linearly to zero at the free surface y_zero, zero above it).
   subroutine read_dload(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      logical :: is_new, ok
      integer :: i, side, stat, nn
      integer(ip) :: iside, e
      real(wp) :: mag, d(3), dnorm, yzero, yref
      character(len=:), allocatable :: label
      type(item_list_t) :: elems
      type(dload_t) :: rec
      call get_op(p, kw, '*DLOAD', is_new)
      if (is_new) then
         p%cur%dnew = .true.
         p%cur%nd = 0
      end if
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         call field_elems(p, model, 1, elems, ok)
         if (.not. ok) cycle
         label = to_upper(squeeze(field(p, 2)))
         if (label == 'GRAV') then
            if (p%f%n > 6) then
               call err_here(p, 'too many fields on a GRAV data line: expected element or set, GRAV, g, dx, dy, dz')
               cycle
            end if
            call get_real(p, 3, 'gravity magnitude', mag, ok, required=.true.)
            if (ok) call get_real(p, 4, 'gravity direction x', d(1), ok)
            if (ok) call get_real(p, 5, 'gravity direction y', d(2), ok)
            if (ok) call get_real(p, 6, 'gravity direction z', d(3), ok)
            if (.not. ok) cycle
            if (abs(d(3)) > 0.0_wp) then
               call err_here(p, 'gravity direction has a z component '//field(p, 6)// &
                             ': it must lie in the x-y plane of a 2D model')
               cycle
            end if
            dnorm = hypot(d(1), d(2))
            if (.not. dnorm > 0.0_wp) then
               call err_here(p, 'gravity direction (dx, dy) is zero', &
                             'write e.g. "EALL, GRAV, 9810., 0., -1." for gravity along -y')
               cycle
            end if
            rec = dload_t(kind=dload_grav, side=0, magnitude=mag, dir=d(1:2)/dnorm)
            do i = 1, elems%n
               rec%elem = elems%a(i)
               rec%amp = p%amp
               call push_dload(p%cur%dload, p%cur%nd, rec)
               call add_grav(p, elems%a(i))
            end do
         else if (len(label) >= 3 .and. label(1:min(2, len(label))) == 'HP') then
            call parse_int(label(3:), iside, stat)
            if (stat /= num_ok .or. iside < 1) then
               call bad_label(label)
               cycle
            end if
            if (p%f%n > 5) then
               call err_here(p, 'too many fields on a hydrostatic pressure data line: expected '// &
                             'element or set, HP<k>, p, y_zero, y_ref')
               cycle
            end if
            call get_real(p, 3, 'hydrostatic pressure magnitude', mag, ok, required=.true.)
            if (ok) call get_real(p, 4, 'free-surface height y_zero (zero pressure)', yzero, ok, required=.true.)
            if (ok) call get_real(p, 5, 'reference height y_ref (where the pressure is the magnitude)', &
                                  yref, ok, required=.true.)
            if (.not. ok) cycle
            if (yref > yzero) then
               call err_here(p, 'the reference height y_ref = '//field(p, 5)//' lies above the free-surface '// &
                             'height y_zero = '//field(p, 4)//', where the hydrostatic pressure is zero', hp_help())
               cycle
            else if (.not. yzero > yref) then
               call err_here(p, 'the free-surface height y_zero and the reference height y_ref are equal ('// &
                             field(p, 4)//', '//field(p, 5)//'): the pressure gradient is undefined', hp_help())
               cycle
            end if
            side = iside
            if (.not. sides_exist(side, label)) cycle
            rec = dload_t(kind=dload_hydrostatic, side=side, magnitude=mag, dir=[yzero, yref])
            do i = 1, elems%n
               rec%elem = elems%a(i)
               rec%amp = p%amp
               call push_dload(p%cur%dload, p%cur%nd, rec)
            end do
         else if (len(label) >= 2 .and. index(label, 'P') == 1) then   ! index: safe on an empty label
            call parse_int(label(2:), iside, stat)
            if (stat /= num_ok .or. iside < 1) then
               call bad_label(label)
               cycle
            end if
            if (p%f%n > 3) then
               call err_here(p, 'too many fields on a pressure data line: expected element or set, P<k>, p')
               cycle
            end if
            call get_real(p, 3, 'pressure', mag, ok, required=.true.)
            if (.not. ok) cycle
            side = iside
            if (.not. sides_exist(side, label)) cycle
            rec = dload_t(kind=dload_pressure, side=side, magnitude=mag, dir=0.0_wp)
            do i = 1, elems%n
               rec%elem = elems%a(i)
               rec%amp = p%amp
               call push_dload(p%cur%dload, p%cur%nd, rec)
            end do
         else
            call bad_label(label)
         end if
      end do
   contains
      subroutine bad_label(lab)
         character(len=*), intent(in) :: lab
         character(len=*), parameter :: labels = 'labels are GRAV, P1, P2, ... (pressure on side k) '// &
                                         'and HP1, HP2, ... (hydrostatic pressure on side k)'
         if (len(lab) == 0) then
            call err_here(p, 'missing load label on a *DLOAD data line', labels)
         else
            call err_here(p, 'unsupported *DLOAD label '//lab, labels)
         end if
      end subroutine bad_label

      !> Whether every element of `elems` has side `k` (reported once if not).
      logical function sides_exist(k, lab)
         integer, intent(in) :: k
         character(len=*), intent(in) :: lab
         integer :: j
         sides_exist = .true.
         do j = 1, elems%n
            e = elems%a(j)
            nn = (model%elem_ptr(e + 1) - model%elem_ptr(e))/element_order(model%elem_type(e))
            if (k > nn) then
               call err_here(p, 'element '//int_str(model%elem_id(e))//' has '//int_str(nn)// &
                             ' sides, so there is no side '//lab, &
                             'side k runs from node k to node k+1 of the element (corner k to corner k+1 '// &
                             'of a second-order element)')
               sides_exist = .false.
               return
            end if
         end do
      end function sides_exist

      pure function hp_help() result(h)
         character(len=:), allocatable :: h
         h = 'write "element or set, HPk, p, y_zero, y_ref" with y_ref below the free surface y_zero, '// &
             'e.g. "UPSTREAM, HP4, 0.98, 100., 0." for water 100 m deep at y = 0 (MPa, m)'
      end function hp_help
   end subroutine read_dload

   subroutine add_grav(p, e)
      type(deck_parser_t), intent(inout) :: p
      integer(ip), intent(in) :: e
      type(grav_ref_t), allocatable :: t(:)
      if (.not. allocated(p%grav)) allocate (p%grav(16))
      if (p%ngrav == size(p%grav)) then
         allocate (t(2*p%ngrav))
         t(1:p%ngrav) = p%grav(1:p%ngrav)
         call move_alloc(t, p%grav)
      end if
      p%ngrav = p%ngrav + 1
      p%grav(p%ngrav) = grav_ref_t(elem=e, loc=here(p))
   end subroutine add_grav

   !> *STEP [, NLGEOM=NO] [, INC=n] [, NAME=name] (no data lines).
   subroutine start_step(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: val
      logical :: found
      if (p%in_step) then
         call err_here(p, '*STEP inside a step: the step started at '//loc_str(p, p%step_loc)// &
                       ' has no *END STEP')
         call end_step(p, model)
      end if
      call get_param(kw, 'NLGEOM', val, found)
      if (found .and. val /= 'NO') then
         call refuse_here(p, 'NLGEOM (geometric nonlinearity)', 'vemcontact is a small-strain code: '// &
                          'remove NLGEOM or write NLGEOM=NO to run the step linearly')
         return
      end if
      p%in_step = .true.
      p%procedure_seen = .false.
      p%step_loc = here(p)
      p%cur = step_acc_t()
      call get_param(kw, 'NAME', val, found)
      if (found) then
         p%cur%name = val
      else
         p%cur%name = 'Step-'//int_str(p%nstep + 1)
      end if
      if (has_param(kw, 'INC')) continue   ! accepted: the increments have no count limit
      call get_param(kw, 'AMPLITUDE', val, found)
      if (found) p%cur%ramp = val /= 'STEP'
   end subroutine start_step

   !> *STATIC [, SOLVER=...] [, DIRECT] or, with `geostatic`, *GEOSTATIC (Abaqus): the
   !> procedure of the step, exactly one per step.  The optional data line of *STATIC
   !> gives the increments (read_increments); *GEOSTATIC's is checked and ignored (the
   !> geostatic step is one increment).  SOLVER= names the run's linear solver (read_solver).
   subroutine read_procedure(p, geostatic, model, kw)
      type(deck_parser_t), intent(inout) :: p
      logical, intent(in) :: geostatic
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      integer :: nline
      logical :: found
      character(len=:), allocatable :: kname, other, val
      character(len=*), parameter :: one = 'a step has exactly one procedure: *STATIC, or *GEOSTATIC in the first step'
      if (geostatic) then
         kname = '*GEOSTATIC'
      else
         kname = '*STATIC'
      end if
      if (p%procedure_seen) then
         other = '*STATIC'
         if (p%cur%procedure == procedure_geostatic) other = '*GEOSTATIC'
         if (p%cur%procedure == procedure_strength_reduction) other = '*STRENGTH REDUCTION'
         if (other == kname) then
            call err_here(p, 'second '//kname//' in the step started at '//loc_str(p, p%step_loc), one)
         else
            call err_here(p, kname//' in the step started at '//loc_str(p, p%step_loc)// &
                          ', which already has '//other, one)
         end if
      else if (geostatic .and. p%nstep > 0) then
         call err_here(p, 'a geostatic step must be the first step', &
                       '*GEOSTATIC sets the initial state (e.g. under self-weight) that later steps '// &
                       'are measured from; use *STATIC in step '//int_str(p%nstep + 1))
      else if (geostatic) then
         p%cur%procedure = procedure_geostatic
      else
         p%cur%procedure = procedure_static
      end if
      p%procedure_seen = .true.
      call get_param(kw, 'SOLVER', val, found)
      if (found) call read_solver(p, model, val)
      if (.not. geostatic) p%cur%direct = has_param(kw, 'DIRECT')
      nline = 0
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         nline = nline + 1
         if (nline == 2) call err_here(p, kname//' takes at most one data line')
         if (nline > 1) cycle
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (p%f%n > 4) then
            call err_here(p, 'too many fields on the '//kname//' data line: expected at most 4 time values')
            cycle
         end if
         call read_increments(p, geostatic)
      end do
   end subroutine read_procedure

   !> The *STATIC data line (CalculiX): initial time increment (default 1), time period
   !> of the step (default 1), minimum increment (default min(initial, 1e-5 period)),
   !> maximum increment (default 1e30); empty fields take the default.  Every value
   !> given must be positive, the minimum at most the initial increment, the maximum at
   !> least the initial increment.  An initial increment beyond the period is the period
   !> (CalculiX); with DIRECT, increments that do not divide the period end with a shorter
   !> one (warned of).
   subroutine read_increments(p, geostatic)
      type(deck_parser_t), intent(inout) :: p
      logical, intent(in) :: geostatic
      real(wp) :: v(4), n
      logical :: ok, given(4)
      integer :: k
      character(len=*), parameter :: what(4) = [character(len=24) :: 'initial time increment', &
                                                'time period of the step', 'minimum time increment', &
                                                'maximum time increment']
      character(len=*), parameter :: help = 'the *STATIC data line is: initial time increment, time period '// &
                                             'of the step, minimum increment, maximum increment (docs/deck-reference.md)'
      v = [1.0_wp, 1.0_wp, 0.0_wp, 1.0e30_wp]
      given = .false.
      do k = 1, p%f%n
         if (len_trim(field(p, k)) == 0) cycle
         call get_real(p, k, trim(what(k)), v(k), ok)
         if (.not. ok) return
         given(k) = .true.
         if (.not. (v(k) > 0.0_wp)) then
            call err_here(p, 'the '//trim(what(k))//' must be positive, not '//field(p, k), help)
            return
         end if
      end do
      if (geostatic) return
      if (given(3) .and. v(3) > v(1)) then
         call err_here(p, 'the minimum time increment '//field(p, 3)//' is larger than the initial increment '// &
                       trim(field_or(1, '1')), help)
         return
      end if
      if (given(4) .and. v(4) < min(v(1), v(2))) then
         call err_here(p, 'the maximum time increment '//field(p, 4)//' is smaller than the initial increment '// &
                       trim(field_or(1, '1')), help)
         return
      end if
      if (p%cur%direct .and. v(1) < v(2)) then
         n = v(2)/v(1)
         if (abs(n - anint(n)) > 1.0e-6_wp*n) call warn_here(p, 'the fixed increment '//trim(field_or(1, '1'))// &
                                                            ' does not divide the step time '// &
                                                            trim(field_or(2, '1'))//': the last increment is shorter')
      end if
      p%cur%dt_initial = v(1)
      p%cur%period = v(2)
      p%cur%dt_min = v(3)
      p%cur%dt_max = v(4)
   contains
      function field_or(k, dflt) result(s)
         integer, intent(in) :: k
         character(len=*), intent(in) :: dflt
         character(len=:), allocatable :: s
         s = dflt
         if (given(k)) s = field(p, k)
      end function field_or
   end subroutine read_increments

   !> SOLVER= of *STATIC: vemcontact's linear solvers CHOLMOD, GAMG, HYPRE, MUMPS set
   !> model%linear_solver (the command line's --solver wins); CalculiX's SPOOLES,
   !> PARDISO, PASTIX, ITERATIVE SCALING and ITERATIVE CHOLESKY are accepted for the
   !> default.  One solver per run: a step naming another than an earlier step is warned of.
   subroutine read_solver(p, model, val)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      character(len=*), intent(in) :: val
      character(len=:), allocatable :: name
      select case (val)
      case ('CHOLMOD')
         name = 'cholmod'
      case ('GAMG')
         name = 'gamg'
      case ('HYPRE')
         name = 'hypre'
      case ('MUMPS')
         name = 'mumps'
      case ('SPOOLES', 'PARDISO', 'PASTIX', 'ITERATIVESCALING', 'ITERATIVECHOLESKY')
         return
      case default
         call err_here(p, 'unknown SOLVER='//val//' on *STATIC', &
                       'vemcontact''s linear solvers are CHOLMOD, GAMG, HYPRE and MUMPS (docs/deck-reference.md); '// &
                       'CalculiX''s SPOOLES, PARDISO, PASTIX, ITERATIVE SCALING and ITERATIVE CHOLESKY are '// &
                       'accepted for the default')
         return
      end select
      if (.not. allocated(model%linear_solver)) then
         model%linear_solver = name
      else if (model%linear_solver /= name) then
         call warn_here(p, 'SOLVER='//val//' is not used: one linear solver per run, the first step''s ('// &
                        to_upper(model%linear_solver)//')')
      end if
   end subroutine read_solver

   !> *END STEP, or the implicit end of a step: store the step in the model.
   !> model%steps grows by doubling (its size is the capacity while the deck is read,
   !> trim_steps makes it exact), so that reading n steps costs O(n).
   subroutine end_step(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(step_t), allocatable :: t(:)
      integer :: k
      if (.not. p%procedure_seen) then
         call err_at(p, p%step_loc, 'the step has no procedure', &
                     'add *STATIC inside the step (or *GEOSTATIC, in the first step only)')
      end if
      if (p%cur%procedure == procedure_strength_reduction .and. p%cur%load_loc%line > 0) then
         call err_at(p, p%cur%load_loc, p%cur%load_kw//' in a *STRENGTH REDUCTION step', &
                     'a strength reduction step keeps the loads of the step before it; change loads in a '// &
                     '*STATIC step before the *STRENGTH REDUCTION step')
      end if
      if (.not. allocated(model%steps)) allocate (model%steps(4))
      if (p%nstep == size(model%steps)) then
         allocate (t(2*p%nstep))
         do k = 1, p%nstep
            call move_step(model%steps(k), t(k))
         end do
         call move_alloc(t, model%steps)
      end if
      p%nstep = p%nstep + 1
      call acc_to_step(p%cur, model%steps(p%nstep))
      model%steps(p%nstep)%loc = p%step_loc
      if (p%nstep > 1) call carry_outputs(model%steps(p%nstep - 1), model%steps(p%nstep), p%cur%out_seen)
      p%in_step = .false.
      p%cur = step_acc_t()
   end subroutine end_step

   !> model%steps of exactly the steps read (end_step leaves it at its capacity).
   subroutine trim_steps(p, model)
      type(deck_parser_t), intent(in) :: p
      type(model_t), intent(inout) :: model
      type(step_t), allocatable :: t(:)
      integer :: k
      if (.not. allocated(model%steps)) then
         allocate (model%steps(0))
         return
      end if
      if (size(model%steps) == p%nstep) return
      allocate (t(p%nstep))
      do k = 1, p%nstep
         call move_step(model%steps(k), t(k))
      end do
      call move_alloc(t, model%steps)
   end subroutine trim_steps

   subroutine move_step(a, b)
      type(step_t), intent(inout) :: a
      type(step_t), intent(out) :: b
      call move_alloc(a%name, b%name)
      b%procedure = a%procedure
      b%dt_initial = a%dt_initial
      b%period = a%period
      b%dt_min = a%dt_min
      b%dt_max = a%dt_max
      b%direct = a%direct
      b%srm = a%srm
      b%ramp = a%ramp
      b%boundary_new = a%boundary_new
      b%cload_new = a%cload_new
      b%dload_new = a%dload_new
      call move_alloc(a%boundary, b%boundary)
      call move_alloc(a%cload, b%cload)
      call move_alloc(a%dload, b%dload)
      call move_alloc(a%uplift, b%uplift)
      call move_alloc(a%friction_changes, b%friction_changes)
      b%temperature_new = a%temperature_new
      call move_alloc(a%temperature, b%temperature)
      call move_alloc(a%outputs, b%outputs)
      b%loc = a%loc
   end subroutine move_step

   !> Exact-size lists of a step from the accumulator.
   subroutine acc_to_step(acc, s)
      type(step_acc_t), intent(in) :: acc
      type(step_t), intent(inout) :: s
      if (allocated(acc%name)) s%name = acc%name
      s%procedure = acc%procedure
      s%dt_initial = acc%dt_initial
      s%period = acc%period
      s%dt_min = acc%dt_min
      s%dt_max = acc%dt_max
      s%direct = acc%direct
      s%srm = acc%srm
      ! *GEOSTATIC applies its loads at once (one increment)
      s%ramp = acc%ramp .and. acc%procedure /= procedure_geostatic
      s%boundary_new = acc%bnew
      s%cload_new = acc%cnew
      s%dload_new = acc%dnew
      allocate (s%boundary(acc%nb), s%cload(acc%nc), s%dload(acc%nd))
      if (acc%nb > 0) s%boundary = acc%boundary(1:acc%nb)
      if (acc%nc > 0) s%cload = acc%cload(1:acc%nc)
      if (acc%nd > 0) s%dload = acc%dload(1:acc%nd)
      if (allocated(acc%uplift)) s%uplift = acc%uplift
      if (allocated(acc%friction_changes)) s%friction_changes = acc%friction_changes
      s%temperature_new = acc%tnew
      allocate (s%temperature(acc%nt))
      if (acc%nt > 0) s%temperature = acc%temperature(1:acc%nt)
      allocate (s%outputs(acc%nout))
      if (acc%nout > 0) s%outputs = acc%outputs(1:acc%nout)
   end subroutine acc_to_step
end module vemcontact_deck_loads
