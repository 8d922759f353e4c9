!> Static analysis over the deck's steps, each applied in one or more load
!> increments (vemcontact_driver_increments), with output after every step.
!> Every completed step is in the VTU files before the next starts and in the
!> HDF5 file, which gets its final name when the run ends: a run that fails part
!> way keeps the steps it completed (the HDF5 file without the step that failed
!> and marked `complete = 0`, the .pvd listing the steps completed); a run stopped
!> by SIGINT or SIGTERM likewise (marked `interrupted` too); a run killed otherwise
!> leaves no HDF5 file.
!>
!> The run is a sequence of stages on one `run_state_t`: the set-up report
!> (set_up), the result files (open_files), then per step its increments
!> (run_step, solve_increment), the post-processing of the converged state
!> (post_process) and the output (write_results).
module vemcontact_driver_static
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, append_message, fatal_error, err_solver
   use vemcontact_model, only: model_t, string_t, form_vem, form_fem, etype_polygon, procedure_geostatic, &
                               element_order, etype_polygon2, pair_surface_to_surface, amplitude_t, &
                               procedure_strength_reduction
   use vemcontact_sparse_mmio, only: write_matrix_market
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_driver_linear, only: linear_system_t
   use vemcontact_driver_validate, only: element_warnings
   use vemcontact_driver_ranges, only: validate_ranges
   use vemcontact_driver_contact_checks, only: check_contact_pairs
   use vemcontact_driver_pair_roles, only: choose_pair_roles
   use vemcontact_driver_load_state, only: load_state_t, init_load_state, advance_load_state
   use vemcontact_driver_increments, only: increment_control_t, loads_at
   use vemcontact_driver_assembly, only: element_stresses, element_strains, assemble_loads
   use vemcontact_post_stress, only: nodal_average
   use vemcontact_post_estimate, only: error_estimate_t, estimate_error
   use vemcontact_post_estimate2, only: estimate_error2
   use vemcontact_post_reactions, only: reaction_forces, constrained_sets
   use vemcontact_driver_thermal, only: add_thermal_forces
   use vemcontact_post_labels, only: element_section_sets, element_parts
   use vemcontact_output_vtu, only: write_vtu, vtu_extras_t
   use vemcontact_output_sta, only: sta_list_t
   use vemcontact_output_pvd, only: pvd_list_t, pvd_rewrite_due
   use vemcontact_output_hdf5, only: h5_writer_t
   use vemcontact_output_xdmf, only: write_xdmf
   use vemcontact_output_contact, only: write_contact_csv, write_contact_vtu
   use vemcontact_output_selection, only: field_selection_t, step_selection
   use vemcontact_output_print, only: has_print_requests, write_print_csv
   use vemcontact_contact_table, only: contact_table_t
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_insertion, only: insert_tie_nodes
   use vemcontact_driver_inserted_values, only: interpolate_inserted
   use vemcontact_contact_friction, only: tangent_stick, tangent_slip
   use vemcontact_log, only: logger_t
   use vemcontact_contact_tangential, only: friction_params_t
   use vemcontact_driver_strength_reduction, only: srm_result_t, run_strength_reduction, reduced_strength
   use vemcontact_output_srm, only: write_srm_csv
   use vemcontact_interrupt, only: interrupt_error, interrupt_context, is_interrupt, err_interrupt_base
   use vemcontact_solver_stop, only: agreed_stop_signal
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
      logical :: write_vtu = .true.           !< .vtu and .pvd files (--no-vtu: not)
      !> .false.: a process of a distributed run other than rank 0, which solves with
      !> the others but writes nothing and skips the post-processing
      logical :: write_files = .true.
   end type run_options_t

   !> The results of a converged state derived from its displacements: what the
   !> output writes.
   type :: state_results_t
      real(wp), allocatable :: u_out(:)       !< displacements relative to the geostatic step
      real(wp), allocatable :: s_elem(:, :), s_node(:, :)
      !> second-order elements: stress and strain at each element's nodes
      real(wp), allocatable :: s_at(:, :), e_at(:, :)
      real(wp), allocatable :: ku(:), f(:)    !< K u and the applied loads
      type(vtu_extras_t) :: extra             !< strains, reactions, labels, time
      type(error_estimate_t) :: est
      type(string_t), allocatable :: set_names(:)
      real(wp), allocatable :: set_rf(:, :)   !< reaction totals of the constrained node sets
      type(contact_table_t) :: tab
   end type state_results_t

   !> Everything the run carries from stage to stage and from step to step.
   type :: run_state_t
      type(linear_system_t) :: sys
      type(contact_state_t) :: contact
      type(h5_writer_t) :: h5
      type(load_state_t) :: given       !< the step's loads as the deck gives them
      type(load_state_t) :: applied     !< the loads of the increment being solved
      type(load_state_t) :: prev        !< the loads applied at the end of the previous step
      real(wp), allocatable :: u(:)     !< displacements of the last converged increment
      real(wp), allocatable :: u_ref(:) !< displacements at the end of a geostatic step
      type(state_results_t) :: res
      !> the trials of the current step when it is a strength reduction step
      type(srm_result_t) :: srm
      type(pvd_list_t) :: pvd           !< the VTU files written, for JOB.pvd
      type(sta_list_t) :: sta           !< the converged increments, for JOB.sta
      character(len=:), allocatable :: base  !< out_dir/job
      integer :: current = 0            !< the step being run
      integer :: done = 0               !< the last step whose results are in every file
      real(wp) :: t_start = 0.0_wp      !< total time at the start of the current step
      logical :: matrix_written = .false.  !< --write-matrix: JOB.mtx is written
      integer :: pvd_steps = 0          !< the completed steps JOB.pvd lists
      integer :: pvd_done = 0           !< the entries of rs%pvd of the completed steps
   end type run_state_t

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
      type(run_state_t) :: rs
      type(error_t), allocatable :: err2
      character(len=24) :: b
      call run_steps(model, opts, log, rs, error)
      if (.not. allocated(error)) return
      if (is_interrupt(error%code)) then
         b = ''
         if (rs%current > rs%done) write (b, '(a,i0)') 'in step ', rs%current
         call interrupt_context(error, trim(b), rs%done)
      end if
      ! JOB.sta: every converged increment, those of the failed step too (where it stopped)
      if (opts%write_files .and. allocated(rs%base) .and. rs%current > 0) then
         call rs%sta%write(rs%base//'.sta', err2)
         if (allocated(err2)) call append_message(error, '(no .sta file: '//err2%message//')')
         if (allocated(err2)) deallocate (err2)
      end if
      ! the .pvd lists every completed step, and only those
      if (opts%write_files .and. opts%write_vtu .and. rs%done > rs%pvd_steps) then
         rs%pvd%n = rs%pvd_done
         call rs%pvd%write(rs%base//'.pvd', err2)
         if (allocated(err2)) call append_message(error, '(no .pvd file: '//err2%message//')')
         if (allocated(err2)) deallocate (err2)
      end if
      if (.not. rs%h5%is_open()) return
      if (rs%current > rs%done) call rs%h5%discard_step(rs%current, err2)
      if (allocated(err2)) then
         call rs%h5%discard()
      else if (is_interrupt(error%code)) then
         call rs%h5%close(err2, interrupted=error%code - err_interrupt_base)
      else
         call rs%h5%close(err2)
         if (.not. allocated(err2)) &
            call write_xdmf(opts%out_dir//'/'//opts%job//'.xdmf', opts%job//'.h5', model, rs%done, err2)
      end if
      if (allocated(err2)) call append_message(error, '(no HDF5 results file: '//err2%message//')')
   end subroutine run_static

   !> The analysis and its output, stage by stage.
   subroutine run_steps(model, opts, log, rs, error)
      type(model_t), intent(inout) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      type(error_t), allocatable, intent(out) :: error
      integer :: istep, sig
      character(len=16) :: b
      call set_up(model, opts, log, rs, error)
      if (allocated(error)) return
      call open_files(model, opts, log, rs, error)
      if (allocated(error)) return
      call init_state(model, rs)
      call log%lap('write mesh')
      do istep = 1, size(model%steps)
         ! a safe point, the same on every process
         sig = agreed_stop_signal()
         if (sig > 0) then
            write (b, '(i0)') istep
            call interrupt_error(sig, 'before step '//trim(b)//' ('//step_name(model, istep)//')', error)
            return
         end if
         call run_step(model, opts, log, rs, istep, error)
         if (allocated(error)) return
      end do
      log%step = 0
      if (opts%write_files) then
         call rs%h5%close(error, complete=.true.)
         if (allocated(error)) return
         ! JOB.xdmf: the steps of JOB.h5 for ParaView and meshio, read in place
         call write_xdmf(rs%base//'.xdmf', opts%job//'.h5', model, size(model%steps), error)
         if (allocated(error)) return
      end if
      call rs%sys%solver%release()
      call log%say('results')
      if (opts%write_vtu) call log%say('  '//rs%base//'.pvd')
      call log%say('  '//rs%base//'.h5')
      call log%say('  '//rs%base//'.sta')
      call log%say('  '//rs%base//'.xdmf')
   end subroutine run_steps

   !> Contact pairs, the linear system and its solver, with the set-up report.
   subroutine set_up(model, opts, log, rs, error)
      type(model_t), intent(inout) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      type(error_t), allocatable, intent(out) :: error
      type(string_t), allocatable :: warnings(:)
      integer(ip), allocatable :: tie_added(:)
      integer(ip) :: n0
      character(len=256) :: buf
      integer :: iw
      ! the magnitudes before anything is computed from them (the contact stiffness
      ! of contact%init is E times the thickness); sys%setup checks the rest
      call validate_ranges(model, error)
      if (allocated(error)) return
      ! node to surface pairs with the softer, finer face as the slave, before anything
      ! is built on their roles
      call choose_pair_roles(model, warnings, error)
      if (allocated(error)) return
      do iw = 1, size(warnings)
         call log%say(warnings(iw)%s)
      end do
      ! pairs that would make the contact meaningless (a face on its own master's element,
      ! an overclosure no contact starts with)
      call check_contact_pairs(model, error)
      if (allocated(error)) return
      ! the ties' insertions first: the contact pairs then see the faces as they stay
      n0 = model%nnode
      call insert_tie_nodes(model, tie_added)
      call report_ties(model, tie_added, log)
      call rs%contact%init(model, error)
      if (allocated(error)) return
      call interpolate_inserted(model, n0)
      call report_model(model, rs%contact, log)
      call rs%sys%setup(model, opts%ordering, error, rs%contact, opts%solver)
      if (allocated(error)) return
      rs%sys%fallback = opts%solver_fallback
      ! valid but known to be poor: locking FEM sections, non-convex FEM quads
      warnings = element_warnings(model)
      do iw = 1, size(warnings)
         call log%say(warnings(iw)%s)
      end do
      if (any(rs%sys%unused)) then
         write (buf, '(2x,a,i0,a)') 'note: ', count(rs%sys%unused), ' nodes belong to no element and are left out'
         call log%say(trim(buf))
      end if
      ! the factor's size for a direct solver that reports it (none for CG + AMG)
      buf = ''
      if (rs%sys%solver%nnz_factor > 0) write (buf, '(a,i0,a,es9.2)') ', factor nnz ', rs%sys%solver%nnz_factor, &
         ', flops ', rs%sys%solver%flops
      call log%say('  solver '//rs%sys%solver%describe()//trim(buf))
      ! the phases are laps (vemcontact_log): each lap is the time since the
      ! previous one that the phases logged in between do not account for
      call log%phase('validate', rs%sys%t_validate)
      call log%phase('pattern', rs%sys%t_pattern)
      ! of which the contact search for the candidate pairs of the pattern
      if (rs%contact%n > 0) call log%phase('candidates', rs%sys%t_candidates, within='pattern')
      ! of which the partition of the mesh over the processes (distributed)
      if (rs%sys%dist) call log%phase('partition', rs%sys%t_partition, within='pattern')
      call log%phase('assemble', rs%sys%t_assemble)
      call log%phase('analyze', rs%sys%t_analyze)
      ! contact surfaces and pairs, parts, unused nodes, element warnings
      call log%lap('set-up')
   end subroutine set_up

   !> How each *TIE is made: node to node after `added(t)` nodes were inserted, the
   !> virtual face tied to the FEM face after `added(t)` of its nodes were inserted, or
   !> by closest points (added(t) < 0).
   subroutine report_ties(model, added, log)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: added(:)
      type(logger_t), intent(inout) :: log
      character(len=256) :: buf
      integer :: t
      do t = 1, size(added)
         if (allocated(model%ties(t)%partner)) then
            write (buf, '(a,i0,a,i0,a)') ': ', added(t), ' interface nodes inserted, ', &
               size(model%ties(t)%partner, 2), ' node pairs tied'
         else if (added(t) >= 0) then
            write (buf, '(a,i0,a)') ': ', added(t), ' FEM face nodes inserted into the virtual face, '// &
               'whose nodes are tied to the FEM face'
         else
            buf = ': closest-point tie (no insertion: FEM faces, first- and second-order sides, or a held side)'
         end if
         call log%say('  tie '//model%ties(t)%name//trim(buf))
      end do
   end subroutine report_ties

   !> The set-up report of the model: interface nodes, sizes, contact pairs.
   subroutine report_model(model, contact, log)
      type(model_t), intent(in) :: model
      type(contact_state_t), intent(in) :: contact
      type(logger_t), intent(inout) :: log
      character(len=256) :: buf
      integer :: ip_
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
      if (contact%n == 0) return
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
   end subroutine report_model

   !> JOB.h5 with the mesh and its labels (the processes' elements for a distributed run).
   subroutine open_files(model, opts, log, rs, error)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: per_process(:)
      character(len=:), allocatable :: line
      character(len=32) :: buf
      integer :: k
      rs%base = opts%out_dir//'/'//opts%job
      if (opts%write_files) then
         ! the elements of each process (one process: all of them)
         per_process = [model%nelem]
         if (rs%sys%dist) per_process = rs%sys%partition%elements
         call rs%h5%open(rs%base//'.h5', error, solver=rs%sys%solver%describe(), partition=per_process)
         if (allocated(error)) return
         call rs%h5%write_mesh(model, error)
         if (allocated(error)) then
            call rs%h5%discard()
            return
         end if
         rs%res%extra%elem_set = element_section_sets(model)
         rs%res%extra%elem_part = element_parts(model, rs%sys%part)
         call rs%h5%write_labels(model, rs%res%extra%elem_set, rs%res%extra%elem_part, error)
         if (allocated(error)) then
            call rs%h5%discard()
            return
         end if
      end if
      if (rs%sys%dist) then
         write (buf, '(2x,a,i0,a)') 'distributed over ', rs%sys%partition%nparts, ' processes'
         line = trim(buf)//' (METIS partition of the nodes): elements per process'
         do k = 1, rs%sys%partition%nparts
            write (buf, '(i0)') rs%sys%partition%elements(k)
            line = line//' '//trim(buf)
         end do
         call log%say(line)
      end if
   end subroutine open_files

   !> The state before the first step: no loads, zero displacements, the result arrays.
   subroutine init_state(model, rs)
      type(model_t), intent(inout) :: model
      type(run_state_t), intent(inout) :: rs
      integer :: ie
      integer(ip) :: nat
      if (.not. allocated(model%amplitudes)) allocate (model%amplitudes(0))
      call init_load_state(model, rs%given)
      rs%prev = rs%given
      rs%prev%fixed = .false.
      allocate (rs%u(2*model%nnode), source=0.0_wp)
      ! displacements are reported relative to the end of a geostatic step
      allocate (rs%u_ref(2*model%nnode), source=0.0_wp)
      associate (r => rs%res)
         allocate (r%s_elem(4, model%nelem), r%s_node(4, model%nnode))
         allocate (r%extra%e_elem(4, model%nelem), r%extra%e_node(4, model%nnode), r%extra%rf(2, model%nnode))
         allocate (r%ku(2*model%nnode), r%f(2*model%nnode))
         if (any([(element_order(model%elem_type(ie)) == 2, ie=1, int(model%nelem))])) then
            nat = model%elem_ptr(model%nelem + 1) - 1
            allocate (r%s_at(4, nat), r%e_at(4, nat))
         end if
      end associate
   end subroutine init_state

   !> The increments of step `istep` (*STATIC, *GEOSTATIC): each solved from the last
   !> converged state, cut back when its contact iteration runs out of iterations, the
   !> results of every FREQUENCY-th increment written as a frame.
   subroutine run_increments(model, opts, log, rs, istep, error)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      integer, intent(in) :: istep
      type(error_t), allocatable, intent(out) :: error
      type(increment_control_t) :: ctl
      type(contact_state_t) :: contact_saved
      real(wp), allocatable :: u_start(:), u_saved(:)
      real(wp) :: t_before
      logical :: ok, several
      integer :: frequency, attempt
      character(len=200) :: buf
      frequency = output_frequency(model, istep)
      call ctl%start(model%steps(istep))
      ! one increment (the default): the log as without increments
      several = ctl%dt < ctl%period
      u_start = rs%u
      attempt = 1
      do while (.not. ctl%finished())
         call ctl%next()
         if (several) then
            write (buf, '(2x,a,i0,a,es12.5,a,es12.5,a)') 'increment ', ctl%increment + 1, ': step time ', &
               ctl%t_try, ' (increment ', ctl%t_try - ctl%t, ')'
            call log%say(trim(buf))
         end if
         ! a failed increment starts again from the last converged displacements and
         ! contact state (the whole state: every history it carries)
         if (.not. ctl%direct) then
            u_saved = rs%u
            if (rs%contact%n > 0) contact_saved = rs%contact
         end if
         rs%applied = loads_at(model%steps(istep), rs%given, rs%prev, u_start, ctl%step_fraction(), rs%t_start, &
                               model%amplitudes)
         call solve_increment(model, opts, log, rs, istep, error)
         if (allocated(error)) then
            ! only a contact iteration that used up its MAXIT iterations is worth a smaller
            ! increment: an ill-conditioned or singular system, or an active set that
            ! cycles, stops the run as in one increment
            if (error%code /= err_solver .or. rs%contact%n == 0) return
            if (rs%sys%iterations < model%controls%max_iterations) return
            call ctl%cut_back(ok)
            if (.not. ok) then
               call increment_failure(model, ctl, istep, error)
               return
            end if
            write (buf, '(2x,a,es12.5,a)') 'increment not converged: cut back to ', ctl%dt, &
               ' (from the last converged state)'
            call log%say(trim(buf)//'; '//first_line(error%message))
            deallocate (error)
            rs%u = u_saved
            if (rs%contact%n > 0) rs%contact = contact_saved
            several = .true.
            attempt = attempt + 1
            cycle
         end if
         t_before = ctl%t
         call ctl%accept(rs%sys%iterations)
         call rs%sta%add(istep, ctl%increment, attempt, rs%sys%iterations, rs%t_start + ctl%t, ctl%t, &
                         ctl%t - t_before)
         attempt = 1
         ! JOB.sta as the run goes, after 1, 2, 4, ... increments (O(increments) in all)
         if (opts%write_files .and. iand(rs%sta%n, rs%sta%n - 1) == 0) then
            call rs%sta%write(rs%base//'.sta', error)
            if (allocated(error)) return
         end if
         if (ctl%finished()) exit
         if (frequency > 0) then
            if (mod(ctl%increment, frequency) == 0) then
               ! *NODE FILE, FREQUENCY=n etc.: the results of this increment
               call write_frame(model, opts, log, rs, istep, ctl, error)
               if (allocated(error)) return
            end if
         end if
      end do
   end subroutine run_increments

   !> The step's *CHANGE FRICTION: the pairs of each interaction named take its law
   !> from the state the step starts from (contact_state_t%change_friction).
   subroutine change_friction_laws(model, rs, istep, log, error)
      type(model_t), intent(in) :: model
      type(run_state_t), intent(inout) :: rs
      integer, intent(in) :: istep
      type(logger_t), intent(inout) :: log
      type(error_t), allocatable, intent(out) :: error
      integer :: k
      if (.not. allocated(model%steps(istep)%friction_changes)) return
      if (rs%contact%n == 0) return
      do k = 1, size(model%steps(istep)%friction_changes)
         associate (c => model%steps(istep)%friction_changes(k))
            call rs%contact%change_friction(model, rs%u, c%interaction, &
                                            friction_params_t(.true., c%rough, c%mu, c%stick_slope, c%cohesion), error)
            if (allocated(error)) return
            call log%say('  friction of interaction '//model%interactions(c%interaction)%name//' changed')
         end associate
      end do
   end subroutine change_friction_laws

   !> Step `istep`: its increments (or the trials of a strength reduction step), then
   !> the post-processing and output of its end.
   subroutine run_step(model, opts, log, rs, istep, error)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      integer, intent(in) :: istep
      type(error_t), allocatable, intent(out) :: error
      character(len=200) :: buf
      rs%current = istep
      log%step = istep
      call log%say('step '//step_name(model, istep))
      call advance_load_state(model%steps(istep), rs%given)
      call change_friction_laws(model, rs, istep, log, error)
      if (allocated(error)) return
      if (model%steps(istep)%procedure == procedure_strength_reduction) then
         ! the loads in force at the end of the previous step (the step has none of its
         ! own, and amplitudes are not evaluated anew), the trials instead of the increments
         rs%applied = rs%prev
         call run_strength_reduction(model, model%steps(istep)%srm, rs%sys, rs%applied, rs%u, rs%contact, log, &
                                     rs%srm, error)
         if (allocated(error)) return
         call say_factor(log, rs%srm)
         call log%lap('strength reduction')
      else
         call run_increments(model, opts, log, rs, istep, error)
         if (allocated(error)) return
      end if
      rs%prev = rs%applied
      rs%t_start = rs%t_start + model%steps(istep)%period
      if (model%steps(istep)%procedure == procedure_geostatic) then
         rs%u_ref = rs%u
         call log%say('  geostatic step: its displacements are the reference (reported as zero), '// &
                      'its stresses are kept')
      end if
      rs%res%u_out = rs%u - rs%u_ref
      ! K u for the reactions: every process together (distributed, the shares are added)
      call rs%sys%elastic_times(rs%u, rs%res%ku)
      if (.not. opts%write_files) then
         ! the post-processing and the output are rank 0's
         rs%done = istep
         return
      end if
      call post_process(model, log, rs, .false.)
      rs%res%extra%time = rs%t_start
      call write_results(model, opts, log, rs, istep, 0, error)
      if (allocated(error)) return
      if (model%steps(istep)%procedure == procedure_strength_reduction) then
         call write_srm(rs, istep, error)
         if (allocated(error)) return
      else
         call write_increments(rs, istep, error)
         if (allocated(error)) return
      end if
      rs%done = istep
      rs%pvd_done = rs%pvd%n
      ! the .pvd and an HDF5 flush cost O(steps so far) each: after steps 1, 2, 4, ...
      ! (and the last), so that a run costs O(steps)
      if (pvd_rewrite_due(istep) .or. istep == size(model%steps)) then
         call rs%h5%flush(error)
         if (allocated(error)) return
      end if
      if (opts%write_vtu .and. (pvd_rewrite_due(istep) .or. istep == size(model%steps))) then
         call rs%pvd%write(rs%base//'.pvd', error)
         if (allocated(error)) return
         rs%pvd_steps = istep
      end if
      if (pvd_rewrite_due(istep) .or. istep == size(model%steps)) then
         call rs%sta%write(rs%base//'.sta', error)
         if (allocated(error)) return
      end if
      call log%lap('write')
      write (buf, '(2x,a,es12.4,a,es12.4,a,es10.3)') 'max |u_x| ', maxval(abs(rs%res%u_out(1::2))), &
         ', max |u_y| ', maxval(abs(rs%res%u_out(2::2))), ', rcond ', rs%sys%solver%rcond()
      call log%say(trim(buf))
      call log%failed(error)
   end subroutine run_step

   !> The error of a step whose increment reached the minimum without converging:
   !> the step, the time reached, the last contact message.
   subroutine increment_failure(model, ctl, istep, error)
      type(model_t), intent(in) :: model
      type(increment_control_t), intent(in) :: ctl
      integer, intent(in) :: istep
      type(error_t), allocatable, intent(inout) :: error
      character(len=300) :: buf
      character(len=:), allocatable :: why, help
      integer :: k
      why = first_line(error%message)
      ! the contact iteration's own help lines (what the run can change) stay
      k = index(error%message, new_line('a'))
      help = ''
      if (k > 0) help = error%message(k:)
      deallocate (error)
      if (ctl%direct) then
         write (buf, '(a,es12.5,a,es12.5,a)') ' did not converge at step time ', ctl%t, ' of ', ctl%period, &
            ' with fixed increments (DIRECT): '
      else
         write (buf, '(a,es12.5,a,es12.5,a,es10.3,a)') ' did not converge at step time ', ctl%t, ' of ', &
            ctl%period, ': the increment reached its minimum ', ctl%dt_min, ': '
      end if
      call fatal_error(error, 'error: step '//step_name(model, istep)//trim(buf)//' '//why//help//new_line('a')// &
                       '  = help: a smaller initial or minimum increment on the *STATIC data line, '// &
                       'or more contact iterations (*CONTACT CONTROLS, MAXIT)', err_solver)
   end subroutine increment_failure

   !> The first line of a message without its "error: " prefix.
   pure function first_line(msg) result(s)
      character(len=*), intent(in) :: msg
      character(len=:), allocatable :: s
      integer :: j, k
      k = index(msg, new_line('a'))
      if (k == 0) k = len(msg) + 1
      j = 1
      if (index(msg, 'error: ') == 1) j = 8
      s = msg(j:k - 1)
   end function first_line

   !> Solve one increment with the loads rs%applied, from rs%u; its log lines and phases.
   subroutine solve_increment(model, opts, log, rs, istep, error)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      integer, intent(in) :: istep
      type(error_t), allocatable, intent(out) :: error
      type(sym_csc_t) :: kwhole
      character(len=120) :: buf
      call rs%sys%solve_state(model, rs%applied, rs%u, error, rs%contact, log)
      if (allocated(error)) return
      if (rs%sys%fell_back .and. opts%write_files) then
         ! the solver that ran, once it is CHOLMOD after a failed CG
         call rs%h5%set_solver(rs%sys%solver%describe(), error)
         if (allocated(error)) return
         rs%sys%fell_back = .false.
      end if
      if (rs%sys%iterations > 0) then
         write (buf, '(2x,a,i0,a,i0,a)') 'contact converged in ', rs%sys%iterations, ' iterations (', &
            rs%sys%factorizations, ' numeric factorizations)'
         call log%say(trim(buf))
      end if
      if (rs%sys%refactorized) call log%phase('factorize', rs%sys%t_factorize)
      call log%phase('solve', rs%sys%t_solve)
      ! pairing and active set of every iteration of the step (also in the iteration lines)
      if (rs%contact%n > 0) call log%phase('search', rs%sys%t_search)
      ! the rest of solve_state: load vector, constraints, the contact iteration's own work
      call log%lap('system')
      if (.not. opts%write_matrix .or. istep /= 1 .or. rs%matrix_written) return
      ! the matrix of the first increment of the first step
      if (rs%sys%dist) then
         ! the whole matrix: the sum of the processes' shares, on every process
         kwhole = rs%sys%kb
         call rs%sys%solver%sum_over_ranks(kwhole%val, error)
         if (allocated(error)) return
         if (opts%write_files) call write_matrix_market(rs%base//'.mtx', kwhole, error)
         deallocate (kwhole%val)
      else if (opts%write_files) then
         call write_matrix_market(rs%base//'.mtx', rs%sys%kb, error)
      end if
      if (allocated(error)) return
      rs%matrix_written = .true.
      call log%lap('write matrix')
   end subroutine solve_increment

   !> The smallest FREQUENCY=n > 0 of the file output requests in force in step
   !> `istep`: its results are written every n increments too (0: at its end only).
   pure integer function output_frequency(model, istep) result(n)
      type(model_t), intent(in) :: model
      integer, intent(in) :: istep
      integer :: k
      n = 0
      if (.not. allocated(model%steps(istep)%outputs)) return
      do k = 1, size(model%steps(istep)%outputs)
         associate (r => model%steps(istep)%outputs(k))
            if (r%print .or. r%frequency <= 0) cycle
            if (n == 0) then
               n = r%frequency
            else
               n = min(n, r%frequency)
            end if
         end associate
      end do
   end function output_frequency

   !> The results of increment ctl%increment within step `istep` (not its last): a
   !> frame in JOB.h5 (/increments/NNNN/MMMM), JOB_NNNN_MMMM.vtu (and the contact
   !> points' JOB_contact_NNNN_MMMM.vtu) with an entry in JOB.pvd at the total time.
   subroutine write_frame(model, opts, log, rs, istep, ctl, error)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      integer, intent(in) :: istep
      type(increment_control_t), intent(in) :: ctl
      type(error_t), allocatable, intent(out) :: error
      rs%res%u_out = rs%u - rs%u_ref
      call rs%sys%elastic_times(rs%u, rs%res%ku)
      if (.not. opts%write_files) return
      call post_process(model, log, rs, .true.)
      rs%res%extra%time = rs%t_start + ctl%t
      call rs%h5%set_increment(ctl%increment)
      call write_results(model, opts, log, rs, istep, ctl%increment, error)
      call rs%h5%set_increment(0)
   end subroutine write_frame

   !> Stresses, strains, the error estimate and the reactions of the converged state
   !> (`quiet`: without their log lines, for the frames of increments).
   subroutine post_process(model, log, rs, quiet)
      type(model_t), intent(in) :: model
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      logical, intent(in) :: quiet
      integer, allocatable :: rf_sets(:)
      real(wp), allocatable :: fc(:)
      integer :: k
      associate (r => rs%res, st => rs%applied)
         ! second-order elements give their own stress and strain at each node
         ! (linear for the k = 2 VEM), averaged at the nodes instead of the
         ! element values; strains E = D^-1 S from the same recovery
         ! (element_strains)
         if (allocated(r%s_at)) then
            call element_stresses(model, rs%u, r%s_elem, st%dload, r%s_at, st%dtemp)
            call nodal_average(model, r%s_elem, r%s_node, r%s_at)
            call element_strains(model, r%s_elem, r%extra%e_elem, r%s_at, r%e_at, st%dtemp)
            call nodal_average(model, r%extra%e_elem, r%extra%e_node, r%e_at)
         else
            call element_stresses(model, rs%u, r%s_elem, st%dload, dtemp=st%dtemp)
            call nodal_average(model, r%s_elem, r%s_node)
            call element_strains(model, r%s_elem, r%extra%e_elem, dtemp=st%dtemp)
            call nodal_average(model, r%extra%e_elem, r%extra%e_node)
         end if
         if (.not. quiet) call log%lap('stresses')
         ! the recovery-based error estimate: second-order models recover a quadratic
         ! stress from the cells' own linear stresses (s_at)
         if (.not. allocated(r%s_at)) then
            call estimate_error(model, r%s_elem, r%est)
         else
            call estimate_error2(model, r%s_at, r%est)
         end if
         if (.not. quiet) call log%lap('estimate')
         if (.not. quiet) call say_estimate(log, r%est)
         ! reactions: the force the supports exert, K u - f_ext - f_contact at the
         ! constrained dofs with the loads in force (a constrained slave or master node
         ! also takes its contact force: the support carries the rest); contact%forces
         ! adds -f_contact, the contact springs' pull -N A^T n; thermal strains add their
         ! (self-equilibrated) forces; K u is that of the system with *EQUATION eliminated
         ! (docs/output-format.md, "Reaction forces")
         call assemble_loads(model, st%force, st%dload, r%f)
         call add_thermal_forces(model, st%dtemp, r%f)
         call rs%sys%reduce_loads(r%f)
         if (rs%contact%n > 0) then
            allocate (fc(size(r%f)), source=0.0_wp)
            call rs%contact%forces(fc)
            call reaction_forces(r%ku, r%f - fc, st%fixed, r%extra%rf)
         else
            call reaction_forces(r%ku, r%f, st%fixed, r%extra%rf)
         end if
         rf_sets = constrained_sets(model, st%fixed)
         if (allocated(r%set_rf)) deallocate (r%set_rf, r%set_names)
         allocate (r%set_rf(2, size(rf_sets)), r%set_names(size(rf_sets)))
         do k = 1, size(rf_sets)
            r%set_names(k)%s = model%nsets(rf_sets(k))%name
            r%set_rf(:, k) = sum(r%extra%rf(:, model%nsets(rf_sets(k))%items), dim=2)
         end do
         if (.not. quiet) call log_reactions(log, r%extra%rf, r%f, r%set_names, r%set_rf)
      end associate
   end subroutine post_process

   !> The results of step `istep` in every file: VTU, HDF5, contact VTU and CSV, PRINT
   !> CSV; of its increment `frame` > 0: VTU, HDF5 and contact VTU (file names with
   !> _NNNN_MMMM; the HDF5 group is the writer's, set_increment).
   subroutine write_results(model, opts, log, rs, istep, frame, error)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      integer, intent(in) :: istep, frame
      type(error_t), allocatable, intent(out) :: error
      type(field_selection_t) :: sel
      character(len=64) :: buf
      character(len=:), allocatable :: vtu_name
      real(wp) :: time
      integer :: nn
      nn = int(model%nnode)
      time = rs%res%extra%time
      associate (r => rs%res)
         ! the fields the deck's output requests select (all without requests)
         sel = step_selection(model, istep)
         vtu_name = opts%out_dir//'/'//opts%job//'_'//frame_suffix(istep, frame)//'.vtu'
         if (opts%write_vtu) then
            call write_vtu(vtu_name, model, reshape(r%u_out, [2, nn]), r%s_elem, r%s_node, error, &
                           opts%compress_vtu, r%extra, sel, indicator=r%est%indicator)
            if (allocated(error)) return
            call rs%pvd%add(vtu_name, time, 0)
         end if
         call rs%h5%write_step(istep, step_name(model, istep), time, reshape(r%u_out, [2, nn]), &
                               r%s_elem, r%s_node, error, sel, indicator=r%est%indicator, &
                               estimate=r%est%estimate, energy=r%est%energy)
         if (allocated(error)) return
         call rs%h5%write_results(istep, r%extra%e_elem, r%extra%e_node, r%extra%rf, r%set_names, r%set_rf, &
                                  error, sel, load_total=[sum(r%f(1::2)), sum(r%f(2::2))])
         if (allocated(error)) return
         if (rs%contact%n > 0) then
            call write_contact_results(model, opts, log, rs, istep, frame, sel, error)
            if (allocated(error)) return
         end if
         if (frame > 0) return
         if (has_print_requests(model, istep)) then
            ! *NODE PRINT, *EL PRINT, *CONTACT PRINT: CalculiX's JOB.dat as a CSV table
            buf = '_print_'//frame_suffix(istep, 0)//'.csv'
            if (rs%contact%n > 0) then
               call write_print_csv(rs%base//trim(buf), model, istep, reshape(r%u_out, [2, nn]), r%extra%rf, &
                                    r%s_elem, r%extra%e_elem, error, r%tab)
            else
               call write_print_csv(rs%base//trim(buf), model, istep, reshape(r%u_out, [2, nn]), r%extra%rf, &
                                    r%s_elem, r%extra%e_elem, error)
            end if
            if (allocated(error)) return
         end if
      end associate
   end subroutine write_results

   !> Contact results: a point set beside the mesh (part 1), a CSV and an HDF5 group
   !> per pair when a contact field is selected; the iteration records; the log's summary.
   subroutine write_contact_results(model, opts, log, rs, istep, frame, sel, error)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(logger_t), intent(inout) :: log
      type(run_state_t), intent(inout) :: rs
      integer, intent(in) :: istep, frame
      type(field_selection_t), intent(in) :: sel
      type(error_t), allocatable, intent(out) :: error
      character(len=160) :: buf
      character(len=:), allocatable :: name
      integer :: ip_
      real(wp), allocatable :: fluid(:), wet
      associate (tab => rs%res%tab, u_out => rs%res%u_out)
         tab = rs%contact%table(model, u_out)
         if (sel%contact() .and. opts%write_vtu) then
            name = opts%out_dir//'/'//opts%job//'_contact_'//frame_suffix(istep, frame)//'.vtu'
            call write_contact_vtu(name, tab, reshape(u_out, [2, int(model%nnode)]), error, opts%compress_vtu, sel)
            if (allocated(error)) return
            call rs%pvd%add(name, rs%res%extra%time, 1)
         end if
         do ip_ = 1, size(model%pairs)
            if (.not. sel%contact()) exit
            ! CFLUIDP with *UPLIFT (an unallocated actual argument is absent)
            if (allocated(fluid)) deallocate (fluid)
            if (allocated(tab%cfluidp)) fluid = pack(tab%cfluidp, tab%pair == ip_)
            ! the length the water entered, on the pairs of a pressure penetration
            if (allocated(wet)) deallocate (wet)
            if (allocated(rs%contact%water_entered)) then
               if (rs%contact%water_entered(ip_) >= 0.0_wp) wet = rs%contact%water_entered(ip_)
            end if
            if (frame == 0) then
               write (buf, '(a,i0,a)') '_contact_pair', ip_, '_'
               call write_contact_csv(opts%out_dir//'/'//opts%job//trim(buf)//frame_suffix(istep, 0)//'.csv', &
                                      tab, ip_, error, sel)
               if (allocated(error)) return
            end if
            call rs%h5%write_contact(istep, ip_, pack(tab%node_id, tab%pair == ip_), &
                                     reshape(pack(tab%x, spread(tab%pair == ip_, 1, 2)), [2, count(tab%pair == ip_)]), &
                                     pack(tab%copen, tab%pair == ip_), pack(tab%cpress, tab%pair == ip_), &
                                     pack(tab%cslip, tab%pair == ip_), pack(tab%cnarea, tab%pair == ip_), &
                                     pack(tab%status, tab%pair == ip_), error, sel, &
                                     cshear=pack(tab%cshear, tab%pair == ip_), cfluidp=fluid, &
                                     strength=strength_in_force(model, rs, istep, ip_), &
                                     water_entered=wet, &
                                     slave_surface=model%surfaces(model%pairs(ip_)%slave)%name, &
                                     master_surface=model%surfaces(model%pairs(ip_)%master)%name, &
                                     roles_swapped=model%pairs(ip_)%roles_swapped)
            if (allocated(error)) return
         end do
      end associate
      ! the contact iterations of the increment just solved: a frame's own, and at the
      ! step's end those of its last increment
      call rs%h5%write_iterations(istep, rs%sys%records, error)
      if (allocated(error)) return
      if (frame > 0) return
      write (buf, '(2x,a,i0,a,i0,a,es12.4,a,es12.4)') 'contact: ', count(rs%contact%active), ' of ', rs%contact%n, &
         ' slave nodes closed, max pressure ', rs%contact%max_pressure(), ', max penetration ', &
         rs%contact%max_penetration()
      call log%say(trim(buf))
      if (rs%contact%fric%on) then
         write (buf, '(2x,a,i0,a,i0,a)') 'friction: ', rs%contact%count_state(tangent_stick), ' stick, ', &
            rs%contact%count_state(tangent_slip), ' slip'
         call log%say(trim(buf))
      end if
   end subroutine write_contact_results

   !> The friction coefficient and cohesion of pair ip_ in force in step istep: those
   !> of its interaction (or of a *CHANGE FRICTION), divided by the factor of safety in a strength reduction step.
   function strength_in_force(model, rs, istep, ip_) result(s)
      type(model_t), intent(in) :: model
      type(run_state_t), intent(in) :: rs
      integer, intent(in) :: istep, ip_
      real(wp) :: s(2)
      real(wp) :: f
      f = 1.0_wp
      if (model%steps(istep)%procedure == procedure_strength_reduction) f = rs%srm%f_lower
      call reduced_strength(model, model%steps(istep)%srm, rs%contact, ip_, f, s(1), s(2))
   end function strength_in_force

   !> The factor of safety of a strength reduction step in the log.
   subroutine say_factor(log, srm)
      type(logger_t), intent(inout) :: log
      type(srm_result_t), intent(in) :: srm
      character(len=200) :: buf
      if (srm%f_upper >= huge(1.0_wp)) then
         write (buf, '(2x,a,f12.6,a,i0,a)') 'factor of safety >= ', srm%f_lower, &
            ' (equilibrium up to the largest factor; ', size(srm%f), ' trials)'
      else
         write (buf, '(2x,a,f12.6,a,f12.6,a,f12.6,a,es9.2,a,i0,a,i0,a)') 'factor of safety ', srm%f_lower, &
            ' (equilibrium at F = ', srm%f_lower, ', none at F = ', srm%f_upper, '; tolerance ', srm%tolerance, &
            '; ', size(srm%f), ' trials, ', srm%factorizations, ' factorizations)'
      end if
      call log%say(trim(buf))
   end subroutine say_factor

   !> A strength reduction step's trials: /steps/NNNN/strength_reduction and the step
   !> attribute factor_of_safety in JOB.h5, JOB_srm_NNNN.csv.
   subroutine write_srm(rs, istep, error)
      type(run_state_t), intent(inout) :: rs
      integer, intent(in) :: istep
      type(error_t), allocatable, intent(out) :: error
      real(wp) :: upper
      associate (r => rs%srm)
         upper = r%f_upper
         if (upper >= huge(1.0_wp)) upper = ieee_value(upper, ieee_positive_inf)
         call rs%h5%write_strength_reduction(istep, r%f, r%converged, r%u_char, r%iterations, r%tolerance, &
                                             r%f_lower, upper, error)
         if (allocated(error)) return
         call write_srm_csv(rs%base//'_srm_'//frame_suffix(istep, 0)//'.csv', r%f, r%converged, r%u_char, &
                            r%iterations, r%reason, error)
      end associate
   end subroutine write_srm

   !> The converged increments of step istep in /steps/NNNN/increments.
   subroutine write_increments(rs, istep, error)
      type(run_state_t), intent(inout) :: rs
      integer, intent(in) :: istep
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: step_time(:), increment_time(:)
      integer, allocatable :: attempt(:), iterations(:)
      call rs%sta%of_step(istep, step_time, increment_time, attempt, iterations)
      call rs%h5%write_increments(istep, step_time, increment_time, attempt, iterations, error)
   end subroutine write_increments

   !> NNNN (the step, four digits or more) or NNNN_MMMM for increment `frame` > 0.
   pure function frame_suffix(istep, frame) result(s)
      integer, intent(in) :: istep, frame
      character(len=:), allocatable :: s
      character(len=24) :: b
      ! four digits, more beyond 9999 (as the HDF5 groups)
      call put(istep, b)
      s = trim(b)
      if (frame <= 0) return
      call put(frame, b)
      s = s//'_'//trim(b)
   contains
      !> i4.4, or i0 when it does not fit
      pure subroutine put(v, t)
         integer, intent(in) :: v
         character(len=*), intent(out) :: t
         if (v <= 9999) then
            write (t, '(i4.4)') v
         else
            write (t, '(i0)') v
         end if
      end subroutine put
   end function frame_suffix

   !> "estimated relative energy error 2.3 %; 50 % of it in 4.1 % of the cells, around (x, y)"
   subroutine say_estimate(log, e)
      type(logger_t), intent(inout) :: log
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
   subroutine log_reactions(log, rf, fext, names, totals)
      type(logger_t), intent(inout) :: log
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

   !> The step's NAME=, else Step-i.
   function step_name(model, i) result(s)
      type(model_t), intent(in) :: model
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
end module vemcontact_driver_static
