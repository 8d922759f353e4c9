!> Tangential contact laws: the friction of a contact point, behind one interface,
!> so that the contact iteration treats frictionless, Coulomb, Mohr-Coulomb and
!> rough contact alike (docs/contact-formulation.md, "Friction").
!>
!> A contact point's law is its normal law (LINEAR or HARD, vemcontact_contact_active_set)
!> times a tangential law here.  The tangential law sees one number, the trial
!> tangential force
!>
!>     T_trial = lambda_t + k_t (s - s_p)
!>
!> with s the relative tangential displacement of the slave node (along the master's
!> unit tangent), s_p the slip the point is anchored at (its irreversible slip), k_t
!> the tangential spring (the stick slope times the tributary area, or the
!> augmentation stiffness of exact stick) and lambda_t the tangential multiplier of
!> exact stick (0 for a stick slope).  Its return mapping turns T_trial and the
!> normal force N into the tangential force T, the stick/slip state and the
!> derivatives of T that the tangent needs:
!>
!> * stick, |T_trial| <= bound: T = T_trial, dT/dT_trial = 1;
!> * slip, |T_trial| > bound: T = bound sign(T_trial), dT/dT_trial = 0 and
!>   dT/dN = mu sign(T_trial) (the coupling that makes the tangent unsymmetric);
!> * open: T = 0.
!>
!> with bound = mu N + c A for Coulomb (c = 0) and Mohr-Coulomb (cohesion c on the
!> tributary area A while the point is closed; an open point carries nothing).
module vemcontact_contact_friction
   use vemcontact_kinds, only: wp
   implicit none
   private

   !> Tangential state of a contact point: open (or not in contact), no tangential
   !> law (frictionless and closed), sticking, slipping.
   integer, parameter, public :: tangent_open = 0, tangent_free = 1, tangent_stick = 2, tangent_slip = 3

   !> What the return mapping gives back for one contact point.
   type, public :: tangential_response_t
      real(wp) :: force = 0.0_wp     !< tangential force T, along the master's tangent
      integer :: state = tangent_open
      real(wp) :: dtrial = 0.0_wp    !< dT/dT_trial: 1 sticking, 0 slipping
      real(wp) :: dnormal = 0.0_wp   !< dT/dN: mu sign(T_trial) slipping, else 0
   end type tangential_response_t

   !> A tangential law.  `exact` laws enforce stick by a multiplier (no elastic slip:
   !> the tangential counterpart of HARD); the others by the tangential spring of
   !> their stick slope (traction per unit elastic slip, CalculiX's meaning).
   type, abstract, public :: tangential_law_t
   contains
      procedure(return_map_i), deferred :: return_map
      !> Whether the law carries tangential force at all (false: frictionless).
      procedure(flag_i), deferred :: frictional
      !> Whether stick is exact (a multiplier) rather than a spring.
      procedure(flag_i), deferred :: exact
      !> Stick slope, tangential traction per unit elastic slip (0 when exact or frictionless).
      procedure(slope_i), deferred :: stick_slope
   end type tangential_law_t

   abstract interface
      !> The tangential force of a point with trial force `trial`, normal force
      !> `normal` (>= 0) and tributary area `area`, closed or not.
      pure function return_map_i(self, trial, normal, area, closed) result(r)
         import :: tangential_law_t, tangential_response_t, wp
         class(tangential_law_t), intent(in) :: self
         real(wp), intent(in) :: trial, normal, area
         logical, intent(in) :: closed
         type(tangential_response_t) :: r
      end function return_map_i
      pure logical function flag_i(self)
         import :: tangential_law_t
         class(tangential_law_t), intent(in) :: self
      end function flag_i
      pure real(wp) function slope_i(self)
         import :: tangential_law_t, wp
         class(tangential_law_t), intent(in) :: self
      end function slope_i
   end interface

   !> No friction: the tangential force is zero, open or closed.
   type, extends(tangential_law_t), public :: frictionless_law_t
   contains
      procedure :: return_map => frictionless_map
      procedure :: frictional => frictionless_frictional
      procedure :: exact => frictionless_exact
      procedure :: stick_slope => frictionless_slope
   end type frictionless_law_t

   !> Coulomb friction |T| <= mu N, with cohesion c (Mohr-Coulomb:
   !> |T| <= c A + mu N while closed).  slope > 0: stick is the tangential spring of
   !> this stick slope (traction per unit elastic slip); slope = 0: exact stick.
   type, extends(tangential_law_t), public :: coulomb_law_t
      real(wp) :: mu = 0.0_wp
      real(wp) :: slope = 0.0_wp
      real(wp) :: cohesion = 0.0_wp
   contains
      procedure :: return_map => coulomb_map
      procedure :: frictional => coulomb_frictional
      procedure :: exact => coulomb_exact
      procedure :: stick_slope => coulomb_slope
   end type coulomb_law_t

   !> Rough contact (Abaqus *FRICTION, ROUGH): no slip while closed, exact stick
   !> with no bound on the tangential force.
   type, extends(tangential_law_t), public :: rough_law_t
   contains
      procedure :: return_map => rough_map
      procedure :: frictional => rough_frictional
      procedure :: exact => rough_exact
      procedure :: stick_slope => rough_slope
   end type rough_law_t

contains

   pure function frictionless_map(self, trial, normal, area, closed) result(r)
      class(frictionless_law_t), intent(in) :: self
      real(wp), intent(in) :: trial, normal, area
      logical, intent(in) :: closed
      type(tangential_response_t) :: r
      r = tangential_response_t(0.0_wp, merge(tangent_free, tangent_open, closed), 0.0_wp, 0.0_wp)
   end function frictionless_map

   pure logical function frictionless_frictional(self)
      class(frictionless_law_t), intent(in) :: self
      frictionless_frictional = .false.
   end function frictionless_frictional

   pure logical function frictionless_exact(self)
      class(frictionless_law_t), intent(in) :: self
      frictionless_exact = .false.
   end function frictionless_exact

   pure real(wp) function frictionless_slope(self)
      class(frictionless_law_t), intent(in) :: self
      frictionless_slope = 0.0_wp
   end function frictionless_slope

   !> The radial return of Coulomb/Mohr-Coulomb friction on the bound c A + mu N.
   pure function coulomb_map(self, trial, normal, area, closed) result(r)
      class(coulomb_law_t), intent(in) :: self
      real(wp), intent(in) :: trial, normal, area
      logical, intent(in) :: closed
      type(tangential_response_t) :: r
      real(wp) :: bound, sgn
      if (.not. closed) then
         r = tangential_response_t()
         return
      end if
      bound = self%cohesion*area + self%mu*max(normal, 0.0_wp)
      if (abs(trial) <= bound) then
         r = tangential_response_t(trial, tangent_stick, 1.0_wp, 0.0_wp)
      else
         sgn = sign(1.0_wp, trial)
         r = tangential_response_t(sgn*bound, tangent_slip, 0.0_wp, &
                                   merge(sgn*self%mu, 0.0_wp, normal > 0.0_wp))
      end if
   end function coulomb_map

   pure logical function coulomb_frictional(self)
      class(coulomb_law_t), intent(in) :: self
      coulomb_frictional = self%mu > 0.0_wp .or. self%cohesion > 0.0_wp
   end function coulomb_frictional

   pure logical function coulomb_exact(self)
      class(coulomb_law_t), intent(in) :: self
      coulomb_exact = .not. self%slope > 0.0_wp
   end function coulomb_exact

   pure real(wp) function coulomb_slope(self)
      class(coulomb_law_t), intent(in) :: self
      coulomb_slope = self%slope
   end function coulomb_slope

   pure function rough_map(self, trial, normal, area, closed) result(r)
      class(rough_law_t), intent(in) :: self
      real(wp), intent(in) :: trial, normal, area
      logical, intent(in) :: closed
      type(tangential_response_t) :: r
      if (closed) then
         r = tangential_response_t(trial, tangent_stick, 1.0_wp, 0.0_wp)
      else
         r = tangential_response_t()
      end if
   end function rough_map

   pure logical function rough_frictional(self)
      class(rough_law_t), intent(in) :: self
      rough_frictional = .true.
   end function rough_frictional

   pure logical function rough_exact(self)
      class(rough_law_t), intent(in) :: self
      rough_exact = .true.
   end function rough_exact

   pure real(wp) function rough_slope(self)
      class(rough_law_t), intent(in) :: self
      rough_slope = 0.0_wp
   end function rough_slope
end module vemcontact_contact_friction
