!> Consistent nodal weights of Abaqus-style hydrostatic pressure (HP) on a side:
!> exact closed form for a fully wet side, and against brute-force quadrature for
!> sides that cross the free surface, lie above it, or run downwards.
program test_hydrostatic
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: dload_t, dload_hydrostatic
   use vemcontact_driver_assembly, only: hydrostatic_moments
   implicit none
   type(checker_t) :: t
   type(dload_t) :: load
   real(wp) :: wa, wb, ra, rb
   real(wp), parameter :: gw = 9810.0_wp

   ! water to y = 15, pressure gw*5 at y = 10 (the dam face of the paper's example 4)
   load = dload_t(1, dload_hydrostatic, 1, gw*5.0_wp, [15.0_wp, 10.0_wp])
   ! side from y = 10 up to y = 15: p(s) = p0 (1 - s): wa = p0/3, wb = p0/6
   call hydrostatic_moments(load, 10.0_wp, 15.0_wp, wa, wb)
   call t%close(wa, gw*5.0_wp/3.0_wp, 1.0e-14_wp, 'wet side, lower node')
   call t%close(wb, gw*5.0_wp/6.0_wp, 1.0e-14_wp, 'wet side, upper node')
   ! the same side run downwards swaps the weights
   call hydrostatic_moments(load, 15.0_wp, 10.0_wp, wa, wb)
   call t%close(wa, gw*5.0_wp/6.0_wp, 1.0e-14_wp, 'downward side, upper node')
   ! crossing the free surface, above it, below it: against quadrature
   call check(load, 12.0_wp, 17.0_wp, 'side crossing the free surface upwards')
   call check(load, 17.0_wp, 12.0_wp, 'side crossing the free surface downwards')
   call check(load, 16.0_wp, 18.0_wp, 'dry side')
   call check(load, 3.0_wp, 3.0_wp, 'horizontal wet side')
   call hydrostatic_moments(load, 16.0_wp, 18.0_wp, wa, wb)
   call t%close(abs(wa) + abs(wb), 0.0_wp, 0.0_wp, 'dry side carries nothing', atol=0.0_wp)
   ! negative magnitude (suction side convention) is still linear in y and clipped
   load%magnitude = -load%magnitude
   call check(load, 12.0_wp, 17.0_wp, 'negative magnitude')
   call t%finish()
contains
   subroutine check(ld, ya, yb, what)
      type(dload_t), intent(in) :: ld
      real(wp), intent(in) :: ya, yb
      character(len=*), intent(in) :: what
      integer, parameter :: m = 200000
      integer :: i
      real(wp) :: s, p, y
      call hydrostatic_moments(ld, ya, yb, wa, wb)
      ra = 0; rb = 0
      do i = 1, m                      ! midpoint rule: error O(1/m^2) away from the kink
         s = (i - 0.5_wp)/m
         y = ya + s*(yb - ya)
         p = ld%magnitude*(ld%dir(1) - y)/(ld%dir(1) - ld%dir(2))
         if (p*sign(1.0_wp, ld%magnitude) < 0.0_wp) p = 0.0_wp
         ra = ra + p*(1 - s)/m
         rb = rb + p*s/m
      end do
      ! the kink at the free surface costs the midpoint rule O(1/m) of one cell: 1e-5 relative
      call t%close(wa, ra, 1.0e-5_wp, what//': lower weight', atol=1.0e-9_wp*abs(ld%magnitude))
      call t%close(wb, rb, 1.0e-5_wp, what//': upper weight', atol=1.0e-9_wp*abs(ld%magnitude))
   end subroutine check
end program test_hydrostatic
