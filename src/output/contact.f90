!> Contact results of one pair in one step: a CSV table and a VTU point set of
!> the slave nodes (vertex cells), so that ParaView shows them beside the mesh.
!> Columns/fields (docs/output-format.md): node id, coordinates (undeformed), COPEN
!> (normal gap, positive open, negative = overclosure), CPRESS (contact pressure,
!> positive in compression: the normal force the solution balances / CNAREA), CSLIP
!> (tangential displacement of the slave node relative to its master point, along the
!> master segment's direction a -> b; 0 without a master segment), CNAREA (tributary
!> length * thickness), STATUS (1 closed, 0 open, 2 slid off the master's end), PAIR;
!> with *UPLIFT, CFLUIDP (the water pressure in the joint) beside CPRESS.
module vemcontact_output_contact
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t
   use vemcontact_output_base64, only: as_bytes
   use vemcontact_output_vtu, only: put, put_array, vtk_file_attributes, int_type_name, finish_file
   use vemcontact_text, only: int_text
   use vemcontact_safe_file, only: safe_file_t
   use vemcontact_contact_table, only: contact_table_t
   use vemcontact_output_selection, only: field_selection_t
   implicit none
   private

   public :: write_contact_csv, write_contact_vtu


contains

   !> CSV of the entries of `tab` that belong to pair `ipair`, full precision; with
   !> `sel` only the selected columns of COPEN, CPRESS, CSLIP (node, x, y, CNAREA and
   !> STATUS always).
   subroutine write_contact_csv(path, tab, ipair, error, sel)
      character(len=*), intent(in) :: path
      type(contact_table_t), intent(in) :: tab
      integer, intent(in) :: ipair
      type(error_t), allocatable, intent(out) :: error
      type(field_selection_t), intent(in), optional :: sel
      type(field_selection_t) :: w
      type(safe_file_t) :: out
      integer :: k
      character(len=32) :: num
      character(len=:), allocatable :: head, line
      if (present(sel)) w = sel
      call out%open(path, error)
      if (allocated(error)) return
      head = 'node,x,y'
      if (w%copen) head = head//',COPEN'
      if (w%cpress) head = head//',CPRESS,CSHEAR'
      if (w%cpress .and. allocated(tab%cfluidp)) head = head//',CFLUIDP'
      if (w%cslip) head = head//',CSLIP'
      call out%write(head//',CNAREA,STATUS'//new_line('a'))
      do k = 1, size(tab%node_id)
         if (tab%pair(k) /= ipair) cycle
         write (num, '(i0)') tab%node_id(k)
         line = trim(num)
         call column(tab%x(1, k))
         call column(tab%x(2, k))
         if (w%copen) call column(tab%copen(k))
         if (w%cpress) call column(tab%cpress(k))
         if (w%cpress) call column(shear(k))
         if (w%cpress .and. allocated(tab%cfluidp)) call column(tab%cfluidp(k))
         if (w%cslip) call column(tab%cslip(k))
         call column(tab%cnarea(k))
         call out%write(line//','//status_name(tab%status(k))//new_line('a'))
      end do
      ! a failed write is reported (file and reason) by the commit
      call out%commit(error)
   contains
      subroutine column(v)
         real(wp), intent(in) :: v
         write (num, '(",",es24.16e3)') v
         line = line//trim(num)
      end subroutine column
      !> CSHEAR of row k (0 for a table made without it)
      real(wp) function shear(k)
         integer, intent(in) :: k
         shear = 0.0_wp
         if (allocated(tab%cshear)) shear = tab%cshear(k)
      end function shear
   end subroutine write_contact_csv

   !> CSV name of a STATUS value.
   pure function status_name(status) result(s)
      integer, intent(in) :: status
      character(len=:), allocatable :: s
      select case (status)
      case (1)
         s = 'CLOSED'
      case (2)
         s = 'SLID_OFF'
      case (3)
         s = 'STICK'
      case (4)
         s = 'SLIP'
      case default
         s = 'OPEN'
      end select
   end function status_name

   !> All entries of `tab` as VTK vertices with point data U (the slave nodes'
   !> displacements, so that warping moves them with the mesh), COPEN, CPRESS,
   !> CSLIP, CNAREA, STATUS, PAIR, NODE_ID; zlib-compressed arrays unless
   !> `compress` is present and false.  With `sel` only the selected of U, COPEN,
   !> CPRESS and CSLIP are written (the labels CNAREA, STATUS, PAIR, NODE_ID always).
   subroutine write_contact_vtu(path, tab, u, error, compress, sel)
      character(len=*), intent(in) :: path
      type(contact_table_t), intent(in) :: tab
      real(wp), intent(in) :: u(:, :)     !< (2, nnode) the step's reported displacements
      type(error_t), allocatable, intent(out) :: error
      logical, intent(in), optional :: compress
      type(field_selection_t), intent(in), optional :: sel
      type(field_selection_t) :: w
      character(len=1), parameter :: nl = new_line('a')
      character(len=:), allocatable :: itype
      real(wp), allocatable :: xyz(:, :)
      integer(ip), allocatable :: ibuf(:)
      type(safe_file_t) :: unit
      integer :: ios
      integer(ip) :: n, k
      logical :: z
      z = .true.
      if (present(compress)) z = compress
      if (present(sel)) w = sel
      n = size(tab%node_id)
      itype = int_type_name()
      call unit%open(path, error)
      if (allocated(error)) return
      ios = 0
      call put(unit, '<?xml version="1.0"?>'//nl//'<VTKFile type="UnstructuredGrid" version="1.0"' &
               //vtk_file_attributes(z)//'>'//nl//'<UnstructuredGrid>'//nl &
               //'<Piece NumberOfPoints="'//int_text(int(n, i8))//'" NumberOfCells="'//int_text(int(n, i8))//'">'//nl &
               //'<PointData'//trim(merge(' Vectors="U"', '            ', w%u))//'>'//nl, ios)
      allocate (xyz(3, n))
      xyz(1:2, :) = u(:, tab%node)
      xyz(3, :) = 0.0_wp
      if (w%u) call put_array(unit, 'type="Float64" Name="U" NumberOfComponents="3"', as_bytes(xyz), ios, z)
      if (w%copen) call put_array(unit, 'type="Float64" Name="COPEN"', as_bytes(tab%copen), ios, z)
      if (w%cpress) call put_array(unit, 'type="Float64" Name="CPRESS"', as_bytes(tab%cpress), ios, z)
      if (w%cpress .and. allocated(tab%cshear)) &
         call put_array(unit, 'type="Float64" Name="CSHEAR"', as_bytes(tab%cshear), ios, z)
      if (w%cpress .and. allocated(tab%cfluidp)) &
         call put_array(unit, 'type="Float64" Name="CFLUIDP"', as_bytes(tab%cfluidp), ios, z)
      if (w%cslip) call put_array(unit, 'type="Float64" Name="CSLIP"', as_bytes(tab%cslip), ios, z)
      call put_array(unit, 'type="Float64" Name="CNAREA"', as_bytes(tab%cnarea), ios, z)
      ibuf = int(tab%status, ip)
      call put_array(unit, 'type="'//itype//'" Name="STATUS"', as_bytes(ibuf), ios, z)
      ibuf = int(tab%pair, ip)
      call put_array(unit, 'type="'//itype//'" Name="PAIR"', as_bytes(ibuf), ios, z)
      call put_array(unit, 'type="'//itype//'" Name="NODE_ID"', as_bytes(tab%node_id), ios, z)
      call put(unit, '</PointData>'//nl//'<Points>'//nl, ios)
      xyz(1:2, :) = tab%x
      xyz(3, :) = 0.0_wp
      call put_array(unit, 'type="Float64" Name="Points" NumberOfComponents="3"', as_bytes(xyz), ios, z)
      call put(unit, '</Points>'//nl//'<Cells>'//nl, ios)
      ibuf = [(k - 1_ip, k=1, n)]
      call put_array(unit, 'type="'//itype//'" Name="connectivity"', as_bytes(ibuf), ios, z)
      ibuf = ibuf + 1_ip
      call put_array(unit, 'type="'//itype//'" Name="offsets"', as_bytes(ibuf), ios, z)
      call put_array(unit, 'type="UInt8" Name="types"', repeat(achar(1), n), ios, z)   ! VTK_VERTEX
      call put(unit, '</Cells>'//nl//'</Piece>'//nl//'</UnstructuredGrid>'//nl//'</VTKFile>'//nl, ios)
      call finish_file(unit, path, ios, error)
   end subroutine write_contact_vtu
end module vemcontact_output_contact
