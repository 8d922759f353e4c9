!> Test mesh generators: structured and perturbed quads, the barycentric dual
!> of a triangulation (a genuine polygon mesh), quads with hanging nodes, the
!> two-element cantilever, random single polygons, and node selection helpers.
!> Meshes come as x(2, nnode) and CSR connectivity ptr(nelem+1), conn(:),
!> polygons counter-clockwise.  Randomness comes from a xorshift64 generator
!> carried in an integer(i8) state, so meshes are reproducible across
!> compilers (random_number is not).
module vemcontact_test_polymesh
   use vemcontact_kinds, only: wp, ip, i8
   implicit none
   private

   public :: rng_init, rng_uniform
   public :: quad_grid, dual_polymesh, hanging_quad_grid, cantilever_two_quads
   public :: nodes_on_line, random_convex_polygon, random_star_polygon

   real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp

contains

   !> A non-zero generator state from any integer seed (equal seeds, equal streams).
   function rng_init(seed) result(state)
      integer, intent(in) :: seed
      integer(i8) :: state
      real(wp) :: r
      integer :: k
      state = ieor(88172645463325252_i8, int(seed, i8))
      state = ieor(state, ishft(int(seed, i8), 32))
      if (state == 0_i8) state = 88172645463325252_i8
      do k = 1, 8     ! let nearby seeds decorrelate
         call rng_uniform(state, r)
      end do
   end function rng_init

   !> Next uniform number in [0, 1): xorshift64 (Marsaglia 2003), top 53 bits.
   !> Shifts and xors only, so no integer overflow is involved.
   subroutine rng_uniform(state, r)
      integer(i8), intent(inout) :: state
      real(wp), intent(out) :: r
      state = ieor(state, ishft(state, 13))
      state = ieor(state, ishft(state, -7))
      state = ieor(state, ishft(state, 17))
      r = real(ishft(state, -11), wp)*2.0_wp**(-53)
   end subroutine rng_uniform

   !> nx x ny quads on [x0, x0+lx] x [y0, y0+ly]; interior nodes moved in each
   !> coordinate by a uniform amount in [-perturb*h, perturb*h], h = min cell
   !> side (perturb < 0.25 keeps every quad convex).  Node (i, j), i = 0..nx,
   !> j = 0..ny, is number j*(nx+1) + i + 1; element (i, j) is j*nx + i + 1.
   subroutine quad_grid(nx, ny, x0, y0, lx, ly, perturb, seed, x, ptr, conn)
      integer, intent(in) :: nx, ny, seed
      real(wp), intent(in) :: x0, y0, lx, ly, perturb
      real(wp), allocatable, intent(out) :: x(:, :)
      integer(ip), allocatable, intent(out) :: ptr(:), conn(:)
      integer(i8) :: state
      real(wp) :: h, r
      integer :: i, j, e, k
      state = rng_init(seed)
      h = min(lx/nx, ly/ny)
      allocate (x(2, (nx + 1)*(ny + 1)), ptr(nx*ny + 1), conn(4*nx*ny))
      do j = 0, ny
         do i = 0, nx
            k = j*(nx + 1) + i + 1
            x(1, k) = x0 + lx*real(i, wp)/nx
            x(2, k) = y0 + ly*real(j, wp)/ny
            if (i > 0 .and. i < nx .and. j > 0 .and. j < ny) then
               call rng_uniform(state, r)
               x(1, k) = x(1, k) + (2.0_wp*r - 1.0_wp)*perturb*h
               call rng_uniform(state, r)
               x(2, k) = x(2, k) + (2.0_wp*r - 1.0_wp)*perturb*h
            end if
         end do
      end do
      ptr(1) = 1
      do j = 0, ny - 1
         do i = 0, nx - 1
            e = j*nx + i + 1
            k = j*(nx + 1) + i + 1
            conn(4*e - 3:4*e) = [k, k + 1, k + nx + 2, k + nx + 1]
            ptr(e + 1) = ptr(e) + 4
         end do
      end do
   end subroutine quad_grid

   !> Barycentric dual of the triangulation of an (n+1) x (n+1) grid on [0,1]^2
   !> (every square cut by its SW-NE diagonal; interior grid points moved in each
   !> coordinate by up to perturb/n; test_element_polymesh checks that the cells
   !> stay valid for perturb = 0.3, which leaves the triangles far from folding).
   !> Cell c = j*(n+1) + i + 1 belongs to grid point (i, j): the polygon
   !> through the centroids of its triangles in angular order, which is
   !> star-shaped about the grid point and so simple; interior cells are
   !> hexagons.  A boundary cell also holds the midpoints of its two boundary
   !> sides and the grid point itself (collinear with the midpoints except at
   !> the 4 corners).  Nodes: 2n^2 centroids, then 4n boundary midpoints, then
   !> 4n boundary grid points; centroids are shared by 3 cells, midpoints by 2.
   !>
   !> The centroid hexagon of an interior point is 2/3 of the midpoint polygon
   !> of its neighbours, which stays convex unless the neighbourhood is badly
   !> tangled, so these cells are convex in practice.  With `median` = .true.
   !> the midpoints of the interior triangle sides are inserted between the
   !> centroids as well (the median dual of finite volumes: 12-gons inside,
   !> numbered after the other nodes, shared by 2 cells); a midpoint is collinear
   !> with its two centroids on the unperturbed grid and becomes reflex for about
   !> half of them under perturbation, giving genuinely non-convex cells.
   subroutine dual_polymesh(n, perturb, seed, x, ptr, conn, median)
      integer, intent(in) :: n, seed
      real(wp), intent(in) :: perturb
      real(wp), allocatable, intent(out) :: x(:, :)
      integer(ip), allocatable, intent(out) :: ptr(:), conn(:)
      logical, intent(in), optional :: median
      real(wp), allocatable :: g(:, :, :)
      integer, allocatable :: hm(:, :), vm(:, :), dm(:, :), bv(:, :)
      integer(ip), allocatable :: tmp(:)
      integer(i8) :: state
      real(wp) :: r
      integer :: i, j, k, nn, nc, c, a, b, kk
      integer :: si(6), sj(6), st(6), ei(7), ej(7)
      logical :: have(6), med

      med = .false.
      if (present(median)) med = median
      state = rng_init(seed)
      allocate (g(2, 0:n, 0:n))
      do j = 0, n
         do i = 0, n
            g(:, i, j) = [real(i, wp), real(j, wp)]/n
            if (i > 0 .and. i < n .and. j > 0 .and. j < n) then
               call rng_uniform(state, r)
               g(1, i, j) = g(1, i, j) + (2.0_wp*r - 1.0_wp)*perturb/n
               call rng_uniform(state, r)
               g(2, i, j) = g(2, i, j) + (2.0_wp*r - 1.0_wp)*perturb/n
            end if
         end do
      end do

      ! side midpoints: hm(i, j) on (i,j)-(i+1,j), vm(i, j) on (i,j)-(i,j+1),
      ! dm(i, j) on (i,j)-(i+1,j+1); 0 when the node does not exist
      allocate (x(2, 2*n*n + 8*n + merge(3*n*n - 2*n, 0, med)))
      allocate (hm(0:n - 1, 0:n), vm(0:n, 0:n - 1), dm(0:n - 1, 0:n - 1), bv(0:n, 0:n))
      hm = 0
      vm = 0
      dm = 0
      bv = 0
      ! centroids: lower triangle (i,j),(i+1,j),(i+1,j+1) is 2*(j*n+i)+1, upper
      ! (i,j),(i+1,j+1),(i,j+1) the next
      do j = 0, n - 1
         do i = 0, n - 1
            k = 2*(j*n + i)
            x(:, k + 1) = (g(:, i, j) + g(:, i + 1, j) + g(:, i + 1, j + 1))/3.0_wp
            x(:, k + 2) = (g(:, i, j) + g(:, i + 1, j + 1) + g(:, i, j + 1))/3.0_wp
         end do
      end do
      nn = 2*n*n
      do i = 0, n - 1
         call new_mid(hm(i, 0), g(:, i, 0), g(:, i + 1, 0))
         call new_mid(hm(i, n), g(:, i, n), g(:, i + 1, n))
         call new_mid(vm(0, i), g(:, 0, i), g(:, 0, i + 1))
         call new_mid(vm(n, i), g(:, n, i), g(:, n, i + 1))
      end do
      do j = 0, n
         do i = 0, n
            if (i == 0 .or. i == n .or. j == 0 .or. j == n) then
               nn = nn + 1
               bv(i, j) = nn
               x(:, nn) = g(:, i, j)
            end if
         end do
      end do
      if (med) then
         do j = 0, n
            do i = 0, n
               if (i < n .and. j > 0 .and. j < n) call new_mid(hm(i, j), g(:, i, j), g(:, i + 1, j))
               if (j < n .and. i > 0 .and. i < n) call new_mid(vm(i, j), g(:, i, j), g(:, i, j + 1))
               if (i < n .and. j < n) call new_mid(dm(i, j), g(:, i, j), g(:, i + 1, j + 1))
            end do
         end do
      end if

      nc = (n + 1)**2
      allocate (ptr(nc + 1), tmp(12*nc))
      ptr(1) = 1
      do j = 0, n
         do i = 0, n
            c = j*(n + 1) + i + 1
            ! the six triangle slots around (i, j) counter-clockwise from east:
            ! slot k lies between neighbour directions e_k and e_(k+1)
            si = [i, i, i - 1, i - 1, i - 1, i]
            sj = [j, j, j, j - 1, j - 1, j - 1]
            st = [1, 2, 1, 2, 1, 2]
            ei = [i + 1, i + 1, i, i - 1, i - 1, i, i + 1]
            ej = [j, j + 1, j + 1, j, j - 1, j - 1, j]
            do k = 1, 6
               have(k) = si(k) >= 0 .and. si(k) < n .and. sj(k) >= 0 .and. sj(k) < n
            end do
            kk = ptr(c) - 1
            if (all(have)) then
               do k = 1, 6
                  if (med) call push(side_mid(i, j, ei(k), ej(k)))
                  call push(2*(sj(k)*n + si(k)) + st(k))
               end do
            else
               ! the present slots form one cyclic run a..b
               do a = 1, 6
                  if (have(a) .and. .not. have(modulo(a - 2, 6) + 1)) exit
               end do
               call push(bv(i, j))
               call push(side_mid(i, j, ei(a), ej(a)))
               b = a
               do
                  call push(2*(sj(b)*n + si(b)) + st(b))
                  if (.not. have(modulo(b, 6) + 1)) exit
                  b = modulo(b, 6) + 1
                  if (med) call push(side_mid(i, j, ei(b), ej(b)))
               end do
               call push(side_mid(i, j, ei(b + 1), ej(b + 1)))
            end if
            ptr(c + 1) = kk + 1
         end do
      end do
      conn = tmp(1:ptr(nc + 1) - 1)

   contains

      subroutine new_mid(idx, p1, p2)
         integer, intent(inout) :: idx
         real(wp), intent(in) :: p1(2), p2(2)
         nn = nn + 1
         idx = nn
         x(:, nn) = 0.5_wp*(p1 + p2)
      end subroutine new_mid

      subroutine push(node)
         integer, intent(in) :: node
         kk = kk + 1
         tmp(kk) = node
      end subroutine push

      !> Midpoint node of the triangle side from (i1, j1) to (i2, j2).
      integer function side_mid(i1, j1, i2, j2) result(m)
         integer, intent(in) :: i1, j1, i2, j2
         if (j1 == j2) then
            m = hm(min(i1, i2), j1)
         else if (i1 == i2) then
            m = vm(i1, min(j1, j2))
         else
            m = dm(min(i1, i2), min(j1, j2))
         end if
      end function side_mid
   end subroutine dual_polymesh

   !> nx x ny cells on [0,1]^2 in a checkerboard: cells with i+j even are
   !> refined into 4 quads through their side midpoints and centre; the other
   !> cells keep their 4 corners plus the midpoints of the sides they share
   !> with refined neighbours, i.e. they are polygons with collinear (hanging)
   !> vertices: 8 in the interior, 6-7 along the boundary (5 when nx or ny is
   !> 1).  Grid node (i, j) is j*(nx+1) + i + 1; midpoints and centres follow.
   subroutine hanging_quad_grid(nx, ny, x, ptr, conn)
      integer, intent(in) :: nx, ny
      real(wp), allocatable, intent(out) :: x(:, :)
      integer(ip), allocatable, intent(out) :: ptr(:), conn(:)
      integer, allocatable :: hm(:, :), vm(:, :), cen(:, :)
      integer(ip), allocatable :: tmp(:)
      real(wp), allocatable :: xt(:, :)
      integer :: i, j, nn, ne, kk, c00, c10, c11, c01, mb, mr, mt, ml, cc

      allocate (hm(0:nx - 1, 0:ny), vm(0:nx, 0:ny - 1), cen(0:nx - 1, 0:ny - 1))
      allocate (xt(2, (nx + 1)*(ny + 1) + 2*nx*ny + nx + ny + nx*ny))
      nn = 0
      do j = 0, ny
         do i = 0, nx
            nn = nn + 1
            xt(:, nn) = [real(i, wp)/nx, real(j, wp)/ny]
         end do
      end do
      hm = 0
      vm = 0
      cen = 0
      do j = 0, ny - 1
         do i = 0, nx - 1
            if (modulo(i + j, 2) /= 0) cycle
            call add_mid(hm(i, j), [real(2*i + 1, wp)/(2*nx), real(j, wp)/ny])
            call add_mid(hm(i, j + 1), [real(2*i + 1, wp)/(2*nx), real(j + 1, wp)/ny])
            call add_mid(vm(i, j), [real(i, wp)/nx, real(2*j + 1, wp)/(2*ny)])
            call add_mid(vm(i + 1, j), [real(i + 1, wp)/nx, real(2*j + 1, wp)/(2*ny)])
            call add_mid(cen(i, j), [real(2*i + 1, wp)/(2*nx), real(2*j + 1, wp)/(2*ny)])
         end do
      end do
      x = xt(:, 1:nn)

      allocate (tmp(16*nx*ny), ptr(4*nx*ny + 1))
      ptr(1) = 1
      ne = 0
      kk = 0
      do j = 0, ny - 1
         do i = 0, nx - 1
            c00 = j*(nx + 1) + i + 1
            c10 = c00 + 1
            c11 = c00 + nx + 2
            c01 = c00 + nx + 1
            mb = hm(i, j)
            mt = hm(i, j + 1)
            ml = vm(i, j)
            mr = vm(i + 1, j)
            if (modulo(i + j, 2) == 0) then
               cc = cen(i, j)
               call add_elem([c00, mb, cc, ml])
               call add_elem([mb, c10, mr, cc])
               call add_elem([cc, mr, c11, mt])
               call add_elem([ml, cc, mt, c01])
            else
               ne = ne + 1
               kk = kk + 1
               tmp(kk) = c00
               if (mb > 0) call push(mb)
               call push(c10)
               if (mr > 0) call push(mr)
               call push(c11)
               if (mt > 0) call push(mt)
               call push(c01)
               if (ml > 0) call push(ml)
               ptr(ne + 1) = kk + 1
            end if
         end do
      end do
      ptr = ptr(1:ne + 1)
      conn = tmp(1:kk)

   contains

      subroutine add_mid(idx, p)
         integer, intent(inout) :: idx
         real(wp), intent(in) :: p(2)
         if (idx > 0) return
         nn = nn + 1
         idx = nn
         xt(:, nn) = p
      end subroutine add_mid

      subroutine add_elem(nodes)
         integer, intent(in) :: nodes(4)
         ne = ne + 1
         tmp(kk + 1:kk + 4) = nodes
         kk = kk + 4
         ptr(ne + 1) = kk + 1
      end subroutine add_elem

      subroutine push(node)
         integer, intent(in) :: node
         kk = kk + 1
         tmp(kk) = node
      end subroutine push
   end subroutine hanging_quad_grid

   !> The beam [0,L] x [0,b] as two quadrilaterals whose shared side runs from
   !> (L/2 - d, 0) to (L/2 + d, b); d = 0 gives two rectangles, 2d/b is the
   !> skew.  Nodes: 1 (0,0), 2 (L/2-d,0), 3 (L,0), 4 (L,b), 5 (L/2+d,b), 6 (0,b);
   !> elements (1,2,5,6) and (2,3,4,5).
   subroutine cantilever_two_quads(length, depth, d, x, ptr, conn)
      real(wp), intent(in) :: length, depth, d
      real(wp), allocatable, intent(out) :: x(:, :)
      integer(ip), allocatable, intent(out) :: ptr(:), conn(:)
      x = reshape([0.0_wp, 0.0_wp, 0.5_wp*length - d, 0.0_wp, length, 0.0_wp, &
                   length, depth, 0.5_wp*length + d, depth, 0.0_wp, depth], [2, 6])
      ptr = [1_ip, 5_ip, 9_ip]
      conn = [1_ip, 2_ip, 5_ip, 6_ip, 2_ip, 3_ip, 4_ip, 5_ip]
   end subroutine cantilever_two_quads

   !> Nodes with |x(dir, i) - value| <= tol (dir = 1: a vertical line x = value,
   !> dir = 2: a horizontal line y = value), in increasing order.
   subroutine nodes_on_line(x, dir, value, tol, idx)
      real(wp), intent(in) :: x(:, :)
      integer, intent(in) :: dir
      real(wp), intent(in) :: value, tol
      integer(ip), allocatable, intent(out) :: idx(:)
      integer :: i
      allocate (idx(0))
      do i = 1, size(x, 2)
         if (abs(x(dir, i) - value) <= tol) idx = [idx, int(i, ip)]
      end do
   end subroutine nodes_on_line

   !> A random convex n-gon: points at increasing, jittered angles on an
   !> ellipse of random aspect (0.3..1), rotated and shifted at random.
   subroutine random_convex_polygon(n, state, xy)
      integer, intent(in) :: n
      integer(i8), intent(inout) :: state
      real(wp), allocatable, intent(out) :: xy(:, :)
      real(wp) :: r, aspect, phi, t, p(2), shift(2)
      integer :: k
      allocate (xy(2, n))
      call rng_uniform(state, r)
      aspect = 0.3_wp + 0.7_wp*r
      call rng_uniform(state, r)
      phi = 2.0_wp*pi*r
      call rng_uniform(state, shift(1))
      call rng_uniform(state, shift(2))
      do k = 1, n
         call rng_uniform(state, r)
         t = 2.0_wp*pi*(real(k - 1, wp) + 0.1_wp + 0.8_wp*r)/n
         p = [cos(t), aspect*sin(t)]
         xy(:, k) = [cos(phi)*p(1) - sin(phi)*p(2), sin(phi)*p(1) + cos(phi)*p(2)] + shift
      end do
   end subroutine random_convex_polygon

   !> A random star-shaped n-gon about its centre: jittered angles, radii
   !> alternating between 0.9..1.1 and 0.2..0.3.  For n >= 6 the neighbours of
   !> an inner vertex subtend at most 138 degrees, so their chord passes at
   !> least 0.9 cos(69 deg) = 0.32 from the centre: every inner vertex is reflex.
   subroutine random_star_polygon(n, state, xy)
      integer, intent(in) :: n
      integer(i8), intent(inout) :: state
      real(wp), allocatable, intent(out) :: xy(:, :)
      real(wp) :: r, rad, t
      integer :: k
      allocate (xy(2, n))
      do k = 1, n
         call rng_uniform(state, r)
         t = 2.0_wp*pi*(real(k - 1, wp) + 0.35_wp + 0.3_wp*r)/n
         call rng_uniform(state, r)
         if (modulo(k, 2) == 1) then
            rad = 0.9_wp + 0.2_wp*r
         else
            rad = 0.2_wp + 0.1_wp*r
         end if
         xy(:, k) = rad*[cos(t), sin(t)]
      end do
   end subroutine random_star_polygon
end module vemcontact_test_polymesh
