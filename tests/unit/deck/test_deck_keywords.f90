!> Parsing results of every keyword: decks under tests/data/deck (run from
!> tests/unit) and small decks written to a temporary folder.
program test_deck_keywords
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, find_set, etype_polygon, etype_quad4, etype_tri3, &
                               plane_strain, plane_stress, form_vem, form_fem, dload_grav, dload_pressure
   use vemcontact_deck_reader, only: read_deck
   implicit none
   type(checker_t) :: t
   character(len=*), parameter :: data = '../data/deck/'
   real(wp), parameter :: tol = 1.0e-15_wp   ! values are read exactly: only rounding of the literal

   call test_basic()
   call test_include()
   call test_ops_and_defaults()
   call test_sparse_ids_and_crlf()
   call t%finish()

contains

   !> Every keyword of basic.inp: heading, nodes, elements (with continuation), sets incl.
   !> GENERATE, appending and set names, materials, sections, boundary, steps and loads.
   subroutine test_basic()
      type(model_t) :: m
      type(error_t), allocatable :: err
      integer :: k
      call read_deck(data//'basic.inp', m, err)
      call t%check(.not. allocated(err), 'basic.inp reads without error')
      if (allocated(err)) then
         print '(a)', err%message
         return
      end if
      call t%check(m%heading == 'Cantilever, two quads'//new_line('a')//'and a pentagon', '*HEADING text')
      call t%check(m%files(1)%s == '../data/deck/basic.inp', 'files(1) is the deck')
      ! *NODE
      call t%equal(int(m%nnode), 7, 'node count')
      call t%equal(int(m%node_id(7)), 10, 'user id of the last node')
      call t%close(m%x(1, 7), 3.0_wp, tol, 'x of node 10')
      call t%close(m%x(2, 7), 0.5_wp, tol, 'y of node 10')
      call t%close(m%x(1, 3), 2.0_wp, tol, 'x of node 3 (z = 0. given)')
      call t%equal(m%node_loc(7)%line, 12, 'line of node 10')
      call t%equal(m%node_loc(7)%file, 1, 'file of node 10')
      ! *ELEMENT
      call t%equal(int(m%nelem), 3, 'element count')
      call t%check(all(m%elem_id == [1, 2, 100]), 'element ids')
      call t%check(all(m%elem_conn(m%elem_ptr(1):m%elem_ptr(2) - 1) == [1, 2, 5, 4]), 'CPE4 connectivity')
      call t%check(all(m%elem_conn(m%elem_ptr(3):m%elem_ptr(4) - 1) == [3, 7, 6, 5, 2]), &
                   'polygon connectivity over continuation lines, mapped to internal indices')
      call t%check(all(m%elem_type == [etype_quad4, etype_quad4, etype_polygon]), 'element types')
      call t%check(all(m%elem_plane == [plane_strain, plane_strain, plane_stress]), 'CPE4 strain, VPS stress')
      call t%equal(m%elem_loc(3)%line, 17, 'line of a continued element is its first line')
      ! *NSET / *ELSET
      call t%check(set_is(m%nsets, 'NALL', [1, 2, 3, 4, 5, 6, 7]), '*NODE, NSET=')
      call t%check(set_is(m%nsets, 'LEFT', [1, 2, 4]), '*NSET appended by a second *NSET (case-insensitive)')
      call t%check(set_is(m%nsets, 'RIGHT', [3, 6]), '*NSET GENERATE with increment')
      call t%check(set_is(m%elsets, 'QUADS', [1, 2]), '*ELEMENT, ELSET=')
      call t%check(set_is(m%elsets, 'ALL', [1, 2, 3]), '*ELSET from set names')
      call t%equal(m%nsets(find_set(m%nsets, 'LEFT'))%loc%line, 20, 'set location is its first definition')
      ! *MATERIAL, *ELASTIC, *DENSITY
      call t%equal(size(m%materials), 2, 'material count')
      call t%check(m%materials(1)%name == 'STEEL' .and. m%materials(2)%name == 'ALU', 'material names upper case')
      call t%close(m%materials(1)%young, 210000.0_wp, tol, 'E of STEEL')
      call t%close(m%materials(1)%poisson, 0.3_wp, tol, 'nu of STEEL')
      call t%close(m%materials(1)%density, 7.85e-9_wp, tol, 'density of STEEL')
      call t%check(m%materials(1)%has_density .and. .not. m%materials(2)%has_density, 'has_density')
      call t%close(m%materials(2)%poisson, 0.33_wp, tol, 'nu .33 of ALU')
      ! *SOLID SECTION
      call t%equal(size(m%sections), 2, 'section count')
      call t%check(all(m%elem_mat == [1, 1, 2]), 'element materials from sections')
      call t%close(m%elem_thick(1), 2.5_wp, tol, 'thickness from the data line')
      call t%close(m%elem_thick(3), 1.0_wp, tol, 'default thickness 1')
      call t%check(all(m%elem_form == [form_fem, form_fem, form_vem]), 'default formulation FEM for CPE4')
      call t%equal(m%sections(2)%formulation, form_vem, 'FORMULATION=VEM stored')
      call t%equal(m%sections(1)%imat, 1, 'section material index')
      ! *BOUNDARY before the first step
      call t%equal(size(m%initial%boundary), 6, 'initial boundary: 3 nodes x 2 dofs')
      call t%check(all(m%initial%boundary%node == [1, 1, 2, 2, 4, 4]), 'initial boundary nodes')
      call t%check(all(m%initial%boundary%dof == [1, 2, 1, 2, 1, 2]), 'initial boundary dofs')
      call t%check(all(abs(m%initial%boundary%value) <= 0.0_wp), 'boundary value defaults to 0')
      ! *STEP, *CLOAD, *DLOAD
      call t%equal(size(m%steps), 2, 'step count')
      call t%check(m%steps(1)%name == 'Step-1', 'default step name')
      call t%equal(m%steps(1)%loc%line, 41, 'step location')
      call t%equal(size(m%steps(1)%cload), 1, 'one cload')
      call t%equal(int(m%steps(1)%cload(1)%node), 7, 'cload node (internal index of id 10)')
      call t%equal(m%steps(1)%cload(1)%dof, 2, 'cload dof')
      call t%close(m%steps(1)%cload(1)%value, -1.5_wp, tol, 'cload value')
      call t%equal(size(m%steps(1)%dload), 3, 'pressure on one element + GRAV on two')
      call t%equal(m%steps(1)%dload(1)%kind, dload_pressure, 'P2 is a pressure')
      call t%equal(m%steps(1)%dload(1)%side, 2, 'P2 side')
      call t%close(m%steps(1)%dload(1)%magnitude, 3.0_wp, tol, 'pressure value')
      do k = 2, 3
         call t%equal(m%steps(1)%dload(k)%kind, dload_grav, 'GRAV kind')
         call t%close(m%steps(1)%dload(k)%magnitude, 9810.0_wp, tol, 'GRAV magnitude')
         call t%close(m%steps(1)%dload(k)%dir(2), -1.0_wp, tol, 'GRAV direction normalised', atol=tol)
         call t%close(m%steps(1)%dload(k)%dir(1), 0.0_wp, tol, 'GRAV direction x', atol=tol)
      end do
      call t%check(.not. m%steps(1)%boundary_new, 'no OP=NEW in step 1')
      call t%check(m%steps(2)%name == 'second', 'NAME= on *STEP')
      call t%check(m%steps(2)%boundary_new, 'OP=NEW on *BOUNDARY')
      call t%equal(size(m%steps(2)%boundary), 6, 'dofs 1 to 3: dof 3 ignored')
      call t%close(m%steps(2)%boundary(1)%value, 0.1_wp, tol, 'boundary value')
   end subroutine test_basic

   !> Nested *INCLUDE relative to the including file, data lines from an included file.
   subroutine test_include()
      type(model_t) :: m
      type(error_t), allocatable :: err
      call read_deck(data//'include_main.inp', m, err)
      call t%check(.not. allocated(err), 'include_main.inp reads without error')
      if (allocated(err)) then
         print '(a)', err%message
         return
      end if
      call t%equal(size(m%files), 4, 'four files read')
      call t%check(m%files(2)%s == '../data/deck/sub/mesh.inp', 'include path relative to the deck')
      call t%check(m%files(3)%s == '../data/deck/material.inp', 'nested include relative to sub/')
      call t%equal(m%node_loc(3)%file, 2, 'node from the included file')
      call t%equal(m%node_loc(3)%line, 4, 'its line in that file')
      call t%equal(m%elem_loc(1)%file, 4, 'element data line from an included data-only file')
      call t%equal(m%elem_type(1), etype_tri3, 'CPS3 is a triangle')
      call t%equal(m%elem_plane(1), plane_stress, 'CPS3 is plane stress')
      call t%close(m%materials(1)%young, 100.0_wp, tol, 'material from the nested include')
      call t%close(m%elem_thick(1), 0.5_wp, tol, 'thickness')
   end subroutine test_include

   !> OP=NEW on *CLOAD and *DLOAD, blank last dof, loads on sets, ELSET GENERATE, FEM on a
   !> 4-node polygon, keyword and parameter spelling variants.
   subroutine test_ops_and_defaults()
      type(model_t) :: m
      type(error_t), allocatable :: err
      character(len=:), allocatable :: path
      path = write_deck('ops.inp', [character(len=60) :: &
                        '*nset, nset=poly_n', '1, 2, 3, 4, 2', &
                        '*node', '1,0,0', '2,1,0', '3,1,1', '4,0,1', '5,2,0', '6,2,1', &
                        '*nset, nset=poly_n', '1, 2, 3, 4, 2', &
                        '*element,type=vpe', '1, 1,2,3,4', '*Element, Type=CPE3', '2, 2, 5, 6', '3, 2, 6, 3', &
                        '*elset, elset=tris, generate', '2, 3', '*elset,elset=POLY', '1', &
                        '*material,name=m', '*elastic', '1.,0.', '*density', '2.', &
                        '*solidsection, elset=poly, material=M, formulation=FEM', &
                        '*SOLID  SECTION, ELSET=TRIS, MATERIAL=M', '', &
                        '*step, nlgeom=no', '*static', '*boundary', '1, 2,, 0.5', &
                        '*cload', '2, 1, 1.', '*cload, op=new', 'POLY_N, 2, -3.', &
                        '*dload', '1, P1, 1.', '*dload, OP=NEW', 'tris, p3, 2.', '*end step'])
      call read_deck(path, m, err)
      ! an *NSET before any node is an error (its ids are undefined), nothing else
      call t%check(allocated(err), 'set before its nodes is an error')
      if (allocated(err)) call t%check(index(err%message, 'ops.inp:2: error: undefined node 1') > 0, &
                                       'set before its nodes: message')
      path = write_deck('ops2.inp', [character(len=60) :: &
                        '*node', '1,0,0', '2,1,0', '3,1,1', '4,0,1', '5,2,0', '6,2,1', &
                        '*nset, nset=poly_n', '1, 2, 3, 4, 2', &
                        '*element,type=vpe', '1, 1,2,3,4', '*Element, Type=CPE3', '2, 2, 5, 6', '3, 2, 6, 3', &
                        '*elset, elset=tris, generate', '2, 3', '*elset,elset=POLY', '1', &
                        '*material,name=m', '*elastic', '1.,0.', '*density', '2.', &
                        '*solidsection, elset=poly, material=M, formulation=FEM', &
                        '*SOLID  SECTION, ELSET=TRIS, MATERIAL=M', '', &
                        '*step, nlgeom=no', '*static', '*boundary', '1, 2,, 0.5', &
                        '*cload', '2, 1, 1.', '*cload, op=new', 'POLY_N, 2, -3.', &
                        '*dload', '1, P1, 1.', '*dload, OP=NEW', 'tris, p3, 2.', '*end step'])
      call read_deck(path, m, err)
      call t%check(.not. allocated(err), 'ops2.inp reads without error')
      if (allocated(err)) then
         print '(a)', err%message
         return
      end if
      call t%check(set_is(m%elsets, 'TRIS', [2, 3]), '*ELSET GENERATE')
      call t%check(all(m%elem_form == [form_fem, form_fem, form_fem]), 'FEM on a 4-node VPE is allowed')
      call t%check(all(m%elem_type == [etype_polygon, etype_tri3, etype_tri3]), 'types')
      call t%close(m%elem_thick(2), 1.0_wp, tol, 'blank thickness line keeps 1')
      call t%equal(size(m%steps(1)%boundary), 1, 'blank last dof: one dof')
      call t%equal(m%steps(1)%boundary(1)%dof, 2, 'blank last dof = first dof')
      call t%close(m%steps(1)%boundary(1)%value, 0.5_wp, tol, 'value after blank last dof')
      call t%check(m%steps(1)%cload_new .and. m%steps(1)%dload_new, 'OP=NEW flags on *CLOAD and *DLOAD')
      call t%equal(size(m%steps(1)%cload), 4, 'OP=NEW drops earlier cloads of the step; one per set node')
      call t%check(all(m%steps(1)%cload%node == [1, 2, 3, 4]), 'cload on a node set')
      call t%equal(size(m%steps(1)%dload), 2, 'OP=NEW drops earlier dloads of the step; one per element')
      call t%check(all(m%steps(1)%dload%side == [3, 3]), 'P3 side')
   end subroutine test_ops_and_defaults

   !> Widely spread ids (sorted id map), CRLF line ends and tabs.
   subroutine test_sparse_ids_and_crlf()
      type(model_t) :: m
      type(error_t), allocatable :: err
      character(len=:), allocatable :: path
      character(len=1), parameter :: cr = achar(13), tab = achar(9)
      path = write_deck('sparse.inp', [character(len=60) :: &
                        '*NODE'//cr, '2000000000,'//tab//'0., 0.'//cr, '7, 1., 0.'//cr, '123456789, 1., 1.'//cr, &
                        '*ELEMENT, TYPE=CPS3, ELSET=E'//cr, '1000000, 2000000000, 7, 123456789'//cr, &
                        '*MATERIAL, NAME=M'//cr, '*ELASTIC'//cr, '1., 0.2'//cr, &
                        '*SOLID SECTION, ELSET=E, MATERIAL=M'//cr, '*STEP'//cr, '*STATIC'//cr, &
                        '*BOUNDARY'//cr, '123456789, 1, 2'//cr, '*END STEP'//cr])
      call read_deck(path, m, err)
      call t%check(.not. allocated(err), 'sparse.inp reads without error')
      if (allocated(err)) then
         print '(a)', err%message
         return
      end if
      call t%check(all(m%elem_conn == [1, 2, 3]), 'sparse ids mapped to internal indices')
      call t%equal(int(m%elem_id(1)), 1000000, 'element id kept')
      call t%equal(int(m%steps(1)%boundary(1)%node), 3, 'boundary on a sparse id')
   end subroutine test_sparse_ids_and_crlf

   logical function set_is(sets, name, items)
      use vemcontact_model, only: named_set_t
      type(named_set_t), intent(in) :: sets(:)
      character(len=*), intent(in) :: name
      integer, intent(in) :: items(:)
      integer :: k
      set_is = .false.
      k = find_set(sets, name)
      if (k == 0) return
      if (size(sets(k)%items) /= size(items)) return
      set_is = all(sets(k)%items == int(items, ip))
   end function set_is

   !> Write `lines` (trailing blanks trimmed) to a file in the temporary folder; return its path.
   function write_deck(name, lines) result(path)
      character(len=*), intent(in) :: name
      character(len=*), intent(in) :: lines(:)
      character(len=:), allocatable :: path
      character(len=256) :: dir
      integer :: u, k, n
      call get_environment_variable('TMPDIR', dir, n)
      if (n == 0) dir = '/tmp'
      path = trim(dir)//'/vemcontact_test_deck_keywords_'//name
      open (newunit=u, file=path, status='replace', action='write')
      do k = 1, size(lines)
         write (u, '(a)') trim(lines(k))
      end do
      close (u)
   end function write_deck
end program test_deck_keywords
