!> The linear system of a model and its solution for a given load state.
!>
!> `setup` builds the pattern, assembles the stiffness and runs CHOLMOD's symbolic
!> analysis once; `solve_state` imposes a state's prescribed displacements, pays a
!> numeric factorization only when the set of fixed dofs differs from the one last
!> factorized (the matrix does not depend on the prescribed values), and solves.
!> Contact will add its springs to the same pattern and reuse the analysis.
module vemcontact_driver_linear
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_solver
   use vemcontact_model, only: model_t
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: build_pattern
   use vemcontact_solver_cholmod, only: cholmod_solver_t
   use vemcontact_solver_ordering, only: node_graph_from_elements, nodal_metis_ordering
   use vemcontact_driver_validate, only: validate_elements
   use vemcontact_driver_supports, only: find_parts, check_supports, unused_nodes
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_driver_assembly, only: assemble_stiffness, assemble_loads
   use vemcontact_driver_dirichlet, only: apply_dirichlet, constrain_rhs
   use vemcontact_clock, only: wall_time
   implicit none
   private

   public :: linear_system_t

   integer, parameter, public :: ordering_auto = 0, ordering_metis = 1, ordering_cholmod = 2
   !> Below this many nodes CHOLMOD's own ordering is cheap and as good; above it,
   !> METIS on the node graph avoids ordering the four times larger dof graph.
   integer, parameter :: metis_threshold = 5000

   type :: linear_system_t
      type(sym_csc_t) :: k                        !< assembled stiffness, no constraints
      type(sym_csc_t) :: kb                       !< with the constraints of the last factorization
      type(cholmod_solver_t) :: solver
      integer(ip), allocatable :: part(:)         !< part (connected body) of each node
      integer(ip) :: nparts = 0
      logical, allocatable :: unused(:)           !< nodes of no element
      logical, allocatable :: factored_fixed(:)   !< fixed dofs of the current factor
      logical :: factored = .false.
      ! phase timings of the last call, seconds
      real(wp) :: t_pattern = 0, t_assemble = 0, t_analyze = 0, t_factorize = 0, t_solve = 0
      logical :: refactorized = .false.           !< whether the last solve_state factorized
   contains
      procedure :: setup
      procedure :: solve_state
   end type linear_system_t

contains

   subroutine setup(self, model, ordering, error)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      integer, intent(in) :: ordering
      type(error_t), allocatable, intent(out) :: error
      integer(i8), allocatable :: adj_ptr(:)
      integer(ip), allocatable :: adj(:), perm(:)
      real(wp) :: t0

      call validate_elements(model, error)
      if (allocated(error)) return
      self%unused = unused_nodes(model)
      call find_parts(model, self%part, self%nparts)

      t0 = wall_time()
      call node_graph_from_elements(model%nnode, model%elem_ptr, model%elem_conn, adj_ptr, adj, error)
      if (allocated(error)) return
      call build_pattern(model%nnode, adj_ptr, adj, self%k)
      self%t_pattern = wall_time() - t0

      t0 = wall_time()
      call assemble_stiffness(model, self%k, error)
      if (allocated(error)) return
      self%t_assemble = wall_time() - t0

      t0 = wall_time()
      if (ordering == ordering_metis .or. (ordering == ordering_auto .and. model%nnode >= metis_threshold)) then
         allocate (perm(2*model%nnode))
         call nodal_metis_ordering(model%nnode, adj_ptr, adj, perm, error)
         if (allocated(error)) return
         call self%solver%analyze(self%k, error, perm)
      else
         call self%solver%analyze(self%k, error)
      end if
      if (allocated(error)) return
      self%t_analyze = wall_time() - t0
      self%factored = .false.
   end subroutine setup

   !> Solve for the displacements u(2*nnode) of a load state.
   subroutine solve_state(self, model, st, u, error)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(load_state_t), intent(in) :: st
      real(wp), intent(out) :: u(:)
      type(error_t), allocatable, intent(out) :: error
      logical, allocatable :: fixed(:)
      real(wp), allocatable :: f(:)
      real(wp) :: t0
      fixed = st%fixed
      ! nodes of no element carry nothing: hold them so the matrix stays regular
      fixed(1::2) = fixed(1::2) .or. self%unused
      fixed(2::2) = fixed(2::2) .or. self%unused
      allocate (f(size(u)))
      call assemble_loads(model, st%force, st%dload, f)
      self%refactorized = .false.
      self%t_factorize = 0
      if (.not. self%factored) then
         self%refactorized = .true.
      else
         self%refactorized = any(fixed .neqv. self%factored_fixed)
      end if
      if (self%refactorized) then
         call check_supports(model, self%part, self%nparts, fixed, error)
         if (allocated(error)) return
         self%kb = self%k
         call apply_dirichlet(self%kb, fixed, st%prescribed, f)
         t0 = wall_time()
         call self%solver%factorize(self%kb, error)
         if (allocated(error)) return
         self%t_factorize = wall_time() - t0
         self%factored_fixed = fixed
         self%factored = .true.
      else
         ! same constraints: only the right-hand side changes (kb is already reduced,
         ! so the known values are moved with the unreduced stiffness)
         call constrain_rhs(self%k, fixed, st%prescribed, f)
      end if
      t0 = wall_time()
      call self%solver%solve(f, u, error)
      if (allocated(error)) return
      self%t_solve = wall_time() - t0
      if (.not. all(abs(u) <= huge(1.0_wp))) then
         call fatal_error(error, 'error: the solution has NaN or infinite values: the model is '// &
                          'numerically singular', err_solver)
         return
      end if
   end subroutine solve_state
end module vemcontact_driver_linear
