!> Prescribed values moved to the right-hand side give the same solution as
!> solving the reduced system by hand; constrained shares of a matrix (a distributed
!> run's) add up to the constrained matrix, their moves to the whole matrix's.
program test_dirichlet
   use vemcontact_kinds, only: wp, i8
   use vemcontact_testing, only: checker_t
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_driver_dirichlet, only: apply_dirichlet, constrain_matrix, dirichlet_moves
   implicit none
   type(checker_t) :: t
   type(sym_csc_t) :: a
   real(wp) :: f(3), dense(3, 3), x(3)
   logical :: fixed(3)
   real(wp) :: value(3)
   ! chain of two springs k=2 and k=3: dofs 1-2-3, dof 1 held at 0.5, force 1 at dof 3
   ! K = [[2,-2,0],[-2,5,-3],[0,-3,3]]
   a%n = 3
   a%col_ptr = [1_i8, 2_i8, 4_i8, 6_i8]
   a%row_idx = [1, 1, 2, 2, 3]
   a%val = [2.0_wp, -2.0_wp, 5.0_wp, -3.0_wp, 3.0_wp]
   fixed = [.true., .false., .false.]
   value = [0.5_wp, 0.0_wp, 0.0_wp]
   f = [0.0_wp, 0.0_wp, 1.0_wp]
   call apply_dirichlet(a, fixed, value, f)
   call t%close(a%val(2), 0.0_wp, 0.0_wp, 'coupling removed', atol=0.0_wp)
   call t%close(a%val(1), 2.0_wp, 0.0_wp, 'diagonal kept')
   ! dense solve of the modified system
   dense = 0.0_wp
   dense(1, 1) = a%val(1); dense(2, 2) = a%val(3); dense(2, 3) = a%val(4); dense(3, 2) = a%val(4)
   dense(3, 3) = a%val(5); dense(1, 2) = a%val(2); dense(2, 1) = a%val(2)
   call solve3(dense, f, x)
   ! exact: u1 = 0.5, spring forces 1 everywhere: u2 = 0.5 + 1/2, u3 = u2 + 1/3
   call t%close(x(1), 0.5_wp, 1.0e-14_wp, 'prescribed value')
   call t%close(x(2), 1.0_wp, 1.0e-14_wp, 'u2')
   call t%close(x(3), 1.0_wp + 1.0_wp/3.0_wp, 1.0e-14_wp, 'u3')
   call test_shares(t)
   call t%finish()
contains
   ! K of the chain above split into two shares (the springs k=2 and k=3, one each),
   ! dofs 1 and 3 held at 0.5 and -0.25: the shares, constrained with the whole
   ! diagonal, add up to apply_dirichlet's matrix, and their moves plus the fixed rows
   ! to its right-hand side.  Sums of two numbers: exact to round-off, 1e-15.
   subroutine test_shares(t)
      type(checker_t), intent(inout) :: t
      type(sym_csc_t) :: whole, s1, s2
      real(wp) :: fw(3), g(3), v(3), diag(3)
      logical :: fx(3)
      whole%n = 3
      whole%col_ptr = [1_i8, 2_i8, 4_i8, 6_i8]
      whole%row_idx = [1, 1, 2, 2, 3]
      whole%val = [2.0_wp, -2.0_wp, 5.0_wp, -3.0_wp, 3.0_wp]
      s1 = whole
      s1%val = [2.0_wp, -2.0_wp, 2.0_wp, 0.0_wp, 0.0_wp]
      s2 = whole
      s2%val = [0.0_wp, 0.0_wp, 3.0_wp, -3.0_wp, 3.0_wp]
      fx = [.true., .false., .true.]
      v = [0.5_wp, 0.0_wp, -0.25_wp]
      diag = [2.0_wp, 5.0_wp, 3.0_wp]
      fw = [0.0_wp, 1.0_wp, 0.0_wp]
      g = 0.0_wp
      call dirichlet_moves(s1, fx, v, g)
      call dirichlet_moves(s2, fx, v, g)
      call apply_dirichlet(whole, fx, v, fw)
      call t%close(1.0_wp + g(2), fw(2), 1.0e-15_wp, 'moves of the shares add up (free row)')
      call constrain_matrix(s1, fx, diag, .true.)
      call constrain_matrix(s2, fx, diag, .false.)
      call t%close(maxval(abs(s1%val + s2%val - whole%val)), 0.0_wp, 0.0_wp, &
                   'constrained shares add up to the constrained matrix', atol=1.0e-15_wp)
      call t%close(s2%val(1), 0.0_wp, 0.0_wp, 'fixed diagonal held by the owner only', atol=0.0_wp)
   end subroutine test_shares

   subroutine solve3(m, b, y)
      real(wp), intent(in) :: m(3, 3), b(3)
      real(wp), intent(out) :: y(3)
      real(wp) :: det
      det = m(1, 1)*(m(2, 2)*m(3, 3) - m(2, 3)*m(3, 2)) - m(1, 2)*(m(2, 1)*m(3, 3) - m(2, 3)*m(3, 1)) &
            + m(1, 3)*(m(2, 1)*m(3, 2) - m(2, 2)*m(3, 1))
      y(1) = (b(1)*(m(2, 2)*m(3, 3) - m(2, 3)*m(3, 2)) - m(1, 2)*(b(2)*m(3, 3) - m(2, 3)*b(3)) &
              + m(1, 3)*(b(2)*m(3, 2) - m(2, 2)*b(3)))/det
      y(2) = (m(1, 1)*(b(2)*m(3, 3) - m(2, 3)*b(3)) - b(1)*(m(2, 1)*m(3, 3) - m(2, 3)*m(3, 1)) &
              + m(1, 3)*(m(2, 1)*b(3) - b(2)*m(3, 1)))/det
      y(3) = (m(1, 1)*(m(2, 2)*b(3) - b(2)*m(3, 2)) - m(1, 2)*(m(2, 1)*b(3) - b(2)*m(3, 1)) &
              + b(1)*(m(2, 1)*m(3, 2) - m(2, 2)*m(3, 1)))/det
   end subroutine solve3
end program test_dirichlet
