!> One check per error message of the deck reader: read_deck must return an
!> error whose message names the file, the right line and a key phrase.  Each
!> case is a valid base deck with one line changed or inserted, written to the
!> temporary folder; a few cases use decks under tests/data/deck.
program test_deck_errors
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t, err_input, err_io
   use vemcontact_model, only: model_t
   use vemcontact_deck_reader, only: read_deck
   implicit none
   type(checker_t) :: t
   integer, parameter :: w = 60
   character(len=w), parameter :: base(18) = [character(len=w) :: &
                                  '*NODE', '1, 0., 0.', '2, 1., 0.', '3, 1., 1.', '4, 0., 1.', &
                                  '*ELEMENT, TYPE=CPE4, ELSET=E', '1, 1, 2, 3, 4', &
                                  '*MATERIAL, NAME=M', '*ELASTIC', '1000., 0.3', &
                                  '*SOLID SECTION, ELSET=E, MATERIAL=M', '*BOUNDARY', '1, 1, 2', &
                                  '*STEP', '*STATIC', '*CLOAD', '3, 1, 1.', '*END STEP']
   character(len=*), parameter :: data = '../data/deck/'
   type(model_t) :: m
   type(error_t), allocatable :: err
   character(len=:), allocatable :: path
   integer :: k
   !> lines of many_errors.inp with an error (one per line, several kinds)
   integer, parameter :: many_lines(*) = [5, 7, 8, 9, 10, 13, 14, 15, 17, 18, 22, 23, 25, 28, 29, 31, 33, 34]

   path = write_deck('base', base)
   call read_deck(path, m, err)
   call t%check(.not. allocated(err), 'the base deck is valid')

   ! keyword lines
   call expect('unknown_kw', ins(5, '*FOO, BAR=1'), 6, 'unknown keyword *FOO')
   call expect('spelling', ins(5, '*ELEMNT, TYPE=CPE4'), 6, 'did you mean *ELEMENT?')
   call expect('calculix_kw', ins(5, '*ORIENTATION, NAME=O'), 6, 'keyword *ORIENTATION is not supported')
   call expect('unknown_param', rep(1, '*NODE, NSETT=A'), 1, 'unknown parameter NSETT of *NODE')
   call expect('param_suggest', rep(1, '*NODE, NSETT=A'), 1, 'did you mean NSET?')
   call expect('param_no_value', ins(5, '*NSET, NSET='), 6, 'parameter NSET of *NSET needs a value')
   call expect('flag_with_value', ins(5, '*NSET, NSET=A, GENERATE=1'), 6, 'parameter GENERATE of *NSET takes no value')
   call expect('param_twice', rep(6, '*ELEMENT, TYPE=CPE4, TYPE=CPE4'), 6, 'parameter TYPE of *ELEMENT is given twice')
   call expect('missing_type', rep(6, '*ELEMENT, ELSET=E'), 6, 'missing required parameter TYPE of *ELEMENT')
   call expect('missing_name', rep(8, '*MATERIAL'), 8, 'missing required parameter NAME of *MATERIAL')
   call expect('bad_value', rep(11, '*SOLID SECTION, ELSET=E, MATERIAL=M, FORMULATION=XFEM'), 11, &
               'invalid value XFEM for parameter FORMULATION')
   call expect('data_first', ins(0, '1, 2, 3'), 1, 'data line before the first keyword')
   call expect('data_after_step', ins(14, '1, 2'), 15, 'unexpected data line: *STEP takes no data lines')
   ! nodes
   call expect('coord_text', rep(3, '2, 1., abc'), 3, 'y coordinate must be a number, found ''abc''')
   call expect('coord_nan', rep(3, '2, NaN, 0.'), 3, 'NaN is not allowed as x coordinate')
   call expect('coord_inf', rep(3, '2, 1., -Inf'), 3, 'infinite value is not allowed as y coordinate')
   call expect('coord_huge', rep(3, '2, 1e999, 0.'), 3, 'x coordinate ''1e999'' is out of range')
   call expect('id_overflow', rep(3, '99999999999, 1., 0.'), 3, 'node id ''99999999999'' is out of range')
   call expect('id_real', rep(3, '2.5, 1., 0.'), 3, 'node id must be an integer, found ''2.5''')
   call expect('id_zero', rep(3, '0, 1., 0.'), 3, 'node id 0 must be a positive integer')
   call expect('node_z', rep(3, '2, 1., 0., 0.5'), 3, 'node 2 has z = 0.5')
   call expect('node_fields', rep(3, '2, 1., 0., 0., x7'), 3, 'field 5 of a *NODE line (id, x, y, z) must be a number')
   call expect('dup_node', ins(5, '2, 5., 5.'), 6, 'duplicate node id 2 (first defined at')
   ! elements
   call expect('elem_type', rep(6, '*ELEMENT, TYPE=CPE44, ELSET=E'), 6, 'unsupported element type CPE44')
   call expect('elem_scope', rep(6, '*ELEMENT, TYPE=C3D8, ELSET=E'), 6, &
               'element type C3D8 (three-dimensional solid) is outside vemcontact''s scope')
   call expect('elem_axi', rep(6, '*ELEMENT, TYPE=CAX4, ELSET=E'), 6, 'element type CAX4 (axisymmetric) is outside')
   call expect('freq_scope', rep(15, '*FREQUENCY'), 15, 'a frequency step (*FREQUENCY) is outside')
   call expect('heat_scope', rep(15, '*HEAT TRANSFER'), 15, 'heat transfer (*HEAT TRANSFER) is outside')
   ! a refusal is one message: the element set E it leaves undefined, the section and
   ! the loads on its nodes would each give a follow-on error
   call expect_one('elem_scope_one', rep(6, '*ELEMENT, TYPE=CAX4, ELSET=E'))
   call expect_one('nlgeom_one', rep(14, '*STEP, NLGEOM'))
   call expect('elem_count', rep(7, '1, 1, 2, 3'), 7, 'element 1 of type CPE4 needs 4 nodes, found 3')
   call expect('poly_count', [character(len=w) :: base(1:5), line('*ELEMENT, TYPE=VPE, ELSET=P'), line('9, 1, 2'), base(6:)], 7, &
               'element 9 of type VPE needs at least 3 nodes, found 2')
   call expect('elem_node', rep(7, '1, 1, 2, 3, 44'), 7, 'element 1 refers to undefined node 44')
   call expect('elem_node_text', rep(7, '1, 1, 2, 3, x'), 7, 'node id of element 1 must be a number, found ''x''')
   call expect('dup_elem', ins(7, '1, 2, 3, 4, 1'), 8, 'duplicate element id 1')
   ! sets
   call expect('set_undef_node', ins(5, '*NSET, NSET=A'//achar(10)//'1, 77'), 7, 'undefined node 77')
   call expect('set_undef_name', ins(5, '*NSET, NSET=A'//achar(10)//'1, BB'), 7, 'undefined node set BB')
   call expect('generate_missing', ins(5, '*NSET, NSET=A, GENERATE'//achar(10)//'1, 9'), 7, &
               '5 of the ids 1 to 9 are not defined nodes (the first is 5)')
   call expect('generate_fields', ins(5, '*NSET, NSET=A, GENERATE'//achar(10)//'1'), 7, &
               'a GENERATE data line needs first, last [, increment]')
   call expect('generate_range', ins(5, '*NSET, NSET=A, GENERATE'//achar(10)//'4, 1'), 7, &
               'GENERATE range is empty')
   ! materials and sections
   call expect('young', rep(10, '-1000., 0.3'), 10, 'Young''s modulus E = -1000. must be positive')
   call expect('poisson', rep(10, '1000., 0.5'), 10, 'Poisson''s ratio nu = 0.5 must satisfy -1 < nu < 0.5')
   call expect('elastic_missing_data', rep(10, '*DENSITY'), 10, '*ELASTIC needs a data line: E, nu')
   call expect('elastic_table', ins(10, '2000., 0.3, 100.'), 11, 'temperature-dependent properties are not supported')
   call expect('elastic_alone', ins(7, '*ELASTIC'//achar(10)//'1., 0.'), 8, '*ELASTIC must follow a *MATERIAL')
   call expect('dup_material', ins(10, '*MATERIAL, NAME=m'), 11, 'duplicate material name M')
   call expect('no_elastic', rep(10, '*DENSITY'//achar(10)//'1.'), 8, 'material M has no *ELASTIC constants')
   call expect('undef_material', rep(11, '*SOLID SECTION, ELSET=E, MATERIAL=N'), 11, 'undefined material N')
   call expect('undef_elset', rep(11, '*SOLID SECTION, ELSET=EE, MATERIAL=M'), 11, 'undefined element set EE')
   call expect('no_section', rep(11, '** no section'), 7, 'element 1 has no section')
   call expect('two_sections', ins(11, '*SOLID SECTION, ELSET=E, MATERIAL=M'), 12, &
               'element 1 already has a section (from ')
   call expect('thickness', ins(11, '-2.'), 12, 'thickness -2. must be positive')
   call expect('fem_polygon', [character(len=w) :: base(1:5), line('5, 2., 0.5'), line('*ELEMENT, TYPE=VPE, ELSET=E'), &
                               line('1, 1, 2, 5, 3, 4'), base(8:10), &
                               line('*SOLID SECTION, ELSET=E, MATERIAL=M, FORMULATION=FEM'), base(12:)], &
               12, 'FORMULATION=FEM on element 1 with 5 nodes')
   ! boundary conditions, loads, steps
   call expect('undef_nset', rep(13, 'LEFT, 1, 2'), 13, 'undefined node set LEFT')
   call expect('undef_node', rep(13, '9, 1, 2'), 13, 'undefined node 9')
   call expect('dof6', rep(13, '1, 1, 6'), 13, 'degree of freedom 6 does not exist in a 2D model')
   call expect('dof_order', rep(13, '1, 2, 1'), 13, 'last degree of freedom 1 is smaller than the first 2')
   call expect('op_new_model', rep(12, '*BOUNDARY, OP=NEW'), 12, 'OP=NEW on *BOUNDARY is only meaningful inside a *STEP')
   call expect('cload_outside', ins(13, '*CLOAD'//achar(10)//'3, 1, 1.'), 14, '*CLOAD is only allowed inside a *STEP')
   call expect('cload_z', rep(17, '3, 3, 1.'), 17, 'a force in z (dof 3) cannot be applied')
   call expect('cload_value', rep(17, '3, 1, one'), 17, 'load value must be a number')
   call expect('dload_side', ins(17, '*DLOAD'//achar(10)//'1, P5, 1.'), 19, 'element 1 has 4 sides, so there is no side P5')
   call expect('dload_label', ins(17, '*DLOAD'//achar(10)//'E, BX, 1.'), 19, 'unsupported *DLOAD label BX')
   call expect('grav_density', ins(17, '*DLOAD'//achar(10)//'E, GRAV, 9.81, 0., -1.'), 19, &
               'GRAV on element 1 whose material M has no *DENSITY')
   call expect('grav_zero', ins(17, '*DLOAD'//achar(10)//'E, GRAV, 9.81, 0., 0.'), 19, 'gravity direction (dx, dy) is zero')
   call expect('grav_z', ins(17, '*DLOAD'//achar(10)//'E, GRAV, 9.81, 0., -1., 1.'), 19, &
               'gravity direction has a z component')
   call expect('bc_type', rep(13, '1, FIXED'), 13, 'unknown boundary type FIXED')
   call expect('nlgeom', rep(14, '*STEP, NLGEOM=YES'), 14, 'NLGEOM (geometric nonlinearity) is outside')
   call expect('inc', rep(14, '*STEP, INC=-3'), 14, 'parameter INC of *STEP must be a positive integer')
   call expect('node_in_step', ins(15, '*NODE'//achar(10)//'9, 0., 0.'), 16, '*NODE is not allowed inside a *STEP')
   call expect('no_static', rep(15, '** no static'), 14, 'the step has no procedure')
   call expect('two_static', ins(15, '*STATIC'), 16, 'second *STATIC in the step started at')
   call expect('static_data', ins(15, '1., x'), 16, 'time period of the step must be a number')
   ! the *STATIC data line: initial increment, period, minimum, maximum
   call expect('static_negative', ins(15, '-0.1, 1.'), 16, 'the initial time increment must be positive, not -0.1')
   call expect('static_zero_period', ins(15, '0.1, 0.'), 16, 'the time period of the step must be positive, not 0.')
   call expect('static_min_above', ins(15, '0.1, 1., 0.2'), 16, &
               'the minimum time increment 0.2 is larger than the initial increment 0.1')
   call expect('static_max_below', ins(15, '0.1, 1., 0.01, 0.05'), 16, &
               'the maximum time increment 0.05 is smaller than the initial increment 0.1')
   call expect('no_end_step', base(1:17), 14, 'the step is not closed by *END STEP')
   call expect('end_without_step', [character(len=w) :: base, '*END STEP'], 19, '*END STEP without a matching *STEP')
   call expect('step_in_step', ins(17, '*STEP'), 18, '*STEP inside a step: the step started at')
   call expect_noline('no_step', base(1:13), 'nothing to solve: the deck has no *STEP')
   call expect_noline('empty', [character(len=w) :: '** only a comment', ''], 'the deck is empty')
   ! files
   call expect_file(data//'missing_include.inp', data//'missing_include.inp:3: error: cannot include ''no_such_file.inp''')
   call expect_file(data//'cycle_a.inp', data//'sub/cycle_b.inp:2: error: cannot include ''../cycle_a.inp'': include cycle: ')
   call read_deck(data//'no_such_deck.inp', m, err)
   call t%check(allocated(err), 'unreadable deck: error')
   if (allocated(err)) then
      call t%check(index(err%message, data//'no_such_deck.inp: error: cannot open') == 1, 'unreadable deck: message')
      call t%equal(err%code, err_io, 'unreadable deck: I/O error code')
   end if
   ! all errors of a deck in one run
   call read_deck(data//'many_errors.inp', m, err)
   call t%check(allocated(err), 'many_errors.inp: error')
   if (allocated(err)) then
      call t%equal(err%code, err_input, 'many errors: input error code')
      do k = 1, size(many_lines)
         call t%check(index(err%message, 'many_errors.inp:'//trim(itoa(many_lines(k)))//': error:') > 0, &
                      'many errors: line '//trim(itoa(many_lines(k)))//' reported')
      end do
      call t%check(index(err%message, 'many_errors.inp:24: error: undefined material STEL') > 0, &
                   'many errors: deferred error reported too')
      call t%check(index(err%message, 'error: the deck has 21 errors') > 0, 'many errors: summary line')
   end if
   ! the message cap
   block
      character(len=w) :: lines(70)
      lines(1) = '*NODE'
      do k = 2, 70
         write (lines(k), '(i0,a)') k, ', 1., bad'
      end do
      call read_deck(write_deck('cap', lines), m, err)
      call t%check(allocated(err), 'cap: error')
      if (allocated(err)) then
         call t%check(index(err%message, '... and 19 more errors not shown') > 0, 'cap: 50 shown, 19 counted')
         call t%check(index(err%message, 'error: the deck has 69 errors') > 0, 'cap: total count')
      end if
   end block
   call t%finish()

contains

   function line(s) result(l)
      character(len=*), intent(in) :: s
      character(len=w) :: l
      l = s
   end function line

   !> Base deck with line k replaced by `s` (which may hold several lines).
   function rep(k, s) result(lines)
      integer, intent(in) :: k
      character(len=*), intent(in) :: s
      character(len=w), allocatable :: lines(:)
      lines = [character(len=w) :: base(1:k - 1), s, base(k + 1:)]
   end function rep

   !> Base deck with `s` inserted after line k.
   function ins(k, s) result(lines)
      integer, intent(in) :: k
      character(len=*), intent(in) :: s
      character(len=w), allocatable :: lines(:)
      lines = [character(len=w) :: base(1:k), s, base(k + 1:)]
   end function ins

   !> The deck must fail with "<path>:<line>: error: ..." and contain `phrase`.
   subroutine expect(name, lines, lineno, phrase)
      character(len=*), intent(in) :: name
      character(len=w), intent(in) :: lines(:)
      integer, intent(in) :: lineno
      character(len=*), intent(in) :: phrase
      character(len=:), allocatable :: p
      type(model_t) :: mm
      type(error_t), allocatable :: e
      p = write_deck(name, lines)
      call read_deck(p, mm, e)
      call t%check(allocated(e), name//': error returned')
      if (.not. allocated(e)) return
      call t%check(index(e%message, p//':'//trim(itoa(lineno))//': error: ') > 0, name//': file and line named')
      call t%check(index(e%message, phrase) > 0, name//': message says "'//phrase//'"')
      if (index(e%message, phrase) == 0 .or. index(e%message, p//':'//trim(itoa(lineno))//':') == 0) then
         print '(a)', e%message
      end if
   end subroutine expect

   !> Exactly one error message (a refused deck).
   subroutine expect_one(name, lines)
      character(len=*), intent(in) :: name
      character(len=w), intent(in) :: lines(:)
      character(len=:), allocatable :: p
      type(model_t) :: mm
      type(error_t), allocatable :: e
      integer :: n, at, k
      p = write_deck(name, lines)
      call read_deck(p, mm, e)
      call t%check(allocated(e), name//': error returned')
      if (.not. allocated(e)) return
      n = 0
      at = 1
      do
         k = index(e%message(at:), ': error: ')
         if (k == 0) exit
         n = n + 1
         at = at + k + 8
      end do
      call t%check(n == 1, name//': exactly one error message')
      if (n /= 1) print '(a)', e%message
   end subroutine expect_one

   !> Errors about the deck as a whole: "<path>: error: ...".
   subroutine expect_noline(name, lines, phrase)
      character(len=*), intent(in) :: name
      character(len=w), intent(in) :: lines(:)
      character(len=*), intent(in) :: phrase
      character(len=:), allocatable :: p
      type(model_t) :: mm
      type(error_t), allocatable :: e
      p = write_deck(name, lines)
      call read_deck(p, mm, e)
      call t%check(allocated(e), name//': error returned')
      if (.not. allocated(e)) return
      call t%check(index(e%message, p//': error: '//phrase) > 0, name//': message says "'//phrase//'"')
   end subroutine expect_noline

   subroutine expect_file(p, text)
      character(len=*), intent(in) :: p, text
      type(model_t) :: mm
      type(error_t), allocatable :: e
      call read_deck(p, mm, e)
      call t%check(allocated(e), p//': error returned')
      if (.not. allocated(e)) return
      call t%check(index(e%message, text) > 0, p//': message "'//text//'"')
      if (index(e%message, text) == 0) print '(a)', e%message
   end subroutine expect_file

   function itoa(i) result(s)
      integer, intent(in) :: i
      character(len=12) :: s
      write (s, '(i0)') i
   end function itoa

   !> Write `lines` (a line may contain new lines) to the temporary folder; return the path.
   function write_deck(name, lines) result(p)
      character(len=*), intent(in) :: name
      character(len=w), intent(in) :: lines(:)
      character(len=:), allocatable :: p
      character(len=256) :: dir
      integer :: u, j, n
      call get_environment_variable('TMPDIR', dir, n)
      if (n == 0) dir = '/tmp'
      p = trim(dir)//'/vemcontact_test_deck_errors_'//name//'.inp'
      open (newunit=u, file=p, status='replace', action='write')
      do j = 1, size(lines)
         write (u, '(a)') trim(lines(j))
      end do
      close (u)
   end function write_deck
end program test_deck_errors
