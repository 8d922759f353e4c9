!> Products with the strain-displacement matrix of the first-order FEM elements,
!> B = [B_1 ... B_n] with B_i = [[dx_i, 0], [0, dy_i], [dy_i, dx_i]] (rows exx, eyy,
!> gxy; dx_i, dy_i the derivatives of shape function i), held as a (3, 2n) array with
!> those zeros.  The products are written out without the zero terms, with the same
!> sums in the same order as matmul over the full B, so they give the same numbers;
!> gfortran's inline matmul would store and reload every partial sum, which made it
!> most of the element kernels' time.
module vemcontact_element_bmatrix
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: add_btdb, b_times

contains

   !> ke(1:2n, 1:2n) += w B^T D B on the upper block triangle (node blocks i <= j);
   !> the caller mirrors it into the lower triangle.
   pure subroutine add_btdb(b, d, w, ke)
      real(wp), intent(in) :: b(:, :), d(3, 3), w
      real(wp), intent(inout) :: ke(:, :)
      real(wp) :: db(3, 2), dxi, dyi
      integer :: i, j, r, c
      do j = 1, size(b, 2)/2
         c = 2*j - 1
         ! D B_j: B_j's columns are (dx, 0, dy) and (0, dy, dx)
         db(:, 1) = d(:, 1)*b(1, c) + d(:, 3)*b(3, c)
         db(:, 2) = d(:, 2)*b(2, c + 1) + d(:, 3)*b(3, c + 1)
         do i = 1, j
            r = 2*i - 1
            dxi = b(1, r)
            dyi = b(2, r + 1)
            ke(r, c) = ke(r, c) + w*(dxi*db(1, 1) + dyi*db(3, 1))
            ke(r + 1, c) = ke(r + 1, c) + w*(dyi*db(2, 1) + dxi*db(3, 1))
            ke(r, c + 1) = ke(r, c + 1) + w*(dxi*db(1, 2) + dyi*db(3, 2))
            ke(r + 1, c + 1) = ke(r + 1, c + 1) + w*(dyi*db(2, 2) + dxi*db(3, 2))
         end do
      end do
   end subroutine add_btdb

   !> B u: the strain (exx, eyy, gxy) of the element displacements u(2n).
   pure function b_times(b, u) result(eps)
      real(wp), intent(in) :: b(:, :), u(:)
      real(wp) :: eps(3)
      integer :: i
      eps = 0.0_wp
      do i = 1, size(b, 2)/2
         eps(1) = eps(1) + b(1, 2*i - 1)*u(2*i - 1)
         eps(2) = eps(2) + b(2, 2*i)*u(2*i)
         eps(3) = eps(3) + b(3, 2*i - 1)*u(2*i - 1)
         eps(3) = eps(3) + b(3, 2*i)*u(2*i)
      end do
   end function b_times
end module vemcontact_element_bmatrix
