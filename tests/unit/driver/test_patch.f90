!> Displacement patch test on whole meshes: a linear displacement field must be
!> reproduced exactly (to round-off) by VEM on polygon meshes with non-convex
!> cells and hanging nodes, and by the FEM quad on distorted quads, in plane
!> strain and plane stress, with prescribed displacements on the whole boundary
!> and with tractions on the boundary (only 3 dofs held).
program test_patch
   use vemcontact_kinds, only: wp, ip
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, plane_strain, plane_stress, form_vem, form_fem
   use vemcontact_material_elastic, only: elastic_matrix
   use vemcontact_driver_linear, only: linear_system_t, ordering_auto
   use vemcontact_driver_load_state, only: load_state_t
   use vemcontact_test_model, only: make_model, boundary_mask
   use vemcontact_test_polymesh, only: dual_polymesh, hanging_quad_grid, quad_grid
   implicit none
   type(checker_t) :: t
   real(wp), allocatable :: x(:, :)
   integer(ip), allocatable :: ptr(:), conn(:)
   integer :: plane, bc

   do plane = plane_strain, plane_stress
      do bc = 1, 2
         call dual_polymesh(8, 0.3_wp, 11, x, ptr, conn)
         call patch(x, ptr, conn, plane, form_vem, bc, 'VEM dual polygon mesh')
         call dual_polymesh(8, 0.3_wp, 11, x, ptr, conn, median=.true.)
         call patch(x, ptr, conn, plane, form_vem, bc, 'VEM non-convex median-dual mesh')
         call hanging_quad_grid(5, 4, x, ptr, conn)
         call patch(x, ptr, conn, plane, form_vem, bc, 'VEM quads with hanging nodes')
         call quad_grid(6, 5, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.45_wp, 3, x, ptr, conn)
         call patch(x, ptr, conn, plane, form_vem, bc, 'VEM distorted quads')
         call patch(x, ptr, conn, plane, form_fem, bc, 'FEM distorted quads')
      end do
   end do
   call t%finish()

contains

   subroutine patch(x, ptr, conn, plane, form, bc, what)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: ptr(:), conn(:)
      integer, intent(in) :: plane, form, bc
      character(len=*), intent(in) :: what
      type(model_t) :: m
      type(linear_system_t) :: sys
      type(load_state_t) :: st
      type(error_t), allocatable :: error
      real(wp), allocatable :: u(:), uex(:)
      real(wp) :: d(3, 3), sig(3), tr(2), tvec(2)
      logical, allocatable :: onb(:)
      integer :: i, e, k, n, p, q, i0, i1
      integer(ip) :: nn
      character(len=80) :: label
      ! E = 2e5, nu = 0.3, thickness 0.5: nothing is 1, so scale errors would show
      call make_model(x, ptr, conn, 2.0e5_wp, 0.3_wp, plane, form, 0.5_wp, m)
      nn = m%nnode
      allocate (uex(2*nn), u(2*nn))
      do i = 1, nn
         uex(2*i - 1) = 1.0e-3_wp*(1.0_wp + 2.0_wp*x(1, i) + 3.0_wp*x(2, i))
         uex(2*i) = 1.0e-3_wp*(-2.0_wp + 1.0_wp*x(1, i) - 4.0_wp*x(2, i))
      end do
      allocate (st%fixed(2*nn), source=.false.)
      allocate (st%prescribed(2*nn), source=0.0_wp)
      allocate (st%force(2*nn), source=0.0_wp)
      allocate (st%dload(0))
      st%prescribed = uex
      if (bc == 1) then
         onb = boundary_mask(nn, ptr, conn)
         st%fixed(1::2) = onb
         st%fixed(2::2) = onb
         label = what//', prescribed boundary'
      else
         ! traction sigma.n on every boundary edge, consistent nodal forces (linear trace)
         call elastic_matrix(2.0e5_wp, 0.3_wp, plane, d)
         sig = matmul(d, 1.0e-3_wp*[2.0_wp, -4.0_wp, 3.0_wp + 1.0_wp])
         do e = 1, m%nelem
            n = ptr(e + 1) - ptr(e)
            do k = 0, n - 1
               p = conn(ptr(e) + k)
               q = conn(ptr(e) + mod(k + 1, n))
               if (.not. is_boundary_edge(ptr, conn, p, q)) cycle
               tvec = x(:, q) - x(:, p)
               ! outward normal times length: (t_y, -t_x)
               tr = [sig(1)*tvec(2) - sig(3)*tvec(1), sig(3)*tvec(2) - sig(2)*tvec(1)]
               st%force(2*p - 1:2*p) = st%force(2*p - 1:2*p) + 0.5_wp*0.5_wp*tr
               st%force(2*q - 1:2*q) = st%force(2*q - 1:2*q) + 0.5_wp*0.5_wp*tr
            end do
         end do
         ! hold rigid motion only: both dofs of the node nearest (0,0), y of the one nearest (1,0)
         i0 = minloc(norm2(x, dim=1), 1)
         i1 = minloc(norm2(x - spread([1.0_wp, 0.0_wp], 2, nn), dim=1), 1)
         st%fixed([2*i0 - 1, 2*i0, 2*i1]) = .true.
         label = what//', boundary tractions'
      end if
      if (plane == plane_stress) label = trim(label)//', plane stress'
      if (plane == plane_strain) label = trim(label)//', plane strain'
      call sys%setup(m, ordering_auto, error)
      call t%check(.not. allocated(error), trim(label)//': setup')
      if (allocated(error)) then
         print '(a)', error%message
         return
      end if
      call sys%solve_state(m, st, u, error)
      call t%check(.not. allocated(error), trim(label)//': solve')
      if (allocated(error)) then
         print '(a)', error%message
         return
      end if
      ! exact up to round-off: 1e-10 relative to the largest displacement
      call t%close(maxval(abs(u - uex))/maxval(abs(uex)), 0.0_wp, 0.0_wp, trim(label), atol=1.0e-10_wp)
   end subroutine patch

   !> Edge a->b is on the boundary when no element has the edge b->a.
   logical function is_boundary_edge(ptr, conn, a, b)
      integer(ip), intent(in) :: ptr(:), conn(:)
      integer, intent(in) :: a, b
      integer :: f, j, nf
      is_boundary_edge = .true.
      do f = 1, size(ptr) - 1
         nf = ptr(f + 1) - ptr(f)
         do j = 0, nf - 1
            if (conn(ptr(f) + j) == b .and. conn(ptr(f) + mod(j + 1, nf)) == a) then
               is_boundary_edge = .false.
               return
            end if
         end do
      end do
   end function is_boundary_edge
end program test_patch
