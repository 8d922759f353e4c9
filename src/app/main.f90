!> The vemcontact program: command line, results folder, log, deck, analysis,
!> exit status.  Before anything in the results folder is touched the job's lock
!> JOB.lock is taken (a second run of the job into the same folder stops with
!> exit status 2 and changes nothing); then the previous run's result files of
!> the job are removed, so that none of them can be taken for this run's.
!> Exit status: 0 success, 1 bad input, 2 file error, 3 model not solvable,
!> 4 solver failure, 5 internal error.
program vemcontact_main
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t
   use vemcontact_app_cli, only: cli_t, parse_command_line, usage_text, version_text
   use vemcontact_log, only: logger_t
   use vemcontact_clock, only: wall_time
   use vemcontact_app_process, only: exit_process, make_directory
   use vemcontact_safe_file, only: job_lock_t, lock_job, remove_job_files
   use vemcontact_text, only: escape_controls
   use vemcontact_deck_reader, only: read_deck
   use vemcontact_driver_static, only: run_options_t, run_static
   use vemcontact_output_phases, only: write_phases
   use vemcontact_app_blas_threads, only: set_blas_threads
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   implicit none
   type(cli_t) :: cli
   type(error_t), allocatable :: error
   type(logger_t) :: log
   type(model_t) :: model
   type(run_options_t) :: opts
   type(job_lock_t) :: lock
   real(wp) :: tstart
   character(len=:), allocatable :: note
   integer :: nremoved, iw

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
   call make_directory(cli%out_dir, error)
   if (allocated(error)) call fail(error)
   ! held until the process ends
   call lock_job(cli%out_dir//'/'//cli%job//'.lock', lock, error)
   if (allocated(error)) call fail(error)
   call remove_job_files(cli%out_dir, cli%job, nremoved, error)
   if (allocated(error)) call fail(error)
   log%quiet = cli%quiet
   call log%open(cli%out_dir//'/'//cli%job//'.log', error)
   if (allocated(error)) call fail(error)
   call log%say(version_text()//': job '//cli%job//', deck '//cli%deck)
   call set_blas_threads(cli%blas_threads, note)
   call log%say('  '//note)
   ! the phases are laps from here to the end (vemcontact_log): they add up to the total
   call log%start_clock(tstart)
   ! results folder, lock, removal of the previous results, log
   call log%lap('start')

   call read_deck(cli%deck, model, error)
   if (allocated(error)) call fail(error)
   ! valid input that is partly ignored (output variables vemcontact does not compute, ...)
   do iw = 1, size(model%warnings)
      call log%say(model%warnings(iw)%s)
   end do
   call log%lap('read')

   opts%out_dir = cli%out_dir
   opts%job = cli%job
   opts%ordering = cli%ordering
   opts%write_matrix = cli%write_matrix
   opts%compress_vtu = cli%compress_vtu
   call run_static(model, opts, log, error)
   if (allocated(error)) call fail(error)
   ! HDF5 file closed, factor, matrices and result arrays released (run_static's return)
   call log%lap('finish')
   call log%phase('total', wall_time() - tstart)
   call write_phases(cli%out_dir//'/'//cli%job//'_phases.csv', log, error)
   if (allocated(error)) call fail(error)
   call log%close(error)
   if (allocated(error)) call fail(error)
   call exit_process(0)

contains

   !> Report the error on stderr and in the log, then end with its status.
   subroutine fail(err)
      type(error_t), intent(in) :: err
      write (error_unit, '(a)') escape_controls(err%message)
      if (log%opened) then
         log%quiet = .true.
         call log%say(err%message)
         call log%close()
      end if
      call exit_process(err%code)
   end subroutine fail
end program vemcontact_main
