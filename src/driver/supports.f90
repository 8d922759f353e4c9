!> Detection of parts of the model that are not held against rigid-body motion.
!> A singular stiffness matrix is found before factorization and explained in
!> terms of the model (which part, which motion), rather than surfacing as a
!> zero pivot or a garbage solution.  A part is a set of elements connected
!> through shared nodes.  Its supports suppress rigid motion u = (a - w*y, b + w*x)
!> iff the constraint rows [1, 0, -y] (x fixed) and [0, 1, x] (y fixed) have rank 3.
module vemcontact_driver_supports
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, append_message, err_model
   use vemcontact_model, only: model_t, location_string
   use vemcontact_linalg_lapack, only: dsyev
   implicit none
   private

   public :: find_parts, check_supports, unused_nodes

contains

   !> Label each node with its part (0 for nodes in no element); nparts parts.
   subroutine find_parts(model, part, nparts)
      type(model_t), intent(in) :: model
      integer(ip), allocatable, intent(out) :: part(:)
      integer(ip), intent(out) :: nparts
      integer(ip), allocatable :: parent(:)
      integer(ip) :: e, k, r1, r2, i
      allocate (parent(model%nnode))
      parent = [(i, i=1, model%nnode)]
      do e = 1, model%nelem
         r1 = root(model%elem_conn(model%elem_ptr(e)))
         do k = model%elem_ptr(e) + 1, model%elem_ptr(e + 1) - 1
            r2 = root(model%elem_conn(k))
            if (r1 /= r2) parent(r2) = r1
         end do
      end do
      allocate (part(model%nnode), source=0_ip)
      nparts = 0
      ! number the roots, then every used node takes its root's number
      do e = 1, model%nelem
         do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
            r1 = root(model%elem_conn(k))
            if (part(r1) == 0) then
               nparts = nparts + 1
               part(r1) = nparts
            end if
         end do
      end do
      do e = 1, model%nelem
         do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
            i = model%elem_conn(k)
            part(i) = part(root(i))
         end do
      end do
   contains
      integer(ip) function root(node) result(r)
         integer(ip), intent(in) :: node
         integer(ip) :: nxt, cur
         r = node
         do while (parent(r) /= r)
            r = parent(r)
         end do
         cur = node       ! path compression
         do while (parent(cur) /= r)
            nxt = parent(cur)
            parent(cur) = r
            cur = nxt
         end do
      end function root
   end subroutine find_parts

   !> Mask of nodes that belong to no element.
   pure function unused_nodes(model) result(unused)
      type(model_t), intent(in) :: model
      logical, allocatable :: unused(:)
      allocate (unused(model%nnode), source=.true.)
      unused(model%elem_conn) = .false.
   end function unused_nodes

   !> Error naming every part that its fixed dofs do not hold.
   subroutine check_supports(model, part, nparts, fixed, error)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: part(:), nparts
      logical, intent(in) :: fixed(:)
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: lo(:, :), hi(:, :), ctc(:, :, :)
      integer(ip), allocatable :: nelem(:), first_elem(:)
      real(wp) :: c(2), s, r(3), ev(3), work(20), m(3, 3), v(3)
      integer :: p, i, e, info
      character(len=160) :: buf
      character(len=:), allocatable :: motion
      allocate (lo(2, nparts), source=huge(1.0_wp))
      allocate (hi(2, nparts), source=-huge(1.0_wp))
      allocate (ctc(3, 3, nparts), source=0.0_wp)
      allocate (nelem(nparts), source=0_ip)
      allocate (first_elem(nparts), source=0_ip)
      do i = 1, model%nnode
         p = part(i)
         if (p == 0) cycle
         lo(:, p) = min(lo(:, p), model%x(:, i))
         hi(:, p) = max(hi(:, p), model%x(:, i))
      end do
      do e = 1, model%nelem
         p = part(model%elem_conn(model%elem_ptr(e)))
         nelem(p) = nelem(p) + 1
         if (first_elem(p) == 0) first_elem(p) = e
      end do
      ! constraint rows in coordinates centred on and scaled by the part's box,
      ! so the rank test is independent of units and position
      do i = 1, model%nnode
         p = part(i)
         if (p == 0) cycle
         c = 0.5_wp*(lo(:, p) + hi(:, p))
         s = max(maxval(hi(:, p) - lo(:, p)), tiny(1.0_wp))
         if (fixed(2*i - 1)) then
            r = [1.0_wp, 0.0_wp, -(model%x(2, i) - c(2))/s]
            ctc(:, :, p) = ctc(:, :, p) + spread(r, 2, 3)*spread(r, 1, 3)
         end if
         if (fixed(2*i)) then
            r = [0.0_wp, 1.0_wp, (model%x(1, i) - c(1))/s]
            ctc(:, :, p) = ctc(:, :, p) + spread(r, 2, 3)*spread(r, 1, 3)
         end if
      end do
      do p = 1, nparts
         m = ctc(:, :, p)
         call dsyev('V', 'U', 3, m, 3, ev, work, size(work), info)
         ! rows are O(1); a smallest eigenvalue below 1e-10 of the largest means the
         ! supports leave a rigid motion free (exact zero in exact arithmetic)
         if (info == 0 .and. ev(1) > 1.0e-10_wp*max(ev(3), 1.0_wp)) cycle
         v = m(:, 1)
         c = 0.5_wp*(lo(:, p) + hi(:, p))
         s = max(maxval(hi(:, p) - lo(:, p)), tiny(1.0_wp))
         if (ev(3) <= 0.0_wp) then
            motion = 'it has no support at all (no *BOUNDARY on any of its nodes)'
         else if (abs(v(3)) < 1.0e-8_wp) then
            write (buf, '(a,2(es10.3,a))') 'it can translate freely along (', v(1)/norm2(v(1:2)), ',', &
               v(2)/norm2(v(1:2)), ')'
            motion = trim(buf)
         else
            write (buf, '(a,2(g0.6,a))') 'it can rotate freely about the point (', &
               c(1) - v(2)/v(3)*s, ', ', c(2) + v(1)/v(3)*s, ')'
            motion = trim(buf)
         end if
         write (buf, '(a,i0,a,i0,a,i0,a,i0)') 'error: the model is not held: part ', p, ' of ', nparts, &
            ' (', nelem(p), ' elements, among them element ', model%elem_id(first_elem(p))
         call append_message(error, trim(buf)//' defined at '// &
                             location_string(model, model%elem_loc(first_elem(p)))//') floats: '//motion// &
                             '. Add *BOUNDARY conditions that hold it.', err_model)
      end do
   end subroutine check_supports
end module vemcontact_driver_supports
