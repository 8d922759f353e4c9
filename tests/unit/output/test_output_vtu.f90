!> VTU and PVD writers.  Writes a mesh of a pentagon, a quad and a triangle
!> (plus a node in no element) with deterministic, non-round field values, and
!> the values it expects a reader to find as text with 18 significant digits
!> (enough to read back as the same doubles).  check_vtu.py reads the .vtu
!> (zlib-compressed, and raw as test_output_vtu_raw.vtu) with meshio and
!> compares exactly (CTest test test_output_vtu_meshio).
!> Files go next to the test executable, i.e. into the build tree.
!> This program itself checks the atomic write (no .tmp left behind), the
!> errors for bad shapes and unwritable paths, and the .pvd text.
program test_output_vtu
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, err_io, err_internal
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: model_t, string_t, etype_polygon, etype_quad4, etype_tri3, &
                               form_vem, form_fem, plane_strain
   use vemcontact_post_stress, only: principal_stresses
   use vemcontact_output_vtu, only: write_vtu, vtu_extras_t
   use vemcontact_output_pvd, only: write_pvd, relative_path
   implicit none
   type(checker_t) :: t
   type(model_t) :: model
   type(error_t), allocatable :: error
   real(wp), allocatable :: u(:, :), s_elem(:, :), s_node(:, :)
   character(len=:), allocatable :: dir, vtu, rel, text
   type(string_t) :: files(2)
   type(vtu_extras_t) :: extra
   logical :: exists, ok
   integer :: i

   dir = output_dir()
   call make_mesh(model)
   allocate (u(2, model%nnode), s_elem(4, model%nelem), s_node(4, model%nnode))
   do i = 1, model%nnode
      u(:, i) = [sin(real(i, wp))*1.0e-3_wp, -cos(real(i, wp))/3.0_wp]
      s_node(:, i) = [real(i, wp)/7.0_wp, -real(i, wp)**2/11.0_wp, 1.0_wp/real(i + 2, wp), &
                      exp(real(i, wp))]
   end do
   s_node(:, model%nnode) = 0.0_wp
   do i = 1, model%nelem
      s_elem(:, i) = [1.0e8_wp/real(i, wp), -3.0e-9_wp*i, sqrt(real(i, wp)), -1.0_wp/3.0_wp]
   end do

   vtu = dir//'test_output_vtu.vtu'
   call write_vtu(vtu, model, u, s_elem, s_node, error)
   call t%check(.not. allocated(error), 'write_vtu succeeds')
   if (allocated(error)) print '(a)', error%message
   inquire (file=vtu, exist=exists)
   call t%check(exists, 'the .vtu exists')
   inquire (file=vtu//'.tmp', exist=exists)
   call t%check(.not. exists, 'no .tmp left behind')
   call write_expected(dir//'test_output_vtu.expected', model, u, s_elem, s_node)
   ! the same uncompressed (--raw-vtu)
   call write_vtu(dir//'test_output_vtu_raw.vtu', model, u, s_elem, s_node, error, compress=.false.)
   call t%check(.not. allocated(error), 'write_vtu (raw) succeeds')
   ! with the extras: E = S/1000 (xy engineering), RF = 5 U, ELSET, PART, names, time;
   ! the set names need XML escaping
   allocate (model%elsets(3), model%materials(2))
   model%elsets(1)%name = 'PLATE'
   model%elsets(2)%name = 'A&B<C>'
   model%elsets(3)%name = 'UNUSED'
   model%materials(1)%name = 'ROCK'
   model%materials(2)%name = 'CONCRETE'
   extra%e_node = s_node/1000.0_wp
   extra%e_elem = s_elem/1000.0_wp
   extra%rf = 5.0_wp*u
   extra%elem_set = [2_ip, 1_ip, 2_ip]
   extra%elem_part = [1_ip, 1_ip, 2_ip]
   extra%time = 2.5_wp
   call write_vtu(dir//'test_output_vtu_extra.vtu', model, u, s_elem, s_node, error, extra=extra)
   call t%check(.not. allocated(error), 'write_vtu (extras) succeeds')
   extra%elem_part = [1_ip, 1_ip]
   call write_vtu(dir//'test_output_vtu_bad.vtu', model, u, s_elem, s_node, error, extra=extra)
   call t%check(allocated(error), 'write_vtu rejects a short extra array')

   ! wrong shape: internal error, nothing written
   call write_vtu(dir//'test_output_vtu_bad.vtu', model, u(:, 1:2), s_elem, s_node, error)
   call t%check(allocated(error), 'write_vtu rejects a short u')
   if (allocated(error)) call t%equal(error%code, err_internal, 'short u: internal error')
   ! unwritable path: i/o error naming the file
   call write_vtu(dir//'no-such-dir/x.vtu', model, u, s_elem, s_node, error)
   call t%check(allocated(error), 'write_vtu into a missing folder fails')
   if (allocated(error)) then
      call t%equal(error%code, err_io, 'missing folder: i/o error')
      call t%check(index(error%message, 'no-such-dir/x.vtu') > 0, 'missing folder: message names file')
   end if

   ! relative paths for the .pvd
   call relative_path('out/a_0001.vtu', 'out', rel, ok)
   call t%check(ok .and. rel == 'a_0001.vtu', 'relative: same folder')
   call relative_path('./out/vtu/a.vtu', 'out/', rel, ok)
   call t%check(ok .and. rel == 'vtu/a.vtu', 'relative: subfolder, ./ and trailing /')
   call relative_path('vtu/a.vtu', 'out/pvd', rel, ok)
   call t%check(ok .and. rel == '../../vtu/a.vtu', 'relative: sibling tree')
   call relative_path('/r/x/../y/a.vtu', '/r/y', rel, ok)
   call t%check(ok .and. rel == 'a.vtu', 'relative: absolute with ..')
   call relative_path('a.vtu', '', rel, ok)
   call t%check(ok .and. rel == 'a.vtu', 'relative: .pvd in the working folder')
   call relative_path('/abs/a.vtu', 'out', rel, ok)
   call t%check(ok .and. rel == '/abs/a.vtu', 'relative: absolute file kept')
   call relative_path('a.vtu', '/abs', rel, ok)
   call t%check(.not. ok, 'relative: relative file, absolute folder: cannot')
   call relative_path('a.vtu', '../out', rel, ok)
   call t%check(.not. ok, 'relative: folder above the working folder: cannot')

   ! .pvd: files relative to its folder, times with 17 digits, XML escaped
   files(1)%s = dir//'test_output_vtu.vtu'
   files(2)%s = dir//'sub/b&c.vtu'
   call write_pvd(dir//'test_output_vtu.pvd', files, [0.0_wp, 0.1_wp], error)
   call t%check(.not. allocated(error), 'write_pvd succeeds')
   text = read_text(dir//'test_output_vtu.pvd')
   call t%check(text == '<?xml version="1.0"?>'//new_line('a') &
                //'<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">'//new_line('a') &
                //'<Collection>'//new_line('a') &
                //'<DataSet timestep="0.0000000000000000E+000" group="" part="0" file="test_output_vtu.vtu"/>' &
                //new_line('a') &
                //'<DataSet timestep="1.0000000000000001E-001" group="" part="0" file="sub/b&amp;c.vtu"/>' &
                //new_line('a')//'</Collection>'//new_line('a')//'</VTKFile>'//new_line('a'), &
                '.pvd text')
   inquire (file=dir//'test_output_vtu.pvd.tmp', exist=exists)
   call t%check(.not. exists, 'no .pvd.tmp left behind')
   call write_pvd(dir//'test_output_vtu.pvd', files(1:1), [0.0_wp, 1.0_wp], error)
   call t%check(allocated(error), 'write_pvd rejects mismatched lengths')

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

   !> Nodes 1-5 pentagon, 2-6-7-3 quad, 6-8-7 triangle, node 9 in no element;
   !> user ids not equal to the indices.
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

   !> What a reader must find: "array NAME NROWS NCOLS" then rows; "cells N"
   !> then "nverts i1 i2 ..." with 0-based indices.
   subroutine write_expected(path, m, u, s_elem, s_node)
      character(len=*), intent(in) :: path
      type(model_t), intent(in) :: m
      real(wp), intent(in) :: u(:, :), s_elem(:, :), s_node(:, :)
      real(wp) :: p(3, m%nnode)
      integer :: unit, e, n
      open (newunit=unit, file=path, status='replace', action='write')
      write (unit, '(a,i0,a)') 'array points ', m%nnode, ' 3'
      write (unit, '(3es26.17e3)') (m%x(:, n), 0.0_wp, n=1, m%nnode)
      write (unit, '(a,i0,a)') 'array U ', m%nnode, ' 3'
      write (unit, '(3es26.17e3)') (u(:, n), 0.0_wp, n=1, m%nnode)
      write (unit, '(a,i0,a)') 'array S_point ', m%nnode, ' 4'
      write (unit, '(4es26.17e3)') s_node
      do n = 1, m%nnode
         call principal_stresses(s_node(:, n), p(1, n), p(2, n), p(3, n))
      end do
      write (unit, '(a,i0,a)') 'array S1 ', m%nnode, ' 1'
      write (unit, '(es26.17e3)') p(1, :)
      write (unit, '(a,i0,a)') 'array S3 ', m%nnode, ' 1'
      write (unit, '(es26.17e3)') p(2, :)
      write (unit, '(a,i0,a)') 'array MISES ', m%nnode, ' 1'
      write (unit, '(es26.17e3)') p(3, :)
      write (unit, '(a,i0,a)') 'array NODE_ID ', m%nnode, ' 1'
      write (unit, '(i0)') m%node_id
      write (unit, '(a,i0,a)') 'array S_cell ', m%nelem, ' 4'
      write (unit, '(4es26.17e3)') s_elem
      write (unit, '(a,i0,a)') 'array MATERIAL ', m%nelem, ' 1'
      write (unit, '(i0)') m%elem_mat
      write (unit, '(a,i0,a)') 'array ELEMENT_ID ', m%nelem, ' 1'
      write (unit, '(i0)') m%elem_id
      write (unit, '(a,i0)') 'cells ', m%nelem
      do e = 1, m%nelem
         write (unit, '(*(i0,:,1x))') m%elem_ptr(e + 1) - m%elem_ptr(e), &
            m%elem_conn(m%elem_ptr(e):m%elem_ptr(e + 1) - 1) - 1
      end do
      close (unit)
   end subroutine write_expected

   !> Whole file as one string.
   function read_text(path) result(s)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: s
      integer :: unit, n
      open (newunit=unit, file=path, access='stream', form='unformatted', action='read')
      inquire (unit=unit, size=n)
      allocate (character(len=n) :: s)
      read (unit) s
      close (unit)
   end function read_text
end program test_output_vtu
