!> zlib-format compression for the compressed binary arrays of the .vtu files
!> (VTK's vtkZLibDataCompressor: the array cut into blocks of a fixed size, every
!> block an independent zlib stream, RFC 1950).  The streams are made by libdeflate
!> through a thin C layer (src/output/deflate_blocks.c), which compresses the blocks
!> of one array on several threads at once: libdeflate writes standard zlib streams
!> 2.4x faster than zlib's own `compress2` at level 1 on float64 results, for the
!> same size (docs/performance.md, "The peers' cantilever"), and any zlib reader
!> (VTK, ParaView, meshio) reads them.  The bytes are the same for any number of
!> threads (each block is compressed alone) and deterministic for a given level
!> and libdeflate version.
module vemcontact_output_zlib
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_int64_t
   use vemcontact_kinds, only: i8
   implicit none
   private

   public :: zlib_compress_blocks, zlib_processors

   interface
      function c_processors() bind(C, name='vc_deflate_processors') result(n)
         import :: c_int
         integer(c_int) :: n
      end function c_processors

      function c_bound(nbytes) bind(C, name='vc_deflate_bound') result(n)
         import :: c_int64_t
         integer(c_int64_t), value :: nbytes
         integer(c_int64_t) :: n
      end function c_bound

      function c_blocks(src, nbytes, block, level, threads, dst, bound, sizes, total) &
         bind(C, name='vc_deflate_blocks') result(status)
         import :: c_char, c_int, c_int64_t
         character(kind=c_char), intent(in) :: src(*)
         integer(c_int64_t), value :: nbytes, block
         integer(c_int), value :: level, threads
         character(kind=c_char), intent(inout) :: dst(*)
         integer(c_int64_t), value :: bound
         integer(c_int64_t), intent(out) :: sizes(*)
         integer(c_int64_t), intent(out) :: total
         integer(c_int) :: status
      end function c_blocks
   end interface

contains

   !> Processors this process may run on (its affinity mask), at least 1.
   integer function zlib_processors()
      zlib_processors = int(c_processors())
   end function zlib_processors

   !> Compress `source` in blocks of `block` bytes (the last one shorter), each one
   !> zlib stream at `level` (libdeflate's 0-12; 1 is its fastest that compresses,
   !> 6 zlib's default), with up to `threads` threads.  On return
   !> `packed(1:nout)` holds the streams in block order and `sizes(k)` the length of
   !> block k's; `ok` is false when a compressor cannot be allocated (out of memory).
   !> An empty source has no block.
   subroutine zlib_compress_blocks(source, block, level, threads, packed, sizes, nout, ok)
      character(len=*), intent(in) :: source
      integer(i8), intent(in) :: block
      integer, intent(in) :: level, threads
      character(len=:), allocatable, intent(out) :: packed
      integer(i8), allocatable, intent(out) :: sizes(:)
      integer(i8), intent(out) :: nout
      logical, intent(out) :: ok
      integer(i8) :: nb, nblocks, bound
      integer(c_int64_t) :: total
      nb = len(source, kind=i8)
      nblocks = (nb + block - 1_i8)/block
      allocate (sizes(nblocks))
      nout = 0
      ok = .true.
      if (nblocks == 0) then
         allocate (character(len=0) :: packed)
         return
      end if
      bound = int(c_bound(int(block, c_int64_t)), i8)
      allocate (character(len=nblocks*bound) :: packed)
      ok = c_blocks(source, int(nb, c_int64_t), int(block, c_int64_t), int(level, c_int), &
                    int(max(threads, 1), c_int), packed, int(bound, c_int64_t), sizes, total) == 0
      if (ok) nout = int(total, i8)
   end subroutine zlib_compress_blocks
end module vemcontact_output_zlib
