!> Reaction forces RF (Abaqus/CalculiX name): the forces the prescribed
!> displacements exert on the body, `K u - f_ext` at the constrained dofs and 0
!> at the free ones (where it is zero to round-off anyway), and their totals over
!> the node sets that carry the constraints.  With the elastic stiffness K (no
!> contact springs), summed over the whole model RF balances the applied loads:
!> K annihilates rigid translations, so sum(K u) = 0 and sum(RF) = -sum(f_ext)
!> up to the contact forces at constrained dofs (action and reaction elsewhere).
module vemcontact_post_reactions
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t
   implicit none
   private

   public :: reaction_forces, constrained_sets

contains

   !> rf(2, nnode) from ku = K u and f = f_ext (both per dof, 2*nnode), `fixed` per dof.
   pure subroutine reaction_forces(ku, f, fixed, rf)
      real(wp), intent(in) :: ku(:), f(:)
      logical, intent(in) :: fixed(:)
      real(wp), intent(out) :: rf(:, :)
      rf = reshape(merge(ku - f, 0.0_wp, fixed), shape(rf))
   end subroutine reaction_forces

   !> Indices (into model%nsets) of the node sets all of whose nodes have a
   !> constrained dof: the sets a *BOUNDARY names (and sets they contain), the
   !> ones whose reaction totals are reported.  Empty sets are left out.
   pure function constrained_sets(model, fixed) result(idx)
      type(model_t), intent(in) :: model
      logical, intent(in) :: fixed(:)      !< per dof, 2*nnode
      integer, allocatable :: idx(:)
      logical, allocatable :: keep(:)
      integer :: k
      integer(ip) :: n
      if (.not. allocated(model%nsets)) then
         allocate (idx(0))
         return
      end if
      allocate (keep(size(model%nsets)), source=.false.)
      do k = 1, size(model%nsets)
         if (size(model%nsets(k)%items) == 0) cycle
         keep(k) = .true.
         do n = 1, size(model%nsets(k)%items, kind=ip)
            associate (node => model%nsets(k)%items(n))
               if (.not. (fixed(2*node - 1) .or. fixed(2*node))) then
                  keep(k) = .false.
                  exit
               end if
            end associate
         end do
      end do
      idx = pack([(k, k=1, size(model%nsets))], keep)
   end function constrained_sets
end module vemcontact_post_reactions
