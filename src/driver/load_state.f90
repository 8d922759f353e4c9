!> The boundary conditions and loads in force during a step, accumulated over
!> the steps with CalculiX's OP semantics: with OP=MOD (default) a step's entry
!> replaces an earlier one on the same dof (or element, load kind and side) and
!> keeps the others; OP=NEW first removes all entries of that kind from earlier
!> steps.  Conditions given before the first *STEP (model definition) hold in
!> every step and are not removed by OP=NEW.
module vemcontact_driver_load_state
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, step_t, dload_t, dof_value_t, uplift_t
   implicit none
   private

   public :: load_state_t, init_load_state, advance_load_state

   type :: load_state_t
      logical, allocatable :: fixed(:)        !< (ndof) dof has a prescribed displacement
      real(wp), allocatable :: prescribed(:)  !< (ndof) its value
      real(wp), allocatable :: force(:)       !< (ndof) concentrated loads
      !> (ndof) the *AMPLITUDE of the prescribed value and of the load at each dof
      !> (index into model%amplitudes, 0: the step's ramp)
      integer, allocatable :: fixed_amp(:), force_amp(:)
      type(dload_t), allocatable :: dload(:)  !< distributed loads in force
      type(uplift_t), allocatable :: uplift(:) !< *UPLIFT in force, one per interaction
      logical, allocatable :: base_fixed(:)   !< model-definition constraints
      real(wp), allocatable :: base_value(:)
      integer, allocatable :: base_amp(:)
      !> (nnode) temperatures: T0 (*INITIAL CONDITIONS), T in force, and dT = T - T0
      real(wp), allocatable :: temp0(:), temp(:), dtemp(:)
   end type load_state_t

contains

   !> State before the first step: only the model-definition boundary conditions.
   subroutine init_load_state(model, st)
      type(model_t), intent(in) :: model
      type(load_state_t), intent(out) :: st
      integer(ip) :: ndof
      ndof = 2*model%nnode
      allocate (st%fixed(ndof), source=.false.)
      allocate (st%prescribed(ndof), source=0.0_wp)
      allocate (st%force(ndof), source=0.0_wp)
      allocate (st%fixed_amp(ndof), st%force_amp(ndof), source=0)
      allocate (st%dload(0), st%uplift(0))
      if (allocated(model%initial%boundary)) &
         call set_dofs(model%initial%boundary, st%fixed, st%prescribed, st%fixed_amp)
      st%base_fixed = st%fixed
      st%base_value = st%prescribed
      st%base_amp = st%fixed_amp
      allocate (st%temp0(model%nnode), source=0.0_wp)
      if (allocated(model%initial%temperature)) call set_values(model%initial%temperature, st%temp0)
      st%temp = st%temp0
      st%dtemp = st%temp - st%temp0
   end subroutine init_load_state

   !> Apply the entries of `step` to the state left by the previous step.
   subroutine advance_load_state(step, st)
      type(step_t), intent(in) :: step
      type(load_state_t), intent(inout) :: st
      logical, allocatable :: dummy(:)
      if (step%boundary_new) then
         st%fixed = st%base_fixed
         st%prescribed = st%base_value
         st%fixed_amp = st%base_amp
      end if
      if (allocated(step%boundary)) call set_dofs(step%boundary, st%fixed, st%prescribed, st%fixed_amp)
      if (step%cload_new) then
         st%force = 0.0_wp
         st%force_amp = 0
      end if
      if (allocated(step%cload)) then
         allocate (dummy(size(st%force)), source=.false.)
         call set_dofs(step%cload, dummy, st%force, st%force_amp)
      end if
      if (step%dload_new) then
         deallocate (st%dload)
         allocate (st%dload(0))
      end if
      if (allocated(step%dload)) call merge_dloads(st%dload, step%dload)
      if (allocated(step%uplift)) call merge_uplift(st%uplift, step%uplift)
      if (allocated(st%temp)) then
         if (step%temperature_new) st%temp = st%temp0
         if (allocated(step%temperature)) call set_values(step%temperature, st%temp)
         st%dtemp = st%temp - st%temp0
      end if
   end subroutine advance_load_state

   !> A step's *UPLIFT replaces the one in force on the same interaction, a
   !> *PRESSURE PENETRATION the one on the same contact pair.
   pure subroutine merge_uplift(old, new)
      type(uplift_t), allocatable, intent(inout) :: old(:)
      type(uplift_t), intent(in) :: new(:)
      integer :: k, j
      logical :: replaced
      do k = 1, size(new)
         replaced = .false.
         do j = 1, size(old)
            if (old(j)%interaction == new(k)%interaction .and. old(j)%pair == new(k)%pair) then
               old(j) = new(k)
               replaced = .true.
            end if
         end do
         if (.not. replaced) old = [old, new(k)]
      end do
   end subroutine merge_uplift

   !> Nodal values (temperatures) of the listed nodes, the last entry for a node winning.
   pure subroutine set_values(entries, value)
      type(dof_value_t), intent(in) :: entries(:)
      real(wp), intent(inout) :: value(:)
      integer :: k
      do k = 1, size(entries)
         value(entries(k)%node) = entries(k)%value
      end do
   end subroutine set_values

   !> Set the value of each listed dof, the last entry for a dof winning.
   pure subroutine set_dofs(entries, flag, value, amp)
      type(dof_value_t), intent(in) :: entries(:)
      logical, intent(inout) :: flag(:)
      real(wp), intent(inout) :: value(:)
      integer, intent(inout) :: amp(:)
      integer :: k, d
      do k = 1, size(entries)
         d = 2*entries(k)%node - 2 + entries(k)%dof
         flag(d) = .true.
         value(d) = entries(k)%value
         amp(d) = entries(k)%amp
      end do
   end subroutine set_dofs

   !> Keep the old loads whose (element, kind, side) the new ones do not name; append the new ones.
   subroutine merge_dloads(old, new)
      type(dload_t), allocatable, intent(inout) :: old(:)
      type(dload_t), intent(in) :: new(:)
      integer(ip), allocatable :: keys(:, :), order(:)
      logical, allocatable :: keep(:)
      type(dload_t), allocatable :: merged(:)
      integer :: k
      allocate (keys(3, size(new)))
      do k = 1, size(new)
         keys(:, k) = [new(k)%elem, int(new(k)%kind, ip), int(new(k)%side, ip)]
      end do
      call sort_keys(keys, order)
      allocate (keep(size(old)))
      do k = 1, size(old)
         keep(k) = .not. key_present(keys, order, [old(k)%elem, int(old(k)%kind, ip), int(old(k)%side, ip)])
      end do
      allocate (merged(count(keep) + size(new)))
      merged(:count(keep)) = pack(old, keep)
      merged(count(keep) + 1:) = new
      call move_alloc(merged, old)
   end subroutine merge_dloads

   !> Index order sorting 3-integer keys lexicographically (insertion into a merge sort).
   pure subroutine sort_keys(keys, order)
      integer(ip), intent(in) :: keys(:, :)
      integer(ip), allocatable, intent(out) :: order(:)
      integer(ip), allocatable :: tmp(:)
      integer :: n, width, lo, mid, hi, i, j, k
      n = size(keys, 2)
      allocate (order(n), tmp(n))
      order = [(int(i, ip), i=1, n)]
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
               else if (key_less(keys(:, order(j)), keys(:, order(i)))) then
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
   end subroutine sort_keys

   pure logical function key_less(a, b)
      integer(ip), intent(in) :: a(3), b(3)
      integer :: k
      do k = 1, 3
         if (a(k) /= b(k)) then
            key_less = a(k) < b(k)
            return
         end if
      end do
      key_less = .false.
   end function key_less

   pure logical function key_present(keys, order, key)
      integer(ip), intent(in) :: keys(:, :), order(:), key(3)
      integer :: lo, hi, mid
      lo = 1; hi = size(order)
      key_present = .false.
      do while (lo <= hi)
         mid = (lo + hi)/2
         if (all(keys(:, order(mid)) == key)) then
            key_present = .true.
            return
         else if (key_less(keys(:, order(mid)), key)) then
            lo = mid + 1
         else
            hi = mid - 1
         end if
      end do
   end function key_present
end module vemcontact_driver_load_state
