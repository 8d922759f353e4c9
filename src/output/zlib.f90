!> zlib-format compression of byte strings, for the compressed binary arrays of
!> the .vtu files (VTK's vtkZLibDataCompressor: every block an independent zlib
!> stream, RFC 1950).  The streams are made by libdeflate (the interop with its C
!> API: `libdeflate_alloc_compressor`, `libdeflate_zlib_compress`,
!> `libdeflate_zlib_compress_bound`), which writes standard zlib streams 2.4x
!> faster than zlib's own `compress2` at level 1 on float64 results, for the same
!> size (docs/performance.md, "The peers' cantilever"); any zlib reader (VTK,
!> ParaView, meshio) reads them.  The output is deterministic for a given level
!> and libdeflate version.  `size_t` is `c_size_t`.
module vemcontact_output_zlib
   use, intrinsic :: iso_c_binding, only: c_associated, c_char, c_int, c_null_ptr, c_ptr, c_size_t
   use vemcontact_kinds, only: i8
   implicit none
   private

   public :: zlib_bound, zlib_compress

   interface
      function c_alloc_compressor(level) bind(C, name='libdeflate_alloc_compressor') result(c)
         import :: c_int, c_ptr
         integer(c_int), value :: level
         type(c_ptr) :: c
      end function c_alloc_compressor

      subroutine c_free_compressor(c) bind(C, name='libdeflate_free_compressor')
         import :: c_ptr
         type(c_ptr), value :: c
      end subroutine c_free_compressor

      function c_zlib_compress(c, source, source_len, dest, dest_len) bind(C, name='libdeflate_zlib_compress') &
         result(n)
         import :: c_char, c_ptr, c_size_t
         type(c_ptr), value :: c
         character(kind=c_char), intent(in) :: source(*)
         integer(c_size_t), value :: source_len
         character(kind=c_char), intent(inout) :: dest(*)
         integer(c_size_t), value :: dest_len
         integer(c_size_t) :: n
      end function c_zlib_compress

      function c_zlib_compress_bound(c, source_len) bind(C, name='libdeflate_zlib_compress_bound') result(n)
         import :: c_ptr, c_size_t
         type(c_ptr), value :: c
         integer(c_size_t), value :: source_len
         integer(c_size_t) :: n
      end function c_zlib_compress_bound
   end interface

contains

   !> Largest compressed size of `nbytes` bytes at any level.
   function zlib_bound(nbytes) result(n)
      integer(i8), intent(in) :: nbytes
      integer(i8) :: n
      ! a null compressor: the bound for every level (libdeflate.h)
      n = int(c_zlib_compress_bound(c_null_ptr, int(nbytes, c_size_t)), i8)
   end function zlib_bound

   !> Compress `source` as one zlib stream into `dest(1:nout)` at `level`
   !> (libdeflate's 0-12; 1 is its fastest that compresses, 6 zlib's default).
   !> `dest` must hold at least zlib_bound(len(source)) bytes; `ok` is false when
   !> the compressor cannot be allocated (out of memory) or the stream does not
   !> fit, and `nout` is then 0.  A compressor per call: its set-up is negligible
   !> against a block of 256 KiB (measured: no difference in the total).
   subroutine zlib_compress(source, dest, level, nout, ok)
      character(len=*), intent(in) :: source
      character(len=*), intent(inout) :: dest
      integer, intent(in) :: level
      integer(i8), intent(out) :: nout
      logical, intent(out) :: ok
      type(c_ptr) :: c
      integer(c_size_t) :: n
      character(len=1) :: empty
      nout = 0
      c = c_alloc_compressor(int(level, c_int))
      ok = c_associated(c)
      if (.not. ok) return
      if (len(source) == 0) then
         empty = achar(0)
         n = c_zlib_compress(c, empty, 0_c_size_t, dest, int(len(dest, kind=i8), c_size_t))
      else
         n = c_zlib_compress(c, source, int(len(source, kind=i8), c_size_t), dest, int(len(dest, kind=i8), c_size_t))
      end if
      call c_free_compressor(c)
      ok = n > 0_c_size_t
      if (ok) nout = int(n, i8)
   end subroutine zlib_compress
end module vemcontact_output_zlib
