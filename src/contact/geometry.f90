!> Node-to-segment contact kinematics and the penalty element of one contact
!> point (docs/contact-formulation.md has the derivation).
!>
!> A slave node s at x_s and a master segment a -> b, oriented as the side of its
!> counter-clockwise element, so that n = (t_y, -t_x)/l (t = x_b - x_a, l = |t|)
!> is the master body's outward normal.  The projection parameter is normalized,
!> xi = (x_s - x_a).t / l**2 (0 at a, 1 at b), the normal gap is
!> g = n.(x_s - x_xi) (> 0 open, < 0 penetration), and the relative displacement
!> u_s - u_xi = A(xi) [u_s; u_a; u_b] with A = [I, -(1-xi) I, -xi I].
!> The penalty energy 1/2 k <-g>**2 gives the force f = k g A^T n (g < 0) and,
!> with n and xi frozen, the stiffness k A^T n n^T A (the paper's Eq. 3.13).
!> The tangential part of the relative displacement, tau.(u_s - u_xi) with the
!> unit tangent tau = t/l, is the slip CSLIP (contact_slip).
module vemcontact_contact_geometry
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: project_point_segment, relative_map, contact_force, contact_stiffness
   public :: segment_normal, projection_gradient, sliding_tangent, ray_projection, ray_gradient
   public :: contact_energy, contact_pressure, contact_slip, segment_is_degenerate, length2
   public :: common_normal

   !> project_point_segment status: a proper segment
   integer, parameter, public :: seg_ok = 0
   !> project_point_segment status: zero length within round-off, no normal exists
   integer, parameter, public :: seg_degenerate = 1

   ! A segment is degenerate when its length is below a few ulps of its end
   ! coordinates: then t = x_b - x_a is pure round-off and carries no direction.
   real(wp), parameter :: degenerate_rel = 16.0_wp*epsilon(1.0_wp)

contains

   !> True when a -> b has no usable direction: l <= 16 eps max(|x_a|, |x_b|)
   !> (max norm), or l = 0 for end points at the origin.
   pure logical function segment_is_degenerate(xa, xb) result(deg)
      real(wp), intent(in) :: xa(2), xb(2)
      real(wp) :: scale, l
      scale = max(maxval(abs(xa)), maxval(abs(xb)))
      l = length2(xb - xa)
      deg = l <= degenerate_rel*scale .or. .not. (l > 0.0_wp)
   end function segment_is_degenerate

   !> Closest-point projection of `xs` on the segment xa -> xb.
   !> xi: normalized parameter of the projection on the segment's line (not clamped);
   !> gap: n.(xs - x_xi), the signed distance to the line (> 0 on the outward side);
   !> normal: outward unit normal (t_y, -t_x)/l; dist: distance from xs to the
   !> closest point of the segment itself (xi clamped to [0, 1]).
   !> A degenerate segment returns status = seg_degenerate, xi = 0, normal = 0,
   !> dist = |xs - xa| and gap = dist (open, so that a caller ignoring the
   !> status does not create a contact force).
   pure subroutine project_point_segment(xs, xa, xb, xi, gap, normal, dist, status)
      real(wp), intent(in) :: xs(2), xa(2), xb(2)
      real(wp), intent(out) :: xi, gap, normal(2), dist
      integer, intent(out) :: status
      real(wp) :: t(2), l, d(2), xc
      if (segment_is_degenerate(xa, xb)) then
         status = seg_degenerate
         xi = 0.0_wp
         normal = 0.0_wp
         dist = length2(xs - xa)
         gap = dist
         return
      end if
      status = seg_ok
      t = xb - xa
      l = length2(t)
      d = xs - xa
      ! with the unit tangent rather than t.t / l**2: no square of a length, which
      ! would underflow or overflow for coordinates beyond 1e-154 or 1e154
      xi = dot_product(d, t/l)/l
      normal = segment_normal(xa, xb)
      ! n.t = 0, so n.(xs - x_xi) = n.(xs - xa) for any xi: no cancellation from xi
      gap = dot_product(normal, d)
      xc = min(max(xi, 0.0_wp), 1.0_wp)
      dist = length2(d - xc*t)
   end subroutine project_point_segment

   !> Outward unit normal (t_y, -t_x)/l of the segment xa -> xb (t = xb - xa, l = |t|);
   !> the segment must not be degenerate (segment_is_degenerate).
   pure function segment_normal(xa, xb) result(normal)
      real(wp), intent(in) :: xa(2), xb(2)
      real(wp) :: normal(2), t(2)
      t = xb - xa
      normal = [t(2), -t(1)]/length2(t)
   end function segment_normal

   !> Euclidean length of a 2-vector without under- or overflow of the squares
   !> (gfortran's norm2 returns 0 for (1e-200, 0)): lengths of meshes at any scale
   !> that the coordinates can represent.
   pure real(wp) function length2(v) result(l)
      real(wp), intent(in) :: v(2)
      l = hypot(v(1), v(2))
   end function length2

   !> A(xi) = [I2, -(1-xi) I2, -xi I2]: u_s - u_xi = A [u_s; u_a; u_b] (dof order
   !> s_x, s_y, a_x, a_y, b_x, b_y).
   pure function relative_map(xi) result(a)
      real(wp), intent(in) :: xi
      real(wp) :: a(2, 6)
      a = 0.0_wp
      a(1, 1) = 1.0_wp
      a(2, 2) = 1.0_wp
      a(1, 3) = -(1.0_wp - xi)
      a(2, 4) = -(1.0_wp - xi)
      a(1, 5) = -xi
      a(2, 6) = -xi
   end function relative_map

   !> Contact force on the dofs (s, a, b): k g A(xi)^T n when g < 0, else zero.
   !> It enters the equilibrium as K u + f_c = f_ext (gradient of 1/2 k <-g>**2).
   pure function contact_force(xi, normal, k, gap) result(f)
      real(wp), intent(in) :: xi, normal(2), k, gap
      real(wp) :: f(6)
      if (gap < 0.0_wp) then
         f = k*gap*matmul(normal, relative_map(xi))
      else
         f = 0.0_wp
      end if
   end function contact_force

   !> Contact stiffness k A^T n n^T A when g < 0 (else zero): the derivative of
   !> contact_force with n and xi frozen.  Symmetric, rank one.
   pure function contact_stiffness(xi, normal, k, gap) result(kc)
      real(wp), intent(in) :: xi, normal(2), k, gap
      real(wp) :: kc(6, 6)
      real(wp) :: v(6)
      integer :: j
      if (gap < 0.0_wp) then
         v = matmul(normal, relative_map(xi))
         do j = 1, 6
            kc(:, j) = k*(v*v(j))
         end do
      else
         kc = 0.0_wp
      end if
   end function contact_stiffness

   !> The derivative w = dxi/du of the closest-point parameter of the slave xs on the
   !> segment xa -> xb (current coordinates), dof order of relative_map: from
   !> (x_s - x_xi).t = 0, w = (A^T t + [0; -d; d]) / |t|**2 with t = x_b - x_a and
   !> d = x_s - x_xi.
   pure function projection_gradient(xi, xs, xa, xb) result(w)
      real(wp), intent(in) :: xi, xs(2), xa(2), xb(2)
      real(wp) :: w(6)
      real(wp) :: t(2), d(2)
      t = xb - xa
      d = xs - ((1.0_wp - xi)*xa + xi*xb)
      w = (matmul(t, relative_map(xi)) + [0.0_wp, 0.0_wp, -d, d])/dot_product(t, t)
   end function projection_gradient

   !> The point of the current segment xa -> xb that the line through xs along the
   !> reference normal meets (the normal of the reference segment, whose direction
   !> is tref): the normalized parameter xi = tref.(xs - xa) / tref.(xb - xa), so
   !> that xs - x_xi is parallel to the reference normal and the gap
   !> n.(xs - x_xi) is the distance along it.  Unlike the closest point, this
   !> meets a polyline whose reference normals agree once, and the gap is
   !> continuous where it passes from a segment to the next (xi = 1 on one is
   !> xi = 0 on the other).  ok = .false. when the current segment has turned by
   !> a right angle or more from the reference (tref.(xb - xa) <= 0): no such
   !> point.
   pure subroutine ray_projection(xs, xa, xb, tref, xi, ok)
      real(wp), intent(in) :: xs(2), xa(2), xb(2), tref(2)
      real(wp), intent(out) :: xi
      logical, intent(out) :: ok
      real(wp) :: tt, lr
      lr = length2(tref)
      tt = dot_product(tref/lr, xb - xa)
      ok = tt > 0.0_wp
      xi = 0.0_wp
      if (ok) xi = dot_product(tref/lr, xs - xa)/tt
   end subroutine ray_projection

   !> The derivative w = dxi/du of ray_projection, dof order of relative_map: from
   !> tref.(x_s - x_a - xi (x_b - x_a)) = 0, w = A(xi)^T tref / tref.(x_b - x_a).
   pure function ray_gradient(xi, xa, xb, tref) result(w)
      real(wp), intent(in) :: xi, xa(2), xb(2), tref(2)
      real(wp) :: w(6)
      real(wp) :: tu(2)
      tu = tref/length2(tref)
      w = matmul(tu, relative_map(xi))/dot_product(tu, xb - xa)
   end function ray_gradient

   !> What the motion of the projection adds to the tangent of one contact point
   !> whose force acts along a fixed normal n (the reference normal of small strain):
   !> the force is f = -N A(xi)^T n with N = lambda - k g and the gap
   !> g = n.(x_s - x_xi) at a point xi of the current segment that follows the
   !> sliding (ray_projection; or the closest point), so that
   !>
   !>     df = k A^T n n^T A du - (k c A^T n + N B) w^T du
   !>
   !> with c = n.t (t = x_b - x_a, current; dg/dxi = -c), B = (dA/dxi)^T n =
   !> [0; n; -n] and w = dxi/du (projection_gradient for the closest point,
   !> ray_gradient for the point along the reference normal).  This returns the second
   !> term, J = -(k c A^T n + N B) w^T: not symmetric, of size (k |c| + N) / l, zero
   !> where nothing slides and the master keeps its direction; the first term is
   !> contact_stiffness.
   pure function sliding_tangent(xi, normal, k, force, c, w) result(jc)
      real(wp), intent(in) :: xi, normal(2), k, force, c, w(6)
      real(wp) :: jc(6, 6)
      real(wp) :: v(6)
      integer :: j
      v = -(k*c*matmul(normal, relative_map(xi)) + force*[0.0_wp, 0.0_wp, normal, -normal])
      do j = 1, 6
         jc(:, j) = v*w(j)
      end do
   end function sliding_tangent

   !> Penalty energy 1/2 k <-g>**2 of one contact point.
   pure real(wp) function contact_energy(k, gap) result(e)
      real(wp), intent(in) :: k, gap
      e = 0.5_wp*k*min(gap, 0.0_wp)**2
   end function contact_energy

   !> Contact pressure (CPRESS) K <-g> for the interaction slope K: the force
   !> k_s (-g) spread over the slave's tributary area L_s * thickness.
   pure real(wp) function contact_pressure(penalty, gap) result(p)
      real(wp), intent(in) :: penalty, gap
      p = penalty*max(-gap, 0.0_wp)
   end function contact_pressure

   !> Slip (CSLIP) of a slave node against the point xi of its master segment:
   !> tau.(u_s - u_xi) = tau.A(xi) u with u = [u_s; u_a; u_b] (dof order of
   !> relative_map) and tau = (-n_y, n_x) = t/l the unit tangent a -> b, recovered
   !> from the outward normal n = (t_y, -t_x)/l.  Positive when the slave node moves
   !> along a -> b relative to the master; zero for rigid translations.  The normal
   !> may be shorter than 1 (the mean normal at a kink of a SURFACE TO SURFACE master):
   !> tau is then scaled back to unit length.
   pure real(wp) function contact_slip(xi, normal, u) result(s)
      real(wp), intent(in) :: xi, normal(2), u(6)
      real(wp) :: nn
      s = dot_product([-normal(2), normal(1)], matmul(relative_map(xi), u))
      nn = norm2(normal)
      if (nn > 0.0_wp) s = s/nn
   end function contact_slip
   !> The normal of the interface that two facing faces become under contact: where the
   !> master's normal nm (out of the master) and the slave's ns (out of the slave) are not
   !> opposite (a disc on a block: they differ by x/R), each face bends toward the
   !> other in proportion to its compliance c = (1 - nu**2)/E (plane strain; 1/E plane
   !> stress), as the surface displacements of two half-planes under one pressure do, so
   !> the common surface keeps the stiffer face's shape: its normal is the direction of
   !> c_s nm - c_m ns, with the length of nm (a mean normal shorter than 1 at a kink;
   !> docs/contact-formulation.md).  Where -ns = nm (a common interface) the result is
   !> nm; without a slave normal or compliance (ns = 0, c_s + c_m <= 0) it is nm.
   pure function common_normal(nm, ns, cm, cs) result(n)
      real(wp), intent(in) :: nm(2), ns(2), cm, cs
      real(wp) :: n(2)
      real(wp) :: d(2), ld, lm
      n = nm
      lm = length2(nm)
      if (.not. (cs + cm > 0.0_wp) .or. .not. (length2(ns) > 0.0_wp) .or. .not. (lm > 0.0_wp)) return
      d = (cs*nm/lm - cm*ns/length2(ns))/(cs + cm)
      ld = length2(d)
      if (.not. (ld > 0.0_wp)) return
      n = (lm/ld)*d
   end function common_normal

end module vemcontact_contact_geometry
