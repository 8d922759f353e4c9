!> The k = 2 virtual element kernel (vemcontact_element_vem2):
!>  - single elements (random convex, star-shaped non-convex, with collinear
!>    corners): symmetry, rigid modes in the kernel, and the element patch test
!>    K u = f for a quadratic u, with f the exact nodal forces of its traction
!>    sigma.n (Simpson on each side: the trace of a node's basis function is the
!>    Lagrange quadratic of the side and sigma.n is linear, so the rule is exact)
!>    and of its constant body force -div sigma;
!>  - whole meshes (dual, non-convex median-dual, hanging-node polygons with
!>    side nodes added): u prescribed on the boundary, body force inside, every
!>    node's displacement reproduced within 1e-10 relative;
!>  - the stress recovered from the node displacements is the exact (linear)
!>    stress, at the nodes and on average;
!>  - curved sides (side nodes off the middle, each side the quadratic curve
!>    through its nodes): straight sides give the straight element (the checks
!>    above), a curved cell keeps the rigid modes in its kernel, its body load
!>    sums to t|E| with |E| from Archimedes' parabolic segments (4/3 of the
!>    triangle a-m-b on each side), and a linear field (in the curved-side
!>    space) passes the element patch test (traction sigma.n integrated along
!>    the curve) and the mesh patch test on meshes with every side curved; a
!>    quadratic field (not in the space on curved sides) does not.
program test_vem2
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: plane_strain, plane_stress
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element_vem2, only: vem2_workspace_size, vem2_stiffness, vem2_body_load, vem2_stress
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_centroid
   use vemcontact_test_polymesh, only: rng_init, random_convex_polygon, random_star_polygon, &
                                       dual_polymesh, hanging_quad_grid
   use vemcontact_test_second_order, only: add_side_nodes
   implicit none
   type(checker_t) :: t
   real(wp), allocatable :: xy(:, :), x(:, :), x2(:, :)
   integer(ip), allocatable :: ptr(:), conn(:), ptr2(:), conn2(:)
   integer(i8) :: state
   integer :: n, k, plane
   ! a quadratic field: u_c = sum_j coef(j, c) (1, x, y, x^2, xy, y^2)_j
   real(wp), parameter :: coef(6, 2) = 1.0e-3_wp*reshape([0.3_wp, 1.0_wp, -2.0_wp, 0.7_wp, -1.1_wp, 0.4_wp, &
                                                           -0.5_wp, 0.6_wp, 1.3_wp, -0.9_wp, 0.8_wp, 1.2_wp], [6, 2])

   state = rng_init(7)
   do plane = plane_strain, plane_stress
      do k = 1, 6
         n = 2 + k
         call random_convex_polygon(n, state, xy)
         call single(xy, plane, 'convex polygon', 1.0_wp)
         call single(xy, plane, 'convex polygon, tau = 0.3', 0.3_wp)
         if (n >= 6) then
            call random_star_polygon(n, state, xy)
            call single(xy, plane, 'star polygon', 1.0_wp)
         end if
      end do
      ! a square with two collinear corners on its bottom side, and a triangle
      ! with one collinear corner
      xy = reshape([0.0_wp, 0.0_wp, 0.3_wp, 0.0_wp, 0.7_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
                    1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 6])
      call single(xy, plane, 'square with collinear corners', 1.0_wp)
      xy = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.5_wp, 0.5_wp], [2, 4])
      call single(xy, plane, 'triangle with a collinear corner', 1.0_wp)

      call dual_polymesh(4, 0.3_wp, 3, x, ptr, conn)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call mesh_patch(x2, ptr2, conn2, plane, 'dual polygon mesh')
      call dual_polymesh(4, 0.2_wp, 5, x, ptr, conn, median=.true.)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call mesh_patch(x2, ptr2, conn2, plane, 'non-convex median-dual mesh')
      call hanging_quad_grid(3, 3, x, ptr, conn)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call mesh_patch(x2, ptr2, conn2, plane, 'collinear-corner (hanging node) mesh')

      ! curved sides
      do k = 1, 4
         n = 2 + k
         call random_convex_polygon(n, state, xy)
         call curved_single(xy, plane, 'curved convex polygon')
      end do
      call random_star_polygon(6, state, xy)
      call curved_single(xy, plane, 'curved star polygon')
      call dual_polymesh(4, 0.3_wp, 3, x, ptr, conn)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call bend_sides(x2, ptr2, conn2)
      call mesh_patch(x2, ptr2, conn2, plane, 'curved-side dual polygon mesh', linear=.true.)
      call dual_polymesh(4, 0.2_wp, 5, x, ptr, conn, median=.true.)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call bend_sides(x2, ptr2, conn2)
      call mesh_patch(x2, ptr2, conn2, plane, 'curved-side non-convex median-dual mesh', linear=.true.)
   end do
   call t%finish()

contains

   pure function field(p) result(u)
      real(wp), intent(in) :: p(2)
      real(wp) :: u(2)
      u = matmul([1.0_wp, p(1), p(2), p(1)**2, p(1)*p(2), p(2)**2], coef)
   end function field

   pure function strain(p) result(e)
      real(wp), intent(in) :: p(2)
      real(wp) :: e(3)
      e(1) = coef(2, 1) + 2*coef(4, 1)*p(1) + coef(5, 1)*p(2)
      e(2) = coef(3, 2) + coef(5, 2)*p(1) + 2*coef(6, 2)*p(2)
      e(3) = coef(3, 1) + coef(5, 1)*p(1) + 2*coef(6, 1)*p(2) &
             + coef(2, 2) + 2*coef(4, 2)*p(1) + coef(5, 2)*p(2)
   end function strain

   !> The linear part of field.
   pure function field1(p) result(u)
      real(wp), intent(in) :: p(2)
      real(wp) :: u(2)
      u = matmul([1.0_wp, p(1), p(2)], coef(1:3, :))
   end function field1

   !> -div(D eps), constant.
   pure function body(d) result(b)
      real(wp), intent(in) :: d(3, 3)
      real(wp) :: b(2), sx(3), sy(3)
      sx = matmul(d, [2*coef(4, 1), coef(5, 2), coef(5, 1) + 2*coef(4, 2)])
      sy = matmul(d, [coef(5, 1), 2*coef(6, 2), 2*coef(6, 1) + coef(5, 2)])
      b = -[sx(1) + sy(3), sx(3) + sy(2)]
   end function body

   !> Corners xy(2, n) -> 2n nodes with the side nodes at the middles.
   function with_sides(xy) result(xy2)
      real(wp), intent(in) :: xy(:, :)
      real(wp), allocatable :: xy2(:, :)
      integer :: i, n
      n = size(xy, 2)
      allocate (xy2(2, 2*n))
      xy2(:, 1:n) = xy
      do i = 1, n
         xy2(:, n + i) = 0.5_wp*(xy(:, i) + xy(:, mod(i, n) + 1))
      end do
   end function with_sides

   !> Each side node moved across its side by a fraction of the side's length
   !> (between -0.15 and 0.15, varying from side to side): every side curved,
   !> shared sides alike for both neighbours.
   subroutine bend_sides(x, ptr, conn)
      real(wp), intent(inout) :: x(:, :)
      integer(ip), intent(in) :: ptr(:), conn(:)
      logical, allocatable :: done(:)
      integer :: e, nc, i, node
      real(wp) :: s(2)
      allocate (done(size(x, 2)), source=.false.)
      do e = 1, size(ptr) - 1
         nc = (ptr(e + 1) - ptr(e))/2
         do i = 1, nc
            node = conn(ptr(e) + nc + i - 1)
            if (done(node)) cycle
            done(node) = .true.
            s = x(:, conn(ptr(e) + mod(i, nc))) - x(:, conn(ptr(e) + i - 1))
            x(:, node) = x(:, node) + 0.15_wp*sin(1.3_wp*node)*[s(2), -s(1)]
         end do
      end do
   end subroutine bend_sides

   !> A cell of corners cxy with every side curved (side node moved across the
   !> side by +-0.1 to 0.2 of its length).
   subroutine curved_single(cxy, plane, what)
      real(wp), intent(in) :: cxy(:, :)
      integer, intent(in) :: plane
      character(len=*), intent(in) :: what
      real(wp), allocatable :: xy2(:, :), ke(:, :), work(:), fb(:, :), u(:), f(:), r(:), sn(:, :)
      real(wp) :: d(3, 3), sig(3), thick, kn, area, sd(2), dd(2), p(2), dp(2), lag(3), nrm(2)
      real(wp), parameter :: gt(3) = [0.5_wp - 0.5_wp*sqrt(0.6_wp), 0.5_wp, 0.5_wp + 0.5_wp*sqrt(0.6_wp)]
      real(wp), parameter :: gw(3) = [5.0_wp/18.0_wp, 8.0_wp/18.0_wp, 5.0_wp/18.0_wp]
      integer :: n, nn, i, j, g, k, info, m, node(3)
      n = size(cxy, 2)
      xy2 = with_sides(cxy)
      nn = 2*n
      area = polygon_signed_area(cxy)
      do i = 1, n
         j = mod(i, n) + 1
         sd = cxy(:, j) - cxy(:, i)
         dd = (0.1_wp + 0.1_wp*mod(i, 2))*merge(1.0_wp, -1.0_wp, mod(i, 3) /= 0)*[sd(2), -sd(1)]
         xy2(:, n + i) = xy2(:, n + i) + dd
         area = area + 2.0_wp/3.0_wp*(dd(1)*sd(2) - dd(2)*sd(1))    ! Archimedes: 4/3 of triangle a-m-b
      end do
      thick = 0.5_wp
      call elastic_matrix(2.0e5_wp, 0.3_wp, plane, d)
      allocate (ke(2*nn, 2*nn), work(vem2_workspace_size(nn)), fb(2*nn, 2), u(2*nn), f(2*nn), sn(3, nn))
      call vem2_stiffness(xy2, d, thick, ke, work, info)
      call t%check(info == 0, what//': info = 0')
      if (info /= 0) return
      kn = maxval(abs(ke))
      call t%check(maxval(abs(ke - transpose(ke))) <= 1.0e-14_wp*kn, what//': symmetric')
      do m = 1, 3
         do i = 1, nn
            select case (m)
            case (1); u(2*i - 1:2*i) = [1.0_wp, 0.0_wp]
            case (2); u(2*i - 1:2*i) = [0.0_wp, 1.0_wp]
            case (3); u(2*i - 1:2*i) = [-xy2(2, i), xy2(1, i)]
            end select
         end do
         r = matmul(ke, u)
         call t%check(maxval(abs(r)) <= 1.0e-12_wp*kn*maxval(abs(u)), what//': rigid mode in the kernel')
      end do
      call vem2_body_load(xy2, d, thick, fb, work, info)
      call t%close(sum(fb(1::2, 1)), thick*area, 1.0e-12_wp, what//': body load sums to t|E| (curved |E|)')
      ! traction of the linear field's constant stress along each curve: the
      ! trace of a node's basis function is its Lagrange quadratic in t and
      ! n ds = (y'(t), -x'(t)) dt is linear, so 3-point Gauss is exact
      do k = 1, 2
         f = 0
         do i = 1, n
            node = [i, mod(i, n) + 1, n + i]
            do g = 1, 3
               call curve_point(xy2(:, node(1)), xy2(:, node(2)), xy2(:, node(3)), gt(g), p, dp, lag)
               nrm = gw(g)*[dp(2), -dp(1)]
               do j = 1, 3
                  if (k == 1) then
                     call add_traction(f, d, thick, nrm, node(j), [0.0_wp, 0.0_wp], lag(j), linear=.true.)
                  else
                     call add_traction(f, d, thick, nrm, node(j), p, lag(j))
                  end if
               end do
            end do
         end do
         if (k == 2) f = f + matmul(fb, body(d))
         do i = 1, nn
            if (k == 1) u(2*i - 1:2*i) = field1(xy2(:, i))
            if (k == 2) u(2*i - 1:2*i) = field(xy2(:, i))
         end do
         r = matmul(ke, u) - f
         if (k == 1) then
            ! 1e-10 as the straight element patch test
            call t%check(maxval(abs(r)) <= 1.0e-10_wp*maxval(abs(f)), what//': element patch test, linear field')
            call vem2_stress(xy2, d, thick, u, work, sig, signode=sn)
            sig = matmul(d, [coef(2, 1), coef(3, 2), coef(3, 1) + coef(2, 2)])
            call t%check(maxval(abs(sn - spread(sig, 2, nn))) <= 1.0e-9_wp*maxval(abs(sig)), &
                         what//': constant stress exact at the nodes')
         else
            ! not in the space: a residual of the order of the curvature, far above round-off
            print '(a,es10.2)', what//': quadratic field, relative residual ', maxval(abs(r))/maxval(abs(f))
            call t%check(maxval(abs(r)) > 1.0e-6_wp*maxval(abs(f)), what//': quadratic field not reproduced')
         end if
      end do
   end subroutine curved_single

   !> Point, derivative and Lagrange quadratics (t = 0, 1, 1/2) of the side a, b, m at t.
   pure subroutine curve_point(a, b, m, t, p, dp, lag)
      real(wp), intent(in) :: a(2), b(2), m(2), t
      real(wp), intent(out) :: p(2), dp(2), lag(3)
      lag = [2*(t - 0.5_wp)*(t - 1), 2*t*(t - 0.5_wp), 4*t*(1 - t)]
      p = lag(1)*a + lag(2)*b + lag(3)*m
      dp = (4*t - 3)*a + (4*t - 1)*b + (4 - 8*t)*m
   end subroutine curve_point

   subroutine single(cxy, plane, what, tau)
      real(wp), intent(in) :: cxy(:, :), tau
      integer, intent(in) :: plane
      character(len=*), intent(in) :: what
      real(wp), allocatable :: xy2(:, :), ke(:, :), work(:), fb(:, :), u(:), f(:), r(:), sn(:, :)
      real(wp) :: d(3, 3), sig(3), b(2), nrm(2), thick, kn, xc(2), area
      integer :: n, nn, i, j, info, m
      n = size(cxy, 2)
      xy2 = with_sides(cxy)
      nn = 2*n
      thick = 0.5_wp
      call elastic_matrix(2.0e5_wp, 0.3_wp, plane, d)
      allocate (ke(2*nn, 2*nn), work(vem2_workspace_size(nn)), fb(2*nn, 2), u(2*nn), f(2*nn), sn(3, nn))
      call vem2_stiffness(xy2, d, thick, ke, work, info, tau)
      call t%check(info == 0, what//': info = 0')
      if (info /= 0) return
      kn = maxval(abs(ke))
      call t%check(maxval(abs(ke - transpose(ke))) <= 1.0e-14_wp*kn, what//': symmetric')
      ! rigid modes: two translations and a rotation (1e-12: round-off of a
      ! sum of O(10 n) terms of size kn)
      do m = 1, 3
         do i = 1, nn
            select case (m)
            case (1); u(2*i - 1:2*i) = [1.0_wp, 0.0_wp]
            case (2); u(2*i - 1:2*i) = [0.0_wp, 1.0_wp]
            case (3); u(2*i - 1:2*i) = [-xy2(2, i), xy2(1, i)]
            end select
         end do
         r = matmul(ke, u)
         call t%check(maxval(abs(r)) <= 1.0e-12_wp*kn*maxval(abs(u)), what//': rigid mode in the kernel')
      end do
      ! element patch test
      call vem2_body_load(xy2, d, thick, fb, work, info, tau)
      call t%check(info == 0, what//': body load info = 0')
      area = polygon_signed_area(cxy)
      call t%close(sum(fb(1::2, 1)), thick*area, 1.0e-12_wp, what//': body load sums to t|E|')
      call t%close(sum(fb(2::2, 2)), thick*area, 1.0e-12_wp, what//': body load sums to t|E| (y)')
      b = body(d)
      f = matmul(fb, b)
      do i = 1, n
         j = mod(i, n) + 1
         nrm = [cxy(2, j) - cxy(2, i), -(cxy(1, j) - cxy(1, i))]
         call add_traction(f, d, thick, nrm, i, xy2(:, i), 1.0_wp/6)
         call add_traction(f, d, thick, nrm, j, xy2(:, j), 1.0_wp/6)
         call add_traction(f, d, thick, nrm, n + i, xy2(:, n + i), 4.0_wp/6)
      end do
      do i = 1, nn
         u(2*i - 1:2*i) = field(xy2(:, i))
      end do
      r = matmul(ke, u) - f
      ! 1e-10: the element operators are formed from O(n) sums and small dense solves
      call t%check(maxval(abs(r)) <= 1.0e-10_wp*maxval(abs(f)), what//': element patch test')
      call vem2_stress(xy2, d, thick, u, work, sig, b, tau, sn)
      call polygon_centroid(cxy, xc)
      call t%check(maxval(abs(sig - matmul(d, strain(xc)))) <= 1.0e-9_wp*maxval(abs(matmul(d, strain(xc)))), &
                   what//': mean stress exact')
      do i = 1, nn
         sig = matmul(d, strain(xy2(:, i)))
         if (maxval(abs(sn(:, i) - sig)) > 1.0e-9_wp*maxval(abs(sig))) then
            call t%check(.false., what//': nodal stress exact')
            exit
         end if
      end do
   end subroutine single

   !> f(node) += w t sigma(p) nrm (nrm: the side's length times its outward normal).
   !> With `linear`, sigma of the linear part of field (constant).
   subroutine add_traction(f, d, thick, nrm, node, p, w, linear)
      real(wp), intent(inout) :: f(:)
      real(wp), intent(in) :: d(3, 3), thick, nrm(2), p(2), w
      integer, intent(in) :: node
      logical, intent(in), optional :: linear
      real(wp) :: s(3)
      s = thick*matmul(d, strain(p))
      if (present(linear)) then
         if (linear) s = thick*matmul(d, [coef(2, 1), coef(3, 2), coef(3, 1) + coef(2, 2)])
      end if
      f(2*node - 1) = f(2*node - 1) + w*(s(1)*nrm(1) + s(3)*nrm(2))
      f(2*node) = f(2*node) + w*(s(3)*nrm(1) + s(2)*nrm(2))
   end subroutine add_traction

   !> Dense assembly, u prescribed on the boundary nodes, the body force inside;
   !> with `linear`, the linear part of the field and no body force.
   subroutine mesh_patch(x, ptr, conn, plane, what, linear)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: ptr(:), conn(:)
      integer, intent(in) :: plane
      character(len=*), intent(in) :: what
      logical, intent(in), optional :: linear
      logical :: lin
      real(wp), allocatable :: a(:, :), f(:), u(:), uex(:), ke(:, :), fb(:, :), work(:)
      logical, allocatable :: fixed(:)
      integer, allocatable :: cnt(:)
      integer, allocatable :: dofs(:)
      real(wp) :: d(3, 3), b(2)
      integer :: nnode, ne, e, nn, i, j, info, lo, hi
      nnode = size(x, 2)
      ne = size(ptr) - 1
      lin = .false.
      if (present(linear)) lin = linear
      call elastic_matrix(2.0e5_wp, 0.3_wp, plane, d)
      b = body(d)
      if (lin) b = 0
      allocate (a(2*nnode, 2*nnode), f(2*nnode), u(2*nnode), uex(2*nnode), fixed(2*nnode))
      allocate (cnt(nnode), source=0)
      a = 0
      f = 0
      do e = 1, ne
         nn = ptr(e + 1) - ptr(e)
         allocate (ke(2*nn, 2*nn), fb(2*nn, 2), work(vem2_workspace_size(nn)))
         call vem2_stiffness(x(:, conn(ptr(e):ptr(e + 1) - 1)), d, 0.5_wp, ke, work, info)
         call t%check(info == 0, what//': element accepted')
         call vem2_body_load(x(:, conn(ptr(e):ptr(e + 1) - 1)), d, 0.5_wp, fb, work, info)
         dofs = [(2*conn(ptr(e) + (i - 1)/2) - mod(i, 2), i=1, 2*nn)]
         a(dofs, dofs) = a(dofs, dofs) + ke
         f(dofs) = f(dofs) + matmul(fb, b)
         deallocate (ke, fb, work)
      end do
      ! boundary nodes: side nodes used by one element only, and corners of such sides
      do e = 1, ne
         nn = ptr(e + 1) - ptr(e)
         do i = nn/2 + 1, nn
            j = conn(ptr(e) + i - 1)
            cnt(j) = cnt(j) + 1
         end do
      end do
      fixed = .false.
      do e = 1, ne
         nn = ptr(e + 1) - ptr(e)
         do i = 1, nn/2
            j = conn(ptr(e) + nn/2 + i - 1)
            if (cnt(j) == 1) then
               lo = conn(ptr(e) + i - 1)
               hi = conn(ptr(e) + mod(i, nn/2))
               fixed(2*j - 1:2*j) = .true.
               fixed(2*lo - 1:2*lo) = .true.
               fixed(2*hi - 1:2*hi) = .true.
            end if
         end do
      end do
      do i = 1, nnode
         uex(2*i - 1:2*i) = field(x(:, i))
         if (lin) uex(2*i - 1:2*i) = field1(x(:, i))
      end do
      ! move the prescribed values to the right-hand side, identity rows for them
      f = f - matmul(a, merge(uex, 0.0_wp, fixed))
      do i = 1, 2*nnode
         if (fixed(i)) then
            a(i, :) = 0
            a(:, i) = 0
            a(i, i) = 1
            f(i) = uex(i)
         end if
      end do
      call cholesky_solve(a, f, u, info)
      call t%check(info == 0, what//': stiffness positive definite')
      ! 1e-10 relative: the issue's target for the displacement patch test
      call t%check(maxval(abs(u - uex)) <= 1.0e-10_wp*maxval(abs(uex)), &
                   what//': '//merge('linear   ', 'quadratic', lin)//' field reproduced at every node')
      print '(a,es10.2)', what//': max relative nodal error ', maxval(abs(u - uex))/maxval(abs(uex))
   end subroutine mesh_patch

   !> Dense Cholesky solve of the symmetric positive definite a x = f.
   subroutine cholesky_solve(a, f, x, info)
      real(wp), intent(inout) :: a(:, :)
      real(wp), intent(in) :: f(:)
      real(wp), intent(out) :: x(:)
      integer, intent(out) :: info
      integer :: j, n
      n = size(f)
      info = 0
      do j = 1, n
         a(j, j) = a(j, j) - dot_product(a(j, 1:j - 1), a(j, 1:j - 1))
         if (.not. a(j, j) > 0.0_wp) then
            info = j
            return
         end if
         a(j, j) = sqrt(a(j, j))
         a(j + 1:n, j) = (a(j + 1:n, j) - matmul(a(j + 1:n, 1:j - 1), a(j, 1:j - 1)))/a(j, j)
      end do
      x = f
      do j = 1, n
         x(j) = (x(j) - dot_product(a(j, 1:j - 1), x(1:j - 1)))/a(j, j)
      end do
      do j = n, 1, -1
         x(j) = (x(j) - dot_product(a(j + 1:n, j), x(j + 1:n)))/a(j, j)
      end do
   end subroutine cholesky_solve
end program test_vem2
