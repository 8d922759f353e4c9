!> Lowest-order (k = 1) virtual element for 2D small-strain elasticity on a
!> polygon with any number n >= 3 of vertices; docs/vem-formulation.md has the
!> derivation.  In short, with q_i = (l_{i-1} n_{i-1} + l_i n_i)/2 the
!> boundary-integral weight of vertex i (half the rotated chord from vertex
!> i-1 to vertex i+1):
!>
!>   grad(Pi u)  = (1/|E|) sum_i u_i (x) q_i          (exact: u is linear on sides)
!>   eps(Pi u)   = B u,   B_i = (1/|E|) [[qx,0],[0,qy],[qy,qx]]
!>   (Pi u)(x_j) = ubar + grad(Pi u) (x_j - xbar)     (ubar, xbar: vertex means)
!>   K = |E| t B^T D B + (I - P)^T S (I - P),   P = p (x) I_2,
!>       p_ji = 1/n + q_i . (x_j - xbar)/|E|,  S = s (x) I_2 (D-recipe, see vem_tau).
!>
!> The kernels take a caller-provided work array of vem_workspace_size(n)
!> reals and allocate nothing.
module vemcontact_element_vem
   use vemcontact_kinds, only: wp
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_centroid
   implicit none
   private

   public :: vem_workspace_size, vem_stiffness, vem_strain, vem_stress, vem_load_weights

   !> Stabilisation S = s (x) I_2 with, for vertex i,
   !>   s_i = tau * max((Kc_(ix,ix) + Kc_(iy,iy))/2, vem_floor * trace(Kc)/(2n)),
   !> tau = vem_tau unless the caller passes its own (*SOLID SECTION,
   !> STABILIZATION=tau; docs/vem-stabilisation.md measures its effect).  The
   !> floor is scaled with tau as well, so S(tau) = tau S(1) exactly: tau is a
   !> pure scale of the hourglass stiffness and the floor keeps its meaning (a
   !> fraction of the stabilisation level, not of the consistency part).
   !> Kc_ii is the stiffness the consistency part gives dof i, so S follows the
   !> material (E, nu, thickness) and the local geometry and, like Kc, is
   !> invariant under scaling of the element (2D elasticity is scale-free).
   !> This is the D-recipe of Beirao da Veiga, Dassi, Russo 2017 with the two
   !> diagonals of a vertex averaged: the trace of a vertex block is invariant
   !> under rotation, so K rotates with the element (the per-dof diagonal would
   !> make the stabilisation depend on the orientation of the axes).
   !> tau = 1: on a square the k = 1 virtual space is Q1, and tau = 1 gives the
   !> hourglass mode 3/4 of its Galerkin (exactly integrated bilinear) energy,
   !> between the energy of pure bending (tau ~ 0.9 in plane stress, nu = 0..0.3)
   !> and the shear-locking Q4 value (tau = 4/3).  The floor only acts at a
   !> vertex whose two neighbours nearly coincide (|q_i| below about a tenth of
   !> the typical one, e.g. between two tiny sides), where the own diagonal
   !> would leave the vertex held almost only through its neighbours; at 1% of
   !> the mean diagonal it leaves ordinary vertices alone.
   real(wp), parameter, public :: vem_tau = 1.0_wp
   real(wp), parameter, public :: vem_floor = 1.0e-2_wp
   !> Cap on the Lame constant seen by the stabilisation: Kc_ii is taken with
   !> D12 (lambda) limited to vem_lambda_cap * D33 (mu).  The stabilisation only
   !> has to hold the non-polynomial (hourglass) modes, whose stiffness is shear
   !> stiffness; with lambda in it, S grows like 1/(1 - 2 nu) and imposes a
   !> spurious incompressibility constraint on those modes: the k = 1 VEM then
   !> locks as badly as the full-integration Q4 (tip deflection 0.28 of exact at
   !> nu = 0.4999 on a plane-strain cantilever, docs/stability-elements.md).
   !> lambda = 2 mu is nu = 1/3 in plane strain and nu = 1/2 in plane stress, so
   !> the cap leaves plane stress and every plane-strain material up to nu = 1/3
   !> untouched (bit for bit) and makes the stabilisation stop growing beyond.
   real(wp), parameter, public :: vem_lambda_cap = 2.0_wp

contains

   !> Reals of work needed by an n-vertex element: q (2n) and s (n).
   pure function vem_workspace_size(n) result(nw)
      integer, intent(in) :: n
      integer :: nw
      ! q (2n), s (n), and for the stabilisation g = q/|E| (2n) and r = x - xbar (2n)
      nw = 7*max(n, 1)
   end function vem_workspace_size

   !> Boundary weights q_i into work(1:2n) as (qx1, qy1, qx2, ...).  With a
   !> counter-clockwise polygon l_k n_k = (dy_k, -dx_k) for side k, and the two
   !> sides at vertex i add up to the chord from vertex i-1 to vertex i+1.
   pure subroutine vem_boundary_weights(xy, q)
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(inout) :: q(:)
      integer :: i, n, im1, ip1
      n = size(xy, 2)
      do i = 1, n
         im1 = modulo(i - 2, n) + 1
         ip1 = modulo(i, n) + 1
         q(2*i - 1) = 0.5_wp*(xy(2, ip1) - xy(2, im1))
         q(2*i) = -0.5_wp*(xy(1, ip1) - xy(1, im1))
      end do
   end subroutine vem_boundary_weights

   !> Stiffness ke(2n, 2n), dof order (u1x, u1y, u2x, ...).  info = 1 when the
   !> signed area is not positive (clockwise or degenerate polygon); ke = 0 then.
   !> `tau` (> 0, default vem_tau) scales the stabilisation; the consistency
   !> part, hence the patch test, does not depend on it.
   !> Precondition: size(work) >= vem_workspace_size(n), ke is (2n, 2n).
   pure subroutine vem_stiffness(xy, d, thick, ke, work, info, tau)
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: ke(:, :)
      real(wp), intent(inout) :: work(:)
      integer, intent(out) :: info
      real(wp), intent(in), optional :: tau
      real(wp) :: area, xbar(2), cl(3, 2), qx, qy, m2gl(2), tr, floor_s, ts
      real(wp) :: m0, m1(2), m2(2, 2), gi(2), gl(2), ri(2), rl(2), ail, ali, k, si, sl, rn, excess
      integer :: n, i, l, a, ia, js, jg, jr

      n = size(xy, 2)
      info = 0
      area = polygon_signed_area(xy)
      if (n < 3 .or. .not. area > 0.0_wp) then
         ke = 0.0_wp
         info = 1
         return
      end if
      ! every entry of ke is written below (the upper block triangle by the consistency
      ! loop, the rest by the mirror at the end): no zeroing first
      call vem_boundary_weights(xy, work(1:2*n))
      js = 2*n     ! s is stored in work(js+1 : js+n)

      ! consistency part, upper block triangle: |E| t B_i^T D B_l = (t/|E|) b_i^T D b_l,
      ! with c = (t/|E|) D b_l formed once per l and b_i's sparsity written out (this
      ! loop is most of the assembly time)
      do l = 1, n
         ! (t/|E|) D b_l, b_l = |E| B_l = [[qx, 0], [0, qy], [qy, qx]]: the sums of
         ! matmul(d, b_l) in the same order without the zero terms (gfortran's inline
         ! matmul would store and reload every partial sum)
         qx = work(2*l - 1)
         qy = work(2*l)
         cl(:, 1) = (thick/area)*(d(:, 1)*qx + d(:, 3)*qy)
         cl(:, 2) = (thick/area)*(d(:, 2)*qy + d(:, 3)*qx)
         do i = 1, l
            qx = work(2*i - 1)
            qy = work(2*i)
            ke(2*i - 1, 2*l - 1) = qx*cl(1, 1) + qy*cl(3, 1)
            ke(2*i, 2*l - 1) = qy*cl(2, 1) + qx*cl(3, 1)
            ke(2*i - 1, 2*l) = qx*cl(1, 2) + qy*cl(3, 2)
            ke(2*i, 2*l) = qy*cl(2, 2) + qx*cl(3, 2)
         end do
      end do

      ! D-recipe stabilisation weights, one per vertex (see vem_tau), from the
      ! diagonal of Kc with lambda capped (see vem_lambda_cap): the excess
      ! lambda contributes (t/|E|) excess qx^2 and qy^2 to the two diagonals
      excess = d(1, 2) - vem_lambda_cap*d(3, 3)
      tr = 0.0_wp
      do ia = 1, 2*n
         tr = tr + ke(ia, ia)
      end do
      do i = 1, n
         work(js + i) = ke(2*i - 1, 2*i - 1) + ke(2*i, 2*i)
      end do
      if (excess > 0.0_wp) then
         do i = 1, n
            work(js + i) = work(js + i) - (thick/area)*excess*(work(2*i - 1)**2 + work(2*i)**2)
         end do
         tr = sum(work(js + 1:js + n))
      end if
      ts = vem_tau
      if (present(tau)) ts = tau
      ! with ts = 1 both products are exact: the default matrices are bit for bit
      ! those of the fixed tau = 1
      floor_s = ts*(vem_floor*tr/real(2*n, wp))
      do i = 1, n
         work(js + i) = max(0.5_wp*ts*work(js + i), floor_s)
      end do

      ! (I-P)^T S (I-P) couples equal components only, since P = p (x) I_2 and
      ! S = s (x) I_2.  Entry (i,l) of sum_j s_j m_ji m_jl with m = I - p is
      !   s_i delta_il - s_i p_il - s_l p_li + sum_j s_j p_ji p_jl
      ! and, with p_ji = 1/n + g_i.r_j, the last sum needs only the moments
      ! M0 = sum s_j, M1 = sum s_j r_j, M2 = sum s_j r_j r_j^T: O(n^2), no n x n work.
      xbar = sum(xy, dim=2)/real(n, wp)
      rn = 1.0_wp/real(n, wp)
      ! g_i = q_i/|E| in work(jg+1 : jg+2n), r_i = x_i - xbar in work(jr+1 : jr+2n),
      ! formed once instead of once per pair
      jg = 3*n
      jr = 5*n
      do i = 1, n
         work(jg + 2*i - 1:jg + 2*i) = work(2*i - 1:2*i)/area
         work(jr + 2*i - 1:jr + 2*i) = xy(:, i) - xbar
      end do
      m0 = 0.0_wp
      m1 = 0.0_wp
      m2 = 0.0_wp
      do i = 1, n
         ri = work(jr + 2*i - 1:jr + 2*i)
         si = work(js + i)
         m0 = m0 + si
         m1 = m1 + si*ri
         m2(:, 1) = m2(:, 1) + si*ri(1)*ri
         m2(:, 2) = m2(:, 2) + si*ri(2)*ri
      end do
      do l = 1, n
         gl = work(jg + 2*l - 1:jg + 2*l)
         rl = work(jr + 2*l - 1:jr + 2*l)
         sl = work(js + l)
         m2gl = matmul(m2, gl)
         do i = 1, l
            gi = work(jg + 2*i - 1:jg + 2*i)
            ri = work(jr + 2*i - 1:jr + 2*i)
            si = work(js + i)
            ail = rn + dot_product(gl, ri)
            ali = rn + dot_product(gi, rl)
            k = -si*ail - sl*ali + m0*rn*rn + rn*dot_product(gi + gl, m1) &
                + dot_product(gi, m2gl)
            if (i == l) k = k + si
            do a = 1, 2
               ke(2*i - 2 + a, 2*l - 2 + a) = ke(2*i - 2 + a, 2*l - 2 + a) + k
            end do
         end do
      end do

      ! mirror the upper triangle: symmetric to the last bit
      do l = 1, 2*n
         do i = l + 1, 2*n
            ke(i, l) = ke(l, i)
         end do
      end do
   end subroutine vem_stiffness

   !> Projected (constant) strain (exx, eyy, gxy) of the element displacements ue(2n).
   !> Returns zero for a polygon of non-positive area, which vem_stiffness rejects.
   pure subroutine vem_strain(xy, ue, work, eps)
      real(wp), intent(in) :: xy(:, :), ue(:)
      real(wp), intent(inout) :: work(:)
      real(wp), intent(out) :: eps(3)
      real(wp) :: area
      integer :: i, n
      n = size(xy, 2)
      eps = 0.0_wp
      area = polygon_signed_area(xy)
      if (n < 3 .or. .not. area > 0.0_wp) return
      call vem_boundary_weights(xy, work(1:2*n))
      ! sum of b_i u_i, b_i = |E| B_i with rows (qx, 0), (0, qy), (qy, qx), written out
      ! without the zero terms
      do i = 1, n
         eps(1) = eps(1) + work(2*i - 1)*ue(2*i - 1)
         eps(2) = eps(2) + work(2*i)*ue(2*i)
         eps(3) = eps(3) + (work(2*i)*ue(2*i - 1) + work(2*i - 1)*ue(2*i))
      end do
      eps = eps/area
   end subroutine vem_strain

   !> Stress (sxx, syy, sxy) = D * projected strain, constant over the element.
   pure subroutine vem_stress(xy, d, ue, work, sig)
      real(wp), intent(in) :: xy(:, :), d(3, 3), ue(:)
      real(wp), intent(inout) :: work(:)
      real(wp), intent(out) :: sig(3)
      real(wp) :: eps(3)
      call vem_strain(xy, ue, work, eps)
      sig = matmul(d, eps)
   end subroutine vem_stress

   !> w_i = integral of Pi phi_i = |E| (Pi phi_i)(x_c)
   !>     = |E|/n + q_i . (x_c - xbar),
   !> since Pi phi_i is linear with vertex mean 1/n and gradient q_i/|E|.
   !> sum w_i = |E| because sum q_i = 0 (closed boundary), and sum w_i x_i =
   !> integral of x, because sum_i x_i phi_i = x is linear, so Pi reproduces it.
   !> The weights of a strongly non-convex polygon may be negative.
   pure subroutine vem_load_weights(xy, work, w)
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(inout) :: work(:)
      real(wp), intent(out) :: w(:)
      real(wp) :: area, xc(2), dx(2)
      integer :: i, n
      n = size(xy, 2)
      w = 0.0_wp
      area = polygon_signed_area(xy)
      if (n < 3 .or. .not. area > 0.0_wp) return
      call vem_boundary_weights(xy, work(1:2*n))
      call polygon_centroid(xy, xc)
      dx = xc - sum(xy, dim=2)/real(n, wp)
      do i = 1, n
         w(i) = area/real(n, wp) + dot_product(work(2*i - 1:2*i), dx)
      end do
   end subroutine vem_load_weights
end module vemcontact_element_vem
