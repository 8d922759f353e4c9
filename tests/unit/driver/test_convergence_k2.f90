!> Convergence of the k = 2 virtual element on Lloyd-Voronoi meshes of the unit
!> square (256, 1024, 4096 cells; made by vctools from tests/data/voronoi/
!> unit_square.toml into the directory VC_VORONOI_DIR before this test runs),
!> side nodes added at the middles: observed rates near 3 in the L2 norm of the displacement and near 2
!> in the energy norm (the issue's targets: within 2.8-3.2 and 1.8-2.2).
!>   u = grad(e^x sin y) = (e^x sin y, e^x cos y): div u = 0 and lap u = 0, so it
!>   solves Navier's equations without body force for every material, plane
!>   strain and plane stress; u prescribed at every boundary node.
!> Nearly incompressible plane strain (nu = 0.4999; u is divergence-free, so
!> the exact solution does not depend on nu): the same rates, and errors no
!> larger than at nu = 0.3 (within 20 %): no volumetric locking.
!> L2: the nodal error weighted by |E|/(2n) at each of an element's 2n nodes.
!> Energy: integral of (eps - eps_h)^T D (eps - eps_h) with eps_h the element's
!> projected (linear) strain, on the fan of triangles from the centroid with
!> the 3-point edge-midpoint rule (the projected stress is linear: its value at
!> the side node, at the centroid (its mean) and half-way between are exact).
program test_convergence_k2
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, plane_strain, plane_stress, form_vem
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element_vem2, only: vem2_workspace_size, vem2_stress
   use vemcontact_element_geometry, only: polygon_centroid, polygon_signed_area
   use vemcontact_deck_reader, only: read_deck
   use vemcontact_driver_linear, only: linear_system_t, ordering_auto
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_test_model, only: make_model
   use vemcontact_test_second_order, only: add_side_nodes, boundary_mask2
   implicit none
   real(wp), parameter :: young = 1.0_wp
   integer, parameter :: nmesh = 3
   integer, parameter :: cells(nmesh) = [256, 1024, 4096]
   type(checker_t) :: t
   real(wp) :: el2(nmesh), een(nmesh), h(nmesh), rate, nu, een_ref
   integer :: k, plane, icase
   character(len=:), allocatable :: dir
   character(len=512) :: path
   character(len=64) :: name
   integer :: nlen, stat

   call get_environment_variable('VC_VORONOI_DIR', length=nlen, status=stat)
   if (stat /= 0) then
      print '(a)', 'VC_VORONOI_DIR is not set: run this test through CTest (it makes the meshes first)'
      stop 1
   end if
   allocate (character(len=nlen) :: dir)
   call get_environment_variable('VC_VORONOI_DIR', dir)
   een_ref = 0
   do icase = 1, 3
      plane = merge(plane_stress, plane_strain, icase == 2)
      nu = merge(0.4999_wp, 0.3_wp, icase == 3)
      name = merge('k = 2 VEM, Voronoi, plane strain', 'k = 2 VEM, Voronoi, plane stress', plane == plane_strain)
      if (icase == 3) name = 'k = 2 VEM, Voronoi, plane strain, nu = 0.4999'
      do k = 1, nmesh
         call wrapper_deck(dir, cells(k), path)
         call errors(trim(path), plane, nu, el2(k), een(k))
         h(k) = 1.0_wp/sqrt(real(cells(k), wp))
         print '(a,i6,2es12.4)', trim(name)//': cells, L2 error, energy error: ', cells(k), el2(k), een(k)
      end do
      if (any(el2 >= huge(1.0_wp))) cycle
      ! rates from the two finest meshes (h ~ cells^-1/2, exactly halved)
      rate = log(el2(nmesh - 1)/el2(nmesh))/log(h(nmesh - 1)/h(nmesh))
      print '(a,f6.3)', trim(name)//': L2 rate ', rate
      call t%check(rate > 2.8_wp .and. rate < 3.2_wp, trim(name)//': L2 rate near 3 (2.8-3.2)')
      rate = log(een(nmesh - 1)/een(nmesh))/log(h(nmesh - 1)/h(nmesh))
      print '(a,f6.3)', trim(name)//': energy rate ', rate
      call t%check(rate > 1.8_wp .and. rate < 2.2_wp, trim(name)//': energy rate near 2 (1.8-2.2)')
      call t%check(all(el2(2:) < el2(:nmesh - 1)) .and. all(een(2:) < een(:nmesh - 1)), &
                   trim(name)//': errors decrease monotonically')
      if (icase == 1) een_ref = een(nmesh)
      if (icase == 3) call t%check(een(nmesh) <= 1.2_wp*een_ref, &
                                   trim(name)//': energy error within 20 % of nu = 0.3 (no locking)')
   end do
   call t%finish()

contains

   !> A deck around the mesh file unit_square_c<cells>.inp (which has only the
   !> mesh): material, section and an empty step, for the deck reader.
   subroutine wrapper_deck(dir, ncell, path)
      character(len=*), intent(in) :: dir
      integer, intent(in) :: ncell
      character(len=*), intent(out) :: path
      integer :: u
      character(len=32) :: mesh
      write (mesh, '(a,i0,a)') 'unit_square_c', ncell, '.inp'
      write (path, '(a,i0,a)') dir//'/k2_c', ncell, '.inp'
      open (newunit=u, file=trim(path), status='replace', action='write')
      write (u, '(a)') '*INCLUDE, INPUT='//trim(mesh), '*MATERIAL, NAME=M', '*ELASTIC', '1.0, 0.3', &
         '*SOLID SECTION, ELSET=SQ, MATERIAL=M', '1.0', '*STEP', '*STATIC', '*END STEP'
      close (u)
   end subroutine wrapper_deck

   pure function exact_u(p) result(u)
      real(wp), intent(in) :: p(2)
      real(wp) :: u(2)
      u = exp(p(1))*[sin(p(2)), cos(p(2))]
   end function exact_u

   !> Strain (xx, yy, engineering xy) of exact_u.
   pure function exact_strain(p) result(eps)
      real(wp), intent(in) :: p(2)
      real(wp) :: eps(3)
      eps = exp(p(1))*[sin(p(2)), -sin(p(2)), 2*cos(p(2))]
   end function exact_strain

   subroutine errors(path, plane, nu, el2, een)
      character(len=*), intent(in) :: path
      integer, intent(in) :: plane
      real(wp), intent(in) :: nu
      real(wp), intent(out) :: el2, een
      type(model_t) :: deck, m
      type(linear_system_t) :: sys
      type(load_state_t) :: st
      type(error_t), allocatable :: error
      real(wp), allocatable :: x(:, :), u(:), work(:), xy(:, :), ue(:), sn(:, :)
      integer(ip), allocatable :: ptr(:), conn(:)
      logical, allocatable :: onb(:)
      real(wp) :: d(3, 3), c(2), area, sig(3), de(3), dc(3), dp(3), dq(3), tarea, mid(2), ds(3)
      integer :: e, n, nn, i, j, nmax
      integer(ip) :: node
      el2 = huge(1.0_wp)
      een = huge(1.0_wp)
      call read_deck(path, deck, error)
      call t%check(.not. allocated(error), 'read '//path)
      if (allocated(error)) then
         print '(a)', error%message
         return
      end if
      call add_side_nodes(deck%x, deck%elem_ptr, deck%elem_conn, x, ptr, conn)
      call make_model(x, ptr, conn, young, nu, plane, form_vem, 1.0_wp, m, order=2)
      call elastic_matrix(young, nu, plane, d)
      nmax = maxval(ptr(2:) - ptr(:size(ptr) - 1))
      allocate (work(vem2_workspace_size(nmax)), xy(2, nmax), ue(2*nmax), sn(3, nmax))
      allocate (u(2*m%nnode), st%fixed(2*m%nnode), st%prescribed(2*m%nnode), st%force(2*m%nnode), st%dload(0))
      onb = boundary_mask2(int(m%nnode), ptr, conn)
      st%fixed(1::2) = onb
      st%fixed(2::2) = onb
      do i = 1, int(m%nnode)
         st%prescribed(2*i - 1:2*i) = exact_u(x(:, i))
      end do
      st%force = 0.0_wp
      call sys%setup(m, ordering_auto, error)
      if (.not. allocated(error)) call sys%solve_state(m, st, u, error)
      call t%check(.not. allocated(error), 'solve '//path)
      if (allocated(error)) return
      el2 = 0
      een = 0
      do e = 1, int(m%nelem)
         nn = ptr(e + 1) - ptr(e)
         n = nn/2
         do i = 1, nn
            node = conn(ptr(e) + i - 1)
            xy(:, i) = x(:, node)
            ue(2*i - 1:2*i) = u(2*node - 1:2*node)
         end do
         area = polygon_signed_area(xy(:, :n))
         call polygon_centroid(xy(:, :n), c)
         do i = 1, nn
            el2 = el2 + area/nn*sum((ue(2*i - 1:2*i) - exact_u(xy(:, i)))**2)
         end do
         call vem2_stress(xy(:, :nn), d, 1.0_wp, ue(:2*nn), work, sig, signode=sn(:, :nn))
         ! strains of the projected stress: at the centroid (the mean) and at the nodes
         call solve3(d, sig, dc)
         do i = 1, n
            j = mod(i, n) + 1
            call solve3(d, sn(:, i), dp)
            call solve3(d, sn(:, j), dq)
            call solve3(d, sn(:, n + i), de)
            associate (p => xy(:, i), q => xy(:, j))
               tarea = 0.5_wp*((p(1) - c(1))*(q(2) - c(2)) - (q(1) - c(1))*(p(2) - c(2)))
               mid = 0.5_wp*(p + q)
               ds = exact_strain(mid) - de
               een = een + tarea/3*dot_product(ds, matmul(d, ds))
               mid = 0.5_wp*(c + p)
               ds = exact_strain(mid) - 0.5_wp*(dc + dp)
               een = een + tarea/3*dot_product(ds, matmul(d, ds))
               mid = 0.5_wp*(c + q)
               ds = exact_strain(mid) - 0.5_wp*(dc + dq)
               een = een + tarea/3*dot_product(ds, matmul(d, ds))
            end associate
         end do
      end do
      el2 = sqrt(el2)
      een = sqrt(een)
   end subroutine errors

   !> Solve the 3x3 system a*y = b (Cramer's rule; a is a well-conditioned elasticity matrix).
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
end program test_convergence_k2
