!> The return mapping of each tangential law alone (vemcontact_contact_friction):
!> stick inside the bound, radial return on it, open points, cohesion, and the
!> derivatives against finite differences of the mapping itself.
program test_contact_friction
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_contact_friction, only: tangential_law_t, frictionless_law_t, coulomb_law_t, rough_law_t, &
                                          tangential_response_t, tangent_open, tangent_free, tangent_stick, &
                                          tangent_slip
   implicit none
   type(checker_t) :: t
   type(tangential_response_t) :: r, rp, rm
   type(coulomb_law_t) :: law
   type(coulomb_law_t) :: penalty, exact, mohr
   type(frictionless_law_t) :: none
   type(rough_law_t) :: rough

   penalty = coulomb_law_t(mu=0.3_wp, slope=1.0e4_wp, cohesion=0.0_wp)
   exact = coulomb_law_t(mu=0.3_wp, slope=0.0_wp, cohesion=0.0_wp)
   mohr = coulomb_law_t(mu=0.5_wp, slope=0.0_wp, cohesion=2.0_wp)

   ! ---- frictionless: no force, closed or open
   r = none%return_map(5.0_wp, 10.0_wp, 1.0_wp, .true.)
   call t%close(r%force, 0.0_wp, 0.0_wp, 'frictionless: no tangential force')
   call t%equal(r%state, tangent_free, 'frictionless closed point: no tangential state')
   r = none%return_map(5.0_wp, 10.0_wp, 1.0_wp, .false.)
   call t%equal(r%state, tangent_open, 'frictionless open point')
   call t%check(.not. none%frictional(), 'frictionless carries no tangential force')

   ! ---- Coulomb: bound mu N = 3 for N = 10
   r = penalty%return_map(2.9_wp, 10.0_wp, 1.0_wp, .true.)
   call t%equal(r%state, tangent_stick, 'Coulomb below mu N sticks')
   call t%close(r%force, 2.9_wp, 0.0_wp, 'stick: T = T_trial')
   call t%close(r%dtrial, 1.0_wp, 0.0_wp, 'stick: dT/dT_trial = 1')
   call t%close(r%dnormal, 0.0_wp, 0.0_wp, 'stick: dT/dN = 0')
   r = penalty%return_map(-3.1_wp, 10.0_wp, 1.0_wp, .true.)
   call t%equal(r%state, tangent_slip, 'Coulomb beyond mu N slips')
   ! exact: 0.3 * 10 is 3 to one rounding
   call t%close(r%force, -3.0_wp, 4.0_wp*epsilon(1.0_wp), 'slip: T = -mu N, the trial''s sign')
   call t%close(r%dtrial, 0.0_wp, 0.0_wp, 'slip: dT/dT_trial = 0')
   call t%close(r%dnormal, -0.3_wp, 0.0_wp, 'slip: dT/dN = mu sign(T_trial)')
   ! the derivative against a central difference of the mapping (linear on each side:
   ! exact to round-off of the difference, 1e-9 relative for steps of 1e-6)
   rp = penalty%return_map(-3.1_wp, 10.0_wp + 1.0e-6_wp, 1.0_wp, .true.)
   rm = penalty%return_map(-3.1_wp, 10.0_wp - 1.0e-6_wp, 1.0_wp, .true.)
   call t%close((rp%force - rm%force)/2.0e-6_wp, r%dnormal, 1.0e-8_wp, 'slip: dT/dN against a central difference')
   rp = penalty%return_map(2.0_wp + 1.0e-6_wp, 10.0_wp, 1.0_wp, .true.)
   rm = penalty%return_map(2.0_wp - 1.0e-6_wp, 10.0_wp, 1.0_wp, .true.)
   call t%close((rp%force - rm%force)/2.0e-6_wp, 1.0_wp, 1.0e-8_wp, &
                'stick: dT/dT_trial against a central difference')
   r = penalty%return_map(2.0_wp, 10.0_wp, 1.0_wp, .false.)
   call t%equal(r%state, tangent_open, 'Coulomb open point')
   call t%close(r%force, 0.0_wp, 0.0_wp, 'open: no tangential force')
   call t%close(penalty%stick_slope(), 1.0e4_wp, 0.0_wp, 'stick slope kept')
   call t%check(.not. penalty%exact() .and. exact%exact(), 'stick slope: spring; none: exact stick')
   ! closed with zero normal force (a touching point): Coulomb carries nothing
   r = exact%return_map(1.0e-3_wp, 0.0_wp, 1.0_wp, .true.)
   call t%equal(r%state, tangent_slip, 'Coulomb at N = 0 slips')
   call t%close(r%force, 0.0_wp, 0.0_wp, 'Coulomb at N = 0: T = 0')

   ! ---- Mohr-Coulomb: bound c A + mu N = 2 * 1.5 + 0.5 * 4 = 5
   r = mohr%return_map(4.99_wp, 4.0_wp, 1.5_wp, .true.)
   call t%equal(r%state, tangent_stick, 'Mohr-Coulomb below c A + mu N sticks')
   r = mohr%return_map(-6.0_wp, 4.0_wp, 1.5_wp, .true.)
   call t%equal(r%state, tangent_slip, 'Mohr-Coulomb beyond c A + mu N slips')
   call t%close(r%force, -5.0_wp, 4.0_wp*epsilon(1.0_wp), 'Mohr-Coulomb slip: T = -(c A + mu N)')
   ! closed at zero pressure: the cohesion alone holds
   r = mohr%return_map(2.9_wp, 0.0_wp, 1.5_wp, .true.)
   call t%equal(r%state, tangent_stick, 'Mohr-Coulomb at N = 0: the cohesion holds c A')
   r = mohr%return_map(2.9_wp, 4.0_wp, 1.5_wp, .false.)
   call t%equal(r%state, tangent_open, 'Mohr-Coulomb open: nothing, no tension or cohesion')
   call t%close(r%force, 0.0_wp, 0.0_wp, 'Mohr-Coulomb open: T = 0')
   call t%check(mohr%frictional() .and. exact%frictional(), 'Coulomb and Mohr-Coulomb are frictional')
   law = coulomb_law_t(mu=0.0_wp, slope=0.0_wp, cohesion=1.0_wp)
   call t%check(law%frictional(), 'pure cohesion is frictional')
   law = coulomb_law_t(mu=0.0_wp, slope=0.0_wp, cohesion=0.0_wp)
   call t%check(.not. law%frictional(), 'mu = 0 without cohesion is frictionless')

   ! ---- rough: no bound
   r = rough%return_map(1.0e12_wp, 1.0_wp, 1.0_wp, .true.)
   call t%equal(r%state, tangent_stick, 'rough sticks whatever the force')
   call t%close(r%force, 1.0e12_wp, 0.0_wp, 'rough: T = T_trial')
   r = rough%return_map(1.0e12_wp, 1.0_wp, 1.0_wp, .false.)
   call t%equal(r%state, tangent_open, 'rough open point carries nothing')
   call t%check(rough%exact(), 'rough stick is exact')

   call t%finish()
end program test_contact_friction
