!> The pressure of a SURFACE TO SURFACE pair on the slave face's own sides
!> (side_pressure) and the normal of two facing faces (common_normal): a uniform
!> pressure exact on a kinked face split unevenly, the reported pressures times their
!> areas equal to the forces with an open node among them, the inserted nodes on the
!> line through their side's end values, the vertex force spread over its own
!> side; the common normal on a common interface, for a stiff master or slave, for
!> equal compliances.
program test_contact_recovery
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_contact_recovery, only: side_pressure
   use vemcontact_contact_geometry, only: common_normal
   implicit none
   type(checker_t) :: t
   real(wp) :: x(2, 6), w(6), f(6), p(6), n(2), s
   integer(ip) :: edge(2, 5), node(6)
   logical :: new(6), active(6), keep(6)
   integer :: j

   ! the slave face's own nodes 1 (0,0), 2 (1,0), 3 (2,1): a kink at 2; nodes 4, 5
   ! inserted into side 1 -> 2 at 0.25 and 0.6, node 6 into side 2 -> 3 at its middle
   x = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 0.25_wp, 0.0_wp, 0.6_wp, 0.0_wp, &
                1.5_wp, 0.5_wp], [2, 6])
   edge = reshape([1_ip, 4_ip, 4_ip, 5_ip, 5_ip, 2_ip, 2_ip, 6_ip, 6_ip, 3_ip], [2, 5])
   node = [1_ip, 2_ip, 3_ip, 4_ip, 5_ip, 6_ip]
   new = [.false., .false., .false., .true., .true., .true.]
   s = sqrt(2.0_wp)/2.0_wp
   ! tributary lengths (half the lengths of the split face's sides at each node)
   w = [0.125_wp, 0.2_wp + 0.5_wp*s, 0.5_wp*s, 0.3_wp, 0.375_wp, s]
   active = .true.
   keep = .false.

   ! a uniform pressure: F_j = p w_j, reproduced at every node
   f = 3.7_wp*w
   p = side_pressure(x, edge, new, node, f, w, active, keep)
   do j = 1, 6
      call t%close(p(j), 3.7_wp, 1.0e-14_wp, 'uniform pressure on a kinked, unevenly split face')
   end do

   ! uneven forces with node 3 open: the open node reports 0, the closed ones' p w add
   ! up to the forces, and the inserted nodes lie on the line through their side's ends
   f = [1.0_wp, 2.5_wp, 0.0_wp, 0.4_wp, 3.0_wp, 0.7_wp]
   active(3) = .false.
   p = side_pressure(x, edge, new, node, f, w, active, keep)
   call t%close(p(3), 0.0_wp, 0.0_wp, 'an open node reports no pressure', atol=0.0_wp)
   call t%close(sum(p*w, mask=active), sum(f, mask=active), 1.0e-14_wp, 'sum of p w = sum of the forces')
   call t%close(p(4), 0.75_wp*p(1) + 0.25_wp*p(2), 1.0e-14_wp, 'inserted node 4: (1 - t) p_a + t p_b')
   call t%close(p(5), 0.4_wp*p(1) + 0.6_wp*p(2), 1.0e-14_wp, 'inserted node 5')
   ! node 1 gathers its own force and the shares of 4 and 5 (hat weights 0.75, 0.4)
   call t%close(p(1), (1.0_wp + 0.75_wp*0.4_wp + 0.4_wp*3.0_wp)/(0.125_wp + 0.75_wp*0.3_wp + 0.4_wp*0.375_wp), &
                1.0e-14_wp, 'node 1: its hat function''s share of the forces over its share of the lengths')

   ! a force at the vertex 2 alone is spread over its own sides, not left on its
   ! tributary length of the split face
   f = 0.0_wp
   f(2) = 1.0_wp
   active = .true.
   p = side_pressure(x, edge, new, node, f, w, active, keep)
   call t%check(p(2) < f(2)/w(2), 'a vertex force spread over the vertex''s own sides')
   call t%close(sum(p*w), 1.0_wp, 1.0e-14_wp, 'and still adding up to it')

   ! node 1 held by a support (keep): its force stays there, and the inserted nodes
   ! next to it keep theirs (their side has no end to gather to)
   f = [1.0_wp, 2.5_wp, 0.2_wp, 0.4_wp, 3.0_wp, 0.7_wp]
   keep(1) = .true.
   p = side_pressure(x, edge, new, node, f, w, active, keep)
   call t%close(p(1), f(1)/w(1), 1.0e-15_wp, 'a held node keeps f / w')
   call t%close(p(4), f(4)/w(4), 1.0e-15_wp, 'a node inserted next to it keeps f / w')
   call t%close(sum(p*w), sum(f), 1.0e-14_wp, 'the sum with a held node')

   ! the common normal: opposite faces give the master's normal, whatever its length
   n = common_normal([0.0_wp, 0.9_wp], [0.0_wp, -0.9_wp], 1.0_wp, 1.0_wp)
   call t%close(n(1), 0.0_wp, 0.0_wp, 'common interface: nm (x)', atol=1.0e-16_wp)
   call t%close(n(2), 0.9_wp, 1.0e-15_wp, 'common interface: nm (y)')
   ! a rigid master (c_m = 0): the master's normal; a rigid slave: the slave's, reversed
   n = common_normal([0.0_wp, 1.0_wp], [0.6_wp, -0.8_wp], 0.0_wp, 1.0_wp)
   call t%close(n(1), 0.0_wp, 0.0_wp, 'rigid master keeps its normal', atol=1.0e-16_wp)
   n = common_normal([0.0_wp, 1.0_wp], [0.6_wp, -0.8_wp], 1.0_wp, 0.0_wp)
   call t%close(n(1), -0.6_wp, 1.0e-15_wp, 'rigid slave: its normal reversed (x)')
   call t%close(n(2), 0.8_wp, 1.0e-15_wp, 'rigid slave: its normal reversed (y)')
   ! equal compliances: the bisector, with the master normal's length
   n = common_normal([0.0_wp, 2.0_wp], [0.6_wp, -0.8_wp], 1.0_wp, 1.0_wp)
   call t%close(atan2(-n(1), n(2)), 0.5_wp*atan2(0.6_wp, 0.8_wp), 1.0e-14_wp, 'equal compliances: the bisector')
   call t%close(hypot(n(1), n(2)), 2.0_wp, 1.0e-15_wp, 'with the master normal''s length')
   ! no slave normal or no compliance: the master's normal
   n = common_normal([0.3_wp, 0.4_wp], [0.0_wp, 0.0_wp], 1.0_wp, 1.0_wp)
   call t%close(n(1), 0.3_wp, 0.0_wp, 'no slave normal', atol=0.0_wp)
   n = common_normal([0.3_wp, 0.4_wp], [0.6_wp, -0.8_wp], 0.0_wp, 0.0_wp)
   call t%close(n(2), 0.4_wp, 0.0_wp, 'no compliance', atol=0.0_wp)
   call t%finish()
end program test_contact_recovery
