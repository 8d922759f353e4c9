!> The interface node insertion of SURFACE TO SURFACE pairs on a small model whose
!> result is known by hand: one node inserted into the master side, the element's
!> connectivity, the renumbered element surfaces and pressure loads, the node
!> partners; inserted points on the chord of a curved face; the refusal of FEM sides.
program test_contact_insertion
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: model_t, contact_pair_t, surface_t, dload_t, surface_element, &
                               plane_strain, form_vem, form_fem, pair_surface_to_surface, dload_pressure, &
                               etype_polygon
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

   ! a side of a curved face (a regular 12-gon on a circle of radius 5): the inserted
   ! point stays on the chord, the element's boundary, not on the circle
   r = 5.0_wp
   p = on_face(r*[1.0_wp, 0.0_wp], r*[cos(acos(-1.0_wp)/6), sin(acos(-1.0_wp)/6)], 0.5_wp)
   call t%close(norm2(p), r*cos(acos(-1.0_wp)/12), 1.0e-15_wp, 'the mid-side point on the chord, inside the circle')
   p = on_face([0.0_wp, 0.0_wp], [1.0_wp, 0.0_wp], 0.3_wp)
   call t%check(all(abs(p - [0.3_wp, 0.0_wp]) <= 0.0_wp), 'a straight face: exactly on the side')
   call t%finish()
end program test_contact_insertion
