!> Load increments (vemcontact_driver_increments): the increment sizes of CalculiX's
!> *STATIC (fixed with DIRECT, automatic otherwise: cut back by 4 down to the minimum,
!> grown by 1.5 after two easy increments, the last ending at the period exactly), the
!> *AMPLITUDE curve, and the loads in force within a step (ramp from the previous
!> step's values, AMPLITUDE=STEP, amplitudes), each against values worked by hand.
program test_increments
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: step_t, amplitude_t, dload_t, dload_pressure
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_driver_increments, only: increment_control_t, amplitude_value, loads_at
   implicit none
   type(checker_t) :: t
   type(increment_control_t) :: c
   type(step_t) :: s
   type(amplitude_t) :: amps(1)
   type(load_state_t) :: prev, cur, st
   real(wp), allocatable :: ends(:)
   real(wp), parameter :: tol = 1.0e-14_wp  ! sums of a few decimal fractions: round-off only
   logical :: ok

   ! DIRECT 0.3 over a period 1: 0.3, 0.6, 0.9 and a last, shorter increment to 1 exactly
   s%dt_initial = 0.3_wp
   s%direct = .true.
   call c%start(s)
   ends = run_all(c)
   call t%equal(size(ends), 4, 'DIRECT 0.3 / 1: four increments')
   call t%close(ends(3), 0.9_wp, tol, 'DIRECT: third increment ends at 0.9')
   call t%close(ends(4), 1.0_wp, 0.0_wp, 'DIRECT: the last ends at the period exactly')
   ! DIRECT 0.25 over 1 (it divides): four increments, the last at 1 exactly
   s%dt_initial = 0.25_wp
   call c%start(s)
   ends = run_all(c)
   call t%equal(size(ends), 4, 'DIRECT 0.25 / 1: four increments')
   call t%close(ends(4), 1.0_wp, 0.0_wp, 'DIRECT 0.25: the last ends at 1 exactly')
   ! automatic, easy increments: 0.3, 0.6, then 1.5 x 0.3 = 0.45 reaches the end
   s%direct = .false.
   s%dt_initial = 0.3_wp
   call c%start(s)
   ends = run_all(c)
   call t%equal(size(ends), 3, 'automatic 0.3 / 1, easy: three increments (grown after two)')
   call t%close(ends(2), 0.6_wp, tol, 'automatic: second increment ends at 0.6')
   ! maximum increment 0.35 caps the growth: 0.3, 0.6, 0.95 (0.35), 1
   s%dt_max = 0.35_wp
   call c%start(s)
   ends = run_all(c)
   call t%equal(size(ends), 4, 'automatic with maximum 0.35: four increments')
   call t%close(ends(3), 0.95_wp, tol, 'automatic with maximum: third ends at 0.95')
   s%dt_max = 1.0e30_wp
   ! cut-back: 0.3 fails -> 0.075; with a minimum of 0.1 the retry is the minimum,
   ! and a failure at the minimum ends the step
   s%dt_min = 0.1_wp
   call c%start(s)
   call c%next()
   call c%cut_back(ok)
   call t%check(ok, 'cut back after a failed increment')
   call t%close(c%dt, 0.1_wp, tol, 'cut back to max(0.3/4, minimum 0.1)')
   call c%next()
   call t%close(c%t_try, 0.1_wp, tol, 'the retry ends at 0.1')
   call c%cut_back(ok)
   call t%check(.not. ok, 'a failure at the minimum increment is final')
   ! without a minimum: CalculiX's default min(initial, 1e-5 period)
   s%dt_min = 0.0_wp
   call c%start(s)
   call t%close(c%dt_min, 1.0e-5_wp, tol, 'default minimum 1e-5 of the period')
   call c%next()
   call c%cut_back(ok)
   call t%close(c%dt, 0.075_wp, tol, 'cut back by a factor 4')
   ! DIRECT never cuts back
   s%direct = .true.
   call c%start(s)
   call c%next()
   call c%cut_back(ok)
   call t%check(.not. ok, 'DIRECT: no cut-back')

   ! amplitude (0, 0), (1, 2), (3, 2), (4, 0): linear between, constant beyond
   amps(1)%name = 'A'
   amps(1)%t = [0.0_wp, 1.0_wp, 3.0_wp, 4.0_wp]
   amps(1)%a = [0.0_wp, 2.0_wp, 2.0_wp, 0.0_wp]
   call t%close(amplitude_value(amps(1), 0.25_wp), 0.5_wp, tol, 'amplitude at 0.25')
   call t%close(amplitude_value(amps(1), 2.0_wp), 2.0_wp, tol, 'amplitude on its plateau')
   call t%close(amplitude_value(amps(1), 3.5_wp), 1.0_wp, tol, 'amplitude at 3.5')
   call t%close(amplitude_value(amps(1), -1.0_wp), 0.0_wp, 0.0_wp, 'amplitude constant before its start')
   call t%close(amplitude_value(amps(1), 9.0_wp), 0.0_wp, 0.0_wp, 'amplitude constant beyond its end')

   ! loads within a step: two dofs; dof 1 prescribed 0.5 (0.1 at the start), dof 2
   ! loaded 30 (10 at the end of the previous step); a pressure 8 on element 1 side 1
   ! (4 before)
   call state(prev, 10.0_wp, 4.0_wp)
   prev%fixed = .false.
   call state(cur, 30.0_wp, 8.0_wp)
   cur%fixed(1) = .true.
   cur%prescribed(1) = 0.5_wp
   s = step_t()
   st = loads_at(s, cur, prev, [0.1_wp, 0.0_wp], 0.25_wp, 0.0_wp, amps)
   call t%close(st%prescribed(1), 0.2_wp, tol, 'RAMP: prescribed displacement from the start value 0.1 to 0.5')
   call t%close(st%force(2), 15.0_wp, tol, 'RAMP: force from 10 to 30 at a quarter')
   call t%close(sum(st%dload%magnitude), 5.0_wp, tol, 'RAMP: pressure from 4 to 8 at a quarter (both loads scaled)')
   st = loads_at(s, cur, prev, [0.1_wp, 0.0_wp], 1.0_wp, 0.0_wp, amps)
   ! exactly (rtol 0): a linear model's increments end with the answer of one increment
   call t%close(st%prescribed(1), 0.5_wp, 0.0_wp, 'RAMP at the end: the prescribed value exactly')
   call t%close(st%force(2), 30.0_wp, 0.0_wp, 'RAMP at the end: the force exactly')
   call t%equal(size(st%dload), 1, 'RAMP at the end: only the step''s own pressure')
   s%ramp = .false.
   st = loads_at(s, cur, prev, [0.1_wp, 0.0_wp], 0.25_wp, 0.0_wp, amps)
   call t%close(st%prescribed(1), 0.5_wp, 0.0_wp, 'AMPLITUDE=STEP: the prescribed value at once')
   call t%close(st%force(2), 30.0_wp, 0.0_wp, 'AMPLITUDE=STEP: the force at once')
   call t%close(sum(st%dload%magnitude), 8.0_wp, 0.0_wp, 'AMPLITUDE=STEP: the pressure at once')
   ! with the amplitude: value times A(step time), the step period 2 -> at frac 0.25
   ! the step time is 0.5, A = 1; total time with a start at 2.5: A(3) = 2
   s%ramp = .true.
   s%period = 2.0_wp
   cur%force_amp(2) = 1
   cur%dload(1)%amp = 1
   st = loads_at(s, cur, prev, [0.1_wp, 0.0_wp], 0.25_wp, 2.5_wp, amps)
   call t%close(st%force(2), 30.0_wp, tol, 'amplitude on the step time: 30 x A(0.5) = 30')
   call t%close(sum(st%dload%magnitude), 8.0_wp, tol, 'amplitude: the previous pressure is replaced, 8 x A(0.5)')
   amps(1)%total_time = .true.
   st = loads_at(s, cur, prev, [0.1_wp, 0.0_wp], 0.25_wp, 2.5_wp, amps)
   call t%close(st%force(2), 60.0_wp, tol, 'TIME=TOTAL TIME: 30 x A(2.5 + 0.5) = 60')
   call t%finish()

contains

   !> Run the increments of `c` to the end (every one converging in one iteration).
   function run_all(c) result(ends)
      type(increment_control_t), intent(inout) :: c
      real(wp), allocatable :: ends(:)
      allocate (ends(0))
      do while (.not. c%finished())
         call c%next()
         call c%accept(1)
         ends = [ends, c%t]
         if (size(ends) > 100) exit
      end do
   end function run_all

   subroutine state(st, force, pressure)
      type(load_state_t), intent(out) :: st
      real(wp), intent(in) :: force, pressure
      allocate (st%fixed(2), source=.false.)
      allocate (st%prescribed(2), source=0.0_wp)
      allocate (st%force(2), source=0.0_wp)
      allocate (st%fixed_amp(2), st%force_amp(2), source=0)
      st%force(2) = force
      st%dload = [dload_t(elem=1, kind=dload_pressure, side=1, magnitude=pressure)]
   end subroutine state
end program test_increments
