!> HDF5 results file: the mesh once, then one group per step; the layout is
!> documented in docs/output-format.md.  The file is written under a unique
!> temporary name beside its final name (created by src/safe_file.f90 without
!> following links) and renamed to the final name by `close` only after HDF5
!> closed it without error and it was fsync'ed; `close` also writes the root
!> attribute `complete` (1: the run finished).  `discard` (and finalization)
!> removes the temporary instead: a killed or failed run never leaves a torn
!> file under the final name.
!>
!> This module is an interop spot: the HDF5 Fortran API passes buffers as
!> `c_ptr` and handles as `hid_t`/`hsize_t`.  Every HDF5 return code is checked
!> and turned into an `error_t` naming the file and the object; HDF5's own
!> error printing is switched off, the message we return replaces it (with the
!> system's reason, such as "No space left on device", read from HDF5's error
!> stack by src/output/hdf5_shim.c).
!> Datasets are stored little-endian (`H5T_IEEE_F64LE`, `H5T_STD_I32LE`,
!> `H5T_STD_I64LE`) whatever the host, and written contiguous and uncompressed:
!> that is the fastest to write and to read back in slices.
module vemcontact_output_hdf5
   use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_null_ptr, c_char, c_int, c_null_char
   use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5eset_auto_f, h5lexists_f, h5fcreate_f, h5fclose_f, &
                   h5fflush_f, h5ldelete_f, h5gcreate_f, h5gopen_f, h5gclose_f, h5screate_simple_f, h5screate_f, &
                   h5sclose_f, h5dcreate_f, h5dwrite_f, h5dclose_f, h5acreate_f, h5awrite_f, &
                   h5aclose_f, h5aexists_f, h5adelete_f, h5tcopy_f, h5tset_size_f, h5tset_strpad_f, h5tclose_f, &
                   h5kind_to_type, H5F_ACC_TRUNC_F, H5F_SCOPE_GLOBAL_F, H5S_SCALAR_F, &
                   H5T_IEEE_F64LE, H5T_STD_I32LE, H5T_STD_I64LE, H5T_C_S1, H5T_STR_NULLPAD_F, &
                   H5_REAL_KIND, H5_INTEGER_KIND
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_io, err_internal
   use vemcontact_model, only: model_t, string_t
   use vemcontact_output_selection, only: field_selection_t
   use vemcontact_output_xdmf, only: xdmf_topology, xdmf_layout
   use vemcontact_contact_iteration, only: iteration_record_t
   use vemcontact_safe_file, only: create_temporary, publish_file, remove_file
   implicit none
   private

   !> Value of the root attribute `format` and its version.
   character(len=*), parameter, public :: h5_format_name = 'vemcontact-results'
   integer(ip), parameter, public :: h5_format_version = 1_ip

   !> Writer of one results file.  `open` creates its temporary, `write_mesh`
   !> writes /mesh once, `write_step` adds /steps/NNNN, `discard_step` removes a
   !> step that could not be completed, `close` puts the file under its name,
   !> `discard` (or finalization) abandons it.
   type, public :: h5_writer_t
      private
      integer(hid_t) :: file = -1
      character(len=:), allocatable :: path
      !> the temporary being written, renamed to `path` by `close`
      character(len=:), allocatable :: tmp
      !> sizes of the mesh written, to check the steps against; -1 before write_mesh
      integer(ip) :: nnode = -1, nelem = -1
      !> 0: the results written go to the step's group /steps/NNNN; m > 0: to the
      !> frame of increment m, /increments/NNNN/MMMM (set_increment)
      integer :: frame = 0
   contains
      procedure :: open => h5_open
      procedure :: set_increment => h5_set_increment
      procedure :: flush => h5_flush
      procedure :: write_mesh => h5_write_mesh
      procedure :: write_step => h5_write_step
      procedure :: write_contact => h5_write_contact
      procedure :: write_iterations => h5_write_iterations
      procedure :: write_strength_reduction => h5_write_strength_reduction
      procedure :: write_increments => h5_write_increments
      procedure :: discard_step => h5_discard_step
      procedure :: write_labels => h5_write_labels
      procedure :: write_results => h5_write_results
      procedure :: close => h5_close
      procedure :: discard => h5_discard
      procedure :: is_open => h5_is_open
      procedure :: set_solver => h5_set_solver
      final :: h5_final
   end type h5_writer_t

contains

   !> Start the file `path` (as a new temporary beside it), write the root
   !> attributes (with `solver`: the linear solver that ran, root attribute `solver`;
   !> with `partition`: the elements each MPI process assembled, root attributes
   !> `processes` and `elements_per_process`) and /steps.
   subroutine h5_open(self, path, error, solver, partition)
      class(h5_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: error
      character(len=*), intent(in), optional :: solver
      integer(ip), intent(in), optional :: partition(:)
      integer :: hdferr
      integer(hid_t) :: grp

      call h5_discard(self)
      self%path = path
      self%nnode = -1
      self%nelem = -1
      ! h5open_f is reference counted by HDF5 and safe to call for every file
      call h5open_f(hdferr)
      if (failed(self, hdferr, 'initialising the HDF5 library', error)) return
      call h5eset_auto_f(0, hdferr)
      if (failed(self, hdferr, 'switching off HDF5 error printing', error)) return
      call create_temporary(path, self%tmp, error)
      if (allocated(error)) return
      ! the temporary was just created empty and exclusively: HDF5 takes it over
      call h5fcreate_f(self%tmp, H5F_ACC_TRUNC_F, self%file, hdferr)
      if (failed(self, hdferr, 'creating the file', error)) then
         self%file = -1
         call remove_file(self%tmp)
         return
      end if
      call put_string_attribute(self, self%file, 'format', h5_format_name, error)
      if (allocated(error)) return
      call put_int_attribute(self, self%file, 'format_version', h5_format_version, error)
      if (allocated(error)) return
      if (present(solver)) then
         call put_string_attribute(self, self%file, 'solver', solver, error)
         if (allocated(error)) return
      end if
      if (present(partition)) then
         call put_int_attribute(self, self%file, 'processes', int(size(partition), ip), error)
         if (allocated(error)) return
         call put_int_array_attribute(self, self%file, 'elements_per_process', partition, error)
         if (allocated(error)) return
      end if
      call h5gcreate_f(self%file, 'steps', grp, hdferr)
      if (failed(self, hdferr, 'creating group /steps', error)) return
      call h5gclose_f(grp, hdferr)
      if (failed(self, hdferr, 'closing group /steps', error)) return
   end subroutine h5_open

   !> Write /mesh: coordinates, ids, 0-based CSR connectivity, element type,
   !> formulation and material, and the cells as XDMF's topology (xdmf_topology).
   subroutine h5_write_mesh(self, model, error)
      class(h5_writer_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      integer(hid_t) :: grp
      integer :: hdferr
      integer(ip) :: nconn
      integer(hsize_t) :: nn, ne
      integer :: xkind, nper
      integer(i8) :: xlength

      if (.not. check_open(self, 'write_mesh', error)) return
      if (.not. mesh_arrays_fit(model)) then
         call fatal_error(error, 'write_mesh: model arrays shorter than nnode/nelem ('// &
                          self%path//')', err_internal)
         return
      end if
      call h5gcreate_f(self%file, 'mesh', grp, hdferr)
      if (failed(self, hdferr, 'creating group /mesh', error)) return
      nconn = model%elem_ptr(model%nelem + 1) - 1_ip
      nn = int(model%nnode, hsize_t)
      ne = int(model%nelem, hsize_t)
      call put_real(self, grp, 'coordinates', [2_hsize_t, nn], model%x, error)
      if (.not. allocated(error)) call put_int(self, grp, 'node_ids', [nn], model%node_id, error)
      if (.not. allocated(error)) &
         call put_i8(self, grp, 'element_offsets', [ne + 1], &
                     int(model%elem_ptr(1:model%nelem + 1), i8) - 1_i8, error)
      if (.not. allocated(error)) &
         call put_int(self, grp, 'element_connectivity', [int(nconn, hsize_t)], &
                      model%elem_conn(1:nconn) - 1_ip, error)
      if (.not. allocated(error)) call put_int(self, grp, 'element_ids', [ne], model%elem_id, error)
      if (.not. allocated(error)) &
         call put_int(self, grp, 'element_material', [ne], int(model%elem_mat(1:model%nelem), ip), &
                      error)
      if (.not. allocated(error)) &
         call put_int(self, grp, 'element_type', [ne], int(model%elem_type(1:model%nelem), ip), error)
      if (.not. allocated(error)) &
         call put_int(self, grp, 'element_formulation', [ne], &
                      int(model%elem_form(1:model%nelem), ip), error)
      ! the cells as JOB.xdmf's topology (vemcontact_output_xdmf)
      if (.not. allocated(error) .and. model%nelem > 0) then
         call xdmf_layout(model, xkind, nper, xlength)
         if (nper > 0) then
            call put_int(self, grp, 'xdmf_topology', [int(nper, hsize_t), ne], xdmf_topology(model), error)
         else
            call put_int(self, grp, 'xdmf_topology', [int(xlength, hsize_t)], xdmf_topology(model), error)
         end if
      end if
      call h5gclose_f(grp, hdferr)
      if (allocated(error)) return
      if (failed(self, hdferr, 'closing group /mesh', error)) return
      call h5fflush_f(self%file, H5F_SCOPE_GLOBAL_F, hdferr)
      if (failed(self, hdferr, 'flushing', error)) return
      self%nnode = model%nnode
      self%nelem = model%nelem
   end subroutine h5_write_mesh

   !> The model's arrays hold at least what nnode and nelem promise (they are
   !> passed by sequence association, so a short array would be read past its end).
   pure logical function mesh_arrays_fit(model)
      type(model_t), intent(in) :: model
      mesh_arrays_fit = .false.
      if (model%nnode < 0 .or. model%nelem < 0) return
      if (.not. (allocated(model%x) .and. allocated(model%node_id) .and. &
                 allocated(model%elem_ptr) .and. allocated(model%elem_conn) .and. &
                 allocated(model%elem_id) .and. allocated(model%elem_mat) .and. &
                 allocated(model%elem_type) .and. allocated(model%elem_form))) return
      if (size(model%x, 1) /= 2 .or. size(model%x, 2) < model%nnode) return
      if (size(model%node_id) < model%nnode .or. size(model%elem_ptr) < model%nelem + 1) return
      if (size(model%elem_id) < model%nelem .or. size(model%elem_mat) < model%nelem .or. &
          size(model%elem_type) < model%nelem .or. size(model%elem_form) < model%nelem) return
      if (size(model%elem_conn) < model%elem_ptr(model%nelem + 1) - 1) return
      mesh_arrays_fit = .true.
   end function mesh_arrays_fit

   !> Write /steps/NNNN (index zero-padded to 4 digits, wider beyond 9999) with
   !> attributes name and time and datasets U, S_element, S_node (with `sel`: those
   !> selected).  With `indicator`, written with S: the dataset
   !> ERROR_INDICATOR (nelem) and the step attributes error_estimate and energy_norm
   !> (vemcontact_post_estimate).
   subroutine h5_write_step(self, istep, name, time, u, s_elem, s_node, error, sel, indicator, estimate, energy)
      class(h5_writer_t), intent(inout) :: self
      integer, intent(in) :: istep
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: time
      real(wp), intent(in) :: u(:, :)        !< (2, nnode)
      real(wp), intent(in) :: s_elem(:, :)   !< (4, nelem)
      real(wp), intent(in) :: s_node(:, :)   !< (4, nnode)
      type(error_t), allocatable, intent(out) :: error
      type(field_selection_t), intent(in), optional :: sel
      real(wp), intent(in), optional :: indicator(:)  !< (nelem) error indicator per cell
      real(wp), intent(in), optional :: estimate      !< the global error estimate
      real(wp), intent(in), optional :: energy        !< energy norm of the discrete stress
      type(field_selection_t) :: w
      character(len=:), allocatable :: gname
      integer(hid_t) :: grp
      integer :: hdferr

      if (present(sel)) w = sel
      if (.not. check_open(self, 'write_step', error)) return
      if (size(u, 1) /= 2 .or. size(s_elem, 1) /= 4 .or. size(s_node, 1) /= 4 &
          .or. size(s_node, 2) /= size(u, 2) .or. self%nnode < 0 &
          .or. size(u, 2) /= self%nnode .or. size(s_elem, 2) /= self%nelem) then
         call fatal_error(error, 'write_step: array shapes do not match the mesh written ('// &
                          self%path//')', err_internal)
         return
      end if
      if (present(indicator)) then
         if (size(indicator) /= self%nelem) then
            call fatal_error(error, 'write_step: indicator size does not match the mesh written ('// &
                             self%path//')', err_internal)
            return
         end if
      end if
      if (istep < 0) then
         call fatal_error(error, 'write_step: negative step index ('//self%path//')', err_internal)
         return
      end if
      gname = result_group(self, istep)
      if (self%frame > 0) then
         call ensure_group(self, '/increments', error)
         if (.not. allocated(error)) call ensure_group(self, gname(1:index(gname, '/', back=.true.) - 1), error)
         if (allocated(error)) return
      end if
      call h5gcreate_f(self%file, gname, grp, hdferr)
      if (failed(self, hdferr, 'creating group '//gname, error)) return
      call put_string_attribute(self, grp, 'name', name, error)
      if (.not. allocated(error)) call put_real_attribute(self, grp, 'time', time, error)
      if (.not. allocated(error) .and. w%u) call put_real(self, grp, 'U', shape(u, hsize_t), u, error)
      if (.not. allocated(error) .and. w%s) &
         call put_real(self, grp, 'S_element', shape(s_elem, hsize_t), s_elem, error)
      if (.not. allocated(error) .and. w%s) &
         call put_real(self, grp, 'S_node', shape(s_node, hsize_t), s_node, error)
      if (present(indicator) .and. w%s) then
         if (.not. allocated(error)) &
            call put_real(self, grp, 'ERROR_INDICATOR', [int(self%nelem, hsize_t)], indicator(1:self%nelem), error)
         if (present(estimate) .and. .not. allocated(error)) &
            call put_real_attribute(self, grp, 'error_estimate', estimate, error)
         if (present(energy) .and. .not. allocated(error)) &
            call put_real_attribute(self, grp, 'energy_norm', energy, error)
      end if
      call h5gclose_f(grp, hdferr)
      if (allocated(error)) return
      if (failed(self, hdferr, 'closing group '//gname, error)) return
   end subroutine h5_write_step

   !> Write /steps/NNNN/contact/pair_K (the step group must exist): slave node ids,
   !> undeformed coordinates, COPEN, CPRESS, CSLIP (with `sel`: those selected), CSHEAR
   !> (with CPRESS, when given), CNAREA and STATUS (0 open, 1 closed, 2 slid off, 3 stick,
   !> 4 slip), with *UPLIFT CFLUIDP beside CPRESS and, with pressure penetration, the
   !> attribute water_entered.
   subroutine h5_write_contact(self, istep, ipair, node_id, x, copen, cpress, cslip, cnarea, status, error, sel, &
                               cshear, cfluidp, strength, water_entered, slave_surface, master_surface, &
                               roles_swapped)
      class(h5_writer_t), intent(inout) :: self
      integer, intent(in) :: istep, ipair
      integer(ip), intent(in) :: node_id(:)
      real(wp), intent(in) :: x(:, :), copen(:), cpress(:), cslip(:), cnarea(:)
      integer, intent(in) :: status(:)
      type(error_t), allocatable, intent(out) :: error
      type(field_selection_t), intent(in), optional :: sel
      !> the shear traction along the master's tangent (written beside CPRESS)
      real(wp), intent(in), optional :: cshear(:)
      !> CFLUIDP, the water pressure in the joint (*UPLIFT), written beside CPRESS
      real(wp), intent(in), optional :: cfluidp(:)
      !> the friction coefficient and cohesion in force (attributes friction_coefficient, cohesion)
      real(wp), intent(in), optional :: strength(2)
      !> pressure penetration: the length along the joint the water filled (attribute
      !> water_entered)
      real(wp), intent(in), optional :: water_entered
      !> the slave and master surfaces as the pair used them (attributes slave_surface,
      !> master_surface), and whether they are the deck's exchanged (roles_swapped, 0/1)
      character(len=*), intent(in), optional :: slave_surface, master_surface
      logical, intent(in), optional :: roles_swapped
      type(field_selection_t) :: w
      character(len=:), allocatable :: gname
      character(len=24) :: buf
      integer(hid_t) :: grp
      integer(ip), allocatable :: st(:)
      integer :: hdferr
      if (present(sel)) w = sel
      if (.not. check_open(self, 'write_contact', error)) return
      call contact_group(self, istep, gname, error)
      if (allocated(error)) return
      write (buf, '(i0)') ipair
      gname = gname//'/pair_'//trim(buf)
      call h5gcreate_f(self%file, gname, grp, hdferr)
      if (failed(self, hdferr, 'creating group '//gname, error)) return
      st = int(status, ip)
      call put_int(self, grp, 'node_ids', shape(node_id, hsize_t), node_id, error)
      if (.not. allocated(error)) call put_real(self, grp, 'coordinates', shape(x, hsize_t), x, error)
      if (.not. allocated(error) .and. w%copen) &
         call put_real(self, grp, 'COPEN', shape(copen, hsize_t), copen, error)
      if (.not. allocated(error) .and. w%cpress) &
         call put_real(self, grp, 'CPRESS', shape(cpress, hsize_t), cpress, error)
      if (present(cshear)) then
         if (.not. allocated(error) .and. w%cpress) &
            call put_real(self, grp, 'CSHEAR', shape(cshear, hsize_t), cshear, error)
      end if
      if (present(cfluidp)) then
         if (.not. allocated(error) .and. w%cpress) &
            call put_real(self, grp, 'CFLUIDP', shape(cfluidp, hsize_t), cfluidp, error)
      end if
      if (.not. allocated(error) .and. w%cslip) &
         call put_real(self, grp, 'CSLIP', shape(cslip, hsize_t), cslip, error)
      if (.not. allocated(error)) call put_real(self, grp, 'CNAREA', shape(cnarea, hsize_t), cnarea, error)
      if (.not. allocated(error)) call put_int(self, grp, 'STATUS', shape(st, hsize_t), st, error)
      if (present(strength)) then
         if (.not. allocated(error)) call put_real_attribute(self, grp, 'friction_coefficient', strength(1), error)
         if (.not. allocated(error)) call put_real_attribute(self, grp, 'cohesion', strength(2), error)
      end if
      if (present(water_entered)) then
         if (.not. allocated(error)) call put_real_attribute(self, grp, 'water_entered', water_entered, error)
      end if
      if (present(slave_surface)) then
         if (.not. allocated(error)) call put_string_attribute(self, grp, 'slave_surface', slave_surface, error)
      end if
      if (present(master_surface)) then
         if (.not. allocated(error)) call put_string_attribute(self, grp, 'master_surface', master_surface, error)
      end if
      if (present(roles_swapped)) then
         if (.not. allocated(error)) call put_int_attribute(self, grp, 'roles_swapped', merge(1_ip, 0_ip, roles_swapped), error)
      end if
      call h5gclose_f(grp, hdferr)
      if (allocated(error)) return
      if (failed(self, hdferr, 'closing group '//gname, error)) return
   end subroutine h5_write_contact

   !> Write /steps/NNNN/contact/iterations: one entry per contact iteration of the
   !> step (the paper's Table 1 and the log's iteration lines): iteration, active
   !> (closed slave entries), changed, slip_changes (frictional entries that changed
   !> between stick and slip), residual (relative), max_penetration,
   !> max_pressure, step (line search), factorized (1: a numeric factorization was
   !> paid), rebuilt (1: the matrix pattern was rebuilt), time (wall seconds).  Call
   !> after write_contact of the step's pairs.
   subroutine h5_write_iterations(self, istep, records, error)
      class(h5_writer_t), intent(inout) :: self
      integer, intent(in) :: istep
      type(iteration_record_t), intent(in) :: records(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: col(:)
      real(wp), allocatable :: val(:)
      character(len=:), allocatable :: gname
      integer(hid_t) :: grp
      integer(hsize_t) :: dims(1)
      integer :: hdferr
      if (.not. check_open(self, 'write_iterations', error)) return
      call contact_group(self, istep, gname, error)
      if (allocated(error)) return
      gname = gname//'/iterations'
      call h5gcreate_f(self%file, gname, grp, hdferr)
      if (failed(self, hdferr, 'creating group '//gname, error)) return
      dims = size(records, kind=hsize_t)
      ! each component copied into a contiguous array first: a component of an array
      ! of records is strided, and the assumed-size arguments of put_real/put_int would
      ! each take a temporary copy
      col = records%iteration
      call put_int(self, grp, 'iteration', dims, col, error)
      col = records%active
      if (.not. allocated(error)) call put_int(self, grp, 'active', dims, col, error)
      col = records%changed
      if (.not. allocated(error)) call put_int(self, grp, 'changed', dims, col, error)
      col = records%slip_changes
      if (.not. allocated(error)) call put_int(self, grp, 'slip_changes', dims, col, error)
      col = merge(1, 0, records%factorized)
      if (.not. allocated(error)) call put_int(self, grp, 'factorized', dims, col, error)
      col = merge(1, 0, records%rebuilt)
      if (.not. allocated(error)) call put_int(self, grp, 'rebuilt', dims, col, error)
      val = records%residual
      if (.not. allocated(error)) call put_real(self, grp, 'residual', dims, val, error)
      val = records%penetration
      if (.not. allocated(error)) call put_real(self, grp, 'max_penetration', dims, val, error)
      val = records%pressure
      if (.not. allocated(error)) call put_real(self, grp, 'max_pressure', dims, val, error)
      val = records%step
      if (.not. allocated(error)) call put_real(self, grp, 'step', dims, val, error)
      val = records%time
      if (.not. allocated(error)) call put_real(self, grp, 'time', dims, val, error)
      call h5gclose_f(grp, hdferr)
      if (allocated(error)) return
      if (failed(self, hdferr, 'closing group '//gname, error)) return
   end subroutine h5_write_iterations

   !> Write a strength reduction step's search: the step attribute factor_of_safety and
   !> the group /steps/NNNN/strength_reduction with one entry per trial in trial order
   !> (F, converged 0/1, u_char, iterations) and the attributes tolerance, F_lower,
   !> F_upper (+Inf when no trial failed).
   subroutine h5_write_strength_reduction(self, istep, f, converged, u_char, iterations, tolerance, f_lower, &
                                          f_upper, error)
      class(h5_writer_t), intent(inout) :: self
      integer, intent(in) :: istep
      real(wp), intent(in) :: f(:), u_char(:), tolerance, f_lower, f_upper
      integer, intent(in) :: converged(:), iterations(:)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: gname
      integer(hid_t) :: grp
      integer(hsize_t) :: dims(1)
      integer(ip), allocatable :: col(:)
      integer :: hdferr
      if (.not. check_open(self, 'write_strength_reduction', error)) return
      gname = result_group(self, istep)
      call h5gopen_f(self%file, gname, grp, hdferr)
      if (failed(self, hdferr, 'opening group '//gname, error)) return
      call put_real_attribute(self, grp, 'factor_of_safety', f_lower, error)
      call h5gclose_f(grp, hdferr)
      if (allocated(error)) return
      if (failed(self, hdferr, 'closing group '//gname, error)) return
      gname = gname//'/strength_reduction'
      call h5gcreate_f(self%file, gname, grp, hdferr)
      if (failed(self, hdferr, 'creating group '//gname, error)) return
      dims = size(f, kind=hsize_t)
      call put_real(self, grp, 'F', dims, f, error)
      col = int(converged, ip)
      if (.not. allocated(error)) call put_int(self, grp, 'converged', dims, col, error)
      if (.not. allocated(error)) call put_real(self, grp, 'u_char', dims, u_char, error)
      col = int(iterations, ip)
      if (.not. allocated(error)) call put_int(self, grp, 'iterations', dims, col, error)
      if (.not. allocated(error)) call put_real_attribute(self, grp, 'tolerance', tolerance, error)
      if (.not. allocated(error)) call put_real_attribute(self, grp, 'F_lower', f_lower, error)
      if (.not. allocated(error)) call put_real_attribute(self, grp, 'F_upper', f_upper, error)
      call h5gclose_f(grp, hdferr)
      if (allocated(error)) return
      if (failed(self, hdferr, 'closing group '//gname, error)) return
   end subroutine h5_write_strength_reduction

   !> The converged increments of step istep (JOB.sta's lines of the step), group
   !> /steps/NNNN/increments: step_time and increment (size) at each increment's end,
   !> attempts (1 + the cut-backs before it converged), iterations (contact
   !> iterations; 1 without contact).
   subroutine h5_write_increments(self, istep, step_time, increment_time, attempts, iterations, error)
      class(h5_writer_t), intent(inout) :: self
      integer, intent(in) :: istep
      real(wp), intent(in) :: step_time(:), increment_time(:)
      integer, intent(in) :: attempts(:), iterations(:)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: gname
      integer(hid_t) :: grp
      integer(hsize_t) :: dims(1)
      integer(ip), allocatable :: col(:)
      integer :: hdferr
      if (.not. check_open(self, 'write_increments', error)) return
      gname = result_group(self, istep)//'/increments'
      call h5gcreate_f(self%file, gname, grp, hdferr)
      if (failed(self, hdferr, 'creating group '//gname, error)) return
      dims = size(step_time, kind=hsize_t)
      call put_real(self, grp, 'step_time', dims, step_time, error)
      if (.not. allocated(error)) call put_real(self, grp, 'increment', dims, increment_time, error)
      col = int(attempts, ip)
      if (.not. allocated(error)) call put_int(self, grp, 'attempts', dims, col, error)
      col = int(iterations, ip)
      if (.not. allocated(error)) call put_int(self, grp, 'iterations', dims, col, error)
      call h5gclose_f(grp, hdferr)
      if (allocated(error)) return
      if (failed(self, hdferr, 'closing group '//gname, error)) return
   end subroutine h5_write_increments

   !> Add to /mesh (after write_mesh) the labels of the elements: element_set
   !> (index into element_set_names, the set of the element's *SOLID SECTION, 1-based,
   !> 0 = none), element_part (connected body, 1-based), and the names of all
   !> element sets and materials in deck order (material ids are element_material).
   subroutine h5_write_labels(self, model, elem_set, elem_part, error)
      class(h5_writer_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: elem_set(:), elem_part(:)
      type(error_t), allocatable, intent(out) :: error
      type(string_t), allocatable :: names(:)
      integer(hid_t) :: grp
      integer :: hdferr, k
      if (.not. check_open(self, 'write_labels', error)) return
      if (self%nelem < 0 .or. size(elem_set) /= self%nelem .or. size(elem_part) /= self%nelem) then
         call fatal_error(error, 'write_labels: array sizes do not match the mesh written ('// &
                          self%path//')', err_internal)
         return
      end if
      call h5gopen_f(self%file, '/mesh', grp, hdferr)
      if (failed(self, hdferr, 'opening group /mesh', error)) return
      call put_int(self, grp, 'element_set', shape(elem_set, hsize_t), elem_set, error)
      if (.not. allocated(error)) &
         call put_int(self, grp, 'element_part', shape(elem_part, hsize_t), elem_part, error)
      ! filled one by one: gfortran 12 loses deferred-length components in an
      ! implied-do array constructor of derived type
      allocate (names(0))
      if (allocated(model%elsets)) then
         deallocate (names)
         allocate (names(size(model%elsets)))
         do k = 1, size(model%elsets)
            names(k)%s = model%elsets(k)%name
         end do
      end if
      if (.not. allocated(error)) call put_strings(self, grp, 'element_set_names', names, error)
      deallocate (names)
      allocate (names(0))
      if (allocated(model%materials)) then
         deallocate (names)
         allocate (names(size(model%materials)))
         do k = 1, size(model%materials)
            names(k)%s = model%materials(k)%name
         end do
      end if
      if (.not. allocated(error)) call put_strings(self, grp, 'material_names', names, error)
      call h5gclose_f(grp, hdferr)
      if (allocated(error)) return
      if (failed(self, hdferr, 'closing group /mesh', error)) return
      call h5fflush_f(self%file, H5F_SCOPE_GLOBAL_F, hdferr)
      if (failed(self, hdferr, 'flushing', error)) return
   end subroutine h5_write_labels

   !> Add to /steps/NNNN (after write_step): strains E_element (4, nelem) and
   !> E_node (4, nnode), reaction forces RF (2, nnode), RF_total (2) over all
   !> nodes, LOAD_total (2) the applied loads it balances, and RF_sets/names, RF_sets/RF (2, nsets): the totals over the
   !> constrained node sets (with `sel`: E and RF as selected).
   subroutine h5_write_results(self, istep, e_elem, e_node, rf, set_names, set_rf, error, sel, load_total)
      class(h5_writer_t), intent(inout) :: self
      integer, intent(in) :: istep
      real(wp), intent(in) :: e_elem(:, :), e_node(:, :), rf(:, :), set_rf(:, :)
      type(string_t), intent(in) :: set_names(:)
      type(error_t), allocatable, intent(out) :: error
      type(field_selection_t), intent(in), optional :: sel
      !> the sum of the applied loads (written as LOAD_total with RF_total, which balances it)
      real(wp), intent(in), optional :: load_total(2)
      type(field_selection_t) :: w
      character(len=:), allocatable :: gname
      integer(hid_t) :: grp, sub
      integer :: hdferr
      logical :: bad
      if (present(sel)) w = sel
      if (.not. check_open(self, 'write_results', error)) return
      if (size(e_elem, 1) /= 4 .or. size(e_elem, 2) /= self%nelem .or. size(e_node, 1) /= 4 &
          .or. size(e_node, 2) /= self%nnode .or. size(rf, 1) /= 2 .or. size(rf, 2) /= self%nnode &
          .or. size(set_rf, 1) /= 2 .or. size(set_rf, 2) /= size(set_names)) then
         call fatal_error(error, 'write_results: array shapes do not match the mesh written ('// &
                          self%path//')', err_internal)
         return
      end if
      gname = result_group(self, istep)
      call h5gopen_f(self%file, gname, grp, hdferr)
      if (failed(self, hdferr, 'opening group '//gname, error)) return
      if (w%e) call put_real(self, grp, 'E_element', shape(e_elem, hsize_t), e_elem, error)
      if (.not. allocated(error) .and. w%e) &
         call put_real(self, grp, 'E_node', shape(e_node, hsize_t), e_node, error)
      if (.not. allocated(error) .and. w%rf) call put_real(self, grp, 'RF', shape(rf, hsize_t), rf, error)
      if (.not. allocated(error) .and. w%rf) &
         call put_real(self, grp, 'RF_total', [2_hsize_t], sum(rf, dim=2), error)
      if (.not. allocated(error) .and. w%rf .and. present(load_total)) &
         call put_real(self, grp, 'LOAD_total', [2_hsize_t], load_total, error)
      if (.not. allocated(error) .and. w%rf) then
         call h5gcreate_f(grp, 'RF_sets', sub, hdferr)
         if (.not. failed(self, hdferr, 'creating group '//gname//'/RF_sets', error)) then
            call put_strings(self, sub, 'names', set_names, error)
            if (.not. allocated(error)) call put_real(self, sub, 'RF', shape(set_rf, hsize_t), set_rf, error)
            call h5gclose_f(sub, hdferr)
            if (.not. allocated(error)) bad = failed(self, hdferr, 'closing group '//gname//'/RF_sets', error)
         end if
      end if
      call h5gclose_f(grp, hdferr)
      if (allocated(error)) return
      if (failed(self, hdferr, 'closing group '//gname, error)) return
   end subroutine h5_write_results

   !> The name of /steps/NNNN/contact, created when it does not exist yet.
   !> The group of step istep: /steps/NNNN (four digits, more when needed).
   pure function step_group(istep) result(gname)
      integer, intent(in) :: istep
      character(len=:), allocatable :: gname
      character(len=24) :: buf
      if (istep <= 9999) then
         write (buf, '(i4.4)') istep
      else
         write (buf, '(i0)') istep
      end if
      gname = '/steps/'//trim(buf)
   end function step_group

   subroutine contact_group(self, istep, gname, error)
      class(h5_writer_t), intent(inout) :: self
      integer, intent(in) :: istep
      character(len=:), allocatable, intent(out) :: gname
      type(error_t), allocatable, intent(out) :: error
      gname = result_group(self, istep)//'/contact'
      call ensure_group(self, gname, error)
   end subroutine contact_group

   !> Create the group `gname` (its parent must exist) unless it exists.
   subroutine ensure_group(self, gname, error)
      class(h5_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: gname
      type(error_t), allocatable, intent(out) :: error
      integer(hid_t) :: grp
      integer :: hdferr
      logical :: exists
      call h5lexists_f(self%file, gname, exists, hdferr)
      if (failed(self, hdferr, 'looking up '//gname, error)) return
      if (.not. exists) then
         call h5gcreate_f(self%file, gname, grp, hdferr)
         if (failed(self, hdferr, 'creating group '//gname, error)) return
         call h5gclose_f(grp, hdferr)
         if (failed(self, hdferr, 'closing group '//gname, error)) return
      end if
   end subroutine ensure_group

   !> Where the results of step istep go: /steps/NNNN, or the frame of the increment
   !> set by set_increment, /increments/NNNN/MMMM (four digits each, more when needed).
   pure function result_group(self, istep) result(gname)
      class(h5_writer_t), intent(in) :: self
      integer, intent(in) :: istep
      character(len=:), allocatable :: gname
      character(len=24) :: buf
      gname = step_group(istep)
      if (self%frame <= 0) return
      if (self%frame <= 9999) then
         write (buf, '(i4.4)') self%frame
      else
         write (buf, '(i0)') self%frame
      end if
      gname = '/increments/'//gname(len('/steps/') + 1:)//'/'//trim(buf)
   end function result_group

   !> Flush the file (HDF5 metadata and data to the operating system).  A flush walks
   !> the whole metadata cache, whose size grows with the groups written, so the
   !> driver flushes on a doubling schedule (after steps 1, 2, 4, ...), not after
   !> every write: a flush per step made a run quadratic in its number of steps.
   subroutine h5_flush(self, error)
      class(h5_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: error
      integer :: hdferr
      if (.not. check_open(self, 'flush', error)) return
      call h5fflush_f(self%file, H5F_SCOPE_GLOBAL_F, hdferr)
      if (failed(self, hdferr, 'flushing', error)) return
   end subroutine h5_flush

   !> The results written next are those of increment m of the step (m > 0: the
   !> frame /increments/NNNN/MMMM), or of the end of the step (m = 0: /steps/NNNN).
   subroutine h5_set_increment(self, m)
      class(h5_writer_t), intent(inout) :: self
      integer, intent(in) :: m
      self%frame = m
   end subroutine h5_set_increment

   !> Remove /steps/NNNN if it exists: a step that failed part way, so that the
   !> file lists only steps complete in every results file.
   subroutine h5_discard_step(self, istep, error)
      class(h5_writer_t), intent(inout) :: self
      integer, intent(in) :: istep
      type(error_t), allocatable, intent(out) :: error
      integer :: hdferr
      logical :: exists
      if (.not. check_open(self, 'discard_step', error)) return
      call h5lexists_f(self%file, step_group(istep), exists, hdferr)
      if (failed(self, hdferr, 'looking up '//step_group(istep), error)) return
      if (.not. exists) return
      call h5ldelete_f(self%file, step_group(istep), hdferr)
      if (failed(self, hdferr, 'removing the incomplete '//step_group(istep), error)) return
   end subroutine h5_discard_step

   !> Finish the file: root attribute `complete` (1 when `complete` is true: the
   !> run finished; 0 by default), with `interrupted` the root attribute of that name
   !> (the signal number that stopped the run), close it with HDF5, fsync it and rename it to
   !> its final name.  On any failure the temporary is removed (no file of that
   !> name, rather than a torn one) and `error` says why.  Nothing if not open.
   subroutine h5_close(self, error, complete, interrupted)
      class(h5_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: error
      logical, intent(in), optional :: complete
      !> the signal that interrupted the run: root attribute `interrupted`
      integer, intent(in), optional :: interrupted
      integer :: hdferr
      integer(ip) :: flag
      if (self%file < 0) return
      flag = 0_ip
      if (present(complete)) then
         if (complete) flag = 1_ip
      end if
      call put_int_attribute(self, self%file, 'complete', flag, error)
      if (present(interrupted) .and. .not. allocated(error)) &
         call put_int_attribute(self, self%file, 'interrupted', int(interrupted, ip), error)
      if (allocated(error)) then
         call h5_discard(self)
         return
      end if
      call h5fclose_f(self%file, hdferr)
      self%file = -1
      if (failed(self, hdferr, 'closing the file', error)) then
         call remove_file(self%tmp)
         return
      end if
      call publish_file(self%tmp, self%path, error)
   end subroutine h5_close

   !> Abandon the file: close it (errors ignored) and remove the temporary.
   subroutine h5_discard(self)
      class(h5_writer_t), intent(inout) :: self
      integer :: hdferr
      if (self%file < 0) return
      call h5fclose_f(self%file, hdferr)
      self%file = -1
      call remove_file(self%tmp)
   end subroutine h5_discard

   !> True between a successful `open` and `close`.
   pure logical function h5_is_open(self)
      class(h5_writer_t), intent(in) :: self
      h5_is_open = self%file >= 0
   end function h5_is_open

   !> A writer going out of scope abandons a file it did not close.
   subroutine h5_final(self)
      type(h5_writer_t), intent(inout) :: self
      call h5_discard(self)
   end subroutine h5_final

   ! ---------------------------------------------------------------- helpers

   !> True (and `error` set) when an HDF5 call returned a negative code.
   logical function failed(self, hdferr, what, error)
      class(h5_writer_t), intent(in) :: self
      integer, intent(in) :: hdferr
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(inout) :: error
      character(len=16) :: code
      character(kind=c_char, len=256) :: reason
      integer :: n
      interface
         subroutine c_system_reason(buf, len) bind(C, name='vc_h5_system_reason')
            import :: c_char, c_int
            character(kind=c_char), intent(out) :: buf(*)
            integer(c_int), value :: len
         end subroutine c_system_reason
      end interface
      failed = hdferr < 0
      if (.not. failed) return
      write (code, '(i0)') hdferr
      call c_system_reason(reason, int(len(reason), c_int))
      n = max(0, index(reason, c_null_char) - 1)
      if (n > 0) then
         call fatal_error(error, 'error: cannot write '''//self%path//''': '//reason(1:n)// &
                          ' (HDF5 error '//trim(code)//' '//what//')', err_io)
      else
         call fatal_error(error, 'HDF5 error (code '//trim(code)//') '//what//' in '''// &
                          self%path//'''', err_io)
      end if
   end function failed

   logical function check_open(self, what, error)
      class(h5_writer_t), intent(in) :: self
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(out) :: error
      check_open = self%file >= 0
      if (.not. check_open) call fatal_error(error, 'h5_writer_t%'//what// &
                                             ': no results file is open', err_internal)
   end function check_open

   !> Create dataset `name` under `loc` with the given file type and shape
   !> (Fortran order; h5py shows it reversed) and write `buf` of type `mem_type`.
   subroutine put_dataset(self, loc, name, file_type, mem_type, dims, buf, error)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc, file_type, mem_type
      character(len=*), intent(in) :: name
      integer(hsize_t), intent(in) :: dims(:)
      type(c_ptr), intent(in) :: buf
      type(error_t), allocatable, intent(inout) :: error
      integer(hid_t) :: space, dset
      integer :: hdferr, ignore
      call h5screate_simple_f(size(dims), dims, space, hdferr)
      if (failed(self, hdferr, 'creating the dataspace of '//name, error)) return
      call h5dcreate_f(loc, name, file_type, space, dset, hdferr)
      if (failed(self, hdferr, 'creating dataset '//name, error)) then
         call h5sclose_f(space, ignore)
         return
      end if
      ! a zero-size dataset has nothing to write (and no address to write from)
      if (product(dims) > 0) then
         call h5dwrite_f(dset, mem_type, buf, hdferr)
         if (failed(self, hdferr, 'writing dataset '//name, error)) then
            call h5dclose_f(dset, ignore)
            call h5sclose_f(space, ignore)
            return
         end if
      end if
      call h5dclose_f(dset, hdferr)
      if (failed(self, hdferr, 'closing dataset '//name, error)) then
         call h5sclose_f(space, ignore)
         return
      end if
      call h5sclose_f(space, hdferr)
      if (failed(self, hdferr, 'closing the dataspace of '//name, error)) return
   end subroutine put_dataset

   ! The typed writers take the data as assumed-size arrays: any rank binds by
   ! sequence association, and gfortran passes contiguous actuals without a copy
   ! (a `contiguous` assumed-shape dummy makes gfortran 12 copy every time).

   !> Float64 dataset of Fortran shape `dims` from `a`.
   subroutine put_real(self, loc, name, dims, a, error)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer(hsize_t), intent(in) :: dims(:)
      real(wp), intent(in), target :: a(*)
      type(error_t), allocatable, intent(inout) :: error
      type(c_ptr) :: buf
      buf = c_null_ptr
      if (product(dims) > 0) buf = c_loc(a(1))
      call put_dataset(self, loc, name, H5T_IEEE_F64LE, h5kind_to_type(wp, H5_REAL_KIND), dims, &
                       buf, error)
   end subroutine put_real

   !> Int32 dataset of Fortran shape `dims` from `a`.
   subroutine put_int(self, loc, name, dims, a, error)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer(hsize_t), intent(in) :: dims(:)
      integer(ip), intent(in), target :: a(*)
      type(error_t), allocatable, intent(inout) :: error
      type(c_ptr) :: buf
      buf = c_null_ptr
      if (product(dims) > 0) buf = c_loc(a(1))
      call put_dataset(self, loc, name, H5T_STD_I32LE, h5kind_to_type(ip, H5_INTEGER_KIND), dims, &
                       buf, error)
   end subroutine put_int

   !> Int64 dataset of Fortran shape `dims` from `a`.
   subroutine put_i8(self, loc, name, dims, a, error)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer(hsize_t), intent(in) :: dims(:)
      integer(i8), intent(in), target :: a(*)
      type(error_t), allocatable, intent(inout) :: error
      type(c_ptr) :: buf
      buf = c_null_ptr
      if (product(dims) > 0) buf = c_loc(a(1))
      call put_dataset(self, loc, name, H5T_STD_I64LE, h5kind_to_type(i8, H5_INTEGER_KIND), dims, &
                       buf, error)
   end subroutine put_i8

   !> 1-D dataset of fixed-length, null-padded ASCII strings, as long as the
   !> longest value (h5py returns `bytes`).
   subroutine put_strings(self, loc, name, values, error)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      type(string_t), intent(in) :: values(:)
      type(error_t), allocatable, intent(inout) :: error
      character(len=1), allocatable, target :: buf(:, :)
      integer(hid_t) :: stype
      type(c_ptr) :: p
      integer :: hdferr, ignore, k, j, width
      width = 1
      do k = 1, size(values)
         width = max(width, len(values(k)%s))
      end do
      allocate (buf(width, size(values)))
      buf = achar(0)
      do k = 1, size(values)
         do j = 1, len(values(k)%s)
            buf(j, k) = values(k)%s(j:j)
         end do
      end do
      p = c_null_ptr
      if (size(values) > 0) p = c_loc(buf(1, 1))
      call h5tcopy_f(H5T_C_S1, stype, hdferr)
      if (failed(self, hdferr, 'creating the string type of '//name, error)) return
      call h5tset_size_f(stype, int(width, size_t), hdferr)
      if (.not. failed(self, hdferr, 'sizing the string type of '//name, error)) then
         call h5tset_strpad_f(stype, H5T_STR_NULLPAD_F, hdferr)
         if (.not. failed(self, hdferr, 'padding the string type of '//name, error)) &
            call put_dataset(self, loc, name, stype, stype, [size(values, kind=hsize_t)], p, error)
      end if
      if (allocated(error)) then
         call h5tclose_f(stype, ignore)
         return
      end if
      call h5tclose_f(stype, hdferr)
      if (failed(self, hdferr, 'closing the string type of '//name, error)) return
   end subroutine put_strings

   !> Attribute of `file_type` from `buf` of `mem_type`: a scalar, or with `length`
   !> a one-dimensional array of that many values.
   subroutine put_attribute(self, loc, name, file_type, mem_type, buf, error, length)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc, file_type, mem_type
      character(len=*), intent(in) :: name
      type(c_ptr), intent(in) :: buf
      type(error_t), allocatable, intent(inout) :: error
      integer, intent(in), optional :: length
      integer(hid_t) :: space, attr
      integer :: hdferr, ignore
      if (present(length)) then
         call h5screate_simple_f(1, [int(length, hsize_t)], space, hdferr)
      else
         call h5screate_f(H5S_SCALAR_F, space, hdferr)
      end if
      if (failed(self, hdferr, 'creating the dataspace of attribute '//name, error)) return
      call h5acreate_f(loc, name, file_type, space, attr, hdferr)
      if (failed(self, hdferr, 'creating attribute '//name, error)) then
         call h5sclose_f(space, ignore)
         return
      end if
      call h5awrite_f(attr, mem_type, buf, hdferr)
      if (failed(self, hdferr, 'writing attribute '//name, error)) then
         call h5aclose_f(attr, ignore)
         call h5sclose_f(space, ignore)
         return
      end if
      call h5aclose_f(attr, hdferr)
      if (failed(self, hdferr, 'closing attribute '//name, error)) then
         call h5sclose_f(space, ignore)
         return
      end if
      call h5sclose_f(space, hdferr)
      if (failed(self, hdferr, 'closing the dataspace of attribute '//name, error)) return
   end subroutine put_attribute

   subroutine put_real_attribute(self, loc, name, value, error)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: value
      type(error_t), allocatable, intent(inout) :: error
      real(wp), target :: buf
      buf = value
      call put_attribute(self, loc, name, H5T_IEEE_F64LE, h5kind_to_type(wp, H5_REAL_KIND), &
                         c_loc(buf), error)
   end subroutine put_real_attribute

   subroutine put_int_attribute(self, loc, name, value, error)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer(ip), intent(in) :: value
      type(error_t), allocatable, intent(inout) :: error
      integer(ip), target :: buf
      buf = value
      call put_attribute(self, loc, name, H5T_STD_I32LE, h5kind_to_type(ip, H5_INTEGER_KIND), &
                         c_loc(buf), error)
   end subroutine put_int_attribute

   !> One-dimensional 32-bit integer attribute `name` of `loc` holding `values` (one
   !> zero when `values` is empty: HDF5 has no empty simple dataspace).
   subroutine put_int_array_attribute(self, loc, name, values, error)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer(ip), intent(in) :: values(:)
      type(error_t), allocatable, intent(inout) :: error
      integer(ip), allocatable, target :: buf(:)
      buf = values
      if (size(buf) == 0) buf = [0_ip]
      call put_attribute(self, loc, name, H5T_STD_I32LE, h5kind_to_type(ip, H5_INTEGER_KIND), &
                         c_loc(buf), error, size(buf))
   end subroutine put_int_array_attribute

   !> The root attribute `solver` replaced by `solver`: the one that ran, when it is not
   !> the one the file was opened with (`auto`'s fallback to CHOLMOD).
   subroutine h5_set_solver(self, solver, error)
      class(h5_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: solver
      type(error_t), allocatable, intent(out) :: error
      integer :: hdferr
      logical :: exists
      call h5aexists_f(self%file, 'solver', exists, hdferr)
      if (failed(self, hdferr, 'looking up attribute solver', error)) return
      if (exists) then
         call h5adelete_f(self%file, 'solver', hdferr)
         if (failed(self, hdferr, 'deleting attribute solver', error)) return
      end if
      call put_string_attribute(self, self%file, 'solver', solver, error)
   end subroutine h5_set_solver

   !> Fixed-length, null-padded ASCII string attribute of exactly len(value)
   !> characters (h5py returns it as `bytes`).  An empty value is stored as one
   !> NUL, which null padding reads back as the empty string.
   subroutine put_string_attribute(self, loc, name, value, error)
      class(h5_writer_t), intent(in) :: self
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name, value
      type(error_t), allocatable, intent(inout) :: error
      character(len=1), allocatable, target :: buf(:)
      integer(hid_t) :: stype
      integer :: hdferr, ignore, k
      allocate (buf(max(1, len(value))))
      buf(1) = achar(0)
      do k = 1, len(value)
         buf(k) = value(k:k)
      end do
      call h5tcopy_f(H5T_C_S1, stype, hdferr)
      if (failed(self, hdferr, 'creating the string type of attribute '//name, error)) return
      call h5tset_size_f(stype, int(size(buf), size_t), hdferr)
      if (.not. failed(self, hdferr, 'sizing the string type of attribute '//name, error)) then
         call h5tset_strpad_f(stype, H5T_STR_NULLPAD_F, hdferr)
         if (.not. failed(self, hdferr, 'padding the string type of attribute '//name, error)) &
            call put_attribute(self, loc, name, stype, stype, c_loc(buf), error)
      end if
      if (allocated(error)) then
         call h5tclose_f(stype, ignore)
         return
      end if
      call h5tclose_f(stype, hdferr)
      if (failed(self, hdferr, 'closing the string type of attribute '//name, error)) return
   end subroutine put_string_attribute
end module vemcontact_output_hdf5
