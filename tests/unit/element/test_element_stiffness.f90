!> Properties every element stiffness must have, on many shapes: symmetry,
!> exactly three zero eigenvalues (rigid modes) and positive semi-definiteness,
!> polynomial consistency (K u_lin = consistent nodal forces of the constant
!> stress, i.e. the patch test), exact stress recovery of linear fields, and
!> invariance of the VEM stiffness under translation, scaling and rotation.
program test_element_stiffness
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_model, only: plane_strain, plane_stress, form_vem, form_fem
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element, only: element_workspace_size, element_stiffness, element_stress
   use vemcontact_element_geometry, only: polygon_is_simple, polygon_is_convex, polygon_diameter
   use vemcontact_test_polymesh, only: rng_init, rng_uniform, random_convex_polygon, &
      random_star_polygon, dual_polymesh, hanging_quad_grid
   use vemcontact_testing, only: checker_t
   use vemcontact_linalg_lapack, only: dsyev
   implicit none


   !> Tolerances.  Symmetry: the kernels mirror their upper triangle, so 1e-14
   !> only allows for nothing.  Zero eigenvalues: rounding in K is ~eps*|K|, and
   !> dsyev is backward stable, so rigid-mode eigenvalues come out at ~1e-15 of
   !> the largest; 1e-12 leaves a margin of 1000.  Non-zero eigenvalues: the
   !> worst shapes here (aspect 100, 1e-6 sides, nu = 0.49) keep the fourth
   !> eigenvalue far above 1e-8 of the largest; a missing stabilisation would
   !> give ~1e-16.  Consistency and stress: a product of n terms of size |K||u|
   !> rounds at ~n*eps*|K||u| ~ 1e-14, so 1e-12 of |K||u| separates rounding from
   !> any real inconsistency, which is O(1).
   real(wp), parameter :: tol_sym = 1.0e-14_wp, tol_zero = 1.0e-12_wp, tol_pos = 1.0e-8_wp
   real(wp), parameter :: tol_cons = 1.0e-12_wp
   real(wp), parameter :: young = 7.0e4_wp, thick = 0.5_wp

   type(checker_t) :: t
   integer(i8) :: state
   real(wp), allocatable :: xy(:, :)
   real(wp) :: worst_pos, worst_zero
   real(wp), allocatable :: xm(:, :)
   integer(ip), allocatable :: ptr(:), conn(:)
   integer :: n, rep, ncount, e
   character(len=64) :: label
   character(len=:), allocatable :: worst_label, worst_vem_label
   real(wp) :: worst_vem = huge(1.0_wp)

   state = rng_init(20240611)
   worst_pos = huge(1.0_wp)
   worst_zero = 0.0_wp
   ncount = 0

   ! 1. VEM on random convex polygons, n = 3..10
   do n = 3, 10
      do rep = 1, 5
         call random_convex_polygon(n, state, xy)
         write (label, '(a,i0,a,i0)') 'VEM convex n=', n, ' #', rep
         call t%check(polygon_is_convex(xy), trim(label)//' generator gives convex')
         call check_all(form_vem, xy, trim(label))
      end do
   end do
   ! star-shaped non-convex polygons
   do n = 4, 12
      do rep = 1, 3
         call random_star_polygon(n, state, xy)
         write (label, '(a,i0,a,i0)') 'VEM star n=', n, ' #', rep
         call t%check(polygon_is_simple(xy), trim(label)//' simple')
         if (n >= 6) call t%check(.not. polygon_is_convex(xy), trim(label)//' non-convex')
         call check_all(form_vem, xy, trim(label))
      end do
   end do
   ! L and U shapes, exact and jittered
   do rep = 0, 3
      xy = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, &
                    1.0_wp, 2.0_wp, 0.0_wp, 2.0_wp], [2, 6])
      call jitter(xy, 0.05_wp*rep)
      call check_all(form_vem, xy, 'VEM L-shape')
      xy = reshape([0.0_wp, 0.0_wp, 3.0_wp, 0.0_wp, 3.0_wp, 2.0_wp, 2.0_wp, 2.0_wp, &
                    2.0_wp, 0.5_wp, 1.0_wp, 0.5_wp, 1.0_wp, 2.0_wp, 0.0_wp, 2.0_wp], [2, 8])
      call jitter(xy, 0.05_wp*rep)
      call check_all(form_vem, xy, 'VEM U-shape')
   end do
   ! strongly distorted quads
   xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.6_wp, 0.1_wp, 0.4_wp, 0.1_wp], [2, 4])
   call check_all(form_vem, xy, 'VEM flat trapezoid')
   call check_all(form_fem, xy, 'Q4 flat trapezoid')
   xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.5_wp, 0.49_wp], [2, 4])
   call check_all(form_vem, xy, 'VEM dart quad')
   xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.5_wp, 0.51_wp], [2, 4])
   call check_all(form_vem, xy, 'VEM 179-degree quad')
   call check_all(form_fem, xy, 'Q4 179-degree quad')
   xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 3.0_wp, 1.0_wp, 2.0_wp, 1.0_wp], [2, 4])
   call check_all(form_vem, xy, 'VEM skewed parallelogram')
   call check_all(form_fem, xy, 'Q4 skewed parallelogram')
   xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.01_wp, 0.0_wp, 0.01_wp], [2, 4])
   call check_all(form_vem, xy, 'VEM aspect 100')
   call check_all(form_fem, xy, 'Q4 aspect 100')
   xy = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.3_wp, 1.2_wp, 1.5_wp, -0.5_wp, 0.8_wp], [2, 4])
   call check_all(form_vem, xy, 'VEM general quad')
   call check_all(form_fem, xy, 'Q4 general quad')
   ! collinear (hanging) vertices
   xy = reshape([0.0_wp, 0.0_wp, 0.5_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.5_wp, &
                 1.0_wp, 1.0_wp, 0.5_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp], [2, 8])
   call check_all(form_vem, xy, 'VEM square with 4 midpoints')
   xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.5_wp, 1.0_wp, 1.0_wp, &
                 0.0_wp, 1.0_wp], [2, 5])
   call check_all(form_vem, xy, 'VEM square with 1 midpoint')
   xy = reshape([0.0_wp, 0.0_wp, 0.2_wp, 0.0_wp, 0.7_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
                 0.3_wp, 0.8_wp], [2, 5])
   call check_all(form_vem, xy, 'VEM triangle with 2 collinear')
   xy = reshape([0.0_wp, 0.0_wp, 0.1_wp, 0.0_wp, 0.15_wp, 0.0_wp, 1.5_wp, 0.0_wp, &
                 2.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 7])
   call check_all(form_vem, xy, 'VEM rectangle with 3 collinear')
   ! 20 crowded collinear vertices on one side of a square (negative load weights)
   deallocate (xy)
   allocate (xy(2, 24))
   xy(:, 1) = [0.0_wp, 0.0_wp]
   do n = 1, 20
      xy(:, 1 + n) = [0.005_wp*n, 0.0_wp]
   end do
   xy(:, 22:24) = reshape([1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 3])
   call check_all(form_vem, xy, 'VEM square with 20 crowded collinear')
   ! sides of 1e-6 of the diameter
   xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp - 1.0e-6_wp, &
                 1.0_wp - 1.0e-6_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 5])
   call check_all(form_vem, xy, 'VEM square with 1e-6 corner cut')
   xy = reshape([1.0_wp, 0.0_wp, 0.5_wp, 0.8660254_wp, -0.5_wp, 0.8660254_wp, -1.0_wp, 0.0_wp, &
                 -0.5_wp, -0.8660254_wp, 0.5_wp, -0.8660254_wp, 0.5_wp + 2.0e-6_wp, -0.8660254_wp], &
                [2, 7])
   call check_all(form_vem, xy, 'VEM hexagon with 1e-6 side')
   xy = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, &
                 1.0_wp, 1.0_wp + 2.0e-6_wp, 1.0_wp - 1.0e-6_wp, 1.0_wp + 2.0e-6_wp, &
                 1.0_wp - 1.0e-6_wp, 2.0_wp, 0.0_wp, 2.0_wp], [2, 8])
   call t%check(polygon_is_simple(xy), 'L with 1e-6 step is simple')
   call check_all(form_vem, xy, 'VEM L-shape with 1e-6 step')

   ! every cell of the test meshes other tests run on
   call dual_polymesh(4, 0.3_wp, 3, xm, ptr, conn, median=.true.)
   do e = 1, size(ptr) - 1
      call check_all(form_vem, xm(:, conn(ptr(e):ptr(e + 1) - 1)), 'VEM median-dual cell')
   end do
   call hanging_quad_grid(3, 3, xm, ptr, conn)
   do e = 1, size(ptr) - 1
      call check_all(form_vem, xm(:, conn(ptr(e):ptr(e + 1) - 1)), 'VEM hanging-grid cell')
   end do

   ! 2. FEM quads (convex, non-degenerate) and triangles
   do rep = 1, 20
      call random_convex_polygon(4, state, xy)
      call check_all(form_fem, xy, 'Q4 random convex')
      call check_all(form_vem, xy, 'VEM random convex quad')
      call random_convex_polygon(3, state, xy)
      call check_all(form_fem, xy, 'CST random')
      call check_vem_equals_cst(xy)
   end do

   call check_invariance()
   call check_info_codes()

   write (*, '(a,i0,a)') 'stiffness checks on ', ncount, ' element/material cases'
   write (*, '(a,es10.3,a)') 'smallest lambda_4/lambda_max: ', worst_pos, ' ('//worst_label//')'
   write (*, '(a,es10.3,a)') 'smallest lambda_4/lambda_max, VEM: ', worst_vem, ' ('//worst_vem_label//')'
   write (*, '(a,es10.3)') 'largest |lambda_3|/lambda_max: ', worst_zero
   call t%finish()

contains

   !> Small random moves of the vertices (amplitude a), keeping the shape simple.
   subroutine jitter(p, a)
      real(wp), intent(inout) :: p(:, :)
      real(wp), intent(in) :: a
      real(wp) :: r
      integer :: k, c
      do k = 1, size(p, 2)
         do c = 1, 2
            call rng_uniform(state, r)
            p(c, k) = p(c, k) + a*(2.0_wp*r - 1.0_wp)
         end do
      end do
   end subroutine jitter

   !> All checks for one shape, for plane strain (nu 0.3 and 0.49) and plane stress.
   subroutine check_all(form, p, what)
      integer, intent(in) :: form
      real(wp), intent(in) :: p(:, :)
      character(len=*), intent(in) :: what
      real(wp) :: d(3, 3)
      call elastic_matrix(young, 0.3_wp, plane_strain, d)
      call check_one(form, p, d, what//' plane strain')
      call elastic_matrix(young, 0.49_wp, plane_strain, d)
      call check_one(form, p, d, what//' plane strain nu=0.49')
      call elastic_matrix(young, 0.3_wp, plane_stress, d)
      call check_one(form, p, d, what//' plane stress')
   end subroutine check_all

   subroutine check_one(form, p, d, what)
      integer, intent(in) :: form
      real(wp), intent(in) :: p(:, :), d(3, 3)
      character(len=*), intent(in) :: what
      real(wp), allocatable :: ke(:, :), work(:), a(:, :), lam(:), lwork(:), u(:), f(:)
      real(wp) :: kmax, g(2, 2), c(2), eps(3), sig(3), sig_h(3), smat(2, 2), ln(2), xbar(2)
      integer :: n, info, k, j, m, rep

      n = size(p, 2)
      m = 2*n
      ncount = ncount + 1
      allocate (ke(m, m), work(element_workspace_size(n)), a(m, m), lam(m), lwork(64*m), u(m), f(m))
      call element_stiffness(form, p, d, thick, ke, work, info)
      call t%equal(info, 0, what//': info')
      if (info /= 0) return
      kmax = maxval(abs(ke))
      call t%check(maxval(abs(ke - transpose(ke))) <= tol_sym*kmax, what//': symmetric')

      a = ke
      call dsyev('N', 'U', m, a, m, lam, lwork, size(lwork), info)
      call t%equal(info, 0, what//': dsyev')
      call t%check(maxval(abs(lam(1:3))) < tol_zero*lam(m), what//': 3 zero eigenvalues')
      call t%check(lam(4) > tol_pos*lam(m), what//': 4th eigenvalue positive')
      call t%check(lam(1) >= -tol_zero*lam(m), what//': positive semi-definite')
      if (lam(4)/lam(m) < worst_pos) worst_label = what
      if (form == form_vem .and. lam(4)/lam(m) < worst_vem) then
         worst_vem = lam(4)/lam(m)
         worst_vem_label = what
      end if
      worst_pos = min(worst_pos, lam(4)/lam(m))
      worst_zero = max(worst_zero, maxval(abs(lam(1:3)))/lam(m))

      ! rigid modes: two translations and a rotation about the vertex mean
      xbar = sum(p, dim=2)/n
      do k = 1, 3
         do j = 1, n
            select case (k)
            case (1)
               u(2*j - 1:2*j) = [1.0_wp, 0.0_wp]
            case (2)
               u(2*j - 1:2*j) = [0.0_wp, 1.0_wp]
            case (3)
               u(2*j - 1:2*j) = [-(p(2, j) - xbar(2)), p(1, j) - xbar(1)]
            end select
         end do
         call t%check(maxval(abs(matmul(ke, u))) <= tol_cons*kmax*maxval(abs(u)), &
                      what//': rigid mode in null space')
      end do

      ! random linear fields u = c + G x: K u against the nodal forces of the
      ! constant stress, assembled side by side (l n = (dy, -dx) for a
      ! counter-clockwise side), and the recovered stress against D eps(G)
      do rep = 1, 3
         do k = 1, 2
            call rng_uniform(state, c(k))
            do j = 1, 2
               call rng_uniform(state, g(k, j))
            end do
         end do
         g = 2.0_wp*g - 1.0_wp
         do j = 1, n
            u(2*j - 1:2*j) = c + matmul(g, p(:, j))
         end do
         eps = [g(1, 1), g(2, 2), g(1, 2) + g(2, 1)]
         sig = matmul(d, eps)
         smat = reshape([sig(1), sig(3), sig(3), sig(2)], [2, 2])
         f = 0.0_wp
         do j = 1, n
            k = modulo(j, n) + 1
            ln = [p(2, k) - p(2, j), -(p(1, k) - p(1, j))]
            f(2*j - 1:2*j) = f(2*j - 1:2*j) + 0.5_wp*thick*matmul(smat, ln)
            f(2*k - 1:2*k) = f(2*k - 1:2*k) + 0.5_wp*thick*matmul(smat, ln)
         end do
         call t%check(maxval(abs(matmul(ke, u) - f)) <= tol_cons*kmax*maxval(abs(u)), &
                      what//': K u_lin = consistent nodal forces')
         call element_stress(form, p, d, u, work, sig_h)
         call t%check(maxval(abs(sig_h - sig)) <= tol_cons*maxval(abs(d))*maxval(abs(g)), &
                      what//': stress of a linear field')
      end do
   end subroutine check_one

   !> On a triangle the k = 1 virtual space is the linear space, so the
   !> stabilisation vanishes and the VEM must coincide with the CST.
   subroutine check_vem_equals_cst(p)
      real(wp), intent(in) :: p(:, :)
      real(wp) :: d(3, 3), kv(6, 6), kf(6, 6), work(element_workspace_size(3))
      integer :: info
      call elastic_matrix(young, 0.3_wp, plane_strain, d)
      call element_stiffness(form_vem, p, d, thick, kv, work, info)
      call element_stiffness(form_fem, p, d, thick, kf, work, info)
      ! both are rounding-level (~1e-15) away from the exact matrix
      call t%check(maxval(abs(kv - kf)) <= 1.0e-13_wp*maxval(abs(kf)), 'VEM on a triangle = CST')
   end subroutine check_vem_equals_cst

   !> VEM stiffness unchanged by translation and uniform scaling (2D elasticity
   !> is scale-free) and rotated with the element: K(Rx) = Q K(x) Q^T, Q =
   !> diag(R).  1e-12: translating by ~40 changes coordinates by ~40 eps.
   subroutine check_invariance()
      real(wp), allocatable :: p(:, :), p2(:, :), k0(:, :), k1(:, :), q(:, :), work(:)
      real(wp) :: d(3, 3), rot(2, 2), s
      integer :: rep, n, info, j, ks
      call elastic_matrix(young, 0.3_wp, plane_stress, d)
      do rep = 1, 12
         n = 3 + modulo(rep, 8)
         if (modulo(rep, 2) == 0) then
            call random_convex_polygon(n, state, p)
         else
            call random_star_polygon(max(n, 4), state, p)
            n = size(p, 2)
         end if
         if (allocated(k0)) deallocate (k0, k1, q, work)
         allocate (k0(2*n, 2*n), k1(2*n, 2*n), q(2*n, 2*n), work(element_workspace_size(n)))
         call element_stiffness(form_vem, p, d, thick, k0, work, info)
         p2 = p
         p2(1, :) = p2(1, :) + 37.5_wp
         p2(2, :) = p2(2, :) - 12.25_wp
         call element_stiffness(form_vem, p2, d, thick, k1, work, info)
         call t%check(maxval(abs(k1 - k0)) <= 1.0e-12_wp*maxval(abs(k0)), 'VEM translation invariance')
         do ks = 1, 2
            s = merge(1.0e3_wp, 1.0e-3_wp, ks == 1)
            p2 = s*p
            call element_stiffness(form_vem, p2, d, thick, k1, work, info)
            call t%check(maxval(abs(k1 - k0)) <= 1.0e-12_wp*maxval(abs(k0)), 'VEM scaling invariance')
         end do
         rot = reshape([cos(0.7_wp), sin(0.7_wp), -sin(0.7_wp), cos(0.7_wp)], [2, 2])
         p2 = matmul(rot, p)
         q = 0.0_wp
         do j = 1, n
            q(2*j - 1:2*j, 2*j - 1:2*j) = rot
         end do
         call element_stiffness(form_vem, p2, d, thick, k1, work, info)
         call t%check(maxval(abs(k1 - matmul(q, matmul(k0, transpose(q))))) <= 1.0e-12_wp*maxval(abs(k0)), &
                      'VEM rotation equivariance')
         ! thickness and Young's modulus enter linearly, consistency and stabilisation alike
         call element_stiffness(form_vem, p, 3.0_wp*d, 2.0_wp*thick, k1, work, info)
         call t%check(maxval(abs(k1 - 6.0_wp*k0)) <= 1.0e-13_wp*maxval(abs(k1)), 'VEM linear in E and t')
         call t%check(polygon_diameter(p) > 0.0_wp, 'diameter')
      end do
   end subroutine check_invariance

   subroutine check_info_codes()
      real(wp) :: d(3, 3), k8(8, 8), k10(10, 10), work(element_workspace_size(5))
      real(wp), allocatable :: p(:, :)
      integer :: info
      call elastic_matrix(young, 0.3_wp, plane_stress, d)
      ! clockwise square: non-positive area for every formulation
      p = reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 0.0_wp], [2, 4])
      call element_stiffness(form_vem, p, d, thick, k8, work, info)
      call t%equal(info, 1, 'clockwise VEM: info 1')
      call element_stiffness(form_fem, p, d, thick, k8, work, info)
      call t%equal(info, 1, 'clockwise Q4: info 1')
      ! dart: positive area but folded isoparametric map
      p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.5_wp, 0.2_wp], [2, 4])
      call element_stiffness(form_fem, p, d, thick, k8, work, info)
      call t%equal(info, 3, 'dart Q4: info 3')
      call element_stiffness(form_vem, p, d, thick, k8, work, info)
      call t%equal(info, 0, 'dart as VEM: info 0')
      ! FEM on a pentagon
      p = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.5_wp, 0.5_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 5])
      call element_stiffness(form_fem, p, d, thick, k10, work, info)
      call t%equal(info, 2, 'FEM pentagon: info 2')
      call t%check(.not. any(abs(k10) > 0.0_wp), 'rejected element has ke = 0')
   end subroutine check_info_codes
end program test_element_stiffness
