!> Linear static analysis over the deck's steps, with output after every step.
!> Every completed step is in the VTU and PVD files before the next starts and
!> in the HDF5 file, which gets its final name when the run ends: a run that
!> fails part way keeps the steps it completed (the HDF5 file without the step
!> that failed and marked `complete = 0`); a killed run leaves no HDF5 file.
module vemcontact_driver_static
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, append_message
   use vemcontact_model, only: model_t, string_t, form_vem, form_fem, etype_polygon, procedure_geostatic, &
                               element_order, etype_polygon2, &
                               pair_surface_to_surface
   use vemcontact_sparse_mmio, only: write_matrix_market
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_driver_linear, only: linear_system_t
   use vemcontact_driver_validate, only: element_warnings
   use vemcontact_driver_load_state, only: load_state_t, init_load_state, advance_load_state
   use vemcontact_driver_assembly, only: element_stresses, element_strains, assemble_loads
   use vemcontact_post_stress, only: nodal_average
   use vemcontact_post_estimate, only: error_estimate_t, estimate_error
   use vemcontact_post_estimate2, only: estimate_error2
   use vemcontact_post_reactions, only: reaction_forces, constrained_sets
   use vemcontact_post_labels, only: element_section_sets, element_parts
   use vemcontact_output_vtu, only: write_vtu, vtu_extras_t
   use vemcontact_output_pvd, only: write_pvd
   use vemcontact_output_hdf5, only: h5_writer_t
   use vemcontact_output_contact, only: write_contact_csv, write_contact_vtu
   use vemcontact_output_selection, only: field_selection_t, step_selection
   use vemcontact_output_print, only: has_print_requests, write_print_csv
   use vemcontact_contact_table, only: contact_table_t
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_friction, only: tangent_stick, tangent_slip
   use vemcontact_log, only: logger_t
   implicit none
   private

   public :: run_options_t, run_static

   type :: run_options_t
      character(len=:), allocatable :: out_dir
      character(len=:), allocatable :: job
      integer :: ordering = 0                 !< vemcontact_driver_linear's ordering_*
      integer :: solver = 0                   !< vemcontact_solver_factory's solver_* (0: auto)
      !> `solver` was chosen by `auto`: an iterative solver that fails falls back to
      !> CHOLMOD (one process; vemcontact_driver_linear's solve_state)
      logical :: solver_fallback = .false.
      logical :: write_matrix = .false.
      logical :: compress_vtu = .true.        !< zlib-compressed .vtu arrays
      !> .false.: a process of a distributed run other than rank 0, which solves with
      !> the others but writes nothing and skips the post-processing
      logical :: write_files = .true.
   end type run_options_t

contains

   !> Run every step.  The model gains the interface nodes of SURFACE TO SURFACE
   !> contact pairs (contact_state_t%init) before anything is assembled.  When a
   !> step fails, the HDF5 file keeps the steps before it and is closed with
   !> `complete = 0`.
   subroutine run_static(model, opts, log, error)
      type(model_t), intent(inout) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(error_t), allocatable, intent(out) :: error
      type(h5_writer_t) :: h5
      type(error_t), allocatable :: err2
      integer :: current, done
      current = 0
      done = 0
      call run_steps(model, opts, log, h5, current, done, error)
      if (.not. allocated(error) .or. .not. h5%is_open()) return
      if (current > done) call h5%discard_step(current, err2)
      if (allocated(err2)) then
         call h5%discard()
      else
         call h5%close(err2)
      end if
      if (allocated(err2)) call append_message(error, '(no HDF5 results file: '//err2%message//')')
   end subroutine run_static

   !> The analysis and its output; `current` is the step being run, `done` the
   !> last step whose results are in every file.
   subroutine run_steps(model, opts, log, h5, current, done, error)
      type(model_t), intent(inout) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(h5_writer_t), intent(inout) :: h5
      integer, intent(inout) :: current, done
      type(error_t), allocatable, intent(out) :: error
      type(linear_system_t) :: sys
      type(sym_csc_t) :: kwhole
      integer(ip), allocatable :: per_process(:)
      type(load_state_t) :: st
      type(contact_state_t) :: contact
      type(contact_table_t) :: tab
      type(error_estimate_t) :: est
      integer, allocatable :: parts(:)
      integer :: ip_
      real(wp), allocatable :: u(:), u_ref(:), u_out(:), s_elem(:, :), s_node(:, :), times(:), s_at(:, :)
      real(wp), allocatable :: e_at(:, :), ku(:), f(:), set_rf(:, :)
      integer, allocatable :: rf_sets(:)
      type(string_t), allocatable :: set_names(:)
      type(vtu_extras_t) :: extra
      type(field_selection_t) :: sel
      integer :: ie
      type(string_t), allocatable :: vtu_files(:), warnings(:)
      integer :: istep, iw
      character(len=256) :: buf
      character(len=:), allocatable :: base, vtu_name, name

      call contact%init(model, error)
      if (allocated(error)) return
      do ip_ = 1, size(contact%inserted)
         if (model%pairs(ip_)%formulation /= pair_surface_to_surface) cycle
         write (buf, '(2x,a,i0,a,i0,a,i0,a)') 'contact pair ', ip_, ' (SURFACE TO SURFACE): ', contact%inserted(ip_), &
            ' interface nodes inserted, ', size(model%pairs(ip_)%partner, 2), ' node pairs'
         call log%say(trim(buf))
         if (contact%pairs(ip_)%nslave > size(model%pairs(ip_)%partner, 2)) then
            write (buf, '(2x,a,i0,a)') 'note: ', contact%pairs(ip_)%nslave - size(model%pairs(ip_)%partner, 2), &
               ' slave nodes face no master side (beyond its ends or farther than two sides): they '// &
               'carry no contact'
            call log%say(trim(buf))
         end if
      end do
      write (buf, '(2x,a,i0,a,i0,a,i0,a,i0)') 'nodes ', model%nnode, ', elements ', model%nelem, &
         ', unknowns ', 2*model%nnode, ', steps ', size(model%steps)
      call log%say(trim(buf))
      write (buf, '(2x,a,i0,a,i0,a,i0,a,i0)') 'VEM elements ', count(model%elem_form == form_vem), &
         ', FEM elements ', count(model%elem_form == form_fem), ', of them polygons (VPE/VPS) ', &
         count(model%elem_type == etype_polygon), ', second-order polygons (VPE2/VPS2) ', &
         count(model%elem_type == etype_polygon2)
      call log%say(trim(buf))

      if (contact%n > 0) then
         write (buf, '(2x,a,i0,a,i0,a)') 'contact: ', size(contact%pairs), ' pairs, ', contact%n, ' slave nodes'
         call log%say(trim(buf))
         do ip_ = 1, size(model%pairs)
            write (buf, '(4x,a,i0,a,i0,a,i0,a,es10.3,a)') 'pair ', ip_, ': ', contact%pairs(ip_)%nslave, &
               ' slave nodes on ', size(contact%pairs(ip_)%seg, 2), ' master segments, K = ', &
               contact%pairs(ip_)%slope, ' (pressure per unit overclosure)'
            call log%say(trim(buf)//', '//model%surfaces(model%pairs(ip_)%slave)%name//' on '// &
                         model%surfaces(model%pairs(ip_)%master)%name)
         end do
         if (contact%nexcluded > 0) then
            write (buf, '(2x,a,i0,a)') 'note: ', contact%nexcluded, &
               ' slave nodes are also master nodes (joint tips, bonded nodes) and are left out of contact'
            call log%say(trim(buf))
         end if
      end if
      call sys%setup(model, opts%ordering, error, contact, opts%solver)
      if (allocated(error)) return
      sys%fallback = opts%solver_fallback
      ! valid but known to be poor: locking FEM sections, non-convex FEM quads
      warnings = element_warnings(model)
      do iw = 1, size(warnings)
         call log%say(warnings(iw)%s)
      end do
      if (any(sys%unused)) then
         write (buf, '(2x,a,i0,a)') 'note: ', count(sys%unused), ' nodes belong to no element and are left out'
         call log%say(trim(buf))
      end if
      ! the factor's size for a direct solver that reports it (none for CG + AMG)
      buf = ''
      if (sys%solver%nnz_factor > 0) write (buf, '(a,i0,a,es9.2)') ', factor nnz ', sys%solver%nnz_factor, &
         ', flops ', sys%solver%flops
      call log%say('  solver '//sys%solver%describe()//trim(buf))
      ! the phases are laps (vemcontact_log): each lap is the time since the
      ! previous one that the phases logged in between do not account for
      call log%phase('validate', sys%t_validate)
      call log%phase('pattern', sys%t_pattern)
      ! of which the contact search for the candidate pairs of the pattern
      if (contact%n > 0) call log%phase('candidates', sys%t_candidates, within='pattern')
      ! of which the partition of the mesh over the processes (distributed)
      if (sys%dist) call log%phase('partition', sys%t_partition, within='pattern')
      call log%phase('assemble', sys%t_assemble)
      call log%phase('analyze', sys%t_analyze)
      ! contact surfaces and pairs, parts, unused nodes, element warnings
      call log%lap('set-up')

      base = opts%out_dir//'/'//opts%job
      if (opts%write_files) then
         ! the elements of each process (one process: all of them)
         per_process = [model%nelem]
         if (sys%dist) per_process = sys%partition%elements
         call h5%open(base//'.h5', error, solver=sys%solver%describe(), partition=per_process)
         if (allocated(error)) return
         call h5%write_mesh(model, error)
         if (allocated(error)) then
            call h5%discard()
            return
         end if
         extra%elem_set = element_section_sets(model)
         extra%elem_part = element_parts(model, sys%part)
         call h5%write_labels(model, extra%elem_set, extra%elem_part, error)
         if (allocated(error)) then
            call h5%discard()
            return
         end if
      end if
      if (sys%dist) then
         write (buf, '(2x,a,i0,a)') 'distributed over ', sys%partition%nparts, ' processes (METIS partition '// &
            'of the nodes): elements per process'
         name = trim(buf)
         do iw = 1, sys%partition%nparts
            write (buf, '(i0)') sys%partition%elements(iw)
            name = name//' '//trim(buf)
         end do
         call log%say(name)
      end if

      call init_load_state(model, st)
      allocate (u(2*model%nnode), s_elem(4, model%nelem), s_node(4, model%nnode))
      allocate (extra%e_elem(4, model%nelem), extra%e_node(4, model%nnode), extra%rf(2, model%nnode))
      allocate (ku(2*model%nnode), f(2*model%nnode))
      if (any([(element_order(model%elem_type(ie)) == 2, ie=1, int(model%nelem))])) &
         allocate (s_at(4, model%elem_ptr(model%nelem + 1) - 1), e_at(4, model%elem_ptr(model%nelem + 1) - 1))
      ! displacements are reported relative to the end of a geostatic step
      allocate (u_ref(2*model%nnode), source=0.0_wp)
      allocate (vtu_files(0), times(0), parts(0))
      u = 0.0_wp
      call log%lap('write mesh')
      do istep = 1, size(model%steps)
         current = istep
         log%step = istep
         name = step_name(istep)
         call log%say('step '//name)
         call advance_load_state(model%steps(istep), st)
         call sys%solve_state(model, st, u, error, contact, log)
         if (allocated(error)) return
         if (sys%fell_back .and. opts%write_files) then
            ! the solver that ran, once it is CHOLMOD after a failed CG
            call h5%set_solver(sys%solver%describe(), error)
            if (allocated(error)) return
            sys%fell_back = .false.
         end if
         if (sys%iterations > 0) then
            write (buf, '(2x,a,i0,a,i0,a)') 'contact converged in ', sys%iterations, ' iterations (', &
               sys%factorizations, ' numeric factorizations)'
            call log%say(trim(buf))
         end if
         if (sys%refactorized) call log%phase('factorize', sys%t_factorize)
         call log%phase('solve', sys%t_solve)
         ! pairing and active set of every iteration of the step (also in the iteration lines)
         if (contact%n > 0) call log%phase('search', sys%t_search)
         ! the rest of solve_state: load vector, constraints, the contact iteration's own work
         call log%lap('system')
         if (opts%write_matrix .and. istep == 1) then
            if (sys%dist) then
               ! the whole matrix: the sum of the processes' shares, on every process
               kwhole = sys%kb
               call sys%solver%sum_over_ranks(kwhole%val, error)
               if (allocated(error)) return
               if (opts%write_files) call write_matrix_market(base//'.mtx', kwhole, error)
               deallocate (kwhole%val)
            else if (opts%write_files) then
               call write_matrix_market(base//'.mtx', sys%kb, error)
            end if
            if (allocated(error)) return
            call log%lap('write matrix')
         end if

         if (model%steps(istep)%procedure == procedure_geostatic) then
            u_ref = u
            call log%say('  geostatic step: its displacements are the reference (reported as zero), '// &
                         'its stresses are kept')
         end if
         u_out = u - u_ref
         ! K u for the reactions: every process together (distributed, the shares are added)
         call sys%elastic_times(u, ku)
         if (.not. opts%write_files) then
            ! the post-processing and the output are rank 0's
            done = istep
            cycle
         end if

         ! second-order elements give their own stress and strain at each node
         ! (linear for the k = 2 VEM), averaged at the nodes instead of the
         ! element values; strains E = D^-1 S from the same recovery
         ! (element_strains)
         if (allocated(s_at)) then
            call element_stresses(model, u, s_elem, st%dload, s_at)
            call nodal_average(model, s_elem, s_node, s_at)
            call element_strains(model, s_elem, extra%e_elem, s_at, e_at)
            call nodal_average(model, extra%e_elem, extra%e_node, e_at)
         else
            call element_stresses(model, u, s_elem, st%dload)
            call nodal_average(model, s_elem, s_node)
            call element_strains(model, s_elem, extra%e_elem)
            call nodal_average(model, extra%e_elem, extra%e_node)
         end if
         call log%lap('stresses')
         ! the recovery-based error estimate: second-order models recover a quadratic
         ! stress from the cells' own linear stresses (s_at)
         if (.not. allocated(s_at)) then
            call estimate_error(model, s_elem, est)
         else
            call estimate_error2(model, s_at, est)
         end if
         call log%lap('estimate')
         call say_estimate(est)
         ! reactions: K u - f_ext at the constrained dofs, with the loads in force
         call assemble_loads(model, st%force, st%dload, f)
         call reaction_forces(ku, f, st%fixed, extra%rf)
         rf_sets = constrained_sets(model, st%fixed)
         allocate (set_rf(2, size(rf_sets)), set_names(size(rf_sets)))
         do iw = 1, size(rf_sets)
            set_names(iw)%s = model%nsets(rf_sets(iw))%name
            set_rf(:, iw) = sum(extra%rf(:, model%nsets(rf_sets(iw))%items), dim=2)
         end do
         call log_reactions(extra%rf, f, set_names, set_rf)
         extra%time = real(istep, wp)
         ! the fields the deck's output requests select (all without requests)
         sel = step_selection(model, istep)
         write (buf, '(a,i4.4,a)') '_', istep, '.vtu'
         vtu_name = opts%job//trim(buf)
         call write_vtu(opts%out_dir//'/'//vtu_name, model, reshape(u_out, [2, int(model%nnode)]), &
                        s_elem, s_node, error, opts%compress_vtu, extra, sel, indicator=est%indicator)
         if (allocated(error)) return
         vtu_files = [vtu_files, string_t(opts%out_dir//'/'//vtu_name)]
         times = [times, real(istep, wp)]
         parts = [parts, 0]
         call h5%write_step(istep, name, real(istep, wp), reshape(u_out, [2, int(model%nnode)]), &
                            s_elem, s_node, error, sel, indicator=est%indicator, &
                            estimate=est%estimate, energy=est%energy)
         if (allocated(error)) return
         call h5%write_results(istep, extra%e_elem, extra%e_node, extra%rf, set_names, set_rf, error, sel)
         if (allocated(error)) return
         deallocate (set_rf, set_names)
         if (contact%n > 0) then
            ! contact results: a point set beside the mesh (part 1), a CSV and an HDF5 group per
            ! pair, when a contact field is selected
            tab = contact%table(model, u_out)
            if (sel%contact()) then
               write (buf, '(a,i4.4,a)') '_contact_', istep, '.vtu'
               call write_contact_vtu(opts%out_dir//'/'//opts%job//trim(buf), tab, &
                                      reshape(u_out, [2, int(model%nnode)]), error, opts%compress_vtu, sel)
               if (allocated(error)) return
               vtu_files = [vtu_files, string_t(opts%out_dir//'/'//opts%job//trim(buf))]
               times = [times, real(istep, wp)]
               parts = [parts, 1]
            end if
            do ip_ = 1, size(model%pairs)
               if (.not. sel%contact()) exit
               write (buf, '(a,i0,a,i4.4,a)') '_contact_pair', ip_, '_', istep, '.csv'
               call write_contact_csv(opts%out_dir//'/'//opts%job//trim(buf), tab, ip_, error, sel)
               if (allocated(error)) return
               call h5%write_contact(istep, ip_, pack(tab%node_id, tab%pair == ip_), &
                                     reshape(pack(tab%x, spread(tab%pair == ip_, 1, 2)), [2, count(tab%pair == ip_)]), &
                                     pack(tab%copen, tab%pair == ip_), pack(tab%cpress, tab%pair == ip_), &
                                     pack(tab%cslip, tab%pair == ip_), pack(tab%cnarea, tab%pair == ip_), &
                                     pack(tab%status, tab%pair == ip_), error, sel, &
                                     cshear=pack(tab%cshear, tab%pair == ip_))
               if (allocated(error)) return
            end do
            call h5%write_iterations(istep, sys%records, error)
            if (allocated(error)) return
            write (buf, '(2x,a,i0,a,i0,a,es12.4,a,es12.4)') 'contact: ', count(contact%active), ' of ', contact%n, &
               ' slave nodes closed, max pressure ', contact%max_pressure(), ', max penetration ', &
               contact%max_penetration()
            call log%say(trim(buf))
            if (contact%fric%on) then
               write (buf, '(2x,a,i0,a,i0,a)') 'friction: ', contact%count_state(tangent_stick), ' stick, ', &
                  contact%count_state(tangent_slip), ' slip'
               call log%say(trim(buf))
            end if
         end if
         if (has_print_requests(model, istep)) then
            ! *NODE PRINT, *EL PRINT, *CONTACT PRINT: CalculiX's JOB.dat as a CSV table
            write (buf, '(a,i4.4,a)') '_print_', istep, '.csv'
            if (contact%n > 0) then
               call write_print_csv(base//trim(buf), model, istep, reshape(u_out, [2, int(model%nnode)]), extra%rf, &
                                    s_elem, extra%e_elem, error, tab)
            else
               call write_print_csv(base//trim(buf), model, istep, reshape(u_out, [2, int(model%nnode)]), extra%rf, &
                                    s_elem, extra%e_elem, error)
            end if
            if (allocated(error)) return
         end if
         call write_pvd(base//'.pvd', vtu_files, times, error, parts)
         if (allocated(error)) return
         done = istep
         call log%lap('write')
         write (buf, '(2x,a,es12.4,a,es12.4,a,es10.3)') 'max |u_x| ', maxval(abs(u_out(1::2))), &
            ', max |u_y| ', maxval(abs(u_out(2::2))), ', rcond ', sys%solver%rcond()
         call log%say(trim(buf))
         call log%failed(error)
         if (allocated(error)) return
      end do
      log%step = 0
      if (opts%write_files) then
         call h5%close(error, complete=.true.)
         if (allocated(error)) return
      end if
      call sys%solver%release()
      call log%say('results')
      call log%say('  '//base//'.pvd')
      call log%say('  '//base//'.h5')
   contains
      !> "estimated relative energy error 2.3 %; 50 % of it in 4.1 % of the cells, around (x, y)"
      subroutine say_estimate(e)
         type(error_estimate_t), intent(in) :: e
         if (.not. (e%estimate > 0.0_wp)) then
            call log%say('  estimated relative energy error 0 %')
            return
         end if
         call log%say('  estimated relative energy error '//number(100.0_wp*e%relative, 3)//' %; 50 % of it in '// &
                      number(100.0_wp*e%half_fraction, 2)//' % of the cells, around ('//number(e%largest_at(1), 5)//', '// &
                      number(e%largest_at(2), 5)//')')
      end subroutine say_estimate

      !> A value with `digits` significant digits, fixed-point from 1e-3 to 1e5, else exponential.
      function number(v, digits) result(s)
         real(wp), intent(in) :: v
         integer, intent(in) :: digits
         character(len=:), allocatable :: s
         character(len=32) :: b
         character(len=16) :: f
         if (abs(v) >= 1.0e-3_wp .and. abs(v) < 1.0e5_wp) then
            write (f, '(a,i0,a)') '(f24.', max(0, digits - 1 - floor(log10(abs(v)))), ')'
         else if (abs(v) > 0.0_wp) then
            write (f, '(a,i0,a)') '(es24.', digits - 1, ')'
         else
            f = '(f3.1)'
         end if
         write (b, f) v
         s = trim(adjustl(b))
      end function number

      !> Totals of the reaction forces (all nodes, and per constrained node set)
      !> beside the applied loads they balance.
      subroutine log_reactions(rf, fext, names, totals)
         real(wp), intent(in) :: rf(:, :), fext(:), totals(:, :)
         type(string_t), intent(in) :: names(:)
         character(len=160) :: line
         integer :: k
         write (line, '(2x,a,2es14.6,a,2es14.6)') 'reaction forces RF1, RF2: all nodes', sum(rf, dim=2), &
            '; applied loads', sum(fext(1::2)), sum(fext(2::2))
         call log%say(trim(line))
         do k = 1, size(names)
            write (line, '(4x,a,2es14.6)') 'node set '//names(k)%s//':', totals(:, k)
            call log%say(trim(line))
         end do
      end subroutine log_reactions

      function step_name(i) result(s)
         integer, intent(in) :: i
         character(len=:), allocatable :: s
         character(len=16) :: b
         if (allocated(model%steps(i)%name)) then
            s = model%steps(i)%name
         else
            write (b, '(a,i0)') 'Step-', i
            s = trim(b)
         end if
      end function step_name
   end subroutine run_steps
end module vemcontact_driver_static
