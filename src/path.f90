!> File-path helpers shared by the command line and the output writers.
module vemcontact_path
   implicit none
   private

   public :: dirname

contains

   !> Folder part of `path`: '' when there is no '/', '/' for a file in the root.
   pure function dirname(path) result(d)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: d
      integer :: k
      k = index(path, '/', back=.true.)
      if (k == 0) then
         d = ''
      else if (k == 1) then
         d = '/'
      else
         d = path(1:k - 1)
      end if
   end function dirname
end module vemcontact_path
