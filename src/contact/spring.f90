!> A closed contact spring seen as a support between the parts it joins: the
!> floating-part check (vemcontact_driver_supports) counts closed springs as
!> supports, so that a body held only by contact is not reported as floating.
module vemcontact_contact_spring
   use vemcontact_kinds, only: wp, ip
   implicit none
   private

   public :: spring_t

   !> A closed contact spring: where it acts, its normal, and the parts it joins.
   type :: spring_t
      real(wp) :: x(2) = 0.0_wp
      real(wp) :: normal(2) = 0.0_wp
      integer(ip) :: part_slave = 0
      integer(ip) :: part_master = 0
   end type spring_t
end module vemcontact_contact_spring
