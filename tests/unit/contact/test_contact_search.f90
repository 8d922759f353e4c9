!> Contact search: grid candidates and chosen segments against brute force,
!> a polygonal circle (gap sign and chord error), the vertex rule at a convex
!> corner, the end rule of an open surface, bounded work per query as the
!> number of segments grows, and the node-graph merge used for the pattern.
program test_contact_search
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t
   use vemcontact_testing, only: checker_t
   use vemcontact_test_polymesh, only: rng_init, rng_uniform
   use vemcontact_contact_geometry, only: project_point_segment
   use vemcontact_contact_search, only: segment_grid_t, build_segment_grid, query_segments, &
                                        select_segment, closest_segments, contact_graph_pairs, &
                                        merge_node_pairs
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: build_pattern, add_element_matrix
   implicit none
   real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp
   type(checker_t) :: t

   call brute_force_random()
   call circle()
   call vertex_rule()
   call end_rule()
   call scaling()
   call graph_merge()
   call t%finish()
contains

   !> Random disconnected segments and a random connected polyline; random points.
   !> Candidate lists (single- and multi-cell queries) and chosen segments must
   !> equal brute force exactly.
   subroutine brute_force_random()
      integer, parameter :: nseg = 400, npt = 3000
      type(segment_grid_t) :: grid
      type(error_t), allocatable :: error
      real(wp), allocatable :: x(:, :)
      integer(ip), allocatable :: seg(:, :), cand(:), brute(:)
      integer(i8) :: st
      real(wp) :: r, p(2), ang, xi1, g1, n1(2), d1, xi2, g2, n2(2), dmin, radius, rbuild
      integer(ip) :: i, j, ncand, nb, is1, is2
      integer :: s, mism_c, mism_s, mism_m, pass, nchosen, ist
      st = rng_init(42)
      do pass = 1, 2
         allocate (x(2, 2*nseg), seg(2, nseg))
         if (pass == 1) then
            ! disconnected: every segment has two open ends
            do j = 1, nseg
               call rng_uniform(st, r)
               x(1, 2*j - 1) = 10.0_wp*r
               call rng_uniform(st, r)
               x(2, 2*j - 1) = 10.0_wp*r
               call rng_uniform(st, ang)
               call rng_uniform(st, r)
               x(:, 2*j) = x(:, 2*j - 1) + (0.05_wp + r)*[cos(2*pi*ang), sin(2*pi*ang)]
               seg(:, j) = [2*j - 1, 2*j]
            end do
         else
            ! a random walk polyline: convex and concave vertices, one open start and end
            x(:, 1) = [5.0_wp, 5.0_wp]
            ang = 0.0_wp
            do j = 2, nseg + 1
               call rng_uniform(st, r)
               ang = ang + (r - 0.5_wp)*2.0_wp
               call rng_uniform(st, r)
               x(:, j) = x(:, j - 1) + (0.1_wp + 0.3_wp*r)*[cos(ang), sin(ang)]
            end do
            seg(1, :) = [(j, j=1, nseg)]
            seg(2, :) = [(j + 1, j=1, nseg)]
         end if
         radius = 0.7_wp
         do s = 1, 2
            rbuild = radius
            if (s == 2) rbuild = 0.2_wp     ! queries wider than the build radius read several cells
            call build_segment_grid(x, seg, rbuild, grid, error)
            call t%check(.not. allocated(error), 'grid built')
            mism_c = 0
            mism_s = 0
            mism_m = 0
            nchosen = 0
            allocate (cand(4), brute(nseg))
            do i = 1, npt
               ! near a random node: within reach of the segments wherever the walk went
               call rng_uniform(st, r)
               p = x(:, 1 + int(r*size(x, 2)))
               call rng_uniform(st, r)
               p(1) = p(1) + 1.6_wp*(r - 0.5_wp)
               call rng_uniform(st, r)
               p(2) = p(2) + 1.6_wp*(r - 0.5_wp)
               call query_segments(grid, x, seg, p, radius, cand, ncand)
               nb = 0
               dmin = huge(1.0_wp)
               do j = 1, nseg
                  call project_point_segment(p, x(:, seg(1, j)), x(:, seg(2, j)), xi1, g1, n1, d1, ist)
                  if (d1 <= radius) then
                     nb = nb + 1
                     brute(nb) = j
                     dmin = min(dmin, d1)
                  end if
               end do
               if (ncand /= nb) then
                  mism_c = mism_c + 1
               else if (any(cand(:ncand) /= brute(:nb))) then
                  mism_c = mism_c + 1
               end if
               call select_segment(grid, x, seg, p, cand(:ncand), 0_ip, is1, xi1, g1, n1)
               call select_segment(grid, x, seg, p, brute(:nb), 0_ip, is2, xi2, g2, n2)
               if (is1 /= is2) mism_s = mism_s + 1
               ! independent of the tie rules: the choice is a closest segment
               if (is1 /= 0) then
                  nchosen = nchosen + 1
                  call project_point_segment(p, x(:, seg(1, is1)), x(:, seg(2, is1)), xi1, g1, n1, d1, ist)
                  if (d1 > dmin*(1.0_wp + 1.0e-12_wp) + 1.0e-10_wp) mism_m = mism_m + 1
               end if
            end do
            call t%equal(mism_c, 0, 'candidates = brute force (pass, build radius case)')
            call t%equal(mism_s, 0, 'chosen segment = brute force')
            call t%equal(mism_m, 0, 'chosen segment is a closest one')
            write (*, '(a,i0,a,i0,a,i0)') 'random segments, pass ', pass, ': points with a partner ', nchosen, ' of ', npt
            call t%check(nchosen > npt/3, 'a fair share of points found a partner')
            deallocate (cand, brute)
         end do
         deallocate (x, seg)
      end do
   end subroutine brute_force_random

   !> A closed polygon of 100 segments on a circle of radius 10 (ccw: the disk is
   !> the master body).  The gap to a chord differs from the distance to the
   !> circle rho - R by at most (rho/R) * sagitta, sagitta = R (1 - cos(pi/100)).
   subroutine circle()
      integer, parameter :: nseg = 100, npt = 2000
      real(wp), parameter :: rc = 10.0_wp
      type(segment_grid_t) :: grid
      type(error_t), allocatable :: error
      real(wp) :: x(2, nseg + npt), sag, rho, th, r, errmax, bound
      integer(ip) :: seg(2, nseg), slave(npt), iseg(npt)
      real(wp) :: xi(npt), gap(npt), normal(2, npt)
      integer(i8) :: st
      integer :: j, nsign, nfound
      do j = 1, nseg
         th = 2.0_wp*pi*(j - 1)/nseg
         x(:, j) = rc*[cos(th), sin(th)]
         seg(:, j) = [j, mod(j, nseg) + 1]
      end do
      sag = rc*(1.0_wp - cos(pi/nseg))
      st = rng_init(7)
      do j = 1, npt
         call rng_uniform(st, r)
         rho = 9.0_wp + 2.0_wp*r
         call rng_uniform(st, th)
         x(:, nseg + j) = rho*[cos(2*pi*th), sin(2*pi*th)]
         slave(j) = nseg + j
      end do
      call build_segment_grid(x, seg, 1.5_wp, grid, error)
      call t%check(.not. allocated(error), 'circle grid built')
      call closest_segments(grid, x, seg, slave, 1.5_wp, iseg, xi, gap, normal)
      nsign = 0
      nfound = 0
      errmax = 0.0_wp
      do j = 1, npt
         if (iseg(j) == 0) cycle
         nfound = nfound + 1
         rho = norm2(x(:, nseg + j))
         if (abs(rho - rc) > 1.1_wp*sag .and. (gap(j) > 0.0_wp .neqv. rho > rc)) nsign = nsign + 1
         errmax = max(errmax, abs(gap(j) - (rho - rc))/(max(rho, rc)/rc*sag))
      end do
      call t%equal(nfound, npt, 'closed circle: every node has a partner')
      call t%equal(nsign, 0, 'circle: gap sign = inside/outside')
      ! round-off of the gap is ~1e-15 * 10, far below the sagitta 4.9e-3
      bound = 1.0_wp + 1.0e-10_wp
      write (*, '(a,f8.5,a,es10.3)') 'circle: max |g - (rho - R)| / ((rho/R) sagitta) = ', errmax, &
         '  sagitta = ', sag
      call t%check(errmax <= bound, 'circle: |g| within the chord error of the true distance')
   end subroutine circle

   !> Convex corner V = (1, 0) of the unit square: s1 = bottom (0,0)->(1,0),
   !> s2 = right (1,0)->(1,1).  Its vertex region x > 1, y < 0 lies between the
   !> normals (0,-1) and (1,0); both gaps are positive there.
   subroutine vertex_rule()
      type(segment_grid_t) :: grid
      type(error_t), allocatable :: error
      real(wp) :: x(2, 3), p0(2), xi, g, n(2), alpha
      integer(ip) :: seg(2, 2), is, ip0, k, nswitch, prev
      integer :: m
      real(wp), parameter :: dirs(2, 8) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, &
                                                   0.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, &
                                                   -1.0_wp, -1.0_wp, 1.0_wp, -1.0_wp], [2, 8])
      x(:, 1) = [0.0_wp, 0.0_wp]
      x(:, 2) = [1.0_wp, 0.0_wp]
      x(:, 3) = [1.0_wp, 1.0_wp]
      seg(:, 1) = [1, 2]
      seg(:, 2) = [2, 3]
      call build_segment_grid(x, seg, 0.5_wp, grid, error)
      call t%check(.not. allocated(error), 'corner grid built')
      ! away from the bisector the normal rule decides, and 1e-12 moves change nothing
      do m = 1, 2
         alpha = -pi/6.0_wp
         if (m == 2) alpha = -pi/3.0_wp
         p0 = x(:, 2) + 0.1_wp*[cos(alpha), sin(alpha)]
         ip0 = pick(p0, 0_ip)
         call t%equal(int(ip0), 3 - m, 'vertex region: segment whose normal is closest to V->node')
         nswitch = 0
         do k = 1, 8
            if (pick(p0 + 1.0e-12_wp*dirs(:, k), 0_ip) /= ip0) nswitch = nswitch + 1
         end do
         call t%equal(int(nswitch), 0, 'vertex region: 1e-12 moves do not switch segments')
      end do
      ! on the bisector itself the last choice is kept (hysteresis), from either side
      p0 = x(:, 2) + 0.1_wp*[cos(-pi/4.0_wp), sin(-pi/4.0_wp)]
      do prev = 1, 2
         nswitch = 0
         do k = 1, 8
            if (pick(p0 + 1.0e-12_wp*dirs(:, k), prev) /= prev) nswitch = nswitch + 1
         end do
         call t%equal(int(nswitch), 0, 'bisector: the previous segment is kept under 1e-12 moves')
      end do
      ! a sequence of calls moving around the corner by 1e-12 steps, feeding back the choice
      prev = pick(p0, 0_ip)
      nswitch = 0
      do k = 1, 200
         is = pick(p0 + 1.0e-12_wp*[cos(0.1_wp*k), sin(0.1_wp*k)], prev)
         if (is /= prev) nswitch = nswitch + 1
         prev = is
      end do
      call t%equal(int(nswitch), 0, 'bisector: no flip-flop over 200 perturbed calls')
      ! both gaps are open in the vertex region: the choice never changes a force
      call select_segment(grid, x, seg, p0, [1_ip], 0_ip, is, xi, g, n)
      call t%check(g > 0.0_wp, 'vertex region: open gap on s1')
      call select_segment(grid, x, seg, p0, [2_ip], 0_ip, is, xi, g, n)
      call t%check(g > 0.0_wp, 'vertex region: open gap on s2')
      ! a tie at the shared vertex goes to the segment whose xi is in [0, 1]
      call t%equal(int(pick([1.0_wp, -0.3_wp], 0_ip)), 1, 'tie at V: projection inside s1 (xi = 1)')
      call t%equal(int(pick([1.3_wp, 0.0_wp], 0_ip)), 2, 'tie at V: projection inside s2 (xi = 0)')
   end subroutine vertex_rule

   integer(ip) function pick(p, prev) result(is)
      real(wp), intent(in) :: p(2)
      integer(ip), intent(in) :: prev
      type(segment_grid_t) :: grid
      type(error_t), allocatable :: error
      real(wp) :: x(2, 3), xi, g, n(2)
      integer(ip) :: seg(2, 2), ncand
      integer(ip), allocatable :: cand(:)
      x = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp], [2, 3])
      seg = reshape([1_ip, 2_ip, 2_ip, 3_ip], [2, 2])
      call build_segment_grid(x, seg, 0.5_wp, grid, error)
      call query_segments(grid, x, seg, p, 0.5_wp, cand, ncand)
      call select_segment(grid, x, seg, p, cand(:ncand), prev, is, xi, g, n)
   end function pick

   !> An open line of 10 segments (0,0) -> (10,0): nodes beyond the ends by more
   !> than end_tol (1e-6 of a segment) have no partner.
   subroutine end_rule()
      type(segment_grid_t) :: grid
      type(error_t), allocatable :: error
      real(wp) :: x(2, 17)
      integer(ip) :: seg(2, 10), iseg(6)
      real(wp) :: xi(6), gap(6), normal(2, 6)
      integer :: j
      do j = 0, 10
         x(:, j + 1) = [real(j, wp), 0.0_wp]
         if (j > 0) seg(:, j) = [j, j + 1]
      end do
      x(:, 12) = [-0.5_wp, -0.1_wp]
      x(:, 13) = [-1.0e-9_wp, -0.1_wp]
      x(:, 14) = [10.5_wp, 0.2_wp]
      x(:, 15) = [10.0_wp + 1.0e-8_wp, -0.01_wp]
      x(:, 16) = [5.5_wp, -0.1_wp]
      x(:, 17) = [5.5_wp, 0.1_wp]
      call build_segment_grid(x(:, :11), seg, 1.0_wp, grid, error)
      call closest_segments(grid, x, seg, [12_ip, 13_ip, 14_ip, 15_ip, 16_ip, 17_ip], 1.0_wp, &
                            iseg, xi, gap, normal)
      call t%equal(int(iseg(1)), 0, 'end rule: beyond the start')
      call t%equal(int(iseg(2)), 1, 'end rule: 1e-9 before the start is still paired')
      call t%equal(int(iseg(3)), 0, 'end rule: beyond the end')
      call t%equal(int(iseg(4)), 10, 'end rule: 1e-8 past the end is still paired')
      call t%equal(int(iseg(5)), 6, 'open line: interior node below')
      call t%close(gap(5), 0.1_wp, 1.0e-14_wp, 'open line: below a bottom side is open')
      call t%close(gap(6), -0.1_wp, 1.0e-14_wp, 'open line: above a bottom side penetrates')
      call t%close(xi(6), 0.5_wp, 1.0e-14_wp, 'open line: xi')
   end subroutine end_rule

   !> Polygonal circles of 1e2 .. 1e5 segments, search radius two segment lengths,
   !> nodes within one segment length of the curve: the segments read per query
   !> and the registrations per segment must not grow with n.
   subroutine scaling()
      type(segment_grid_t) :: grid
      type(error_t), allocatable :: error
      real(wp), allocatable :: x(:, :)
      integer(ip), allocatable :: seg(:, :), cand(:)
      real(wp) :: l, th, r, rho, radius, mean(4)
      integer(ip) :: ncand, nexam, maxexam(4)
      integer(i8) :: st
      integer :: n, j, m
      st = rng_init(3)
      do m = 1, 4
         n = 10**(m + 1)
         allocate (x(2, n), seg(2, n), cand(16))
         do j = 1, n
            th = 2.0_wp*pi*(j - 1)/n
            x(:, j) = 10.0_wp*[cos(th), sin(th)]
            seg(:, j) = [j, mod(j, n) + 1]
         end do
         l = norm2(x(:, 2) - x(:, 1))
         radius = 2.0_wp*l
         call build_segment_grid(x, seg, radius, grid, error)
         maxexam(m) = 0
         mean(m) = 0.0_wp
         do j = 1, 2000
            call rng_uniform(st, r)
            rho = 10.0_wp + (2.0_wp*r - 1.0_wp)*l
            call rng_uniform(st, th)
            call query_segments(grid, x, seg, rho*[cos(2*pi*th), sin(2*pi*th)], radius, cand, ncand, nexam)
            maxexam(m) = max(maxexam(m), nexam)
            mean(m) = mean(m) + nexam/2000.0_wp
         end do
         write (*, '(a,i7,a,i4,a,f7.2,a,f6.2)') 'n = ', n, ': max examined ', maxexam(m), ', mean ', mean(m), &
            ', registrations per segment ', real(size(grid%cell_seg), wp)/n
         ! a cell of side 2l with a 2l margin meets at most ~6 sqrt(2) l of curve,
         ! i.e. ~9 segments; 16 leaves room for the cell's position on the curve
         call t%check(maxexam(m) <= 16, 'segments examined per query bounded')
         call t%check(size(grid%cell_seg) <= 12*n, 'registrations per segment bounded')
         deallocate (x, seg, cand)
      end do
      call t%check(mean(4) <= 1.2_wp*mean(1), 'mean work per query does not grow from 1e2 to 1e5 segments')
   end subroutine scaling

   !> Merge random pairs into a random symmetric graph and compare with a dense
   !> adjacency matrix; then the pattern accepts a contact element of (s, a, b).
   subroutine graph_merge()
      integer, parameter :: nn = 40
      logical :: dense(nn, nn)
      integer(i8), allocatable :: ptr(:), nptr(:)
      integer(ip), allocatable :: adj(:), nadj(:), pairs(:, :)
      type(error_t), allocatable :: error
      type(segment_grid_t) :: grid
      type(sym_csc_t) :: a
      real(wp) :: r, x(2, 6), ke(6, 6)
      integer(i8) :: st, k
      integer :: i, j, bad
      logical :: ok
      st = rng_init(11)
      dense = .false.
      do i = 1, nn
         do j = i + 1, nn
            call rng_uniform(st, r)
            if (r < 0.15_wp) then
               dense(i, j) = .true.
               dense(j, i) = .true.
            end if
         end do
      end do
      call to_csr(dense, ptr, adj)
      allocate (pairs(2, 60))
      do k = 1, 60
         call rng_uniform(st, r)
         pairs(1, k) = 1 + int(r*nn)
         call rng_uniform(st, r)
         pairs(2, k) = 1 + int(r*nn)
      end do
      pairs(:, 60) = pairs(:, 59)        ! a duplicate
      pairs(:, 58) = [5, 5]              ! a self pair, ignored
      call merge_node_pairs(int(nn, ip), ptr, adj, pairs, nptr, nadj, error)
      call t%check(.not. allocated(error), 'merge: no error')
      do k = 1, 60
         if (pairs(1, k) /= pairs(2, k)) then
            dense(pairs(1, k), pairs(2, k)) = .true.
            dense(pairs(2, k), pairs(1, k)) = .true.
         end if
      end do
      call to_csr(dense, ptr, adj)
      call t%check(all(nptr == ptr), 'merged pointers = dense reference')
      call t%check(size(nadj) == size(adj), 'merged size = dense reference')
      if (size(nadj) == size(adj)) call t%check(all(nadj == adj), 'merged lists sorted, unique, symmetric')
      bad = 0
      do i = 1, nn
         do k = nptr(i), nptr(i + 1) - 1
            if (nadj(k) == i) bad = bad + 1
         end do
      end do
      call t%equal(bad, 0, 'merged graph has no self loops')
      pairs(1, 1) = nn + 1
      call merge_node_pairs(int(nn, ip), ptr, adj, pairs, nptr, nadj, error)
      call t%check(allocated(error), 'merge: index out of range is an error')

      ! two bodies: slave nodes 1, 2 above segments 3->4, 4->5; node 6 far away
      x = reshape([0.2_wp, 0.05_wp, 1.6_wp, 0.1_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, &
                   9.0_wp, 9.0_wp], [2, 6])
      call build_segment_grid(x, reshape([3_ip, 4_ip, 4_ip, 5_ip], [2, 2]), 0.5_wp, grid, error)
      call contact_graph_pairs(grid, x, reshape([3_ip, 4_ip, 4_ip, 5_ip], [2, 2]), [1_ip, 2_ip, 6_ip], &
                               0.5_wp, pairs)
      ! node 1 (x=0.2) is within 0.5 of segment 1 only: (1,3), (1,4); node 2 (x=1.6)
      ! of segment 2 only: (2,4), (2,5); node 6 of none
      call t%equal(size(pairs, 2), 4, 'contact pairs: count')
      if (size(pairs, 2) == 4) then
         call t%check(all(pairs == reshape([1_ip, 3_ip, 1_ip, 4_ip, 2_ip, 4_ip, 2_ip, 5_ip], [2, 4])), &
                      'contact pairs: slave with both segment nodes')
      end if
      dense(:6, :6) = .false.
      call to_csr(dense(:6, :6), ptr, adj)
      call merge_node_pairs(6_ip, ptr, adj, pairs, nptr, nadj, error)
      call build_pattern(6_ip, nptr, nadj, a)
      ke = 1.0_wp
      call add_element_matrix(a, [1_ip, 3_ip, 4_ip], ke, ok)
      call t%check(.not. ok, 'pattern without the segment side (a, b) misses it')
      ! the side (a, b) comes from the element graph; add it as the mesh would
      call merge_node_pairs(6_ip, nptr, nadj, reshape([3_ip, 4_ip, 4_ip, 5_ip], [2, 2]), ptr, adj, error)
      call build_pattern(6_ip, ptr, adj, a)
      call add_element_matrix(a, [1_ip, 3_ip, 4_ip], ke, ok)
      call t%check(ok, 'contact element (s, a, b) fits the merged pattern')
   end subroutine graph_merge

   subroutine to_csr(dense, ptr, adj)
      logical, intent(in) :: dense(:, :)
      integer(i8), allocatable, intent(out) :: ptr(:)
      integer(ip), allocatable, intent(out) :: adj(:)
      integer :: i, j, n
      n = size(dense, 1)
      allocate (ptr(n + 1), adj(count(dense)))
      ptr(1) = 1
      do i = 1, n
         ptr(i + 1) = ptr(i)
         do j = 1, n
            if (dense(j, i)) then
               adj(ptr(i + 1)) = j
               ptr(i + 1) = ptr(i + 1) + 1
            end if
         end do
      end do
   end subroutine to_csr
end program test_contact_search
