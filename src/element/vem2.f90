!> Second-order (k = 2) virtual element for 2D small-strain elasticity on a
!> polygon with n >= 3 corners, straight sides, convex or not, collinear
!> corners allowed; docs/vem-formulation.md has the derivation.
!>
!> Nodes: the n corners counter-clockwise, then one node per side (side i runs
!> from corner i to corner i+1, its node is node n+i), so 2n nodes, as in
!> Abaqus' quadratic elements.  The side node is the middle point of the side:
!> with the two corners it makes the 3-point Gauss-Lobatto rule of the side
!> (Simpson), which integrates the product of the quadratic trace of u with a
!> linear function exactly; the boundary integrals below are all of that kind.
!> Degrees of freedom: u at the 2n nodes and the cell moments
!> mu = (1/|E|) integral of u (2 components), numbered as a node 2n+1.
!>
!> Consistency: the L2 projection of the strain onto linear symmetric tensors,
!>   integral eps(u) : tau = - integral u . div tau + boundary integral u . tau n,
!> computable for every linear tau (div tau is constant: the cell moment;
!> the boundary term: Simpson).  Kc = t integral Pi(eps)^T D Pi(eps) is then
!> exact for quadratic u and a_h(p, v) = a(p, v) for every quadratic p, the
!> patch test.
!> Stabilisation: (I - Pi)^T S (I - Pi) per component, with Pi the H1
!> projection of each component onto quadratics (mean fixed by the cell
!> moment) and S diagonal: the D-recipe of the k = 1 element (vem_tau,
!> vem_floor, vem_lambda_cap of vemcontact_element_vem), the weight of a node
!> the mean of its two Kc diagonals computed with lambda capped at 2 mu.
!> The cell moments are condensed statically: the kernels return the 4n x 4n
!> stiffness of the node dofs, the nodal forces of a unit body force
!> (vem2_body_load) and recover the moments for the stress (vem2_stress).
!> Polygon integrals of polynomials come from the divergence theorem (exact
!> for any simple polygon), with 3-point Gauss on each side.
!>
!> Kernels are pure, take a work array of vem2_workspace_size(2n) reals and
!> allocate nothing.
module vemcontact_element_vem2
   use vemcontact_kinds, only: wp
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_centroid
   use vemcontact_element_vem, only: vem_tau, vem_floor, vem_lambda_cap
   implicit none
   private

   public :: vem2_workspace_size, vem2_stiffness, vem2_body_load, vem2_stress

   !> info codes (1 is the bad area of every element kernel)
   integer, parameter, public :: vem2_bad_area = 1
   integer, parameter, public :: vem2_bad_nodes = 4      !< odd node count or fewer than 6 nodes
   integer, parameter, public :: vem2_bad_side_node = 5  !< a side node off the middle of its side
   integer, parameter, public :: vem2_singular = 6       !< projection or condensation failed
   !> A side node may be off the middle of its side by this fraction of the
   !> side's length: decks carry rounded coordinates, while a node visibly off
   !> the middle is an error (the element places its dof at the middle).
   real(wp), parameter, public :: vem2_side_rtol = 1.0e-3_wp

   ! 3-point Gauss-Legendre rule on [0, 1]
   real(wp), parameter :: gl_t(3) = [0.5_wp - 0.5_wp*sqrt(0.6_wp), 0.5_wp, 0.5_wp + 0.5_wp*sqrt(0.6_wp)]
   real(wp), parameter :: gl_w(3) = [5.0_wp/18.0_wp, 8.0_wp/18.0_wp, 5.0_wp/18.0_wp]
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
   !> info: 0 ok, 1 non-positive area, 4 not 2n >= 6 nodes, 5 a side node off
   !> the middle of its side, 6 singular projection; ke = 0 when info /= 0.
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
   !> and W = D G1^-1 B into work (see offsets); area the polygon's area.
   pure subroutine full_stiffness(xy, d, thick, ts, work, nn, info, area)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick, ts
      real(wp), intent(inout) :: work(:)
      integer, intent(in) :: nn
      integer, intent(out) :: info
      real(wp), intent(out) :: area
      integer :: n, i, ip1, ok, ob, ow, op, oq, os, od, ns, nd
      real(wp) :: side(2), off(2)
      info = 0
      area = 0.0_wp
      if (nn < 6 .or. mod(nn, 2) /= 0) then
         info = vem2_bad_nodes
         return
      end if
      n = nn/2
      area = polygon_signed_area(xy(:, 1:n))
      if (.not. area > 0.0_wp) then
         info = vem2_bad_area
         return
      end if
      do i = 1, n
         ip1 = mod(i, n) + 1
         side = xy(:, ip1) - xy(:, i)
         off = xy(:, n + i) - 0.5_wp*(xy(:, i) + xy(:, ip1))
         if (norm2(off) > vem2_side_rtol*norm2(side)) then
            info = vem2_bad_side_node
            return
         end if
      end do
      ns = nn + 1
      nd = 2*ns
      call offsets(nn, ok, ob, ow, op, oq, os, od)
      call build(xy(:, 1:n), n, ns, nd, area, d, thick, ts, work(ok:ok + nd*nd - 1), &
                 work(ob:ob + 9*nd - 1), work(ow:ow + 9*nd - 1), work(op:op + ns*ns - 1), &
                 work(oq:oq + 6*ns - 1), work(os:os + ns - 1), work(od:od + nd - 1), info)
   end subroutine full_stiffness

   !> Geometry of the polygon: centroid xc, size h (largest corner distance
   !> from xc), integrals mono = integral of (1, xi, eta, xi^2, xi eta, eta^2)
   !> with xi = (x - xc)/h, eta = (y - yc)/h, by the divergence theorem:
   !> integral xi^a eta^b = (h/(a+1)) boundary integral xi^(a+1) eta^b n_x ds,
   !> with n_x ds = dy dt on a counter-clockwise side (degree <= 3: 3-point
   !> Gauss is exact).
   pure subroutine geometry(cxy, n, xc, h, mono)
      real(wp), intent(in) :: cxy(:, :)
      integer, intent(in) :: n
      real(wp), intent(out) :: xc(2), h, mono(6)
      real(wp) :: p(2), q(2), dy, xi, eta, w
      integer :: i, g
      call polygon_centroid(cxy, xc)
      h = 0.0_wp
      do i = 1, n
         h = max(h, norm2(cxy(:, i) - xc))
      end do
      mono = 0.0_wp
      do i = 1, n
         p = cxy(:, i)
         q = cxy(:, mod(i, n) + 1)
         dy = q(2) - p(2)
         do g = 1, 3
            xi = (p(1) + gl_t(g)*(q(1) - p(1)) - xc(1))/h
            eta = (p(2) + gl_t(g)*(q(2) - p(2)) - xc(2))/h
            w = gl_w(g)*dy*h
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

   pure subroutine build(cxy, n, ns, nd, area, d, thick, ts, kf, bm, wm, pm, pst, sv, dia, info)
      real(wp), intent(in) :: cxy(:, :)
      integer, intent(in) :: n, ns, nd
      real(wp), intent(in) :: area, d(3, 3), thick, ts
      real(wp), intent(out) :: kf(nd, nd), bm(3, nd, 3), wm(3, nd, 3), pm(ns, ns), pst(6, ns), sv(ns), dia(nd)
      integer, intent(out) :: info
      real(wp) :: xc(2), h, mono(6), g1(3, 3), g1c(3, 3), g1i(3, 3), g2(6, 6), dcap(3, 3), excess
      real(wp) :: pa(2), pb(2), pc(2), nrm(2), ma(6), mb(6), mc(6), ga(2), gb(2), gc(2)
      real(wp) :: tr, floor_s, c(3), acc
      integer :: i, j, a, k, l, ia, ib, ic, al, be
      logical :: ok
      info = 0
      call geometry(cxy, n, xc, h, mono)

      ! strain projection: B_alpha(v) = integral eps(v) m_alpha (Voigt, engineering
      ! shear) for m_alpha = 1, xi, eta
      bm = 0.0_wp
      pst = 0.0_wp
      do i = 1, n
         j = mod(i, n) + 1
         pa = cxy(:, i)
         pb = cxy(:, j)
         pc = 0.5_wp*(pa + pb)
         nrm = [pb(2) - pa(2), -(pb(1) - pa(1))]    ! length times outward normal
         ma = monomials(pa, xc, h)
         mb = monomials(pb, xc, h)
         mc = monomials(pc, xc, h)
         ia = i            ! node numbers of the side's Simpson points
         ib = j
         ic = n + i
         do al = 1, 3
            call side_term(bm, nd, al, ia, ma(al)/6.0_wp, nrm)
            call side_term(bm, nd, al, ib, mb(al)/6.0_wp, nrm)
            call side_term(bm, nd, al, ic, 4.0_wp*mc(al)/6.0_wp, nrm)
         end do
         ! H1 projection rows 2..6: h boundary integral u (h grad m) . n
         do al = 2, 6
            ga = [dot_product(cgx(:, al), ma(1:3)), dot_product(cgy(:, al), ma(1:3))]
            gb = [dot_product(cgx(:, al), mb(1:3)), dot_product(cgy(:, al), mb(1:3))]
            gc = [dot_product(cgx(:, al), mc(1:3)), dot_product(cgy(:, al), mc(1:3))]
            pst(al, ia) = pst(al, ia) + h*dot_product(ga, nrm)/6.0_wp
            pst(al, ib) = pst(al, ib) + h*dot_product(gb, nrm)/6.0_wp
            pst(al, ic) = pst(al, ic) + 4.0_wp*h*dot_product(gc, nrm)/6.0_wp
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
         if (j <= n) then
            ma = monomials(cxy(:, j), xc, h)
         else if (j < ns) then
            ma = monomials(0.5_wp*(cxy(:, j - n) + cxy(:, mod(j - n, n) + 1)), xc, h)
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

   !> Boundary part of B_alpha (bm(:, :, al)) at node `node`: the Simpson weight
   !> times m_alpha, w, times the side's length-weighted normal nrm.
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
      real(wp) :: kmi(2, 2), mu(2), xc(2), h, mono(6), m(6)
      real(wp) :: coef(3, 3)
      nd = 2*nn + 2
      n = nn/2
      call offsets(nn, ok, ob, ow, op, oq, os, od)
      call moments(work(ok:ok + nd*nd - 1), nn, ue, fm, mu, kmi, info)
      if (info /= 0) return
      call geometry(xy(:, 1:n), n, xc, h, mono)
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
