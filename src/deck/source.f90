!> Deck files as a stream of lines: whole-file reads, the *INCLUDE stack and line continuation.
!> Each file is read whole into a buffer (vemcontact_deck_file: regular text files only) and lines are cut
!> from it; comment (`**`) and blank lines are skipped here.  The current line is
!> copied, trimmed, into `text(1:length)`, a buffer that only grows, so the hot loop
!> allocates nothing.  Buffers of all files are kept until the source is dropped so
!> that errors found after parsing can still quote the offending line.
!> A UTF-8 byte-order mark at the start of a file is read as blanks, and a
!> carriage return not followed by a line feed (old Mac line ends) ends a line
!> like a line feed; CR LF line ends work as before (the CR is trimmed).
module vemcontact_deck_source
   use vemcontact_kinds, only: i8
   use vemcontact_deck_file, only: read_text_file
   implicit none
   private

   public :: deck_source_t, normalize_path, directory_of

   !> Kind of the current line.
   integer, parameter, public :: line_eof = 0
   integer, parameter, public :: line_keyword = 1
   integer, parameter, public :: line_data = 2
   !> Result of `push_file`.
   integer, parameter, public :: push_ok = 0
   integer, parameter, public :: push_unreadable = 1
   integer, parameter, public :: push_cycle = 2
   integer, parameter, public :: push_too_deep = 3
   integer, parameter, public :: push_not_text = 4

   !> Nesting limit of *INCLUDE; cycles are detected by path before this is reached.
   integer, parameter :: max_depth = 40

   !> A file that was read, with a cursor used to look up line texts after parsing.
   type :: file_buf_t
      character(len=:), allocatable :: path
      character(len=:), allocatable :: buf
      integer(i8) :: look_pos = 1
      integer :: look_line = 1
   end type file_buf_t

   !> A file being read: index into `files`, next byte, number of lines consumed.
   type :: open_file_t
      integer :: file = 0
      integer(i8) :: pos = 1
      integer :: line = 0
   end type open_file_t

   !> The line source of a deck.
   type :: deck_source_t
      type(file_buf_t), allocatable :: files(:)
      integer :: nfiles = 0
      type(open_file_t), allocatable :: stack(:)
      integer :: depth = 0
      !> current line, trimmed: text(1:length)
      character(len=:), allocatable :: text
      integer :: length = 0
      integer :: kind = line_eof
      integer :: file = 0   !< file index of the current line
      integer :: line = 0   !< line number of the current line (first line if continued)
   contains
      procedure :: push_file
      procedure :: next => next_line
      procedure :: continue_line
      procedure :: line_text
      procedure :: path => current_path
      procedure :: chain => include_chain
   end type deck_source_t

contains

   !> Read `path` whole (a regular text file, lines of at most max_line_length
   !> characters: vemcontact_deck_file) and make it the file lines come from next.
   !> `message` explains a failure (push_unreadable, push_cycle, push_too_deep,
   !> push_not_text).
   subroutine push_file(self, path, stat, message)
      class(deck_source_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: message
      character(len=:), allocatable :: npath
      type(file_buf_t), allocatable :: tmpf(:)
      type(open_file_t), allocatable :: tmps(:)
      character(len=:), allocatable :: buf
      integer :: k, ifile
      logical :: not_text

      stat = push_ok
      npath = normalize_path(path)
      do k = 1, self%depth
         if (self%files(self%stack(k)%file)%path == npath) then
            stat = push_cycle
            message = 'include cycle: '//self%chain()//' -> '//npath
            return
         end if
      end do
      if (self%depth >= max_depth) then
         stat = push_too_deep
         message = 'includes nested deeper than the limit of 40'
         return
      end if
      ! a file included again (not recursively) is not read twice
      ifile = 0
      do k = 1, self%nfiles
         if (self%files(k)%path == npath) ifile = k
      end do
      if (ifile == 0) then
         call read_text_file(npath, buf, message, not_text)
         if (allocated(message)) then
            stat = merge(push_not_text, push_unreadable, not_text)
            return
         end if
         if (.not. allocated(self%files)) allocate (self%files(4))
         if (self%nfiles == size(self%files)) then
            allocate (tmpf(2*size(self%files)))
            do k = 1, self%nfiles
               call move_alloc(self%files(k)%path, tmpf(k)%path)
               call move_alloc(self%files(k)%buf, tmpf(k)%buf)
            end do
            call move_alloc(tmpf, self%files)
         end if
         ifile = self%nfiles + 1
         call move_alloc(buf, self%files(ifile)%buf)
         call normalize_line_ends(self%files(ifile)%buf)
         self%files(ifile)%path = npath
         self%nfiles = ifile
      end if
      if (.not. allocated(self%stack)) allocate (self%stack(4))
      if (self%depth == size(self%stack)) then
         allocate (tmps(2*size(self%stack)))
         tmps(1:self%depth) = self%stack(1:self%depth)
         call move_alloc(tmps, self%stack)
      end if
      self%depth = self%depth + 1
      self%stack(self%depth) = open_file_t(file=ifile, pos=1, line=0)
   end subroutine push_file

   !> Blank out a UTF-8 byte-order mark and turn every CR that is not followed by
   !> LF into LF, in place (byte positions and line numbers are kept).
   pure subroutine normalize_line_ends(buf)
      character(len=*), intent(inout) :: buf
      character(len=1), parameter :: lf = achar(10), cr = achar(13)
      integer(i8) :: k, n
      n = len(buf, kind=i8)
      if (n >= 3) then
         if (buf(1:3) == char(239)//char(187)//char(191)) buf(1:3) = '   '
      end if
      do k = 1, n
         if (buf(k:k) /= cr) cycle
         if (k < n) then
            if (buf(k + 1:k + 1) == lf) cycle
         end if
         buf(k:k) = lf
      end do
   end subroutine normalize_line_ends

   !> Advance to the next keyword or data line (skipping comments and blanks), popping
   !> finished included files; kind = line_eof when all files are done.
   subroutine next_line(self)
      class(deck_source_t), intent(inout) :: self
      integer(i8) :: a, b
      integer :: f, kind
      do while (self%depth > 0)
         f = self%stack(self%depth)%file
         call cut_line(self%files(f)%buf, self%stack(self%depth)%pos, self%stack(self%depth)%line, a, b, kind)
         if (kind == line_eof) then
            self%depth = self%depth - 1
            cycle
         end if
         self%kind = kind
         self%file = f
         self%line = self%stack(self%depth)%line
         self%length = 0
         call append_text(self, self%files(f)%buf(a:b))
         return
      end do
      self%kind = line_eof
      self%length = 0
   end subroutine next_line

   !> Append the next line of the same file to the current one when it is a data line
   !> (continuation of a data line that ended with a comma).  `ok` is false, and
   !> nothing is consumed, when the next line is a keyword line or the file ends.
   subroutine continue_line(self, ok)
      class(deck_source_t), intent(inout) :: self
      logical, intent(out) :: ok
      integer(i8) :: a, b, pos
      integer :: f, kind, line
      ok = .false.
      if (self%depth == 0) return
      f = self%stack(self%depth)%file
      if (f /= self%file) return
      pos = self%stack(self%depth)%pos
      line = self%stack(self%depth)%line
      call cut_line(self%files(f)%buf, pos, line, a, b, kind)
      if (kind /= line_data) return
      self%stack(self%depth)%pos = pos
      self%stack(self%depth)%line = line
      call append_text(self, self%files(f)%buf(a:b))
      ok = .true.
   end subroutine continue_line

   !> From byte `pos`, find the next non-blank, non-comment line: its trimmed extent
   !> buf(a:b) and its kind.  `pos` moves past it and `line` counts the lines consumed.
   pure subroutine cut_line(buf, pos, line, a, b, kind)
      character(len=*), intent(in) :: buf
      integer(i8), intent(inout) :: pos
      integer, intent(inout) :: line
      integer(i8), intent(out) :: a, b
      integer, intent(out) :: kind
      integer(i8) :: n, q
      character(len=1), parameter :: lf = achar(10), cr = achar(13), tab = achar(9)
      n = len(buf, kind=i8)
      kind = line_eof
      a = 1
      b = 0
      do while (pos <= n)
         q = pos
         do while (q <= n)
            if (buf(q:q) == lf) exit
            q = q + 1
         end do
         line = line + 1
         a = pos
         b = q - 1
         pos = q + 1
         do while (a <= b)
            if (buf(a:a) /= ' ' .and. buf(a:a) /= tab) exit
            a = a + 1
         end do
         do while (b >= a)
            if (buf(b:b) /= ' ' .and. buf(b:b) /= tab .and. buf(b:b) /= cr) exit
            b = b - 1
         end do
         if (b < a) cycle
         if (buf(a:a) == '*') then
            if (a < b) then
               if (buf(a + 1:a + 1) == '*') cycle
            end if
            kind = line_keyword
         else
            kind = line_data
         end if
         return
      end do
   end subroutine cut_line

   !> Append `s` to the current line, growing the buffer geometrically.
   subroutine append_text(self, s)
      class(deck_source_t), intent(inout) :: self
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: tmp
      integer :: need
      need = self%length + len(s)
      if (.not. allocated(self%text)) allocate (character(len=max(256, need)) :: self%text)
      if (need > len(self%text)) then
         allocate (character(len=max(need, 2*len(self%text))) :: tmp)
         tmp(1:self%length) = self%text(1:self%length)
         call move_alloc(tmp, self%text)
      end if
      self%text(self%length + 1:need) = s
      self%length = need
   end subroutine append_text

   !> Path of the file the current line came from (of `ifile` when given).
   function current_path(self, ifile) result(p)
      class(deck_source_t), intent(in) :: self
      integer, intent(in), optional :: ifile
      character(len=:), allocatable :: p
      integer :: f
      f = self%file
      if (present(ifile)) f = ifile
      if (f >= 1 .and. f <= self%nfiles) then
         p = self%files(f)%path
      else
         p = '<unknown>'
      end if
   end function current_path

   !> "a.inp -> b.inp" for the files currently open, outermost first.
   function include_chain(self) result(s)
      class(deck_source_t), intent(in) :: self
      character(len=:), allocatable :: s
      integer :: k
      s = ''
      do k = 1, self%depth
         if (k > 1) s = s//' -> '
         s = s//self%files(self%stack(k)%file)%path
      end do
   end function include_chain

   !> Trimmed text of line `line` of file `ifile` (empty if unknown).  Lookups are
   !> cheap when made in increasing line order, as the checks after parsing do.
   function line_text(self, ifile, line) result(s)
      class(deck_source_t), intent(inout) :: self
      integer, intent(in) :: ifile, line
      character(len=:), allocatable :: s
      integer(i8) :: pos, n, a, b
      integer :: cur
      character(len=1), parameter :: lf = achar(10), cr = achar(13), tab = achar(9)
      s = ''
      if (ifile < 1 .or. ifile > self%nfiles .or. line < 1) return
      if (.not. allocated(self%files(ifile)%buf)) return
      associate (buf => self%files(ifile)%buf)
         n = len(buf, kind=i8)
         pos = self%files(ifile)%look_pos
         cur = self%files(ifile)%look_line
         if (cur > line) then
            pos = 1
            cur = 1
         end if
         do while (cur < line .and. pos <= n)
            if (buf(pos:pos) == lf) cur = cur + 1
            pos = pos + 1
         end do
         self%files(ifile)%look_pos = pos
         self%files(ifile)%look_line = cur
         if (cur /= line .or. pos > n) return
         a = pos
         b = pos
         do while (b <= n)
            if (buf(b:b) == lf) exit
            b = b + 1
         end do
         b = b - 1
         do while (a <= b)
            if (buf(a:a) /= ' ' .and. buf(a:a) /= tab) exit
            a = a + 1
         end do
         do while (b >= a)
            if (buf(b:b) /= ' ' .and. buf(b:b) /= tab .and. buf(b:b) /= cr) exit
            b = b - 1
         end do
         if (b >= a) s = buf(a:b)
      end associate
   end function line_text

   !> Lexically normalised path: no "//", "./" or "dir/.." parts (symbolic links are
   !> not resolved; the include depth limit still stops cycles through them).
   pure function normalize_path(path) result(r)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: r
      character(len=:), allocatable :: part
      integer, allocatable :: starts(:)
      integer :: i, j, n, np
      logical :: absolute
      character(len=len(path)) :: parts_buf
      n = len_trim(path)
      absolute = .false.
      if (n > 0) absolute = path(1:1) == '/'
      allocate (starts(0:n + 1))
      ! rebuild the path component by component in parts_buf; starts(k) marks component k
      np = 0
      j = 0
      i = 1
      do while (i <= n)
         do while (i <= n)
            if (path(i:i) /= '/') exit
            i = i + 1
         end do
         if (i > n) exit
         part = ''
         do while (i <= n)
            if (path(i:i) == '/') exit
            part = part//path(i:i)
            i = i + 1
         end do
         if (part == '.') cycle
         if (part == '..' .and. np > 0) then
            if (parts_buf(starts(np):j) /= '..') then
               j = starts(np) - 1
               if (j > 0) j = j - 1 ! drop the separator
               np = np - 1
               cycle
            end if
         end if
         if (part == '..' .and. np == 0 .and. absolute) cycle
         if (j > 0) then
            j = j + 1
            parts_buf(j:j) = '/'
         end if
         np = np + 1
         starts(np) = j + 1
         parts_buf(j + 1:j + len(part)) = part
         j = j + len(part)
      end do
      if (absolute) then
         r = '/'//parts_buf(1:j)
      else if (j == 0) then
         r = '.'
      else
         r = parts_buf(1:j)
      end if
   end function normalize_path

   !> Folder part of a path including the trailing '/', '' for a bare file name.
   pure function directory_of(path) result(d)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: d
      integer :: k
      k = index(path, '/', back=.true.)
      d = path(1:k)
   end function directory_of
end module vemcontact_deck_source
