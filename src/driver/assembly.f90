!> Global assembly: stiffness into the fixed pattern, load vector, element stresses.
!> Work arrays are sized once for the largest element, so the element loop allocates nothing.
module vemcontact_driver_assembly
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, append_message, err_model, err_internal
   use vemcontact_model, only: model_t, dload_t, location_string, dload_grav, dload_pressure, dload_hydrostatic, &
                               plane_stress
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: add_element_matrix
   use vemcontact_material_elastic, only: elastic_matrix, out_of_plane_stress
   use vemcontact_element, only: element_stiffness, element_stress, element_load_weights, &
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
   subroutine assemble_stiffness(model, a, error)
      type(model_t), intent(in) :: model
      type(sym_csc_t), intent(inout) :: a
      type(error_t), allocatable, intent(out) :: error
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
         first = model%elem_ptr(e)
         n = model%elem_ptr(e + 1) - first
         xy(:, :n) = model%x(:, model%elem_conn(first:first + n - 1))
         associate (mat => model%materials(model%elem_mat(e)))
            call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
         end associate
         if (allocated(model%elem_stab)) then
            call element_stiffness(model%elem_form(e), xy(:, :n), d, &
                                   model%elem_thick(e), ke(:2*n, :2*n), work, info, model%elem_stab(e))
         else
            call element_stiffness(model%elem_form(e), xy(:, :n), d, &
                                   model%elem_thick(e), ke(:2*n, :2*n), work, info)
         end if
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
      case (2); s = 'FORMULATION=FEM needs a 3- or 4-node element'
      case (3); s = 'FEM Jacobian is not positive at a Gauss point (element too distorted for FEM; use FORMULATION=VEM)'
      case default; s = 'element routine failed'
      end select
   end function info_text

   !> Load vector of the state: concentrated loads plus distributed loads.
   subroutine assemble_loads(model, force, dloads, f)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: force(:)
      type(dload_t), intent(in) :: dloads(:)
      real(wp), intent(out) :: f(:)
      real(wp), allocatable :: xy(:, :), w(:), work(:)
      real(wp) :: t(2), scale, wa, wb
      integer :: k, n, e, a, b, i, nmax
      integer(ip) :: first, node
      nmax = max_element_nodes(model)
      allocate (xy(2, nmax), w(nmax), work(element_workspace_size(nmax)))
      f = force
      do k = 1, size(dloads)
         e = dloads(k)%elem
         first = model%elem_ptr(e)
         n = model%elem_ptr(e + 1) - first
         select case (dloads(k)%kind)
         case (dload_grav)
            xy(:, :n) = model%x(:, model%elem_conn(first:first + n - 1))
            call element_load_weights(model%elem_form(e), xy(:, :n), work, w(:n))
            scale = model%materials(model%elem_mat(e))%density*dloads(k)%magnitude*model%elem_thick(e)
            do i = 1, n
               node = model%elem_conn(first + i - 1)
               f(2*node - 1:2*node) = f(2*node - 1:2*node) + scale*w(i)*dloads(k)%dir
            end do
         case (dload_pressure)
            ! edge a->b of a counter-clockwise polygon has outward normal (t_y, -t_x)/|t|;
            ! a positive pressure pushes inward, split equally (the trace is linear on the edge)
            a = model%elem_conn(first + dloads(k)%side - 1)
            b = model%elem_conn(first + mod(dloads(k)%side, n))
            t = model%x(:, b) - model%x(:, a)
            scale = -0.5_wp*dloads(k)%magnitude*model%elem_thick(e)
            f(2*a - 1:2*a) = f(2*a - 1:2*a) + scale*[t(2), -t(1)]
            f(2*b - 1:2*b) = f(2*b - 1:2*b) + scale*[t(2), -t(1)]
         case (dload_hydrostatic)
            a = model%elem_conn(first + dloads(k)%side - 1)
            b = model%elem_conn(first + mod(dloads(k)%side, n))
            t = model%x(:, b) - model%x(:, a)
            call hydrostatic_moments(dloads(k), model%x(2, a), model%x(2, b), wa, wb)
            f(2*a - 1:2*a) = f(2*a - 1:2*a) - wa*model%elem_thick(e)*[t(2), -t(1)]
            f(2*b - 1:2*b) = f(2*b - 1:2*b) - wb*model%elem_thick(e)*[t(2), -t(1)]
         end select
      end do
   end subroutine assemble_loads

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
   subroutine element_stresses(model, u, s_elem)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      real(wp), intent(out) :: s_elem(:, :)
      real(wp), allocatable :: xy(:, :), ue(:), work(:)
      real(wp) :: d(3, 3), sig(3)
      integer :: e, n, i, nmax
      integer(ip) :: first, node
      nmax = max_element_nodes(model)
      allocate (xy(2, nmax), ue(2*nmax), work(element_workspace_size(nmax)))
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         n = model%elem_ptr(e + 1) - first
         do i = 1, n
            node = model%elem_conn(first + i - 1)
            xy(:, i) = model%x(:, node)
            ue(2*i - 1:2*i) = u(2*node - 1:2*node)
         end do
         associate (mat => model%materials(model%elem_mat(e)))
            call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
            call element_stress(model%elem_form(e), xy(:, :n), d, ue(:2*n), work, sig)
            s_elem(:, e) = [sig(1), sig(2), out_of_plane_stress(mat%poisson, model%elem_plane(e), sig(1), sig(2)), sig(3)]
         end associate
      end do
   end subroutine element_stresses

   !> Element strains E (total strain, Abaqus' E) `(xx, yy, zz, xy)` with the
   !> engineering shear strain gamma_xy = 2 eps_xy, as Abaqus writes E12; the
   !> same recovery as element_stresses: every kernel's stress is d times its
   !> (projected, for VEM; Gauss-averaged, for the quad) strain, so the kernel
   !> run with d = identity returns that strain, and S = D E holds element by
   !> element.  zz: 0 in plane strain; in plane stress the thickness strain
   !> -nu/(1 - nu) (xx + yy) that makes S_zz zero.
   subroutine element_strains(model, u, e_elem)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:)
      real(wp), intent(out) :: e_elem(:, :)
      real(wp), allocatable :: xy(:, :), ue(:), work(:)
      real(wp), parameter :: identity(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
                                                       0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
      real(wp) :: eps(3), ezz, nu
      integer :: e, n, i, nmax
      integer(ip) :: first, node
      nmax = max_element_nodes(model)
      allocate (xy(2, nmax), ue(2*nmax), work(element_workspace_size(nmax)))
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         n = model%elem_ptr(e + 1) - first
         do i = 1, n
            node = model%elem_conn(first + i - 1)
            xy(:, i) = model%x(:, node)
            ue(2*i - 1:2*i) = u(2*node - 1:2*node)
         end do
         call element_stress(model%elem_form(e), xy(:, :n), identity, ue(:2*n), work, eps)
         ezz = 0.0_wp
         if (model%elem_plane(e) == plane_stress) then
            nu = model%materials(model%elem_mat(e))%poisson
            ezz = -nu/(1.0_wp - nu)*(eps(1) + eps(2))
         end if
         e_elem(:, e) = [eps(1), eps(2), ezz, eps(3)]
      end do
   end subroutine element_strains
end module vemcontact_driver_assembly
