!> The test mesh generators deliver what other tests rely on: valid,
!> counter-clockwise, conforming polygon meshes that cover their domain.
program test_element_polymesh
   use vemcontact_kinds, only: wp, ip
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_is_simple, polygon_is_convex
   use vemcontact_test_polymesh, only: quad_grid, dual_polymesh, hanging_quad_grid, &
      cantilever_two_quads, nodes_on_line
   use vemcontact_testing, only: checker_t
   implicit none

   !> total areas are sums of O(100) cell areas of ~1e-2: rounding ~1e-15
   real(wp), parameter :: rtol = 1.0e-13_wp
   type(checker_t) :: t
   real(wp), allocatable :: x(:, :), x2(:, :)
   integer(ip), allocatable :: ptr(:), conn(:), ptr2(:), conn2(:), idx(:)
   integer, allocatable :: uses(:)
   integer :: n, e, nonconvex, minv, maxv

   ! structured perturbed quads on [1,4] x [-1,1]
   call quad_grid(6, 4, 1.0_wp, -1.0_wp, 3.0_wp, 2.0_wp, 0.2_wp, 5, x, ptr, conn)
   call t%equal(size(x, 2), 35, 'quad_grid nodes')
   call t%equal(size(ptr) - 1, 24, 'quad_grid elements')
   call check_mesh(x, ptr, conn, 6.0_wp, 'quad_grid')
   do e = 1, size(ptr) - 1
      if (.not. polygon_is_convex(x(:, conn(ptr(e):ptr(e + 1) - 1)))) call t%check(.false., 'quad_grid convex')
   end do
   call nodes_on_line(x, 1, 1.0_wp, 1.0e-12_wp, idx)
   call t%equal(size(idx), 5, 'quad_grid: 5 nodes on x = 1 (boundary not perturbed)')
   call nodes_on_line(x, 2, 1.0_wp, 1.0e-12_wp, idx)
   call t%equal(size(idx), 7, 'quad_grid: 7 nodes on y = 1')
   call quad_grid(6, 4, 1.0_wp, -1.0_wp, 3.0_wp, 2.0_wp, 0.2_wp, 5, x2, ptr2, conn2)
   call t%check(all(abs(x2 - x) <= 0.0_wp), 'quad_grid reproducible for equal seeds')
   call quad_grid(6, 4, 1.0_wp, -1.0_wp, 3.0_wp, 2.0_wp, 0.2_wp, 6, x2, ptr2, conn2)
   call t%check(any(abs(x2 - x) > 0.0_wp), 'quad_grid differs for other seeds')

   ! barycentric dual polygon mesh of the unit square
   n = 6
   call dual_polymesh(n, 0.3_wp, 11, x, ptr, conn)
   call t%equal(size(ptr) - 1, (n + 1)**2, 'dual: one cell per grid point')
   call t%equal(size(x, 2), 2*n*n + 8*n, 'dual: centroids + boundary midpoints + boundary points')
   call check_mesh(x, ptr, conn, 1.0_wp, 'dual')
   call count_uses()
   call t%check(all(uses(1:2*n*n) == 3), 'dual: each centroid shared by 3 cells')
   call t%check(all(uses(2*n*n + 1:2*n*n + 4*n) == 2), 'dual: each boundary midpoint shared by 2 cells')
   call t%check(all(uses(2*n*n + 4*n + 1:) == 1), 'dual: each boundary grid point in its own cell')
   call cell_stats('dual')
   call t%equal(minv, 4, 'dual: corner cells with one triangle have 4 vertices')
   call t%equal(maxv, 6, 'dual: interior and boundary cells have 6 vertices')
   e = 3*(n + 1) + 3 + 1
   call t%equal(ptr(e + 1) - ptr(e), 6, 'dual: interior cell (3,3) is a hexagon')
   call dual_polymesh(n, 0.0_wp, 11, x, ptr, conn)
   call check_mesh(x, ptr, conn, 1.0_wp, 'dual unperturbed')

   ! median dual: interior side midpoints between the centroids
   call dual_polymesh(n, 0.3_wp, 11, x, ptr, conn, median=.true.)
   call t%equal(size(x, 2), 2*n*n + 8*n + 3*n*n - 2*n, 'median dual: + interior side midpoints')
   call check_mesh(x, ptr, conn, 1.0_wp, 'median dual')
   call count_uses()
   call t%check(all(uses(1:2*n*n) == 3), 'median dual: each centroid shared by 3 cells')
   call t%check(all(uses(2*n*n + 1:2*n*n + 4*n) == 2), 'median dual: boundary midpoints shared by 2')
   call t%check(all(uses(2*n*n + 8*n + 1:) == 2), 'median dual: interior midpoints shared by 2')
   call cell_stats('median dual')
   call t%check(nonconvex > 0, 'median dual: perturbation makes cells non-convex')
   call t%equal(maxv, 12, 'median dual: interior cells have 12 vertices')
   call dual_polymesh(n, 0.0_wp, 11, x, ptr, conn, median=.true.)
   call check_mesh(x, ptr, conn, 1.0_wp, 'median dual unperturbed')
   call cell_stats('median dual unperturbed')
   call t%equal(nonconvex, 0, 'median dual unperturbed: all convex (midpoints collinear)')

   ! hanging nodes
   call hanging_quad_grid(4, 3, x, ptr, conn)
   call check_mesh(x, ptr, conn, 1.0_wp, 'hanging')
   ! 6 refined cells (i+j even) give 24 quads, 6 coarse cells remain
   call t%equal(size(ptr) - 1, 30, 'hanging: 24 sub-quads + 6 coarse polygons')
   minv = huge(1)
   maxv = 0
   do e = 1, size(ptr) - 1
      if (ptr(e + 1) - ptr(e) > 4) then
         minv = min(minv, ptr(e + 1) - ptr(e))
         maxv = max(maxv, ptr(e + 1) - ptr(e))
         call t%check(polygon_is_convex(x(:, conn(ptr(e):ptr(e + 1) - 1))), 'hanging: coarse cell convex')
      end if
   end do
   call t%equal(minv, 6, 'hanging: smallest coarse polygon (corner-ish) has 6 vertices')
   call t%equal(maxv, 8, 'hanging: interior coarse polygon has 8 vertices')

   ! two-quad cantilever: both halves have area L b / 2 for any skew d < L/2
   call cantilever_two_quads(10.0_wp, 2.0_wp, 1.5_wp, x, ptr, conn)
   call check_mesh(x, ptr, conn, 20.0_wp, 'cantilever')
   call t%close(polygon_signed_area(x(:, conn(1:4))), 10.0_wp, rtol, 'cantilever: element 1 area')
   call t%close(polygon_signed_area(x(:, conn(5:8))), 10.0_wp, rtol, 'cantilever: element 2 area')
   call t%close(x(1, 2), 3.5_wp, rtol, 'cantilever: shared side starts at L/2 - d')
   call t%close(x(1, 5), 6.5_wp, rtol, 'cantilever: shared side ends at L/2 + d')
   call nodes_on_line(x, 1, 0.0_wp, 1.0e-12_wp, idx)
   call t%check(size(idx) == 2 .and. all(idx == [1_ip, 6_ip]), 'cantilever: clamped end nodes 1 and 6')
   call t%finish()

contains

   subroutine count_uses()
      integer :: kk
      if (allocated(uses)) deallocate (uses)
      allocate (uses(size(x, 2)))
      uses = 0
      do kk = 1, size(conn)
         uses(conn(kk)) = uses(conn(kk)) + 1
      end do
   end subroutine count_uses

   subroutine cell_stats(what)
      character(len=*), intent(in) :: what
      integer :: ee
      nonconvex = 0
      minv = huge(1)
      maxv = 0
      do ee = 1, size(ptr) - 1
         if (.not. polygon_is_convex(x(:, conn(ptr(ee):ptr(ee + 1) - 1)))) nonconvex = nonconvex + 1
         minv = min(minv, ptr(ee + 1) - ptr(ee))
         maxv = max(maxv, ptr(ee + 1) - ptr(ee))
      end do
      write (*, '(a,i0,a,i0,a,i0,a,i0)') what//': ', size(ptr) - 1, ' cells, ', nonconvex, &
         ' non-convex, vertices per cell ', minv, '..', maxv
   end subroutine cell_stats

   !> Every cell simple with positive area, areas add up to the domain, and the
   !> mesh is conforming: each directed side (a, b) of a cell meets exactly one
   !> (b, a) in a neighbour, or none when it lies on the boundary of the domain
   !> (an axis-parallel line through the bounding box).
   subroutine check_mesh(xx, pp, cc, total, what)
      real(wp), intent(in) :: xx(:, :)
      integer(ip), intent(in) :: pp(:), cc(:)
      real(wp), intent(in) :: total
      character(len=*), intent(in) :: what
      integer, allocatable :: ea(:), eb(:)
      real(wp) :: area, a, lo(2), hi(2), tol
      integer :: ee, j, m, i, nmatch, ne
      logical :: ok_simple, ok_area, ok_conf
      ne = size(pp) - 1
      allocate (ea(size(cc)), eb(size(cc)))
      m = 0
      area = 0.0_wp
      ok_simple = .true.
      ok_area = .true.
      do ee = 1, ne
         associate (cell => cc(pp(ee):pp(ee + 1) - 1))
            a = polygon_signed_area(xx(:, cell))
            area = area + a
            ok_area = ok_area .and. a > 0.0_wp
            ok_simple = ok_simple .and. polygon_is_simple(xx(:, cell))
            do j = 1, size(cell)
               m = m + 1
               ea(m) = cell(j)
               eb(m) = cell(modulo(j, size(cell)) + 1)
            end do
         end associate
      end do
      call t%check(ok_area, what//': all cells counter-clockwise with positive area')
      call t%check(ok_simple, what//': all cells simple')
      call t%close(area, total, rtol, what//': total area')
      lo = minval(xx, dim=2)
      hi = maxval(xx, dim=2)
      tol = 1.0e-12_wp*maxval(hi - lo)
      ok_conf = .true.
      do i = 1, m
         nmatch = count(ea(1:m) == eb(i) .and. eb(1:m) == ea(i))
         if (nmatch == 0) then
            ! boundary side: both ends on the same side of the bounding box
            ok_conf = ok_conf .and. (any(abs(xx(:, ea(i)) - lo) <= tol .and. abs(xx(:, eb(i)) - lo) <= tol) &
                                     .or. any(abs(xx(:, ea(i)) - hi) <= tol .and. abs(xx(:, eb(i)) - hi) <= tol))
         else
            ok_conf = ok_conf .and. nmatch == 1 .and. count(ea(1:m) == ea(i) .and. eb(1:m) == eb(i)) == 1
         end if
      end do
      call t%check(ok_conf, what//': conforming (every side shared once or on the boundary)')
   end subroutine check_mesh
end program test_element_polymesh
