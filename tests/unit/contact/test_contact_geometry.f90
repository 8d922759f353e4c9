!> Node-to-segment kinematics and the penalty element: projection and gap on
!> known geometry, A(xi) on rigid motions, stiffness against finite differences
!> of the force, force as the gradient of the penalty energy, the slip (CSLIP) on
!> known motions.
program test_contact_geometry
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_contact_geometry, only: project_point_segment, relative_map, contact_force, &
                                          contact_stiffness, contact_energy, contact_pressure, &
                                          segment_normal, contact_slip, seg_ok, seg_degenerate, &
                                          sliding_tangent, projection_gradient, ray_projection, ray_gradient
   implicit none
   type(checker_t) :: t
   real(wp) :: xa(2), xb(2), tt(2), nn(2), xs(2), xi, g, n(2), d, l
   real(wp) :: a(2, 6), u(6), x6(6), kc(6, 6), kfd(6, 6), f(6), fp(6), fm(6), du(6), dx
   real(wp) :: n0(2), js(6, 6), jt(6, 6), lam
   !> the reference configuration of the tangential checks: segment xa0 -> xb0 along
   !> tref0 (length 2), normal nref0 = (t_y, -t_x), the slave at xs0
   real(wp), parameter :: tref0(2) = [1.0_wp, 0.0_wp], nref0(2) = [0.0_wp, -1.0_wp]
   real(wp), parameter :: xa0(2) = [0.0_wp, 0.0_wp], xb0(2) = [2.0_wp, 0.0_wp], xs0(2) = [0.8_wp, -0.05_wp]
   logical :: ok
   real(wp) :: k, de, diff, ratio, gtarget, c(2), w, sc, xi1, g1, n1(2), d1
   integer :: st, j, m
   character(len=32) :: lab

   ! ---- projection on a 3-4-5 segment: t = (3, 4), l = 5, n = (4, -3)/5
   xa = [1.0_wp, 1.0_wp]
   xb = [4.0_wp, 5.0_wp]
   tt = (xb - xa)/5.0_wp
   nn = [4.0_wp, -3.0_wp]/5.0_wp
   ! exact decimal data: results agree to a few ulps of the coordinates
   call project_point_segment(xa + 0.3_wp*5.0_wp*tt + 2.0_wp*nn, xa, xb, xi, g, n, d, st)
   call t%equal(st, seg_ok, 'status of a proper segment')
   call t%close(xi, 0.3_wp, 1.0e-14_wp, 'xi inside')
   call t%close(g, 2.0_wp, 1.0e-14_wp, 'gap inside')
   call t%close(d, 2.0_wp, 1.0e-14_wp, 'distance inside = |g|')
   call t%close(n(1), 0.8_wp, 1.0e-15_wp, 'normal x')
   call t%close(maxval(abs(segment_normal(xa, xb) - nn)), 0.0_wp, 1.0e-15_wp, 'segment_normal')
   call t%close(n(2), -0.6_wp, 1.0e-15_wp, 'normal y')
   call project_point_segment(xa - 0.4_wp*5.0_wp*tt + 1.5_wp*nn, xa, xb, xi, g, n, d, st)
   call t%close(xi, -0.4_wp, 1.0e-14_wp, 'xi < 0')
   call t%close(g, 1.5_wp, 1.0e-14_wp, 'gap before a')
   call t%close(d, 2.5_wp, 1.0e-14_wp, 'distance to a (clamped)')
   call project_point_segment(xa + 1.6_wp*5.0_wp*tt - 0.5_wp*nn, xa, xb, xi, g, n, d, st)
   call t%close(xi, 1.6_wp, 1.0e-14_wp, 'xi > 1')
   call t%close(g, -0.5_wp, 1.0e-14_wp, 'gap after b')
   call t%close(d, sqrt(9.0_wp + 0.25_wp), 1.0e-14_wp, 'distance to b (clamped)')

   ! ---- gap sign: a -> b along +x is the bottom side of a ccw element (body above)
   call project_point_segment([0.5_wp, 0.1_wp], [0.0_wp, 0.0_wp], [1.0_wp, 0.0_wp], xi, g, n, d, st)
   call t%check(g < 0.0_wp, 'point above a bottom side (inside the body): g < 0')
   call t%close(g, -0.1_wp, 1.0e-15_wp, 'its gap')
   call project_point_segment([0.5_wp, -0.1_wp], [0.0_wp, 0.0_wp], [1.0_wp, 0.0_wp], xi, g, n, d, st)
   call t%check(g > 0.0_wp, 'point below a bottom side: g > 0')
   ! b -> a: a top side (body below)
   call project_point_segment([0.5_wp, 0.1_wp], [1.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], xi, g, n, d, st)
   call t%check(g > 0.0_wp, 'point above a top side: g > 0')
   call t%close(xi, 0.5_wp, 1.0e-15_wp, 'xi on a reversed side')
   call project_point_segment([0.5_wp, -0.1_wp], [1.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], xi, g, n, d, st)
   call t%check(g < 0.0_wp, 'point below a top side: g < 0')
   ! vertical sides of the unit square: right side (1,0)->(1,1), left side (0,1)->(0,0)
   call project_point_segment([1.2_wp, 0.5_wp], [1.0_wp, 0.0_wp], [1.0_wp, 1.0_wp], xi, g, n, d, st)
   call t%check(g > 0.0_wp .and. n(1) > 0.99_wp, 'right side: outward normal +x, outside point open')
   call project_point_segment([0.2_wp, 0.5_wp], [0.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], xi, g, n, d, st)
   call t%check(g < 0.0_wp .and. n(1) < -0.99_wp, 'left side: outward normal -x, inside point penetrates')

   ! ---- degenerate segment: a status, no division by zero
   call project_point_segment([1.0_wp, 2.0_wp], [3.0_wp, 3.0_wp], [3.0_wp, 3.0_wp], xi, g, n, d, st)
   call t%equal(st, seg_degenerate, 'zero-length segment flagged')
   call t%check(g > 0.0_wp .and. maxval(abs(n)) <= 0.0_wp, 'degenerate: open gap, no normal')
   call project_point_segment([1.0_wp, 2.0_wp], [1.0e8_wp, 0.0_wp], [1.0e8_wp, 1.0e-9_wp], xi, g, n, d, st)
   call t%equal(st, seg_degenerate, 'segment below round-off of its coordinates flagged')

   ! ---- A(xi): rigid translations give no relative displacement, for any xi
   do j = -2, 6
      xi = 0.25_wp*j
      a = relative_map(xi)
      u = [0.3_wp, -1.7_wp, 0.3_wp, -1.7_wp, 0.3_wp, -1.7_wp]
      call t%close(maxval(abs(matmul(a, u))), 0.0_wp, 0.0_wp, 'A(xi) on a translation', atol=1.0e-15_wp)
   end do
   ! an infinitesimal rotation w x r about any point leaves n.(u_s - u_xi) = 0
   ! when xi is the projection (u_s - u_xi = w x (g n) is tangential)
   xs = [2.5_wp, 0.7_wp]
   call project_point_segment(xs, xa, xb, xi, g, n, d, st)
   c = [-3.0_wp, 2.0_wp]
   x6 = [xs, xa, xb]
   do j = 1, 3
      u(2*j - 1) = -(x6(2*j) - c(2))
      u(2*j) = x6(2*j - 1) - c(1)
   end do
   call t%close(dot_product(n, matmul(relative_map(xi), u)), 0.0_wp, 0.0_wp, &
                'normal relative displacement of a rotation', atol=1.0e-14_wp*maxval(abs(u)))

   ! ---- slip (CSLIP) tau.(u_s - u_xi) on the 3-4-5 segment, tau = (0.6, 0.8): the
   ! tangent comes from the normal that the projection returns.  Data are O(1), so
   ! the results are exact to a few ulps: 1e-14 absolute.
   call project_point_segment(xa + 0.3_wp*5.0_wp*tt + 2.0_wp*nn, xa, xb, xi, g, n, d, st)
   u = [1.5_wp*tt, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
   call t%close(contact_slip(xi, n, u), 1.5_wp, 1.0e-14_wp, 'slip: slave along a -> b')
   u = [0.0_wp, 0.0_wp, 0.7_wp*tt, 0.7_wp*tt]
   call t%close(contact_slip(xi, n, u), -0.7_wp, 1.0e-14_wp, 'slip: master along a -> b')
   u = [0.0_wp, 0.0_wp, 2.0_wp*tt, 0.0_wp, 0.0_wp]
   call t%close(contact_slip(xi, n, u), -(1.0_wp - xi)*2.0_wp, 1.0e-14_wp, 'slip: node a alone, weight 1 - xi')
   u = [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 2.0_wp*tt]
   call t%close(contact_slip(xi, n, u), -xi*2.0_wp, 1.0e-14_wp, 'slip: node b alone, weight xi')
   u = [-0.4_wp*nn, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
   call t%close(contact_slip(xi, n, u), 0.0_wp, 0.0_wp, 'slip: normal motion', atol=1.0e-15_wp)
   u = [0.3_wp, -1.7_wp, 0.3_wp, -1.7_wp, 0.3_wp, -1.7_wp]
   call t%close(contact_slip(xi, n, u), 0.0_wp, 0.0_wp, 'slip: rigid translation', atol=1.0e-15_wp)
   ! reversing the segment reverses the tangent and so the sign
   call project_point_segment(xa + 0.3_wp*5.0_wp*tt - 2.0_wp*nn, xb, xa, xi, g, n, d, st)
   u = [1.5_wp*tt, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
   call t%close(contact_slip(xi, n, u), -1.5_wp, 1.0e-14_wp, 'slip: reversed segment b -> a')

   ! ---- force and stiffness
   k = 3.0e4_wp
   xs = [2.0_wp, 3.9_wp]          ! inside the body side of a -> b (3-4-5 segment)
   call project_point_segment(xs, xa, xb, xi, g, n, d, st)
   call t%check(g < 0.0_wp, 'force state penetrates')
   f = contact_force(xi, n, k, g)
   call t%close(sum(f(1::2)), 0.0_wp, 0.0_wp, 'force balance x', atol=1.0e-12_wp*maxval(abs(f)))
   call t%close(sum(f(2::2)), 0.0_wp, 0.0_wp, 'force balance y', atol=1.0e-12_wp*maxval(abs(f)))
   call t%close(norm2(f(1:2)), k*abs(g), 1.0e-14_wp, 'slave force magnitude k|g|')
   ! f_c sits with K u on the left of K u + f_c = f_ext, so the load it puts on the
   ! slave is -f_s = k |g| n: outward, pushing the node out of the master body
   call t%check(dot_product(-f(1:2), n) > 0.0_wp, 'contact reaction on the slave is outward')
   call t%close(contact_pressure(2.0_wp, g), -2.0_wp*g, 1.0e-15_wp, 'CPRESS = K (-g)')
   call t%close(contact_pressure(2.0_wp, 0.1_wp), 0.0_wp, 0.0_wp, 'no pressure when open')
   call t%close(maxval(abs(contact_force(xi, n, k, 0.1_wp))), 0.0_wp, 0.0_wp, 'zero force for g > 0')
   call t%close(maxval(abs(contact_stiffness(xi, n, k, 0.1_wp))), 0.0_wp, 0.0_wp, 'zero stiffness for g > 0')
   call t%close(maxval(abs(contact_force(xi, n, k, 0.0_wp))), 0.0_wp, 0.0_wp, 'zero force at g = 0')

   ! frozen n and xi: f(x) = k (n.A x) A^T n is linear, so central differences are
   ! exact up to round-off eps*|f|/dx ~ 1e-16*1e5/1e-6: 1e-8 relative is ample
   kc = contact_stiffness(xi, n, k, g)
   call t%close(maxval(abs(kc - transpose(kc))), 0.0_wp, 0.0_wp, 'stiffness symmetric')
   x6 = [xs, xa, xb]
   dx = 1.0e-6_wp
   do j = 1, 6
      du = 0.0_wp
      du(j) = dx
      fp = frozen_force(x6 + du)
      fm = frozen_force(x6 - du)
      kfd(:, j) = (fp - fm)/(2.0_wp*dx)
   end do
   call t%close(maxval(abs(kfd - kc))/maxval(abs(kc)), 0.0_wp, 0.0_wp, &
                'stiffness = FD of the force (n, xi frozen)', atol=1.0e-8_wp)
   write (*, '(a,es10.3)') 'frozen FD stiffness relative error: ', maxval(abs(kfd - kc))/maxval(abs(kc))

   ! projection recomputed: the true Jacobian adds k g d(A^T n)/dx, whose entries
   ! are at most ~ k |g| / l (n and xi change by O(1/l) per unit motion): the
   ! difference relative to max|K_c| must be O(|g|/l): asserted within [0.5, 2] |g|/l
   ! (observed 1.00 |g|/l for this geometry at |g|/l = 1e-2, 1e-4, 1e-6)
   l = 5.0_wp
   do m = 1, 3
      gtarget = -l*10.0_wp**(-2*m)
      xs = xa + 0.37_wp*(xb - xa) + gtarget*nn
      x6 = [xs, xa, xb]
      call project_point_segment(xs, xa, xb, xi, g, n, d, st)
      kc = contact_stiffness(xi, n, k, g)
      dx = 1.0e-3_wp*abs(g)       ! stays on the penetrating side
      do j = 1, 6
         du = 0.0_wp
         du(j) = dx
         kfd(:, j) = (full_force(x6 + du) - full_force(x6 - du))/(2.0_wp*dx)
      end do
      diff = maxval(abs(kfd - kc))/maxval(abs(kc))
      ratio = diff/(abs(g)/l)
      write (lab, '(a,es8.1)') ' |g|/l=', abs(g)/l
      write (*, '(a,es10.3,a,f8.4)') 'recomputed projection: rel. difference ', diff, &
         '  / (|g|/l) = ', ratio
      call t%check(ratio <= 2.0_wp, 'K_c vs FD with projection recomputed within 2|g|/l,'//trim(lab))
      call t%check(ratio >= 0.5_wp, 'the neglected term is really O(|g|/l) (not zero),'//trim(lab))
   end do

   ! energy: f_c is the gradient of 1/2 k <-g>^2 with the projection recomputed
   ! (dg = n.(du_s - du_xi) exactly); central difference error O(|du|^2/(|g| l)) + round-off
   xs = xa + 0.61_wp*(xb - xa) - 0.05_wp*nn
   x6 = [xs, xa, xb]
   du = [0.3_wp, -0.2_wp, 0.1_wp, 0.5_wp, -0.4_wp, 0.2_wp]*1.0e-7_wp
   call project_point_segment(xs, xa, xb, xi, g, n, d, st)
   f = contact_force(xi, n, k, g)
   de = energy(x6 + du) - energy(x6 - du)
   call t%close(de, 2.0_wp*dot_product(f, du), 1.0e-8_wp, 'f_c . du = dE')
   w = energy([xa + 0.5_wp*(xb - xa) + 0.1_wp*nn, xa, xb])
   call t%close(w, 0.0_wp, 0.0_wp, 'no energy when open')
   ! ---- absolute scale: the 3-4-5 projection with all coordinates scaled by
   ! 1e-300 .. 1e300 gives the same xi and normal and a gap and distance scaled by
   ! the factor (to a few ulps: the scaled decimal data are rounded); the length
   ! and xi involve no squares of lengths, which would underflow or overflow
   xs = xa + 0.3_wp*5.0_wp*tt + 2.0_wp*nn
   call project_point_segment(xs, xa, xb, xi1, g1, n1, d1, st)
   do j = -30, 30, 5
      sc = 10.0_wp**(10*j)
      call project_point_segment(sc*xs, sc*xa, sc*xb, xi, g, n, d, st)
      write (lab, '(a,es8.1)') 'scale ', sc
      call t%equal(st, seg_ok, trim(lab)//': proper segment')
      call t%close(xi, xi1, 1.0e-14_wp, trim(lab)//': xi')
      call t%close(g/sc, g1, 1.0e-14_wp, trim(lab)//': gap / scale')
      call t%close(d/sc, d1, 1.0e-14_wp, trim(lab)//': distance / scale')
      call t%close(maxval(abs(n - n1)), 0.0_wp, 0.0_wp, trim(lab)//': normal', atol=1.0e-15_wp)
   end do

   ! ---- finite sliding with the reference normal: f = -N A(xi)^T n0 with N = -k g,
   ! g = n0.(x_s - x_xi) and xi the closest point of the current segment.  Its
   ! Jacobian, with xi recomputed, is contact_stiffness + sliding_tangent: checked by
   ! central differences on a segment turned (c = n0.t /= 0) and a slave off it
   ! (d /= 0).  The force is smooth here: the difference error is O(dx**2) relative to
   ! the second derivatives (about k/l**2 * dx**2 ~ 1e-12 of k) plus the round-off
   ! eps |f| / dx ~ 1e-10 of k: 1e-7 of max|J| is ample, and far below the sliding
   ! part itself (asserted to be more than 1e-3 of max|J|, so that it is tested)
   n0 = [0.0_wp, 1.0_wp]                   ! reference segment along x
   xa = [0.1_wp, 0.02_wp]                  ! current ends: turned by 0.1 rad, moved
   xb = xa + 2.0_wp*[cos(0.1_wp), sin(0.1_wp)]
   xs = xa + 0.7_wp*(xb - xa) + 0.05_wp*[-sin(0.1_wp), cos(0.1_wp)] - [0.0_wp, 0.2_wp]
   x6 = [xs, xa, xb]
   k = 3.0e5_wp
   call project_point_segment(xs, xa, xb, xi, g, n, d, st)
   g = dot_product(n0, xs - ((1.0_wp - xi)*xa + xi*xb))
   call t%check(g < 0.0_wp, 'sliding test point penetrates')
   ! c = n0.t: the reference segment is along x, so n0.(u_b - u_a) = n0.(x_b - x_a)
   js = sliding_tangent(xi, n0, k, -k*g, dot_product(n0, xb - xa), projection_gradient(xi, xs, xa, xb))
   jt = contact_stiffness(xi, n0, k, -1.0_wp) + js
   dx = 1.0e-6_wp
   do j = 1, 6
      du = 0.0_wp
      du(j) = dx
      kfd(:, j) = (sliding_force(x6 + du) - sliding_force(x6 - du))/(2.0_wp*dx)
   end do
   diff = maxval(abs(kfd - jt))/maxval(abs(jt))
   write (*, '(a,es10.3,a,es10.3)') 'sliding tangent vs FD: ', diff, '  sliding part / tangent: ', &
      maxval(abs(js))/maxval(abs(jt))
   call t%check(diff <= 1.0e-7_wp, 'contact_stiffness + sliding_tangent = FD with xi recomputed')
   call t%check(maxval(abs(js))/maxval(abs(jt)) > 1.0e-3_wp, 'the sliding part is not negligible here')
   ! ---- finite sliding along the reference normal (the pairing of NODE TO SURFACE):
   ! xi the point of the current segment on the line through the slave along n0
   ! (ray_projection), g = n0.(x_s - x_xi), f = -N A(xi)^T n0 with N = lam - k g.
   ! Its Jacobian, with xi recomputed, is contact_stiffness + sliding_tangent with
   ! w = ray_gradient: central differences on the turned, moved segment above, the
   ! slave penetrating (lam = 0) and open but pressed by its multiplier (lam > k g >
   ! 0), where the N B w^T term dominates.  Tolerance as above (same smoothness and
   ! scales)
   do m = 1, 2
      lam = 0.0_wp
      if (m == 2) then
         xs = xa + 0.3_wp*(xb - xa) - 0.04_wp*[-sin(0.1_wp), cos(0.1_wp)]
         lam = 2.0_wp*k*0.04_wp
      end if
      x6 = [xs, xa, xb]
      call ray_projection(xs, xa, xb, [1.0_wp, 0.0_wp], xi, ok)
      call t%check(ok, 'ray projection exists')
      g = dot_product(n0, xs - ((1.0_wp - xi)*xa + xi*xb))
      call t%close(abs(dot_product([1.0_wp, 0.0_wp], xs - ((1.0_wp - xi)*xa + xi*xb))), 0.0_wp, 0.0_wp, &
                   'x_s - x_xi along the reference normal', atol=1.0e-15_wp)
      write (lab, '(a,i0)') ' case ', m
      call t%check(lam - k*g > 0.0_wp, 'the ray test point carries a force,'//trim(lab))
      js = sliding_tangent(xi, n0, k, lam - k*g, dot_product(n0, xb - xa), ray_gradient(xi, xa, xb, [1.0_wp, 0.0_wp]))
      jt = contact_stiffness(xi, n0, k, -1.0_wp) + js
      do j = 1, 6
         du = 0.0_wp
         du(j) = dx
         kfd(:, j) = (ray_force(x6 + du, lam) - ray_force(x6 - du, lam))/(2.0_wp*dx)
      end do
      diff = maxval(abs(kfd - jt))/maxval(abs(jt))
      write (*, '(a,es10.3,a,es10.3)') 'ray tangent vs FD: ', diff, '  sliding part / tangent: ', &
         maxval(abs(js))/maxval(abs(jt))
      call t%check(diff <= 1.0e-7_wp, 'contact_stiffness + sliding_tangent(ray_gradient) = FD,'//trim(lab))
      call t%check(maxval(abs(js))/maxval(abs(jt)) > 1.0e-3_wp, 'the ray sliding part is not negligible,'//trim(lab))
      ! the closest point's w in its place is not the tangent of this force
      js = sliding_tangent(xi, n0, k, lam - k*g, dot_product(n0, xb - xa), projection_gradient(xi, xs, xa, xb))
      call t%check(maxval(abs(kfd - contact_stiffness(xi, n0, k, -1.0_wp) - js))/maxval(abs(jt)) > 1.0e-4_wp, &
                   'the test tells the two projections apart,'//trim(lab))
   end do
   ! no ray through a segment turned by a right angle
   call ray_projection([0.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [0.0_wp, 2.0_wp], [1.0_wp, 0.0_wp], xi, ok)
   call t%check(.not. ok, 'no ray projection on a segment turned by 90 degrees')
   ! without c and d (a master that keeps its direction, the slave on it) only the
   ! shift of the force between a and b remains: N B w^T
   js = sliding_tangent(0.5_wp, n0, k, 2.0_wp, 0.0_wp, projection_gradient(0.5_wp, [1.0_wp, 0.0_wp], &
                        [0.0_wp, 0.0_wp], [2.0_wp, 0.0_wp]))
   call t%close(js(4, 1), -2.0_wp*0.5_wp, 1.0e-15_wp, 'N B w^T: force moves to b as the slave slides')
   ! ---- the tangential force of finite sliding along the reference normal (friction on
   ! NODE TO SURFACE re-paired at every iteration; the stepwise pairing that runs keeps
   ! the pairing within a load state and needs no such term): f = T A(xi)^T t0, xi the ray
   ! point, t0 the reference tangent a -> b, n0 = (t0_y, -t0_x).  Sticking, T = kt (s -
   ! s_p) with the slip s = s0 + t0.A(xi) u, s0 = t0.(X_s - X_a), which the ray makes
   ! the reference arc length xi l0; slipping, T = mu (lam - k g).  Its Jacobian, xi
   ! recomputed, is the frozen part (kt a a^T, a = A^T t0; or -mu k a (A^T n0)^T) plus
   ! sliding_tangent with t0 for n: (t0, kt, -T, c_t = t0.(u_b - u_a)) sticking,
   ! (t0, -mu k, -T, c = n0.(u_b - u_a)) slipping, w = ray_gradient.  Central
   ! differences on the turned, moved segment of the ray case; tolerance as above
   do m = 1, 2
      x6 = [xa + 0.4_wp*(xb - xa) + 0.03_wp*[-sin(0.1_wp), cos(0.1_wp)], xa, xb]
      call ray_projection(x6(1:2), x6(3:4), x6(5:6), tref0, xi, ok)
      call t%check(ok, 'tangential: ray projection exists')
      call t%close(tangential_slip(x6), 2.0_wp*xi, 1.0e-14_wp, 'the slip is the reference arc length xi l0')
      g = dot_product(nref0, x6(1:2) - ((1.0_wp - xi)*x6(3:4) + xi*x6(5:6)))
      f = matmul(tref0, relative_map(xi))
      if (m == 1) then
         lam = k*(tangential_slip(x6) - 0.3_wp)       ! the sticking force T
         jt = 0.0_wp
         do j = 1, 6
            jt(:, j) = k*f*f(j)
         end do
         js = sliding_tangent(xi, tref0, k, -lam, dot_product(tref0, (x6(5:6) - xb0) - (x6(3:4) - xa0)), &
                              ray_gradient(xi, x6(3:4), x6(5:6), tref0))
         lab = ' stick'
      else
         lam = 0.3_wp*(0.5_wp*k - k*g)                ! the slipping force mu N, N = lam_n - k g
         fp = matmul(nref0, relative_map(xi))
         do j = 1, 6
            jt(:, j) = -0.3_wp*k*f*fp(j)
         end do
         js = sliding_tangent(xi, tref0, -0.3_wp*k, -lam, dot_product(nref0, (x6(5:6) - xb0) - (x6(3:4) - xa0)), &
                              ray_gradient(xi, x6(3:4), x6(5:6), tref0))
         lab = ' slip'
      end if
      jt = jt + js
      do j = 1, 6
         du = 0.0_wp
         du(j) = dx
         kfd(:, j) = (tangential_force(x6 + du, m) - tangential_force(x6 - du, m))/(2.0_wp*dx)
      end do
      diff = maxval(abs(kfd - jt))/maxval(abs(jt))
      write (*, '(a,a,es10.3,a,es10.3)') 'tangential ray tangent vs FD,', trim(lab), diff, &
         '  sliding part / tangent: ', maxval(abs(js))/maxval(abs(jt))
      call t%check(diff <= 1.0e-7_wp, 'tangential force: frozen part + sliding_tangent(t0) = FD,'//trim(lab))
      call t%check(maxval(abs(js))/maxval(abs(jt)) > 1.0e-3_wp, 'the tangential sliding part is not negligible,'// &
                   trim(lab))
   end do
   call t%finish()
contains
   !> The slip s = s0 + t0.A(xi) u of the configuration x (slave, a, b) against the
   !> reference one (X_s, xa0, xb0 along tref0, S_a = 0), xi the ray point
   function tangential_slip(x) result(sl)
      real(wp), intent(in) :: x(6)
      real(wp) :: sl, xi1, u1(6)
      logical :: ok1
      call ray_projection(x(1:2), x(3:4), x(5:6), tref0, xi1, ok1)
      u1 = x - [xs0, xa0, xb0]
      sl = dot_product(tref0, xs0 - xa0) + dot_product(tref0, matmul(relative_map(xi1), u1))
   end function tangential_slip

   !> The tangential force T A(xi)^T t0 of the configuration x: sticking (m = 1) T =
   !> k (s - 0.3), slipping (m = 2) T = 0.3 (k/2 - k g), g = n0.(x_s - x_xi)
   function tangential_force(x, m) result(ff)
      real(wp), intent(in) :: x(6)
      integer, intent(in) :: m
      real(wp) :: ff(6), xi1, g1, tf
      logical :: ok1
      call ray_projection(x(1:2), x(3:4), x(5:6), tref0, xi1, ok1)
      if (m == 1) then
         tf = k*(tangential_slip(x) - 0.3_wp)
      else
         g1 = dot_product(nref0, x(1:2) - ((1.0_wp - xi1)*x(3:4) + xi1*x(5:6)))
         tf = 0.3_wp*(0.5_wp*k - k*g1)
      end if
      ff = tf*matmul(tref0, relative_map(xi1))
   end function tangential_force

   !> The contact force f_c = -N A(xi)^T n0 of the configuration x (slave, a, b), xi
   !> the point along n0 (ray_projection, reference segment along x), N = lam - k g
   function ray_force(x, lam) result(ff)
      real(wp), intent(in) :: x(6), lam
      real(wp) :: ff(6), xi1, g1
      logical :: ok1
      call ray_projection(x(1:2), x(3:4), x(5:6), [1.0_wp, 0.0_wp], xi1, ok1)
      g1 = dot_product(n0, x(1:2) - ((1.0_wp - xi1)*x(3:4) + xi1*x(5:6)))
      ff = -(lam - k*g1)*matmul(n0, relative_map(xi1))
   end function ray_force

   !> The contact force f_c = -N A(xi)^T n0 (K u + f_c = f_ext) of the configuration
   !> x (slave, a, b), xi re-projected, N = -k g
   function sliding_force(x) result(ff)
      real(wp), intent(in) :: x(6)
      real(wp) :: ff(6), xi1, g1, n1(2), d1
      integer :: s1
      call project_point_segment(x(1:2), x(3:4), x(5:6), xi1, g1, n1, d1, s1)
      g1 = dot_product(n0, x(1:2) - ((1.0_wp - xi1)*x(3:4) + xi1*x(5:6)))
      ff = k*g1*matmul(n0, relative_map(xi1))
   end function sliding_force

   function frozen_force(x) result(ff)
      real(wp), intent(in) :: x(6)
      real(wp) :: ff(6), gg
      gg = dot_product(n, matmul(relative_map(xi), x))
      ff = contact_force(xi, n, k, gg)
   end function frozen_force

   function full_force(x) result(ff)
      real(wp), intent(in) :: x(6)
      real(wp) :: ff(6), xi1, g1, n1(2), d1
      integer :: s1
      call project_point_segment(x(1:2), x(3:4), x(5:6), xi1, g1, n1, d1, s1)
      ff = contact_force(xi1, n1, k, g1)
   end function full_force

   real(wp) function energy(x)
      real(wp), intent(in) :: x(6)
      real(wp) :: xi1, g1, n1(2), d1
      integer :: s1
      call project_point_segment(x(1:2), x(3:4), x(5:6), xi1, g1, n1, d1, s1)
      energy = contact_energy(k, g1)
   end function energy
end program test_contact_geometry
