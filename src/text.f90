!> Text shown to the user: control characters of deck text (terminal escape
!> sequences, stray bytes) are shown escaped so that they neither act on the
!> terminal nor hide in the log; integers as the shortest decimal text.
module vemcontact_text
   use vemcontact_kinds, only: i8
   implicit none
   private

   public :: escape_controls, cap_lines, int_text

   !> An integer (default or 64-bit) as its decimal digits, without blanks.
   interface int_text
      module procedure int_text_default, int_text_i8
   end interface int_text

   !> Longest line of a message shown to the user: deck text quoted in a message
   !> (a parameter value, a name) is cut there, so that no input makes a message
   !> longer than a few lines however long its lines are.
   integer, parameter, public :: max_message_line = 400

contains

   !> `s` with every control character except line feed and tab (bytes 0-31 and
   !> 127) written as \xHH.
   pure function escape_controls(s) result(e)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: e
      character(len=*), parameter :: hex = '0123456789ABCDEF'
      integer :: k, c, n
      n = 0
      do k = 1, len(s)
         if (is_shown_escaped(iachar(s(k:k)))) n = n + 1
      end do
      if (n == 0) then
         e = s
         return
      end if
      allocate (character(len=len(s) + 3*n) :: e)
      n = 0
      do k = 1, len(s)
         c = iachar(s(k:k))
         if (is_shown_escaped(c)) then
            e(n + 1:n + 4) = '\x'//hex(c/16 + 1:c/16 + 1)//hex(mod(c, 16) + 1:mod(c, 16) + 1)
            n = n + 4
         else
            e(n + 1:n + 1) = s(k:k)
            n = n + 1
         end if
      end do
   end function escape_controls

   !> `s` with every line (between line feeds) longer than `max_message_line`
   !> characters cut there and marked with ' ... (N more characters)'.
   pure function cap_lines(s) result(e)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: e
      character(len=24) :: b
      integer :: a, z, n
      if (len(s) <= max_message_line) then
         e = s
         return
      end if
      e = ''
      a = 1
      do while (a <= len(s))
         z = index(s(a:), new_line('a'))
         if (z == 0) then
            z = len(s) + 1
         else
            z = a + z - 1
         end if
         n = z - a
         if (n > max_message_line) then
            write (b, '(i0)') n - max_message_line
            e = e//s(a:a + max_message_line - 1)//' ... ('//trim(b)//' more characters)'
         else
            e = e//s(a:z - 1)
         end if
         if (z <= len(s)) e = e//new_line('a')
         a = z + 1
      end do
   end function cap_lines

   pure logical function is_shown_escaped(c)
      integer, intent(in) :: c
      is_shown_escaped = (c < 32 .and. c /= 10 .and. c /= 9) .or. c == 127
   end function is_shown_escaped
   pure function int_text_default(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=12) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function int_text_default

   pure function int_text_i8(i) result(s)
      integer(i8), intent(in) :: i
      character(len=:), allocatable :: s
      character(len=21) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function int_text_i8
end module vemcontact_text
