!> Isoparametric bilinear quadrilateral (CalculiX CPE4/CPS4): full 2 x 2 Gauss
!> integration, so it is exact for parallelograms and has no spurious modes.
!> Natural coordinates of the nodes: (-1,-1), (1,-1), (1,1), (-1,1).
module vemcontact_element_quad4
   use vemcontact_kinds, only: wp
   use vemcontact_element_geometry, only: polygon_signed_area
   use vemcontact_element_bmatrix, only: add_btdb, b_times
   implicit none
   private

   public :: quad4_stiffness, quad4_stress, quad4_load_weights, quad4_min_gauss_jacobian

   real(wp), parameter :: xi_node(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]
   real(wp), parameter :: eta_node(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
   !> 2-point Gauss abscissa 1/sqrt(3); weights are 1
   real(wp), parameter :: gp = 0.57735026918962576450914878050196_wp

contains

   !> Stiffness ke(8, 8).  info = 1 for a non-positive area, 3 when the Jacobian
   !> is not positive at a Gauss point (a non-convex or tangled quad: its
   !> isoparametric map folds, so the element is not usable); ke = 0 then.
   pure subroutine quad4_stiffness(xy, d, thick, ke, info)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: ke(:, :)
      integer, intent(out) :: info
      real(wp) :: b(3, 8), detj, nsh(4)
      integer :: g, i, j
      ke = 0.0_wp
      info = 0
      if (.not. polygon_signed_area(xy) > 0.0_wp) then
         info = 1
         return
      end if
      do g = 1, 4
         call quad4_point(xy, gp*xi_node(g), gp*eta_node(g), nsh, b, detj)
         if (.not. detj > 0.0_wp) then
            ke = 0.0_wp
            info = 3
            return
         end if
         ! ke += t det J B^T D B on the upper block triangle (mirrored below)
         call add_btdb(b, d, thick*detj, ke)
      end do
      do j = 1, 8
         do i = j + 1, 8
            ke(i, j) = ke(j, i)
         end do
      end do
   end subroutine quad4_stiffness

   !> Smallest Jacobian determinant over the 4 Gauss points, divided by the
   !> element area/4 (its value on a parallelogram): 1 for a parallelogram, <= 0
   !> when quad4_stiffness rejects the element.  Lets the model checks name the
   !> problem before assembly.
   pure function quad4_min_gauss_jacobian(xy) result(r)
      real(wp), intent(in) :: xy(:, :)
      real(wp) :: r, detj, nsh(4), dxi(4), deta(4), jac(2, 2), a
      integer :: g
      r = huge(1.0_wp)
      do g = 1, 4
         call quad4_jacobian(xy, gp*xi_node(g), gp*eta_node(g), nsh, dxi, deta, jac, detj)
         r = min(r, detj)
      end do
      a = abs(polygon_signed_area(xy))
      if (a > 0.0_wp) then
         r = r/(0.25_wp*a)
      else
         r = min(r, 0.0_wp)
      end if
   end function quad4_min_gauss_jacobian

   !> Average of the four Gauss-point stresses (sxx, syy, sxy); zero for an
   !> element with a non-positive Jacobian (rejected by quad4_stiffness).
   pure subroutine quad4_stress(xy, d, ue, sig)
      real(wp), intent(in) :: xy(:, :), d(3, 3), ue(:)
      real(wp), intent(out) :: sig(3)
      real(wp) :: b(3, 8), detj, nsh(4), eps(3)
      integer :: g
      sig = 0.0_wp
      do g = 1, 4
         call quad4_point(xy, gp*xi_node(g), gp*eta_node(g), nsh, b, detj)
         if (.not. detj > 0.0_wp) then
            sig = 0.0_wp
            return
         end if
         eps = b_times(b, ue(1:8))
         sig = sig + (d(:, 1)*eps(1) + d(:, 2)*eps(2) + d(:, 3)*eps(3))
      end do
      sig = 0.25_wp*sig
   end subroutine quad4_stress

   !> w_i = integral of N_i by 2 x 2 Gauss: exact, since N_i det J is at most
   !> quadratic in each natural coordinate.
   pure subroutine quad4_load_weights(xy, w)
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(out) :: w(:)
      real(wp) :: b(3, 8), detj, nsh(4)
      integer :: g
      w = 0.0_wp
      do g = 1, 4
         call quad4_point(xy, gp*xi_node(g), gp*eta_node(g), nsh, b, detj)
         w(1:4) = w(1:4) + detj*nsh
      end do
   end subroutine quad4_load_weights

   !> Shape functions, B matrix and Jacobian determinant at (xi, eta).  B is
   !> left zero when det J <= 0.  Coordinates are taken relative to node 1 so
   !> that an element far from the origin keeps its digits.
   pure subroutine quad4_point(xy, xi, eta, nsh, b, detj)
      real(wp), intent(in) :: xy(:, :), xi, eta
      real(wp), intent(out) :: nsh(4), b(3, 8), detj
      real(wp) :: dxi(4), deta(4), jac(2, 2), dx, dy
      integer :: i
      call quad4_jacobian(xy, xi, eta, nsh, dxi, deta, jac, detj)
      b = 0.0_wp
      if (.not. detj > 0.0_wp) return
      do i = 1, 4
         dx = (jac(2, 2)*dxi(i) - jac(1, 2)*deta(i))/detj
         dy = (-jac(2, 1)*dxi(i) + jac(1, 1)*deta(i))/detj
         b(1, 2*i - 1) = dx
         b(2, 2*i) = dy
         b(3, 2*i - 1) = dy
         b(3, 2*i) = dx
      end do
   end subroutine quad4_point

   !> Shape functions, their derivatives in the natural coordinates, the Jacobian
   !> and its determinant at (xi, eta), coordinates relative to node 1.
   pure subroutine quad4_jacobian(xy, xi, eta, nsh, dxi, deta, jac, detj)
      real(wp), intent(in) :: xy(:, :), xi, eta
      real(wp), intent(out) :: nsh(4), dxi(4), deta(4), jac(2, 2), detj
      real(wp) :: rel(2)
      integer :: i
      jac = 0.0_wp
      do i = 1, 4
         nsh(i) = 0.25_wp*(1.0_wp + xi*xi_node(i))*(1.0_wp + eta*eta_node(i))
         dxi(i) = 0.25_wp*xi_node(i)*(1.0_wp + eta*eta_node(i))
         deta(i) = 0.25_wp*eta_node(i)*(1.0_wp + xi*xi_node(i))
         rel = xy(:, i) - xy(:, 1)
         jac(1, :) = jac(1, :) + dxi(i)*rel
         jac(2, :) = jac(2, :) + deta(i)*rel
      end do
      detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
   end subroutine quad4_jacobian
end module vemcontact_element_quad4
