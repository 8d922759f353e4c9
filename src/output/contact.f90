!> Contact results of one pair in one step: a CSV table and a VTU point set of
!> the slave nodes (vertex cells), so that ParaView shows them beside the mesh.
!> Columns/fields (docs/output-format.md): node id, coordinates (undeformed), COPEN
!> (normal gap, positive open, negative = overclosure), CPRESS (contact pressure,
!> positive in compression: the normal force the solution balances / CNAREA), CSLIP
!> (tangential displacement of the slave node relative to its master point, along the
!> master segment's direction a -> b; 0 without a master segment), CNAREA (tributary
!> length * thickness), STATUS (1 closed, 0 open, 2 slid off the master's end), PAIR.
module vemcontact_output_contact
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t
   use vemcontact_output_base64, only: as_bytes
   use vemcontact_output_vtu, only: put, put_array, byte_order, int_type_name, itoa
   use vemcontact_safe_file, only: safe_file_t
   use vemcontact_contact_table, only: contact_table_t
   implicit none
   private

   public :: write_contact_csv, write_contact_vtu


contains

   !> CSV of the entries of `tab` that belong to pair `ipair`, full precision.
   subroutine write_contact_csv(path, tab, ipair, error)
      character(len=*), intent(in) :: path
      type(contact_table_t), intent(in) :: tab
      integer, intent(in) :: ipair
      type(error_t), allocatable, intent(out) :: error
      type(safe_file_t) :: out
      integer :: k
      character(len=256) :: line
      call out%open(path, error)
      if (allocated(error)) return
      call out%write('node,x,y,COPEN,CPRESS,CSLIP,CNAREA,STATUS'//new_line('a'))
      do k = 1, size(tab%node_id)
         if (tab%pair(k) /= ipair) cycle
         write (line, '(i0,6(",",es24.16e3),",",a)') tab%node_id(k), tab%x(:, k), &
            tab%copen(k), tab%cpress(k), tab%cslip(k), tab%cnarea(k), status_name(tab%status(k))
         call out%write(trim(line)//new_line('a'))
      end do
      call out%commit(error)
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
      case default
         s = 'OPEN'
      end select
   end function status_name

   !> All entries of `tab` as VTK vertices with point data COPEN, CPRESS, CSLIP, CNAREA, STATUS, PAIR, NODE_ID.
   subroutine write_contact_vtu(path, tab, error)
      character(len=*), intent(in) :: path
      type(contact_table_t), intent(in) :: tab
      type(error_t), allocatable, intent(out) :: error
      character(len=1), parameter :: nl = new_line('a')
      character(len=:), allocatable :: itype
      real(wp), allocatable :: xyz(:, :)
      integer(ip), allocatable :: ibuf(:)
      type(safe_file_t) :: unit
      integer :: ios
      integer(ip) :: n, k
      n = size(tab%node_id)
      itype = int_type_name()
      call unit%open(path, error)
      if (allocated(error)) return
      ios = 0
      call put(unit, '<?xml version="1.0"?>'//nl//'<VTKFile type="UnstructuredGrid" version="1.0" byte_order="' &
               //byte_order()//'" header_type="UInt64">'//nl//'<UnstructuredGrid>'//nl &
               //'<Piece NumberOfPoints="'//itoa(int(n, i8))//'" NumberOfCells="'//itoa(int(n, i8))//'">'//nl &
               //'<PointData>'//nl, ios)
      call put_array(unit, 'type="Float64" Name="COPEN"', as_bytes(tab%copen), ios)
      call put_array(unit, 'type="Float64" Name="CPRESS"', as_bytes(tab%cpress), ios)
      call put_array(unit, 'type="Float64" Name="CSLIP"', as_bytes(tab%cslip), ios)
      call put_array(unit, 'type="Float64" Name="CNAREA"', as_bytes(tab%cnarea), ios)
      ibuf = int(tab%status, ip)
      call put_array(unit, 'type="'//itype//'" Name="STATUS"', as_bytes(ibuf), ios)
      ibuf = int(tab%pair, ip)
      call put_array(unit, 'type="'//itype//'" Name="PAIR"', as_bytes(ibuf), ios)
      call put_array(unit, 'type="'//itype//'" Name="NODE_ID"', as_bytes(tab%node_id), ios)
      call put(unit, '</PointData>'//nl//'<Points>'//nl, ios)
      allocate (xyz(3, n))
      xyz(1:2, :) = tab%x
      xyz(3, :) = 0.0_wp
      call put_array(unit, 'type="Float64" Name="Points" NumberOfComponents="3"', as_bytes(xyz), ios)
      call put(unit, '</Points>'//nl//'<Cells>'//nl, ios)
      ibuf = [(k - 1_ip, k=1, n)]
      call put_array(unit, 'type="'//itype//'" Name="connectivity"', as_bytes(ibuf), ios)
      ibuf = ibuf + 1_ip
      call put_array(unit, 'type="'//itype//'" Name="offsets"', as_bytes(ibuf), ios)
      call put_array(unit, 'type="UInt8" Name="types"', repeat(achar(1), n), ios)   ! VTK_VERTEX
      call put(unit, '</Cells>'//nl//'</Piece>'//nl//'</UnstructuredGrid>'//nl//'</VTKFile>'//nl, ios)
      ! a failed write is reported (file and reason) by the commit
      call unit%commit(error)
   end subroutine write_contact_vtu
end module vemcontact_output_contact
