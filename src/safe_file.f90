!> Safe result files: the Fortran side of src/safe_file_shim.c.
!>
!> A `safe_file_t` is written to a uniquely named temporary in the folder of its
!> final name (created with O_EXCL|O_NOFOLLOW, so a planted link or file is never
!> followed or overwritten), through checked write(2) calls; `commit` fsyncs,
!> checks the close and renames it into place.  A failure names the file and the
!> system's reason ("No space left on device") and leaves no temporary behind.
!> gfortran's own I/O is not used for results: it reports success when the disk
!> fills up inside its buffers or at CLOSE.
!>
!> Also here: the lock that makes a job's results folder single-writer
!> (`job_lock_t`), the removal of a previous run's files of a job, and the
!> primitives that the run log and the HDF5 writer use.
!> This module is an interop spot (C descriptors and errno values).
module vemcontact_safe_file
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_int64_t, c_null_char
   use vemcontact_kinds, only: i8
   use vemcontact_error, only: error_t, fatal_error, err_io
   implicit none
   private

   public :: safe_file_t, job_lock_t, lock_job, remove_job_files, create_temporary, publish_file, &
             remove_file, open_fresh, write_bytes, close_synced, io_reason

   !> Bytes collected before a write(2): small pieces (XML tags, CSV lines) are
   !> joined, large ones (base64 pieces of several MiB) go straight through.
   integer(i8), parameter :: buffer_bytes = 1048576_i8

   !> A result file being written: `open`, any number of `write`, then `commit`
   !> (or `discard`).  After a failed write further writes are skipped and
   !> `commit` reports the first failure.
   type :: safe_file_t
      private
      integer(c_int) :: fd = -1
      integer(c_int) :: errno = 0
      character(len=:), allocatable :: path, tmp, buf
      integer(i8) :: nbuf = 0
   contains
      procedure :: open => sf_open
      procedure :: write => sf_write
      procedure :: failed => sf_failed
      procedure :: commit => sf_commit
      procedure :: discard => sf_discard
   end type safe_file_t

   !> The lock of one job's results in one folder (flock on JOB.lock), held
   !> until `release` or the end of the process.
   type :: job_lock_t
      private
      integer(c_int) :: fd = -1
   contains
      procedure :: release => lock_release
   end type job_lock_t

   interface
      function c_create(final_path, fd, tmp, tmplen) bind(C, name='vc_sf_create') result(rc)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: final_path(*)
         integer(c_int), intent(out) :: fd
         character(kind=c_char), intent(out) :: tmp(*)
         integer(c_int), value :: tmplen
         integer(c_int) :: rc
      end function c_create
      function c_write(fd, buf, n) bind(C, name='vc_sf_write') result(rc)
         import :: c_char, c_int, c_int64_t
         integer(c_int), value :: fd
         character(kind=c_char), intent(in) :: buf(*)
         integer(c_int64_t), value :: n
         integer(c_int) :: rc
      end function c_write
      function c_close(fd) bind(C, name='vc_sf_close') result(rc)
         import :: c_int
         integer(c_int), value :: fd
         integer(c_int) :: rc
      end function c_close
      function c_rename(tmp, final_path) bind(C, name='vc_sf_rename') result(rc)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: tmp(*), final_path(*)
         integer(c_int) :: rc
      end function c_rename
      function c_sync_path(path) bind(C, name='vc_sf_sync_path') result(rc)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: rc
      end function c_sync_path
      function c_unlink(path) bind(C, name='vc_sf_unlink') result(rc)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: rc
      end function c_unlink
      function c_create_fresh(path, fd) bind(C, name='vc_sf_create_fresh') result(rc)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), intent(out) :: fd
         integer(c_int) :: rc
      end function c_create_fresh
      function c_lock(path, fd) bind(C, name='vc_sf_lock') result(rc)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), intent(out) :: fd
         integer(c_int) :: rc
      end function c_lock
      subroutine c_unlock(fd) bind(C, name='vc_sf_unlock')
         import :: c_int
         integer(c_int), value :: fd
      end subroutine c_unlock
      function c_remove_job_files(dir, job, nremoved, bad, badlen) bind(C, name='vc_sf_remove_job_files') result(rc)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: dir(*), job(*)
         integer(c_int), intent(out) :: nremoved
         character(kind=c_char), intent(out) :: bad(*)
         integer(c_int), value :: badlen
         integer(c_int) :: rc
      end function c_remove_job_files
      subroutine c_strerror(err, buf, len) bind(C, name='vc_sf_strerror')
         import :: c_char, c_int
         integer(c_int), value :: err
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_int), value :: len
      end subroutine c_strerror
   end interface

contains

   !> Start writing `path`: a new temporary beside it.
   subroutine sf_open(self, path, error)
      class(safe_file_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: error
      if (self%fd >= 0) call self%discard()
      self%path = path
      self%errno = 0
      self%nbuf = 0
      call create_temporary_fd(path, self%fd, self%tmp, error)
      if (allocated(error)) return
      if (.not. allocated(self%buf)) allocate (character(len=buffer_bytes) :: self%buf)
   end subroutine sf_open

   !> Append `text` (skipped after an earlier failure).
   subroutine sf_write(self, text)
      class(safe_file_t), intent(inout) :: self
      character(len=*), intent(in) :: text
      integer(i8) :: n
      if (self%fd < 0 .or. self%errno /= 0) return
      n = len(text, kind=i8)
      if (self%nbuf + n > buffer_bytes) call flush_buffer(self)
      if (self%errno /= 0) return
      if (n >= buffer_bytes) then
         self%errno = c_write(self%fd, text, int(n, c_int64_t))
      else if (n > 0) then
         self%buf(self%nbuf + 1:self%nbuf + n) = text
         self%nbuf = self%nbuf + n
      end if
   end subroutine sf_write

   subroutine flush_buffer(self)
      type(safe_file_t), intent(inout) :: self
      if (self%nbuf > 0 .and. self%errno == 0) &
         self%errno = c_write(self%fd, self%buf(1:self%nbuf), int(self%nbuf, c_int64_t))
      self%nbuf = 0
   end subroutine flush_buffer

   !> True after a write failed (or when the file is not open).
   pure logical function sf_failed(self)
      class(safe_file_t), intent(in) :: self
      sf_failed = self%fd < 0 .or. self%errno /= 0
   end function sf_failed

   !> Finish the file: write what is buffered, fsync, close and rename it to its
   !> final name.  On any failure the temporary is removed and `error` names the
   !> final file and the reason.
   subroutine sf_commit(self, error)
      class(safe_file_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: rc
      if (self%fd < 0) then
         call fatal_error(error, 'error: cannot write '''//self%path//''': it is not open', err_io)
         return
      end if
      call flush_buffer(self)
      if (self%errno /= 0) then
         rc = self%errno
         call self%discard()
         call fatal_error(error, 'error: cannot write '''//self%path//''': '//io_reason(rc), err_io)
         return
      end if
      rc = c_close(self%fd)
      self%fd = -1
      if (rc /= 0) then
         call remove_file(self%tmp)
         call fatal_error(error, 'error: cannot write '''//self%path//''': '//io_reason(rc), err_io)
         return
      end if
      call publish_file(self%tmp, self%path, error)
   end subroutine sf_commit

   !> Abandon the file: close and remove the temporary; the final name is untouched.
   subroutine sf_discard(self)
      class(safe_file_t), intent(inout) :: self
      integer(c_int) :: rc
      if (self%fd < 0) return
      rc = c_close(self%fd)
      self%fd = -1
      call remove_file(self%tmp)
   end subroutine sf_discard

   !> A new temporary file beside `path`, created and closed: for a library
   !> (HDF5) that opens the file itself.  Publish it with `publish_file`.
   subroutine create_temporary(path, tmp, error)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: tmp
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: fd, rc
      call create_temporary_fd(path, fd, tmp, error)
      if (allocated(error)) return
      rc = c_close(fd)
      if (rc /= 0) then
         call remove_file(tmp)
         call fatal_error(error, 'error: cannot write '''//path//''': '//io_reason(rc), err_io)
      end if
   end subroutine create_temporary

   subroutine create_temporary_fd(path, fd, tmp, error)
      character(len=*), intent(in) :: path
      integer(c_int), intent(out) :: fd
      character(len=:), allocatable, intent(out) :: tmp
      type(error_t), allocatable, intent(out) :: error
      character(kind=c_char, len=:), allocatable :: name
      integer(c_int) :: rc
      integer :: n
      allocate (character(len=len(path) + 64) :: name)
      rc = c_create(path//c_null_char, fd, name, int(len(name), c_int))
      if (rc /= 0) then
         fd = -1
         tmp = ''
         call fatal_error(error, 'error: cannot create a file beside '''//path//''': '//io_reason(rc), err_io)
         return
      end if
      n = index(name, c_null_char) - 1
      tmp = name(1:n)
   end subroutine create_temporary_fd

   !> fsync the closed file `tmp` and rename it to `path`; on failure `tmp` is removed.
   subroutine publish_file(tmp, path, error)
      character(len=*), intent(in) :: tmp, path
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: rc
      rc = c_sync_path(tmp//c_null_char)
      if (rc /= 0) then
         call remove_file(tmp)
         call fatal_error(error, 'error: cannot write '''//path//''': '//io_reason(rc), err_io)
         return
      end if
      rc = c_rename(tmp//c_null_char, path//c_null_char)
      if (rc /= 0) then
         call remove_file(tmp)
         call fatal_error(error, 'error: cannot put the results under the name '''//path//''': '// &
                          io_reason(rc), err_io)
      end if
   end subroutine publish_file

   !> Remove a file (a link itself, not its target); a missing file is fine and
   !> a failure is ignored (used for clean-up after another error).
   subroutine remove_file(path)
      character(len=*), intent(in) :: path
      integer(c_int) :: rc
      rc = c_unlink(path//c_null_char)
   end subroutine remove_file

   !> Create `path` afresh for appending (a file or link of that name is removed,
   !> never followed) and return its descriptor.
   subroutine open_fresh(path, fd, error)
      character(len=*), intent(in) :: path
      integer, intent(out) :: fd
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: cfd, rc
      rc = c_create_fresh(path//c_null_char, cfd)
      fd = int(cfd)
      if (rc /= 0) call fatal_error(error, 'error: cannot write '''//path//''': '//io_reason(rc), err_io)
   end subroutine open_fresh

   !> Write all of `text` to descriptor `fd`: 0 or the errno of the failure.
   integer function write_bytes(fd, text) result(errno)
      integer, intent(in) :: fd
      character(len=*), intent(in) :: text
      errno = int(c_write(int(fd, c_int), text, int(len(text), c_int64_t)))
   end function write_bytes

   !> fsync and close descriptor `fd`: 0 or the errno of the failure.
   integer function close_synced(fd) result(errno)
      integer, intent(in) :: fd
      errno = int(c_close(int(fd, c_int)))
   end function close_synced

   !> Take the lock `path` (JOB.lock in the results folder) without waiting.
   !> Held by another process: an error saying so (exit status 2).
   subroutine lock_job(path, lock, error)
      character(len=*), intent(in) :: path
      type(job_lock_t), intent(inout) :: lock
      type(error_t), allocatable, intent(out) :: error
      integer(c_int) :: rc
      rc = c_lock(path//c_null_char, lock%fd)
      if (rc == -1_c_int) then
         call fatal_error(error, 'error: another vemcontact run is writing these results (it holds '''// &
                          path//'''); nothing was changed: wait for it to finish or choose another '// &
                          'output folder with -o', err_io)
      else if (rc /= 0) then
         call fatal_error(error, 'error: cannot lock '''//path//''': '//io_reason(rc), err_io)
      end if
   end subroutine lock_job

   subroutine lock_release(self)
      class(job_lock_t), intent(inout) :: self
      call c_unlock(self%fd)
      self%fd = -1
   end subroutine lock_release

   !> Remove the result files of `job` in folder `dir` left by an earlier run
   !> (JOB.pvd, JOB.h5, JOB.mtx, JOB_NNNN.vtu, JOB_contact_NNNN.vtu, the increments'
   !> JOB_NNNN_MMMM.vtu and JOB_contact_NNNN_MMMM.vtu,
   !> JOB_contact_pairK_NNNN.csv, JOB_print_NNNN.csv, JOB_srm_NNNN.csv, JOB_phases.csv and
   !> temporaries of them), so that none can be taken for this run's.  `nremoved` counts them.
   subroutine remove_job_files(dir, job, nremoved, error)
      character(len=*), intent(in) :: dir, job
      integer, intent(out) :: nremoved
      type(error_t), allocatable, intent(out) :: error
      character(kind=c_char, len=1024) :: bad
      integer(c_int) :: rc, n
      rc = c_remove_job_files(dir//c_null_char, job//c_null_char, n, bad, int(len(bad), c_int))
      nremoved = int(n)
      if (rc /= 0) call fatal_error(error, 'error: cannot remove the earlier results '''//dir//'/'// &
                                    bad(1:max(0, index(bad, c_null_char) - 1))//''': '//io_reason(rc), err_io)
   end subroutine remove_job_files

   !> The system's text for an errno value.
   function io_reason(errno) result(s)
      integer, intent(in) :: errno
      character(len=:), allocatable :: s
      character(kind=c_char, len=256) :: buf
      call c_strerror(int(errno, c_int), buf, int(len(buf), c_int))
      s = buf(1:max(0, index(buf, c_null_char) - 1))
   end function io_reason
end module vemcontact_safe_file
