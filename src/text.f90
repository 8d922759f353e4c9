!> Text shown to the user: control characters of deck text (terminal escape
!> sequences, stray bytes) are shown escaped so that they neither act on the
!> terminal nor hide in the log.
module vemcontact_text
   implicit none
   private

   public :: escape_controls

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

   pure logical function is_shown_escaped(c)
      integer, intent(in) :: c
      is_shown_escaped = (c < 32 .and. c /= 10 .and. c /= 9) .or. c == 127
   end function is_shown_escaped
end module vemcontact_text
