!> Plane polygon geometry: area, centroid, diameter, simplicity and convexity.
!> Polygons are given as `xy(2, n)`, side k running from vertex k to vertex k+1
!> (the last back to the first).  Everything is computed relative to the first
!> vertex so that results do not lose digits when the element sits far from the
!> origin.
module vemcontact_element_geometry
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: polygon_signed_area, polygon_centroid, polygon_diameter
   public :: polygon_is_simple, polygon_is_convex, polygon_defect, polygon_max_angle

   !> Defects found by polygon_defect, in the order they are looked for.
   integer, parameter, public :: defect_none = 0
   integer, parameter, public :: defect_few = 1        !< fewer than 3 vertices or zero diameter
   integer, parameter, public :: defect_coincident = 2 !< vertices i and j within geom_rtol*h
   integer, parameter, public :: defect_fold = 3       !< side i-1..i folds back onto side i..i+1
   integer, parameter, public :: defect_crossing = 4   !< side i..i+1 crosses or touches side j..j+1

   !> Geometric tolerance relative to the polygon diameter.  Coordinates that
   !> went through a few arithmetic operations (translation, scaling, a mesher's
   !> decimal output) carry errors of a few ulp, about 1e-15 h; features smaller
   !> than 1e-10 h are therefore indistinguishable from rounding a few hundred
   !> thousand times over, while real features, such as the 1e-6 h edges that a
   !> polygon clipper produces and that the VEM handles, stay four orders of
   !> magnitude above the threshold.
   real(wp), parameter, public :: geom_rtol = 1.0e-10_wp

contains

   !> Shoelace area, positive for counter-clockwise vertices; 0 for fewer than 3.
   pure function polygon_signed_area(xy) result(a)
      real(wp), intent(in) :: xy(:, :)
      real(wp) :: a
      integer :: k, n
      n = size(xy, 2)
      a = 0.0_wp
      do k = 2, n - 1
         a = a + cross2(xy(:, k) - xy(:, 1), xy(:, k + 1) - xy(:, 1))
      end do
      a = 0.5_wp*a
   end function polygon_signed_area

   !> Area centroid.  A polygon of zero area has no area centroid: the vertex
   !> mean is returned then, so that callers never divide by zero.
   pure subroutine polygon_centroid(xy, c)
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(out) :: c(2)
      real(wp) :: a, w, p(2), q(2), s
      integer :: k, n
      n = size(xy, 2)
      if (n == 0) then
         c = 0.0_wp
         return
      end if
      ! the sums below are cubic in the lengths: relative to x1 and scaled by the
      ! largest offset s, they stay of order one for any element inside the
      ! documented coordinate range (1e130 cubed would overflow)
      s = 0.0_wp
      do k = 2, n
         s = max(s, maxval(abs(xy(:, k) - xy(:, 1))))
      end do
      a = 0.0_wp
      c = 0.0_wp
      if (s > 0.0_wp) then
         do k = 2, n - 1
            p = (xy(:, k) - xy(:, 1))/s
            q = (xy(:, k + 1) - xy(:, 1))/s
            w = cross2(p, q)
            a = a + w
            ! centroid of triangle (x1, xk, xk+1) relative to x1 is (p+q)/3,
            ! weighted by twice its signed area
            c = c + w*(p + q)
         end do
      end if
      if (.not. abs(a) > 0.0_wp) then
         c = xy(:, 1) + sum(xy - spread(xy(:, 1), 2, n), dim=2)/real(n, wp)
      else
         c = xy(:, 1) + s*(c/(3.0_wp*a))
      end if
   end subroutine polygon_centroid

   !> Largest vertex-to-vertex distance, the length scale of the element.
   pure function polygon_diameter(xy) result(h)
      real(wp), intent(in) :: xy(:, :)
      real(wp) :: h
      real(wp) :: d2, best
      integer :: i, j, bi, bj
      ! the farthest pair by squared distances (no square roots), then its hypot; where
      ! a square could overflow (a coordinate beyond 1e150) or the largest is
      ! subnormal, the hypot of every pair decides
      best = -1.0_wp
      bi = 1
      bj = 1
      if (size(xy, 2) > 1) then
         if (maxval(abs(xy)) > 1.0e150_wp) best = huge(1.0_wp)
      end if
      if (best < 0.0_wp) then
         do j = 2, size(xy, 2)
            do i = 1, j - 1
               d2 = (xy(1, j) - xy(1, i))**2 + (xy(2, j) - xy(2, i))**2
               if (d2 > best) then
                  best = d2
                  bi = i
                  bj = j
               end if
            end do
         end do
      end if
      if (best >= tiny(1.0_wp) .and. best < huge(1.0_wp)) then
         h = hypot(xy(1, bj) - xy(1, bi), xy(2, bj) - xy(2, bi))
         return
      end if
      h = 0.0_wp
      do j = 2, size(xy, 2)
         do i = 1, j - 1
            h = max(h, hypot(xy(1, j) - xy(1, i), xy(2, j) - xy(2, i)))
         end do
      end do
   end function polygon_diameter

   !> True when the boundary does not cross or touch itself: no two vertices
   !> closer than geom_rtol*h (this covers zero-length sides and repeated
   !> vertices), no two non-adjacent sides closer than that, and no side folding
   !> back onto its neighbour.  Consecutive collinear sides (a hanging node on a
   !> straight side) are allowed: they are a legitimate VEM element.  Either
   !> orientation is accepted; the sign of the area tells it.
   pure function polygon_is_simple(xy) result(ok)
      real(wp), intent(in) :: xy(:, :)
      logical :: ok
      integer :: kind, i, j
      real(wp) :: dist
      call polygon_defect(xy, kind, i, j, dist)
      ok = kind == defect_none
   end function polygon_is_simple

   !> The first defect that makes the polygon not simple (see polygon_is_simple),
   !> for messages: kind (defect_*), the vertex or side numbers i < j involved
   !> (side k runs from vertex k to vertex k+1), and the distance found, which is
   !> at most geom_rtol*h.  defect_fold gives the vertex i whose two sides fold.
   !> A zero-length side is defect_coincident with j = i+1 (or i = 1, j = n).
   !> `diameter` (optional): polygon_diameter(xy), when the caller has it already.
   pure subroutine polygon_defect(xy, kind, i, j, dist, diameter)
      real(wp), intent(in) :: xy(:, :)
      integer, intent(out) :: kind, i, j
      real(wp), intent(out) :: dist
      real(wp), intent(in), optional :: diameter
      ! the vertices relative to the first and in units of the diameter: every
      ! coordinate within [-1, 1], so squared distances neither overflow nor lose the
      ! tolerance (geom_rtol^2 = 1e-20) to underflow, and no square root is needed
      real(wp) :: xs(2, size(xy, 2))
      real(wp) :: h, tol2, d2
      integer :: n, ip1, jp1, im1, k
      n = size(xy, 2)
      kind = defect_few
      i = 0
      j = 0
      dist = 0.0_wp
      if (n < 3) return
      if (present(diameter)) then
         h = diameter
      else
         h = polygon_diameter(xy)
      end if
      if (h <= 0.0_wp) return
      tol2 = geom_rtol**2
      do k = 1, n
         xs(:, k) = (xy(:, k) - xy(:, 1))/h
      end do
      kind = defect_coincident
      do j = 2, n
         do i = 1, j - 1
            d2 = (xs(1, j) - xs(1, i))**2 + (xs(2, j) - xs(2, i))**2
            if (d2 <= tol2) then
               dist = h*sqrt(d2)
               return
            end if
         end do
      end do
      ! a side folds back on its predecessor exactly when the far end of the
      ! shorter one lies on the longer one
      kind = defect_fold
      j = 0
      do i = 1, n
         im1 = modulo(i - 2, n) + 1
         ip1 = modulo(i, n) + 1
         d2 = min(point_segment_distance2(xs(:, ip1), xs(:, im1), xs(:, i)), &
                  point_segment_distance2(xs(:, im1), xs(:, i), xs(:, ip1)))
         if (d2 <= tol2) then
            dist = h*sqrt(d2)
            return
         end if
      end do
      kind = defect_crossing
      do i = 1, n - 2
         ip1 = i + 1
         do j = i + 2, n
            if (i == 1 .and. j == n) cycle   ! sides n and 1 are adjacent
            jp1 = modulo(j, n) + 1
            d2 = segment_distance2(xs(:, i), xs(:, ip1), xs(:, j), xs(:, jp1))
            if (d2 <= tol2) then
               dist = h*sqrt(d2)
               return
            end if
         end do
      end do
      kind = defect_none
      i = 0
      j = 0
      dist = 0.0_wp
   end subroutine polygon_defect

   !> Largest interior angle in degrees and the vertex where it is, for a
   !> polygon of either orientation (180 at a hanging node, above 180 at a
   !> reflex vertex).  Vertices on a zero-length side count as 180.
   pure subroutine polygon_max_angle(xy, angle, at)
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(out) :: angle
      integer, intent(out) :: at
      real(wp), parameter :: rad2deg = 57.295779513082320876798154814105_wp
      real(wp) :: s, e1(2), e2(2), a
      integer :: i, n
      n = size(xy, 2)
      angle = 0.0_wp
      at = 0
      s = sign(1.0_wp, polygon_signed_area(xy))
      do i = 1, n
         e1 = xy(:, i) - xy(:, modulo(i - 2, n) + 1)
         e2 = xy(:, modulo(i, n) + 1) - xy(:, i)
         a = 180.0_wp
         if (norm2(e1) > 0.0_wp .and. norm2(e2) > 0.0_wp) &
            a = 180.0_wp - s*rad2deg*atan2(cross2(e1, e2), dot_product(e1, e2))
         if (a > angle) then
            angle = a
            at = i
         end if
      end do
   end subroutine polygon_max_angle

   !> True for a simple polygon that turns the same way at every vertex; a
   !> vertex whose turn is within the geometric tolerance of straight (a
   !> hanging node) does not break convexity.
   pure function polygon_is_convex(xy) result(ok)
      real(wp), intent(in) :: xy(:, :)
      logical :: ok
      real(wp) :: h, s, e1(2), e2(2)
      integer :: i, n
      ok = .false.
      if (.not. polygon_is_simple(xy)) return
      n = size(xy, 2)
      h = polygon_diameter(xy)
      s = sign(1.0_wp, polygon_signed_area(xy))
      do i = 1, n
         e1 = xy(:, i) - xy(:, modulo(i - 2, n) + 1)
         e2 = xy(:, modulo(i, n) + 1) - xy(:, i)
         ! cross/|e| is the distance of the next (or previous) vertex from the
         ! line of the other side; the longer side gives the well-conditioned one
         if (s*cross2(e1, e2) < -geom_rtol*h*max(norm2(e1), norm2(e2))) return
      end do
      ok = .true.
   end function polygon_is_convex

   pure function cross2(a, b) result(c)
      real(wp), intent(in) :: a(2), b(2)
      real(wp) :: c
      c = a(1)*b(2) - a(2)*b(1)
   end function cross2

   !> Squared distance from p to the segment [a, b] (of coordinates whose squares
   !> neither overflow nor underflow: polygon_defect's scaled ones).
   pure function point_segment_distance2(p, a, b) result(d2)
      real(wp), intent(in) :: p(2), a(2), b(2)
      real(wp) :: d2
      real(wp) :: e(2), ee, t, r(2)
      e = b - a
      ee = e(1)**2 + e(2)**2
      t = 0.0_wp
      if (ee > 0.0_wp) t = min(1.0_wp, max(0.0_wp, dot_product(p - a, e)/ee))
      r = p - (a + t*e)
      d2 = r(1)**2 + r(2)**2
   end function point_segment_distance2

   !> Squared distance between the segments [a, b] and [c, d]: zero when they
   !> cross, otherwise attained at an end point of one of them.
   pure function segment_distance2(a, b, c, d) result(d2)
      real(wp), intent(in) :: a(2), b(2), c(2), d(2)
      real(wp) :: d2
      real(wp) :: o1, o2, o3, o4
      o1 = cross2(b - a, c - a)
      o2 = cross2(b - a, d - a)
      o3 = cross2(d - c, a - c)
      o4 = cross2(d - c, b - c)
      if (((o1 > 0.0_wp .and. o2 < 0.0_wp) .or. (o1 < 0.0_wp .and. o2 > 0.0_wp)) .and. &
          ((o3 > 0.0_wp .and. o4 < 0.0_wp) .or. (o3 < 0.0_wp .and. o4 > 0.0_wp))) then
         d2 = 0.0_wp
         return
      end if
      d2 = min(point_segment_distance2(a, c, d), point_segment_distance2(b, c, d), &
               point_segment_distance2(c, a, b), point_segment_distance2(d, a, b))
   end function segment_distance2
end module vemcontact_element_geometry
