!> The vemcontact program: command line, results folder, log, deck, analysis,
!> exit status.  Before anything in the results folder is touched the job's lock
!> JOB.lock is taken (a second run of the job into the same folder stops with
!> exit status 2 and changes nothing); then the previous run's result files of
!> the job are removed, so that none of them can be taken for this run's.
!> Exit status: 0 success, 1 bad input, 2 file error, 3 model not solvable,
!> 4 solver failure, 5 internal error, 130 stopped by SIGINT (Ctrl-C), 143 stopped by
!> SIGTERM (128 + the signal number: the results of the completed steps are kept,
!> docs/output-format.md).
program vemcontact_main
   use vemcontact_kinds, only: wp, i8
   use vemcontact_error, only: error_t, fatal_error, err_input, err_model, err_solver
   use vemcontact_model, only: model_t, plane_strain
   use vemcontact_app_cli, only: cli_t, parse_command_line, usage_text, version_text
   use vemcontact_log, only: logger_t
   use vemcontact_clock, only: wall_time
   use vemcontact_app_process, only: exit_process, make_directory, pause_seconds
   use vemcontact_safe_file, only: job_lock_t, lock_job, remove_job_files
   use vemcontact_text, only: escape_controls, cap_lines
   use vemcontact_deck_reader, only: read_deck
   use vemcontact_driver_static, only: run_options_t, run_static
   use vemcontact_solver_factory, only: uses_petsc, solver_auto, solver_gamg, solver_cholmod, solver_kind, &
      auto_solver, auto_gamg_unknowns, auto_gamg_poisson
   use vemcontact_solver_petsc, only: petsc_initialize, petsc_finalize, petsc_abort, petsc_ranks, petsc_rank, &
      mpi_launched
   use vemcontact_output_phases, only: write_phases
   use vemcontact_app_blas_threads, only: set_blas_threads
   use vemcontact_interrupt, only: install_interrupt_handlers, interrupt_error, interrupt_context, is_interrupt, &
      stop_signal
   use vemcontact_solver_stop, only: agreed_stop_signal
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   implicit none
   type(cli_t) :: cli
   type(error_t), allocatable :: error
   type(logger_t) :: log
   type(model_t) :: model
   type(run_options_t) :: opts
   type(job_lock_t) :: lock
   real(wp) :: tstart
   integer :: nremoved, iw, rank
   logical :: solver_chosen
   !> the solver was chosen by `auto` (choose_solver)
   logical :: auto_chosen = .false.
   !> Whether an error now is met by every process alike (the command line, reading the
   !> deck and choosing the solver: the same on all): then rank 0 reports it and all end
   !> normally; any other error may be one process's alone (rank 0's lock, log and
   !> files, the analysis, ...) and ends all of them (MPI_Abort).
   logical :: collective_phase = .true.
   !> Seconds a process other than rank 0 waits before it reports a model or input error
   !> itself (fail): rank 0, meeting the same error, normally ends the run before.
   integer, parameter :: rank0_grace_s = 3
   character(len=:), allocatable :: job, note
   character(len=16) :: buf

   ! SIGINT and SIGTERM stop the run at the next safe point (vemcontact_interrupt)
   call install_interrupt_handlers()
   call parse_command_line(cli, error)
   if (allocated(error)) call fail(error)
   if (cli%help) then
      write (output_unit, '(a)') usage_text()
      call exit_process(0)
   end if
   if (cli%version) then
      write (output_unit, '(a)') version_text()
      call exit_process(0)
   end if

   tstart = wall_time()
   ! PETSc and MPI only for a PETSc solver or under an MPI launcher: the default run
   ! never starts MPI.  With several processes every one runs the analysis (the
   ! element loop, the assembly and the solves are distributed); rank 0 alone
   ! post-processes and writes: the others touch no file.
   rank = 0
   job = cli%job
   ! the command line's --solver wins over the deck's *STATIC, SOLVER=
   solver_chosen = cli%solver /= solver_auto
   if (uses_petsc(cli%solver) .or. mpi_launched()) then
      call petsc_initialize(cli%petsc_options, error)
      if (allocated(error)) call fail(error)
      ! PETSc installs its own handler for SIGTERM
      call install_interrupt_handlers()
      if (petsc_ranks() > 1) then
         if (cli%solver == solver_auto) cli%solver = solver_gamg
         if (.not. uses_petsc(cli%solver)) then
            call fatal_error(error, 'error: --solver cholmod runs on one process; under an MPI launcher '// &
                             'with several processes use --solver gamg, hypre or mumps', err_input)
            call fail(error)
         end if
         rank = petsc_rank()
      end if
   end if
   ! rank 0's files: their errors are its own
   collective_phase = .false.
   if (rank == 0) then
      call make_directory(cli%out_dir, error)
      if (allocated(error)) call fail(error)
      ! held until the process ends
      call lock_job(cli%out_dir//'/'//job//'.lock', lock, error)
      if (allocated(error)) call fail(error)
      call remove_job_files(cli%out_dir, job, nremoved, error)
      if (allocated(error)) call fail(error)
   end if
   log%quiet = cli%quiet .or. rank > 0
   if (rank == 0) then
      call log%open(cli%out_dir//'/'//job//'.log', error)
      if (allocated(error)) call fail(error)
   end if
   call log%say(version_text()//': job '//cli%job//', deck '//cli%deck)
   call set_blas_threads(cli%blas_threads, note)
   call log%say('  '//note)
   ! the phases are laps from here to the end (vemcontact_log): they add up to the total
   call log%start_clock(tstart)
   ! results folder, lock, removal of the previous results, log
   call log%lap('start')

   collective_phase = .true.
   call read_deck(cli%deck, model, error)
   if (allocated(error)) call fail(error)
   ! valid input that is partly ignored (output variables vemcontact does not compute, ...)
   do iw = 1, size(model%warnings)
      call log%say(cap_lines(model%warnings(iw)%s))
   end do
   call choose_solver()
   ! reading ends with the choice of solver (and PETSc's start for it)
   call log%lap('read')
   iw = agreed_stop_signal()
   if (iw > 0) then
      call interrupt_error(iw, 'after reading the deck', error)
      call interrupt_context(error, '', 0)
      call fail(error)
   end if

   collective_phase = .false.
   opts%out_dir = cli%out_dir
   opts%job = job
   opts%ordering = cli%ordering
   opts%solver = cli%solver
   opts%solver_fallback = auto_chosen .and. uses_petsc(cli%solver)
   opts%write_matrix = cli%write_matrix
   opts%compress_vtu = cli%compress_vtu
   opts%write_vtu = cli%write_vtu
   opts%write_files = rank == 0
   call run_static(model, opts, log, error)
   if (allocated(error)) call fail(error)
   ! HDF5 file closed, factor, matrices and result arrays released (run_static's return)
   call log%lap('finish')
   call log%phase('total', wall_time() - tstart)
   if (rank == 0) then
      call write_phases(cli%out_dir//'/'//job//'_phases.csv', log, error)
      if (allocated(error)) call fail(error)
      call log%close(error)
      if (allocated(error)) call fail(error)
   end if
   call petsc_finalize()
   call exit_process(0)

contains

   !> The solver once the deck is read: --solver, else the deck's *STATIC, SOLVER=, else
   !> `auto` (vemcontact_solver_factory's auto_solver: by unknowns, contact pairs and
   !> processes, logged with the reason).  PETSc is started for a PETSc solver (under an
   !> MPI launcher it already is); a gamg that auto chose falls back to cholmod when
   !> PETSc cannot start (a build without it).
   subroutine choose_solver()
      logical :: auto, has_contact
      integer(i8) :: unknowns
      real(wp) :: nu
      character(len=120) :: why
      if (.not. solver_chosen .and. allocated(model%linear_solver)) then
         cli%solver = solver_kind(model%linear_solver)
         if (petsc_ranks() > 1 .and. .not. uses_petsc(cli%solver)) then
            call fatal_error(error, 'error: SOLVER=CHOLMOD (*STATIC) runs on one process; under an MPI launcher '// &
                             'with several processes use GAMG, HYPRE or MUMPS', err_input)
            call fail(error)
         end if
      end if
      auto = cli%solver == solver_auto
      auto_chosen = auto
      if (auto) then
         has_contact = .false.
         if (allocated(model%pairs)) has_contact = size(model%pairs) > 0
         unknowns = 2_i8*model%nnode
         nu = plane_strain_poisson(model)
         cli%solver = auto_solver(unknowns, petsc_ranks(), has_contact, nu)
         if (petsc_ranks() > 1) then
            why = 'several processes'
         else if (has_contact) then
            write (why, '(i0,a)') unknowns, ' unknowns, contact pairs: a direct solver for the contact iteration'
         else if (unknowns >= auto_gamg_unknowns .and. nu > auto_gamg_poisson) then
            write (why, '(i0,a,f6.4,a,f4.2,a)') unknowns, ' unknowns, plane strain with nu = ', nu, ' > ', &
               auto_gamg_poisson, ': CG would need many iterations'
         else if (cli%solver == solver_gamg) then
            write (why, '(i0,a,i0,a)') unknowns, ' unknowns >= ', auto_gamg_unknowns, ' (measured crossover)'
         else
            write (why, '(i0,a,i0)') unknowns, ' unknowns < ', auto_gamg_unknowns
         end if
      end if
      if (uses_petsc(cli%solver)) then
         call petsc_initialize(cli%petsc_options, error)
         call install_interrupt_handlers()
         if (allocated(error)) then
            if (.not. auto) call fail(error)
            deallocate (error)
            cli%solver = solver_cholmod
            why = trim(why)//', but built without PETSc (or it could not start)'
         end if
      end if
      if (auto) call log%say('  solver auto: '//trim(merge('gamg   ', 'cholmod', cli%solver == solver_gamg))// &
                             ' ('//trim(why)//')')
   end subroutine choose_solver

   !> The largest Poisson ratio of the materials of plane-strain elements (0 if none).
   pure real(wp) function plane_strain_poisson(m) result(nu)
      type(model_t), intent(in) :: m
      integer :: e
      nu = 0.0_wp
      if (.not. allocated(m%elem_mat) .or. .not. allocated(m%elem_plane) .or. .not. allocated(m%materials)) return
      do e = 1, m%nelem
         if (m%elem_plane(e) /= plane_strain .or. m%elem_mat(e) < 1) cycle
         nu = max(nu, m%materials(m%elem_mat(e))%poisson)
      end do
   end function plane_strain_poisson

   !> Report the error on stderr and in the log, then end with its status.  With
   !> several MPI processes an error of the collective phase is reported by rank 0
   !> alone; a later one by the process that met it, which then ends all of them.
   !> A later error of the model or the input (a floating part, a bad element) is met
   !> by every process at the same point, as all hold the same model, and so is a
   !> solver's failure (PETSc's convergence test and its set-up failures are collective):
   !> a process other than rank 0 waits a moment first, so that rank 0 reports it
   !> without the prefix and ends the run; it reports the error itself only if that
   !> does not happen.
   subroutine fail(err)
      type(error_t), intent(in) :: err
      integer :: r
      r = petsc_rank()
      ! every process stops at the same safe point on SIGINT/SIGTERM: rank 0 reports
      if (is_interrupt(err%code)) collective_phase = .true.
      if (r > 0 .and. .not. collective_phase .and. (err%code == err_input .or. err%code == err_model .or. &
                                             err%code == err_solver)) then
         call pause_seconds(rank0_grace_s)
         ! the launcher ends this process (SIGTERM) once rank 0 has reported and ended:
         ! then end without a second report
         if (stop_signal() > 0) call exit_process(err%code, now=.true.)
      end if
      if (r == 0) then
         write (error_unit, '(a)') escape_controls(cap_lines(err%message))
      else if (.not. collective_phase) then
         write (buf, '(i0)') r
         write (error_unit, '(a)') 'MPI rank '//trim(buf)//': '//escape_controls(cap_lines(err%message))
      end if
      if (log%opened) then
         log%quiet = .true.
         call log%say(cap_lines(err%message))
         call log%close()
      end if
      flush (error_unit)
      if (.not. collective_phase .and. petsc_ranks() > 1) call petsc_abort(err%code)
      call petsc_finalize()
      call exit_process(err%code, now=.true.)
   end subroutine fail
end program vemcontact_main
