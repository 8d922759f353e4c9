!> Slave tributary lengths and master segments from model surfaces: element
!> surfaces on uniform and graded lines, node surfaces on a mesh boundary with
!> a corner and along a joint that ends at an interior tip shared with the
!> master, exclusion of nodes shared with the master, outward normals of a
!> square's four sides, and the errors (isolated slave node, interior master
!> side, zero-length master side).
program test_contact_surfaces
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: model_t, contact_pair_t, surface_element, surface_node, &
                               plane_strain, form_vem
   use vemcontact_test_model, only: make_model
   use vemcontact_test_polymesh, only: quad_grid
   use vemcontact_contact_surfaces, only: master_segments, slave_nodes
   use vemcontact_contact_geometry, only: project_point_segment
   implicit none
   type(checker_t) :: t
   type(model_t) :: model
   type(contact_pair_t) :: pair
   type(error_t), allocatable :: error
   real(wp), allocatable :: x(:, :), length(:), thick(:)
   integer(ip), allocatable :: ptr(:), conn(:), node(:), seg(:, :), seg_elem(:)
   integer, allocatable :: seg_side(:)
   integer(ip) :: nexcl
   real(wp) :: xg(0:6), xi, g, n(2), d, expect(4, 2)
   integer :: i, k, st

   pair = contact_pair_t(slave=1, master=2, interaction=1)

   ! ---- element surface on a uniform line: 8 x 2 quads on [0,4] x [0,1];
   ! slave = bottom sides (side 1) of the bottom row, master = top sides (side 3)
   call quad_grid(8, 2, 0.0_wp, 0.0_wp, 4.0_wp, 1.0_wp, 0.0_wp, 1, x, ptr, conn)
   call make_model(x, ptr, conn, 1.0_wp, 0.3_wp, plane_strain, form_vem, 2.5_wp, model)
   call set_surfaces(model, [(int(i, ip), i=1, 8)], [(1, i=1, 8)], [(int(i, ip), i=9, 16)], [(3, i=1, 8)])
   call slave_nodes(model, pair, node, length, thick, nexcl, error)
   call t%check(.not. allocated(error), 'uniform line: no error')
   call t%equal(size(node), 9, 'uniform line: 9 slave nodes')
   call t%equal(int(nexcl), 0, 'uniform line: none excluded')
   ! lengths are sums of exact binary fractions: exact up to one rounding
   call t%close(length(1), 0.25_wp, 1.0e-15_wp, 'uniform line: end node half a facet')
   call t%close(length(5), 0.5_wp, 1.0e-15_wp, 'uniform line: interior node one facet')
   call t%close(sum(length), 4.0_wp, 1.0e-14_wp, 'uniform line: lengths sum to the surface length')
   call t%close(maxval(abs(thick - 2.5_wp)), 0.0_wp, 0.0_wp, 'uniform line: thickness', atol=1.0e-15_wp)

   ! ---- graded line: 6 quads, widths growing by 1.7, thickness varying per element
   xg(0) = 0.0_wp
   do i = 1, 6
      xg(i) = xg(i - 1) + 0.3_wp*1.7_wp**(i - 1)
   end do
   deallocate (x)
   allocate (x(2, 14))
   do i = 0, 6
      x(:, i + 1) = [xg(i), 0.0_wp]
      x(:, i + 8) = [xg(i), 0.5_wp]
   end do
   ptr = [(int(1 + 4*i, ip), i=0, 6)]
   conn = [(int([i, i + 1, i + 8, i + 7], ip), i=1, 6)]
   call make_model(x, ptr, conn, 1.0_wp, 0.3_wp, plane_strain, form_vem, 1.0_wp, model)
   model%elem_thick = [(1.0_wp + 0.5_wp*i, i=1, 6)]
   call set_surfaces(model, [(int(i, ip), i=1, 6)], [(1, i=1, 6)], [(int(i, ip), i=1, 6)], [(3, i=1, 6)])
   call slave_nodes(model, pair, node, length, thick, nexcl, error)
   call t%check(.not. allocated(error), 'graded line: no error')
   call t%equal(size(node), 7, 'graded line: 7 slave nodes')
   do i = 2, 6
      call t%close(length(i), 0.5_wp*(xg(i) - xg(i - 2)), 1.0e-14_wp, 'graded line: interior tributary')
   end do
   call t%close(sum(length), xg(6), 1.0e-14_wp, 'graded line: lengths sum to the surface length')
   ! length*thick is sum of (l/2) t_e: at node 3 between elements 2 and 3
   call t%close(length(3)*thick(3), 0.5_wp*(xg(2) - xg(1))*2.0_wp + 0.5_wp*(xg(3) - xg(2))*2.5_wp, &
                1.0e-14_wp, 'graded line: L*t is the sum of half-facet areas')
   call t%close(sum(length*thick), sum([((xg(i) - xg(i - 1))*(1.0_wp + 0.5_wp*i), i=1, 6)]), 1.0e-14_wp, &
                'graded line: total slave area')

   ! ---- node surface on a mesh boundary: 4 x 3 unit quads; bottom nodes then
   ! bottom + right side (corner (4,0) gets half of a bottom and half of a right edge)
   call quad_grid(4, 3, 0.0_wp, 0.0_wp, 4.0_wp, 3.0_wp, 0.0_wp, 1, x, ptr, conn)
   call make_model(x, ptr, conn, 1.0_wp, 0.3_wp, plane_strain, form_vem, 1.0_wp, model)
   model%node_id = [(int(100 + i, ip), i=1, 20)]
   model%elem_id = [(int(500 + i, ip), i=1, 12)]
   ! master = top sides of the top row (elements 9..12, side 3), away from the slaves
   call set_node_surface(model, [1_ip, 2_ip, 3_ip, 4_ip, 5_ip], [9_ip, 10_ip, 11_ip, 12_ip], [3, 3, 3, 3])
   call slave_nodes(model, pair, node, length, thick, nexcl, error)
   call t%check(.not. allocated(error), 'node surface: no error')
   call t%close(sum(length), 4.0_wp, 1.0e-15_wp, 'node surface (bottom): total length')
   call t%close(length(1), 0.5_wp, 1.0e-15_wp, 'node surface: end node')
   call t%close(length(3), 1.0_wp, 1.0e-15_wp, 'node surface: interior node')
   call set_node_surface(model, [1_ip, 2_ip, 3_ip, 4_ip, 5_ip, 10_ip, 15_ip], [1_ip], [4])
   call slave_nodes(model, pair, node, length, thick, nexcl, error)
   call t%check(.not. allocated(error), 'node surface with a corner: no error')
   ! master = left side of element 1 (nodes 6 -> 1): node 1 is shared and excluded
   call t%equal(int(nexcl), 1, 'node shared with the master excluded')
   call t%check(all(node /= 1_ip), 'excluded node is not a slave')
   call t%equal(size(node), 6, 'node surface with a corner: 6 slaves remain')
   call t%close(length(findloc(node, 5_ip, 1)), 1.0_wp, 1.0e-15_wp, 'corner node: half of each edge')
   call t%close(length(findloc(node, 15_ip, 1)), 0.5_wp, 1.0e-15_wp, 'end of the right side')
   call t%close(length(findloc(node, 2_ip, 1)), 1.0_wp, 1.0e-15_wp, &
                'neighbour of the excluded node keeps its half edge')
   ! the interior line y = 1 (nodes 6..10) has no boundary edge except at x = 0 and 4
   call set_node_surface(model, [1_ip, 2_ip, 3_ip, 4_ip, 5_ip, 8_ip], [9_ip], [3])
   call slave_nodes(model, pair, node, length, thick, nexcl, error)
   call t%check(allocated(error), 'isolated slave node: error')
   if (allocated(error)) then
      write (*, '(a)') error%message
      call t%check(index(error%message, 'slave node 108 ') > 0, 'error names the isolated node by its id')
      call t%check(index(error%message, 'SLAVE') > 0, 'error names the surface')
   end if

   ! ---- node surface along a joint ending at an interior tip: 4 x 2 quads on
   ! [0,4] x [0,2], column i = 1 moved to x = 0.7; the joint runs along y = 1
   ! from the left edge (0,1) to the tip (2,1), node 8.  Its nodes (0,1) = 6 and
   ! (0.7,1) = 7 are duplicated as 16 and 17 for the upper elements 5 and 6; the
   ! tip is shared.  Lower face: sides 3 of elements 1 and 2, 7 -> 6 and 8 -> 7
   ! (the edge to the tip starts at the tip); upper face: sides 1 of elements
   ! 5 and 6, 16 -> 17 and 17 -> 8 (the edge to the tip ends at the tip).
   call quad_grid(4, 2, 0.0_wp, 0.0_wp, 4.0_wp, 2.0_wp, 0.0_wp, 1, x, ptr, conn)
   x(1, [2, 7, 12]) = 0.7_wp
   x = reshape([x, x(:, 6), x(:, 7)], [2, 17])
   conn(17:24) = [16_ip, 17_ip, 12_ip, 11_ip, 17_ip, 8_ip, 13_ip, 12_ip]
   call make_model(x, ptr, conn, 1.0_wp, 0.3_wp, plane_strain, form_vem, 1.0_wp, model)
   model%elem_thick(1:2) = [1.5_wp, 2.5_wp]
   ! the mesher's slave set: the lower face without the tip; master: the upper face
   ! every edge of the face gives half its length to each end; the tip's half of
   ! the edge 7-8 (0.65) stays with the tip, which carries no spring
   call set_node_surface(model, [6_ip, 7_ip], [5_ip, 6_ip], [1, 1])
   call slave_nodes(model, pair, node, length, thick, nexcl, error)
   call t%check(.not. allocated(error), 'joint tip, lower face: no error')
   call t%equal(size(node), 2, 'joint tip, lower face: 2 slave nodes')
   call t%equal(int(nexcl), 0, 'joint tip, lower face: the tip is not in the set')
   ! a few roundings of lengths 0.7 and 1.3: 1e-15 relative
   call t%close(length(1), 0.35_wp, 1.0e-15_wp, 'joint tip, lower face: mouth node, half its edge')
   call t%close(length(2), 0.5_wp*(0.7_wp + 1.3_wp), 1.0e-15_wp, &
                'joint tip, lower face: node next to the tip has half of the edge to the tip')
   call t%close(sum(length) + 0.65_wp, 2.0_wp, 1.0e-15_wp, &
                'joint tip, lower face: with the tip''s half edge, the lengths sum to the face length')
   call t%close(length(2)*thick(2), 0.35_wp*1.5_wp + 0.65_wp*2.5_wp, 1.0e-15_wp, &
                'joint tip, lower face: thickness of the edge to the tip from its element')
   ! the same face with the tip written in the set: dropped, nothing counted twice
   call set_node_surface(model, [6_ip, 7_ip, 8_ip], [5_ip, 6_ip], [1, 1])
   call slave_nodes(model, pair, node, length, thick, nexcl, error)
   call t%check(.not. allocated(error), 'joint tip in the set: no error')
   call t%equal(int(nexcl), 1, 'joint tip in the set: excluded')
   call t%equal(size(node), 2, 'joint tip in the set: 2 slave nodes')
   call t%close(length(2), 1.0_wp, 1.0e-15_wp, 'joint tip in the set: the edge to the tip counted once')
   call t%close(sum(length) + 0.65_wp, 2.0_wp, 1.0e-15_wp, &
                'joint tip in the set: with the tip''s half edge, the lengths sum to the face length')
   ! the upper face as slave (nodes 16, 17), the lower face as master
   call set_node_surface(model, [16_ip, 17_ip], [1_ip, 2_ip], [3, 3])
   call slave_nodes(model, pair, node, length, thick, nexcl, error)
   call t%check(.not. allocated(error), 'joint tip, upper face: no error')
   call t%equal(size(node), 2, 'joint tip, upper face: 2 slave nodes')
   call t%close(length(1), 0.35_wp, 1.0e-15_wp, 'joint tip, upper face: mouth node, half its edge')
   call t%close(length(2), 1.0_wp, 1.0e-15_wp, &
                'joint tip, upper face: node next to the tip has half of the edge to the tip')
   call t%close(sum(length) + 0.65_wp, 2.0_wp, 1.0e-15_wp, &
                'joint tip, upper face: with the tip''s half edge, the lengths sum to the face length')
   ! the element surfaces of the same faces give the same lengths
   call set_surfaces(model, [1_ip, 2_ip], [3, 3], [5_ip, 6_ip], [1, 1])
   call slave_nodes(model, pair, node, length, thick, nexcl, error)
   call t%check(.not. allocated(error), 'joint tip, element surface: no error')
   call t%equal(int(nexcl), 1, 'joint tip, element surface: the tip excluded')
   call t%close(length(1), 0.35_wp, 1.0e-15_wp, 'joint tip, element surface: mouth node')
   call t%close(length(2), 1.0_wp, 1.0e-15_wp, 'joint tip, element surface: node next to the tip')

   ! ---- master segments on the four sides of a 3 x 3 square mesh: outward normals
   call quad_grid(3, 3, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1, x, ptr, conn)
   call make_model(x, ptr, conn, 1.0_wp, 0.3_wp, plane_strain, form_vem, 1.0_wp, model)
   model%elem_id = [(int(700 + i, ip), i=1, 9)]
   call set_surfaces(model, [1_ip], [1], [1_ip, 2_ip, 3_ip, 3_ip, 6_ip, 9_ip, 9_ip, 8_ip, 7_ip, 7_ip, 4_ip, 1_ip], &
                     [1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4])
   call master_segments(model, pair, seg, seg_elem, seg_side, error)
   call t%check(.not. allocated(error), 'square boundary: no error')
   call t%equal(size(seg, 2), 12, 'square boundary: 12 segments')
   expect(:, 1) = [0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp]
   expect(:, 2) = [-1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp]
   do k = 1, 12
      associate (xa => model%x(:, seg(1, k)), xb => model%x(:, seg(2, k)))
         call project_point_segment(0.5_wp*(xa + xb), xa, xb, xi, g, n, d, st)
         i = (k - 1)/3 + 1
         call t%close(norm2(n - expect(i, :)), 0.0_wp, 0.0_wp, 'outward normal of a square side', &
                      atol=1.0e-15_wp)
         ! the centre of the square is inside: negative gap of -1/2 on every side
         call project_point_segment([0.5_wp, 0.5_wp], xa, xb, xi, g, n, d, st)
         call t%close(g, -0.5_wp, 1.0e-15_wp, 'square centre penetrates every side by 1/2')
      end associate
   end do
   call t%equal(int(seg_elem(5)), 6, 'segment element')
   call t%equal(seg_side(5), 2, 'segment side')
   ! an interior side: element 5 (centre) side 1 is shared with element 2
   call set_surfaces(model, [1_ip], [1], [1_ip, 5_ip], [1, 1])
   call master_segments(model, pair, seg, seg_elem, seg_side, error)
   call t%check(allocated(error), 'interior master side: error')
   if (allocated(error)) then
      write (*, '(a)') error%message
      call t%check(index(error%message, 'element 705 side 1') > 0, 'error names element and side')
      call t%check(index(error%message, 'element 702') > 0, 'error names the neighbour')
   end if
   ! a zero-length side: move node 2 onto node 1
   model%x(:, 2) = model%x(:, 1)
   call set_surfaces(model, [2_ip], [1], [1_ip], [1])
   call master_segments(model, pair, seg, seg_elem, seg_side, error)
   call t%check(allocated(error), 'zero-length master side: error')
   if (allocated(error)) then
      write (*, '(a)') error%message
      call t%check(index(error%message, 'zero length') > 0, 'zero length reported')
   end if
   ! a node surface cannot be a master
   call set_node_surface(model, [1_ip, 2_ip], [1_ip], [1])
   pair%master = 1
   pair%slave = 2
   call master_segments(model, pair, seg, seg_elem, seg_side, error)
   call t%check(allocated(error), 'node surface as master: error')
   call t%finish()
contains
   subroutine set_surfaces(m, se, ss, me, ms)
      type(model_t), intent(inout) :: m
      integer(ip), intent(in) :: se(:), me(:)
      integer, intent(in) :: ss(:), ms(:)
      if (allocated(m%surfaces)) deallocate (m%surfaces)
      allocate (m%surfaces(2))
      m%surfaces(1)%name = 'SLAVE'
      m%surfaces(1)%kind = surface_element
      m%surfaces(1)%elem = se
      m%surfaces(1)%side = ss
      m%surfaces(2)%name = 'MASTER'
      m%surfaces(2)%kind = surface_element
      m%surfaces(2)%elem = me
      m%surfaces(2)%side = ms
   end subroutine set_surfaces

   subroutine set_node_surface(m, nodes, me, ms)
      type(model_t), intent(inout) :: m
      integer(ip), intent(in) :: nodes(:), me(:)
      integer, intent(in) :: ms(:)
      if (allocated(m%surfaces)) deallocate (m%surfaces)
      allocate (m%surfaces(2))
      m%surfaces(1)%name = 'SLAVE'
      m%surfaces(1)%kind = surface_node
      m%surfaces(1)%nodes = nodes
      m%surfaces(2)%name = 'MASTER'
      m%surfaces(2)%kind = surface_element
      m%surfaces(2)%elem = me
      m%surfaces(2)%side = ms
   end subroutine set_node_surface
end program test_contact_surfaces
