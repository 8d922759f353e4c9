!> The linear system of a model and its solution for a given load state.
!>
!> `setup` builds the pattern, assembles the stiffness and runs the linear solver's
!> analysis once (vemcontact_solver_linear_solver: CHOLMOD by default); `solve_state` imposes a state's prescribed displacements, pays a
!> numeric factorization only when the set of fixed dofs differs from the one last
!> factorized (the matrix does not depend on the prescribed values), and solves.
!> With contact, the contact iteration (vemcontact_contact_iteration) adds its
!> springs to the same pattern through the contact_system_t operations below and
!> reuses the analysis.
!>
!> Distributed (a solver on several MPI processes): the mesh is partitioned
!> (vemcontact_driver_partition), each process assembles only its own elements, so
!> `k` and `kb` hold its share of the matrix (the matrix is the sum of the shares),
!> and the solver adds the shares.  Everything else stays whole and the same on every
!> process: the load vector, the solution, the right-hand side (the moves of the
!> prescribed values are linear in the matrix and summed over the processes), the
!> diagonal of the fixed dofs (summed; held by rank 0's share only), the contact
!> springs (in rank 0's share), K u (summed).
module vemcontact_driver_linear
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_solver
   use vemcontact_model, only: model_t
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: build_pattern
   use vemcontact_solver_linear_solver, only: linear_solver_t
   use vemcontact_solver_factory, only: make_solver, solver_auto, solver_cholmod
   use vemcontact_solver_ordering, only: node_graph_from_elements, nodal_metis_ordering, nodal_metis_ordering_last
   use vemcontact_driver_validate, only: validate_elements
   use vemcontact_driver_ranges, only: validate_ranges
   use vemcontact_driver_memory, only: check_memory
   use vemcontact_driver_supports, only: find_parts, check_supports, unused_nodes
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_driver_assembly, only: assemble_stiffness, assemble_loads
   use vemcontact_driver_dirichlet, only: apply_dirichlet, constrain_rhs, constrain_matrix, dirichlet_moves, &
      kept_diagonal
   use vemcontact_driver_partition, only: partition_t, partition_mesh
   use vemcontact_clock, only: wall_time
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_iteration, only: contact_system_t, judge_conditioning
   use vemcontact_driver_penetration, only: solve_with_uplift
   use vemcontact_contact_rules, only: matrix_key_t
   use vemcontact_contact_search, only: merge_node_pairs
   use vemcontact_driver_thermal, only: add_thermal_forces
   use vemcontact_driver_equations, only: constraint_set_t, resolve_equations, equation_graph, &
                                          eliminate_equations, transform_loads, recover_dependent, dependent_dofs
   use vemcontact_sparse_matvec, only: sym_matvec
   use vemcontact_log, only: logger_t
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   implicit none
   private

   public :: linear_system_t

   integer, parameter, public :: ordering_auto = 0, ordering_metis = 1, ordering_cholmod = 2
   !> Below this many nodes CHOLMOD's own ordering is cheap and as good; above it,
   !> METIS on the node graph avoids ordering the four times larger dof graph.
   integer, parameter :: metis_threshold = 5000

   !> The stiffness, its factorization and the operations the contact iteration
   !> (vemcontact_contact_iteration) needs; the components of contact_system_t keep
   !> the fixed dofs and contact matrix of the current factor and the counts of the
   !> last solve_state.
   type, extends(contact_system_t) :: linear_system_t
      type(sym_csc_t) :: k                        !< assembled stiffness, no constraints
      type(sym_csc_t) :: kb                       !< with the constraints of the last factorization
      !> the backend chosen by `setup`; only its interface is used
      class(linear_solver_t), allocatable :: solver
      integer(ip), allocatable :: part(:)         !< part (connected body) of each node
      integer(ip) :: nparts = 0
      logical, allocatable :: unused(:)           !< nodes of no element
      ! phase timings of the last call, seconds (factorize, solve, search: contact_system_t)
      real(wp) :: t_validate = 0, t_pattern = 0, t_assemble = 0, t_analyze = 0
      !> of t_pattern, the search for the candidate node pairs of the pattern
      real(wp) :: t_candidates = 0
      !> of t_pattern, the partition of the mesh (distributed)
      real(wp) :: t_partition = 0
      integer :: ordering = 0
      integer :: pattern_builds = 0
      !> distributed: this process holds its share of `k` and `kb` (see the module)
      logical :: dist = .false.
      !> distributed: the partition of the mesh over the processes
      type(partition_t) :: partition
      !> distributed: the largest |diagonal entry| of the whole stiffness (its diagonal
      !> summed over the processes)
      real(wp) :: kmax_whole = 0
      !> the solver was chosen by `auto`: if it fails in a step without contact, the
      !> step is solved again with CHOLMOD (one process only; see solve_state)
      logical :: fallback = .false.
      !> a fallback to CHOLMOD happened (the log and the results name the solver that ran)
      logical :: fell_back = .false.
      !> the *EQUATION constraints, resolved; `k` holds T^T K T (vemcontact_driver_equations)
      type(constraint_set_t) :: cs
      !> where every pairing is fixed (SMALL SLIDING, SURFACE TO SURFACE) and some pair
      !> has friction or may gain it (*CHANGE FRICTION): the nodes of
      !> the contact rows (slave nodes and master segment nodes of every pair), which
      !> the METIS ordering eliminates last, and their dofs, on which `solve_columns`
      !> reads the contact compliance from the factor's trailing block
      integer(ip), allocatable :: contact_nodes(:), contact_dofs(:)
   contains
      procedure :: setup
      procedure :: solve_state
      procedure, private :: build_system
      procedure, private :: analyze_system
      procedure :: contact_matrix
      procedure :: numeric_factorize
      procedure :: rcond
      procedure :: solve_system
      procedure :: solve_columns
      procedure :: elastic_times
      procedure :: largest_elastic_diagonal
      procedure :: reduce_loads
      procedure, private :: constrain
      procedure, private :: solve_linear
   end type linear_system_t

contains

   !> Validate, find the parts, build the pattern (covering the contact candidates
   !> of `contact` at the undeformed state), assemble and analyze with the linear
   !> solver `solver` (vemcontact_solver_factory's solver_*; default solver_auto).
   subroutine setup(self, model, ordering, error, contact, solver)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      integer, intent(in) :: ordering
      type(error_t), allocatable, intent(out) :: error
      type(contact_state_t), intent(in), optional :: contact
      integer, intent(in), optional :: solver
      real(wp), allocatable :: u0(:)
      integer :: kind
      real(wp) :: t0
      t0 = wall_time()
      ! the memory bound first: it is linear in the elements, the checks of their shapes are not
      call check_memory(model, error)
      if (allocated(error)) return
      call validate_elements(model, error)
      if (allocated(error)) return
      call validate_ranges(model, error)
      if (allocated(error)) return
      self%t_validate = wall_time() - t0
      self%unused = unused_nodes(model)
      call find_parts(model, self%part, self%nparts)
      self%ordering = ordering
      kind = solver_auto
      if (present(solver)) kind = solver
      if (allocated(self%solver)) then
         call self%solver%release()
         deallocate (self%solver)
      end if
      call make_solver(kind, self%solver, error)
      if (allocated(error)) return
      self%dist = self%solver%processes > 1
      self%solver%shares = self%dist
      call resolve_equations(model, self%cs, error)
      if (allocated(error)) return
      allocate (u0(2*model%nnode), source=0.0_wp)
      call self%build_system(model, error, contact, u0)
   end subroutine setup

   !> Pattern (element graph plus contact candidate pairs at displacements u),
   !> stiffness and symbolic analysis.
   subroutine build_system(self, model, error, contact, u)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      type(contact_state_t), intent(in), optional :: contact
      real(wp), intent(in) :: u(:)
      integer(i8), allocatable :: adj_ptr(:), ptr2(:)
      integer(ip), allocatable :: adj(:), adj2(:), extra(:, :)
      real(wp) :: t0, t1, failed(1)
      real(wp), allocatable :: kdiag(:)
      type(error_t), allocatable :: err2
      integer(ip) :: j
      logical :: ok

      t0 = wall_time()
      self%t_candidates = 0
      call node_graph_from_elements(model%nnode, model%elem_ptr, model%elem_conn, adj_ptr, adj, error)
      if (allocated(error)) return
      if (self%dist .and. self%partition%nparts == 0) then
         ! once, from the elements' graph: it holds when contact pairs rebuild the pattern
         t1 = wall_time()
         call partition_mesh(model%nnode, model%elem_ptr, model%elem_conn, adj_ptr, adj, &
                             self%solver%processes, self%partition, error)
         if (allocated(error)) return
         self%solver%owned_dofs = 2*self%partition%nodes(self%solver%rank + 1)
         self%t_partition = wall_time() - t1
      end if
      if (allocated(self%contact_nodes)) deallocate (self%contact_nodes, self%contact_dofs)
      if (present(contact)) then
         if (contact%n > 0) then
            t1 = wall_time()
            call contact%graph_pairs(model, u, extra, error)
            if (allocated(error)) return
            self%t_candidates = wall_time() - t1
            call merge_node_pairs(model%nnode, adj_ptr, adj, extra, ptr2, adj2, error)
            if (allocated(error)) return
            call move_alloc(ptr2, adj_ptr)
            call move_alloc(adj2, adj)
         end if
         if (may_have_friction(model, contact)) call fixed_pairing_nodes(model%nnode, contact, self%contact_nodes, &
                                                                  self%contact_dofs)
      end if
      call equation_graph(model%nnode, self%cs, adj_ptr, adj, error)
      if (allocated(error)) return
      call build_pattern(model%nnode, adj_ptr, adj, self%k)
      self%pattern_builds = self%pattern_builds + 1
      self%t_pattern = wall_time() - t0

      t0 = wall_time()
      if (self%dist) then
         call assemble_stiffness(model, self%k, error, self%partition%elem_part == self%solver%rank)
         ! an element that fails fails on one process: all stop, with the messages of all
         ! elements (assembled again on every process, only on this path)
         failed = merge(1.0_wp, 0.0_wp, allocated(error))
         call self%solver%sum_over_ranks(failed, err2)
         if (allocated(err2)) then
            call move_alloc(err2, error)
            return
         end if
         if (failed(1) > 0.0_wp) then
            call assemble_stiffness(model, self%k, error)
            if (.not. allocated(error)) call fatal_error(error, 'internal error: an element failed on one '// &
                                                         'process only', err_solver)
            return
         end if
      else
         call assemble_stiffness(model, self%k, error)
         if (allocated(error)) return
      end if
      ! under MPI each process eliminates from its share: T^T K T is linear in K, so the
      ! eliminated shares add up to the eliminated matrix
      call eliminate_equations(self%cs, self%k, adj_ptr, adj, ok)
      if (.not. ok) then
         call fatal_error(error, 'internal error: an *EQUATION coupling is outside the matrix pattern', err_solver)
         return
      end if
      if (self%dist) then
         kdiag = [(self%k%val(self%k%col_ptr(j + 1) - 1), j=1, self%k%n)]
         call self%solver%sum_over_ranks(kdiag, error)
         self%kmax_whole = max(0.0_wp, maxval(abs(kdiag)))
      end if
      if (allocated(error)) return
      self%t_assemble = wall_time() - t0

      call self%analyze_system(model, adj_ptr, adj, error)
   end subroutine build_system

   !> The solver's analysis of the pattern of `k`, whose node graph is `adj_ptr`/`adj`
   !> (for a fill-reducing ordering); the last factorization is discarded.
   subroutine analyze_system(self, model, adj_ptr, adj, error)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: perm(:)
      real(wp) :: t0
      t0 = wall_time()
      call self%solver%release()
      if (self%dist) then
         ! each process's rows contiguous: the nodes part by part
         call self%solver%analyze(self%k, error, self%partition%perm, model%x)
      else if (self%solver%takes_ordering .and. (self%ordering == ordering_metis .or. &
          (self%ordering == ordering_auto .and. model%nnode >= metis_threshold))) then
         allocate (perm(2*model%nnode))
         if (allocated(self%contact_nodes)) then
            call nodal_metis_ordering_last(model%nnode, adj_ptr, adj, self%contact_nodes, perm, error)
         else
            call nodal_metis_ordering(model%nnode, adj_ptr, adj, perm, error)
         end if
         if (allocated(error)) return
         call self%solver%analyze(self%k, error, perm, model%x)
      else
         call self%solver%analyze(self%k, error, coords=model%x)
      end if
      if (allocated(error)) return
      self%t_analyze = wall_time() - t0
      self%factored = .false.
   end subroutine analyze_system

   !> Solve for the displacements u(2*nnode) of a load state.
   !> With `contact`, the active-set iteration of solve_contact; `u` then holds
   !> the previous state on entry (the pairing starts from it) and the new one on exit.
   subroutine solve_state(self, model, st, u, error, contact, log)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(load_state_t), intent(in) :: st
      real(wp), intent(inout) :: u(:)
      type(error_t), allocatable, intent(out) :: error
      type(contact_state_t), intent(inout), optional :: contact
      type(logger_t), intent(inout), optional :: log
      logical, allocatable :: fixed(:)
      real(wp), allocatable :: f(:), f0(:)
      integer(i8), allocatable :: adj_ptr(:)
      integer(ip), allocatable :: adj(:)
      integer :: j, k
      self%iterations = 0
      self%factorizations = 0
      self%t_search = 0
      fixed = st%fixed
      ! nodes of no element carry nothing: hold them so the matrix stays regular
      fixed(1::2) = fixed(1::2) .or. self%unused
      fixed(2::2) = fixed(2::2) .or. self%unused
      ! the dependent dofs of *EQUATION are eliminated: held at 0, recovered after the solve
      fixed = fixed .or. dependent_dofs(self%cs, size(fixed))
      allocate (f(size(u)))
      call assemble_loads(model, st%force, st%dload, f)
      if (allocated(st%dtemp)) call add_thermal_forces(model, st%dtemp, f)
      call transform_loads(self%cs, f)
      if (present(contact)) then
         if (contact%n > 0) then
            call solve_with_uplift(self, model, st%uplift, fixed, st%prescribed, f, u, contact, error, log)
            if (.not. allocated(error)) call recover_dependent(self%cs, u)
            return
         end if
      end if
      if (self%fallback .and. .not. self%dist) f0 = f
      call self%solve_linear(model, st, fixed, f, u, error, log)
      if (.not. allocated(error)) call recover_dependent(self%cs, u)
      if (.not. allocated(error) .or. .not. allocated(f0)) return
      if (error%code /= err_solver) return
      ! the iterative solver `auto` chose failed (CG did not converge, or its set-up
      ! failed): the step again with the direct solver, which needs no convergence
      ! the message's first line (its help names --solver, which auto replaces here)
      k = index(error%message, new_line('a'))
      if (k == 0) k = len(error%message) + 1
      j = 1
      if (index(error%message, 'error: ') == 1) j = 8
      if (present(log)) call log%say('  note: '//error%message(j:k - 1)//new_line('a')// &
                                     '  solver auto: falling back to cholmod for this run')
      deallocate (error)
      call self%solver%release()
      deallocate (self%solver)
      call make_solver(solver_cholmod, self%solver, error)
      if (allocated(error)) return
      self%fallback = .false.
      self%fell_back = .true.
      ! the assembled stiffness and its pattern stay: a new analysis for the new solver
      call node_graph_from_elements(model%nnode, model%elem_ptr, model%elem_conn, adj_ptr, adj, error)
      if (allocated(error)) return
      call equation_graph(model%nnode, self%cs, adj_ptr, adj, error)
      if (allocated(error)) return
      call self%analyze_system(model, adj_ptr, adj, error)
      if (allocated(error)) return
      f = f0
      call self%solve_linear(model, st, fixed, f, u, error, log)
      if (.not. allocated(error)) call recover_dependent(self%cs, u)
   end subroutine solve_state

   !> solve_state without contact: constraints, a factorization when the fixed dofs
   !> changed, one solve.
   subroutine solve_linear(self, model, st, fixed, f, u, error, log)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(load_state_t), intent(in) :: st
      logical, intent(in) :: fixed(:)
      real(wp), intent(inout) :: f(:), u(:)
      type(error_t), allocatable, intent(out) :: error
      type(logger_t), intent(inout), optional :: log
      real(wp) :: t0
      logical :: warned
      self%refactorized = .false.
      self%t_factorize = 0
      if (.not. self%factored) then
         self%refactorized = .true.
      else
         self%refactorized = any(fixed .neqv. self%factored_fixed)
      end if
      if (self%refactorized) then
         call check_supports(model, self%part, self%nparts, fixed, error, cs=self%cs)
         if (allocated(error)) return
         call copy_values(self%k, self%kb)
         call self%constrain(self%kb, fixed, st%prescribed, f, .true., error)
         if (allocated(error)) return
         t0 = wall_time()
         call self%solver%factorize(self%kb, error)
         if (allocated(error)) return
         self%t_factorize = wall_time() - t0
         self%factorizations = 1
         warned = .false.
         call judge_conditioning(self%solver%rcond(), 0.0_wp, .false., warned, error, log)
         if (allocated(error)) return
         self%factored_fixed = fixed
         self%factored = .true.
         self%factored_key = matrix_key_t()
      else
         ! same constraints: only the right-hand side changes (kb is already reduced,
         ! so the known values are moved with the unreduced stiffness)
         call self%constrain(self%k, fixed, st%prescribed, f, .false., error)
         if (allocated(error)) return
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
   end subroutine solve_linear

   !> Kb = K + the contact terms with the constraints, f = fext + the contact terms
   !> (constrained); a new pattern and analysis when the pairing left the pattern.
   subroutine contact_matrix(self, model, contact, u, fixed, prescribed, fext, f, rebuilt, error)
      class(linear_system_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(contact_state_t), intent(in) :: contact
      real(wp), intent(in) :: u(:), prescribed(:), fext(:)
      logical, intent(in) :: fixed(:)
      real(wp), intent(out) :: f(:)
      logical, intent(out) :: rebuilt
      type(error_t), allocatable, intent(out) :: error
      logical :: ok, owner
      rebuilt = .false.
      ! distributed: the springs in rank 0's share (the others only check the pattern)
      owner = self%solver%rank == 0
      call copy_values(self%k, self%kb)
      call contact%add_stiffness(self%kb, ok, owner)
      if (.not. ok) then
         ! the pairing left the candidate pairs of the pattern: new pattern and analysis
         call self%build_system(model, error, contact, u)
         if (allocated(error)) return
         rebuilt = .true.
         call copy_values(self%k, self%kb)
         call contact%add_stiffness(self%kb, ok, owner)
         if (.not. ok) then
            call fatal_error(error, 'internal error: contact spring outside the rebuilt pattern', err_solver)
            return
         end if
      end if
      f = fext
      call contact%add_rhs(f)
      call check_supports(model, self%part, self%nparts, fixed, error, contact%springs(model, self%part), &
                          self%cs, contact%fric%on)
      if (allocated(error)) return
      call self%constrain(self%kb, fixed, prescribed, f, .true., error)
   end subroutine contact_matrix

   !> The right-hand side f (the loads on entry) of the prescribed `value`s at the
   !> `fixed` dofs, from the unconstrained matrix `a`, and with `matrix` `a` constrained.
   !> Distributed, `a` is this process's share: the moves and the diagonal at the fixed
   !> dofs are summed over the processes, and f comes out whole on every process.
   subroutine constrain(self, a, fixed, value, f, matrix, error)
      class(linear_system_t), intent(in) :: self
      type(sym_csc_t), intent(inout) :: a
      logical, intent(in) :: fixed(:), matrix
      real(wp), intent(in) :: value(:)
      real(wp), intent(inout) :: f(:)
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: g(:), d(:), diag(:)
      integer(ip) :: j
      if (.not. self%dist) then
         if (matrix) then
            call apply_dirichlet(a, fixed, value, f)
         else
            call constrain_rhs(a, fixed, value, f)
         end if
         return
      end if
      ! the whole matrix's diagonal at the fixed dofs
      d = pack([(a%val(a%col_ptr(j + 1) - 1), j=1, a%n)], fixed)
      call self%solver%sum_over_ranks(d, error)
      if (allocated(error)) return
      diag = unpack(d, fixed, 0.0_wp)
      allocate (g(size(f)), source=0.0_wp)
      call dirichlet_moves(a, fixed, value, g)
      call self%solver%sum_over_ranks(g, error)
      if (allocated(error)) return
      do j = 1, a%n
         if (fixed(j)) then
            f(j) = kept_diagonal(diag(j))*value(j)
         else
            f(j) = f(j) + g(j)
         end if
      end do
      if (matrix) call constrain_matrix(a, fixed, diag, self%solver%rank == 0)
   end subroutine constrain

   subroutine numeric_factorize(self, error)
      class(linear_system_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: error
      call self%solver%factorize(self%kb, error)
      self%pivot_failed = allocated(error) .and. self%solver%failed_column > 0
   end subroutine numeric_factorize

   real(wp) function rcond(self)
      class(linear_system_t), intent(in) :: self
      rcond = self%solver%rcond()
   end function rcond

   subroutine solve_system(self, f, u, error)
      class(linear_system_t), intent(inout) :: self
      real(wp), intent(in) :: f(:)
      real(wp), intent(inout) :: u(:)
      type(error_t), allocatable, intent(out) :: error
      call self%solver%solve(f, u, error)
   end subroutine solve_system

   !> Columns of contact rows with the current factor, x(:, c) = A^-1 b(:, c) at the
   !> contact nodes at least: from the factor's trailing block where the ordering
   !> put the contact nodes last (solve_trailing; x is then zero away from them),
   !> otherwise by a direct solver's blocked full solve.
   subroutine solve_columns(self, b, x, error)
      class(linear_system_t), intent(inout) :: self
      real(wp), intent(in) :: b(:, :)
      real(wp), intent(out) :: x(:, :)
      type(error_t), allocatable, intent(out) :: error
      logical :: done
      done = .false.
      if (allocated(self%contact_dofs)) then
         call self%solver%solve_trailing(self%contact_dofs, b, x, done, error)
         if (allocated(error)) return
      end if
      self%columns_local = done
      if (.not. done) call self%solver%solve(b, x, error)
   end subroutine solve_columns

   !> Whether some pair is frictional now or a step's *CHANGE FRICTION may make it so:
   !> only then does the contact iteration solve compliance columns (condensed_applies),
   !> which the ordering of the contact nodes last serves.
   pure logical function may_have_friction(model, contact) result(frictional)
      type(model_t), intent(in) :: model
      type(contact_state_t), intent(in) :: contact
      integer :: s
      frictional = contact%fric%on
      if (frictional .or. .not. allocated(model%steps)) return
      do s = 1, size(model%steps)
         if (allocated(model%steps(s)%friction_changes)) frictional = frictional .or. &
            size(model%steps(s)%friction_changes) > 0
      end do
   end function may_have_friction

   !> The nodes of the contact rows of `contact` (every pair's slave nodes and master
   !> segment nodes, sorted) and their dofs, where every pair's pairing is fixed
   !> (SMALL SLIDING or SURFACE TO SURFACE): the rows of any of its pairings then lie
   !> on them.  Unallocated otherwise (finite sliding pairs over the whole master).
   pure subroutine fixed_pairing_nodes(nnode, contact, nodes, dofs)
      integer(ip), intent(in) :: nnode
      type(contact_state_t), intent(in) :: contact
      integer(ip), allocatable, intent(out) :: nodes(:), dofs(:)
      logical, allocatable :: on(:)
      integer :: p
      integer(ip) :: i
      if (contact%n == 0 .or. .not. allocated(contact%pairs)) return
      if (.not. all(contact%pairs%small_sliding .or. contact%pairs%node_to_node)) return
      allocate (on(nnode), source=.false.)
      on(contact%node(:contact%n)) = .true.
      do p = 1, size(contact%pairs)
         if (size(contact%pairs(p)%seg) > 0) on(reshape(contact%pairs(p)%seg, [size(contact%pairs(p)%seg)])) = .true.
      end do
      nodes = pack([(i, i=1, nnode)], on)
      dofs = reshape(transpose(reshape([2*nodes - 1, 2*nodes], [size(nodes), 2])), [2*size(nodes)])
   end subroutine fixed_pairing_nodes

   subroutine elastic_times(self, u, ku)
      class(linear_system_t), intent(in) :: self
      real(wp), intent(in) :: u(:)
      real(wp), intent(out) :: ku(:)
      type(error_t), allocatable :: error
      call sym_matvec(self%k, u, ku)
      if (.not. self%dist) return
      call self%solver%sum_over_ranks(ku, error)
      ! not reached: MPI's own errors end the run (MPI_ERRORS_ARE_FATAL, the default);
      ! should one return, K u is marked not finite rather than left a share
      if (allocated(error)) ku = ieee_value(1.0_wp, ieee_quiet_nan)
   end subroutine elastic_times

   !> f <- T^T f, the loads of the system `k` holds (with *EQUATION eliminated), for
   !> the reactions K u - f.
   pure subroutine reduce_loads(self, f)
      class(linear_system_t), intent(in) :: self
      real(wp), intent(inout) :: f(:)
      call transform_loads(self%cs, f)
   end subroutine reduce_loads

   real(wp) function largest_elastic_diagonal(self) result(kmax)
      class(linear_system_t), intent(in) :: self
      integer(ip) :: j
      kmax = 0.0_wp
      if (self%dist) then
         kmax = self%kmax_whole
         return
      end if
      do j = 1, self%k%n
         kmax = max(kmax, abs(self%k%val(self%k%col_ptr(j + 1) - 1)))
      end do
   end function largest_elastic_diagonal

   !> b = a, copying only the values when b already has a's pattern (the common
   !> case in the contact iterations: the pattern is fixed, the values change).
   subroutine copy_values(a, b)
      type(sym_csc_t), intent(in) :: a
      type(sym_csc_t), intent(inout) :: b
      logical :: same
      same = allocated(b%val) .and. b%n == a%n
      if (same) same = size(b%val) == size(a%val)
      if (same) same = all(b%col_ptr == a%col_ptr)
      if (same) then
         b%val = a%val
      else
         b = a
      end if
   end subroutine copy_values
end module vemcontact_driver_linear
