!> Second-order elements through the whole solution path (model, assembly,
!> loads, CHOLMOD, stress recovery):
!>  - the paper's example 1 (cantilever under an end moment, two elements whose
!>    shared side is skewed by 2d/b in [0, 4.875]): pure bending is a quadratic
!>    field, so the k = 2 virtual element gives the exact tip deflection at
!>    every skew; the 8-node quad only on rectangles (its map is not affine
!>    once skewed);
!>  - patch tests with a quadratic field and its constant body force (a *DLOAD
!>    GRAV record): k = 2 VEM on dual, non-convex and collinear-corner meshes,
!>    the 6-node triangle on perturbed triangles, the 8-node quad on rectangles;
!>    the recovered element stress is the exact mean stress, and each element's
!>    stress at its nodes the exact nodal stress; the same for the strains E
!>    (element_strains, the same recovery); the reactions RF = K u - f at the
!>    constrained boundary balance the applied body force (resultant and moment,
!>    the body force's resultant computed independently from the element areas);
!>  - uniform pressure on second-order sides (consistent 1/6, 4/6, 1/6 loads):
!>    the exact uniform stress state on a block;
!>  - hydrostatic pressure cut by its free surface on a second-order side gives
!>    the same resultant and moment as on the first-order side.
program test_second_order
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, dload_t, plane_strain, plane_stress, form_vem, form_fem, &
                               dload_grav, dload_pressure, dload_hydrostatic
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_driver_linear, only: linear_system_t, ordering_auto
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_driver_assembly, only: element_stresses, element_strains, assemble_loads
   use vemcontact_post_reactions, only: reaction_forces
   use vemcontact_element_geometry, only: polygon_centroid, polygon_signed_area
   use vemcontact_test_model, only: make_model
   use vemcontact_test_polymesh, only: cantilever_two_quads, dual_polymesh, hanging_quad_grid, quad_grid
   use vemcontact_test_second_order, only: add_side_nodes, boundary_mask2, split_quads
   implicit none
   real(wp), parameter :: length = 40, depth = 8, young = 1000, moment = 16
   real(wp), parameter :: exact = moment*length**2/(2*young*depth**3/12)
   ! a quadratic field: u_c = sum_j coef(j, c) (1, x, y, x^2, xy, y^2)_j
   real(wp), parameter :: coef(6, 2) = 1.0e-3_wp*reshape([0.3_wp, 1.0_wp, -2.0_wp, 0.7_wp, -1.1_wp, 0.4_wp, &
                                                           -0.5_wp, 0.6_wp, 1.3_wp, -0.9_wp, 0.8_wp, 1.2_wp], [6, 2])
   type(checker_t) :: t
   real(wp), allocatable :: x(:, :), x2(:, :)
   integer(ip), allocatable :: ptr(:), conn(:), ptr2(:), conn2(:), ptr3(:), conn3(:)
   real(wp) :: rv, rq, worst
   integer :: k, plane

   ! example 1: 2d/b = 0, 0.375, ..., 4.875 (at 5 the shared side would reach a corner)
   worst = 0
   do k = 0, 13
      rv = tip(0.375_wp*k, form_vem)/exact
      rq = tip(0.375_wp*k, form_fem)/exact
      print '(a,f6.3,a,f12.9,a,f9.5)', '2d/b = ', 0.375_wp*k, '  k = 2 VEM ratio ', rv, '  Q8 ratio ', rq
      worst = max(worst, abs(rv - 1))
      ! rectangles: the serendipity quad holds the quadratic bending field exactly
      if (k == 0) call t%close(rq, 1.0_wp, 1.0e-10_wp, 'Q8, 2d/b = 0: exact tip deflection')
   end do
   ! the issue's target: ratio 1 within 1e-8 at every skew
   call t%check(worst <= 1.0e-8_wp, 'k = 2 VEM: tip deflection ratio 1 within 1e-8 for 2d/b in [0, 4.875]')

   do plane = plane_strain, plane_stress
      call dual_polymesh(5, 0.3_wp, 3, x, ptr, conn)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call patch(x2, ptr2, conn2, plane, form_vem, 'k = 2 VEM, dual polygon mesh')
      call pressure_block(x2, ptr2, conn2, plane, form_vem, 'k = 2 VEM, dual polygon mesh')
      call dual_polymesh(5, 0.2_wp, 5, x, ptr, conn, median=.true.)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call patch(x2, ptr2, conn2, plane, form_vem, 'k = 2 VEM, non-convex median-dual mesh')
      call hanging_quad_grid(3, 3, x, ptr, conn)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call patch(x2, ptr2, conn2, plane, form_vem, 'k = 2 VEM, collinear-corner mesh')
      call quad_grid(4, 3, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.2_wp, 7, x, ptr, conn)
      call split_quads(ptr, conn, ptr3, conn3)
      call add_side_nodes(x, ptr3, conn3, x2, ptr2, conn2)
      call patch(x2, ptr2, conn2, plane, form_fem, 'T6, perturbed triangles')
      call pressure_block(x2, ptr2, conn2, plane, form_fem, 'T6, perturbed triangles')
      call quad_grid(4, 3, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 7, x, ptr, conn)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call patch(x2, ptr2, conn2, plane, form_fem, 'Q8, rectangles')
      call quad_grid(4, 3, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.2_wp, 7, x, ptr, conn)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call pressure_block(x2, ptr2, conn2, plane, form_fem, 'Q8, perturbed quads')
   end do
   call hydrostatic_side()
   call t%finish()

contains

   pure function field(p) result(u)
      real(wp), intent(in) :: p(2)
      real(wp) :: u(2)
      u = matmul([1.0_wp, p(1), p(2), p(1)**2, p(1)*p(2), p(2)**2], coef)
   end function field

   pure function strain(p) result(e)
      real(wp), intent(in) :: p(2)
      real(wp) :: e(3)
      e(1) = coef(2, 1) + 2*coef(4, 1)*p(1) + coef(5, 1)*p(2)
      e(2) = coef(3, 2) + coef(5, 2)*p(1) + 2*coef(6, 2)*p(2)
      e(3) = coef(3, 1) + coef(5, 1)*p(1) + 2*coef(6, 1)*p(2) &
             + coef(2, 2) + 2*coef(4, 2)*p(1) + coef(5, 2)*p(2)
   end function strain

   !> -div(D eps), constant.
   pure function body(d) result(b)
      real(wp), intent(in) :: d(3, 3)
      real(wp) :: b(2), sx(3), sy(3)
      sx = matmul(d, [2*coef(4, 1), coef(5, 2), coef(5, 1) + 2*coef(4, 2)])
      sy = matmul(d, [coef(5, 1), 2*coef(6, 2), 2*coef(6, 1) + coef(5, 2)])
      b = -[sx(1) + sy(3), sx(3) + sy(2)]
   end function body

   !> Tip deflection of example 1 on two second-order elements (side nodes at
   !> the middles): x held on the whole clamped side, y at its bottom corner;
   !> the couple +-M/b on the tip corners, which is the consistent load of the
   !> linear bending stress on the 3-node tip side (its middle node gets none).
   real(wp) function tip(ratio, form)
      real(wp), intent(in) :: ratio
      integer, intent(in) :: form
      real(wp), allocatable :: x(:, :), x2(:, :), u(:)
      integer(ip), allocatable :: ptr(:), conn(:), ptr2(:), conn2(:)
      type(model_t) :: m
      type(linear_system_t) :: sys
      type(load_state_t) :: st
      type(error_t), allocatable :: error
      integer :: i, n, ibl, ibr, itr
      call cantilever_two_quads(length, depth, 0.5_wp*ratio*depth, x, ptr, conn)
      call add_side_nodes(x, ptr, conn, x2, ptr2, conn2)
      call make_model(x2, ptr2, conn2, young, 0.0_wp, plane_strain, form, 1.0_wp, m, order=2)
      n = m%nnode
      allocate (u(2*n), st%fixed(2*n), st%prescribed(2*n), st%force(2*n), st%dload(0))
      st%fixed = .false.; st%prescribed = 0; st%force = 0
      ibl = 0; ibr = 0; itr = 0
      do i = 1, n
         if (abs(x2(1, i)) < 1e-12_wp) st%fixed(2*i - 1) = .true.
         if (abs(x2(1, i)) < 1e-12_wp .and. abs(x2(2, i)) < 1e-12_wp) ibl = i
         if (abs(x2(1, i) - length) < 1e-12_wp .and. abs(x2(2, i)) < 1e-12_wp) ibr = i
         if (abs(x2(1, i) - length) < 1e-12_wp .and. abs(x2(2, i) - depth) < 1e-12_wp) itr = i
      end do
      st%fixed(2*ibl) = .true.
      st%force(2*ibr - 1) = moment/depth
      st%force(2*itr - 1) = -moment/depth
      call sys%setup(m, ordering_auto, error)
      if (.not. allocated(error)) call sys%solve_state(m, st, u, error)
      call t%check(.not. allocated(error), 'solve')
      if (allocated(error)) print '(a)', error%message
      tip = 0.5_wp*(u(2*ibr) + u(2*itr))
   end function tip

   !> Quadratic field prescribed on the boundary, its body force as a GRAV load
   !> on every element; nodal displacements within 1e-10 relative (the issue's
   !> target) and element stresses equal to the exact mean stress.
   subroutine patch(x, ptr, conn, plane, form, what)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: ptr(:), conn(:)
      integer, intent(in) :: plane, form
      character(len=*), intent(in) :: what
      type(model_t) :: m
      type(linear_system_t) :: sys
      type(load_state_t) :: st
      type(error_t), allocatable :: error
      real(wp), allocatable :: u(:), uex(:), s_elem(:, :), s_at(:, :), e_elem(:, :), e_at(:, :)
      real(wp), allocatable :: ku(:), f(:), rf(:, :)
      logical, allocatable :: onb(:)
      real(wp) :: d(3, 3), b(2), c(2), sig(3), eps(3), err, area, mom
      integer :: i, e, n
      call make_model(x, ptr, conn, 2.0e5_wp, 0.3_wp, plane, form, 0.5_wp, m, order=2)
      m%materials(1)%density = 2.0_wp
      m%materials(1)%has_density = .true.
      call elastic_matrix(2.0e5_wp, 0.3_wp, plane, d)
      b = body(d)
      allocate (u(2*m%nnode), uex(2*m%nnode), st%fixed(2*m%nnode), st%prescribed(2*m%nnode), &
                st%force(2*m%nnode), st%dload(m%nelem), s_elem(4, m%nelem))
      onb = boundary_mask2(int(m%nnode), ptr, conn)
      st%fixed(1::2) = onb
      st%fixed(2::2) = onb
      do i = 1, int(m%nnode)
         uex(2*i - 1:2*i) = field(x(:, i))
      end do
      st%prescribed = uex
      st%force = 0
      ! GRAV: rho * g * dir with rho = 2
      do e = 1, int(m%nelem)
         st%dload(e) = dload_t(elem=e, kind=dload_grav, side=0, magnitude=norm2(b)/2.0_wp, dir=b/norm2(b))
      end do
      call sys%setup(m, ordering_auto, error)
      if (.not. allocated(error)) call sys%solve_state(m, st, u, error)
      call t%check(.not. allocated(error), what//': solve')
      if (allocated(error)) then
         print '(a)', error%message
         return
      end if
      err = maxval(abs(u - uex))/maxval(abs(uex))
      print '(a,es10.2)', what//': patch test, max relative nodal error ', err
      call t%check(err <= 1.0e-10_wp, what//': quadratic field reproduced at every node (1e-10)')
      allocate (s_at(4, size(conn)))
      call element_stresses(m, u, s_elem, st%dload, s_at)
      ! each element's own stress at each of its nodes: exact (the stress of a
      ! quadratic field is linear, and every element holds it)
      err = 0
      do i = 1, size(conn)
         sig = matmul(d, strain(x(:, conn(i))))
         err = max(err, maxval(abs(s_at([1, 2, 4], i) - sig))/maxval(abs(sig)))
      end do
      call t%check(err <= 1.0e-8_wp, what//': element stresses at the nodes exact')
      err = 0
      do e = 1, int(m%nelem)
         n = (ptr(e + 1) - ptr(e))/2
         call polygon_centroid(x(:, conn(ptr(e):ptr(e) + n - 1)), c)
         sig = matmul(d, strain(c))      ! the stress is linear: its mean is its centroid value
         err = max(err, maxval(abs(s_elem([1, 2, 4], e) - sig))/maxval(abs(sig)))
      end do
      ! 1e-8: the mean of a stress field whose nodal values are reproduced to 1e-13
      ! relative, through the element's dense solves
      call t%check(err <= 1.0e-8_wp, what//': element stress is the exact mean stress')

      ! strains E: the same recovery, exact at the nodes and as the element mean
      ! (engineering shear gamma_xy; zz the plane-stress thickness strain)
      allocate (e_elem(4, m%nelem), e_at(4, size(conn)))
      call element_strains(m, s_elem, e_elem, s_at, e_at)
      err = 0
      do i = 1, size(conn)
         eps = strain(x(:, conn(i)))
         err = max(err, maxval(abs(e_at([1, 2, 4], i) - eps))/maxval(abs(eps)), &
                   abs(e_at(3, i) - ezz_of(eps, plane))/maxval(abs(eps)))
      end do
      ! 1e-8 as for the stresses (E = D^-1 S, D well conditioned at nu = 0.3)
      call t%check(err <= 1.0e-8_wp, what//': element strains at the nodes exact')
      err = 0
      area = 0
      do e = 1, int(m%nelem)
         n = (ptr(e + 1) - ptr(e))/2
         call polygon_centroid(x(:, conn(ptr(e):ptr(e) + n - 1)), c)
         area = area + polygon_signed_area(x(:, conn(ptr(e):ptr(e) + n - 1)))
         eps = strain(c)
         err = max(err, maxval(abs(e_elem([1, 2, 4], e) - eps))/maxval(abs(eps)), &
                   abs(e_elem(3, e) - ezz_of(eps, plane))/maxval(abs(eps)))
      end do
      call t%check(err <= 1.0e-8_wp, what//': element strain is the exact mean strain')

      ! reactions: K annihilates rigid motions, so the reactions at the fixed
      ! boundary balance the body force: sum RF = -b rho |Omega| t (the body
      ! force's resultant from the areas, independent of the element load
      ! vectors) and the moments of RF and f about the origin cancel
      allocate (ku(2*m%nnode), f(2*m%nnode), rf(2, m%nnode))
      call sys%elastic_times(u, ku)
      call assemble_loads(m, st%force, st%dload, f)
      call reaction_forces(ku, f, st%fixed, rf)
      err = maxval(abs(sum(rf, dim=2) + b*area*0.5_wp))/maxval(abs(b*area*0.5_wp))
      mom = 0
      do i = 1, int(m%nnode)
         mom = mom + x(1, i)*(rf(2, i) + f(2*i)) - x(2, i)*(rf(1, i) + f(2*i - 1))
      end do
      err = max(err, abs(mom)/(maxval(abs(b*area*0.5_wp))*maxval(abs(x))))
      print '(a,es10.2)', what//': reaction balance, relative error ', err
      ! 1e-10: round-off of K u over the boundary nodes (the balance is exact)
      call t%check(err <= 1.0e-10_wp, what//': reactions balance the body force (resultant and moment)')
   end subroutine patch

   !> Thickness strain of the in-plane strain eps at nu = 0.3: 0 in plane strain.
   pure real(wp) function ezz_of(eps, plane)
      real(wp), intent(in) :: eps(3)
      integer, intent(in) :: plane
      ezz_of = 0
      if (plane == plane_stress) ezz_of = -0.3_wp/(1 - 0.3_wp)*(eps(1) + eps(2))
   end function ezz_of

   !> The unit block under a uniform pressure p on its top (y = 1) sides, rollers
   !> on the bottom and the left: uniform stress syy = -p, so the linear
   !> displacement field of that stress is exact for every element.
   subroutine pressure_block(x, ptr, conn, plane, form, what)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: ptr(:), conn(:)
      integer, intent(in) :: plane, form
      character(len=*), intent(in) :: what
      real(wp), parameter :: p = 3.0_wp, ey = 2.0e5_wp, nu = 0.3_wp
      type(model_t) :: m
      type(linear_system_t) :: sys
      type(load_state_t) :: st
      type(error_t), allocatable :: error
      real(wp), allocatable :: u(:), uex(:)
      real(wp) :: exx, eyy, err
      integer :: i, e, n, k, a, b
      call make_model(x, ptr, conn, ey, nu, plane, form, 0.5_wp, m, order=2)
      if (plane == plane_strain) then
         exx = p*nu*(1 + nu)/ey
         eyy = -p*(1 - nu*nu)/ey
      else
         exx = p*nu/ey
         eyy = -p/ey
      end if
      allocate (u(2*m%nnode), uex(2*m%nnode), st%fixed(2*m%nnode), st%prescribed(2*m%nnode), &
                st%force(2*m%nnode), st%dload(0))
      st%fixed = .false.
      st%prescribed = 0
      st%force = 0
      do i = 1, int(m%nnode)
         uex(2*i - 1:2*i) = [exx*x(1, i), eyy*x(2, i)]
         if (abs(x(1, i)) < 1e-12_wp) st%fixed(2*i - 1) = .true.
         if (abs(x(2, i)) < 1e-12_wp) st%fixed(2*i) = .true.
      end do
      do e = 1, int(m%nelem)
         n = (ptr(e + 1) - ptr(e))/2
         do k = 1, n
            a = conn(ptr(e) + k - 1)
            b = conn(ptr(e) + mod(k, n))
            if (abs(x(2, a) - 1) < 1e-12_wp .and. abs(x(2, b) - 1) < 1e-12_wp) &
               st%dload = [st%dload, dload_t(elem=e, kind=dload_pressure, side=k, magnitude=p, dir=0.0_wp)]
         end do
      end do
      call t%check(size(st%dload) > 0, what//': top sides found')
      call sys%setup(m, ordering_auto, error)
      if (.not. allocated(error)) call sys%solve_state(m, st, u, error)
      call t%check(.not. allocated(error), what//': pressure block solve')
      if (allocated(error)) return
      err = maxval(abs(u - uex))/maxval(abs(uex))
      print '(a,es10.2)', what//': uniform pressure, max relative nodal error ', err
      ! 1e-10: round-off of the solve (the uniform stress state is exact for all elements)
      call t%check(err <= 1.0e-10_wp, what//': uniform pressure on second-order sides exact')
   end subroutine pressure_block

   !> One square element [0,2]^2, hydrostatic pressure on its right side (x = 2,
   !> side 2, from (2,0) up to (2,2)) with the free surface at y = 1.3 and
   !> magnitude 5 at y = 0: the nodal forces of the second-order side have the
   !> resultant and moment of the first-order side's (both exact), and a uniform
   !> pressure on the second-order side gives 1/6, 4/6, 1/6 of p L.
   subroutine hydrostatic_side()
      real(wp), parameter :: sq(2, 4) = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 2.0_wp, 0.0_wp, 2.0_wp], [2, 4])
      real(wp), allocatable :: x2(:, :), f1(:), f2(:)
      integer(ip), allocatable :: ptr2(:), conn2(:)
      type(model_t) :: m1, m2
      type(dload_t) :: load(1)
      real(wp) :: r1(3), r2(3)
      integer :: i
      call add_side_nodes(sq, [1_ip, 5_ip], [1_ip, 2_ip, 3_ip, 4_ip], x2, ptr2, conn2)
      call make_model(sq, [1_ip, 5_ip], [1_ip, 2_ip, 3_ip, 4_ip], 1.0_wp, 0.3_wp, plane_strain, form_vem, 1.0_wp, m1)
      call make_model(x2, ptr2, conn2, 1.0_wp, 0.3_wp, plane_strain, form_vem, 1.0_wp, m2, order=2)
      load(1) = dload_t(elem=1, kind=dload_hydrostatic, side=2, magnitude=5.0_wp, dir=[1.3_wp, 0.0_wp])
      allocate (f1(8), f2(16))
      call assemble_loads(m1, spread(0.0_wp, 1, 8), load, f1)
      call assemble_loads(m2, spread(0.0_wp, 1, 16), load, f2)
      r1 = 0
      r2 = 0
      do i = 1, 4
         r1 = r1 + [f1(2*i - 1), f1(2*i), sq(1, i)*f1(2*i) - sq(2, i)*f1(2*i - 1)]
      end do
      do i = 1, 8
         r2 = r2 + [f2(2*i - 1), f2(2*i), x2(1, i)*f2(2*i) - x2(2, i)*f2(2*i - 1)]
      end do
      ! exact: resultant -integral p dy = -5 * 1.3/2 in x (p falls linearly from 5 at y = 0 to 0 at 1.3)
      call t%close(r2(1), -5.0_wp*1.3_wp/2, 1.0e-12_wp, 'hydrostatic on a 3-node side: resultant')
      call t%close(r2(1), r1(1), 1.0e-12_wp, 'hydrostatic: resultant as on the 2-node side')
      call t%check(abs(r2(2)) <= 1.0e-14_wp, 'hydrostatic: no y force on a vertical side')
      call t%close(r2(3), r1(3), 1.0e-12_wp, 'hydrostatic: moment as on the 2-node side')
      load(1) = dload_t(elem=1, kind=dload_pressure, side=2, magnitude=6.0_wp, dir=0.0_wp)
      call assemble_loads(m2, spread(0.0_wp, 1, 16), load, f2)
      ! corners 2 (2,0) and 3 (2,2), side node 6 (2,1); p L = 12 pushing in -x
      call t%close(f2(3), -2.0_wp, 1.0e-14_wp, 'uniform pressure: 1/6 p L at the first corner')
      call t%close(f2(5), -2.0_wp, 1.0e-14_wp, 'uniform pressure: 1/6 p L at the second corner')
      call t%close(f2(11), -8.0_wp, 1.0e-14_wp, 'uniform pressure: 4/6 p L at the side node')
   end subroutine hydrostatic_side
end program test_second_order
