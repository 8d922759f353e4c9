!> A posteriori estimate of the energy-norm error by gradient (stress) recovery:
!> the Zienkiewicz-Zhu estimator with the superconvergent patch recovery (SPR).
!>
!> The element stress that the code reports (VEM: D times the projected strain,
!> constant per cell; FEM: the cell's mean) is sampled at the cell centroids; at
!> every node a linear polynomial per stress component is fitted by least squares
!> to the centroid values of the cells around it (the patch), and its value at the
!> node is the recovered stress there.  Inside a cell the recovered stress is
!> linear on each triangle of the fan (vertex mean, v_k, v_k+1).  The indicator of
!> a cell is the energy norm of the difference,
!>
!>     eta_e^2 = t_e * int_e (s* - s_h)^T D^-1 (s* - s_h) dA,
!>
!> integrated exactly (edge-midpoint rule on the fan).  The estimate is
!> sqrt(sum eta_e^2); the relative error divides it by sqrt(|s_h|^2 + eta^2), the
!> estimated energy norm of the exact solution.  docs/error-estimate.md explains the
!> choice and states the effectivities measured.
!>
!> Patches: cells of one material only (stresses jump across material boundaries);
!> nodes are not shared between bodies in contact or across open joints, so
!> patches never cross them.  A patch with fewer than three cells or with centroids
!> too close to a line for a linear fit (boundary nodes, corners) is widened by one
!> ring of cells (those sharing a node with it); if that still fails, the recovered
!> stress is the patch mean.  All work is O(number of cells x nodes per cell).
!>
!> Models with second-order cells (k = 2 VEM, 6-node triangles, 8-node quads) take
!> estimate_error2: the same estimator one degree up (the cells' own linear or quadratic
!> stresses, a quadratic patch recovery at the corners).
module vemcontact_post_estimate
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, element_order
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_centroid
   implicit none
   private

   public :: error_estimate_t, estimate_error, recover_stress, estimate_error2

   !> The estimate of one solution.
   type :: error_estimate_t
      !> per cell: eta_e, the estimated energy norm of the error in the cell
      !> (units of sqrt(energy): sqrt(N m) for a thickness in m)
      real(wp), allocatable :: indicator(:)
      real(wp) :: estimate = 0.0_wp   !< sqrt(sum eta_e^2)
      real(wp) :: energy = 0.0_wp     !< energy norm of the discrete stress, sqrt(sum t int s_h D^-1 s_h)
      real(wp) :: relative = 0.0_wp   !< estimate / sqrt(energy^2 + estimate^2)
      !> fraction of the cells that holds half of sum eta_e^2 (the cells with the largest indicators)
      real(wp) :: half_fraction = 0.0_wp
      real(wp) :: largest_at(2) = 0.0_wp  !< centroid of the cell with the largest indicator
   end type error_estimate_t

   !> the normal matrix of a linear fit is accepted when det(M)/(trace(M)/3)^3 exceeds this
   !> (coordinates scaled by the patch size; 1 for three centroids at the corners of an
   !> equilateral triangle around the node, 0 for collinear centroids): 1e-3 keeps the
   !> extrapolation of a nearly flat patch from amplifying the stress noise more than
   !> about tenfold
   real(wp), parameter :: fit_tol = 1.0e-3_wp
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

contains

   !> The error estimate of the element stresses `s_elem` (4, nelem), (xx, yy, zz, xy),
   !> as element_stresses writes them.
   subroutine estimate_error(model, s_elem, est)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: s_elem(:, :)
      type(error_estimate_t), intent(out) :: est
      real(wp), allocatable :: srec(:, :), xy(:, :), ev(:, :)
      real(wp) :: d(3, 3), cinv(3, 3), sh(3), ec(3), q(3), a, e2, en2, c(2)
      integer(ip) :: e, first
      integer :: n, k, k1, nmax

      allocate (est%indicator(model%nelem), source=0.0_wp)
      if (model%nelem == 0) return
      call recover_stress(model, s_elem, srec)
      nmax = maxval(model%elem_ptr(2:model%nelem + 1) - model%elem_ptr(1:model%nelem))
      allocate (xy(2, nmax), ev(3, nmax))
      en2 = 0.0_wp
      do e = 1, model%nelem
         if (model%elem_mat(e) < 1) cycle
         first = model%elem_ptr(e)
         n = int(model%elem_ptr(e + 1) - first)
         xy(:, :n) = model%x(:, model%elem_conn(first:first + n - 1))
         associate (mat => model%materials(model%elem_mat(e)))
            call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
         end associate
         call compliance(d, cinv)
         sh = s_elem([1, 2, 4], e)
         do k = 1, n
            ev(:, k) = srec(:, first + k - 1) - sh
         end do
         ec = sum(ev(:, :n), dim=2)/real(n, wp)
         c = sum(xy(:, :n), dim=2)/real(n, wp)
         e2 = 0.0_wp
         do k = 1, n
            k1 = merge(1, k + 1, k == n)
            ! signed area of the fan triangle (c, v_k, v_k+1)
            a = 0.5_wp*((xy(1, k) - c(1))*(xy(2, k1) - c(2)) - (xy(1, k1) - c(1))*(xy(2, k) - c(2)))
            q = 0.5_wp*(ec + ev(:, k))
            e2 = e2 + a/3.0_wp*dot_product(q, matmul(cinv, q))
            q = 0.5_wp*(ev(:, k) + ev(:, k1))
            e2 = e2 + a/3.0_wp*dot_product(q, matmul(cinv, q))
            q = 0.5_wp*(ev(:, k1) + ec)
            e2 = e2 + a/3.0_wp*dot_product(q, matmul(cinv, q))
         end do
         a = polygon_signed_area(xy(:, :n))
         est%indicator(e) = sqrt(max(e2, 0.0_wp)*model%elem_thick(e))
         en2 = en2 + a*model%elem_thick(e)*dot_product(sh, matmul(cinv, sh))
      end do
      call summarize(model, en2, est)
   end subroutine estimate_error

   !> Recovered stress (xx, yy, xy) at every corner of every cell: srec(:, k) belongs to
   !> node elem_conn(k) as seen from the cell that owns position k (its material's patch).
   subroutine recover_stress(model, s_elem, srec)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: s_elem(:, :)
      real(wp), allocatable, intent(out) :: srec(:, :)
      integer(ip), allocatable :: nptr(:), nel(:), stamp(:), patch(:), group(:)
      real(wp), allocatable :: cen(:, :)
      integer(ip) :: e, k, node, first, last, i, m
      integer :: np, ng, tag, j, mat
      real(wp) :: s(3)
      logical :: ok

      allocate (srec(3, max(model%elem_ptr(model%nelem + 1) - 1, 0)), source=0.0_wp)
      call node_cells(model, nptr, nel)
      allocate (cen(2, model%nelem))
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         last = model%elem_ptr(e + 1) - 1
         call polygon_centroid(model%x(:, model%elem_conn(first:last)), cen(:, e))
      end do

      allocate (stamp(model%nelem), source=0_ip)
      allocate (patch(64), group(64))
      tag = 0
      do node = 1, model%nnode
         first = nptr(node)
         last = nptr(node + 1) - 1
         if (last < first) cycle
         ! one recovery per material among the node's cells
         do i = first, last
            mat = model%elem_mat(nel(i))
            ! done already for this material?
            if (any(model%elem_mat(nel(first:i - 1)) == mat)) cycle
            ng = 0
            do m = i, last
               if (model%elem_mat(nel(m)) == mat) then
                  ng = ng + 1
                  group(ng) = nel(m)
               end if
            end do
            ok = .false.
            if (ng >= 3) call fit(group(:ng), s, ok)
            if (.not. ok) then
               ! one more ring: cells of the material that share a node with the group
               tag = tag + 1
               np = 0
               do j = 1, ng
                  e = group(j)
                  do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
                     do m = nptr(model%elem_conn(k)), nptr(model%elem_conn(k) + 1) - 1
                        if (stamp(nel(m)) == tag .or. model%elem_mat(nel(m)) /= mat) cycle
                        stamp(nel(m)) = tag
                        np = np + 1
                        if (np > size(patch)) call grow(patch)
                        patch(np) = nel(m)
                     end do
                  end do
               end do
               if (np >= 3) call fit(patch(:np), s, ok)
            end if
            if (.not. ok) then
               s = 0.0_wp
               do j = 1, ng
                  s = s + s_elem([1, 2, 4], group(j))
               end do
               s = s/real(ng, wp)
            end if
            do j = 1, ng
               e = group(j)
               do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
                  if (model%elem_conn(k) == node) srec(:, k) = s
               end do
            end do
         end do
      end do
   contains
      !> Least-squares linear fit of the cell stresses of `cells` at their centroids,
      !> evaluated at the node; ok = .false. when the fit is ill-posed.
      subroutine fit(cells, sfit, ok)
         integer(ip), intent(in) :: cells(:)
         real(wp), intent(out) :: sfit(3)
         logical, intent(out) :: ok
         real(wp) :: mm(3, 3), rhs(3, 3), p(3), h, det, tr, inv(3, 3)
         integer :: jj
         h = 0.0_wp
         do jj = 1, size(cells)
            h = max(h, hypot(cen(1, cells(jj)) - model%x(1, node), cen(2, cells(jj)) - model%x(2, node)))
         end do
         ok = .false.
         sfit = 0.0_wp
         if (.not. (h > 0.0_wp)) return
         mm = 0.0_wp
         rhs = 0.0_wp
         do jj = 1, size(cells)
            p = [1.0_wp, (cen(1, cells(jj)) - model%x(1, node))/h, (cen(2, cells(jj)) - model%x(2, node))/h]
            mm = mm + spread(p, 2, 3)*spread(p, 1, 3)
            ! rhs(:, component)
            rhs = rhs + spread(p, 2, 3)*spread(s_elem([1, 2, 4], cells(jj)), 1, 3)
         end do
         tr = (mm(1, 1) + mm(2, 2) + mm(3, 3))/3.0_wp
         call inverse3(mm, inv, det)
         if (.not. (det > fit_tol*tr**3)) return
         ! value at the node: the constant coefficient
         sfit = matmul(inv(1, :), rhs)
         ok = .true.
      end subroutine fit
   end subroutine recover_stress

   !> The error estimate of second-order models (any cell of order 2): `s_at` (4, size of
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
   subroutine estimate_error2(model, s_at, est)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: s_at(:, :)
      type(error_estimate_t), intent(out) :: est
      real(wp), allocatable :: shq(:, :, :), cen(:, :), hsc(:), srec(:, :), xy(:, :), bas(:, :), vals(:, :)
      integer(ip), allocatable :: nptr(:), nel(:), stamp(:), patch(:), group(:)
      real(wp) :: d(3, 3), cinv(3, 3), q(3), a, e2, en2, c(2), quad(3, 6), p(2), sh(3), w6(6), l6(3, 6)
      integer(ip) :: e, first, node, i, m, k, ka, kb
      logical, allocatable :: iscorner(:)
      real(wp), allocatable :: poly(:, :, :), hp(:)
      real(wp) :: cq(3, 6), hq
      integer :: n, nc, kk, k1, nmax, j, tag, np, ng, mat, g, ring
      logical :: ok

      allocate (est%indicator(model%nelem), source=0.0_wp)
      if (model%nelem == 0) return
      call node_cells(model, nptr, nel)
      nmax = maxval(model%elem_ptr(2:model%nelem + 1) - model%elem_ptr(1:model%nelem))
      allocate (xy(2, nmax), bas(6, nmax), vals(3, nmax))
      ! the cells' stresses: s_h(x) = shq(:, :) . basis((x - cen)/hsc), cen the corner mean,
      ! hsc the largest corner distance
      allocate (shq(3, 6, model%nelem), cen(2, model%nelem), hsc(model%nelem))
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         n = int(model%elem_ptr(e + 1) - first)
         nc = n/element_order(model%elem_type(e))
         xy(:, :n) = model%x(:, model%elem_conn(first:first + n - 1))
         cen(:, e) = sum(xy(:, :nc), dim=2)/real(nc, wp)
         hsc(e) = 0.0_wp
         do kk = 1, nc
            hsc(e) = max(hsc(e), hypot(xy(1, kk) - cen(1, e), xy(2, kk) - cen(2, e)))
         end do
         do kk = 1, n
            bas(:, kk) = basis((xy(:, kk) - cen(:, e))/hsc(e))
         end do
         call cell_fit(bas(:, :n), s_at([1, 2, 4], first:first + n - 1), shq(:, :, e))
      end do

      ! recovery at every corner node, one per material among its cells: a polynomial per
      ! patch (coefficients about the node, scaled by hp), kept at the corner's positions
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
               if (ring > 0) call widen()
               call patch_fit(patch(:np), 2, cq, hq, ok)
               if (ok) exit
            end do
            if (.not. ok) call patch_fit(patch(:np), 1, cq, hq, ok)
            if (.not. ok) then
               cq = 0.0_wp
               do j = 1, ng
                  cq(:, 1) = cq(:, 1) + shq(:, 1, group(j))
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
      ! recovered values: a corner its patch's value; a side node the mean of the values of
      ! the patches of the side's two corners there (Zienkiewicz-Zhu for quadratic elements)
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

      ! indicators: 6-point rule exact for degree 4 on each fan triangle
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
         ! s* in the cell: quadratic (linear below six nodes) least-squares fit of its nodes' values
         do kk = 1, n
            bas(:, kk) = basis((xy(:, kk) - cen(:, e))/hsc(e))
         end do
         call cell_fit(bas(:, :n), srec(:, first:first + n - 1), quad)
         c = cen(:, e)
         e2 = 0.0_wp
         a = 0.0_wp
         do kk = 1, nc
            k1 = merge(1, kk + 1, kk == nc)
            a = 0.5_wp*((xy(1, kk) - c(1))*(xy(2, k1) - c(2)) - (xy(1, k1) - c(1))*(xy(2, kk) - c(2)))
            do g = 1, 6
               p = l6(1, g)*c + l6(2, g)*xy(:, kk) + l6(3, g)*xy(:, k1)
               bas(:, 1) = basis((p - c)/hsc(e))
               sh = matmul(shq(:, :, e), bas(:, 1))
               q = matmul(quad, bas(:, 1)) - sh
               e2 = e2 + a*w6(g)*dot_product(q, matmul(cinv, q))
               en2 = en2 + a*w6(g)*model%elem_thick(e)*dot_product(sh, matmul(cinv, sh))
            end do
         end do
         est%indicator(e) = sqrt(max(e2, 0.0_wp)*model%elem_thick(e))
      end do
      call summarize(model, en2, est)
   contains
      !> One more ring: the cells of the material that share a node with the patch.
      subroutine widen()
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
      end subroutine widen

      !> Least-squares fit of degree `dg` (1 or 2) of the patch cells' stresses sampled at
      !> their corner means and sample_frac of the way to each corner: the coefficients
      !> coef(3, 6) of basis((x - node)/h) (unused ones zero).
      subroutine patch_fit(cells, dg, coef, h, okf)
         integer(ip), intent(in) :: cells(:)
         integer, intent(in) :: dg
         real(wp), intent(out) :: coef(3, 6), h
         logical, intent(out) :: okf
         real(wp) :: mm(6, 6), rhs(6, 3), b(6), z(2), sv(3), pt(2), wt
         integer :: jj, kc, nb, ncj
         integer(ip) :: ee, f0
         nb = merge(6, 3, dg == 2)
         h = 0.0_wp
         do jj = 1, size(cells)
            h = max(h, hypot(cen(1, cells(jj)) - model%x(1, node), cen(2, cells(jj)) - model%x(2, node)) + &
                0.5_wp*hsc(cells(jj)))
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
                  z = sample_frac*(model%x(:, model%elem_conn(f0 + kc - 1)) - cen(:, ee))/hsc(ee)
                  wt = 1.0_wp
               end if
               sv = matmul(shq(:, :, ee), basis(z))
               pt = cen(:, ee) + hsc(ee)*z
               b = basis((pt - model%x(:, node))/h)
               mm(:nb, :nb) = mm(:nb, :nb) + wt*spread(b(:nb), 2, nb)*spread(b(:nb), 1, nb)
               rhs(:nb, :) = rhs(:nb, :) + wt*spread(b(:nb), 2, 3)*spread(sv, 1, nb)
            end do
         end do
         call spd_solve(mm(:nb, :nb), rhs(:nb, :), fit_tol2, okf)
         if (okf) coef(:, :nb) = transpose(rhs(:nb, :))
      end subroutine patch_fit
   end subroutine estimate_error2

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

   !> Node -> cells (CSR): the cells of node i are nel(nptr(i):nptr(i + 1) - 1), in cell order.
   pure subroutine node_cells(model, nptr, nel)
      type(model_t), intent(in) :: model
      integer(ip), allocatable, intent(out) :: nptr(:), nel(:)
      integer(ip), allocatable :: fill(:)
      integer(ip) :: e, k, node, i
      allocate (nptr(model%nnode + 1), source=0_ip)
      do k = 1, model%elem_ptr(model%nelem + 1) - 1
         node = model%elem_conn(k)
         nptr(node + 1) = nptr(node + 1) + 1
      end do
      nptr(1) = 1
      do i = 1, model%nnode
         nptr(i + 1) = nptr(i + 1) + nptr(i)
      end do
      allocate (nel(nptr(model%nnode + 1) - 1), fill(model%nnode))
      fill = nptr(1:model%nnode)
      do e = 1, model%nelem
         do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
            node = model%elem_conn(k)
            nel(fill(node)) = e
            fill(node) = fill(node) + 1
         end do
      end do
   end subroutine node_cells

   !> The estimate, the energy norm (from its square en2), the relative error and the
   !> concentration (the fewest cells, largest indicators first, holding half of the total)
   !> from est%indicator.
   subroutine summarize(model, en2, est)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: en2
      type(error_estimate_t), intent(inout) :: est
      real(wp), allocatable :: w(:)
      real(wp) :: total, cum
      integer(ip), allocatable :: order(:)
      integer(ip) :: e, first
      integer :: n, j
      total = sum(est%indicator**2)
      est%estimate = sqrt(total)
      est%energy = sqrt(max(en2, 0.0_wp))
      if (est%estimate > 0.0_wp) est%relative = est%estimate/sqrt(est%energy**2 + total)

      allocate (w(model%nelem))
      w = est%indicator**2
      order = descending_order(w)
      e = order(1)
      first = model%elem_ptr(e)
      ! the corners (second-order cells list them first)
      n = int(model%elem_ptr(e + 1) - first)/element_order(model%elem_type(e))
      call polygon_centroid(model%x(:, model%elem_conn(first:first + n - 1)), est%largest_at)
      if (.not. (total > 0.0_wp)) return
      cum = 0.0_wp
      do j = 1, size(order)
         cum = cum + w(order(j))
         if (cum >= 0.5_wp*total) exit
      end do
      est%half_fraction = real(min(j, size(order)), wp)/real(model%nelem, wp)
   end subroutine summarize

   subroutine grow(a)
      integer(ip), allocatable, intent(inout) :: a(:)
      integer(ip), allocatable :: b(:)
      allocate (b(2*size(a)))
      b(:size(a)) = a
      call move_alloc(b, a)
   end subroutine grow

   !> Inverse and determinant of a 3 x 3 matrix (adjugate; the callers check det).
   pure subroutine inverse3(a, inv, det)
      real(wp), intent(in) :: a(3, 3)
      real(wp), intent(out) :: inv(3, 3), det
      inv(1, 1) = a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)
      inv(1, 2) = a(1, 3)*a(3, 2) - a(1, 2)*a(3, 3)
      inv(1, 3) = a(1, 2)*a(2, 3) - a(1, 3)*a(2, 2)
      inv(2, 1) = a(2, 3)*a(3, 1) - a(2, 1)*a(3, 3)
      inv(2, 2) = a(1, 1)*a(3, 3) - a(1, 3)*a(3, 1)
      inv(2, 3) = a(1, 3)*a(2, 1) - a(1, 1)*a(2, 3)
      inv(3, 1) = a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1)
      inv(3, 2) = a(1, 2)*a(3, 1) - a(1, 1)*a(3, 2)
      inv(3, 3) = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
      det = a(1, 1)*inv(1, 1) + a(1, 2)*inv(2, 1) + a(1, 3)*inv(3, 1)
      if (abs(det) > 0.0_wp) inv = inv/det
   end subroutine inverse3

   !> Compliance D^-1 of an elasticity matrix of elastic_matrix (xx, yy block and shear).
   pure subroutine compliance(d, cinv)
      real(wp), intent(in) :: d(3, 3)
      real(wp), intent(out) :: cinv(3, 3)
      real(wp) :: det
      det = d(1, 1)*d(2, 2) - d(1, 2)*d(2, 1)
      cinv = 0.0_wp
      cinv(1, 1) = d(2, 2)/det
      cinv(2, 2) = d(1, 1)/det
      cinv(1, 2) = -d(1, 2)/det
      cinv(2, 1) = -d(2, 1)/det
      cinv(3, 3) = 1.0_wp/d(3, 3)
   end subroutine compliance

   !> Indices that sort `w` in descending order (heap sort, O(n log n)).
   pure function descending_order(w) result(idx)
      real(wp), intent(in) :: w(:)
      integer(ip), allocatable :: idx(:)
      integer(ip) :: n, i, t, last
      n = size(w)
      allocate (idx(n))
      idx = [(i, i=1, n)]
      ! a min-heap on w: popping the smallest to the end leaves the order descending
      do i = n/2, 1, -1
         call sift(i, n)
      end do
      do last = n, 2, -1
         t = idx(1)
         idx(1) = idx(last)
         idx(last) = t
         call sift(1_ip, last - 1)
      end do
   contains
      pure subroutine sift(start, nn)
         integer(ip), intent(in) :: start, nn
         integer(ip) :: root, child, tt
         root = start
         do
            child = 2*root
            if (child > nn) exit
            if (child < nn) then
               if (w(idx(child + 1)) < w(idx(child))) child = child + 1
            end if
            if (w(idx(child)) < w(idx(root))) then
               tt = idx(root)
               idx(root) = idx(child)
               idx(child) = tt
               root = child
            else
               exit
            end if
         end do
      end subroutine sift
   end function descending_order
end module vemcontact_post_estimate
