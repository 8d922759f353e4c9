!> Second-order meshes from first-order ones for tests: each side gets a node
!> at its middle, shared by the two elements on the side; element e's nodes
!> become its n corners then its n side nodes (side i from corner i to i+1),
!> Abaqus' order for quadratic elements.  The new nodes follow the old ones.
module vemcontact_test_second_order
   use vemcontact_kinds, only: wp, ip
   implicit none
   private

   public :: add_side_nodes, boundary_mask2, split_quads

contains

   subroutine add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: ptr(:), conn(:)
      real(wp), allocatable, intent(out) :: x2(:, :)
      integer(ip), allocatable, intent(out) :: ptr2(:), conn2(:)
      integer(ip), allocatable :: head(:), next(:), nbr(:), mid(:)
      real(wp), allocatable :: xm(:, :)
      integer :: e, n, i, a, b, lo, hi, k, nnode, nside, ne
      nnode = size(x, 2)
      ne = size(ptr) - 1
      allocate (head(nnode), source=0_ip)
      allocate (next(size(conn)), nbr(size(conn)), mid(size(conn)), xm(2, size(conn)))
      allocate (ptr2(ne + 1), conn2(2*size(conn)))
      nside = 0
      ptr2(1) = 1
      do e = 1, ne
         n = ptr(e + 1) - ptr(e)
         ptr2(e + 1) = ptr2(e) + 2*n
         do i = 1, n
            a = conn(ptr(e) + i - 1)
            b = conn(ptr(e) + mod(i, n))
            conn2(ptr2(e) + i - 1) = a
            lo = min(a, b)
            hi = max(a, b)
            k = head(lo)
            do while (k > 0)
               if (nbr(k) == hi) exit
               k = next(k)
            end do
            if (k == 0) then
               nside = nside + 1
               k = nside
               nbr(k) = hi
               next(k) = head(lo)
               head(lo) = k
               mid(k) = nnode + nside
               xm(:, nside) = 0.5_wp*(x(:, a) + x(:, b))
            end if
            conn2(ptr2(e) + n + i - 1) = mid(k)
         end do
      end do
      allocate (x2(2, nnode + nside))
      x2(:, 1:nnode) = x
      x2(:, nnode + 1:) = xm(:, 1:nside)
   end subroutine add_side_nodes

   !> Nodes on the mesh boundary of a second-order mesh: the side nodes used by
   !> one element only, and the corners of their sides.
   function boundary_mask2(nnode, ptr, conn) result(on)
      integer, intent(in) :: nnode
      integer(ip), intent(in) :: ptr(:), conn(:)
      logical, allocatable :: on(:)
      integer, allocatable :: cnt(:)
      integer :: e, n, i, j
      allocate (on(nnode), source=.false.)
      allocate (cnt(nnode), source=0)
      do e = 1, size(ptr) - 1
         n = (ptr(e + 1) - ptr(e))/2
         do i = 1, n
            j = conn(ptr(e) + n + i - 1)
            cnt(j) = cnt(j) + 1
         end do
      end do
      do e = 1, size(ptr) - 1
         n = (ptr(e + 1) - ptr(e))/2
         do i = 1, n
            j = conn(ptr(e) + n + i - 1)
            if (cnt(j) == 1) then
               on(j) = .true.
               on(conn(ptr(e) + i - 1)) = .true.
               on(conn(ptr(e) + mod(i, n))) = .true.
            end if
         end do
      end do
   end function boundary_mask2

   !> Every quad (a, b, c, d) of a first-order mesh as the triangles (a, b, c) and (a, c, d).
   subroutine split_quads(ptr, conn, ptr2, conn2)
      integer(ip), intent(in) :: ptr(:), conn(:)
      integer(ip), allocatable, intent(out) :: ptr2(:), conn2(:)
      integer :: e, ne
      ne = size(ptr) - 1
      allocate (ptr2(2*ne + 1), conn2(6*ne))
      ptr2 = [(int(3*e + 1, ip), e=0, 2*ne)]
      do e = 1, ne
         associate (q => conn(ptr(e):ptr(e) + 3))
            conn2(6*e - 5:6*e) = [q(1), q(2), q(3), q(1), q(3), q(4)]
         end associate
      end do
   end subroutine split_quads
end module vemcontact_test_second_order
