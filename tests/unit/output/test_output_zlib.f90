!> Block compression of the .vtu arrays: the streams decompress (libdeflate's own
!> zlib decoder, an independent check of every block's stream) to the original
!> blocks, their sizes add up, and the bytes are the same for 1, 2, 3 and 8 threads
!> (each block is compressed alone, whichever thread takes it).
program test_output_zlib
   use, intrinsic :: iso_c_binding, only: c_associated, c_char, c_int, c_ptr, c_size_t
   use vemcontact_kinds, only: wp, i8
   use vemcontact_testing, only: checker_t
   use vemcontact_output_base64, only: as_bytes
   use vemcontact_output_zlib, only: zlib_compress_blocks, zlib_processors
   implicit none
   interface
      function c_alloc_decompressor() bind(C, name='libdeflate_alloc_decompressor') result(d)
         import :: c_ptr
         type(c_ptr) :: d
      end function c_alloc_decompressor
      subroutine c_free_decompressor(d) bind(C, name='libdeflate_free_decompressor')
         import :: c_ptr
         type(c_ptr), value :: d
      end subroutine c_free_decompressor
      function c_zlib_decompress(d, src, nsrc, dst, ndst, nout) bind(C, name='libdeflate_zlib_decompress') result(r)
         import :: c_char, c_int, c_ptr, c_size_t
         type(c_ptr), value :: d
         character(kind=c_char), intent(in) :: src(*)
         integer(c_size_t), value :: nsrc
         character(kind=c_char), intent(inout) :: dst(*)
         integer(c_size_t), value :: ndst
         integer(c_size_t), intent(out) :: nout
         integer(c_int) :: r
      end function c_zlib_decompress
   end interface
   type(checker_t) :: t
   character(len=:), allocatable :: bytes, packed1, packed
   integer(i8), allocatable :: sizes1(:), sizes(:)
   real(wp), allocatable :: v(:)
   integer(i8) :: nout1, nout, block, k
   integer :: i, threads(3) = [2, 3, 8]
   logical :: ok

   call t%check(zlib_processors() >= 1, 'at least one processor')

   ! float64 values with zero components between them (as a stress tensor's), 800 016
   ! bytes: 13 blocks of 64 KiB, the last one partial
   allocate (v(100002))
   do i = 1, size(v)
      v(i) = merge(0.0_wp, sin(1.0e3_wp*i)*1.0e5_wp, mod(i, 3) == 0)
   end do
   bytes = as_bytes(v)
   block = 65536
   call zlib_compress_blocks(bytes, block, 1, 1, packed1, sizes1, nout1, ok)
   call t%check(ok, 'one thread: compressed')
   call t%equal(size(sizes1), 13, 'one thread: 13 blocks')
   call t%check(sum(sizes1) == nout1, 'the block sizes add up to the streams')
   call t%check(nout1 < len(bytes, kind=i8), 'the streams are shorter than the data')
   call check_round_trip(packed1(1:nout1), sizes1, bytes, block)
   do i = 1, size(threads)
      call zlib_compress_blocks(bytes, block, 1, threads(i), packed, sizes, nout, ok)
      call t%check(ok, 'several threads: compressed')
      call t%check(nout == nout1, 'several threads: the same length as one')
      if (nout == nout1) call t%check(packed(1:nout) == packed1(1:nout1), 'several threads: the same bytes')
      call t%check(all(sizes == sizes1), 'several threads: the same block sizes')
   end do

   ! an empty array has no block; a single short block
   call zlib_compress_blocks('', block, 1, 4, packed, sizes, nout, ok)
   call t%check(ok .and. size(sizes) == 0 .and. nout == 0, 'empty: no block')
   call zlib_compress_blocks('abc', block, 1, 4, packed, sizes, nout, ok)
   call t%check(ok .and. size(sizes) == 1, 'three bytes: one block')
   call check_round_trip(packed(1:nout), sizes, 'abc', block)
   call t%finish()
contains
   !> Every block's stream decompresses to the block it came from.
   subroutine check_round_trip(streams, sizes, original, block)
      character(len=*), intent(in) :: streams, original
      integer(i8), intent(in) :: sizes(:), block
      type(c_ptr) :: d
      character(len=:), allocatable :: out
      integer(c_size_t) :: n
      integer(i8) :: pos, first, last
      logical :: same
      d = c_alloc_decompressor()
      call t%check(c_associated(d), 'decompressor allocated')
      if (.not. c_associated(d)) return
      allocate (character(len=block) :: out)
      pos = 0
      same = .true.
      do k = 1, size(sizes)
         first = (k - 1)*block + 1
         last = min(len(original, kind=i8), k*block)
         if (c_zlib_decompress(d, streams(pos + 1:pos + sizes(k)), int(sizes(k), c_size_t), out, &
                               int(block, c_size_t), n) /= 0) then
            same = .false.
         else
            same = same .and. n == last - first + 1 .and. out(1:n) == original(first:last)
         end if
         pos = pos + sizes(k)
      end do
      call c_free_decompressor(d)
      call t%check(same, 'every block decompresses to the original')
   end subroutine check_round_trip
end program test_output_zlib
