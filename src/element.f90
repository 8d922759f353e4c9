!> Element dispatcher: one entry point per element quantity over the element
!> orders and formulations (form_*) of vemcontact_model.  First order (the
!> default): form_fem takes the CST for 3 nodes and the 2 x 2 Gauss bilinear
!> quad for 4 nodes; any other form value is the k = 1 virtual element, which
!> works for every n >= 3.  Second order (`order` = 2, nodes: corners then one
!> per side): form_fem takes the 6-node triangle and the 8-node serendipity
!> quad; otherwise the k = 2 virtual element on any polygon.  The element type
!> is informative only: order and node count are what the kernels need, and
!> the model checks verify that they fit the type.
module vemcontact_element
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: form_fem
   use vemcontact_element_vem, only: vem_workspace_size, vem_stiffness, vem_stress, &
      vem_load_weights
   use vemcontact_element_vem2, only: vem2_workspace_size, vem2_stiffness, vem2_stress, vem2_body_load
   use vemcontact_element_quad4, only: quad4_stiffness, quad4_stress, quad4_load_weights
   use vemcontact_element_tri3, only: tri3_stiffness, tri3_stress, tri3_load_weights
   use vemcontact_element_quad8, only: quad8_stiffness, quad8_stress, quad8_load_weights
   use vemcontact_element_tri6, only: tri6_stiffness, tri6_stress, tri6_load_weights
   implicit none
   private

   public :: element_workspace_size, element_stiffness, element_stress, element_load_weights, &
             element_body_load

   !> info codes of element_stiffness
   integer, parameter, public :: elem_ok = 0
   integer, parameter, public :: elem_bad_area = 1       !< signed area <= 0 (clockwise or degenerate)
   integer, parameter, public :: elem_fem_nodes = 2      !< form_fem with n not 3 or 4 (6 or 8 for order 2)
   integer, parameter, public :: elem_bad_jacobian = 3   !< det J <= 0 at a Gauss point (FEM quad)
   integer, parameter, public :: elem_bad_nodes = 4      !< second order with an odd node count or fewer than 6
   integer, parameter, public :: elem_bad_side_node = 5  !< k = 2 VEM: a side node too far from the middle of its side
   integer, parameter, public :: elem_singular = 6       !< k = 2 VEM: singular projection or condensation

contains

   !> Reals of `work` an n-node element needs, whatever its type, order and
   !> form; one array of element_workspace_size(max nodes per element) serves a
   !> whole mesh.
   pure function element_workspace_size(n) result(nw)
      integer, intent(in) :: n
      integer :: nw
      ! the FEM kernels use fixed-size locals only
      nw = max(vem_workspace_size(n), vem2_workspace_size(n))
   end function element_workspace_size

   !> Element stiffness ke(2n, 2n), dof order (u1x, u1y, u2x, u2y, ...); `d` from
   !> elastic_matrix, `thick` the thickness.  info: 0 ok, else one of the elem_*
   !> codes above; ke = 0 when info /= 0.  `tau` (optional, > 0): the VEM
   !> stabilisation factor (default 1); the FEM kernels have no stabilisation and
   !> ignore it.  `order` (optional, default 1): the element's order.
   !> `reduced` (optional, default false): reduced Gauss integration of the
   !> 8-node FEM quad (CPE8R/CPS8R); the other kernels ignore it.
   pure subroutine element_stiffness(form, xy, d, thick, ke, work, info, tau, order, reduced)
      integer, intent(in) :: form
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: ke(:, :)
      real(wp), intent(inout) :: work(:)
      integer, intent(out) :: info
      real(wp), intent(in), optional :: tau
      integer, intent(in), optional :: order
      logical, intent(in), optional :: reduced
      if (second(order)) then
         if (form == form_fem) then
            select case (size(xy, 2))
            case (6)
               call tri6_stiffness(xy, d, thick, ke, info)
            case (8)
               call quad8_stiffness(xy, d, thick, ke, info, reduced)
            case default
               ke = 0.0_wp
               info = elem_fem_nodes
            end select
         else
            call vem2_stiffness(xy, d, thick, ke, work, info, tau)
         end if
      else if (form == form_fem) then
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

   !> Element stress (sxx, syy, sxy) from element displacements ue(2n).  k = 1
   !> VEM: D times the projected constant strain; k = 2 VEM: the mean of its
   !> projected linear stress, with the cell moments recovered from ue and the
   !> element's body force `body` (per unit volume; default zero); FEM quads
   !> and quadratic FEM: mean of the Gauss-point stresses; CST: its constant
   !> stress.  Elements that element_stiffness rejects give zero.
   !> `signode(3, n)` (optional): the element's stress at each of its nodes:
   !> the k = 2 virtual element's projected (linear) stress there, the 6- and
   !> 8-node FEM stress evaluated at the node, the element stress above for
   !> every first-order element.  `reduced` as in element_stiffness.
   pure subroutine element_stress(form, xy, d, ue, work, sig, order, thick, tau, body, signode, reduced)
      integer, intent(in) :: form
      real(wp), intent(in) :: xy(:, :), d(3, 3), ue(:)
      real(wp), intent(inout) :: work(:)
      real(wp), intent(out) :: sig(3)
      integer, intent(in), optional :: order
      real(wp), intent(in), optional :: thick, tau, body(2)
      real(wp), intent(out), optional :: signode(:, :)
      logical, intent(in), optional :: reduced
      real(wp) :: t
      integer :: i
      sig = 0.0_wp
      if (second(order)) then
         if (form == form_fem) then
            select case (size(xy, 2))
            case (6)
               call tri6_stress(xy, d, ue, sig, signode)
               return
            case (8)
               call quad8_stress(xy, d, ue, sig, signode, reduced)
               return
            end select
         else
            t = 1.0_wp
            if (present(thick)) t = thick
            call vem2_stress(xy, d, t, ue, work, sig, body, tau, signode)
            return
         end if
      else if (form == form_fem) then
         select case (size(xy, 2))
         case (3)
            call tri3_stress(xy, d, ue, sig)
         case (4)
            call quad4_stress(xy, d, ue, sig)
         end select
      else
         call vem_stress(xy, d, ue, work, sig)
      end if
      if (present(signode)) then
         do i = 1, size(xy, 2)
            signode(:, i) = sig
         end do
      end if
   end subroutine element_stress

   !> Load weights w(n): the integral over the element of the shape function of
   !> node i per unit thickness, so a constant body force b gives nodal forces
   !> b*thick*w(i); sum(w) is the area.  VEM (k = 1): integral of Pi phi_i
   !> (computable from boundary data); FEM: of N_i.  The k = 2 virtual element
   !> has no such scalar weights (its body load couples the components, see
   !> element_body_load): w = 0 for it.
   pure subroutine element_load_weights(form, xy, work, w, order)
      integer, intent(in) :: form
      real(wp), intent(in) :: xy(:, :)
      real(wp), intent(inout) :: work(:)
      real(wp), intent(out) :: w(:)
      integer, intent(in), optional :: order
      w = 0.0_wp
      if (second(order)) then
         if (form == form_fem) then
            select case (size(xy, 2))
            case (6)
               call tri6_load_weights(xy, w)
            case (8)
               call quad8_load_weights(xy, w)
            end select
         end if
      else if (form == form_fem) then
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

   !> Nodal forces fb(2n, 2) of a constant body force of unit size per unit
   !> volume in x (column 1) and y (column 2), thickness included: a body force
   !> b gives fb b.  thick * w (x) I_2 from element_load_weights, except for the
   !> k = 2 virtual element, whose load sits on the condensed cell moments
   !> (vem2_body_load; it needs d and tau).  info as element_stiffness (k = 2
   !> VEM only; 0 otherwise).
   pure subroutine element_body_load(form, xy, d, thick, fb, work, w, info, tau, order)
      integer, intent(in) :: form
      real(wp), intent(in) :: xy(:, :), d(3, 3), thick
      real(wp), intent(out) :: fb(:, :)
      real(wp), intent(inout) :: work(:), w(:)
      integer, intent(out) :: info
      real(wp), intent(in), optional :: tau
      integer, intent(in), optional :: order
      integer :: i, n
      info = 0
      fb = 0.0_wp
      if (second(order) .and. form /= form_fem) then
         call vem2_body_load(xy, d, thick, fb, work, info, tau)
         return
      end if
      n = size(xy, 2)
      call element_load_weights(form, xy, work, w(1:n), order)
      do i = 1, n
         fb(2*i - 1, 1) = thick*w(i)
         fb(2*i, 2) = thick*w(i)
      end do
   end subroutine element_body_load

   pure logical function second(order)
      integer, intent(in), optional :: order
      second = .false.
      if (present(order)) second = order == 2
   end function second
end module vemcontact_element
