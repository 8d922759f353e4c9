!> Temperatures of thermal loading (CalculiX/Abaqus): *INITIAL CONDITIONS,
!> TYPE=TEMPERATURE gives the reference temperature T0 of the nodes (model
!> data; nodes without one have T0 = 0, as in CalculiX), *TEMPERATURE the
!> temperatures T of a step (they stay in force in later steps unless changed;
!> OP=NEW first returns every node to T0).  With *EXPANSION the thermal strain
!> is alpha (T - T0) (vemcontact_driver_thermal).
module vemcontact_deck_thermal
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, dof_value_t
   use vemcontact_deck_state, only: deck_parser_t, item_list_t, err_here, get_real, push_dof
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: keyword_line_t, get_param, split_fields
   use vemcontact_deck_loads, only: field_nodes, get_op
   implicit none
   private

   public :: read_initial_conditions, read_temperature

contains

   !> *INITIAL CONDITIONS, TYPE=TEMPERATURE; data lines: node or node set, T0.
   !> Other TYPEs (initial stresses, velocities, ...) are not supported.
   subroutine read_initial_conditions(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: tname
      logical :: found
      call get_param(kw, 'TYPE', tname, found)
      if (tname /= 'TEMPERATURE') then
         call err_here(p, '*INITIAL CONDITIONS, TYPE='//tname//' is not supported', &
                       'vemcontact reads TYPE=TEMPERATURE (the reference temperature of thermal strains)')
         call skip(p)
         return
      end if
      call read_node_values(p, model, '*INITIAL CONDITIONS', p%init%temperature, p%init%nt)
   end subroutine read_initial_conditions

   !> *TEMPERATURE [, OP=MOD|NEW] (in a step); data lines: node or node set, T.
   subroutine read_temperature(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      logical :: is_new
      call get_op(p, kw, '*TEMPERATURE', is_new)
      if (is_new) then
         p%cur%tnew = .true.
         p%cur%nt = 0
      end if
      call read_node_values(p, model, '*TEMPERATURE', p%cur%temperature, p%cur%nt)
   end subroutine read_temperature

   !> Data lines "node or node set, value" into list(1:n).
   subroutine read_node_values(p, model, kname, list, n)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      character(len=*), intent(in) :: kname
      type(dof_value_t), allocatable, intent(inout) :: list(:)
      integer, intent(inout) :: n
      type(item_list_t) :: nodes
      logical :: ok
      real(wp) :: t
      integer :: i
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (p%f%n /= 2) then
            call err_here(p, 'a '//kname//' data line holds a node or node set and a temperature')
            cycle
         end if
         call field_nodes(p, model, 1, nodes, ok)
         if (.not. ok) cycle
         call get_real(p, 2, 'temperature', t, ok, required=.true.)
         if (.not. ok) cycle
         do i = 1, nodes%n
            call push_dof(list, n, dof_value_t(nodes%a(i), 1, t))
         end do
      end do
   end subroutine read_node_values

   subroutine skip(p)
      type(deck_parser_t), intent(inout) :: p
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
      end do
   end subroutine skip
end module vemcontact_deck_thermal
