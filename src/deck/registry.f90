!> The one registry of deck keywords and their parameters.
!> Everything the parser accepts is listed here: keyword names, where they may
!> appear (model data, inside a step, anywhere), whether they take data lines,
!> and each parameter with its kind, whether it is required and its allowed
!> values.  `check_keyword` validates a keyword line against it, and
!> docs/deck-reference.md documents the same table.
module vemcontact_deck_registry
   use vemcontact_deck_fields, only: keyword_line_t, to_upper, squeeze, edit_distance
   implicit none
   private

   public :: keyword_spec_t, param_spec_t, keywords, params
   public :: find_keyword, find_param, keyword_suggestion, param_suggestion, known_keyword_list
   public :: is_calculix_keyword, allowed_value, param_list, out_of_scope_feature

   !> Keyword ids (index into `keywords`).
   integer, parameter, public :: kw_heading = 1, kw_include = 2, kw_node = 3, kw_element = 4, &
                                 kw_nset = 5, kw_elset = 6, kw_material = 7, kw_elastic = 8, &
                                 kw_density = 9, kw_solid_section = 10, kw_boundary = 11, &
                                 kw_cload = 12, kw_dload = 13, kw_step = 14, kw_static = 15, &
                                 kw_end_step = 16, kw_surface = 17, kw_surface_interaction = 18, &
                                 kw_surface_behavior = 19, kw_contact_pair = 20, kw_contact_controls = 21, &
                                 kw_geostatic = 22, kw_dsload = 23, kw_node_file = 24, kw_el_file = 25, &
                                 kw_contact_file = 26, kw_node_print = 27, kw_el_print = 28, &
                                 kw_contact_print = 29, kw_node_output = 30, kw_element_output = 31, &
                                 kw_contact_output = 32, kw_output = 33, kw_uplift = 34, kw_equation = 35, &
                                 kw_part = 36, kw_end_part = 37, kw_assembly = 38, kw_end_assembly = 39, &
                                 kw_instance = 40, kw_end_instance = 41, kw_preprint = 42, kw_restart = 43, &
                                 kw_initial_conditions = 44, kw_temperature = 45, kw_expansion = 46, kw_tie = 47, &
                                 kw_amplitude = 48, kw_friction = 49, kw_strength_reduction = 50, &
                                 kw_pressure_penetration = 51, kw_change_friction = 52
   !> Where a keyword may appear.
   integer, parameter, public :: ctx_model = 1  !< before the first *STEP / between steps
   integer, parameter, public :: ctx_step = 2   !< between *STEP and *END STEP
   integer, parameter, public :: ctx_any = 3
   !> Data lines.
   integer, parameter, public :: data_none = 0, data_optional = 1, data_required = 2
   !> Parameter kinds.
   integer, parameter, public :: par_flag = 1      !< bare word, no value
   integer, parameter, public :: par_value = 2     !< NAME=value
   integer, parameter, public :: par_optvalue = 3  !< bare word or NAME=value
   !> How a parameter value is stored.
   integer, parameter, public :: val_name = 1      !< upper case, blanks removed
   integer, parameter, public :: val_path = 2      !< kept as written
   integer, parameter, public :: val_int = 3       !< positive integer
   integer, parameter, public :: val_real = 4      !< a finite real number, kept as written

   type :: keyword_spec_t
      character(len=24) :: name      !< as written in decks, e.g. 'SOLID SECTION'
      integer :: context
      integer :: data
   end type keyword_spec_t

   type :: param_spec_t
      integer :: keyword
      character(len=24) :: name      !< blanks allowed ('SMALL SLIDING'); compared without them
      integer :: kind
      logical :: required
      integer :: vkind
      character(len=40) :: allowed   !< blank-separated allowed values, '' = any
   end type param_spec_t

   type(keyword_spec_t), parameter :: keywords(52) = [ &
                                      keyword_spec_t('HEADING', ctx_model, data_optional), &
                                      keyword_spec_t('INCLUDE', ctx_any, data_none), &
                                      keyword_spec_t('NODE', ctx_model, data_optional), &
                                      keyword_spec_t('ELEMENT', ctx_model, data_optional), &
                                      keyword_spec_t('NSET', ctx_model, data_optional), &
                                      keyword_spec_t('ELSET', ctx_model, data_optional), &
                                      keyword_spec_t('MATERIAL', ctx_model, data_none), &
                                      keyword_spec_t('ELASTIC', ctx_model, data_required), &
                                      keyword_spec_t('DENSITY', ctx_model, data_required), &
                                      keyword_spec_t('SOLID SECTION', ctx_model, data_optional), &
                                      keyword_spec_t('BOUNDARY', ctx_any, data_optional), &
                                      keyword_spec_t('CLOAD', ctx_step, data_optional), &
                                      keyword_spec_t('DLOAD', ctx_step, data_optional), &
                                      keyword_spec_t('STEP', ctx_model, data_none), &
                                      keyword_spec_t('STATIC', ctx_step, data_optional), &
                                      keyword_spec_t('END STEP', ctx_step, data_none), &
                                      keyword_spec_t('SURFACE', ctx_model, data_required), &
                                      keyword_spec_t('SURFACE INTERACTION', ctx_model, data_none), &
                                      keyword_spec_t('SURFACE BEHAVIOR', ctx_model, data_required), &
                                      keyword_spec_t('CONTACT PAIR', ctx_model, data_required), &
                                      keyword_spec_t('CONTACT CONTROLS', ctx_model, data_none), &
                                      keyword_spec_t('GEOSTATIC', ctx_step, data_optional), &
                                      keyword_spec_t('DSLOAD', ctx_step, data_optional), &
                                      keyword_spec_t('NODE FILE', ctx_step, data_optional), &
                                      keyword_spec_t('EL FILE', ctx_step, data_optional), &
                                      keyword_spec_t('CONTACT FILE', ctx_step, data_optional), &
                                      keyword_spec_t('NODE PRINT', ctx_step, data_optional), &
                                      keyword_spec_t('EL PRINT', ctx_step, data_optional), &
                                      keyword_spec_t('CONTACT PRINT', ctx_step, data_optional), &
                                      keyword_spec_t('NODE OUTPUT', ctx_step, data_optional), &
                                      keyword_spec_t('ELEMENT OUTPUT', ctx_step, data_optional), &
                                      keyword_spec_t('CONTACT OUTPUT', ctx_step, data_optional), &
                                      keyword_spec_t('OUTPUT', ctx_step, data_none), &
                                      keyword_spec_t('UPLIFT', ctx_step, data_required), &
                                      keyword_spec_t('EQUATION', ctx_model, data_required), &
                                      keyword_spec_t('PART', ctx_model, data_none), &
                                      keyword_spec_t('END PART', ctx_model, data_none), &
                                      keyword_spec_t('ASSEMBLY', ctx_model, data_none), &
                                      keyword_spec_t('END ASSEMBLY', ctx_model, data_none), &
                                      keyword_spec_t('INSTANCE', ctx_model, data_optional), &
                                      keyword_spec_t('END INSTANCE', ctx_model, data_none), &
                                      keyword_spec_t('PREPRINT', ctx_model, data_none), &
                                      keyword_spec_t('RESTART', ctx_any, data_none), &
                                      keyword_spec_t('INITIAL CONDITIONS', ctx_model, data_required), &
                                      keyword_spec_t('TEMPERATURE', ctx_step, data_required), &
                                      keyword_spec_t('EXPANSION', ctx_model, data_required), &
                                      keyword_spec_t('TIE', ctx_model, data_required), &
                                      keyword_spec_t('AMPLITUDE', ctx_any, data_required), &
                                      keyword_spec_t('FRICTION', ctx_any, data_optional), &
                                      keyword_spec_t('STRENGTH REDUCTION', ctx_step, data_optional), &
                                      keyword_spec_t('PRESSURE PENETRATION', ctx_step, data_required), &
                                      keyword_spec_t('CHANGE FRICTION', ctx_step, data_none)]

   type(param_spec_t), parameter :: params(164) = [ &
                                    param_spec_t(kw_include, 'INPUT', par_value, .true., val_path, ''), &
                                    param_spec_t(kw_node, 'NSET', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_element, 'TYPE', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_element, 'ELSET', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_nset, 'NSET', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_nset, 'GENERATE', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_elset, 'ELSET', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_elset, 'GENERATE', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_material, 'NAME', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_elastic, 'TYPE', par_value, .false., val_name, 'ISO'), &
                                    param_spec_t(kw_solid_section, 'ELSET', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_solid_section, 'MATERIAL', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_solid_section, 'FORMULATION', par_value, .false., val_name, 'VEM FEM'), &
                                    ! vemcontact: VEM stabilisation factor tau; positivity checked by the handler
                                    param_spec_t(kw_solid_section, 'STABILIZATION', par_value, .false., val_real, ''), &
                                    param_spec_t(kw_solid_section, 'OFFSET', par_value, .false., val_real, ''), &
                                    param_spec_t(kw_boundary, 'OP', par_value, .false., val_name, 'MOD NEW'), &
                                    param_spec_t(kw_cload, 'OP', par_value, .false., val_name, 'MOD NEW'), &
                                    param_spec_t(kw_dload, 'OP', par_value, .false., val_name, 'MOD NEW'), &
                                    param_spec_t(kw_dsload, 'OP', par_value, .false., val_name, 'MOD NEW'), &
                                    param_spec_t(kw_static, 'SOLVER', par_value, .false., val_name, ''), &
                                    ! vemcontact: TOLERANCE's range is checked by the handler
                                    param_spec_t(kw_strength_reduction, 'INTERACTION', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_strength_reduction, 'TOLERANCE', par_value, .false., val_real, ''), &
                                    param_spec_t(kw_strength_reduction, 'NSET', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_step, 'NLGEOM', par_optvalue, .false., val_name, 'NO YES'), &
                                    param_spec_t(kw_step, 'INC', par_value, .false., val_int, ''), &
                                    param_spec_t(kw_step, 'NAME', par_value, .false., val_path, ''), &
                                    param_spec_t(kw_surface, 'NAME', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_surface, 'TYPE', par_value, .false., val_name, 'ELEMENT NODE'), &
                                    param_spec_t(kw_surface_interaction, 'NAME', par_value, .true., val_name, ''), &
                                    ! checked by the handler, which tells supported from unknown values
                                    param_spec_t(kw_surface_behavior, 'PRESSURE-OVERCLOSURE', par_value, .true., &
                                                 val_name, ''), &
                                    param_spec_t(kw_contact_pair, 'INTERACTION', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_contact_pair, 'TYPE', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_contact_pair, 'ADJUST', par_value, .false., val_path, ''), &
                                    param_spec_t(kw_contact_pair, 'SMALL SLIDING', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_contact_pair, 'ROLES', par_value, .false., val_name, 'AUTO KEEP'), &
                                    param_spec_t(kw_contact_controls, 'MAXIT', par_value, .false., val_int, ''), &
                                    param_spec_t(kw_contact_controls, 'TOLERANCE', par_value, .false., val_real, ''), &
                                   param_spec_t(kw_contact_controls, 'STIFFNESS SCALE FACTOR', par_value, .false., &
                                                val_real, ''), &
                                    ! accepted without effect (docs/deck-reference.md)
                                    param_spec_t(kw_nset, 'INTERNAL', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_nset, 'UNSORTED', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_elset, 'INTERNAL', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_elset, 'UNSORTED', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_static, 'DIRECT', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_static, 'TIME RESET', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_static, 'TOTAL TIME AT START', par_value, .false., val_real, ''), &
                                    param_spec_t(kw_step, 'AMPLITUDE', par_value, .false., val_name, 'RAMP STEP'), &
                                    param_spec_t(kw_step, 'INCF', par_value, .false., val_int, ''), &
                                    ! output requests (src/deck/outputs.f90); FREQUENCY is checked by the handler
                                    param_spec_t(kw_node_file, 'NSET', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_file, 'GLOBAL', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_node_file, 'OUTPUT', par_value, .false., val_name, '2D 3D'), &
                                    param_spec_t(kw_node_file, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_file, 'FREQUENCYF', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_file, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_file, 'LAST ITERATIONS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_node_file, 'CONTACT ELEMENTS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_node_output, 'NSET', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_output, 'GLOBAL', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_node_output, 'OUTPUT', par_value, .false., val_name, '2D 3D'), &
                                    param_spec_t(kw_node_output, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_output, 'FREQUENCYF', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_output, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_output, 'LAST ITERATIONS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_node_output, 'CONTACT ELEMENTS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_el_file, 'NSET', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_el_file, 'GLOBAL', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_el_file, 'OUTPUT', par_value, .false., val_name, '2D 3D'), &
                                    param_spec_t(kw_el_file, 'SECTION FORCES', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_el_file, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_el_file, 'FREQUENCYF', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_el_file, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_el_file, 'LAST ITERATIONS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_el_file, 'CONTACT ELEMENTS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_element_output, 'ELSET', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_element_output, 'GLOBAL', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_element_output, 'OUTPUT', par_value, .false., val_name, '2D 3D'), &
                                    param_spec_t(kw_element_output, 'SECTION FORCES', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_element_output, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_element_output, 'FREQUENCYF', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_element_output, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_element_output, 'LAST ITERATIONS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_element_output, 'CONTACT ELEMENTS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_element_output, 'POSITION', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_output, 'VARIABLE', par_value, .false., val_name, 'PRESELECT ALL'), &
                                    param_spec_t(kw_element_output, 'VARIABLE', par_value, .false., val_name, 'PRESELECT ALL'), &
                                    param_spec_t(kw_contact_output, 'VARIABLE', par_value, .false., val_name, 'PRESELECT ALL'), &
                                    param_spec_t(kw_contact_file, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_contact_file, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_contact_file, 'LAST ITERATIONS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_contact_file, 'CONTACT ELEMENTS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_contact_output, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_contact_output, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_contact_output, 'LAST ITERATIONS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_contact_output, 'CONTACT ELEMENTS', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_node_print, 'NSET', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_el_print, 'ELSET', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_node_print, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_print, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_print, 'TOTALS', par_value, .false., val_name, 'YES ONLY NO'), &
                                    param_spec_t(kw_el_print, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_el_print, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_el_print, 'TOTALS', par_value, .false., val_name, 'YES ONLY NO'), &
                                    param_spec_t(kw_contact_print, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_contact_print, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_contact_print, 'TOTALS', par_value, .false., val_name, 'YES ONLY NO'), &
                                    param_spec_t(kw_node_print, 'FREQUENCYF', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_node_print, 'GLOBAL', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_el_print, 'FREQUENCYF', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_el_print, 'GLOBAL', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_output, 'FIELD', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_output, 'HISTORY', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_output, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_output, 'FREQUENCYF', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_output, 'TIME POINTS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_output, 'NUMBER INTERVAL', par_value, .false., val_int, ''), &
                                    param_spec_t(kw_output, 'VARIABLE', par_value, .false., val_name, 'PRESELECT ALL'), &
                                    ! *UPLIFT (vemcontact, src/deck/uplift.f90)
                                    param_spec_t(kw_uplift, 'INTERACTION', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_uplift, 'UNIT WEIGHT', par_value, .true., val_real, ''), &
                                    param_spec_t(kw_uplift, 'PENETRATION', par_flag, .false., val_name, ''), &
                                    ! *PRESSURE PENETRATION (Abaqus, src/deck/pressure_penetration.f90)
                                    param_spec_t(kw_pressure_penetration, 'MASTER', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_pressure_penetration, 'SLAVE', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_pressure_penetration, 'CRITICAL PRESSURE', par_value, .false., &
                                                 val_real, ''), &
                                    param_spec_t(kw_pressure_penetration, 'PENETRATION TIME', par_value, .false., &
                                                 val_real, ''), &
                                    param_spec_t(kw_pressure_penetration, 'AMPLITUDE', par_value, .false., val_name, ''), &
                                    ! Abaqus/CAE structure (src/deck/assembly.f90)
                                    param_spec_t(kw_part, 'NAME', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_assembly, 'NAME', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_instance, 'NAME', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_instance, 'PART', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_nset, 'INSTANCE', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_elset, 'INSTANCE', par_value, .false., val_name, ''), &
                                    ! accepted and ignored, with a note in the log
                                    param_spec_t(kw_preprint, 'ECHO', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_preprint, 'MODEL', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_preprint, 'HISTORY', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_preprint, 'CONTACT', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_preprint, 'MASSPROP', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_preprint, 'PARSUBSTITUTION', par_value, .false., val_name, &
                                                 'YES NO'), &
                                    param_spec_t(kw_restart, 'WRITE', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_restart, 'READ', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_restart, 'FREQUENCY', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_restart, 'NUMBER INTERVAL', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_restart, 'OVERLAY', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_restart, 'TIME MARKS', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_restart, 'STEP', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_restart, 'INC', par_value, .false., val_name, ''), &
                                    ! Abaqus/CAE writes it on every *ELEMENT OUTPUT: local directions (none in 2D)
                                    param_spec_t(kw_element_output, 'DIRECTIONS', par_value, .false., val_name, 'YES NO'), &
                                    ! thermal strains (src/deck/thermal.f90, *EXPANSION in src/deck/props.f90)
                                    param_spec_t(kw_initial_conditions, 'TYPE', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_temperature, 'OP', par_value, .false., val_name, 'MOD NEW'), &
                                    param_spec_t(kw_expansion, 'TYPE', par_value, .false., val_name, 'ISO'), &
                                    param_spec_t(kw_expansion, 'ZERO', par_value, .false., val_real, ''), &
                                    ! bonded surfaces (src/deck/tie.f90)
                                    param_spec_t(kw_tie, 'NAME', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_tie, 'POSITION TOLERANCE', par_value, .false., val_real, ''), &
                                    param_spec_t(kw_tie, 'ADJUST', par_value, .false., val_name, 'YES NO'), &
                                    param_spec_t(kw_tie, 'TYPE', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_tie, 'CYCLIC SYMMETRY', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_tie, 'MULTISTAGE', par_flag, .false., val_name, ''), &
                                    param_spec_t(kw_tie, 'FLUID PRESSURE', par_flag, .false., val_name, ''), &
                                    ! load increments: *AMPLITUDE and the loads that name one
                                    param_spec_t(kw_amplitude, 'NAME', par_value, .true., val_name, ''), &
                                    param_spec_t(kw_amplitude, 'TIME', par_value, .false., val_name, &
                                                 'TOTALTIME STEPTIME'), &
                                    param_spec_t(kw_boundary, 'AMPLITUDE', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_cload, 'AMPLITUDE', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_dload, 'AMPLITUDE', par_value, .false., val_name, ''), &
                                    param_spec_t(kw_dsload, 'AMPLITUDE', par_value, .false., val_name, ''), &
                                    ! *FRICTION under *SURFACE INTERACTION (src/deck/contact.f90)
                                    param_spec_t(kw_friction, 'ROUGH', par_flag, .false., val_name, ''), &
                                    ! vemcontact: Mohr-Coulomb cohesion; sign checked by the handler
                                    param_spec_t(kw_friction, 'COHESION', par_value, .false., val_real, ''), &
                                    ! *CHANGE FRICTION in a step, followed by its *FRICTION (CalculiX, Abaqus)
                                    param_spec_t(kw_change_friction, 'INTERACTION', par_value, .true., val_name, '')]

   !> CalculiX keywords vemcontact does not support (for a clearer message than "unknown").
   character(len=24), parameter :: calculix_only(21) = [character(len=24) :: &
                                   'BEAMSECTION', 'BUCKLE', 'CONTROLS', &
                                   'COUPLING', 'CREEP', 'DEFORMATIONPLASTICITY', 'DYNAMIC', &
                                   'VISCO', 'FILM', 'FREQUENCY', &
                                   'HEATTRANSFER', 'KINEMATIC', &
                                   'MPC', 'ORIENTATION', 'PLASTIC', 'SHELLSECTION', &
                                   'SPECIFICHEAT', &
                                   'TIEPOINTS', 'TRANSFORM', 'CONDUCTIVITY', 'SPRING']

   !> CalculiX/Abaqus keywords of what vemcontact does not model at all (another
   !> analysis, another kind of element or material law): the deck is refused at
   !> the first of them with one message (out_of_scope_feature).  Squeezed names,
   !> then what the message calls the feature.
   character(len=28), parameter :: scope_names(30) = [character(len=28) :: &
                                   'FREQUENCY', 'DYNAMIC', 'MODALDYNAMIC', 'STEADYSTATEDYNAMICS', &
                                   'HEATTRANSFER', 'COUPLEDTEMPERATURE-DISPLACEMENT', 'BUCKLE', 'VISCO', &
                                   'UNCOUPLEDTEMPERATURE-DISPLACEMENT', 'COMPLEXFREQUENCY', 'ELECTROMAGNETICS', &
                                   'SENSITIVITY', 'GREEN', 'RIGIDBODY', 'PLASTIC', 'CREEP', 'HYPERELASTIC', &
                                   'DEFORMATIONPLASTICITY', 'HYPERFOAM', 'USERMATERIAL', 'BEAMSECTION', &
                                   'SHELLSECTION', 'MEMBRANESECTION', 'SPRING', 'DASHPOT', 'GAP', 'MASS', &
                                   'CONDUCTIVITY', 'SPECIFICHEAT', 'FLUIDSECTION']
   character(len=44), parameter :: scope_what(30) = [character(len=44) :: &
                                   'a frequency step (*FREQUENCY)', 'a dynamic step (*DYNAMIC)', &
                                   'a modal dynamic step (*MODAL DYNAMIC)', &
                                   'a steady-state dynamics step', 'heat transfer (*HEAT TRANSFER)', &
                                   'coupled temperature-displacement analysis', 'buckling (*BUCKLE)', &
                                   'viscous creep steps (*VISCO)', 'temperature-displacement analysis', &
                                   'complex frequency analysis', 'electromagnetics', 'sensitivity analysis', &
                                   'Green function analysis', 'a rigid body (*RIGID BODY)', &
                                   'plasticity (*PLASTIC)', 'creep (*CREEP)', 'hyperelasticity', &
                                   'deformation plasticity', 'hyperfoam materials', 'a user material', &
                                   'beam sections (*BEAM SECTION)', 'shell sections (*SHELL SECTION)', &
                                   'membrane sections', 'spring elements (*SPRING)', 'dashpot elements', &
                                   'gap elements (*GAP)', 'point masses (*MASS)', 'heat conduction (*CONDUCTIVITY)', &
                                   'heat capacity (*SPECIFIC HEAT)', 'fluid sections']

contains

   !> What out-of-scope feature the keyword `name` (squeezed, upper case) stands
   !> for, '' when it is not one of them.
   pure function out_of_scope_feature(name) result(what)
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: what
      integer :: k
      what = ''
      do k = 1, size(scope_names)
         if (trim(scope_names(k)) == name) what = trim(scope_what(k))
      end do
   end function out_of_scope_feature

   !> Id of the keyword with squeezed upper-case name `name` (e.g. 'SOLIDSECTION'), 0 if unknown.
   pure function find_keyword(name) result(id)
      character(len=*), intent(in) :: name
      integer :: id
      do id = 1, size(keywords)
         if (squeeze(keywords(id)%name) == name) return
      end do
      id = 0
   end function find_keyword

   !> The spec of parameter `name` of keyword `kw`; `found` false if not allowed.
   pure subroutine find_param(kw, name, spec, found)
      integer, intent(in) :: kw
      character(len=*), intent(in) :: name
      type(param_spec_t), intent(out) :: spec
      logical, intent(out) :: found
      integer :: k
      found = .false.
      spec = params(1)
      do k = 1, size(params)
         if (params(k)%keyword == kw .and. squeeze(params(k)%name) == name) then
            spec = params(k)
            found = .true.
            return
         end if
      end do
   end subroutine find_param

   !> All parameters of keyword `kw`, "A, B, C" ('none' if it takes none).
   pure function param_list(kw) result(s)
      integer, intent(in) :: kw
      character(len=:), allocatable :: s
      integer :: k
      s = ''
      do k = 1, size(params)
         if (params(k)%keyword == kw) call add(trim(params(k)%name))
      end do
      if (len(s) == 0) s = 'none'
   contains
      pure subroutine add(n)
         character(len=*), intent(in) :: n
         if (len(s) > 0) s = s//', '
         s = s//n
      end subroutine add
   end function param_list

   !> Whether `value` (upper case) is allowed for `spec`.
   pure function allowed_value(spec, value) result(ok)
      type(param_spec_t), intent(in) :: spec
      character(len=*), intent(in) :: value
      logical :: ok
      ok = len_trim(spec%allowed) == 0 .or. len(value) == 0
      if (ok) return
      ok = index(' '//trim(spec%allowed)//' ', ' '//value//' ') > 0
   end function allowed_value

   !> "did you mean *X?" for an unknown keyword, else the list of known keywords.
   pure function keyword_suggestion(name) result(help)
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: help
      integer :: k, d, best, kbest
      best = huge(1)
      kbest = 0
      do k = 1, size(keywords)
         d = edit_distance(name, squeeze(keywords(k)%name))
         if (d < best) then
            best = d
            kbest = k
         end if
      end do
      if (kbest > 0 .and. best <= max(1, len(name)/3)) then
         help = 'did you mean *'//trim(keywords(kbest)%name)//'?'
      else
         help = 'known keywords are '//known_keyword_list()
      end if
   end function keyword_suggestion

   !> "*HEADING, *INCLUDE, ..."
   pure function known_keyword_list() result(s)
      character(len=:), allocatable :: s
      integer :: k
      s = ''
      do k = 1, size(keywords)
         if (k > 1) s = s//', '
         s = s//'*'//trim(keywords(k)%name)
      end do
   end function known_keyword_list

   !> "did you mean X?" for an unknown parameter of keyword `kw`, else the allowed list.
   pure function param_suggestion(kw, name) result(help)
      integer, intent(in) :: kw
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: help
      integer :: k, d, best
      character(len=24) :: pbest
      best = huge(1)
      pbest = ''
      do k = 1, size(params)
         if (params(k)%keyword /= kw) cycle
         d = edit_distance(name, squeeze(params(k)%name))
         if (d < best) then
            best = d
            pbest = params(k)%name
         end if
      end do
      if (len_trim(pbest) > 0 .and. best <= max(1, len(name)/3)) then
         help = 'did you mean '//trim(pbest)//'?'
      else
         help = 'parameters of *'//trim(keywords(kw)%name)//': '//param_list(kw)
      end if
   end function param_suggestion

   !> Whether `name` (squeezed, upper case) is a CalculiX keyword vemcontact lacks.
   pure function is_calculix_keyword(name) result(yes)
      character(len=*), intent(in) :: name
      logical :: yes
      integer :: k
      yes = .false.
      do k = 1, size(calculix_only)
         if (squeeze(calculix_only(k)) == name) yes = .true.
      end do
   end function is_calculix_keyword
end module vemcontact_deck_registry
