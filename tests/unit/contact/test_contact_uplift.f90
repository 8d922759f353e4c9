!> The uplift diagrams of *UPLIFT (vemcontact_contact_uplift), against the guideline
!> formulas worked by hand: linear between the heads, USACE's drain effectiveness
!> (USBR's rule E = 2/3), a crack from the heel short of the drain line and past it,
!> the hydrostatic variation along an inclined joint, and positions off the joint.
program test_contact_uplift
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: uplift_t
   use vemcontact_contact_uplift, only: joint_position, uplift_head, uplift_pressure
   implicit none
   type(checker_t) :: t
   type(uplift_t) :: up
   real(wp), parameter :: gw = 9810.0_wp
   real(wp) :: hd
   ! exact up to a few roundings of numbers of order 10: 1e-14
   real(wp), parameter :: tol = 1.0e-14_wp

   ! base joint y = 0 from the heel (0, 0) to the toe (10, 0); headwater 12, tailwater 2
   up%heel = [0.0_wp, 0.0_wp]
   up%toe = [10.0_wp, 0.0_wp]
   up%head_heel = 12.0_wp
   up%head_toe = 2.0_wp
   up%gamma = gw
   call t%close(joint_position(up, [2.5_wp, 0.0_wp]), 0.25_wp, tol, 'position along the chord')
   call t%close(joint_position(up, [2.5_wp, -3.0_wp]), 0.25_wp, tol, 'a point off the chord: its projection')
   call t%close(joint_position(up, [-1.0_wp, 0.0_wp]), 0.0_wp, 0.0_wp, 'before the heel: clipped to 0')
   call t%close(joint_position(up, [11.0_wp, 0.0_wp]), 1.0_wp, 0.0_wp, 'beyond the toe: clipped to 1')
   ! no drains: linear, 12 -> 2
   call t%close(uplift_pressure(up, [0.0_wp, 0.0_wp], 0.0_wp), gw*12.0_wp, tol, 'linear: heel')
   call t%close(uplift_pressure(up, [3.0_wp, 0.0_wp], 0.0_wp), gw*9.0_wp, tol, 'linear: x = 3')
   call t%close(uplift_pressure(up, [10.0_wp, 0.0_wp], 0.0_wp), gw*2.0_wp, tol, 'linear: toe, the tailwater')

   ! a drain line at x = 2, E = 0.5 (USACE): head at the drain 2 + 0.5 * 10 = 7
   up%drained = .true.
   up%drain = [2.0_wp, 5.0_wp]
   up%effectiveness = 0.5_wp
   call t%close(uplift_head(up, 0.1_wp, 0.0_wp), 9.5_wp, tol, 'drained: between the heel and the drain')
   call t%close(uplift_head(up, 0.2_wp, 0.0_wp), 7.0_wp, tol, 'drained: the drain head tail + (1 - E) dH')
   call t%close(uplift_head(up, 0.6_wp, 0.0_wp), 4.5_wp, tol, 'drained: between the drain and the toe')
   ! USBR: E = 2/3, a third of the head difference above the tailwater
   up%effectiveness = 2.0_wp/3.0_wp
   hd = 2.0_wp + 10.0_wp/3.0_wp
   call t%close(uplift_head(up, 0.2_wp, 0.0_wp), hd, tol, 'USBR: tail + (head - tail)/3 at the drain')

   ! a crack from the heel to s = 0.1, short of the drain (0.2): headwater in the crack,
   ! from its tip linear to the drain head, then to the toe
   call t%close(uplift_head(up, 0.05_wp, 0.1_wp), 12.0_wp, tol, 'crack: headwater inside')
   call t%close(uplift_head(up, 0.15_wp, 0.1_wp), 12.0_wp + 0.5_wp*(hd - 12.0_wp), tol, &
                'crack short of the drain: restarted at the tip, to the drain head')
   call t%close(uplift_head(up, 0.6_wp, 0.1_wp), uplift_head(up, 0.6_wp, 0.0_wp), tol, &
                'crack short of the drain: unchanged beyond the drain')
   ! past the drain (tip at 0.5): drains without effect, linear from the tip to the toe
   call t%close(uplift_head(up, 0.75_wp, 0.5_wp), 7.0_wp, tol, 'crack past the drain: tip to toe, linear')
   call t%close(uplift_head(up, 1.0_wp, 0.5_wp), 2.0_wp, tol, 'crack past the drain: the tailwater at the toe')
   call t%close(uplift_head(up, 0.7_wp, 1.0_wp), 12.0_wp, tol, 'crack through the whole joint: headwater')

   ! an inclined joint from (0, 0) down to (8, -6): the pressure follows the depth;
   ! heads 12 and 2 as elevations: at the toe p = gw (2 + 6)
   up%drained = .false.
   up%toe = [8.0_wp, -6.0_wp]
   call t%close(uplift_pressure(up, [4.0_wp, -3.0_wp], 0.0_wp), gw*(7.0_wp + 3.0_wp), tol, &
                'inclined joint: gamma (head - y) at mid-length')
   call t%close(uplift_pressure(up, [8.0_wp, -6.0_wp], 0.0_wp), gw*8.0_wp, tol, 'inclined joint: toe')
   ! a tailwater below the joint: no suction
   up%head_toe = -10.0_wp
   call t%close(uplift_pressure(up, [8.0_wp, -6.0_wp], 0.0_wp), 0.0_wp, 0.0_wp, &
                'tailwater below the joint: zero pressure, no suction')
   call t%finish()
end program test_contact_uplift
