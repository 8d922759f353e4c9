!> The analysis model as read from a deck: mesh, sets, materials, sections and steps.
!> Everything is stored with internal 1-based indices; the user's ids are kept
!> for output and messages.  Every node and element remembers the file and line
!> it came from so that checks done after parsing can still name file:line.
module vemcontact_model
   use vemcontact_kinds, only: wp, ip
   implicit none
   private

   public :: model_t, named_set_t, material_t, section_t, step_t
   public :: dof_value_t, dload_t, string_t, source_loc_t
   public :: surface_t, interaction_t, contact_pair_t, contact_controls_t, output_request_t
   public :: uplift_t, strength_reduction_t, friction_change_t
   public :: find_set, location_string, output_requested, element_order, element_side
   public :: amplitude_t
   public :: equation_t, tie_t

   !> Element topology
   integer, parameter, public :: etype_polygon = 1 !< VPE/VPS: any number of nodes
   integer, parameter, public :: etype_quad4 = 2   !< CPE4/CPS4
   integer, parameter, public :: etype_tri3 = 3    !< CPE3/CPS3
   !> Second-order elements: corner nodes first, then one node per side
   !> (node n+k on side k, from corner k to corner k+1), Abaqus' order
   integer, parameter, public :: etype_polygon2 = 4 !< VPE2/VPS2: second-order polygon, 2n nodes
   integer, parameter, public :: etype_quad8 = 5    !< CPE8/CPS8: serendipity quad
   integer, parameter, public :: etype_tri6 = 6     !< CPE6/CPS6: quadratic triangle
   !> Plane assumption
   integer, parameter, public :: plane_strain = 1
   integer, parameter, public :: plane_stress = 2
   !> Discretisation of an element
   integer, parameter, public :: form_vem = 1
   integer, parameter, public :: form_fem = 2
   !> Distributed load kinds
   integer, parameter, public :: dload_grav = 1     !< body force rho*g*dir per unit volume
   integer, parameter, public :: dload_pressure = 2 !< uniform pressure on an element side
   integer, parameter, public :: dload_hydrostatic = 3 !< pressure linear in y on a side (Abaqus HP<k>)
   !> Surface kinds
   integer, parameter, public :: surface_element = 1 !< element sides (TYPE=ELEMENT)
   integer, parameter, public :: surface_node = 2    !< nodes (TYPE=NODE)
   !> Contact formulations of a pair (contact_pair_t%formulation)
   integer, parameter, public :: pair_node_to_surface = 1
   integer, parameter, public :: pair_surface_to_surface = 2
   !> Step procedures
   integer, parameter, public :: procedure_static = 1
   integer, parameter, public :: procedure_geostatic = 2 !< *GEOSTATIC: displacements reset to zero after it
   !> *STRENGTH REDUCTION (vemcontact): the factor of safety of the previous step's state
   integer, parameter, public :: procedure_strength_reduction = 3
   !> Output request categories (output_request_t%category)
   integer, parameter, public :: output_node = 1     !< *NODE FILE, *NODE OUTPUT, *NODE PRINT
   integer, parameter, public :: output_element = 2  !< *EL FILE, *ELEMENT OUTPUT, *EL PRINT
   integer, parameter, public :: output_contact = 3  !< *CONTACT FILE, *CONTACT OUTPUT, *CONTACT PRINT
   !> TOTALS= of *NODE PRINT and *EL PRINT (output_request_t%totals)
   integer, parameter, public :: totals_no = 0, totals_yes = 1, totals_only = 2

   !> A deferred-length string, for lists of names.
   type :: string_t
      character(len=:), allocatable :: s
   end type string_t

   !> Where an entity was defined: index into model%files and line number.
   type :: source_loc_t
      integer :: file = 0
      integer :: line = 0
   end type source_loc_t

   !> A named node or element set; items are internal indices, sorted and unique.
   type :: named_set_t
      character(len=:), allocatable :: name   !< upper case
      integer(ip), allocatable :: items(:)
      type(source_loc_t) :: loc
   end type named_set_t

   !> Isotropic linear elastic material.
   type :: material_t
      character(len=:), allocatable :: name   !< upper case
      real(wp) :: young = 0.0_wp
      real(wp) :: poisson = 0.0_wp
      real(wp) :: density = 0.0_wp
      logical :: has_elastic = .false.
      logical :: has_density = .false.
      !> *EXPANSION: isotropic thermal expansion coefficient (thermal strain alpha (T - T0))
      real(wp) :: expansion = 0.0_wp
      logical :: has_expansion = .false.
      type(source_loc_t) :: loc
   end type material_t

   !> *SOLID SECTION: assigns material, thickness, formulation and the VEM
   !> stabilisation factor to an element set.
   type :: section_t
      character(len=:), allocatable :: elset     !< upper case
      character(len=:), allocatable :: material  !< upper case
      integer :: imat = 0                        !< index into model%materials
      real(wp) :: thickness = 1.0_wp
      integer :: formulation = 0                 !< form_vem, form_fem, or 0 = element default
      real(wp) :: stabilization = 1.0_wp         !< VEM stabilisation factor tau (STABILIZATION=)
      logical :: has_stabilization = .false.     !< STABILIZATION= given (refused on FEM elements)
      type(source_loc_t) :: loc
   end type section_t

   !> A prescribed value on one degree of freedom (*BOUNDARY, *CLOAD).
   type :: dof_value_t
      integer(ip) :: node = 0
      integer :: dof = 0          !< 1 = x, 2 = y
      real(wp) :: value = 0.0_wp
      !> AMPLITUDE= of its keyword: index into model%amplitudes (the value times the
      !> amplitude at the time), 0 = the step's AMPLITUDE=RAMP or STEP
      integer :: amp = 0
   end type dof_value_t

   !> A distributed load on one element (*DLOAD).
   type :: dload_t
      integer(ip) :: elem = 0
      integer :: kind = 0         !< dload_grav, dload_pressure or dload_hydrostatic
      integer :: side = 0         !< for pressure: side k runs from node k to node k+1
      real(wp) :: magnitude = 0.0_wp  !< g for GRAV; p for pressure (positive pushes inward);
                                      !< for HP the pressure at height dir(2)
      real(wp) :: dir(2) = 0.0_wp     !< unit direction for GRAV; for HP: (y of zero pressure, y of magnitude)
      integer :: amp = 0              !< AMPLITUDE=: index into model%amplitudes, 0 = the step's ramp
   end type dload_t

   !> *AMPLITUDE (CalculiX): a piecewise linear function of time through the points
   !> (t(k), a(k)), constant beyond the first and the last point.  A load or boundary
   !> condition naming it takes its value times the amplitude instead of the step's ramp.
   type :: amplitude_t
      character(len=:), allocatable :: name   !< upper case
      real(wp), allocatable :: t(:), a(:)     !< times, increasing, and values
      !> TIME=TOTAL TIME: t is the total time (sum of the earlier steps' periods plus the
      !> step time), else the step time
      logical :: total_time = .false.
      type(source_loc_t) :: loc
   end type amplitude_t

   !> *SURFACE: element sides (elem(k), side(k)) or nodes.
   !> A linear multi-point constraint (*EQUATION): sum_i coef(i) u(node(i), dof(i)) = 0;
   !> the first term's dof is dependent (eliminated), as in CalculiX.
   type :: equation_t
      integer(ip), allocatable :: node(:)     !< internal node index of each term
      integer, allocatable :: dof(:)          !< 1 = x, 2 = y
      real(wp), allocatable :: coef(:)        !< coef(1) /= 0
      type(source_loc_t) :: loc               !< the line with the number of terms
   end type equation_t

   !> A *TIE: the slave surface's nodes bonded to the master surface (element sides)
   !> by linear constraints (vemcontact_driver_tie): node to node where the interface
   !> nodes were inserted into both faces (virtual elements), else each slave node to
   !> the point of the master face closest to it, as CalculiX.
   type :: tie_t
      character(len=:), allocatable :: name       !< upper case
      character(len=:), allocatable :: slave_name, master_name
      integer :: slave = 0, master = 0             !< indices into model%surfaces
      real(wp) :: tolerance = -1.0_wp             !< POSITION TOLERANCE; < 0: the default
      !> the (slave node, master node) pairs made by the interface node insertion
      !> (vemcontact_contact_insertion, insert_tie_nodes); unallocated: no insertion
      integer(ip), allocatable :: partner(:, :)
      !> the slave face's elements are FEM and the master's virtual: the slave face's
      !> nodes were inserted into the master face, whose nodes are then tied to the
      !> slave face (closest points), the roles of the faces swapped
      logical :: reverse = .false.
      type(source_loc_t) :: loc
   end type tie_t

   type :: surface_t
      character(len=:), allocatable :: name   !< upper case
      integer :: kind = 0                     !< surface_element or surface_node
      integer(ip), allocatable :: elem(:)     !< element of each facet (element surfaces)
      integer, allocatable :: side(:)         !< side of each facet: from node k to node k+1
      integer(ip), allocatable :: nodes(:)    !< node surfaces: nodes, sorted and unique
      type(source_loc_t) :: loc
   end type surface_t

   !> *SURFACE INTERACTION with its *SURFACE BEHAVIOR: PRESSURE-OVERCLOSURE=LINEAR
   !> (contact pressure = penalty * overclosure, no tension offset) or HARD (no
   !> overclosure: the pressure is a Lagrange multiplier).
   type :: interaction_t
      character(len=:), allocatable :: name   !< upper case
      real(wp) :: penalty = 0.0_wp            !< LINEAR: slope K, pressure per unit overclosure
      !> LINEAR, CalculiX's second and third values: the tension at large clearance of its
      !> regularised law p = K d (1/2 + atan(d/eps)/pi), eps = pi sigma_inf / K, and the
      !> clearance factor c0 of its spring generation.  Recorded; vemcontact solves the
      !> limit sigma_inf -> 0 (p = K max(d, 0)), see docs/deck-reference.md.
      real(wp) :: sigma_inf = 0.0_wp
      real(wp) :: c0 = 0.0_wp
      logical :: hard = .false.               !< PRESSURE-OVERCLOSURE=HARD
      logical :: has_behavior = .false.
      !> *FRICTION: Coulomb |t_T| <= mu p (CalculiX's data line mu [, stick slope]); with
      !> the stick slope (traction per unit elastic slip) stick is a tangential spring,
      !> without it exact (a multiplier); ROUGH: no slip; COHESION=c (ours): Mohr-Coulomb,
      !> |t_T| <= c + mu p while closed.  Without *FRICTION, or with mu = 0 and no
      !> cohesion, the interaction is frictionless.
      logical :: has_friction = .false.
      real(wp) :: mu = 0.0_wp
      real(wp) :: stick_slope = 0.0_wp        !< 0: exact stick
      real(wp) :: cohesion = 0.0_wp
      logical :: rough = .false.
      type(source_loc_t) :: loc
   end type interaction_t

   !> *CONTACT PAIR: slave (node or element surface) on master (element surface).
   type :: contact_pair_t
      integer :: slave = 0                    !< index into model%surfaces
      integer :: master = 0                   !< index into model%surfaces (surface_element)
      integer :: interaction = 0              !< index into model%interactions
      !> pair_node_to_surface (TYPE=NODE TO SURFACE: the paper's node-to-segment
      !> contact) or pair_surface_to_surface (TYPE=SURFACE TO SURFACE: each side's
      !> interface nodes are inserted into the other side's polygons, then node to node)
      integer :: formulation = 1
      !> SURFACE TO SURFACE: the (slave node, master node) pairs made by the interface
      !> node insertion (vemcontact_contact_insertion), one per slave node with a partner
      integer(ip), allocatable :: partner(:, :)
      !> SMALL SLIDING (CalculiX): the pairing of each slave node (segment, xi, normal)
      !> is found once in the undeformed configuration and kept; otherwise it is
      !> found anew in the deformed configuration at every iteration
      logical :: small_sliding = .false.
      !> NODE TO SURFACE: slave and master are the deck's master and slave, exchanged
      !> because the deck's master is the softer or finer face (vemcontact_contact_roles)
      logical :: roles_swapped = .false.
      !> ROLES=AUTO (vemcontact, the default): the roles may be exchanged; KEEP: never
      logical :: auto_roles = .true.
      type(source_loc_t) :: loc
   end type contact_pair_t

   !> Active-set iteration controls (*CONTACT CONTROLS), defaults for any model.
   type :: contact_controls_t
      integer :: max_iterations = 50          !< per step
      !> relative to the norm of the external and reaction forces.  1e-10: with the
      !> Newton step of the pairing this costs about one iteration more than 1e-8 and
      !> brings every deck under inputs/ within 1.2e-7 of its converged answer (at 1e-8:
      !> up to 2.3e-3 in the Hertz stresses); 1e-12 reaches the round-off floor of the
      !> dam's joint (docs/contact-robustness.md).
      real(wp) :: residual_tol = 1.0e-10_wp
      !> scales the internal augmentation stiffness of PRESSURE-OVERCLOSURE=HARD
      !> (STIFFNESS SCALE FACTOR, Abaqus' name); the converged answer does not depend on it
      real(wp) :: stiffness_scale = 1.0_wp
      !> HARD contact has converged when no overclosure exceeds this fraction of the
      !> local element size (the slave node's tributary length)
      real(wp) :: overclosure_tol = 1.0e-10_wp
   end type contact_controls_t

   !> One output request of a step: the result fields that a *NODE FILE, *EL FILE,
   !> *CONTACT FILE (or Abaqus' *NODE OUTPUT, *ELEMENT OUTPUT, *CONTACT OUTPUT), *NODE PRINT,
   !> *EL PRINT or *CONTACT PRINT selects, as vemcontact's field names (docs/deck-reference.md:
   !> CalculiX's CDIS is COPEN and CSLIP, CSTR is CPRESS).  Requests for what vemcontact
   !> cannot compute are left out (with a warning when the deck is read).
   type :: output_request_t
      integer :: category = 0                 !< output_node, output_element or output_contact
      !> a *... PRINT request (CalculiX writes it to its .dat file; vemcontact to
      !> JOB_print_NNNN.csv), else a result-file request (*... FILE, *... OUTPUT: VTU, HDF5, CSV)
      logical :: print = .false.
      character(len=:), allocatable :: set    !< NSET= or ELSET= (upper case), '' = the whole model
      integer :: totals = totals_no           !< TOTALS= of a PRINT request
      !> FREQUENCY=n: results also every n-th increment of the step (0: at its end only)
      integer :: frequency = 0
      type(string_t), allocatable :: fields(:)  !< e.g. U, RF, S, E, CPRESS, COPEN, CSLIP
      type(source_loc_t) :: loc
   end type output_request_t

   !> *UPLIFT (vemcontact): the water pressure inside the joints of one surface
   !> interaction, acting on both faces and pushing them apart.  The head (the
   !> elevation of the water surface, y up) falls linearly along the joint from the
   !> heel to the toe, or through a drain line; the pressure at a point of elevation
   !> y is gamma max(0, head - y).  With penetration, the joint's part open from the
   !> heel carries the headwater (docs/deck-reference.md, docs/sliding-safety.md).
   type :: uplift_t
      integer :: interaction = 0              !< index into model%interactions
      real(wp) :: heel(2) = 0.0_wp            !< where the headwater enters the joint
      real(wp) :: toe(2) = 0.0_wp             !< where the tailwater stands
      real(wp) :: head_heel = 0.0_wp          !< headwater elevation
      real(wp) :: head_toe = 0.0_wp           !< tailwater elevation
      real(wp) :: gamma = 0.0_wp              !< unit weight of water (UNIT WEIGHT=)
      logical :: drained = .false.            !< a drain line is given
      real(wp) :: drain(2) = 0.0_wp           !< a point of the drain line
      !> drain effectiveness E (USACE): head at the drain = tail + (1 - E)(head - tail);
      !> USBR's rule, a third of the difference above the tailwater, is E = 2/3
      real(wp) :: effectiveness = 0.0_wp
      !> pressure penetration (Abaqus' meaning): the open part contiguous from the heel
      !> carries the headwater, the rest the distribution restarted at the crack tip
      logical :: penetration = .false.
      !> *PRESSURE PENETRATION (Abaqus' keyword): the contact pair (index into model%pairs)
      !> whose joint the fluid enters; 0 for *UPLIFT.  The fluid pressure is then uniform
      !> over the open part reached from the exposed slave node (heel holds its
      !> coordinates) and zero beyond it.
      integer :: pair = 0
      integer(ip) :: exposed_slave = 0        !< node exposed to the fluid on the slave
      integer(ip) :: exposed_master = 0       !< node exposed to the fluid on the master
      real(wp) :: fluid_pressure = 0.0_wp     !< the fluid pressure p
      !> a node is open to the fluid while its contact pressure is at or below this
      real(wp) :: critical_pressure = 0.0_wp
      !> the part of the water pressure in force: below 1 within a ramped step that
      !> brings this uplift in (the driver's load increments)
      real(wp) :: factor = 1.0_wp
      type(source_loc_t) :: loc
   end type uplift_t

   !> *STRENGTH REDUCTION's parameters (docs/sliding-safety.md, "Factor of safety by
   !> strength reduction"): the friction of `interaction` (0: of every interaction with
   !> Coulomb/Mohr-Coulomb *FRICTION) is divided by trial factors F from f_first up to
   !> f_max until no equilibrium exists, located to the relative `tolerance`; the
   !> characteristic displacement is the largest |U - U_start| of node set `nset`
   !> (0: of every node).
   type :: strength_reduction_t
      integer :: interaction = 0
      integer :: nset = 0
      real(wp) :: tolerance = 1.0e-3_wp
      real(wp) :: f_first = 1.5_wp
      real(wp) :: f_max = 100.0_wp
      !> the first trial factor was given on the data line: the bracket grows from it
      !> instead of probing the estimate of the trial at F = 1
      logical :: first_given = .false.
   end type strength_reduction_t

   !> A step's *CHANGE FRICTION: interaction `interaction` takes the tangential law
   !> of the *FRICTION that follows it (the fields as in interaction_t) from this
   !> step on.
   type :: friction_change_t
      integer :: interaction = 0
      logical :: rough = .false.
      real(wp) :: mu = 0.0_wp
      real(wp) :: stick_slope = 0.0_wp
      real(wp) :: cohesion = 0.0_wp
      type(source_loc_t) :: loc
   end type friction_change_t

   !> One *STEP.  Loads follow CalculiX: with OP=MOD (default) a step's entries
   !> replace those of earlier steps on the same dof/element and keep the rest;
   !> OP=NEW on a keyword first removes everything of that kind from earlier steps.
   type :: step_t
      character(len=:), allocatable :: name
      integer :: procedure = procedure_static
      !> *STATIC data line (CalculiX): initial time increment, time period of the step,
      !> minimum and maximum increment; without it one increment of the whole period 1.
      !> dt_min 0: CalculiX's default, min(dt_initial, 1e-5 period)
      real(wp) :: dt_initial = 1.0_wp, period = 1.0_wp, dt_min = 0.0_wp, dt_max = 1.0e30_wp
      !> *STATIC, DIRECT: fixed increments dt_initial, no cut-back (the last increment
      !> ends the step: shorter when dt_initial does not divide the period)
      logical :: direct = .false.
      !> *STRENGTH REDUCTION's parameters (procedure_strength_reduction)
      type(strength_reduction_t) :: srm
      !> *STEP, AMPLITUDE=RAMP (the default of *STATIC: loads and prescribed
      !> displacements go linearly from their values at the end of the previous step to
      !> the step's values) or AMPLITUDE=STEP (.false.: the step's values at once;
      !> the default of *GEOSTATIC)
      logical :: ramp = .true.
      logical :: boundary_new = .false.
      logical :: cload_new = .false.
      logical :: dload_new = .false.
      type(dof_value_t), allocatable :: boundary(:)
      type(dof_value_t), allocatable :: cload(:)
      type(dload_t), allocatable :: dload(:)
      !> *UPLIFT of the step: replaces an earlier one of the same interaction, holds after
      type(uplift_t), allocatable :: uplift(:)
      !> nodal temperatures: *TEMPERATURE of a step (dof unused), or in `model%initial`
      !> *INITIAL CONDITIONS, TYPE=TEMPERATURE (the reference temperature T0)
      type(dof_value_t), allocatable :: temperature(:)
      logical :: temperature_new = .false.   !< *TEMPERATURE, OP=NEW: back to T0 first
      !> *CHANGE FRICTION of the step, in deck order
      type(friction_change_t), allocatable :: friction_changes(:)
      !> the output requests in force in this step: those of the step, and for each
      !> category (node, element, contact) and kind (file, print) without a request in
      !> the step those of the step before (CalculiX: the first request of a kind in a
      !> step replaces the earlier selection of that kind, else the earlier one applies)
      type(output_request_t), allocatable :: outputs(:)
      type(source_loc_t) :: loc
   end type step_t

   !> The whole model.
   type :: model_t
      character(len=:), allocatable :: heading
      type(string_t), allocatable :: files(:)      !< deck and included files, for messages
      ! nodes
      integer(ip) :: nnode = 0
      integer(ip), allocatable :: node_id(:)       !< user id of node i
      real(wp), allocatable :: x(:, :)             !< (2, nnode) coordinates
      type(source_loc_t), allocatable :: node_loc(:)
      ! elements, connectivity in CSR form: nodes of element e are
      ! elem_conn(elem_ptr(e):elem_ptr(e+1)-1), counter-clockwise
      integer(ip) :: nelem = 0
      integer(ip), allocatable :: elem_id(:)
      integer(ip), allocatable :: elem_ptr(:)
      integer(ip), allocatable :: elem_conn(:)
      integer, allocatable :: elem_type(:)         !< etype_*
      integer, allocatable :: elem_plane(:)        !< plane_strain / plane_stress
      integer, allocatable :: elem_form(:)         !< form_* after sections are applied
      integer, allocatable :: elem_mat(:)          !< material index, 0 = none
      real(wp), allocatable :: elem_thick(:)
      !> VEM stabilisation factor tau of each element (1 = the default of the
      !> element kernel); models built without it (unallocated) use 1 everywhere
      real(wp), allocatable :: elem_stab(:)
      !> reduced integration (CPE8R/CPS8R: 2 x 2 Gauss on the 8-node quad); models
      !> built without it (unallocated) use full integration everywhere
      logical, allocatable :: elem_reduced(:)
      type(source_loc_t), allocatable :: elem_loc(:)
      ! sets, materials, sections, steps
      type(named_set_t), allocatable :: nsets(:)
      type(named_set_t), allocatable :: elsets(:)
      type(material_t), allocatable :: materials(:)
      type(section_t), allocatable :: sections(:)
      !> boundary conditions and loads given before the first *STEP: they hold in every step
      type(step_t) :: initial
      type(step_t), allocatable :: steps(:)
      !> *AMPLITUDE definitions, named by AMPLITUDE= on *BOUNDARY, *CLOAD, *DLOAD, *DSLOAD
      type(amplitude_t), allocatable :: amplitudes(:)
      !> the linear solver named by *STATIC, SOLVER= (cholmod, gamg, hypre or mumps; one
      !> per run); unallocated when no step names one of them
      character(len=:), allocatable :: linear_solver
      ! contact
      type(surface_t), allocatable :: surfaces(:)
      type(interaction_t), allocatable :: interactions(:)
      type(contact_pair_t), allocatable :: pairs(:)
      type(contact_controls_t) :: controls
      !> linear constraints (*EQUATION), eliminated in the linear system; unallocated = none
      type(equation_t), allocatable :: equations(:)
      !> bonded surfaces (*TIE), turned into constraints by the driver; unallocated = none
      type(tie_t), allocatable :: ties(:)
      !> the deck has output requests: only the fields they select are written; without
      !> any, every field is written (output_requested)
      logical :: has_output_requests = .false.
      !> warnings of the deck reader, one line each ("file:line: warning: ..."), for the log
      type(string_t), allocatable :: warnings(:)
   end type model_t

contains

   !> Polynomial order of an element type: 2 for the second-order types (whose
   !> nodes are the corners, then one node per side), 1 otherwise.
   pure integer function element_order(etype)
      integer, intent(in) :: etype
      select case (etype)
      case (etype_polygon2, etype_quad8, etype_tri6)
         element_order = 2
      case default
         element_order = 1
      end select
   end function element_order

   !> Nodes of side k of element e: (corner k, corner k+1, side node or 0 for
   !> a first-order element); the element has nsides sides (its corners).
   pure subroutine element_side(model, e, k, abc, nsides)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: e
      integer, intent(in) :: k
      integer(ip), intent(out) :: abc(3)
      integer, intent(out) :: nsides
      integer(ip) :: p0
      integer :: n, order
      p0 = model%elem_ptr(e)
      n = model%elem_ptr(e + 1) - p0
      order = 1
      if (allocated(model%elem_type)) order = element_order(model%elem_type(e))
      nsides = n/order
      abc = 0
      if (k < 1 .or. k > nsides) return
      abc(1) = model%elem_conn(p0 + k - 1)
      abc(2) = model%elem_conn(p0 + mod(k, nsides))
      if (order == 2) abc(3) = model%elem_conn(p0 + nsides + k - 1)
   end subroutine element_side

   !> Index of the set called `name` (case-insensitive, caller passes upper case), 0 if absent.
   pure function find_set(sets, name) result(k)
      type(named_set_t), intent(in) :: sets(:)
      character(len=*), intent(in) :: name
      integer :: k
      do k = 1, size(sets)
         if (sets(k)%name == name) return
      end do
      k = 0
   end function find_set

   !> Whether result field `name` (upper case, e.g. 'U', 'S', 'RF', 'CPRESS') is to be
   !> written to the result files (VTU, HDF5) of step `istep`: always when the deck has no
   !> output requests, else when a file request (not a PRINT) in force in the step selects it.
   pure function output_requested(model, istep, name) result(yes)
      type(model_t), intent(in) :: model
      integer, intent(in) :: istep
      character(len=*), intent(in) :: name
      logical :: yes
      integer :: k, j
      yes = .not. model%has_output_requests
      if (yes) return
      if (.not. allocated(model%steps)) return
      if (istep < 1 .or. istep > size(model%steps)) return
      if (.not. allocated(model%steps(istep)%outputs)) return
      do k = 1, size(model%steps(istep)%outputs)
         associate (r => model%steps(istep)%outputs(k))
            if (r%print .or. .not. allocated(r%fields)) cycle
            do j = 1, size(r%fields)
               if (r%fields(j)%s == name) yes = .true.
            end do
         end associate
      end do
   end function output_requested

   !> "file:line" for messages.
   pure function location_string(model, loc) result(s)
      type(model_t), intent(in) :: model
      type(source_loc_t), intent(in) :: loc
      character(len=:), allocatable :: s
      character(len=16) :: buf
      if (loc%file < 1 .or. .not. allocated(model%files)) then
         s = '<unknown>'
         return
      end if
      if (loc%file > size(model%files)) then
         s = '<unknown>'
         return
      end if
      write (buf, '(i0)') loc%line
      s = model%files(loc%file)%s//':'//trim(buf)
   end function location_string
end module vemcontact_model
