!> Global assembly: stiffness into the fixed pattern, load vector, element stresses.
!> Work arrays are sized once for the largest element, so the element loop allocates nothing.
module vemcontact_driver_assembly
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, append_message, err_model, err_internal
   use vemcontact_model, only: model_t, dload_t, location_string, dload_grav, dload_pressure, dload_hydrostatic, &
                               element_order, element_side, plane_stress
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: add_element_matrix
   use vemcontact_material_elastic, only: elastic_matrix, out_of_plane_stress
   use vemcontact_driver_thermal, only: thermal_stress, thermal_strain, add_thermal_body
   use vemcontact_element, only: element_stiffness, element_stress, element_body_load, &
                                 element_workspace_size
   implicit none
   private

   public :: assemble_stiffness, assemble_loads, element_stresses, element_strains, max_element_nodes, hydrostatic_moments

contains

   !> Largest number of nodes of any element.
   pure integer function max_element_nodes(model) result(nmax)
      type(model_t), intent(in) :: model
      nmax = 0
      if (model%nelem > 0) nmax = maxval(model%elem_ptr(2:) - model%elem_ptr(:model%nelem))
   end function max_element_nodes

   !> Assemble the stiffness matrix into `a` (pattern already built, values overwritten).
   !> With `mine`, only the elements e with mine(e) (this process's share of the matrix).
   subroutine assemble_stiffness(model, a, error, mine)
      type(model_t), intent(in) :: model
      type(sym_csc_t), intent(inout) :: a
      type(error_t), allocatable, intent(out) :: error
      logical, intent(in), optional :: mine(:)
      real(wp), allocatable :: xy(:, :), ke(:, :), work(:)
      real(wp) :: d(3, 3)
      integer :: nmax, n, info, e, nerr
      integer(ip) :: first
      logical :: ok
      character(len=32) :: buf
      nmax = max_element_nodes(model)
      allocate (xy(2, nmax), ke(2*nmax, 2*nmax), work(element_workspace_size(nmax)))
      a%val = 0.0_wp
      nerr = 0
      do e = 1, model%nelem
         if (present(mine)) then
            if (.not. mine(e)) cycle
         end if
         first = model%elem_ptr(e)
         n = model%elem_ptr(e + 1) - first
         xy(:, :n) = model%x(:, model%elem_conn(first:first + n - 1))
         associate (mat => model%materials(model%elem_mat(e)))
            call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
         end associate
         call element_stiffness(model%elem_form(e), xy(:, :n), d, model%elem_thick(e), ke(:2*n, :2*n), &
                                work, info, stab(model, e), element_order(model%elem_type(e)), reduced(model, e))
         if (info /= 0) then
            nerr = nerr + 1
            write (buf, '(i0)') model%elem_id(e)
            call append_message(error, location_string(model, model%elem_loc(e))// &
                                ': error: element '//trim(buf)//': '//info_text(info), err_model)
            if (nerr >= 50) return
            cycle
         end if
         call add_element_matrix(a, model%elem_conn(first:first + n - 1), ke(:2*n, :2*n), ok)
         if (.not. ok) then
            call append_message(error, 'internal error: element outside the matrix pattern', err_internal)
            return
         end if
      end do
   end subroutine assemble_stiffness

   pure function info_text(info) result(s)
      integer, intent(in) :: info
      character(len=:), allocatable :: s
      select case (info)
      case (1); s = 'area is zero or negative'
      case (2); s = 'FORMULATION=FEM needs a 3- or 4-node element (6 or 8 nodes for a second-order one)'
      case (3); s = 'FEM Jacobian is not positive at a Gauss point (element too distorted for FEM; use FORMULATION=VEM)'
      case (4); s = 'a second-order element needs an even number of nodes, at least 6'
      case (5); s = 'a side node is not at the middle of its side (the second-order VEM needs straight sides)'
      case (6); s = 'the second-order VEM projection is singular'
      case default; s = 'element routine failed'
      end select
   end function info_text

   !> Load vector of the state: concentrated loads plus distributed loads.
   !> Body loads use element_body_load (the consistent nodal forces of each
   !> element kind); pressure on a side with a middle node is integrated along
   !> the side's quadratic map (side_loads_quadratic).
   subroutine assemble_loads(model, force, dloads, f)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: force(:)
      type(dload_t), intent(in) :: dloads(:)
      real(wp), intent(out) :: f(:)
      real(wp), allocatable :: xy(:, :), w(:), work(:), fb(:, :)
      real(wp) :: t(2), scale, wa, wb, d(3, 3), fs(2, 3)
      integer :: k, n, e, i, nmax, info, nsides
      integer(ip) :: first, node, abc(3), a, b
      nmax = max_element_nodes(model)
      allocate (xy(2, nmax), w(nmax), work(element_workspace_size(nmax)), fb(2*nmax, 2))
      f = force
      do k = 1, size(dloads)
         e = dloads(k)%elem
         first = model%elem_ptr(e)
         n = model%elem_ptr(e + 1) - first
         select case (dloads(k)%kind)
         case (dload_grav)
            xy(:, :n) = model%x(:, model%elem_conn(first:first + n - 1))
            associate (mat => model%materials(model%elem_mat(e)))
               call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
               scale = mat%density*dloads(k)%magnitude
            end associate
            call element_body_load(model%elem_form(e), xy(:, :n), d, model%elem_thick(e), fb(:2*n, :), &
                                   work, w, info, stab(model, e), element_order(model%elem_type(e)))
            do i = 1, n
               node = model%elem_conn(first + i - 1)
               f(2*node - 1:2*node) = f(2*node - 1:2*node) + scale*matmul(fb(2*i - 1:2*i, :), dloads(k)%dir)
            end do
         case (dload_pressure, dload_hydrostatic)
            call element_side(model, int(e, ip), dloads(k)%side, abc, nsides)
            a = abc(1)
            b = abc(2)
            if (abc(3) /= 0) then
               call side_loads_quadratic(model%x(:, abc), dloads(k), fs)
               do i = 1, 3
                  node = abc(i)
                  f(2*node - 1:2*node) = f(2*node - 1:2*node) + model%elem_thick(e)*fs(:, i)
               end do
            else if (dloads(k)%kind == dload_pressure) then
               ! edge a->b of a counter-clockwise polygon has outward normal (t_y, -t_x)/|t|;
               ! a positive pressure pushes inward, split equally (the trace is linear on the edge)
               t = model%x(:, b) - model%x(:, a)
               scale = -0.5_wp*dloads(k)%magnitude*model%elem_thick(e)
               f(2*a - 1:2*a) = f(2*a - 1:2*a) + scale*[t(2), -t(1)]
               f(2*b - 1:2*b) = f(2*b - 1:2*b) + scale*[t(2), -t(1)]
            else
               t = model%x(:, b) - model%x(:, a)
               call hydrostatic_moments(dloads(k), model%x(2, a), model%x(2, b), wa, wb)
               f(2*a - 1:2*a) = f(2*a - 1:2*a) - wa*model%elem_thick(e)*[t(2), -t(1)]
               f(2*b - 1:2*b) = f(2*b - 1:2*b) - wb*model%elem_thick(e)*[t(2), -t(1)]
            end if
         end select
      end do
   end subroutine assemble_loads

   !> The element's VEM stabilisation factor (1 when the model has none).
   pure real(wp) function stab(model, e)
      type(model_t), intent(in) :: model
      integer, intent(in) :: e
      stab = 1.0_wp
      if (allocated(model%elem_stab)) stab = model%elem_stab(e)
   end function stab

   !> Whether the element has reduced integration (false when the model has no such flags).
   pure logical function reduced(model, e)
      type(model_t), intent(in) :: model
      integer, intent(in) :: e
      reduced = .false.
      if (allocated(model%elem_reduced)) reduced = model%elem_reduced(e)
   end function reduced

   !> Consistent nodal forces per unit thickness, fs(:, i) for the side's nodes
   !> xs(:, 1) (start corner), xs(:, 2) (end corner), xs(:, 3) (middle node), of
   !> a uniform (dload_pressure) or hydrostatic (dload_hydrostatic) pressure:
   !> f_i = - integral p(s) N_i(s) (y'(s), -x'(s)) ds over s in [0, 1] with the
   !> quadratic map x(s) = sum N_i(s) x_i, N = ((1-s)(1-2s), s(2s-1), 4s(1-s)).
   !> On a straight side with its node at the middle a uniform pressure gives
   !> 1/6, 1/6, 4/6 of p L.  The hydrostatic pressure is cut where y(s) crosses
   !> the free surface (roots of a quadratic), and each wet piece is integrated
   !> with 3-point Gauss: the integrand is of degree 5 at most, so exactly.
   pure subroutine side_loads_quadratic(xs, load, fs)
      real(wp), intent(in) :: xs(2, 3)
      type(dload_t), intent(in) :: load
      real(wp), intent(out) :: fs(2, 3)
      real(wp), parameter :: gt(3) = [0.5_wp - 0.5_wp*sqrt(0.6_wp), 0.5_wp, 0.5_wp + 0.5_wp*sqrt(0.6_wp)]
      real(wp), parameter :: gw(3) = [5.0_wp/18.0_wp, 8.0_wp/18.0_wp, 5.0_wp/18.0_wp]
      real(wp) :: cut(4), q0, q1, q2, disc, r, s, lo, hi, nsh(3), dsh(3), tang(2), p
      integer :: ncut, i, j, g
      fs = 0.0_wp
      ncut = 2
      cut(1) = 0.0_wp
      cut(2) = 1.0_wp
      if (load%kind == dload_hydrostatic) then
         ! y(s) - y0 = q0 + q1 s + q2 s^2
         q0 = xs(2, 1) - load%dir(1)
         q1 = -3*xs(2, 1) - xs(2, 2) + 4*xs(2, 3)
         q2 = 2*xs(2, 1) + 2*xs(2, 2) - 4*xs(2, 3)
         if (abs(q2) > 1.0e-12_wp*(abs(q1) + abs(q0))) then
            disc = q1*q1 - 4*q2*q0
            if (disc >= 0.0_wp) then
               do j = -1, 1, 2
                  r = (-q1 + j*sqrt(disc))/(2*q2)
                  if (r > 0.0_wp .and. r < 1.0_wp) call insert_cut(cut, ncut, r)
               end do
            end if
         else if (abs(q1) > 0.0_wp) then
            r = -q0/q1
            if (r > 0.0_wp .and. r < 1.0_wp) call insert_cut(cut, ncut, r)
         end if
      end if
      do i = 1, ncut - 1
         lo = cut(i)
         hi = cut(i + 1)
         if (load%kind == dload_hydrostatic) then
            if (pressure(0.5_wp*(lo + hi))*sign(1.0_wp, load%magnitude) < 0.0_wp) cycle   ! dry
         end if
         do g = 1, 3
            s = lo + gt(g)*(hi - lo)
            nsh = [(1 - s)*(1 - 2*s), s*(2*s - 1), 4*s*(1 - s)]
            dsh = [4*s - 3, 4*s - 1, 4 - 8*s]
            tang = matmul(xs, dsh)
            p = pressure(s)
            do j = 1, 3
               fs(:, j) = fs(:, j) - gw(g)*(hi - lo)*p*nsh(j)*[tang(2), -tang(1)]
            end do
         end do
      end do
   contains
      pure real(wp) function pressure(s)
         real(wp), intent(in) :: s
         real(wp) :: y
         if (load%kind == dload_hydrostatic) then
            y = dot_product(xs(2, :), [(1 - s)*(1 - 2*s), s*(2*s - 1), 4*s*(1 - s)])
            pressure = load%magnitude*(load%dir(1) - y)/(load%dir(1) - load%dir(2))
         else
            pressure = load%magnitude
         end if
      end function pressure
   end subroutine side_loads_quadratic

   !> Insert r into the sorted cut(1:ncut), keeping it sorted.
   pure subroutine insert_cut(cut, ncut, r)
      real(wp), intent(inout) :: cut(:)
      integer, intent(inout) :: ncut
      real(wp), intent(in) :: r
      integer :: i
      i = ncut
      do while (i >= 1)
         if (cut(i) <= r) exit
         cut(i + 1) = cut(i)
         i = i - 1
      end do
      cut(i + 1) = r
      ncut = ncut + 1
   end subroutine insert_cut

   !> Consistent nodal weights of a hydrostatic pressure on a side from height ya
   !> (s = 0) to yb (s = 1): wa = integral of p(s) (1 - s) ds, wb = integral of p(s) s ds.
   !> p = magnitude * (y0 - y)/(y0 - yref) on the wet side of the free surface y0
   !> and 0 beyond it (Abaqus HP); the integrals are exact on the wet part of the side.
   pure subroutine hydrostatic_moments(load, ya, yb, wa, wb)
      type(dload_t), intent(in) :: load
      real(wp), intent(in) :: ya, yb
      real(wp), intent(out) :: wa, wb
      real(wp) :: alpha, beta, s0, s1, y0, yref
      y0 = load%dir(1)
      yref = load%dir(2)
      ! p(s) = alpha + beta*s along the side
      alpha = load%magnitude*(y0 - ya)/(y0 - yref)
      beta = load%magnitude*(ya - yb)/(y0 - yref)
      s0 = 0.0_wp
      s1 = 1.0_wp
      ! keep the part of [0,1] where p*sign(magnitude) >= 0, i.e. the wet side
      if (abs(beta) > 0.0_wp) then      ! exactly zero only on a horizontal side
         if (sign(1.0_wp, load%magnitude)*beta > 0.0_wp) then
            s0 = max(0.0_wp, min(1.0_wp, -alpha/beta))
         else
            s1 = max(0.0_wp, min(1.0_wp, -alpha/beta))
         end if
      else if (sign(1.0_wp, load%magnitude)*alpha < 0.0_wp) then
         s1 = s0
      end if
      wa = prim_a(s1) - prim_a(s0)
      wb = prim_b(s1) - prim_b(s0)
   contains
      pure real(wp) function prim_a(x)   ! antiderivative of (alpha + beta x)(1 - x)
         real(wp), intent(in) :: x
         prim_a = alpha*x + (beta - alpha)*x**2/2 - beta*x**3/3
      end function prim_a
      pure real(wp) function prim_b(x)   ! antiderivative of (alpha + beta x) x
         real(wp), intent(in) :: x
         prim_b = alpha*x**2/2 + beta*x**3/3
      end function prim_b
   end subroutine hydrostatic_moments

   !> Element stresses (xx, yy, zz, xy) from the displacement field u(2*nnode).
   !> `dloads` (optional): the distributed loads the displacements were solved
   !> with; the k = 2 virtual element recovers its condensed cell moments from
   !> the body force among them.
   !> `s_at` (optional, (4, size of elem_conn)): each element's stress at each
   !> of its nodes (element_stress's signode), for nodal_average.
   !> `dtemp` (optional, (nnode)): the temperature changes T - T0; the stresses are
   !> then D (E - thermal strain) (vemcontact_driver_thermal).
   subroutine element_stresses(model, u, s_elem, dloads, s_at, dtemp)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      real(wp), intent(out) :: s_elem(:, :)
      type(dload_t), intent(in), optional :: dloads(:)
      real(wp), intent(out), optional :: s_at(:, :)
      real(wp), intent(in), optional :: dtemp(:)
      real(wp), allocatable :: xy(:, :), ue(:), work(:), body(:, :), sn(:, :)
      real(wp) :: d(3, 3), sig(3)
      integer :: e, n, i, nmax
      integer(ip) :: first
      nmax = max_element_nodes(model)
      allocate (xy(2, nmax), ue(2*nmax), work(element_workspace_size(nmax)), sn(3, nmax))
      body = element_body_forces(model, dloads)
      if (present(dtemp)) call add_thermal_body(model, dtemp, body)
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         call gather_element(model, u, e, xy, ue, n)
         associate (mat => model%materials(model%elem_mat(e)))
            call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
            call element_stress(model%elem_form(e), xy(:, :n), d, ue(:2*n), work, sig, &
                                element_order(model%elem_type(e)), model%elem_thick(e), stab(model, e), body(:, e), &
                                sn(:, :n), reduced(model, e))
            s_elem(:, e) = [sig(1), sig(2), out_of_plane_stress(mat%poisson, model%elem_plane(e), sig(1), sig(2)), sig(3)]
            if (present(s_at)) then
               do i = 1, n
                  s_at(:, first + i - 1) = [sn(1, i), sn(2, i), &
                                            out_of_plane_stress(mat%poisson, model%elem_plane(e), sn(1, i), sn(2, i)), &
                                            sn(3, i)]
               end do
            end if
         end associate
      end do
      if (present(dtemp)) call thermal_stress(model, dtemp, s_elem, s_at)
   end subroutine element_stresses

   !> The coordinates xy(:, :n) and displacements ue(:2n) of the n nodes of element e,
   !> into the caller's work arrays (sized for the largest element).
   pure subroutine gather_element(model, u, e, xy, ue, n)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      integer, intent(in) :: e
      real(wp), intent(inout) :: xy(:, :), ue(:)
      integer, intent(out) :: n
      integer :: i
      integer(ip) :: node
      n = int(model%elem_ptr(e + 1) - model%elem_ptr(e))
      do i = 1, n
         node = model%elem_conn(model%elem_ptr(e) + i - 1)
         xy(:, i) = model%x(:, node)
         ue(2*i - 1:2*i) = u(2*node - 1:2*node)
      end do
   end subroutine gather_element

   !> Body force per unit volume of every element (2, nelem): the sum of the
   !> GRAV loads among `dloads` (zero without them).
   pure function element_body_forces(model, dloads) result(body)
      type(model_t), intent(in) :: model
      type(dload_t), intent(in), optional :: dloads(:)
      real(wp), allocatable :: body(:, :)
      integer :: k, e
      allocate (body(2, model%nelem), source=0.0_wp)
      if (.not. present(dloads)) return
      do k = 1, size(dloads)
         if (dloads(k)%kind /= dload_grav) cycle
         e = dloads(k)%elem
         body(:, e) = body(:, e) + model%materials(model%elem_mat(e))%density*dloads(k)%magnitude*dloads(k)%dir
      end do
   end function element_body_forces

   !> Element strains E (total strain, Abaqus' E) `(xx, yy, zz, xy)` with the
   !> engineering shear strain gamma_xy = 2 eps_xy, as Abaqus writes E12, from the
   !> stresses of element_stresses: every kernel's stress is D times its strain (the
   !> projected one for the VEM, the Gauss-averaged one for the quad, the element's own
   !> nodal values for second-order elements), so E = D^-1 S element by element, with
   !> no second pass through the element kernels.
   !> zz: 0 in plane strain; in plane stress the thickness strain
   !> -nu/(1 - nu) (xx + yy) that makes S_zz zero.
   !> `s_at`, `e_at` (optional, (4, size of elem_conn)): each element's stress and
   !> strain at each of its nodes (element_stresses' s_at), for nodal_average.
   !> `dtemp` (optional): with thermal strains, D^-1 S is the mechanical strain and
   !> the thermal strain is added to give the total.
   pure subroutine element_strains(model, s_elem, e_elem, s_at, e_at, dtemp)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: s_elem(:, :)
      real(wp), intent(out) :: e_elem(:, :)
      real(wp), intent(in), optional :: s_at(:, :)
      real(wp), intent(out), optional :: e_at(:, :)
      real(wp), intent(in), optional :: dtemp(:)
      real(wp) :: d(3, 3)
      integer :: e
      integer(ip) :: k
      do e = 1, model%nelem
         associate (mat => model%materials(model%elem_mat(e)))
            call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
            e_elem(:, e) = strain4(strain_of(d, s_elem([1, 2, 4], e)), mat%poisson, model%elem_plane(e))
            if (present(s_at) .and. present(e_at)) then
               do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
                  e_at(:, k) = strain4(strain_of(d, s_at([1, 2, 4], k)), mat%poisson, model%elem_plane(e))
               end do
            end if
         end associate
      end do
      if (present(dtemp)) call thermal_strain(model, dtemp, e_elem, e_at)
   end subroutine element_strains

   !> The strain (xx, yy, gamma_xy) whose stress under the elastic matrix d is sig:
   !> d has the isotropic block form [a b 0; b a 0; 0 0 g] (elastic_matrix).
   pure function strain_of(d, sig) result(eps)
      real(wp), intent(in) :: d(3, 3), sig(3)
      real(wp) :: eps(3), det
      det = d(1, 1)*d(2, 2) - d(1, 2)*d(2, 1)
      eps(1) = (d(2, 2)*sig(1) - d(1, 2)*sig(2))/det
      eps(2) = (d(1, 1)*sig(2) - d(2, 1)*sig(1))/det
      eps(3) = sig(3)/d(3, 3)
   end function strain_of

   !> (xx, yy, zz, xy) strain from the in-plane (xx, yy, gamma_xy): zz is 0 in
   !> plane strain, -nu/(1 - nu) (xx + yy) in plane stress.
   pure function strain4(eps, nu, plane) result(e4)
      real(wp), intent(in) :: eps(3), nu
      integer, intent(in) :: plane
      real(wp) :: e4(4), ezz
      ezz = 0.0_wp
      if (plane == plane_stress) ezz = -nu/(1.0_wp - nu)*(eps(1) + eps(2))
      e4 = [eps(1), eps(2), ezz, eps(3)]
   end function strain4
end module vemcontact_driver_assembly
