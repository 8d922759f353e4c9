!> State of a deck being parsed, and the helpers every keyword handler uses:
!> error reporting at the current line, field conversion, growing the model's
!> arrays, id lookup and set lookup.
!> Nodes and elements are stored in the order they appear, so internal indices
!> never change while parsing; the id maps are rebuilt lazily when a lookup finds
!> them older than the entity count.
module vemcontact_deck_state
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, source_loc_t, named_set_t, dof_value_t, dload_t, &
                               find_set, procedure_static, string_t, output_request_t, uplift_t, &
                               strength_reduction_t, friction_change_t
   use vemcontact_deck_source, only: deck_source_t
   use vemcontact_deck_diagnostics, only: diag_t
   use vemcontact_deck_fields, only: field_list_t, edit_distance, to_upper, squeeze
   use vemcontact_deck_numbers, only: parse_int, parse_real, number_problem, num_ok, num_empty, &
                                      num_syntax
   use vemcontact_deck_idmap, only: id_map_t, sort_unique
   implicit none
   private

   public :: deck_parser_t, item_list_t, step_acc_t, grav_ref_t, pair_ref_t, part_ref_t
   public :: here, err_here, refuse_here, err_at, warn_here, loc_str, field, get_int, get_id, get_real
   public :: push_item, push_dof, push_dload, node_index, elem_index
   public :: get_set, set_suggestion, ref_kind, tidy_items

   !> Result of `ref_kind`: what a node-or-set field holds.
   integer, parameter, public :: ref_id = 1, ref_name = 2, ref_bad = 3

   !> Growable list of internal indices.
   type :: item_list_t
      integer(ip), allocatable :: a(:)
      integer(ip) :: n = 0
   end type item_list_t

   !> Boundary conditions and loads of one step (or of the model part) while parsing.
   type :: step_acc_t
      type(dof_value_t), allocatable :: boundary(:), cload(:)
      type(dload_t), allocatable :: dload(:)
      type(uplift_t), allocatable :: uplift(:)   !< *UPLIFT (vemcontact)
      type(friction_change_t), allocatable :: friction_changes(:)   !< *CHANGE FRICTION
      type(dof_value_t), allocatable :: temperature(:)   !< *TEMPERATURE (or initial T0)
      integer :: nt = 0
      logical :: tnew = .false.
      integer :: nb = 0, nc = 0, nd = 0
      logical :: bnew = .false., cnew = .false., dnew = .false.  !< OP=NEW seen
      integer :: procedure = procedure_static
      !> the *STATIC data line and parameters, *STEP's AMPLITUDE= (model's step_t)
      real(wp) :: dt_initial = 1.0_wp, period = 1.0_wp, dt_min = 0.0_wp, dt_max = 1.0e30_wp
      logical :: direct = .false., ramp = .true.
      !> *STRENGTH REDUCTION's parameters
      type(strength_reduction_t) :: srm
      !> the first load keyword of the step (line 0: none), refused in a strength reduction step
      type(source_loc_t) :: load_loc
      character(len=:), allocatable :: load_kw
      character(len=:), allocatable :: name
      type(output_request_t), allocatable :: outputs(:)
      integer :: nout = 0
      !> an output request of (category, 1 = file / 2 = print) was given in this step
      logical :: out_seen(3, 2) = .false.
   end type step_acc_t

   !> A *CONTACT PAIR data line; the names are resolved once the whole deck is read.
   type :: pair_ref_t
      character(len=:), allocatable :: slave, master, interaction  !< upper case
      logical :: small_sliding = .false.
      logical :: auto_roles = .true.          !< ROLES=AUTO (default) or KEEP
      integer :: formulation = 0              !< model's pair_node_to_surface / pair_surface_to_surface
      type(source_loc_t) :: loc
   end type pair_ref_t

   !> A GRAV load on one element, checked for a density once sections are applied.
   type :: grav_ref_t
      integer(ip) :: elem = 0
      type(source_loc_t) :: loc
   end type grav_ref_t

   !> An Abaqus/CAE *PART, read into the model directly (vemcontact_deck_assembly):
   !> its nodes first_node.., elements first_elem.., ids shifted by the offsets.
   type :: part_ref_t
      character(len=:), allocatable :: name       !< upper case
      character(len=:), allocatable :: instance   !< its *INSTANCE name, '' until instanced
      integer(ip) :: first_node = 1, last_node = 0, first_elem = 1, last_elem = 0
      integer(ip) :: node_offset = 0, elem_offset = 0
      type(source_loc_t) :: loc
   end type part_ref_t

   type :: deck_parser_t
      type(deck_source_t) :: src
      type(diag_t) :: diag
      type(field_list_t) :: f
      integer(ip) :: node_cap = 0, elem_cap = 0, conn_cap = 0, nconn = 0
      type(id_map_t) :: node_map, elem_map
      integer :: nnset = 0, nelset = 0, nmat = 0, nsec = 0, nstep = 0
      integer :: nsurf = 0, ninter = 0, npair = 0
      type(item_list_t), allocatable :: nset_items(:), elset_items(:), sec_items(:)
      type(item_list_t) :: reduced            !< elements of the reduced-integration types (CPE8R/CPS8R)
      integer :: cur_mat = 0                !< material that *ELASTIC and *DENSITY apply to
      integer :: cur_inter = 0              !< interaction that *SURFACE BEHAVIOR applies to, -1 = dropped
      !> in a step, the interaction of the *CHANGE FRICTION that the next *FRICTION
      !> changes (-1: the *CHANGE FRICTION line was wrong), and where it is
      integer :: change_inter = 0
      type(source_loc_t) :: change_loc
      !> AMPLITUDE= of the load keyword being read: index into model%amplitudes, 0 = none
      integer :: amp = 0
      logical :: in_step = .false.
      logical :: procedure_seen = .false.   !< *STATIC or *GEOSTATIC in the current step
      logical :: section_errors = .false.   !< suppresses "no section" noise after a bad *SOLID SECTION
      logical :: element_errors = .false.   !< suppresses "no section" noise after a bad *ELEMENT
      !> Abaqus/CAE structure: the parts read so far, the one being read (0 = none),
      !> in_assembly between *ASSEMBLY and *END ASSEMBLY, in_instance likewise
      type(part_ref_t), allocatable :: parts(:)
      integer :: cur_part = 0
      logical :: in_assembly = .false.
      integer :: cur_instance = 0                !< part of the open *INSTANCE, 0 = none
      !> added to the node and element ids of the data lines read now: a part's own
      !> ids, or those of INSTANCE= on *NSET and *ELSET (0 elsewhere)
      integer(ip) :: node_offset = 0, elem_offset = 0
      !> the deck uses a feature outside vemcontact's scope (refuse_here): reading stops
      !> there, so that its one message is not followed by the errors it would cause
      logical :: refused = .false.
      type(source_loc_t) :: step_loc
      type(step_acc_t) :: init, cur
      type(grav_ref_t), allocatable :: grav(:)
      integer :: ngrav = 0
      type(pair_ref_t), allocatable :: pair_refs(:)
      type(source_loc_t) :: controls_loc      !< the *CONTACT CONTROLS line, file 0 if none yet
      integer :: nkeyword = 0
      !> warnings (valid input that is partly ignored), one line each, for model%warnings
      type(string_t), allocatable :: warnings(:)
   end type deck_parser_t

contains

   !> Location of the current line.
   pure function here(p) result(loc)
      type(deck_parser_t), intent(in) :: p
      type(source_loc_t) :: loc
      loc = source_loc_t(file=p%src%file, line=p%src%line)
   end function here

   !> Report an error at the current line, quoting it.
   subroutine err_here(p, message, help)
      type(deck_parser_t), intent(inout) :: p
      character(len=*), intent(in) :: message
      character(len=*), intent(in), optional :: help
      call p%diag%report(p%src%path(), p%src%line, message, p%src%text(1:p%src%length), help)
   end subroutine err_here

   !> Refuse the deck at the current line: `feature` (e.g. "axisymmetric element
   !> type CAX8") is outside vemcontact's scope.  One message; the parser stops
   !> reading, since the rest of the deck depends on what it cannot model.
   subroutine refuse_here(p, feature, help)
      type(deck_parser_t), intent(inout) :: p
      character(len=*), intent(in) :: feature
      character(len=*), intent(in), optional :: help
      if (present(help)) then
         call err_here(p, feature//' is outside vemcontact''s scope (linear static plane stress and plane '// &
                       'strain); the deck is not read further', help)
      else
         call err_here(p, feature//' is outside vemcontact''s scope (linear static plane stress and plane '// &
                       'strain); the deck is not read further', 'docs/deck-reference.md lists what is out of scope')
      end if
      p%refused = .true.
   end subroutine refuse_here

   !> Record a warning at the current line: "file:line: warning: message".
   subroutine warn_here(p, message)
      type(deck_parser_t), intent(inout) :: p
      character(len=*), intent(in) :: message
      character(len=16) :: buf
      if (.not. allocated(p%warnings)) allocate (p%warnings(0))
      write (buf, '(i0)') p%src%line
      p%warnings = [p%warnings, string_t(p%src%path()//':'//trim(buf)//': warning: '//message)]
   end subroutine warn_here

   !> Report an error at an earlier location, quoting that line.
   subroutine err_at(p, loc, message, help)
      type(deck_parser_t), intent(inout) :: p
      type(source_loc_t), intent(in) :: loc
      character(len=*), intent(in) :: message
      character(len=*), intent(in), optional :: help
      if (p%diag%count >= p%diag%limit) then
         p%diag%count = p%diag%count + 1  ! not shown: skip the line lookup
         return
      end if
      call p%diag%report(p%src%path(loc%file), loc%line, message, p%src%line_text(loc%file, loc%line), help)
   end subroutine err_at

   !> "file:line" of a location.
   function loc_str(p, loc) result(s)
      type(deck_parser_t), intent(in) :: p
      type(source_loc_t), intent(in) :: loc
      character(len=:), allocatable :: s
      character(len=12) :: buf
      write (buf, '(i0)') loc%line
      s = p%src%path(loc%file)//':'//trim(buf)
   end function loc_str

   !> Text of field k of the current data line ('' if absent).
   function field(p, k) result(s)
      type(deck_parser_t), intent(in) :: p
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      s = ''
      if (k <= p%f%n) s = p%src%text(p%f%first(k):p%f%last(k))
   end function field

   !> Integer in field k; on failure reports "<what> must be an integer ..." and ok = .false.
   subroutine get_int(p, k, what, val, ok)
      type(deck_parser_t), intent(inout) :: p
      integer, intent(in) :: k
      character(len=*), intent(in) :: what
      integer(ip), intent(out) :: val
      logical, intent(out) :: ok
      integer :: stat
      if (k <= p%f%n) then
         call parse_int(p%src%text(p%f%first(k):p%f%last(k)), val, stat)
      else
         val = 0
         stat = num_empty
      end if
      ok = stat == num_ok
      if (.not. ok) call err_here(p, number_problem(stat, field(p, k), what))
   end subroutine get_int

   !> Positive integer id in field k.
   subroutine get_id(p, k, what, val, ok)
      type(deck_parser_t), intent(inout) :: p
      integer, intent(in) :: k
      character(len=*), intent(in) :: what
      integer(ip), intent(out) :: val
      logical, intent(out) :: ok
      call get_int(p, k, what, val, ok)
      if (ok .and. val <= 0) then
         call err_here(p, what//' '//field(p, k)//' must be a positive integer')
         ok = .false.
      end if
   end subroutine get_id

   !> Real in field k.  A blank or missing field is 0 as in CalculiX, unless `required`.
   subroutine get_real(p, k, what, val, ok, required)
      type(deck_parser_t), intent(inout) :: p
      integer, intent(in) :: k
      character(len=*), intent(in) :: what
      real(wp), intent(out) :: val
      logical, intent(out) :: ok
      logical, intent(in), optional :: required
      integer :: stat
      logical :: req
      req = .false.
      if (present(required)) req = required
      if (k <= p%f%n) then
         call parse_real(p%src%text(p%f%first(k):p%f%last(k)), val, stat)
      else
         val = 0.0_wp
         stat = num_empty
      end if
      if (stat == num_empty .and. .not. req) stat = num_ok
      ok = stat == num_ok
      if (.not. ok) call err_here(p, number_problem(stat, field(p, k), what))
   end subroutine get_real

   !> Classify field k as a positive id (returned in `id`) or a set name.
   subroutine ref_kind(p, k, kind, id, what)
      type(deck_parser_t), intent(inout) :: p
      integer, intent(in) :: k
      integer, intent(out) :: kind
      integer(ip), intent(out) :: id
      character(len=*), intent(in) :: what
      integer :: stat
      call parse_int(p%src%text(p%f%first(k):p%f%last(k)), id, stat)
      if (stat == num_ok) then
         kind = ref_id
         if (id <= 0) then
            call err_here(p, what//' id '//field(p, k)//' must be a positive integer')
            kind = ref_bad
         end if
      else if (stat == num_syntax) then
         kind = ref_name
      else if (stat == num_empty) then
         call err_here(p, 'missing '//what//' id or set name')
         kind = ref_bad
      else
         call err_here(p, number_problem(stat, field(p, k), what//' id'))
         kind = ref_bad
      end if
   end subroutine ref_kind

   subroutine push_item(list, v)
      type(item_list_t), intent(inout) :: list
      integer(ip), intent(in) :: v
      integer(ip), allocatable :: t(:)
      if (.not. allocated(list%a)) allocate (list%a(16))
      if (list%n == size(list%a)) then
         allocate (t(2*size(list%a)))
         t(1:list%n) = list%a(1:list%n)
         call move_alloc(t, list%a)
      end if
      list%n = list%n + 1
      list%a(list%n) = v
   end subroutine push_item

   !> Sort a set's items and drop repeats, so that a load on a set reaches each member once.
   subroutine tidy_items(list)
      type(item_list_t), intent(inout) :: list
      if (list%n > 1) call sort_unique(list%a, list%n)
   end subroutine tidy_items

   subroutine push_dof(list, n, v)
      type(dof_value_t), allocatable, intent(inout) :: list(:)
      integer, intent(inout) :: n
      type(dof_value_t), intent(in) :: v
      type(dof_value_t), allocatable :: t(:)
      if (.not. allocated(list)) allocate (list(16))
      if (n == size(list)) then
         allocate (t(2*size(list)))
         t(1:n) = list(1:n)
         call move_alloc(t, list)
      end if
      n = n + 1
      list(n) = v
   end subroutine push_dof

   subroutine push_dload(list, n, v)
      type(dload_t), allocatable, intent(inout) :: list(:)
      integer, intent(inout) :: n
      type(dload_t), intent(in) :: v
      type(dload_t), allocatable :: t(:)
      if (.not. allocated(list)) allocate (list(16))
      if (n == size(list)) then
         allocate (t(2*size(list)))
         t(1:n) = list(1:n)
         call move_alloc(t, list)
      end if
      n = n + 1
      list(n) = v
   end subroutine push_dload

   !> Internal index of node id `id` among the nodes read so far, 0 if undefined.
   function node_index(p, model, id) result(i)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: id
      integer(ip) :: i
      if (p%node_map%n /= model%nnode) call p%node_map%build(model%node_id(1:model%nnode))
      i = p%node_map%lookup(id + p%node_offset)
   end function node_index

   !> Internal index of element id `id` among the elements read so far, 0 if undefined.
   function elem_index(p, model, id) result(i)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: id
      integer(ip) :: i
      if (p%elem_map%n /= model%nelem) call p%elem_map%build(model%elem_id(1:model%nelem))
      i = p%elem_map%lookup(id + p%elem_offset)
   end function elem_index

   !> Index of set `name` in `sets(1:nsets)`, created (with `items`) if `create` and absent.
   subroutine get_set(sets, items, nsets, name, loc, create, k)
      type(named_set_t), allocatable, intent(inout) :: sets(:)
      type(item_list_t), allocatable, intent(inout) :: items(:)
      integer, intent(inout) :: nsets
      character(len=*), intent(in) :: name
      type(source_loc_t), intent(in) :: loc
      logical, intent(in) :: create
      integer, intent(out) :: k
      type(named_set_t), allocatable :: ts(:)
      type(item_list_t), allocatable :: ti(:)
      integer :: j
      if (.not. allocated(sets)) allocate (sets(8), items(8))
      k = find_set(sets(1:nsets), name)
      if (k > 0 .or. .not. create) return
      if (nsets == size(sets)) then
         allocate (ts(2*nsets), ti(2*nsets))
         do j = 1, nsets
            call move_alloc(sets(j)%name, ts(j)%name)
            ts(j)%loc = sets(j)%loc
            call move_alloc(items(j)%a, ti(j)%a)
            ti(j)%n = items(j)%n
         end do
         call move_alloc(ts, sets)
         call move_alloc(ti, items)
      end if
      nsets = nsets + 1
      k = nsets
      sets(k)%name = name
      sets(k)%loc = loc
   end subroutine get_set

   !> "did you mean X?" among the names of `sets(1:n)`, or ''.
   function set_suggestion(sets, n, name) result(help)
      type(named_set_t), allocatable, intent(in) :: sets(:)
      integer, intent(in) :: n
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: help
      integer :: k, d, best, kbest
      help = ''
      if (.not. allocated(sets)) return
      best = huge(1)
      kbest = 0
      do k = 1, n
         d = edit_distance(name, sets(k)%name)
         if (d < best) then
            best = d
            kbest = k
         end if
      end do
      if (kbest > 0 .and. best <= max(1, len(name)/3)) help = 'did you mean '//sets(kbest)%name//'?'
   end function set_suggestion
end module vemcontact_deck_state
