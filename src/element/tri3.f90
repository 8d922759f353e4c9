!> Constant strain triangle (CalculiX CPE3/CPS3), in the textbook form
!> B = (1/2A) [[b_i, 0], [0, c_i], [c_i, b_i]], b_i = y_j - y_k, c_i = x_k - x_j
!> with (i, j, k) cyclic.  Written independently of the VEM kernel so that the
!> tests can use the identity "VEM on a triangle = CST" as a cross-check.
module vemcontact_element_tri3
   use vemcontact_kinds, only: wp
   use vemcontact_element_bmatrix, only: add_btdb, b_times
   implicit none
   private

   public :: tri3_stiffness, tri3_stress, tri3_load_weights

contains

   !> Stiffness ke(6, 6) = A t B^T D B; info = 1 for a non-positive area (ke = 0).
   pure subroutine tri3_stiffness(xy, d, thick, ke, info)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: ke(:, :)
      integer, intent(out) :: info
      real(wp) :: b(3, 6), area
      integer :: i, j
      ke = 0.0_wp
      info = 0
      call tri3_b(xy, b, area)
      if (.not. area > 0.0_wp) then
         info = 1
         return
      end if
      ! A t B^T D B on the upper block triangle, mirrored below
      call add_btdb(b, d, area*thick, ke)
      do j = 1, 6
         do i = j + 1, 6
            ke(i, j) = ke(j, i)
         end do
      end do
   end subroutine tri3_stiffness

   !> Constant stress (sxx, syy, sxy); zero for a non-positive area.
   pure subroutine tri3_stress(xy, d, ue, sig)
      real(wp), intent(in) :: xy(:, :), d(3, 3), ue(:)
      real(wp), intent(out) :: sig(3)
      real(wp) :: b(3, 6), area, eps(3)
      call tri3_b(xy, b, area)
      sig = 0.0_wp
      if (.not. area > 0.0_wp) return
      eps = b_times(b, ue(1:6))
      sig = d(:, 1)*eps(1) + d(:, 2)*eps(2) + d(:, 3)*eps(3)
   end subroutine tri3_stress

   !> Integral of the linear shape functions: A/3 each (negative area: -|A|/3
   !> would be meaningless, the element is rejected by tri3_stiffness).
   pure subroutine tri3_load_weights(xy, w)
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(out) :: w(:)
      real(wp) :: area
      area = 0.5_wp*((xy(1, 2) - xy(1, 1))*(xy(2, 3) - xy(2, 1)) &
                     - (xy(1, 3) - xy(1, 1))*(xy(2, 2) - xy(2, 1)))
      w = 0.0_wp
      w(1:3) = area/3.0_wp
   end subroutine tri3_load_weights

   pure subroutine tri3_b(xy, b, area)
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(out) :: b(3, 6), area
      real(wp) :: bi, ci
      integer :: i, j, k
      area = 0.5_wp*((xy(1, 2) - xy(1, 1))*(xy(2, 3) - xy(2, 1)) &
                     - (xy(1, 3) - xy(1, 1))*(xy(2, 2) - xy(2, 1)))
      b = 0.0_wp
      if (.not. area > 0.0_wp) return
      do i = 1, 3
         j = modulo(i, 3) + 1
         k = modulo(i + 1, 3) + 1
         bi = (xy(2, j) - xy(2, k))/(2.0_wp*area)
         ci = (xy(1, k) - xy(1, j))/(2.0_wp*area)
         b(1, 2*i - 1) = bi
         b(2, 2*i) = ci
         b(3, 2*i - 1) = ci
         b(3, 2*i) = bi
      end do
   end subroutine tri3_b
end module vemcontact_element_tri3
