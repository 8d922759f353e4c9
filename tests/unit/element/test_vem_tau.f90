!> The VEM stabilisation factor tau (*SOLID SECTION, STABILIZATION=tau):
!>  1. on the unit square the hourglass energy is tau t (D11 + D33)
!>     (docs/vem-formulation.md), so 3/4 of the bilinear element's at tau = 1
!>     and equal to it at tau = 4/3;
!>  2. K(tau) = K(0) + tau (K(1) - K(0)): tau scales the stabilisation only, the
!>     floor included (K(0) is the bare consistency part);
!>  3. the consistency part does not see tau: K(tau) u_lin equals the nodal forces
!>     t sigma q_i of the constant stress for every tau (the patch test);
!>  4. exactly three zero eigenvalues (rigid modes) for every tau > 0;
!>  5. tau passed through element_stiffness gives the same matrix as through
!>     vem_stiffness, and leaving it out is tau = 1 bit for bit.
program test_vem_tau
   use vemcontact_kinds, only: wp, i8
   use vemcontact_model, only: plane_strain, plane_stress, form_vem, form_fem
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element, only: element_workspace_size, element_stiffness
   use vemcontact_element_vem, only: vem_stiffness, vem_tau
   use vemcontact_linalg_lapack, only: dsyev
   use vemcontact_test_polymesh, only: rng_init, random_convex_polygon, random_star_polygon
   use vemcontact_testing, only: checker_t
   implicit none

   !> Tolerances.  The square's energies and K's linearity in tau are sums of
   !> O(n^2) products of entries of size |K|: rounding ~1e-15 |K|, so 1e-12 of
   !> |K| (resp. 1e-13 relative on an energy) is rounding only, while a tau that
   !> missed the floor or touched the consistency part would be off by O(tau - 1).
   !> Zero eigenvalues: rounding ~eps |K| and dsyev is backward stable, so
   !> rigid modes come out at ~1e-15 of the largest; 1e-12 leaves a margin of
   !> 1000.  The fourth eigenvalue on these shapes is >= 1e-3 of the largest at
   !> tau = 1 and scales at worst like tau, so at tau = 1/16 it stays far above
   !> 1e-8 (without stabilisation it is ~1e-16).
   real(wp), parameter :: tol_lin = 1.0e-12_wp, tol_energy = 1.0e-13_wp
   real(wp), parameter :: tol_zero = 1.0e-12_wp, tol_pos = 1.0e-8_wp
   real(wp), parameter :: taus(8) = [1.0_wp/16, 0.125_wp, 0.25_wp, 0.5_wp, 0.75_wp, 1.0_wp, 2.0_wp, 4.0_wp]
   real(wp), parameter :: unit_square(2, 4) = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
                                                       1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
   real(wp), parameter :: young = 2.1e5_wp, thick = 0.25_wp

   type(checker_t) :: t
   real(wp) :: d(3, 3), kv(8, 8), kq(8, 8), hg(8), evem, eq4
   real(wp), allocatable :: work(:), xy(:, :)
   integer(i8) :: state
   integer :: info, k, n, iplane
   character(len=64) :: label

   allocate (work(element_workspace_size(32)))

   ! 1. the square's hourglass mode u_x = (+1, -1, +1, -1) has zero projected
   ! strain, so its energy is pure stabilisation: tau * sum_i s_i(1) = tau t (D11 + D33);
   ! the bilinear element gives (4/3) t (D11 + D33) in every plane and for every nu
   hg = [1.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 0.0_wp]
   do iplane = 1, 2
      call elastic_matrix(young, 0.3_wp, merge(plane_strain, plane_stress, iplane == 1), d)
      call element_stiffness(form_fem, unit_square, d, thick, kq, work, info)
      eq4 = dot_product(hg, matmul(kq, hg))
      do k = 1, size(taus)
         call element_stiffness(form_vem, unit_square, d, thick, kv, work, info, taus(k))
         call t%equal(info, 0, 'square info')
         evem = dot_product(hg, matmul(kv, hg))
         write (label, '(a,f7.4,a,i0)') 'tau=', taus(k), ' plane=', iplane
         call t%close(evem, taus(k)*thick*(d(1, 1) + d(3, 3)), tol_energy, &
                      trim(label)//': square hourglass energy = tau t (D11 + D33)')
         call t%close(evem/eq4, 0.75_wp*taus(k), tol_energy, trim(label)//': VEM/Q4 hourglass = 3 tau/4')
      end do
      call element_stiffness(form_vem, unit_square, d, thick, kv, work, info, 4.0_wp/3.0_wp)
      call t%close(dot_product(hg, matmul(kv, hg)), eq4, tol_energy, 'tau = 4/3: hourglass energy = Q4''s')
   end do

   ! 2.-5. on a range of shapes and materials
   state = rng_init(20250214)
   call elastic_matrix(young, 0.3_wp, plane_strain, d)
   call check_shape(unit_square, d, 'unit square')
   ! a 20 x 8 rectangle, the undistorted element of the paper's example 1
   call check_shape(reshape([0.0_wp, 0.0_wp, 20.0_wp, 0.0_wp, 20.0_wp, 8.0_wp, 0.0_wp, 8.0_wp], [2, 4]), &
                    d, 'rectangle 20 x 8')
   ! example 1 at 2d/b = 4 (shared edge from (4, 0) to (36, 8)): a very skewed quad
   call check_shape(reshape([0.0_wp, 0.0_wp, 4.0_wp, 0.0_wp, 36.0_wp, 8.0_wp, 0.0_wp, 8.0_wp], [2, 4]), &
                    d, 'example-1 quad 2d/b=4')
   do n = 3, 9
      call random_convex_polygon(n, state, xy)
      write (label, '(a,i0)') 'convex n=', n
      call check_shape(xy, d, trim(label))
   end do
   do n = 6, 10, 2
      call random_star_polygon(n, state, xy)
      write (label, '(a,i0)') 'star n=', n
      call check_shape(xy, d, trim(label))
   end do
   ! a vertex between two tiny sides: there the floor sets its weight, and the
   ! floor must scale with tau too (check 2 fails otherwise)
   xy = reshape([0.0_wp, 0.0_wp, 0.5_wp, 0.0_wp, 0.5_wp + 1.0e-4_wp, 1.0e-4_wp, 0.5_wp + 2.0e-4_wp, 0.0_wp, &
                 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 7])
   call check_shape(xy, d, 'tiny sides (floor active)')
   ! nearly incompressible plane strain: lambda is capped in the weights, not in Kc
   call elastic_matrix(young, 0.49_wp, plane_strain, d)
   call random_convex_polygon(6, state, xy)
   call check_shape(xy, d, 'convex n=6 nu=0.49')
   call elastic_matrix(young, 0.0_wp, plane_stress, d)
   call random_convex_polygon(5, state, xy)
   call check_shape(xy, d, 'convex n=5 plane stress nu=0')
   call t%finish()

contains

   subroutine check_shape(p, dm, what)
      real(wp), intent(in) :: p(:, :), dm(3, 3)
      character(len=*), intent(in) :: what
      real(wp), allocatable :: k0(:, :), k1(:, :), kt(:, :), kd(:, :), a(:, :), lam(:), lw(:), u(:), f(:)
      real(wp) :: kmax, eps(3), sig(3), q(2), unorm
      integer :: m, nv, j, kk, inf, im1, ip1
      character(len=24) :: tl
      nv = size(p, 2)
      m = 2*nv
      allocate (k0(m, m), k1(m, m), kt(m, m), kd(m, m), a(m, m), lam(m), lw(64*m), u(m), f(m))
      call vem_stiffness(p, dm, thick, k0, work, inf, 0.0_wp)
      call vem_stiffness(p, dm, thick, k1, work, inf, 1.0_wp)
      call t%equal(inf, 0, what//': info')
      ! 5. no tau = the default vem_tau = 1, bit for bit
      call vem_stiffness(p, dm, thick, kd, work, inf)
      call t%check(all(abs(kd - k1) <= 0.0_wp), what//': tau absent = tau 1 bit for bit')
      call t%check(abs(vem_tau - 1.0_wp) <= 0.0_wp, 'default vem_tau is 1')
      kmax = maxval(abs(k1))
      ! a linear field u = c + G x with a general G: constant strain eps
      eps = [1.3e-3_wp, -0.7e-3_wp, 0.9e-3_wp]
      do j = 1, nv
         u(2*j - 1) = 0.2_wp + eps(1)*p(1, j) + 0.5_wp*(eps(3) + 0.4e-3_wp)*p(2, j)
         u(2*j) = -0.1_wp + 0.5_wp*(eps(3) - 0.4e-3_wp)*p(1, j) + eps(2)*p(2, j)
      end do
      unorm = maxval(abs(u))
      ! consistent nodal forces of the constant stress: f_i = t sigma q_i,
      ! q_i = half the rotated chord from vertex i-1 to vertex i+1 (counter-clockwise)
      sig = matmul(dm, eps)
      do j = 1, nv
         im1 = modulo(j - 2, nv) + 1
         ip1 = modulo(j, nv) + 1
         q = 0.5_wp*[p(2, ip1) - p(2, im1), -(p(1, ip1) - p(1, im1))]
         f(2*j - 1:2*j) = thick*[sig(1)*q(1) + sig(3)*q(2), sig(3)*q(1) + sig(2)*q(2)]
      end do
      do kk = 1, size(taus)
         write (tl, '(a,f7.4)') ' tau=', taus(kk)
         call element_stiffness(form_vem, p, dm, thick, kt, work, inf, taus(kk))
         call t%equal(inf, 0, what//trim(tl)//': info')
         ! 5. through the dispatcher = the kernel
         call vem_stiffness(p, dm, thick, kd, work, inf, taus(kk))
         call t%check(all(abs(kd - kt) <= 0.0_wp), what//trim(tl)//': element_stiffness = vem_stiffness')
         ! 2. linear in tau, floor included
         call t%check(maxval(abs(kt - (k0 + taus(kk)*(k1 - k0)))) <= tol_lin*max(1.0_wp, taus(kk))*kmax, &
                      what//trim(tl)//': K(tau) = K(0) + tau (K(1) - K(0))')
         ! 3. patch test: the stabilisation vanishes on linear fields whatever tau
         call t%check(maxval(abs(matmul(kt, u) - f)) <= tol_lin*max(1.0_wp, taus(kk))*kmax*unorm*m, &
                      what//trim(tl)//': K u_lin = t sigma q (patch test)')
         ! 4. three rigid modes, nothing else singular
         a = kt
         call dsyev('N', 'U', m, a, m, lam, lw, size(lw), inf)
         call t%equal(inf, 0, what//trim(tl)//': dsyev')
         call t%check(maxval(abs(lam(1:3))) < tol_zero*lam(m), what//trim(tl)//': 3 zero eigenvalues')
         call t%check(lam(4) > tol_pos*lam(m), what//trim(tl)//': 4th eigenvalue positive')
      end do
   end subroutine check_shape
end program test_vem_tau
