!> Each rule of the contact iteration alone (vemcontact_contact_rules): the line
!> search against a hand-solved piecewise-quadratic energy, the hold, the cycle
!> test, the conditioning verdicts, the residual norm and
!> the reuse key of the factorization, the help of a run that did not converge.
program test_contact_rules
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_rules, only: line_search_step, needs_line_search, hold_nodes, &
                                       is_cycle, conditioning_verdict, residual_norm, matrix_key_t, key_of, &
                                       same_key, cond_ok, cond_warn, cond_stop, cond_stop_penalty, armijo, &
                                       nonconvergence_hint
   implicit none
   type(checker_t) :: t
   real(wp) :: step, tstar, tarm, disc
   logical :: hist(2, 0:2)
   real(wp) :: gaps(2, 0:2)
   type(contact_state_t) :: c
   type(matrix_key_t) :: key


   ! ---- line search: E(t) = a t + b t^2/2 + k/2 (<-(g0 + t h)>^2 - <-g0>^2)
   ! no contact along the step (h = 0): the solve's own minimum, t = 1
   step = line_search_step(-1.0_wp, 1.0_wp, [10.0_wp], [0.5_wp], [0.0_wp])
   call t%close(step, 1.0_wp, 0.0_wp, 'no new contact: the full step')
   ! a node at gap 0.5 closing at t = 0.5 with k = 10: E'(t) = -1 + t + 10 (t - 1/2) for
   ! t > 1/2, minimum t* = 6/11; the longest Armijo step solves
   ! E(t) = c t E'(0) = -c t: (1/2 + 5) t^2 - (1 + 5 - c) t + 5/4 = 0, the larger root
   step = line_search_step(-1.0_wp, 1.0_wp, [10.0_wp], [0.5_wp], [-1.0_wp])
   tstar = 6.0_wp/11.0_wp
   disc = (6.0_wp - armijo)**2 - 4.0_wp*5.5_wp*1.25_wp
   tarm = ((6.0_wp - armijo) + sqrt(disc))/(2.0_wp*5.5_wp)
   call t%close(step, tarm, 1.0e-12_wp, 'overshooting step cut to the longest Armijo step')
   call t%check(step > tstar .and. step < 1.0_wp, 'the cut step lies between the minimum and 1')
   ! no descent at t = 0 (round-off at convergence): keep the solve
   step = line_search_step(1.0e-20_wp, 1.0_wp, [10.0_wp], [0.5_wp], [-1.0_wp])
   call t%close(step, 1.0_wp, 0.0_wp, 'no descent: the full step')
   call t%check(.not. needs_line_search([.true., .false.], [-1.0_wp, 1.0_wp], [-2.0_wp, 0.5_wp]), &
                'closed set kept, nothing new closes: no line search')
   call t%check(needs_line_search([.true., .false.], [-1.0_wp, 1.0_wp], [-2.0_wp, -0.5_wp]), &
                'an open node penetrates at the end of the step: line search')
   call t%check(needs_line_search([.false., .false.], [-1.0_wp, 1.0_wp], [-2.0_wp, 0.5_wp]), &
                'a node closed at the start but not in the solve: line search')

   ! ---- hold: closed, frozen gap closed, re-paired gap open, not held before
   call t%check(all(hold_nodes([.true., .true., .true., .false.], [-1.0_wp, -1.0_wp, 1.0_wp, -1.0_wp], &
                               [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp], [.false., .true., .false., .false.]) .eqv. &
                    [.true., .false., .false., .false.]), 'hold only nodes opened by the re-pairing, once')

   ! ---- cycle: the same active set and gaps as an earlier iteration
   hist(:, 0) = [.true., .false.]
   hist(:, 1) = [.true., .true.]
   gaps(:, 0) = [-1.0e-3_wp, 2.0e-3_wp]
   gaps(:, 1) = [-1.0e-3_wp, -1.0e-4_wp]
   call t%equal(is_cycle(hist, gaps, [.true., .false.], [-1.0e-3_wp, 2.0e-3_wp], 2, 1.0e-3_wp, 1.0_wp), 0, &
                'back to the start: a cycle with iteration 0')
   call t%equal(is_cycle(hist, gaps, [.true., .false.], [-1.1e-3_wp, 2.0e-3_wp], 2, 1.0e-3_wp, 1.0_wp), -1, &
                'the same active set with other gaps is no cycle')
   call t%equal(is_cycle(hist, gaps, [.false., .false.], [-1.0e-3_wp, 2.0e-3_wp], 2, 1.0e-3_wp, 1.0_wp), -1, &
                'another active set is no cycle')

   ! ---- conditioning
   call t%equal(conditioning_verdict(-1.0_wp, 1.0_wp, .true.), cond_ok, 'no estimate: trusted')
   call t%equal(conditioning_verdict(1.0e-6_wp, 1.0_wp, .true.), cond_ok, 'well conditioned')
   call t%equal(conditioning_verdict(1.0e-10_wp*0.5_wp, 0.5_wp, .true.), cond_warn, &
                'soft springs: warn below 1e-9 only')
   call t%equal(conditioning_verdict(5.0e-11_wp, 10.0_wp, .true.), cond_stop_penalty, &
                'stiff closed springs: stop below 1e-10')
   call t%equal(conditioning_verdict(5.0e-13_wp, 0.0_wp, .false.), cond_stop, 'stop below 1e-12')

   ! ---- residual norm: |r| / ((kmax + kc) |u| + |f| + |fc|)
   call t%close(residual_norm([3.0_wp, 4.0_wp], [1.0_wp, 0.0_wp], [0.0_wp, 2.0_wp], [0.0_wp, 0.0_wp], &
                              2.0_wp, 1.0_wp), 1.0_wp, 1.0e-15_wp, 'residual relative to the forces')
   call t%close(residual_norm([0.0_wp], [0.0_wp], [0.0_wp], [0.0_wp], 1.0_wp, 0.0_wp), 0.0_wp, 0.0_wp, &
                'nothing loaded: zero')

   ! ---- reuse key: same active set, pairing and springs
   c%n = 2
   c%active = [.true., .false.]
   c%iseg = [1_ip, 0_ip]
   c%xi = [0.25_wp, 0.0_wp]
   c%normal = reshape([0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp], [2, 2])
   c%k = [1.0_wp, 1.0_wp]
   call t%check(.not. same_key(key, c), 'no factor yet: no reuse')
   key = key_of(c)
   call t%check(same_key(key, c), 'the same contact matrix: reuse')
   c%xi(2) = 0.7_wp
   call t%check(same_key(key, c), 'an open entry re-paired: the matrix is the same')
   c%xi(1) = 0.3_wp
   call t%check(.not. same_key(key, c), 'an active entry re-paired: refactorize')
   c%xi(1) = 0.25_wp
   c%active(2) = .true.
   call t%check(.not. same_key(key, c), 'another active set: refactorize')
   c%active(2) = .false.
   c%k(1) = 100.0_wp
   call t%check(.not. same_key(key, c), 'a stiffer spring (HARD after its search): refactorize')

   ! ---- the help of a run that did not converge names only what the run can change
   call t%check(index(nonconvergence_hint(.false., .true., 0.0_wp), 'SURFACE TO SURFACE') == 0 .and. &
                index(nonconvergence_hint(.false., .true., 0.0_wp), 'SMALL SLIDING') == 0, &
                'fixed pairing (SURFACE TO SURFACE, HARD): no pairing advice')
   call t%check(index(nonconvergence_hint(.false., .true., 0.0_wp), 'STIFFNESS SCALE FACTOR') > 0, &
                'HARD: a stiffer augmentation')
   call t%check(index(nonconvergence_hint(.true., .false., 1.0e3_wp), 'SMALL SLIDING') > 0, &
                'finite sliding: fix the pairing')
   call t%check(index(nonconvergence_hint(.true., .false., 1.0e3_wp), 'HARD') == 0, &
                'a moderate LINEAR penalty: no HARD advice')
   call t%check(index(nonconvergence_hint(.true., .false., 1.0e8_wp), 'PRESSURE-OVERCLOSURE=HARD') > 0, &
                'a stiff LINEAR penalty with finite sliding: HARD recommended')
   call t%check(index(nonconvergence_hint(.true., .true., 0.0_wp), 'STIFFNESS SCALE FACTOR') > 0 .and. &
                index(nonconvergence_hint(.false., .false., 0.0_wp), 'STIFFNESS SCALE FACTOR') == 0, &
                'augmentation advice to HARD runs only')
   call t%finish()
end program test_contact_rules
