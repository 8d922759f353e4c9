!> The order of the error estimate's summary (vemcontact_post_estimate's
!> descending_order, a radix sort on the bit patterns of the non-negative values):
!> against a sort by comparisons written here, on values over 600 orders of
!> magnitude with zeros, subnormals, infinity and ties.
program test_post_descending_order
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_post_estimate, only: descending_order
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
   implicit none
   type(checker_t) :: t
   real(wp), allocatable :: w(:)
   integer(ip), allocatable :: idx(:), ref(:)
   real(wp) :: u
   integer :: i, n

   n = 5000
   allocate (w(n))
   do i = 1, n
      call random_number(u)
      w(i) = 10.0_wp**(600.0_wp*u - 300.0_wp)
   end do
   w(1:n:97) = 0.0_wp                      ! zeros
   w(2:n:89) = 1.0e-310_wp                 ! subnormals
   w(3:n:83) = w(3)                        ! a tie of many
   w(4) = ieee_value(1.0_wp, ieee_positive_inf)
   idx = descending_order(w)
   ref = insertion_order(w)
   call t%equal(size(idx), n, 'one index per value')
   call t%check(all(idx == ref), 'the same order as a comparison sort (ties in index order)')
   call t%check(all(w(idx(1:n - 1)) >= w(idx(2:n))), 'descending')
   call t%equal(int(idx(1)), 4, 'infinity first')
   idx = descending_order([real(wp) ::])
   call t%equal(size(idx), 0, 'empty')
   idx = descending_order([2.0_wp, 2.0_wp, 3.0_wp, 0.0_wp])
   call t%check(all(idx == [3, 1, 2, 4]), 'small case with a tie')
   call t%finish()
contains
   !> Stable insertion sort by decreasing value: the reference.
   pure function insertion_order(v) result(o)
      real(wp), intent(in) :: v(:)
      integer(ip), allocatable :: o(:)
      integer(ip) :: i, j, x
      o = [(i, i=1, size(v, kind=ip))]
      do i = 2, size(v, kind=ip)
         x = o(i)
         j = i - 1
         do while (j >= 1)
            if (.not. v(o(j)) < v(x)) exit
            o(j + 1) = o(j)
            j = j - 1
         end do
         o(j + 1) = x
      end do
   end function insertion_order
end program test_post_descending_order
