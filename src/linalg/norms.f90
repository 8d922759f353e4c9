!> Vector norms safe at any scale the numbers can represent.
module vemcontact_linalg_norms
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: safe_norm2

contains

   !> The 2-norm without under- or overflow of the squares: gfortran's norm2 returns 0
   !> for entries of 1e-200 (forces of a model in units that small,
   !> docs/stability-contact.md).  Infinite or NaN entries give an infinite or NaN norm.
   pure real(wp) function safe_norm2(x) result(nrm)
      real(wp), intent(in) :: x(:)
      real(wp) :: s
      nrm = 0.0_wp
      if (size(x) == 0) return
      s = maxval(abs(x))
      if (s > 0.0_wp .and. s <= huge(1.0_wp)) then
         nrm = s*norm2(x/s)
      else if (.not. s <= huge(1.0_wp)) then
         nrm = s
      end if
   end function safe_norm2
end module vemcontact_linalg_norms
