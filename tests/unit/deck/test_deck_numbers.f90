!> The fast number parser against Fortran's own READ: hand-picked forms, then
!> random mantissas and exponents.  In the fast path (mantissa <= 2**53,
!> |exponent| <= 22) results must be bit-identical to READ; longer mantissas and
!> larger exponents go through the fallback and must agree as well.
program test_deck_numbers
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_testing, only: checker_t
   use vemcontact_deck_numbers, only: parse_int, parse_real, num_ok, num_syntax, num_overflow, &
                                      num_nan, num_inf, num_empty, num_not_int
   implicit none
   type(checker_t) :: t
   real(wp) :: v, ref, u
   integer(ip) :: iv
   integer :: stat, k, ios, ndig, ex, nbad_fast, nbad_slow, nfast
   integer(i8) :: mant
   character(len=64) :: buf
   character(len=*), parameter :: good(*) = [character(len=24) :: '1', '-1.', '.5', '1e3', &
                                             '1.5E-03', '1.5d0', '+2.', '-0.0', '0.1', '123456789012345678', &
                                             '1.7976931348623157e307', '2.2250738585072014e-308', '4.9e-324', &
                                             '00012.50', '1D+2', '3.14159265358979323846', '9.900000000000000e-01', &
                                             '12345678901234567890123', '-.25e-1']
   character(len=*), parameter :: bad(*) = [character(len=12) :: 'abc', '1.2.3', '1e', 'e5', '.', '-', &
                                            '1,5', '1 5', '0x10', '1e+', '--1', '1.5q0', '1e3.0', '+e1']

   ! well-formed forms: bit-identical to READ
   do k = 1, size(good)
      call parse_real(trim(good(k)), v, stat)
      buf = good(k)
      read (buf, *, iostat=ios) ref
      call t%equal(stat, num_ok, 'parse_real status of '//trim(good(k)))
      call t%check(ios == 0 .and. same_bits(v, ref), 'parse_real value of '//trim(good(k)))
   end do
   call parse_real('-0.0', v, stat)
   call t%check(sign(1.0_wp, v) < 0.0_wp, 'negative zero keeps its sign')
   do k = 1, size(bad)
      call parse_real(trim(bad(k)), v, stat)
      call t%equal(stat, num_syntax, 'parse_real rejects '//trim(bad(k)))
   end do
   call parse_real('', v, stat)
   call t%equal(stat, num_empty, 'empty token')
   call parse_real('NaN', v, stat)
   call t%equal(stat, num_nan, 'NaN rejected')
   call parse_real('-inf', v, stat)
   call t%equal(stat, num_inf, '-inf rejected')
   call parse_real('Infinity', v, stat)
   call t%equal(stat, num_inf, 'Infinity rejected')
   call parse_real('1e400', v, stat)
   call t%equal(stat, num_overflow, '1e400 overflows')
   call parse_real('-2.5e308', v, stat)
   call t%equal(stat, num_overflow, '-2.5e308 overflows')
   call parse_real('1e-400', v, stat)
   call t%check(stat == num_ok .and. abs(v) <= 0.0_wp, '1e-400 underflows to 0')

   ! integers
   call parse_int('42', iv, stat)
   call t%check(stat == num_ok .and. iv == 42, 'int 42')
   call parse_int('+7', iv, stat)
   call t%check(stat == num_ok .and. iv == 7, 'int +7')
   call parse_int('-2147483648', iv, stat)
   call t%check(stat == num_ok .and. iv == -huge(iv) - 1, 'int -2**31')
   call parse_int('2147483647', iv, stat)
   call t%check(stat == num_ok .and. iv == huge(iv), 'int 2**31-1')
   call parse_int('2147483648', iv, stat)
   call t%equal(stat, num_overflow, 'int 2**31 overflows')
   call parse_int('99999999999999999999999', iv, stat)
   call t%equal(stat, num_overflow, 'int with 23 digits overflows')
   call parse_int('1.0', iv, stat)
   call t%equal(stat, num_not_int, 'int: 1.0 is a real')
   call parse_int('1x', iv, stat)
   call t%equal(stat, num_syntax, 'int: 1x is garbage')
   call parse_int('', iv, stat)
   call t%equal(stat, num_empty, 'int: empty')

   ! random values: fast path (<= 15 digits, |e| small) and fallback (long mantissas, big exponents)
   nbad_fast = 0
   nbad_slow = 0
   nfast = 0
   do k = 1, 200000
      call random_number(u)
      ndig = 1 + int(u*18.0_wp)   ! 10**18 still fits int64
      call random_number(u)
      mant = int(u*10.0_wp**ndig, i8)
      call random_number(u)
      if (mod(k, 2) == 0) then
         ex = int(u*44.0_wp) - 22 - (ndig - 1)/2
      else
         ex = int(u*600.0_wp) - 320
      end if
      select case (mod(k, 4))
      case (0)
         write (buf, '(i0,a,i0)') mant, 'e', ex
      case (1)
         write (buf, '(a,i0,a,i0)') '-0.', mant, 'E', ex
      case (2)
         write (buf, '(i0,a,i0)') mant, 'd', ex
      case default
         write (buf, '(i0,a)') mant, '.'
      end select
      call parse_real(trim(buf), v, stat)
      ! READ itself would raise the overflow trap on these
      if (stat == num_overflow) cycle
      read (buf, *, iostat=ios) ref
      if (stat /= num_ok .or. ios /= 0 .or. .not. same_bits(v, ref)) then
         if (mant <= 2_i8**53 .and. abs(ex) <= 22) then
            nbad_fast = nbad_fast + 1
         else
            nbad_slow = nbad_slow + 1
         end if
         if (nbad_fast + nbad_slow < 5) print '(a,2es26.17)', 'mismatch '//trim(buf), v, ref
      else if (mant <= 2_i8**53 .and. abs(ex) <= 22) then
         nfast = nfast + 1
      end if
   end do
   call t%equal(nbad_fast, 0, 'random values in the fast path: bit-identical to READ')
   call t%equal(nbad_slow, 0, 'random values in the fallback path: identical to READ')
   call t%check(nfast > 50000, 'the random sample exercises the fast path')
   call t%finish()
contains
   logical function same_bits(a, b)
      real(wp), intent(in) :: a, b
      same_bits = transfer(a, 0_i8) == transfer(b, 0_i8)
   end function same_bits
end program test_deck_numbers
