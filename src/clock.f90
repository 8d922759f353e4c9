!> Wall-clock time for phase timings: what the user waits for, not CPU time.
module vemcontact_clock
   use vemcontact_kinds, only: wp, i8
   implicit none
   private

   public :: wall_time

contains

   !> Seconds since an arbitrary origin.
   function wall_time() result(t)
      real(wp) :: t
      integer(i8) :: count, rate
      call system_clock(count, rate)
      t = real(count, wp)/real(rate, wp)
   end function wall_time
end module vemcontact_clock
