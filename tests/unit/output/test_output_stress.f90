!> Principal and von Mises stresses on hand-computed states, and nodal
!> averaging on a two-element mesh with an unconnected node.
program test_output_stress
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_testing, only: checker_t
   use vemcontact_model, only: model_t
   use vemcontact_post_stress, only: nodal_average, principal_stresses
   implicit none
   type(checker_t) :: t
   ! a few ulps: each result is a handful of roundings of O(1) numbers
   real(wp), parameter :: rtol = 1.0e-14_wp
   real(wp), parameter :: sig = 250.0_wp, tau = 40.0_wp, nu = 0.3_wp
   real(wp), parameter :: pi = 4.0_wp*atan(1.0_wp)
   real(wp) :: s1, s3, vm, th, c, s
   real(wp) :: s_elem(4, 2), s_node(4, 7)
   type(model_t) :: model
   integer :: k

   ! uniaxial tension along x
   call principal_stresses([sig, 0.0_wp, 0.0_wp, 0.0_wp], s1, s3, vm)
   call t%close(s1, sig, rtol, 'uniaxial x: s1')
   call t%close(s3, 0.0_wp, rtol, 'uniaxial x: s3', atol=rtol*sig)
   call t%close(vm, sig, rtol, 'uniaxial x: mises')
   ! uniaxial compression along y
   call principal_stresses([0.0_wp, -sig, 0.0_wp, 0.0_wp], s1, s3, vm)
   call t%close(s1, 0.0_wp, rtol, 'uniaxial -y: s1', atol=rtol*sig)
   call t%close(s3, -sig, rtol, 'uniaxial -y: s3')
   call t%close(vm, sig, rtol, 'uniaxial -y: mises')
   ! pure shear: s1 = tau, s3 = -tau, mises = sqrt(3) tau
   call principal_stresses([0.0_wp, 0.0_wp, 0.0_wp, tau], s1, s3, vm)
   call t%close(s1, tau, rtol, 'pure shear: s1')
   call t%close(s3, -tau, rtol, 'pure shear: s3')
   call t%close(vm, sqrt(3.0_wp)*tau, rtol, 'pure shear: mises')
   ! uniaxial tension along a direction at 30 degrees: same invariants
   th = pi/6.0_wp
   c = cos(th)
   s = sin(th)
   call principal_stresses([sig*c*c, sig*s*s, 0.0_wp, sig*s*c], s1, s3, vm)
   call t%close(s1, sig, rtol, 'rotated uniaxial: s1')
   call t%close(s3, 0.0_wp, rtol, 'rotated uniaxial: s3', atol=4.0_wp*epsilon(1.0_wp)*sig)
   call t%close(vm, sig, rtol, 'rotated uniaxial: mises')
   ! plane strain uniaxial: szz = nu sxx enters mises, not s1/s3:
   ! mises = sig sqrt(((1)^2 + nu^2 + (nu-1)^2)/2) = sig sqrt(1 - nu + nu^2)
   call principal_stresses([sig, 0.0_wp, nu*sig, 0.0_wp], s1, s3, vm)
   call t%close(s1, sig, rtol, 'plane strain: s1')
   call t%close(s3, 0.0_wp, rtol, 'plane strain: s3', atol=rtol*sig)
   call t%close(vm, sig*sqrt(1.0_wp - nu + nu*nu), rtol, 'plane strain: mises')
   ! extreme magnitudes: the squares would overflow (1e200) or underflow (1e-200)
   call principal_stresses([0.0_wp, 0.0_wp, 0.0_wp, 1.0e200_wp], s1, s3, vm)
   call t%close(vm, sqrt(3.0_wp)*1.0e200_wp, rtol, 'pure shear 1e200: mises')
   call t%close(s1, 1.0e200_wp, rtol, 'pure shear 1e200: s1')
   call principal_stresses([1.0e-200_wp, 0.0_wp, 0.0_wp, 0.0_wp], s1, s3, vm)
   call t%close(vm, 1.0e-200_wp, rtol, 'uniaxial 1e-200: mises')
   ! hydrostatic: no deviator
   call principal_stresses([-sig, -sig, -sig, 0.0_wp], s1, s3, vm)
   call t%close(s1, -sig, rtol, 'hydrostatic: s1')
   call t%close(s3, -sig, rtol, 'hydrostatic: s3')
   call t%close(vm, 0.0_wp, rtol, 'hydrostatic: mises', atol=rtol*sig)
   ! s1 >= s3 and s1 + s3 = sxx + syy for general states
   do k = 1, 20
      th = real(k, wp)
      call principal_stresses([sig*sin(th), tau*cos(3.0_wp*th), nu*sig, tau*sin(7.0_wp*th)], &
                              s1, s3, vm)
      call t%check(s1 >= s3, 'general state: s1 >= s3')
      call t%close(s1 + s3, sig*sin(th) + tau*cos(3.0_wp*th), rtol, 'general state: trace', &
                   atol=rtol*sig)
   end do

   ! nodal average: two quads 1-2-5-4 and 2-3-6-5 side by side, node 7 unused
   model%nnode = 7
   model%nelem = 2
   model%elem_ptr = [1_ip, 5_ip, 9_ip]
   model%elem_conn = [1_ip, 2_ip, 5_ip, 4_ip, 2_ip, 3_ip, 6_ip, 5_ip]
   s_elem(:, 1) = [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp]
   s_elem(:, 2) = [5.0_wp, 6.0_wp, 7.0_wp, 8.0_wp]
   s_node = -1.0_wp
   call nodal_average(model, s_elem, s_node)
   ! exact: sums and halves of small integers
   call t%check(same_bits(s_node(:, 1), s_elem(:, 1)), 'node 1: element 1 only')
   call t%check(same_bits(s_node(:, 4), s_elem(:, 1)), 'node 4: element 1 only')
   call t%check(same_bits(s_node(:, 3), s_elem(:, 2)), 'node 3: element 2 only')
   call t%check(same_bits(s_node(:, 6), s_elem(:, 2)), 'node 6: element 2 only')
   call t%check(same_bits(s_node(:, 2), [3.0_wp, 4.0_wp, 5.0_wp, 6.0_wp]), 'node 2: mean of both')
   call t%check(same_bits(s_node(:, 5), [3.0_wp, 4.0_wp, 5.0_wp, 6.0_wp]), 'node 5: mean of both')
   call t%check(same_bits(s_node(:, 7), [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]), 'node 7: in no element, zero')

   call t%finish()

contains

   !> Bit-identical arrays: the averages here are exact in binary floating point.
   pure logical function same_bits(a, b)
      real(wp), intent(in) :: a(:), b(:)
      same_bits = size(a) == size(b)
      if (same_bits) same_bits = all(transfer(a, [0_i8]) == transfer(b, [0_i8]))
   end function same_bits
end program test_output_stress
