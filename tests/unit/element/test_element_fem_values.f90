!> FEM stiffness entries against values derived by hand, and the calibration of
!> the VEM stabilisation against the bilinear element on a square.
program test_element_fem_values
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: plane_strain, plane_stress, form_vem, form_fem
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element, only: element_workspace_size, element_stiffness
   use vemcontact_testing, only: checker_t
   implicit none

   !> 2 x 2 Gauss integrates the bilinear element on rectangles exactly, so the
   !> only error is rounding of O(10) operations: 1e-14 relative.
   real(wp), parameter :: rtol = 1.0e-14_wp

   type(checker_t) :: t
   real(wp) :: d(3, 3), ke(8, 8), kref(8, 8), k6(6, 6), kv(8, 8)
   real(wp), allocatable :: work(:)
   real(wp) :: kk(8), nu, a, b, e, th, hg(8), evem, eq4
   integer :: info, i, j
   integer, parameter :: pat(8, 8) = reshape([ &
                                             1, 2, 3, 4, 5, 6, 7, 8, &
                                             2, 1, 8, 7, 6, 5, 4, 3, &
                                             3, 8, 1, 6, 7, 4, 5, 2, &
                                             4, 7, 6, 1, 8, 3, 2, 5, &
                                             5, 6, 7, 8, 1, 2, 3, 4, &
                                             6, 5, 4, 3, 2, 1, 8, 7, &
                                             7, 4, 5, 2, 3, 8, 1, 6, &
                                             8, 3, 2, 5, 4, 7, 6, 1], [8, 8])
   real(wp), parameter :: unit_square(2, 4) = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
                                                       1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])

   allocate (work(element_workspace_size(4)))

   ! Unit square, E = 1, nu = 0, t = 1, plane stress: D = diag(1, 1, 1/2).
   ! N1 = (1-x)(1-y), N2 = x(1-y), N3 = xy, N4 = (1-x)y.
   !   K(1,1) = int N1x^2 + N1y^2/2          = 1/3 + 1/6          =  1/2
   !   K(1,2) = int N1y N1x / 2              = (1/4)/2            =  1/8
   !   K(1,3) = int N1x N2x + N1y N2y / 2    = -1/3 + (1/6)/2     = -1/4
   !   K(1,4) = int N1y N2x / 2 (nu = 0)     = (-1/4)/2           = -1/8
   !   K(1,5) = int N1x N3x + N1y N3y / 2    = -1/6 - (1/6)/2     = -1/4
   !   K(1,7) = int N1x N4x + N1y N4y / 2    = 1/6 - (1/3)/2      =  0
   !   K(1,8) = int N1y N4x / 2              = (1/4)/2            =  1/8
   call elastic_matrix(1.0_wp, 0.0_wp, plane_stress, d)
   call element_stiffness(form_fem, unit_square, d, 1.0_wp, ke, work, info)
   call t%equal(info, 0, 'unit square info')
   call t%close(ke(1, 1), 0.5_wp, rtol, 'square nu=0 K(1,1) = 1/2')
   call t%close(ke(1, 2), 0.125_wp, rtol, 'square nu=0 K(1,2) = 1/8')
   call t%close(ke(1, 3), -0.25_wp, rtol, 'square nu=0 K(1,3) = -1/4')
   call t%close(ke(1, 4), -0.125_wp, rtol, 'square nu=0 K(1,4) = -1/8')
   call t%close(ke(1, 5), -0.25_wp, rtol, 'square nu=0 K(1,5) = -1/4')
   call t%close(ke(1, 7), 0.0_wp, rtol, 'square nu=0 K(1,7) = 0', atol=1.0e-15_wp)
   call t%close(ke(1, 8), 0.125_wp, rtol, 'square nu=0 K(1,8) = 1/8')

   ! General nu, E, t on the unit square: the closed form (e.g. Sigmund's
   ! 99-line code), E t/(1-nu^2) k(pat) with
   ! k = [1/2-nu/6, 1/8+nu/8, -1/4-nu/12, -1/8+3nu/8, -1/4+nu/12, -1/8-nu/8, nu/6, 1/8-3nu/8];
   ! its first row follows from the integrals above with D12 = nu E/(1-nu^2),
   ! D33 = (1-nu) E/(2(1-nu^2)), and the rest from the symmetry of the square.
   nu = 0.3_wp
   e = 2.1e5_wp
   th = 0.25_wp
   kk = [0.5_wp - nu/6, 0.125_wp + nu/8, -0.25_wp - nu/12, -0.125_wp + 3*nu/8, &
         -0.25_wp + nu/12, -0.125_wp - nu/8, nu/6, 0.125_wp - 3*nu/8]
   do j = 1, 8
      do i = 1, 8
         kref(i, j) = e*th/(1.0_wp - nu**2)*kk(pat(i, j))
      end do
   end do
   call elastic_matrix(e, nu, plane_stress, d)
   call element_stiffness(form_fem, unit_square, d, th, ke, work, info)
   call t%check(maxval(abs(ke - kref)) <= rtol*10*maxval(abs(kref)), 'square nu=0.3: all 64 entries')
   ! the same square translated far away: same matrix (Jacobian built from differences)
   call element_stiffness(form_fem, unit_square + 1.0e3_wp, d, th, ke, work, info)
   call t%check(maxval(abs(ke - kref)) <= 1.0e-12_wp*maxval(abs(kref)), 'translated square')

   ! Rectangle a x b, E = 1, nu = 0, t = 1, plane stress:
   !   K(1,1) =  b/(3a) + a/(6b)     K(1,2) = 1/8        K(1,3) = -b/(3a) + a/(12b)
   !   K(1,5) = -b/(6a) - a/(12b)    K(1,7) = b/(6a) - a/(6b)
   a = 3.0_wp
   b = 0.5_wp
   call elastic_matrix(1.0_wp, 0.0_wp, plane_stress, d)
   call element_stiffness(form_fem, reshape([0.0_wp, 0.0_wp, a, 0.0_wp, a, b, 0.0_wp, b], &
                                                         [2, 4]), d, 1.0_wp, ke, work, info)
   call t%close(ke(1, 1), b/(3*a) + a/(6*b), rtol, 'rectangle K(1,1)')
   call t%close(ke(1, 2), 0.125_wp, rtol, 'rectangle K(1,2)')
   call t%close(ke(1, 3), -b/(3*a) + a/(12*b), rtol, 'rectangle K(1,3)')
   call t%close(ke(1, 5), -b/(6*a) - a/(12*b), rtol, 'rectangle K(1,5)')
   call t%close(ke(1, 7), b/(6*a) - a/(6*b), rtol, 'rectangle K(1,7)')
   call t%close(ke(2, 2), a/(3*b) + b/(6*a), rtol, 'rectangle K(2,2) (x <-> y swapped)')

   ! CST (0,0), (1,0), (0,1), E = 1, nu = 0, t = 1, plane stress, A = 1/2:
   ! grad N1 = (-1,-1), grad N2 = (1,0), grad N3 = (0,1); B columns of u1x, u1y,
   ! u2x, u2y, u3x, u3y: (-1,0,-1), (0,-1,-1), (1,0,0), (0,0,1), (0,0,1), (0,1,0);
   ! K(I,J) = A b_I^T diag(1,1,1/2) b_J:
   !   K(1,1) = 3/4   K(1,2) = 1/4   K(1,3) = -1/2   K(1,4) = -1/4
   !   K(1,5) = -1/4  K(1,6) = 0     K(2,3) = 0      K(2,4) = -1/4
   call element_stiffness(form_fem, reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], &
                                                        [2, 3]), d, 1.0_wp, k6, work, info)
   call t%close(k6(1, 1), 0.75_wp, rtol, 'CST K(1,1)')
   call t%close(k6(1, 3), -0.5_wp, rtol, 'CST K(1,3)')
   call t%close(k6(1, 5), -0.25_wp, rtol, 'CST K(1,5)')
   call t%close(k6(1, 2), 0.25_wp, rtol, 'CST K(1,2)')
   call t%close(k6(1, 4), -0.25_wp, rtol, 'CST K(1,4)')
   call t%close(k6(1, 6), 0.0_wp, rtol, 'CST K(1,6)', atol=1.0e-16_wp)
   call t%close(k6(2, 3), 0.0_wp, rtol, 'CST K(2,3)', atol=1.0e-16_wp)
   call t%close(k6(2, 4), -0.25_wp, rtol, 'CST K(2,4)')

   ! Stabilisation calibration (docs/vem-formulation.md): on the unit square the
   ! hourglass mode h (u_x = +1,-1,+1,-1) has zero projected strain, so its VEM
   ! energy is pure stabilisation, sum s_i = D11 + D33 (tau = 1); the bilinear
   ! element gives (4/3)(D11 + D33).  Ratio exactly 3/4, any nu and plane.
   hg = [1.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 0.0_wp]
   do i = 1, 2
      call elastic_matrix(e, nu, merge(plane_strain, plane_stress, i == 1), d)
      call element_stiffness(form_vem, unit_square, d, th, kv, work, info)
      call element_stiffness(form_fem, unit_square, d, th, ke, work, info)
      evem = dot_product(hg, matmul(kv, hg))
      eq4 = dot_product(hg, matmul(ke, hg))
      call t%close(evem, th*(d(1, 1) + d(3, 3)), 1.0e-13_wp, 'VEM hourglass energy = t (D11 + D33)')
      call t%close(evem/eq4, 0.75_wp, 1.0e-13_wp, 'VEM/Q4 hourglass energy on a square = 3/4')
   end do
   call t%finish()
end program test_element_fem_values
