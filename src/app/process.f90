!> Interop with the C library for ending the process with a status code: Fortran's
!> `stop code` prints "STOP code", which would clutter the one clear message we give.
module vemcontact_app_process
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
   use vemcontact_error, only: error_t, fatal_error, err_io
   implicit none
   private

   public :: exit_process, make_directory, pause_seconds

   interface
      subroutine c_exit(status) bind(C, name='exit')
         import :: c_int
         integer(c_int), value :: status
      end subroutine c_exit
      subroutine c_exit_now(status) bind(C, name='_exit')
         import :: c_int
         integer(c_int), value :: status
      end subroutine c_exit_now
      function c_sleep(seconds) result(left) bind(C, name='sleep')
         import :: c_int
         integer(c_int), value :: seconds
         integer(c_int) :: left
      end function c_sleep
      function c_mkdir(path, mode) result(rc) bind(C, name='mkdir')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: mode
         integer(c_int) :: rc
      end function c_mkdir
   end interface

contains

   !> Flush Fortran units and end the process with `status`.  With `now`, the exit
   !> handlers of the libraries are skipped (_exit): after an error, HDF5's handler
   !> would try again to flush a results file whose writing failed (a full disk) and
   !> can crash doing so; everything the program keeps is closed before it ends.
   subroutine exit_process(status, now)
      integer, intent(in) :: status
      logical, intent(in), optional :: now
      flush (6)
      flush (0)
      if (present(now)) then
         if (now) call c_exit_now(int(status, c_int))
      end if
      call c_exit(int(status, c_int))
   end subroutine exit_process

   !> Wait `seconds` (or until a signal ends the process).
   subroutine pause_seconds(seconds)
      integer, intent(in) :: seconds
      integer(c_int) :: left
      left = c_sleep(int(seconds, c_int))
   end subroutine pause_seconds

   !> Create a folder and its parents (like mkdir -p); existing folders are fine.
   subroutine make_directory(path, error)
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: error
      integer :: k, rc
      logical :: exists
      do k = 2, len(path) + 1
         if (k <= len(path)) then
            if (path(k:k) /= '/') cycle
         end if
         ! 493 = octal 755; an already existing folder makes mkdir fail harmlessly
         rc = c_mkdir(path(:k - 1)//c_null_char, 493_c_int)
      end do
      inquire (file=path//'/.', exist=exists)
      if (.not. exists) call fatal_error(error, 'error: cannot create the output folder '//path, err_io)
   end subroutine make_directory
end module vemcontact_app_process
