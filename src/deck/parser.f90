!> The keyword loop: each keyword line is looked up in the registry, its
!> parameters and its place (model data or step) are checked, and its handler
!> reads the data lines that follow.  After an error the parser goes on with the
!> next line it can make sense of, so one run reports all problems of a deck.
module vemcontact_deck_parser
   use vemcontact_model, only: model_t, output_node, output_element, output_contact
   use vemcontact_deck_state, only: deck_parser_t, err_here, err_at, refuse_here, here
   use vemcontact_deck_source, only: line_keyword, line_data, line_eof
   use vemcontact_deck_fields, only: keyword_line_t, parse_keyword_line
   use vemcontact_deck_registry, only: keywords, find_keyword, keyword_suggestion, is_calculix_keyword, &
                                       out_of_scope_feature, &
                                       known_keyword_list, ctx_model, ctx_step, &
                                       kw_heading, kw_node, kw_element, kw_nset, kw_elset, &
                                       kw_material, kw_elastic, kw_density, kw_solid_section, &
                                       kw_boundary, kw_cload, kw_dload, kw_step, kw_static, kw_end_step, &
                                       kw_surface, kw_surface_interaction, kw_surface_behavior, &
                                       kw_contact_pair, kw_contact_controls, kw_geostatic, kw_dsload, &
                                       kw_node_file, kw_el_file, kw_contact_file, kw_node_print, kw_el_print, &
                                       kw_contact_print, kw_node_output, kw_element_output, kw_contact_output, &
                                       kw_output, kw_uplift, kw_equation, kw_part, kw_end_part, kw_assembly, &
                                       kw_end_assembly, kw_instance, kw_end_instance, kw_preprint, kw_restart, &
                                       kw_initial_conditions, kw_temperature, kw_expansion, kw_tie, kw_amplitude, kw_friction, &
                                       kw_strength_reduction, kw_pressure_penetration, kw_change_friction
   use vemcontact_deck_lines, only: advance, check_keyword, skip_data, no_data
   use vemcontact_deck_mesh, only: read_nodes, read_elements, read_set
   use vemcontact_deck_props, only: read_material, read_elastic, read_density, read_section, read_expansion
   use vemcontact_deck_thermal, only: read_initial_conditions, read_temperature
   use vemcontact_deck_tie, only: read_tie
   use vemcontact_deck_loads, only: read_heading, read_boundary, read_cload, read_dload, start_step, &
                                    read_procedure, end_step
   use vemcontact_deck_surface_loads, only: read_dsload
   use vemcontact_deck_equations, only: read_equation
   use vemcontact_deck_assembly, only: read_part, end_part, read_assembly, end_assembly, read_instance, &
                                       end_instance, read_noop, instance_offsets, qualify_in_part
   use vemcontact_deck_amplitude, only: read_amplitude, load_amplitude
   use vemcontact_deck_outputs, only: read_output_request, read_output
   use vemcontact_deck_uplift, only: read_uplift
   use vemcontact_deck_pressure_penetration, only: read_pressure_penetration
   use vemcontact_deck_strength_reduction, only: read_strength_reduction
   use vemcontact_deck_contact, only: read_surface, read_interaction, read_behavior, drop_behavior, &
                                      read_contact_pair, read_controls, read_friction, read_change_friction
   implicit none
   private

   public :: parse_lines

contains

   !> Parse all lines of the source already opened in `p` into `model`.
   subroutine parse_lines(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t) :: kw
      integer :: id
      logical :: ok, first_data
      first_data = .true.
      call advance(p)
      do while (p%src%kind /= line_eof .and. .not. p%refused)
         if (p%src%kind == line_data) then
            ! only possible before the first keyword: handlers consume their data lines
            if (first_data) call err_here(p, 'data line before the first keyword', &
                                          'a deck starts with a keyword line such as *HEADING or *NODE')
            first_data = .false.
            call advance(p)
            cycle
         end if
         p%nkeyword = p%nkeyword + 1
         call parse_keyword_line(p%src%text(1:p%src%length), kw)
         id = find_keyword(kw%name)
         if (id == 0) then
            if (len(out_of_scope_feature(kw%name)) > 0) then
               call refuse_here(p, out_of_scope_feature(kw%name))
               exit
            end if
            if (len(kw%name) == 0) then
               call err_here(p, 'missing keyword name after *', 'known keywords are '//known_keyword_list())
            else if (is_calculix_keyword(kw%name)) then
               call err_here(p, 'keyword *'//kw%display//' is not supported by vemcontact', &
                             'supported keywords are '//known_keyword_list())
            else
               call err_here(p, 'unknown keyword *'//kw%display, keyword_suggestion(kw%name))
            end if
            call skip_data(p)
            cycle
         end if
         if (id /= kw_elastic .and. id /= kw_density .and. id /= kw_expansion) p%cur_mat = 0
         if (id /= kw_surface_behavior .and. id /= kw_friction) p%cur_inter = 0
         if (id /= kw_friction) call end_change_friction(p)
         call check_keyword(p, kw, id, ok)
         if (ok) call check_context(p, id, ok)
         if (.not. ok) then
            if (id == kw_solid_section) p%section_errors = .true.
            if (id == kw_element) p%element_errors = .true.
            if (id == kw_material) p%cur_mat = -1   ! its *ELASTIC and *DENSITY are dropped silently
            if (id == kw_surface_interaction) p%cur_inter = -1   ! and its *SURFACE BEHAVIOR
            if (id == kw_change_friction) p%change_inter = -1   ! and its *FRICTION
            if (id == kw_surface_behavior) call drop_behavior(p, model)
            if (id == kw_friction .and. p%cur_inter > 0) model%interactions(p%cur_inter)%has_friction = .true.
            call skip_data(p)
            cycle
         end if
         if (p%in_step) call note_load(p, id)
         if (p%cur_part > 0) call qualify_set_names(p, kw)
         if (id == kw_nset .or. id == kw_elset) then
            call instance_offsets(p, kw, ok)
            if (.not. ok) then
               call skip_data(p)
               cycle
            end if
         end if
         call dispatch(p, model, kw, id)
      end do
   end subroutine parse_lines

   !> Hands the keyword line to its handler, which reads the data lines that follow.
   subroutine dispatch(p, model, kw, id)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(inout) :: kw
      integer, intent(in) :: id
      logical :: handled
      call read_mesh_data(p, model, kw, id, handled)
      if (.not. handled) call read_step_data(p, model, kw, id, handled)
      if (.not. handled) call read_contact_data(p, model, kw, id, handled)
      if (.not. handled) call read_output_data(p, model, kw, id, handled)
      if (.not. handled) call read_assembly_data(p, model, kw, id, handled)
      ! *INCLUDE is handled by advance; nothing else is registered
      if (.not. handled) call skip_data(p)
   end subroutine dispatch

   !> Mesh, sets, materials, sections and constraints.
   subroutine read_mesh_data(p, model, kw, id, handled)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(inout) :: kw
      integer, intent(in) :: id
      logical, intent(out) :: handled
      handled = .true.
      select case (id)
      case (kw_heading)
         call read_heading(p, model)
      case (kw_node)
         call read_nodes(p, model, kw)
      case (kw_element)
         call read_elements(p, model, kw)
      case (kw_nset)
         call read_set(p, model, kw, .true.)
         call restore_offsets(p)
      case (kw_elset)
         call read_set(p, model, kw, .false.)
         call restore_offsets(p)
      case (kw_material)
         call read_material(p, model, kw)
         call no_data(p, '*MATERIAL')
      case (kw_elastic)
         call read_elastic(p, model)
      case (kw_density)
         call read_density(p, model)
      case (kw_solid_section)
         call read_section(p, model, kw)
      case (kw_expansion)
         call read_expansion(p, model)
      case (kw_equation)
         call read_equation(p, model)
      case (kw_tie)
         call read_tie(p, model, kw)
      case default
         handled = .false.
      end select
   end subroutine read_mesh_data

   !> Steps, their procedures and loads, initial conditions.
   subroutine read_step_data(p, model, kw, id, handled)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(inout) :: kw
      integer, intent(in) :: id
      logical, intent(out) :: handled
      handled = .true.
      select case (id)
      case (kw_boundary)
         call load_amplitude(p, model, kw, '*BOUNDARY')
         call read_boundary(p, model, kw)
         p%amp = 0
      case (kw_cload)
         call load_amplitude(p, model, kw, '*CLOAD')
         call read_cload(p, model, kw)
         p%amp = 0
      case (kw_dload)
         call load_amplitude(p, model, kw, '*DLOAD')
         call read_dload(p, model, kw)
         p%amp = 0
      case (kw_amplitude)
         call read_amplitude(p, model, kw)
      case (kw_step)
         call start_step(p, model, kw)
         call no_data(p, '*STEP')
      case (kw_static)
         call read_procedure(p, .false., model, kw)
      case (kw_geostatic)
         call read_procedure(p, .true., model, kw)
      case (kw_strength_reduction)
         call read_strength_reduction(p, model, kw)
      case (kw_dsload)
         call load_amplitude(p, model, kw, '*DSLOAD')
         call read_dsload(p, model, kw)
         p%amp = 0
      case (kw_uplift)
         call read_uplift(p, model, kw)
      case (kw_pressure_penetration)
         call read_pressure_penetration(p, model, kw)
      case (kw_initial_conditions)
         call read_initial_conditions(p, model, kw)
      case (kw_temperature)
         call read_temperature(p, model, kw)
      case (kw_end_step)
         call end_step(p, model)
         call no_data(p, '*END STEP')
      case default
         handled = .false.
      end select
   end subroutine read_step_data

   !> Surfaces, interactions and contact pairs.
   subroutine read_contact_data(p, model, kw, id, handled)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(inout) :: kw
      integer, intent(in) :: id
      logical, intent(out) :: handled
      handled = .true.
      select case (id)
      case (kw_surface)
         call read_surface(p, model, kw)
      case (kw_surface_interaction)
         call read_interaction(p, model, kw)
         call no_data(p, '*SURFACE INTERACTION')
      case (kw_surface_behavior)
         call read_behavior(p, model, kw)
      case (kw_friction)
         call read_friction(p, model, kw)
      case (kw_change_friction)
         call read_change_friction(p, model, kw)
         call no_data(p, '*CHANGE FRICTION')
      case (kw_contact_pair)
         call read_contact_pair(p, kw)
      case (kw_contact_controls)
         call read_controls(p, model, kw)
         call no_data(p, '*CONTACT CONTROLS')
      case default
         handled = .false.
      end select
   end subroutine read_contact_data

   !> Output requests.
   subroutine read_output_data(p, model, kw, id, handled)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(inout) :: kw
      integer, intent(in) :: id
      logical, intent(out) :: handled
      handled = .true.
      select case (id)
      case (kw_node_file, kw_node_output, kw_node_print)
         call read_output_request(p, model, kw, '*'//trim(keywords(id)%name), output_node, id == kw_node_print)
      case (kw_el_file, kw_element_output, kw_el_print)
         call read_output_request(p, model, kw, '*'//trim(keywords(id)%name), output_element, id == kw_el_print)
      case (kw_contact_file, kw_contact_output, kw_contact_print)
         call read_output_request(p, model, kw, '*'//trim(keywords(id)%name), output_contact, &
                                  id == kw_contact_print)
      case (kw_output)
         call read_output(p, model, kw)
      case default
         handled = .false.
      end select
   end subroutine read_output_data

   !> Parts, the assembly and its instances; keywords read and ignored.
   subroutine read_assembly_data(p, model, kw, id, handled)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(inout) :: kw
      integer, intent(in) :: id
      logical, intent(out) :: handled
      handled = .true.
      select case (id)
      case (kw_part)
         call read_part(p, model, kw)
         call no_data(p, '*PART')
      case (kw_end_part)
         call end_part(p, model)
         call no_data(p, '*END PART')
      case (kw_assembly)
         call read_assembly(p)
         call no_data(p, '*ASSEMBLY')
      case (kw_end_assembly)
         call end_assembly(p)
         call no_data(p, '*END ASSEMBLY')
      case (kw_instance)
         call read_instance(p, model, kw)
      case (kw_end_instance)
         call end_instance(p)
         call no_data(p, '*END INSTANCE')
      case (kw_preprint)
         call read_noop(p, kw, 'PREPRINT')
      case (kw_restart)
         call read_noop(p, kw, 'RESTART')
      case default
         handled = .false.
      end select
   end subroutine read_assembly_data

   !> A *CHANGE FRICTION ends with the *FRICTION after it; any other keyword there
   !> leaves it without one (an error at its line).
   subroutine end_change_friction(p)
      type(deck_parser_t), intent(inout) :: p
      if (p%change_inter > 0) call err_at(p, p%change_loc, '*CHANGE FRICTION must be followed by *FRICTION', &
                                          'the *FRICTION line after it gives the new law: mu [, stick slope]')
      p%change_inter = 0
   end subroutine end_change_friction

   !> Inside a *PART, the set names of NSET= and ELSET= are the part's own:
   !> "part.name" until its *INSTANCE renames them.
   subroutine qualify_set_names(p, kw)
      type(deck_parser_t), intent(in) :: p
      type(keyword_line_t), intent(inout) :: kw
      integer :: k
      do k = 1, kw%nparam
         if (kw%pname(k)%s == 'NSET' .or. kw%pname(k)%s == 'ELSET') &
            kw%pvalue(k)%s = qualify_in_part(p, kw%pvalue(k)%s)
      end do
   end subroutine qualify_set_names

   !> After a set keyword: the offsets of the part being read (those of an
   !> INSTANCE= parameter held for that keyword only).
   subroutine restore_offsets(p)
      type(deck_parser_t), intent(inout) :: p
      p%node_offset = 0
      p%elem_offset = 0
      if (p%cur_part > 0) then
         p%node_offset = p%parts(p%cur_part)%node_offset
         p%elem_offset = p%parts(p%cur_part)%elem_offset
      end if
   end subroutine restore_offsets

   !> The first load keyword of the current step (its location and name), which a
   !> strength reduction step refuses (end_step): it keeps the previous step's loads.
   subroutine note_load(p, id)
      type(deck_parser_t), intent(inout) :: p
      integer, intent(in) :: id
      if (p%cur%load_loc%line > 0) return
      select case (id)
      case (kw_boundary, kw_cload, kw_dload, kw_dsload, kw_uplift, kw_temperature, kw_pressure_penetration, &
            kw_change_friction)
         p%cur%load_loc = here(p)
         p%cur%load_kw = '*'//trim(keywords(id)%name)
      end select
   end subroutine note_load

   !> Model-data keywords may not appear inside a step, step keywords only there.
   subroutine check_context(p, id, ok)
      type(deck_parser_t), intent(inout) :: p
      integer, intent(in) :: id
      logical, intent(out) :: ok
      character(len=:), allocatable :: kname
      ok = .true.
      kname = '*'//trim(keywords(id)%name)
      if (keywords(id)%context == ctx_model .and. p%in_step) then
         if (id == kw_step) then
            ok = .true.  ! reported by start_step, which closes the open step
         else
            call err_here(p, kname//' is not allowed inside a *STEP', &
                          'model data goes before the first *STEP')
            ok = .false.
         end if
      else if (keywords(id)%context == ctx_step .and. .not. p%in_step) then
         if (id == kw_end_step) then
            call err_here(p, '*END STEP without a matching *STEP')
         else
            call err_here(p, kname//' is only allowed inside a *STEP', &
                          'loads and the procedure go between *STEP and *END STEP')
         end if
         ok = .false.
      end if
   end subroutine check_context
end module vemcontact_deck_parser
