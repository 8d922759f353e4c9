!> Polygon geometry (area, centroid, diameter, simplicity, convexity) on shapes
!> with known answers, and the elasticity matrices against their closed forms.
program test_element_geometry
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: plane_strain, plane_stress
   use vemcontact_material_elastic, only: elastic_matrix, out_of_plane_stress
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_centroid, &
      polygon_diameter, polygon_is_simple, polygon_is_convex
   use vemcontact_testing, only: checker_t
   implicit none

   !> a handful of operations on O(1) numbers: rounding is ~1e-16, so 1e-14
   real(wp), parameter :: rtol = 1.0e-14_wp
   type(checker_t) :: t
   real(wp), allocatable :: p(:, :)
   real(wp) :: c(2), d(3, 3), s3
   integer :: k

   ! unit square, both orientations
   p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
   call t%close(polygon_signed_area(p), 1.0_wp, rtol, 'square area')
   call polygon_centroid(p, c)
   call t%close(c(1), 0.5_wp, rtol, 'square centroid x')
   call t%close(c(2), 0.5_wp, rtol, 'square centroid y')
   call t%close(polygon_diameter(p), sqrt(2.0_wp), rtol, 'square diameter')
   call t%check(polygon_is_simple(p), 'square simple')
   call t%check(polygon_is_convex(p), 'square convex')
   call t%close(polygon_signed_area(p(:, 4:1:-1)), -1.0_wp, rtol, 'clockwise square area < 0')
   call t%check(polygon_is_convex(p(:, 4:1:-1)), 'clockwise square convex')
   ! far from the origin: computed relative to the first vertex, so still exact
   call t%close(polygon_signed_area(p + 1.0e6_wp), 1.0_wp, 1.0e-9_wp, 'square at 1e6 area')

   ! L-shape: [0,2]x[0,1] (area 2, centroid (1, 1/2)) + [0,1]x[1,2] (area 1,
   ! centroid (1/2, 3/2)): area 3, centroid (5/6, 5/6)
   p = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, &
                1.0_wp, 2.0_wp, 0.0_wp, 2.0_wp], [2, 6])
   call t%close(polygon_signed_area(p), 3.0_wp, rtol, 'L area')
   call polygon_centroid(p, c)
   call t%close(c(1), 5.0_wp/6.0_wp, rtol, 'L centroid x')
   call t%close(c(2), 5.0_wp/6.0_wp, rtol, 'L centroid y')
   call t%close(polygon_diameter(p), sqrt(8.0_wp), rtol, 'L diameter')
   call t%check(polygon_is_simple(p), 'L simple (non-convex accepted)')
   call t%check(.not. polygon_is_convex(p), 'L not convex')

   ! regular hexagon of circumradius 2: area 3 sqrt(3)/2 r^2 = 6 sqrt(3), centroid at its centre
   deallocate (p)
   allocate (p(2, 6))
   do k = 1, 6
      p(:, k) = [3.0_wp, -1.0_wp] + 2.0_wp*[cos((k - 1)*acos(-1.0_wp)/3), sin((k - 1)*acos(-1.0_wp)/3)]
   end do
   call t%close(polygon_signed_area(p), 6.0_wp*sqrt(3.0_wp), rtol, 'hexagon area')
   call polygon_centroid(p, c)
   call t%close(c(1), 3.0_wp, rtol, 'hexagon centroid x')
   call t%close(c(2), -1.0_wp, rtol, 'hexagon centroid y')
   call t%close(polygon_diameter(p), 4.0_wp, rtol, 'hexagon diameter')
   call t%check(polygon_is_convex(p), 'hexagon convex')

   ! triangle: centroid = vertex mean
   p = reshape([0.0_wp, 0.0_wp, 4.0_wp, 1.0_wp, 1.0_wp, 3.0_wp], [2, 3])
   call t%close(polygon_signed_area(p), 5.5_wp, rtol, 'triangle area')
   call polygon_centroid(p, c)
   call t%close(c(1), 5.0_wp/3.0_wp, rtol, 'triangle centroid x')
   call t%close(c(2), 4.0_wp/3.0_wp, rtol, 'triangle centroid y')
   ! rectangle 3 x 4: diameter 5
   p = reshape([0.0_wp, 0.0_wp, 3.0_wp, 0.0_wp, 3.0_wp, 4.0_wp, 0.0_wp, 4.0_wp], [2, 4])
   call t%close(polygon_diameter(p), 5.0_wp, rtol, 'rectangle diameter')

   ! rejected by polygon_is_simple
   p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 4])
   call t%check(.not. polygon_is_simple(p), 'bow-tie rejected')
   call t%check(.not. polygon_is_convex(p), 'bow-tie not convex')
   p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, 0.5_wp, 1.0_wp, 1.0_wp, &
                0.0_wp, 1.0_wp, 0.5_wp, 0.5_wp], [2, 6])
   call t%check(.not. polygon_is_simple(p), 'repeated vertex (pinched polygon) rejected')
   p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 5])
   call t%check(.not. polygon_is_simple(p), 'zero-length side rejected')
   p = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp], [2, 4])
   call t%check(.not. polygon_is_simple(p), 'side folding back on its neighbour rejected')
   p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 2.0_wp, 0.0_wp], [2, 3])
   call t%check(.not. polygon_is_simple(p), 'collinear triangle rejected')
   ! vertex 1e-12 h from a non-adjacent side: touching within rounding
   p = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 2.0_wp, 1.0_wp, 1.0e-12_wp, 0.0_wp, 2.0_wp], [2, 5])
   call t%check(.not. polygon_is_simple(p), 'vertex touching a side rejected')
   p(2, 4) = 1.0e-6_wp
   call t%check(polygon_is_simple(p), 'vertex 1e-6 h from a side accepted')

   ! accepted: collinear (hanging) vertices, tiny sides
   p = reshape([0.0_wp, 0.0_wp, 0.5_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.5_wp, &
                1.0_wp, 1.0_wp, 0.5_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp], [2, 8])
   call t%check(polygon_is_simple(p), 'square with midpoints simple')
   call t%check(polygon_is_convex(p), 'square with midpoints convex')
   call t%close(polygon_signed_area(p), 1.0_wp, rtol, 'square with midpoints area')
   p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp - 1.0e-6_wp, &
                1.0_wp - 1.0e-6_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 5])
   call t%check(polygon_is_simple(p), '1e-6 side accepted')
   call t%check(polygon_is_convex(p), '1e-6 corner cut convex')
   ! dart: simple, not convex
   p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.5_wp, 0.2_wp], [2, 4])
   call t%check(polygon_is_simple(p), 'dart simple')
   call t%check(.not. polygon_is_convex(p), 'dart not convex')

   ! elasticity, E = 1, nu = 1/4.  Plane strain: c = E/((1+nu)(1-2nu)) = 1.6,
   ! D11 = c(1-nu) = 1.2, D12 = c nu = 0.4, D33 = E/(2(1+nu)) = 0.4.
   call elastic_matrix(1.0_wp, 0.25_wp, plane_strain, d)
   call t%close(d(1, 1), 1.2_wp, rtol, 'plane strain D11')
   call t%close(d(2, 2), 1.2_wp, rtol, 'plane strain D22')
   call t%close(d(1, 2), 0.4_wp, rtol, 'plane strain D12')
   call t%close(d(2, 1), 0.4_wp, rtol, 'plane strain D21')
   call t%close(d(3, 3), 0.4_wp, rtol, 'plane strain D33')
   call t%check(maxval(abs([d(1, 3), d(2, 3), d(3, 1), d(3, 2)])) < tiny(1.0_wp), 'no shear coupling')
   ! plane stress: D11 = E/(1-nu^2) = 16/15, D12 = 4/15, D33 = 0.4; it must be
   ! the inverse of the compliance [[1, -nu, 0], [-nu, 1, 0], [0, 0, 2(1+nu)]]/E
   call elastic_matrix(1.0_wp, 0.25_wp, plane_stress, d)
   call t%close(d(1, 1), 16.0_wp/15.0_wp, rtol, 'plane stress D11')
   call t%close(d(1, 2), 4.0_wp/15.0_wp, rtol, 'plane stress D12')
   call t%close(d(3, 3), 0.4_wp, rtol, 'plane stress D33')
   s3 = d(1, 1) - 0.25_wp*d(1, 2)
   call t%close(s3, 1.0_wp, rtol, 'plane stress: compliance * D = I (1,1)')
   call t%close(out_of_plane_stress(0.25_wp, plane_strain, 3.0_wp, 5.0_wp), 2.0_wp, rtol, 'szz plane strain')
   call t%close(out_of_plane_stress(0.25_wp, plane_stress, 3.0_wp, 5.0_wp), 0.0_wp, rtol, &
                'szz plane stress', atol=0.0_wp)
   call t%finish()
end program test_element_geometry
