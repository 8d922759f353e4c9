!> XDMF (version 3) description of JOB.h5: JOB.xdmf lets ParaView, VisIt and meshio
!> read the HDF5 results in place, without a copy of the data (docs/output-format.md,
!> "XDMF").  One uniform grid per step in a temporal collection; every grid
!> references the mesh (/mesh/coordinates, /mesh/xdmf_topology) and its step's
!> datasets in JOB.h5.  The topology is XDMF's Mixed one (polygons with their node
!> count) for a mesh of several cell kinds, or the single kind of a mesh of one kind
!> (which meshio's reader, without polygons in Mixed topologies, reads too).
module vemcontact_output_xdmf
   use vemcontact_kinds, only: ip, i8
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, etype_polygon, etype_quad4, etype_tri3, etype_polygon2, &
                               etype_quad8, etype_tri6
   use vemcontact_safe_file, only: safe_file_t
   use vemcontact_text, only: int_text
   use vemcontact_output_xml, only: xml_escape
   use vemcontact_output_selection, only: field_selection_t, step_selection
   implicit none
   private

   public :: xdmf_topology, xdmf_layout, write_xdmf

   ! XDMF's cell kinds (XdmfTopologyType ids)
   integer, parameter :: xdmf_polygon = 3, xdmf_triangle = 4, xdmf_quadrilateral = 5, &
                         xdmf_triangle6 = 36, xdmf_quadrilateral8 = 37

contains

   !> XDMF cell kind and node count of element e.  A first-order element of 3 or 4
   !> nodes is a triangle or quadrilateral whatever its formulation (the same
   !> straight sides); other first-order elements and second-order polygons are
   !> polygons (through all 2n nodes of a VPE2, in boundary order).
   pure subroutine cell_kind(model, e, kind, n)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: e
      integer, intent(out) :: kind, n
      n = int(model%elem_ptr(e + 1) - model%elem_ptr(e))
      select case (model%elem_type(e))
      case (etype_tri6)
         kind = xdmf_triangle6
      case (etype_quad8)
         kind = xdmf_quadrilateral8
      case (etype_polygon2)
         kind = xdmf_polygon
      case default
         if (n == 3) then
            kind = xdmf_triangle
         else if (n == 4) then
            kind = xdmf_quadrilateral
         else
            kind = xdmf_polygon
         end if
      end select
   end subroutine cell_kind

   !> The topology's layout: `nper` > 0 for a mesh of one kind (`kind` its XDMF kind,
   !> `nper` its nodes per cell; the dataset is (nelem, nper)), `nper` = 0 for a mixed
   !> mesh (the dataset is flat, `length` entries).
   pure subroutine xdmf_layout(model, kind, nper, length)
      type(model_t), intent(in) :: model
      integer, intent(out) :: kind, nper
      integer(i8), intent(out) :: length
      integer(ip) :: e
      integer :: k, n
      kind = 0
      nper = 0
      length = 0_i8
      do e = 1, model%nelem
         call cell_kind(model, e, k, n)
         if (e == 1) then
            kind = k
            nper = n
         else if (k /= kind .or. n /= nper) then
            nper = 0
         end if
         length = length + n + 1_i8
         if (k == xdmf_polygon) length = length + 1_i8
      end do
      if (nper > 0) length = int(nper, i8)*model%nelem
   end subroutine xdmf_layout

   !> The cells as XDMF's topology, 0-based node indices (int32, as the connectivity): for a mesh of one kind the
   !> nodes of each cell in turn; for a mixed mesh each cell as its kind, for a
   !> polygon its node count, then its nodes.  XDMF's quadratic triangle and
   !> quadrilateral take the deck's order (corners, then side nodes).
   pure function xdmf_topology(model) result(topo)
      type(model_t), intent(in) :: model
      integer(ip), allocatable :: topo(:)
      integer(i8) :: length, p
      integer(ip) :: e, p0
      integer :: kind, nper, k, n, j
      call xdmf_layout(model, kind, nper, length)
      allocate (topo(length))
      p = 0_i8
      do e = 1, model%nelem
         call cell_kind(model, e, k, n)
         p0 = model%elem_ptr(e)
         if (nper == 0) then
            topo(p + 1) = int(k, ip)
            p = p + 1
            if (k == xdmf_polygon) then
               topo(p + 1) = int(n, ip)
               p = p + 1
            end if
         end if
         if (model%elem_type(e) == etype_polygon2) then
            ! corners first, then side nodes -> corner 1, side 1, corner 2, ...
            do j = 1, n/2
               topo(p + 2*j - 1) = model%elem_conn(p0 + j - 1) - 1
               topo(p + 2*j) = model%elem_conn(p0 + n/2 + j - 1) - 1
            end do
         else
            topo(p + 1:p + n) = model%elem_conn(p0:p0 + n - 1) - 1
         end if
         p = p + n
      end do
   end function xdmf_topology

   !> Write `path` (JOB.xdmf) for steps 1..nsteps of JOB.h5 (`h5name`, relative to the
   !> folder of `path`): the fields each step's output requests select.
   subroutine write_xdmf(path, h5name, model, nsteps, error)
      character(len=*), intent(in) :: path, h5name
      type(model_t), intent(in) :: model
      integer, intent(in) :: nsteps
      type(error_t), allocatable, intent(out) :: error
      character(len=1), parameter :: nl = new_line('a')
      type(safe_file_t) :: out
      type(field_selection_t) :: sel
      character(len=:), allocatable :: h5, topo, nn, ne, name, grp
      character(len=32) :: b
      integer(i8) :: length
      integer :: kind, nper, istep

      h5 = xml_escape(h5name)
      nn = int_text(int(model%nnode, i8))
      ne = int_text(int(model%nelem, i8))
      call xdmf_layout(model, kind, nper, length)
      if (nper == 0) then
         topo = '<Topology TopologyType="Mixed" NumberOfElements="'//ne//'">'//nl// &
                item(int_text(length), 'Int', '4', '/mesh/xdmf_topology')//'</Topology>'//nl
      else
         topo = '<Topology TopologyType="'//kind_name(kind)//'" NumberOfElements="'//ne//'"'
         if (kind == xdmf_polygon) topo = topo//' NodesPerElement="'//int_text(int(nper, i8))//'"'
         topo = topo//'>'//nl//item(ne//' '//int_text(int(nper, i8)), 'Int', '4', '/mesh/xdmf_topology')// &
                '</Topology>'//nl
      end if
      topo = topo//'<Geometry GeometryType="XY">'//nl//item(nn//' 2', 'Float', '8', '/mesh/coordinates')// &
             '</Geometry>'//nl// &
             attribute('NODE_ID', 'Scalar', 'Node', item(nn, 'Int', '4', '/mesh/node_ids'))// &
             attribute('ELEMENT_ID', 'Scalar', 'Cell', item(ne, 'Int', '4', '/mesh/element_ids'))// &
             attribute('MATERIAL', 'Scalar', 'Cell', item(ne, 'Int', '4', '/mesh/element_material'))// &
             attribute('ELSET', 'Scalar', 'Cell', item(ne, 'Int', '4', '/mesh/element_set'))// &
             attribute('PART', 'Scalar', 'Cell', item(ne, 'Int', '4', '/mesh/element_part'))

      call out%open(path, error)
      if (allocated(error)) return
      call out%write('<?xml version="1.0"?>'//nl//'<Xdmf Version="3.0">'//nl//'<Domain>'//nl// &
                     '<Grid Name="steps" GridType="Collection" CollectionType="Temporal">'//nl)
      do istep = 1, nsteps
         if (istep <= 9999) then
            write (b, '(i4.4)') istep
         else
            write (b, '(i0)') istep
         end if
         grp = '/steps/'//trim(b)
         if (allocated(model%steps(istep)%name)) then
            name = model%steps(istep)%name
         else
            name = 'Step-'//int_text(int(istep, i8))
         end if
         sel = step_selection(model, istep)
         call out%write('<Grid Name="'//xml_escape(name)//'" GridType="Uniform">'//nl// &
                        '<Time Value="'//int_text(int(istep, i8))//'"/>'//nl//topo)
         if (sel%u) call out%write(attribute('U', 'Vector', 'Node', item(nn//' 2', 'Float', '8', grp//'/U')))
         if (sel%rf) call out%write(attribute('RF', 'Vector', 'Node', item(nn//' 2', 'Float', '8', grp//'/RF')))
         if (sel%s) call out%write( &
            attribute('S_node', 'Vector', 'Node', item(nn//' 4', 'Float', '8', grp//'/S_node'))// &
            attribute('S_element', 'Vector', 'Cell', item(ne//' 4', 'Float', '8', grp//'/S_element'))// &
            attribute('ERROR_INDICATOR', 'Scalar', 'Cell', item(ne, 'Float', '8', grp//'/ERROR_INDICATOR')))
         if (sel%e) call out%write( &
            attribute('E_node', 'Vector', 'Node', item(nn//' 4', 'Float', '8', grp//'/E_node'))// &
            attribute('E_element', 'Vector', 'Cell', item(ne//' 4', 'Float', '8', grp//'/E_element')))
         call out%write('</Grid>'//nl)
      end do
      call out%write('</Grid>'//nl//'</Domain>'//nl//'</Xdmf>'//nl)
      call out%commit(error)
   contains
      function item(dims, ntype, precision, dataset) result(s)
         character(len=*), intent(in) :: dims, ntype, precision, dataset
         character(len=:), allocatable :: s
         s = '<DataItem Dimensions="'//dims//'" NumberType="'//ntype//'" Precision="'//precision// &
             '" Format="HDF">'//h5//':'//dataset//'</DataItem>'//nl
      end function item
   end subroutine write_xdmf

   function attribute(name, atype, center, data) result(s)
      character(len=*), intent(in) :: name, atype, center, data
      character(len=:), allocatable :: s
      s = '<Attribute Name="'//name//'" AttributeType="'//atype//'" Center="'//center//'">'// &
          new_line('a')//data//'</Attribute>'//new_line('a')
   end function attribute

   pure function kind_name(kind) result(s)
      integer, intent(in) :: kind
      character(len=:), allocatable :: s
      select case (kind)
      case (xdmf_triangle)
         s = 'Triangle'
      case (xdmf_quadrilateral)
         s = 'Quadrilateral'
      case (xdmf_triangle6)
         s = 'Triangle_6'
      case (xdmf_quadrilateral8)
         s = 'Quadrilateral_8'
      case default
         s = 'Polygon'
      end select
   end function kind_name

end module vemcontact_output_xdmf
