!> Output requests (*NODE FILE, *EL FILE, *CONTACT FILE, *NODE PRINT, *EL PRINT, Abaqus'
!> *OUTPUT, *ELEMENT OUTPUT, *CONTACT OUTPUT) from tests/data/deck/outputs.inp (run from
!> tests/unit): the fields recorded per step, CalculiX's carry-over to later steps, and
!> one warning line (file:line) per variable vemcontact does not compute.
program test_deck_outputs
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, output_requested, find_set, output_node, output_element, output_contact, &
                               totals_yes
   use vemcontact_deck_reader, only: read_deck
   implicit none
   type(checker_t) :: t
   type(model_t) :: m
   type(error_t), allocatable :: err
   character(len=*), parameter :: deck = '../data/deck/outputs.inp'

   call read_deck(deck, m, err)
   call t%check(.not. allocated(err), 'a deck with output requests reads without error')
   if (allocated(err)) then
      print '(a)', err%message
      call t%finish()
   end if
   call t%check(m%heading == 'Output requests as CalculiX and Abaqus decks write them', '*HEADING text')
   call t%check(m%has_output_requests, 'the deck has file output requests')
   call t%equal(size(m%steps), 3, 'three steps')
   ! step 1: two *NODE FILE (U, RF), *EL FILE (S, E), *CONTACT FILE (CDIS = COPEN, CSLIP; CSTR = CPRESS)
   call t%check(output_requested(m, 1, 'U') .and. output_requested(m, 1, 'RF'), 'step 1: U and RF')
   call t%check(output_requested(m, 1, 'S') .and. output_requested(m, 1, 'E'), 'step 1: S and E')
   call t%check(output_requested(m, 1, 'COPEN') .and. output_requested(m, 1, 'CSLIP') .and. &
                output_requested(m, 1, 'CPRESS'), 'step 1: CDIS and CSTR as COPEN, CSLIP, CPRESS')
   call t%check(.not. output_requested(m, 1, 'NT'), 'step 1: NT (temperatures) is not selected')
   call t%equal(size(m%steps(1)%outputs), 6, 'step 1: six requests')
   if (size(m%steps(1)%outputs) == 6) then
      associate (r => m%steps(1)%outputs(5))
         call t%check(r%print .and. r%category == output_node .and. r%set == 'LEFT' .and. &
                      r%totals == totals_yes, '*NODE PRINT, NSET=LEFT, TOTALS=YES recorded')
         call t%check(size(r%fields) == 1, 'the print request selects one field')
         if (size(r%fields) == 1) call t%check(r%fields(1)%s == 'RF', '... RF')
      end associate
      call t%check(m%steps(1)%outputs(6)%category == output_element .and. m%steps(1)%outputs(6)%print, &
                   '*EL PRINT recorded')
   end if
   ! step 2: its *NODE FILE replaces the node selection; element, contact and print carry over
   call t%check(output_requested(m, 2, 'U') .and. .not. output_requested(m, 2, 'RF'), &
                'step 2: the new *NODE FILE replaces U, RF by U')
   call t%check(.not. any_field(2, output_node, 'S'), 'step 2: S under *NODE FILE is not a nodal field')
   call t%check(output_requested(m, 2, 'S') .and. output_requested(m, 2, 'E'), 'step 2: *EL FILE carried over')
   call t%check(output_requested(m, 2, 'CPRESS'), 'step 2: *CONTACT FILE carried over')
   call t%equal(count(m%steps(2)%outputs%print), 2, 'step 2: both print requests carried over')
   ! step 3 (Abaqus): *ELEMENT OUTPUT replaces the element selection, *CONTACT OUTPUT the contact one
   call t%check(output_requested(m, 3, 'S') .and. .not. output_requested(m, 3, 'E'), 'step 3: MISES selects S')
   call t%check(output_requested(m, 3, 'CPRESS') .and. output_requested(m, 3, 'COPEN') .and. &
                .not. output_requested(m, 3, 'CSLIP'), 'step 3: CPRESS and COPEN')
   call t%check(output_requested(m, 3, 'U'), 'step 3: the node selection of step 2 carries over')
   call t%check(any_field(3, output_contact, 'COPEN'), 'step 3: contact request recorded')
   ! warnings: NT, ENER, CELS and S under *NODE FILE, one line each with file:line
   call t%equal(size(m%warnings), 4, 'four warnings')
   call t%check(has_warning(':23: warning: output variable NT of *NODE FILE'), 'NT named at its line')
   call t%check(has_warning(':27: warning: output variable ENER of *EL FILE'), 'ENER named at its line')
   call t%check(has_warning(':29: warning: output variable CELS of *CONTACT FILE'), 'CELS named at its line')
   call t%check(has_warning(':38: warning: S under *NODE FILE is ignored'), 'S under *NODE FILE named')
   call calculix_forms()
   call t%finish()

contains

   !> Forms CalculiX users write: GENERATE with an increment and over several lines,
   !> UNSORTED, *STEP AMPLITUDE/INC/INCF, *STATIC DIRECT with a time line, *ELASTIC with
   !> a temperature field.
   subroutine calculix_forms()
      type(model_t) :: f
      type(error_t), allocatable :: e
      integer :: k
      call read_deck('../data/deck/calculix_forms.inp', f, e)
      call t%check(.not. allocated(e), 'calculix_forms.inp reads without error')
      if (allocated(e)) then
         print '(a)', e%message
         return
      end if
      k = find_set(f%nsets, 'LEFT')
      call t%check(k > 0, 'GENERATE set LEFT')
      if (k > 0) call t%check(all(f%node_id(f%nsets(k)%items) == [1, 4]), 'GENERATE 1, 4, 3 gives nodes 1 and 4')
      k = find_set(f%nsets, 'RIGHT')
      if (k > 0) call t%check(all(f%node_id(f%nsets(k)%items) == [3, 6]), 'UNSORTED set RIGHT: nodes 3 and 6')
      k = find_set(f%elsets, 'E1')
      if (k > 0) call t%equal(size(f%elsets(k)%items), 2, 'two GENERATE lines add up')
      call t%check(size(f%warnings) == 0, 'no warnings')
      call t%check(f%has_output_requests .and. output_requested(f, 1, 'U') .and. output_requested(f, 1, 'S') &
                   .and. .not. output_requested(f, 1, 'RF'), 'U and S requested, RF not')
   end subroutine calculix_forms

   logical function has_warning(text)
      character(len=*), intent(in) :: text
      integer :: k
      has_warning = .false.
      do k = 1, size(m%warnings)
         if (index(m%warnings(k)%s, deck//text) == 1) has_warning = .true.
      end do
      if (.not. has_warning) then
         do k = 1, size(m%warnings)
            print '(a)', m%warnings(k)%s
         end do
      end if
   end function has_warning

   logical function any_field(istep, category, name)
      integer, intent(in) :: istep, category
      character(len=*), intent(in) :: name
      integer :: k, j
      any_field = .false.
      do k = 1, size(m%steps(istep)%outputs)
         if (m%steps(istep)%outputs(k)%category /= category) cycle
         do j = 1, size(m%steps(istep)%outputs(k)%fields)
            if (m%steps(istep)%outputs(k)%fields(j)%s == name) any_field = .true.
         end do
      end do
   end function any_field
end program test_deck_outputs
