!> Isotropic linear elasticity matrices for the 2D plane assumptions.
!> Voigt order (xx, yy, xy) with the engineering shear strain gamma_xy = 2 eps_xy,
!> so that strain energy density is eps^T D eps / 2 without extra factors.
module vemcontact_material_elastic
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: plane_strain, plane_stress
   implicit none
   private

   public :: elastic_matrix, out_of_plane_stress

contains

   !> Elasticity matrix `d` (stress = d * strain) for `plane` = plane_strain or
   !> plane_stress.  Preconditions (checked by the model checks, not here, so
   !> that this stays pure and branch-free in the element loop): young > 0,
   !> -1 < poisson < 0.5 (plane strain) or -1 < poisson < 1 (plane stress).
   !> Any other `plane` value is treated as plane stress.
   pure subroutine elastic_matrix(young, poisson, plane, d)
      real(wp), intent(in) :: young, poisson
      integer, intent(in) :: plane
      real(wp), intent(out) :: d(3, 3)
      real(wp) :: c
      d = 0.0_wp
      if (plane == plane_strain) then
         c = young/((1.0_wp + poisson)*(1.0_wp - 2.0_wp*poisson))
         d(1, 1) = c*(1.0_wp - poisson)
         d(2, 2) = d(1, 1)
         d(1, 2) = c*poisson
         d(2, 1) = d(1, 2)
      else
         c = young/(1.0_wp - poisson*poisson)
         d(1, 1) = c
         d(2, 2) = c
         d(1, 2) = c*poisson
         d(2, 1) = d(1, 2)
      end if
      ! the shear modulus in both cases; written as E/(2(1+nu)) rather than from
      ! c so that it does not pick up the rounding of the (1-2nu) factor
      d(3, 3) = young/(2.0_wp*(1.0_wp + poisson))
   end subroutine elastic_matrix

   !> Out-of-plane normal stress: eps_zz = 0 gives nu*(sxx+syy) in plane strain;
   !> plane stress has szz = 0 by assumption.
   pure function out_of_plane_stress(poisson, plane, sxx, syy) result(szz)
      real(wp), intent(in) :: poisson
      integer, intent(in) :: plane
      real(wp), intent(in) :: sxx, syy
      real(wp) :: szz
      if (plane == plane_strain) then
         szz = poisson*(sxx + syy)
      else
         szz = 0.0_wp
      end if
   end function out_of_plane_stress
end module vemcontact_material_elastic
