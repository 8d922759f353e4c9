!> element_load_weights: the integrals of the shape functions.  All must sum to
!> the area.  The VEM weights w_i = |E| (1/n + q_i.(x_c - xbar)/|E|) are the
!> integrals of Pi phi_i, and since sum_i x_i phi_i = x is linear and Pi
!> reproduces linear functions, sum_i w_i x_i = integral of x over E exactly:
!> a body force load is exact for the first moments, on every polygon.  The
!> same holds for the CST and the Q4 (x = sum N_i x_i there, integrated
!> exactly by 2 x 2 Gauss).
program test_element_load_weights
   use vemcontact_kinds, only: wp, i8
   use vemcontact_model, only: form_vem, form_fem
   use vemcontact_element, only: element_workspace_size, element_load_weights
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_centroid, polygon_diameter
   use vemcontact_test_polymesh, only: rng_init, random_convex_polygon, random_star_polygon
   use vemcontact_testing, only: checker_t
   implicit none

   !> sums of n terms of size |E| and |E| h: rounding ~n eps; 1e-13 is 100 times that
   real(wp), parameter :: rtol = 1.0e-13_wp
   type(checker_t) :: t
   integer(i8) :: state
   real(wp), allocatable :: p(:, :), w(:), work(:)
   integer :: n, rep
   logical :: any_negative

   state = rng_init(77)
   any_negative = .false.
   do n = 3, 10
      do rep = 1, 4
         call random_convex_polygon(n, state, p)
         call check_moments(form_vem, p, 'VEM convex')
         call random_star_polygon(max(n, 4), state, p)
         call check_moments(form_vem, p, 'VEM star')
      end do
   end do
   p = reshape([0.0_wp, 0.0_wp, 3.0_wp, 0.0_wp, 3.0_wp, 2.0_wp, 2.0_wp, 2.0_wp, &
                2.0_wp, 0.5_wp, 1.0_wp, 0.5_wp, 1.0_wp, 2.0_wp, 0.0_wp, 2.0_wp], [2, 8])
   call check_moments(form_vem, p, 'VEM U-shape')
   p = reshape([0.0_wp, 0.0_wp, 0.2_wp, 0.0_wp, 0.7_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.3_wp, 0.8_wp], [2, 5])
   call check_moments(form_vem, p, 'VEM triangle with 2 collinear')
   p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp - 1.0e-6_wp, &
                1.0_wp - 1.0e-6_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 5])
   call check_moments(form_vem, p + 10.0_wp, 'VEM 1e-6 corner cut, shifted')

   ! square: every formulation gives area/4 by symmetry
   p = reshape([1.0_wp, 1.0_wp, 3.0_wp, 1.0_wp, 3.0_wp, 3.0_wp, 1.0_wp, 3.0_wp], [2, 4])
   call get_weights(form_fem, p)
   call t%check(maxval(abs(w - 1.0_wp)) <= rtol, 'Q4 square: area/4 each')
   call get_weights(form_vem, p)
   call t%check(maxval(abs(w - 1.0_wp)) <= rtol, 'VEM square: area/4 each')
   ! triangle: area/3 each, and the VEM agrees (x_c = xbar on a triangle)
   do rep = 1, 5
      call random_convex_polygon(3, state, p)
      call get_weights(form_fem, p)
      call t%check(maxval(abs(w - polygon_signed_area(p)/3)) <= rtol*polygon_signed_area(p), 'CST: area/3 each')
      call check_moments(form_fem, p, 'CST')
      call get_weights(form_vem, p)
      call t%check(maxval(abs(w - polygon_signed_area(p)/3)) <= rtol*polygon_signed_area(p), 'VEM triangle: area/3')
      call random_convex_polygon(4, state, p)
      call check_moments(form_fem, p, 'Q4 convex')
   end do
   ! trapezoid (0,0),(4,0),(3,1),(1,1), area 3.  Q4 by hand: the bilinear map
   ! has dx/dxi = (3-eta)/2, dy/dxi = 0, dy/deta = 1/2, so det J = (3-eta)/4 and
   !   w_1 = w_2 = int (1-xi)/2 d xi * int (1-eta)(3-eta)/8 d eta = 1 * (20/3)/8 = 5/6
   !   w_3 = w_4 = 1 * int (1+eta)(3-eta)/8 d eta = (16/3)/8 = 2/3.
   p = reshape([0.0_wp, 0.0_wp, 4.0_wp, 0.0_wp, 3.0_wp, 1.0_wp, 1.0_wp, 1.0_wp], [2, 4])
   call get_weights(form_fem, p)
   call t%close(w(1), 5.0_wp/6.0_wp, rtol, 'Q4 trapezoid w1 = 5/6')
   call t%close(w(2), 5.0_wp/6.0_wp, rtol, 'Q4 trapezoid w2 = 5/6')
   call t%close(w(3), 2.0_wp/3.0_wp, rtol, 'Q4 trapezoid w3 = 2/3')
   call t%close(w(4), 2.0_wp/3.0_wp, rtol, 'Q4 trapezoid w4 = 2/3')
   ! VEM by the formula: xbar = (2, 1/2), x_c = (2, 4/9), so w_i = 3/4 - q_iy/18
   ! with q_1 = (y2 - y4, x4 - x2)/2 = (-1/2, -3/2) and q_3 = (1/2, 3/2):
   ! w_1 = w_2 = 3/4 + 1/12 = 5/6, w_3 = w_4 = 3/4 - 1/12 = 2/3 (the Q4 values).
   call get_weights(form_vem, p)
   call t%close(w(1), 5.0_wp/6.0_wp, rtol, 'VEM trapezoid w1 = 5/6')
   call t%close(w(2), 5.0_wp/6.0_wp, rtol, 'VEM trapezoid w2 = 5/6')
   call t%close(w(3), 2.0_wp/3.0_wp, rtol, 'VEM trapezoid w3 = 2/3')
   call t%close(w(4), 2.0_wp/3.0_wp, rtol, 'VEM trapezoid w4 = 2/3')
   ! crowded vertices: unit square with 20 collinear vertices on 0 < x <= 0.1
   ! of its bottom side.  x_c = (1/2, 1/2) but xbar ~ (0.127, 0.083), and the
   ! corner (0,0) has q = (-1/2, -1/400), so w_1 = 1/24 + q.(x_c - xbar) < 0:
   ! w_1 = 1/24 - 0.1875 = -0.146: the VEM weights are not always positive,
   ! yet still exact in their moments.
   deallocate (p)
   allocate (p(2, 24))
   p(:, 1) = [0.0_wp, 0.0_wp]
   do n = 1, 20
      p(:, 1 + n) = [0.005_wp*n, 0.0_wp]
   end do
   p(:, 22) = [1.0_wp, 0.0_wp]
   p(:, 23) = [1.0_wp, 1.0_wp]
   p(:, 24) = [0.0_wp, 1.0_wp]
   call check_moments(form_vem, p, 'VEM square with crowded side')
   write (*, '(a,es12.4)') 'crowded square: w at corner (0,0) = ', w(1)
   call t%check(w(1) < 0.0_wp, 'VEM weight can be negative (crowded vertices)')
   write (*, '(a,l1)') 'negative VEM weight seen: ', any_negative
   call t%finish()

contains

   subroutine get_weights(form, xy)
      integer, intent(in) :: form
      real(wp), intent(in) :: xy(:, :)
      if (allocated(w)) deallocate (w, work)
      allocate (w(size(xy, 2)), work(element_workspace_size(size(xy, 2))))
      call element_load_weights(form, xy, work, w)
   end subroutine get_weights

   !> sum w = |E| and sum w_i x_i = |E| x_c
   subroutine check_moments(form, xy, what)
      integer, intent(in) :: form
      real(wp), intent(in) :: xy(:, :)
      character(len=*), intent(in) :: what
      real(wp) :: area, xc(2), scale
      call get_weights(form, xy)
      area = polygon_signed_area(xy)
      call polygon_centroid(xy, xc)
      scale = area*(maxval(abs(xc)) + polygon_diameter(xy))
      call t%close(sum(w), area, rtol, what//': sum of weights = area')
      call t%close(sum(w*xy(1, :)), area*xc(1), 0.0_wp, what//': sum w x = integral of x', atol=rtol*scale)
      call t%close(sum(w*xy(2, :)), area*xc(2), 0.0_wp, what//': sum w y = integral of y', atol=rtol*scale)
      if (any(w < 0.0_wp)) any_negative = .true.
   end subroutine check_moments
end program test_element_load_weights
