!> Isoparametric 8-node serendipity quadrilateral (Abaqus/CalculiX CPE8/CPS8):
!> corners 1-4 counter-clockwise, then side nodes 5 (side 1-2), 6 (2-3),
!> 7 (3-4), 8 (4-1).  Full 3 x 3 Gauss integration, as Abaqus' CPE8 (CPE8R
!> would be 2 x 2): exact for the stiffness of a parallelogram with straight
!> sides (B^T D B is of degree 4 in each natural coordinate there), and free of
!> the spurious modes the reduced rule lets through.
module vemcontact_element_quad8
   use vemcontact_kinds, only: wp
   use vemcontact_element_geometry, only: polygon_signed_area
   use vemcontact_element_isoparametric, only: iso_point
   implicit none
   private

   public :: quad8_stiffness, quad8_stress, quad8_load_weights

   real(wp), parameter :: xi_node(8) = [-1, 1, 1, -1, 0, 1, 0, -1]
   real(wp), parameter :: eta_node(8) = [-1, -1, 1, 1, -1, 0, 1, 0]
   !> 3-point Gauss rule on [-1, 1]
   real(wp), parameter :: gx(3) = [-sqrt(0.6_wp), 0.0_wp, sqrt(0.6_wp)]
   real(wp), parameter :: gw(3) = [5.0_wp/9.0_wp, 8.0_wp/9.0_wp, 5.0_wp/9.0_wp]

contains

   !> Stiffness ke(16, 16).  info = 1 for a non-positive area (corners), 3 when
   !> the Jacobian is not positive at a Gauss point; ke = 0 then.
   pure subroutine quad8_stiffness(xy, d, thick, ke, info)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: ke(:, :)
      integer, intent(out) :: info
      real(wp) :: b(3, 16), detj, nsh(8)
      integer :: g, h, i, j
      ke = 0.0_wp
      info = 0
      if (.not. polygon_signed_area(xy(:, 1:4)) > 0.0_wp) then
         info = 1
         return
      end if
      do g = 1, 3
         do h = 1, 3
            call quad8_point(xy, gx(g), gx(h), nsh, b, detj)
            if (.not. detj > 0.0_wp) then
               ke = 0.0_wp
               info = 3
               return
            end if
            ke(1:16, 1:16) = ke(1:16, 1:16) + (gw(g)*gw(h)*thick*detj)*matmul(transpose(b), matmul(d, b))
         end do
      end do
      do j = 1, 16
         do i = j + 1, 16
            ke(i, j) = ke(j, i)
         end do
      end do
   end subroutine quad8_stiffness

   !> Mean stress (sxx, syy, sxy) over the element (3 x 3 Gauss); zero for an
   !> element quad8_stiffness rejects.  `signode(3, 8)` (optional): the stress
   !> evaluated at each node (its natural coordinates), the mean where the
   !> Jacobian is not positive there.
   pure subroutine quad8_stress(xy, d, ue, sig, signode)
      real(wp), intent(in) :: xy(:, :), d(3, 3), ue(:)
      real(wp), intent(out) :: sig(3)
      real(wp), intent(out), optional :: signode(:, :)
      real(wp) :: b(3, 16), detj, nsh(8), area
      integer :: g, h
      sig = 0.0_wp
      area = 0.0_wp
      do g = 1, 3
         do h = 1, 3
            call quad8_point(xy, gx(g), gx(h), nsh, b, detj)
            if (.not. detj > 0.0_wp) then
               sig = 0.0_wp
               if (present(signode)) signode = 0.0_wp
               return
            end if
            sig = sig + (gw(g)*gw(h)*detj)*matmul(d, matmul(b, ue(1:16)))
            area = area + gw(g)*gw(h)*detj
         end do
      end do
      sig = sig/area
      if (present(signode)) then
         do g = 1, 8
            call quad8_point(xy, xi_node(g), eta_node(g), nsh, b, detj)
            signode(:, g) = sig
            if (detj > 0.0_wp) signode(:, g) = matmul(d, matmul(b, ue(1:16)))
         end do
      end if
   end subroutine quad8_stress

   !> w_i = integral of N_i (3 x 3 Gauss; the corner weights are negative,
   !> -|E|/12 on a parallelogram, the side weights |E|/3).
   pure subroutine quad8_load_weights(xy, w)
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(out) :: w(:)
      real(wp) :: b(3, 16), detj, nsh(8)
      integer :: g, h
      w = 0.0_wp
      do g = 1, 3
         do h = 1, 3
            call quad8_point(xy, gx(g), gx(h), nsh, b, detj)
            w(1:8) = w(1:8) + (gw(g)*gw(h)*detj)*nsh
         end do
      end do
   end subroutine quad8_load_weights

   !> Shape functions, B and det J at (xi, eta).
   pure subroutine quad8_point(xy, xi, eta, nsh, b, detj)
      real(wp), intent(in) :: xy(:, :), xi, eta
      real(wp), intent(out) :: nsh(8), b(3, 16), detj
      real(wp) :: dxi(8), deta(8), a, c
      integer :: i
      do i = 1, 8
         a = xi_node(i)
         c = eta_node(i)
         if (i <= 4) then
            nsh(i) = 0.25_wp*(1 + xi*a)*(1 + eta*c)*(xi*a + eta*c - 1)
            dxi(i) = 0.25_wp*a*(1 + eta*c)*(2*xi*a + eta*c)
            deta(i) = 0.25_wp*c*(1 + xi*a)*(xi*a + 2*eta*c)
         else if (i == 5 .or. i == 7) then     ! side nodes with xi = 0
            nsh(i) = 0.5_wp*(1 - xi*xi)*(1 + eta*c)
            dxi(i) = -xi*(1 + eta*c)
            deta(i) = 0.5_wp*c*(1 - xi*xi)
         else
            nsh(i) = 0.5_wp*(1 + xi*a)*(1 - eta*eta)
            dxi(i) = 0.5_wp*a*(1 - eta*eta)
            deta(i) = -eta*(1 + xi*a)
         end if
      end do
      call iso_point(xy(:, 1:8), dxi, deta, b, detj)
   end subroutine quad8_point
end module vemcontact_element_quad8
