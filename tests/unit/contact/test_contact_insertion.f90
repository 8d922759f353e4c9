!> The interface node insertion of SURFACE TO SURFACE pairs on a small model whose
!> result is known by hand: one node inserted into the master side, the element's
!> connectivity, the renumbered element surfaces and pressure loads, the node
!> partners, for first- and second-order sides; inserted points on the chord of a curved
!> face; the refusal of FEM sides.
program test_contact_insertion
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: model_t, contact_pair_t, surface_t, dload_t, surface_element, &
                               plane_strain, form_vem, form_fem, pair_surface_to_surface, dload_pressure, &
                               etype_polygon, etype_polygon2
   use vemcontact_test_model, only: make_model
   use vemcontact_contact_insertion, only: insert_interface_nodes, on_face
   implicit none
   type(checker_t) :: t
   type(model_t) :: model, model0
   type(error_t), allocatable :: error
   integer(ip), allocatable :: added(:)
   real(wp), allocatable :: x(:, :)
   real(wp) :: p(2), r
   integer :: k, n

   ! lower block [0,2]x[0,1]: one element, nodes 1-4; upper [0,1]x[1,2] and [1,2]x[1,2]:
   ! nodes 5-10 (bottom 5, 6, 7 at x = 0, 1, 2; top 8, 9, 10).  Slave: the upper
   ! bottom (sides 1 of elements 2 and 3); master: the lower top (side 3 of element 1,
   ! from (2,1) to (0,1)).  The slave node 6 at x = 1 projects to the middle of the
   ! master side; the master nodes 3 and 4 coincide with slave nodes 7 and 5.
   x = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, &
                0.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 2.0_wp, 1.0_wp, &
                0.0_wp, 2.0_wp, 1.0_wp, 2.0_wp, 2.0_wp, 2.0_wp], [2, 10])
   call make_model(x, [1_ip, 5_ip, 9_ip, 13_ip], [1_ip, 2_ip, 3_ip, 4_ip, 5_ip, 6_ip, 9_ip, 8_ip, &
                                                  6_ip, 7_ip, 10_ip, 9_ip], 1.0_wp, 0.3_wp, plane_strain, &
                   form_vem, 1.0_wp, model)
   allocate (model%surfaces(2))
   model%surfaces(1) = surface_t(name='SLAVE', kind=surface_element, elem=[2_ip, 3_ip], side=[1, 1])
   model%surfaces(2) = surface_t(name='MASTER', kind=surface_element, elem=[1_ip], side=[3])
   model%pairs = [contact_pair_t(slave=1, master=2, interaction=1, formulation=pair_surface_to_surface)]
   ! pressures on the split side and on the side after it
   model%initial%dload = [dload_t(elem=1, kind=dload_pressure, side=3, magnitude=1.0_wp), &
                          dload_t(elem=1, kind=dload_pressure, side=4, magnitude=2.0_wp)]
   model0 = model
   call insert_interface_nodes(model, added, error)
   call t%check(.not. allocated(error), 'insertion without error')
   if (allocated(error)) print '(a)', error%message
   call t%equal(int(added(1)), 1, 'one node inserted')
   call t%equal(int(model%nnode), 11, 'the model gains it')
   call t%close(model%x(1, 11), 1.0_wp, 1.0e-15_wp, 'at the projection x = 1')
   call t%close(model%x(2, 11), 1.0_wp, 1.0e-15_wp, 'on the straight side, y = 1')
   call t%equal(int(model%node_id(11)), 11, 'numbered after the largest id')
   call t%check(all(model%elem_conn(model%elem_ptr(1):model%elem_ptr(2) - 1) == [1_ip, 2_ip, 3_ip, 11_ip, 4_ip]), &
                'the master element takes it between the side''s end nodes')
   call t%equal(model%elem_type(1), etype_polygon, 'the quad became a polygon')
   call t%check(all(model%elem_conn(model%elem_ptr(2):) == model0%elem_conn(model0%elem_ptr(2):)), &
                'the slave elements are unchanged (their nodes coincide with the master''s)')
   call t%check(all(model%surfaces(2)%elem == [1_ip, 1_ip]) .and. all(model%surfaces(2)%side == [3, 4]), &
                'the master facet became its two pieces')
   call t%check(size(model%initial%dload) == 3, 'the pressure on the split side acts on both pieces')
   if (size(model%initial%dload) == 3) then
      call t%check(all(model%initial%dload%side == [3, 4, 5]) .and. &
                   all(abs(model%initial%dload%magnitude - [1.0_wp, 1.0_wp, 2.0_wp]) <= 0.0_wp), 'sides renumbered')
   end if
   ! partners: slave 5 - master 4, 6 - 11 (inserted), 7 - 3
   call t%check(allocated(model%pairs(1)%partner), 'partners recorded')
   if (allocated(model%pairs(1)%partner)) then
      n = size(model%pairs(1)%partner, 2)
      call t%equal(n, 3, 'three node pairs')
      do k = 1, n
         select case (model%pairs(1)%partner(1, k))
         case (5)
            call t%equal(int(model%pairs(1)%partner(2, k)), 4, 'slave 5 faces master 4')
         case (6)
            call t%equal(int(model%pairs(1)%partner(2, k)), 11, 'slave 6 faces the inserted node')
         case (7)
            call t%equal(int(model%pairs(1)%partner(2, k)), 3, 'slave 7 faces master 3')
         case default
            call t%check(.false., 'an unexpected slave node in the pairs')
         end select
      end do
   end if

   ! FEM sides cannot take nodes
   model = model0
   model%elem_form(1) = form_fem
   call insert_interface_nodes(model, added, error)
   call t%check(allocated(error), 'a FEM side is refused')
   if (allocated(error)) call t%check(index(error%message, 'FEM elements have sides') > 0, 'the message says why')

   ! second order: the lower VPE2 square [0,2]x[0,1] (corners 1-4, side nodes 5-8), the
   ! upper VPE2 squares [0,1]x[1,2] (9-12, 13-16) and [1,2]x[1,2] (10, 17, 18, 11; 19-21,
   ! 14).  The slave corner 10 at x = 1 projects onto the master side 3 -> 4 at t = 1/2
   ! (its side node 7): a corner is inserted there, the piece [1/2, 1] keeps node 7 moved
   ! to its middle (0.5, 1), the piece [0, 1/2] gets a new side node at (1.5, 1), and the
   ! slave side nodes 13 and 19 face them.
   deallocate (x)
   x = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, &
                1.0_wp, 0.0_wp, 2.0_wp, 0.5_wp, 1.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, &
                0.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, &
                0.5_wp, 1.0_wp, 1.0_wp, 1.5_wp, 0.5_wp, 2.0_wp, 0.0_wp, 1.5_wp, &
                2.0_wp, 1.0_wp, 2.0_wp, 2.0_wp, 1.5_wp, 1.0_wp, 2.0_wp, 1.5_wp, 1.5_wp, 2.0_wp], [2, 21])
   call make_model(x, [1_ip, 9_ip, 17_ip, 25_ip], &
                   [1_ip, 2_ip, 3_ip, 4_ip, 5_ip, 6_ip, 7_ip, 8_ip, &
                    9_ip, 10_ip, 11_ip, 12_ip, 13_ip, 14_ip, 15_ip, 16_ip, &
                    10_ip, 17_ip, 18_ip, 11_ip, 19_ip, 20_ip, 21_ip, 14_ip], 1.0_wp, 0.3_wp, plane_strain, &
                   form_vem, 1.0_wp, model, order=2)
   allocate (model%surfaces(2))
   model%surfaces(1) = surface_t(name='SLAVE', kind=surface_element, elem=[2_ip, 3_ip], side=[1, 1])
   model%surfaces(2) = surface_t(name='MASTER', kind=surface_element, elem=[1_ip], side=[3])
   model%pairs = [contact_pair_t(slave=1, master=2, interaction=1, formulation=pair_surface_to_surface)]
   call insert_interface_nodes(model, added, error)
   call t%check(.not. allocated(error), 'second order: insertion without error')
   if (allocated(error)) print '(a)', error%message
   call t%equal(int(added(1)), 2, 'a corner and a side node added')
   call t%check(all(model%elem_conn(model%elem_ptr(1):model%elem_ptr(2) - 1) == &
                    [1_ip, 2_ip, 3_ip, 22_ip, 4_ip, 5_ip, 6_ip, 23_ip, 7_ip, 8_ip]), &
                'corners with the inserted one, then a side node per piece')
   call t%equal(model%elem_type(1), etype_polygon2, 'still a second-order polygon')
   call t%check(all(abs(model%x(:, 22) - [1.0_wp, 1.0_wp]) <= 1.0e-15_wp), 'the corner at (1, 1)')
   call t%check(all(abs(model%x(:, 23) - [1.5_wp, 1.0_wp]) <= 1.0e-15_wp), 'the new side node at (1.5, 1)')
   call t%check(all(abs(model%x(:, 7) - [0.5_wp, 1.0_wp]) <= 1.0e-15_wp), 'the old one moved to (0.5, 1)')
   call t%check(all(model%surfaces(2)%side == [3, 4]), 'the master facet became its two pieces')
   if (allocated(model%pairs(1)%partner)) then
      n = size(model%pairs(1)%partner, 2)
      call t%equal(n, 5, 'three corner pairs and two side-node pairs')
      do k = 1, n
         associate (pr => model%pairs(1)%partner(:, k))
            select case (pr(1))
            case (9)
               call t%equal(int(pr(2)), 4, 'slave 9 faces master 4')
            case (10)
               call t%equal(int(pr(2)), 22, 'slave 10 faces the inserted corner')
            case (17)
               call t%equal(int(pr(2)), 3, 'slave 17 faces master 3')
            case (13)
               call t%equal(int(pr(2)), 7, 'slave side node 13 faces the moved side node 7')
            case (19)
               call t%equal(int(pr(2)), 23, 'slave side node 19 faces the new side node')
            case default
               call t%check(.false., 'an unexpected slave node in the pairs')
            end select
         end associate
      end do
   end if

   ! a side of a curved face (a regular 12-gon on a circle of radius 5): the inserted
   ! point stays on the chord, the element's boundary, not on the circle
   r = 5.0_wp
   p = on_face(r*[1.0_wp, 0.0_wp], r*[cos(acos(-1.0_wp)/6), sin(acos(-1.0_wp)/6)], 0.5_wp)
   call t%close(norm2(p), r*cos(acos(-1.0_wp)/12), 1.0e-15_wp, 'the mid-side point on the chord, inside the circle')
   p = on_face([0.0_wp, 0.0_wp], [1.0_wp, 0.0_wp], 0.3_wp)
   call t%check(all(abs(p - [0.3_wp, 0.0_wp]) <= 0.0_wp), 'a straight face: exactly on the side')
   call t%finish()
end program test_contact_insertion
