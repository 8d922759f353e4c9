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
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_model, only: model_t, element_order
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_centroid
   implicit none
   private

   public :: error_estimate_t, estimate_error, recover_stress
   ! shared with the second-order estimate (vemcontact_post_estimate2)
   public :: node_cells, summarize, grow, compliance
   ! public for its unit test
   public :: descending_order

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
            e2 = e2 + a/3.0_wp*energy_density(cinv, q)
            q = 0.5_wp*(ev(:, k) + ev(:, k1))
            e2 = e2 + a/3.0_wp*energy_density(cinv, q)
            q = 0.5_wp*(ev(:, k1) + ec)
            e2 = e2 + a/3.0_wp*energy_density(cinv, q)
         end do
         a = polygon_signed_area(xy(:, :n))
         est%indicator(e) = sqrt(max(e2, 0.0_wp)*model%elem_thick(e))
         en2 = en2 + a*model%elem_thick(e)*energy_density(cinv, sh)
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
         real(wp) :: mm(3, 3), rhs(3, 3), p(3), sc(3), h, det, tr, inv(3, 3)
         integer :: jj, kk
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
            sc = s_elem([1, 2, 4], cells(jj))
            ! outer products p p^T and p s^T (rhs(:, component)), without temporaries
            do kk = 1, 3
               mm(:, kk) = mm(:, kk) + p*p(kk)
               rhs(:, kk) = rhs(:, kk) + p*sc(kk)
            end do
         end do
         tr = (mm(1, 1) + mm(2, 2) + mm(3, 3))/3.0_wp
         call inverse3(mm, inv, det)
         if (.not. (det > fit_tol*tr**3)) return
         ! value at the node: the constant coefficient
         sfit = matmul(inv(1, :), rhs)
         ok = .true.
      end subroutine fit
   end subroutine recover_stress

   !> q^T C q for a 3 x 3 C: dot_product(q, matmul(c, q)) with the same sums in the
   !> same order, written out (gfortran's inline matmul would store and reload every
   !> partial sum of this hot loop).
   pure real(wp) function energy_density(c, q) result(r)
      real(wp), intent(in) :: c(3, 3), q(3)
      real(wp) :: v(3)
      v = c(:, 1)*q(1) + c(:, 2)*q(2) + c(:, 3)*q(3)
      r = q(1)*v(1) + q(2)*v(2) + q(3)*v(3)
   end function energy_density

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

   !> Indices that sort the non-negative `w` in descending order, equal values in index
   !> order (LSD radix sort, O(n)).
   pure function descending_order(w) result(idx)
      real(wp), intent(in) :: w(:)
      integer(ip), allocatable :: idx(:)
      integer(ip), allocatable :: tmp(:), count(:)
      integer(i8), allocatable :: key(:)
      integer(ip) :: n, i, d
      integer :: pass
      n = size(w)
      allocate (idx(n), tmp(n), key(n), count(0:65536))
      ! the bit patterns of non-negative doubles order like their values; complemented,
      ! an ascending sort puts the largest first.  Four stable counting passes of 16 bits
      ! (least significant first) keep equal values in index order.
      do i = 1, n
         key(i) = not(transfer(w(i), 0_i8))
         idx(i) = i
      end do
      do pass = 0, 3
         count = 0
         do i = 1, n
            d = int(ibits(key(idx(i)), 16*pass, 16), ip)
            count(d + 1) = count(d + 1) + 1
         end do
         do d = 1, 65536
            count(d) = count(d) + count(d - 1)
         end do
         do i = 1, n
            d = int(ibits(key(idx(i)), 16*pass, 16), ip)
            count(d) = count(d) + 1
            tmp(count(d)) = idx(i)
         end do
         idx = tmp
      end do
   end function descending_order
end module vemcontact_post_estimate
