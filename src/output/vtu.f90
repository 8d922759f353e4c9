!> VTK XML UnstructuredGrid (.vtu) writer: version 1.0, UInt64 block headers,
!> inline base64 "binary" arrays, so every double is stored exactly.
!>
!> Every element is written as VTK_POLYGON (7), triangles and quads included:
!> one cell type keeps the file uniform (VEM meshes mix polygons of any size
!> with FEM cells), the element's own kind is in `/mesh/element_type` of the
!> HDF5 file, and linear triangles and quads render identically as polygons.
!>
!> The file is written with stream access as raw bytes (XML text and base64
!> payloads), never a formatted write per number, to `path//'.tmp'`, and renamed
!> to `path` only when complete: a crash leaves the previous file (or none),
!> never a truncated one.  The rename goes through C's `rename` (atomic on
!> POSIX file systems), the one interop spot of this module.
module vemcontact_output_vtu
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_io, err_internal
   use vemcontact_model, only: model_t
   use vemcontact_post_stress, only: principal_stresses
   use vemcontact_output_base64, only: base64_encode, base64_length, as_bytes
   implicit none
   private

   public :: write_vtu, replace_file, put, put_array, byte_order, int_type_name, itoa

   !> VTK cell type of every element.
   integer, parameter :: vtk_polygon = 7
   !> Bytes encoded per piece: a multiple of 3 so that pieces join without padding;
   !> 3 MiB keeps the encoded buffer (4 MiB) in cache-friendly range.
   integer(i8), parameter :: piece_bytes = 3_i8*1048576_i8

   interface
      function c_rename(old, new) bind(C, name='rename') result(rc)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: old(*), new(*)
         integer(c_int) :: rc
      end function c_rename
   end interface

contains

   !> Write the mesh with displacements and stresses to the .vtu file `path`.
   !> Point data: U (3 comps, z = 0), S (xx,yy,zz,xy averaged at nodes), S1, S3,
   !> MISES, NODE_ID; cell data: S (element stress), MATERIAL, ELEMENT_ID and, when
   !> given, ERROR_INDICATOR (vemcontact_post_estimate).
   subroutine write_vtu(path, model, u, s_elem, s_node, error, indicator)
      character(len=*), intent(in) :: path
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:, :)        !< (2, nnode)
      real(wp), intent(in) :: s_elem(:, :)   !< (4, nelem)
      real(wp), intent(in) :: s_node(:, :)   !< (4, nnode)
      type(error_t), allocatable, intent(out) :: error
      real(wp), intent(in), optional :: indicator(:)  !< (nelem) error indicator per cell
      character(len=:), allocatable :: tmp, itype
      character(len=*), parameter :: s_names = ' ComponentName0="XX" ComponentName1="YY"' &
                                      //' ComponentName2="ZZ" ComponentName3="XY"'
      character(len=512) :: msg
      real(wp), allocatable :: xyz(:, :), p1(:), p3(:), vm(:)
      integer(ip), allocatable :: ibuf(:)
      character(len=:), allocatable :: types
      integer(ip) :: i
      integer :: unit, ios
      character(len=1), parameter :: nl = new_line('a')

      if (size(u, 1) /= 2 .or. size(u, 2) /= model%nnode .or. size(s_elem, 1) /= 4 &
          .or. size(s_elem, 2) /= model%nelem .or. size(s_node, 1) /= 4 &
          .or. size(s_node, 2) /= model%nnode) then
         call fatal_error(error, 'write_vtu: array shapes do not match the model ('//path//')', &
                          err_internal)
         return
      end if
      if (present(indicator)) then
         if (size(indicator) /= model%nelem) then
            call fatal_error(error, 'write_vtu: indicator size does not match the model ('//path//')', &
                             err_internal)
            return
         end if
      end if
      itype = int_type_name()
      tmp = path//'.tmp'
      open (newunit=unit, file=tmp, access='stream', form='unformatted', status='replace', &
            action='write', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, 'cannot open '''//tmp//''' for writing: '//trim(msg), err_io)
         return
      end if

      call put(unit, '<?xml version="1.0"?>'//nl &
               //'<VTKFile type="UnstructuredGrid" version="1.0" byte_order="'//byte_order() &
               //'" header_type="UInt64">'//nl//'<UnstructuredGrid>'//nl &
               //'<Piece NumberOfPoints="'//itoa(int(model%nnode, i8)) &
               //'" NumberOfCells="'//itoa(int(model%nelem, i8))//'">'//nl, ios)

      ! point data
      call put(unit, '<PointData Vectors="U">'//nl, ios)
      allocate (xyz(3, model%nnode))
      xyz(1:2, :) = u
      xyz(3, :) = 0.0_wp
      call put_array(unit, 'type="Float64" Name="U" NumberOfComponents="3"', as_bytes(xyz), ios)
      call put_array(unit, 'type="Float64" Name="S" NumberOfComponents="4"'//s_names, &
                     as_bytes(s_node), ios)
      allocate (p1(model%nnode), p3(model%nnode), vm(model%nnode))
      do i = 1, model%nnode
         call principal_stresses(s_node(:, i), p1(i), p3(i), vm(i))
      end do
      call put_array(unit, 'type="Float64" Name="S1"', as_bytes(p1), ios)
      call put_array(unit, 'type="Float64" Name="S3"', as_bytes(p3), ios)
      call put_array(unit, 'type="Float64" Name="MISES"', as_bytes(vm), ios)
      deallocate (p1, p3, vm)
      call put_array(unit, 'type="'//itype//'" Name="NODE_ID"', as_bytes(model%node_id(1:model%nnode)), ios)
      call put(unit, '</PointData>'//nl, ios)

      ! cell data
      call put(unit, '<CellData>'//nl, ios)
      call put_array(unit, 'type="Float64" Name="S" NumberOfComponents="4"'//s_names, &
                     as_bytes(s_elem), ios)
      allocate (ibuf(model%nelem))
      ibuf = int(model%elem_mat(1:model%nelem), ip)
      call put_array(unit, 'type="'//itype//'" Name="MATERIAL"', as_bytes(ibuf), ios)
      call put_array(unit, 'type="'//itype//'" Name="ELEMENT_ID"', as_bytes(model%elem_id(1:model%nelem)), ios)
      if (present(indicator)) &
         call put_array(unit, 'type="Float64" Name="ERROR_INDICATOR"', as_bytes(indicator(1:model%nelem)), ios)
      call put(unit, '</CellData>'//nl, ios)

      ! geometry: z = 0
      xyz(1:2, :) = model%x(:, 1:model%nnode)
      xyz(3, :) = 0.0_wp
      call put(unit, '<Points>'//nl, ios)
      call put_array(unit, 'type="Float64" Name="Points" NumberOfComponents="3"', as_bytes(xyz), ios)
      call put(unit, '</Points>'//nl, ios)
      deallocate (xyz)

      ! topology: 0-based connectivity, offsets = end of each cell (VTK XML convention)
      call put(unit, '<Cells>'//nl, ios)
      call put_array(unit, 'type="'//itype//'" Name="connectivity"', &
                     as_bytes(model%elem_conn(1:model%elem_ptr(model%nelem + 1) - 1) - 1_ip), ios)
      ibuf = model%elem_ptr(2:model%nelem + 1) - 1_ip
      call put_array(unit, 'type="'//itype//'" Name="offsets"', as_bytes(ibuf), ios)
      types = repeat(achar(vtk_polygon), model%nelem)
      call put_array(unit, 'type="UInt8" Name="types"', types, ios)
      call put(unit, '</Cells>'//nl//'</Piece>'//nl//'</UnstructuredGrid>'//nl//'</VTKFile>'//nl, ios)

      if (ios /= 0) then
         close (unit, status='delete', iostat=ios)
         call fatal_error(error, 'error while writing '''//tmp//'''', err_io)
         return
      end if
      close (unit, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, 'cannot close '''//tmp//''': '//trim(msg), err_io)
         return
      end if
      call replace_file(tmp, path, error)
   end subroutine write_vtu

   !> Rename `from` to `to`, replacing `to` atomically (POSIX rename).
   subroutine replace_file(from, to, error)
      character(len=*), intent(in) :: from, to
      type(error_t), allocatable, intent(out) :: error
      if (c_rename(from//c_null_char, to//c_null_char) /= 0_c_int) then
         call fatal_error(error, 'cannot rename '''//from//''' to '''//to//'''', err_io)
      end if
   end subroutine replace_file

   !> Write text bytes unless an earlier write failed.
   subroutine put(unit, text, ios)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: text
      integer, intent(inout) :: ios
      if (ios /= 0) return
      write (unit, iostat=ios) text
   end subroutine put

   !> One binary DataArray: base64 of (UInt64 byte count, data), encoded as one
   !> stream as VTK does for uncompressed data.  The 8-byte header plus the first
   !> data byte form a first 9-byte piece; the rest goes in pieces of
   !> `piece_bytes` (a multiple of 3), so the text is that of one encoding.
   subroutine put_array(unit, attributes, bytes, ios)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: attributes
      character(len=*), intent(in) :: bytes
      integer, intent(inout) :: ios
      character(len=:), allocatable :: buf
      integer(i8) :: nb, first, last, nout
      nb = len(bytes, kind=i8)
      call put(unit, '<DataArray '//attributes//' format="binary">'//new_line('a'), ios)
      if (ios /= 0) return
      allocate (character(len=base64_length(max(piece_bytes, 9_i8))) :: buf)
      first = min(1_i8, nb)
      call base64_encode(as_bytes(nb)//bytes(1:first), buf)
      write (unit, iostat=ios) buf(1:base64_length(8_i8 + first))
      first = first + 1
      do while (first <= nb .and. ios == 0)
         last = min(nb, first + piece_bytes - 1)
         call base64_encode(bytes(first:last), buf)
         nout = base64_length(last - first + 1)
         write (unit, iostat=ios) buf(1:nout)
         first = last + 1
      end do
      call put(unit, new_line('a')//'</DataArray>'//new_line('a'), ios)
   end subroutine put_array

   !> VTK name of the host's byte order (the arrays are written as they are in memory).
   pure function byte_order() result(s)
      character(len=:), allocatable :: s
      character(len=4) :: probe
      probe = transfer(1_ip, probe)
      if (probe(1:1) == achar(1)) then
         s = 'LittleEndian'
      else
         s = 'BigEndian'
      end if
   end function byte_order

   !> VTK type name of integer(ip).
   pure function int_type_name() result(s)
      character(len=:), allocatable :: s
      if (storage_size(0_ip) == 64) then
         s = 'Int64'
      else
         s = 'Int32'
      end if
   end function int_type_name

   pure function itoa(n) result(s)
      integer(i8), intent(in) :: n
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') n
      s = trim(buf)
   end function itoa
end module vemcontact_output_vtu
