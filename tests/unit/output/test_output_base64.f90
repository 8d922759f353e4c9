!> Base64 encoding: the RFC 4648 section 10 test vectors, bytes with the high
!> bit set, raw bytes of numbers (expected strings from Python's base64 module
!> on little-endian IEEE data), and encoding in pieces equal to encoding whole.
program test_output_base64
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_testing, only: checker_t
   use vemcontact_output_base64, only: base64, base64_encode, base64_length, as_bytes
   implicit none
   type(checker_t) :: t
   character(len=:), allocatable :: bytes, whole, pieces
   integer(i8) :: k, first, last, piece

   ! RFC 4648, section 10
   call t%check(base64('') == '', 'base64("")')
   call t%check(base64('f') == 'Zg==', 'base64("f")')
   call t%check(base64('fo') == 'Zm8=', 'base64("fo")')
   call t%check(base64('foo') == 'Zm9v', 'base64("foo")')
   call t%check(base64('foob') == 'Zm9vYg==', 'base64("foob")')
   call t%check(base64('fooba') == 'Zm9vYmE=', 'base64("fooba")')
   call t%check(base64('foobar') == 'Zm9vYmFy', 'base64("foobar")')
   call t%equal(int(base64_length(0_i8)), 0, 'length of 0 bytes')
   call t%equal(int(base64_length(7_i8)), 12, 'length of 7 bytes')

   ! bytes >= 128 (ichar must give 0..255) and the two last symbols '+' and '/'
   call t%check(base64(char(251)//char(255)) == '+/8=', 'base64(FB FF)')
   call t%check(base64(char(255)//char(255)//char(255)) == '////', 'base64(FF FF FF)')

   ! raw bytes of numbers: python base64.b64encode(struct.pack('<d', 1.0)), ...('<i', -2)
   call t%check(base64(as_bytes([1.0_wp])) == 'AAAAAAAA8D8=', 'base64 of real64 1.0')
   call t%check(base64(as_bytes([-2_ip])) == '/v///w==', 'base64 of int32 -2')
   call t%equal(len(as_bytes(reshape([1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp], [2, 2]))), 32, &
                'bytes of a 2x2 real64 array')
   call t%equal(len(as_bytes([1_i8, 2_i8])), 16, 'bytes of two int64')

   ! pieces of a multiple of 3 bytes concatenate to the whole encoding
   allocate (character(len=1000) :: bytes)
   do k = 1, 1000
      bytes(k:k) = char(int(mod(k*37_i8, 256_i8)))
   end do
   whole = base64(bytes)
   allocate (character(len=base64_length(1000_i8)) :: pieces)
   piece = 3*7
   first = 1
   do while (first <= 1000)
      last = min(1000_i8, first + piece - 1)
      call base64_encode(bytes(first:last), pieces(4*(first - 1)/3 + 1:))
      first = last + 1
   end do
   call t%check(pieces == whole, 'encoding in 21-byte pieces equals encoding whole')
   ! 1000 = 3*333 + 1: one byte left over, two padding characters
   call t%check(whole(len(whole) - 1:) == '==' .and. whole(len(whole) - 2:len(whole) - 2) /= '=', &
                '1000 bytes end with "=="')

   call t%finish()
end program test_output_base64
