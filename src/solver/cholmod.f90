!> Sparse Cholesky factorization of the global stiffness matrix with CHOLMOD:
!> the `linear_solver_t` backend `cholmod`.
!> The C shim `cholmod_shim.c` owns CHOLMOD's workspace, the copied matrix and
!> the factor behind an opaque handle; this module binds to it and wraps it in
!> `cholmod_solver_t`.  The usual sequence is one `analyze` (ordering and
!> symbolic factorization of the pattern) followed by any number of
!> `factorize`/`solve` pairs with changing values, as in the contact active-set
!> iterations.  The factor is always supernodal.
!>
!> A solver owns C memory: it is released by `release` or its final procedure.
!> Do not copy a solver with intrinsic assignment (both copies would own the
!> same handle); pass it by reference instead.  gfortran 12 does not finalize
!> local arrays of derived type: release solvers held in arrays explicitly.
module vemcontact_solver_cholmod
   use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_int32_t, &
      c_int64_t, c_double
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_solver, err_internal
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_solver_linear_solver, only: linear_solver_t, check_matrix_arrays
   use vemcontact_linalg_lapack, only: dpotrs
   implicit none
   private

   public :: cholmod_solver_t

   ! Status codes of cholmod_shim.c.
   integer(c_int), parameter :: st_ok = 0, st_nomem = 1, st_bad_input = 2, st_not_posdef = 3, &
      st_order = 4, st_mismatch = 5, st_too_large = 6

   !> CHOLMOD's ordering codes (cholmod_core.h), for `ordering_name`.
   !> The largest dense trailing block read for `solve_trailing` (values; 128 MB).
   real(wp), parameter :: trailing_max_values = 1.6e7_wp

   character(len=*), parameter :: ordering_names(0:6) = [character(len=11) :: 'natural', 'given', &
      'amd', 'metis', 'nesdis', 'colamd', 'postordered']

   !> Cholesky solver for a symmetric positive definite `sym_csc_t`.
   !> `nnz_factor` is nnz(L) without the explicit zeros of supernodes, `ordering`
   !> 'given', 'amd', 'metis', 'nesdis', ...
   type, extends(linear_solver_t) :: cholmod_solver_t
      !> Whether the factor is supernodal (always requested).
      logical :: supernodal = .false.
      type(c_ptr), private :: handle = c_null_ptr
      !> The factor's trailing block for `solve_trailing` (lower triangle of L from
      !> the first position of its dofs on) and the original dof of each of its
      !> positions; `trailing_state` 0: not read for this factor, 1: read, -1: too
      !> large or unavailable (full solves).
      real(wp), allocatable, private :: lt(:, :)
      integer(ip), allocatable, private :: tdof(:)
      integer, private :: trailing_state = 0
   contains
      procedure :: analyze
      procedure :: factorize
      procedure :: solve_one
      procedure :: solve_many
      procedure :: solve_trailing
      procedure :: rcond
      procedure :: release
      procedure :: describe
      final :: finalize
   end type cholmod_solver_t

   interface
      integer(c_int) function vc_cholmod_create(handle) bind(c, name='vc_cholmod_create')
         import :: c_int, c_ptr
         type(c_ptr), intent(out) :: handle
      end function vc_cholmod_create

      integer(c_int) function vc_cholmod_analyze(handle, n, col_ptr, row_idx, has_perm, perm, info) &
         bind(c, name='vc_cholmod_analyze')
         import :: c_int, c_ptr, c_int64_t, c_int32_t
         type(c_ptr), value :: handle
         integer(c_int64_t), value :: n
         integer(c_int64_t), intent(in) :: col_ptr(*)
         integer(c_int32_t), intent(in) :: row_idx(*)
         integer(c_int), value :: has_perm
         integer(c_int32_t), intent(in) :: perm(*)
         integer(c_int64_t), intent(out) :: info
      end function vc_cholmod_analyze

      integer(c_int) function vc_cholmod_factorize(handle, n, col_ptr, row_idx, val, info) &
         bind(c, name='vc_cholmod_factorize')
         import :: c_int, c_ptr, c_int64_t, c_int32_t, c_double
         type(c_ptr), value :: handle
         integer(c_int64_t), value :: n
         integer(c_int64_t), intent(in) :: col_ptr(*)
         integer(c_int32_t), intent(in) :: row_idx(*)
         real(c_double), intent(in) :: val(*)
         integer(c_int64_t), intent(out) :: info
      end function vc_cholmod_factorize

      integer(c_int) function vc_cholmod_solve(handle, n, nrhs, b, x) bind(c, name='vc_cholmod_solve')
         import :: c_int, c_ptr, c_int64_t, c_double
         type(c_ptr), value :: handle
         integer(c_int64_t), value :: n, nrhs
         real(c_double), intent(in) :: b(*)
         real(c_double), intent(out) :: x(*)
      end function vc_cholmod_solve

      integer(c_int) function vc_cholmod_rcond(handle, rcond) bind(c, name='vc_cholmod_rcond')
         import :: c_int, c_ptr, c_double
         type(c_ptr), value :: handle
         real(c_double), intent(out) :: rcond
      end function vc_cholmod_rcond

      integer(c_int) function vc_cholmod_stats(handle, nnz_factor, flops, ordering, is_super) &
         bind(c, name='vc_cholmod_stats')
         import :: c_int, c_ptr, c_int64_t, c_double
         type(c_ptr), value :: handle
         integer(c_int64_t), intent(out) :: nnz_factor
         real(c_double), intent(out) :: flops
         integer(c_int), intent(out) :: ordering, is_super
      end function vc_cholmod_stats

      integer(c_int) function vc_cholmod_trailing_size(handle, ndofs, dofs, mt) &
         bind(c, name='vc_cholmod_trailing_size')
         import :: c_int, c_ptr, c_int64_t, c_int32_t
         type(c_ptr), value :: handle
         integer(c_int64_t), value :: ndofs
         integer(c_int32_t), intent(in) :: dofs(*)
         integer(c_int64_t), intent(out) :: mt
      end function vc_cholmod_trailing_size

      integer(c_int) function vc_cholmod_trailing_block(handle, mt, lt, dof) &
         bind(c, name='vc_cholmod_trailing_block')
         import :: c_int, c_ptr, c_int64_t, c_double
         type(c_ptr), value :: handle
         integer(c_int64_t), value :: mt
         real(c_double), intent(out) :: lt(*)
         integer(c_int64_t), intent(out) :: dof(*)
      end function vc_cholmod_trailing_block

      subroutine vc_cholmod_free(handle) bind(c, name='vc_cholmod_free')
         import :: c_ptr
         type(c_ptr), intent(inout) :: handle
      end subroutine vc_cholmod_free
   end interface

contains

   !> Ordering and symbolic factorization of the pattern of `a` (values unused).
   !> `perm(k)` is the original dof eliminated k-th (1-based); without it CHOLMOD's
   !> default strategy chooses (AMD, and METIS when AMD's fill is high).
   !> Any earlier analysis and factor are discarded.  `coords` is not used.
   subroutine analyze(self, a, error, perm, coords)
      class(cholmod_solver_t), intent(inout) :: self
      type(sym_csc_t), intent(in) :: a
      type(error_t), allocatable, intent(out) :: error
      integer(ip), intent(in), optional :: perm(:)
      real(wp), intent(in), optional :: coords(:, :)
      integer(c_int) :: st, ordering, is_super
      integer(c_int64_t) :: info, lnz
      real(c_double) :: fl
      integer(c_int32_t) :: no_perm(1)
      character(len=24) :: buf

      if (present(coords)) continue   ! a factorization has no use for the coordinates
      call forget_trailing(self)
      self%failed_column = 0
      self%nnz_factor = 0
      self%flops = 0.0_wp
      self%supernodal = .false.
      if (allocated(self%ordering)) deallocate (self%ordering)
      call check_matrix_arrays(a, .false., 'CHOLMOD', error)
      if (allocated(error)) return
      if (.not. c_associated(self%handle)) then
         st = vc_cholmod_create(self%handle)
         if (st /= st_ok) then
            call fatal_error(error, 'CHOLMOD: cannot start ('//status_text(st)//')', err_solver)
            return
         end if
      end if
      if (present(perm)) then
         if (size(perm) /= a%n) then
            call fatal_error(error, 'CHOLMOD analyze: permutation has the wrong length', err_internal)
            return
         end if
         st = vc_cholmod_analyze(self%handle, int(a%n, c_int64_t), a%col_ptr, a%row_idx, 1_c_int, perm, info)
      else
         no_perm = 0
         st = vc_cholmod_analyze(self%handle, int(a%n, c_int64_t), a%col_ptr, a%row_idx, 0_c_int, no_perm, info)
      end if
      if (st == st_bad_input) then
         write (buf, '(i0)') info
         if (present(perm)) then
            call fatal_error(error, 'CHOLMOD analyze: invalid upper-triangle pattern or permutation at '// &
               'column/position '//trim(buf), err_internal)
         else
            call fatal_error(error, 'CHOLMOD analyze: invalid upper-triangle pattern at column '//trim(buf), &
               err_internal)
         end if
         return
      else if (st /= st_ok) then
         call fatal_error(error, 'CHOLMOD analyze failed: '//status_text(st, info), err_solver)
         return
      end if
      st = vc_cholmod_stats(self%handle, lnz, fl, ordering, is_super)
      self%nnz_factor = int(lnz, i8)
      self%flops = real(fl, wp)
      self%supernodal = is_super /= 0
      if (ordering >= lbound(ordering_names, 1) .and. ordering <= ubound(ordering_names, 1)) then
         self%ordering = trim(ordering_names(ordering))
      else
         self%ordering = 'unknown'
      end if
   end subroutine analyze

   !> Numeric factorization of `a`, which must have the analysed pattern.
   !> If `a` is not positive definite the error is err_solver and
   !> `failed_column` names the dof (original numbering) whose pivot failed.
   subroutine factorize(self, a, error)
      class(cholmod_solver_t), intent(inout) :: self
      type(sym_csc_t), intent(in) :: a
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: st
      integer(c_int64_t) :: info
      character(len=24) :: buf

      call forget_trailing(self)
      self%failed_column = 0
      if (.not. c_associated(self%handle)) then
         call fatal_error(error, 'CHOLMOD factorize called before analyze', err_internal)
         return
      end if
      call check_matrix_arrays(a, .true., 'CHOLMOD', error)
      if (allocated(error)) return
      st = vc_cholmod_factorize(self%handle, int(a%n, c_int64_t), a%col_ptr, a%row_idx, a%val, info)
      select case (st)
      case (st_ok)
      case (st_not_posdef)
         self%failed_column = int(info, ip)
         write (buf, '(i0)') info
         call fatal_error(error, 'matrix is not positive definite: the pivot of dof '//trim(buf)// &
            ' (internal numbering) is not positive', err_solver)
      case (st_order)
         call fatal_error(error, 'CHOLMOD factorize called before analyze', err_internal)
      case (st_mismatch)
         write (buf, '(i0)') info
         call fatal_error(error, 'CHOLMOD factorize: pattern differs from the analysed one (column '// &
            trim(buf)//')', err_internal)
      case default
         call fatal_error(error, 'CHOLMOD factorize failed: '//status_text(st, info), err_solver)
      end select
   end subroutine factorize

   !> Solve A x = b with the current factor.
   subroutine solve_one(self, b, x, error)
      class(cholmod_solver_t), intent(inout) :: self
      real(wp), intent(in) :: b(:)
      real(wp), intent(out) :: x(:)
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: st

      if (size(x) /= size(b)) then
         call fatal_error(error, 'CHOLMOD solve: b and x differ in length', err_internal)
         return
      end if
      st = vc_cholmod_solve(self%handle, int(size(b), c_int64_t), 1_c_int64_t, b, x)
      call solve_status(st, error)
   end subroutine solve_one

   !> Solve A x(:, k) = b(:, k) for every column k with the current factor.
   subroutine solve_many(self, b, x, error)
      class(cholmod_solver_t), intent(inout) :: self
      real(wp), intent(in) :: b(:, :)
      real(wp), intent(out) :: x(:, :)
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: st

      if (any(shape(x) /= shape(b))) then
         call fatal_error(error, 'CHOLMOD solve: b and x differ in shape', err_internal)
         return
      end if
      st = vc_cholmod_solve(self%handle, int(size(b, 1), c_int64_t), int(size(b, 2), c_int64_t), b, x)
      call solve_status(st, error)
   end subroutine solve_many

   !> x = A^-1 b at `dofs` for columns b(:, k) that vanish off them, from the
   !> factor's trailing block: with A = P^T L L^T P and the dofs in the positions
   !> p0..n of the elimination order, (A^-1 b) there is (L_t L_t^T)^-1 b_t, two dense
   !> triangular solves (LAPACK dpotrs) of the block's size mt instead of two sparse
   !> solves of the whole factor.  The block is read once per factor; `done` is false
   !> (the caller solves in full) when mt**2 exceeds nnz(L) or trailing_max_values,
   !> i.e. when the dofs are not ordered last.  x is zero off the block.
   subroutine solve_trailing(self, dofs, b, x, done, error)
      class(cholmod_solver_t), intent(inout) :: self
      integer(ip), intent(in) :: dofs(:)
      real(wp), intent(in) :: b(:, :)
      real(wp), intent(out) :: x(:, :)
      logical, intent(out) :: done
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: bt(:, :)
      integer :: mt, info

      done = .false.
      x = 0.0_wp
      if (any(shape(x) /= shape(b))) then
         call fatal_error(error, 'CHOLMOD solve: b and x differ in shape', err_internal)
         return
      end if
      if (self%trailing_state == 0) call read_trailing(self, dofs, error)
      if (allocated(error) .or. self%trailing_state /= 1) return
      mt = size(self%tdof)
      if (size(b, 2) == 0) then
         done = .true.
         return
      end if
      bt = b(self%tdof, :)
      call dpotrs('L', mt, size(b, 2), self%lt, mt, bt, mt, info)
      if (info /= 0) then
         call fatal_error(error, 'CHOLMOD trailing solve: dpotrs failed', err_internal)
         return
      end if
      x(self%tdof, :) = bt
      done = .true.
   end subroutine solve_trailing

   !> Read the trailing block of the current factor that holds `dofs`, or mark it
   !> unavailable (too large for a dense block, or not a supernodal LL^T factor).
   subroutine read_trailing(self, dofs, error)
      class(cholmod_solver_t), intent(inout) :: self
      integer(ip), intent(in) :: dofs(:)
      type(error_t), allocatable, intent(out) :: error
      integer(c_int64_t) :: mt
      integer(c_int64_t), allocatable :: dof(:)
      integer(c_int) :: st

      self%trailing_state = -1
      if (size(dofs) == 0) return
      st = vc_cholmod_trailing_size(self%handle, int(size(dofs), c_int64_t), int(dofs, c_int32_t), mt)
      if (st /= st_ok) then
         call solve_status(st, error)
         return
      end if
      if (real(mt, wp)**2 > min(real(self%nnz_factor, wp), trailing_max_values)) return
      allocate (self%lt(mt, mt), dof(mt))
      st = vc_cholmod_trailing_block(self%handle, mt, self%lt, dof)
      if (st == st_order .or. st == st_mismatch) then
         call solve_status(st, error)
         return
      else if (st /= st_ok) then
         deallocate (self%lt)
         return
      end if
      self%tdof = int(dof, ip)
      self%trailing_state = 1
   end subroutine read_trailing

   !> Drop the trailing block of the previous factor.
   pure subroutine forget_trailing(self)
      class(cholmod_solver_t), intent(inout) :: self
      if (allocated(self%lt)) deallocate (self%lt)
      if (allocated(self%tdof)) deallocate (self%tdof)
      self%trailing_state = 0
   end subroutine forget_trailing

   !> CHOLMOD's reciprocal condition estimate of the current factor,
   !> (min diag(L) / max diag(L))**2: cheap but rough (exact only for diagonal
   !> matrices; 0.39 for a 20x20 Laplacian whose true value is ~6e-3).
   !> -1 when there is no valid factor.
   function rcond(self) result(r)
      class(cholmod_solver_t), intent(in) :: self
      real(wp) :: r
      real(c_double) :: rc
      integer(c_int) :: st

      st = vc_cholmod_rcond(self%handle, rc)
      r = -1.0_wp
      if (st == st_ok) r = real(rc, wp)
   end function rcond

   !> Free the factor, the matrix copy and CHOLMOD's workspace.  Safe to call twice;
   !> the solver can be analysed again afterwards.
   subroutine release(self)
      class(cholmod_solver_t), intent(inout) :: self
      call vc_cholmod_free(self%handle)
      self%handle = c_null_ptr
      call forget_trailing(self)
      self%failed_column = 0
      self%nnz_factor = 0
      self%flops = 0.0_wp
      self%supernodal = .false.
      if (allocated(self%ordering)) deallocate (self%ordering)
   end subroutine release

   !> 'cholmod (ordering metis)': the backend and the ordering of the last analysis.
   function describe(self) result(s)
      class(cholmod_solver_t), intent(in) :: self
      character(len=:), allocatable :: s
      s = 'cholmod'
      if (allocated(self%ordering)) s = s//' (ordering '//self%ordering//')'
   end function describe

   ! Elemental, so that arrays of solvers are finalized too.
   impure elemental subroutine finalize(self)
      type(cholmod_solver_t), intent(inout) :: self
      call vc_cholmod_free(self%handle)
      self%handle = c_null_ptr
   end subroutine finalize


   subroutine solve_status(st, error)
      integer(c_int), intent(in) :: st
      type(error_t), allocatable, intent(out) :: error
      select case (st)
      case (st_ok)
      case (st_order)
         call fatal_error(error, 'CHOLMOD solve called without a valid factorization', err_internal)
      case (st_mismatch)
         call fatal_error(error, 'CHOLMOD solve: right-hand side length differs from the matrix order', &
            err_internal)
      case default
         call fatal_error(error, 'CHOLMOD solve failed: '//status_text(st), err_solver)
      end select
   end subroutine solve_status

   function status_text(st, info) result(s)
      integer(c_int), intent(in) :: st
      integer(c_int64_t), intent(in), optional :: info
      character(len=:), allocatable :: s
      character(len=24) :: buf
      select case (st)
      case (st_nomem)
         s = 'out of memory'
      case (st_too_large)
         s = 'problem too large (integer overflow in CHOLMOD)'
      case default
         s = 'CHOLMOD error'
         if (present(info)) then
            write (buf, '(i0)') info
            s = s//' (status '//trim(buf)//')'
         end if
      end select
   end function status_text
end module vemcontact_solver_cholmod
