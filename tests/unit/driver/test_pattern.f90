!> The sparse pattern holds exactly the node-graph blocks, and scattering element
!> matrices gives the same upper triangle as dense assembly.
program test_pattern
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_testing, only: checker_t
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: build_pattern, add_element_matrix
   implicit none
   type(checker_t) :: t
   type(sym_csc_t) :: a
   ! two elements sharing nodes 2 and 3: (1,2,3) and (2,4,3)... node graph of 4 nodes
   integer(i8), parameter :: adj_ptr(5) = [1_i8, 3_i8, 6_i8, 9_i8, 11_i8]
   integer(ip), parameter :: adj(10) = [2, 3, 1, 3, 4, 1, 2, 4, 2, 3]
   integer(ip), parameter :: e1(3) = [1, 2, 3], e2(3) = [2, 4, 3]
   real(wp) :: k1(6, 6), k2(6, 6), dense(8, 8), r(6, 6)
   integer :: j
   integer(i8) :: k
   logical :: ok

   call build_pattern(4_ip, adj_ptr, adj, a)
   call t%equal(int(a%n), 8, 'pattern size')
   ! per node J: 3 entries of its diagonal block + 4 per lower neighbour;
   ! lower neighbours: node 1 none, 2 {1}, 3 {1,2}, 4 {2,3} -> 4*3 + 4*5 = 32
   call t%equal(int(a%col_ptr(a%n + 1) - 1), 32, 'number of stored entries')
   do j = 1, a%n
      call t%check(a%row_idx(a%col_ptr(j + 1) - 1) == j, 'diagonal last in its column')
      do k = a%col_ptr(j), a%col_ptr(j + 1) - 2
         call t%check(a%row_idx(k) < a%row_idx(k + 1), 'rows sorted')
      end do
   end do

   ! random symmetric element matrices, assembled sparse and dense
   call random_sym(k1, 1)
   call random_sym(k2, 7)
   dense = 0.0_wp
   call scatter_dense(dense, e1, k1)
   call scatter_dense(dense, e2, k2)
   call add_element_matrix(a, e1, k1, ok)
   call t%check(ok, 'element 1 in pattern')
   call add_element_matrix(a, e2, k2, ok)
   call t%check(ok, 'element 2 in pattern')
   do j = 1, a%n
      do k = a%col_ptr(j), a%col_ptr(j + 1) - 1
         call t%close(a%val(k), dense(a%row_idx(k), j), 1.0e-15_wp, 'assembled entry')
      end do
   end do
   ! everything of the dense upper triangle is in the pattern (dense(1:2,7:8) is zero)
   call t%close(sum(a%val), sum([(sum(dense(:j, j)), j=1, 8)]), 1.0e-13_wp, 'sum of upper triangle')
   r = 0.0_wp
   call add_element_matrix(a, [1_ip, 4_ip], r(:4, :4), ok)
   call t%check(.not. ok, 'pair outside the pattern is reported')
   call t%finish()
contains
   subroutine random_sym(m, seed)
      real(wp), intent(out) :: m(:, :)
      integer, intent(in) :: seed
      integer :: p, q
      do q = 1, size(m, 2)
         do p = 1, q
            m(p, q) = real(mod(37*(p + seed) + 11*q*q, 17), wp) - 8.0_wp
            m(q, p) = m(p, q)
         end do
      end do
   end subroutine random_sym
   subroutine scatter_dense(d, nodes, ke)
      real(wp), intent(inout) :: d(:, :)
      integer(ip), intent(in) :: nodes(:)
      real(wp), intent(in) :: ke(:, :)
      integer :: p, q, dp, dq
      do q = 1, size(nodes)
         do p = 1, size(nodes)
            do dq = 0, 1
               do dp = 0, 1
                  d(2*nodes(p) - 1 + dp, 2*nodes(q) - 1 + dq) = d(2*nodes(p) - 1 + dp, 2*nodes(q) - 1 + dq) &
                                                                + ke(2*p - 1 + dp, 2*q - 1 + dq)
               end do
            end do
         end do
      end do
   end subroutine scatter_dense
end program test_pattern
