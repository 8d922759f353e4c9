!> zlib compression of byte strings (the interop with C's zlib: `compress2`,
!> `compressBound`), for the compressed binary arrays of the .vtu files
!> (VTK's vtkZLibDataCompressor: every block an independent zlib stream).
!> zlib's `uLong` is C's `unsigned long`: `c_long` on the LP64 hosts supported
!> (the sizes involved stay far below 2**63).
module vemcontact_output_zlib
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_long
   use vemcontact_kinds, only: i8
   implicit none
   private

   public :: zlib_bound, zlib_compress

   interface
      function c_compress2(dest, dest_len, source, source_len, level) bind(C, name='compress2') result(rc)
         import :: c_char, c_int, c_long
         character(kind=c_char), intent(inout) :: dest(*)
         integer(c_long), intent(inout) :: dest_len
         character(kind=c_char), intent(in) :: source(*)
         integer(c_long), value :: source_len
         integer(c_int), value :: level
         integer(c_int) :: rc
      end function c_compress2

      function c_compress_bound(source_len) bind(C, name='compressBound') result(n)
         import :: c_long
         integer(c_long), value :: source_len
         integer(c_long) :: n
      end function c_compress_bound
   end interface

contains

   !> Largest compressed size of `nbytes` bytes (zlib's compressBound).
   function zlib_bound(nbytes) result(n)
      integer(i8), intent(in) :: nbytes
      integer(i8) :: n
      n = int(c_compress_bound(int(nbytes, c_long)), i8)
   end function zlib_bound

   !> Compress `source` as one zlib stream into `dest(1:nout)` at `level` (0-9).
   !> `dest` must hold at least zlib_bound(len(source)) bytes; `ok` is false when
   !> zlib reports an error (out of memory), and `nout` is then 0.
   subroutine zlib_compress(source, dest, level, nout, ok)
      character(len=*), intent(in) :: source
      character(len=*), intent(inout) :: dest
      integer, intent(in) :: level
      integer(i8), intent(out) :: nout
      logical, intent(out) :: ok
      integer(c_long) :: n
      character(len=1) :: empty
      n = int(len(dest, kind=i8), c_long)
      if (len(source) == 0) then
         empty = achar(0)
         ok = c_compress2(dest, n, empty, 0_c_long, int(level, c_int)) == 0_c_int
      else
         ok = c_compress2(dest, n, source, int(len(source, kind=i8), c_long), int(level, c_int)) == 0_c_int
      end if
      nout = 0
      if (ok) nout = int(n, i8)
   end subroutine zlib_compress
end module vemcontact_output_zlib
