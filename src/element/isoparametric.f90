!> The isoparametric map of a 2D element at one point: from the shape functions'
!> natural derivatives and the node coordinates to the Jacobian determinant and
!> the strain-displacement matrix B (3 x 2n, dof order (u1x, u1y, ...), Voigt
!> (xx, yy, xy) with engineering shear).  Shared by the quadratic FEM kernels.
module vemcontact_element_isoparametric
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: iso_point

contains

   !> B and det J at a point with natural derivatives dxi(n), deta(n).  B is
   !> left zero when det J <= 0.  Coordinates are taken relative to node 1 so
   !> that an element far from the origin keeps its digits.
   pure subroutine iso_point(xy, dxi, deta, b, detj)
      real(wp), intent(in) :: xy(:, :), dxi(:), deta(:)
      real(wp), intent(out) :: b(:, :), detj
      real(wp) :: jac(2, 2), dx, dy, rel(2)
      integer :: i, n
      n = size(dxi)
      jac = 0.0_wp
      do i = 1, n
         rel = xy(:, i) - xy(:, 1)
         jac(1, :) = jac(1, :) + dxi(i)*rel
         jac(2, :) = jac(2, :) + deta(i)*rel
      end do
      detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
      b = 0.0_wp
      if (.not. detj > 0.0_wp) return
      do i = 1, n
         dx = (jac(2, 2)*dxi(i) - jac(1, 2)*deta(i))/detj
         dy = (-jac(2, 1)*dxi(i) + jac(1, 1)*deta(i))/detj
         b(1, 2*i - 1) = dx
         b(2, 2*i) = dy
         b(3, 2*i - 1) = dy
         b(3, 2*i) = dx
      end do
   end subroutine iso_point
end module vemcontact_element_isoparametric
