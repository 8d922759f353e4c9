!> Contact search: which master segment each slave node is paired with.
!>
!> A hashed uniform grid over the master segments: cells of side
!> h = max(median segment length, build radius r_b); each segment is registered in
!> every cell that its r_b-neighbourhood (a capsule) can touch, rasterized row by
!> row so that long or slanted segments do not fill their whole bounding box.
!> Only occupied cells are stored, in an open-addressing hash table, so memory
!> is O(registrations) whatever the extent of the mesh, building is O(nseg)
!> (expected) and a query with radius <= r_b reads one cell.
!>
!> Selection rules (docs/contact-formulation.md): the closest segment by the
!> distance to its clamped closest point; distances equal within
!> tie_rel * (segment length) are ties, broken by (1) the segment chosen last
!> time (`previous`), (2) a projection inside [0, 1], (3) the normal closest to
!> the direction from the closest point to the node, (4) the lower index.
!> A node whose chosen segment is the first (last) of an open surface and
!> whose xi < -end_tol (xi > 1 + end_tol) is past the end: no partner (0).
module vemcontact_contact_search
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_internal
   use vemcontact_contact_geometry, only: project_point_segment, seg_ok, length2
   implicit none
   private

   public :: segment_grid_t, build_segment_grid, query_segments, select_segment
   public :: closest_segments, contact_graph_pairs, merge_node_pairs, median

   !> Distances within tie_rel * segment length are equal: the two distances to
   !> a shared vertex differ by round-off only (~1e-16 relative to coordinates),
   !> and 1e-10 leaves room for coordinates 1e5 times the segment length.
   real(wp), parameter, public :: tie_rel = 1.0e-10_wp
   !> A projection is inside a segment when -tie_rel <= xi <= 1 + tie_rel.
   !> Past the end of an open surface means xi < -end_tol or xi > 1 + end_tol:
   !> the nodes facing each other at the end of a joint sit at xi = 0 or 1 up to
   !> round-off and slip of the order of the displacements; 1e-6 of a segment
   !> keeps them paired through round-off while a real slide-off is released.
   real(wp), parameter, public :: end_tol = 1.0e-6_wp

   !> Hashed bucket grid over master segments (built by build_segment_grid).
   type :: segment_grid_t
      integer(ip) :: nseg = 0
      real(wp) :: h = 1.0_wp               !< cell side
      real(wp) :: radius = 0.0_wp          !< build radius r_b
      real(wp) :: origin(2) = 0.0_wp       !< corner of cell (0, 0)
      integer(i8) :: nx = 0, ny = 0        !< cells per direction; key = iy*nx + ix
      integer(i8) :: mask = -1             !< hash capacity - 1 (a power of two minus one)
      integer(i8), allocatable :: slot_key(:)   !< (0:mask) cell key, -1 = empty
      integer(ip), allocatable :: slot_cell(:)  !< (0:mask) occupied cell number
      integer(i8), allocatable :: cell_ptr(:)   !< segments of cell c: cell_seg(cell_ptr(c):cell_ptr(c+1)-1)
      integer(ip), allocatable :: cell_seg(:)   !< ascending within a cell
      integer(ip), allocatable :: prev(:)  !< segment ending at this one's start, 0 at an open start
      integer(ip), allocatable :: next(:)  !< segment starting at this one's end, 0 at an open end
   end type segment_grid_t

   ! band and range slack of the rasterization, relative to h: rounding in the
   ! clipping must never drop a cell, extra cells are harmless
   real(wp), parameter :: raster_slack = 1.0e-9_wp

contains

   !> Build the grid of segments seg(:, k) = (a, b) (node indices into x(2, :),
   !> the current coordinates) for queries of radius up to `radius`.
   pure subroutine build_segment_grid(x, seg, radius, grid, error)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :)
      real(wp), intent(in) :: radius
      type(segment_grid_t), intent(out) :: grid
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: len(:)
      real(wp) :: lo(2), hi(2), ext(2), h
      integer(ip) :: nseg, k, c
      integer(i8) :: cap, s, nreg, ncell, nkey, m
      integer(i8), allocatable :: count(:), fill(:), keys(:)

      nseg = int(size(seg, 2), ip)
      if (.not. (radius >= 0.0_wp .and. radius <= huge(radius))) then
         call fatal_error(error, 'build_segment_grid: radius must be finite and >= 0', err_internal)
         return
      end if
      if (nseg > 0) then
         if (size(seg, 1) /= 2 .or. minval(seg) < 1 .or. maxval(seg) > size(x, 2)) then
            call fatal_error(error, 'build_segment_grid: segment node index out of range', err_internal)
            return
         end if
      end if
      grid%nseg = nseg
      grid%radius = radius
      allocate (grid%prev(nseg), grid%next(nseg))
      if (nseg == 0) then
         allocate (grid%slot_key(0:-1), grid%slot_cell(0:-1), grid%cell_ptr(1), grid%cell_seg(0))
         grid%cell_ptr = 1
         return
      end if
      allocate (len(nseg))
      lo = huge(1.0_wp)
      hi = -huge(1.0_wp)
      do k = 1, nseg
         associate (xa => x(:, seg(1, k)), xb => x(:, seg(2, k)))
            if (.not. all(abs([xa, xb]) <= huge(1.0_wp))) then
               call fatal_error(error, 'build_segment_grid: coordinates not finite', err_internal)
               return
            end if
            len(k) = length2(xb - xa)
            lo = min(lo, xa, xb)
            hi = max(hi, xa, xb)
         end associate
      end do
      h = max(median(len), radius)
      ext = hi - lo + 2.0_wp*radius
      if (.not. (h > 0.0_wp)) h = maxval(ext)
      if (.not. (h > 0.0_wp)) h = 1.0_wp
      ! keys iy*nx + ix must fit in 62 bits
      do while ((ext(1)/h + 4.0_wp)*(ext(2)/h + 4.0_wp) > 2.0_wp**60)
         h = 2.0_wp*h
      end do
      grid%h = h
      grid%origin = lo - radius - h
      grid%nx = int((ext(1) + 2.0_wp*h)/h, i8) + 1
      grid%ny = int((ext(2) + 2.0_wp*h)/h, i8) + 1

      call link_segments(seg, grid%prev, grid%next)

      ! pass 1 hashes the occupied cells and counts registrations per slot,
      ! pass 2 fills the cells; the table doubles when half full
      cap = 16
      do while (cap < 4_i8*nseg)
         cap = 2*cap
      end do
      grid%mask = cap - 1
      allocate (grid%slot_key(0:grid%mask), source=-1_i8)
      allocate (count(0:grid%mask), source=0_i8)
      allocate (keys(64))
      ncell = 0
      do k = 1, nseg
         call segment_cells(grid, x(:, seg(1, k)), x(:, seg(2, k)), keys, nkey)
         do m = 1, nkey
            call insert_key(grid%slot_key, grid%mask, count, ncell, keys(m))
         end do
      end do
      allocate (grid%slot_cell(0:grid%mask), source=0_ip)
      allocate (grid%cell_ptr(ncell + 1))
      grid%cell_ptr(1) = 1
      ncell = 0
      do s = 0, grid%mask
         if (grid%slot_key(s) < 0) cycle
         ncell = ncell + 1
         grid%slot_cell(s) = int(ncell, ip)
         grid%cell_ptr(ncell + 1) = grid%cell_ptr(ncell) + count(s)
      end do
      nreg = grid%cell_ptr(ncell + 1) - 1
      allocate (grid%cell_seg(nreg))
      fill = grid%cell_ptr(:ncell)
      do k = 1, nseg
         call segment_cells(grid, x(:, seg(1, k)), x(:, seg(2, k)), keys, nkey)
         do m = 1, nkey
            c = grid%slot_cell(find_slot(grid, keys(m)))
            grid%cell_seg(fill(c)) = k
            fill(c) = fill(c) + 1
         end do
      end do
   end subroutine build_segment_grid

   !> Segments whose closest point is within `radius` of `p`, ascending, in
   !> cand(1:ncand) (cand grows when too small).  With radius <= the build
   !> radius this reads a single cell; otherwise the block of cells within
   !> radius - r_b.  `nexamined`: segments read from the cells (cost measure).
   pure subroutine query_segments(grid, x, seg, p, radius, cand, ncand, nexamined)
      type(segment_grid_t), intent(in) :: grid
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :)
      real(wp), intent(in) :: p(2), radius
      integer(ip), allocatable, intent(inout) :: cand(:)
      integer(ip), intent(out) :: ncand
      integer(ip), intent(out), optional :: nexamined
      integer(i8) :: ix0, ix1, iy0, iy1, ix, iy, slot, m
      integer(ip) :: j, c, nexam
      real(wp) :: extra, xi, g, n(2), dist
      integer :: st
      logical :: several

      ncand = 0
      nexam = 0
      if (.not. allocated(cand)) allocate (cand(16))
      if (grid%nseg > 0 .and. radius >= 0.0_wp) then
         extra = max(radius - grid%radius, 0.0_wp)
         ix0 = max(0_i8, cell_index(p(1) - extra, grid%origin(1), grid%h, grid%nx))
         ix1 = min(grid%nx - 1, cell_index(p(1) + extra, grid%origin(1), grid%h, grid%nx))
         iy0 = max(0_i8, cell_index(p(2) - extra, grid%origin(2), grid%h, grid%ny))
         iy1 = min(grid%ny - 1, cell_index(p(2) + extra, grid%origin(2), grid%h, grid%ny))
         several = ix1 > ix0 .or. iy1 > iy0
         do iy = iy0, iy1
            do ix = ix0, ix1
               slot = find_slot(grid, iy*grid%nx + ix)
               if (slot < 0) cycle
               c = grid%slot_cell(slot)
               do m = grid%cell_ptr(c), grid%cell_ptr(c + 1) - 1
                  j = grid%cell_seg(m)
                  nexam = nexam + 1
                  call project_point_segment(p, x(:, seg(1, j)), x(:, seg(2, j)), xi, g, n, dist, st)
                  if (dist > radius) cycle
                  if (ncand == size(cand)) call grow_int(cand)
                  ncand = ncand + 1
                  cand(ncand) = j
               end do
            end do
         end do
         if (several) call sort_unique(cand, ncand)
      end if
      if (present(nexamined)) nexamined = nexam
   end subroutine query_segments

   !> Choose among the candidate segments cand(:) for the point p (rules in
   !> the module header).  iseg = 0 when no candidate qualifies; xi (raw, not
   !> clamped), gap and normal are those of the chosen segment (0 otherwise).
   !> `previous` is the segment chosen last time for this node (0: none).
   pure subroutine select_segment(grid, x, seg, p, cand, previous, iseg, xi, gap, normal)
      type(segment_grid_t), intent(in) :: grid
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :)
      real(wp), intent(in) :: p(2)
      integer(ip), intent(in) :: cand(:)
      integer(ip), intent(in) :: previous
      integer(ip), intent(out) :: iseg
      real(wp), intent(out) :: xi, gap, normal(2)
      integer(ip) :: j, c
      integer :: st
      real(wp) :: xij, gj, nj(2), dj, lj, sj, dbest, lbest, sbest, tol
      logical :: take

      iseg = 0
      xi = 0.0_wp
      gap = 0.0_wp
      normal = 0.0_wp
      dbest = huge(1.0_wp)
      lbest = 0.0_wp
      sbest = -2.0_wp
      do c = 1, size(cand)
         j = cand(c)
         associate (xa => x(:, seg(1, j)), xb => x(:, seg(2, j)))
            call project_point_segment(p, xa, xb, xij, gj, nj, dj, st)
            if (st /= seg_ok) cycle
            lj = length2(xb - xa)
            sj = alignment(p, xa, xb, xij, nj)
         end associate
         if (iseg == 0) then
            take = .true.
         else
            tol = tie_rel*max(lj, lbest)
            if (dj < dbest - tol) then
               take = .true.
            else if (dj > dbest + tol) then
               take = .false.
            else if (previous /= 0 .and. (j == previous .or. iseg == previous)) then
               take = j == previous
            else if (inside(xij) .neqv. inside(xi)) then
               take = inside(xij)
            else if (abs(sj - sbest) > tie_rel) then
               take = sj > sbest
            else
               take = j < iseg
            end if
         end if
         if (take) then
            iseg = j
            xi = xij
            gap = gj
            normal = nj
            dbest = dj
            lbest = lj
            sbest = sj
         end if
      end do
      if (iseg /= 0) then
         if ((xi < -end_tol .and. grid%prev(iseg) == 0) .or. (xi > 1.0_wp + end_tol .and. grid%next(iseg) == 0)) then
            iseg = 0
            xi = 0.0_wp
            gap = 0.0_wp
            normal = 0.0_wp
         end if
      end if
   end subroutine select_segment

   !> For every slave node slave(i) at x(:, slave(i)): the chosen segment iseg(i)
   !> (0 if none within `radius` or past the end of an open surface), the raw
   !> projection xi(i), the gap(i) and the outward normal(:, i).
   !> previous(i): last choice for this node, which wins ties (hysteresis).
   pure subroutine closest_segments(grid, x, seg, slave, radius, iseg, xi, gap, normal, previous)
      type(segment_grid_t), intent(in) :: grid
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :), slave(:)
      real(wp), intent(in) :: radius
      integer(ip), intent(out) :: iseg(:)
      real(wp), intent(out) :: xi(:), gap(:), normal(:, :)
      integer(ip), intent(in), optional :: previous(:)
      integer(ip), allocatable :: cand(:)
      integer(ip) :: i, ncand, prev
      allocate (cand(64))
      do i = 1, size(slave)
         call query_segments(grid, x, seg, x(:, slave(i)), radius, cand, ncand)
         prev = 0
         if (present(previous)) prev = previous(i)
         call select_segment(grid, x, seg, x(:, slave(i)), cand(:ncand), prev, &
                             iseg(i), xi(i), gap(i), normal(:, i))
      end do
   end subroutine closest_segments

   !> Node pairs the contact terms can couple: for each slave node s, every
   !> segment (a, b) within `radius` gives (s, a) and (s, b).  pairs(2, npair),
   !> unique per slave node; a pair with s = a or s = b is skipped.
   pure subroutine contact_graph_pairs(grid, x, seg, slave, radius, pairs)
      type(segment_grid_t), intent(in) :: grid
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :), slave(:)
      real(wp), intent(in) :: radius
      integer(ip), allocatable, intent(out) :: pairs(:, :)
      integer(ip), allocatable :: cand(:), nodes(:), buf(:, :), tmp(:, :)
      integer(ip) :: i, c, ncand, nn, k, npair, s
      allocate (cand(64), nodes(128), buf(2, 256))
      npair = 0
      do i = 1, size(slave)
         s = slave(i)
         call query_segments(grid, x, seg, x(:, s), radius, cand, ncand)
         if (size(nodes) < 2*ncand) then
            deallocate (nodes)
            allocate (nodes(4*ncand))
         end if
         nn = 0
         do c = 1, ncand
            do k = 1, 2
               if (seg(k, cand(c)) == s) cycle
               nn = nn + 1
               nodes(nn) = seg(k, cand(c))
            end do
         end do
         call sort_unique(nodes, nn)
         if (npair + nn > size(buf, 2)) then
            allocate (tmp(2, max(2*size(buf, 2), npair + nn)))
            tmp(:, :npair) = buf(:, :npair)
            call move_alloc(tmp, buf)
         end if
         do k = 1, nn
            buf(:, npair + k) = [s, nodes(k)]
         end do
         npair = npair + nn
      end do
      pairs = buf(:, :npair)
   end subroutine contact_graph_pairs

   !> Merge node pairs (i, j) into the CSR node graph adj_ptr/adj (symmetric,
   !> sorted unique neighbours, no self loops): the result has the same
   !> properties and contains both (i, j) and (j, i).  Pairs with i = j are
   !> ignored; an index outside 1..nnode is an err_internal error.
   pure subroutine merge_node_pairs(nnode, adj_ptr, adj, pairs, new_ptr, new_adj, error)
      integer(ip), intent(in) :: nnode
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      integer(ip), intent(in) :: pairs(:, :)
      integer(i8), allocatable, intent(out) :: new_ptr(:)
      integer(ip), allocatable, intent(out) :: new_adj(:)
      type(error_t), allocatable, intent(out) :: error
      integer(i8), allocatable :: xptr(:), fill(:)
      integer(ip), allocatable :: xadj(:), row(:)
      integer(i8) :: k, p, q, pos, nnz
      integer(ip) :: i, j, nrow, m

      if (size(adj_ptr) /= nnode + 1) then
         call fatal_error(error, 'merge_node_pairs: adj_ptr must have nnode+1 entries', err_internal)
         return
      end if
      if (size(pairs) > 0) then
         if (minval(pairs) < 1 .or. maxval(pairs) > nnode) then
            call fatal_error(error, 'merge_node_pairs: node index out of range', err_internal)
            return
         end if
      end if
      ! extra neighbours per node, CSR
      allocate (xptr(nnode + 1), source=0_i8)
      do k = 1, size(pairs, 2, kind=i8)
         i = pairs(1, k)
         j = pairs(2, k)
         if (i == j) cycle
         xptr(i + 1) = xptr(i + 1) + 1
         xptr(j + 1) = xptr(j + 1) + 1
      end do
      xptr(1) = 1
      do i = 1, nnode
         xptr(i + 1) = xptr(i + 1) + xptr(i)
      end do
      allocate (xadj(xptr(nnode + 1) - 1))
      fill = xptr(:nnode)
      do k = 1, size(pairs, 2, kind=i8)
         i = pairs(1, k)
         j = pairs(2, k)
         if (i == j) cycle
         xadj(fill(i)) = j
         fill(i) = fill(i) + 1
         xadj(fill(j)) = i
         fill(j) = fill(j) + 1
      end do
      ! each row: existing (sorted) plus extras, sorted and unique
      allocate (new_ptr(nnode + 1))
      allocate (new_adj(size(adj) + size(xadj)))
      allocate (row(64))
      new_ptr(1) = 1
      pos = 0
      do i = 1, nnode
         p = adj_ptr(i)
         q = xptr(i)
         nrow = int(adj_ptr(i + 1) - p + xptr(i + 1) - q, ip)
         if (nrow > size(row)) then
            deallocate (row)
            allocate (row(2*nrow))
         end if
         m = int(adj_ptr(i + 1) - p, ip)
         row(:m) = adj(p:adj_ptr(i + 1) - 1)
         row(m + 1:nrow) = xadj(q:xptr(i + 1) - 1)
         call sort_unique(row, nrow)
         new_adj(pos + 1:pos + nrow) = row(:nrow)
         pos = pos + nrow
         new_ptr(i + 1) = pos + 1
      end do
      nnz = pos
      new_adj = new_adj(:nnz)
   end subroutine merge_node_pairs

   ! ---------------------------------------------------------------- helpers

   !> Keys of the cells that the grid%radius-capsule of segment xa -> xb can
   !> touch, row by row: a point of row band [y0, y1] within r of the segment has
   !> its closest point in the part of the segment with y in [y0 - r, y1 + r], and
   !> lies within r of that part's x-range.  keys grows when too small.
   pure subroutine segment_cells(grid, xa, xb, keys, nkey)
      type(segment_grid_t), intent(in) :: grid
      real(wp), intent(in) :: xa(2), xb(2)
      integer(i8), allocatable, intent(inout) :: keys(:)
      integer(i8), intent(out) :: nkey
      real(wp) :: d(2), ylo, yhi, t1, t2, tlo, thi, xl, xh, r, slack
      integer(i8) :: iy, iy0, iy1, ix, ix0, ix1
      integer(i8), allocatable :: tmp(:)
      d = xb - xa
      r = grid%radius
      slack = raster_slack*grid%h
      nkey = 0
      iy0 = max(0_i8, int((min(xa(2), xb(2)) - r - slack - grid%origin(2))/grid%h, i8))
      iy1 = min(grid%ny - 1, int((max(xa(2), xb(2)) + r + slack - grid%origin(2))/grid%h, i8))
      do iy = iy0, iy1
         ylo = grid%origin(2) + real(iy, wp)*grid%h - r - slack
         yhi = grid%origin(2) + real(iy + 1, wp)*grid%h + r + slack
         if (.not. (abs(d(2)) > 0.0_wp)) then
            if (xa(2) < ylo .or. xa(2) > yhi) cycle
            tlo = 0.0_wp
            thi = 1.0_wp
         else
            t1 = (ylo - xa(2))/d(2)
            t2 = (yhi - xa(2))/d(2)
            tlo = max(0.0_wp, min(t1, t2))
            thi = min(1.0_wp, max(t1, t2))
            if (tlo > thi) cycle
         end if
         xl = min(xa(1) + tlo*d(1), xa(1) + thi*d(1)) - r - slack
         xh = max(xa(1) + tlo*d(1), xa(1) + thi*d(1)) + r + slack
         ix0 = max(0_i8, int((xl - grid%origin(1))/grid%h, i8))
         ix1 = min(grid%nx - 1, int((xh - grid%origin(1))/grid%h, i8))
         if (nkey + ix1 - ix0 + 1 > size(keys, kind=i8)) then
            allocate (tmp(2*(nkey + ix1 - ix0 + 1)))
            tmp(:nkey) = keys(:nkey)
            call move_alloc(tmp, keys)
         end if
         do ix = ix0, ix1
            nkey = nkey + 1
            keys(nkey) = iy*grid%nx + ix
         end do
      end do
   end subroutine segment_cells

   !> Insert a cell key (if new) and count one registration for it; the table
   !> doubles when more than half full, which keeps probe sequences short.
   pure subroutine insert_key(slot_key, mask, count, ncell, key)
      integer(i8), allocatable, intent(inout) :: slot_key(:)
      integer(i8), intent(inout) :: mask
      integer(i8), allocatable, intent(inout) :: count(:)
      integer(i8), intent(inout) :: ncell
      integer(i8), intent(in) :: key
      integer(i8), allocatable :: old_key(:), old_count(:)
      integer(i8) :: slot, s0, t
      slot = hash(key, mask)
      do
         if (slot_key(slot) == key) then
            count(slot) = count(slot) + 1
            return
         end if
         if (slot_key(slot) < 0) exit
         slot = iand(slot + 1, mask)
      end do
      slot_key(slot) = key
      count(slot) = 1
      ncell = ncell + 1
      if (2_i8*ncell <= mask + 1) return
      call move_alloc(slot_key, old_key)
      call move_alloc(count, old_count)
      mask = 2*mask + 1
      allocate (slot_key(0:mask), source=-1_i8)
      allocate (count(0:mask), source=0_i8)
      do s0 = lbound(old_key, 1, kind=i8), ubound(old_key, 1, kind=i8)
         if (old_key(s0) < 0) cycle
         t = hash(old_key(s0), mask)
         do while (slot_key(t) >= 0)
            t = iand(t + 1, mask)
         end do
         slot_key(t) = old_key(s0)
         count(t) = old_count(s0)
      end do
   end subroutine insert_key

   !> How well the segment's normal points from its closest point to p: +1
   !> straight outward, -1 straight inward; a point on the segment scores 1.
   pure real(wp) function alignment(p, xa, xb, xi, n) result(s)
      real(wp), intent(in) :: p(2), xa(2), xb(2), xi, n(2)
      real(wp) :: c(2), d(2), dn
      c = xa + min(max(xi, 0.0_wp), 1.0_wp)*(xb - xa)
      d = p - c
      dn = length2(d)
      if (dn > 0.0_wp) then
         s = dot_product(n, d)/dn
      else
         s = 1.0_wp
      end if
   end function alignment

   pure logical function inside(xi)
      real(wp), intent(in) :: xi
      inside = xi >= -tie_rel .and. xi <= 1.0_wp + tie_rel
   end function inside

   !> prev/next neighbours through shared end nodes (first found when a node
   !> joins more than two segments).
   pure subroutine link_segments(seg, prev, next)
      integer(ip), intent(in) :: seg(:, :)
      integer(ip), intent(out) :: prev(:), next(:)
      integer(ip), allocatable :: starts(:), ends(:)
      integer(ip) :: k, nmax
      nmax = maxval(seg)
      allocate (starts(nmax), ends(nmax), source=0_ip)
      do k = size(seg, 2), 1, -1
         if (seg(1, k) == seg(2, k)) cycle
         starts(seg(1, k)) = k
         ends(seg(2, k)) = k
      end do
      do k = 1, size(seg, 2)
         prev(k) = ends(seg(1, k))
         next(k) = starts(seg(2, k))
         if (prev(k) == k) prev(k) = 0
         if (next(k) == k) next(k) = 0
      end do
   end subroutine link_segments

   !> Cell of coordinate v, clamped to [-1, n] before conversion (no overflow).
   pure integer(i8) function cell_index(v, o, h, n) result(i)
      real(wp), intent(in) :: v, o, h
      integer(i8), intent(in) :: n
      real(wp) :: s
      s = (v - o)/h
      if (.not. (s >= 0.0_wp)) then
         i = -1
      else if (s >= real(n, wp)) then
         i = n
      else
         i = int(s, i8)
      end if
   end function cell_index

   !> Slot of cell `key` in the hash table, -1 if the cell is empty.
   pure integer(i8) function find_slot(grid, key) result(slot)
      type(segment_grid_t), intent(in) :: grid
      integer(i8), intent(in) :: key
      slot = hash(key, grid%mask)
      do
         if (grid%slot_key(slot) == key) return
         if (grid%slot_key(slot) < 0) exit
         slot = iand(slot + 1, grid%mask)
      end do
      slot = -1
   end function find_slot

   !> Multiplicative hash of a non-negative key, in 31-bit pieces so that no
   !> product overflows 63 bits; the odd multipliers make consecutive keys
   !> (cells along a row) a permutation of the low bits.
   pure integer(i8) function hash(key, mask) result(slot)
      integer(i8), intent(in) :: key, mask
      integer(i8), parameter :: m31 = 2147483647_i8, c1 = 1103515245_i8, c2 = 2013265921_i8
      integer(i8) :: lo, hi, v
      lo = iand(key, m31)
      hi = ishft(key, -31)
      v = iand(lo*c1, m31) + iand(hi*c2, m31)
      v = ieor(v, ishft(v, -16))
      slot = iand(v, mask)
   end function hash

   pure subroutine grow_int(a)
      integer(ip), allocatable, intent(inout) :: a(:)
      integer(ip), allocatable :: b(:)
      allocate (b(2*size(a)))
      b(:size(a)) = a
      call move_alloc(b, a)
   end subroutine grow_int

   !> Sort a(1:n) ascending (heap sort: no recursion, O(n log n) for any row)
   !> and drop duplicates; n becomes the number of distinct values.
   pure subroutine sort_unique(a, n)
      integer(ip), intent(inout) :: a(:)
      integer(ip), intent(inout) :: n
      integer(ip) :: i, k, t
      do i = n/2, 1, -1
         call sift(a, i, n)
      end do
      do i = n, 2, -1
         t = a(1)
         a(1) = a(i)
         a(i) = t
         call sift(a, 1_ip, i - 1_ip)
      end do
      k = min(n, 1_ip)
      do i = 2, n
         if (a(i) /= a(k)) then
            k = k + 1
            a(k) = a(i)
         end if
      end do
      n = k
   end subroutine sort_unique

   pure subroutine sift(a, start, last)
      integer(ip), intent(inout) :: a(:)
      integer(ip), intent(in) :: start, last
      integer(ip) :: r, c, v
      r = start
      v = a(r)
      do
         c = 2*r
         if (c > last) exit
         if (c < last) then
            if (a(c + 1) > a(c)) c = c + 1
         end if
         if (a(c) <= v) exit
         a(r) = a(c)
         r = c
      end do
      a(r) = v
   end subroutine sift

   !> Median of a (a copy is partially reordered: Wirth's selection, O(n) expected,
   !> robust to many equal values as in uniform meshes).
   pure real(wp) function median(a) result(med)
      real(wp), intent(in) :: a(:)
      real(wp), allocatable :: w(:)
      real(wp) :: pivot, t
      integer :: l, r, i, j, k
      w = a
      k = (size(w) + 1)/2
      l = 1
      r = size(w)
      do while (l < r)
         pivot = w(k)
         i = l
         j = r
         do
            do while (w(i) < pivot)
               i = i + 1
            end do
            do while (pivot < w(j))
               j = j - 1
            end do
            if (i <= j) then
               t = w(i)
               w(i) = w(j)
               w(j) = t
               i = i + 1
               j = j - 1
            end if
            if (i > j) exit
         end do
         if (j < k) l = i
         if (k < i) r = j
      end do
      med = w(k)
   end function median
end module vemcontact_contact_search
