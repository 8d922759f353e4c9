!> Line-level parsing shared by all keyword handlers: advancing to the next line
!> (with *INCLUDE handled transparently, so an included file may also hold only
!> data lines, as in CalculiX), validating a keyword line against the registry,
!> and skipping data lines.
module vemcontact_deck_lines
   use vemcontact_kinds, only: ip, wp
   use vemcontact_deck_state, only: deck_parser_t, err_here
   use vemcontact_deck_source, only: line_keyword, line_data, push_ok, directory_of
   use vemcontact_deck_fields, only: keyword_line_t, parse_keyword_line, to_upper, squeeze
   use vemcontact_deck_registry, only: keywords, param_spec_t, find_param, param_suggestion, &
                                       allowed_value, kw_include, par_flag, par_value, &
                                       val_name, val_int, val_real, params
   use vemcontact_deck_numbers, only: parse_int, parse_real, num_ok, number_problem
   implicit none
   private

   public :: advance, check_keyword, skip_data, no_data

contains

   !> Move to the next line.  *INCLUDE lines are processed here: the included file
   !> is pushed and reading continues with its first line.
   subroutine advance(p)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t) :: kw
      character(len=:), allocatable :: path, msg, input
      integer :: stat, k
      logical :: ok
      do
         call p%src%next()
         if (p%src%kind /= line_keyword) return
         call parse_keyword_line(p%src%text(1:p%src%length), kw)
         if (kw%name /= 'INCLUDE') return
         p%nkeyword = p%nkeyword + 1
         call check_keyword(p, kw, kw_include, ok)
         if (.not. ok) cycle
         input = ''
         do k = 1, kw%nparam
            if (kw%pname(k)%s == 'INPUT') input = kw%pvalue(k)%s
         end do
         if (input(1:1) == '/') then
            path = input
         else
            path = directory_of(p%src%path())//input
         end if
         call p%src%push_file(path, stat, msg)
         if (stat /= push_ok) then
            call err_here(p, 'cannot include '''//input//''': '//msg)
         end if
      end do
   end subroutine advance

   !> Check the parameters of keyword line `kw` (keyword id `id`) against the registry,
   !> reporting every problem; values are normalised in place (names upper case).
   !> `ok` is false when a required parameter is missing or unusable.
   subroutine check_keyword(p, kw, id, ok)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t), intent(inout) :: kw
      integer, intent(in) :: id
      logical, intent(out) :: ok
      type(param_spec_t) :: spec
      logical :: found, bad
      integer :: k, j, stat
      integer(ip) :: ival
      real(wp) :: rval
      character(len=:), allocatable :: kname, blanked
      kname = '*'//trim(keywords(id)%name)
      blanked = ' '
      ok = .true.
      do k = 1, kw%nparam
         call find_param(id, kw%pname(k)%s, spec, found)
         if (.not. found) then
            call err_here(p, 'unknown parameter '//kw%pname(k)%s//' of '//kname, &
                          param_suggestion(id, kw%pname(k)%s))
            kw%pname(k)%s = ''
            cycle
         end if
         do j = 1, k - 1
            if (kw%pname(j)%s == kw%pname(k)%s) then
               call err_here(p, 'parameter '//kw%pname(k)%s//' of '//kname//' is given twice')
               ok = .false.
            end if
         end do
         bad = .false.
         if (spec%kind == par_flag .and. kw%has_value(k)) then
            call err_here(p, 'parameter '//kw%pname(k)%s//' of '//kname//' takes no value')
            bad = .true.
         else if (spec%kind == par_value .and. len(kw%pvalue(k)%s) == 0) then
            call err_here(p, 'parameter '//kw%pname(k)%s//' of '//kname//' needs a value ('// &
                          kw%pname(k)%s//'=...)')
            bad = .true.
         end if
         if (.not. bad .and. spec%vkind == val_name) then
            kw%pvalue(k)%s = to_upper(squeeze(kw%pvalue(k)%s))
            if (.not. allowed_value(spec, kw%pvalue(k)%s)) then
               call err_here(p, 'invalid value '//kw%pvalue(k)%s//' for parameter '//kw%pname(k)%s// &
                             ' of '//kname, 'allowed values: '//trim(spec%allowed))
               bad = .true.
            end if
         else if (.not. bad .and. spec%vkind == val_int) then
            call parse_int(squeeze(kw%pvalue(k)%s), ival, stat)
            if (stat /= num_ok .or. ival <= 0) then
               call err_here(p, 'parameter '//kw%pname(k)%s//' of '//kname// &
                             ' must be a positive integer, found '''//kw%pvalue(k)%s//'''')
               bad = .true.
            end if
         else if (.not. bad .and. spec%vkind == val_real) then
            call parse_real(squeeze(kw%pvalue(k)%s), rval, stat)
            if (stat /= num_ok) then
               call err_here(p, number_problem(stat, kw%pvalue(k)%s, &
                                               'parameter '//kw%pname(k)%s//' of '//kname))
               bad = .true.
            end if
         end if
         if (bad) then
            if (spec%required) ok = .false.
            blanked = blanked//kw%pname(k)%s//' '
            kw%pname(k)%s = ''
         end if
      end do
      do k = 1, size(params)
         if (params(k)%keyword /= id .or. .not. params(k)%required) cycle
         found = .false.
         do j = 1, kw%nparam
            if (kw%pname(j)%s == squeeze(params(k)%name)) found = .true.
         end do
         if (.not. found) then
            ! a parameter blanked above for a bad value was already reported
            if (index(blanked, ' '//squeeze(params(k)%name)//' ') == 0) then
               call err_here(p, 'missing required parameter '//trim(params(k)%name)//' of '//kname, &
                             'write '//kname//', '//trim(params(k)%name)//'=...')
            end if
            ok = .false.
         end if
      end do
   end subroutine check_keyword

   !> Skip the data lines of the current keyword (after an error on its keyword line).
   subroutine skip_data(p)
      type(deck_parser_t), intent(inout) :: p
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
      end do
   end subroutine skip_data

   !> For keywords without data lines: report the first data line that follows, skip all.
   subroutine no_data(p, kname)
      type(deck_parser_t), intent(inout) :: p
      character(len=*), intent(in) :: kname
      logical :: first
      first = .true.
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         if (first) call err_here(p, 'unexpected data line: '//kname//' takes no data lines')
         first = .false.
      end do
   end subroutine no_data
end module vemcontact_deck_lines
