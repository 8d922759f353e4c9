!> Convergence on a manufactured smooth solution over a sequence of polygon
!> meshes: observed rates near 2 in the (discrete) L2 norm of the displacement
!> and near 1 in the energy norm, for VEM on perturbed barycentric-dual polygon
!> meshes, and for the FEM quad on perturbed quads as a baseline.
!>   u_x = sin(pi x) sin(pi y),  u_y = x^2 y   on the unit square, plane strain,
!>   body force b = -div sigma = -(mu lap u + (lambda + mu) grad div u).
program test_convergence
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, plane_strain, form_vem, form_fem
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element, only: element_load_weights, element_stress, element_workspace_size
   use vemcontact_element_geometry, only: polygon_centroid, polygon_signed_area
   use vemcontact_driver_linear, only: linear_system_t, ordering_auto
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_test_model, only: make_model, boundary_mask
   use vemcontact_test_polymesh, only: dual_polymesh, quad_grid
   implicit none
   real(wp), parameter :: pi = acos(-1.0_wp), young = 1.0_wp, nu = 0.3_wp
   real(wp), parameter :: lam = young*nu/((1 + nu)*(1 - 2*nu)), mu = young/(2*(1 + nu))
   integer, parameter :: nmesh = 4
   integer, parameter :: sizes(nmesh) = [8, 16, 32, 64]
   type(checker_t) :: t
   real(wp) :: el2(nmesh), een(nmesh), h(nmesh), rate
   real(wp), allocatable :: x(:, :)
   integer(ip), allocatable :: ptr(:), conn(:)
   integer :: k, family
   character(len=40) :: name

   do family = 1, 3
      do k = 1, nmesh
         if (family == 1) then
            call dual_polymesh(sizes(k), 0.3_wp, 5, x, ptr, conn)
            call errors(x, ptr, conn, form_vem, el2(k), een(k))
            name = 'VEM, dual polygon meshes'
         else if (family == 2) then
            ! 12-gons, most of them non-convex (at 0.3 a few cells of the finer
            ! meshes fold over themselves, which the validation rightly refuses)
            call dual_polymesh(sizes(k), 0.2_wp, 5, x, ptr, conn, median=.true.)
            call errors(x, ptr, conn, form_vem, el2(k), een(k))
            name = 'VEM, non-convex median-dual meshes'
         else
            call quad_grid(sizes(k), sizes(k), 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.3_wp, 5, x, ptr, conn)
            call errors(x, ptr, conn, form_fem, el2(k), een(k))
            name = 'FEM, perturbed quads'
         end if
         h(k) = 1.0_wp/sizes(k)
         print '(a,i4,2es12.4)', trim(name)//': n, L2 error, energy error: ', sizes(k), el2(k), een(k)
      end do
      if (any(el2 >= huge(1.0_wp))) cycle
      ! rates from the two finest meshes; the asymptotic values are 2 and 1, the
      ! bounds leave room for the pre-asymptotic effect of the random perturbation
      rate = log(el2(nmesh - 1)/el2(nmesh))/log(h(nmesh - 1)/h(nmesh))
      print '(a,f6.3)', trim(name)//': L2 rate ', rate
      call t%check(rate > 1.8_wp .and. rate < 2.3_wp, trim(name)//': L2 rate near 2')
      rate = log(een(nmesh - 1)/een(nmesh))/log(h(nmesh - 1)/h(nmesh))
      print '(a,f6.3)', trim(name)//': energy rate ', rate
      call t%check(rate > 0.9_wp .and. rate < 1.2_wp, trim(name)//': energy rate near 1')
      call t%check(all(el2(2:) < el2(:nmesh - 1)) .and. all(een(2:) < een(:nmesh - 1)), &
                   trim(name)//': errors decrease monotonically')
   end do
   call t%finish()

contains

   pure function exact_u(p) result(u)
      real(wp), intent(in) :: p(2)
      real(wp) :: u(2)
      u = [sin(pi*p(1))*sin(pi*p(2)), p(1)**2*p(2)]
   end function exact_u

   !> Strain (xx, yy, engineering xy).
   pure function exact_strain(p) result(eps)
      real(wp), intent(in) :: p(2)
      real(wp) :: eps(3)
      eps = [pi*cos(pi*p(1))*sin(pi*p(2)), p(1)**2, pi*sin(pi*p(1))*cos(pi*p(2)) + 2*p(1)*p(2)]
   end function exact_strain

   pure function body_force(p) result(b)
      real(wp), intent(in) :: p(2)
      real(wp) :: b(2), ss, cc
      ss = sin(pi*p(1))*sin(pi*p(2))
      cc = cos(pi*p(1))*cos(pi*p(2))
      b(1) = -(mu*(-2*pi**2*ss) + (lam + mu)*(-pi**2*ss + 2*p(1)))
      b(2) = -(mu*(2*p(2)) + (lam + mu)*(pi**2*cc))
   end function body_force

   subroutine errors(x, ptr, conn, form, el2, een)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: ptr(:), conn(:)
      integer, intent(in) :: form
      real(wp), intent(out) :: el2, een
      type(model_t) :: m
      type(linear_system_t) :: sys
      type(load_state_t) :: st
      type(error_t), allocatable :: error
      real(wp), allocatable :: u(:), work(:), w(:), xy(:, :), ue(:)
      logical, allocatable :: onb(:)
      real(wp) :: d(3, 3), c(2), area, sig(3), ds(3), de(3), tarea, mid(2)
      integer :: e, n, i, j, nmax
      integer(ip) :: node
      call make_model(x, ptr, conn, young, nu, plane_strain, form, 1.0_wp, m)
      call elastic_matrix(young, nu, plane_strain, d)
      nmax = maxval(ptr(2:) - ptr(:size(ptr) - 1))
      allocate (work(element_workspace_size(nmax)), w(nmax), xy(2, nmax), ue(2*nmax))
      allocate (u(2*m%nnode))
      allocate (st%fixed(2*m%nnode), st%prescribed(2*m%nnode), st%force(2*m%nnode), st%dload(0))
      onb = boundary_mask(m%nnode, ptr, conn)
      st%fixed(1::2) = onb
      st%fixed(2::2) = onb
      do i = 1, m%nnode
         st%prescribed(2*i - 1:2*i) = exact_u(x(:, i))
      end do
      ! body force sampled at the centroid, distributed with the load weights:
      ! first-order accurate, which keeps the optimal rates of k = 1
      st%force = 0.0_wp
      do e = 1, m%nelem
         n = ptr(e + 1) - ptr(e)
         xy(:, :n) = x(:, conn(ptr(e):ptr(e + 1) - 1))
         call polygon_centroid(xy(:, :n), c)
         call element_load_weights(form, xy(:, :n), work, w(:n))
         do i = 1, n
            node = conn(ptr(e) + i - 1)
            st%force(2*node - 1:2*node) = st%force(2*node - 1:2*node) + w(i)*body_force(c)
         end do
      end do
      call sys%setup(m, ordering_auto, error)
      if (.not. allocated(error)) call sys%solve_state(m, st, u, error)
      if (allocated(error)) then
         call t%check(.false., 'solve: '//error%message)
         el2 = huge(1.0_wp); een = huge(1.0_wp)
         return
      end if
      ! discrete L2 norm: vertex average of |u - u_h|^2 per cell; energy norm of the
      ! strain error integrated over each cell
      el2 = 0; een = 0
      do e = 1, m%nelem
         n = ptr(e + 1) - ptr(e)
         do i = 1, n
            node = conn(ptr(e) + i - 1)
            xy(:, i) = x(:, node)
            ue(2*i - 1:2*i) = u(2*node - 1:2*node)
         end do
         area = polygon_signed_area(xy(:, :n))
         call polygon_centroid(xy(:, :n), c)
         do i = 1, n
            el2 = el2 + area/n*sum((ue(2*i - 1:2*i) - exact_u(xy(:, i)))**2)
         end do
         call element_stress(form, xy(:, :n), d, ue(:2*n), work, sig)
         ! energy norm of eps(u) - eps_h over the cell: signed fan of triangles from
         ! the centroid (an exact decomposition of any simple polygon, convex or
         ! not) with the 3-point edge-midpoint rule (degree 2) on each triangle
         call solve3(d, sig, de)
         do i = 1, n
            associate (p => xy(:, i), q => xy(:, mod(i, n) + 1))
               tarea = 0.5_wp*((p(1) - c(1))*(q(2) - c(2)) - (q(1) - c(1))*(p(2) - c(2)))
               do j = 1, 3
                  if (j == 1) mid = 0.5_wp*(p + q)
                  if (j == 2) mid = 0.5_wp*(c + p)
                  if (j == 3) mid = 0.5_wp*(c + q)
                  ds = exact_strain(mid) - de
                  een = een + tarea/3*dot_product(ds, matmul(d, ds))
               end do
            end associate
         end do
      end do
      el2 = sqrt(el2)
      een = sqrt(een)
   end subroutine errors

   !> Solve the 3x3 system d*y = b (Cramer's rule; d is a well-conditioned elasticity matrix).
   pure subroutine solve3(a, b, y)
      real(wp), intent(in) :: a(3, 3), b(3)
      real(wp), intent(out) :: y(3)
      real(wp) :: det, m(3, 3)
      integer :: j
      det = a(1, 1)*(a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)) - a(1, 2)*(a(2, 1)*a(3, 3) - a(2, 3)*a(3, 1)) &
            + a(1, 3)*(a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1))
      do j = 1, 3
         m = a
         m(:, j) = b
         y(j) = (m(1, 1)*(m(2, 2)*m(3, 3) - m(2, 3)*m(3, 2)) - m(1, 2)*(m(2, 1)*m(3, 3) - m(2, 3)*m(3, 1)) &
                 + m(1, 3)*(m(2, 1)*m(3, 2) - m(2, 2)*m(3, 1)))/det
      end do
   end subroutine solve3
end program test_convergence
