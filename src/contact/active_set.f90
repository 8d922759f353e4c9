!> The contact state of all pairs of a model: slave nodes with their springs,
!> master segments with their search grids, the current pairing (segment, xi,
!> normal, gap) and the active set.  The driver's iteration asks it for the
!> candidate node pairs of the matrix pattern, the contact stiffness of the
!> active springs, their right-hand side, the contact forces of a displacement
!> field, the springs that hold bodies, and the table written as results.
!>
!> Kinematics (small strain, docs/contact-formulation.md): the pairing (segment,
!> xi) is found in the current configuration x + u, so that it follows the sliding:
!> with finite sliding, the point of the master on the line through the slave node
!> along the segment's reference normal (ray_pair), so that the gap is continuous
!> from one segment to the next; the normal n is the master segment's normal in the
!> reference configuration, as small strain has no finite rotations.  With the pairing frozen the gap is linear
!> in u, g = g0 + n.A(xi) u with g0 = n.(X_s - X_xi) from the reference
!> coordinates, so an iteration with a fixed active set and pairing is one linear
!> solve, and the iteration on the pairing is a fixed point that only the sliding
!> moves (docs/contact-robustness.md).  A slave node is active when g <= 0 (H(-g)
!> of the paper, so surfaces that touch initially, as the Hertz disc, start closed).
module vemcontact_contact_active_set
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, fatal_error, append_message, err_input
   use vemcontact_model, only: model_t, contact_pair_t, location_string, pair_surface_to_surface, plane_stress, &
                               element_side
   use vemcontact_contact_surfaces, only: master_segments, slave_nodes, slave_edges
   use vemcontact_contact_insertion, only: insert_interface_nodes
   use vemcontact_contact_recovery, only: side_pressure
   use vemcontact_contact_search, only: segment_grid_t, build_segment_grid, closest_segments, &
                                        contact_graph_pairs, median
   use vemcontact_contact_geometry, only: relative_map, contact_stiffness, project_point_segment, seg_ok, &
                                          length2, contact_slip, segment_normal, segment_is_degenerate, &
                                          projection_gradient, sliding_tangent, common_normal, ray_projection, &
                                          ray_gradient
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: add_element_matrix
   use vemcontact_contact_spring, only: spring_t
   use vemcontact_contact_table, only: contact_table_t
   use vemcontact_contact_tangential, only: friction_state_t, make_law, friction_params_t
   use vemcontact_contact_friction, only: tangent_stick, tangent_slip, tangential_response_t
   use vemcontact_contact_master_arc, only: master_arcs
   implicit none
   private

   public :: contact_state_t

   !> A node keeps its segment while its projection stays within this fraction of
   !> the segment's length beyond the segment's ends.  Without it a node above a
   !> master vertex can flip between the two segments from one iteration to the
   !> next when the master bends there (each solve makes the other one closer).
   real(wp), parameter, public :: pairing_hysteresis = 0.05_wp

   !> Finite sliding: the most segments the point along the reference normal
   !> (ray_pair) is followed from the closest one; it is next to it on a polyline
   !> whose reference normals turn by less than a right angle per segment.
   integer, parameter :: ray_walk_limit = 4

   !> A reference gap g0 within this many units of round-off of the coordinates
   !> involved (eps times their largest magnitude) is taken as exactly zero.  Surfaces
   !> that touch in the mesh (the two faces of a joint) have g0 = 0 up to the rounding
   !> of the coordinates, and its sign decided whether a node started open or closed:
   !> the dam deck with its lengths scaled by 1e9 started with one joint node open
   !> and converged, along another path, to results 2.5e-6 away from the unscaled
   !> ones (docs/stability-contact.md).  A gap of a few ulps of the coordinates is
   !> not representable geometry; overclosures from displacements are not affected.
   real(wp), parameter, public :: gap0_roundoff = 16.0_wp

   !> Augmentation stiffness of HARD contact, K h / E with h the median master
   !> segment and E t the smallest modulus times thickness of the pair: the
   !> Uzawa update lowers the overclosure by about a factor 1 + K h / E per solve
   !> (only triangular solves while the active set holds), and the system stays far
   !> from the conditioning limits (docs/contact-formulation.md).  Scaled by
   !> STIFFNESS SCALE FACTOR on *CONTACT CONTROLS; the converged answer does not
   !> depend on it.
   real(wp), parameter, public :: hard_stiffness = 1.0e3_wp
   !> HARD contact searches its active set with springs this much softer than the
   !> default augmentation stiffness, K h/E = 10 (never stiffer than the augmentation
   !> itself, whatever the STIFFNESS SCALE FACTOR; the penalty of the paper's Hertz
   !> decks, where the active set grows from a point in 4-5 iterations; at 1e3 the line
   !> search lets it grow one or two nodes per iteration, 11-15 iterations).  The first
   !> Uzawa update then starts the multipliers from the soft penalty's forces, and the
   !> springs stiffen to hard_stiffness for the updates that remove the overclosure.
   real(wp), parameter, public :: hard_search_ratio = 1.0e-2_wp
   !> How far (a fraction of its segment) a closed node of a stepwise pair may end a
   !> load state beyond its segment's end before it is paired anew (release_stepwise):
   !> round-off of a node at a vertex, not a slide
   !> SURFACE TO SURFACE pressures are projected onto the own sides of the master
   !> instead of the slave when the master's vertices turn by more than this factor
   !> times the slave's (plus curved_face_floor radians, so that round-off on two
   !> straight faces changes nothing): the polygon of a curve is the face whose
   !> corners the projection must smooth (recover_side_pressures)
   real(wp), parameter :: curved_face_ratio = 2.0_wp
   !> see contact_state_t%support_shared
   real(wp), parameter :: support_share_floor = 1.0e-3_wp
   real(wp), parameter :: curved_face_floor = 1.0e-8_wp
   real(wp), parameter :: stepwise_slack = 1.0e-6_wp

   !> One contact pair's geometry.
   type :: pair_data_t
      integer(ip), allocatable :: seg(:, :)   !< (2, nseg) master segments, element orientation
      !> the pair's own nodes: the search works on their coordinates only, so that it
      !> costs O(slave nodes + master segments) whatever the size of the model
      integer(ip), allocatable :: lnode(:)    !< model node of each local node (the slaves first)
      integer(ip), allocatable :: lseg(:, :)  !< seg in local numbering
      integer(ip), allocatable :: lslave(:)   !< the slave nodes in local numbering
      integer :: first = 0                    !< its slave nodes are entries first+1 .. first+nslave
      integer :: nslave = 0
      real(wp) :: radius = 0.0_wp             !< search radius: twice the longest master segment
      real(wp) :: slope = 0.0_wp              !< penalty slope K of the interaction
      real(wp) :: h = 0.0_wp                  !< median master segment length
      !> smallest E * thickness of the elements of the slave nodes and master segments
      real(wp) :: stiffness = 0.0_wp
      logical :: small_sliding = .false.      !< pairing fixed at the undeformed state
      logical :: paired = .false.             !< the small-sliding pairing has been made
      !> a frictional NODE TO SURFACE pair with finite sliding: paired anew at the start
      !> of every load state (increment) at its displacements, and that pairing kept
      !> within it (set_pair_law, start_state)
      logical :: stepwise = .false.
      !> SURFACE TO SURFACE: node to node with the partners of the interface node
      !> insertion; per slave entry a segment that ends at the partner (0: no partner),
      !> xi = 0 or 1 exactly, and the partner's vertex normal
      logical :: node_to_node = .false.
      !> PRESSURE-OVERCLOSURE=HARD: slope is the internal augmentation stiffness, and
      !> the pressure is the converged multiplier (no overclosure)
      logical :: hard = .false.
      !> HARD: k of the active-set search over the augmentation stiffness,
      !> hard_search_ratio / STIFFNESS SCALE FACTOR, at most 1
      real(wp) :: search_ratio = 1.0_wp
      integer(ip), allocatable :: nn_seg(:)
      real(wp), allocatable :: nn_xi(:), nn_normal(:, :)
      !> finite sliding: the reference arc length along the master where each
      !> segment starts, and the length of its closed loop (0 on an open chain)
      !> (master_arcs): the slip of a slave node is measured along it
      real(wp), allocatable :: arc(:), period(:)
   end type pair_data_t

   type :: contact_state_t
      type(pair_data_t), allocatable :: pairs(:)
      integer :: n = 0                         !< slave entries over all pairs
      integer(ip), allocatable :: node(:)      !< slave node of each entry
      integer, allocatable :: pair(:)          !< its pair
      real(wp), allocatable :: length(:)       !< undeformed tributary length
      real(wp), allocatable :: thick(:)
      real(wp), allocatable :: k(:)            !< spring stiffness K * length * thick
      !> HARD entries: the augmentation stiffness, which k reaches at the first Uzawa
      !> update of a step (k starts at hard_search_ratio times it); LINEAR: k
      real(wp), allocatable :: k_full(:)
      !> normal force of the augmented Lagrangian (HARD pairs; 0 for LINEAR): an entry
      !> pushes with N = max(0, lambda - k g), so that lambda is the contact force once
      !> the gap has closed to zero
      real(wp), allocatable :: lambda(:)
      !> normal force of each entry as the solution balances it (set_balanced): the
      !> normal component of K u - f_ext at the slave node, which the elastic body
      !> transmits; what CPRESS reports
      real(wp), allocatable :: balanced(:)
      !> whether an entry's balanced force is its spring's (set_balanced: a fixed dof of
      !> the slave node along the normal, where the support takes part of the force);
      !> such a force stays at its node when CPRESS is recovered (recover_side_pressures)
      logical, allocatable :: held(:)
      !> held entries whose fixed dofs take a visible part of the normal force (a normal
      !> component above support_share_floor along a fixed dof): their force stays at
      !> their node when CPRESS is recovered.  A node on a symmetry line whose pair
      !> normal is tilted off it by the faces' curvature (1e-5 on the Hertz decks) is
      !> held, its multiplier being its force, but shares nothing with the support.
      logical, allocatable :: support_shared(:)
      integer(ip), allocatable :: iseg(:)      !< chosen segment (index into its pair's seg), 0 if none
      real(wp), allocatable :: xi(:), gap(:), gap0(:), normal(:, :)
      !> finite sliding: c = n.t and w = dxi/du of the pairing (sliding_tangent), for
      !> the part of the tangent that the motion of the projection adds (w = 0 where
      !> the pairing is fixed)
      real(wp), allocatable :: slide_c(:), slide_w(:, :)
      !> finite sliding, the slip s = s0 + t.A(xi) u along the master (entry_slip):
      !> s0 = S_a + t.(X_s - X_a), S_a the reference arc length at the segment's start
      !> (0 where the pairing is fixed)
      real(wp), allocatable :: slide_s0(:)
      !> stepwise pairs: the arc length s0 of the load state's pairing, taken off the
      !> slip and the anchor while the pairing is kept (their difference then keeps its
      !> digits: arc lengths of metres, elastic slips of micrometres)
      real(wp), allocatable :: slide_base(:)
      logical, allocatable :: active(:)
      !> the entry had a master segment at the start of the step and has none at its
      !> end: it slid past the end of an open master surface (set by the driver)
      logical, allocatable :: slid_off(:)
      !> CFLUIDP: the uplift on each entry (vemcontact_contact_uplift), unallocated
      !> when no *UPLIFT is in force
      real(wp), allocatable :: cfluidp(:)
      !> per pair: the length along the joint that pressure penetration filled from the
      !> heel (-1: no penetration on the pair); unallocated when no *UPLIFT is in force
      real(wp), allocatable :: water_entered(:)
      integer :: nexcluded = 0                 !< slave nodes dropped because they belong to the master
      integer(ip), allocatable :: inserted(:)  !< nodes inserted for each pair (SURFACE TO SURFACE)
      !> the number of nodes before the insertion: pair p's nodes follow those of the pairs before it
      integer(ip) :: node_base = 0
      !> the tangential law of each pair and the tangential state of each entry
      !> (vemcontact_contact_tangential): forces along the unit tangent t = (-n_y, n_x)
      type(friction_state_t) :: fric
   contains
      procedure :: init
      procedure :: graph_pairs
      procedure :: project
      procedure :: update_active
      procedure :: add_stiffness
      procedure :: add_rhs
      procedure :: forces
      procedure :: frozen_gaps
      procedure :: has_hard
      procedure :: augment
      procedure :: gap_noise
      procedure :: multiplier_entries
      procedure :: multiplier_load
      procedure :: gap_change
      procedure :: has_finite_sliding
      procedure :: penalty_ratio
      procedure :: start_state
      procedure :: normal_force
      procedure :: set_balanced
      procedure :: linear_forces
      procedure :: tangent_times
      procedure :: has_sliding
      procedure :: springs
      procedure :: table
      procedure :: max_penetration
      procedure :: max_pressure
      procedure :: update_friction
      procedure :: zero_normal_strength
      procedure :: add_tension
      procedure :: augment_friction
      procedure :: commit_friction
      procedure :: change_friction
      procedure :: release_stepwise
      procedure :: has_exact_friction
      procedure :: tangential_line_terms
      procedure :: count_state
      procedure :: has_coupling
   end type contact_state_t

contains

   !> Prepare the model's contact pairs: insert the interface nodes of the SURFACE TO
   !> SURFACE pairs into the model (vemcontact_contact_insertion: the model gains nodes
   !> and its polygons vertices, so this comes before anything is assembled), then
   !> gather every pair's slave nodes and master segments; nothing is active yet.
   subroutine init(self, model, error)
      class(contact_state_t), intent(out) :: self
      type(model_t), intent(inout) :: model
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      integer(ip), allocatable :: seg(:, :), seg_elem(:), node(:)
      integer, allocatable :: seg_side(:)
      real(wp), allocatable :: length(:), thick(:)
      integer(ip) :: nex
      integer :: p, nseg, i
      integer(ip), allocatable :: all_node(:)
      integer, allocatable :: all_pair(:)
      real(wp), allocatable :: all_len(:), all_thick(:)
      if (.not. allocated(model%pairs)) then
         allocate (self%pairs(0), self%inserted(0))
         call allocate_entries(self, 0)
         return
      end if
      self%node_base = model%nnode
      call insert_interface_nodes(model, self%inserted, error)
      if (allocated(error)) return
      allocate (self%pairs(size(model%pairs)))
      allocate (all_node(0), all_pair(0), all_len(0), all_thick(0))
      do p = 1, size(model%pairs)
         call master_segments(model, model%pairs(p), seg, seg_elem, seg_side, err)
         if (allocated(err)) then
            call append_message(error, location_string(model, model%pairs(p)%loc)//': '//err%message, err%code)
            cycle
         end if
         call slave_nodes(model, model%pairs(p), node, length, thick, nex, err)
         if (allocated(err)) then
            call append_message(error, location_string(model, model%pairs(p)%loc)//': '//err%message, err%code)
            cycle
         end if
         nseg = size(seg, 2)
         self%pairs(p)%seg = seg
         self%pairs(p)%radius = 0.0_wp
         do i = 1, nseg
            self%pairs(p)%radius = max(self%pairs(p)%radius, &
                                       2.0_wp*length2(model%x(:, seg(2, i)) - model%x(:, seg(1, i))))
         end do
         self%pairs(p)%slope = model%interactions(model%pairs(p)%interaction)%penalty
         self%pairs(p)%stiffness = pair_stiffness(model, seg_elem, node)
         if (nseg > 0) self%pairs(p)%h = median_length(model, seg)
         if (model%interactions(model%pairs(p)%interaction)%hard .and. size(node) > 0) then
            self%pairs(p)%hard = .true.
            self%pairs(p)%search_ratio = min(1.0_wp, hard_search_ratio/model%controls%stiffness_scale)
            self%pairs(p)%slope = hard_stiffness*model%controls%stiffness_scale*self%pairs(p)%stiffness/ &
                                  (median_length(model, seg)*maxval(thick, mask=thick > 0.0_wp))
         end if
         self%pairs(p)%small_sliding = model%pairs(p)%small_sliding
         call master_arcs(model%x, seg, self%pairs(p)%arc, self%pairs(p)%period)
         if (model%pairs(p)%formulation == pair_surface_to_surface) then
            call node_partners(model, model%pairs(p), node, seg, seg_elem, self%pairs(p), err)
            if (allocated(err)) then
               call append_message(error, location_string(model, model%pairs(p)%loc)//': '//err%message, err%code)
               cycle
            end if
         end if
         self%pairs(p)%first = size(all_node)
         self%pairs(p)%nslave = size(node)
         self%nexcluded = self%nexcluded + nex
         call local_numbering(model%nnode, node, seg, self%pairs(p))
         all_node = [all_node, node]
         all_pair = [all_pair, spread(p, 1, size(node))]
         all_len = [all_len, length]
         all_thick = [all_thick, thick]
      end do
      if (allocated(error)) return
      call allocate_entries(self, size(all_node))
      self%node = all_node
      self%pair = all_pair
      self%length = all_len
      self%thick = all_thick
      do i = 1, self%n
         self%k(i) = self%pairs(self%pair(i))%slope*self%length(i)*self%thick(i)
         self%k_full(i) = self%k(i)
      end do
      call init_friction(self, model, error)
      if (allocated(error)) return
      if (self%n == 0 .and. size(model%pairs) > 0) then
         call fatal_error(error, location_string(model, model%pairs(1)%loc)// &
                          ': error: the contact pairs have no slave nodes', err_input)
      end if
   end subroutine init

   !> The tangential law of every pair and the tangential spring of every entry: the
   !> stick slope times the tributary area, or for exact stick the augmentation
   !> stiffness of HARD (hard_stiffness E/h, scaled by STIFFNESS SCALE FACTOR).
   !> A frictional NODE TO SURFACE pair with finite sliding is paired stepwise: anew
   !> at the start of each load state, at the displacements it starts from, and kept
   !> within it.  Re-paired at every iteration (with the slip along the master's arc
   !> length and the sliding tangent of the tangential force), the stick/slip states
   !> and the pairing did not settle together: the F1 pad in increments stopped at
   !> MAXIT (docs/contact-formulation.md, "Friction with finite sliding").
   subroutine init_friction(self, model, error)
      type(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      integer :: p
      allocate (self%fric%laws(size(self%pairs)), self%fric%params(size(self%pairs)))
      call self%fric%allocate_entries(self%n)
      do p = 1, size(self%pairs)
         associate (it => model%interactions(model%pairs(p)%interaction))
            call set_pair_law(self, model, p, friction_params_t(it%has_friction, it%rough, it%mu, &
                                                                it%stick_slope, it%cohesion))
         end associate
      end do
   end subroutine init_friction

   !> Pair p's tangential law from `params`, its entries' tangential springs (the
   !> stick slope times the tributary area, or for exact stick the augmentation
   !> stiffness of HARD, hard_stiffness E/h scaled by STIFFNESS SCALE FACTOR), and
   !> whether some pair is frictional (fric%on) or sticks exactly (fric%exact).
   subroutine set_pair_law(self, model, p, params)
      type(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      integer, intent(in) :: p
      type(friction_params_t), intent(in) :: params
      real(wp) :: slope
      integer :: i, q
      self%fric%params(p) = params
      call make_law(params%has_friction, params%rough, params%mu, params%slope, params%cohesion, self%fric%laws(p))
      self%pairs(p)%stepwise = self%fric%laws(p)%law%frictional() .and. .not. self%pairs(p)%small_sliding .and. &
                               .not. self%pairs(p)%node_to_node
      slope = self%fric%laws(p)%law%stick_slope()
      associate (first => self%pairs(p)%first, ns => self%pairs(p)%nslave)
         if (self%fric%laws(p)%law%exact() .and. ns > 0) then
            slope = hard_stiffness*model%controls%stiffness_scale*self%pairs(p)%stiffness/ &
                    (median_length(model, self%pairs(p)%seg)* &
                     maxval(self%thick(first + 1:first + ns), mask=self%thick(first + 1:first + ns) > 0.0_wp))
         end if
         do i = first + 1, first + ns
            self%fric%kt(i) = 0.0_wp
            if (self%fric%laws(p)%law%frictional()) self%fric%kt(i) = slope*self%length(i)*self%thick(i)
         end do
      end associate
      self%fric%on = .false.
      self%fric%exact = .false.
      do q = 1, size(self%fric%laws)
         if (.not. allocated(self%fric%laws(q)%law)) cycle
         if (self%fric%laws(q)%law%frictional()) then
            self%fric%on = .true.
            self%fric%exact = self%fric%exact .or. self%fric%laws(q)%law%exact()
         end if
      end do
   end subroutine set_pair_law

   !> A step's *CHANGE FRICTION: the pairs of interaction `inter` take the law of
   !> `params` from the state at u (the last converged one).  Every entry's history
   !> is committed again with the laws now in force (friction_state_t%commit): its
   !> tangential force carries over (a sticking entry holds it, and the first update
   !> maps it onto the new bound), and a pair that had no friction starts anchored
   !> where it is, with no force.
   subroutine change_friction(self, model, u, inter, params, error)
      class(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer, intent(in) :: inter
      type(friction_params_t), intent(in) :: params
      type(error_t), allocatable, intent(out) :: error
      logical :: was_on
      integer :: p, i
      was_on = self%fric%on
      do p = 1, size(self%pairs)
         if (model%pairs(p)%interaction /= inter) cycle
         call set_pair_law(self, model, p, params)
      end do
      if (.not. self%fric%on) return
      do i = 1, self%n
         if (self%iseg(i) > 0) self%fric%slip(i) = entry_slip(self, i, u)
         if (.not. was_on) self%fric%force(i) = 0.0_wp
      end do
      call self%fric%commit(self%pair)
   end subroutine change_friction

   !> Median length of the segments seg(:, k) = (a, b).
   function median_length(model, seg) result(h)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: seg(:, :)
      real(wp) :: h
      real(wp), allocatable :: l(:)
      integer :: k
      allocate (l(size(seg, 2)))
      do k = 1, size(seg, 2)
         l(k) = length2(model%x(:, seg(2, k)) - model%x(:, seg(1, k)))
      end do
      h = median(l)
   end function median_length

   !> The fixed node-to-node pairing of a SURFACE TO SURFACE pair: each slave node's
   !> partner from the interface node insertion, as the end xi = 0 or 1 of a master
   !> segment, with the mean normal of the master surface at the partner: the unit
   !> normals of the segments that meet there weighted by their half lengths, over
   !> the sum of those half lengths (not normalized).  The gap n . d is then the mean
   !> of the face gaps n_f . d over the node's tributary length, and the force N n is
   !> the lumped force of a pressure N / L on those faces: on a straight face the
   !> side's unit normal; at a kink shorter than 1 by cos of half the turn, which keeps
   !> a uniform pressure exact there (docs/contact-formulation.md).  Where the faces
   !> are not one curve (a disc on a block) the direction is that of the interface the
   !> two faces become, from both faces' mean normals and compliances (common_normal):
   !> the slave's mean normal is taken over its sides whose both ends are paired (the
   !> sides that face the master), at a node between two such sides or where both
   !> faces end (a symmetry line: there each face has one side, and the one-sided
   !> normal of the softer face, a disc's chord tilted by half its turn, is not the
   !> interface's); at an end of the paired slave face only (a support, a slave face
   !> turning away past the master's end) one side's normal is not the face's, and
   !> the master's is kept.
   subroutine node_partners(model, pair, node, seg, seg_elem, pd, error)
      type(model_t), intent(in) :: model
      type(contact_pair_t), intent(in) :: pair
      integer(ip), intent(in) :: node(:), seg(:, :), seg_elem(:)
      type(pair_data_t), intent(inout) :: pd
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: partner(:), seg_at(:), sseg(:, :), selem(:)
      integer, allocatable :: sside(:)
      real(wp), allocatable :: vn(:, :), lsum(:), vs(:, :), cm(:), cs(:)
      logical, allocatable :: facing(:)
      integer, allocatable :: nsides(:), mseg_count(:)
      real(wp) :: t(2), l
      integer :: k, i, j
      integer(ip) :: m
      pd%node_to_node = .true.
      pd%small_sliding = .true.
      allocate (partner(model%nnode), source=0_ip)
      if (allocated(pair%partner)) then
         do k = 1, size(pair%partner, 2)
            partner(pair%partner(1, k)) = pair%partner(2, k)
         end do
      end if
      allocate (vn(2, model%nnode), lsum(model%nnode), source=0.0_wp)
      allocate (seg_at(model%nnode), source=0_ip)
      allocate (mseg_count(model%nnode), source=0)
      call face_normals(model, seg, seg_elem, [(.true., k=1, size(seg, 2))], vn, cm)
      do k = 1, size(seg, 2)
         l = length2(model%x(:, seg(2, k)) - model%x(:, seg(1, k)))
         do j = 1, 2
            lsum(seg(j, k)) = lsum(seg(j, k)) + l
            mseg_count(seg(j, k)) = mseg_count(seg(j, k)) + 1
            if (seg_at(seg(j, k)) == 0) seg_at(seg(j, k)) = k
         end do
      end do
      call slave_edges(model, pair, sseg, selem, sside, error)
      if (allocated(error)) return
      facing = partner(sseg(1, :)) > 0 .and. partner(sseg(2, :)) > 0
      call face_normals(model, sseg, selem, facing, vs, cs)
      allocate (nsides(model%nnode), source=0)
      do k = 1, size(sseg, 2)
         if (facing(k)) nsides(sseg(:, k)) = nsides(sseg(:, k)) + 1
      end do
      allocate (pd%nn_seg(size(node)), source=0_ip)
      allocate (pd%nn_xi(size(node)), source=0.0_wp)
      allocate (pd%nn_normal(2, size(node)), source=0.0_wp)
      do i = 1, size(node)
         m = partner(node(i))
         if (m == 0) cycle
         if (seg_at(m) == 0) cycle
         pd%nn_seg(i) = seg_at(m)
         pd%nn_xi(i) = merge(0.0_wp, 1.0_wp, seg(1, seg_at(m)) == m)
         t = vn(:, m)/lsum(m)
         pd%nn_normal(:, i) = t
         if (nsides(node(i)) == 2 .or. (nsides(node(i)) == 1 .and. mseg_count(m) == 1)) &
            pd%nn_normal(:, i) = common_normal(t, vs(:, node(i)), cm(m), cs(node(i)))
      end do
   end subroutine node_partners

   !> At every node of the sides seg(:, k) = (a, b) of elements elem(k) with take(k):
   !> vn, the sum of the sides' (t_y, -t_x) (t = x_b - x_a: length times the outward
   !> normal), and c, the length-weighted mean compliance of the sides' elements,
   !> (1 - nu**2)/E in plane strain, 1/E in plane stress (0 without a material).
   subroutine face_normals(model, seg, elem, take, vn, c)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: seg(:, :), elem(:)
      logical, intent(in) :: take(:)
      real(wp), allocatable, intent(out) :: vn(:, :), c(:)
      real(wp), allocatable :: lsum(:)
      real(wp) :: t(2), l, ce
      integer :: k, j
      allocate (vn(2, model%nnode), c(model%nnode), lsum(model%nnode), source=0.0_wp)
      do k = 1, size(seg, 2)
         if (.not. take(k)) cycle
         t = model%x(:, seg(2, k)) - model%x(:, seg(1, k))
         l = length2(t)
         ce = element_compliance(model, elem(k))
         do j = 1, 2
            vn(:, seg(j, k)) = vn(:, seg(j, k)) + [t(2), -t(1)]
            c(seg(j, k)) = c(seg(j, k)) + l*ce
            lsum(seg(j, k)) = lsum(seg(j, k)) + l
         end do
      end do
      where (lsum > 0.0_wp) c = c/lsum
   end subroutine face_normals

   !> The compliance of element e's material under a surface pressure: (1 - nu**2)/E in
   !> plane strain, 1/E in plane stress; 0 without an elastic material.
   pure real(wp) function element_compliance(model, e) result(c)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: e
      c = 0.0_wp
      if (.not. (allocated(model%elem_mat) .and. allocated(model%materials))) return
      if (model%elem_mat(e) < 1) return
      associate (mat => model%materials(model%elem_mat(e)))
         if (.not. (mat%young > 0.0_wp)) return
         c = 1.0_wp/mat%young
         if (allocated(model%elem_plane)) then
            if (model%elem_plane(e) /= plane_stress) c = (1.0_wp - mat%poisson**2)/mat%young
         end if
      end associate
   end function element_compliance

   !> Local numbering of a pair's nodes (slaves first, then the other master nodes).
   subroutine local_numbering(nnode, node, seg, pd)
      integer(ip), intent(in) :: nnode
      integer(ip), intent(in) :: node(:), seg(:, :)
      type(pair_data_t), intent(inout) :: pd
      integer(ip), allocatable :: loc(:), buf(:)
      integer :: i, k, m
      allocate (loc(nnode), source=0_ip)
      allocate (buf(size(node) + size(seg)))
      m = 0
      do i = 1, size(node)
         if (loc(node(i)) /= 0) cycle
         m = m + 1
         buf(m) = node(i)
         loc(node(i)) = int(m, ip)
      end do
      do k = 1, size(seg, 2)
         do i = 1, 2
            if (loc(seg(i, k)) /= 0) cycle
            m = m + 1
            buf(m) = seg(i, k)
            loc(seg(i, k)) = int(m, ip)
         end do
      end do
      pd%lnode = buf(:m)
      pd%lslave = loc(node)
      pd%lseg = reshape(loc(reshape(seg, [size(seg)])), shape(seg))
   end subroutine local_numbering

   !> Current coordinates x + u of a pair's local nodes.
   pure function local_coordinates(pd, model, u) result(xl)
      type(pair_data_t), intent(in) :: pd
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      real(wp), allocatable :: xl(:, :)
      integer :: j
      allocate (xl(2, size(pd%lnode)))
      do j = 1, size(pd%lnode)
         xl(:, j) = model%x(:, pd%lnode(j)) + u(2*pd%lnode(j) - 1:2*pd%lnode(j))
      end do
   end function local_coordinates

   subroutine allocate_entries(self, n)
      type(contact_state_t), intent(inout) :: self
      integer, intent(in) :: n
      self%n = n
      allocate (self%node(n), self%pair(n), self%length(n), self%thick(n), self%k(n))
      allocate (self%iseg(n), source=0_ip)
      allocate (self%xi(n), self%gap(n), self%gap0(n), source=0.0_wp)
      allocate (self%normal(2, n), source=0.0_wp)
      allocate (self%slide_c(n), source=0.0_wp)
      allocate (self%slide_w(6, n), source=0.0_wp)
      allocate (self%slide_s0(n), self%slide_base(n), source=0.0_wp)
      allocate (self%active(n), source=.false.)
      allocate (self%lambda(n), source=0.0_wp)
      allocate (self%k_full(n), source=0.0_wp)
      allocate (self%slid_off(n), source=.false.)
   end subroutine allocate_entries

   !> Smallest E * thickness over the master segments' elements and the elements
   !> around the slave nodes (0 when no element has a material).
   function pair_stiffness(model, seg_elem, node) result(et)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: seg_elem(:), node(:)
      real(wp) :: et
      logical, allocatable :: is_slave(:), is_master(:)
      logical :: found
      integer(ip) :: e
      et = 0.0_wp
      if (.not. (allocated(model%elem_mat) .and. allocated(model%elem_thick) .and. &
                 allocated(model%materials))) return
      et = huge(1.0_wp)
      found = .false.
      allocate (is_slave(model%nnode), is_master(model%nelem), source=.false.)
      is_slave(node) = .true.
      is_master(seg_elem) = .true.
      do e = 1, model%nelem
         if (model%elem_mat(e) < 1) cycle
         if (.not. (is_master(e) .or. &
                    any(is_slave(model%elem_conn(model%elem_ptr(e):model%elem_ptr(e + 1) - 1))))) cycle
         et = min(et, model%materials(model%elem_mat(e))%young*model%elem_thick(e))
         found = .true.
      end do
      if (.not. found) et = 0.0_wp
   end function pair_stiffness

   !> Node pairs (slave, master node) that contact can couple with displacements
   !> u (current configuration x + u): the extra edges of the matrix pattern.
   subroutine graph_pairs(self, model, u, pairs, error)
      class(contact_state_t), intent(in) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer(ip), allocatable, intent(out) :: pairs(:, :)
      type(error_t), allocatable, intent(out) :: error
      type(segment_grid_t) :: grid
      integer(ip), allocatable :: pp(:, :)
      real(wp), allocatable :: xl(:, :)
      integer :: p
      allocate (pairs(2, 0))
      do p = 1, size(self%pairs)
         if (self%pairs(p)%nslave == 0) cycle
         ! twice the search radius: room for the pairing to move without a new pattern
         associate (pd => self%pairs(p))
            xl = local_coordinates(pd, model, u)
            call build_segment_grid(xl, pd%lseg, 2.0_wp*search_radius(pd, u), grid, error)
            if (allocated(error)) return
            call contact_graph_pairs(grid, xl, pd%lseg, pd%lslave, 2.0_wp*search_radius(pd, u), pp)
            pp = reshape(pd%lnode(reshape(pp, [size(pp)])), shape(pp))
         end associate
         pairs = reshape([pairs, pp], [2, size(pairs, 2) + size(pp, 2)])
      end do
   end subroutine graph_pairs

   !> Pair every slave node in the current configuration x + u.
   subroutine project(self, model, u, error)
      class(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      type(error_t), allocatable, intent(out) :: error
      integer :: p, i, lo, hi
      do p = 1, size(self%pairs)
         if (self%pairs(p)%nslave == 0) cycle
         lo = self%pairs(p)%first + 1
         hi = self%pairs(p)%first + self%pairs(p)%nslave
         if (self%pairs(p)%node_to_node .and. .not. self%pairs(p)%paired) then
            call pair_node_to_node(self, model, u, p, lo, hi)
            cycle
         end if
         if ((self%pairs(p)%small_sliding .or. self%pairs(p)%stepwise) .and. self%pairs(p)%paired) then
            ! the pairing stays that of the undeformed state (or of the load state's
            ! start): only the gaps move, linearly in u, so the frozen stiffness is exact
            do i = lo, hi
               if (self%iseg(i) /= 0) self%gap(i) = frozen_gap(self, i, u)
            end do
            cycle
         end if
         call search_pair(self, model, u, p, lo, hi, error)
         if (allocated(error)) return
      end do
   end subroutine project

   !> Pair the slave entries lo..hi of pair p anew at u: the closest segments, kept
   !> within the hysteresis, then (finite sliding) the point along the reference normal,
   !> with the reference normal, the gap, the sliding terms and the stick anchor.
   subroutine search_pair(self, model, u, p, lo, hi, error)
      type(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer, intent(in) :: p, lo, hi
      type(error_t), allocatable, intent(out) :: error
      type(segment_grid_t) :: grid
      real(wp), allocatable :: xl(:, :)
      integer(ip), allocatable :: prev(:)
      integer :: i
      integer(ip) :: a, b
      real(wp) :: radius
      associate (pd => self%pairs(p))
         radius = search_radius(pd, u)
         xl = local_coordinates(pd, model, u)
         call build_segment_grid(xl, pd%lseg, radius, grid, error)
         if (allocated(error)) return
         prev = self%iseg(lo:hi)
         call closest_segments(grid, xl, pd%lseg, pd%lslave, radius, self%iseg(lo:hi), &
                               self%xi(lo:hi), self%gap(lo:hi), self%normal(:, lo:hi), prev)
         do i = lo, hi
            if (pd%stepwise) call shift_arc(self, i, self%slide_base(i))
            call keep_previous(self, model, u, i, prev(i - lo + 1), radius)
            if (self%iseg(i) == 0) cycle
            if (.not. pd%small_sliding) call ray_pair(self, model, u, i, pd%seg, grid)
            a = pd%seg(1, self%iseg(i))
            b = pd%seg(2, self%iseg(i))
            ! the reference segment's normal (a segment of zero length in the mesh
            ! keeps the current one: the search found it a direction)
            if (.not. segment_is_degenerate(model%x(:, a), model%x(:, b))) &
               self%normal(:, i) = segment_normal(model%x(:, a), model%x(:, b))
            call reference_gap(self, model, u, i, a, b)
            self%slide_c(i) = 0.0_wp
            self%slide_w(:, i) = 0.0_wp
            self%slide_s0(i) = 0.0_wp
            if (.not. pd%small_sliding) call sliding_terms(self, model, u, i, a, b)
            if (.not. pd%small_sliding) call carry_anchor(self, u, i, prev(i - lo + 1))
            if (pd%stepwise) then
               ! the pairing is kept through the load state: no sliding part in the
               ! tangent; the slip and anchor counted from the arc length s0
               self%slide_c(i) = 0.0_wp
               self%slide_w(:, i) = 0.0_wp
               call shift_arc(self, i, -self%slide_s0(i))
               self%slide_s0(i) = 0.0_wp
            end if
         end do
         pd%paired = .true.
      end associate
   end subroutine search_pair

   !> Entry i's slip and anchor counted from ds further back along the master
   !> (slide_base less ds).
   pure subroutine shift_arc(self, i, ds)
      type(contact_state_t), intent(inout) :: self
      integer, intent(in) :: i
      real(wp), intent(in) :: ds
      self%fric%slip(i) = self%fric%slip(i) + ds
      self%fric%anchor(i) = self%fric%anchor(i) + ds
      if (ds < 0.0_wp .or. ds > 0.0_wp) self%slide_base(i) = self%slide_base(i) - ds
   end subroutine shift_arc

   !> The fixed pairing of a SURFACE TO SURFACE pair (node_partners) and its gaps.
   subroutine pair_node_to_node(self, model, u, p, lo, hi)
      type(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer, intent(in) :: p, lo, hi
      integer :: i
      do i = lo, hi
         self%iseg(i) = self%pairs(p)%nn_seg(i - lo + 1)
         if (self%iseg(i) == 0) cycle
         self%xi(i) = self%pairs(p)%nn_xi(i - lo + 1)
         self%normal(:, i) = self%pairs(p)%nn_normal(:, i - lo + 1)
         call reference_gap(self, model, u, i, self%pairs(p)%seg(1, self%iseg(i)), self%pairs(p)%seg(2, self%iseg(i)))
      end do
      self%pairs(p)%paired = .true.
   end subroutine pair_node_to_node

   !> g0 = n.(X_s - X_xi) of entry i on segment a -> b, and its gap at u.
   subroutine reference_gap(self, model, u, i, a, b)
      type(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer, intent(in) :: i
      integer(ip), intent(in) :: a, b
      ! reference gap with this pairing frozen: g = g0 + n.A u.  The gap is
      ! evaluated in this form (from displacement differences) rather than from
      ! the current coordinates: an overclosure of 1e-10 of the coordinates
      ! would otherwise lose most of its digits to cancellation
      self%gap0(i) = dot_product(self%normal(:, i), model%x(:, self%node(i)) - &
                                 ((1.0_wp - self%xi(i))*model%x(:, a) + self%xi(i)*model%x(:, b)))
      if (abs(self%gap0(i)) <= gap0_roundoff*epsilon(1.0_wp)* &
          max(maxval(abs(model%x(:, self%node(i)))), maxval(abs(model%x(:, a))), &
              maxval(abs(model%x(:, b))))) self%gap0(i) = 0.0_wp
      self%gap(i) = frozen_gap(self, i, u)
   end subroutine reference_gap

   !> c = n.(u_b - u_a) and w = dxi/du of entry i on the segment a -> b at u, for
   !> the sliding part of the tangent (sliding_tangent, tangent_times); the
   !> reference segment is normal to n, so that c = n.t of the current one.  And
   !> the slip's terms: s0 = S_a + t.(X_s - X_a) with S_a the reference arc length
   !> at a, so that s = s0 + t.A(xi) u = S(xi) + t.(x_s - x_xi) is the arc length of
   !> the projection (the current x_s - x_xi is normal to the current segment: its
   !> t component is the gap times the segment's rotation), continuous across
   !> segment changes.
   subroutine sliding_terms(self, model, u, i, a, b)
      type(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer, intent(in) :: i
      integer(ip), intent(in) :: a, b
      real(wp) :: t(2)
      self%slide_c(i) = dot_product(self%normal(:, i), u(2*b - 1:2*b) - u(2*a - 1:2*a))
      if (segment_is_degenerate(model%x(:, a), model%x(:, b))) then
         self%slide_w(:, i) = projection_gradient(self%xi(i), current_x(model, u, self%node(i)), &
                                                  current_x(model, u, a), current_x(model, u, b))
      else
         self%slide_w(:, i) = ray_gradient(self%xi(i), current_x(model, u, a), current_x(model, u, b), &
                                           model%x(:, b) - model%x(:, a))
      end if
      t = tangent_of(self%normal(:, i))
      self%slide_s0(i) = self%pairs(self%pair(i))%arc(self%iseg(i)) + &
                         dot_product(t, model%x(:, self%node(i)) - model%x(:, a))
   end subroutine sliding_terms

   !> The stick anchor of a frictional entry under finite sliding, a position on
   !> the master's arc length: an entry paired anew (none before) anchors where it
   !> is; on a closed loop the anchor follows the slip round the wrap of the arc
   !> length (the nearest of its copies a loop length apart).
   subroutine carry_anchor(self, u, i, iprev)
      type(contact_state_t), intent(inout) :: self
      real(wp), intent(in) :: u(:)
      integer, intent(in) :: i
      integer(ip), intent(in) :: iprev
      real(wp) :: sl, period
      if (.not. self%fric%on) return
      if (.not. self%fric%frictional_pair(self%pair(i))) return
      sl = entry_slip(self, i, u)
      if (iprev == 0) self%fric%anchor(i) = sl
      period = self%pairs(self%pair(i))%period(self%iseg(i))
      if (period > 0.0_wp) self%fric%anchor(i) = self%fric%anchor(i) + period*anint((sl - self%fric%anchor(i))/period)
   end subroutine carry_anchor

   !> Finite sliding: entry i moves to the point of the master surface on the line
   !> through its slave node along the reference normal (ray_projection), walking
   !> from the closest segment to its neighbours while that point lies beyond the
   !> segment's ends.  Where the lines of two neighbours leave a wedge between them
   !> (a vertex where the reference normals turn away from the slave) the node keeps
   !> the segment it overshoots less.  A segment of zero length in the mesh keeps
   !> the closest point.
   subroutine ray_pair(self, model, u, i, seg, grid)
      type(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer, intent(in) :: i
      integer(ip), intent(in) :: seg(:, :)
      type(segment_grid_t), intent(in) :: grid
      integer(ip) :: j, nb, from
      real(wp) :: xi, xin
      logical :: ok, take
      integer :: step
      j = self%iseg(i)
      call ray_xi(model, u, self%node(i), seg(:, j), xi, ok)
      if (.not. ok) return
      from = 0
      do step = 1, ray_walk_limit
         nb = 0
         if (xi < 0.0_wp) nb = grid%prev(j)
         if (xi > 1.0_wp) nb = grid%next(j)
         if (nb == 0 .or. nb == from) exit
         call ray_xi(model, u, self%node(i), seg(:, nb), xin, ok)
         if (.not. ok) exit
         take = .true.
         ! the wedge: the neighbour's point is back beyond the vertex they share
         if (xi < 0.0_wp .and. xin > 1.0_wp) &
            take = (xin - 1.0_wp)*seg_length(model, u, seg(:, nb)) < -xi*seg_length(model, u, seg(:, j))
         if (xi > 1.0_wp .and. xin < 0.0_wp) &
            take = -xin*seg_length(model, u, seg(:, nb)) < (xi - 1.0_wp)*seg_length(model, u, seg(:, j))
         if (take) then
            from = j
            j = nb
            xi = xin
         end if
         if (.not. take .or. (xin >= 0.0_wp .and. xin <= 1.0_wp)) exit
      end do
      self%iseg(i) = j
      self%xi(i) = xi
   end subroutine ray_pair

   !> ray_projection of slave node s on the segment sg (ok = .false. for a segment of
   !> zero length in the mesh or turned by a right angle).
   pure subroutine ray_xi(model, u, s, sg, xi, ok)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer(ip), intent(in) :: s, sg(2)
      real(wp), intent(out) :: xi
      logical, intent(out) :: ok
      xi = 0.0_wp
      ok = .not. segment_is_degenerate(model%x(:, sg(1)), model%x(:, sg(2)))
      if (ok) call ray_projection(current_x(model, u, s), current_x(model, u, sg(1)), current_x(model, u, sg(2)), &
                                  model%x(:, sg(2)) - model%x(:, sg(1)), xi, ok)
   end subroutine ray_xi

   !> current length of the segment sg
   pure real(wp) function seg_length(model, u, sg) result(l)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer(ip), intent(in) :: sg(2)
      l = length2(current_x(model, u, sg(2)) - current_x(model, u, sg(1)))
   end function seg_length

   !> Entry i goes back to its previous segment iprev while its projection stays
   !> within pairing_hysteresis of it and within the search radius.
   subroutine keep_previous(self, model, u, i, iprev, radius)
      type(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:), radius
      integer, intent(in) :: i
      integer(ip), intent(in) :: iprev
      real(wp) :: xi, gap, normal(2), dist
      integer :: status
      if (iprev == 0 .or. iprev == self%iseg(i)) return
      associate (sg => self%pairs(self%pair(i))%seg(:, iprev))
         call project_point_segment(current_x(model, u, self%node(i)), current_x(model, u, sg(1)), &
                                    current_x(model, u, sg(2)), xi, gap, normal, dist, status)
      end associate
      if (status /= seg_ok) return
      if (xi < -pairing_hysteresis .or. xi > 1.0_wp + pairing_hysteresis) return
      if (dist > radius) return          ! no longer a candidate: the pattern may not hold it
      self%iseg(i) = iprev
      self%xi(i) = xi
   end subroutine keep_previous

   !> x + u of model node j
   pure function current_x(model, u, j) result(xj)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer(ip), intent(in) :: j
      real(wp) :: xj(2)
      xj = model%x(:, j) + u(2*j - 1:2*j)
   end function current_x

   !> New active set from the current gaps; returns how many entries changed.
   !> Entries of `hold` that are active stay active whatever their gap; they are
   !> counted as changed when their gap says open, so that the caller does not stop
   !> on them (the driver holds nodes opened by the pairing update alone).
   subroutine update_active(self, nchanged, hold, pin)
      class(contact_state_t), intent(inout) :: self
      integer, intent(out) :: nchanged
      logical, intent(in), optional :: hold(:)
      !> entries kept closed whatever their force, and not counted as changes
      !> (solve_contact's pins: an entry between open and closed)
      logical, intent(in), optional :: pin(:)
      logical, allocatable :: new(:)
      ! N = lambda - k g >= 0: g <= 0 for LINEAR pairs (lambda = 0)
      new = self%iseg > 0 .and. self%lambda - self%k*self%gap >= 0.0_wp
      if (present(pin)) new = new .or. (pin .and. self%iseg > 0)
      nchanged = count(new .neqv. self%active)
      if (present(hold)) new = new .or. (hold .and. self%active .and. self%iseg > 0)
      self%active = new
   end subroutine update_active

   !> Add k A^T n n^T A of the active springs to `a`; `ok` false when a spring
   !> couples nodes the pattern does not hold (the caller rebuilds the pattern).
   subroutine add_stiffness(self, a, ok, values)
      class(contact_state_t), intent(in) :: self
      type(sym_csc_t), intent(inout) :: a
      logical, intent(out) :: ok
      !> .false.: only whether the springs are inside the pattern (`a` unchanged: a
      !> process whose share of the matrix does not hold them); default .true.
      logical, intent(in), optional :: values
      real(wp) :: scale
      integer :: i
      ok = .true.
      scale = 1.0_wp
      if (present(values)) scale = merge(1.0_wp, 0.0_wp, values)
      do i = 1, self%n
         if (.not. self%active(i)) cycle
         ! closed springs carry their stiffness even at g = 0 exactly (initial touching);
         ! adding exact zeros leaves a share as it was
         call add_element_matrix(a, nodes_of(self, i), &
                                 scale*contact_stiffness(self%xi(i), self%normal(:, i), self%k(i), -1.0_wp), ok)
         if (.not. ok) return
         ! a sticking entry: its tangential spring (the same rank-one form along t)
         if (self%fric%state(i) == tangent_stick) then
            call add_element_matrix(a, nodes_of(self, i), scale*contact_stiffness(self%xi(i), &
                                    tangent_of(self%normal(:, i)), self%fric%kt(i), -1.0_wp), ok)
            if (.not. ok) return
         end if
      end do
   end subroutine add_stiffness

   !> The unit tangent t = (-n_y, n_x) of the master at an entry with normal n: the
   !> direction of the master segment a -> b, along which CSLIP and CSHEAR count.
   pure function tangent_of(normal) result(t)
      real(wp), intent(in) :: normal(2)
      real(wp) :: t(2)
      t = [-normal(2), normal(1)]
   end function tangent_of

   !> The tangential force of entry i in the frozen system at u: a sticking entry's
   !> spring, lambda + kt (s(u) - anchor); a slipping entry's force of the last update
   !> followed linearly by its normal force, T + dT/dN (N(u) - N) with
   !> N(u) = lambda - k g(u) the frozen spring's.
   pure real(wp) function frozen_tangential(self, i, u) result(tf)
      type(contact_state_t), intent(in) :: self
      integer, intent(in) :: i
      real(wp), intent(in) :: u(:)
      select case (self%fric%state(i))
      case (tangent_stick)
         tf = self%fric%lambda(i) + self%fric%kt(i)*(entry_slip(self, i, u) - self%fric%anchor(i))
      case (tangent_slip)
         tf = self%fric%force(i) + self%fric%dnormal(i)* &
              (self%lambda(i) - self%k(i)*frozen_gap(self, i, u) - self%fric%normal(i))
      case default
         tf = 0.0_wp
      end select
   end function frozen_tangential

   !> Whether some slipping entry's force follows its normal force (dT/dN /= 0): the
   !> frozen system then has the unsymmetric part that tangent_times applies and the
   !> symmetric factor lacks.
   pure logical function has_coupling(self)
      class(contact_state_t), intent(in) :: self
      has_coupling = .false.
      if (.not. self%fric%on) return
      has_coupling = any(self%active .and. self%fric%state == tangent_slip .and. abs(self%fric%dnormal) > 0.0_wp)
   end function has_coupling

   !> The slip of entry i at u: s = s0 + t.A(xi) u, the relative tangential
   !> displacement (contact_slip) plus s0, which for finite sliding makes it the arc
   !> length of the projection along the master (sliding_terms; s0 = 0 where the
   !> pairing is fixed).
   pure real(wp) function entry_slip(self, i, u) result(sl)
      type(contact_state_t), intent(in) :: self
      integer, intent(in) :: i
      real(wp), intent(in) :: u(:)
      sl = self%slide_s0(i) + relative_slip(self, i, u)
   end function entry_slip

   !> Relative tangential displacement t.A(xi) v of entry i (contact_slip): the
   !> slip's change along v with the pairing frozen.
   pure real(wp) function relative_slip(self, i, v) result(sl)
      type(contact_state_t), intent(in) :: self
      integer, intent(in) :: i
      real(wp), intent(in) :: v(:)
      integer(ip) :: nodes(3)
      nodes = nodes_of(self, i)
      sl = contact_slip(self%xi(i), self%normal(:, i), [v(2*nodes(1) - 1:2*nodes(1)), &
                                                         v(2*nodes(2) - 1:2*nodes(2)), v(2*nodes(3) - 1:2*nodes(3))])
   end function relative_slip

   !> The return mapping of every entry's tangential law at u (after update_active):
   !> stick/slip states and forces for the next solve; nchanged counts the
   !> frictional entries whose state changed.
   subroutine update_friction(self, u, nchanged, closing_slips)
      class(contact_state_t), intent(inout) :: self
      real(wp), intent(in) :: u(:)
      integer, intent(out) :: nchanged
      !> entries that close slip in the next solve (friction_state_t%update): within the
      !> iteration, not at its start
      logical, intent(in) :: closing_slips
      real(wp), allocatable :: sl(:), nf(:)
      integer :: i
      nchanged = 0
      if (.not. self%fric%on) return
      allocate (sl(self%n), nf(self%n), source=0.0_wp)
      do i = 1, self%n
         if (self%iseg(i) == 0) cycle
         sl(i) = entry_slip(self, i, u)
         nf(i) = self%normal_force(i)
      end do
      ! the slips' round-off: of the displacements, and of the arc length s0 they carry
      ! under finite sliding (positions along the master, metres where the slips are
      ! micrometres: near the limit of a strength reduction the dam's stick/slip states
      ! flipped on it until MAXIT)
      call self%fric%update(self%pair, sl, nf, self%active .and. self%iseg > 0, self%length*self%thick, nchanged, &
                            closing_slips, 16.0_wp*epsilon(1.0_wp)*max(maxval(abs(u)), maxval(abs(self%slide_s0))))
   end subroutine update_friction

   !> The shear force that entry i's law carries closed at zero normal force (the
   !> cohesion c A of Mohr-Coulomb; 0 for Coulomb, frictionless or without friction).
   pure real(wp) function zero_normal_strength(self, i) result(t)
      class(contact_state_t), intent(in) :: self
      integer, intent(in) :: i
      type(tangential_response_t) :: r
      t = 0.0_wp
      if (.not. self%fric%on) return
      r = self%fric%laws(self%pair(i))%law%return_map(huge(1.0_wp), 0.0_wp, self%length(i)*self%thick(i), .true.)
      if (r%state == tangent_slip) t = abs(r%force)
   end function zero_normal_strength

   !> Uzawa update of the exact-stick entries (friction_state_t%augment): the largest
   !> change of a tangential force beyond `noise`, relative to the largest contact
   !> force, and the largest elastic slip relative to the tributary length, from
   !> before the update.
   subroutine augment_friction(self, noise, change, elastic_slip)
      class(contact_state_t), intent(inout) :: self
      !> force changes within this round-off of the equilibrium count as none
      real(wp), intent(in) :: noise
      real(wp), intent(out) :: change, elastic_slip
      real(wp) :: fmax
      integer :: i
      call self%fric%augment(self%pair, self%length, noise, change, elastic_slip)
      fmax = 0.0_wp
      do i = 1, self%n
         if (self%active(i)) fmax = max(fmax, self%normal_force(i), abs(self%fric%force(i)))
      end do
      if (fmax > 0.0_wp) change = change/fmax
   end subroutine augment_friction

   !> The slip history the next increment starts from (friction_state_t%commit).
   subroutine commit_friction(self)
      class(contact_state_t), intent(inout) :: self
      if (self%fric%on) call self%fric%commit(self%pair)
   end subroutine commit_friction

   !> Whether some pair enforces stick exactly (a multiplier: Uzawa updates).
   pure logical function has_exact_friction(self)
      class(contact_state_t), intent(in) :: self
      has_exact_friction = self%fric%on .and. self%fric%exact
   end function has_exact_friction

   !> The tangential terms of the line search energy along d from u0 (line_search_step):
   !> a = d.f_t(u0) with the frozen tangential forces, b = d.K_t d with the sticking
   !> entries' springs.
   subroutine tangential_line_terms(self, u0, d, a, b)
      class(contact_state_t), intent(in) :: self
      real(wp), intent(in) :: u0(:), d(:)
      real(wp), intent(out) :: a, b
      real(wp) :: ds
      integer :: i
      a = 0.0_wp
      b = 0.0_wp
      if (.not. self%fric%on) return
      do i = 1, self%n
         if (.not. self%active(i)) cycle
         if (self%fric%state(i) /= tangent_stick .and. self%fric%state(i) /= tangent_slip) cycle
         ds = relative_slip(self, i, d)
         a = a + frozen_tangential(self, i, u0)*ds
         if (self%fric%state(i) == tangent_stick) b = b + self%fric%kt(i)*ds*ds
      end do
   end subroutine tangential_line_terms

   !> The number of active entries in tangential state `state` (tangent_stick, tangent_slip).
   pure integer function count_state(self, state) result(m)
      class(contact_state_t), intent(in) :: self
      integer, intent(in) :: state
      m = count(self%active .and. self%fric%state == state)
   end function count_state

   !> Right-hand side of the active springs, (lambda - k g0) A^T n: with the pairing
   !> frozen, (K + K_c) u = f_ext + sum (lambda - k g0) A^T n is the equilibrium.
   subroutine add_rhs(self, f)
      class(contact_state_t), intent(in) :: self
      real(wp), intent(inout) :: f(:)
      integer :: i
      do i = 1, self%n
         if (.not. self%active(i)) cycle
         call scatter(f, nodes_of(self, i), (self%lambda(i) - self%k(i)*self%gap0(i))* &
                      matmul(self%normal(:, i), relative_map(self%xi(i))))
         ! the tangential force's part that does not depend on u: lambda - kt (anchor -
         ! s0) of a sticking entry, the frozen force of a slipping one (opposite sign: it
         ! enters as K u + f_c = f_ext with f_c = T A^T t)
         select case (self%fric%state(i))
         case (tangent_stick)
            call scatter(f, nodes_of(self, i), -(self%fric%lambda(i) - self%fric%kt(i)*(self%fric%anchor(i) - &
                                                                                   self%slide_s0(i)))* &
                         matmul(tangent_of(self%normal(:, i)), relative_map(self%xi(i))))
         case (tangent_slip)
            call scatter(f, nodes_of(self, i), -(self%fric%force(i) + self%fric%dnormal(i)* &
                                                 (self%lambda(i) - self%k(i)*self%gap0(i) - self%fric%normal(i)))* &
                         matmul(tangent_of(self%normal(:, i)), relative_map(self%xi(i))))
         end select
      end do
   end subroutine add_rhs

   !> Contact forces -N A^T n of the active springs at the current pairing and gaps,
   !> N = max(0, lambda - k g) (k <-g> for LINEAR pairs).
   subroutine forces(self, f)
      class(contact_state_t), intent(in) :: self
      real(wp), intent(inout) :: f(:)
      integer :: i
      do i = 1, self%n
         if (.not. self%active(i)) cycle
         call scatter(f, nodes_of(self, i), -self%normal_force(i)* &
                      matmul(self%normal(:, i), relative_map(self%xi(i))) + &
                      self%fric%force(i)*matmul(tangent_of(self%normal(:, i)), relative_map(self%xi(i))))
      end do
   end subroutine forces

   !> The tension that the springs of the entries `mask` carry (lambda - k g < 0),
   !> added to the contact forces f as forces does the pressures: the force of an
   !> entry held closed by solve_contact's pins, which the solve balances.
   subroutine add_tension(self, mask, f)
      class(contact_state_t), intent(in) :: self
      logical, intent(in) :: mask(:)
      real(wp), intent(inout) :: f(:)
      integer :: i
      do i = 1, self%n
         if (.not. (mask(i) .and. self%active(i))) cycle
         call scatter(f, nodes_of(self, i), -min(0.0_wp, self%lambda(i) - self%k(i)*self%gap(i))* &
                      matmul(self%normal(:, i), relative_map(self%xi(i))))
      end do
   end subroutine add_tension

   !> The forces (k g(u) - lambda) A^T n of the active springs with the pairing frozen,
   !> g(u) = g0 + n.A u: the contact part of the matrix-vector product of the
   !> current linear system minus its right-hand side, evaluated from the gaps so that
   !> the stiff springs contribute k times a small number rather than a small
   !> difference of large ones (the driver's iterative refinement).
   subroutine linear_forces(self, u, f)
      class(contact_state_t), intent(in) :: self
      real(wp), intent(in) :: u(:)
      real(wp), intent(inout) :: f(:)
      integer :: i
      do i = 1, self%n
         if (.not. self%active(i)) cycle
         call scatter(f, nodes_of(self, i), (self%k(i)*frozen_gap(self, i, u) - self%lambda(i))* &
                      matmul(self%normal(:, i), relative_map(self%xi(i))) + &
                      frozen_tangential(self, i, u)*matmul(tangent_of(self%normal(:, i)), relative_map(self%xi(i))))
      end do
   end subroutine linear_forces

   !> jv = jv + K_c v with the contact tangent of the active entries at the current
   !> pairing: k A^T n n^T A and the sticking entries' kt A^T t t^T A (the matrix the
   !> factor holds), the slipping entries' -dT/dN k A^T t n^T A (their force follows
   !> the normal force: not symmetric) and, when `sliding`, the part the motion of the
   !> projection adds for finite sliding (sliding_tangent; zero for the fixed
   !> pairings), which is not symmetric either.
   subroutine tangent_times(self, v, jv, sliding)
      class(contact_state_t), intent(in) :: self
      real(wp), intent(in) :: v(:)
      real(wp), intent(inout) :: jv(:)
      logical, intent(in) :: sliding
      real(wp) :: ve(6), an(6), at(6), kc(6, 6)
      integer(ip) :: nodes(3)
      integer :: i, j
      do i = 1, self%n
         if (.not. self%active(i)) cycle
         nodes = nodes_of(self, i)
         do j = 1, 3
            ve(2*j - 1:2*j) = v(2*nodes(j) - 1:2*nodes(j))
         end do
         an = matmul(self%normal(:, i), relative_map(self%xi(i)))
         kc = 0.0_wp
         if (sliding) kc = sliding_tangent(self%xi(i), self%normal(:, i), self%k(i), self%normal_force(i), &
                                           self%slide_c(i), self%slide_w(:, i))
         call scatter(jv, nodes, self%k(i)*an*dot_product(an, ve) + matmul(kc, ve))
         if (self%fric%state(i) == tangent_stick) then
            at = matmul(tangent_of(self%normal(:, i)), relative_map(self%xi(i)))
            call scatter(jv, nodes, self%fric%kt(i)*at*dot_product(at, ve))
         else if (self%fric%state(i) == tangent_slip) then
            ! the slipping force's share of the normal force: dT/dN (-k n.A v) along t
            at = matmul(tangent_of(self%normal(:, i)), relative_map(self%xi(i)))
            call scatter(jv, nodes, -self%fric%dnormal(i)*self%k(i)*dot_product(an, ve)*at)
         end if
      end do
   end subroutine tangent_times

   !> Whether the pairing of some active entry follows the sliding (finite sliding
   !> node to surface): then the tangent has the part of sliding_tangent.
   pure logical function has_sliding(self)
      class(contact_state_t), intent(in) :: self
      has_sliding = any(self%active .and. any(abs(self%slide_w) > 0.0_wp, dim=1))
   end function has_sliding

   !> Normal force N = max(0, lambda - k g) of entry i (0 when inactive).
   pure real(wp) function normal_force(self, i) result(f)
      class(contact_state_t), intent(in) :: self
      integer, intent(in) :: i
      f = 0.0_wp
      if (self%active(i)) f = max(0.0_wp, self%lambda(i) - self%k(i)*self%gap(i))
   end function normal_force

   !> The normal force of each active entry that the solution balances, from
   !> r = K u - f_ext (the force the contact exerts on each node): n . r / |n|^2 at the slave
   !> node, where that node takes part in no other active entry and no fixed dof of it
   !> has a normal component (so that n . r is this entry's force alone); the spring's own force
   !> N = max(0, lambda - k g) elsewhere.  The spring force is K times an overclosure
   !> that is a small difference of displacements and loses digits like the penalty
   !> grows; r is the elastic body's own force, accurate to the round-off of the
   !> stresses, and it is the force that the displacements are in equilibrium with.
   subroutine set_balanced(self, model, r, fixed)
      class(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: r(:)
      logical, intent(in) :: fixed(:)
      integer, allocatable :: uses(:)
      integer(ip) :: nodes(3), s
      integer :: i
      allocate (uses(model%nnode), source=0)
      do i = 1, self%n
         if (.not. self%active(i)) cycle
         nodes = nodes_of(self, i)
         uses(nodes(1)) = uses(nodes(1)) + 1
         ! a master node with weight exactly 0 (node to node: xi = 0 or 1) takes no force
         if (abs(1.0_wp - self%xi(i)) > 0.0_wp) uses(nodes(2)) = uses(nodes(2)) + 1
         if (abs(self%xi(i)) > 0.0_wp) uses(nodes(3)) = uses(nodes(3)) + 1
      end do
      if (.not. allocated(self%balanced)) allocate (self%balanced(self%n))
      if (.not. allocated(self%held)) allocate (self%held(self%n))
      if (.not. allocated(self%support_shared)) allocate (self%support_shared(self%n))
      self%held = .false.
      self%support_shared = .false.
      do i = 1, self%n
         self%balanced(i) = self%normal_force(i)
         self%fric%balanced(i) = -self%fric%force(i)
         if (.not. self%active(i)) cycle
         s = self%node(i)
         if (uses(s) /= 1) cycle
         ! a fixed dof's residual holds its reaction: usable only across the normal
         ! (the tangent) when the fixed dofs have no component along it; the force on the
         ! node is N n + T t, with |n| = |t| < 1 at a kink of a SURFACE TO SURFACE master
         self%held(i) = (fixed(2*s - 1) .and. abs(self%normal(1, i)) > 0.0_wp) .or. &
                        (fixed(2*s) .and. abs(self%normal(2, i)) > 0.0_wp)
         self%support_shared(i) = &
            (fixed(2*s - 1) .and. abs(self%normal(1, i)) > support_share_floor*norm2(self%normal(:, i))) .or. &
            (fixed(2*s) .and. abs(self%normal(2, i)) > support_share_floor*norm2(self%normal(:, i)))
         if (.not. self%held(i)) &
            self%balanced(i) = dot_product(self%normal(:, i), r(2*s - 1:2*s))/ &
                               dot_product(self%normal(:, i), self%normal(:, i))
         if (.not. ((fixed(2*s - 1) .and. abs(self%normal(2, i)) > 0.0_wp) .or. &
                    (fixed(2*s) .and. abs(self%normal(1, i)) > 0.0_wp))) &
            self%fric%balanced(i) = dot_product(tangent_of(self%normal(:, i)), r(2*s - 1:2*s))/ &
                                    dot_product(self%normal(:, i), self%normal(:, i))
      end do
   end subroutine set_balanced

   !> Whether any pair has PRESSURE-OVERCLOSURE=HARD.
   pure logical function has_hard(self)
      class(contact_state_t), intent(in) :: self
      integer :: p
      has_hard = .false.
      do p = 1, size(self%pairs)
         has_hard = has_hard .or. (self%pairs(p)%hard .and. self%pairs(p)%nslave > 0)
      end do
   end function has_hard

   !> The multiplier update of the HARD entries after a solve whose active set held,
   !> lambda <- max(0, lambda + dlam) with the step `dlam` of multiplier_step
   !> (vemcontact_contact_iteration: the gaps' equation solved by conjugate gradients
   !> on the condensed compliance, whose first iterate is the plain Uzawa update
   !> dlam = -k g at its best length).  Inactive entries get 0, and the springs of
   !> the search stiffen to the augmentation (k_full).  Returns, from before the
   !> update, the largest overclosure beyond the round-off `noise` (gap_noise)
   !> relative to the tributary length (0 when none overclose) and the largest
   !> change |dlam| of a force relative to the largest force: the relative error of
   !> the pressures that the update corrects.
   subroutine augment(self, noise, dlam, overclosure, change)
      class(contact_state_t), intent(inout) :: self
      real(wp), intent(in) :: noise(:), dlam(:)
      real(wp), intent(out) :: overclosure, change
      real(wp) :: fmax
      integer :: i
      overclosure = 0.0_wp
      change = 0.0_wp
      fmax = 0.0_wp
      do i = 1, self%n
         if (.not. self%pairs(self%pair(i))%hard .or. self%iseg(i) == 0) cycle
         if (self%active(i)) then
            overclosure = max(overclosure, (-self%gap(i) - noise(i))/self%length(i))
            change = max(change, abs(dlam(i)))
            fmax = max(fmax, self%normal_force(i))
            self%lambda(i) = max(0.0_wp, self%lambda(i) + dlam(i))
         else
            self%lambda(i) = 0.0_wp
         end if
         self%k(i) = self%k_full(i)
      end do
      if (fmax > 0.0_wp) change = change/fmax
   end subroutine augment

   !> The round-off of each entry's gap, below which a gap counts as zero: a stiff
   !> augmentation cannot correct below it.  `noise_u` from the displacements, plus
   !> `noise_x` from the coordinates for an entry whose reference gap is not exactly
   !> zero (a node facing a segment between its ends; nodes that coincide have g0 = 0
   !> exactly, gap0_roundoff), plus the forward error of the solve: the elastic
   !> forces carry the round-off `noise_f` (eps times the largest elastic diagonal
   !> times the largest displacement), which moves a gap by at most noise_f / k, the
   !> compliance of the entry being below that of its spring alone.  The last term
   !> decides with a stiffness contrast: a stiff body resting on a soft one carries
   !> a rigid motion 1/contrast times larger than its strain, whose round-off
   !> reaches the gaps (1e-16 of a gap of 1e-3 at contrast 1e6,
   !> docs/contact-robustness.md).
   pure function gap_noise(self, noise_u, noise_x, noise_f) result(noise)
      class(contact_state_t), intent(in) :: self
      real(wp), intent(in) :: noise_u, noise_x, noise_f
      real(wp) :: noise(self%n)
      integer :: i
      do i = 1, self%n
         noise(i) = noise_u
         if (abs(self%gap0(i)) > 0.0_wp) noise(i) = noise(i) + noise_x
         if (self%k(i) > 0.0_wp) noise(i) = noise(i) + noise_f/self%k(i)
      end do
   end function gap_noise

   !> The entries whose multipliers an update moves: active HARD entries with a
   !> master segment.
   pure function multiplier_entries(self) result(mask)
      class(contact_state_t), intent(in) :: self
      logical :: mask(self%n)
      integer :: i
      do i = 1, self%n
         mask(i) = self%active(i) .and. self%iseg(i) > 0 .and. self%pairs(self%pair(i))%hard
      end do
   end function multiplier_entries

   !> f = f + sum dlam A^T n over the entries of `mask` at the current pairing: the
   !> right-hand side that the multipliers' change dlam adds (add_rhs).
   subroutine multiplier_load(self, mask, dlam, f)
      class(contact_state_t), intent(in) :: self
      logical, intent(in) :: mask(:)
      real(wp), intent(in) :: dlam(:)
      real(wp), intent(inout) :: f(:)
      integer :: i
      do i = 1, self%n
         if (.not. mask(i)) cycle
         call scatter(f, nodes_of(self, i), dlam(i)*matmul(self%normal(:, i), relative_map(self%xi(i))))
         ! a slipping entry's force follows its normal force (dT/dN dlam along t);
         ! with finite sliding the slide it drives moves the gaps (-c dxi)
         if (self%fric%state(i) == tangent_slip .and. any(abs(self%slide_w(:, i)) > 0.0_wp)) &
            call scatter(f, nodes_of(self, i), -self%fric%dnormal(i)*dlam(i)* &
                         matmul(tangent_of(self%normal(:, i)), relative_map(self%xi(i))))
      end do
   end subroutine multiplier_load

   !> dg = n.A(xi) du for the entries of `mask` at the current pairing (0 elsewhere):
   !> the change of their frozen gaps by the displacements du; with `sliding`, minus
   !> c dxi, the part that the motion of the projection adds (finite sliding:
   !> dxi = w.du, c = n.t; sliding_tangent is the force of it).
   pure subroutine gap_change(self, mask, du, dg, sliding)
      class(contact_state_t), intent(in) :: self
      logical, intent(in) :: mask(:)
      real(wp), intent(in) :: du(:)
      real(wp), intent(out) :: dg(:)
      logical, intent(in) :: sliding
      integer(ip) :: nodes(3)
      real(wp) :: ve(6)
      integer :: i, j
      do i = 1, self%n
         dg(i) = 0.0_wp
         if (.not. mask(i)) cycle
         dg(i) = frozen_gap(self, i, du) - self%gap0(i)
         if (.not. sliding) cycle
         nodes = nodes_of(self, i)
         do j = 1, 3
            ve(2*j - 1:2*j) = du(2*nodes(j) - 1:2*nodes(j))
         end do
         dg(i) = dg(i) - self%slide_c(i)*dot_product(self%slide_w(:, i), ve)
      end do
   end subroutine gap_change

   !> Whether a pair re-pairs its nodes at every iteration (NODE TO SURFACE with
   !> finite sliding, the default), as the help of a run that does not converge says.
   pure logical function has_finite_sliding(self)
      class(contact_state_t), intent(in) :: self
      integer :: p
      has_finite_sliding = .false.
      do p = 1, size(self%pairs)
         has_finite_sliding = has_finite_sliding .or. (.not. self%pairs(p)%small_sliding .and. &
                                                       .not. self%pairs(p)%node_to_node .and. &
                                                       self%pairs(p)%nslave > 0)
      end do
   end function has_finite_sliding

   !> The largest penalty slope of a LINEAR pair with finite sliding relative to its
   !> bodies, K h / E (h the median master segment, E t the pair's smallest modulus
   !> times thickness, over the largest slave thickness), 0 when there is none.
   pure real(wp) function penalty_ratio(self) result(r)
      class(contact_state_t), intent(in) :: self
      integer :: p, i
      r = 0.0_wp
      do p = 1, size(self%pairs)
         associate (pd => self%pairs(p))
            if (pd%hard .or. pd%small_sliding .or. pd%node_to_node .or. pd%nslave == 0) cycle
            if (pd%stiffness <= 0.0_wp) cycle
            do i = pd%first + 1, pd%first + pd%nslave
               if (self%length(i) > 0.0_wp) r = max(r, self%k(i)/self%length(i)*pd%h/pd%stiffness)
            end do
         end associate
      end do
   end function penalty_ratio

   !> Start a load state: the springs of HARD entries soften to K h/E = 10 (their
   !> pair's search_ratio) for the search of the active set (augment stiffens
   !> them again); the multipliers are kept from the previous state.  An entry that
   !> ends the previous state closed and carrying force keeps its stiff spring: its
   !> multiplier already holds it, there is nothing to search, and the first solve
   !> of the new state then has the matrix of the previous state's factor when the
   !> active set holds (one numeric factorization less per load increment:
   !> softening and stiffening again were two new matrices, bench/friction_cost.py).
   !> Frictional pairs with finite sliding (stepwise) are paired anew from here.
   subroutine start_state(self)
      class(contact_state_t), intent(inout) :: self
      integer :: i, p
      do p = 1, size(self%pairs)
         if (self%pairs(p)%stepwise) self%pairs(p)%paired = .false.
      end do
      do i = 1, self%n
         if (.not. self%pairs(self%pair(i))%hard) cycle
         if (self%active(i) .and. self%iseg(i) > 0 .and. self%lambda(i) > 0.0_wp) then
            self%k(i) = self%k_full(i)
         else
            self%k(i) = self%pairs(self%pair(i))%search_ratio*self%k_full(i)
         end if
      end do
   end subroutine start_state

   !> The stepwise pairs (frictional, finite sliding) with a closed entry that slid
   !> beyond the ends of its master segment at u (the arc length of its slip, S_a +
   !> t.(x_s - x_a) = slide_base + entry_slip, outside [S_a, S_a + l] by more than
   !> stepwise_slack l) are to be
   !> paired anew by the next project; released: some were.
   subroutine release_stepwise(self, model, u, released)
      class(contact_state_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      logical, intent(out) :: released
      real(wp) :: along, l
      integer(ip) :: a, b
      integer :: i, p
      released = .false.
      do i = 1, self%n
         p = self%pair(i)
         if (.not. self%pairs(p)%stepwise .or. .not. self%active(i) .or. self%iseg(i) == 0) cycle
         a = self%pairs(p)%seg(1, self%iseg(i))
         b = self%pairs(p)%seg(2, self%iseg(i))
         l = length2(model%x(:, b) - model%x(:, a))
         along = self%slide_base(i) + entry_slip(self, i, u) - self%pairs(p)%arc(self%iseg(i))
         if (along >= -stepwise_slack*l .and. along <= (1.0_wp + stepwise_slack)*l) cycle
         ! where the master goes on straight the segment's extension is the master
         if (.not. turns_at(self%pairs(p)%seg, self%iseg(i), merge(b, a, along > l))) cycle
         self%pairs(p)%paired = .false.
         released = .true.
      end do
   contains
      !> Whether the master turns at node v, the end of segment k: the segment on the
      !> other side of v is not parallel to k (none there: the master ends).
      logical function turns_at(seg, k, v) result(turns)
         integer(ip), intent(in) :: seg(:, :)
         integer(ip), intent(in) :: k, v
         real(wp) :: d0(2), d1(2)
         integer :: j
         turns = .false.
         d0 = model%x(:, seg(2, k)) - model%x(:, seg(1, k))
         do j = 1, size(seg, 2)
            if (j == k .or. .not. any(seg(:, j) == v)) cycle
            d1 = model%x(:, seg(2, j)) - model%x(:, seg(1, j))
            ! parallel to round-off of the coordinates
            turns = abs(d0(1)*d1(2) - d0(2)*d1(1)) > 64.0_wp*epsilon(1.0_wp)*norm2(d0)*norm2(d1)
            return
         end do
      end function turns_at
   end subroutine release_stepwise

   !> Gaps of every entry at displacements u with the current pairing frozen,
   !> g = g0 + n.A(xi) u (linear in u), for the line search of the driver; entries
   !> without a partner get huge (they never close along the line).
   pure subroutine frozen_gaps(self, u, g)
      class(contact_state_t), intent(in) :: self
      real(wp), intent(in) :: u(:)
      real(wp), intent(out) :: g(:)
      integer :: i
      do i = 1, self%n
         g(i) = huge(1.0_wp)
         if (self%iseg(i) /= 0) g(i) = frozen_gap(self, i, u)
      end do
   end subroutine frozen_gaps

   !> Gap of entry i with its pairing frozen: g = g0 + n.(u_s - ((1 - xi) u_a + xi u_b)),
   !> from displacement differences (the reference gap g0 carries the coordinates),
   !> so that an overclosure of 1e-10 of the coordinates keeps its digits.
   pure real(wp) function frozen_gap(self, i, u) result(g)
      type(contact_state_t), intent(in) :: self
      integer, intent(in) :: i
      real(wp), intent(in) :: u(:)
      integer(ip) :: nodes(3)
      nodes = nodes_of(self, i)
      g = self%gap0(i) + dot_product(self%normal(:, i), u(2*nodes(1) - 1:2*nodes(1)) - &
                                     ((1.0_wp - self%xi(i))*u(2*nodes(2) - 1:2*nodes(2)) + &
                                      self%xi(i)*u(2*nodes(3) - 1:2*nodes(3))))
   end function frozen_gap

   !> Closed springs as supports between parts, for the floating-part check.
   function springs(self, model, part) result(s)
      class(contact_state_t), intent(in) :: self
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: part(:)
      type(spring_t), allocatable :: s(:)
      integer :: i, m
      integer(ip) :: nodes(3)
      allocate (s(count(self%active) + self%count_state(tangent_stick)))
      m = 0
      do i = 1, self%n
         if (.not. self%active(i)) cycle
         m = m + 1
         nodes = nodes_of(self, i)
         s(m) = spring_t(model%x(:, nodes(1)), self%normal(:, i), part(nodes(1)), part(nodes(2)))
         ! a sticking entry holds along the tangent too
         if (self%fric%state(i) == tangent_stick) then
            m = m + 1
            s(m) = spring_t(model%x(:, nodes(1)), tangent_of(self%normal(:, i)), part(nodes(1)), part(nodes(2)))
         end if
      end do
   end function springs

   !> Results of every slave node: COPEN = gap, CPRESS = the balanced normal force
   !> (set_balanced; the spring's force before it is set) per tributary length and
   !> thickness, CSHEAR = the balanced tangential force along t = (-n_y, n_x) per
   !> tributary length and thickness, STATUS (2: slid off, 3 stick, 4 slip), CSLIP =
   !> t.(u_s - u_xi) in the displacements `u` with the unit tangent t of the paired
   !> segment (contact_slip); a node without a segment gets CSLIP = 0.
   function table(self, model, u) result(tab)
      class(contact_state_t), intent(in) :: self
      type(model_t), intent(in) :: model
      !> displacements to report the slip in, (u_x, u_y) per node: the step's
      !> reported ones (relative to the end of a geostatic step)
      real(wp), intent(in) :: u(:)
      type(contact_table_t) :: tab
      integer(ip) :: nodes(3)
      integer :: i
      tab%node = self%node
      tab%node_id = model%node_id(self%node)
      tab%x = model%x(:, self%node)
      tab%pair = self%pair
      allocate (tab%copen(self%n), tab%cpress(self%n), tab%cslip(self%n), tab%status(self%n))
      allocate (tab%cshear(self%n), source=0.0_wp)
      tab%cnarea = self%length*self%thick
      if (allocated(self%cfluidp)) tab%cfluidp = self%cfluidp
      do i = 1, self%n
         tab%status(i) = merge(1, 0, self%active(i))
         if (self%active(i) .and. self%fric%state(i) == tangent_stick) tab%status(i) = 3
         if (self%active(i) .and. self%fric%state(i) == tangent_slip) tab%status(i) = 4
         if (self%slid_off(i)) tab%status(i) = 2
         ! the shear traction on the slave along the master's tangent t (the force the
         ! solution balances, set_balanced), as CPRESS is the normal one
         if (self%active(i)) tab%cshear(i) = self%fric%balanced(i)/(self%length(i)*self%thick(i))
         if (self%iseg(i) == 0) then
            ! no master segment within the search radius: the gap is at least the radius
            tab%copen(i) = self%pairs(self%pair(i))%radius
            tab%cpress(i) = 0.0_wp
            tab%cslip(i) = 0.0_wp
         else
            tab%copen(i) = self%gap(i)
            if (allocated(self%balanced)) then
               tab%cpress(i) = self%balanced(i)/(self%length(i)*self%thick(i))
            else
               tab%cpress(i) = self%normal_force(i)/(self%length(i)*self%thick(i))
            end if
            nodes = nodes_of(self, i)
            tab%cslip(i) = contact_slip(self%xi(i), self%normal(:, i), &
                                        [u(2*nodes(1) - 1:2*nodes(1)), u(2*nodes(2) - 1:2*nodes(2)), &
                                         u(2*nodes(3) - 1:2*nodes(3))])
         end if
      end do
      call recover_side_pressures(self, model, tab)
   end function table

   !> CPRESS of the first-order SURFACE TO SURFACE pairs on the slave face's own sides
   !> (side_pressure, src/contact/recovery.f90): the nodes inserted into the slave face
   !> of pair p are the ones its insertion appended (self%inserted(p) nodes from
   !> self%node_base on, after those of the pairs before it).
   subroutine recover_side_pressures(self, model, tab)
      class(contact_state_t), intent(in) :: self
      type(model_t), intent(in) :: model
      type(contact_table_t), intent(inout) :: tab
      type(error_t), allocatable :: err
      integer(ip), allocatable :: edge(:, :), edge_elem(:), chain(:, :), mchain(:, :), melem(:), on(:), mnode(:)
      integer, allocatable :: edge_side(:), mside(:)
      logical, allocatable :: new(:), keep(:), closed(:)
      integer(ip) :: n0
      integer :: p, lo, hi, i
      if (size(self%inserted) /= size(self%pairs)) return
      n0 = self%node_base
      do p = 1, size(self%pairs)
         if (p > 1) n0 = n0 + self%inserted(p - 1)
         if (.not. self%pairs(p)%node_to_node .or. self%inserted(p) == 0) cycle
         if (model%pairs(p)%formulation /= pair_surface_to_surface) cycle
         call slave_edges(model, model%pairs(p), edge, edge_elem, edge_side, err)
         if (allocated(err)) cycle
         if (size(edge_elem) == 0) cycle
         allocate (new(model%nnode), source=.false.)
         new(n0 + 1:n0 + self%inserted(p)) = .true.
         lo = self%pairs(p)%first + 1
         hi = self%pairs(p)%first + self%pairs(p)%nslave
         allocate (keep(hi - lo + 1), source=.false.)
         if (allocated(self%support_shared)) keep = self%support_shared(lo:hi)
         closed = tab%status(lo:hi) /= 0 .and. tab%status(lo:hi) /= 2
         ! the projection onto the own sides of the face that is the polygon of a curve:
         ! the master's, through each entry's partner, when its vertices turn more
         chain = face_chain(model, edge_elem, edge_side)
         on = self%node(lo:hi)
         mnode = [(partner_of(self, i), i=lo, hi)]
         call master_segments(model, model%pairs(p), mchain, melem, mside, err)
         if (.not. allocated(err)) then
            if (mean_turn(model%x, mchain, new, mnode, closed) > &
                curved_face_ratio*mean_turn(model%x, chain, new, on, closed) + curved_face_floor) then
               chain = mchain
               on = mnode
            end if
         end if
         tab%cpress(lo:hi) = side_pressure(model%x, chain, new, on, tab%cpress(lo:hi)*tab%cnarea(lo:hi), &
                                           tab%cnarea(lo:hi), closed, keep)
         deallocate (keep)
         deallocate (new)
      end do
   end subroutine recover_side_pressures

   !> The partner (master node) of node-to-node entry i, the end of its segment at
   !> xi = 0 or 1; the slave node itself where it has none (it is then on no master side).
   pure integer(ip) function partner_of(self, i) result(m)
      type(contact_state_t), intent(in) :: self
      integer, intent(in) :: i
      integer(ip) :: nodes(3)
      m = self%node(i)
      if (self%iseg(i) == 0) return
      nodes = nodes_of(self, i)
      m = merge(nodes(2), nodes(3), self%xi(i) < 0.5_wp)
   end function partner_of

   !> Mean turning angle (radians) of a face chain at its own nodes (not `new`) among
   !> the closed entries' nodes `node`: 0 on a straight face, the polygon's turn per
   !> vertex on a curve meshed by straight sides.
   pure real(wp) function mean_turn(x, chain, new, node, closed) result(turn)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: chain(:, :), node(:)
      logical, intent(in) :: new(:), closed(:)
      integer(ip), allocatable :: next(:), prev(:)
      real(wp) :: d1(2), d2(2)
      integer :: j, k, n
      allocate (next(size(x, 2)), prev(size(x, 2)), source=0_ip)
      do k = 1, size(chain, 2)
         next(chain(1, k)) = chain(2, k)
         prev(chain(2, k)) = chain(1, k)
      end do
      turn = 0.0_wp
      n = 0
      do j = 1, size(node)
         if (.not. closed(j) .or. new(node(j))) cycle
         if (next(node(j)) == 0 .or. prev(node(j)) == 0) cycle
         d1 = x(:, node(j)) - x(:, prev(node(j)))
         d2 = x(:, next(node(j))) - x(:, node(j))
         turn = turn + abs(atan2(d1(1)*d2(2) - d1(2)*d2(1), dot_product(d1, d2)))
         n = n + 1
      end do
      if (n > 0) turn = turn/n
   end function mean_turn

   !> The slave face as a chain of straight pieces (a, b): a first-order side as it
   !> is, a second-order side (a, m, b) as a -> m and m -> b, so that its side node
   !> is one of the face's own nodes.
   pure function face_chain(model, elem, side) result(chain)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: elem(:)
      integer, intent(in) :: side(:)
      integer(ip), allocatable :: chain(:, :)
      integer(ip) :: abc(3)
      integer :: k, m, ns
      allocate (chain(2, 2*size(elem)))
      m = 0
      do k = 1, size(elem)
         call element_side(model, elem(k), side(k), abc, ns)
         if (abc(3) == 0) then
            m = m + 1
            chain(:, m) = abc(1:2)
         else
            chain(:, m + 1) = [abc(1), abc(3)]
            chain(:, m + 2) = [abc(3), abc(2)]
            m = m + 2
         end if
      end do
      chain = chain(:, :m)
   end function face_chain

   !> Largest overclosure of the active springs (0 if none).
   pure real(wp) function max_penetration(self) result(m)
      class(contact_state_t), intent(in) :: self
      m = maxval(-self%gap, mask=self%active)
      if (.not. any(self%active)) m = 0.0_wp
      m = max(m, 0.0_wp)
   end function max_penetration

   !> Largest contact pressure N / (length * thickness) of the active springs.
   pure real(wp) function max_pressure(self) result(m)
      class(contact_state_t), intent(in) :: self
      integer :: i
      m = 0.0_wp
      do i = 1, self%n
         if (self%active(i)) m = max(m, self%normal_force(i)/(self%length(i)*self%thick(i)))
      end do
   end function max_pressure

   !> Search radius of a pair at displacements u: twice its longest master segment
   !> plus twice the largest displacement of the pair's nodes, since a node that has
   !> penetrated cannot lie deeper than the slave and master nodes have moved toward
   !> each other (a body held by a single closed spring can sink far).
   pure real(wp) function search_radius(pd, u) result(r)
      type(pair_data_t), intent(in) :: pd
      real(wp), intent(in) :: u(:)
      integer :: j
      integer(ip) :: i
      real(wp) :: umax
      umax = 0.0_wp
      do j = 1, size(pd%lnode)
         i = pd%lnode(j)
         umax = max(umax, hypot(u(2*i - 1), u(2*i)))
      end do
      r = pd%radius + 2.0_wp*umax
   end function search_radius

   pure function nodes_of(self, i) result(nodes)
      type(contact_state_t), intent(in) :: self
      integer, intent(in) :: i
      integer(ip) :: nodes(3)
      nodes = [self%node(i), self%pairs(self%pair(i))%seg(:, self%iseg(i))]
   end function nodes_of

   pure subroutine scatter(f, nodes, fe)
      real(wp), intent(inout) :: f(:)
      integer(ip), intent(in) :: nodes(3)
      real(wp), intent(in) :: fe(6)
      integer :: j
      do j = 1, 3
         f(2*nodes(j) - 1:2*nodes(j)) = f(2*nodes(j) - 1:2*nodes(j)) + fe(2*j - 1:2*j)
      end do
   end subroutine scatter
end module vemcontact_contact_active_set
