!> JOB.xdmf's topology (vemcontact_output_xdmf): the flat Mixed list of a mesh of
!> several cell kinds, written out by hand from XDMF's cell ids (3 polygon with its
!> node count, 4 triangle, 5 quadrilateral, 37 quadratic quadrilateral), with a VPE2
!> polygon taken round its boundary (corner, side node, corner, ...); and the plain
!> (nelem, nodes per cell) layout of a mesh of one kind.  The readers' view (VTK,
!> meshio, h5py) is postprocess/tests/test_xdmf.py's.
program test_output_xdmf
   use vemcontact_kinds, only: ip, i8
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: model_t, etype_polygon, etype_polygon2, etype_quad8, etype_tri3
   use vemcontact_output_xdmf, only: xdmf_topology, xdmf_layout
   implicit none
   type(checker_t) :: t
   type(model_t) :: m
   integer(ip), allocatable :: topo(:), want(:)
   integer :: kind, nper
   integer(i8) :: length
   integer :: k

   ! pentagon (VPE), quadrilateral (VPE), VPE2 triangle, CPE8, CPE3
   m%nnode = 30
   m%nelem = 5
   m%elem_type = [etype_polygon, etype_polygon, etype_polygon2, etype_quad8, etype_tri3]
   m%elem_ptr = [1_ip, 6_ip, 10_ip, 16_ip, 24_ip, 27_ip]
   m%elem_conn = [1_ip, 2_ip, 3_ip, 4_ip, 5_ip, &
                  6_ip, 7_ip, 8_ip, 9_ip, &
                  10_ip, 11_ip, 12_ip, 13_ip, 14_ip, 15_ip, &
                  16_ip, 17_ip, 18_ip, 19_ip, 20_ip, 21_ip, 22_ip, 23_ip, &
                  24_ip, 25_ip, 26_ip]
   want = [3_ip, 5_ip, 0_ip, 1_ip, 2_ip, 3_ip, 4_ip, &
           5_ip, 5_ip, 6_ip, 7_ip, 8_ip, &
           3_ip, 6_ip, 9_ip, 12_ip, 10_ip, 13_ip, 11_ip, 14_ip, &
           37_ip, 15_ip, 16_ip, 17_ip, 18_ip, 19_ip, 20_ip, 21_ip, 22_ip, &
           4_ip, 23_ip, 24_ip, 25_ip]
   call xdmf_layout(m, kind, nper, length)
   call t%equal(nper, 0, 'mixed mesh: no single kind')
   call t%equal(int(length), size(want), 'mixed mesh: length of the list')
   topo = xdmf_topology(m)
   call t%equal(size(topo), size(want), 'mixed mesh: size of the topology')
   if (size(topo) == size(want)) call t%check(all(topo == want), 'mixed mesh: kinds, counts and nodes')

   ! two CPE8: one kind, the deck's order (corners, then side nodes), 0-based
   m%nelem = 2
   m%elem_type = [etype_quad8, etype_quad8]
   m%elem_ptr = [1_ip, 9_ip, 17_ip]
   m%elem_conn = [(int(k, ip), k = 1, 16)]
   call xdmf_layout(m, kind, nper, length)
   call t%equal(kind, 37, 'one kind: Quadrilateral_8')
   call t%equal(nper, 8, 'one kind: 8 nodes per cell')
   call t%equal(int(length), 16, 'one kind: no kind or count entries')
   topo = xdmf_topology(m)
   call t%check(all(topo == [(int(k, ip), k = 0, 15)]), 'one kind: the connectivity, 0-based')

   ! VEM quadrilaterals and FEM-looking ones alike are XDMF quadrilaterals
   m%elem_type = [etype_polygon, etype_polygon]
   m%elem_ptr = [1_ip, 5_ip, 9_ip]
   call xdmf_layout(m, kind, nper, length)
   call t%equal(kind, 5, 'VEM quadrilaterals: Quadrilateral')
   call t%equal(nper, 4, 'VEM quadrilaterals: 4 nodes per cell')
   call t%finish()
end program test_output_xdmf
