!> The contact solve of a load state with water in the joints (*UPLIFT): the uplift
!> forces on both faces of each joint join the external forces, and with pressure
!> penetration an outer loop around the contact iteration lets the water follow the
!> opening: the part of a joint open contiguously from its heel carries the headwater,
!> the rest the prescribed distribution restarted at the crack tip, and the state is
!> solved again until the open part no longer changes (opening and uplift agree).
!> Starting from the uncracked joint, each pass can only lengthen the crack while the
!> opening grows with the uplift, so the loop reaches the shortest crack in
!> equilibrium with its own water, the one the no-tension gravity method finds.
!> A *PRESSURE PENETRATION (an uplift bound to one pair) runs through the same loop
!> with Abaqus' law: it starts dry, and the fluid pressure fills the part reached from
!> the exposed node through open nodes, nothing beyond (vemcontact_contact_uplift).
module vemcontact_driver_penetration
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t, fatal_error, err_solver, err_input
   use vemcontact_model, only: model_t, uplift_t, location_string
   use vemcontact_contact_iteration, only: contact_system_t, iteration_record_t, solve_contact
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_uplift, only: uplift_of_entries, crack_front, add_uplift_forces, slave_face_vectors
   use vemcontact_log, only: logger_t
   implicit none
   private

   public :: solve_with_uplift

   !> Passes of the pressure-penetration loop before it is declared unsettled: each
   !> pass opens at least one more node, so a joint of n slave nodes needs at most n;
   !> the dams of the tests settle in 2-4.
   integer, parameter :: max_passes = 100

contains

   !> solve_contact with the uplifts in force (none: solve_contact itself).  The
   !> contact state's cfluidp holds the uplift of each slave entry afterwards.
   subroutine solve_with_uplift(sys, model, uplifts, fixed, prescribed, fext, u, contact, error, log)
      class(contact_system_t), intent(inout), target :: sys
      type(model_t), intent(in) :: model
      type(uplift_t), intent(in) :: uplifts(:)
      logical, intent(in), target :: fixed(:)
      real(wp), intent(in) :: prescribed(:), fext(:)
      real(wp), intent(inout) :: u(:)
      type(contact_state_t), intent(inout), target :: contact
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      integer, allocatable :: which(:), nopen(:), nall(:)
      real(wp), allocatable :: s_tip(:), s_new(:), f(:), seen(:, :), arc(:), arc_new(:), face(:, :)
      type(iteration_record_t), allocatable :: records(:)
      integer :: pass, j, iterations, factorizations
      real(wp) :: t_fact, t_solve, t_search
      logical :: changed
      character(len=320) :: buf

      if (allocated(contact%cfluidp)) deallocate (contact%cfluidp)
      if (allocated(contact%water_entered)) deallocate (contact%water_entered)
      if (size(uplifts) == 0) then
         call solve_contact(sys, model, fixed, prescribed, fext, u, contact, error, log)
         return
      end if
      which = uplift_of_entries(model, contact, uplifts)
      allocate (s_tip(size(uplifts)), s_new(size(uplifts)), arc(size(uplifts)), arc_new(size(uplifts)), &
                source=0.0_wp)
      allocate (nopen(size(uplifts)), nall(size(uplifts)), source=0)
      ! a *PRESSURE PENETRATION starts dry (-1: not even the exposed node wetted)
      where (uplifts%pair > 0) s_tip = -1.0_wp
      call check_exposed(model, contact, uplifts, error)
      if (allocated(error)) return
      allocate (contact%cfluidp(contact%n), f(size(fext)), records(0), seen(size(uplifts), 0))
      iterations = 0
      factorizations = 0
      t_fact = 0.0_wp
      t_solve = 0.0_wp
      t_search = 0.0_wp
      do pass = 1, max_passes
         ! the pairing the uplift acts along: the state the solve starts from
         call contact%project(model, u, error)
         if (allocated(error)) return
         f = fext
         call slave_face_vectors(model, contact, which, face, error)
         if (allocated(error)) return
         call add_uplift_forces(model, contact, uplifts, which, s_tip, f, contact%cfluidp, face)
         call solve_contact(sys, model, fixed, prescribed, f, u, contact, error, log)
         if (allocated(error)) return
         records = [records, sys%records]
         iterations = iterations + sys%iterations
         factorizations = factorizations + sys%factorizations
         t_fact = t_fact + sys%t_factorize
         t_solve = t_solve + sys%t_solve
         t_search = t_search + sys%t_search
         changed = .false.
         do j = 1, size(uplifts)
            if (.not. uplifts(j)%penetration) cycle
            call crack_front(model, contact, which, j, uplifts(j), s_new(j), nopen(j), nall(j), arc_new(j))
            if (abs(s_new(j) - s_tip(j)) > 0.0_wp) changed = .true.
         end do
         arc = arc_new
         if (.not. changed) exit
         ! a crack that returns to an earlier length would alternate for ever
         seen = reshape([seen, s_tip], [size(uplifts), pass])
         if (any([(all(abs(seen(:, j) - s_new) <= 0.0_wp), j=1, pass)])) then
            call fatal_error(error, 'error: pressure penetration cycles: the open part of a joint returns '// &
                             'to an earlier length with the water in it (a crack that closes under its own '// &
                             'water); try a stiffer joint (the penalty K) or HARD contact', err_solver)
            return
         end if
         s_tip = s_new
         do j = 1, size(uplifts)
            if (.not. uplifts(j)%penetration) cycle
            write (buf, '(2x,a,i0,a,es12.5,a,i0,a,i0,a)') 'pressure penetration, pass ', pass, &
               ': water entered ', arc(j), ' along the joint from the heel (', nopen(j), ' of ', nall(j), &
               ' slave nodes open from the heel) on interaction '
            if (uplifts(j)%pair > 0) write (buf, '(2x,a,i0,a,es12.5,a,i0,a,i0,a,i0)') &
               'pressure penetration, pass ', pass, ': fluid entered ', arc(j), &
               ' along the joint from the exposed node (', nopen(j), ' of ', nall(j), &
               ' slave nodes wetted) on contact pair ', uplifts(j)%pair
            if (.not. present(log)) cycle
            if (uplifts(j)%pair > 0) then
               call log%say(trim(buf)//'; solving again with the fluid in the joint')
            else
               call log%say(trim(buf)//' '//model%interactions(uplifts(j)%interaction)%name// &
                            '; solving again with the headwater in the crack')
            end if
         end do
      end do
      if (pass > max_passes) then
         write (buf, '(a,i0,a)') 'error: pressure penetration did not settle in ', max_passes, &
            ' passes: the open part of a joint keeps changing with the water in it'
         call fatal_error(error, trim(buf), err_solver)
         return
      end if
      allocate (contact%water_entered(size(model%pairs)), source=-1.0_wp)
      do j = 1, size(uplifts)
         if (.not. uplifts(j)%penetration) cycle
         if (uplifts(j)%pair > 0) then
            contact%water_entered(uplifts(j)%pair) = arc(j)
         else
            where (model%pairs%interaction == uplifts(j)%interaction) contact%water_entered = arc(j)
         end if
      end do
      sys%records = records
      sys%iterations = iterations
      sys%factorizations = factorizations
      sys%t_factorize = t_fact
      sys%t_solve = t_solve
      sys%t_search = t_search
      if (present(log)) call summary()
   contains
      !> Per uplift: the uplift force (sum CFLUIDP * CNAREA) and, with penetration,
      !> how far the water entered.
      subroutine summary()
         real(wp) :: force
         do j = 1, size(uplifts)
            force = sum(contact%cfluidp*contact%length*contact%thick, mask=which == j)
            write (buf, '(2x,a,es13.6,a)') 'uplift on interaction '// &
               model%interactions(uplifts(j)%interaction)%name//': force ', force, &
               ' (sum of CFLUIDP * CNAREA)'
            if (uplifts(j)%pair > 0) then
               write (buf, '(2x,a,i0,a,es13.6,a,es12.5,a,i0,a,i0,a,i0,a)') '*PRESSURE PENETRATION on contact pair ', &
                  uplifts(j)%pair, ': fluid force ', force, ' (sum of CFLUIDP * CNAREA); fluid entered ', arc(j), &
                  ' along the joint from the exposed node (', nopen(j), ' of ', nall(j), &
                  ' slave nodes wetted; contact solved ', pass, ' times)'
            else if (uplifts(j)%penetration) then
               write (buf, '(a,a,es12.5,a,i0,a,i0,a,i0,a)') trim(buf), '; water entered ', arc(j), &
                  ' along the joint from the heel (', nopen(j), ' of ', nall(j), &
                  ' slave nodes open from the heel; contact '// &
                  'solved ', pass, ' times)'
            end if
            call log%say(trim(buf))
         end do
      end subroutine summary
   end subroutine solve_with_uplift

   !> Each *PRESSURE PENETRATION's exposed nodes lie on its pair: the slave node among
   !> the pair's slave entries, the master node on one of its master segments.
   subroutine check_exposed(model, contact, uplifts, error)
      type(model_t), intent(in) :: model
      type(contact_state_t), intent(in) :: contact
      type(uplift_t), intent(in) :: uplifts(:)
      type(error_t), allocatable, intent(out) :: error
      integer :: j
      character(len=32) :: id
      do j = 1, size(uplifts)
         associate (up => uplifts(j))
            if (up%pair == 0) cycle
            if (.not. any(contact%pair(1:contact%n) == up%pair .and. contact%node(1:contact%n) == up%exposed_slave)) then
               write (id, '(i0)') model%node_id(up%exposed_slave)
               call fatal_error(error, location_string(model, up%loc)//': error: *PRESSURE PENETRATION: the exposed '// &
                                'slave node '//trim(id)//' is not a node of the contact pair''s slave surface', &
                                err_input)
               return
            end if
            if (.not. any(contact%pairs(up%pair)%seg == up%exposed_master)) then
               write (id, '(i0)') model%node_id(up%exposed_master)
               call fatal_error(error, location_string(model, up%loc)//': error: *PRESSURE PENETRATION: the exposed '// &
                                'master node '//trim(id)//' is not a node of the contact pair''s master surface', &
                                err_input)
               return
            end if
         end associate
      end do
   end subroutine check_exposed
end module vemcontact_driver_penetration
