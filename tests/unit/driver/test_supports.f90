!> Parts not held against rigid motion are found and described.
program test_supports
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t, err_model
   use vemcontact_model, only: model_t, string_t, source_loc_t
   use vemcontact_driver_supports, only: find_parts, check_supports, unused_nodes
   use vemcontact_contact_spring, only: spring_t
   use vemcontact_driver_equations, only: constraint_set_t
   implicit none
   type(checker_t) :: t
   type(model_t) :: m
   type(error_t), allocatable :: error
   type(constraint_set_t) :: cs
   integer(ip), allocatable :: part(:)
   integer(ip) :: nparts
   logical :: fixed(16)

   ! two separate unit squares (nodes 1-4 and 5-8) and a lone node 9..8 unused
   m%nnode = 8
   m%x = reshape([0., 0., 1., 0., 1., 1., 0., 1., 3., 0., 4., 0., 4., 1., 3., 1.], [2, 8])*1.0_wp
   m%nelem = 2
   m%elem_ptr = [1, 5, 9]
   m%elem_conn = [1, 2, 3, 4, 5, 6, 7, 8]
   m%elem_id = [10, 20]
   m%files = [string_t('deck.inp')]
   m%elem_loc = [source_loc_t(1, 7), source_loc_t(1, 8)]
   call find_parts(m, part, nparts)
   call t%equal(int(nparts), 2, 'two parts')
   call t%check(all(part(1:4) == part(1)) .and. all(part(5:8) == part(5)) .and. part(1) /= part(5), 'part labels')
   call t%check(.not. any(unused_nodes(m)), 'no unused nodes')

   ! part 1 clamped (node 1 both, node 4 x), part 2: pinned at one node only -> rotates
   fixed = .false.
   fixed([1, 2, 7]) = .true.
   fixed([9, 10]) = .true.
   call check_supports(m, part, nparts, fixed, error)
   call t%check(allocated(error), 'pinned part floats')
   if (allocated(error)) then
      call t%equal(error%code, err_model, 'error category')
      call t%check(index(error%message, 'rotate') > 0, 'rotation named: '//error%message)
      print '(a)', error%message
      call t%check(index(error%message, 'element 20') > 0, 'part named by an element id')
      call t%check(index(error%message, 'deck.inp:8') > 0, 'part named by file:line')
      call t%check(index(error%message, '(3.0') > 0 .or. index(error%message, '( 3.0') > 0 &
                   .or. index(error%message, '(3.00') > 0, 'rotation centre is the pinned node (3,0)')
      call t%check(index(error%message, 'element 10') == 0, 'held part not named')
   end if
   ! part 2 on rollers in y only -> translates in x
   fixed(9:16) = .false.
   fixed([10, 12]) = .true.
   call check_supports(m, part, nparts, fixed, error)
   call t%check(allocated(error), 'roller-only part floats')
   if (allocated(error)) call t%check(index(error%message, 'translate') > 0, 'translation named: '//error%message)
   ! part 2 held: x at node 5, y at nodes 5 and 6
   fixed(9:16) = .false.
   fixed([9, 10, 12]) = .true.
   call check_supports(m, part, nparts, fixed, error)
   call t%check(.not. allocated(error), 'both parts held')
   ! no support at all
   fixed = .false.
   call check_supports(m, part, nparts, fixed, error)
   call t%check(allocated(error), 'unsupported model')
   if (allocated(error)) call t%check(index(error%message, 'no support') > 0, 'no support named')
   ! contact springs: part 1 clamped; part 2 rests on part 1 through two vertical
   ! springs (frictionless): it can still slide along x
   fixed = .false.
   fixed([1, 2, 7]) = .true.
   call check_supports(m, part, nparts, fixed, error, &
                       [spring_t([3.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], 2, 1), spring_t([4.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], 2, 1)])
   call t%check(allocated(error), 'body on a frictionless plane floats')
   if (allocated(error)) then
      call t%check(index(error%message, 'part 2') > 0 .and. index(error%message, 'translate') > 0 &
                   .and. index(error%message, 'part 1') == 0, 'it slides along x: '//error%message)
   end if
   ! one x support added on part 2: held by the springs and that support
   fixed(9) = .true.
   call check_supports(m, part, nparts, fixed, error, &
                       [spring_t([3.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], 2, 1), spring_t([4.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], 2, 1)])
   call t%check(.not. allocated(error), 'held by contact and one support')
   ! a single spring: it can rotate about the spring point on the x support line
   call check_supports(m, part, nparts, fixed, error, [spring_t([4.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], 2, 1)])
   call t%check(allocated(error), 'one spring and one x support: rotation free')
   ! no contact closed and no support on part 2 (the model has a contact pair)
   allocate (m%pairs(1))
   fixed(9) = .false.
   call check_supports(m, part, nparts, fixed, error, [spring_t::])
   call t%check(allocated(error), 'no closed contact')
   if (allocated(error)) call t%check(index(error%message, 'no closed contact') > 0, 'says so: '//error%message)
   ! linear constraints (*EQUATION, *TIE): part 2 held only through equations that make
   ! three dofs of part 2 (node 5 x and y, node 6 y) depend on clamped part 1's node 3
   ! and node 2: held, though its only "fixed" dofs are the eliminated dependents
   deallocate (m%pairs)
   cs%n = 3
   cs%dep = [9_ip, 10_ip, 12_ip]
   cs%ptr = [1, 2, 3, 4]
   cs%dof = [5_ip, 6_ip, 4_ip]
   cs%a = [1.0_wp, 1.0_wp, 1.0_wp]
   fixed = .false.
   fixed([1, 2, 7]) = .true.
   fixed(cs%dep) = .true.
   call check_supports(m, part, nparts, fixed, error, cs=cs)
   call t%check(.not. allocated(error), 'a part held by equations on a held part')
   ! the same with part 1 free: the dependents of part 2 held nothing, both parts float
   ! together (before the equations were rows, the dependents counted as supports)
   fixed(1:8) = .false.
   call check_supports(m, part, nparts, fixed, error, cs=cs)
   call t%check(allocated(error), 'parts joined by equations float together')
   if (allocated(error)) call t%check(index(error%message, 'part 1') > 0 .and. index(error%message, 'part 2') > 0, &
                                      'both named: '//error%message)
   ! the independent side unsupported, the dependent side clamped: the equations make
   ! part 1's nodes 2 and 3 follow part 2 (x of node 2, y of nodes 2 and 3)
   cs%dep = [3_ip, 4_ip, 6_ip]
   cs%dof = [9_ip, 10_ip, 12_ip]
   fixed = .false.
   fixed([1, 2, 7]) = .true.
   fixed(cs%dep) = .true.
   call check_supports(m, part, nparts, fixed, error, cs=cs)
   call t%check(.not. allocated(error), 'a part held as the independent side of equations')
   call check_supports(m, part, nparts, fixed, error)
   call t%check(allocated(error), 'without the equations it floats')
   call t%finish()
end program test_supports
