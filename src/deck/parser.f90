!> The keyword loop: each keyword line is looked up in the registry, its
!> parameters and its place (model data or step) are checked, and its handler
!> reads the data lines that follow.  After an error the parser goes on with the
!> next line it can make sense of, so one run reports all problems of a deck.
module vemcontact_deck_parser
   use vemcontact_model, only: model_t, output_node, output_element, output_contact
   use vemcontact_deck_state, only: deck_parser_t, err_here
   use vemcontact_deck_source, only: line_keyword, line_data, line_eof
   use vemcontact_deck_fields, only: keyword_line_t, parse_keyword_line
   use vemcontact_deck_registry, only: keywords, find_keyword, keyword_suggestion, is_calculix_keyword, &
                                       known_keyword_list, ctx_model, ctx_step, &
                                       kw_heading, kw_node, kw_element, kw_nset, kw_elset, &
                                       kw_material, kw_elastic, kw_density, kw_solid_section, &
                                       kw_boundary, kw_cload, kw_dload, kw_step, kw_static, kw_end_step, &
                                       kw_surface, kw_surface_interaction, kw_surface_behavior, &
                                       kw_contact_pair, kw_contact_controls, kw_geostatic, kw_dsload, &
                                       kw_node_file, kw_el_file, kw_contact_file, kw_node_print, kw_el_print, &
                                       kw_contact_print, kw_node_output, kw_element_output, kw_contact_output, &
                                       kw_output, kw_uplift, kw_friction
   use vemcontact_deck_lines, only: advance, check_keyword, skip_data, no_data
   use vemcontact_deck_mesh, only: read_nodes, read_elements, read_set
   use vemcontact_deck_props, only: read_material, read_elastic, read_density, read_section
   use vemcontact_deck_loads, only: read_heading, read_boundary, read_cload, read_dload, start_step, &
                                    read_procedure, end_step
   use vemcontact_deck_surface_loads, only: read_dsload
   use vemcontact_deck_outputs, only: read_output_request, read_output
   use vemcontact_deck_uplift, only: read_uplift
   use vemcontact_deck_contact, only: read_surface, read_interaction, read_behavior, drop_behavior, &
                                      read_contact_pair, read_controls, read_friction
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
      do while (p%src%kind /= line_eof)
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
         if (id /= kw_elastic .and. id /= kw_density) p%cur_mat = 0
         if (id /= kw_surface_behavior .and. id /= kw_friction) p%cur_inter = 0
         call check_keyword(p, kw, id, ok)
         if (ok) call check_context(p, id, ok)
         if (.not. ok) then
            if (id == kw_solid_section) p%section_errors = .true.
            if (id == kw_element) p%element_errors = .true.
            if (id == kw_material) p%cur_mat = -1   ! its *ELASTIC and *DENSITY are dropped silently
            if (id == kw_surface_interaction) p%cur_inter = -1   ! and its *SURFACE BEHAVIOR
            if (id == kw_surface_behavior) call drop_behavior(p, model)
            if (id == kw_friction .and. p%cur_inter > 0) model%interactions(p%cur_inter)%has_friction = .true.
            call skip_data(p)
            cycle
         end if
         select case (id)
         case (kw_heading)
            call read_heading(p, model)
         case (kw_node)
            call read_nodes(p, model, kw)
         case (kw_element)
            call read_elements(p, model, kw)
         case (kw_nset)
            call read_set(p, model, kw, .true.)
         case (kw_elset)
            call read_set(p, model, kw, .false.)
         case (kw_material)
            call read_material(p, model, kw)
            call no_data(p, '*MATERIAL')
         case (kw_elastic)
            call read_elastic(p, model)
         case (kw_density)
            call read_density(p, model)
         case (kw_solid_section)
            call read_section(p, model, kw)
         case (kw_boundary)
            call read_boundary(p, model, kw)
         case (kw_cload)
            call read_cload(p, model, kw)
         case (kw_dload)
            call read_dload(p, model, kw)
         case (kw_step)
            call start_step(p, model, kw)
            call no_data(p, '*STEP')
         case (kw_static)
            call read_procedure(p, .false., model, kw)
         case (kw_geostatic)
            call read_procedure(p, .true., model, kw)
         case (kw_dsload)
            call read_dsload(p, model, kw)
         case (kw_surface)
            call read_surface(p, model, kw)
         case (kw_surface_interaction)
            call read_interaction(p, model, kw)
            call no_data(p, '*SURFACE INTERACTION')
         case (kw_surface_behavior)
            call read_behavior(p, model, kw)
         case (kw_friction)
            call read_friction(p, model, kw)
         case (kw_contact_pair)
            call read_contact_pair(p, kw)
         case (kw_contact_controls)
            call read_controls(p, model, kw)
            call no_data(p, '*CONTACT CONTROLS')
         case (kw_node_file, kw_node_output, kw_node_print)
            call read_output_request(p, model, kw, '*'//trim(keywords(id)%name), output_node, id == kw_node_print)
         case (kw_el_file, kw_element_output, kw_el_print)
            call read_output_request(p, model, kw, '*'//trim(keywords(id)%name), output_element, id == kw_el_print)
         case (kw_contact_file, kw_contact_output, kw_contact_print)
            call read_output_request(p, model, kw, '*'//trim(keywords(id)%name), output_contact, &
                                     id == kw_contact_print)
         case (kw_output)
            call read_output(p, model, kw)
         case (kw_uplift)
            call read_uplift(p, model, kw)
         case (kw_end_step)
            call end_step(p, model)
            call no_data(p, '*END STEP')
         case default
            ! *INCLUDE is handled by advance; nothing else is registered
            call skip_data(p)
         end select
      end do
   end subroutine parse_lines

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
