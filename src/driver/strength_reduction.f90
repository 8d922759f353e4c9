!> A strength reduction step (*STRENGTH REDUCTION, docs/sliding-safety.md "Factor of
!> safety by strength reduction"): the friction coefficient and cohesion of the reduced
!> interactions are divided by trial factors F, each trial solving equilibrium with the
!> previous step's loads, until the largest F with equilibrium is located (the rules of
!> vemcontact_driver_srm_search).
!>
!> The trial at F = 1 starts from the base state, the previous step's converged
!> displacements and contact state (its friction history included); every later trial
!> from the last converged trial's state.  The search only ever tries factors above
!> the largest that held (srm_search_t), so the trials follow one path of increasing
!> F, as the incremental reduction of Plaxis' safety phase or FLAC's SOLVE fos: friction
!> is path dependent, and a trial from the base state at a larger F would jump over
!> the states between.  A failed trial leaves nothing behind.  Starting next to the
!> limit also makes a failing trial short (2 contact iterations on the dam instead of
!> 7 from the base state).  The factorization is the linear system's own business: a
!> trial whose contact state matches the current factor's (the stick/slip and
!> open/closed key) solves with it.
!>
!> A trial fails, and the reason is named in its log line, when
!> * the contact iteration does not converge (MAXIT iterations, a cycle of its active
!>   set, a factorization that fails or a solution with non-finite values: the matrix
!>   of a mechanism, every node of the joint slipping, is singular); MAXIT and a cycle
!>   only after the same factor was tried again in four steps from the last converged
!>   trial (cut_back), as the increments of a *STATIC step cut back;
!> * it converges to a displacement from the base state larger than `runaway` times
!>   the scale of the base state (its largest |U|, or a millionth of the model's size
!>   when that is zero): a body in frictional equilibrium moves by elastic deformation
!>   and elastic slip, of the order of what the loads already did; a thousand times
!>   that is sliding that the penalty springs merely arrest.
!> Only an interrupt (SIGINT, SIGTERM) ends the step from inside a trial.
module vemcontact_driver_strength_reduction
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t, fatal_error, err_model
   use vemcontact_model, only: model_t, strength_reduction_t
   use vemcontact_driver_linear, only: linear_system_t
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_driver_srm_search, only: srm_search_t, srm_slides, srm_unbounded
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_iteration, only: iteration_record_t
   use vemcontact_contact_tangential, only: make_law
   use vemcontact_log, only: logger_t
   use vemcontact_interrupt, only: is_interrupt
   implicit none
   private

   public :: srm_result_t, run_strength_reduction, reduced_strength

   !> a converged displacement beyond this many times the base state's scale has slid
   real(wp), parameter :: runaway = 1.0e3_wp
   !> the reasons of the failures that a cut-back may cure
   character(len=*), parameter :: reason_maxit = 'no convergence in MAXIT iterations', &
                                  reason_cycle = 'active set cycles'

   !> The trials of a strength reduction step, in trial order, and the factor found.
   type :: srm_result_t
      real(wp), allocatable :: f(:), u_char(:)
      integer, allocatable :: converged(:), iterations(:)
      character(len=64), allocatable :: reason(:)   !< 'converged' or what ended the trial
      real(wp) :: tolerance = 0.0_wp
      real(wp) :: f_lower = 0.0_wp   !< the largest factor that converged: the factor of safety
      real(wp) :: f_upper = 0.0_wp   !< the smallest that failed (+Inf: none up to the largest)
      integer :: factorizations = 0  !< numeric factorizations of all trials
   end type srm_result_t

contains

   !> The friction coefficient and cohesion of pair p at factor f (f = 1: those in
   !> force, the interaction's or a *CHANGE FRICTION's); pairs that the step does not
   !> reduce keep theirs.
   pure subroutine reduced_strength(model, srm, contact, p, f, mu, c)
      type(model_t), intent(in) :: model
      type(strength_reduction_t), intent(in) :: srm
      type(contact_state_t), intent(in) :: contact
      integer, intent(in) :: p
      real(wp), intent(in) :: f
      real(wp), intent(out) :: mu, c
      mu = contact%fric%params(p)%mu
      c = contact%fric%params(p)%cohesion
      if (.not. reduced(model, srm, contact, p)) return
      mu = mu/f
      c = c/f
   end subroutine reduced_strength

   !> Whether pair p is reduced: a Coulomb/Mohr-Coulomb law in force, on the
   !> interaction named (or any).
   pure logical function reduced(model, srm, contact, p)
      type(model_t), intent(in) :: model
      type(strength_reduction_t), intent(in) :: srm
      type(contact_state_t), intent(in) :: contact
      integer, intent(in) :: p
      associate (prm => contact%fric%params(p))
         reduced = prm%has_friction .and. .not. prm%rough .and. (prm%mu > 0.0_wp .or. prm%cohesion > 0.0_wp)
      end associate
      if (srm%interaction > 0) reduced = reduced .and. model%pairs(p)%interaction == srm%interaction
   end function reduced

   !> The strength reduction step: trials from the base state (u, contact), then from
   !> the last converged trial, with the loads `applied` until the search ends; u and contact are then the last converged
   !> trial's (with the unreduced laws again, for the steps after it).  Bodies that
   !> slide at F = 1 end the run (err_model: exit 3).
   subroutine run_strength_reduction(model, srm, sys, applied, u, contact, log, res, error)
      type(model_t), intent(in) :: model
      type(strength_reduction_t), intent(in) :: srm
      type(linear_system_t), intent(inout) :: sys
      type(load_state_t), intent(in) :: applied
      real(wp), intent(inout) :: u(:)
      type(contact_state_t), intent(inout) :: contact
      type(logger_t), intent(inout) :: log
      type(srm_result_t), intent(out) :: res
      type(error_t), allocatable, intent(out) :: error
      type(srm_search_t) :: search
      type(contact_state_t) :: base, best
      type(iteration_record_t), allocatable :: records(:)
      real(wp), allocatable :: u_base(:), u_best(:)
      real(wp) :: f, scale, uc
      logical :: ok
      integer :: iters
      character(len=64) :: why
      search = srm_search_t(tolerance=srm%tolerance, f_first=srm%f_first, f_max=srm%f_max)
      allocate (res%f(0), res%u_char(0), res%converged(0), res%iterations(0), res%reason(0))
      res%tolerance = srm%tolerance
      u_base = u
      base = contact
      scale = base_scale(model, u_base)
      call log%say(trial_header())
      do while (.not. search%done())
         f = search%next_factor()
         if (allocated(u_best)) then
            u = u_best
            contact = best
         else
            u = u_base
            contact = base
         end if
         call set_laws(model, srm, contact, f)
         call run_trial(model, sys, applied, u, u_base, scale, contact, ok, iters, why, error)
         if (allocated(error)) return
         res%factorizations = res%factorizations + sys%factorizations
         ! a contact iteration that ran out of iterations or cycled may only have been
         ! asked too large a step from the last converged trial: again in smaller ones
         if (.not. ok .and. allocated(u_best) .and. (why == reason_maxit .or. why == reason_cycle)) then
            u = u_best
            contact = best
            call cut_back(model, srm, sys, applied, u, u_base, scale, contact, search%f_ok, f, ok, iters, why, &
                          res%factorizations, error)
            if (allocated(error)) return
         end if
         uc = 0.0_wp
         if (ok) uc = char_displacement(model, srm, u, u_base)
         res%f = [res%f, f]
         res%u_char = [res%u_char, uc]
         res%converged = [res%converged, merge(1, 0, ok)]
         res%iterations = [res%iterations, iters]
         res%reason = [character(len=64) :: res%reason, why]
         call log%say(trial_line(size(res%f), f, ok, why, iters, uc))
         ! the estimate that the probes bracket, unless the deck gives the first trial
         if (search%trials == 0 .and. ok .and. .not. srm%first_given) &
            search%estimate = mobilized_ratio(model, srm, contact)
         call search%record(f, ok)
         if (ok) then
            u_best = u
            best = contact
            records = sys%records
         end if
      end do
      if (search%phase == srm_slides) then
         u = u_base
         contact = base
         call fatal_error(error, 'error: no equilibrium at F = 1: the bodies slide ('//trim(why)//')'// &
                          new_line('a')//'  = help: the joints cannot carry the loads of the previous step '// &
                          'with their friction as given; the factor of safety is below 1', err_model)
         return
      end if
      u = u_best
      contact = best
      ! the iteration records of the step: those of the state it reports
      sys%records = records
      res%f_lower = search%f_ok
      res%f_upper = search%f_fail
      if (search%phase == srm_unbounded) res%f_upper = huge(1.0_wp)
      ! the steps after this one have the strengths as given
      call set_laws(model, srm, contact, 1.0_wp)
   end subroutine run_strength_reduction

   !> One trial: the contact iteration from the base state; ok, its iterations, and the
   !> reason it ended.  Errors of the solve are the trial's failure, except interrupts.
   subroutine run_trial(model, sys, applied, u, u_base, scale, contact, ok, iters, why, error)
      type(model_t), intent(in) :: model
      type(linear_system_t), intent(inout) :: sys
      type(load_state_t), intent(in) :: applied
      real(wp), intent(inout) :: u(:)
      real(wp), intent(in) :: u_base(:), scale
      type(contact_state_t), intent(inout) :: contact
      logical, intent(out) :: ok
      integer, intent(out) :: iters
      character(len=*), intent(out) :: why
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      call sys%solve_state(model, applied, u, err, contact)
      iters = sys%iterations
      ok = .not. allocated(err)
      if (ok) then
         why = 'converged'
         if (maxval(abs(u - u_base)) > runaway*scale) then
            ok = .false.
            why = 'displacement grows without bound'
         end if
         return
      end if
      if (is_interrupt(err%code)) then
         call move_alloc(err, error)
         return
      end if
      why = failure_reason(err%message, iters, model%controls%max_iterations)
   end subroutine run_trial

   !> A trial at f whose contact iteration did not converge (MAXIT, a cycle), again in
   !> `nsub` equal steps of the factor from the last converged trial's state at f_ok (u,
   !> contact on entry), each from the one before: the increments' cut-back, a quarter
   !> (CalculiX's D_F).  ok when every step converges; iters adds their iterations; the
   !> reason says "(cut back)".
   subroutine cut_back(model, srm, sys, applied, u, u_base, scale, contact, f_ok, f, ok, iters, why, nfact, error)
      type(model_t), intent(in) :: model
      type(strength_reduction_t), intent(in) :: srm
      type(linear_system_t), intent(inout) :: sys
      type(load_state_t), intent(in) :: applied
      real(wp), intent(inout) :: u(:)
      real(wp), intent(in) :: u_base(:), scale, f_ok, f
      type(contact_state_t), intent(inout) :: contact
      logical, intent(out) :: ok
      integer, intent(inout) :: iters
      character(len=*), intent(out) :: why
      integer, intent(inout) :: nfact   !< numeric factorizations, the steps' added
      type(error_t), allocatable, intent(out) :: error
      integer, parameter :: nsub = 4
      integer :: k, it
      ok = .false.
      do k = 1, nsub
         call set_laws(model, srm, contact, f_ok + (f - f_ok)*real(k, wp)/real(nsub, wp))
         call run_trial(model, sys, applied, u, u_base, scale, contact, ok, it, why, error)
         if (allocated(error)) return
         nfact = nfact + sys%factorizations
         iters = iters + it
         if (.not. ok) exit
      end do
      why = trim(why)//' (cut back)'
   end subroutine cut_back

   !> What ended a trial whose solve failed, from its message.
   pure function failure_reason(msg, iters, maxit) result(why)
      character(len=*), intent(in) :: msg
      integer, intent(in) :: iters, maxit
      character(len=64) :: why
      if (index(msg, 'NaN') > 0 .or. index(msg, 'singular') > 0 .or. index(msg, 'positive') > 0) then
         why = 'singular matrix (a mechanism)'
      else if (index(msg, 'bodies slide') > 0) then
         why = 'a body slides on its joints (a mechanism)'
      else if (index(msg, 'cycle') > 0) then
         why = reason_cycle
      else if (iters >= maxit) then
         why = reason_maxit
      else if (index(msg, 'condition') > 0) then
         why = 'ill-conditioned matrix (a mechanism)'
      else
         why = 'contact iteration failed'
      end if
   end function failure_reason

   !> The estimate of the factor of safety from a converged state with the strengths as
   !> given: for each reduced pair, the strength its closed entries offer,
   !> sum(mu N + c A), over the shear they carry, |sum T| (N, T the balanced normal and
   !> tangential forces, what CPRESS and CSHEAR report); the smallest over the pairs that
   !> carry shear (0: none does).  For one planar joint that stays closed, sum N and
   !> sum T are the resultants the loads impose whatever F is, so the ratio is the
   !> limit-equilibrium factor itself; elsewhere it only guides the first two trials.
   pure real(wp) function mobilized_ratio(model, srm, contact) result(r)
      type(model_t), intent(in) :: model
      type(strength_reduction_t), intent(in) :: srm
      type(contact_state_t), intent(in) :: contact
      real(wp) :: mu, c, strength, shear, scale
      integer :: p, i
      r = 0.0_wp
      if (.not. allocated(contact%balanced)) return
      do p = 1, size(model%pairs)
         if (.not. reduced(model, srm, contact, p)) cycle
         call reduced_strength(model, srm, contact, p, 1.0_wp, mu, c)
         strength = 0.0_wp
         shear = 0.0_wp
         scale = 0.0_wp
         do i = 1, contact%n
            if (contact%pair(i) /= p .or. .not. contact%active(i) .or. contact%iseg(i) <= 0) cycle
            strength = strength + mu*max(contact%balanced(i), 0.0_wp) + c*contact%length(i)*contact%thick(i)
            shear = shear + contact%fric%balanced(i)
            scale = scale + abs(contact%fric%balanced(i))
         end do
         ! a pair whose shear cancels to round-off carries none
         if (.not. (abs(shear) > 1.0e-9_wp*scale .and. strength > 0.0_wp)) cycle
         if (r > 0.0_wp) then
            r = min(r, strength/abs(shear))
         else
            r = strength/abs(shear)
         end if
      end do
   end function mobilized_ratio

   !> The tangential laws of every pair at factor f.
   subroutine set_laws(model, srm, contact, f)
      type(model_t), intent(in) :: model
      type(strength_reduction_t), intent(in) :: srm
      type(contact_state_t), intent(inout) :: contact
      real(wp), intent(in) :: f
      real(wp) :: mu, c
      integer :: p
      do p = 1, size(model%pairs)
         if (.not. reduced(model, srm, contact, p)) cycle
         call reduced_strength(model, srm, contact, p, f, mu, c)
         associate (prm => contact%fric%params(p))
            call make_law(prm%has_friction, prm%rough, mu, prm%slope, c, contact%fric%laws(p))
         end associate
      end do
   end subroutine set_laws

   !> The displacement scale of the base state: its largest |U|, or a millionth of the
   !> model's size when nothing has moved yet.
   pure real(wp) function base_scale(model, u_base) result(s)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u_base(:)
      real(wp) :: size_
      size_ = max(maxval(model%x(1, :)) - minval(model%x(1, :)), maxval(model%x(2, :)) - minval(model%x(2, :)))
      s = maxval(abs(u_base))
      if (.not. (s > 0.0_wp)) s = 1.0e-6_wp*size_
   end function base_scale

   !> The largest |U - U_base| of the step's node set (every node without NSET).
   pure real(wp) function char_displacement(model, srm, u, u_base) result(d)
      type(model_t), intent(in) :: model
      type(strength_reduction_t), intent(in) :: srm
      real(wp), intent(in) :: u(:), u_base(:)
      integer :: k, i
      d = 0.0_wp
      if (srm%nset == 0) then
         do i = 1, int(model%nnode)
            d = max(d, norm2(u(2*i - 1:2*i) - u_base(2*i - 1:2*i)))
         end do
      else
         do k = 1, size(model%nsets(srm%nset)%items)
            i = int(model%nsets(srm%nset)%items(k))
            d = max(d, norm2(u(2*i - 1:2*i) - u_base(2*i - 1:2*i)))
         end do
      end if
   end function char_displacement

   pure function trial_header() result(s)
      character(len=:), allocatable :: s
      s = '  strength reduction: trial, F, outcome, contact iterations, u_char'
   end function trial_header

   !> "    trial 3  F = 1.750000  converged  (7 iterations)  u_char = 1.2345E-03"
   pure function trial_line(k, f, ok, why, iters, uc) result(s)
      integer, intent(in) :: k, iters
      real(wp), intent(in) :: f, uc
      logical, intent(in) :: ok
      character(len=*), intent(in) :: why
      character(len=:), allocatable :: s
      character(len=200) :: b
      if (ok) then
         write (b, '(4x,a,i0,a,f12.6,a,i0,a,es12.5)') 'trial ', k, '  F = ', f, '  '//trim(why)//'  (', iters, &
            ' iterations)  u_char = ', uc
      else
         write (b, '(4x,a,i0,a,f12.6,a,i0,a)') 'trial ', k, '  F = ', f, '  failed: '//trim(why)//'  (', iters, &
            ' iterations)'
      end if
      s = trim(b)
   end function trial_line
end module vemcontact_driver_strength_reduction
