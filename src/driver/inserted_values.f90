!> The nodal temperatures of the nodes that the interface node insertions (*TIE on
!> virtual elements, TYPE=SURFACE TO SURFACE contact: vemcontact_contact_insertion)
!> add to the model.  The deck's temperatures were resolved to its own nodes when it
!> was read, so a node inserted into a side would otherwise keep T = T0 = 0 and its
!> polygons a thermal strain that the deck never gave.  Each inserted node gets, in
!> the initial conditions and in every step that sets a temperature at both end
!> nodes of the deck's side it lies on, the value interpolated linearly along that
!> side (by length along the pieces of the side): a temperature field linear along
!> the side is kept exactly.  A second-order side node that the insertion moved to
!> the middle of its piece, and the side nodes of the new pieces, get the mean of
!> their piece's ends the same way.
module vemcontact_driver_inserted_values
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, dof_value_t, element_side
   implicit none
   private

   public :: interpolate_inserted

contains

   !> Temperatures of the nodes n0+1 .. model%nnode (and of the moved side nodes):
   !> appended to model%initial%temperature and to each step's list.
   subroutine interpolate_inserted(model, n0)
      type(model_t), intent(inout) :: model
      integer(ip), intent(in) :: n0
      integer(ip), allocatable :: ends(:, :)
      real(wp), allocatable :: t(:)
      integer :: s
      if (model%nnode <= n0) return
      call locate(model, n0, ends, t)
      if (allocated(model%initial%temperature)) call extend(model%initial%temperature, ends, t)
      if (.not. allocated(model%steps)) return
      do s = 1, size(model%steps)
         if (allocated(model%steps(s)%temperature)) call extend(model%steps(s)%temperature, ends, t)
      end do
   end subroutine interpolate_inserted

   !> For each node i placed by an insertion: the deck's side (ends(1, i), ends(2, i))
   !> it lies on and its parameter t(i) along it (0 at ends(1, i)); ends(:, i) = 0 for
   !> the other nodes.  The deck's corners are the nodes up to n0; a node past n0 among
   !> an element's corners lies between the nearest deck corners before and after it.
   subroutine locate(model, n0, ends, t)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: n0
      integer(ip), allocatable, intent(out) :: ends(:, :)
      real(wp), allocatable, intent(out) :: t(:)
      integer(ip), allocatable :: c(:), mid(:)
      real(wp), allocatable :: tc(:)
      integer(ip) :: e, abc(3), a, b
      integer :: ns, i, j, k
      allocate (ends(2, model%nnode), source=0_ip)
      allocate (t(model%nnode), source=0.0_wp)
      k = int(maxval(model%elem_ptr(2:) - model%elem_ptr(:model%nelem)))
      allocate (c(k), mid(k), tc(k))
      do e = 1, model%nelem
         ! only the elements that took a node (the interfaces' neighbours)
         if (.not. any(model%elem_conn(model%elem_ptr(e):model%elem_ptr(e + 1) - 1) > n0)) cycle
         call element_side(model, e, 1, abc, ns)
         do k = 1, ns
            call element_side(model, e, k, abc, ns)
            c(k) = abc(1)
            mid(k) = abc(3)
         end do
         if (any(c(:ns) > n0) .and. any(c(:ns) <= n0)) then
            do i = 1, ns
               if (c(i) <= n0) cycle
               j = back(i)
               a = c(j)
               b = c(forward(i))
               ends(:, c(i)) = [a, b]
               t(c(i)) = along(j, i)/(along(j, i) + along(i, forward(i)))
            end do
            ! the side node of each piece of a split side: the mean of the piece's ends
            do i = 1, ns
               k = modulo(i, ns) + 1
               if (mid(i) == 0 .or. (c(i) <= n0 .and. c(k) <= n0)) cycle
               if (c(i) <= n0) then
                  ends(:, mid(i)) = ends(:, c(k))
                  t(mid(i)) = 0.5_wp*t(c(k))
               else
                  ends(:, mid(i)) = ends(:, c(i))
                  tc(i) = 1.0_wp
                  if (c(k) > n0) tc(i) = t(c(k))
                  t(mid(i)) = 0.5_wp*(t(c(i)) + tc(i))
               end if
            end do
         end if
      end do
   contains
      !> The nearest deck corner before corner i (cyclic).
      integer function back(i)
         integer, intent(in) :: i
         back = i
         do
            back = modulo(back - 2, ns) + 1
            if (c(back) <= n0) return
         end do
      end function back
      !> The nearest deck corner after corner i (cyclic).
      integer function forward(i)
         integer, intent(in) :: i
         forward = i
         do
            forward = modulo(forward, ns) + 1
            if (c(forward) <= n0) return
         end do
      end function forward
      !> The length of the chords from corner i to corner j going forward.
      real(wp) function along(i, j)
         integer, intent(in) :: i, j
         integer :: k, l
         along = 0.0_wp
         k = i
         do while (k /= j)
            l = modulo(k, ns) + 1
            along = along + norm2(model%x(:, c(l)) - model%x(:, c(k)))
            k = l
         end do
      end function along
   end subroutine locate

   !> Append to `list` an entry for each located node whose side has both end nodes in
   !> the list (their last entries), the value interpolated between theirs.
   subroutine extend(list, ends, t)
      type(dof_value_t), allocatable, intent(inout) :: list(:)
      integer(ip), intent(in) :: ends(:, :)
      real(wp), intent(in) :: t(:)
      type(dof_value_t), allocatable :: more(:)
      integer, allocatable :: last(:)
      integer :: k, m
      integer(ip) :: i
      allocate (last(size(t)), source=0)
      do k = 1, size(list)
         last(list(k)%node) = k
      end do
      allocate (more(size(t)))
      m = 0
      do i = 1, size(t, kind=ip)
         if (ends(1, i) == 0) cycle
         if (last(ends(1, i)) == 0 .or. last(ends(2, i)) == 0) cycle
         associate (va => list(last(ends(1, i))), vb => list(last(ends(2, i))))
            m = m + 1
            more(m) = va
            more(m)%node = i
            more(m)%value = (1.0_wp - t(i))*va%value + t(i)*vb%value
         end associate
      end do
      if (m > 0) list = [list, more(1:m)]
   end subroutine extend
end module vemcontact_driver_inserted_values
