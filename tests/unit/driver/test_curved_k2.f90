!> Convergence of the k = 2 virtual element with curved sides on Lame's thick
!> cylinder: the quarter annulus 1 < r < 2, 0 < theta < pi/2, plane strain,
!> pressure p = 1 inside, the outside free, symmetry on the two straight edges
!> (u_y = 0 on y = 0, u_x = 0 on x = 0).  Exact: u_r = A r + B/r with
!> sigma_rr(1) = -p, sigma_rr(2) = 0.
!> Polar grids of nr x 2nr quadrilateral VPE2 cells (nr = 4, 8, 16); the radial
!> sides are straight, the arc sides either curved (side node on the circle,
!> the side the quadratic curve through its three nodes) or straight (side node
!> at the middle of the chord: the polygon through the corners, the straight-
!> sided k = 2 element).  The pressure's nodal forces are integrated along each
!> inner side as the element sees it (n ds = (y'(t), -x'(t)) dt, 3-point Gauss,
!> exact: a Lagrange quadratic times a linear function of t).
!> Energy error: integral of (sigma - sigma_h) : C : (sigma - sigma_h) over the
!> exact annulus, cell by cell on its polar rectangle (4 x 4 Gauss in r and
!> theta), sigma_h the element's projected (linear) stress.  L2 error: the
!> nodal displacement error, each node of a cell weighted by 1/8 of its area.
!> Measured (nr = 4 .. 64): curved sides energy rate 2.00, L2 rate 3.5 (nodal
!> values superconverge); straight sides energy rate 2.00 too (errors 4 %
!> larger: the chords' O(h^2) geometry error is below the energy error), but
!> L2 rate 2.00: the chords shorten the loaded boundary by O(h^2), which moves
!> every node by O(h^2) (55 times the curved error at nr = 16).
!> Asserted on nr = 8 -> 16: curved energy rate 1.8-2.2, curved L2 rate above
!> 2.8; straight L2 rate 1.8-2.2 with an error at least 10 times the curved one.
program test_curved_k2
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, plane_strain, form_vem
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element_vem2, only: vem2_workspace_size, vem2_stress
   use vemcontact_driver_linear, only: linear_system_t, ordering_auto
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_test_model, only: make_model
   implicit none
   real(wp), parameter :: young = 1.0_wp, nu = 0.3_wp, p_in = 1.0_wp
   real(wp), parameter :: pi = acos(-1.0_wp)
   integer, parameter :: nmesh = 3
   integer, parameter :: levels(nmesh) = [4, 8, 16]
   type(checker_t) :: t
   real(wp) :: een(nmesh, 2), el2(nmesh, 2), rate(2), rate2(2), lam, mu, ca, cb
   integer :: k, kind
   character(len=8), parameter :: names(2) = ['curved  ', 'straight']

   lam = young*nu/((1 + nu)*(1 - 2*nu))
   mu = young/(2*(1 + nu))
   cb = 2*p_in/(3*mu)                 ! sigma_rr(2) = 0, sigma_rr(1) = -p
   ca = mu*cb/(4*(lam + mu))
   do kind = 1, 2
      do k = 1, nmesh
         call errors(levels(k), kind == 1, el2(k, kind), een(k, kind))
         print '(a,i4,2es12.4)', 'Lame cylinder, '//trim(names(kind))//' arc sides: nr, L2 and energy errors', &
            levels(k), el2(k, kind), een(k, kind)
      end do
      rate(kind) = log(een(nmesh - 1, kind)/een(nmesh, kind))/log(2.0_wp)
      rate2(kind) = log(el2(nmesh - 1, kind)/el2(nmesh, kind))/log(2.0_wp)
      print '(a,2f6.3)', 'Lame cylinder, '//trim(names(kind))//' arc sides: L2 and energy rates ', &
         rate2(kind), rate(kind)
   end do
   call t%check(rate(1) > 1.8_wp .and. rate(1) < 2.2_wp, 'curved sides: energy rate near 2 (1.8-2.2)')
   call t%check(all(een(2:, 1) < een(:nmesh - 1, 1)), 'curved sides: errors decrease')
   call t%check(rate2(1) > 2.8_wp, 'curved sides: L2 rate above 2.8')
   call t%check(rate2(2) > 1.8_wp .and. rate2(2) < 2.2_wp, 'straight sides: L2 rate limited to 2 by the chords')
   call t%check(el2(nmesh, 2) > 10*el2(nmesh, 1), 'straight sides: L2 error at least 10 times the curved one')
   call t%finish()

contains

   !> Exact stress (xx, yy, xy) at p.
   pure function exact_stress(p) result(s)
      real(wp), intent(in) :: p(2)
      real(wp) :: s(3), r, c, sn, srr, stt
      r = norm2(p)
      c = p(1)/r
      sn = p(2)/r
      srr = 2*(lam + mu)*ca - 2*mu*cb/r**2
      stt = 2*(lam + mu)*ca + 2*mu*cb/r**2
      s = [srr*c*c + stt*sn*sn, srr*sn*sn + stt*c*c, (srr - stt)*c*sn]
   end function exact_stress

   !> L2 (nodal) and energy errors of the nr x 2nr polar grid, arc sides
   !> curved or straight.
   subroutine errors(nr, curved, el2, een)
      integer, intent(in) :: nr
      logical, intent(in) :: curved
      real(wp), intent(out) :: el2, een
      integer, parameter :: ng = 4
      real(wp), parameter :: gs = sqrt(3.0_wp/7.0_wp - 2.0_wp/7.0_wp*sqrt(1.2_wp))
      real(wp), parameter :: gl = sqrt(3.0_wp/7.0_wp + 2.0_wp/7.0_wp*sqrt(1.2_wp))
      real(wp), parameter :: gt(ng) = 0.5_wp + 0.5_wp*[-gl, -gs, gs, gl]
      real(wp), parameter :: gw(ng) = 0.5_wp*[(18 - sqrt(30.0_wp))/36, (18 + sqrt(30.0_wp))/36, &
                                              (18 + sqrt(30.0_wp))/36, (18 - sqrt(30.0_wp))/36]
      real(wp), parameter :: qt(3) = [0.5_wp - 0.5_wp*sqrt(0.6_wp), 0.5_wp, 0.5_wp + 0.5_wp*sqrt(0.6_wp)]
      real(wp), parameter :: qw(3) = [5.0_wp/18.0_wp, 8.0_wp/18.0_wp, 5.0_wp/18.0_wp]
      type(model_t) :: m
      type(linear_system_t) :: sys
      type(load_state_t) :: st
      type(error_t), allocatable :: error
      real(wp), allocatable :: x(:, :), u(:), work(:)
      integer(ip), allocatable :: ptr(:), conn(:)
      real(wp) :: d(3, 3), dinv(3, 3), xy(2, 8), ue(16), sn(3, 8), sig(3), r, th, dr, dth, p(2), ds(3)
      real(wp) :: lag(3), dp(2), g(2, 2), c1(3), c2(3), det
      integer :: nt, ncorner, nrad, i, j, e, a, b, node(8), q(3)
      nt = 2*nr
      dr = 1.0_wp/nr
      dth = 0.5_wp*pi/nt
      ncorner = (nr + 1)*(nt + 1)
      nrad = nr*(nt + 1)                       ! radial sides
      allocate (x(2, ncorner + nrad + (nr + 1)*nt), ptr(nr*nt + 1), conn(8*nr*nt))
      do i = 0, nr
         do j = 0, nt
            x(:, corner(nt, i, j)) = (1 + i*dr)*[cos(j*dth), sin(j*dth)]
         end do
      end do
      do i = 0, nr - 1
         do j = 0, nt
            x(:, radial(nr, nt, i, j)) = (1 + (i + 0.5_wp)*dr)*[cos(j*dth), sin(j*dth)]
         end do
      end do
      do i = 0, nr
         do j = 0, nt - 1
            if (curved) then
               x(:, arc(nr, nt, i, j)) = (1 + i*dr)*[cos((j + 0.5_wp)*dth), sin((j + 0.5_wp)*dth)]
            else
               x(:, arc(nr, nt, i, j)) = 0.5_wp*(x(:, corner(nt, i, j)) + x(:, corner(nt, i, j + 1)))
            end if
         end do
      end do
      e = 0
      ptr(1) = 1
      do i = 0, nr - 1
         do j = 0, nt - 1
            e = e + 1
            conn(ptr(e):ptr(e) + 7) = [corner(nt, i, j), corner(nt, i + 1, j), corner(nt, i + 1, j + 1), corner(nt, i, j + 1), &
                                       radial(nr, nt, i, j), arc(nr, nt, i + 1, j), radial(nr, nt, i, j + 1), arc(nr, nt, i, j)]
            ptr(e + 1) = ptr(e) + 8
         end do
      end do
      call make_model(x, ptr, conn, young, nu, plane_strain, form_vem, 1.0_wp, m, order=2)
      call elastic_matrix(young, nu, plane_strain, d)
      dinv = inverse3(d)
      allocate (u(2*m%nnode), st%fixed(2*m%nnode), st%prescribed(2*m%nnode), st%force(2*m%nnode), st%dload(0))
      allocate (work(vem2_workspace_size(8)))
      st%fixed = .false.
      st%prescribed = 0
      st%force = 0
      do j = 1, int(m%nnode)
         if (abs(x(2, j)) < 1.0e-12_wp) st%fixed(2*j) = .true.
         if (abs(x(1, j)) < 1.0e-12_wp) st%fixed(2*j - 1) = .true.
      end do
      ! pressure on side 4 (corner 4 -> corner 1, node 8) of the inner cells
      do j = 0, nt - 1
         q = [corner(nt, 0, j + 1), corner(nt, 0, j), arc(nr, nt, 0, j)]
         do a = 1, 3
            lag = [2*(qt(a) - 0.5_wp)*(qt(a) - 1), 2*qt(a)*(qt(a) - 0.5_wp), 4*qt(a)*(1 - qt(a))]
            dp = (4*qt(a) - 3)*x(:, q(1)) + (4*qt(a) - 1)*x(:, q(2)) + (4 - 8*qt(a))*x(:, q(3))
            do b = 1, 3
               st%force(2*q(b) - 1:2*q(b)) = st%force(2*q(b) - 1:2*q(b)) - p_in*qw(a)*lag(b)*[dp(2), -dp(1)]
            end do
         end do
      end do
      call sys%setup(m, ordering_auto, error)
      if (.not. allocated(error)) call sys%solve_state(m, st, u, error)
      call t%check(.not. allocated(error), 'solve')
      een = huge(1.0_wp)
      el2 = huge(1.0_wp)
      if (allocated(error)) return
      een = 0
      el2 = 0
      do e = 1, int(m%nelem)
         node = conn(ptr(e):ptr(e) + 7)
         do a = 1, 8
            xy(:, a) = x(:, node(a))
            ue(2*a - 1:2*a) = u(2*node(a) - 1:2*node(a))
         end do
         call vem2_stress(xy, d, 1.0_wp, ue, work, sig, signode=sn)
         i = (e - 1)/nt
         do a = 1, 8
            r = norm2(xy(:, a))
            el2 = el2 + (1 + (i + 0.5_wp)*dr)*dr*dth/8*sum((ue(2*a - 1:2*a) - (ca*r + cb/r)*xy(:, a)/r)**2)
         end do
         ! the linear stress from its values at corners 1, 2, 4
         g(:, 1) = xy(:, 2) - xy(:, 1)
         g(:, 2) = xy(:, 4) - xy(:, 1)
         det = g(1, 1)*g(2, 2) - g(1, 2)*g(2, 1)
         i = (e - 1)/nt
         j = mod(e - 1, nt)
         do a = 1, ng
            do b = 1, ng
               r = 1 + (i + gt(a))*dr
               th = (j + gt(b))*dth
               p = r*[cos(th), sin(th)] - xy(:, 1)
               ! p = s g(:, 1) + w g(:, 2)
               c1 = (p(1)*g(2, 2) - p(2)*g(1, 2))/det*(sn(:, 2) - sn(:, 1))
               c2 = (g(1, 1)*p(2) - g(2, 1)*p(1))/det*(sn(:, 4) - sn(:, 1))
               ds = exact_stress(r*[cos(th), sin(th)]) - (sn(:, 1) + c1 + c2)
               een = een + gw(a)*gw(b)*dr*dth*r*dot_product(ds, matmul(dinv, ds))
            end do
         end do
      end do
      een = sqrt(een)
      el2 = sqrt(el2)
   end subroutine errors

   !> Node numbers: corners (i, j) of the polar grid, then the radial sides'
   !> nodes (i + 1/2, j), then the arc sides' nodes (i, j + 1/2).
   pure integer(ip) function corner(nt, i, j)
      integer, intent(in) :: nt, i, j
      corner = int(i*(nt + 1) + j + 1, ip)
   end function corner

   pure integer(ip) function radial(nr, nt, i, j)
      integer, intent(in) :: nr, nt, i, j
      radial = int((nr + 1)*(nt + 1) + i*(nt + 1) + j + 1, ip)
   end function radial

   pure integer(ip) function arc(nr, nt, i, j)
      integer, intent(in) :: nr, nt, i, j
      arc = int((nr + 1)*(nt + 1) + nr*(nt + 1) + i*nt + j + 1, ip)
   end function arc

   pure function inverse3(a) result(ai)
      real(wp), intent(in) :: a(3, 3)
      real(wp) :: ai(3, 3), det
      ai(1, 1) = a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)
      ai(1, 2) = a(1, 3)*a(3, 2) - a(1, 2)*a(3, 3)
      ai(1, 3) = a(1, 2)*a(2, 3) - a(1, 3)*a(2, 2)
      ai(2, 1) = a(2, 3)*a(3, 1) - a(2, 1)*a(3, 3)
      ai(2, 2) = a(1, 1)*a(3, 3) - a(1, 3)*a(3, 1)
      ai(2, 3) = a(1, 3)*a(2, 1) - a(1, 1)*a(2, 3)
      ai(3, 1) = a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1)
      ai(3, 2) = a(1, 2)*a(3, 1) - a(1, 1)*a(3, 2)
      ai(3, 3) = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
      det = a(1, 1)*ai(1, 1) + a(1, 2)*ai(2, 1) + a(1, 3)*ai(3, 1)
      ai = ai/det
   end function inverse3
end program test_curved_k2
