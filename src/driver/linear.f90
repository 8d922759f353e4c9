!> The linear system of a model and its solution for a given load state.
!>
!> `setup` builds the pattern, assembles the stiffness and runs CHOLMOD's symbolic
!> analysis once; `solve_state` imposes a state's prescribed displacements, pays a
!> numeric factorization only when the set of fixed dofs differs from the one last
!> factorized (the matrix does not depend on the prescribed values), and solves.
!> Contact will add its springs to the same pattern and reuse the analysis.
module vemcontact_driver_linear
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_solver
   use vemcontact_model, only: model_t
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: build_pattern
   use vemcontact_solver_cholmod, only: cholmod_solver_t
   use vemcontact_solver_ordering, only: node_graph_from_elements, nodal_metis_ordering
   use vemcontact_driver_validate, only: validate_elements
   use vemcontact_driver_supports, only: find_parts, check_supports, unused_nodes
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_driver_assembly, only: assemble_stiffness, assemble_loads
   use vemcontact_driver_dirichlet, only: apply_dirichlet, constrain_rhs, constrain_matrix
   use vemcontact_clock, only: wall_time
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_search, only: merge_node_pairs
   use vemcontact_sparse_matvec, only: sym_matvec
   use vemcontact_log, only: logger_t
   implicit none
   private

   public :: linear_system_t

   !> What the contact part of the matrix depends on.
   type :: contact_key_t
      logical, allocatable :: active(:)
      integer(ip), allocatable :: iseg(:)
      real(wp), allocatable :: xi(:), normal(:, :), geo_weight(:)
   end type contact_key_t

   integer, parameter, public :: ordering_auto = 0, ordering_metis = 1, ordering_cholmod = 2
   !> CHOLMOD's reciprocal condition estimate below which results lose accuracy
   !> (relative errors of about eps/rcond: 1e-7 and worse) and a warning is logged,
   !> and below which the run stops: at 1e-12 the round-off in the contact gaps
   !> exceeds the overclosures, so the active set only cycles on noise (seen in a
   !> penalty sweep on two blocks, K from 1e2 to 1e18 E/h: relative pressure errors
   !> 1e-14, 1e-10, 2e-6 and 4e-4 at K = 1e2, 1e6, 1e8 and 1e10 E/h, then cycling;
   !> postprocess/tests/test_contact.py locks this in).
   real(wp), parameter, public :: rcond_warn = 1.0e-9_wp, rcond_stop = 1.0e-12_wp
   !> The stop when closed springs stiffer than the elastic entries set the
   !> conditioning.  The contact pressure is K times an overclosure that is a tiny
   !> difference of displacements, so it loses accuracy faster than the displacements:
   !> in the penalty sweep (docs/stability-penalty.md, blocks, K h/E = 1e0..1e16) the
   !> pressure error is 7e-7 at rcond 4e-10, 9e-4 at 4e-11 and 6e-2 at 4e-12 (the
   !> tributary mean on non-matching meshes 3e-3 at 6e-11), while the displacement
   !> estimate eps/rcond says 5e-5.  Stopping below 1e-10 keeps every answer given
   !> within 1e-3.  Weaker springs (a contrast of materials) keep rcond_stop: there the
   !> answers stay exact down to it (docs/stability-contact.md).
   real(wp), parameter, public :: rcond_stop_penalty = 1.0e-10_wp
   !> Below this many nodes CHOLMOD's own ordering is cheap and as good; above it,
   !> METIS on the node graph avoids ordering the four times larger dof graph.
   integer, parameter :: metis_threshold = 5000
   !> Sufficient-decrease constant of the contact line search (energy_step).  On the
   !> Hertz decks (inputs/hertz_*) and the refined meshes of bench/hertz_refined.toml,
   !> c = 0.15 to 0.3 gives 3-4 iterations everywhere; the exact minimum (c = 0.5)
   !> gives 5 on the paper decks (growth by one node per iteration), the longest
   !> decreasing step (c = 1e-4, about 2 t*) 5 on the refined ones
   !> (docs/contact-robustness.md).
   real(wp), parameter :: armijo = 0.25_wp

   type :: linear_system_t
      type(sym_csc_t) :: k                        !< assembled stiffness, no constraints
      type(sym_csc_t) :: kb                       !< with the constraints of the last factorization
      type(cholmod_solver_t) :: solver
      integer(ip), allocatable :: part(:)         !< part (connected body) of each node
      integer(ip) :: nparts = 0
      logical, allocatable :: unused(:)           !< nodes of no element
      logical, allocatable :: factored_fixed(:)   !< fixed dofs of the current factor
      logical :: factored = .false.
      ! phase timings of the last call, seconds
      real(wp) :: t_pattern = 0, t_assemble = 0, t_analyze = 0, t_factorize = 0, t_solve = 0
      !> contact search of the last solve_state: pairing every slave node with its
      !> master segment (grid build, queries, gaps) and the new active set, summed
      !> over the projections of the iterations (the first one included)
      real(wp) :: t_search = 0
      !> of t_pattern, the search for the candidate node pairs of the pattern
      real(wp) :: t_candidates = 0
      logical :: refactorized = .false.           !< whether the last solve_state factorized
      integer :: ordering = 0
      integer :: iterations = 0                   !< contact iterations of the last solve_state
      integer :: factorizations = 0               !< numeric factorizations of the last solve_state
      integer :: pattern_builds = 0
      !> contact matrix of the current factor: active set, pairing and geometric
      !> weights, so that an iteration that changes none of them (the augmentation of
      !> HARD contact, a small-sliding pairing that holds) only solves again
      type(contact_key_t) :: factored_key
   contains
      procedure :: setup
      procedure :: solve_state
      procedure, private :: build_system
      procedure, private :: solve_contact
   end type linear_system_t

contains

   !> Validate, find the parts, build the pattern (covering the contact candidates
   !> of `contact` at the undeformed state), assemble and analyze.
   subroutine setup(self, model, ordering, error, contact)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      integer, intent(in) :: ordering
      type(error_t), allocatable, intent(out) :: error
      type(contact_state_t), intent(in), optional :: contact
      real(wp), allocatable :: u0(:)
      call validate_elements(model, error)
      if (allocated(error)) return
      self%unused = unused_nodes(model)
      call find_parts(model, self%part, self%nparts)
      self%ordering = ordering
      allocate (u0(2*model%nnode), source=0.0_wp)
      call self%build_system(model, error, contact, u0)
   end subroutine setup

   !> Pattern (element graph plus contact candidate pairs at displacements u),
   !> stiffness and symbolic analysis.
   subroutine build_system(self, model, error, contact, u)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      type(contact_state_t), intent(in), optional :: contact
      real(wp), intent(in) :: u(:)
      integer(i8), allocatable :: adj_ptr(:), ptr2(:)
      integer(ip), allocatable :: adj(:), adj2(:), perm(:), extra(:, :)
      real(wp) :: t0, t1

      t0 = wall_time()
      self%t_candidates = 0
      call node_graph_from_elements(model%nnode, model%elem_ptr, model%elem_conn, adj_ptr, adj, error)
      if (allocated(error)) return
      if (present(contact)) then
         if (contact%n > 0) then
            t1 = wall_time()
            call contact%graph_pairs(model, u, extra, error)
            if (allocated(error)) return
            self%t_candidates = wall_time() - t1
            call merge_node_pairs(model%nnode, adj_ptr, adj, extra, ptr2, adj2, error)
            if (allocated(error)) return
            call move_alloc(ptr2, adj_ptr)
            call move_alloc(adj2, adj)
         end if
      end if
      call build_pattern(model%nnode, adj_ptr, adj, self%k)
      self%pattern_builds = self%pattern_builds + 1
      self%t_pattern = wall_time() - t0

      t0 = wall_time()
      call assemble_stiffness(model, self%k, error)
      if (allocated(error)) return
      self%t_assemble = wall_time() - t0

      t0 = wall_time()
      call self%solver%release()
      if (self%ordering == ordering_metis .or. &
          (self%ordering == ordering_auto .and. model%nnode >= metis_threshold)) then
         allocate (perm(2*model%nnode))
         call nodal_metis_ordering(model%nnode, adj_ptr, adj, perm, error)
         if (allocated(error)) return
         call self%solver%analyze(self%k, error, perm)
      else
         call self%solver%analyze(self%k, error)
      end if
      if (allocated(error)) return
      self%t_analyze = wall_time() - t0
      self%factored = .false.
   end subroutine build_system

   !> Solve for the displacements u(2*nnode) of a load state.
   !> With `contact`, the active-set iteration of solve_contact; `u` then holds
   !> the previous state on entry (the pairing starts from it) and the new one on exit.
   subroutine solve_state(self, model, st, u, error, contact, log)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(load_state_t), intent(in) :: st
      real(wp), intent(inout) :: u(:)
      type(error_t), allocatable, intent(out) :: error
      type(contact_state_t), intent(inout), optional :: contact
      type(logger_t), intent(in), optional :: log
      logical, allocatable :: fixed(:)
      real(wp), allocatable :: f(:)
      real(wp) :: t0
      logical :: warned
      self%iterations = 0
      self%factorizations = 0
      self%t_search = 0
      if (present(contact)) then
         if (contact%n > 0) then
            call self%solve_contact(model, st, u, contact, error, log)
            return
         end if
      end if
      fixed = st%fixed
      ! nodes of no element carry nothing: hold them so the matrix stays regular
      fixed(1::2) = fixed(1::2) .or. self%unused
      fixed(2::2) = fixed(2::2) .or. self%unused
      allocate (f(size(u)))
      call assemble_loads(model, st%force, st%dload, f)
      self%refactorized = .false.
      self%t_factorize = 0
      if (.not. self%factored) then
         self%refactorized = .true.
      else
         self%refactorized = any(fixed .neqv. self%factored_fixed)
      end if
      if (self%refactorized) then
         call check_supports(model, self%part, self%nparts, fixed, error)
         if (allocated(error)) return
         call copy_values(self%k, self%kb)
         call apply_dirichlet(self%kb, fixed, st%prescribed, f)
         t0 = wall_time()
         call self%solver%factorize(self%kb, error)
         if (allocated(error)) return
         self%t_factorize = wall_time() - t0
         self%factorizations = 1
         warned = .false.
         call check_conditioning(self%solver%rcond(), 0.0_wp, .false., warned, error, log)
         if (allocated(error)) return
         self%factored_fixed = fixed
         self%factored = .true.
         self%factored_key = contact_key_t()
      else
         ! same constraints: only the right-hand side changes (kb is already reduced,
         ! so the known values are moved with the unreduced stiffness)
         call constrain_rhs(self%k, fixed, st%prescribed, f)
      end if
      t0 = wall_time()
      call self%solver%solve(f, u, error)
      if (allocated(error)) return
      self%t_solve = wall_time() - t0
      if (.not. all(abs(u) <= huge(1.0_wp))) then
         call fatal_error(error, 'error: the solution has NaN or infinite values: the model is '// &
                          'numerically singular', err_solver)
         return
      end if
   end subroutine solve_state

   !> Active-set iterations of the penalty contact problem for one load state.
   subroutine solve_contact(self, model, st, u, contact, error, log)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(load_state_t), intent(in) :: st
      real(wp), intent(inout) :: u(:)
      type(contact_state_t), intent(inout) :: contact
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(in), optional :: log
      logical, allocatable :: fixed(:), history(:, :), hold(:), held(:)
      integer(ip), allocatable :: iseg_start(:)
      real(wp), allocatable :: fext(:), f(:), ku(:), fc(:), r(:), u0(:), gaps(:, :), gfrozen(:)
      real(wp) :: t0, rel, scale, kmax, t_iter, t_fact, t_srch, step, rc_min, gap_tol, overclosure, change
      logical :: warned, cut, newton_solve, same_matrix
      real(wp) :: rel_prev
      integer :: it, nchanged, maxit, j, nrise
      logical :: ok
      character(len=160) :: buf

      fixed = st%fixed
      fixed(1::2) = fixed(1::2) .or. self%unused
      fixed(2::2) = fixed(2::2) .or. self%unused
      allocate (fext(size(u)), f(size(u)), ku(size(u)), fc(size(u)), r(size(u)))
      call assemble_loads(model, st%force, st%dload, fext)
      maxit = model%controls%max_iterations
      warned = .false.
      kmax = 0.0_wp
      do j = 1, self%k%n
         kmax = max(kmax, abs(self%k%val(self%k%col_ptr(j + 1) - 1)))
      end do
      allocate (history(contact%n, 0:maxit), gaps(contact%n, 0:maxit), gfrozen(contact%n))
      allocate (held(contact%n), source=.false.)
      rc_min = 1.0_wp
      self%refactorized = .false.
      rel_prev = huge(1.0_wp)
      nrise = 0
      call contact%set_geometric(.true.)
      ! start from the state left by the previous step (or the undeformed one)
      t0 = wall_time()
      call contact%project(model, u, error)
      if (allocated(error)) return
      call contact%update_active(nchanged)
      self%t_search = wall_time() - t0
      iseg_start = contact%iseg
      history(:, 0) = contact%active
      gaps(:, 0) = merge(contact%gap, 0.0_wp, contact%iseg > 0)
      self%t_factorize = 0
      self%t_solve = 0
      if (present(log)) call log%say('  iter  active  changed     residual  max penetration  max pressure'// &
                                     '    time [s]  factorize [s]  search [s]    step')
      do it = 1, maxit
         self%iterations = it
         t_iter = wall_time()
         call copy_values(self%k, self%kb)
         call contact%add_stiffness(self%kb, ok)
         if (.not. ok) then
            ! the pairing left the candidate pairs of the pattern: new pattern and analysis
            call self%build_system(model, error, contact, u)
            if (allocated(error)) return
            if (present(log)) call log%say('        (contact pairs moved: matrix pattern rebuilt)')
            call copy_values(self%k, self%kb)
            call contact%add_stiffness(self%kb, ok)
            if (.not. ok) then
               call fatal_error(error, 'internal error: contact spring outside the rebuilt pattern', err_solver)
               return
            end if
         end if
         f = fext
         call contact%add_rhs(f)
         call check_supports(model, self%part, self%nparts, fixed, error, contact%springs(model, self%part))
         if (allocated(error)) return
         call constrain_rhs(self%kb, fixed, st%prescribed, f)
         call constrain_matrix(self%kb, fixed)
         newton_solve = contact%newton()
         ! the matrix of the current factor: solve again without factorizing
         same_matrix = self%factored
         if (same_matrix) same_matrix = .not. any(fixed .neqv. self%factored_fixed)
         if (same_matrix) same_matrix = same_key(self%factored_key, contact)
         t_fact = 0.0_wp
         if (.not. same_matrix) then
            t0 = wall_time()
            call self%solver%factorize(self%kb, error)
            if (allocated(error) .and. newton_solve) then
               ! the indefinite geometric part tipped the matrix: go on without it
               deallocate (error)
               self%factored = .false.
               call geometric_off('the matrix with it is not positive definite')
               cycle
            end if
            if (allocated(error)) then
               ! a penalty stiff enough to swamp the elastic stiffness loses positive
               ! definiteness to round-off: say so in the model's terms
               if (any(contact%active)) error%message = 'error: with the closed contact springs the '// &
                  'stiffness matrix is not positive definite in floating point ('//error%message//')'// &
                  new_line('a')//conditioning_hint(maxval(contact%k, mask=contact%active)/kmax)
               return
            end if
            t_fact = wall_time() - t0
            self%factorizations = self%factorizations + 1
            call check_conditioning(self%solver%rcond(), maxval(contact%k, mask=contact%active, dim=1)/kmax, &
                                    any(contact%active), warned, error, log)
            if (allocated(error)) return
            if (self%solver%rcond() > 0.0_wp) rc_min = min(rc_min, self%solver%rcond())
            self%t_factorize = self%t_factorize + t_fact
            self%factored_key = key_of(contact)
         end if
         ! the start of the step, with this state's prescribed values
         u0 = merge(st%prescribed, u, fixed)
         t0 = wall_time()
         call self%solver%solve(f, u, error)
         if (allocated(error)) return
         self%t_solve = self%t_solve + (wall_time() - t0)
         if (.not. all(abs(u) <= huge(1.0_wp))) then
            call fatal_error(error, 'error: the solution has NaN or infinite values: the model is '// &
                             'numerically singular', err_solver)
            return
         end if
         self%factored = .true.
         ! one step of iterative refinement with the residual evaluated from the gaps:
         ! the backward error of the factorization is eps times the stiffest spring,
         ! which with K h/E = 1e7 leaves 2e-8 in the contact forces; the refined
         ! solve brings it to the round-off of the elastic forces
         if (.not. newton_solve) then
            call refine(u)
            if (allocated(error)) return
         end if
         self%refactorized = self%refactorized .or. .not. same_matrix
         self%factored_fixed = fixed
         ! a solve without the geometric term minimizes the frozen-pairing energy with
         ! the current springs: cut it when it overshoots into new contact
         step = 1.0_wp
         if (.not. contact%newton()) step = energy_step(self%k, contact, fext, fixed, u0, u)
         cut = step < 1.0_wp
         if (cut) u = u0 + step*(u - u0)

         ! new pairing and active set; residual of the equilibrium with them.  A closed
         ! node that the step leaves closed with the pairing it was solved with
         ! (frozen gap <= 0) but that the new pairing opens is held closed for one more
         ! solve, with the new pairing, instead of being released: its opening comes
         ! from the pairing update (the frozen gaps are exact to O(|du|^2/h) only), which
         ! with a stiff penalty exceeds the overclosure p/K.  On Hertz at K h/E >= 1e5 a
         ! large step opened up to three edge nodes this way, and the next solves closed
         ! them again one per iteration (8 iterations at 1e8, 5 with the hold).  At most
         ! once in a row per node, and it counts as a change, so a held node that is
         ! really open opens at the next projection and no run converges on a hold.
         t0 = wall_time()
         call contact%frozen_gaps(u, gfrozen)
         call contact%project(model, u, error)
         if (allocated(error)) return
         hold = contact%active .and. gfrozen <= 0.0_wp .and. contact%gap > 0.0_wp .and. .not. held
         call contact%update_active(nchanged, hold)
         held = hold .and. contact%active
         t_srch = wall_time() - t0
         self%t_search = self%t_search + t_srch
         call sym_matvec(self%k, u, ku)
         fc = 0.0_wp
         call contact%forces(fc)
         r = fext - ku - fc
         where (fixed) r = 0.0_wp
         ! normwise backward error |r| / (|K| |u| + |f|), with |K| estimated by its
         ! largest diagonal entry plus the stiffest closed spring: meaningful also
         ! when the problem is driven by prescribed displacements and carries no load
         scale = (kmax + maxval(contact%k, mask=contact%active, dim=1)*merge(1.0_wp, 0.0_wp, any(contact%active))) &
                 *norm2(u) + norm2(merge(0.0_wp, fext, fixed)) + norm2(fc)
         rel = 0.0_wp
         if (scale > 0.0_wp) rel = norm2(r)/scale
         write (buf, '(2x,i4,2x,i6,2x,i7,2x,es11.3,2x,es15.4,2x,es12.4,2x,f10.4,2x,f13.4,2x,f10.6,2x,f6.4)') it, &
            count(contact%active), nchanged, rel, contact%max_penetration(), contact%max_pressure(), &
            wall_time() - t_iter, t_fact, t_srch, step
         if (present(log)) call log%say(trim(buf))
         history(:, it) = contact%active
         gaps(:, it) = merge(contact%gap, 0.0_wp, contact%iseg > 0)
         if (nchanged == 0 .and. rel <= model%controls%residual_tol) then
            if (contact%has_hard()) then
               ! HARD: the augmented Lagrangian's Uzawa update; converged once the solve
               ! left no overclosure beyond the tolerance and the update would change no
               ! force by more than the residual tolerance (the pressures' accuracy)
               ! the gaps' round-off: a few ulps of the largest displacement
               call contact%augment(16.0_wp*epsilon(1.0_wp)*maxval(abs(u)), overclosure, change)
               if (overclosure > model%controls%overclosure_tol .or. &
                   change > model%controls%residual_tol) cycle
            end if
            call contact%set_balanced(model, ku - fext, fixed)
            call report_slid_off()
            return
         end if
         ! Newton steps that raise the residual three times in a row are far from the
         ! quadratic regime and are given up for the frozen-pairing fixed point, which
         ! converges (slowly).  On a fine structured non-matching interface at K h/E ~ 10
         ! (bench/accuracy, 1.3e5 unknowns) the first two Newton steps after the solve at
         ! the undeformed pairing raise it 25-fold with FEM quads, which then converge
         ! in 10 iterations (36 without the geometric part); with VEM quads the third
         ! step lost positive definiteness instead (caught at the factorization above).
         if (newton_solve .and. rel > rel_prev) then
            nrise = nrise + 1
         else
            nrise = 0
         end if
         if (nrise >= 3) call geometric_off('three Newton steps in a row raised the residual')
         rel_prev = rel
         ! A cycle: the active set and the gaps of an earlier iterate, up to the
         ! round-off of the solves, so that the next solves would repeat the same
         ! iterates.  That round-off is about eps / rcond of the overclosures (the
         ! relative pressure errors of the penalty sweep, rcond_stop_penalty) plus the
         ! rounding of the displacements for the open gaps.  Returning to an earlier active
         ! set alone is no cycle: every step lowers the penalty energy of its pairing
         ! (energy_step), so the iterate is a different one.  With stiff springs
         ! (K h/E >= 1e5 on Hertz) a node at the edge of the contact zone, where the
         ! exact pressure vanishes, opens after a large step only because the pairing
         ! moved (the frozen gaps are exact to O(|du|^2/h), more than the overclosure
         ! p/K), and closes again from a near-converged state: the old test, on the
         ! active set alone, stopped these runs (docs/contact-robustness.md).
         if (nchanged > 0) then
            do j = 0, it - 1
               gap_tol = 10.0_wp*epsilon(1.0_wp)*(max(0.0_wp, -minval(gaps(:, j)), -minval(gaps(:, it)))/rc_min + &
                                                  maxval(abs(u)))
               if (all(history(:, j) .eqv. contact%active) .and. &
                   all(abs(gaps(:, j) - gaps(:, it)) <= gap_tol)) then
                  write (buf, '(a,i0,a,i0)') 'error: contact iterations cycle: iteration ', it, &
                     ' returns to the active set and gaps of iteration ', j
                  call fatal_error(error, trim(buf)//' (the penalty may be too large for the mesh, or a '// &
                                   'slave node sits at the end of a master surface)', err_solver)
                  return
               end if
            end do
         end if
      end do
      write (buf, '(a,i0,a,es10.3,a)') 'error: contact iterations did not converge in ', maxit, &
         ' iterations (relative residual ', rel, ')'
      call fatal_error(error, trim(buf)//'; raise MAXIT on *CONTACT CONTROLS or check the penalty', err_solver)
   contains
      !> Slave nodes that had a master segment at the start of the step and have none at
      !> its end slid past the end of the master surface: they carry no pressure and
      !> their neighbours the load they would carry; say so, naming them.
      subroutine report_slid_off()
         integer :: i, m
         character(len=:), allocatable :: list
         contact%slid_off = iseg_start > 0 .and. contact%iseg == 0
         if (.not. any(contact%slid_off) .or. .not. present(log)) return
         list = ''
         m = 0
         do i = 1, contact%n
            if (.not. contact%slid_off(i)) cycle
            m = m + 1
            if (m <= 20) then
               write (buf, '(i0)') model%node_id(contact%node(i))
               list = list//', '//trim(buf)
            end if
         end do
         if (m > 20) list = list//', ...'
         write (buf, '(i0)') m
         call log%say('  warning: '//trim(buf)//' slave nodes slid past the end of their master surface '// &
                      'and carry no contact pressure (STATUS 2), their neighbours the load: nodes '//list(3:))
         call log%say('  = help: extend the master surface beyond the slave''s, or, when the sliding is '// &
                      'small, use SMALL SLIDING or TYPE=SURFACE TO SURFACE (pairing fixed at the start)')
      end subroutine report_slid_off

      !> u <- u + A^-1 (b - A u) with b - A u = f_ext - K u - f_c(u), the contact
      !> forces of the frozen pairing from the gaps (contact_state_t%linear_forces).
      subroutine refine(u)
         real(wp), intent(inout) :: u(:)
         real(wp), allocatable :: du(:)
         call sym_matvec(self%k, u, ku)
         fc = 0.0_wp
         call contact%linear_forces(u, fc)
         r = fext - ku - fc
         where (fixed) r = 0.0_wp
         allocate (du(size(u)))
         t0 = wall_time()
         call self%solver%solve(r, du, error)
         if (allocated(error)) return
         self%t_solve = self%t_solve + (wall_time() - t0)
         u = u + du
      end subroutine refine

      subroutine geometric_off(why)
         character(len=*), intent(in) :: why
         call contact%set_geometric(.false.)
         if (present(log)) call log%say('        (geometric contact stiffness off for this step: '//why//')')
      end subroutine geometric_off
   end subroutine solve_contact

   !> The contact matrix key of the current state.
   pure function key_of(contact) result(key)
      type(contact_state_t), intent(in) :: contact
      type(contact_key_t) :: key
      key%active = contact%active
      key%iseg = contact%iseg
      key%xi = contact%xi
      key%normal = contact%normal
      key%geo_weight = contact%geo_weight
   end function key_of

   !> Whether the contact part of the matrix is that of `key`: same active set and,
   !> for the active entries, the same pairing and geometric weights.
   pure logical function same_key(key, contact) result(same)
      type(contact_key_t), intent(in) :: key
      type(contact_state_t), intent(in) :: contact
      integer :: i
      same = allocated(key%active)
      if (.not. same) return
      same = size(key%active) == contact%n
      if (.not. same) return
      same = all(key%active .eqv. contact%active)
      if (.not. same) return
      do i = 1, contact%n
         if (.not. contact%active(i)) cycle
         ! the geometric part also depends on the gaps: a Newton matrix is never reused
         same = key%iseg(i) == contact%iseg(i) .and. key%xi(i) == contact%xi(i) .and. &
                all(key%normal(:, i) == contact%normal(:, i)) .and. key%geo_weight(i) == 0.0_wp .and. &
                contact%geo_weight(i) == 0.0_wp
         if (.not. same) return
      end do
   end function same_key

   !> Length t in (0, 1] of the step from u0 to u1, the solve with the pairing
   !> frozen and the springs of u0's active set, on the penalty energy
   !>   E(t) = 1/2 v^T K v - fext^T v + sum_s 1/2 k_s <-g_s(v)>^2,  v = u0 + t (u1 - u0),
   !> whose gaps g_s are linear in v (frozen pairing): E is convex and piecewise
   !> quadratic along the line, and the solve minimizes it with u0's springs only.
   !> When nodes outside that set penetrate at u1, the full step overshoots: in the
   !> first iteration of a curved contact one node holds the whole load and the body
   !> sinks 0.3-0.6 where the true approach is 1e-3, the next active set is twice
   !> the true one and is peeled back one ring per iteration.  The step is then cut
   !> to the longest t past the minimum t* of E with sufficient decrease (Armijo),
   !> E(t) <= E(0) + c t E'(0), c = `armijo`; that is about 1.5 t* (2 (1 - c) t* on
   !> a quadratic), so the newly closing nodes penetrate a little: at t* alone the
   !> active set grows one node per iteration from below on coarse meshes.  A step
   !> that closes no new node stays 1 (opening springs only lower E), so a settled
   !> active set converges as before.
   function energy_step(k, contact, fext, fixed, u0, u1) result(t)
      type(sym_csc_t), intent(in) :: k
      type(contact_state_t), intent(in) :: contact
      real(wp), intent(in) :: fext(:), u0(:), u1(:)
      logical, intent(in) :: fixed(:)
      real(wp) :: t
      real(wp), allocatable :: d(:), kd(:), ku(:), g0(:), h(:)
      real(wp) :: a, b, lo, hi, e0
      integer :: it
      t = 1.0_wp
      allocate (g0(contact%n), h(contact%n))
      call contact%frozen_gaps(u0, g0)
      call contact%frozen_gaps(u1, h)
      ! HARD entries push with max(0, lambda - k g) = k <-(g - lambda/k)>: the energy
      ! of the augmented Lagrangian is that of the penalty with the gaps shifted
      where (g0 < huge(1.0_wp) .and. contact%k > 0.0_wp)
         g0 = g0 - contact%lambda/contact%k
         h = h - contact%lambda/contact%k
      end where
      ! E'(1) = sum over the solve's springs open at u1 of -k g(1) (g(1) - g(0)) plus
      ! sum over the other nodes closed at u1 of k g(1) (g(1) - g(0)): with no new
      ! contact and every spring closed at u0, E'(1) <= 0 and the full step stands,
      ! without the two products with K below (every iteration of a settled active set)
      if (.not. any(contact%active .neqv. g0 <= 0.0_wp) .and. &
          .not. any(.not. contact%active .and. h < 0.0_wp)) return
      d = merge(0.0_wp, u1 - u0, fixed)
      allocate (kd(size(d)), ku(size(d)))
      call sym_matvec(k, d, kd)
      call sym_matvec(k, u0, ku)
      a = dot_product(d, ku - fext)
      b = dot_product(d, kd)
      where (g0 < huge(1.0_wp))
         h = h - g0
      elsewhere
         h = 0.0_wp
      end where
      ! E'(1) <= 0: the minimum along the line is at or beyond the full step;
      ! E'(0) >= 0: no descent (round-off at convergence), keep the solve
      if (slope(1.0_wp) <= 0.0_wp .or. slope(0.0_wp) >= 0.0_wp) return
      ! E' is continuous, piecewise linear and nondecreasing: bisect to its root
      lo = 0.0_wp
      hi = 1.0_wp
      do it = 1, 60
         t = 0.5_wp*(lo + hi)
         if (slope(t) > 0.0_wp) then
            hi = t
         else
            lo = t
         end if
      end do
      ! the longest step with sufficient decrease, E(t) <= E(0) + c t E'(0), between
      ! the minimum and 1: E(t) - c t E'(0) is convex, <= 0 at the minimum
      e0 = slope(0.0_wp)
      if (energy(1.0_wp) <= armijo*e0) then
         t = 1.0_wp
         return
      end if
      lo = hi
      hi = 1.0_wp
      do it = 1, 60
         t = 0.5_wp*(lo + hi)
         if (energy(t) <= armijo*t*e0) then
            lo = t
         else
            hi = t
         end if
      end do
      t = lo
   contains
      real(wp) function energy(s)
         real(wp), intent(in) :: s
         energy = s*a + 0.5_wp*s*s*b + 0.5_wp*sum(contact%k*(min(g0 + s*h, 0.0_wp)**2 - min(g0, 0.0_wp)**2))
      end function energy
      real(wp) function slope(s)
         real(wp), intent(in) :: s
         slope = a + s*b + sum(contact%k*h*min(g0 + s*h, 0.0_wp))
      end function slope
   end function energy_step

   !> Stop when the factor is too ill-conditioned to trust, warn (once) when it
   !> costs accuracy; `ratio` is the stiffest closed spring over the largest
   !> elastic diagonal entry, the usual culprit when contact is closed.
   subroutine check_conditioning(rc, ratio, contact_closed, warned, error, log)
      real(wp), intent(in) :: rc, ratio
      logical, intent(in) :: contact_closed
      logical, intent(inout) :: warned
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(in), optional :: log
      character(len=120) :: buf
      logical :: penalty_bound
      if (rc < 0.0_wp) return            ! no estimate available
      ! the springs are the culprit only when they are stiffer than the elastic
      ! entries; weaker springs (a soft body on a stiff one: 5e-10 at contrast
      ! 1e-12, docs/stability-contact.md) point at the materials instead
      penalty_bound = contact_closed .and. ratio >= 1.0_wp
      if (rc < rcond_stop .or. (penalty_bound .and. rc < rcond_stop_penalty)) then
         write (buf, '(a,es9.2,a)') 'error: the system is too ill-conditioned to solve accurately '// &
            '(CHOLMOD''s reciprocal condition estimate ', rc, ')'
         if (penalty_bound) then
            call fatal_error(error, trim(buf)//new_line('a')//conditioning_hint(ratio), err_solver)
         else
            call fatal_error(error, trim(buf)//new_line('a')//'  = help: look for materials whose moduli '// &
                             'differ by many orders of magnitude, nearly incompressible materials '// &
                             '(nu close to 0.5) or degenerate elements', err_solver)
         end if
      else if (rc < rcond_warn .and. .not. warned .and. present(log)) then
         write (buf, '(a,es9.2,a,es9.2,a)') '  warning: ill-conditioned system (rcond ', rc, &
            '): results may carry relative errors of about ', epsilon(1.0_wp)/rc, ' and more'
         call log%say(trim(buf))
         warned = .true.
      end if
   end subroutine check_conditioning

   pure function conditioning_hint(ratio) result(s)
      real(wp), intent(in) :: ratio
      character(len=:), allocatable :: s
      character(len=16) :: b
      write (b, '(es9.2)') ratio
      s = '  = help: the stiffest closed contact spring is '//trim(adjustl(b))//' times the largest '// &
          'elastic stiffness entry; lower the penalty slope K on *SURFACE BEHAVIOR (K*h/E of 10 to 1e4 '// &
          'already keeps the overclosure below 1e-4 of the element size h)'
   end function conditioning_hint

   !> b = a, copying only the values when b already has a's pattern (the common
   !> case in the contact iterations: the pattern is fixed, the values change).
   subroutine copy_values(a, b)
      type(sym_csc_t), intent(in) :: a
      type(sym_csc_t), intent(inout) :: b
      logical :: same
      same = allocated(b%val) .and. b%n == a%n
      if (same) same = size(b%val) == size(a%val)
      if (same) same = all(b%col_ptr == a%col_ptr)
      if (same) then
         b%val = a%val
      else
         b = a
      end if
   end subroutine copy_values
end module vemcontact_driver_linear
