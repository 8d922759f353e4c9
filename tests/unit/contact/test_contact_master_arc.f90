!> The reference arc length along a master surface (vemcontact_contact_master_arc):
!> an open chain given out of order, a closed loop and two separate chains, against
!> the segment lengths summed by hand.
program test_contact_master_arc
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_contact_master_arc, only: master_arcs
   implicit none
   type(checker_t) :: t
   real(wp), allocatable :: x(:, :), arc(:), period(:)
   integer(ip), allocatable :: seg(:, :)
   ! the arc lengths are sums of two or three exact lengths (1, 2, 5: a 3-4-5
   ! triangle): exact to a few roundings
   real(wp), parameter :: tol = 4.0_wp*epsilon(1.0_wp)

   ! ---- an open chain 1 -> 2 -> 3 -> 4 (lengths 1, 2, 5), its segments out of order
   x = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 2.0_wp, 4.0_wp, 6.0_wp], [2, 4])
   seg = reshape([3_ip, 4_ip, 1_ip, 2_ip, 2_ip, 3_ip], [2, 3])
   call master_arcs(x, seg, arc, period)
   call t%close(arc(2), 0.0_wp, 0.0_wp, 'open chain: its first segment starts at 0')
   call t%close(arc(3), 1.0_wp, tol, 'open chain: the second starts after the first''s length')
   call t%close(arc(1), 3.0_wp, tol, 'open chain: the third after both')
   call t%check(all(period == 0.0_wp), 'open chain: no period')

   ! ---- a closed loop: the unit square, counter-clockwise from segment 1
   x = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
   seg = reshape([1_ip, 2_ip, 2_ip, 3_ip, 3_ip, 4_ip, 4_ip, 1_ip], [2, 4])
   call master_arcs(x, seg, arc, period)
   call t%close(arc(1), 0.0_wp, 0.0_wp, 'loop: starts at its first segment')
   call t%close(arc(4), 3.0_wp, tol, 'loop: the last segment starts at 3')
   call t%check(all(abs(period - 4.0_wp) <= tol), 'loop: the period is the perimeter')

   ! ---- two chains: 1 -> 2 and 3 -> 4, each from 0
   x = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 5.0_wp, 0.0_wp, 7.0_wp, 0.0_wp], [2, 4])
   seg = reshape([3_ip, 4_ip, 1_ip, 2_ip], [2, 2])
   call master_arcs(x, seg, arc, period)
   call t%check(all(arc == 0.0_wp) .and. all(period == 0.0_wp), 'two chains: each starts at 0, open')

   call t%finish()
end program test_contact_master_arc
