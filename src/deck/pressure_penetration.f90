!> *PRESSURE PENETRATION (Abaqus' keyword, in a step): the fluid of an exposed end
!> enters a contact pair's joint wherever it has opened (docs/deck-reference.md,
!> docs/sliding-safety.md).
!>
!>   *PRESSURE PENETRATION, MASTER=master surface, SLAVE=slave surface
!>        [, CRITICAL PRESSURE=p_c] [, PENETRATION TIME=t]
!>   slave node (or one-node set) exposed, master node (or one-node set) exposed, fluid pressure
!>        [, critical contact pressure p_c]
!>
!> The data line is Abaqus' (its fourth field the critical contact pressure);
!> CRITICAL PRESSURE= is vemcontact's spelling of the same value, one or the other.
!> It becomes an uplift_t of the pair (uplift_t%pair > 0) that the pressure-penetration
!> loop of *UPLIFT, PENETRATION drives (vemcontact_driver_penetration) with Abaqus'
!> law: the pressure is uniform on the part reached from the exposed node through open
!> nodes and zero beyond.  The fluid pressure follows the step's ramp; newly opened
!> parts take it at once, so PENETRATION TIME is accepted and has no effect;
!> AMPLITUDE and further data lines are refused.
module vemcontact_deck_pressure_penetration
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, uplift_t
   use vemcontact_deck_state, only: deck_parser_t, item_list_t, here, err_here, refuse_here, warn_here, field, get_real
   use vemcontact_deck_fields, only: keyword_line_t, split_fields, get_param, has_param, squeeze, to_upper, int_str
   use vemcontact_deck_numbers, only: parse_real, num_ok
   use vemcontact_deck_lines, only: advance, skip_data
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_uplift, only: push
   use vemcontact_deck_loads, only: field_nodes
   implicit none
   private

   public :: read_pressure_penetration

   character(len=*), parameter :: data_help = 'the data line is: slave node (or node set) exposed to the '// &
                                              'fluid, master node (or node set) exposed, fluid pressure '// &
                                              '[, critical contact pressure]'
   character(len=*), parameter :: critical_help = 'a node is open to the fluid while its contact pressure '// &
                                                  'is at or below it (default 0: only where contact is lost)'

contains

   !> Read one *PRESSURE PENETRATION and its data line into the current step.
   subroutine read_pressure_penetration(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      type(uplift_t) :: up
      character(len=:), allocatable :: slave, master, val
      logical :: found, found_pc, ok
      integer :: k, nline, stat
      up%loc = here(p)
      if (has_param(kw, 'AMPLITUDE')) then
         call refuse_here(p, '*PRESSURE PENETRATION, AMPLITUDE= is not supported', &
                          'the fluid pressure follows the step''s ramp (*STEP, AMPLITUDE=RAMP or STEP)')
         call skip_data(p)
         return
      end if
      call get_param(kw, 'SLAVE', slave, found)
      slave = to_upper(squeeze(slave))
      call get_param(kw, 'MASTER', master, found)
      master = to_upper(squeeze(master))
      do k = 1, p%npair
         if (p%pair_refs(k)%slave == slave .and. p%pair_refs(k)%master == master) up%pair = k
      end do
      if (up%pair == 0) then
         call err_here(p, 'no *CONTACT PAIR has the slave surface '//slave//' and the master surface '//master, &
                       '*PRESSURE PENETRATION names the two surfaces of an existing *CONTACT PAIR')
         call skip_data(p)
         return
      end if
      up%interaction = 0
      do k = 1, p%ninter
         if (model%interactions(k)%name == p%pair_refs(up%pair)%interaction) up%interaction = k
      end do
      up%critical_pressure = 0.0_wp
      call get_param(kw, 'CRITICALPRESSURE', val, found_pc)
      if (found_pc) then
         call parse_real(squeeze(val), up%critical_pressure, stat)
         if (stat /= num_ok .or. .not. up%critical_pressure >= 0.0_wp) then
            call err_here(p, 'CRITICAL PRESSURE = '//val//' must be a number at or above 0', critical_help)
            call skip_data(p)
            return
         end if
      end if
      if (has_param(kw, 'PENETRATIONTIME')) &
         call warn_here(p, '*PRESSURE PENETRATION, PENETRATION TIME= is accepted and has no effect: '// &
                        'a static step applies the fluid pressure on newly opened parts at once')
      up%penetration = .true.
      nline = 0
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         nline = nline + 1
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (nline > 1) then
            call err_here(p, 'more than one *PRESSURE PENETRATION data line', &
                          'vemcontact takes one exposed end per contact pair (a later *PRESSURE PENETRATION '// &
                          'of the same pair replaces the earlier one)')
            cycle
         end if
         if (p%f%n > 4) then
            call err_here(p, 'too many fields on the *PRESSURE PENETRATION data line', data_help)
            cycle
         end if
         if (p%f%n < 3) then
            call err_here(p, 'missing fields on the *PRESSURE PENETRATION data line', data_help)
            cycle
         end if
         call one_node(1, 'slave', up%exposed_slave, ok)
         if (ok) call one_node(2, 'master', up%exposed_master, ok)
         if (ok) call get_real(p, 3, 'fluid pressure', up%fluid_pressure, ok, required=.true.)
         if (.not. ok) cycle
         if (p%f%n == 4) then
            if (len_trim(field(p, 4)) > 0) then
               if (found_pc) then
                  call err_here(p, 'the critical contact pressure is given twice (CRITICAL PRESSURE= and '// &
                                'the fourth field)', 'give it in one place')
                  cycle
               end if
               call get_real(p, 4, 'critical contact pressure', up%critical_pressure, ok, required=.true.)
               if (.not. ok) cycle
               if (.not. up%critical_pressure >= 0.0_wp) then
                  call err_here(p, 'critical contact pressure '//field(p, 4)//' must be a number at or above 0', &
                                critical_help)
                  cycle
               end if
            end if
         end if
         up%heel = model%x(:, up%exposed_slave)
         up%toe = up%heel
         call push(p%cur%uplift, up)
      end do
      if (nline == 0) call err_here(p, '*PRESSURE PENETRATION needs a data line', data_help)
   contains
      !> The single node named by field k (a node id or a node set of one node).
      subroutine one_node(k, which, node, ok)
         integer, intent(in) :: k
         character(len=*), intent(in) :: which
         integer(ip), intent(out) :: node
         logical, intent(out) :: ok
         type(item_list_t) :: nodes
         node = 0
         call field_nodes(p, model, k, nodes, ok)
         if (.not. ok) return
         if (nodes%n /= 1) then
            ok = .false.
            call err_here(p, 'the exposed '//which//' node set '//to_upper(squeeze(field(p, k)))//' has '// &
                          int_str(int(nodes%n))//' nodes', &
                          'give the one node of the '//which//' surface at the joint''s exposed end')
            return
         end if
         node = nodes%a(1)
      end subroutine one_node
   end subroutine read_pressure_penetration
end module vemcontact_deck_pressure_penetration
