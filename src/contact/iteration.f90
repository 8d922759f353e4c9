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
                                       hold_nodes, newton_rises, is_cycle, conditioning_verdict, &
                                       conditioning_hint, residual_norm, max_rises, cond_ok, cond_warn, &
                                       cond_stop, cond_stop_penalty
   use vemcontact_log, only: logger_t
   use vemcontact_clock, only: wall_time
   implicit none
   private

   public :: contact_system_t, iteration_record_t, solve_contact, judge_conditioning

   !> One iteration, as logged and written to the results.
   type :: iteration_record_t
      integer :: iteration = 0
      integer :: active = 0              !< closed slave entries after the iteration
      integer :: changed = 0             !< entries whose state changed (holds included)
      real(wp) :: residual = 0.0_wp      !< relative residual (residual_norm)
      real(wp) :: penetration = 0.0_wp   !< largest overclosure
      real(wp) :: pressure = 0.0_wp      !< largest contact pressure
      real(wp) :: step = 1.0_wp          !< line search step
      logical :: factorized = .false.    !< a numeric factorization was paid
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
      real(wp) :: t_factorize = 0, t_solve = 0, t_search = 0
      type(iteration_record_t), allocatable :: records(:)
   contains
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

contains

   !> Solve for the displacements u of a load state with contact: u holds the
   !> previous state on entry (the pairing starts from it) and the new one on exit.
   subroutine solve_contact(sys, model, fixed, prescribed, fext, u, contact, error, log)
      class(contact_system_t), intent(inout) :: sys
      type(model_t), intent(in) :: model
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: prescribed(:), fext(:)
      real(wp), intent(inout) :: u(:)
      type(contact_state_t), intent(inout) :: contact
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      logical, allocatable :: history(:, :), hold(:), held(:)
      integer(ip), allocatable :: iseg_start(:)
      real(wp), allocatable :: f(:), ku(:), fc(:), r(:), u0(:), gaps(:, :), gfrozen(:)
      real(wp) :: t0, rel, kmax, t_iter, t_fact, t_srch, step, rc_min, rel_prev, overclosure, change, rc
      logical :: warned, newton_solve, same_matrix, rebuilt
      integer :: it, nchanged, maxit, nrise, j
      character(len=160) :: buf
      type(iteration_record_t) :: rec

      allocate (f(size(u)), ku(size(u)), fc(size(u)), r(size(u)))
      maxit = model%controls%max_iterations
      warned = .false.
      kmax = sys%largest_elastic_diagonal()
      allocate (history(contact%n, 0:maxit), gaps(contact%n, 0:maxit), gfrozen(contact%n))
      allocate (held(contact%n), source=.false.)
      if (allocated(sys%records)) deallocate (sys%records)
      allocate (sys%records(0))
      sys%iterations = 0
      sys%factorizations = 0
      sys%refactorized = .false.
      sys%t_factorize = 0
      sys%t_solve = 0
      rc_min = 1.0_wp
      rel_prev = huge(1.0_wp)
      nrise = 0
      call contact%set_geometric(.true.)
      call contact%start_state()
      ! start from the state left by the previous step (or the undeformed one)
      t0 = wall_time()
      call contact%project(model, u, error)
      if (allocated(error)) return
      call contact%update_active(nchanged)
      sys%t_search = wall_time() - t0
      iseg_start = contact%iseg
      history(:, 0) = contact%active
      gaps(:, 0) = merge(contact%gap, 0.0_wp, contact%iseg > 0)
      if (present(log)) call log%say('  iter  active  changed     residual  max penetration  max pressure'// &
                                     '    time [s]  factorize [s]  search [s]    step')
      do it = 1, maxit
         sys%iterations = it
         t_iter = wall_time()
         call sys%contact_matrix(model, contact, u, fixed, prescribed, fext, f, rebuilt, error)
         if (allocated(error)) return
         if (rebuilt .and. present(log)) call log%say('        (contact pairs moved: matrix pattern rebuilt)')
         ! the matrix of the current factor: solve again without factorizing
         newton_solve = contact%newton()
         same_matrix = sys%factored .and. .not. rebuilt
         if (same_matrix) same_matrix = .not. any(fixed .neqv. sys%factored_fixed)
         if (same_matrix) same_matrix = same_key(sys%factored_key, contact)
         t_fact = 0.0_wp
         if (.not. same_matrix) then
            t0 = wall_time()
            sys%factored = .false.
            call sys%numeric_factorize(error)
            if (allocated(error) .and. newton_solve) then
               ! the indefinite geometric part tipped the matrix: go on without it
               deallocate (error)
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
            sys%t_factorize = sys%t_factorize + t_fact
            sys%factorizations = sys%factorizations + 1
            sys%factored = .true.
            sys%factored_fixed = fixed
            sys%factored_key = key_of(contact)
            sys%refactorized = .true.
            rc = sys%rcond()
            call judge_conditioning(rc, merge(maxval(contact%k, mask=contact%active, dim=1)/kmax, 0.0_wp, &
                                              any(contact%active)), any(contact%active), warned, error, log)
            if (allocated(error)) return
            if (rc > 0.0_wp) rc_min = min(rc_min, rc)
         end if
         ! the start of the step, with this state's prescribed values
         u0 = merge(prescribed, u, fixed)
         call timed_solve(f, u)
         if (allocated(error)) return
         if (.not. all(abs(u) <= huge(1.0_wp))) then
            call fatal_error(error, 'error: the solution has NaN or infinite values: the model is '// &
                             'numerically singular', err_solver)
            return
         end if
         if (.not. newton_solve) then
            ! one step of iterative refinement with the residual from the gaps: the
            ! backward error of the factorization is eps times the stiffest spring,
            ! which at K h/E = 1e7 leaves 2e-8 in the contact forces; the refined
            ! solve brings it to the round-off of the elastic forces
            call refine(u)
            if (allocated(error)) return
            ! a solve without the geometric term minimizes the frozen-pairing energy
            ! with the current springs: cut it when it overshoots into new contact
            step = energy_step(u0, u)
         else
            step = 1.0_wp
         end if
         if (step < 1.0_wp) u = u0 + step*(u - u0)

         ! new pairing and active set (closed nodes opened by the re-pairing alone
         ! held, hold_nodes), and the residual of the equilibrium with them
         t0 = wall_time()
         call contact%frozen_gaps(u, gfrozen)
         call contact%project(model, u, error)
         if (allocated(error)) return
         hold = hold_nodes(contact%active, gfrozen, contact%gap, held)
         call contact%update_active(nchanged, hold)
         held = hold .and. contact%active
         t_srch = wall_time() - t0
         sys%t_search = sys%t_search + t_srch
         call sys%elastic_times(u, ku)
         fc = 0.0_wp
         call contact%forces(fc)
         r = fext - ku - fc
         where (fixed) r = 0.0_wp
         rel = residual_norm(r, u, merge(0.0_wp, fext, fixed), fc, kmax, &
                             merge(maxval(contact%k, mask=contact%active, dim=1), 0.0_wp, any(contact%active)))
         rec = iteration_record_t(it, count(contact%active), nchanged, rel, contact%max_penetration(), &
                                  contact%max_pressure(), step, .not. same_matrix, wall_time() - t_iter)
         sys%records = [sys%records, rec]
         write (buf, '(2x,i4,2x,i6,2x,i7,2x,es11.3,2x,es15.4,2x,es12.4,2x,f10.4,2x,f13.4,2x,f10.6,2x,f6.4)') it, &
            rec%active, nchanged, rel, rec%penetration, rec%pressure, rec%time, t_fact, t_srch, step
         if (present(log)) call log%say(trim(buf))
         history(:, it) = contact%active
         gaps(:, it) = merge(contact%gap, 0.0_wp, contact%iseg > 0)
         if (nchanged == 0 .and. rel <= model%controls%residual_tol) then
            if (contact%has_hard()) then
               ! HARD: the augmented Lagrangian's Uzawa update; converged once the solve
               ! left no overclosure beyond the tolerance and the update would change no
               ! force by more than the residual tolerance (the pressures' accuracy).
               ! The gaps' round-off is excluded: a few ulps of the coordinates (the
               ! reference gaps) and of the displacements; on the dam (coordinates 25 m,
               ! K = 4e13 Pa/m) it is worth 1e-6 of the forces, which the updates only stir.
               ! From the first update on, the geometric part of finite sliding is off
               ! for the step: its right-hand side belongs to the pairing of the solve
               ! it was made for, and kept with a new one it held the residual at 2e-7
               ! (voronoi_500 of example 3, NODE TO SURFACE with HARD); without it the
               ! pairing converges as the frozen-pairing fixed point (21 iterations there).
               call contact%augment(16.0_wp*epsilon(1.0_wp)*maxval(abs(u)), &
                                    16.0_wp*epsilon(1.0_wp)*maxval(abs(model%x)), overclosure, change)
               if (overclosure > model%controls%overclosure_tol .or. &
                   change > model%controls%residual_tol) then
                  ! where the pairing is fixed (SMALL SLIDING, SURFACE TO SURFACE) the
                  ! matrix then holds and only the right-hand side changes
                  call contact%set_geometric(.false.)
                  cycle
               end if
            end if
            call contact%set_balanced(model, ku - fext, fixed)
            call report_slid_off()
            return
         end if
         nrise = newton_rises(nrise, newton_solve, rel, rel_prev)
         if (nrise >= max_rises) call geometric_off('three Newton steps in a row raised the residual')
         rel_prev = rel
         if (nchanged > 0) then
            j = is_cycle(history, gaps, contact%active, gaps(:, it), it, rc_min, maxval(abs(u)))
            if (j >= 0) then
               write (buf, '(a,i0,a,i0)') 'error: contact iterations cycle: iteration ', it, &
                  ' returns to the active set and gaps of iteration ', j
               call fatal_error(error, trim(buf)//' (the penalty may be too large for the mesh, or a '// &
                                'slave node sits at the end of a master surface)', err_solver)
               return
            end if
         end if
      end do
      write (buf, '(a,i0,a,es10.3,a)') 'error: contact iterations did not converge in ', maxit, &
         ' iterations (relative residual ', rel, ')'
      call fatal_error(error, trim(buf)//'; raise MAXIT on *CONTACT CONTROLS or check the penalty'// &
                       new_line('a')//'  = help: node-to-segment contact with finite sliding re-pairs the '// &
                       'nodes at every iteration and can alternate where they face master vertices; '// &
                       'TYPE=SURFACE TO SURFACE (VEM bodies) or SMALL SLIDING keep the pairing fixed', err_solver)
   contains
      subroutine timed_solve(rhs, x)
         real(wp), intent(in) :: rhs(:)
         real(wp), intent(inout) :: x(:)
         real(wp) :: ts
         ts = wall_time()
         call sys%solve_system(rhs, x, error)
         sys%t_solve = sys%t_solve + (wall_time() - ts)
      end subroutine timed_solve

      !> u <- u + A^-1 (b - A u) with b - A u = f_ext - K u - f_c(u), the contact
      !> forces of the frozen pairing from the gaps (contact_state_t%linear_forces).
      subroutine refine(x)
         real(wp), intent(inout) :: x(:)
         real(wp), allocatable :: dx(:)
         call sys%elastic_times(x, ku)
         fc = 0.0_wp
         call contact%linear_forces(x, fc)
         r = fext - ku - fc
         where (fixed) r = 0.0_wp
         allocate (dx(size(x)), source=0.0_wp)
         call timed_solve(r, dx)
         if (allocated(error)) return
         x = x + dx
      end subroutine refine

      !> The line search along the solve from ua to ub (line_search_step), with the
      !> gaps frozen and shifted by lambda/k for HARD entries.
      real(wp) function energy_step(ua, ub) result(t)
         real(wp), intent(in) :: ua(:), ub(:)
         real(wp), allocatable :: d(:), kd(:), g0(:), h(:)
         t = 1.0_wp
         allocate (g0(contact%n), h(contact%n))
         call contact%frozen_gaps(ua, g0)
         call contact%frozen_gaps(ub, h)
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
         d = merge(0.0_wp, ub - ua, fixed)
         allocate (kd(size(d)))
         call sys%elastic_times(d, kd)
         call sys%elastic_times(ua, ku)
         t = line_search_step(dot_product(d, ku - fext), dot_product(d, kd), contact%k, g0, h)
      end function energy_step

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

      subroutine geometric_off(why)
         character(len=*), intent(in) :: why
         call contact%set_geometric(.false.)
         if (present(log)) call log%say('        (geometric contact stiffness off for this step: '//why//')')
      end subroutine geometric_off
   end subroutine solve_contact

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
