!> Handlers of the output requests: CalculiX's *NODE FILE, *EL FILE, *CONTACT FILE,
!> *NODE PRINT, *EL PRINT, *CONTACT PRINT, Abaqus' *NODE OUTPUT, *ELEMENT OUTPUT,
!> *CONTACT OUTPUT and *OUTPUT.  Each request becomes an `output_request_t` of the step
!> with vemcontact's names of the fields it selects.  A variable vemcontact does not
!> compute is one warning line (file:line, the variable), never an error, so that decks
!> written for CalculiX run as they are.
module vemcontact_deck_outputs
   use vemcontact_model, only: model_t, step_t, output_request_t, string_t, output_node, output_element, &
                               output_contact, totals_yes, totals_only
   use vemcontact_deck_state, only: deck_parser_t, here, err_here, warn_here, field, get_set, set_suggestion
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: keyword_line_t, split_fields, get_param, has_param, to_upper, squeeze
   use vemcontact_deck_numbers, only: parse_int, num_ok
   use vemcontact_kinds, only: ip
   implicit none
   private

   public :: read_output_request, read_output, carry_outputs

   !> Variables vemcontact writes, by category: the request key (CalculiX's, or Abaqus'
   !> where CalculiX has none) and the fields it selects (blank-separated).
   type :: key_map_t
      character(len=8) :: key
      integer :: category
      character(len=16) :: fields
   end type key_map_t

   type(key_map_t), parameter :: known(14) = [ &
                                 key_map_t('U', output_node, 'U'), &
                                 key_map_t('RF', output_node, 'RF'), &
                                 key_map_t('S', output_element, 'S'), &
                                 key_map_t('E', output_element, 'E'), &
                                 key_map_t('MISES', output_element, 'S'), &
                                 key_map_t('CDIS', output_contact, 'COPEN CSLIP'), &
                                 key_map_t('CSTR', output_contact, 'CPRESS'), &
                                 key_map_t('CDISP', output_contact, 'COPEN CSLIP'), &
                                 key_map_t('CSTRESS', output_contact, 'CPRESS'), &
                                 key_map_t('CPRESS', output_contact, 'CPRESS'), &
                                 key_map_t('COPEN', output_contact, 'COPEN'), &
                                 key_map_t('CSLIP', output_contact, 'CSLIP'), &
                                 ! the shear traction goes with the pressure (CalculiX's CSTR holds both)
                                 key_map_t('CSHEAR', output_contact, 'CPRESS'), &
                                 key_map_t('CSHEAR1', output_contact, 'CPRESS')]

   character(len=*), parameter :: category_name(3) = [character(len=7) :: 'nodal', 'element', 'contact']
   character(len=*), parameter :: category_article(3) = [character(len=2) :: 'a', 'an', 'a']
   character(len=*), parameter :: category_keys(3) = [character(len=36) :: 'U, RF', 'S, E', &
                                                      'CDIS, CSTR (or CPRESS, COPEN, CSLIP)']
   character(len=*), parameter :: category_file(3) = [character(len=16) :: '*NODE FILE', '*EL FILE', &
                                                      '*CONTACT FILE']

contains

   !> One output request keyword in a step: `category` (output_node, output_element,
   !> output_contact) and `print` (a *... PRINT request).  Data lines: the variables.
   subroutine read_output_request(p, model, kw, kname, category, print)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=*), intent(in) :: kname
      integer, intent(in) :: category
      logical, intent(in) :: print
      type(output_request_t) :: r
      character(len=:), allocatable :: val, key
      logical :: found
      integer :: k, ks
      r%category = category
      r%print = print
      r%loc = here(p)
      r%set = ''
      allocate (r%fields(0))
      call check_frequency(p, kw, kname, r%frequency)
      found = .false.
      if (category == output_node) call get_param(kw, 'NSET', val, found)
      if (category == output_element) call get_param(kw, 'ELSET', val, found)
      if (category /= output_contact .and. found) then
         r%set = val
         if (category == output_node) then
            call get_set(model%nsets, p%nset_items, p%nnset, val, here(p), .false., ks)
            if (ks == 0) call err_here(p, 'undefined node set '//val, set_suggestion(model%nsets, p%nnset, val))
         else
            call get_set(model%elsets, p%elset_items, p%nelset, val, here(p), .false., ks)
            if (ks == 0) call err_here(p, 'undefined element set '//val, &
                                       set_suggestion(model%elsets, p%nelset, val))
         end if
      end if
      call get_param(kw, 'TOTALS', val, found)
      if (found) then
         if (val == 'YES') r%totals = totals_yes
         if (val == 'ONLY') r%totals = totals_only
      end if
      call get_param(kw, 'VARIABLE', val, found)
      if (found) then
         ! Abaqus: PRESELECT (its default list) or ALL: every field vemcontact writes
         do k = 1, size(known)
            if (known(k)%category == category) call add_fields(r, known(k)%fields)
         end do
      end if
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         do k = 1, p%f%n
            key = to_upper(squeeze(field(p, k)))
            if (len(key) == 0) cycle
            call select_key(p, r, key, kname)
         end do
      end do
      call push_request(p, model, r)
   end subroutine read_output_request

   !> *OUTPUT [, FIELD | HISTORY] [, FREQUENCY=n] [, VARIABLE=PRESELECT|ALL]: for CalculiX
   !> only the output frequency (irrelevant to a linear step, whose results are written
   !> at its end); with Abaqus' VARIABLE every field vemcontact writes is requested.
   subroutine read_output(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      type(output_request_t) :: r
      integer :: c, k, freq
      call check_frequency(p, kw, '*OUTPUT', freq)
      if (has_param(kw, 'VARIABLE')) then
         do c = output_node, output_contact
            r = output_request_t(category=c, loc=here(p))
            r%set = ''
            allocate (r%fields(0))
            do k = 1, size(known)
               if (known(k)%category == c) call add_fields(r, known(k)%fields)
            end do
            call push_request(p, model, r)
         end do
      end if
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call err_here(p, 'unexpected data line: *OUTPUT takes no data lines', &
                       'the variables go under *NODE OUTPUT, *ELEMENT OUTPUT or *CONTACT OUTPUT')
      end do
   end subroutine read_output

   !> FREQUENCY=n (CalculiX and Abaqus): a non-negative integer, `freq` (0 without it).
   !> A file request's n > 0 writes the results of every n-th increment of the step
   !> besides its end (the driver); the end of a step is always written.
   subroutine check_frequency(p, kw, kname, freq)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t), intent(in) :: kw
      character(len=*), intent(in) :: kname
      integer, intent(out) :: freq
      character(len=:), allocatable :: val
      logical :: found
      integer :: stat
      integer(ip) :: n
      freq = 0
      call get_param(kw, 'FREQUENCY', val, found)
      if (.not. found) return
      call parse_int(val, n, stat)
      if (stat /= num_ok .or. n < 0) then
         call err_here(p, 'FREQUENCY of '//kname//' must be a non-negative integer, found '''//val//'''')
         return
      end if
      freq = int(n)
   end subroutine check_frequency

   !> Add the fields of variable `key` to `r`, or warn that it is not available.
   subroutine select_key(p, r, key, kname)
      type(deck_parser_t), intent(inout) :: p
      type(output_request_t), intent(inout) :: r
      character(len=*), intent(in) :: key, kname
      integer :: k
      do k = 1, size(known)
         if (trim(known(k)%key) /= key) cycle
         if (known(k)%category == r%category) then
            call add_fields(r, known(k)%fields)
         else
            call warn_here(p, key//' under '//kname//' is ignored: it is '// &
                           trim(category_article(known(k)%category))//' '// &
                           trim(category_name(known(k)%category))//' variable (request it with '// &
                           trim(category_file(known(k)%category))//')')
         end if
         return
      end do
      call warn_here(p, 'output variable '//key//' of '//kname//' is not available in vemcontact and '// &
                     'is ignored (its '//trim(category_name(r%category))//' variables are '// &
                     trim(category_keys(r%category))//')')
   end subroutine select_key

   !> Add the blank-separated field names `names` to `r`, without repeats.
   pure subroutine add_fields(r, names)
      type(output_request_t), intent(inout) :: r
      character(len=*), intent(in) :: names
      integer :: a, b, j
      logical :: have
      a = 1
      do while (a <= len_trim(names))
         b = index(names(a:), ' ')
         if (b == 0) then
            b = len_trim(names) + 1
         else
            b = a + b - 1
         end if
         have = .false.
         do j = 1, size(r%fields)
            if (r%fields(j)%s == names(a:b - 1)) have = .true.
         end do
         if (.not. have) r%fields = [r%fields, string_t(names(a:b - 1))]
         a = b + 1
         do while (a <= len(names))
            if (names(a:a) /= ' ') exit
            a = a + 1
         end do
      end do
   end subroutine add_fields

   !> Append `r` to the current step; the first request of its kind in the step replaces
   !> the selection carried over from the step before (see carry_outputs).
   subroutine push_request(p, model, r)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(output_request_t), intent(in) :: r
      type(output_request_t), allocatable :: t(:)
      integer :: kind
      kind = 1
      if (r%print) kind = 2
      if (.not. r%print) model%has_output_requests = .true.
      p%cur%out_seen(r%category, kind) = .true.
      if (.not. allocated(p%cur%outputs)) allocate (p%cur%outputs(4))
      if (p%cur%nout == size(p%cur%outputs)) then
         allocate (t(2*p%cur%nout))
         t(1:p%cur%nout) = p%cur%outputs(1:p%cur%nout)
         call move_alloc(t, p%cur%outputs)
      end if
      p%cur%nout = p%cur%nout + 1
      p%cur%outputs(p%cur%nout) = r
   end subroutine push_request

   !> The requests in force in step `cur`: its own, and for every (category, file/print)
   !> kind without a request in the step (`seen` false), those of the step before
   !> (CalculiX: "if no *NODE FILE card is used within a step the selections of the
   !> previous step apply").
   subroutine carry_outputs(prev, cur, seen)
      type(step_t), intent(in) :: prev
      type(step_t), intent(inout) :: cur
      logical, intent(in) :: seen(3, 2)
      integer :: k, kind
      if (.not. allocated(prev%outputs)) return
      if (.not. allocated(cur%outputs)) allocate (cur%outputs(0))
      do k = 1, size(prev%outputs)
         kind = 1
         if (prev%outputs(k)%print) kind = 2
         if (.not. seen(prev%outputs(k)%category, kind)) cur%outputs = [cur%outputs, prev%outputs(k)]
      end do
   end subroutine carry_outputs
end module vemcontact_deck_outputs
