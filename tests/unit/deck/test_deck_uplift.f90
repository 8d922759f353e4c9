!> Parsing of *UPLIFT (vemcontact) from tests/data/deck/uplift.inp (run from tests/unit):
!> heel, toe, heads, unit weight, the drain and its default effectiveness (USBR's 2/3),
!> PENETRATION, names in any case; and the load state's rule that a later step's
!> *UPLIFT replaces the one of the same interaction and keeps the others.
program test_deck_uplift
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t
   use vemcontact_deck_reader, only: read_deck
   use vemcontact_driver_load_state, only: load_state_t, init_load_state, advance_load_state
   implicit none
   type(checker_t) :: t
   type(model_t) :: m
   type(error_t), allocatable :: err
   type(load_state_t) :: st
   real(wp), parameter :: tol = 1.0e-15_wp   ! values are read exactly: only rounding of the literal

   call read_deck('../data/deck/uplift.inp', m, err)
   call t%check(.not. allocated(err), 'uplift.inp reads without error')
   if (allocated(err)) then
      print '(a)', err%message
      call t%finish()
   end if
   call t%equal(size(m%steps), 3, 'three steps')
   call t%check(.not. allocated(m%steps(1)%uplift), 'the dry step has no uplift')
   call t%equal(size(m%steps(2)%uplift), 2, 'two uplifts in the wet step')
   associate (u => m%steps(2)%uplift(1))
      call t%equal(u%interaction, 1, 'INTERACTION=soft is the first interaction')
      call t%close(u%gamma, 9.81_wp, tol, 'UNIT WEIGHT')
      call t%check(all(abs(u%heel - [0.0_wp, 1.0_wp]) <= tol) .and. all(abs(u%toe - [2.0_wp, 1.0_wp]) <= tol), &
                   'heel and toe')
      call t%close(u%head_heel, 12.5_wp, tol, 'headwater elevation')
      call t%close(u%head_toe, 2.0_wp, tol, 'tailwater elevation')
      call t%check(u%drained .and. all(abs(u%drain - [0.5_wp, 1.0_wp]) <= tol), 'drain line')
      call t%close(u%effectiveness, 2.0_wp/3.0_wp, tol, 'E omitted: USBR''s rule, 2/3')
      call t%check(.not. u%penetration, 'no PENETRATION')
      call t%equal(u%loc%line, 59, 'location: the keyword line')
   end associate
   associate (u => m%steps(2)%uplift(2))
      call t%equal(u%interaction, 2, 'INTERACTION=HARD')
      call t%check(u%penetration, 'PENETRATION')
      call t%close(u%effectiveness, 0.25_wp, tol, 'E given')
      call t%close(u%head_toe, 1.0_wp, tol, 'a trailing comma is no field')
   end associate
   call t%equal(size(m%steps(3)%uplift), 1, 'the third step names one uplift')

   call init_load_state(m, st)
   call advance_load_state(m%steps(1), st)
   call t%equal(size(st%uplift), 0, 'step 1: none in force')
   call advance_load_state(m%steps(2), st)
   call t%equal(size(st%uplift), 2, 'step 2: both in force')
   call advance_load_state(m%steps(3), st)
   call t%equal(size(st%uplift), 2, 'step 3: still two in force')
   if (size(st%uplift) == 2) then
      call t%close(st%uplift(1)%head_heel, 1.0_wp, tol, 'step 3 replaced the uplift of SOFT')
      call t%check(.not. st%uplift(1)%drained, 'the replacement has no drain')
      call t%check(st%uplift(2)%penetration, 'the uplift of HARD kept')
   end if
   call t%finish()
end program test_deck_uplift
