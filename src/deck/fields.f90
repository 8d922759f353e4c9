!> Splitting deck lines into fields, keyword lines into name and parameters, and
!> small text helpers (upper case, blank removal, edit distance for suggestions).
module vemcontact_deck_fields
   use vemcontact_model, only: string_t
   !> int_str: an integer as text without blanks (the deck's name for int_text)
   use vemcontact_text, only: int_str => int_text
   implicit none
   private

   public :: field_list_t, keyword_line_t
   public :: split_fields, parse_keyword_line, get_param, has_param, to_upper, squeeze, edit_distance, int_str

   !> Fields of a data line: field k is line(first(k):last(k)), blanks trimmed
   !> (empty when last(k) < first(k)).  A trailing empty field after a final comma is dropped.
   type :: field_list_t
      integer :: n = 0
      integer, allocatable :: first(:)
      integer, allocatable :: last(:)
   end type field_list_t

   !> A keyword line: name upper case without blanks ("SOLIDSECTION"), parameters.
   type :: keyword_line_t
      character(len=:), allocatable :: name
      character(len=:), allocatable :: display  !< upper case as written, for messages
      integer :: nparam = 0
      type(string_t), allocatable :: pname(:)   !< upper case, no blanks
      type(string_t), allocatable :: pvalue(:)  !< as written (trimmed, quotes removed)
      logical, allocatable :: has_value(:)      !< "NAME=..." rather than a bare flag
   end type keyword_line_t

contains

   !> Split a data line at commas into `fields`; arrays grow but are never shrunk.
   subroutine split_fields(line, fields)
      character(len=*), intent(in) :: line
      type(field_list_t), intent(inout) :: fields
      integer :: i, n, a, b, nf
      character(len=1), parameter :: tab = achar(9)
      if (.not. allocated(fields%first)) allocate (fields%first(32), fields%last(32))
      n = len(line)
      nf = 0
      i = 1
      do
         a = i
         do while (i <= n)
            if (line(i:i) == ',') exit
            i = i + 1
         end do
         b = i - 1
         do while (a <= b)
            if (line(a:a) /= ' ' .and. line(a:a) /= tab) exit
            a = a + 1
         end do
         do while (b >= a)
            if (line(b:b) /= ' ' .and. line(b:b) /= tab) exit
            b = b - 1
         end do
         if (nf == size(fields%first)) call grow(fields)
         nf = nf + 1
         fields%first(nf) = a
         fields%last(nf) = b
         if (i > n) exit
         i = i + 1
      end do
      if (nf > 1) then
         if (fields%last(nf) < fields%first(nf)) nf = nf - 1
      end if
      fields%n = nf
   end subroutine split_fields

   subroutine grow(fields)
      type(field_list_t), intent(inout) :: fields
      integer, allocatable :: t(:)
      integer :: n
      n = size(fields%first)
      allocate (t(2*n))
      t(1:n) = fields%first
      call move_alloc(t, fields%first)
      allocate (t(2*n))
      t(1:n) = fields%last
      call move_alloc(t, fields%last)
   end subroutine grow

   !> Parse "*NAME, P1=V1, FLAG, ..." (commas inside double quotes do not split).
   subroutine parse_keyword_line(line, kw)
      character(len=*), intent(in) :: line
      type(keyword_line_t), intent(out) :: kw
      integer :: i, a, n, ipart, eq
      logical :: quoted
      character(len=:), allocatable :: part, val
      n = len(line)
      allocate (kw%pname(8), kw%pvalue(8), kw%has_value(8))
      ipart = 0
      i = 2
      do
         a = i
         quoted = .false.
         do while (i <= n)
            if (line(i:i) == '"') quoted = .not. quoted
            if (line(i:i) == ',' .and. .not. quoted) exit
            i = i + 1
         end do
         part = line(a:i - 1)
         ipart = ipart + 1
         if (ipart == 1) then
            kw%name = to_upper(squeeze(part))
            kw%display = to_upper(trim(adjustl(part)))
         else if (len_trim(part) > 0) then
            if (kw%nparam == size(kw%pname)) call grow_params(kw)
            kw%nparam = kw%nparam + 1
            eq = index(part, '=')
            if (eq > 0) then
               kw%pname(kw%nparam)%s = to_upper(squeeze(part(1:eq - 1)))
               val = trim(adjustl(part(eq + 1:)))
               if (len(val) >= 2) then
                  if (val(1:1) == '"' .and. val(len(val):len(val)) == '"') val = val(2:len(val) - 1)
               end if
               kw%pvalue(kw%nparam)%s = val
               kw%has_value(kw%nparam) = .true.
            else
               kw%pname(kw%nparam)%s = to_upper(squeeze(part))
               kw%pvalue(kw%nparam)%s = ''
               kw%has_value(kw%nparam) = .false.
            end if
         end if
         if (i > n) exit
         i = i + 1
      end do
   end subroutine parse_keyword_line

   subroutine grow_params(kw)
      type(keyword_line_t), intent(inout) :: kw
      type(string_t), allocatable :: t1(:), t2(:)
      logical, allocatable :: t3(:)
      integer :: n
      n = size(kw%pname)
      allocate (t1(2*n), t2(2*n), t3(2*n))
      t1(1:n) = kw%pname
      t2(1:n) = kw%pvalue
      t3(1:n) = kw%has_value
      call move_alloc(t1, kw%pname)
      call move_alloc(t2, kw%pvalue)
      call move_alloc(t3, kw%has_value)
   end subroutine grow_params

   !> Value of parameter `name` of a keyword line ('' for a bare flag); `found` false if absent.
   subroutine get_param(kw, name, value, found)
      type(keyword_line_t), intent(in) :: kw
      character(len=*), intent(in) :: name
      character(len=:), allocatable, intent(out) :: value
      logical, intent(out) :: found
      integer :: k
      found = .false.
      value = ''
      do k = 1, kw%nparam
         if (kw%pname(k)%s == name) then
            value = kw%pvalue(k)%s
            found = .true.
            return
         end if
      end do
   end subroutine get_param

   !> Whether the keyword line has parameter `name`.
   pure function has_param(kw, name) result(found)
      type(keyword_line_t), intent(in) :: kw
      character(len=*), intent(in) :: name
      logical :: found
      integer :: k
      found = .false.
      do k = 1, kw%nparam
         if (kw%pname(k)%s == name) found = .true.
      end do
   end function has_param

   !> ASCII upper case.
   pure function to_upper(s) result(u)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: u
      integer :: i, k
      u = s
      do i = 1, len(s)
         k = ichar(s(i:i))
         if (k >= ichar('a') .and. k <= ichar('z')) u(i:i) = achar(k - 32)
      end do
   end function to_upper

   !> `s` without blanks and tabs (CalculiX ignores blanks in keyword lines and names).
   pure function squeeze(s) result(r)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: r
      character(len=len(s)) :: t
      integer :: i, j
      j = 0
      do i = 1, len(s)
         if (s(i:i) == ' ' .or. s(i:i) == achar(9)) cycle
         j = j + 1
         t(j:j) = s(i:i)
      end do
      r = t(1:j)
   end function squeeze

   !> Levenshtein distance, for "did you mean" suggestions.
   pure function edit_distance(a, b) result(d)
      character(len=*), intent(in) :: a, b
      integer :: d
      integer :: prev(0:len(b)), cur(0:len(b))
      integer :: i, j, cost
      do j = 0, len(b)
         prev(j) = j
      end do
      do i = 1, len(a)
         cur(0) = i
         do j = 1, len(b)
            cost = 1
            if (a(i:i) == b(j:j)) cost = 0
            cur(j) = min(prev(j) + 1, cur(j - 1) + 1, prev(j - 1) + cost)
         end do
         prev = cur
      end do
      d = prev(len(b))
   end function edit_distance
end module vemcontact_deck_fields
