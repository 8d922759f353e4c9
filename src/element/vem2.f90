!> Second-order (k = 2) virtual element for 2D small-strain elasticity on a
!> polygon with n >= 3 corners, convex or not, collinear corners allowed, its
!> sides straight or curved; docs/vem-formulation.md has the derivation.
!>
!> Nodes: the n corners counter-clockwise, then one node per side (side i runs
!> from corner i to corner i+1, its node is node n+i), so 2n nodes, as in
!> Abaqus' quadratic elements.  Side i is the quadratic curve through its
!> three nodes, x(t) = a L_a(t) + b L_b(t) + m L_m(t) for t in [0, 1], with
!> L_a, L_b, L_m the Lagrange quadratics of t = 0, 1, 1/2 (the side of the
!> isoparametric 8-node quad); a side node at the middle of its corners gives
!> the straight side.  On each side the trace of u is quadratic in t (the
!> curved-edge space of Beirao da Veiga, Russo, Vacca 2019): u at the corners
!> and at the side node (t = 1/2) fix it.  Degrees of freedom: u at the 2n
!> nodes and the cell moments mu = (1/|E|) integral of u (2 components),
!> numbered as a node 2n+1.
!>
!> Consistency: the L2 projection of the strain onto linear symmetric tensors,
!>   integral eps(u) : tau = - integral u . div tau + boundary integral u . tau n,
!> computable for every linear tau (div tau is constant: the cell moment; the
!> boundary term: along each side's parametrization, n ds = (y'(t), -x'(t)) dt).
!> Stabilisation: (I - Pi)^T S (I - Pi) per component, with Pi the H1
!> projection of each component onto quadratics (mean fixed by the cell
!> moment) and S diagonal: the D-recipe of the k = 1 element (vem_tau,
!> vem_floor, vem_lambda_cap of vemcontact_element_vem), the weight of a node
!> the mean of its two Kc diagonals computed with lambda capped at 2 mu.
!> The cell moments are condensed statically: the kernels return the 4n x 4n
!> stiffness of the node dofs, the nodal forces of a unit body force
!> (vem2_body_load) and recover the moments for the stress (vem2_stress).
!> Every integral is a boundary integral along the sides' parametrizations
!> (the cell's area, centroid and polynomial moments by the divergence
!> theorem), with the 4-point Gauss rule in t, exact for polynomials of degree
!> 7 in t: the integrands have degree <= 7 on a curved side and <= 3 on a
!> straight one, so every integral is exact and a straight-sided element is the
!> straight-sided k = 2 element (Simpson on each side) to round-off.
!> On straight sides the space contains the quadratics (patch test exact for a
!> quadratic field); on curved sides it contains the linear fields (rigid
!> motions and constant strain exact), not the quadratics.
!>
!> Kernels are pure, take a work array of vem2_workspace_size(2n) reals and
!> allocate nothing.
module vemcontact_element_vem2
   use vemcontact_kinds, only: wp
   use vemcontact_element_vem, only: vem_tau, vem_floor, vem_lambda_cap
   implicit none
   private

   public :: vem2_workspace_size, vem2_stiffness, vem2_body_load, vem2_stress

   !> info codes (1 is the bad area of every element kernel)
   integer, parameter, public :: vem2_bad_area = 1
   integer, parameter, public :: vem2_bad_nodes = 4      !< odd node count or fewer than 6 nodes
   integer, parameter, public :: vem2_bad_side_node = 5  !< a side node too far from the middle of its side
   integer, parameter, public :: vem2_singular = 6       !< projection or condensation failed
   !> Limits on where a side node may sit, with d = m - (a + b)/2 its offset
   !> from the middle of the chord a -> b of length l: along the chord,
   !> |d . (b - a)| <= vem2_side_tangent l^2 (the speed |x'(t)| of the side's
   !> parametrization then varies by at most a factor 3; at l^2/4 it vanishes and
   !> the side folds); across it, |d| <= vem2_side_bulge l (a half circle at most).
   real(wp), parameter, public :: vem2_side_tangent = 0.125_wp
   real(wp), parameter, public :: vem2_side_bulge = 0.5_wp

   ! 4-point Gauss-Legendre rule on [0, 1] (exact for degree 7)
   real(wp), parameter :: gq_s = sqrt(3.0_wp/7.0_wp - 2.0_wp/7.0_wp*sqrt(1.2_wp))
   real(wp), parameter :: gq_l = sqrt(3.0_wp/7.0_wp + 2.0_wp/7.0_wp*sqrt(1.2_wp))
   real(wp), parameter :: gl_t(4) = 0.5_wp + 0.5_wp*[-gq_l, -gq_s, gq_s, gq_l]
   real(wp), parameter :: gl_w(4) = 0.5_wp*[(18.0_wp - sqrt(30.0_wp))/36.0_wp, (18.0_wp + sqrt(30.0_wp))/36.0_wp, &
                                         (18.0_wp + sqrt(30.0_wp))/36.0_wp, (18.0_wp - sqrt(30.0_wp))/36.0_wp]
   ! scaled gradients h grad m of the quadratic monomials m = 1, xi, eta, xi^2,
   ! xi eta, eta^2 as linear functions: coefficients of (1, xi, eta)
   real(wp), parameter :: cgx(3, 6) = reshape([0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0], [3, 6])
   real(wp), parameter :: cgy(3, 6) = reshape([0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 2], [3, 6])
   ! h^2 times the Laplacian of each monomial
   real(wp), parameter :: hlap(6) = [0, 0, 0, 2, 0, 2]

contains

   !> Reals of work needed by an element of `nnode` = 2n nodes.
   pure function vem2_workspace_size(nnode) result(nw)
      integer, intent(in) :: nnode
      integer :: nw, ns, nd
      ns = max(nnode, 1) + 1
      nd = 2*ns
      nw = nd*nd + 19*nd + ns*ns + 7*ns
   end function vem2_workspace_size

   !> Condensed stiffness ke(4n, 4n) of the node dofs, order (u1x, u1y, ...).
   !> info: 0 ok, 1 non-positive area, 4 not 2n >= 6 nodes, 5 a side node too
   !> far from the middle of its side (vem2_side_tangent, vem2_side_bulge), 6
   !> singular projection; ke = 0 when info /= 0.
   !> `tau` (> 0, default vem_tau) scales the stabilisation.
   pure subroutine vem2_stiffness(xy, d, thick, ke, work, info, tau)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: ke(:, :)
      real(wp), intent(inout) :: work(:)
      integer, intent(out) :: info
      real(wp), intent(in), optional :: tau
      real(wp) :: ts, area, kmi(2, 2)
      integer :: nn, nd
      ts = vem_tau
      if (present(tau)) ts = tau
      ke = 0.0_wp
      nn = size(xy, 2)
      nd = 2*nn + 2
      call full_stiffness(xy, d, thick, ts, work, nn, info, area)
      if (info /= 0) return
      call condense(work(1:nd*nd), nn, ke, kmi, info)
   end subroutine vem2_stiffness

   !> Nodal forces fb(4n, 2) of a unit body force per unit volume: column c is
   !> the condensed load of b = e_c, so a body force b gives fb b.  Before
   !> condensation the load sits on the cell moments alone (integral of b . v
   !> = |E| t b . mu for a constant b, exact); condensation spreads it over the
   !> nodes with -K_nm K_mm^-1.  The columns sum (over a component) to |E| t.
   pure subroutine vem2_body_load(xy, d, thick, fb, work, info, tau)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: fb(:, :)
      real(wp), intent(inout) :: work(:)
      integer, intent(out) :: info
      real(wp), intent(in), optional :: tau
      real(wp) :: ts, area
      integer :: nn
      ts = vem_tau
      if (present(tau)) ts = tau
      fb = 0.0_wp
      nn = size(xy, 2)
      call full_stiffness(xy, d, thick, ts, work, nn, info, area)
      if (info /= 0) return
      call moment_load(work(1:(2*nn + 2)**2), nn, thick*area, fb, info)
   end subroutine vem2_body_load

   !> Stress (sxx, syy, sxy) of the element: `sig` the mean over the element;
   !> `signode(3, 2n)` (optional) the projected stress at each node.  The cell
   !> moments are recovered from the node displacements ue(4n) and the body
   !> force `body` (per unit volume, default zero) the load was made with.
   !> Zero when vem2_stiffness rejects the element.
   pure subroutine vem2_stress(xy, d, thick, ue, work, sig, body, tau, signode)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick, ue(:)
      real(wp), intent(inout) :: work(:)
      real(wp), intent(out) :: sig(3)
      real(wp), intent(in), optional :: body(2), tau
      real(wp), intent(out), optional :: signode(:, :)
      real(wp) :: ts, area, b(2)
      integer :: nn, info
      ts = vem_tau
      if (present(tau)) ts = tau
      b = 0.0_wp
      if (present(body)) b = body
      sig = 0.0_wp
      if (present(signode)) signode = 0.0_wp
      nn = size(xy, 2)
      call full_stiffness(xy, d, thick, ts, work, nn, info, area)
      if (info /= 0) return
      if (present(signode)) then
         call recover_stress(xy, work, nn, ue, thick*area*b, sig, signode)
      else
         call recover_stress(xy, work, nn, ue, thick*area*b, sig)
      end if
   end subroutine vem2_stress

   ! ------------------------------------------------------------------ internals

   !> Work layout for nn nodes (ns = nn+1 scalar dofs, nd = 2 ns dofs):
   !> K(nd,nd) | B(3,nd,3) | W(3,nd,3) | I-Pi(ns,ns) | Pi*(6,ns) | s(ns) | diag(nd).
   pure subroutine offsets(nn, ok, ob, ow, op, oq, os, od)
      integer, intent(in) :: nn
      integer, intent(out) :: ok, ob, ow, op, oq, os, od
      integer :: ns, nd
      ns = nn + 1
      nd = 2*ns
      ok = 1
      ob = ok + nd*nd
      ow = ob + 9*nd
      op = ow + 9*nd
      oq = op + ns*ns
      os = oq + 6*ns
      od = os + ns
   end subroutine offsets

   !> Full (uncondensed) stiffness into work(1:nd*nd), the strain operator B
   !> and W = D G1^-1 B into work (see offsets); area the cell's area.
   pure subroutine full_stiffness(xy, d, thick, ts, work, nn, info, area)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick, ts
      real(wp), intent(inout) :: work(:)
      integer, intent(in) :: nn
      integer, intent(out) :: info
      real(wp), intent(out) :: area
      integer :: n, i, ip1, ok, ob, ow, op, oq, os, od, ns, nd
      real(wp) :: side(2), off(2), xc(2), h, mono(6)
      info = 0
      area = 0.0_wp
      if (nn < 6 .or. mod(nn, 2) /= 0) then
         info = vem2_bad_nodes
         return
      end if
      n = nn/2
      do i = 1, n
         ip1 = mod(i, n) + 1
         side = xy(:, ip1) - xy(:, i)
         off = xy(:, n + i) - 0.5_wp*(xy(:, i) + xy(:, ip1))
         if (abs(dot_product(off, side)) > vem2_side_tangent*dot_product(side, side) .or. &
             norm2(off) > vem2_side_bulge*norm2(side)) then
            info = vem2_bad_side_node
            return
         end if
      end do
      call geometry(xy, n, xc, h, mono, area)
      if (.not. area > 0.0_wp) then
         info = vem2_bad_area
         return
      end if
      ns = nn + 1
      nd = 2*ns
      call offsets(nn, ok, ob, ow, op, oq, os, od)
      call build(xy, n, ns, nd, area, xc, h, mono, d, thick, ts, work(ok:ok + nd*nd - 1), &
                 work(ob:ob + 9*nd - 1), work(ow:ow + 9*nd - 1), work(op:op + ns*ns - 1), &
                 work(oq:oq + 6*ns - 1), work(os:os + ns - 1), work(od:od + nd - 1), info)
   end subroutine full_stiffness

   !> Point x and derivative dx = x'(t) of side (a, b, m) at t, and the
   !> Lagrange quadratics lag = (L_a, L_b, L_m) of t = 0, 1, 1/2 there.
   pure subroutine side_point(a, b, m, t, x, dx, lag)
      real(wp), intent(in) :: a(2), b(2), m(2), t
      real(wp), intent(out) :: x(2), dx(2), lag(3)
      real(wp) :: dl(3)
      lag = [(1.0_wp - t)*(1.0_wp - 2.0_wp*t), t*(2.0_wp*t - 1.0_wp), 4.0_wp*t*(1.0_wp - t)]
      dl = [4.0_wp*t - 3.0_wp, 4.0_wp*t - 1.0_wp, 4.0_wp - 8.0_wp*t]
      x = a*lag(1) + b*lag(2) + m*lag(3)
      dx = a*dl(1) + b*dl(2) + m*dl(3)
   end subroutine side_point

   !> Geometry of the cell bounded by the sides of xy (corners 1..n, side
   !> nodes n+1..2n): area, centroid xc, size h (largest node distance from
   !> xc) and mono = integral of (1, xi, eta, xi^2, xi eta, eta^2) with
   !> xi = (x - xc)/h, eta = (y - yc)/h, by the divergence theorem:
   !> integral xi^a eta^b = (h/(a+1)) boundary integral xi^(a+1) eta^b n_x ds,
   !> n_x ds = y'(t) dt on a counter-clockwise side.  The integrand of xi^2 has
   !> degree 3*2 + 1 = 7 in t on a curved side: the 4-point rule is exact.  The
   !> area and the centroid first, about the mean of the corners x0 (integrals
   !> of 1, x - x0 and y - y0 the same way).
   pure subroutine geometry(xy, n, xc, h, mono, area)
      real(wp), intent(in) :: xy(:, :)
      integer, intent(in) :: n
      real(wp), intent(out) :: xc(2), h, mono(6), area
      real(wp) :: x0(2), s(2), p(2), dp(2), lag(3), xi, eta, w
      integer :: i, j, g
      x0 = sum(xy(:, 1:n), dim=2)/real(n, wp)
      area = 0.0_wp
      s = 0.0_wp
      do i = 1, n
         j = mod(i, n) + 1
         do g = 1, 4
            call side_point(xy(:, i), xy(:, j), xy(:, n + i), gl_t(g), p, dp, lag)
            p = p - x0
            w = gl_w(g)*dp(2)
            area = area + w*p(1)
            s = s + w*[p(1)*p(1)/2, p(1)*p(2)]
         end do
      end do
      xc = x0
      if (.not. area > 0.0_wp) return
      xc = x0 + s/area
      h = 0.0_wp
      do i = 1, 2*n
         h = max(h, norm2(xy(:, i) - xc))
      end do
      mono = 0.0_wp
      do i = 1, n
         j = mod(i, n) + 1
         do g = 1, 4
            call side_point(xy(:, i), xy(:, j), xy(:, n + i), gl_t(g), p, dp, lag)
            xi = (p(1) - xc(1))/h
            eta = (p(2) - xc(2))/h
            w = gl_w(g)*dp(2)*h
            mono(1) = mono(1) + w*xi
            mono(2) = mono(2) + w*xi*xi/2
            mono(3) = mono(3) + w*xi*eta
            mono(4) = mono(4) + w*xi**3/3
            mono(5) = mono(5) + w*xi*xi*eta/2
            mono(6) = mono(6) + w*xi*eta*eta
         end do
      end do
   end subroutine geometry

   !> The six scaled monomials at a point.
   pure function monomials(x, xc, h) result(m)
      real(wp), intent(in) :: x(2), xc(2), h
      real(wp) :: m(6), xi, eta
      xi = (x(1) - xc(1))/h
      eta = (x(2) - xc(2))/h
      m = [1.0_wp, xi, eta, xi*xi, xi*eta, eta*eta]
   end function monomials

   !> Mass matrix of (1, xi, eta) from the monomial integrals.
   pure function mass_p1(mono) result(g)
      real(wp), intent(in) :: mono(6)
      real(wp) :: g(3, 3)
      g(:, 1) = [mono(1), mono(2), mono(3)]
      g(:, 2) = [mono(2), mono(4), mono(5)]
      g(:, 3) = [mono(3), mono(5), mono(6)]
   end function mass_p1

   pure subroutine build(xy, n, ns, nd, area, xc, h, mono, d, thick, ts, kf, bm, wm, pm, pst, sv, dia, info)
      real(wp), intent(in) :: xy(:, :)
      integer, intent(in) :: n, ns, nd
      real(wp), intent(in) :: area, xc(2), h, mono(6), d(3, 3), thick, ts
      real(wp), intent(out) :: kf(nd, nd), bm(3, nd, 3), wm(3, nd, 3), pm(ns, ns), pst(6, ns), sv(ns), dia(nd)
      integer, intent(out) :: info
      real(wp) :: g1(3, 3), g1c(3, 3), g1i(3, 3), g2(6, 6), dcap(3, 3), excess
      real(wp) :: p(2), dp(2), lag(3), nrm(2), ma(6), gm(2)
      real(wp) :: tr, floor_s, c(3), acc
      integer :: i, j, a, k, l, g, al, be, node(3)
      logical :: ok
      info = 0

      ! strain projection: B_alpha(v) = integral eps(v) m_alpha (Voigt, engineering
      ! shear) for m_alpha = 1, xi, eta
      bm = 0.0_wp
      pst = 0.0_wp
      ! boundary terms along each side: u = sum_k u_k lag_k(t) (k = a, b, m),
      ! n ds = nrm dt; m_alpha linear in x, so degree 2 + 2 + 1 = 5 in t
      do i = 1, n
         node = [i, mod(i, n) + 1, n + i]
         do g = 1, 4
            call side_point(xy(:, node(1)), xy(:, node(2)), xy(:, node(3)), gl_t(g), p, dp, lag)
            nrm = gl_w(g)*[dp(2), -dp(1)]      ! weight times x'(t) turned outward
            ma = monomials(p, xc, h)
            do k = 1, 3
               do al = 1, 3
                  call side_term(bm, nd, al, node(k), lag(k)*ma(al), nrm)
               end do
               ! H1 projection rows 2..6: h boundary integral u (h grad m) . n
               do al = 2, 6
                  gm = [dot_product(cgx(:, al), ma(1:3)), dot_product(cgy(:, al), ma(1:3))]
                  pst(al, node(k)) = pst(al, node(k)) + h*lag(k)*dot_product(gm, nrm)
               end do
            end do
         end do
      end do
      ! volume terms - integral u . div(tau): only m = xi (d/dx = 1/h) and
      ! m = eta (d/dy = 1/h) have a non-zero derivative; integral u = |E| mu
      bm(1, 2*ns - 1, 2) = bm(1, 2*ns - 1, 2) - area/h      ! xx, m = xi, u_x
      bm(3, 2*ns, 2) = bm(3, 2*ns, 2) - area/h              ! xy, m = xi, u_y
      bm(2, 2*ns, 3) = bm(2, 2*ns, 3) - area/h              ! yy, m = eta, u_y
      bm(3, 2*ns - 1, 3) = bm(3, 2*ns - 1, 3) - area/h      ! xy, m = eta, u_x

      g1 = mass_p1(mono)
      g1i = 0.0_wp
      do i = 1, 3
         g1i(i, i) = 1.0_wp
      end do
      g1c = g1      ! solve_dense overwrites its matrix
      call solve_dense(g1c, g1i, 3, 3, ok)
      if (.not. ok) then
         info = vem2_singular
         return
      end if

      ! W_alpha = D sum_beta G1^-1(alpha, beta) B_beta; Kc = t sum_alpha B_alpha^T W_alpha
      do al = 1, 3
         do k = 1, nd
            c = 0.0_wp
            do be = 1, 3
               c = c + g1i(al, be)*bm(:, k, be)
            end do
            wm(:, k, al) = matmul(d, c)
         end do
      end do
      do l = 1, nd
         do k = 1, l
            acc = 0.0_wp
            do al = 1, 3
               acc = acc + dot_product(bm(:, k, al), wm(:, l, al))
            end do
            kf(k, l) = thick*acc
         end do
      end do

      ! stabilisation weights from the diagonal of Kc with lambda capped
      excess = d(1, 2) - vem_lambda_cap*d(3, 3)
      if (excess > 0.0_wp) then
         dcap = d
         dcap(1:2, 1:2) = dcap(1:2, 1:2) - excess
         do k = 1, nd
            acc = 0.0_wp
            do al = 1, 3
               c = 0.0_wp
               do be = 1, 3
                  c = c + g1i(al, be)*bm(:, k, be)
               end do
               acc = acc + dot_product(bm(:, k, al), matmul(dcap, c))
            end do
            dia(k) = thick*acc
         end do
      else
         do k = 1, nd
            dia(k) = kf(k, k)
         end do
      end if
      tr = sum(dia)
      floor_s = ts*(vem_floor*tr/real(nd, wp))
      do j = 1, ns
         sv(j) = max(0.5_wp*ts*(dia(2*j - 1) + dia(2*j)), floor_s)
      end do

      ! H1 projection of a component: G2 Pi* = B2, row 1 the mean (cell moment)
      g2 = 0.0_wp
      g2(1, :) = mono
      do al = 2, 6
         do be = 1, 6
            g2(al, be) = dot_product(cgx(:, al), matmul(g1, cgx(:, be))) &
                         + dot_product(cgy(:, al), matmul(g1, cgy(:, be)))
         end do
      end do
      pst(1, ns) = area
      do al = 2, 6
         pst(al, ns) = pst(al, ns) - hlap(al)*area
      end do
      call solve_dense(g2, pst, 6, ns, ok)
      if (.not. ok) then
         info = vem2_singular
         return
      end if
      ! Pi = Dm Pi*, Dm(j, beta) the dof j of monomial beta; then I - Pi
      do j = 1, ns
         if (j < ns) then
            ma = monomials(xy(:, j), xc, h)
         else
            ma = mono/area
         end if
         do k = 1, ns
            pm(j, k) = -dot_product(ma, pst(:, k))
         end do
         pm(j, j) = pm(j, j) + 1.0_wp
      end do
      ! K += (I - Pi)^T S (I - Pi) on each component
      do l = 1, ns
         do k = 1, l
            acc = 0.0_wp
            do j = 1, ns
               acc = acc + sv(j)*pm(j, k)*pm(j, l)
            end do
            do a = 1, 2
               kf(2*k - 2 + a, 2*l - 2 + a) = kf(2*k - 2 + a, 2*l - 2 + a) + acc
            end do
         end do
      end do
      do l = 1, nd
         do k = l + 1, nd
            kf(k, l) = kf(l, k)
         end do
      end do
   end subroutine build

   !> Boundary part of B_alpha (bm(:, :, al)) at node `node`: w (the node's
   !> Lagrange quadratic times m_alpha at a Gauss point) times nrm (the Gauss
   !> weight times the side's outward normal scaled by |x'(t)|).
   pure subroutine side_term(bm, nd, al, node, w, nrm)
      integer, intent(in) :: nd, al, node
      real(wp), intent(inout) :: bm(3, nd, 3)
      real(wp), intent(in) :: w, nrm(2)
      bm(1, 2*node - 1, al) = bm(1, 2*node - 1, al) + w*nrm(1)
      bm(2, 2*node, al) = bm(2, 2*node, al) + w*nrm(2)
      bm(3, 2*node - 1, al) = bm(3, 2*node - 1, al) + w*nrm(2)
      bm(3, 2*node, al) = bm(3, 2*node, al) + w*nrm(1)
   end subroutine side_term

   !> ke = K_nn - K_nm K_mm^-1 K_mn, kmi = K_mm^-1.
   pure subroutine condense(kf, nn, ke, kmi, info)
      integer, intent(in) :: nn
      real(wp), intent(in) :: kf(2*nn + 2, 2*nn + 2)
      real(wp), intent(out) :: ke(:, :), kmi(2, 2)
      integer, intent(out) :: info
      real(wp) :: t(2), kmm(2, 2)
      integer :: k, l, m
      m = 2*nn
      kmm = kf(m + 1:m + 2, m + 1:m + 2)
      call inverse2(kmm, kmi, info)
      if (info /= 0) return
      do l = 1, m
         t = matmul(kmi, kf(m + 1:m + 2, l))
         do k = 1, l
            ke(k, l) = kf(k, l) - dot_product(kf(k, m + 1:m + 2), t)
         end do
      end do
      do l = 1, m
         do k = l + 1, m
            ke(k, l) = ke(l, k)
         end do
      end do
   end subroutine condense

   !> fb = -K_nm K_mm^-1 (scale I_2): the nodal forces of a unit body force.
   pure subroutine moment_load(kf, nn, scale, fb, info)
      integer, intent(in) :: nn
      real(wp), intent(in) :: kf(2*nn + 2, 2*nn + 2), scale
      real(wp), intent(out) :: fb(:, :)
      integer, intent(out) :: info
      real(wp) :: kmi(2, 2), kmm(2, 2)
      integer :: m
      m = 2*nn
      kmm = kf(m + 1:m + 2, m + 1:m + 2)
      call inverse2(kmm, kmi, info)
      if (info /= 0) return
      fb(1:m, 1:2) = -scale*matmul(kf(1:m, m + 1:m + 2), kmi)
   end subroutine moment_load

   pure subroutine inverse2(a, ai, info)
      real(wp), intent(in) :: a(2, 2)
      real(wp), intent(out) :: ai(2, 2)
      integer, intent(out) :: info
      real(wp) :: det
      info = 0
      det = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
      if (.not. det > 0.0_wp) then
         ai = 0.0_wp
         info = vem2_singular
         return
      end if
      ai(1, 1) = a(2, 2)/det
      ai(2, 2) = a(1, 1)/det
      ai(1, 2) = -a(1, 2)/det
      ai(2, 1) = -a(2, 1)/det
   end subroutine inverse2

   !> Cell moments from the node displacements, then the projected strain's
   !> coefficients E_alpha = sum_beta G1^-1 B_beta v, and D times it.
   pure subroutine recover_stress(xy, work, nn, ue, fm, sig, signode)
      real(wp), intent(in) :: xy(:, :), ue(:), fm(2)
      real(wp), intent(inout) :: work(:)
      integer, intent(in) :: nn
      real(wp), intent(out) :: sig(3)
      real(wp), intent(out), optional :: signode(:, :)
      integer :: ok, ob, ow, op, oq, os, od, nd, n, j, info
      real(wp) :: kmi(2, 2), mu(2), xc(2), h, mono(6), m(6), area
      real(wp) :: coef(3, 3)
      nd = 2*nn + 2
      n = nn/2
      call offsets(nn, ok, ob, ow, op, oq, os, od)
      call moments(work(ok:ok + nd*nd - 1), nn, ue, fm, mu, kmi, info)
      if (info /= 0) return
      call geometry(xy, n, xc, h, mono, area)
      ! W = D G1^-1 B, so D E_alpha = W_alpha v
      call strain_coefficients(work(ow:ow + 9*nd - 1), nd, ue, mu, coef)
      ! mean: (1/|E|) sum_alpha integral(m_alpha) D E_alpha, integral(xi) = integral(eta) = 0
      sig = (coef(:, 1)*mono(1) + coef(:, 2)*mono(2) + coef(:, 3)*mono(3))/mono(1)
      if (present(signode)) then
         do j = 1, nn
            m = monomials(xy(:, j), xc, h)
            signode(:, j) = coef(:, 1)*m(1) + coef(:, 2)*m(2) + coef(:, 3)*m(3)
         end do
      end if
   end subroutine recover_stress

   pure subroutine moments(kf, nn, ue, fm, mu, kmi, info)
      integer, intent(in) :: nn
      real(wp), intent(in) :: kf(2*nn + 2, 2*nn + 2), ue(:), fm(2)
      real(wp), intent(out) :: mu(2), kmi(2, 2)
      integer, intent(out) :: info
      real(wp) :: kmm(2, 2)
      integer :: m
      m = 2*nn
      mu = 0.0_wp
      kmm = kf(m + 1:m + 2, m + 1:m + 2)
      call inverse2(kmm, kmi, info)
      if (info /= 0) return
      mu = matmul(kmi, fm - matmul(kf(m + 1:m + 2, 1:m), ue(1:m)))
   end subroutine moments

   pure subroutine strain_coefficients(wm, nd, ue, mu, coef)
      integer, intent(in) :: nd
      real(wp), intent(in) :: wm(3, nd, 3), ue(:), mu(2)
      real(wp), intent(out) :: coef(3, 3)
      integer :: al
      do al = 1, 3
         coef(:, al) = matmul(wm(:, 1:nd - 2, al), ue(1:nd - 2)) + matmul(wm(:, nd - 1:nd, al), mu)
      end do
   end subroutine strain_coefficients

   !> Solve a x = b in place (b becomes x) by Gaussian elimination with partial
   !> pivoting; ok = .false. for a zero pivot.  a is overwritten.
   pure subroutine solve_dense(a, b, n, nrhs, ok)
      integer, intent(in) :: n, nrhs
      real(wp), intent(inout) :: a(n, n), b(n, nrhs)
      logical, intent(out) :: ok
      real(wp) :: f, tmp
      integer :: i, j, k, p
      ok = .true.
      do k = 1, n
         p = k - 1 + maxloc(abs(a(k:n, k)), dim=1)
         if (.not. abs(a(p, k)) > 0.0_wp) then
            ok = .false.
            return
         end if
         if (p /= k) then
            do j = 1, n
               tmp = a(k, j); a(k, j) = a(p, j); a(p, j) = tmp
            end do
            do j = 1, nrhs
               tmp = b(k, j); b(k, j) = b(p, j); b(p, j) = tmp
            end do
         end if
         do i = k + 1, n
            f = a(i, k)/a(k, k)
            a(i, k:n) = a(i, k:n) - f*a(k, k:n)
            b(i, :) = b(i, :) - f*b(k, :)
         end do
      end do
      do k = n, 1, -1
         do i = k + 1, n
            b(k, :) = b(k, :) - a(k, i)*b(i, :)
         end do
         b(k, :) = b(k, :)/a(k, k)
      end do
   end subroutine solve_dense
end module vemcontact_element_vem2
