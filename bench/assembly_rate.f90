!> Where the assembly's time goes: the node graph and CSC pattern, the element
!> kernels alone, the kernels with the scatter by a binary search per node pair
!> (add_element_matrix_searched, the assembly before issue 15), and
!> assemble_stiffness (one forward walk per column).  Each is repeated and its
!> fastest run kept (the machine is shared); the two assembled matrices are
!> compared entry by entry (the same sums in the same order: 0).
!> Times are processor times of the process (cpu_time), the fastest of the repeats.
!>
!>   bench_assembly_rate deck.inp [repeats]      (default 5 repeats)
!>
!> Prints one CSV line: elements,nodes,nnz,pattern_s,kernel_s,searched_s,assemble_s,max_rel_diff
program bench_assembly_rate
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, element_order
   use vemcontact_deck_reader, only: read_deck
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: build_pattern, add_element_matrix_searched
   use vemcontact_solver_ordering, only: node_graph_from_elements
   use vemcontact_driver_assembly, only: assemble_stiffness, max_element_nodes
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_element, only: element_stiffness, element_workspace_size
   use, intrinsic :: iso_fortran_env, only: error_unit
   implicit none
   type(model_t) :: model
   type(error_t), allocatable :: error
   type(sym_csc_t) :: a, b
   integer(i8), allocatable :: adj_ptr(:)
   integer(ip), allocatable :: adj(:)
   character(len=512) :: deck, arg
   integer :: nrep, r
   real(wp) :: t0, t_pattern, t_kernel, t_searched, t_assemble, diff

   call get_command_argument(1, deck)
   nrep = 5
   if (command_argument_count() >= 2) then
      call get_command_argument(2, arg)
      read (arg, *) nrep
   end if
   call read_deck(trim(deck), model, error)
   call check()
   t_pattern = huge(1.0_wp)
   t_kernel = huge(1.0_wp)
   t_searched = huge(1.0_wp)
   t_assemble = huge(1.0_wp)
   do r = 1, nrep
      t0 = cpu()
      call node_graph_from_elements(model%nnode, model%elem_ptr, model%elem_conn, adj_ptr, adj, error)
      call check()
      call build_pattern(model%nnode, adj_ptr, adj, a)
      t_pattern = min(t_pattern, cpu() - t0)
      b = a
      t0 = cpu()
      call element_loop(.false.)
      t_kernel = min(t_kernel, cpu() - t0)
      t0 = cpu()
      call element_loop(.true.)
      t_searched = min(t_searched, cpu() - t0)
      t0 = cpu()
      call assemble_stiffness(model, a, error)
      call check()
      t_assemble = min(t_assemble, cpu() - t0)
   end do
   diff = maxval(abs(a%val - b%val))/maxval(abs(b%val))
   write (*, '(a)') 'elements,nodes,nnz,pattern_s,kernel_s,searched_s,assemble_s,max_rel_diff'
   write (*, '(i0,",",i0,",",i0,4(",",es10.3),",",es9.2)') model%nelem, model%nnode, size(a%val), &
      t_pattern, t_kernel, t_searched, t_assemble, diff

contains

   !> The element kernels in element order; with `scatter`, added into b by binary searches.
   subroutine element_loop(scatter)
      logical, intent(in) :: scatter
      real(wp), allocatable :: xy(:, :), ke(:, :), work(:)
      real(wp) :: d(3, 3), stab
      integer :: nmax, n, info, e
      integer(ip) :: first
      logical :: ok
      nmax = max_element_nodes(model)
      allocate (xy(2, nmax), ke(2*nmax, 2*nmax), work(element_workspace_size(nmax)))
      if (scatter) b%val = 0.0_wp
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         n = model%elem_ptr(e + 1) - first
         xy(:, :n) = model%x(:, model%elem_conn(first:first + n - 1))
         associate (mat => model%materials(model%elem_mat(e)))
            call elastic_matrix(mat%young, mat%poisson, model%elem_plane(e), d)
         end associate
         stab = 1.0_wp
         if (allocated(model%elem_stab)) stab = model%elem_stab(e)
         call element_stiffness(model%elem_form(e), xy(:, :n), d, model%elem_thick(e), ke(:2*n, :2*n), &
                                work, info, stab, element_order(model%elem_type(e)))
         if (scatter) call add_element_matrix_searched(b, model%elem_conn(first:first + n - 1), ke(:2*n, :2*n), ok)
      end do
   end subroutine element_loop

   !> Processor time of this process (the loops timed are serial): unlike the wall
   !> time, it does not count the time the loaded machine gives to others.
   real(wp) function cpu()
      call cpu_time(cpu)
   end function cpu

   subroutine check()
      if (allocated(error)) then
         write (error_unit, '(a)') error%message
         stop 1
      end if
   end subroutine check
end program bench_assembly_rate
