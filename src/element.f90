!> Element dispatcher: one entry point per element quantity over the element
!> types (etype_*) and formulations (form_*) of vemcontact_model.  The
!> formulation decides the kernel: form_fem takes the CST for 3 nodes and the
!> 2 x 2 Gauss bilinear quad for 4 nodes; any other form value is the virtual
!> element, which works for every n >= 3 (so a quad or triangle mesh can be run
!> with the VEM).  The element type is informative only: the node count is
!> what the kernels need, and the model checks verify that it fits the type.
module vemcontact_element
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: form_fem
   use vemcontact_element_vem, only: vem_workspace_size, vem_stiffness, vem_stress, &
      vem_load_weights
   use vemcontact_element_quad4, only: quad4_stiffness, quad4_stress, quad4_load_weights
   use vemcontact_element_tri3, only: tri3_stiffness, tri3_stress, tri3_load_weights
   implicit none
   private

   public :: element_workspace_size, element_stiffness, element_stress, element_load_weights

   !> info codes of element_stiffness
   integer, parameter, public :: elem_ok = 0
   integer, parameter, public :: elem_bad_area = 1       !< signed area <= 0 (clockwise or degenerate)
   integer, parameter, public :: elem_fem_nodes = 2      !< form_fem with n not 3 or 4
   integer, parameter, public :: elem_bad_jacobian = 3   !< det J <= 0 at a Gauss point (FEM quad)

contains

   !> Reals of `work` an n-node element needs, whatever its type and form; one
   !> array of element_workspace_size(max nodes per element) serves a whole mesh.
   pure function element_workspace_size(n) result(nw)
      integer, intent(in) :: n
      integer :: nw
      ! the FEM kernels use fixed-size locals only
      nw = vem_workspace_size(n)
   end function element_workspace_size

   !> Element stiffness ke(2n, 2n), dof order (u1x, u1y, u2x, u2y, ...); `d` from
   !> elastic_matrix, `thick` the thickness.  info: 0 ok, 1 non-positive area,
   !> 2 FEM requested for an element that is not a 3- or 4-node element,
   !> 3 non-positive Jacobian at a Gauss point (FEM quad); ke = 0 when info /= 0.
   !> `tau` (optional, > 0): the VEM stabilisation factor (vem_stiffness, default
   !> vem_tau = 1); the FEM kernels have no stabilisation and ignore it.
   pure subroutine element_stiffness(form, xy, d, thick, ke, work, info, tau)
      integer, intent(in) :: form
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: ke(:, :)
      real(wp), intent(inout) :: work(:)
      integer, intent(out) :: info
      real(wp), intent(in), optional :: tau
      if (form == form_fem) then
         select case (size(xy, 2))
         case (3)
            call tri3_stiffness(xy, d, thick, ke, info)
         case (4)
            call quad4_stiffness(xy, d, thick, ke, info)
         case default
            ke = 0.0_wp
            info = elem_fem_nodes
         end select
      else
         call vem_stiffness(xy, d, thick, ke, work, info, tau)
      end if
   end subroutine element_stiffness

   !> Element stress (sxx, syy, sxy) from element displacements ue(2n).  VEM:
   !> D times the projected constant strain; FEM quad: mean of the 4 Gauss-point
   !> stresses; CST: its constant stress.  Elements that element_stiffness
   !> rejects give zero.
   pure subroutine element_stress(form, xy, d, ue, work, sig)
      integer, intent(in) :: form
      real(wp), intent(in) :: xy(:, :), d(3, 3), ue(:)
      real(wp), intent(inout) :: work(:)
      real(wp), intent(out) :: sig(3)
      sig = 0.0_wp
      if (form == form_fem) then
         select case (size(xy, 2))
         case (3)
            call tri3_stress(xy, d, ue, sig)
         case (4)
            call quad4_stress(xy, d, ue, sig)
         end select
      else
         call vem_stress(xy, d, ue, work, sig)
      end if
   end subroutine element_stress

   !> Load weights w(n): the integral over the element of the shape function of
   !> node i per unit thickness, so a constant body force b gives nodal forces
   !> b*thick*w(i); sum(w) is the area.  VEM: integral of Pi phi_i (computable
   !> from boundary data); FEM: of N_i.
   pure subroutine element_load_weights(form, xy, work, w)
      integer, intent(in) :: form
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(inout) :: work(:)
      real(wp), intent(out) :: w(:)
      w = 0.0_wp
      if (form == form_fem) then
         select case (size(xy, 2))
         case (3)
            call tri3_load_weights(xy, w)
         case (4)
            call quad4_load_weights(xy, w)
         end select
      else
         call vem_load_weights(xy, work, w)
      end if
   end subroutine element_load_weights
end module vemcontact_element
