!> The linear solver backends by name: the names the command line takes and the
!> `linear_solver_t` of a name.
module vemcontact_solver_factory
   use vemcontact_kinds, only: wp, i8
   use vemcontact_error, only: error_t, fatal_error, err_input
   use vemcontact_solver_linear_solver, only: linear_solver_t
   use vemcontact_solver_cholmod, only: cholmod_solver_t
   use vemcontact_solver_petsc, only: petsc_solver_t, petsc_gamg, petsc_hypre, petsc_mumps, petsc_ranks, petsc_rank
   implicit none
   private

   public :: solver_kind, solver_names, make_solver, uses_petsc, auto_solver

   !> The backends: `auto` is resolved by auto_solver once the deck is read;
   !> gamg, hypre and mumps are PETSc's (vemcontact_solver_petsc).
   integer, parameter, public :: solver_auto = 0, solver_cholmod = 1, solver_gamg = 2, solver_hypre = 3, &
      solver_mumps = 4
   !> Names of the backends, indexed by solver_*.
   character(len=*), parameter :: names(0:4) = [character(len=7) :: 'auto', 'cholmod', 'gamg', 'hypre', 'mumps']
   !> Unknowns from which `auto` takes gamg on one process without contact: the measured
   !> crossover of end-to-end time on Lloyd-Voronoi meshes (docs/performance.md, "PETSc solvers").
   integer(i8), parameter, public :: auto_gamg_unknowns = 200000_i8
   !> The largest plane-strain Poisson ratio for which `auto` takes gamg.  CG + GAMG's
   !> iterations on the peers' 4e5-unknown Voronoi cantilever: 23 at nu = 0.3, 39 at
   !> 0.45, 48 at 0.47, 58 at 0.48, 80 at 0.49, 646 at 0.4999 (50 s against CHOLMOD's
   !> 7 s); at 0.48 the extra iterations cost what gamg saves over CHOLMOD at 4e5
   !> unknowns (docs/performance.md, "PETSc solvers").  Plane stress has no
   !> volumetric locking (its lambda is bounded by 2 mu) and is not limited.
   real(wp), parameter, public :: auto_gamg_poisson = 0.48_wp

contains

   !> The solver_* of `name` (lower case, as on the command line); -1 if unknown.
   pure integer function solver_kind(name) result(k)
      character(len=*), intent(in) :: name
      integer :: i
      k = -1
      do i = lbound(names, 1), ubound(names, 1)
         if (trim(names(i)) == name) k = i
      end do
   end function solver_kind

   !> The backend `auto` stands for with `unknowns` unknowns on `ranks` processes, for
   !> a model with contact pairs if `contact`, whose plane-strain materials have Poisson
   !> ratios up to `poisson`: gamg on several processes; on one, gamg from
   !> auto_gamg_unknowns unknowns on for a compressible model without contact, else
   !> cholmod.  The contact iteration's many solves per step cost a CG solve each (11
   !> times CHOLMOD's time measured at 4e5 unknowns), and CG's iterations grow as the
   !> material nears incompressibility (see auto_gamg_poisson): CHOLMOD's cost does not.
   pure integer function auto_solver(unknowns, ranks, contact, poisson) result(k)
      integer(i8), intent(in) :: unknowns
      integer, intent(in) :: ranks
      logical, intent(in) :: contact
      real(wp), intent(in) :: poisson
      if (ranks > 1 .or. (unknowns >= auto_gamg_unknowns .and. .not. contact .and. &
                          poisson <= auto_gamg_poisson)) then
         k = solver_gamg
      else
         k = solver_cholmod
      end if
   end function auto_solver

   !> 'auto, cholmod, gamg, hypre, mumps': the names solver_kind knows, for messages and help.
   pure function solver_names() result(s)
      character(len=:), allocatable :: s
      integer :: i
      s = trim(names(lbound(names, 1)))
      do i = lbound(names, 1) + 1, ubound(names, 1)
         s = s//', '//trim(names(i))
      end do
   end function solver_names

   !> A new solver of kind `kind` (solver_*); an unresolved `auto` is CHOLMOD.
   subroutine make_solver(kind, solver, error)
      integer, intent(in) :: kind
      class(linear_solver_t), allocatable, intent(out) :: solver
      type(error_t), allocatable, intent(out) :: error
      select case (kind)
      case (solver_auto, solver_cholmod)
         allocate (cholmod_solver_t :: solver)
      case (solver_gamg, solver_hypre, solver_mumps)
         allocate (petsc_solver_t :: solver)
         select type (solver)
         type is (petsc_solver_t)
            solver%method = merge(petsc_gamg, merge(petsc_hypre, petsc_mumps, kind == solver_hypre), &
                                  kind == solver_gamg)
            ! PETSc's solvers order for themselves; with several MPI processes the
            ! driver's partition of the mesh distributes the rows
            solver%takes_ordering = .false.
            solver%processes = petsc_ranks()
            solver%rank = petsc_rank()
         end select
      case default
         call fatal_error(error, 'error: unknown linear solver (known: '//solver_names()//')', err_input)
      end select
   end subroutine make_solver

   !> Whether the backend `kind` runs on PETSc (and MPI).
   pure logical function uses_petsc(kind)
      integer, intent(in) :: kind
      uses_petsc = kind == solver_gamg .or. kind == solver_hypre .or. kind == solver_mumps
   end function uses_petsc
end module vemcontact_solver_factory
