!> Isoparametric 6-node triangle (Abaqus/CalculiX CPE6/CPS6): corners 1-3
!> counter-clockwise, then side nodes 4 (side 1-2), 5 (2-3), 6 (3-1).  The
!> 3-point rule of degree 2 (Abaqus' integration of CPE6): exact for the
!> stiffness of a straight-sided triangle, whose B is linear.
module vemcontact_element_tri6
   use vemcontact_kinds, only: wp
   use vemcontact_element_geometry, only: polygon_signed_area
   use vemcontact_element_isoparametric, only: iso_point
   implicit none
   private

   public :: tri6_stiffness, tri6_stress, tri6_load_weights

   !> Gauss points (xi, eta) of the 3-point rule on the reference triangle, weight 1/6 each
   real(wp), parameter :: gxi(3) = [1.0_wp/6, 2.0_wp/3, 1.0_wp/6]
   real(wp), parameter :: geta(3) = [1.0_wp/6, 1.0_wp/6, 2.0_wp/3]
   real(wp), parameter :: gw = 1.0_wp/6

contains

   !> Stiffness ke(12, 12).  info = 1 for a non-positive area (corners), 3 when
   !> the Jacobian is not positive at a Gauss point; ke = 0 then.
   pure subroutine tri6_stiffness(xy, d, thick, ke, info)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: ke(:, :)
      integer, intent(out) :: info
      real(wp) :: b(3, 12), detj, nsh(6)
      integer :: g, i, j
      ke = 0.0_wp
      info = 0
      if (.not. polygon_signed_area(xy(:, 1:3)) > 0.0_wp) then
         info = 1
         return
      end if
      do g = 1, 3
         call tri6_point(xy, gxi(g), geta(g), nsh, b, detj)
         if (.not. detj > 0.0_wp) then
            ke = 0.0_wp
            info = 3
            return
         end if
         ke(1:12, 1:12) = ke(1:12, 1:12) + (gw*thick*detj)*matmul(transpose(b), matmul(d, b))
      end do
      do j = 1, 12
         do i = j + 1, 12
            ke(i, j) = ke(j, i)
         end do
      end do
   end subroutine tri6_stiffness

   !> Mean stress (sxx, syy, sxy) over the element; zero for a rejected element.
   !> `signode(3, 6)` (optional): the stress at each node (linear on a
   !> straight-sided triangle, so its nodal values are exact for quadratic fields).
   pure subroutine tri6_stress(xy, d, ue, sig, signode)
      real(wp), intent(in) :: xy(:, :), d(3, 3), ue(:)
      real(wp), intent(out) :: sig(3)
      real(wp), intent(out), optional :: signode(:, :)
      real(wp), parameter :: xin(6) = [0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, 0.5_wp, 0.0_wp]
      real(wp), parameter :: etan(6) = [0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, 0.5_wp]
      real(wp) :: b(3, 12), detj, nsh(6), area
      integer :: g
      sig = 0.0_wp
      area = 0.0_wp
      do g = 1, 3
         call tri6_point(xy, gxi(g), geta(g), nsh, b, detj)
         if (.not. detj > 0.0_wp) then
            sig = 0.0_wp
            if (present(signode)) signode = 0.0_wp
            return
         end if
         sig = sig + (gw*detj)*matmul(d, matmul(b, ue(1:12)))
         area = area + gw*detj
      end do
      sig = sig/area
      if (present(signode)) then
         do g = 1, 6
            call tri6_point(xy, xin(g), etan(g), nsh, b, detj)
            signode(:, g) = sig
            if (detj > 0.0_wp) signode(:, g) = matmul(d, matmul(b, ue(1:12)))
         end do
      end if
   end subroutine tri6_stress

   !> w_i = integral of N_i: 0 at the corners and |E|/3 at the side nodes of a
   !> straight-sided triangle.
   pure subroutine tri6_load_weights(xy, w)
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(out) :: w(:)
      real(wp) :: b(3, 12), detj, nsh(6)
      integer :: g
      w = 0.0_wp
      do g = 1, 3
         call tri6_point(xy, gxi(g), geta(g), nsh, b, detj)
         w(1:6) = w(1:6) + (gw*detj)*nsh
      end do
   end subroutine tri6_load_weights

   !> Shape functions, B and det J at (xi, eta); area coordinates
   !> L1 = 1 - xi - eta, L2 = xi, L3 = eta.
   pure subroutine tri6_point(xy, xi, eta, nsh, b, detj)
      real(wp), intent(in) :: xy(:, :), xi, eta
      real(wp), intent(out) :: nsh(6), b(3, 12), detj
      real(wp) :: l1, l2, l3, dxi(6), deta(6)
      l1 = 1 - xi - eta
      l2 = xi
      l3 = eta
      nsh = [l1*(2*l1 - 1), l2*(2*l2 - 1), l3*(2*l3 - 1), 4*l1*l2, 4*l2*l3, 4*l3*l1]
      dxi = [-(4*l1 - 1), 4*l2 - 1, 0.0_wp, 4*(l1 - l2), 4*l3, -4*l3]
      deta = [-(4*l1 - 1), 0.0_wp, 4*l3 - 1, -4*l2, 4*l2, 4*(l1 - l3)]
      call iso_point(xy(:, 1:6), dxi, deta, b, detj)
   end subroutine tri6_point
end module vemcontact_element_tri6
