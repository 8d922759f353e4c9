!> One check per error message of the contact and staging keywords (*SURFACE,
!> *SURFACE INTERACTION, *SURFACE BEHAVIOR, *CONTACT PAIR, *CONTACT CONTROLS,
!> *DLOAD HP<k>, *GEOSTATIC): read_deck must return an error naming the file, the
!> right line and a key phrase.  Each case is a valid base deck (with a contact block
!> after the elements) with one line changed or inserted, written to the temporary folder.
program test_deck_contact_errors
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: model_t, pair_surface_to_surface
   use vemcontact_deck_reader, only: read_deck
   implicit none
   type(checker_t) :: t
   integer, parameter :: w = 60
   character(len=1), parameter :: nl = achar(10)
   character(len=w), parameter :: base(18) = [character(len=w) :: &
                                  '*NODE', '1, 0., 0.', '2, 1., 0.', '3, 1., 1.', '4, 0., 1.', &
                                  '*ELEMENT, TYPE=CPE4, ELSET=E', '1, 1, 2, 3, 4', &
                                  '*MATERIAL, NAME=M', '*ELASTIC', '1000., 0.3', &
                                  '*SOLID SECTION, ELSET=E, MATERIAL=M', '*BOUNDARY', '1, 1, 2', &
                                  '*STEP', '*STATIC', '*CLOAD', '3, 1, 1.', '*END STEP']
   !> inserted after base line 7: block line i is deck line 7 + i
   character(len=w), parameter :: block(9) = [character(len=w) :: &
                                   '*SURFACE, NAME=A', '1, S1', '*SURFACE, NAME=B, TYPE=NODE', '3', &
                                   '*SURFACE INTERACTION, NAME=I', &
                                   '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR', '1000.', &
                                   '*CONTACT PAIR, INTERACTION=I, TYPE=NODE TO SURFACE', 'B, A']
   character(len=w), allocatable :: b(:)
   type(model_t) :: m
   type(error_t), allocatable :: err

   call read_deck(write_deck('base', with_block(block)), m, err)
   call t%check(.not. allocated(err), 'the base deck with contact is valid')
   if (allocated(err)) print '(a)', err%message
   call read_deck(write_deck('blank_sigma', with_block(cb(7, '1000., 0., '))), m, err)
   call t%check(.not. allocated(err), 'sigma_inf 0 and blank c0 are accepted')
   call read_deck(write_deck('geostatic', rep(15, '*GEOSTATIC')), m, err)
   call t%check(.not. allocated(err), '*GEOSTATIC alone is a procedure')
   call read_deck(write_deck('sliding', with_block(cb(8, '*CONTACT PAIR,INTERACTION=I,TYPE=NODETOSURFACE,SMALLSLIDING'))), &
                  m, err)
   call t%check(.not. allocated(err), 'SMALL SLIDING (blanks removed) is accepted')
   call read_deck(write_deck('s2s_hard', with_block([character(len=w) :: block(1:5), &
                                                     '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD', &
                                                     '*CONTACT PAIR, INTERACTION=I, TYPE=SURFACE TO SURFACE', &
                                                     'B, A', '*CONTACT CONTROLS, STIFFNESS SCALE FACTOR=10'])), m, err)
   call t%check(.not. allocated(err), 'TYPE=SURFACE TO SURFACE with HARD and a stiffness scale is accepted')
   if (allocated(err)) print '(a)', err%message
   if (.not. allocated(err)) then
      call t%check(m%interactions(1)%hard .and. m%pairs(1)%formulation == pair_surface_to_surface .and. &
                   abs(m%controls%stiffness_scale - 10.0_wp) <= 0.0_wp, 'HARD, SURFACE TO SURFACE and the scale are read')
   end if

   ! *SURFACE
   call expect('surf_undef_elem', with_block(cb(2, '5, S1')), 9, 'undefined element 5')
   call expect('surf_undef_elset', with_block(cb(2, 'EX, S1')), 9, 'undefined element set EX')
   call expect('surf_undef_node', with_block(cb(4, '7')), 11, 'undefined node 7')
   call expect('surf_undef_nset', with_block(cb(4, 'NX')), 11, 'undefined node set NX')
   call expect('surf_s0', with_block(cb(2, '1, S0')), 9, 'invalid side label S0')
   call expect('surf_s9', with_block(cb(2, '1, S9')), 9, 'element 1 has 4 sides, so there is no side S9')
   call expect('surf_x3', with_block(cb(2, '1, X3')), 9, 'invalid side label X3')
   call expect('surf_no_label', with_block(cb(2, '1')), 9, 'missing side label on a *SURFACE data line')
   call expect('surf_fields', with_block(cb(2, '1, S1, 2')), 9, 'too many fields on a TYPE=ELEMENT *SURFACE')
   call expect('surf_node_area', with_block(cb(4, '3, 1.0')), 11, &
               'a TYPE=NODE *SURFACE data line holds one node or node set')
   call expect('surf_empty', with_block(cb(2, '** none')), 8, 'surface A is empty')
   call expect('surf_type', with_block(cb(3, '*SURFACE, NAME=B, TYPE=NODES')), 10, &
               'invalid value NODES for parameter TYPE of *SURFACE')
   call expect('surf_no_name', with_block(cb(1, '*SURFACE, TYPE=ELEMENT')), 8, &
               'missing required parameter NAME of *SURFACE')
   call expect('surf_twice', with_block(cbi(2, '*SURFACE, NAME=a'//nl//'1, S2')), 10, &
               'surface A already defined at ')
   call expect('surf_after_step', [character(len=w) :: base, '*SURFACE, NAME=Z', '1, S1'], 19, &
               '*SURFACE must come before the first *STEP')
   call expect('surf_in_step', ins(15, '*SURFACE, NAME=Z'//nl//'1, S1'), 16, &
               '*SURFACE is not allowed inside a *STEP')
   ! *SURFACE INTERACTION and *SURFACE BEHAVIOR
   call expect('beh_alone', with_block(cbi(4, '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR'//nl//'5.')), 12, &
               '*SURFACE BEHAVIOR must follow a *SURFACE INTERACTION')
   call expect('beh_exp', with_block(cb(6, '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=EXPONENTIAL')), 13, &
               'PRESSURE-OVERCLOSURE=EXPONENTIAL is not supported')
   call expect('beh_hard', with_block(cb(6, '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD')), 14, &
               'PRESSURE-OVERCLOSURE=HARD takes no data line')
   call expect('beh_tabular', with_block(cb(6, '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR')), 13, &
               'vemcontact supports PRESSURE-OVERCLOSURE=LINEAR (penalty: p = K * overclosure) and HARD')
   call expect('scale_bad', with_block(cbi(9, '*CONTACT CONTROLS, STIFFNESS SCALE FACTOR=1e9')), 17, &
               'STIFFNESS SCALE FACTOR = 1e9 must lie between 1e-3 and 1e4')
   call expect('beh_bad', with_block(cb(6, '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LIN')), 13, &
               'invalid value LIN for parameter PRESSURE-OVERCLOSURE')
   call expect('beh_no_po', with_block(cb(6, '*SURFACE BEHAVIOR')), 13, &
               'missing required parameter PRESSURE-OVERCLOSURE of *SURFACE BEHAVIOR')
   call read_deck(write_deck('beh_sigma_c0', with_block(cb(7, '1000., 0.5, 1e-3'))), m, err)
   call t%check(.not. allocated(err), 'CalculiX''s sigma_inf and c0 are accepted')
   if (.not. allocated(err)) then
      call t%close(m%interactions(1)%sigma_inf, 0.5_wp, 1.0e-15_wp, 'sigma_inf recorded')
      call t%close(m%interactions(1)%c0, 1.0e-3_wp, 1.0e-15_wp, 'c0 recorded')
      call t%equal(size(m%warnings), 1, 'one warning: the tension sigma_inf is not modelled')
      if (size(m%warnings) == 1) call t%check(index(m%warnings(1)%s, ':14: warning: sigma_inf = 0.5') > 0, &
                                              'the warning names file:line and sigma_inf')
   end if
   call expect('beh_sigma', with_block(cb(7, '1000., -0.5')), 14, 'sigma_inf = -0.5 must not be negative')
   call expect('beh_c0', with_block(cb(7, '1000., , -1e-3')), 14, 'c0 = -1e-3 must not be negative')
   call expect('beh_k_zero', with_block(cb(7, '0.')), 14, 'penalty slope K = 0. must be positive')
   call expect('beh_k_missing', with_block(cb(7, ', 0.')), 14, 'missing penalty slope K')
   call expect('beh_fields', with_block(cb(7, '1., 0., 0., 4.')), 14, &
               'too many fields on the *SURFACE BEHAVIOR data line')
   call expect('beh_no_data', with_block(cb(7, '** none')), 15, &
               '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR needs a data line')
   call expect('beh_two_lines', with_block(cbi(7, '2000.')), 15, 'takes one data line')
   call expect('beh_twice', with_block(cbi(7, '*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR'//nl//'5.')), 15, &
               'surface interaction I already has *SURFACE BEHAVIOR')
   b = block
   b(6) = '** no behavior'
   b(7) = '**'
   call expect('beh_missing', with_block(b), 12, 'surface interaction I has no *SURFACE BEHAVIOR')
   ! *FRICTION (after the behavior: deck lines 15 and 16)
   call read_deck(write_deck('fric_ok', with_block(cbi(7, '*FRICTION, COHESION=2.5'//nl//'0.6, 1e4'))), m, err)
   call t%check(.not. allocated(err), '*FRICTION with mu, stick slope and COHESION is accepted')
   if (.not. allocated(err)) then
      call t%check(m%interactions(1)%has_friction .and. abs(m%interactions(1)%mu - 0.6_wp) <= 0.0_wp .and. &
                   abs(m%interactions(1)%stick_slope - 1.0e4_wp) <= 0.0_wp .and. &
                   abs(m%interactions(1)%cohesion - 2.5_wp) <= 0.0_wp, 'mu, stick slope and cohesion are read')
   end if
   call read_deck(write_deck('fric_before', with_block(cbi(5, '*FRICTION'//nl//'0.'))), m, err)
   call t%check(.not. allocated(err), '*FRICTION before *SURFACE BEHAVIOR, mu = 0: accepted')
   call read_deck(write_deck('fric_rough', with_block(cbi(7, '*FRICTION, ROUGH'))), m, err)
   call t%check(.not. allocated(err), '*FRICTION, ROUGH is accepted')
   if (.not. allocated(err)) call t%check(m%interactions(1)%rough, 'ROUGH is read')
   call expect('fric_mu_neg', with_block(cbi(7, '*FRICTION'//nl//'-0.1')), 16, &
               'friction coefficient mu = -0.1 must not be negative')
   call expect('fric_slope_neg', with_block(cbi(7, '*FRICTION'//nl//'0.3, -5.')), 16, &
               'stick slope = -5. must not be negative')
   call expect('fric_c_neg', with_block(cbi(7, '*FRICTION, COHESION=-1'//nl//'0.3')), 15, &
               'cohesion COHESION=-1 must not be negative')
   call expect('fric_c_rough', with_block(cbi(7, '*FRICTION, ROUGH, COHESION=1')), 15, &
               'COHESION is meaningless with ROUGH')
   call expect('fric_alone', with_block(cbi(4, '*FRICTION'//nl//'0.3')), 12, &
               '*FRICTION must follow a *SURFACE INTERACTION')
   call expect('fric_no_data', with_block(cbi(7, '*FRICTION')), 16, '*FRICTION needs a data line')
   call expect('fric_fields', with_block(cbi(7, '*FRICTION'//nl//'0.3, 1., 2.')), 16, &
               'too many fields on the *FRICTION data line')
   call expect('fric_rough_data', with_block(cbi(7, '*FRICTION, ROUGH'//nl//'0.3')), 16, &
               '*FRICTION, ROUGH takes no data line')
   call expect('fric_twice', with_block(cbi(7, '*FRICTION'//nl//'0.3'//nl//'*FRICTION'//nl//'0.2')), 17, &
               'surface interaction I already has *FRICTION')
   call expect('fric_in_step', ins(15, '*FRICTION'//nl//'0.3'), 16, '*FRICTION inside a *STEP must follow *CHANGE FRICTION')
   call expect('inter_twice', with_block(cbi(7, '*SURFACE INTERACTION, NAME=I')), 15, &
               'surface interaction I already defined at ')
   call expect('inter_data', with_block(cbi(5, '1.')), 13, &
               'unexpected data line: *SURFACE INTERACTION takes no data lines')
   ! *CONTACT PAIR
   call expect('pair_n2n', with_block(cb(8, '*CONTACT PAIR, INTERACTION=I, TYPE=NODE TO NODE')), 15, &
               'TYPE=NODETONODE is not supported')
   call expect('pair_no_type', with_block(cb(8, '*CONTACT PAIR, INTERACTION=I')), 15, &
               'missing required parameter TYPE of *CONTACT PAIR')
   call expect('pair_adjust', with_block(cb(8, '*CONTACT PAIR,INTERACTION=I,TYPE=NODETOSURFACE,ADJUST=0.1')), 15, &
               'ADJUST is not supported')
   call expect('pair_undef_slave', with_block(cb(9, 'BB, A')), 16, 'undefined slave surface BB')
   call expect('pair_suggest', with_block(cb(9, 'BB, A')), 16, 'did you mean B?')
   call expect('pair_undef_master', with_block(cb(9, 'B, AX')), 16, 'undefined master surface AX')
   call expect('pair_undef_inter', with_block(cb(8, '*CONTACT PAIR, INTERACTION=II, TYPE=NODE TO SURFACE')), 16, &
               'undefined surface interaction II')
   call expect('pair_inter_suggest', with_block(cb(8, '*CONTACT PAIR, INTERACTION=II, TYPE=NODE TO SURFACE')), 16, &
               'did you mean I?')
   call expect('pair_node_master', with_block(cb(9, 'A, B')), 16, 'master surface B is a TYPE=NODE surface')
   call expect('pair_same', with_block(cb(9, 'A, A')), 16, 'slave and master are the same surface A')
   call expect('pair_fields', with_block(cb(9, 'B')), 16, 'a *CONTACT PAIR data line needs two surface names')
   call expect('pair_no_data', with_block(cb(9, '** none')), 15, '*CONTACT PAIR needs a data line')
   call expect('pair_in_step', ins(15, '*CONTACT PAIR, INTERACTION=I, TYPE=NODE TO SURFACE'//nl//'B, A'), 16, &
               '*CONTACT PAIR is not allowed inside a *STEP')
   ! *CONTACT CONTROLS
   call expect('ctl_maxit', ins(13, '*CONTACT CONTROLS, MAXIT=0'), 14, &
               'parameter MAXIT of *CONTACT CONTROLS must be a positive integer')
   call expect('ctl_tol_range', ins(13, '*CONTACT CONTROLS, TOLERANCE=1.5'), 14, &
               'TOLERANCE = 1.5 must satisfy 0 < TOLERANCE < 1')
   call expect('ctl_tol_text', ins(13, '*CONTACT CONTROLS, TOLERANCE=abc'), 14, &
               'parameter TOLERANCE of *CONTACT CONTROLS must be a number, found ''abc''')
   call expect('ctl_twice', ins(13, '*CONTACT CONTROLS, MAXIT=3'//nl//'*CONTACT CONTROLS'), 15, &
               'second *CONTACT CONTROLS (the first is at ')
   call expect('ctl_data', ins(13, '*CONTACT CONTROLS, MAXIT=3'//nl//'3'), 15, &
               'unexpected data line: *CONTACT CONTROLS takes no data lines')
   call expect('ctl_abaqus', ins(13, '*CONTACT CONTROLS, STABILIZE'), 14, &
               'unknown parameter STABILIZE of *CONTACT CONTROLS')
   call expect('ctl_in_step', ins(15, '*CONTACT CONTROLS, MAXIT=3'), 16, &
               '*CONTACT CONTROLS is not allowed inside a *STEP')
   ! *DLOAD HP<k>
   call expect('hp_equal', ins(17, '*DLOAD'//nl//'1, HP1, 10., 5., 5.'), 19, &
               'the free-surface height y_zero and the reference height y_ref are equal')
   call expect('hp_above', ins(17, '*DLOAD'//nl//'E, HP1, 10., 0., 5.'), 19, &
               'the reference height y_ref = 5. lies above the free-surface height y_zero = 0.')
   call expect('hp_no_yref', ins(17, '*DLOAD'//nl//'1, HP1, 10., 5.'), 19, 'missing reference height y_ref')
   call expect('hp_no_yzero', ins(17, '*DLOAD'//nl//'1, HP1, 10.'), 19, 'missing free-surface height y_zero')
   call expect('hp_no_mag', ins(17, '*DLOAD'//nl//'1, HP1'), 19, 'missing hydrostatic pressure magnitude')
   call expect('hp_side', ins(17, '*DLOAD'//nl//'1, HP5, 10., 1., 0.'), 19, &
               'element 1 has 4 sides, so there is no side HP5')
   call expect('hp_label', ins(17, '*DLOAD'//nl//'1, HPX, 10., 1., 0.'), 19, 'unsupported *DLOAD label HPX')
   call expect('hp_fields', ins(17, '*DLOAD'//nl//'1, HP1, 1., 1., 0., 3.'), 19, &
               'too many fields on a hydrostatic pressure data line')
   ! *GEOSTATIC
   call expect('geo_second_step', [character(len=w) :: base, '*STEP', '*GEOSTATIC', '*END STEP'], 20, &
               'a geostatic step must be the first step')
   call expect('geo_and_static', ins(15, '*GEOSTATIC'), 16, '*GEOSTATIC in the step started at ')
   call expect('geo_and_static_which', ins(15, '*GEOSTATIC'), 16, 'which already has *STATIC')
   call expect('geo_twice', rep(15, '*GEOSTATIC'//nl//'*GEOSTATIC'), 16, 'second *GEOSTATIC in the step')
   call expect('geo_outside', ins(13, '*GEOSTATIC'), 14, '*GEOSTATIC is only allowed inside a *STEP')
   call expect('geo_data', rep(15, '*GEOSTATIC'//nl//'1., x'), 16, 'time period of the step must be a number')
   call expect('geo_param', rep(15, '*GEOSTATIC, UTOL=1.'), 15, 'unknown parameter UTOL of *GEOSTATIC')
   call expect('no_procedure', rep(15, '**'), 14, 'the step has no procedure')
   call t%finish()

contains

   !> The contact block with line i replaced by `s`.
   function cb(i, s) result(lines)
      integer, intent(in) :: i
      character(len=*), intent(in) :: s
      character(len=w), allocatable :: lines(:)
      lines = [character(len=w) :: block(1:i - 1), s, block(i + 1:)]
   end function cb

   !> The contact block with `s` inserted after line i.
   function cbi(i, s) result(lines)
      integer, intent(in) :: i
      character(len=*), intent(in) :: s
      character(len=w), allocatable :: lines(:)
      lines = [character(len=w) :: block(1:i), s, block(i + 1:)]
   end function cbi

   !> The base deck with the contact lines `blk` after the elements (line 7).
   function with_block(blk) result(lines)
      character(len=w), intent(in) :: blk(:)
      character(len=w), allocatable :: lines(:)
      lines = [character(len=w) :: base(1:7), blk, base(8:)]
   end function with_block


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
      p = trim(dir)//'/vemcontact_test_deck_contact_errors_'//name//'.inp'
      open (newunit=u, file=p, status='replace', action='write')
      do j = 1, size(lines)
         write (u, '(a)') trim(lines(j))
      end do
      close (u)
   end function write_deck
end program test_deck_contact_errors
