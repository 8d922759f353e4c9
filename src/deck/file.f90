!> Reading one deck file whole, in bounded pieces, with the checks that keep a wrong
!> file from costing more than it is worth (C shim deck_file_shim.c):
!> - only a regular file is read: a FIFO, a pipe (/dev/stdin), a device, a folder or
!>   a /proc file is refused with a message before anything waits on it;
!> - a NUL byte means the file is not text (a binary file given by mistake): refused
!>   naming the line, without reading further;
!> - a physical line longer than `max_line_length` characters is refused naming the
!>   line, without reading further: the bytes held are at most what was read up to
!>   it plus one piece, however large the file.
!> The file is read in pieces of `piece` bytes into a buffer of the file's size.
module vemcontact_deck_file
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_int64_t, c_null_char
   use vemcontact_kinds, only: i8
   use vemcontact_text, only: int_text
   implicit none
   private

   public :: read_text_file

   !> Longest physical deck line accepted (bytes, line end excluded); decks written by
   !> hand or by vc-mesh have lines of at most a few hundred characters, and a data
   !> line may be continued on the next line (a trailing comma) without limit.
   integer, parameter, public :: max_line_length = 65536

   !> Bytes read per read(2): large enough for throughput, small enough that a bad
   !> file is given up after little work.
   integer(i8), parameter :: piece = 4194304_i8

   integer, parameter :: kind_directory = 1, kind_fifo = 2, kind_char_device = 3, kind_block_device = 4, &
                         kind_socket = 5, kind_pseudo = 6

   interface
      function c_open(path, fd, size, kind) result(rc) bind(C, name='vc_deck_open')
         import :: c_int, c_char, c_int64_t
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), intent(out) :: fd, kind
         integer(c_int64_t), intent(out) :: size
         integer(c_int) :: rc
      end function c_open
      function c_read(fd, buf, n) result(got) bind(C, name='vc_deck_read')
         import :: c_int, c_char, c_int64_t
         integer(c_int), value :: fd
         character(kind=c_char), intent(inout) :: buf(*)
         integer(c_int64_t), value :: n
         integer(c_int64_t) :: got
      end function c_read
      subroutine c_close(fd) bind(C, name='vc_deck_close')
         import :: c_int
         integer(c_int), value :: fd
      end subroutine c_close
      subroutine c_strerror(code, buf, len) bind(C, name='vc_deck_strerror')
         import :: c_int, c_char
         integer(c_int), value :: code
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_int), value :: len
      end subroutine c_strerror
   end interface

contains

   !> Read the regular text file `path` whole into `buf`.  On failure `buf` is not
   !> allocated and `message` says why ("cannot open ...", "... is a FIFO ...",
   !> "line N ...: not a text file", ...) without quoting the file's contents.
   subroutine read_text_file(path, buf, message, not_text)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: buf
      character(len=:), allocatable, intent(out) :: message
      !> the file was read but is no deck text (a NUL byte, an overlong line): bad input
      !> rather than a file that cannot be read
      logical, intent(out) :: not_text
      integer(c_int) :: fd, kind, rc
      integer(c_int64_t) :: size, got
      integer(i8) :: pos, n, line, linelen
      not_text = .false.
      rc = c_open(path//c_null_char, fd, size, kind)
      if (rc > 0) then
         message = 'cannot open '''//path//''': '//strerror(rc)
         return
      else if (rc < 0) then
         message = ''''//path//''' is '//kind_text(kind)//', not a regular file: give the deck and '// &
                   'its *INCLUDE files as ordinary files'
         return
      end if
      allocate (character(len=size) :: buf)
      pos = 1
      line = 1
      linelen = 0
      do while (pos <= size)
         n = min(piece, size - pos + 1)
         got = c_read(fd, buf(pos:pos + n - 1), n)
         if (got < 0) then
            message = 'cannot read '''//path//''': '//strerror(int(-got, c_int))
            exit
         end if
         call check_piece(buf(pos:pos + got - 1), line, linelen, message)
         if (allocated(message)) then
            not_text = .true.
            message = ''''//path//''' line '//int_text(line)//': '//message
            exit
         end if
         if (got < n) then
            ! the file shrank while it was read: keep what is there
            buf = buf(1:pos + got - 1)
            exit
         end if
         pos = pos + got
      end do
      call c_close(fd)
      if (allocated(message)) deallocate (buf)
   end subroutine read_text_file

   !> Check the bytes `s` that follow line `line` (of which `linelen` characters were
   !> seen): no NUL byte, no line longer than max_line_length.  `line` and `linelen`
   !> are carried on to the next piece; `message` is allocated on a problem, and
   !> `line` is then the offending line.
   pure subroutine check_piece(s, line, linelen, message)
      character(len=*), intent(in) :: s
      integer(i8), intent(inout) :: line, linelen
      character(len=:), allocatable, intent(inout) :: message
      character(len=1), parameter :: lf = achar(10), cr = achar(13), nul = achar(0)
      integer(i8) :: k, n, q, stop_at
      n = len(s, kind=i8)
      ! a NUL before anything else decides where checking stops
      stop_at = index(s, nul, kind=i8)
      k = 1
      do while (k <= n)
         ! a lone CR (old Mac line ends) also ends a line for the length check
         q = scan(s(k:), lf//cr, kind=i8)
         if (q == 0) then
            q = n + 1
         else
            q = k + q - 1
         end if
         if (stop_at > 0 .and. stop_at < q) then
            message = 'not a text file (a NUL byte): a deck is plain text'
            return
         end if
         linelen = linelen + (q - k)
         if (linelen > max_line_length) then
            message = 'longer than the limit of '//int_text(int(max_line_length, i8))// &
                      ' characters per line (is it a text deck?); continue a long data line on the next '// &
                      'line after a comma'
            return
         end if
         if (q <= n) then
            if (s(q:q) == lf) line = line + 1
            linelen = 0
         end if
         k = q + 1
      end do
   end subroutine check_piece

   function kind_text(kind) result(s)
      integer(c_int), intent(in) :: kind
      character(len=:), allocatable :: s
      select case (kind)
      case (kind_directory)
         s = 'a folder'
      case (kind_fifo)
         s = 'a FIFO or pipe (a stream, such as /dev/stdin or a shell''s <(...))'
      case (kind_char_device)
         s = 'a character device'
      case (kind_block_device)
         s = 'a block device'
      case (kind_socket)
         s = 'a socket'
      case (kind_pseudo)
         s = 'a system pseudo-file (its size is not known, as in /proc or /sys)'
      case default
         s = 'a special file'
      end select
   end function kind_text

   function strerror(code) result(s)
      integer(c_int), intent(in) :: code
      character(len=:), allocatable :: s
      character(kind=c_char, len=256) :: b
      integer :: n
      call c_strerror(code, b, int(len(b), c_int))
      n = max(0, index(b, c_null_char) - 1)
      s = b(1:n)
   end function strerror
end module vemcontact_deck_file
