!> The `linear_solver_t` backends on PETSc (petsc_shim.c): conjugate gradients
!> preconditioned by PETSc's algebraic multigrid GAMG (with the rigid-body near
!> null space of the node coordinates), CG preconditioned by hypre's BoomerAMG,
!> and MUMPS's sparse Cholesky factorization.
!>
!> PETSc, and with it MPI, is started by `petsc_initialize` (the program does so
!> when a PETSc solver is chosen) or at the first `analyze`; a run with CHOLMOD
!> never starts it.  PETSc's options database (the PETSC_OPTIONS environment
!> variable, the string given to petsc_initialize) overrides the defaults below,
!> for example `-ksp_rtol 1e-12` or `-pc_gamg_threshold 0.02`.
!>
!> Under MPI every process runs the driver with the same data and calls these
!> procedures together; the matrix and the solve are distributed by rows.  With
!> `owned_dofs` set, each process owns that many rows (the driver's partition of
!> the mesh); with `shares`, each passes its share of the matrix (the driver
!> assembles only its own elements) and PETSc adds the shares.
!>
!> Stopping rule of CG: the true (unpreconditioned) residual |b - A x|_2 <=
!> rtol |b|_2 with rtol = 1e-10 (`default_rtol`).  The relative error of x is
!> at most cond(A) rtol; the stiffness matrices of 1e5-1e6 unknowns have
!> cond(A) of about 1e6-1e8 (h^-2 growth), so the bound is 1e-4-1e-2 but the
!> error in the energy norm CG minimizes is far smaller: measured against CHOLMOD,
!> the displacements agree to 1e-8-1e-9 (docs/performance.md), below the
!> discretization error of those meshes (1e-6 at best).  The contact iteration
!> refines every frozen-pairing solve once (iteration.f90), which removes most of
!> the rest.
!>
!> A solver owns C memory: release it with `release` (or let it be finalized);
!> never copy one with intrinsic assignment.
module vemcontact_solver_petsc
   use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_int32_t, &
      c_int64_t, c_double, c_char, c_null_char
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_solver, err_internal, err_input
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_solver_linear_solver, only: linear_solver_t, check_matrix_arrays
   implicit none
   private

   public :: petsc_solver_t, petsc_initialize, petsc_finalize, petsc_abort, petsc_ranks, petsc_rank, mpi_launched, &
      petsc_sum

   !> The methods: CG + GAMG, CG + hypre BoomerAMG, MUMPS Cholesky (petsc_shim.c's kinds).
   integer, parameter, public :: petsc_gamg = 1, petsc_hypre = 2, petsc_mumps = 3
   !> CG's relative residual at which it stops (see the module's description).
   real(wp), parameter, public :: default_rtol = 1.0e-10_wp

   ! Status codes of petsc_shim.c.
   integer(c_int), parameter :: st_ok = 0, st_not_built = 1, st_error = 2, st_diverged = 3, &
      st_bad_input = 4, st_order = 5, st_nomem = 6

   !> A PETSc solver of the method `method` (petsc_gamg, petsc_hypre or petsc_mumps).
   type, extends(linear_solver_t) :: petsc_solver_t
      integer :: method = petsc_gamg
      !> CG's stopping rule: |b - A x| <= rtol |b|
      real(wp) :: rtol = default_rtol
      !> CG's iteration limit
      integer :: max_iterations = 10000
      !> CG iterations of the last solve (the largest over its right-hand sides)
      integer :: iterations = 0
      type(c_ptr), private :: handle = c_null_ptr
   contains
      procedure :: analyze
      procedure :: factorize
      procedure :: solve_one
      procedure :: solve_many
      procedure :: rcond
      procedure :: release
      procedure :: describe
      procedure :: sum_over_ranks
      final :: finalize
   end type petsc_solver_t

   interface
      integer(c_int) function vc_petsc_initialize(options) bind(c, name='vc_petsc_initialize')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: options(*)
      end function vc_petsc_initialize

      subroutine vc_petsc_finalize() bind(c, name='vc_petsc_finalize')
      end subroutine vc_petsc_finalize

      subroutine vc_petsc_abort(code) bind(c, name='vc_petsc_abort')
         import :: c_int
         integer(c_int), value :: code
      end subroutine vc_petsc_abort

      integer(c_int) function vc_petsc_comm_size() bind(c, name='vc_petsc_comm_size')
         import :: c_int
      end function vc_petsc_comm_size

      integer(c_int) function vc_petsc_comm_rank() bind(c, name='vc_petsc_comm_rank')
         import :: c_int
      end function vc_petsc_comm_rank

      integer(c_int) function vc_petsc_create(handle, kind) bind(c, name='vc_petsc_create')
         import :: c_int, c_ptr
         type(c_ptr), intent(out) :: handle
         integer(c_int), value :: kind
      end function vc_petsc_create

      subroutine vc_petsc_free(handle) bind(c, name='vc_petsc_free')
         import :: c_ptr
         type(c_ptr), intent(inout) :: handle
      end subroutine vc_petsc_free

      subroutine vc_petsc_message(handle, buf, len) bind(c, name='vc_petsc_message')
         import :: c_ptr, c_char, c_int
         type(c_ptr), value :: handle
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_int), value :: len
      end subroutine vc_petsc_message

      integer(c_int) function vc_petsc_analyze(handle, n, col_ptr, row_idx, coords, has_coords, perm, has_perm, &
                                               info) bind(c, name='vc_petsc_analyze')
         import :: c_int, c_ptr, c_int64_t, c_int32_t, c_double
         type(c_ptr), value :: handle
         integer(c_int64_t), value :: n
         integer(c_int64_t), intent(in) :: col_ptr(*)
         integer(c_int32_t), intent(in) :: row_idx(*)
         real(c_double), intent(in) :: coords(*)
         integer(c_int), value :: has_coords
         integer(c_int32_t), intent(in) :: perm(*)
         integer(c_int), value :: has_perm
         integer(c_int64_t), intent(out) :: info
      end function vc_petsc_analyze

      integer(c_int) function vc_petsc_factorize(handle, n, nnz, val, rtol, maxit) bind(c, name='vc_petsc_factorize')
         import :: c_int, c_ptr, c_int64_t, c_double
         type(c_ptr), value :: handle
         integer(c_int64_t), value :: n, nnz
         real(c_double), intent(in) :: val(*)
         real(c_double), value :: rtol
         integer(c_int), value :: maxit
      end function vc_petsc_factorize

      integer(c_int) function vc_petsc_solve(handle, n, nrhs, b, x, info) bind(c, name='vc_petsc_solve')
         import :: c_int, c_ptr, c_int64_t, c_double
         type(c_ptr), value :: handle
         integer(c_int64_t), value :: n, nrhs
         real(c_double), intent(in) :: b(*)
         real(c_double), intent(out) :: x(*)
         integer(c_int64_t), intent(out) :: info
      end function vc_petsc_solve

      integer(c_int) function vc_petsc_iterations(handle) bind(c, name='vc_petsc_iterations')
         import :: c_int, c_ptr
         type(c_ptr), value :: handle
      end function vc_petsc_iterations

      integer(c_int) function vc_petsc_distribute(handle, own_dofs, shares) bind(c, name='vc_petsc_distribute')
         import :: c_int, c_ptr, c_int64_t
         type(c_ptr), value :: handle
         integer(c_int64_t), value :: own_dofs
         integer(c_int), value :: shares
      end function vc_petsc_distribute

      integer(c_int) function vc_petsc_sum(x, n) bind(c, name='vc_petsc_sum')
         import :: c_int, c_int64_t, c_double
         real(c_double), intent(inout) :: x(*)
         integer(c_int64_t), value :: n
      end function vc_petsc_sum

   end interface

contains

   !> Start PETSc (and MPI) with PETSc's options `options` ('-pc_gamg_threshold 0.02 ...')
   !> added to its database; nothing when it runs already.
   subroutine petsc_initialize(options, error)
      character(len=*), intent(in) :: options
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: st
      st = vc_petsc_initialize(options//c_null_char)
      if (st /= st_ok) call fatal_error(error, 'error: '//status_text(st, c_null_ptr), err_input)
   end subroutine petsc_initialize

   !> End PETSc and MPI if petsc_initialize (or an analysis) started them.
   subroutine petsc_finalize()
      call vc_petsc_finalize()
   end subroutine petsc_finalize

   !> End all MPI processes of the run with status `code` (MPI_Abort): for an error
   !> that one process meets while the others may wait for it in a collective
   !> operation.  Returns only when MPI is not running.
   subroutine petsc_abort(code)
      integer, intent(in) :: code
      call vc_petsc_abort(int(code, c_int))
   end subroutine petsc_abort

   !> The number of MPI processes (1 while PETSc is not running).
   integer function petsc_ranks()
      petsc_ranks = int(vc_petsc_comm_size())
   end function petsc_ranks

   !> x = the sum of x over the processes (MPI_Allreduce; nothing while PETSc is not
   !> running or on one process).  `ok` is false when the reduction failed.
   subroutine petsc_sum(x, ok)
      real(wp), intent(inout) :: x(:)
      logical, intent(out) :: ok
      ok = .true.
      if (size(x) == 0) return
      ok = vc_petsc_sum(x, int(size(x), c_int64_t)) == st_ok
   end subroutine petsc_sum

   !> This process's MPI rank (0 while PETSc is not running).
   integer function petsc_rank()
      petsc_rank = int(vc_petsc_comm_rank())
   end function petsc_rank

   !> Whether the program was started by an MPI launcher (mpirun, mpiexec, srun):
   !> the variables Open MPI, MPICH and PMIx set for the processes they start.
   logical function mpi_launched()
      character(len=*), parameter :: names(4) = [character(len=20) :: 'OMPI_COMM_WORLD_SIZE', 'PMI_SIZE', &
         'PMIX_RANK', 'PMI_RANK']
      integer :: k, st
      mpi_launched = .false.
      do k = 1, size(names)
         call get_environment_variable(trim(names(k)), status=st)
         if (st == 0) mpi_launched = .true.
      end do
   end function mpi_launched

   !> The matrix of the pattern of `a` and the solver; for GAMG, the near null
   !> space of the rigid-body motions of the nodes `coords(2, nnode)`.  `perm`
   !> numbers the dofs for PETSc, node by node: with several MPI processes each owns
   !> a contiguous share of it, `owned_dofs` long (the driver's partition of the
   !> mesh: each share a part), or an even split without `owned_dofs`; PETSc's
   !> solvers order for themselves.
   subroutine analyze(self, a, error, perm, coords)
      class(petsc_solver_t), intent(inout) :: self
      type(sym_csc_t), intent(in) :: a
      type(error_t), allocatable, intent(out) :: error
      integer(ip), intent(in), optional :: perm(:)
      real(wp), intent(in), optional :: coords(:, :)
      integer(c_int) :: st
      integer(c_int64_t) :: info
      real(c_double) :: none(1)
      integer(c_int32_t) :: no_perm(1)
      integer(c_int) :: has_perm
      character(len=24) :: buf

      self%failed_column = 0
      self%nnz_factor = 0
      self%flops = 0.0_wp
      self%iterations = 0
      call check_matrix_arrays(a, .false., 'PETSc', error)
      if (allocated(error)) return
      st = vc_petsc_initialize(c_null_char)
      if (st /= st_ok) then
         call fatal_error(error, 'error: '//status_text(st, c_null_ptr), err_solver)
         return
      end if
      call vc_petsc_free(self%handle)
      st = vc_petsc_create(self%handle, int(self%method, c_int))
      if (st /= st_ok) then
         call fatal_error(error, 'error: '//status_text(st, c_null_ptr), err_solver)
         return
      end if
      st = vc_petsc_distribute(self%handle, int(self%owned_dofs, c_int64_t), merge(1_c_int, 0_c_int, self%shares))
      if (st /= st_ok) then
         call fatal_error(error, 'error: '//status_text(st, c_null_ptr), err_solver)
         return
      end if
      none = 0.0_c_double
      no_perm = 0
      has_perm = 0
      if (present(perm)) then
         if (size(perm) /= a%n) then
            call fatal_error(error, 'PETSc analyze: permutation has the wrong length', err_internal)
            return
         end if
         has_perm = 1
      end if
      if (present(coords)) then
         if (size(coords, kind=i8) /= int(a%n, i8)) then
            call fatal_error(error, 'PETSc analyze: coordinates do not match the matrix order', err_internal)
            return
         end if
      end if
      if (present(coords) .and. present(perm)) then
         st = vc_petsc_analyze(self%handle, int(a%n, c_int64_t), a%col_ptr, a%row_idx, coords, 1_c_int, perm, &
                               has_perm, info)
      else if (present(coords)) then
         st = vc_petsc_analyze(self%handle, int(a%n, c_int64_t), a%col_ptr, a%row_idx, coords, 1_c_int, no_perm, &
                               has_perm, info)
      else if (present(perm)) then
         st = vc_petsc_analyze(self%handle, int(a%n, c_int64_t), a%col_ptr, a%row_idx, none, 0_c_int, perm, &
                               has_perm, info)
      else
         st = vc_petsc_analyze(self%handle, int(a%n, c_int64_t), a%col_ptr, a%row_idx, none, 0_c_int, no_perm, &
                               has_perm, info)
      end if
      if (st == st_bad_input) then
         write (buf, '(i0)') info
         call fatal_error(error, 'PETSc analyze: invalid upper-triangle pattern or permutation at column/'// &
                          'position '//trim(buf), err_internal)
      else if (st /= st_ok) then
         call fatal_error(error, 'error: PETSc analysis failed: '//status_text(st, self%handle), err_solver)
      end if
   end subroutine analyze

   !> The values of `a` (the analysed pattern) and the preconditioner (GAMG,
   !> hypre) or the factorization (MUMPS).
   subroutine factorize(self, a, error)
      class(petsc_solver_t), intent(inout) :: self
      type(sym_csc_t), intent(in) :: a
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: st
      self%failed_column = 0
      if (.not. c_associated(self%handle)) then
         call fatal_error(error, 'PETSc factorize called before analyze', err_internal)
         return
      end if
      call check_matrix_arrays(a, .true., 'PETSc', error)
      if (allocated(error)) return
      st = vc_petsc_factorize(self%handle, int(a%n, c_int64_t), int(a%col_ptr(a%n + 1) - 1, c_int64_t), a%val, &
                              real(self%rtol, c_double), int(self%max_iterations, c_int))
      if (st == st_order) then
         call fatal_error(error, 'PETSc factorize called before analyze', err_internal)
      else if (st == st_bad_input) then
         call fatal_error(error, 'PETSc factorize: the matrix differs in order or number of entries '// &
                          'from the analysed pattern', err_internal)
      else if (st /= st_ok) then
         call fatal_error(error, 'error: PETSc '//self%describe()//' set-up failed: '// &
                          status_text(st, self%handle), err_solver)
      end if
   end subroutine factorize

   !> x = A^-1 b.
   subroutine solve_one(self, b, x, error)
      class(petsc_solver_t), intent(inout) :: self
      real(wp), intent(in) :: b(:)
      real(wp), intent(out) :: x(:)
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: st
      integer(c_int64_t) :: info
      if (size(x) /= size(b)) then
         call fatal_error(error, 'PETSc solve: b and x differ in length', err_internal)
         return
      end if
      st = vc_petsc_solve(self%handle, int(size(b), c_int64_t), 1_c_int64_t, b, x, info)
      self%iterations = int(vc_petsc_iterations(self%handle))
      call solve_status(self, st, error)
   end subroutine solve_one

   !> x(:, k) = A^-1 b(:, k) for every column k.
   subroutine solve_many(self, b, x, error)
      class(petsc_solver_t), intent(inout) :: self
      real(wp), intent(in) :: b(:, :)
      real(wp), intent(out) :: x(:, :)
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: st
      integer(c_int64_t) :: info
      if (any(shape(x) /= shape(b))) then
         call fatal_error(error, 'PETSc solve: b and x differ in shape', err_internal)
         return
      end if
      st = vc_petsc_solve(self%handle, int(size(b, 1), c_int64_t), int(size(b, 2), c_int64_t), b, x, info)
      self%iterations = int(vc_petsc_iterations(self%handle))
      call solve_status(self, st, error)
   end subroutine solve_many

   !> -1: no condition estimate.
   real(wp) function rcond(self)
      class(petsc_solver_t), intent(in) :: self
      ! CG has no condition estimate, and MUMPS's is not asked for: -1 with or without a solver
      rcond = merge(-1.0_wp, -1.0_wp, c_associated(self%handle))
   end function rcond

   !> Free the PETSc objects; the solver can be analysed again.  PETSc keeps running.
   subroutine release(self)
      class(petsc_solver_t), intent(inout) :: self
      call vc_petsc_free(self%handle)
      self%handle = c_null_ptr
      self%failed_column = 0
      self%nnz_factor = 0
      self%flops = 0.0_wp
      self%iterations = 0
   end subroutine release

   !> 'gamg (CG, rtol 1e-10)', 'hypre (CG, rtol 1e-10)' or 'mumps (Cholesky)'.
   function describe(self) result(s)
      class(petsc_solver_t), intent(in) :: self
      character(len=:), allocatable :: s
      character(len=16) :: buf
      write (buf, '(es8.1)') self%rtol
      select case (self%method)
      case (petsc_gamg)
         s = 'gamg (PETSc CG + GAMG, rtol '//trim(adjustl(buf))//')'
      case (petsc_hypre)
         s = 'hypre (PETSc CG + BoomerAMG, rtol '//trim(adjustl(buf))//')'
      case default
         s = 'mumps (PETSc + MUMPS Cholesky)'
      end select
      write (buf, '(i0)') vc_petsc_comm_size()
      if (vc_petsc_comm_size() > 1) s = s//' on '//trim(buf)//' MPI processes'
   end function describe

   !> x = the sum of x over the processes (MPI_Allreduce), the same on every process.
   subroutine sum_over_ranks(self, x, error)
      class(petsc_solver_t), intent(in) :: self
      real(wp), intent(inout) :: x(:)
      type(error_t), allocatable, intent(out) :: error
      if (self%processes == 1 .or. size(x) == 0) return
      if (vc_petsc_sum(x, int(size(x), c_int64_t)) /= st_ok) &
         call fatal_error(error, 'error: MPI_Allreduce failed in the sum over the processes', err_solver)
   end subroutine sum_over_ranks

   impure elemental subroutine finalize(self)
      type(petsc_solver_t), intent(inout) :: self
      call vc_petsc_free(self%handle)
      self%handle = c_null_ptr
   end subroutine finalize

   subroutine solve_status(self, st, error)
      class(petsc_solver_t), intent(in) :: self
      integer(c_int), intent(in) :: st
      type(error_t), allocatable, intent(out) :: error
      select case (st)
      case (st_ok)
      case (st_order)
         call fatal_error(error, 'PETSc solve called without a set-up solver', err_internal)
      case (st_bad_input)
         call fatal_error(error, 'PETSc solve: right-hand side length differs from the matrix order', &
                          err_internal)
      case (st_diverged)
         call fatal_error(error, 'error: the linear solver '//self%describe()//' did not converge: '// &
                          status_text(st, self%handle)//new_line('a')// &
                          '  = help: try --solver mumps or cholmod, or PETSc options such as -ksp_max_it', &
                          err_solver)
      case default
         call fatal_error(error, 'error: PETSc solve failed: '//status_text(st, self%handle), err_solver)
      end select
   end subroutine solve_status


   ! The shim's message for a status (PETSc's own text where there is one).
   function status_text(st, handle) result(s)
      integer(c_int), intent(in) :: st
      type(c_ptr), intent(in) :: handle
      character(len=:), allocatable :: s
      character(kind=c_char) :: buf(512)
      integer :: k
      select case (st)
      case (st_not_built)
         s = 'vemcontact was built without PETSc (install petsc-dev and rebuild to use --solver gamg, '// &
             'hypre or mumps)'
      case (st_nomem)
         s = 'out of memory'
      case default
         call vc_petsc_message(handle, buf, size(buf, kind=c_int))
         s = ''
         do k = 1, size(buf)
            if (buf(k) == c_null_char) exit
            s = s//buf(k)
         end do
         if (len(s) == 0) s = 'PETSc error'
      end select
   end function status_text
end module vemcontact_solver_petsc
