!> Base64 encoding (RFC 4648, standard alphabet, '=' padding) of raw bytes.
!> Bytes are held in `character` strings: Fortran has no unsigned 8-bit integer,
!> a character is exactly one byte in gfortran, and stream output writes a
!> character string byte for byte.  `as_bytes` turns numeric arrays into such a
!> string by `transfer` (one memcpy).  The encoder writes into a caller-provided,
!> preallocated buffer: no per-character concatenation, so encoding runs at
!> memory speed and large payloads can be encoded in chunks.
module vemcontact_output_base64
   use vemcontact_kinds, only: wp, ip, i8
   implicit none
   private

   public :: base64_length, base64_encode, base64, as_bytes

   !> The 64 symbols of the standard alphabet.
   character(len=64), parameter :: alphabet = &
      'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/'

   !> Raw bytes (in the host's byte order) of a numeric array.
   interface as_bytes
      module procedure :: bytes_real_1, bytes_real_2, bytes_int_1, bytes_i8_1, bytes_i8_0
   end interface as_bytes

contains

   !> Number of base64 characters for `nbytes` bytes (with padding).
   pure function base64_length(nbytes) result(n)
      integer(i8), intent(in) :: nbytes
      integer(i8) :: n
      n = 4_i8*((nbytes + 2_i8)/3_i8)
   end function base64_length

   !> Encode all of `bytes` into `out(1:base64_length(len(bytes)))`.
   !> `out` must be at least that long; characters beyond are left untouched.
   !> Encoding a long byte string in pieces gives the same text as encoding it
   !> whole as long as every piece but the last has a length divisible by 3.
   pure subroutine base64_encode(bytes, out)
      character(len=*), intent(in) :: bytes
      character(len=*), intent(inout) :: out
      integer(i8) :: nb, nfull, i, j
      integer :: v, rest
      nb = len(bytes, kind=i8)
      nfull = (nb/3_i8)*3_i8
      j = 0
      ! whole 3-byte groups: 24 bits -> 4 symbols of 6 bits
      do i = 1, nfull, 3
         v = ichar(bytes(i:i))*65536 + ichar(bytes(i + 1:i + 1))*256 + ichar(bytes(i + 2:i + 2))
         out(j + 1:j + 1) = alphabet(ishft(v, -18) + 1:ishft(v, -18) + 1)
         out(j + 2:j + 2) = alphabet(iand(ishft(v, -12), 63) + 1:iand(ishft(v, -12), 63) + 1)
         out(j + 3:j + 3) = alphabet(iand(ishft(v, -6), 63) + 1:iand(ishft(v, -6), 63) + 1)
         out(j + 4:j + 4) = alphabet(iand(v, 63) + 1:iand(v, 63) + 1)
         j = j + 4
      end do
      rest = int(nb - nfull)
      if (rest == 0) return
      ! one or two trailing bytes: zero-fill to 24 bits, pad with '='
      v = ichar(bytes(nfull + 1:nfull + 1))*65536
      if (rest == 2) v = v + ichar(bytes(nfull + 2:nfull + 2))*256
      out(j + 1:j + 1) = alphabet(ishft(v, -18) + 1:ishft(v, -18) + 1)
      out(j + 2:j + 2) = alphabet(iand(ishft(v, -12), 63) + 1:iand(ishft(v, -12), 63) + 1)
      if (rest == 2) then
         out(j + 3:j + 3) = alphabet(iand(ishft(v, -6), 63) + 1:iand(ishft(v, -6), 63) + 1)
      else
         out(j + 3:j + 3) = '='
      end if
      out(j + 4:j + 4) = '='
   end subroutine base64_encode

   !> Base64 text of `bytes` (allocating convenience for short strings).
   pure function base64(bytes) result(s)
      character(len=*), intent(in) :: bytes
      character(len=:), allocatable :: s
      allocate (character(len=base64_length(len(bytes, kind=i8))) :: s)
      call base64_encode(bytes, s)
   end function base64

   pure function bytes_real_1(a) result(b)
      real(wp), intent(in) :: a(:)
      character(len=:), allocatable :: b
      allocate (character(len=size(a, kind=i8)*storage_size(a, kind=i8)/8_i8) :: b)
      if (len(b) > 0) b = transfer(a, b)
   end function bytes_real_1

   pure function bytes_real_2(a) result(b)
      real(wp), intent(in) :: a(:, :)
      character(len=:), allocatable :: b
      allocate (character(len=size(a, kind=i8)*storage_size(a, kind=i8)/8_i8) :: b)
      if (len(b) > 0) b = transfer(a, b)
   end function bytes_real_2

   pure function bytes_int_1(a) result(b)
      integer(ip), intent(in) :: a(:)
      character(len=:), allocatable :: b
      allocate (character(len=size(a, kind=i8)*storage_size(a, kind=i8)/8_i8) :: b)
      if (len(b) > 0) b = transfer(a, b)
   end function bytes_int_1

   pure function bytes_i8_1(a) result(b)
      integer(i8), intent(in) :: a(:)
      character(len=:), allocatable :: b
      allocate (character(len=size(a, kind=i8)*storage_size(a, kind=i8)/8_i8) :: b)
      if (len(b) > 0) b = transfer(a, b)
   end function bytes_i8_1

   pure function bytes_i8_0(a) result(b)
      integer(i8), intent(in) :: a
      character(len=:), allocatable :: b
      allocate (character(len=storage_size(a)/8) :: b)
      b = transfer(a, b)
   end function bytes_i8_0
end module vemcontact_output_base64
