!> Isoparametric 8-node serendipity quadrilateral (Abaqus/CalculiX CPE8/CPS8):
!> corners 1-4 counter-clockwise, then side nodes 5 (side 1-2), 6 (2-3),
!> 7 (3-4), 8 (4-1).  Full 3 x 3 Gauss integration, as Abaqus' CPE8: exact
!> for the stiffness of a parallelogram with straight sides (B^T D B is of
!> degree 4 in each natural coordinate there), and free of the spurious modes
!> the reduced rule lets through.  `reduced` selects the 2 x 2 rule of CPE8R /
!> CPS8R: softer (it is exact for the element's complete quadratic part only)
!> and with one spurious zero-energy mode per lone element (the hourglass mode
!> of the 2 x 2 rule, which two or more connected elements suppress).
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
   !> 2-point Gauss rule on [-1, 1] (reduced integration)
   real(wp), parameter :: rx(2) = [-1.0_wp/sqrt(3.0_wp), 1.0_wp/sqrt(3.0_wp)]
   real(wp), parameter :: rw(2) = [1.0_wp, 1.0_wp]

contains

   !> Stiffness ke(16, 16).  info = 1 for a non-positive area (corners), 3 when
   !> the Jacobian is not positive at a Gauss point; ke = 0 then.  `reduced`
   !> (optional, default false): 2 x 2 Gauss (CPE8R/CPS8R).
   pure subroutine quad8_stiffness(xy, d, thick, ke, info, reduced)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: ke(:, :)
      integer, intent(out) :: info
      logical, intent(in), optional :: reduced
      real(wp) :: b(3, 16), detj, nsh(8), px(3), pw(3)
      integer :: g, h, i, j, np
      call rule(reduced, px, pw, np)
      ke = 0.0_wp
      info = 0
      if (.not. polygon_signed_area(xy(:, 1:4)) > 0.0_wp) then
         info = 1
         return
      end if
      do g = 1, np
         do h = 1, np
            call quad8_point(xy, px(g), px(h), nsh, b, detj)
            if (.not. detj > 0.0_wp) then
               ke = 0.0_wp
               info = 3
               return
            end if
            ke(1:16, 1:16) = ke(1:16, 1:16) + (pw(g)*pw(h)*thick*detj)*matmul(transpose(b), matmul(d, b))
         end do
      end do
      do j = 1, 16
         do i = j + 1, 16
            ke(i, j) = ke(j, i)
         end do
      end do
   end subroutine quad8_stiffness

   !> Mean stress (sxx, syy, sxy) over the element (3 x 3 Gauss, 2 x 2 when
   !> `reduced`); zero for an element quad8_stiffness rejects.  `signode(3, 8)`
   !> (optional): the stress evaluated at each node (its natural coordinates),
   !> the mean where the Jacobian is not positive there.
   pure subroutine quad8_stress(xy, d, ue, sig, signode, reduced)
      real(wp), intent(in) :: xy(:, :), d(3, 3), ue(:)
      real(wp), intent(out) :: sig(3)
      real(wp), intent(out), optional :: signode(:, :)
      logical, intent(in), optional :: reduced
      real(wp) :: b(3, 16), detj, nsh(8), area, px(3), pw(3)
      integer :: g, h, np
      call rule(reduced, px, pw, np)
      sig = 0.0_wp
      area = 0.0_wp
      do g = 1, np
         do h = 1, np
            call quad8_point(xy, px(g), px(h), nsh, b, detj)
            if (.not. detj > 0.0_wp) then
               sig = 0.0_wp
               if (present(signode)) signode = 0.0_wp
               return
            end if
            sig = sig + (pw(g)*pw(h)*detj)*matmul(d, matmul(b, ue(1:16)))
            area = area + pw(g)*pw(h)*detj
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

   !> The Gauss rule: points px(1:np), weights pw(1:np); 3 points, or 2 when `reduced`.
   pure subroutine rule(reduced, px, pw, np)
      logical, intent(in), optional :: reduced
      real(wp), intent(out) :: px(3), pw(3)
      integer, intent(out) :: np
      px = gx
      pw = gw
      np = 3
      if (present(reduced)) then
         if (reduced) then
            px(1:2) = rx
            pw(1:2) = rw
            np = 2
         end if
      end if
   end subroutine rule

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
