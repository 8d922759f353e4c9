!> Load increments of a step (CalculiX's *STATIC): the increment sizes, the cut-back
!> of an increment that does not converge and the growth after easy ones, and the
!> loads in force at a time within the step (AMPLITUDE=RAMP or STEP of the step,
!> *AMPLITUDE curves of the loads that name one).
!>
!> Automatic incrementation follows CalculiX's (and Abaqus') defaults: an
!> increment that fails is retried at a quarter of its size (never below the
!> minimum: one last try at the minimum, then the step fails); after two
!> consecutive increments that converge in at most `easy_iterations` contact
!> iterations the increment grows by half, never beyond the maximum.  The last
!> increment of a step ends exactly at the step's period.
module vemcontact_driver_increments
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: step_t, amplitude_t, dload_t, uplift_t, procedure_geostatic
   use vemcontact_driver_load_state, only: load_state_t
   implicit none
   private

   public :: increment_control_t, amplitude_value, loads_at, default_dt_min

   !> CalculiX's D_F: an increment that did not converge is retried this much smaller
   real(wp), parameter, public :: cutback_factor = 0.25_wp
   !> CalculiX's D_D: the growth of the increment after easy increments
   real(wp), parameter, public :: growth_factor = 1.5_wp
   !> CalculiX's I_G: an increment converged in at most this many iterations is easy
   integer, parameter, public :: easy_iterations = 4

   !> The state of the incrementation of one step.
   type :: increment_control_t
      real(wp) :: period = 1.0_wp       !< time period of the step
      real(wp) :: dt = 1.0_wp           !< the size of the next increment
      real(wp) :: dt_min = 0.0_wp, dt_max = 1.0e30_wp
      logical :: direct = .false.       !< fixed increments, no cut-back
      real(wp) :: t = 0.0_wp            !< step time reached (last converged increment)
      real(wp) :: t_try = 0.0_wp        !< step time at the end of the increment being tried
      integer :: increment = 0          !< converged increments of the step
      integer :: attempts = 0           !< increments tried (converged or cut back)
      integer :: cutbacks = 0           !< cut-backs in the step
      integer :: easy = 0               !< consecutive easy increments
   contains
      procedure :: start
      procedure :: next
      procedure :: accept
      procedure :: cut_back
      procedure :: finished
      procedure :: step_fraction
   end type increment_control_t

contains

   !> CalculiX's default minimum increment: min(initial increment, 1e-5 period).
   pure real(wp) function default_dt_min(dt_initial, period)
      real(wp), intent(in) :: dt_initial, period
      default_dt_min = min(dt_initial, 1.0e-5_wp*period)
   end function default_dt_min

   !> Start the incrementation of `step`.
   pure subroutine start(self, step)
      class(increment_control_t), intent(inout) :: self
      type(step_t), intent(in) :: step
      self%t = 0.0_wp
      self%t_try = 0.0_wp
      self%increment = 0
      self%attempts = 0
      self%cutbacks = 0
      self%easy = 0
      self%period = step%period
      self%dt = min(step%dt_initial, step%period)
      self%dt_max = step%dt_max
      self%dt_min = step%dt_min
      if (.not. (self%dt_min > 0.0_wp)) self%dt_min = default_dt_min(step%dt_initial, step%period)
      self%direct = step%direct
      if (.not. self%direct) self%dt = min(self%dt, self%dt_max)
   end subroutine start

   !> The next increment: step time t_try at its end.  An increment that would end
   !> within a millionth of an increment of the period ends at the period exactly.
   pure subroutine next(self)
      class(increment_control_t), intent(inout) :: self
      self%attempts = self%attempts + 1
      if (self%t + self%dt >= self%period - 1.0e-6_wp*self%dt) then
         self%t_try = self%period
      else
         self%t_try = self%t + self%dt
      end if
   end subroutine next

   !> The increment converged in `iterations` contact iterations (0 without contact).
   pure subroutine accept(self, iterations)
      class(increment_control_t), intent(inout) :: self
      integer, intent(in) :: iterations
      self%t = self%t_try
      self%increment = self%increment + 1
      if (self%direct) return
      if (iterations <= easy_iterations) then
         self%easy = self%easy + 1
      else
         self%easy = 0
      end if
      if (self%easy >= 2) then
         self%dt = min(growth_factor*self%dt, self%dt_max)
         self%easy = 0
      end if
   end subroutine accept

   !> The increment did not converge: `ok` if a smaller one may be tried (then dt is
   !> the new size), false with fixed increments or when the one tried was the minimum.
   pure subroutine cut_back(self, ok)
      class(increment_control_t), intent(inout) :: self
      logical, intent(out) :: ok
      real(wp) :: tried
      self%easy = 0
      ok = .false.
      if (self%direct) return
      tried = self%t_try - self%t
      ! the minimum itself (up to round-off of t_try - t) has been tried
      if (tried <= self%dt_min*(1.0_wp + 1.0e-12_wp)) return
      self%dt = max(cutback_factor*tried, self%dt_min)
      self%cutbacks = self%cutbacks + 1
      ok = .true.
   end subroutine cut_back

   pure logical function finished(self)
      class(increment_control_t), intent(in) :: self
      finished = self%t >= self%period
   end function finished

   !> The fraction of the step at the end of the increment tried (exactly 1 for the last).
   pure real(wp) function step_fraction(self)
      class(increment_control_t), intent(in) :: self
      if (self%t_try >= self%period) then
         step_fraction = 1.0_wp
      else
         step_fraction = self%t_try/self%period
      end if
   end function step_fraction

   !> The value of amplitude `amp` at time t: linear between its points, constant
   !> beyond its ends (CalculiX).
   pure real(wp) function amplitude_value(amp, t) result(a)
      type(amplitude_t), intent(in) :: amp
      real(wp), intent(in) :: t
      integer :: k, n
      n = size(amp%t)
      if (t <= amp%t(1)) then
         a = amp%a(1)
         return
      end if
      if (t >= amp%t(n)) then
         a = amp%a(n)
         return
      end if
      do k = 2, n
         if (t <= amp%t(k)) exit
      end do
      a = amp%a(k - 1) + (amp%a(k) - amp%a(k - 1))*(t - amp%t(k - 1))/(amp%t(k) - amp%t(k - 1))
   end function amplitude_value

   !> The loads and prescribed displacements in force at `frac` of step `step` (step
   !> time frac * period, total time t_start + frac * period): `cur` is the step's
   !> loads as given (advance_load_state), `prev` the loads applied at the end of
   !> the previous step (loads_at of it at frac = 1), `u0` the displacements at the
   !> start of the step.  AMPLITUDE=RAMP: a value goes linearly from its value at the
   !> end of the previous step (a prescribed displacement from the displacement at
   !> the start of the step; a load removed with OP=NEW goes to zero) to the step's
   !> value; AMPLITUDE=STEP: the step's values at once.  Temperatures and the water
   !> in the joints (*UPLIFT, *PRESSURE PENETRATION) follow the step's ramp
   !> (ramp_temperatures, ramp_uplifts).  A value with an *AMPLITUDE
   !> is the step's value times the amplitude at the step or total time.  At frac = 1
   !> without amplitudes the result is `cur`'s values exactly.  The result has no
   !> amplitudes left (amp = 0, values evaluated).
   pure function loads_at(step, cur, prev, u0, frac, t_start, amps) result(st)
      type(step_t), intent(in) :: step
      type(load_state_t), intent(in) :: cur, prev
      real(wp), intent(in) :: u0(:)
      real(wp), intent(in) :: frac, t_start
      type(amplitude_t), intent(in) :: amps(:)
      type(load_state_t) :: st
      logical :: ramp
      logical, allocatable :: keep_prev(:)
      type(dload_t), allocatable :: scaled(:)
      integer :: d, k, n
      ramp = step%ramp .and. step%procedure /= procedure_geostatic .and. frac < 1.0_wp
      st = cur
      st%fixed_amp = 0
      st%force_amp = 0
      do d = 1, size(cur%fixed)
         if (.not. cur%fixed(d)) cycle
         if (cur%fixed_amp(d) > 0) then
            st%prescribed(d) = cur%prescribed(d)*amp_at(cur%fixed_amp(d))
         else if (ramp) then
            st%prescribed(d) = u0(d) + frac*(cur%prescribed(d) - u0(d))
         end if
      end do
      do d = 1, size(cur%force)
         if (cur%force_amp(d) > 0) then
            st%force(d) = cur%force(d)*amp_at(cur%force_amp(d))
         else if (ramp) then
            st%force(d) = prev%force(d) + frac*(cur%force(d) - prev%force(d))
         end if
      end do
      if (ramp) then
         call ramp_temperatures(cur, prev, frac, st)
         if (allocated(cur%uplift) .and. allocated(prev%uplift)) call ramp_uplifts(cur%uplift, prev%uplift, frac, &
                                                                                  st%uplift)
      end if
      ! distributed loads: the step's scaled by frac (or their amplitude), and with a
      ! ramp the previous step's applied ones scaled by 1 - frac, except those that
      ! the step gives an amplitude (the amplitude alone sets them)
      if (.not. (ramp .or. any(cur%dload%amp > 0))) return
      n = size(cur%dload)
      allocate (keep_prev(size(prev%dload)), source=ramp)
      if (ramp) then
         do k = 1, n
            if (cur%dload(k)%amp == 0) cycle
            where (prev%dload%elem == cur%dload(k)%elem .and. prev%dload%kind == cur%dload(k)%kind .and. &
                   prev%dload%side == cur%dload(k)%side) keep_prev = .false.
         end do
      end if
      allocate (scaled(n + count(keep_prev)))
      scaled(:n) = cur%dload
      do k = 1, n
         if (cur%dload(k)%amp > 0) then
            scaled(k)%magnitude = cur%dload(k)%magnitude*amp_at(cur%dload(k)%amp)
         else if (ramp) then
            scaled(k)%magnitude = frac*cur%dload(k)%magnitude
         end if
         scaled(k)%amp = 0
      end do
      scaled(n + 1:) = pack(prev%dload, keep_prev)
      scaled(n + 1:)%magnitude = (1.0_wp - frac)*scaled(n + 1:)%magnitude
      call move_alloc(scaled, st%dload)
   contains
      pure real(wp) function amp_at(i)
         integer, intent(in) :: i
         if (amps(i)%total_time) then
            amp_at = amplitude_value(amps(i), t_start + frac*step%period)
         else
            amp_at = amplitude_value(amps(i), frac*step%period)
         end if
      end function amp_at
   end function loads_at

   !> With a ramp, the temperatures go linearly from those at the end of the
   !> previous step to the step's, as CalculiX's (T - T0 follows them).
   pure subroutine ramp_temperatures(cur, prev, frac, st)
      type(load_state_t), intent(in) :: cur, prev
      real(wp), intent(in) :: frac
      type(load_state_t), intent(inout) :: st
      if (.not. (allocated(cur%temp) .and. allocated(prev%temp))) return
      st%temp = prev%temp + frac*(cur%temp - prev%temp)
      st%dtemp = st%temp - st%temp0
   end subroutine ramp_temperatures

   !> With a ramp, the water in the joints at `frac` of the step.  An uplift the step
   !> brings in (none before on its interaction or pair) acts with frac of its
   !> pressures.  One that the step changes keeps its geometry (heel, toe, drain
   !> line, pressure penetration or not) and has its heads, drain effectiveness,
   !> unit weight and fluid pressure go linearly from the previous step's values:
   !> the pressures, affine in each of them, go linearly from the old distribution to
   !> the new one (with a head and the drain effectiveness changed together, their
   !> product makes the path between the two slightly curved).  One that the step
   !> gives a new geometry replaces the old at once, as with AMPLITUDE=STEP.
   pure subroutine ramp_uplifts(cur, prev, frac, st)
      type(uplift_t), intent(in) :: cur(:), prev(:)
      real(wp), intent(in) :: frac
      type(uplift_t), intent(inout) :: st(:)
      integer :: k, j
      do k = 1, size(cur)
         j = findloc(prev%interaction == cur(k)%interaction .and. prev%pair == cur(k)%pair, .true., dim=1)
         if (j == 0) then
            st(k)%factor = frac*cur(k)%factor
         else if (same_geometry(cur(k), prev(j))) then
            st(k)%head_heel = lerp(prev(j)%head_heel, cur(k)%head_heel)
            st(k)%head_toe = lerp(prev(j)%head_toe, cur(k)%head_toe)
            st(k)%effectiveness = lerp(prev(j)%effectiveness, cur(k)%effectiveness)
            st(k)%gamma = lerp(prev(j)%gamma, cur(k)%gamma)
            st(k)%fluid_pressure = lerp(prev(j)%fluid_pressure, cur(k)%fluid_pressure)
         end if
      end do
   contains
      pure real(wp) function lerp(a, b)
         real(wp), intent(in) :: a, b
         lerp = a + frac*(b - a)
      end function lerp
   end subroutine ramp_uplifts

   !> Whether two uplifts have the same heel, toe, drain line and kind.
   pure logical function same_geometry(a, b)
      type(uplift_t), intent(in) :: a, b
      same_geometry = all(a%heel == b%heel) .and. all(a%toe == b%toe) .and. (a%drained .eqv. b%drained) .and. &
                      (a%penetration .eqv. b%penetration) .and. a%exposed_slave == b%exposed_slave .and. &
                      a%exposed_master == b%exposed_master
      if (same_geometry .and. a%drained) same_geometry = all(a%drain == b%drain)
   end function same_geometry
end module vemcontact_driver_increments
