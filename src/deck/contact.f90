!> Handlers of the contact keywords: *SURFACE, *SURFACE INTERACTION, *SURFACE BEHAVIOR,
!> *FRICTION, *CONTACT PAIR and *CONTACT CONTROLS, and their resolution after the deck is read.
!> Surfaces are resolved when read (their elements, sets and nodes must be defined
!> before them, as for sets); contact pairs name surfaces and interactions that are
!> looked up at the end, so that a misspelt name gets a suggestion among all of them.
!> All contact definitions hold in every step and go before the first *STEP, as in
!> CalculiX.
module vemcontact_deck_contact
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, surface_t, interaction_t, contact_pair_t, source_loc_t, friction_change_t, &
                               surface_element, surface_node, pair_node_to_surface, pair_surface_to_surface, &
                               element_order
   use vemcontact_deck_state, only: deck_parser_t, item_list_t, pair_ref_t, here, err_here, err_at, &
                                    warn_here, field, get_real, push_item, loc_str
   use vemcontact_deck_loads, only: field_nodes, field_elems
   use vemcontact_deck_lines, only: advance, skip_data
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: keyword_line_t, parse_keyword_line, split_fields, get_param, &
                                     has_param, to_upper, squeeze, int_str, edit_distance
   use vemcontact_deck_numbers, only: parse_int, parse_real, num_ok
   use vemcontact_deck_idmap, only: sort_unique
   implicit none
   private

   public :: read_surface, read_interaction, read_behavior, drop_behavior, read_contact_pair, read_controls
   public :: read_friction, read_change_friction
   public :: finish_contact, find_surface

   character(len=*), parameter :: side_help = 'sides are S1, S2, ...: side Sk runs from node k to node k+1 '// &
                                              'of the element (S1 = nodes 1-2, the last side back to node 1)'

   !> Largest MAXIT of *CONTACT CONTROLS: the hardest contact decks measured need
   !> under 100 iterations, and the iteration's per-iteration history is sized by it.
   integer, parameter :: max_contact_iterations = 1000

contains

   !> Contact definitions hold in every step: they must come before the first *STEP.
   subroutine before_steps(p, kname)
      type(deck_parser_t), intent(inout) :: p
      character(len=*), intent(in) :: kname
      if (p%nstep > 0) then
         call err_here(p, kname//' must come before the first *STEP', &
                       'contact definitions hold in every step (CalculiX also requires them before all steps)')
      end if
   end subroutine before_steps

   !> *SURFACE, NAME=name [, TYPE=ELEMENT|NODE].  TYPE=ELEMENT (default) data lines:
   !> element or element set, S<k>; TYPE=NODE data lines: one node or node set per line.
   subroutine read_surface(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      type(keyword_line_t) :: raw
      character(len=:), allocatable :: name, tname, lab
      logical :: found, ok
      integer :: kind, k, nerr0, side, stat
      integer(ip) :: iside, e, nn, n
      type(source_loc_t) :: kwloc
      type(item_list_t) :: items, elems, sides
      type(item_list_t) :: members   !< nodes, or the element of each side
      call before_steps(p, '*SURFACE')
      kwloc = here(p)
      call get_param(kw, 'NAME', name, found)
      call get_param(kw, 'TYPE', tname, found)
      if (.not. found) then
         ! a TYPE with a bad value was reported and removed by check_keyword: reading
         ! the data lines as element sides would only add noise
         call parse_keyword_line(p%src%text(1:p%src%length), raw)
         if (has_param(raw, 'TYPE')) then
            call skip_data(p)
            ! kept under its name (kind 0, no members) so that pairs naming it are not reported too
            call grow_surfaces(model, p%nsurf)
            p%nsurf = p%nsurf + 1
            model%surfaces(p%nsurf)%name = name
            model%surfaces(p%nsurf)%loc = kwloc
            allocate (model%surfaces(p%nsurf)%elem(0), model%surfaces(p%nsurf)%side(0))
            return
         end if
         tname = 'ELEMENT'
      end if
      kind = surface_element
      if (tname == 'NODE') kind = surface_node
      k = find_surface(model, p%nsurf, name)
      if (k > 0) then
         call err_here(p, 'surface '//name//' already defined at '//loc_str(p, model%surfaces(k)%loc), &
                       'list all sides (or nodes) of a surface under one *SURFACE, or use another name')
         call skip_data(p)
         return
      end if
      nerr0 = p%diag%count
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (kind == surface_node) then
            if (p%f%n > 1) then
               call err_here(p, 'a TYPE=NODE *SURFACE data line holds one node or node set', &
                             'write one entry per line, as CalculiX reads it (Abaqus'' second field, '// &
                             'an area or thickness, is not used by vemcontact)')
               cycle
            end if
            call field_nodes(p, model, 1, items, ok)
            if (.not. ok) cycle
            do k = 1, int(items%n)
               call push_item(members, items%a(k))
            end do
         else
            if (p%f%n > 2) then
               call err_here(p, 'too many fields on a TYPE=ELEMENT *SURFACE data line: expected '// &
                             'element or element set, side label')
               cycle
            end if
            call field_elems(p, model, 1, elems, ok)
            if (.not. ok) cycle
            lab = to_upper(squeeze(field(p, 2)))
            if (len(lab) == 0) then
               call err_here(p, 'missing side label on a *SURFACE data line', side_help)
               cycle
            end if
            stat = -1
            iside = 0
            if (len(lab) >= 2) then
               if (lab(1:1) == 'S') call parse_int(lab(2:), iside, stat)
            end if
            if (stat /= num_ok .or. iside < 1) then
               call err_here(p, 'invalid side label '//lab, side_help)
               cycle
            end if
            side = iside
            ok = .true.
            do k = 1, int(elems%n)
               e = elems%a(k)
               nn = (model%elem_ptr(e + 1) - model%elem_ptr(e))/element_order(model%elem_type(e))
               if (side > nn) then
                  call err_here(p, 'element '//int_str(model%elem_id(e))//' has '//int_str(nn)// &
                                ' sides, so there is no side '//lab, side_help)
                  ok = .false.
                  exit
               end if
            end do
            if (.not. ok) cycle
            do k = 1, int(elems%n)
               call push_item(members, elems%a(k))
               call push_item(sides, iside)
            end do
         end if
      end do
      n = members%n
      if (n == 0 .and. p%diag%count == nerr0) then
         call err_at(p, kwloc, 'surface '//name//' is empty', &
                     'give element sides ("element or set, S<k>") or, with TYPE=NODE, nodes after *SURFACE')
      end if
      ! stored even after errors, so that pairs naming it are not reported again
      call grow_surfaces(model, p%nsurf)
      p%nsurf = p%nsurf + 1
      associate (s => model%surfaces(p%nsurf))
         s%name = name
         s%kind = kind
         s%loc = kwloc
         if (kind == surface_node) then
            if (n > 1) call sort_unique(members%a, n)
            allocate (s%nodes(n))
            if (n > 0) s%nodes = members%a(1:n)
         else
            allocate (s%elem(n), s%side(n))
            if (n > 0) then
               s%elem = members%a(1:n)
               s%side = int(sides%a(1:n))
            end if
         end if
      end associate
   end subroutine read_surface

   subroutine grow_surfaces(model, n)
      type(model_t), intent(inout) :: model
      integer, intent(in) :: n
      type(surface_t), allocatable :: t(:)
      integer :: k
      if (.not. allocated(model%surfaces)) allocate (model%surfaces(4))
      if (n < size(model%surfaces)) return
      allocate (t(2*n))
      do k = 1, n
         call move_alloc(model%surfaces(k)%name, t(k)%name)
         t(k)%kind = model%surfaces(k)%kind
         call move_alloc(model%surfaces(k)%elem, t(k)%elem)
         call move_alloc(model%surfaces(k)%side, t(k)%side)
         call move_alloc(model%surfaces(k)%nodes, t(k)%nodes)
         t(k)%loc = model%surfaces(k)%loc
      end do
      call move_alloc(t, model%surfaces)
   end subroutine grow_surfaces

   !> Index of surface `name` among model%surfaces(1:n), 0 if absent.
   pure function find_surface(model, n, name) result(k)
      type(model_t), intent(in) :: model
      integer, intent(in) :: n
      character(len=*), intent(in) :: name
      integer :: k
      do k = 1, n
         if (model%surfaces(k)%name == name) return
      end do
      k = 0
   end function find_surface

   !> Index of surface interaction `name` among model%interactions(1:n), 0 if absent.
   pure function find_interaction(model, n, name) result(k)
      type(model_t), intent(in) :: model
      integer, intent(in) :: n
      character(len=*), intent(in) :: name
      integer :: k
      do k = 1, n
         if (model%interactions(k)%name == name) return
      end do
      k = 0
   end function find_interaction

   !> *SURFACE INTERACTION, NAME=name (no data lines): starts an interaction; the
   !> *SURFACE BEHAVIOR that follows belongs to it.
   subroutine read_interaction(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      type(interaction_t), allocatable :: t(:)
      character(len=:), allocatable :: name
      logical :: found
      integer :: k
      call before_steps(p, '*SURFACE INTERACTION')
      call get_param(kw, 'NAME', name, found)
      k = find_interaction(model, p%ninter, name)
      if (k > 0) then
         call err_here(p, 'surface interaction '//name//' already defined at '// &
                       loc_str(p, model%interactions(k)%loc))
         p%cur_inter = -1   ! its *SURFACE BEHAVIOR is dropped silently
         return
      end if
      if (.not. allocated(model%interactions)) allocate (model%interactions(4))
      if (p%ninter == size(model%interactions)) then
         allocate (t(2*p%ninter))
         t(1:p%ninter) = model%interactions(1:p%ninter)
         call move_alloc(t, model%interactions)
      end if
      p%ninter = p%ninter + 1
      model%interactions(p%ninter)%name = name
      model%interactions(p%ninter)%loc = here(p)
      p%cur_inter = p%ninter
   end subroutine read_interaction

   !> *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR; data line: K [, sigma_inf, c0].
   !> PRESSURE-OVERCLOSURE=HARD (Abaqus' meaning: no overclosure, the pressure is a
   !> Lagrange multiplier) takes no data line.
   !> vemcontact's law is p = K * overclosure, zero at positive clearance: CalculiX's
   !> regularised law with the tension sigma_inf at large clearances in the limit
   !> sigma_inf -> 0.  sigma_inf and c0 (CalculiX's spring-generation clearance factor)
   !> are recorded; a positive sigma_inf gets a warning that its tension is not modelled.
   subroutine read_behavior(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: po
      logical :: found, ok, ok_k, ok_s, ok_c, first, dup
      real(wp) :: k, sinf, c0
      call before_steps(p, '*SURFACE BEHAVIOR')
      if (p%cur_inter == 0) then
         call err_here(p, '*SURFACE BEHAVIOR must follow a *SURFACE INTERACTION', &
                       'start the interaction with *SURFACE INTERACTION, NAME=...')
      end if
      dup = .false.
      if (p%cur_inter > 0) then
         dup = model%interactions(p%cur_inter)%has_behavior
         if (dup) call err_here(p, 'surface interaction '//model%interactions(p%cur_inter)%name// &
                                ' already has *SURFACE BEHAVIOR')
      end if
      call get_param(kw, 'PRESSURE-OVERCLOSURE', po, found)
      select case (po)
      case ('LINEAR')
         continue
      case ('HARD')
         call read_hard(p, model, dup)
         return
      case ('EXPONENTIAL', 'TABULAR', 'TIED')
         call err_here(p, 'PRESSURE-OVERCLOSURE='//po//' is not supported', &
                       'vemcontact supports PRESSURE-OVERCLOSURE=LINEAR (penalty: p = K * overclosure) '// &
                       'and HARD (no overclosure)')
         call drop_behavior(p, model)
         call skip_data(p)
         return
      case default
         call err_here(p, 'invalid value '//po//' for parameter PRESSURE-OVERCLOSURE of *SURFACE BEHAVIOR', &
                       'allowed values: LINEAR, HARD')
         call drop_behavior(p, model)
         call skip_data(p)
         return
      end select
      call advance(p)
      if (p%src%kind /= line_data) then
         call err_here(p, '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR needs a data line: K, the '// &
                       'contact pressure per unit overclosure')
         call drop_behavior(p, model)
         return
      end if
      call split_fields(p%src%text(1:p%src%length), p%f)
      ok = .true.
      if (p%f%n > 3) then
         call err_here(p, 'too many fields on the *SURFACE BEHAVIOR data line: expected K [, sigma_inf, c0]')
         ok = .false.
      end if
      if (ok) then
         ! each value is checked on its own so that all problems are reported
         call get_real(p, 1, 'penalty slope K', k, ok_k, required=.true.)
         call get_real(p, 2, 'sigma_inf', sinf, ok_s)
         call get_real(p, 3, 'c0', c0, ok_c)
         if (ok_k .and. .not. k > 0.0_wp) then
            call err_here(p, 'penalty slope K = '//field(p, 1)//' must be positive', &
                          'K is the contact pressure per unit overclosure, e.g. 10 to 100 times E over '// &
                          'the element size')
            ok_k = .false.
         end if
         if (ok_s .and. sinf < 0.0_wp) then
            call err_here(p, 'sigma_inf = '//field(p, 2)//' must not be negative', &
                          'sigma_inf is CalculiX''s tension at large clearance (> 0, typically 0.25 % of '// &
                          'the largest stress expected); leave it blank or 0 for none')
            ok_s = .false.
         end if
         if (ok_c .and. c0 < 0.0_wp) then
            call err_here(p, 'c0 = '//field(p, 3)//' must not be negative', &
                          'c0 is CalculiX''s factor of the clearance up to which contact springs are made')
            ok_c = .false.
         end if
         if (ok_k .and. ok_s .and. sinf > 0.0_wp) then
            call warn_here(p, 'sigma_inf = '//field(p, 2)//' (CalculiX''s tension at clearance) is not '// &
                           'modelled: the pressure is K * overclosure, zero at clearance, so pressures '// &
                           'differ from CalculiX''s by at most sigma_inf')
         end if
         ok = ok_k .and. ok_s .and. ok_c
      end if
      if (p%cur_inter > 0 .and. .not. dup) then
         ! after an error the interaction counts as having a behavior: it is not reported again as missing
         if (ok) then
            model%interactions(p%cur_inter)%penalty = k
            model%interactions(p%cur_inter)%sigma_inf = sinf
            model%interactions(p%cur_inter)%c0 = c0
         end if
         model%interactions(p%cur_inter)%has_behavior = .true.
      end if
      first = .true.
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         if (first) call err_here(p, '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR takes one data line')
         first = .false.
      end do
   end subroutine read_behavior

   !> PRESSURE-OVERCLOSURE=HARD: no data line.
   subroutine read_hard(p, model, dup)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      logical, intent(in) :: dup
      logical :: first
      if (p%cur_inter > 0 .and. .not. dup) then
         model%interactions(p%cur_inter)%hard = .true.
         model%interactions(p%cur_inter)%has_behavior = .true.
      end if
      first = .true.
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         if (first) call err_here(p, '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD takes no data line', &
                                  'HARD contact has no penalty slope: remove the line, or use '// &
                                  'PRESSURE-OVERCLOSURE=LINEAR with K on the data line')
         first = .false.
      end do
   end subroutine read_hard

   !> *FRICTION [, ROUGH] [, COHESION=c] under a *SURFACE INTERACTION; data line
   !> mu [, stick slope] (CalculiX: Coulomb friction |t_T| <= mu p; the stick slope is
   !> the tangential traction per unit elastic slip, and without it stick is exact).
   !> ROUGH (Abaqus): no slip, no data line.  COHESION=c (vemcontact's extension):
   !> Mohr-Coulomb, |t_T| <= c + mu p while the contact is closed.  Inside a step it
   !> follows a *CHANGE FRICTION (read_step_friction).
   subroutine read_friction(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      type(friction_change_t) :: law
      logical :: ok, dup
      if (p%in_step) then
         call read_step_friction(p, kw)
         return
      end if
      call before_steps(p, '*FRICTION')
      if (p%cur_inter == 0) then
         call err_here(p, '*FRICTION must follow a *SURFACE INTERACTION', &
                       'put *FRICTION under the *SURFACE INTERACTION, NAME=... it belongs to '// &
                       '(beside its *SURFACE BEHAVIOR)')
      end if
      dup = .false.
      if (p%cur_inter > 0) then
         dup = model%interactions(p%cur_inter)%has_friction
         if (dup) call err_here(p, 'surface interaction '//model%interactions(p%cur_inter)%name// &
                                ' already has *FRICTION')
      end if
      call friction_law(p, kw, law, ok)
      if (p%cur_inter > 0 .and. .not. dup) then
         model%interactions(p%cur_inter)%has_friction = .true.
         if (ok) then
            model%interactions(p%cur_inter)%mu = law%mu
            model%interactions(p%cur_inter)%stick_slope = law%stick_slope
            model%interactions(p%cur_inter)%cohesion = law%cohesion
            model%interactions(p%cur_inter)%rough = law%rough
         end if
      end if
   end subroutine read_friction

   !> The law of a *FRICTION line and its data line (ROUGH, COHESION=, mu [, stick
   !> slope]) into law%rough, mu, stick_slope, cohesion; ok = .false. after an error.
   subroutine friction_law(p, kw, law, ok)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t), intent(in) :: kw
      type(friction_change_t), intent(inout) :: law
      logical, intent(out) :: ok
      character(len=:), allocatable :: cstr
      logical :: rough, has_c, ok_mu, ok_s, first
      real(wp) :: mu, slope, c
      integer :: stat
      rough = has_param(kw, 'ROUGH')
      has_c = has_param(kw, 'COHESION')
      ok = .true.
      c = 0.0_wp
      if (has_c) then
         call get_param(kw, 'COHESION', cstr, has_c)
         call parse_real(cstr, c, stat)
         if (stat /= num_ok) then
            call err_here(p, 'COHESION='//cstr//' is not a number')
            ok = .false.
         else if (c < 0.0_wp) then
            call err_here(p, 'cohesion COHESION='//cstr//' must not be negative', &
                          'COHESION is the shear strength of the closed joint at zero pressure, '// &
                          'c in |t_T| <= c + mu p')
            ok = .false.
         else if (rough) then
            call err_here(p, 'COHESION is meaningless with ROUGH', &
                          'ROUGH contact never slips; for a Mohr-Coulomb joint give mu on the data '// &
                          'line and COHESION=c without ROUGH')
            ok = .false.
         end if
      end if
      mu = 0.0_wp
      slope = 0.0_wp
      if (rough) then
         first = .true.
         do
            call advance(p)
            if (p%src%kind /= line_data) exit
            if (first) call err_here(p, '*FRICTION, ROUGH takes no data line', &
                                     'ROUGH contact has no friction coefficient: remove the line, or '// &
                                     'remove ROUGH for Coulomb friction')
            first = .false.
         end do
      else
         call advance(p)
         if (p%src%kind /= line_data) then
            call err_here(p, '*FRICTION needs a data line: mu [, stick slope]', &
                          'mu is the friction coefficient; the stick slope (tangential traction per '// &
                          'unit elastic slip) is optional: without it stick is exact')
            ok = .false.
         else
            call split_fields(p%src%text(1:p%src%length), p%f)
            if (p%f%n > 2) then
               call err_here(p, 'too many fields on the *FRICTION data line: expected mu [, stick slope]')
               ok = .false.
            else
               call get_real(p, 1, 'friction coefficient mu', mu, ok_mu, required=.true.)
               call get_real(p, 2, 'stick slope', slope, ok_s)
               if (ok_mu .and. mu < 0.0_wp) then
                  call err_here(p, 'friction coefficient mu = '//field(p, 1)//' must not be negative', &
                                'mu = tan(phi) of the joint; 0 is frictionless')
                  ok_mu = .false.
               end if
               if (ok_s .and. slope < 0.0_wp) then
                  call err_here(p, 'stick slope = '//field(p, 2)//' must not be negative', &
                                'the stick slope is the tangential traction per unit elastic slip '// &
                                '(CalculiX: about 1/100 of the normal penalty slope); leave it out '// &
                                'for exact stick')
                  ok_s = .false.
               end if
               ok = ok .and. ok_mu .and. ok_s
            end if
            first = .true.
            do
               call advance(p)
               if (p%src%kind /= line_data) exit
               if (first) call err_here(p, '*FRICTION takes one data line')
               first = .false.
            end do
         end if
      end if
      law%rough = rough
      law%mu = mu
      law%stick_slope = slope
      law%cohesion = c
   end subroutine friction_law

   !> *FRICTION in a step: the new law of the *CHANGE FRICTION just before it.
   subroutine read_step_friction(p, kw)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t), intent(in) :: kw
      type(friction_change_t) :: law
      logical :: ok
      integer :: k
      if (p%change_inter == 0) then
         call err_here(p, '*FRICTION inside a *STEP must follow *CHANGE FRICTION, INTERACTION=name', &
                       'the model''s *FRICTION goes under its *SURFACE INTERACTION before the first *STEP')
      end if
      if (p%change_inter <= 0) then
         call skip_data(p)
         return
      end if
      call friction_law(p, kw, law, ok)
      law%interaction = p%change_inter
      law%loc = p%change_loc
      p%change_inter = 0
      if (.not. ok) return
      if (.not. allocated(p%cur%friction_changes)) allocate (p%cur%friction_changes(0))
      ! a second change of the same interaction in one step replaces the first
      k = findloc(p%cur%friction_changes%interaction, law%interaction, dim=1)
      if (k > 0) then
         p%cur%friction_changes(k) = law
      else
         p%cur%friction_changes = [p%cur%friction_changes, law]
      end if
   end subroutine read_step_friction

   !> *CHANGE FRICTION, INTERACTION=name (in a step; CalculiX, Abaqus): the *FRICTION
   !> that follows gives the interaction's law from this step on.
   subroutine read_change_friction(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: name
      logical :: found
      integer :: k
      p%change_loc = here(p)
      p%change_inter = -1
      call get_param(kw, 'INTERACTION', name, found)
      do k = 1, p%ninter
         if (model%interactions(k)%name == name) p%change_inter = k
      end do
      if (p%change_inter < 0) call err_here(p, 'undefined surface interaction '//name, &
                                            '*CHANGE FRICTION names a *SURFACE INTERACTION of the model')
   end subroutine read_change_friction

   !> After a *SURFACE BEHAVIOR that was reported as wrong, count the current interaction as
   !> having one, so that a pair using it does not report it again as missing.
   subroutine drop_behavior(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      if (p%cur_inter > 0) model%interactions(p%cur_inter)%has_behavior = .true.
   end subroutine drop_behavior

   !> *CONTACT PAIR, INTERACTION=name, TYPE=NODE TO SURFACE|SURFACE TO SURFACE [, SMALL SLIDING]
   !> [, ROLES=AUTO|KEEP]; data lines: slave surface, master surface (one pair per line).
   !> ROLES (vemcontact): AUTO lets a node-to-surface pair take the softer, finer face as
   !> its slave (vemcontact_contact_roles), KEEP the surfaces as written.
   subroutine read_contact_pair(p, kw)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: inter, ctype, shown, roles
      logical :: found, found_roles
      integer :: nline, formulation
      type(pair_ref_t), allocatable :: t(:)
      type(source_loc_t) :: kwloc
      call before_steps(p, '*CONTACT PAIR')
      kwloc = here(p)
      call get_param(kw, 'INTERACTION', inter, found)
      call get_param(kw, 'TYPE', ctype, found)
      call get_param(kw, 'ROLES', roles, found_roles)
      select case (ctype)
      case ('NODETOSURFACE')
         formulation = pair_node_to_surface
      case ('SURFACETOSURFACE')
         formulation = pair_surface_to_surface
      case default
         shown = ctype
         call err_here(p, 'TYPE='//shown//' is not supported', 'write *CONTACT PAIR, INTERACTION='//inter// &
                       ', TYPE=NODE TO SURFACE (node to segment) or TYPE=SURFACE TO SURFACE (interface nodes '// &
                       'inserted, then node to node)')
         call skip_data(p)
         return
      end select
      if (has_param(kw, 'ADJUST')) then
         call err_here(p, 'ADJUST is not supported: vemcontact does not move slave nodes onto the master '// &
                       'surface', 'remove ADJUST; the gap or overclosure of the mesh is used as it is')
      end if
      ! SMALL SLIDING (CalculiX's meaning): the pairing is fixed in the undeformed configuration
      nline = 0
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         nline = nline + 1
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (p%f%n /= 2 .or. len(field(p, 1)) == 0 .or. len(field(p, 2)) == 0) then
            call err_here(p, 'a *CONTACT PAIR data line needs two surface names: slave, master')
            cycle
         end if
         if (.not. allocated(p%pair_refs)) allocate (p%pair_refs(4))
         if (p%npair == size(p%pair_refs)) then
            allocate (t(2*p%npair))
            t(1:p%npair) = p%pair_refs(1:p%npair)
            call move_alloc(t, p%pair_refs)
         end if
         p%npair = p%npair + 1
         associate (r => p%pair_refs(p%npair))
            r%slave = to_upper(squeeze(field(p, 1)))
            r%master = to_upper(squeeze(field(p, 2)))
            r%interaction = inter
            r%small_sliding = has_param(kw, 'SMALL SLIDING') .or. has_param(kw, 'SMALLSLIDING')
            r%auto_roles = .not. (found_roles .and. roles == 'KEEP')
            r%formulation = formulation
            r%loc = here(p)
         end associate
      end do
      if (nline == 0) then
         call err_at(p, kwloc, '*CONTACT PAIR needs a data line: slave surface, master surface')
      end if
   end subroutine read_contact_pair

   !> *CONTACT CONTROLS [, MAXIT=n] [, TOLERANCE=r] [, STIFFNESS SCALE FACTOR=s] (vemcontact):
   !> active-set iterations per step, the relative residual tolerance and the scale of the
   !> internal stiffness of HARD contact (Abaqus' name).  No data lines.
   subroutine read_controls(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: val
      logical :: found
      integer :: stat
      integer(ip) :: maxit
      real(wp) :: tol
      call before_steps(p, '*CONTACT CONTROLS')
      if (p%controls_loc%file > 0) then
         call err_here(p, 'second *CONTACT CONTROLS (the first is at '//loc_str(p, p%controls_loc)//')', &
                       'give MAXIT, TOLERANCE and STIFFNESS SCALE FACTOR on one *CONTACT CONTROLS line')
         return
      end if
      p%controls_loc = here(p)
      call get_param(kw, 'MAXIT', val, found)
      if (found) then
         ! the registry has checked it is a positive integer; the iteration keeps each
         ! slave node's state of every iteration (arrays of MAXIT + 1 columns), so the
         ! count is bounded before anything is sized by it
         call parse_int(squeeze(val), maxit, stat)
         if (stat == num_ok) then
            if (maxit <= max_contact_iterations) then
               model%controls%max_iterations = maxit
            else
               call err_here(p, 'MAXIT = '//squeeze(val)//' is beyond the limit of '// &
                             int_str(max_contact_iterations)//' contact iterations per step', &
                             'a contact iteration that has not converged in a few hundred iterations '// &
                             'will not: see docs/contact-formulation.md for what to change instead')
            end if
         end if
      end if
      call get_param(kw, 'TOLERANCE', val, found)
      if (found) then
         call parse_real(squeeze(val), tol, stat)
         if (stat == num_ok) then
            if (tol > 0.0_wp .and. tol < 1.0_wp) then
               model%controls%residual_tol = tol
            else
               call err_here(p, 'TOLERANCE = '//val//' must satisfy 0 < TOLERANCE < 1', &
                             'it is the residual norm relative to the norm of the external and reaction '// &
                             'forces, e.g. TOLERANCE=1e-8')
            end if
         end if
      end if
      call get_param(kw, 'STIFFNESSSCALEFACTOR', val, found)
      if (found) then
         call parse_real(squeeze(val), tol, stat)
         if (stat == num_ok) then
            ! measured on the contact patch test: 1e-4 converges in 36 iterations and
            ! 1e-5 not in 50; 1e5 warns of the conditioning and 1e6 stops on it
            if (tol >= 1.0e-3_wp .and. tol <= 1.0e4_wp) then
               model%controls%stiffness_scale = tol
            else
               call err_here(p, 'STIFFNESS SCALE FACTOR = '//val//' must lie between 1e-3 and 1e4', &
                             'it scales the internal stiffness of PRESSURE-OVERCLOSURE=HARD contact, '// &
                             '1e3 E/h by default; the converged pressures do not depend on it, smaller '// &
                             'factors need more iterations, larger ones cost conditioning')
            end if
         end if
      end if
   end subroutine read_controls

   !> Exact-size contact arrays and the pairs resolved: surfaces and interactions by
   !> name, a TYPE=ELEMENT master, an interaction with its *SURFACE BEHAVIOR.
   subroutine finish_contact(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(surface_t), allocatable :: ts(:)
      logical, allocatable :: reported(:)
      integer :: k, islave, imaster, iinter
      if (allocated(model%surfaces)) then
         allocate (ts(p%nsurf))
         do k = 1, p%nsurf
            call move_alloc(model%surfaces(k)%name, ts(k)%name)
            ts(k)%kind = model%surfaces(k)%kind
            call move_alloc(model%surfaces(k)%elem, ts(k)%elem)
            call move_alloc(model%surfaces(k)%side, ts(k)%side)
            call move_alloc(model%surfaces(k)%nodes, ts(k)%nodes)
            ts(k)%loc = model%surfaces(k)%loc
         end do
         call move_alloc(ts, model%surfaces)
      else
         allocate (model%surfaces(0))
      end if
      if (allocated(model%interactions)) then
         model%interactions = model%interactions(1:p%ninter)
      else
         allocate (model%interactions(0))
      end if
      allocate (model%pairs(p%npair), reported(p%ninter))
      reported = .false.
      do k = 1, p%npair
         associate (r => p%pair_refs(k))
            islave = find_surface(model, p%nsurf, r%slave)
            imaster = find_surface(model, p%nsurf, r%master)
            iinter = find_interaction(model, p%ninter, r%interaction)
            if (islave == 0) then
               call err_at(p, r%loc, 'undefined slave surface '//r%slave, surface_suggestion(r%slave))
            end if
            if (imaster == 0) then
               call err_at(p, r%loc, 'undefined master surface '//r%master, surface_suggestion(r%master))
            else if (model%surfaces(imaster)%kind == surface_node) then
               call err_at(p, r%loc, 'master surface '//r%master//' is a TYPE=NODE surface', &
                           'the master must be a TYPE=ELEMENT surface (element sides); only the slave '// &
                           'may be TYPE=NODE')
            else if (imaster == islave) then
               call err_at(p, r%loc, 'slave and master are the same surface '//r%master, &
                           'node-to-segment contact needs two different surfaces')
            end if
            if (iinter == 0) then
               call err_at(p, r%loc, 'undefined surface interaction '//r%interaction, &
                           interaction_suggestion(r%interaction))
            else if (.not. model%interactions(iinter)%has_behavior .and. .not. reported(iinter)) then
               reported(iinter) = .true.
               call err_at(p, model%interactions(iinter)%loc, 'surface interaction '//r%interaction// &
                           ' has no *SURFACE BEHAVIOR (it is used by the contact pair at '// &
                           loc_str(p, r%loc)//')', 'add *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR '// &
                           'and a data line with the slope K, or PRESSURE-OVERCLOSURE=HARD, right after '// &
                           '*SURFACE INTERACTION')
            end if
            model%pairs(k) = contact_pair_t(slave=islave, master=imaster, interaction=iinter, &
                                            formulation=r%formulation, small_sliding=r%small_sliding, &
                                            auto_roles=r%auto_roles, loc=r%loc)
         end associate
      end do
   contains
      function surface_suggestion(name) result(help)
         character(len=*), intent(in) :: name
         character(len=:), allocatable :: help
         integer :: j, d, best
         help = ''
         best = huge(1)
         do j = 1, p%nsurf
            d = edit_distance(name, model%surfaces(j)%name)
            if (d < best .and. d <= max(1, len(name)/3)) then
               best = d
               help = 'did you mean '//model%surfaces(j)%name//'?'
            end if
         end do
         if (len(help) == 0 .and. p%nsurf == 0) help = 'define it with *SURFACE, NAME='//name
      end function surface_suggestion

      function interaction_suggestion(name) result(help)
         character(len=*), intent(in) :: name
         character(len=:), allocatable :: help
         integer :: j, d, best
         help = ''
         best = huge(1)
         do j = 1, p%ninter
            d = edit_distance(name, model%interactions(j)%name)
            if (d < best .and. d <= max(1, len(name)/3)) then
               best = d
               help = 'did you mean '//model%interactions(j)%name//'?'
            end if
         end do
         if (len(help) == 0 .and. p%ninter == 0) help = 'define it with *SURFACE INTERACTION, NAME='//name
      end function interaction_suggestion
   end subroutine finish_contact
end module vemcontact_deck_contact
