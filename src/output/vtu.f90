!> VTK XML UnstructuredGrid (.vtu) writer: version 1.0, UInt64 block headers,
!> inline base64 "binary" arrays, so every double is stored exactly; by default
!> zlib-compressed in VTK's block format (vtkZLibDataCompressor), raw on request.
!>
!> Cells of 3 and 4 nodes are VTK_TRIANGLE (5) and VTK_QUAD (9), whatever their
!> formulation (a VEM triangle or quadrilateral has the same linear boundary as
!> the FEM element), all other first-order cells VTK_POLYGON (7): readers such
!> as meshio then know them as "triangle"/"quad" and can export to formats
!> without polygons.  Second-order elements: see second_order_cells.
!> The element's own kind is in `/mesh/element_type` of the HDF5 file.
!>
!> The file is written as raw bytes (XML text and base64 payloads), never a
!> formatted write per number, through `safe_file_t` (src/safe_file.f90): to a
!> unique temporary beside `path`, every write checked, fsync'ed and renamed to
!> `path` only when complete, so a crash or a full disk leaves no file of that
!> name, never a truncated one.
module vemcontact_output_vtu
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_io, err_internal
   use vemcontact_model, only: model_t, etype_polygon2, etype_quad8, etype_tri6
   use vemcontact_post_stress, only: principal_stresses
   use vemcontact_output_base64, only: base64_encode, base64_length, as_bytes
   use vemcontact_output_zlib, only: zlib_compress_blocks, zlib_processors
   use vemcontact_output_xml, only: xml_escape
   use vemcontact_output_selection, only: field_selection_t
   use vemcontact_safe_file, only: safe_file_t
   use vemcontact_text, only: int_text
   implicit none
   private

   public :: write_vtu, finish_file, put, put_array, byte_order, int_type_name, vtk_file_attributes
   public :: vtk_cell_type, full_tensor, tensor_names

   !> VTK cell types of the elements.
   integer, parameter :: vtk_triangle = 5, vtk_quad = 9, vtk_polygon = 7
   !> VTK cell types of the quadratic FEM elements (same node order as Abaqus')
   integer, parameter :: vtk_quadratic_triangle = 22, vtk_quadratic_quad = 23
   !> Uncompressed bytes per zlib block: VTK reads any block size; 256 KiB keeps
   !> the compressor's per-call set-up negligible and the block table short.
   integer(i8), parameter :: zlib_block = 262144_i8
   !> Compression level (libdeflate's, vemcontact_output_zlib): 1 compresses float64
   !> results nearly as well as zlib's default 6 (the mantissas' low bytes are
   !> incompressible either way) at a fraction of the time.
   integer, parameter :: zlib_level = 1
   !> Component names of a 3 x 3 tensor in VTK's order (row by row).
   character(len=*), parameter :: tensor_names = ' ComponentName0="XX" ComponentName1="XY"' &
      //' ComponentName2="XZ" ComponentName3="YX" ComponentName4="YY" ComponentName5="YZ"' &
      //' ComponentName6="ZX" ComponentName7="ZY" ComponentName8="ZZ"'
   !> Bytes encoded per piece: a multiple of 3 so that pieces join without padding;
   !> 3 MiB keeps the encoded buffer (4 MiB) in cache-friendly range.
   integer(i8), parameter :: piece_bytes = 3_i8*1048576_i8

   !> Results beyond U and S that a step's .vtu carries when the driver has them
   !> (docs/output-format.md); each is written when allocated.
   type, public :: vtu_extras_t
      real(wp), allocatable :: e_node(:, :)     !< (4, nnode) strain xx, yy, zz, engineering xy
      real(wp), allocatable :: e_elem(:, :)     !< (4, nelem)
      real(wp), allocatable :: rf(:, :)         !< (2, nnode) reaction forces
      integer(ip), allocatable :: elem_set(:)   !< (nelem) index into model%elsets, 0 none
      integer(ip), allocatable :: elem_part(:)  !< (nelem) part (connected body), 1-based
      real(wp) :: time = 0.0_wp                 !< step time: FieldData TimeValue
   end type vtu_extras_t

contains

   !> Connectivity (1-based, as the model's) and VTK cell type of every element.
   !> First-order elements: their nodes, with the type of vtk_cell_type (triangle,
   !> quad or polygon by the node count).  Second order: the
   !> 6-node triangle and the 8-node quad as VTK_QUADRATIC_TRIANGLE (22) and
   !> VTK_QUADRATIC_QUAD (23), whose node order is Abaqus' (corners, then side
   !> nodes); a second-order polygon as a VTK_POLYGON through all its 2n nodes
   !> in boundary order (corner 1, side node 1, corner 2, ...), so that the
   !> side nodes are kept and readers without quadratic polygons draw it.
   subroutine second_order_cells(model, conn, types)
      type(model_t), intent(in) :: model
      integer(ip), allocatable, intent(out) :: conn(:)
      character(len=:), allocatable, intent(out) :: types
      integer :: e, n, i
      integer(ip) :: p0
      conn = model%elem_conn(1:model%elem_ptr(model%nelem + 1) - 1)
      allocate (character(len=model%nelem) :: types)
      do e = 1, model%nelem
         types(e:e) = achar(vtk_cell_type(model%elem_ptr(e + 1) - model%elem_ptr(e)))
      end do
      if (.not. allocated(model%elem_type)) return
      do e = 1, model%nelem
         select case (model%elem_type(e))
         case (etype_tri6)
            types(e:e) = achar(vtk_quadratic_triangle)
         case (etype_quad8)
            types(e:e) = achar(vtk_quadratic_quad)
         case (etype_polygon2)
            types(e:e) = achar(vtk_polygon)
            p0 = model%elem_ptr(e)
            n = (model%elem_ptr(e + 1) - p0)/2
            do i = 1, n
               conn(p0 + 2*i - 2) = model%elem_conn(p0 + i - 1)
               conn(p0 + 2*i - 1) = model%elem_conn(p0 + n + i - 1)
            end do
         end select
      end do
   end subroutine second_order_cells

   !> Write the mesh with displacements and stresses to the .vtu file `path`.
   !> Point data: U (3 comps, z = 0), S (xx,yy,zz,xy averaged at nodes), S1, S3,
   !> MISES, NODE_ID; cell data: S (element stress), MATERIAL, ELEMENT_ID.
   !> Arrays are zlib-compressed unless `compress` is present and false.
   !> With `extra`: FieldData TimeValue and the names of the element sets and
   !> materials (an Int32 array "ELSET:name" or "MATERIAL:name" holding the id),
   !> point data RF and E, cell data E, ELSET and PART.  With `indicator`: cell
   !> data ERROR_INDICATOR (vemcontact_post_estimate), written with S.  With `sel`
   !> only the selected result fields (U, S with S1, S3, MISES and ERROR_INDICATOR,
   !> RF, E) are written; the mesh and the labels (NODE_ID, ELEMENT_ID, MATERIAL,
   !> ELSET, PART) always.
   subroutine write_vtu(path, model, u, s_elem, s_node, error, compress, extra, sel, indicator)
      character(len=*), intent(in) :: path
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:, :)        !< (2, nnode)
      real(wp), intent(in) :: s_elem(:, :)   !< (4, nelem)
      real(wp), intent(in) :: s_node(:, :)   !< (4, nnode)
      type(error_t), allocatable, intent(out) :: error
      logical, intent(in), optional :: compress
      type(vtu_extras_t), intent(in), optional :: extra
      type(field_selection_t), intent(in), optional :: sel
      real(wp), intent(in), optional :: indicator(:)  !< (nelem) error indicator per cell
      type(field_selection_t) :: w
      character(len=:), allocatable :: itype
      character(len=*), parameter :: s_names = ' NumberOfComponents="9"'//tensor_names
      real(wp), allocatable :: xyz(:, :), p1(:), p3(:), vm(:)
      integer(ip), allocatable :: ibuf(:)
      character(len=:), allocatable :: types
      integer(ip) :: i
      type(safe_file_t) :: unit
      integer :: ios
      logical :: z
      character(len=1), parameter :: nl = new_line('a')

      z = .true.
      if (present(compress)) z = compress
      if (present(sel)) w = sel
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
      if (present(extra)) then
         if (.not. extras_fit(extra, model)) then
            call fatal_error(error, 'write_vtu: extra array shapes do not match the model ('//path//')', &
                             err_internal)
            return
         end if
      end if
      itype = int_type_name()
      call unit%open(path, error)
      if (allocated(error)) return
      ios = 0

      call put(unit, '<?xml version="1.0"?>'//nl &
               //'<VTKFile type="UnstructuredGrid" version="1.0"'//vtk_file_attributes(z) &
               //'>'//nl//'<UnstructuredGrid>'//nl, ios)
      ! the dataset's FieldData comes before its pieces
      if (present(extra)) call put_field_data(unit, model, extra, itype, z, ios)
      call put(unit, '<Piece NumberOfPoints="'//int_text(int(model%nnode, i8)) &
               //'" NumberOfCells="'//int_text(int(model%nelem, i8))//'">'//nl, ios)

      ! point data
      if (w%u) then
         call put(unit, '<PointData Vectors="U">'//nl, ios)
      else
         call put(unit, '<PointData>'//nl, ios)
      end if
      allocate (xyz(3, model%nnode))
      xyz(1:2, :) = u
      xyz(3, :) = 0.0_wp
      if (w%u) call put_array(unit, 'type="Float64" Name="U" NumberOfComponents="3"', as_bytes(xyz), ios, z)
      if (w%s) then
         call put_array(unit, 'type="Float64" Name="S"'//s_names, as_bytes(full_tensor(s_node, 1.0_wp)), ios, z)
         allocate (p1(model%nnode), p3(model%nnode), vm(model%nnode))
         do i = 1, model%nnode
            call principal_stresses(s_node(:, i), p1(i), p3(i), vm(i))
         end do
         call put_array(unit, 'type="Float64" Name="S1"', as_bytes(p1), ios, z)
         call put_array(unit, 'type="Float64" Name="S3"', as_bytes(p3), ios, z)
         call put_array(unit, 'type="Float64" Name="MISES"', as_bytes(vm), ios, z)
         deallocate (p1, p3, vm)
      end if
      call put_array(unit, 'type="'//itype//'" Name="NODE_ID"', as_bytes(model%node_id(1:model%nnode)), ios, z)
      if (present(extra)) then
         if (allocated(extra%rf) .and. w%rf) then
            xyz(1:2, :) = extra%rf
            call put_array(unit, 'type="Float64" Name="RF" NumberOfComponents="3"', as_bytes(xyz), ios, z)
         end if
         if (allocated(extra%e_node) .and. w%e) call put_array(unit, 'type="Float64" Name="E"'//s_names, &
                                                     as_bytes(full_tensor(extra%e_node, 0.5_wp)), ios, z)
      end if
      call put(unit, '</PointData>'//nl, ios)

      ! cell data
      call put(unit, '<CellData>'//nl, ios)
      if (w%s) call put_array(unit, 'type="Float64" Name="S"'//s_names, as_bytes(full_tensor(s_elem, 1.0_wp)), &
                              ios, z)
      allocate (ibuf(model%nelem))
      ibuf = int(model%elem_mat(1:model%nelem), ip)
      call put_array(unit, 'type="'//itype//'" Name="MATERIAL"', as_bytes(ibuf), ios, z)
      call put_array(unit, 'type="'//itype//'" Name="ELEMENT_ID"', as_bytes(model%elem_id(1:model%nelem)), ios, z)
      if (present(indicator) .and. w%s) &
         call put_array(unit, 'type="Float64" Name="ERROR_INDICATOR"', as_bytes(indicator(1:model%nelem)), ios, z)
      if (present(extra)) then
         if (allocated(extra%e_elem) .and. w%e) call put_array(unit, 'type="Float64" Name="E"'//s_names, &
                                                     as_bytes(full_tensor(extra%e_elem, 0.5_wp)), ios, z)
         if (allocated(extra%elem_set)) &
            call put_array(unit, 'type="'//itype//'" Name="ELSET"', as_bytes(extra%elem_set), ios, z)
         if (allocated(extra%elem_part)) &
            call put_array(unit, 'type="'//itype//'" Name="PART"', as_bytes(extra%elem_part), ios, z)
      end if
      call put(unit, '</CellData>'//nl, ios)

      ! geometry: z = 0
      xyz(1:2, :) = model%x(:, 1:model%nnode)
      xyz(3, :) = 0.0_wp
      call put(unit, '<Points>'//nl, ios)
      call put_array(unit, 'type="Float64" Name="Points" NumberOfComponents="3"', as_bytes(xyz), ios, z)
      call put(unit, '</Points>'//nl, ios)
      deallocate (xyz)

      ! topology: 0-based connectivity, offsets = end of each cell (VTK XML convention)
      call put(unit, '<Cells>'//nl, ios)
      call second_order_cells(model, ibuf, types)
      call put_array(unit, 'type="'//itype//'" Name="connectivity"', as_bytes(ibuf - 1_ip), ios, z)
      ibuf = model%elem_ptr(2:model%nelem + 1) - 1_ip
      call put_array(unit, 'type="'//itype//'" Name="offsets"', as_bytes(ibuf), ios, z)
      call put_array(unit, 'type="UInt8" Name="types"', types, ios, z)
      call put(unit, '</Cells>'//nl//'</Piece>'//nl//'</UnstructuredGrid>'//nl//'</VTKFile>'//nl, ios)

      call finish_file(unit, path, ios, error)
   end subroutine write_vtu

   !> The extras have the model's sizes.
   pure logical function extras_fit(extra, model)
      type(vtu_extras_t), intent(in) :: extra
      type(model_t), intent(in) :: model
      extras_fit = .true.
      if (allocated(extra%e_node)) extras_fit = extras_fit .and. size(extra%e_node, 1) == 4 &
                                                .and. size(extra%e_node, 2) == model%nnode
      if (allocated(extra%e_elem)) extras_fit = extras_fit .and. size(extra%e_elem, 1) == 4 &
                                                .and. size(extra%e_elem, 2) == model%nelem
      if (allocated(extra%rf)) extras_fit = extras_fit .and. size(extra%rf, 1) == 2 &
                                            .and. size(extra%rf, 2) == model%nnode
      if (allocated(extra%elem_set)) extras_fit = extras_fit .and. size(extra%elem_set) == model%nelem
      if (allocated(extra%elem_part)) extras_fit = extras_fit .and. size(extra%elem_part) == model%nelem
   end function extras_fit

   !> FieldData: TimeValue (ParaView's name for the time of a dataset), and for
   !> every element set that is some element's ELSET and every material, an Int32
   !> array of one value, the id, named "ELSET:name" or "MATERIAL:name" (meshio
   !> reads them as field_data; VTK XML has string arrays, but meshio cannot read them).
   subroutine put_field_data(unit, model, extra, itype, z, ios)
      type(safe_file_t), intent(inout) :: unit
      type(model_t), intent(in) :: model
      type(vtu_extras_t), intent(in) :: extra
      character(len=*), intent(in) :: itype
      logical, intent(in) :: z
      integer, intent(inout) :: ios
      integer :: k
      character(len=*), parameter :: one = '" NumberOfTuples="1"'
      call put(unit, '<FieldData>'//new_line('a'), ios)
      call put_array(unit, 'type="Float64" Name="TimeValue" NumberOfTuples="1"', as_bytes([extra%time]), ios, z)
      if (allocated(extra%elem_set) .and. allocated(model%elsets)) then
         do k = 1, size(model%elsets)
            if (.not. any(extra%elem_set == k)) cycle
            call put_array(unit, 'type="'//itype//'" Name="ELSET:'//xml_escape(model%elsets(k)%name)//one, &
                           as_bytes([int(k, ip)]), ios, z)
         end do
      end if
      if (allocated(model%materials)) then
         do k = 1, size(model%materials)
            call put_array(unit, 'type="'//itype//'" Name="MATERIAL:'//xml_escape(model%materials(k)%name)//one, &
                           as_bytes([int(k, ip)]), ios, z)
         end do
      end if
      call put(unit, '</FieldData>'//new_line('a'), ios)
   end subroutine put_field_data

   !> Finish a file written with `put`/`put_array`: commit it, which reports a
   !> failed write (file and reason); a failure that was not a write (`ios` set
   !> by zlib) discards the temporary and is reported here.
   subroutine finish_file(unit, path, ios, error)
      type(safe_file_t), intent(inout) :: unit
      character(len=*), intent(in) :: path
      integer, intent(in) :: ios
      type(error_t), allocatable, intent(out) :: error
      if (ios /= 0 .and. .not. unit%failed()) then
         call unit%discard()
         call fatal_error(error, 'error: cannot write '''//path//''': compression failed', err_io)
         return
      end if
      call unit%commit(error)
   end subroutine finish_file

   !> Write text bytes unless an earlier write failed (`ios` becomes non-zero
   !> once a write has failed).
   subroutine put(unit, text, ios)
      type(safe_file_t), intent(inout) :: unit
      character(len=*), intent(in) :: text
      integer, intent(inout) :: ios
      if (ios /= 0) return
      call unit%write(text)
      if (unit%failed()) ios = 1
   end subroutine put

   !> One binary DataArray, zlib-compressed when `compress`, else raw.
   subroutine put_array(unit, attributes, bytes, ios, compress)
      type(safe_file_t), intent(inout) :: unit
      character(len=*), intent(in) :: attributes
      character(len=*), intent(in) :: bytes
      integer, intent(inout) :: ios
      logical, intent(in) :: compress
      call put(unit, '<DataArray '//attributes//' format="binary">'//new_line('a'), ios)
      if (ios /= 0) return
      if (compress) then
         call put_compressed(unit, bytes, ios)
      else
         call put_raw(unit, bytes, ios)
      end if
      call put(unit, new_line('a')//'</DataArray>'//new_line('a'), ios)
   end subroutine put_array

   !> Raw: base64 of (UInt64 byte count, data), encoded as one stream as VTK does
   !> for uncompressed data.  The 8-byte header plus the first data byte form a
   !> first 9-byte piece; the rest goes in pieces of `piece_bytes` (a multiple of
   !> 3), so the text is that of one encoding.
   subroutine put_raw(unit, bytes, ios)
      type(safe_file_t), intent(inout) :: unit
      character(len=*), intent(in) :: bytes
      integer, intent(inout) :: ios
      character(len=:), allocatable :: buf
      integer(i8) :: nb, first
      nb = len(bytes, kind=i8)
      allocate (character(len=base64_length(max(piece_bytes, 9_i8))) :: buf)
      first = min(1_i8, nb)
      call base64_encode(as_bytes(nb)//bytes(1:first), buf)
      call put(unit, buf(1:base64_length(8_i8 + first)), ios)
      call put_base64(unit, bytes(first + 1:), buf, ios)
   end subroutine put_raw

   !> VTK's compressed layout (vtkZLibDataCompressor, header_type UInt64): the
   !> header [number of blocks, block size, uncompressed size of the last block
   !> (0 when it is full), compressed size of each block] base64-encoded on its
   !> own, then the concatenated zlib streams of the blocks as a second base64 stream.
   subroutine put_compressed(unit, bytes, ios)
      type(safe_file_t), intent(inout) :: unit
      character(len=*), intent(in) :: bytes
      integer, intent(inout) :: ios
      character(len=:), allocatable :: packed, buf
      integer(i8), allocatable :: sizes(:), header(:)
      integer(i8) :: nout
      logical :: ok
      ! the blocks on every processor this process may use: the bytes are the same
      call zlib_compress_blocks(bytes, zlib_block, zlib_level, zlib_processors(), packed, sizes, nout, ok)
      if (.not. ok) then
         ios = -1
         return
      end if
      header = [size(sizes, kind=i8), zlib_block, mod(len(bytes, kind=i8), zlib_block), sizes]
      allocate (character(len=base64_length(max(piece_bytes, 8_i8*size(header, kind=i8)))) :: buf)
      call base64_encode(as_bytes(header), buf)
      call put(unit, buf(1:base64_length(8_i8*size(header, kind=i8))), ios)
      call put_base64(unit, packed(1:nout), buf, ios)
   end subroutine put_compressed

   !> Base64 of `bytes` in pieces of `piece_bytes` through the work buffer `buf`.
   subroutine put_base64(unit, bytes, buf, ios)
      type(safe_file_t), intent(inout) :: unit
      character(len=*), intent(in) :: bytes
      character(len=*), intent(inout) :: buf
      integer, intent(inout) :: ios
      integer(i8) :: nb, first, last
      nb = len(bytes, kind=i8)
      first = 1
      do while (first <= nb .and. ios == 0)
         last = min(nb, first + piece_bytes - 1)
         call base64_encode(bytes(first:last), buf)
         call put(unit, buf(1:base64_length(last - first + 1)), ios)
         first = last + 1
      end do
   end subroutine put_base64

   !> The attributes of the VTKFile element after its type and version: byte order,
   !> header type and, for compressed arrays, the compressor.
   pure function vtk_file_attributes(compress) result(s)
      logical, intent(in) :: compress
      character(len=:), allocatable :: s
      s = ' byte_order="'//byte_order()//'" header_type="UInt64"'
      if (compress) s = s//' compressor="vtkZLibDataCompressor"'
   end function vtk_file_attributes

   !> The full 3 x 3 tensors, row by row (VTK's 9-component tensor), of vectors
   !> `(xx, yy, zz, xy)`: xy times `shear` (1 for stresses; 1/2 turns an
   !> engineering shear strain into the tensor component), xz = yz = 0.
   !> Nine components rather than four: VTK, ParaView, XDMF and Gmsh all know a
   !> 9-component array as a tensor, while Gmsh refuses 4 or 6 components.
   pure function full_tensor(v, shear) result(t)
      real(wp), intent(in) :: v(:, :)
      real(wp), intent(in) :: shear
      real(wp) :: t(9, size(v, 2))
      t = 0.0_wp
      t(1, :) = v(1, :)
      t(5, :) = v(2, :)
      t(9, :) = v(3, :)
      t(2, :) = shear*v(4, :)
      t(4, :) = shear*v(4, :)
   end function full_tensor

   !> VTK cell type of an element of `n` nodes.
   pure integer function vtk_cell_type(n)
      integer(ip), intent(in) :: n
      select case (n)
      case (3)
         vtk_cell_type = vtk_triangle
      case (4)
         vtk_cell_type = vtk_quad
      case default
         vtk_cell_type = vtk_polygon
      end select
   end function vtk_cell_type

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

end module vemcontact_output_vtu
