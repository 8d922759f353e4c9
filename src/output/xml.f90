!> XML text helpers shared by the VTK writers.
module vemcontact_output_xml
   implicit none
   private

   public :: xml_escape

contains

   !> Escape the five XML special characters for use in an attribute value.
   pure function xml_escape(s) result(e)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: e
      integer :: k
      e = ''
      do k = 1, len(s)
         select case (s(k:k))
         case ('&')
            e = e//'&amp;'
         case ('<')
            e = e//'&lt;'
         case ('>')
            e = e//'&gt;'
         case ('"')
            e = e//'&quot;'
         case ('''')
            e = e//'&apos;'
         case default
            e = e//s(k:k)
         end select
      end do
   end function xml_escape
end module vemcontact_output_xml
