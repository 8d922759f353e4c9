!> Boundary conditions and loads accumulate over steps with CalculiX's OP meaning.
program test_load_state
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: model_t, step_t, dof_value_t, dload_t, dload_grav, dload_pressure
   use vemcontact_driver_load_state, only: load_state_t, init_load_state, advance_load_state
   implicit none
   type(checker_t) :: t
   type(model_t) :: m
   type(load_state_t) :: st
   type(step_t) :: s1, s2, s3

   m%nnode = 3
   m%initial%boundary = [dof_value_t(1, 1, 0.0_wp)]
   s1%boundary = [dof_value_t(2, 2, 0.1_wp)]
   s1%cload = [dof_value_t(3, 1, 5.0_wp), dof_value_t(3, 2, 1.0_wp)]
   s1%dload = [dload_t(1, dload_grav, 0, 9.81_wp, [0.0_wp, -1.0_wp]), dload_t(1, dload_pressure, 2, 3.0_wp, [0.0_wp, 0.0_wp])]
   ! step 2: OP=MOD changes one load value and one pressure, adds a boundary
   s2%boundary = [dof_value_t(3, 2, -0.2_wp)]
   s2%cload = [dof_value_t(3, 1, 7.0_wp)]
   s2%dload = [dload_t(1, dload_pressure, 2, 4.0_wp, [0.0_wp, 0.0_wp])]
   ! step 3: OP=NEW on boundaries and loads
   s3%boundary_new = .true.
   s3%cload_new = .true.
   s3%dload_new = .true.
   s3%boundary = [dof_value_t(3, 1, 0.0_wp)]

   call init_load_state(m, st)
   call t%check(st%fixed(1) .and. count(st%fixed) == 1, 'model-level boundary')
   call advance_load_state(s1, st)
   call t%equal(count(st%fixed), 2, 'step 1 fixed dofs')
   call t%close(st%prescribed(4), 0.1_wp, 0.0_wp, 'step 1 prescribed value')
   call t%close(st%force(5), 5.0_wp, 0.0_wp, 'step 1 cload x')
   call t%equal(size(st%dload), 2, 'step 1 dloads')
   call advance_load_state(s2, st)
   call t%equal(count(st%fixed), 3, 'step 2 keeps and adds boundaries')
   call t%close(st%force(5), 7.0_wp, 0.0_wp, 'step 2 replaces the cload on the same dof')
   call t%close(st%force(6), 1.0_wp, 0.0_wp, 'step 2 keeps the other cload')
   call t%equal(size(st%dload), 2, 'step 2 replaces the pressure on the same side')
   call t%close(sum(st%dload%magnitude), 9.81_wp + 4.0_wp, 1.0e-15_wp, 'step 2 pressure value')
   call advance_load_state(s3, st)
   call t%check(st%fixed(1) .and. st%fixed(5) .and. count(st%fixed) == 2, &
                'OP=NEW removes step boundaries, keeps model-level ones')
   call t%close(sum(abs(st%force)), 0.0_wp, 0.0_wp, 'OP=NEW removes cloads', atol=0.0_wp)
   call t%equal(size(st%dload), 0, 'OP=NEW removes dloads')
   call t%finish()
end program test_load_state
