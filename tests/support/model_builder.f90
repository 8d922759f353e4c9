!> Builds an in-memory model from a generated mesh, so solver-level tests run the
!> same assembly and solution path as the program without writing decks.
module vemcontact_test_model
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, material_t, string_t, source_loc_t, step_t, &
                               etype_polygon, etype_quad4, etype_tri3, etype_polygon2, etype_quad8, etype_tri6, form_fem
   implicit none
   private

   public :: make_model, boundary_mask

contains

   !> One material, one plane assumption and formulation for all elements.
   !> `order` = 2 (optional): second-order elements (corners, then side nodes):
   !> CPE6/CPE8 types for 6 and 8 nodes under form_fem, VPE2 otherwise.
   subroutine make_model(x, ptr, conn, young, poisson, plane, form, thick, model, order)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: ptr(:), conn(:)
      real(wp), intent(in) :: young, poisson, thick
      integer, intent(in) :: plane, form
      type(model_t), intent(out) :: model
      integer, intent(in), optional :: order
      integer :: e, n
      model%nnode = size(x, 2)
      model%x = x
      model%node_id = [(int(e, ip), e=1, size(x, 2))]
      model%node_loc = [(source_loc_t(1, e), e=1, size(x, 2))]
      model%nelem = size(ptr) - 1
      model%elem_ptr = ptr
      model%elem_conn = conn
      model%elem_id = [(int(e, ip), e=1, model%nelem)]
      allocate (model%elem_type(model%nelem), model%elem_plane(model%nelem), model%elem_form(model%nelem))
      do e = 1, model%nelem
         n = ptr(e + 1) - ptr(e)
         model%elem_type(e) = etype_polygon
         if (n == 4) model%elem_type(e) = etype_quad4
         if (n == 3) model%elem_type(e) = etype_tri3
         if (present(order)) then
            if (order == 2) then
               model%elem_type(e) = etype_polygon2
               if (form == form_fem .and. n == 8) model%elem_type(e) = etype_quad8
               if (form == form_fem .and. n == 6) model%elem_type(e) = etype_tri6
            end if
         end if
      end do
      model%elem_plane = plane
      model%elem_form = form
      allocate (model%elem_mat(model%nelem), source=1)
      allocate (model%elem_thick(model%nelem), source=thick)
      model%elem_loc = [(source_loc_t(1, e), e=1, model%nelem)]
      model%files = [string_t('generated')]
      allocate (model%materials(1))
      model%materials(1)%name = 'M'
      model%materials(1)%young = young
      model%materials(1)%poisson = poisson
      model%materials(1)%has_elastic = .true.
      allocate (model%steps(1))
   end subroutine make_model

   !> Nodes on the boundary edges of the mesh (edges used by one element only).
   function boundary_mask(nnode, ptr, conn) result(on)
      integer(ip), intent(in) :: nnode, ptr(:), conn(:)
      logical, allocatable :: on(:)
      integer(ip), allocatable :: a(:), b(:), key_order(:)
      integer :: e, k, n, m, i
      integer(ip) :: p, q
      ! collect edges as (min, max) pairs, sort, and keep the unpaired ones
      m = size(conn)
      allocate (a(m), b(m))
      i = 0
      do e = 1, size(ptr) - 1
         n = ptr(e + 1) - ptr(e)
         do k = 0, n - 1
            p = conn(ptr(e) + k)
            q = conn(ptr(e) + mod(k + 1, n))
            i = i + 1
            a(i) = min(p, q)
            b(i) = max(p, q)
         end do
      end do
      key_order = sort_pairs(a, b)
      allocate (on(nnode), source=.false.)
      i = 1
      do while (i <= m)
         if (i < m) then
            if (a(key_order(i)) == a(key_order(i + 1)) .and. b(key_order(i)) == b(key_order(i + 1))) then
               i = i + 2
               cycle
            end if
         end if
         on(a(key_order(i))) = .true.
         on(b(key_order(i))) = .true.
         i = i + 1
      end do
   end function boundary_mask

   !> Order of (a, b) pairs, lexicographic (simple merge sort; test meshes are small).
   function sort_pairs(a, b) result(order)
      integer(ip), intent(in) :: a(:), b(:)
      integer(ip), allocatable :: order(:), tmp(:)
      integer :: n, width, lo, mid, hi, i, j, k
      n = size(a)
      order = [(int(i, ip), i=1, n)]
      allocate (tmp(n))
      width = 1
      do while (width < n)
         lo = 1
         do while (lo <= n)
            mid = min(lo + width, n + 1)
            hi = min(lo + 2*width, n + 1)
            i = lo; j = mid; k = lo
            do while (k < hi)
               ! Fortran does not short-circuit: never index order(j) with j = hi
               if (i >= mid) then
                  tmp(k) = order(j); j = j + 1
               else if (j >= hi) then
                  tmp(k) = order(i); i = i + 1
               else if (less(order(j), order(i))) then
                  tmp(k) = order(j); j = j + 1
               else
                  tmp(k) = order(i); i = i + 1
               end if
               k = k + 1
            end do
            lo = hi
         end do
         order = tmp
         width = 2*width
      end do
   contains
      logical function less(p, q)
         integer(ip), intent(in) :: p, q
         less = a(p) < a(q) .or. (a(p) == a(q) .and. b(p) < b(q))
      end function less
   end function sort_pairs
end module vemcontact_test_model
