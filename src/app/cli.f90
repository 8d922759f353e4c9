!> Command line of the vemcontact program.
module vemcontact_app_cli
   use vemcontact_error, only: error_t, fatal_error, err_input
   use vemcontact_driver_linear, only: ordering_auto, ordering_metis, ordering_cholmod
   use vemcontact_solver_factory, only: solver_auto, solver_kind, solver_names
   use vemcontact_path, only: dirname
   implicit none
   private

   public :: cli_t, parse_command_line, usage_text, version_text

   !> Version of the program (kept in one place).
   character(len=*), parameter, public :: vemcontact_version = '0.1.0'

   type :: cli_t
      character(len=:), allocatable :: deck      !< path of the input deck
      character(len=:), allocatable :: out_dir   !< folder for results
      character(len=:), allocatable :: job       !< job name: deck file name without .inp
      logical :: help = .false.
      logical :: version = .false.
      logical :: quiet = .false.
      logical :: write_matrix = .false.
      logical :: compress_vtu = .true.           !< zlib-compressed .vtu arrays (--raw-vtu: not)
      logical :: write_vtu = .true.              !< .vtu and .pvd files (--no-vtu: JOB.h5 and JOB.xdmf only)
      integer :: ordering = ordering_auto
      integer :: solver = solver_auto            !< vemcontact_solver_factory's solver_*
      character(len=:), allocatable :: petsc_options  !< PETSc's own options, for the PETSc solvers
      integer :: blas_threads = 0                !< --blas-threads N; -1: auto; 0: the environment's or 1
   end type cli_t

contains

   function usage_text() result(s)
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      s = 'usage: vemcontact [options] DECK'//nl//nl// &
          '2D small-strain linear elasticity with the virtual element method (VEM) on'//nl// &
          'polygonal meshes, FEM baselines, for decks in Abaqus/CalculiX keyword syntax.'//nl//nl// &
          'Results are written next to the deck (or to -o DIR), named after the deck:'//nl// &
          '  JOB.pvd, JOB_NNNN.vtu (one per step), JOB.h5, JOB.xdmf, JOB.log'//nl//nl// &
          'options:'//nl// &
          '  -o, --output DIR      write results into DIR (created if missing)'//nl// &
          '  --ordering METHOD     fill-reducing ordering: auto (default), metis (METIS on'//nl// &
          '                        the node graph; fixed-pairing contact nodes last),'//nl// &
          '                        cholmod (CHOLMOD''s default strategy)'//nl// &
          '  --solver NAME         linear solver: auto (default: cholmod below 200000'//nl// &
          '                        unknowns or with contact, else gamg if built with'//nl// &
          '                        PETSc), cholmod (sparse Cholesky), and with PETSc:'//nl// &
          '                        gamg (CG + GAMG), hypre'//nl// &
          '                        (CG + BoomerAMG), mumps (MUMPS Cholesky)'//nl// &
          '  --petsc-options OPTS  PETSc''s own options for gamg, hypre, mumps, as one'//nl// &
          '                        string: "-ksp_rtol 1e-12 -pc_gamg_threshold 0.02"'//nl// &
          '  --blas-threads N|auto BLAS (OpenBLAS) threads of the factorization; default:'//nl// &
          '                        OPENBLAS_NUM_THREADS or OMP_NUM_THREADS if set, else 1'//nl// &
          '                        (results repeat to the bit); auto: the cores idle at'//nl// &
          '                        the start (cores minus the load average)'//nl// &
          '  --write-matrix        also write the first step''s matrix as JOB.mtx (Matrix Market)'//nl// &
          '  --raw-vtu             write the .vtu arrays uncompressed (default: zlib, as VTK''s'//nl// &
          '                        vtkZLibDataCompressor)'//nl// &
          '  --no-vtu              no .vtu/.pvd files: JOB.xdmf (ParaView, meshio) reads'//nl// &
          '                        the results in JOB.h5 instead'//nl// &
          '  -q, --quiet           log to JOB.log only'//nl// &
          '  -h, --help            show this help'//nl// &
          '  --version             show the version'
   end function usage_text

   function version_text() result(s)
      character(len=:), allocatable :: s
      s = 'vemcontact '//vemcontact_version
   end function version_text

   subroutine parse_command_line(cli, error)
      type(cli_t), intent(out) :: cli
      type(error_t), allocatable, intent(out) :: error
      integer :: i, n, stat
      character(len=:), allocatable :: arg
      n = command_argument_count()
      i = 0
      do while (i < n)
         i = i + 1
         call get_arg(i, arg)
         select case (arg)
         case ('-h', '--help')
            cli%help = .true.
         case ('--version')
            cli%version = .true.
         case ('-q', '--quiet')
            cli%quiet = .true.
         case ('--write-matrix')
            cli%write_matrix = .true.
         case ('--raw-vtu')
            cli%compress_vtu = .false.
         case ('--no-vtu')
            cli%write_vtu = .false.
         case ('-o', '--output', '--ordering', '--solver', '--petsc-options', '--blas-threads')
            if (i == n) then
               call fatal_error(error, 'error: option '//arg//' needs a value (see vemcontact --help)', err_input)
               return
            end if
            i = i + 1
            if (arg == '--blas-threads') then
               call get_arg(i, arg)
               if (arg == 'auto') then
                  cli%blas_threads = -1
               else
                  read (arg, *, iostat=stat) cli%blas_threads
                  if (stat /= 0 .or. verify(trim(arg), '0123456789') /= 0 .or. cli%blas_threads < 1) then
                     call fatal_error(error, 'error: --blas-threads takes auto or a whole number of at least 1, '// &
                                      'not "'//arg//'"', err_input)
                     return
                  end if
               end if
            else if (arg == '--ordering') then
               call get_arg(i, arg)
               select case (arg)
               case ('auto'); cli%ordering = ordering_auto
               case ('metis'); cli%ordering = ordering_metis
               case ('cholmod'); cli%ordering = ordering_cholmod
               case default
                  call fatal_error(error, 'error: --ordering takes auto, metis or cholmod, not "'//arg//'"', err_input)
                  return
               end select
            else if (arg == '--petsc-options') then
               call get_arg(i, cli%petsc_options)
            else if (arg == '--solver') then
               call get_arg(i, arg)
               cli%solver = solver_kind(arg)
               if (cli%solver < 0) then
                  call fatal_error(error, 'error: --solver takes '//solver_names()//', not "'//arg//'"', err_input)
                  return
               end if
            else
               call get_arg(i, cli%out_dir)
            end if
         case default
            if (len(arg) > 0) then
               if (arg(1:1) == '-') then
                  call fatal_error(error, 'error: unknown option '//arg//' (see vemcontact --help)', err_input)
                  return
               end if
            end if
            if (allocated(cli%deck)) then
               call fatal_error(error, 'error: one deck at a time: got "'//cli%deck//'" and "'//arg//'"', err_input)
               return
            end if
            cli%deck = arg
         end select
      end do
      if (.not. allocated(cli%petsc_options)) cli%petsc_options = ''
      if (cli%help .or. cli%version) return
      if (.not. allocated(cli%deck)) then
         call fatal_error(error, 'error: no input deck given'//new_line('a')//usage_text(), err_input)
         return
      end if
      if (.not. allocated(cli%out_dir)) then
         cli%out_dir = dirname(cli%deck)
         if (len(cli%out_dir) == 0) cli%out_dir = '.'
      end if
      cli%job = job_name(cli%deck)
   end subroutine parse_command_line

   subroutine get_arg(i, arg)
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: arg
      integer :: length
      call get_command_argument(i, length=length)
      allocate (character(len=length) :: arg)
      if (length > 0) call get_command_argument(i, arg)
   end subroutine get_arg


   !> File name without folder and without a trailing ".inp".
   pure function job_name(path) result(j)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: j
      integer :: k
      j = path(index(path, '/', back=.true.) + 1:)
      k = len(j)
      if (k > 4) then
         if (j(k - 3:) == '.inp' .or. j(k - 3:) == '.INP') j = j(:k - 4)
      end if
   end function job_name
end module vemcontact_app_cli
