!> Map from sparse user ids (positive integers) to dense internal indices, and the
!> integer sorting it and the set handling need.
!> When ids are dense enough (range at most 4 times their number) the map is a
!> direct table; otherwise it is the ids sorted by a two-pass radix sort with a
!> binary search.  Either way building is O(n) and a lookup O(1) or O(log n), so
!> resolving the connectivity of millions of elements stays fast.
module vemcontact_deck_idmap
   use vemcontact_kinds, only: ip, i8
   implicit none
   private

   public :: id_map_t, sort_unique, radix_sort_pairs

   type :: id_map_t
      integer(ip) :: n = -1            !< number of ids mapped, -1 = never built
      logical :: direct = .false.
      integer(ip) :: lo = 1, hi = 0
      integer(ip), allocatable :: slot(:)   !< direct: slot(id - lo + 1) = index, 0 = none
      integer(ip), allocatable :: keys(:)   !< sorted ids
      integer(ip), allocatable :: vals(:)   !< index of keys(k)
      integer(ip) :: ndup = 0               !< number of repeated ids found when building
      integer(ip), allocatable :: dup(:, :) !< (2, ndup): index of first and repeated occurrence
   contains
      procedure :: build
      procedure :: lookup
   end type id_map_t

contains

   !> Build the map of ids(1:n); repeated ids map to their first occurrence and are listed in `dup`.
   subroutine build(self, ids)
      class(id_map_t), intent(inout) :: self
      integer(ip), intent(in) :: ids(:)
      integer(ip) :: i, n, k
      integer(i8) :: range
      n = size(ids, kind=ip)
      self%n = n
      self%ndup = 0
      if (allocated(self%slot)) deallocate (self%slot)
      if (allocated(self%keys)) deallocate (self%keys)
      if (allocated(self%vals)) deallocate (self%vals)
      if (allocated(self%dup)) deallocate (self%dup)
      allocate (self%dup(2, 16))
      if (n == 0) then
         self%direct = .true.
         self%lo = 1
         self%hi = 0
         allocate (self%slot(0))
         return
      end if
      self%lo = minval(ids)
      self%hi = maxval(ids)
      range = int(self%hi, i8) - int(self%lo, i8) + 1
      self%direct = range <= 4_i8*int(n, i8) + 1024_i8
      if (self%direct) then
         allocate (self%slot(range))
         self%slot = 0
         do i = 1, n
            k = ids(i) - self%lo + 1
            if (self%slot(k) == 0) then
               self%slot(k) = i
            else
               call add_dup(self, self%slot(k), i)
            end if
         end do
      else
         allocate (self%keys(n), self%vals(n))
         self%keys = ids
         do i = 1, n
            self%vals(i) = i
         end do
         call radix_sort_pairs(self%keys, self%vals)
         do i = 2, n
            if (self%keys(i) == self%keys(i - 1)) then
               ! stable sort: the earlier definition comes first; keep mapping to it
               call add_dup(self, self%vals(i - 1), self%vals(i))
               self%vals(i) = self%vals(i - 1)
            end if
         end do
      end if
   end subroutine build

   subroutine add_dup(self, first, again)
      type(id_map_t), intent(inout) :: self
      integer(ip), intent(in) :: first, again
      integer(ip), allocatable :: t(:, :)
      if (self%ndup == size(self%dup, 2)) then
         allocate (t(2, 2*size(self%dup, 2)))
         t(:, 1:self%ndup) = self%dup(:, 1:self%ndup)
         call move_alloc(t, self%dup)
      end if
      self%ndup = self%ndup + 1
      self%dup(:, self%ndup) = [first, again]
   end subroutine add_dup

   !> Internal index of user id `id`, 0 if it is not mapped.
   pure function lookup(self, id) result(idx)
      class(id_map_t), intent(in) :: self
      integer(ip), intent(in) :: id
      integer(ip) :: idx
      integer(ip) :: a, b, m
      idx = 0
      if (self%direct) then
         if (id >= self%lo .and. id <= self%hi) idx = self%slot(id - self%lo + 1)
         return
      end if
      if (.not. allocated(self%keys)) return
      a = 1
      b = size(self%keys, kind=ip)
      do while (a <= b)
         m = a + (b - a)/2
         if (self%keys(m) < id) then
            a = m + 1
         else if (self%keys(m) > id) then
            b = m - 1
         else
            idx = self%vals(m)
            return
         end if
      end do
   end function lookup

   !> Stable sort of non-negative `keys` carrying `vals` along (LSD radix, two 16-bit passes).
   subroutine radix_sort_pairs(keys, vals)
      integer(ip), intent(inout) :: keys(:), vals(:)
      integer(ip), allocatable :: k2(:), v2(:)
      integer(ip), allocatable :: count(:)
      integer :: pass, shift
      integer(ip) :: i, n, d, j
      n = size(keys, kind=ip)
      if (n < 2) return
      allocate (k2(n), v2(n), count(0:65536))
      do pass = 0, 1
         shift = 16*pass
         count = 0
         do i = 1, n
            d = iand(ishft(keys(i), -shift), 65535_ip)
            count(d + 1) = count(d + 1) + 1
         end do
         do d = 1, 65536
            count(d) = count(d) + count(d - 1)
         end do
         do i = 1, n
            d = iand(ishft(keys(i), -shift), 65535_ip)
            j = count(d) + 1
            count(d) = j
            k2(j) = keys(i)
            v2(j) = vals(i)
         end do
         keys = k2
         vals = v2
      end do
   end subroutine radix_sort_pairs

   !> Sort the non-negative a(1:n) ascending and drop repeats; n becomes the new length.
   subroutine sort_unique(a, n)
      integer(ip), intent(inout) :: a(:)
      integer(ip), intent(inout) :: n
      integer(ip), allocatable :: dummy(:)
      integer(ip) :: i, j, t
      if (n < 2) return
      if (n <= 32) then
         do i = 2, n
            t = a(i)
            j = i - 1
            do while (j >= 1)
               if (a(j) <= t) exit
               a(j + 1) = a(j)
               j = j - 1
            end do
            a(j + 1) = t
         end do
      else
         allocate (dummy(n))
         dummy = 0
         call radix_sort_pairs(a(1:n), dummy)
      end if
      j = 1
      do i = 2, n
         if (a(i) /= a(j)) then
            j = j + 1
            a(j) = a(i)
         end if
      end do
      n = j
   end subroutine sort_unique
end module vemcontact_deck_idmap
