!> Thermal strains (*EXPANSION with *INITIAL CONDITIONS, TYPE=TEMPERATURE and
!> *TEMPERATURE): eps_th = alpha dT, dT = T - T0, isotropic.  The stress is
!> S = D (E - eps0) with the in-plane eigenstrain eps0 = c alpha dT (1, 1, 0):
!> c = 1 in plane stress, c = 1 + nu in plane strain, where eps_zz = 0 makes the
!> out-of-plane stress S_zz = nu (S_xx + S_yy) - E alpha dT (CalculiX's plane
!> strain: its one-layer brick held in z).  So D eps0 = c s alpha dT (1, 1, 0),
!> s = D11 + D12: c s = E / (1 - nu) in plane stress, E / (1 - 2 nu) in plane strain.
!>
!> Nodal forces f(v) = integral of (D eps0) : eps(v) = k integral of dT div v
!> (k = c s alpha thickness), per element with dT its linear fit to the element's
!> nodal values (exact for a constant or linear temperature field):
!>  - first-order elements: the k = 1 virtual element sees the strain projected
!>    onto constants, so only the mean of dT enters, f_i = k mean(dT) times the
!>    boundary integral of N_i n, g_i = (y_{i+1} - y_{i-1}, x_{i-1} - x_{i+1}) / 2;
!>    CPE4/CPS4 and CPE3/CPS3 take the same element mean, as CalculiX does for its
!>    linear elements (a CPE4 plate under a linear dT agrees with ccx 2.20 to its
!>    printed digits this way, and is 10 % off with dT at each Gauss point);
!>  - second-order elements (k = 2 virtual element, CPE8/CPE8R/CPE6): integration by parts,
!>    k (boundary integral of dT v.n - grad dT . integral of v): the first term on
!>    each side with 3 Gauss points along its (quadratic or straight) map, the
!>    second a constant body force -k grad dT through element_body_load (for the
!>    k = 2 element its cell moments, which its strain projection onto linear
!>    fields sees exactly when dT is linear).
module vemcontact_driver_thermal
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, form_fem, plane_strain, element_order
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element, only: element_body_load, element_workspace_size
   implicit none
   private

   public :: has_thermal, add_thermal_forces, thermal_stress, thermal_strain, add_thermal_body

   real(wp), parameter :: gs(3) = [0.5_wp - sqrt(0.15_wp), 0.5_wp, 0.5_wp + sqrt(0.15_wp)]
   real(wp), parameter :: gw(3) = [5.0_wp/18.0_wp, 8.0_wp/18.0_wp, 5.0_wp/18.0_wp]

contains

   !> Whether any element has a thermal strain under the temperature changes dtemp.
   pure logical function has_thermal(model, dtemp)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dtemp(:)
      integer :: k
      has_thermal = .false.
      if (.not. any(abs(dtemp) > 0.0_wp)) return
      do k = 1, size(model%materials)
         if (model%materials(k)%has_expansion .and. abs(model%materials(k)%expansion) > 0.0_wp) has_thermal = .true.
      end do
   end function has_thermal

   !> f <- f + the nodal forces of the thermal strains of dtemp(nnode).
   subroutine add_thermal_forces(model, dtemp, f)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dtemp(:)
      real(wp), intent(inout) :: f(:)
      real(wp), allocatable :: xy(:, :), dt(:), fe(:), fb(:, :), work(:), w(:)
      real(wp) :: d(3, 3), k, t0, g(2), xc(2), xa(2), tau
      integer :: e, n, nmax, i, info, order
      integer(ip) :: node
      if (.not. has_thermal(model, dtemp)) return
      nmax = 0
      do e = 1, model%nelem
         nmax = max(nmax, int(model%elem_ptr(e + 1) - model%elem_ptr(e)))
      end do
      allocate (xy(2, nmax), dt(nmax), fe(2*nmax), fb(2*nmax, 2), work(element_workspace_size(nmax)), w(nmax))
      do e = 1, model%nelem
         associate (mat => model%materials(model%elem_mat(e)))
            if (.not. mat%has_expansion) cycle
            call gather(model, dtemp, e, xy, dt, n)
            if (.not. any(abs(dt(:n)) > 0.0_wp)) cycle
            call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
            k = eigen_factor(mat%poisson, model%elem_plane(e))*(d(1, 1) + d(1, 2))*mat%expansion*model%elem_thick(e)
         end associate
         order = element_order(model%elem_type(e))
         call linear_fit(xy(:, :n), dt(:n), t0, g, xc)
         fe(:2*n) = 0.0_wp
         if (order == 1) then
            xa = area_centroid(xy(:, :n))
            call boundary_mean(xy(:, :n), k*(t0 + dot_product(g, xa - xc)), fe(:2*n))
         else
            call boundary_term(xy(:, :n), order, k, t0, g, xc, fe(:2*n))
            tau = 1.0_wp
            if (allocated(model%elem_stab)) tau = model%elem_stab(e)
            call element_body_load(model%elem_form(e), xy(:, :n), d, model%elem_thick(e), fb(:2*n, :), work, w, &
                                   info, tau, order)
            ! fb has the thickness: the body force per unit volume is -k grad dT / thickness
            fe(:2*n) = fe(:2*n) - matmul(fb(:2*n, :), k*g/model%elem_thick(e))
         end if
         do i = 1, n
            node = model%elem_conn(model%elem_ptr(e) + i - 1)
            f(2*node - 1:2*node) = f(2*node - 1:2*node) + fe(2*i - 1:2*i)
         end do
      end do
   end subroutine add_thermal_forces

   !> body(:, e) <- body(:, e) - c s alpha grad dT per unit volume, the body-force
   !> part of the thermal load (integration by parts above), which the k = 2
   !> virtual element needs again to recover its condensed cell moments.
   pure subroutine add_thermal_body(model, dtemp, body)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dtemp(:)
      real(wp), intent(inout) :: body(:, :)
      real(wp), allocatable :: xy(:, :), dt(:)
      real(wp) :: d(3, 3), t0, g(2), xc(2)
      integer :: e, n
      if (.not. has_thermal(model, dtemp)) return
      allocate (xy(2, 0), dt(0))
      do e = 1, model%nelem
         associate (mat => model%materials(model%elem_mat(e)))
            if (.not. mat%has_expansion) cycle
            n = int(model%elem_ptr(e + 1) - model%elem_ptr(e))
            if (size(dt) < n) then
               deallocate (xy, dt)
               allocate (xy(2, n), dt(n))
            end if
            call gather(model, dtemp, e, xy, dt, n)
            call linear_fit(xy(:, :n), dt(:n), t0, g, xc)
            call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
            body(:, e) = body(:, e) - eigen_factor(mat%poisson, model%elem_plane(e))*(d(1, 1) + d(1, 2))* &
                         mat%expansion*g
         end associate
      end do
   end subroutine add_thermal_body

   !> c of the eigenstrain c alpha dT: 1 in plane stress, 1 + nu in plane strain.
   pure real(wp) function eigen_factor(nu, plane)
      real(wp), intent(in) :: nu
      integer, intent(in) :: plane
      eigen_factor = 1.0_wp
      if (plane == plane_strain) eigen_factor = 1.0_wp + nu
   end function eigen_factor

   !> Coordinates and dT of the nodes of element e.
   pure subroutine gather(model, dtemp, e, xy, dt, n)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dtemp(:)
      integer, intent(in) :: e
      real(wp), intent(inout) :: xy(:, :), dt(:)
      integer, intent(out) :: n
      integer :: i
      integer(ip) :: node
      n = int(model%elem_ptr(e + 1) - model%elem_ptr(e))
      do i = 1, n
         node = model%elem_conn(model%elem_ptr(e) + i - 1)
         xy(:, i) = model%x(:, node)
         dt(i) = dtemp(node)
      end do
   end subroutine gather

   !> Least-squares linear fit dT(x) = t0 + g . (x - xc) of the nodal values
   !> (xc the mean of the nodes): exact when they are linear in x.
   pure subroutine linear_fit(xy, dt, t0, g, xc)
      real(wp), intent(in) :: xy(:, :), dt(:)
      real(wp), intent(out) :: t0, g(2), xc(2)
      real(wp) :: a(2, 2), r(2), det, dx(2)
      integer :: i, n
      n = size(dt)
      xc = sum(xy, dim=2)/n
      t0 = sum(dt)/n
      a = 0.0_wp
      r = 0.0_wp
      do i = 1, n
         dx = xy(:, i) - xc
         a(1, 1) = a(1, 1) + dx(1)*dx(1)
         a(1, 2) = a(1, 2) + dx(1)*dx(2)
         a(2, 2) = a(2, 2) + dx(2)*dx(2)
         r = r + dx*(dt(i) - t0)
      end do
      det = a(1, 1)*a(2, 2) - a(1, 2)**2
      g = 0.0_wp
      if (det > 0.0_wp) g = [a(2, 2)*r(1) - a(1, 2)*r(2), a(1, 1)*r(2) - a(1, 2)*r(1)]/det
   end subroutine linear_fit

   !> Centroid of the polygon xy (counter-clockwise).
   pure function area_centroid(xy) result(c)
      real(wp), intent(in) :: xy(:, :)
      real(wp) :: c(2), cr, area
      integer :: i, j, n
      n = size(xy, 2)
      c = 0.0_wp
      area = 0.0_wp
      do i = 1, n
         j = merge(1, i + 1, i == n)
         cr = xy(1, i)*xy(2, j) - xy(1, j)*xy(2, i)
         area = area + cr
         c = c + cr*(xy(:, i) + xy(:, j))
      end do
      c = c/(3.0_wp*area)
   end function area_centroid

   !> fe_i = q g_i with g_i the boundary integral of N_i n (first-order polygon).
   pure subroutine boundary_mean(xy, q, fe)
      real(wp), intent(in) :: xy(:, :), q
      real(wp), intent(out) :: fe(:)
      integer :: i, n, ip1, im1
      n = size(xy, 2)
      do i = 1, n
         ip1 = merge(1, i + 1, i == n)
         im1 = merge(n, i - 1, i == 1)
         fe(2*i - 1) = 0.5_wp*q*(xy(2, ip1) - xy(2, im1))
         fe(2*i) = 0.5_wp*q*(xy(1, im1) - xy(1, ip1))
      end do
   end subroutine boundary_mean

   !> fe += k times the boundary integral of dT N_i n over every side, dT = t0 +
   !> g . (x - xc); a side of a second-order element runs from corner j through
   !> node nc + j to corner j + 1 along its quadratic map.
   pure subroutine boundary_term(xy, order, k, t0, g, xc, fe)
      real(wp), intent(in) :: xy(:, :), k, t0, g(2), xc(2)
      integer, intent(in) :: order
      real(wp), intent(inout) :: fe(:)
      real(wp) :: s, nsh(3), dn(3), x(2), tang(2), temp
      integer :: j, q, nc, m, idx(3), a
      nc = size(xy, 2)/order
      do j = 1, nc
         idx(1) = j
         idx(2) = merge(1, j + 1, j == nc)
         idx(3) = nc + j
         m = merge(3, 2, order == 2)
         do q = 1, 3
            s = gs(q)
            if (m == 3) then
               nsh = [(1 - s)*(1 - 2*s), s*(2*s - 1), 4*s*(1 - s)]
               dn = [4*s - 3, 4*s - 1, 4 - 8*s]
            else
               nsh = [1 - s, s, 0.0_wp]
               dn = [-1.0_wp, 1.0_wp, 0.0_wp]
            end if
            x = 0.0_wp
            tang = 0.0_wp
            do a = 1, m
               x = x + nsh(a)*xy(:, idx(a))
               tang = tang + dn(a)*xy(:, idx(a))
            end do
            temp = t0 + dot_product(g, x - xc)
            do a = 1, m
               ! outward normal times the length element: (t_y, -t_x) ds
               fe(2*idx(a) - 1) = fe(2*idx(a) - 1) + gw(q)*k*temp*nsh(a)*tang(2)
               fe(2*idx(a)) = fe(2*idx(a)) - gw(q)*k*temp*nsh(a)*tang(1)
            end do
         end do
      end do
   end subroutine boundary_term

   !> S <- S - D eps0 for the element stresses s_elem(4, nelem) (xx, yy, zz, xy)
   !> at the element's mean dT, and s_at (optional, per element node) at the
   !> node's dT for second-order elements, the mean for first-order ones (whose
   !> nodal stress is the element's); S_zz of plane strain = nu (S_xx + S_yy) -
   !> E alpha dT.
   pure subroutine thermal_stress(model, dtemp, s_elem, s_at)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dtemp(:)
      real(wp), intent(inout) :: s_elem(:, :)
      real(wp), intent(inout), optional :: s_at(:, :)
      call thermal_update(model, dtemp, .false., s_elem, s_at)
   end subroutine thermal_stress

   !> E <- E + the thermal strain, for the strains recovered as D^-1 S (mechanical):
   !> the total strain (Abaqus' and CalculiX's E).  Plane stress: alpha dT in xx,
   !> yy and zz; plane strain: (1 + nu) alpha dT in xx and yy (zz stays 0).
   pure subroutine thermal_strain(model, dtemp, e_elem, e_at)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dtemp(:)
      real(wp), intent(inout) :: e_elem(:, :)
      real(wp), intent(inout), optional :: e_at(:, :)
      call thermal_update(model, dtemp, .true., e_elem, e_at)
   end subroutine thermal_strain

   !> The walk thermal_stress and thermal_strain share: every element with expansion,
   !> v_elem at the element's mean dT and v_at (optional) at each element point's dT
   !> (point_dt); `strain` chooses the strain's addition over the stress's correction.
   pure subroutine thermal_update(model, dtemp, strain, v_elem, v_at)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dtemp(:)
      logical, intent(in) :: strain
      real(wp), intent(inout) :: v_elem(:, :)
      real(wp), intent(inout), optional :: v_at(:, :)
      real(wp) :: dmean
      integer :: e, i
      integer(ip) :: first
      if (.not. has_thermal(model, dtemp)) return
      do e = 1, model%nelem
         if (.not. model%materials(model%elem_mat(e))%has_expansion) cycle
         dmean = mean_dt(model, dtemp, e)
         call update(v_elem(:, e), dmean)
         if (present(v_at)) then
            first = model%elem_ptr(e)
            do i = 1, int(model%elem_ptr(e + 1) - first)
               call update(v_at(:, first + i - 1), point_dt(model, dtemp, e, first + i - 1, dmean))
            end do
         end if
      end do
   contains
      pure subroutine update(v, dt)
         real(wp), intent(inout) :: v(4)
         real(wp), intent(in) :: dt
         real(wp) :: d(3, 3), s0
         associate (mat => model%materials(model%elem_mat(e)))
            if (strain) then
               if (model%elem_plane(e) == plane_strain) then
                  v(1:2) = v(1:2) + (1.0_wp + mat%poisson)*mat%expansion*dt
               else
                  v(1:3) = v(1:3) + mat%expansion*dt
               end if
            else
               call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
               s0 = eigen_factor(mat%poisson, model%elem_plane(e))*(d(1, 1) + d(1, 2))*mat%expansion*dt
               v(1:2) = v(1:2) - s0
               if (model%elem_plane(e) == plane_strain) &
                  v(3) = mat%poisson*(v(1) + v(2)) - mat%young*mat%expansion*dt
            end if
         end associate
      end subroutine update
   end subroutine thermal_update

   !> dT at the element point k (an index into elem_conn) of element e: the node's own
   !> for a second-order element, whose stress varies over it, the element's mean
   !> `dmean` for a first-order one, whose nodal stress is the element's.
   pure real(wp) function point_dt(model, dtemp, e, k, dmean)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dtemp(:), dmean
      integer, intent(in) :: e
      integer(ip), intent(in) :: k
      if (element_order(model%elem_type(e)) == 2) then
         point_dt = dtemp(model%elem_conn(k))
      else
         point_dt = dmean
      end if
   end function point_dt

   !> The mean of dT over element e: its linear fit at the centroid of the corners' polygon.
   pure real(wp) function mean_dt(model, dtemp, e)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dtemp(:)
      integer, intent(in) :: e
      real(wp), allocatable :: xy(:, :), dt(:)
      real(wp) :: t0, g(2), xc(2)
      integer :: n, nc
      n = int(model%elem_ptr(e + 1) - model%elem_ptr(e))
      allocate (xy(2, n), dt(n))
      call gather(model, dtemp, e, xy, dt, n)
      call linear_fit(xy, dt, t0, g, xc)
      nc = n/element_order(model%elem_type(e))
      mean_dt = t0 + dot_product(g, area_centroid(xy(:, :nc)) - xc)
   end function mean_dt
end module vemcontact_driver_thermal
