!> The contact iteration of one load state: active set, pairing, line search and,
!> for HARD contact, the augmented Lagrangian's updates, until the equilibrium with
!> the contact forces holds.
!>
!> The iteration needs a linear system that can take the contact terms; the
!> driver's linear system (vemcontact_driver_linear) provides it by extending
!> `contact_system_t`, whose components keep what the iteration must remember
!> across load states (the contact matrix of the current factor) and report (the
!> counts, timings and the records of every iteration, written to the results as
!> the paper's Table 1).  The formulation (node to segment, node to node after the
!> interface node insertion, LINEAR or HARD) is the contact state's business
!> (vemcontact_contact_active_set): the iteration is the same for all.  Its rules
!> are the pure functions of vemcontact_contact_rules.
module vemcontact_contact_iteration
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, fatal_error, err_solver
   use vemcontact_model, only: model_t
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_rules, only: matrix_key_t, key_of, same_key, line_search_step, needs_line_search, &
                                       hold_nodes, is_cycle, conditioning_verdict, &
                                       conditioning_hint, residual_norm, cond_ok, cond_warn, &
                                       near_key, pairing_drift, stick_flips, max_stick_flips, &
                                       cond_stop, cond_stop_penalty, nonconvergence_hint, multiplier_cg_limit
   use vemcontact_linalg_gmres, only: linear_operator_t, gmres, gmres_result_t
   use vemcontact_linalg_norms, only: safe_norm2
   use vemcontact_linalg_cg, only: pcg, cg_result_t
   use vemcontact_contact_condensed, only: compliance_cache_t, woodbury_t, same_pairing, scatter_rows, store_columns, &
                                           build_woodbury, woodbury_rhs, woodbury_correction, contact_compliance, &
                                           row_normal, row_tangent
   use vemcontact_contact_friction, only: tangent_stick, tangent_slip
   use vemcontact_linalg_lapack, only: dgetrf, dgetrs
   use vemcontact_log, only: logger_t
   use vemcontact_clock, only: wall_time
   use vemcontact_interrupt, only: interrupt_error, is_interrupt
   use vemcontact_solver_stop, only: agreed_stop_signal
   implicit none
   private

   public :: contact_system_t, iteration_record_t, solve_contact, judge_conditioning

   !> GMRES restart length and iteration limit of a solve (krylov_solve): with the
   !> factor of the matrix itself one or two iterations do; with the sliding part of
   !> the tangent or a factor of a nearby pairing, 3-10 were measured
   !> (docs/contact-robustness.md); a factor too far away stalls early instead.
   integer, parameter :: gmres_restart = 10, gmres_maxit = 30
   !> Renewals of the stepwise pairings within one load state (repair_stepwise): a
   !> slide over one more master segment each
   integer, parameter :: max_repairs = 4
   !> The largest multiplier step of contact_newton relative to the contact forces
   !> (force_scale) taken as a Newton step
   real(wp), parameter :: newton_jump = 1.0e3_wp
   !> ... and with friction, for a solve with the factor of earlier stick/slip states:
   !> each slipping entry's force follows its normal force (an unsymmetric rank-one
   !> term per slipping entry, which the factor lacks) and each stick/slip change
   !> since the factor is a rank-one term more; on the dam (23-36 slipping entries of
   !> 43) restarts every 10 iterations stalled with a few changes, and each stall cost
   !> a factorization (3 per step); with 30 and 60, 1-2 per step (bench/friction_cost.py,
   !> docs/performance.md).  The solves with the factor of the current states keep 10
   !> and 30.
   integer, parameter :: gmres_restart_friction = 30, gmres_maxit_friction = 60
   !> ... going on below the round-off floor (a hundred times lower for them,
   !> krylov_solve) while each iteration still lowers the residual by a tenth
   real(wp), parameter :: gmres_stall_friction = 0.9_wp
   !> The reduction of the residual a solve aims at (krylov_solve)
   real(wp), parameter :: gmres_reduction = 1.0e-6_wp
   !> ... and with slipping friction: the solve then is the frozen system itself (not
   !> a Newton step on the pairing), so it is solved to its round-off floor, as the
   !> direct solve's refinement does (at 1e-6 the slip patch test stopped at 1e-7 of
   !> the stresses, within the residual tolerance)
   real(wp), parameter :: gmres_reduction_friction = 1.0e-14_wp
   !> ... and a product by the compliance with finite sliding (compliance_apply): the
   !> stiff modes that the multiplier step resolves are 1e-3 to 1e-6 of the soft ones.
   !> On the soft curved master of docs/contact-robustness.md 1e-6 cost two more
   !> iterations (11 against 9), 1e-10 two more GMRES iterations per product than 1e-8
   real(wp), parameter :: multiplier_reduction = 1.0e-8_wp
   !> The multiplier step's conjugate gradients stop when every gap it leaves is within
   !> this fraction of its round-off (gap_noise), which the convergence test accepts:
   !> a step that stops at the round-off itself leaves the stiff modes' forces
   !> undetermined by what a gap of 1e-12 is worth to them (a soft curved master on
   !> a stiff slave: CPRESS 5e-6 apart, 6e-8 of the peak, between two augmentation
   !> stiffnesses; 3e-7 with the sixteenth, at 1-2 more products per step)
   real(wp), parameter :: multiplier_aim = 1.0_wp/16.0_wp
   !> The relative residual (residual_norm) a condensed solve must reach, else the
   !> system is factorized: its refined solves reach the round-off of the direct
   !> solve, 1e-16 to 1e-14
   real(wp), parameter :: condensed_tol = 1.0e-12_wp
   !> ... and below which its first pass needs no refinement (the round-off of the
   !> residual's evaluation, 1e-17 to 1e-16 on the bench of bench/friction_cost.py)
   real(wp), parameter :: condensed_refined = 1.0e-15_wp
   !> Columns of the contact compliance solved together (add_columns): at most
   !> condensed_block_values numbers per block array, 4 to 64 columns
   integer, parameter :: condensed_block_values = 16000000, condensed_block_min = 4, condensed_block_max = 64
   !> The rounds of settle_states per iteration: each is one return mapping of the
   !> states at the contact dofs of the frozen solution, at the cost of two dense
   !> solves with the factor's trailing block
   integer, parameter :: settle_rounds = 8

   !> One iteration, as logged and written to the results.
   type :: iteration_record_t
      integer :: iteration = 0
      integer :: active = 0              !< closed slave entries after the iteration
      integer :: changed = 0             !< entries whose state changed (holds included)
      integer :: slip_changes = 0        !< frictional entries whose stick/slip state changed
      real(wp) :: residual = 0.0_wp      !< relative residual (residual_norm)
      real(wp) :: penetration = 0.0_wp   !< largest overclosure
      real(wp) :: pressure = 0.0_wp      !< largest contact pressure
      real(wp) :: step = 1.0_wp          !< line search step
      logical :: factorized = .false.    !< a numeric factorization was paid
      logical :: rebuilt = .false.       !< the matrix pattern was rebuilt (pairs left it)
      real(wp) :: time = 0.0_wp          !< wall time of the iteration, s
   end type iteration_record_t

   !> A linear system that takes contact terms: the operations the iteration needs,
   !> and what it keeps across load states.
   type, abstract :: contact_system_t
      !> the fixed dofs and the contact matrix of the current factor
      logical :: factored = .false.
      logical, allocatable :: factored_fixed(:)
      type(matrix_key_t) :: factored_key
      ! of the last solve_contact
      integer :: iterations = 0
      integer :: factorizations = 0
      logical :: refactorized = .false.
      !> the last numeric_factorize failed on a pivot that was not positive (a direct
      !> solver's finding that the matrix is not positive definite in floating point)
      logical :: pivot_failed = .false.
      !> the contact-space paths off (condensed_solve, contact_newton): the plain
      !> multiplier updates and GMRES, as solve_contact's second try
      logical :: plain = .false.
      real(wp) :: t_factorize = 0, t_solve = 0, t_search = 0
      !> of the last solve_contact: the contact compliance columns solved (add_columns)
      !> and their time (part of t_solve)
      integer :: columns = 0
      !> the last solve_columns read the factor's trailing block (x exact at the
      !> contact dofs, zero elsewhere): set by the systems that can
      logical :: columns_local = .false.
      real(wp) :: t_columns = 0
      type(iteration_record_t), allocatable :: records(:)
      !> the contact compliance columns computed with the current factor
      !> (vemcontact_contact_condensed), kept across load states with the factor
      type(compliance_cache_t) :: cache
   contains
      !> x(:, c) = A^-1 b(:, c) with the current factor, for columns c of contact rows,
      !> at least at the contact nodes (by default one solve_system per column; a
      !> direct solver solves them together, or reads them from its trailing block)
      procedure :: solve_columns
      procedure(contact_matrix_i), deferred :: contact_matrix
      procedure(factorize_i), deferred :: numeric_factorize
      procedure(rcond_i), deferred :: rcond
      procedure(solve_i), deferred :: solve_system
      procedure(times_i), deferred :: elastic_times
      procedure(kmax_i), deferred :: largest_elastic_diagonal
   end type contact_system_t

   abstract interface
      !> The matrix K + the contact stiffness of `contact` and the right-hand side
      !> f = fext + the contact terms, both with the constraints `fixed` (values
      !> `prescribed`); the matrix pattern is rebuilt (rebuilt = .true.) when the
      !> pairing left it; an error when a part floats with the closed springs.
      subroutine contact_matrix_i(self, model, contact, u, fixed, prescribed, fext, f, rebuilt, error)
         import :: contact_system_t, model_t, contact_state_t, wp, error_t
         class(contact_system_t), intent(inout) :: self
         type(model_t), intent(in) :: model
         type(contact_state_t), intent(in) :: contact
         real(wp), intent(in) :: u(:), prescribed(:), fext(:)
         logical, intent(in) :: fixed(:)
         real(wp), intent(out) :: f(:)
         logical, intent(out) :: rebuilt
         type(error_t), allocatable, intent(out) :: error
      end subroutine contact_matrix_i
      !> Numeric factorization of the last contact_matrix.
      subroutine factorize_i(self, error)
         import :: contact_system_t, error_t
         class(contact_system_t), intent(inout) :: self
         type(error_t), allocatable, intent(out) :: error
      end subroutine factorize_i
      !> Reciprocal condition estimate of the factor (< 0: none).
      real(wp) function rcond_i(self)
         import :: contact_system_t, wp
         class(contact_system_t), intent(in) :: self
      end function rcond_i
      !> u = A^-1 f with the current factor.
      subroutine solve_i(self, f, u, error)
         import :: contact_system_t, wp, error_t
         class(contact_system_t), intent(inout) :: self
         real(wp), intent(in) :: f(:)
         real(wp), intent(inout) :: u(:)
         type(error_t), allocatable, intent(out) :: error
      end subroutine solve_i
      !> ku = K u with the elastic stiffness (no contact, no constraints).
      subroutine times_i(self, u, ku)
         import :: contact_system_t, wp
         class(contact_system_t), intent(in) :: self
         real(wp), intent(in) :: u(:)
         real(wp), intent(out) :: ku(:)
      end subroutine times_i
      !> The largest diagonal entry of the elastic stiffness.
      real(wp) function kmax_i(self)
         import :: contact_system_t, wp
         class(contact_system_t), intent(in) :: self
      end function kmax_i
   end interface

   !> The condensed compliance S = A M^-1 A^T of the HARD entries at the system's
   !> current factor M (multiplier_step), preconditioned by their springs k.
   type, extends(linear_operator_t) :: compliance_t
      class(contact_system_t), pointer :: sys => null()
      type(contact_state_t), pointer :: contact => null()
      logical, pointer :: fixed(:) => null()
      logical, allocatable :: mask(:)
      !> the solves are Newton steps on the pairing of finite sliding (contact_tangent_t)
      logical :: sliding = .false.
   contains
      procedure :: apply => compliance_apply
      procedure :: precondition => compliance_precondition
   end type compliance_t

   !> The tangent of the contact iteration on the free dofs (identity on the fixed
   !> ones): the elastic stiffness, the contact springs and, for a Newton step on the
   !> pairing of finite sliding, the sliding part; preconditioned by the system's
   !> current factor (of the frozen-pairing matrix of this or a nearby pairing).
   type, extends(linear_operator_t) :: contact_tangent_t
      class(contact_system_t), pointer :: sys => null()
      type(contact_state_t), pointer :: contact => null()
      logical, pointer :: fixed(:) => null()
      logical :: sliding = .false.
   contains
      procedure :: apply => tangent_apply
      procedure :: precondition => tangent_precondition
   end type contact_tangent_t

   !> What the stages of one solve_contact share: the counters, the history of the
   !> active sets and gaps (for the cycle test), the work vectors and the tangent.
   type :: iteration_state_t
      integer :: it = 0, maxit = 0
      integer :: nchanged = 0             !< entries whose state changed in the last update
      integer :: nslip = 0                !< entries whose stick/slip state changed in it
      !> the pairings of stepwise pairs renewed within this load state (repair_stepwise)
      integer :: repairs = 0
      real(wp) :: kmax = 0.0_wp           !< largest elastic diagonal entry
      real(wp) :: rel = 0.0_wp            !< relative residual of the last iteration
      real(wp) :: step = 1.0_wp           !< line search step of the last solve
      real(wp) :: rc_min = 1.0_wp         !< smallest reciprocal condition estimate so far
      real(wp) :: t_iter = 0.0_wp, t_fact = 0.0_wp, t_srch = 0.0_wp
      logical :: warned = .false.         !< the ill-conditioning warning was given
      logical :: settled = .false.        !< the last update changed no entry
      !> the active set has held once in this load state (finite sliding: Newton steps
      !> on the pairing from then on)
      logical :: newton = .false.
      logical :: rebuilt = .false.        !< the last matrix needed a new pattern
      !> the last solve was the condensed one, whole (step 1): the residual at u lies on
      !> the contact rows alone (settle_states)
      logical :: condensed = .false.
      logical, allocatable :: history(:, :), held(:)
      !> entries kept closed after a cycle between open and closed (pin_cycle)
      logical, allocatable :: pinned(:)
      real(wp), allocatable :: gaps(:, :)
      integer(ip), allocatable :: iseg_start(:)
      !> right-hand side, K u, contact forces, residual, start of the solve
      real(wp), allocatable :: f(:), ku(:), fc(:), r(:), u0(:)
      type(contact_tangent_t) :: op
   end type iteration_state_t

contains

   subroutine tangent_apply(self, x, y)
      class(contact_tangent_t), intent(inout) :: self
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      real(wp), allocatable :: z(:)
      z = merge(0.0_wp, x, self%fixed)
      call self%sys%elastic_times(z, y)
      call self%contact%tangent_times(z, y, self%sliding)
      where (self%fixed) y = x
   end subroutine tangent_apply

   subroutine tangent_precondition(self, x, y, error)
      class(contact_tangent_t), intent(inout) :: self
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      type(error_t), allocatable, intent(out) :: error
      y = 0.0_wp
      call self%sys%solve_system(merge(0.0_wp, x, self%fixed), y, error)
      where (self%fixed) y = x
   end subroutine tangent_precondition

   !> The contact iteration of one load state (iterate_contact).  With friction the
   !> frozen systems and the multipliers' steps go on the contact space with the
   !> factor (condensed_solve, contact_newton); where that iteration fails (a cycle,
   !> MAXIT) the load state is tried again from its start with the plain multiplier
   !> updates and GMRES (sys%plain), the iteration the contact space accelerates: a
   !> soft disc as the master of a stiff block with exact stick cycled between stick
   !> and slip on the contact space and converges in 7 iterations plainly.
   subroutine solve_contact(sys, model, fixed, prescribed, fext, u, contact, error, log)
      class(contact_system_t), intent(inout), target :: sys
      type(model_t), intent(in) :: model
      logical, intent(in), target :: fixed(:)
      real(wp), intent(in) :: prescribed(:), fext(:)
      real(wp), intent(inout) :: u(:)
      type(contact_state_t), intent(inout), target :: contact
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      type(contact_state_t) :: contact0
      real(wp), allocatable :: u0(:)
      logical :: retry
      retry = contact%fric%on .and. .not. sys%plain
      if (retry) then
         u0 = u
         contact0 = contact
      end if
      call iterate_contact(sys, model, fixed, prescribed, fext, u, contact, error, log)
      if (.not. allocated(error) .or. .not. retry) return
      if (error%code /= err_solver .or. is_interrupt(error%code)) return
      if (present(log)) call log%say('        (contact iteration on the contact space failed: '// &
                                     'the load state again with the plain multiplier updates)')
      deallocate (error)
      u = u0
      contact = contact0
      sys%plain = .true.
      call iterate_contact(sys, model, fixed, prescribed, fext, u, contact, error, log)
      sys%plain = .false.
   end subroutine solve_contact

   !> Solve for the displacements u of a load state with contact: u holds the
   !> previous state on entry (the pairing starts from it) and the new one on exit.
   !> Each iteration runs the stages in turn: the solve with the contact frozen
   !> (solve_frozen), the new pairing and active set (update_contact), the residual
   !> and its record (record_iteration), the multiplier updates and the convergence
   !> test (has_converged), and the cycle test (check_cycle).
   subroutine iterate_contact(sys, model, fixed, prescribed, fext, u, contact, error, log)
      class(contact_system_t), intent(inout), target :: sys
      type(model_t), intent(in) :: model
      logical, intent(in), target :: fixed(:)
      real(wp), intent(in) :: prescribed(:), fext(:)
      real(wp), intent(inout) :: u(:)
      type(contact_state_t), intent(inout), target :: contact
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      type(iteration_state_t) :: s
      character(len=160) :: buf
      character(len=12) :: tbuf
      integer :: it, sig
      logical :: converged

      call start_iteration(s, sys, model, fixed, u, contact, error, log)
      if (allocated(error)) return
      do it = 1, s%maxit
         ! a safe point to stop at on SIGINT/SIGTERM, the same on every process
         sig = agreed_stop_signal()
         if (sig > 0) then
            write (buf, '(a,i0)') 'before contact iteration ', it
            call interrupt_error(sig, trim(buf), error)
            return
         end if
         s%it = it
         sys%iterations = it
         s%t_iter = wall_time()
         call solve_frozen(s, sys, model, fixed, prescribed, fext, u, contact, error, log)
         if (allocated(error)) return
         call update_contact(s, sys, model, u, contact, error)
         if (allocated(error)) return
         call record_iteration(s, sys, fixed, fext, u, contact, log)
         converged = has_converged(s, sys, model, fixed, u, contact, error)
         if (allocated(error)) return
         if (converged) call repair_stepwise(s, sys, model, u, contact, converged, error)
         if (allocated(error)) return
         if (converged) then
            call check_pins(s, contact, error, log)
            if (allocated(error)) return
            call contact%commit_friction()
            call contact%set_balanced(model, s%ku - fext, fixed)
            if (sys%columns > 0 .and. present(log)) then
               write (tbuf, '(f12.3)') sys%t_columns
               write (buf, '(a,i0,a)') '  contact compliance: ', sys%columns, &
                  ' columns solved with the factor in '//trim(adjustl(tbuf))//' s'
               call log%say(trim(buf))
            end if
            call report_slid_off(s, model, contact, log)
            return
         end if
         call check_cycle(s, u, contact, error)
         if (allocated(error)) return
         call settle_states(s, sys, model, fixed, fext, u, contact, error)
         if (allocated(error)) return
      end do
      write (buf, '(a,i0,a,es10.3,a)') 'error: contact iterations did not converge in ', s%maxit, &
         ' iterations (relative residual ', s%rel, ')'
      call fatal_error(error, trim(buf)//nonconvergence_hint(contact%has_finite_sliding(), contact%has_hard(), &
                                                             contact%penalty_ratio()), err_solver)
   end subroutine iterate_contact

   !> The iteration's start: counters and work arrays, and the pairing and active set
   !> of the state left by the previous step (or the undeformed one).
   subroutine start_iteration(s, sys, model, fixed, u, contact, error, log)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout), target :: sys
      type(model_t), intent(in) :: model
      logical, intent(in), target :: fixed(:)
      real(wp), intent(in) :: u(:)
      type(contact_state_t), intent(inout), target :: contact
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      real(wp) :: t0
      allocate (s%f(size(u)), s%ku(size(u)), s%fc(size(u)), s%r(size(u)))
      s%maxit = model%controls%max_iterations
      s%kmax = sys%largest_elastic_diagonal()
      allocate (s%history(contact%n, 0:s%maxit), s%gaps(contact%n, 0:s%maxit))
      allocate (s%held(contact%n), source=.false.)
      allocate (s%pinned(contact%n), source=.false.)
      if (allocated(sys%records)) deallocate (sys%records)
      allocate (sys%records(0))
      sys%iterations = 0
      sys%factorizations = 0
      sys%refactorized = .false.
      sys%t_factorize = 0
      sys%t_solve = 0
      sys%columns = 0
      sys%t_columns = 0
      s%op%sys => sys
      s%op%contact => contact
      s%op%fixed => fixed
      call contact%start_state()
      t0 = wall_time()
      call contact%project(model, u, error)
      if (allocated(error)) return
      call contact%update_active(s%nchanged)
      call contact%update_friction(u, s%nslip, .false.)
      sys%t_search = wall_time() - t0
      s%iseg_start = contact%iseg
      s%history(:, 0) = contact%active
      s%gaps(:, 0) = merge(contact%gap, 0.0_wp, contact%iseg > 0)
      ! with friction, a last column: the entries that changed between stick and slip
      if (present(log)) call log%say('  iter  active  changed     residual  max penetration  max pressure'// &
                                     '    time [s]  factorize [s]  search [s]    step'// &
                                     merge('  stick/slip', '            ', contact%fric%on))
   end subroutine start_iteration

   !> One solve with the contact frozen at the current pairing and active set: the
   !> matrix, then the cheapest solve that holds (the current factor as it is; the
   !> factor of a nearby pairing, or of this one for the Newton step on the pairing,
   !> as GMRES's preconditioner; a new factorization), then the line search.
   subroutine solve_frozen(s, sys, model, fixed, prescribed, fext, u, contact, error, log)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout) :: sys
      type(model_t), intent(in) :: model
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: prescribed(:), fext(:)
      real(wp), intent(inout) :: u(:)
      type(contact_state_t), intent(inout) :: contact
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      logical :: same_matrix, same_pattern, solved, coupled, condensed
      real(wp) :: t0
      call sys%contact_matrix(model, contact, u, fixed, prescribed, fext, s%f, s%rebuilt, error)
      if (allocated(error)) return
      if (s%rebuilt .and. present(log)) call log%say('        (contact pairs moved: matrix pattern rebuilt)')
      ! the start of the step, with this state's prescribed values
      s%u0 = merge(prescribed, u, fixed)
      ! Newton on the pairing once the active set holds: the tangent carries the
      ! part of finite sliding (sliding_tangent), which the factor lacks: GMRES with
      ! the factor as preconditioner solves with it
      s%newton = s%newton .or. s%settled
      s%op%sliding = s%newton .and. contact%has_sliding()
      ! the matrix of the current factor: solve again without factorizing; a
      ! matrix that differs from it only by a small move of the pairing: the old
      ! factor as the preconditioner
      same_pattern = sys%factored .and. .not. s%rebuilt
      if (same_pattern) same_pattern = .not. any(fixed .neqv. sys%factored_fixed)
      same_matrix = same_pattern
      if (same_matrix) same_matrix = same_key(sys%factored_key, contact)
      solved = .false.
      s%condensed = .false.
      ! friction with the factor's pairing: the springs and states differ from the
      ! factor's by low-rank terms, solved exactly on the contact space
      ! (condensed_solve)
      condensed = contact%fric%on .and. .not. s%op%sliding .and. .not. sys%plain
      if (condensed .and. same_pattern) then
         if (same_pairing(sys%factored_key, contact)) then
            call condensed_solve(s, sys, fixed, fext, u, contact, solved, error)
            if (allocated(error)) return
            s%condensed = solved
         end if
      end if
      if (.not. solved .and. same_pattern .and. .not. same_matrix) then
         ! a small move of the pairing, or a few stick/slip changes alone
         if (near_key(sys%factored_key, contact, pairing_drift) .or. &
             flips_within(stick_flips(sys%factored_key, contact), max_stick_flips)) then
            call krylov_solve(s, sys, fixed, fext, u, contact, solved, error, contact%fric%on)
            if (allocated(error)) return
         end if
      end if
      s%t_fact = 0.0_wp
      if (.not. (same_matrix .or. solved)) then
         t0 = wall_time()
         call factorize(s, sys, fixed, contact, error, log)
         if (allocated(error)) return
         s%t_fact = wall_time() - t0
         sys%t_factorize = sys%t_factorize + s%t_fact
         if (condensed) then
            call condensed_solve(s, sys, fixed, fext, u, contact, solved, error)
            if (allocated(error)) return
            s%condensed = solved
         end if
      end if
      ! the unsymmetric parts the factor lacks (the sliding of the pairing, slipping
      ! friction whose force follows the normal force): GMRES with the factor
      coupled = contact%has_coupling()
      if (.not. solved .and. (s%op%sliding .or. coupled)) then
         call krylov_solve(s, sys, fixed, fext, u, contact, solved, error, .false.)
         if (allocated(error)) return
      end if
      if (.not. solved) then
         ! the frozen-pairing step with the factor of its own matrix (also where the
         ! sliding part was too strong for it: said in the log)
         if (s%op%sliding .and. present(log)) call log%say('        (Newton step on the pairing '// &
            'replaced by the frozen-pairing step: GMRES did not converge with the factor)')
         if (coupled .and. present(log)) call log%say('        (friction''s coupling to the normal '// &
            'force left to the next iteration: GMRES did not converge with the factor)')
         s%op%sliding = .false.
         call direct_solve(s, sys, fixed, fext, u, contact, error)
         if (allocated(error)) return
      end if
      if (.not. all(abs(u) <= huge(1.0_wp))) then
         call fatal_error(error, 'error: the solution has NaN or infinite values: the model is '// &
                          'numerically singular', err_solver)
         return
      end if
      ! a frozen-pairing solve minimizes its penalty energy with the current
      ! springs: cut it when it overshoots into new contact
      s%step = 1.0_wp
      if (.not. s%op%sliding) s%step = energy_step(s, sys, fixed, fext, u, contact)
      if (s%step < 1.0_wp) u = s%u0 + s%step*(u - s%u0)
      s%condensed = s%condensed .and. s%step >= 1.0_wp
   end subroutine solve_frozen

   !> The stick/slip states and active set settled on the contact space before the
   !> next full solve (a semismooth Newton on the contact unknowns).  After a whole
   !> condensed solve, u balances the bulk: the residual of the new states at u lies
   !> on the contact dofs, and the next frozen solve's values there come from the
   !> factor's trailing block alone (two dense solves and the Woodbury capacitance,
   !> no solve of the whole system).  The states are updated at those values
   !> (update_contact), as the next iteration would, until they hold or
   !> settle_rounds have passed; the full solve then starts from them.  Only where
   !> the columns are read from the trailing block (columns_local): elsewhere a
   !> round costs as much as an iteration.
   subroutine settle_states(s, sys, model, fixed, fext, u, contact, error)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout) :: sys
      type(model_t), intent(in) :: model
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: fext(:), u(:)
      type(contact_state_t), intent(inout) :: contact
      type(error_t), allocatable, intent(out) :: error
      type(woodbury_t) :: wb
      real(wp), allocatable :: w(:, :), z(:), x(:)
      logical :: ok
      integer :: round
      real(wp) :: t0
      if (.not. (s%condensed .and. sys%columns_local .and. contact%fric%on)) return
      if (.not. same_pairing(sys%factored_key, contact)) return
      t0 = wall_time()
      allocate (w(size(u), 1), z(0))
      do round = 1, settle_rounds
         if (s%nslip == 0 .and. s%nchanged == 0) exit
         call prepare_woodbury(sys, fixed, contact, wb, ok, error)
         if (allocated(error) .or. .not. ok) exit
         if (.not. sys%columns_local) exit
         call frozen_residual(s, sys, fixed, fext, u, contact)
         call sys%solve_columns(reshape(s%r, [size(u), 1]), w, error)
         if (allocated(error)) exit
         where (fixed) w(:, 1) = 0.0_wp
         if (size(z) /= wb%r) then
            deallocate (z)
            allocate (z(wb%r))
         end if
         call woodbury_rhs(wb, contact, fixed, w(:, 1), z)
         call woodbury_correction(wb, contact, fixed, z, s%r)
         where (fixed) s%r = 0.0_wp
         call sys%solve_columns(reshape(s%r, [size(u), 1]), w, error)
         if (allocated(error)) exit
         if (.not. sys%columns_local) exit
         where (fixed) w(:, 1) = 0.0_wp
         x = u + w(:, 1)
         call update_contact(s, sys, model, x, contact, error)
         if (allocated(error)) exit
      end do
      sys%t_solve = sys%t_solve + (wall_time() - t0)
   end subroutine settle_states

   !> A converged state of frictional finite-sliding pairs (stepwise: the pairing of
   !> the load state's start, kept) in which a closed slave node slid past the end of
   !> its master segment (a straight extension of it) is not the answer where the
   !> master turns: those pairs are paired anew at u and the iteration goes on (at
   !> most max_repairs times per load state; a node that a wedge of the master keeps
   !> beyond its segment's end stays so).
   subroutine repair_stepwise(s, sys, model, u, contact, converged, error)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout) :: sys
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      type(contact_state_t), intent(inout) :: contact
      logical, intent(inout) :: converged
      type(error_t), allocatable, intent(out) :: error
      logical :: released
      if (s%repairs >= max_repairs) return
      call contact%release_stepwise(model, u, released)
      if (.not. released) return
      s%repairs = s%repairs + 1
      call update_contact(s, sys, model, u, contact, error)
      converged = .false.
   end subroutine repair_stepwise

   !> The new pairing and active set at u (closed nodes opened by the re-pairing
   !> alone held, hold_nodes).
   subroutine update_contact(s, sys, model, u, contact, error)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout) :: sys
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      type(contact_state_t), intent(inout) :: contact
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: gfrozen(:)
      logical, allocatable :: hold(:)
      real(wp) :: t0
      t0 = wall_time()
      allocate (gfrozen(contact%n))
      call contact%frozen_gaps(u, gfrozen)
      call contact%project(model, u, error)
      if (allocated(error)) return
      hold = hold_nodes(contact%active, gfrozen, contact%gap, s%held)
      call contact%update_active(s%nchanged, hold, s%pinned)
      s%held = hold .and. contact%active
      call contact%update_friction(u, s%nslip, .true.)
      s%settled = s%nchanged == 0
      s%t_srch = wall_time() - t0
      sys%t_search = sys%t_search + s%t_srch
   end subroutine update_contact

   !> The residual of the equilibrium at u with the contact forces of the new
   !> pairing, the iteration's record (sys%records) and its log line.
   subroutine record_iteration(s, sys, fixed, fext, u, contact, log)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout) :: sys
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: fext(:), u(:)
      type(contact_state_t), intent(in) :: contact
      type(logger_t), intent(inout), optional :: log
      type(iteration_record_t) :: rec
      character(len=160) :: buf
      call sys%elastic_times(u, s%ku)
      s%fc = 0.0_wp
      call contact%forces(s%fc)
      if (any(s%pinned)) call contact%add_tension(s%pinned, s%fc)
      s%r = fext - s%ku - s%fc
      where (fixed) s%r = 0.0_wp
      s%rel = residual_norm(s%r, u, merge(0.0_wp, fext, fixed), s%fc, s%kmax, closed_stiffness(contact))
      rec = iteration_record_t(s%it, count(contact%active), s%nchanged, s%nslip, s%rel, contact%max_penetration(), &
                               contact%max_pressure(), s%step, s%t_fact > 0.0_wp, s%rebuilt, wall_time() - s%t_iter)
      sys%records = [sys%records, rec]
      write (buf, '(2x,i4,2x,i6,2x,i7,2x,es11.3,2x,es15.4,2x,es12.4,2x,f10.4,2x,f13.4,2x,f10.6,2x,f6.4)') s%it, &
         rec%active, s%nchanged, s%rel, rec%penetration, rec%pressure, rec%time, s%t_fact, s%t_srch, s%step
      if (contact%fric%on) write (buf(len_trim(buf) + 1:), '(2x,i10)') s%nslip
      if (present(log)) call log%say(trim(buf))
      s%history(:, s%it) = contact%active
      s%gaps(:, s%it) = merge(contact%gap, 0.0_wp, contact%iseg > 0)
   end subroutine record_iteration

   !> Whether the iteration has converged: no entry changed its normal or its
   !> stick/slip state and the residual is small; for HARD and exact stick, after
   !> the augmented Lagrangian's Uzawa updates, which must leave no overclosure, no
   !> elastic slip and no force change beyond the tolerances.
   logical function has_converged(s, sys, model, fixed, u, contact, error) result(converged)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout), target :: sys
      type(model_t), intent(in) :: model
      logical, intent(in), target :: fixed(:)
      real(wp), intent(in) :: u(:)
      type(contact_state_t), intent(inout), target :: contact
      type(error_t), allocatable, intent(out) :: error
      real(wp) :: overclosure, change, tchange, elastic_slip
      real(wp), allocatable :: noise(:), dlam(:), lambda0(:)
      logical :: newton, moving
      converged = .false.
      moving = .false.
      if (s%nchanged == 0 .and. (contact%has_hard() .or. contact%has_exact_friction())) then
         overclosure = 0.0_wp
         change = 0.0_wp
         ! exact stick: the tangential counterpart, at the same iterations (the normal
         ! forces its bounds depend on settle at the same time); a change within a few
         ! times the residual force left by the solve is its round-off (on the dam, K =
         ! 1e13 Pa/m, the exact-stick updates settled at 2.5e-5 N of 1e5 N, the size of
         ! the residual, and would never stop)
         lambda0 = contact%fric%lambda
         call contact%augment_friction(4.0_wp*maxval(abs(s%r)), tchange, elastic_slip)
         ! where the frozen systems are solved on the contact space, the multipliers of
         ! both take a Newton step there instead (contact_newton)
         allocate (dlam(contact%n))
         noise = contact%gap_noise(16.0_wp*epsilon(1.0_wp)*maxval(abs(u)), &
                                   16.0_wp*epsilon(1.0_wp)*maxval(abs(model%x)), &
                                   128.0_wp*min(maxval(abs(s%r)), epsilon(1.0_wp)*s%kmax*maxval(abs(u))))
         newton = condensed_applies(s, sys, fixed, contact)
         if (newton) then
            call contact_newton(sys, fixed, contact, lambda0, noise, dlam, newton, error)
            if (allocated(error)) return
         end if
         if (.not. contact%has_hard()) then
            converged = s%nslip == 0 .and. s%rel <= model%controls%residual_tol .and. &
                        elastic_slip <= model%controls%overclosure_tol .and. tchange <= model%controls%residual_tol
            return
         end if
         ! HARD: the augmented Lagrangian's multiplier update (multiplier_step), at
         ! every iteration that kept the active set (the pairing of finite sliding
         ! settles meanwhile, at the same time); converged once the solve left no
         ! overclosure beyond the tolerance and the update changed no force by more
         ! than the residual tolerance (the pressures' accuracy).  The gaps' round-off
         ! is excluded (gap_noise): a few ulps of the coordinates (the reference
         ! gaps) and of the displacements, and the forward error of the solve, from
         ! the elastic forces' round-off: the residual left, at most eps max K_ii
         ! max|u|, with a margin of 128 (at contrast 1e6 the gaps settled at 0.8 of
         ! 16 times it; docs/contact-robustness.md).  On the dam (coordinates 25 m, K
         ! = 4e13 Pa/m) the gaps' round-off is worth 1e-6 of the forces, which the
         ! updates only stir.
         ! Where the pairing is fixed (SMALL SLIDING, SURFACE TO SURFACE) the matrix
         ! then holds and only the right-hand side changes.  With finite sliding the
         ! step aims at the gaps the next Newton step leaves, and `moving` says that
         ! step still moves them.
         if (.not. newton) then
            call multiplier_step(sys, contact, fixed, noise, s%r, residual_floor(s), dlam, moving, error)
            if (allocated(error)) return
         end if
         call contact%augment(noise, dlam, overclosure, change)
         converged = s%nslip == 0 .and. s%rel <= model%controls%residual_tol .and. &
                     overclosure <= model%controls%overclosure_tol .and. change <= model%controls%residual_tol .and. &
                     .not. moving .and. elastic_slip <= model%controls%overclosure_tol .and. &
                     tchange <= model%controls%residual_tol
      else
         converged = s%nchanged == 0 .and. s%nslip == 0 .and. s%rel <= model%controls%residual_tol
      end if
   end function has_converged

   !> The bound of the round-off of the residual s%r (2-norm), 1e3 eps of its scale
   !> (residual_norm): krylov_solve's floor.
   pure real(wp) function residual_floor(s) result(floor)
      type(iteration_state_t), intent(in) :: s
      floor = 0.0_wp
      if (s%rel > 0.0_wp) floor = 1.0e3_wp*epsilon(1.0_wp)*safe_norm2(s%r)/s%rel
   end function residual_floor

   !> 0 < m <= limit: a few stick/slip changes (stick_flips).
   pure logical function flips_within(m, limit)
      integer, intent(in) :: m, limit
      flips_within = m > 0 .and. m <= limit
   end function flips_within

   !> Stop when the iterates return to the active set and gaps of an earlier
   !> iteration (is_cycle), unless pinning the entries that switched resolves it
   !> (pin_cycle).
   subroutine check_cycle(s, u, contact, error)
      type(iteration_state_t), intent(inout) :: s
      real(wp), intent(in) :: u(:)
      type(contact_state_t), intent(in) :: contact
      type(error_t), allocatable, intent(out) :: error
      character(len=160) :: buf
      integer :: j
      if (s%nchanged == 0) return
      j = is_cycle(s%history, s%gaps, contact%active, s%gaps(:, s%it), s%it, s%rc_min, maxval(abs(u)))
      if (j < 0) return
      if (pin_cycle(s, contact, j)) return
      write (buf, '(a,i0,a,i0)') 'error: contact iterations cycle: iteration ', s%it, &
         ' returns to the active set and gaps of iteration ', j
      call fatal_error(error, trim(buf)//' (the penalty may be too large for the mesh, or a '// &
                       'slave node sits at the end of a master surface)', err_solver)
   end subroutine check_cycle

   !> A cycle from iteration j whose entries that switched between open and closed
   !> all carry shear at zero normal force (cohesion): pin them closed for the rest of
   !> the iteration and go on (true), unless some were pinned already (false: the
   !> cycle stands).  Such an entry has no consistent state of its own: closed, its
   !> cohesive shear c A pulls it open (a tension), open it carries nothing and the
   !> bodies move into it (rock_block_crack6 near the limit: the end node of the joint
   !> at the crack, open by 1e-12 m closed, overclosed by 4e-8 m open, every trial
   !> within 1 % of the limit cycling).  The state between is the node at zero gap
   !> and zero normal force with a shear below c A, where opening and closing meet;
   !> held closed it reaches it up to the tension of its spring, which check_pins
   !> bounds by the entry's cohesive strength and reports.
   logical function pin_cycle(s, contact, j) result(pinned)
      type(iteration_state_t), intent(inout) :: s
      type(contact_state_t), intent(in) :: contact
      integer, intent(in) :: j
      logical, allocatable :: flip(:)
      integer :: k, i
      pinned = .false.
      if (any(s%pinned)) return
      allocate (flip(contact%n), source=.false.)
      do k = j, s%it - 1
         flip = flip .or. (s%history(:, k) .neqv. s%history(:, k + 1))
      end do
      if (.not. any(flip)) return
      do i = 1, contact%n
         if (.not. flip(i)) cycle
         if (.not. (contact%zero_normal_strength(i) > 0.0_wp) .or. contact%iseg(i) <= 0) return
      end do
      s%pinned = flip
      pinned = .true.
   end function pin_cycle

   !> At convergence: a pinned entry (pin_cycle) may carry a tension up to its shear
   !> strength at zero normal force (the Mohr-Coulomb envelope reaches tension c/tan(phi)
   !> there; c A is below it for phi < 45 deg and the order of it beyond); beyond that the
   !> cycle was not between open and closed at zero force, and stands as the error.
   !> The log names the pinned entries and their normal forces.
   subroutine check_pins(s, contact, error, log)
      type(iteration_state_t), intent(in) :: s
      type(contact_state_t), intent(in) :: contact
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      character(len=160) :: buf
      real(wp) :: n
      integer :: i
      if (.not. any(s%pinned)) return
      do i = 1, contact%n
         if (.not. s%pinned(i)) cycle
         n = contact%lambda(i) - contact%k(i)*contact%gap(i)
         if (-n > contact%zero_normal_strength(i)) then
            write (buf, '(a,i0,a,es10.3,a)') 'error: contact iterations cycle: slave node ', contact%node(i), &
               ' between open and closed carries a tension ', -n, ' beyond its cohesive strength'
            call fatal_error(error, trim(buf), err_solver)
            return
         end if
         write (buf, '(a,i0,a,es11.4,a,es11.4,a)') '  slave node ', contact%node(i), &
            ' held closed between open and closed: normal force ', n, &
            ' (cohesive strength ', contact%zero_normal_strength(i), ')'
         if (present(log)) call log%say(trim(buf))
      end do
   end subroutine check_pins

   !> The stiffest closed spring (0 when none is closed), for residual_norm.
   pure real(wp) function closed_stiffness(contact) result(kc)
      type(contact_state_t), intent(in) :: contact
      kc = 0.0_wp
      if (any(contact%active)) kc = maxval(contact%k, mask=contact%active)
   end function closed_stiffness

   !> u = u0 + dx with the factor of the frozen-pairing matrix itself: a solve and
   !> one step of iterative refinement, dx = A^-1 r(u0), then x <- x + A^-1 r(x), with
   !> the residual r = f_ext - K x - f_c(x) from the gaps.  The backward error of
   !> the factorization is eps times the stiffest spring, which at K h/E = 1e7 left
   !> 2e-8 in the contact forces; the refined solution carries the round-off of the
   !> elastic forces (the contact patch test of SURFACE TO SURFACE at K h/E = 1e8:
   !> 1e-13 with the refinement, 3e-7 without).
   subroutine direct_solve(s, sys, fixed, fext, x, contact, error)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout) :: sys
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: fext(:)
      real(wp), intent(inout) :: x(:)
      type(contact_state_t), intent(in) :: contact
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: dx(:)
      real(wp) :: t0
      integer :: pass
      x = s%u0
      allocate (dx(size(x)))
      do pass = 1, 2
         call frozen_residual(s, sys, fixed, fext, x, contact)
         dx = 0.0_wp
         t0 = wall_time()
         call sys%solve_system(s%r, dx, error)
         sys%t_solve = sys%t_solve + (wall_time() - t0)
         if (allocated(error)) return
         x = x + dx
      end do
   end subroutine direct_solve

   !> The residual of the frozen-pairing equilibrium at x, r = f_ext - K x - f_c(x)
   !> (zero on the fixed dofs; f_c in fc), and its relative size rel_x (residual_norm).
   subroutine frozen_residual(s, sys, fixed, fext, x, contact, rel_x)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(in) :: sys
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: fext(:), x(:)
      type(contact_state_t), intent(in) :: contact
      real(wp), intent(out), optional :: rel_x
      call sys%elastic_times(x, s%ku)
      s%fc = 0.0_wp
      call contact%linear_forces(x, s%fc)
      s%r = fext - s%ku - s%fc
      where (fixed) s%r = 0.0_wp
      if (present(rel_x)) rel_x = residual_norm(s%r, x, merge(0.0_wp, fext, fixed), s%fc, s%kmax, &
                                                closed_stiffness(contact))
   end subroutine frozen_residual

   !> x = u0 + dx with J dx = r(u0), the tangent J of `op` (the frozen-pairing
   !> matrix, plus the sliding part for a Newton step), by GMRES preconditioned
   !> with the current factor (of this or a nearby pairing), to a millionth of the
   !> initial residual or its round-off floor.  ok: GMRES converged; otherwise x is
   !> its last iterate.
   subroutine krylov_solve(s, sys, fixed, fext, x, contact, ok, error, old_states)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout) :: sys
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: fext(:)
      real(wp), intent(inout) :: x(:)
      type(contact_state_t), intent(in) :: contact
      logical, intent(out) :: ok
      type(error_t), allocatable, intent(out) :: error
      !> the factor is that of earlier stick/slip states (gmres_restart_friction)
      logical, intent(in) :: old_states
      real(wp), allocatable :: dx(:)
      type(gmres_result_t) :: res
      real(wp) :: rel0, tol_abs, floor_abs, t0, stall
      integer :: restart, maxit
      ok = .false.
      call frozen_residual(s, sys, fixed, fext, s%u0, contact, rel0)
      ! a millionth of the initial residual: an inexact Newton step that keeps the
      ! quadratic rate; a multiplier update of HARD late in the iteration starts
      ! from a residual near the round-off, and must still be applied in full.
      ! The floor, 1e3 eps of the residual's scale, is about the round-off of its
      ! evaluation (floors of 1e-15 to 1e-17 relative were logged): below it GMRES
      ! goes on only while it still halves the residual
      tol_abs = gmres_reduction*safe_norm2(s%r)
      if (contact%has_coupling() .and. .not. s%op%sliding) tol_abs = gmres_reduction_friction*safe_norm2(s%r)
      floor_abs = 0.0_wp
      if (rel0 > 0.0_wp) floor_abs = 1.0e3_wp*epsilon(1.0_wp)*safe_norm2(s%r)/rel0
      ! a residual that starts below that floor is not all round-off: the floor is a
      ! bound, and a multiplier update late in the iteration (gaps of 6e-13 of the
      ! element, forces of 5e-9 of the largest, on the block of bench/friction_cost.py)
      ! starts there.  GMRES stopped at its first iteration, the update stayed
      ! unapplied and was proposed again at every iteration until MAXIT; it must then
      ! lower the residual a thousandfold (or fail: a new factorization), and goes on
      ! below that while it halves it, as below the floor
      if (safe_norm2(s%r) <= floor_abs) floor_abs = 1.0e-3_wp*safe_norm2(s%r)
      restart = gmres_restart
      maxit = gmres_maxit
      stall = 0.5_wp
      if (old_states) then
         ! with the factor of earlier stick/slip states GMRES's rate has plateaus near
         ! the floor, where one iteration that barely lowered the residual stopped it
         ! at the floor itself (2e-8 of the dam's largest pressure in its law checks,
         ! where the current factor reached 1e-9): a floor a hundred times lower,
         ! below which it goes on while each iteration gains a tenth
         restart = gmres_restart_friction
         maxit = gmres_maxit_friction
         stall = gmres_stall_friction
         floor_abs = 1.0e-2_wp*floor_abs
      end if
      allocate (dx(size(s%u0)), source=0.0_wp)
      t0 = wall_time()
      call gmres(s%op, s%r, dx, tol_abs, floor_abs, restart, maxit, stall, res, error)
      sys%t_solve = sys%t_solve + (wall_time() - t0)
      if (allocated(error)) return
      x = s%u0 + dx
      ok = res%converged
   end subroutine krylov_solve

   !> x = u0 + dx with J dx = r(u0) solved exactly with the current factor K0 of
   !> another tangential state of the same pairing (vemcontact_contact_condensed):
   !> the columns K0^-1 t_i of the entries that differ from K0 come from the cache
   !> (computed once per factor), then two solves by K0 and the capacitance give dx;
   !> one pass of refinement on the frozen residual, as direct_solve, unless the
   !> first left only round-off (condensed_refined).  ok false
   !> (x undefined) when the capacitance is singular or the refined residual is not
   !> at the solve's round-off (condensed_tol).
   subroutine condensed_solve(s, sys, fixed, fext, x, contact, ok, error)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout) :: sys
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: fext(:)
      real(wp), intent(inout) :: x(:)
      type(contact_state_t), intent(in) :: contact
      logical, intent(out) :: ok
      type(error_t), allocatable, intent(out) :: error
      type(woodbury_t) :: wb
      real(wp), allocatable :: w(:), g(:), z(:)
      real(wp) :: t0, rel
      integer :: pass
      t0 = wall_time()
      call prepare_woodbury(sys, fixed, contact, wb, ok, error)
      if (allocated(error) .or. .not. ok) return
      x = s%u0
      allocate (w(size(x)), z(wb%r))
      do pass = 1, 2
         call frozen_residual(s, sys, fixed, fext, x, contact, rel)
         ! the refinement only where the first solve left more than its round-off
         if (pass == 2 .and. rel <= condensed_refined) exit
         w = 0.0_wp
         call sys%solve_system(s%r, w, error)
         if (allocated(error)) return
         call woodbury_rhs(wb, contact, fixed, w, z)
         g = s%r
         call woodbury_correction(wb, contact, fixed, z, g)
         where (fixed) g = 0.0_wp
         w = 0.0_wp
         call sys%solve_system(g, w, error)
         if (allocated(error)) return
         where (fixed) w = 0.0_wp
         x = x + w
      end do
      sys%t_solve = sys%t_solve + (wall_time() - t0)
      call frozen_residual(s, sys, fixed, fext, x, contact, rel)
      ok = all(abs(x) <= huge(1.0_wp)) .and. rel <= condensed_tol
   end subroutine condensed_solve

   !> The low-rank difference between the frozen tangent of `contact` and the
   !> current factor, with the columns it needs added to the cache (add_columns)
   !> and its capacitance factored; ok false when the capacitance is singular.
   subroutine prepare_woodbury(sys, fixed, contact, wb, ok, error)
      class(contact_system_t), intent(inout) :: sys
      logical, intent(in) :: fixed(:)
      type(contact_state_t), intent(in) :: contact
      type(woodbury_t), intent(out) :: wb
      logical, intent(out) :: ok
      type(error_t), allocatable, intent(out) :: error
      logical, allocatable :: need(:, :)
      if (.not. allocated(sys%cache%col)) call sys%cache%reset(contact%n)
      allocate (need(2, contact%n))
      call build_woodbury(sys%factored_key, contact, sys%cache, wb, need, .false., ok)
      call add_columns(sys, fixed, contact, need, error)
      if (allocated(error)) return
      call build_woodbury(sys%factored_key, contact, sys%cache, wb, need, .true., ok)
   end subroutine prepare_woodbury

   !> The cache gains the columns K0^-1 b_{i,d} of the rows `need(d, i)` that it lacks,
   !> solved together in blocks of at most condensed_block_values / n columns (the
   !> right-hand sides and solutions of a block are two n x block arrays).
   subroutine add_columns(sys, fixed, contact, need, error)
      class(contact_system_t), intent(inout) :: sys
      logical, intent(in) :: fixed(:)
      type(contact_state_t), intent(in) :: contact
      logical, intent(in) :: need(:, :)
      type(error_t), allocatable, intent(out) :: error
      integer, allocatable :: list(:, :)
      real(wp), allocatable :: b(:, :), z(:, :)
      integer :: first, last, block
      real(wp) :: t0
      t0 = wall_time()
      list = sys%cache%missing(need)
      block = max(condensed_block_min, min(condensed_block_max, condensed_block_values/max(1, size(fixed))))
      do first = 1, size(list, 2), block
         last = min(size(list, 2), first + block - 1)
         allocate (b(size(fixed), last - first + 1), z(size(fixed), last - first + 1))
         call scatter_rows(contact, fixed, list(:, first:last), b)
         call sys%solve_columns(b, z, error)
         if (allocated(error)) return
         call store_columns(sys%cache, contact, fixed, list(:, first:last), z)
         deallocate (b, z)
      end do
      sys%columns = sys%columns + size(list, 2)
      sys%t_columns = sys%t_columns + (wall_time() - t0)
   end subroutine add_columns

   !> x(:, c) = A^-1 b(:, c), one solve_system per column.
   subroutine solve_columns(self, b, x, error)
      class(contact_system_t), intent(inout) :: self
      real(wp), intent(in) :: b(:, :)
      real(wp), intent(out) :: x(:, :)
      type(error_t), allocatable, intent(out) :: error
      integer :: c
      do c = 1, size(b, 2)
         x(:, c) = 0.0_wp
         call self%solve_system(b(:, c), x(:, c), error)
         if (allocated(error)) return
      end do
   end subroutine solve_columns

   !> The multipliers' Newton step on the contact space, where the condensed solve
   !> applies (condensed_applies): the normal multipliers of the HARD entries
   !> (multiplier_entries) and the tangential ones of the sticking entries of exact
   !> laws, so that the next solve, if the states hold, leaves no gap and no elastic
   !> slip.  A change dlam_N of a normal multiplier loads the right-hand side with
   !> dlam_N (n - dT/dN t) (a slipping entry's force follows its normal force), one
   !> dlam_T of a tangential one with -dlam_T t; with the compliance H = B J^-1 B^T of
   !> the contact rows under the frozen tangent J (contact_compliance) the gaps and
   !> elastic slips move linearly, and one dense system gives both steps.  The
   !> plain Uzawa updates divide the error of a mode by 1 + k c (c its compliance)
   !> and ignore the coupling of gaps and slips through the bodies.  Gaps within
   !> `noise` count as zero, as in multiplier_step.  Returns dlam (the normal step,
   !> for augment) and sets the tangential multipliers to lambda0 + dlam_T; ok false
   !> (nothing set) when the system is singular.
   subroutine contact_newton(sys, fixed, contact, lambda0, noise, dlam, ok, error)
      class(contact_system_t), intent(inout) :: sys
      logical, intent(in) :: fixed(:)
      type(contact_state_t), intent(inout) :: contact
      real(wp), intent(in) :: lambda0(:), noise(:)
      real(wp), intent(out) :: dlam(:)
      logical, intent(out) :: ok
      type(error_t), allocatable, intent(out) :: error
      type(woodbury_t) :: wb
      logical, allocatable :: rows(:, :), slipping(:)
      integer, allocatable :: list(:, :), ipiv(:)
      real(wp), allocatable :: h(:, :), y(:)
      integer :: i, p, m, info
      real(wp) :: t0, hmax
      dlam = 0.0_wp
      t0 = wall_time()
      call newton_rows(contact, rows, slipping)
      ok = .true.
      if (.not. any(rows)) return
      call prepare_woodbury(sys, fixed, contact, wb, ok, error)
      if (allocated(error) .or. .not. ok) return
      ! the rows, then the tangential rows of the slipping HARD entries (their loads)
      m = count(rows)
      allocate (list(2, m + count(slipping)), y(m))
      p = 0
      do i = 1, contact%n
         if (rows(row_normal, i)) then
            p = p + 1
            list(:, p) = [row_normal, i]
            y(p) = merge(-contact%gap(i), 0.0_wp, abs(contact%gap(i)) > noise(i))
         end if
         if (rows(row_tangent, i)) then
            p = p + 1
            list(:, p) = [row_tangent, i]
            y(p) = -(contact%fric%slip(i) - contact%fric%anchor(i))
         end if
      end do
      do i = 1, contact%n
         if (.not. slipping(i)) cycle
         p = p + 1
         list(:, p) = [row_tangent, i]
         rows(row_tangent, i) = .true.
      end do
      call add_columns(sys, fixed, contact, rows, error)
      if (allocated(error)) return
      allocate (h(p, p), ipiv(m))
      call contact_compliance(wb, sys%cache, list, h)
      ! a slipping entry's normal load n - dT/dN t
      do p = m + 1, size(list, 2)
         i = list(2, p)
         m = findloc(list(2, 1:count(rows) - count(slipping)), i, 1)
         h(:, m) = h(:, m) - contact%fric%dnormal(i)*h(:, p)
      end do
      m = count(rows) - count(slipping)
      h = h(1:m, 1:m)
      ! the rows of entries whose dofs are all fixed: the solve cannot move their gaps
      ! or slips (their multipliers stay)
      hmax = 0.0_wp
      do p = 1, m
         hmax = max(hmax, abs(h(p, p)))
      end do
      do p = 1, m
         if (abs(h(p, p)) > epsilon(1.0_wp)*hmax) cycle
         h(p, :) = 0.0_wp
         h(:, p) = 0.0_wp
         h(p, p) = 1.0_wp
         y(p) = 0.0_wp
      end do
      call dgetrf(m, m, h, m, ipiv, info)
      if (info == 0) call dgetrs('N', m, 1, h, m, ipiv, y, m, info)
      ok = info == 0 .and. all(abs(y) <= huge(1.0_wp))
      sys%t_solve = sys%t_solve + (wall_time() - t0)
      if (.not. ok) return
      do p = 1, m
         i = list(2, p)
         if (list(1, p) == row_normal) dlam(i) = y(p)
      end do
      ! a step a thousand times the contact forces there are comes from a nearly
      ! singular system (a soft disc as the master of a stiff block with exact stick:
      ! after one stick/slip change, normal steps of 1e6 on forces of 10 and
      ! tangential ones of 1e8, then every entry open and "not held"): the plain
      ! updates instead (ok false: nothing set).  A sound step moves the forces by
      ! the order of the loads (the overshoot seen in sound ones: 160 times)
      ok = maxval(abs(y)) <= newton_jump*force_scale(contact, lambda0)
      if (.not. ok) then
         dlam = 0.0_wp
         return
      end if
      do p = 1, m
         i = list(2, p)
         if (list(1, p) == row_tangent) contact%fric%lambda(i) = lambda0(i) - y(p)
      end do
   contains
      !> The largest contact force of the closed entries: normal, or tangential
      !> multiplier before the step.
      real(wp) function force_scale(contact, lambda0) result(f)
         type(contact_state_t), intent(in) :: contact
         real(wp), intent(in) :: lambda0(:)
         integer :: j
         f = 0.0_wp
         do j = 1, contact%n
            if (contact%active(j)) f = max(f, contact%normal_force(j), abs(lambda0(j)))
         end do
      end function force_scale
   end subroutine contact_newton

   !> The rows of the multipliers' Newton step (contact_newton): rows(row_normal, i)
   !> for the HARD entries' normal multipliers, rows(row_tangent, i) for the sticking
   !> entries of exact laws; `slipping` marks the HARD entries whose force follows
   !> their normal force.
   subroutine newton_rows(contact, rows, slipping)
      type(contact_state_t), intent(in) :: contact
      logical, allocatable, intent(out) :: rows(:, :), slipping(:)
      integer :: i
      allocate (rows(2, contact%n), slipping(contact%n))
      rows(row_normal, :) = contact%multiplier_entries()
      do i = 1, contact%n
         rows(row_tangent, i) = contact%active(i) .and. contact%iseg(i) > 0 .and. &
                                contact%fric%state(i) == tangent_stick
         if (rows(row_tangent, i)) rows(row_tangent, i) = contact%fric%laws(contact%pair(i))%law%exact()
         slipping(i) = rows(row_normal, i) .and. contact%fric%state(i) == tangent_slip .and. &
                       abs(contact%fric%dnormal(i)) > 0.0_wp
      end do
   end subroutine newton_rows

   !> Whether the frozen systems of `contact` are solved on the contact space with
   !> the current factor (condensed_solve, contact_newton): friction, the factor's
   !> fixed dofs and pattern, the pairing fixed since the factor.
   logical function condensed_applies(s, sys, fixed, contact) result(applies)
      type(iteration_state_t), intent(in) :: s
      class(contact_system_t), intent(in) :: sys
      logical, intent(in) :: fixed(:)
      type(contact_state_t), intent(in) :: contact
      applies = contact%fric%on .and. sys%factored .and. .not. s%rebuilt .and. .not. contact%has_sliding() .and. &
                .not. sys%plain
      if (applies) applies = .not. any(fixed .neqv. sys%factored_fixed)
      if (applies) applies = same_pairing(sys%factored_key, contact)
   end function condensed_applies

   !> Numeric factorization of the current matrix, with its conditioning judged.
   subroutine factorize(s, sys, fixed, contact, error, log)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(inout) :: sys
      logical, intent(in) :: fixed(:)
      type(contact_state_t), intent(in) :: contact
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      real(wp) :: rc
      sys%factored = .false.
      call sys%numeric_factorize(error)
      if (allocated(error)) then
         ! a penalty stiff enough to swamp the elastic stiffness loses positive
         ! definiteness to round-off: say so in the model's terms when the solver
         ! found a pivot that was not positive (any other failure, an iterative
         ! solver's or an internal one, stays as it is)
         if (any(contact%active) .and. sys%pivot_failed) &
            error%message = 'error: with the closed contact springs the '// &
            'stiffness matrix is not positive definite in floating point ('//error%message//')'// &
            new_line('a')//conditioning_hint(closed_stiffness(contact)/s%kmax)
         return
      end if
      sys%factorizations = sys%factorizations + 1
      sys%factored = .true.
      call sys%cache%reset(contact%n)
      sys%factored_fixed = fixed
      sys%factored_key = key_of(contact)
      sys%refactorized = .true.
      rc = sys%rcond()
      call judge_conditioning(rc, closed_stiffness(contact)/s%kmax, any(contact%active), s%warned, error, log)
      if (allocated(error)) return
      if (rc > 0.0_wp) s%rc_min = min(s%rc_min, rc)
   end subroutine factorize

   !> The line search along the solve from u0 to u (line_search_step), with the
   !> gaps frozen and shifted by lambda/k for HARD entries.
   real(wp) function energy_step(s, sys, fixed, fext, u, contact) result(t)
      type(iteration_state_t), intent(inout) :: s
      class(contact_system_t), intent(in) :: sys
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: fext(:), u(:)
      type(contact_state_t), intent(in) :: contact
      real(wp), allocatable :: d(:), kd(:), g0(:), h(:)
      real(wp) :: ta, tb
      t = 1.0_wp
      allocate (g0(contact%n), h(contact%n))
      call contact%frozen_gaps(s%u0, g0)
      call contact%frozen_gaps(u, h)
      where (g0 < huge(1.0_wp) .and. contact%k > 0.0_wp)
         g0 = g0 - contact%lambda/contact%k
         h = h - contact%lambda/contact%k
      end where
      if (.not. needs_line_search(contact%active, g0, h)) return
      where (g0 < huge(1.0_wp))
         h = h - g0
      elsewhere
         h = 0.0_wp
      end where
      d = merge(0.0_wp, u - s%u0, fixed)
      allocate (kd(size(d)))
      call sys%elastic_times(d, kd)
      call sys%elastic_times(s%u0, s%ku)
      ! the frozen tangential forces along the step: linear (slip) and quadratic (stick) terms
      call contact%tangential_line_terms(s%u0, d, ta, tb)
      t = line_search_step(dot_product(d, s%ku - fext) + ta, dot_product(d, kd) + tb, contact%k, g0, h)
   end function energy_step

   !> Slave nodes that had a master segment at the start of the step and have none at
   !> its end slid past the end of an open master surface: they carry no pressure and
   !> their neighbours the load they would carry; say so, naming them.
   subroutine report_slid_off(s, model, contact, log)
      type(iteration_state_t), intent(in) :: s
      type(model_t), intent(in) :: model
      type(contact_state_t), intent(inout) :: contact
      type(logger_t), intent(inout), optional :: log
      integer :: i, m
      character(len=:), allocatable :: list
      character(len=160) :: buf
      contact%slid_off = s%iseg_start > 0 .and. contact%iseg == 0
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

   !> The multipliers' step dlam of the HARD entries (vemcontact_contact_active_set,
   !> augment) that closes their gaps g with the pairing and active set of the last
   !> solve: S dlam = -g, S = A M^-1 A^T the condensed compliance of the entries at
   !> the current factor M (the elastic stiffness and the springs), A the rows n.A(xi)
   !> of the gaps.  Solved by conjugate gradients preconditioned with the springs k
   !> (each product by S is one solve with the factor, or with finite sliding one
   !> GMRES solve of the Newton tangent: compliance_apply), whose first iterate is the
   !> plain Uzawa update -k g at its best length.  Uzawa alone divides the error of a
   !> pressure mode by 1 + k c, c its compliance, which is slow for the modes that
   !> the stiffer body carries (c of the stiff body, k of the soft one: 1.35 per
   !> update on a curved soft master under a stiff slave, 1.001 at contrast 1e6);
   !> conjugate gradients solve these few modes in as many steps
   !> (docs/contact-formulation.md).  Gaps within `noise` (gap_noise) count as zero;
   !> the iteration stops when every residual gap is within a sixteenth of its noise
   !> (multiplier_aim), when the compliance has no positive curvature left
   !> (round-off), or after multiplier_cg_limit products.
   !>
   !> With finite sliding, g is the gap that the next Newton step leaves with the
   !> current multipliers, g + A' J^-1 r (gap_response), not the gap at u: that step
   !> also removes the residual r at u (the re-pairing's forces, and what the last
   !> GMRES solve left, a millionth of its right-hand side), and the gaps move with
   !> it.  On the soft Voronoi disc as the slave of a stiff block (Hertz, 480 arc
   !> sides) that residual is 1e-12 of the block's force scale, and still moved the
   !> gaps by 2e-3 of the multipliers' correction (3.4e-10 of 1.5e-7; the gaps are
   !> linear along the step to 1e-17, so not the pairing's curvature): every update
   !> left a thousandth of the last one (11-12 iterations, 9 with r's share).  Its
   !> GMRES solve has no floor: late in the iteration the residual is near
   !> krylov_solve's round-off bound, 1e3 eps of its scale, where it still moves the
   !> gaps by 1e-12 (the disc as the master: 17 and 11 iterations at 480 and 240
   !> sides with that floor, 10 and 9 without).  Where r moves some gap beyond its
   !> noise, u has not converged (`moving`), whatever dlam, unless r is within that
   !> bound, where the next solve would stop anyway: the residual tolerance alone,
   !> relative to the stiffest body's forces, ended the paper's Hertz 389 with an
   !> overclosure of 3.7e-11 pending.
   subroutine multiplier_step(sys, contact, fixed, noise, r, r_floor, dlam, moving, error)
      class(contact_system_t), intent(inout), target :: sys
      type(contact_state_t), intent(in), target :: contact
      logical, intent(in), target :: fixed(:)
      real(wp), intent(in) :: noise(:)
      !> the residual at u with the current multipliers and pairing, and the bound of
      !> its round-off (2-norm) below which the iteration's solves stop (krylov_solve)
      real(wp), intent(in) :: r(:), r_floor
      real(wp), intent(out) :: dlam(:)
      !> the Newton step of r moves some gap beyond its round-off: u has not converged,
      !> whatever dlam
      logical, intent(out) :: moving
      type(error_t), allocatable, intent(out) :: error
      type(compliance_t) :: op
      type(cg_result_t) :: res
      real(wp), allocatable :: b(:), g(:)
      real(wp) :: t0
      t0 = wall_time()
      op%sys => sys
      op%contact => contact
      op%fixed => fixed
      op%mask = contact%multiplier_entries()
      op%sliding = contact%has_sliding()
      g = contact%gap
      moving = .false.
      if (op%sliding) then
         allocate (b(contact%n))
         call gap_response(op, r, b)
         g = g + b
         moving = any(op%mask .and. abs(b) > noise) .and. safe_norm2(r) > r_floor
      end if
      ! -g, without the gaps within their round-off
      b = merge(-g, 0.0_wp, op%mask .and. abs(g) > noise)
      call pcg(op, b, multiplier_aim*noise, multiplier_cg_limit, dlam, res, error)
      ! its solves are solves of the run (the log's solve phase)
      sys%t_solve = sys%t_solve + (wall_time() - t0)
   end subroutine multiplier_step

   !> S v = A M^-1 A^T v on the entries of `mask` (0 elsewhere), one solve with the
   !> system's current factor M; with `sliding`, S v = A' J^-1 A^T v with the Newton
   !> tangent J of the pairing (GMRES preconditioned by the factor, as the solves of
   !> the iteration) and the gaps' change A' with the projection's motion: the
   !> stiff modes of a curved master are sensitive to it (3.6 per update without it
   !> on the soft disc under a stiff block, docs/contact-robustness.md).
   subroutine compliance_apply(self, x, y)
      class(compliance_t), intent(inout) :: self
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      real(wp), allocatable :: w(:)
      allocate (w(size(self%fixed)), source=0.0_wp)
      call self%contact%multiplier_load(self%mask, x, w)
      call gap_response(self, w, y)
   end subroutine compliance_apply

   !> y = A' J^-1 w on the entries of `mask` (0 elsewhere): the change of their gaps
   !> that the solve of the next iteration makes for a load w (compliance_apply, with
   !> the frozen matrix's factor M in place of J where the pairing is fixed or GMRES
   !> does not converge).
   subroutine gap_response(self, w0, y)
      class(compliance_t), intent(inout) :: self
      real(wp), intent(in) :: w0(:)
      real(wp), intent(out) :: y(:)
      type(error_t), allocatable :: error
      type(contact_tangent_t) :: jt
      type(gmres_result_t) :: res
      real(wp), allocatable :: w(:), du(:)
      logical :: solved
      w = merge(0.0_wp, w0, self%fixed)
      allocate (du(size(self%fixed)), source=0.0_wp)
      solved = .false.
      if (self%sliding) then
         jt%sys => self%sys
         jt%contact => self%contact
         jt%fixed => self%fixed
         jt%sliding = .true.
         call gmres(jt, w, du, multiplier_reduction*safe_norm2(w), 0.0_wp, gmres_restart, gmres_maxit, &
                    0.5_wp, res, error)
         solved = res%converged .and. .not. allocated(error)
         if (allocated(error)) deallocate (error)
      end if
      if (.not. solved) then
         du = 0.0_wp
         call self%sys%solve_system(w, du, error)
         ! a failed solve (the factor solved this system just before) gives no curvature:
         ! the conjugate gradients stop at their last iterate
         if (allocated(error)) du = 0.0_wp
      end if
      where (self%fixed) du = 0.0_wp
      call self%contact%gap_change(self%mask, du, y, solved)
   end subroutine gap_response

   !> y = k x: the plain Uzawa update as the preconditioner.
   subroutine compliance_precondition(self, x, y, error)
      class(compliance_t), intent(inout) :: self
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      type(error_t), allocatable, intent(out) :: error
      y = merge(self%contact%k*x, 0.0_wp, self%mask)
   end subroutine compliance_precondition

   !> Stop when a factor is too ill-conditioned to trust, warn (once: `warned`) when it
   !> costs accuracy (conditioning_verdict); `ratio` is the stiffest closed spring
   !> over the largest elastic diagonal entry (0 without closed contact).
   subroutine judge_conditioning(rc, ratio, contact_closed, warned, error, log)
      real(wp), intent(in) :: rc, ratio
      logical, intent(in) :: contact_closed
      logical, intent(inout) :: warned
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      character(len=120) :: msg
      integer :: verdict
      verdict = conditioning_verdict(rc, ratio, contact_closed)
      select case (verdict)
      case (cond_stop, cond_stop_penalty)
         write (msg, '(a,es9.2,a)') 'error: the system is too ill-conditioned to solve accurately '// &
            '(CHOLMOD''s reciprocal condition estimate ', rc, ')'
         if (verdict == cond_stop_penalty) then
            call fatal_error(error, trim(msg)//new_line('a')//conditioning_hint(ratio), err_solver)
         else
            call fatal_error(error, trim(msg)//new_line('a')//'  = help: look for materials whose moduli '// &
                             'differ by many orders of magnitude, nearly incompressible materials '// &
                             '(nu close to 0.5) or degenerate elements', err_solver)
         end if
      case (cond_warn)
         if (.not. warned .and. present(log)) then
            write (msg, '(a,es9.2,a,es9.2,a)') '  warning: ill-conditioned system (rcond ', rc, &
               '): results may carry relative errors of about ', epsilon(1.0_wp)/rc, ' and more'
            call log%say(trim(msg))
            warned = .true.
         end if
      case (cond_ok)
         continue
      end select
   end subroutine judge_conditioning
end module vemcontact_contact_iteration
