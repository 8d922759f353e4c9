!> Arc length along a master surface in the reference configuration: where each
!> master segment starts along the polyline its segments form.  Finite sliding
!> measures a slave node's slip as the change of this arc length at its projection
!> (docs/contact-formulation.md, "Friction"), so that the stick anchor is a position
!> on the master, carried across segment changes.
module vemcontact_contact_master_arc
   use vemcontact_kinds, only: wp, ip
   implicit none
   private

   public :: master_arcs

contains

   !> The reference arc length arc(k) at the start node seg(1, k) of each segment
   !> seg(:, k) = (a, b) (node numbers into x(:, :)), counted along the chain of
   !> segments that follow one another (b of one is a of the next), from 0 at a
   !> chain's first node; period(k) is the length of the closed loop segment k
   !> belongs to (0 on an open chain), over which the arc length wraps.
   pure subroutine master_arcs(x, seg, arc, period)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :)
      real(wp), allocatable, intent(out) :: arc(:), period(:)
      integer, allocatable :: next(:)
      logical, allocatable :: has_prev(:), done(:)
      integer :: k, nseg
      nseg = size(seg, 2)
      allocate (arc(nseg), period(nseg), source=0.0_wp)
      allocate (next(nseg), source=0)
      allocate (has_prev(nseg), done(nseg), source=.false.)
      call link(seg, next, has_prev)
      ! open chains from their first segments, then the closed loops that remain
      do k = 1, nseg
         if (.not. has_prev(k)) call walk(x, seg, next, k, .false., done, arc, period)
      end do
      do k = 1, nseg
         if (.not. done(k)) call walk(x, seg, next, k, .true., done, arc, period)
      end do
   end subroutine master_arcs

   !> Arc lengths along the chain of segments from segment k0 (next: the chain's
   !> links; a loop: back to k0, whose length then is the period of its segments).
   pure subroutine walk(x, seg, next, k0, loop, done, arc, period)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :)
      integer, intent(in) :: next(:), k0
      logical, intent(in) :: loop
      logical, intent(inout) :: done(:)
      real(wp), intent(inout) :: arc(:), period(:)
      integer :: k, m
      real(wp) :: s
      s = 0.0_wp
      k = k0
      m = 0
      do while (k > 0 .and. m < size(next))
         if (done(k)) exit
         done(k) = .true.
         arc(k) = s
         s = s + norm2(x(:, seg(2, k)) - x(:, seg(1, k)))
         k = next(k)
         m = m + 1
      end do
      if (.not. (loop .and. k == k0)) return
      do m = 1, size(next)
         period(k) = s
         k = next(k)
         if (k == k0 .or. k == 0) exit
      end do
   end subroutine walk

   !> next(k): the segment that starts where segment k ends (0: none); has_prev(k):
   !> some segment ends where k starts.  Sorted by start node, each end node finds its
   !> successor by bisection: O(n log n) for the long joints of a dam.
   pure subroutine link(seg, next, has_prev)
      integer(ip), intent(in) :: seg(:, :)
      integer, intent(out) :: next(:)
      logical, intent(out) :: has_prev(:)
      integer, allocatable :: order(:)
      integer :: k, lo, hi, mid, nseg
      nseg = size(seg, 2)
      order = sort_by_start(seg)
      next = 0
      has_prev = .false.
      do k = 1, nseg
         lo = 1
         hi = nseg
         do while (lo < hi)
            mid = (lo + hi)/2
            if (seg(1, order(mid)) < seg(2, k)) then
               lo = mid + 1
            else
               hi = mid
            end if
         end do
         if (seg(1, order(lo)) /= seg(2, k)) cycle
         if (order(lo) == k) cycle
         if (has_prev(order(lo))) cycle
         next(k) = order(lo)
         has_prev(order(lo)) = .true.
      end do
   end subroutine link

   !> The segments' indices ordered by their start nodes (a merge sort: stable).
   pure function sort_by_start(seg) result(order)
      integer(ip), intent(in) :: seg(:, :)
      integer, allocatable :: order(:), tmp(:)
      integer :: width, lo, mid, hi, i, j, k, n
      n = size(seg, 2)
      order = [(k, k=1, n)]
      allocate (tmp(n))
      width = 1
      do while (width < n)
         do lo = 1, n, 2*width
            mid = min(lo + width - 1, n)
            hi = min(lo + 2*width - 1, n)
            i = lo
            j = mid + 1
            do k = lo, hi
               if (j > hi) then
                  tmp(k) = order(i); i = i + 1
               else if (i > mid) then
                  tmp(k) = order(j); j = j + 1
               else if (seg(1, order(j)) < seg(1, order(i))) then
                  tmp(k) = order(j); j = j + 1
               else
                  tmp(k) = order(i); i = i + 1
               end if
            end do
         end do
         order = tmp
         width = 2*width
      end do
   end function sort_by_start
end module vemcontact_contact_master_arc
