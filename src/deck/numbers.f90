!> Fast parsing of integer and real tokens of a deck.
!> Decks with millions of numbers must read in about a second, so tokens are
!> converted by hand instead of with a list-directed READ per number.  Reals use
!> Clinger's fast path: a decimal mantissa of at most 19 digits held exactly in an
!> int64, and when it is at most 2**53 and the power of ten is at most 22 in
!> magnitude, both operands of one multiplication or division are exact doubles,
!> so the single IEEE rounding gives the correctly rounded result.  Every other
!> well-formed token goes to C's strtod (correctly rounded in glibc, and what
!> gfortran's READ calls in the end, without the READ's set-up of an internal unit,
!> which cost 0.15 s on 2e5 coordinates of 17 digits); tokens longer than 63
!> characters fall back to Fortran's internal READ.
module vemcontact_deck_numbers
   use vemcontact_kinds, only: wp, ip, i8
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use, intrinsic :: iso_c_binding, only: c_char, c_double, c_null_ptr, c_ptr
   implicit none
   private

   public :: parse_int, parse_real, number_problem

   !> Status of a conversion.
   integer, parameter, public :: num_ok = 0
   integer, parameter, public :: num_empty = 1    !< empty token
   integer, parameter, public :: num_syntax = 2   !< not a number
   integer, parameter, public :: num_overflow = 3 !< out of range of the kind
   integer, parameter, public :: num_nan = 4      !< NaN spelled out
   integer, parameter, public :: num_inf = 5      !< Infinity spelled out
   integer, parameter, public :: num_not_int = 6  !< a real where an integer is needed

   !> Exactly representable powers of ten (10**22 < 2**53 * 2**22 fits 53 bits of mantissa).
   real(wp), parameter :: pow10(0:22) = [1.0e0_wp, 1.0e1_wp, 1.0e2_wp, 1.0e3_wp, 1.0e4_wp, &
                                         1.0e5_wp, 1.0e6_wp, 1.0e7_wp, 1.0e8_wp, 1.0e9_wp, 1.0e10_wp, 1.0e11_wp, &
                                         1.0e12_wp, 1.0e13_wp, 1.0e14_wp, 1.0e15_wp, 1.0e16_wp, 1.0e17_wp, &
                                         1.0e18_wp, 1.0e19_wp, 1.0e20_wp, 1.0e21_wp, 1.0e22_wp]
   integer(i8), parameter :: two53 = 9007199254740992_i8

   interface
      !> C's strtod, without the end pointer: the token's syntax is checked before.
      pure function c_strtod(str, endptr) bind(C, name='strtod') result(v)
         import :: c_char, c_double, c_ptr
         character(kind=c_char), intent(in) :: str(*)
         type(c_ptr), value, intent(in) :: endptr
         real(c_double) :: v
      end function c_strtod
   end interface

contains

   !> Convert an optionally signed decimal integer (no blanks) to `integer(ip)`.
   pure subroutine parse_int(s, val, stat)
      character(len=*), intent(in) :: s
      integer(ip), intent(out) :: val
      integer, intent(out) :: stat
      integer(i8) :: acc
      integer :: i, d, n
      logical :: neg
      val = 0
      n = len(s)
      if (n == 0) then
         stat = num_empty
         return
      end if
      i = 1
      neg = .false.
      if (s(1:1) == '-' .or. s(1:1) == '+') then
         neg = s(1:1) == '-'
         i = 2
      end if
      if (i > n) then
         stat = num_syntax
         return
      end if
      acc = 0
      stat = num_ok
      do while (i <= n)
         d = ichar(s(i:i)) - ichar('0')
         if (d < 0 .or. d > 9) then
            stat = num_syntax
            exit
         end if
         ! 2**31 + 10 leaves room for one more digit check without int64 overflow
         if (acc <= 2147483658_i8) acc = acc*10 + d
         i = i + 1
      end do
      if (stat == num_syntax) then
         ! "1.", "1.0", "1e3" are reals: say so rather than "not a number"
         stat = real_status(s)
         if (stat == num_ok) stat = num_not_int
         return
      end if
      if (neg) acc = -acc
      if (acc > int(huge(val), i8) .or. acc < -int(huge(val), i8) - 1) then
         stat = num_overflow
         return
      end if
      val = int(acc, ip)
   end subroutine parse_int

   !> Syntax status of `s` as a real, without converting it.
   pure function real_status(s) result(stat)
      character(len=*), intent(in) :: s
      integer :: stat
      real(wp) :: v
      call parse_real(s, v, stat)
   end function real_status

   !> Convert a decimal real (Fortran forms: 1, -1., .5, 1e3, 1.5E-03, 1.5d0, +2.) to `real(wp)`.
   !> NaN and Infinity are rejected: a deck value must be a finite number.
   pure subroutine parse_real(s, val, stat)
      character(len=*), intent(in) :: s
      real(wp), intent(out) :: val
      integer, intent(out) :: stat
      integer(i8) :: mant
      integer :: i, n, d, nd, exp_adj, e, esign, e10, ios
      logical :: neg, seen_digit, truncated, seen_edigit
      character(len=1) :: c
      character(len=64) :: cbuf
      val = 0.0_wp
      n = len(s)
      if (n == 0) then
         stat = num_empty
         return
      end if
      stat = num_syntax
      i = 1
      neg = .false.
      if (s(1:1) == '-' .or. s(1:1) == '+') then
         neg = s(1:1) == '-'
         i = 2
      end if
      mant = 0
      nd = 0
      exp_adj = 0
      seen_digit = .false.
      truncated = .false.
      do while (i <= n)
         d = ichar(s(i:i)) - ichar('0')
         if (d < 0 .or. d > 9) exit
         seen_digit = .true.
         if (nd < 19) then
            if (mant /= 0 .or. d /= 0) then
               mant = mant*10 + d
               nd = nd + 1
            end if
         else
            exp_adj = exp_adj + 1
            if (d /= 0) truncated = .true.
         end if
         i = i + 1
      end do
      if (i <= n) then
         if (s(i:i) == '.') then
            i = i + 1
            do while (i <= n)
               d = ichar(s(i:i)) - ichar('0')
               if (d < 0 .or. d > 9) exit
               seen_digit = .true.
               if (nd < 19) then
                  if (mant /= 0 .or. d /= 0) then
                     mant = mant*10 + d
                     nd = nd + 1
                  end if
                  exp_adj = exp_adj - 1
               else if (d /= 0) then
                  truncated = .true.
               end if
               i = i + 1
            end do
         end if
      end if
      if (.not. seen_digit) then
         stat = special_status(s)
         return
      end if
      e = 0
      if (i <= n) then
         c = s(i:i)
         if (c /= 'e' .and. c /= 'E' .and. c /= 'd' .and. c /= 'D') return
         i = i + 1
         esign = 1
         if (i <= n) then
            if (s(i:i) == '-' .or. s(i:i) == '+') then
               if (s(i:i) == '-') esign = -1
               i = i + 1
            end if
         end if
         seen_edigit = .false.
         do while (i <= n)
            d = ichar(s(i:i)) - ichar('0')
            if (d < 0 .or. d > 9) return
            seen_edigit = .true.
            ! any exponent beyond 10**5 over- or underflows anyway
            if (e < 100000) e = e*10 + d
            i = i + 1
         end do
         if (.not. seen_edigit) return
         e = esign*e
      end if
      stat = num_ok
      if (mant == 0) then
         val = 0.0_wp
         if (neg) val = -val
         return
      end if
      e10 = exp_adj + e
      ! trailing zeros ("9.900000000000000e-01" as printed by %.15e) do not change the
      ! value but would push the mantissa past 2**53: move them into the exponent
      if (.not. truncated .and. mant > two53) then
         do while (mod(mant, 10_i8) == 0)
            mant = mant/10
            e10 = e10 + 1
         end do
      end if
      if (.not. truncated .and. mant <= two53 .and. abs(e10) <= 22) then
         if (e10 >= 0) then
            val = real(mant, wp)*pow10(e10)
         else
            val = real(mant, wp)/pow10(-e10)
         end if
         if (neg) val = -val
         return
      end if
      ! The value lies in [10**(nd-1+e10), 10**(nd+e10)).  Magnitudes from 1e308 up are
      ! rejected here: strtod behind the READ would raise an overflow trap near huge().
      if (nd + e10 > 308) then
         stat = num_overflow
         return
      end if
      if (nd + e10 < -330) then
         val = 0.0_wp
         if (neg) val = -val
         return
      end if
      if (n < len(cbuf)) then
         ! C's spelling of the exponent letter, and a NUL at the end
         cbuf(1:n) = s
         do i = 1, n
            if (cbuf(i:i) == 'd' .or. cbuf(i:i) == 'D') cbuf(i:i) = 'e'
         end do
         cbuf(n + 1:n + 1) = achar(0)
         val = real(c_strtod(cbuf, c_null_ptr), wp)
         ios = 0
      else
         read (s, *, iostat=ios) val
      end if
      if (ios /= 0) then
         stat = num_syntax
         val = 0.0_wp
      else if (.not. ieee_is_finite(val)) then
         stat = num_overflow
         val = 0.0_wp
      end if
   end subroutine parse_real

   !> num_nan / num_inf for spelled-out special values, num_syntax otherwise.
   pure function special_status(s) result(stat)
      character(len=*), intent(in) :: s
      integer :: stat
      character(len=:), allocatable :: u
      integer :: i, k
      u = s
      do i = 1, len(u)
         k = ichar(u(i:i))
         if (k >= ichar('a') .and. k <= ichar('z')) u(i:i) = achar(k - 32)
      end do
      if (len(u) > 0) then
         if (u(1:1) == '+' .or. u(1:1) == '-') u = u(2:)
      end if
      stat = num_syntax
      if (u == 'NAN' .or. index(u, 'NAN(') == 1) stat = num_nan
      if (u == 'INF' .or. u == 'INFINITY') stat = num_inf
   end function special_status

   !> Human-readable reason for a failed conversion, for error messages.
   pure function number_problem(stat, token, what) result(msg)
      integer, intent(in) :: stat
      character(len=*), intent(in) :: token, what
      character(len=:), allocatable :: msg
      select case (stat)
      case (num_empty)
         msg = 'missing '//what
      case (num_nan)
         msg = 'NaN is not allowed as '//what//' ('''//token//''')'
      case (num_inf)
         msg = 'infinite value is not allowed as '//what//' ('''//token//''')'
      case (num_overflow)
         msg = what//' '''//token//''' is out of range'
      case (num_not_int)
         msg = what//' must be an integer, found '''//token//''''
      case default
         msg = what//' must be a number, found '''//token//''''
      end select
   end function number_problem
end module vemcontact_deck_numbers
