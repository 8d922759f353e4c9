!> The interface of a linear solver for the symmetric positive definite global
!> stiffness (`sym_csc_t`, upper triangle): what the driver and, through it, the
!> contact iteration call, whatever the backend (vemcontact_solver_cholmod, the
!> first; vemcontact_solver_factory makes one by name).
!>
!> The sequence is one `analyze` of a pattern (ordering and symbolic
!> factorization for a direct solver, the pattern for an iterative one) followed
!> by any number of `factorize`/`solve` pairs with changing values: `factorize` is
!> the numeric factorization of a direct solver and the preconditioner set-up of
!> an iterative one; `solve` takes one right-hand side or a block of them.  Every
!> failure travels in the error object.
!>
!> Under MPI (a backend with `processes > 1`) every process calls these together;
!> the driver may then distribute the matrix: each process passes its share (its
!> elements' part) with `shares` set and says how many rows it owns (`owned_dofs`),
!> and adds vectors over the processes with `sum_over_ranks`.  A backend on one
!> process (CHOLMOD) keeps the defaults: one process, nothing to add.
!>
!> A solver may own C memory, released by `release` (and by the backend's final
!> procedure): do not copy a solver with intrinsic assignment.
module vemcontact_solver_linear_solver
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_internal
   use vemcontact_sparse_matrix, only: sym_csc_t
   implicit none
   private

   public :: linear_solver_t, check_matrix_arrays

   !> A solver of A x = b for a symmetric positive definite A.
   type, abstract :: linear_solver_t
      !> After a failed `factorize` on a matrix that is not positive definite:
      !> the 1-based dof (original numbering) whose pivot was not positive, 0 otherwise.
      integer(ip) :: failed_column = 0
      !> nnz of the factor of the last analysis (0 for an iterative solver).
      integer(i8) :: nnz_factor = 0
      !> Flop count of the factorization estimated by the last analysis (0 if unknown).
      real(wp) :: flops = 0.0_wp
      !> Ordering used by the last analysis ('amd', 'metis', ...; unallocated if none).
      character(len=:), allocatable :: ordering
      !> Whether `analyze` uses the `perm` it is given (a direct solver's fill-reducing
      !> ordering): callers compute one only then.  vemcontact_solver_factory sets it.
      logical :: takes_ordering = .true.
      !> Set before `analyze`: `factorize` receives this process's share of the matrix,
      !> the matrix being the sum of the shares over the processes (`processes > 1`).
      logical :: shares = .false.
      !> Set before `analyze`: the rows this process owns, the next ones of the order
      !> `perm` after those of the lower ranks (whole nodes); -1: the backend splits evenly.
      integer(ip) :: owned_dofs = -1
      !> The MPI processes that run the solver together and this one's rank (0-based):
      !> 1 and 0 for a backend on one process.  vemcontact_solver_factory sets them.
      integer :: processes = 1
      integer :: rank = 0
   contains
      procedure :: sum_over_ranks
      procedure :: solve_trailing
      procedure(analyze_i), deferred :: analyze
      procedure(factorize_i), deferred :: factorize
      procedure(solve_one_i), deferred :: solve_one
      procedure(solve_many_i), deferred :: solve_many
      !> `solve(b, x, error)` for one right-hand side `b(:)` or several `b(:, :)`.
      generic :: solve => solve_one, solve_many
      procedure(rcond_i), deferred :: rcond
      procedure(release_i), deferred :: release
      procedure(describe_i), deferred :: describe
   end type linear_solver_t

   abstract interface
      !> Analysis of the pattern of `a` (values unused).  `perm(k)`, when given, is
      !> the original dof eliminated k-th (1-based), for a direct solver;
      !> `coords(2, nnode)`, when given, are the coordinates of the nodes whose dofs
      !> (2 per node, x then y) `a` couples, for an algebraic multigrid's near null
      !> space.  Solvers use what they can of the two.  Any earlier analysis is discarded.
      subroutine analyze_i(self, a, error, perm, coords)
         import :: linear_solver_t, sym_csc_t, error_t, ip, wp
         class(linear_solver_t), intent(inout) :: self
         type(sym_csc_t), intent(in) :: a
         type(error_t), allocatable, intent(out) :: error
         integer(ip), intent(in), optional :: perm(:)
         real(wp), intent(in), optional :: coords(:, :)
      end subroutine analyze_i
      !> Numeric factorization (direct) or preconditioner set-up (iterative) of `a`,
      !> which must have the analysed pattern.
      subroutine factorize_i(self, a, error)
         import :: linear_solver_t, sym_csc_t, error_t
         class(linear_solver_t), intent(inout) :: self
         type(sym_csc_t), intent(in) :: a
         type(error_t), allocatable, intent(out) :: error
      end subroutine factorize_i
      !> x = A^-1 b with the current factorization.
      subroutine solve_one_i(self, b, x, error)
         import :: linear_solver_t, wp, error_t
         class(linear_solver_t), intent(inout) :: self
         real(wp), intent(in) :: b(:)
         real(wp), intent(out) :: x(:)
         type(error_t), allocatable, intent(out) :: error
      end subroutine solve_one_i
      !> x(:, k) = A^-1 b(:, k) for every column k.
      subroutine solve_many_i(self, b, x, error)
         import :: linear_solver_t, wp, error_t
         class(linear_solver_t), intent(inout) :: self
         real(wp), intent(in) :: b(:, :)
         real(wp), intent(out) :: x(:, :)
         type(error_t), allocatable, intent(out) :: error
      end subroutine solve_many_i
      !> Reciprocal condition estimate of the current factorization; < 0 when the
      !> solver has none (no factor, or an iterative solver).
      real(wp) function rcond_i(self)
         import :: linear_solver_t, wp
         class(linear_solver_t), intent(in) :: self
      end function rcond_i
      !> Free what the solver holds; it can be analysed again afterwards.
      subroutine release_i(self)
         import :: linear_solver_t
         class(linear_solver_t), intent(inout) :: self
      end subroutine release_i
      !> The backend as the command line names it, with what its last analysis
      !> chose, for the log: 'cholmod (ordering metis)'.
      function describe_i(self) result(s)
         import :: linear_solver_t
         class(linear_solver_t), intent(in) :: self
         character(len=:), allocatable :: s
      end function describe_i
   end interface
contains
   !> x = the sum of x over the processes, the same on every process (nothing on one).
   subroutine sum_over_ranks(self, x, error)
      class(linear_solver_t), intent(in) :: self
      real(wp), intent(inout) :: x(:)
      type(error_t), allocatable, intent(out) :: error
      ! one process: x is the sum already
      if (self%processes /= 1 .and. size(x) > 0) call fatal_error(error, 'sum_over_ranks: a backend on '// &
                                                                    'several processes must add', err_internal)
   end subroutine sum_over_ranks

   !> Whether the arrays of `a` are as long as its `n` says (`val` too when
   !> `need_values`), so that a backend's C code never reads past their ends;
   !> `backend` names the solver in the message.
   subroutine check_matrix_arrays(a, need_values, backend, error)
      type(sym_csc_t), intent(in) :: a
      logical, intent(in) :: need_values
      character(len=*), intent(in) :: backend
      type(error_t), allocatable, intent(out) :: error
      integer(i8) :: nnz
      if (a%n < 0 .or. .not. allocated(a%col_ptr) .or. .not. allocated(a%row_idx)) then
         call fatal_error(error, backend//': matrix not allocated', err_internal)
         return
      end if
      if (size(a%col_ptr, kind=i8) /= int(a%n, i8) + 1) then
         call fatal_error(error, backend//': col_ptr has the wrong length', err_internal)
         return
      end if
      nnz = a%col_ptr(a%n + 1) - 1
      if (nnz < 0 .or. size(a%row_idx, kind=i8) < nnz) then
         call fatal_error(error, backend//': row_idx shorter than col_ptr says', err_internal)
         return
      end if
      if (need_values) then
         if (.not. allocated(a%val)) then
            call fatal_error(error, backend//': matrix values not allocated', err_internal)
         else if (size(a%val, kind=i8) < nnz) then
            call fatal_error(error, backend//': val shorter than col_ptr says', err_internal)
         end if
      end if
   end subroutine check_matrix_arrays

   !> x = A^-1 b at the dofs `dofs` for right-hand sides b(:, k) that vanish off
   !> them, when the backend can do it cheaply (a direct solver whose ordering
   !> eliminates those dofs last: the factor's trailing block); `done` false
   !> otherwise, and the caller solves in full.  Entries of x off `dofs` are
   !> unspecified.  The default: not available.
   subroutine solve_trailing(self, dofs, b, x, done, error)
      class(linear_solver_t), intent(inout) :: self
      integer(ip), intent(in) :: dofs(:)
      real(wp), intent(in) :: b(:, :)
      real(wp), intent(out) :: x(:, :)
      logical, intent(out) :: done
      type(error_t), allocatable, intent(out) :: error
      ! read the arguments only to say that this backend has no such path
      done = .false. .and. self%processes > 0 .and. size(dofs) > 0 .and. size(b) > 0
      x = 0.0_wp
   end subroutine solve_trailing
end module vemcontact_solver_linear_solver
