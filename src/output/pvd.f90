!> ParaView collection (.pvd) of the .vtu files of the steps written so far.
!> The driver rewrites it as the steps complete (pvd_rewrite_due), at the end of the
!> run and when it stops with an error, through `safe_file_t` (a unique temporary,
!> checked writes, fsync, atomic rename), so a run that stops part way leaves a valid
!> collection of completed steps.  File names are stored relative to the .pvd's folder so that
!> the result folder can be moved or copied as a whole.
module vemcontact_output_pvd
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t, fatal_error, err_internal
   use vemcontact_model, only: string_t
   use vemcontact_safe_file, only: safe_file_t
   use vemcontact_path, only: dirname
   use vemcontact_output_xml, only: xml_escape
   implicit none
   private

   public :: write_pvd, relative_path, pvd_list_t, pvd_rewrite_due

   !> The entries of a collection as the run adds them (amortised O(1) per entry).
   type :: pvd_list_t
      type(string_t), allocatable :: files(:)
      real(wp), allocatable :: times(:)
      integer, allocatable :: parts(:)
      integer :: n = 0
   contains
      procedure :: add => pvd_add
      procedure :: write => pvd_list_write
   end type pvd_list_t

contains

   !> Whether the driver rewrites the .pvd after its `n`-th completed step: when n is
   !> a power of two (1, 2, 4, ...).  Each rewrite costs O(n), so a run of N steps
   !> writes fewer than 2N entries in all (linear, where a rewrite after every step
   !> costs N^2/2); the driver also writes it when the run ends or stops with an
   !> error, so only a killed run leaves a .pvd that lists fewer steps (at least half
   !> of the completed ones) than the .vtu files on disk.
   pure logical function pvd_rewrite_due(n)
      integer, intent(in) :: n
      pvd_rewrite_due = n > 0 .and. iand(n, n - 1) == 0
   end function pvd_rewrite_due

   !> Append a file with its time and ParaView part.
   subroutine pvd_add(self, file, time, part)
      class(pvd_list_t), intent(inout) :: self
      character(len=*), intent(in) :: file
      real(wp), intent(in) :: time
      integer, intent(in) :: part
      type(string_t), allocatable :: f(:)
      real(wp), allocatable :: t(:)
      integer, allocatable :: p(:)
      integer :: cap
      if (.not. allocated(self%files)) allocate (self%files(16), self%times(16), self%parts(16))
      if (self%n == size(self%files)) then
         cap = 2*size(self%files)
         allocate (f(cap), t(cap), p(cap))
         f(:self%n) = self%files(:self%n)
         t(:self%n) = self%times(:self%n)
         p(:self%n) = self%parts(:self%n)
         call move_alloc(f, self%files)
         call move_alloc(t, self%times)
         call move_alloc(p, self%parts)
      end if
      self%n = self%n + 1
      self%files(self%n)%s = file
      self%times(self%n) = time
      self%parts(self%n) = part
   end subroutine pvd_add

   !> Write the collection of the entries added so far to `path` (write_pvd).
   subroutine pvd_list_write(self, path, error)
      class(pvd_list_t), intent(in) :: self
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: error
      if (.not. allocated(self%files)) then
         call write_pvd(path, [string_t ::], [real(wp) ::], error, [integer ::])
      else
         call write_pvd(path, self%files(:self%n), self%times(:self%n), error, self%parts(:self%n))
      end if
   end subroutine pvd_list_write

   !> Write the collection `path` with one DataSet per entry of `files` at `times`.
   !> `files` are paths as the program uses them (absolute, or relative to the
   !> working directory like `path`); they are converted to paths relative to
   !> the folder of `path`.
   subroutine write_pvd(path, files, times, error, parts)
      character(len=*), intent(in) :: path
      type(string_t), intent(in) :: files(:)
      real(wp), intent(in) :: times(:)
      type(error_t), allocatable, intent(out) :: error
      !> ParaView part of each file (default 0): the mesh is part 0, contact points part 1
      integer, intent(in), optional :: parts(:)
      character(len=12) :: pbuf
      character(len=:), allocatable :: dir, rel
      character(len=32) :: tbuf
      character(len=1), parameter :: nl = new_line('a')
      type(safe_file_t) :: out
      integer :: k
      logical :: ok

      if (size(files) /= size(times)) then
         call fatal_error(error, 'write_pvd: files and times differ in length ('//path//')', &
                          err_internal)
         return
      end if
      dir = dirname(path)
      call out%open(path, error)
      if (allocated(error)) return
      call out%write('<?xml version="1.0"?>'//nl &
                     //'<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">'//nl &
                     //'<Collection>'//nl)
      ! one write per entry: the cost is linear in the number of entries
      do k = 1, size(files)
         call relative_path(files(k)%s, dir, rel, ok)
         if (.not. ok) then
            call fatal_error(error, 'write_pvd: cannot express '''//files(k)%s &
                             //''' relative to the folder of '''//path//'''', err_internal)
            call out%discard()
            return
         end if
         ! 17 significant digits: the time reads back as the same double
         write (tbuf, '(es24.16e3)') times(k)
         pbuf = '0'
         if (present(parts)) write (pbuf, '(i0)') parts(k)
         call out%write('<DataSet timestep="'//trim(adjustl(tbuf))//'" group="" part="'//trim(pbuf)//'" file="' &
                        //xml_escape(rel)//'"/>'//nl)
      end do
      call out%write('</Collection>'//nl//'</VTKFile>'//nl)
      call out%commit(error)
   end subroutine write_pvd

   !> `file` expressed relative to the folder `dir`, lexically ('.' and '..'
   !> resolved, no file system access).  Both absolute or both relative (to the
   !> same working directory) works; an absolute `file` with a relative `dir` is
   !> returned unchanged (valid from anywhere).  `ok` is false when the answer
   !> needs names the paths do not contain: relative `file` with absolute `dir`,
   !> or `dir` climbing above the common part with '..'.
   pure subroutine relative_path(file, dir, rel, ok)
      character(len=*), intent(in) :: file, dir
      character(len=:), allocatable, intent(out) :: rel
      logical, intent(out) :: ok
      type(string_t), allocatable :: fc(:), dc(:)
      logical :: fabs, dabs
      integer :: c, k
      fabs = is_absolute(file)
      dabs = is_absolute(dir)
      ok = .true.
      if (fabs .and. .not. dabs) then
         rel = file
         return
      end if
      if (dabs .and. .not. fabs) then
         ok = .false.
         rel = file
         return
      end if
      call split_path(file, fabs, fc)
      call split_path(dir, dabs, dc)
      c = 0
      do while (c < min(size(fc) - 1, size(dc)))
         if (fc(c + 1)%s /= dc(c + 1)%s) exit
         c = c + 1
      end do
      rel = ''
      do k = c + 1, size(dc)
         if (dc(k)%s == '..') then
            ok = .false.
            rel = file
            return
         end if
         rel = rel//'../'
      end do
      do k = c + 1, size(fc)
         rel = rel//fc(k)%s
         if (k < size(fc)) rel = rel//'/'
      end do
   end subroutine relative_path

   pure logical function is_absolute(path)
      character(len=*), intent(in) :: path
      is_absolute = .false.
      if (len(path) > 0) is_absolute = path(1:1) == '/'
   end function is_absolute

   !> Folder part of a path ('' for a bare file name).

   !> Components of a path with '', '.' and resolvable '..' removed; leading
   !> '..' of a relative path are kept, '..' at the root of an absolute one dropped.
   pure subroutine split_path(path, absolute, comps)
      character(len=*), intent(in) :: path
      logical, intent(in) :: absolute
      type(string_t), allocatable, intent(out) :: comps(:)
      type(string_t), allocatable :: work(:)
      integer :: i, j, n
      allocate (work(len(path) + 1))
      n = 0
      i = 1
      do while (i <= len(path))
         j = index(path(i:), '/')
         if (j == 0) then
            j = len(path) + 1
         else
            j = i + j - 1
         end if
         if (j > i) then
            if (path(i:j - 1) == '..') then
               if (n > 0) then
                  if (work(n)%s /= '..') then
                     n = n - 1
                  else
                     n = n + 1
                     work(n)%s = '..'
                  end if
               else if (.not. absolute) then
                  n = n + 1
                  work(n)%s = '..'
               end if
            else if (path(i:j - 1) /= '.') then
               n = n + 1
               work(n)%s = path(i:j - 1)
            end if
         end if
         i = j + 1
      end do
      comps = work(1:n)
   end subroutine split_path
end module vemcontact_output_pvd
