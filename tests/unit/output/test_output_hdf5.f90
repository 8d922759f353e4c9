!> HDF5 results file: written with h5_writer_t, read back with the HDF5
!> Fortran API.  Checks the root attributes, the mesh datasets (shapes in
!> Fortran order, 0-based connectivity and offsets), two steps' attributes and
!> that U, S_element, S_node come back bit-identical; the labels and the
!> strain/reaction datasets (checked by check_hdf5.py); and the errors for an
!> unwritable path and for writing before opening.  The file goes next to the
!> test executable (build tree); check_hdf5.py then reads it with h5py
!> (CTest test test_output_hdf5_h5py) to confirm the layout as Python sees it.
program test_output_hdf5
   use, intrinsic :: iso_c_binding, only: c_ptr, c_loc
   use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5fopen_f, h5fclose_f, h5dopen_f, h5dclose_f, &
                   h5dread_f, h5dget_space_f, h5sget_simple_extent_ndims_f, &
                   h5sget_simple_extent_dims_f, h5sclose_f, h5aopen_f, h5aread_f, h5aclose_f, &
                   h5aget_type_f, h5tget_size_f, h5tclose_f, h5kind_to_type, &
                   H5F_ACC_RDONLY_F, H5_REAL_KIND, H5_INTEGER_KIND
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, err_io, err_internal
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: model_t, string_t, etype_polygon, etype_quad4, etype_tri3, form_vem, &
                               form_fem, plane_strain
   use vemcontact_output_hdf5, only: h5_writer_t
   implicit none
   type(checker_t) :: t
   type(model_t) :: model
   type(h5_writer_t) :: w, w2
   type(error_t), allocatable :: error
   real(wp), allocatable :: u1(:, :), u2(:, :), s_elem(:, :), s_node(:, :)
   type(string_t), allocatable :: set_names(:)
   character(len=:), allocatable :: path
   integer(hid_t) :: file
   integer :: hdferr, i

   path = output_dir()//'test_output_hdf5.h5'
   call make_mesh(model)
   allocate (u1(2, model%nnode), u2(2, model%nnode), s_elem(4, model%nelem), s_node(4, model%nnode))
   do i = 1, model%nnode
      u1(:, i) = [sin(real(i, wp))*1.0e-3_wp, -cos(real(i, wp))/3.0_wp]
      s_node(:, i) = [real(i, wp)/7.0_wp, -real(i, wp)**2/11.0_wp, 1.0_wp/real(i + 2, wp), &
                      exp(real(i, wp))]
   end do
   u2 = 2.0_wp*u1 + 1.0_wp/3.0_wp
   do i = 1, model%nelem
      s_elem(:, i) = [1.0e8_wp/real(i, wp), -3.0e-9_wp*i, sqrt(real(i, wp)), -1.0_wp/3.0_wp]
   end do

   ! errors: writing before opening; opening in a missing folder
   call w%write_mesh(model, error)
   call t%check(allocated(error), 'write_mesh before open fails')
   if (allocated(error)) call t%equal(error%code, err_internal, 'write_mesh before open: internal')
   call w2%open(output_dir()//'no-such-dir/x.h5', error)
   call t%check(allocated(error), 'open in a missing folder fails')
   if (allocated(error)) then
      call t%equal(error%code, err_io, 'missing folder: i/o error')
      call t%check(index(error%message, 'no-such-dir/x.h5') > 0, 'missing folder: message names file')
   end if
   call t%check(.not. w2%is_open(), 'failed open leaves the writer closed')

   ! write mesh and two steps
   call w%open(path, error)
   call t%check(.not. allocated(error), 'open')
   if (allocated(error)) print '(a)', error%message
   call w%write_mesh(model, error)
   call t%check(.not. allocated(error), 'write_mesh')
   call w%write_step(1, 'LOAD', 1.0_wp, u1, s_elem, s_node, error)
   call t%check(.not. allocated(error), 'write_step 1')
   ! labels (element sets, materials, parts) and the strains and reactions of step 1
   allocate (model%elsets(3), model%materials(2))
   model%elsets(1)%name = 'PLATE'
   model%elsets(2)%name = 'A_LONGER_SET_NAME'
   model%elsets(3)%name = 'Q'
   model%materials(1)%name = 'ROCK'
   model%materials(2)%name = 'CONCRETE'
   call w%write_labels(model, [3_ip, 1_ip, 0_ip], [1_ip, 1_ip, 2_ip], error)
   call t%check(.not. allocated(error), 'write_labels')
   call w%write_labels(model, [3_ip, 1_ip], [1_ip, 1_ip], error)
   call t%check(allocated(error), 'write_labels with too few elements fails')
   allocate (set_names(2))
   set_names(1)%s = 'BASE'
   set_names(2)%s = 'SIDE'
   call w%write_results(1, 0.5_wp*s_elem, 0.25_wp*s_node, 3.0_wp*u1, set_names, &
                        reshape([1.0_wp, 2.0_wp, -3.0_wp, 0.5_wp], [2, 2]), error)
   call t%check(.not. allocated(error), 'write_results')
   call w%write_results(1, s_elem, s_node, u1(:, 1:2), set_names, reshape([1.0_wp, 2.0_wp], [2, 1]), error)
   call t%check(allocated(error), 'write_results with wrong shapes fails')
   call w%write_step(2, 'UNLOAD step', 0.1_wp, u2, 2.0_wp*s_elem, -s_node, error)
   call t%check(.not. allocated(error), 'write_step 2')
   call w%write_step(2, 'again', 0.2_wp, u2, s_elem, s_node, error)
   call t%check(allocated(error), 'writing step 2 twice fails')
   if (allocated(error)) call t%check(index(error%message, path) > 0, 'step twice: message names file')
   call w%write_step(3, 'short', 0.3_wp, u1(:, 1:2), s_elem, s_node(:, 1:2), error)
   call t%check(allocated(error), 'a step with fewer nodes than the mesh fails')
   if (allocated(error)) call t%equal(error%code, err_internal, 'short step: internal error')
   call w%close(error)
   call t%check(.not. allocated(error), 'close')
   call t%check(.not. w%is_open(), 'closed')

   ! read back
   call h5open_f(hdferr)
   call h5fopen_f(path, H5F_ACC_RDONLY_F, file, hdferr)
   call t%equal(hdferr, 0, 'reopen the file')
   call t%check(read_string_attr(file, '/', 'format') == 'vemcontact-results', 'attribute format')
   call t%equal(read_int_attr(file, '/', 'format_version'), 1, 'attribute format_version')
   call check_real_2(file, '/mesh/coordinates', model%x, 'coordinates')
   call check_int_1(file, '/mesh/node_ids', model%node_id, 'node_ids')
   call check_i8_1(file, '/mesh/element_offsets', [0_i8, 5_i8, 9_i8, 12_i8], 'element_offsets')
   call check_int_1(file, '/mesh/element_connectivity', &
                    [0_ip, 1_ip, 2_ip, 3_ip, 4_ip, 1_ip, 5_ip, 6_ip, 2_ip, 5_ip, 7_ip, 6_ip], &
                    'element_connectivity')
   call check_int_1(file, '/mesh/element_ids', model%elem_id, 'element_ids')
   call check_int_1(file, '/mesh/element_material', [1_ip, 2_ip, 1_ip], 'element_material')
   call check_int_1(file, '/mesh/element_type', &
                    int([etype_polygon, etype_quad4, etype_tri3], ip), 'element_type')
   call check_int_1(file, '/mesh/element_formulation', int([form_vem, form_fem, form_fem], ip), &
                    'element_formulation')
   call t%check(read_string_attr(file, '/steps/0001', 'name') == 'LOAD', 'step 1 name')
   call t%check(same_bits([read_real_attr(file, '/steps/0001', 'time')], [1.0_wp]), 'step 1 time')
   call t%check(read_string_attr(file, '/steps/0002', 'name') == 'UNLOAD step', 'step 2 name')
   call t%check(same_bits([read_real_attr(file, '/steps/0002', 'time')], [0.1_wp]), 'step 2 time')
   call check_real_2(file, '/steps/0001/U', u1, 'step 1 U')
   call check_real_2(file, '/steps/0001/S_element', s_elem, 'step 1 S_element')
   call check_real_2(file, '/steps/0001/S_node', s_node, 'step 1 S_node')
   call check_real_2(file, '/steps/0002/U', u2, 'step 2 U')
   call check_real_2(file, '/steps/0002/S_element', 2.0_wp*s_elem, 'step 2 S_element')
   call check_real_2(file, '/steps/0002/S_node', -s_node, 'step 2 S_node')
   call h5fclose_f(file, hdferr)
   call t%equal(hdferr, 0, 'close the file after reading')

   call t%finish()

contains

   !> Folder of this executable (with trailing '/'), './' if invoked without one.
   function output_dir() result(d)
      character(len=:), allocatable :: d
      character(len=4096) :: arg0
      integer :: k
      call get_command_argument(0, arg0)
      k = index(arg0, '/', back=.true.)
      if (k == 0) then
         d = './'
      else
         d = arg0(1:k)
      end if
   end function output_dir

   !> Pentagon, quad, triangle and an unconnected node, as in test_output_vtu.
   subroutine make_mesh(m)
      type(model_t), intent(out) :: m
      m%nnode = 9
      m%x = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.5_wp, 0.8_wp, 0.5_wp, 1.4_wp, -0.5_wp, 0.8_wp, &
                     2.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 3.0_wp, 0.5_wp, 0.1_wp, -0.3_wp], [2, 9])
      m%node_id = [(10_ip*i + 1_ip, i=1, 9)]
      m%nelem = 3
      m%elem_id = [100_ip, 205_ip, 307_ip]
      m%elem_ptr = [1_ip, 6_ip, 10_ip, 13_ip]
      m%elem_conn = [1_ip, 2_ip, 3_ip, 4_ip, 5_ip, 2_ip, 6_ip, 7_ip, 3_ip, 6_ip, 8_ip, 7_ip]
      m%elem_type = [etype_polygon, etype_quad4, etype_tri3]
      m%elem_form = [form_vem, form_fem, form_fem]
      m%elem_plane = [plane_strain, plane_strain, plane_strain]
      m%elem_mat = [1, 2, 1]
      m%elem_thick = [1.0_wp, 1.0_wp, 1.0_wp]
   end subroutine make_mesh

   pure logical function same_bits(a, b)
      real(wp), intent(in) :: a(:), b(:)
      same_bits = size(a) == size(b)
      if (same_bits) same_bits = all(transfer(a, [0_i8]) == transfer(b, [0_i8]))
   end function same_bits

   !> Open dataset `name`, check its rank and Fortran-order dims; returns the handle.
   subroutine open_dataset(file, name, expected_dims, dset, ok)
      integer(hid_t), intent(in) :: file
      character(len=*), intent(in) :: name
      integer, intent(in) :: expected_dims(:)
      integer(hid_t), intent(out) :: dset
      logical, intent(out) :: ok
      integer(hid_t) :: space
      integer(hsize_t) :: dims(2), maxdims(2)
      integer :: rank, err
      call h5dopen_f(file, name, dset, err)
      call t%equal(err, 0, 'open '//name)
      ok = err == 0
      if (.not. ok) return
      call h5dget_space_f(dset, space, err)
      call h5sget_simple_extent_ndims_f(space, rank, err)
      call t%equal(rank, size(expected_dims), 'rank of '//name)
      call h5sget_simple_extent_dims_f(space, dims(1:rank), maxdims(1:rank), err)
      call t%check(all(int(dims(1:rank)) == expected_dims), 'dims of '//name)
      call h5sclose_f(space, err)
   end subroutine open_dataset

   subroutine check_real_2(file, name, expected, what)
      integer(hid_t), intent(in) :: file
      character(len=*), intent(in) :: name, what
      real(wp), intent(in) :: expected(:, :)
      real(wp), allocatable, target :: a(:, :)
      integer(hid_t) :: dset
      integer :: err
      type(c_ptr) :: ptr
      logical :: ok
      call open_dataset(file, name, shape(expected), dset, ok)
      if (.not. ok) return
      allocate (a(size(expected, 1), size(expected, 2)))
      ptr = c_loc(a)
      call h5dread_f(dset, h5kind_to_type(wp, H5_REAL_KIND), ptr, err)
      call t%equal(err, 0, 'read '//name)
      call t%check(same_bits(reshape(a, [size(a)]), reshape(expected, [size(a)])), &
                   what//' bit-identical')
      call h5dclose_f(dset, err)
   end subroutine check_real_2

   subroutine check_int_1(file, name, expected, what)
      integer(hid_t), intent(in) :: file
      character(len=*), intent(in) :: name, what
      integer(ip), intent(in) :: expected(:)
      integer(ip), allocatable, target :: a(:)
      integer(hid_t) :: dset
      integer :: err
      type(c_ptr) :: ptr
      logical :: ok
      call open_dataset(file, name, shape(expected), dset, ok)
      if (.not. ok) return
      allocate (a(size(expected)))
      ptr = c_loc(a)
      call h5dread_f(dset, h5kind_to_type(ip, H5_INTEGER_KIND), ptr, err)
      call t%equal(err, 0, 'read '//name)
      call t%check(all(a == expected), what)
      call h5dclose_f(dset, err)
   end subroutine check_int_1

   subroutine check_i8_1(file, name, expected, what)
      integer(hid_t), intent(in) :: file
      character(len=*), intent(in) :: name, what
      integer(i8), intent(in) :: expected(:)
      integer(i8), allocatable, target :: a(:)
      integer(hid_t) :: dset
      integer :: err
      type(c_ptr) :: ptr
      logical :: ok
      call open_dataset(file, name, shape(expected), dset, ok)
      if (.not. ok) return
      allocate (a(size(expected)))
      ptr = c_loc(a)
      call h5dread_f(dset, h5kind_to_type(i8, H5_INTEGER_KIND), ptr, err)
      call t%equal(err, 0, 'read '//name)
      call t%check(all(a == expected), what)
      call h5dclose_f(dset, err)
   end subroutine check_i8_1

   function read_string_attr(file, obj, name) result(s)
      integer(hid_t), intent(in) :: file
      character(len=*), intent(in) :: obj, name
      character(len=:), allocatable :: s
      character(len=1), allocatable, target :: buf(:)
      integer(hid_t) :: attr, atype, loc
      integer(size_t) :: n
      integer :: err, k
      type(c_ptr) :: ptr
      call open_object(file, obj, loc)
      call h5aopen_f(loc, name, attr, err)
      call t%equal(err, 0, 'open attribute '//obj//' '//name)
      call h5aget_type_f(attr, atype, err)
      call h5tget_size_f(atype, n, err)
      allocate (buf(n))
      ptr = c_loc(buf)
      call h5aread_f(attr, atype, ptr, err)
      call t%equal(err, 0, 'read attribute '//obj//' '//name)
      s = ''
      do k = 1, int(n)
         if (buf(k) == achar(0)) exit
         s = s//buf(k)
      end do
      call h5tclose_f(atype, err)
      call h5aclose_f(attr, err)
      call close_object(file, loc)
   end function read_string_attr

   integer function read_int_attr(file, obj, name) result(v)
      integer(hid_t), intent(in) :: file
      character(len=*), intent(in) :: obj, name
      integer(ip), target :: buf
      integer(hid_t) :: attr, loc
      integer :: err
      type(c_ptr) :: ptr
      call open_object(file, obj, loc)
      call h5aopen_f(loc, name, attr, err)
      ptr = c_loc(buf)
      call h5aread_f(attr, h5kind_to_type(ip, H5_INTEGER_KIND), ptr, err)
      call t%equal(err, 0, 'read attribute '//obj//' '//name)
      v = int(buf)
      call h5aclose_f(attr, err)
      call close_object(file, loc)
   end function read_int_attr

   real(wp) function read_real_attr(file, obj, name) result(v)
      integer(hid_t), intent(in) :: file
      character(len=*), intent(in) :: obj, name
      real(wp), target :: buf
      integer(hid_t) :: attr, loc
      integer :: err
      type(c_ptr) :: ptr
      call open_object(file, obj, loc)
      call h5aopen_f(loc, name, attr, err)
      ptr = c_loc(buf)
      call h5aread_f(attr, h5kind_to_type(wp, H5_REAL_KIND), ptr, err)
      call t%equal(err, 0, 'read attribute '//obj//' '//name)
      v = buf
      call h5aclose_f(attr, err)
      call close_object(file, loc)
   end function read_real_attr

   !> Group handle of `obj` ('/' is the file itself).
   subroutine open_object(file, obj, loc)
      use hdf5, only: h5gopen_f
      integer(hid_t), intent(in) :: file
      character(len=*), intent(in) :: obj
      integer(hid_t), intent(out) :: loc
      integer :: err
      if (obj == '/') then
         loc = file
      else
         call h5gopen_f(file, obj, loc, err)
         call t%equal(err, 0, 'open group '//obj)
      end if
   end subroutine open_object

   subroutine close_object(file, loc)
      use hdf5, only: h5gclose_f
      integer(hid_t), intent(in) :: file, loc
      integer :: err
      if (loc /= file) call h5gclose_f(loc, err)
   end subroutine close_object
end program test_output_hdf5
