!> The paper's example 1 (Sun et al. 2022, section 4.1): cantilever L = 40,
!> b = 8, E = 1000, nu = 0, end moment M = 16, two quadrilaterals whose shared
!> edge is skewed by d.  Exact tip deflection M L^2 / (2 E I) = 0.3.
program test_cantilever
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, plane_strain, form_vem, form_fem
   use vemcontact_driver_linear, only: linear_system_t, ordering_auto
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_test_model, only: make_model
   use vemcontact_test_polymesh, only: cantilever_two_quads
   implicit none
   real(wp), parameter :: length = 40, depth = 8, young = 1000, moment = 16
   real(wp), parameter :: exact = moment*length**2/(2*young*depth**3/12)
   integer, parameter :: nd = 9
   real(wp), parameter :: skew(nd) = [0.0_wp, 0.5_wp, 1.0_wp, 1.5_wp, 2.0_wp, 2.5_wp, 3.0_wp, 3.5_wp, 4.0_wp]
   type(checker_t) :: t
   real(wp) :: rv(nd), rf(nd)
   integer :: k

   call t%close(exact, 0.3_wp, 1.0e-14_wp, 'exact tip deflection')
   do k = 1, nd
      rv(k) = tip(skew(k), form_vem)/exact
      rf(k) = tip(skew(k), form_fem)/exact
      print '(a,f4.1,a,f8.5,a,f8.5)', '2d/b = ', skew(k), '  VEM ratio ', rv(k), '  FEM ratio ', rf(k)
   end do
   ! Rectangles (d = 0): the full-integration bilinear quad in pure bending carries
   ! the parasitic shear strain gamma = kappa*x, which raises each element's bending
   ! stiffness by 1 + (G/E)(a/b)^2 (a, b half length and half depth; G/E = 1/2 at
   ! nu = 0): 1 + 0.5*(10/4)^2 = 4.125.  The two elements are in series, so the tip
   ! deflection is the exact one divided by 4.125.  Round-off only: 1e-10.
   call t%close(rf(1), 1.0_wp/4.125_wp, 1.0e-10_wp, 'FEM, 2d/b = 0: shear-locking closed form 1/4.125')
   ! both formulations are stiff (ratio below 1) and lose accuracy with distortion
   call t%check(all(rv > 0.0_wp .and. rv < 1.0_wp) .and. all(rf > 0.0_wp .and. rf < 1.0_wp), 'ratios in (0,1)')
   call t%check(all(rv(2:) < rv(:nd - 1)) .and. all(rf(2:) < rf(:nd - 1)), 'accuracy falls with distortion')
   ! the paper's finding: beyond 2d/b = 1 VEM is the more accurate of the two
   call t%check(all(rv(3:) > rf(3:)), 'VEM more accurate than FEM for 2d/b >= 1')
   call t%finish()

contains

   !> Tip deflection: mean vertical displacement of the two end nodes.
   real(wp) function tip(ratio, form)
      real(wp), intent(in) :: ratio
      integer, intent(in) :: form
      real(wp), allocatable :: x(:, :), u(:)
      integer(ip), allocatable :: ptr(:), conn(:)
      type(model_t) :: m
      type(linear_system_t) :: sys
      type(load_state_t) :: st
      type(error_t), allocatable :: error
      integer :: i, n
      integer :: ibl, itl, ibr, itr
      call cantilever_two_quads(length, depth, 0.5_wp*ratio*depth, x, ptr, conn)
      call make_model(x, ptr, conn, young, 0.0_wp, plane_strain, form, 1.0_wp, m)
      n = m%nnode
      allocate (u(2*n), st%fixed(2*n), st%prescribed(2*n), st%force(2*n), st%dload(0))
      st%fixed = .false.; st%prescribed = 0; st%force = 0
      ibl = 0; itl = 0; ibr = 0; itr = 0
      do i = 1, n
         if (abs(x(1, i)) < 1e-12_wp .and. abs(x(2, i)) < 1e-12_wp) ibl = i
         if (abs(x(1, i)) < 1e-12_wp .and. abs(x(2, i) - depth) < 1e-12_wp) itl = i
         if (abs(x(1, i) - length) < 1e-12_wp .and. abs(x(2, i)) < 1e-12_wp) ibr = i
         if (abs(x(1, i) - length) < 1e-12_wp .and. abs(x(2, i) - depth) < 1e-12_wp) itr = i
      end do
      ! clamp: x at both fixed-end nodes, y at the bottom one; couple +-M/b at the free end
      st%fixed([2*ibl - 1, 2*ibl, 2*itl - 1]) = .true.
      st%force(2*ibr - 1) = moment/depth
      st%force(2*itr - 1) = -moment/depth
      call sys%setup(m, ordering_auto, error)
      if (.not. allocated(error)) call sys%solve_state(m, st, u, error)
      call t%check(.not. allocated(error), 'solve')
      tip = 0.5_wp*(u(2*ibr) + u(2*itr))
   end function tip
end program test_cantilever
