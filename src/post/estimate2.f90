!> A posteriori estimate of the energy-norm error of second-order models (any cell of order 2): `s_at` (4, size of
!> elem_conn) holds each cell's own stress at each of its nodes (element_stresses'
!> s_at).  The cell stress s_h is the least-squares quadratic (in x, y) through these
!> nodal values (linear for a cell with fewer than six nodes): exact for the k = 2 VEM
!> and the straight 6-node triangle (linear stress) and for the 8-node quad on
!> parallelograms (quadratic stress).  Recovery (Zienkiewicz-Zhu for quadratic
!> elements): at every corner node a quadratic per component is fitted by least squares
!> to s_h sampled at each patch cell's corner mean (weight centre_weight) and
!> sample_frac of the way to each corner, the patch widened ring by ring (at most twice)
!> until the fit is well-posed, then a linear fit, then the mean; a side node gets the
!> mean of its two corners' polynomials there.  Inside a cell s* is the least-squares
!> quadratic through its nodes' recovered values, and
!> eta_e^2 = t int (s* - s_h)^T D^-1 (s* - s_h) is integrated on the fan of triangles
!> (corner mean, corner k, corner k+1) with a 6-point rule exact for degree 4 (curved
!> sides: their chords).
!>
!> estimate_error2 runs the stages in order, one procedure each: fit_cell_stresses,
!> recover_corners (patch fits, widened by widen_patch), recover_side_nodes,
!> integrate_indicators; the shared parts (node_cells, summarize, ...) are
!> vemcontact_post_estimate's.
module vemcontact_post_estimate2
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, element_order
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_post_estimate, only: error_estimate_t, node_cells, summarize, grow, compliance
   implicit none
   private

   public :: estimate_error2

   !> second-order recovery: a quadratic (or linear) patch fit is accepted when every squared
   !> Cholesky pivot of its unit-diagonal normal matrix exceeds this (coordinates scaled by
   !> the patch size); below, the patch is widened
   real(wp), parameter :: fit_tol2 = 1.0e-4_wp
   !> a cell's own fit through its nodes: the same test, only against a singular fit (its
   !> nodes are unisolvent for the quadratics when it has six or more)
   real(wp), parameter :: cell_tol = 1.0e-10_wp
   !> second-order recovery: a cell is sampled at its corner mean and at the points this
   !> fraction of the way to each corner (1/sqrt(3): the 2 x 2 Gauss points of a
   !> parallelogram, where the 8-node quad's stress is superconvergent)
   real(wp), parameter :: sample_frac = 0.577350269189626_wp
   !> least-squares weight of the corner-mean sample (the others weigh 1): small, so that the
   !> Gauss-like points decide, but enough to keep a quadratic fit well-posed where the
   !> patch has only two rows of them (a single row of quads)
   real(wp), parameter :: centre_weight = 0.1_wp

   !> Each cell's own stress as a polynomial:
   !> s_h(x) = coef(:, :, e) . basis((x - cen(:, e))/hsc(e)), cen the corner mean, hsc the
   !> largest corner distance.
   type :: cell_stresses_t
      real(wp), allocatable :: coef(:, :, :)
      real(wp), allocatable :: cen(:, :)
      real(wp), allocatable :: hsc(:)
   end type cell_stresses_t

contains

   !> The estimate from `s_at` (4, size of elem_conn), each cell's own stress at each of
   !> its nodes (element_stresses' s_at).
   subroutine estimate_error2(model, s_at, est)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: s_at(:, :)
      type(error_estimate_t), intent(out) :: est
      type(cell_stresses_t) :: cs
      integer(ip), allocatable :: nptr(:), nel(:)
      real(wp), allocatable :: poly(:, :, :), hp(:), srec(:, :)
      real(wp) :: en2

      allocate (est%indicator(model%nelem), source=0.0_wp)
      if (model%nelem == 0) return
      call node_cells(model, nptr, nel)
      call fit_cell_stresses(model, s_at, cs)
      call recover_corners(model, cs, nptr, nel, poly, hp)
      call recover_side_nodes(model, poly, hp, srec)
      call integrate_indicators(model, cs, srec, est%indicator, en2)
      call summarize(model, en2, est)
   end subroutine estimate_error2

   !> Each cell's s_h: the least-squares quadratic through its own nodal stresses.
   subroutine fit_cell_stresses(model, s_at, cs)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: s_at(:, :)
      type(cell_stresses_t), intent(out) :: cs
      real(wp), allocatable :: xy(:, :), bas(:, :)
      integer(ip) :: e, first
      integer :: n, nc, kk, nmax
      nmax = maxval(model%elem_ptr(2:model%nelem + 1) - model%elem_ptr(1:model%nelem))
      allocate (xy(2, nmax), bas(6, nmax))
      allocate (cs%coef(3, 6, model%nelem), cs%cen(2, model%nelem), cs%hsc(model%nelem))
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         n = int(model%elem_ptr(e + 1) - first)
         nc = n/element_order(model%elem_type(e))
         xy(:, :n) = model%x(:, model%elem_conn(first:first + n - 1))
         cs%cen(:, e) = sum(xy(:, :nc), dim=2)/real(nc, wp)
         cs%hsc(e) = 0.0_wp
         do kk = 1, nc
            cs%hsc(e) = max(cs%hsc(e), hypot(xy(1, kk) - cs%cen(1, e), xy(2, kk) - cs%cen(2, e)))
         end do
         do kk = 1, n
            bas(:, kk) = basis((xy(:, kk) - cs%cen(:, e))/cs%hsc(e))
         end do
         call cell_fit(bas(:, :n), s_at([1, 2, 4], first:first + n - 1), cs%coef(:, :, e))
      end do
   end subroutine fit_cell_stresses

   !> The recovered polynomial at every corner node, one per material among its cells:
   !> poly(:, :, k) and its scale hp(k) for the node at elem_conn position k (basis about
   !> the node); the patch is widened ring by ring (at most twice) until a quadratic fit
   !> is well-posed, then a linear fit is tried, then the patch mean.
   subroutine recover_corners(model, cs, nptr, nel, poly, hp)
      type(model_t), intent(in) :: model
      type(cell_stresses_t), intent(in) :: cs
      integer(ip), intent(in) :: nptr(:), nel(:)
      real(wp), allocatable, intent(out) :: poly(:, :, :), hp(:)
      logical, allocatable :: iscorner(:)
      integer(ip), allocatable :: stamp(:), patch(:), group(:)
      real(wp) :: cq(3, 6), hq
      integer(ip) :: e, first, node, i, m, k
      integer :: nc, j, tag, np, ng, mat, ring
      logical :: ok

      allocate (iscorner(model%nnode), source=.false.)
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         nc = int(model%elem_ptr(e + 1) - first)/element_order(model%elem_type(e))
         iscorner(model%elem_conn(first:first + nc - 1)) = .true.
      end do
      allocate (poly(3, 6, model%elem_ptr(model%nelem + 1) - 1), source=0.0_wp)
      allocate (hp(model%elem_ptr(model%nelem + 1) - 1), source=1.0_wp)
      allocate (stamp(model%nelem), source=0_ip)
      allocate (patch(64), group(64))
      tag = 0
      do node = 1, model%nnode
         if (.not. iscorner(node)) cycle
         do i = nptr(node), nptr(node + 1) - 1
            mat = model%elem_mat(nel(i))
            if (any(model%elem_mat(nel(nptr(node):i - 1)) == mat)) cycle
            ng = 0
            do m = i, nptr(node + 1) - 1
               if (model%elem_mat(nel(m)) == mat) then
                  ng = ng + 1
                  if (ng > size(group)) call grow(group)
                  group(ng) = nel(m)
               end if
            end do
            do while (size(patch) < ng)
               call grow(patch)
            end do
            patch(:ng) = group(:ng)
            np = ng
            tag = tag + 1
            stamp(patch(:np)) = tag
            ok = .false.
            do ring = 0, 2
               if (ring > 0) call widen_patch(model, nptr, nel, mat, tag, stamp, patch, np)
               call patch_fit(model, cs, node, patch(:np), 2, cq, hq, ok)
               if (ok) exit
            end do
            if (.not. ok) call patch_fit(model, cs, node, patch(:np), 1, cq, hq, ok)
            if (.not. ok) then
               cq = 0.0_wp
               do j = 1, ng
                  cq(:, 1) = cq(:, 1) + cs%coef(:, 1, group(j))
               end do
               cq(:, 1) = cq(:, 1)/real(ng, wp)
            end if
            do j = 1, ng
               e = group(j)
               do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
                  if (model%elem_conn(k) /= node) cycle
                  poly(:, :, k) = cq
                  hp(k) = hq
               end do
            end do
         end do
      end do
   end subroutine recover_corners

   !> One more ring: the cells of material `mat` that share a node with the patch
   !> patch(:np), marked in `stamp` with `tag`.
   subroutine widen_patch(model, nptr, nel, mat, tag, stamp, patch, np)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: nptr(:), nel(:)
      integer, intent(in) :: mat, tag
      integer(ip), intent(inout) :: stamp(:)
      integer(ip), allocatable, intent(inout) :: patch(:)
      integer, intent(inout) :: np
      integer :: jj, last
      integer(ip) :: ee, kq, mq
      last = np
      do jj = 1, last
         ee = patch(jj)
         do kq = model%elem_ptr(ee), model%elem_ptr(ee + 1) - 1
            do mq = nptr(model%elem_conn(kq)), nptr(model%elem_conn(kq) + 1) - 1
               if (stamp(nel(mq)) == tag .or. model%elem_mat(nel(mq)) /= mat) cycle
               stamp(nel(mq)) = tag
               np = np + 1
               if (np > size(patch)) call grow(patch)
               patch(np) = nel(mq)
            end do
         end do
      end do
   end subroutine widen_patch

   !> Least-squares fit of degree `dg` (1 or 2) of the patch cells' stresses sampled at
   !> their corner means and sample_frac of the way to each corner: the coefficients
   !> coef(3, 6) of basis((x - x_node)/h) (unused ones zero).
   pure subroutine patch_fit(model, cs, node, cells, dg, coef, h, okf)
      type(model_t), intent(in) :: model
      type(cell_stresses_t), intent(in) :: cs
      integer(ip), intent(in) :: node, cells(:)
      integer, intent(in) :: dg
      real(wp), intent(out) :: coef(3, 6), h
      logical, intent(out) :: okf
      real(wp) :: mm(6, 6), rhs(6, 3), b(6), z(2), sv(3), pt(2), wt
      integer :: jj, kc, nb, ncj
      integer(ip) :: ee, f0
      nb = merge(6, 3, dg == 2)
      h = 0.0_wp
      do jj = 1, size(cells)
         h = max(h, hypot(cs%cen(1, cells(jj)) - model%x(1, node), cs%cen(2, cells(jj)) - model%x(2, node)) + &
             0.5_wp*cs%hsc(cells(jj)))
      end do
      okf = .false.
      coef = 0.0_wp
      if (.not. (h > 0.0_wp)) return
      mm = 0.0_wp
      rhs = 0.0_wp
      do jj = 1, size(cells)
         ee = cells(jj)
         f0 = model%elem_ptr(ee)
         ncj = int(model%elem_ptr(ee + 1) - f0)/element_order(model%elem_type(ee))
         do kc = 0, ncj
            if (kc == 0) then
               z = [0.0_wp, 0.0_wp]
               wt = centre_weight
            else
               z = sample_frac*(model%x(:, model%elem_conn(f0 + kc - 1)) - cs%cen(:, ee))/cs%hsc(ee)
               wt = 1.0_wp
            end if
            sv = matmul(cs%coef(:, :, ee), basis(z))
            pt = cs%cen(:, ee) + cs%hsc(ee)*z
            b = basis((pt - model%x(:, node))/h)
            mm(:nb, :nb) = mm(:nb, :nb) + wt*spread(b(:nb), 2, nb)*spread(b(:nb), 1, nb)
            rhs(:nb, :) = rhs(:nb, :) + wt*spread(b(:nb), 2, 3)*spread(sv, 1, nb)
         end do
      end do
      call spd_solve(mm(:nb, :nb), rhs(:nb, :), fit_tol2, okf)
      if (okf) coef(:, :nb) = transpose(rhs(:nb, :))
   end subroutine patch_fit

   !> Recovered values srec(3, k) at elem_conn position k: a corner its patch's value; a
   !> side node the mean of the values of the patches of the side's two corners there
   !> (Zienkiewicz-Zhu for quadratic elements).
   subroutine recover_side_nodes(model, poly, hp, srec)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: poly(:, :, :), hp(:)
      real(wp), allocatable, intent(out) :: srec(:, :)
      real(wp) :: p(2)
      integer(ip) :: e, first, ka, kb
      integer :: n, nc, kk
      allocate (srec(3, model%elem_ptr(model%nelem + 1) - 1), source=0.0_wp)
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         n = int(model%elem_ptr(e + 1) - first)
         nc = n/element_order(model%elem_type(e))
         do kk = 1, nc
            srec(:, first + kk - 1) = poly(:, 1, first + kk - 1)
         end do
         do kk = nc + 1, n
            ka = first + kk - nc - 1
            kb = first + mod(kk - nc, nc)
            p = model%x(:, model%elem_conn(first + kk - 1))
            srec(:, first + kk - 1) = 0.5_wp*(matmul(poly(:, :, ka), basis((p - model%x(:, model%elem_conn(ka)))/hp(ka))) &
                                              + matmul(poly(:, :, kb), basis((p - model%x(:, model%elem_conn(kb)))/hp(kb))))
         end do
      end do
   end subroutine recover_side_nodes

   !> eta_e = sqrt(t int (s* - s_h)^T D^-1 (s* - s_h)) per cell, s* the least-squares
   !> quadratic through its nodes' recovered values, with a 6-point rule exact for degree 4
   !> on each fan triangle (corner mean, corner k, corner k+1); en2 = sum t int s_h D^-1 s_h.
   subroutine integrate_indicators(model, cs, srec, indicator, en2)
      type(model_t), intent(in) :: model
      type(cell_stresses_t), intent(in) :: cs
      real(wp), intent(in) :: srec(:, :)
      real(wp), intent(inout) :: indicator(:)
      real(wp), intent(out) :: en2
      real(wp), allocatable :: xy(:, :), bas(:, :)
      real(wp) :: d(3, 3), cinv(3, 3), q(3), a, e2, c(2), quad(3, 6), p(2), sh(3), w6(6), l6(3, 6)
      integer(ip) :: e, first
      integer :: n, nc, kk, k1, nmax, g
      nmax = maxval(model%elem_ptr(2:model%nelem + 1) - model%elem_ptr(1:model%nelem))
      allocate (xy(2, nmax), bas(6, nmax))
      l6(:, 1) = [0.445948490915965_wp, 0.445948490915965_wp, 0.108103018168070_wp]
      l6(:, 2) = [0.445948490915965_wp, 0.108103018168070_wp, 0.445948490915965_wp]
      l6(:, 3) = [0.108103018168070_wp, 0.445948490915965_wp, 0.445948490915965_wp]
      l6(:, 4) = [0.091576213509771_wp, 0.091576213509771_wp, 0.816847572980459_wp]
      l6(:, 5) = [0.091576213509771_wp, 0.816847572980459_wp, 0.091576213509771_wp]
      l6(:, 6) = [0.816847572980459_wp, 0.091576213509771_wp, 0.091576213509771_wp]
      w6 = [0.223381589678011_wp, 0.223381589678011_wp, 0.223381589678011_wp, &
            0.109951743655322_wp, 0.109951743655322_wp, 0.109951743655322_wp]
      en2 = 0.0_wp
      do e = 1, model%nelem
         if (model%elem_mat(e) < 1) cycle
         first = model%elem_ptr(e)
         n = int(model%elem_ptr(e + 1) - first)
         nc = n/element_order(model%elem_type(e))
         xy(:, :n) = model%x(:, model%elem_conn(first:first + n - 1))
         associate (mt => model%materials(model%elem_mat(e)))
            call elastic_matrix(mt%young, mt%poisson, model%elem_plane(e), d)
         end associate
         call compliance(d, cinv)
         do kk = 1, n
            bas(:, kk) = basis((xy(:, kk) - cs%cen(:, e))/cs%hsc(e))
         end do
         call cell_fit(bas(:, :n), srec(:, first:first + n - 1), quad)
         c = cs%cen(:, e)
         e2 = 0.0_wp
         do kk = 1, nc
            k1 = merge(1, kk + 1, kk == nc)
            a = 0.5_wp*((xy(1, kk) - c(1))*(xy(2, k1) - c(2)) - (xy(1, k1) - c(1))*(xy(2, kk) - c(2)))
            do g = 1, 6
               p = l6(1, g)*c + l6(2, g)*xy(:, kk) + l6(3, g)*xy(:, k1)
               bas(:, 1) = basis((p - c)/cs%hsc(e))
               sh = matmul(cs%coef(:, :, e), bas(:, 1))
               q = matmul(quad, bas(:, 1)) - sh
               e2 = e2 + a*w6(g)*dot_product(q, matmul(cinv, q))
               en2 = en2 + a*w6(g)*model%elem_thick(e)*dot_product(sh, matmul(cinv, sh))
            end do
         end do
         indicator(e) = sqrt(max(e2, 0.0_wp)*model%elem_thick(e))
      end do
   end subroutine integrate_indicators

   !> Least-squares polynomial coef(3, 6) through the values vals(3, n) at n nodes with
   !> basis values bas(6, n): quadratic with six nodes or more, else (or when that fit is
   !> ill-posed) linear, else the mean (the unused coefficients zero).
   pure subroutine cell_fit(bas, vals, coef)
      real(wp), intent(in) :: bas(:, :), vals(:, :)
      real(wp), intent(out) :: coef(3, 6)
      logical :: ok
      coef = 0.0_wp
      ok = .false.
      if (size(bas, 2) >= 6) call lsq_fit(bas, vals, coef, cell_tol, ok)
      if (.not. ok) call lsq_fit(bas(:3, :), vals, coef(:, :3), cell_tol, ok)
      if (.not. ok) coef(:, 1) = sum(vals, dim=2)/real(size(vals, 2), wp)
   end subroutine cell_fit

   !> Monomials 1, x, y, x^2, x y, y^2 of a scaled point.
   pure function basis(z) result(b)
      real(wp), intent(in) :: z(2)
      real(wp) :: b(6)
      b = [1.0_wp, z(1), z(2), z(1)*z(1), z(1)*z(2), z(2)*z(2)]
   end function basis

   !> Least-squares coefficients coef(3, nb) of the values vals(3, npt) in the basis
   !> values bas(nb, npt); ok = .false. when the normal matrix fails spd_solve's test at tol.
   pure subroutine lsq_fit(bas, vals, coef, tol, ok)
      real(wp), intent(in) :: bas(:, :), vals(:, :), tol
      real(wp), intent(out) :: coef(:, :)
      logical, intent(out) :: ok
      real(wp) :: mm(size(bas, 1), size(bas, 1)), rhs(size(bas, 1), 3)
      mm = matmul(bas, transpose(bas))
      rhs = matmul(bas, transpose(vals))
      call spd_solve(mm, rhs, tol, ok)
      coef = transpose(rhs)
      if (.not. ok) coef = 0.0_wp
   end subroutine lsq_fit

   !> Solve m x = rhs in place (rhs becomes x) by Cholesky on the diagonally scaled m
   !> (unit diagonal); ok = .false. when a squared pivot falls below tol (an ill-posed fit:
   !> the pivots of the unit-diagonal matrix bound its smallest eigenvalue from above).
   pure subroutine spd_solve(m, rhs, tol, ok)
      real(wp), intent(in) :: m(:, :), tol
      real(wp), intent(inout) :: rhs(:, :)
      logical, intent(out) :: ok
      real(wp) :: l(size(m, 1), size(m, 1)), sc(size(m, 1)), piv
      integer :: i, j, nb
      nb = size(m, 1)
      ok = .false.
      do i = 1, nb
         if (.not. (m(i, i) > 0.0_wp)) return
         sc(i) = 1.0_wp/sqrt(m(i, i))
      end do
      l = 0.0_wp
      do j = 1, nb
         piv = m(j, j)*sc(j)*sc(j) - sum(l(j, :j - 1)**2)
         if (.not. (piv > tol)) return
         l(j, j) = sqrt(piv)
         do i = j + 1, nb
            l(i, j) = (m(i, j)*sc(i)*sc(j) - sum(l(i, :j - 1)*l(j, :j - 1)))/l(j, j)
         end do
      end do
      do j = 1, size(rhs, 2)
         rhs(:, j) = rhs(:, j)*sc
         do i = 1, nb
            rhs(i, j) = (rhs(i, j) - sum(l(i, :i - 1)*rhs(:i - 1, j)))/l(i, i)
         end do
         do i = nb, 1, -1
            rhs(i, j) = (rhs(i, j) - sum(l(i + 1:, i)*rhs(i + 1:, j)))/l(i, i)
         end do
         rhs(:, j) = rhs(:, j)*sc
      end do
      ok = .true.
   end subroutine spd_solve
end module vemcontact_post_estimate2
