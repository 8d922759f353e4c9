!> The tangential state of every slave entry: its pair's tangential law
!> (vemcontact_contact_friction), the tangential spring, the multiplier and anchor
!> that carry the slip history from increment to increment and step to step, and
!> the stick/slip state of the current iterate.
!>
!> With s the relative tangential displacement of the slave node along the master's
!> unit tangent, the trial force is T_trial = lambda + kt (s - anchor) and the law's
!> return mapping gives the force T and the state.  The contact iteration solves
!> with the states frozen: a sticking entry is the spring kt in the symmetric matrix
!> with the force lambda - kt anchor on the right-hand side, a slipping one the force
!> T + dT/dN (N(u) - N) that follows its normal force, whose unsymmetric part the
!> factor lacks and GMRES adds (docs/contact-formulation.md, "Friction"); a
!> stick/slip change changes the symmetric matrix by one rank-one term.
!>
!> * stick slope: lambda = 0, kt = slope x area, the anchor the irreversible slip,
!>   updated when the increment converges (commit);
!> * exact stick (and ROUGH): kt is the augmentation stiffness, and the Uzawa update
!>   (augment) moves lambda to T until the elastic slip s - anchor of the sticking
!>   entries vanishes, the tangential counterpart of HARD's normal multiplier; the
!>   anchor moves to s when the increment converges (commit).
module vemcontact_contact_tangential
   use vemcontact_kinds, only: wp
   use vemcontact_contact_friction, only: tangential_law_t, tangential_response_t, frictionless_law_t, &
                                          coulomb_law_t, rough_law_t, tangent_open, tangent_stick, tangent_slip
   implicit none
   private

   public :: friction_state_t, law_slot_t, make_law, friction_params_t

   !> One pair's tangential law.
   type :: law_slot_t
      class(tangential_law_t), allocatable :: law
   end type law_slot_t

   !> The parameters of a tangential law as the deck gives them (*FRICTION, or a
   !> step's *CHANGE FRICTION): has *FRICTION, ROUGH, mu, the stick slope (0: exact
   !> stick) and the cohesion.
   type :: friction_params_t
      logical :: has_friction = .false.
      logical :: rough = .false.
      real(wp) :: mu = 0.0_wp
      real(wp) :: slope = 0.0_wp
      real(wp) :: cohesion = 0.0_wp
   end type friction_params_t

   type :: friction_state_t
      type(law_slot_t), allocatable :: laws(:)   !< per pair
      type(friction_params_t), allocatable :: params(:)   !< per pair, the parameters in force
      logical :: on = .false.                    !< some pair has a frictional law
      logical :: exact = .false.                 !< some frictional pair has exact stick
      !> per entry: tangential spring (force per unit slip), multiplier, anchor
      real(wp), allocatable :: kt(:), lambda(:), anchor(:)
      !> per entry at the current iterate: slip s, force T (which a slipping entry
      !> carries in the next frozen solve) and the state (tangent_*)
      real(wp), allocatable :: slip(:), force(:)
      !> per entry at the current iterate: the normal force T was mapped with, and
      !> dT/dN (mu sign(T) slipping): a slipping entry's force follows the normal force
      !> of the next solve linearly, T + dT/dN (N(u) - N)
      real(wp), allocatable :: normal(:), dnormal(:)
      integer, allocatable :: state(:)
      !> the tangential force the solution balances (set_balanced), what CSHEAR reports
      real(wp), allocatable :: balanced(:)
   contains
      procedure :: allocate_entries
      procedure :: update
      procedure :: augment
      procedure :: commit
      procedure :: frictional_pair
   end type friction_state_t

contains

   !> The tangential law of an interaction: ROUGH; Coulomb/Mohr-Coulomb when mu or the
   !> cohesion is positive; frictionless otherwise (no *FRICTION, or mu = 0).
   pure subroutine make_law(has_friction, rough, mu, slope, cohesion, slot)
      logical, intent(in) :: has_friction, rough
      real(wp), intent(in) :: mu, slope, cohesion
      type(law_slot_t), intent(out) :: slot
      if (has_friction .and. rough) then
         allocate (slot%law, source=rough_law_t())
      else if (has_friction .and. (mu > 0.0_wp .or. cohesion > 0.0_wp)) then
         allocate (slot%law, source=coulomb_law_t(mu=mu, slope=slope, cohesion=cohesion))
      else
         allocate (slot%law, source=frictionless_law_t())
      end if
   end subroutine make_law

   pure subroutine allocate_entries(self, n)
      class(friction_state_t), intent(inout) :: self
      integer, intent(in) :: n
      allocate (self%kt(n), self%lambda(n), self%anchor(n), self%slip(n), self%force(n), &
                self%balanced(n), self%normal(n), self%dnormal(n), source=0.0_wp)
      allocate (self%state(n), source=tangent_open)
   end subroutine allocate_entries

   !> Whether pair p's law carries tangential force.
   pure logical function frictional_pair(self, p)
      class(friction_state_t), intent(in) :: self
      integer, intent(in) :: p
      frictional_pair = self%laws(p)%law%frictional()
   end function frictional_pair

   !> The return mapping of every entry at the slips s and normal forces `normal` of
   !> the current iterate (`closed`: active with a master segment; `area`: tributary
   !> area; `pair`: the entry's pair): forces and states for the next solve; nchanged counts the frictional entries whose stick/slip state changed.
   pure subroutine update(self, pair, s, normal, closed, area, nchanged, closing_slips, slip_noise)
      class(friction_state_t), intent(inout) :: self
      integer, intent(in) :: pair(:)
      real(wp), intent(in) :: s(:), normal(:), area(:)
      logical, intent(in) :: closed(:)
      integer, intent(out) :: nchanged
      !> an entry that closes slips in the next solve (see below)
      logical, intent(in) :: closing_slips
      !> the round-off of the slips (a few ulps of the largest displacement): kt times
      !> it is the round-off of a trial force
      real(wp), intent(in) :: slip_noise
      type(tangential_response_t) :: r, rs
      real(wp) :: trial, band
      integer :: i
      nchanged = 0
      do i = 1, size(pair)
         self%slip(i) = s(i)
         trial = self%lambda(i) + self%kt(i)*(s(i) - self%anchor(i))
         r = self%laws(pair(i))%law%return_map(trial, normal(i), area(i), closed(i))
         ! the round-off of the trial force: its last bits, and the stiff spring kt
         ! times the round-off of the slip (K = 1e13 Pa/m on displacements of 1e-4 m:
         ! 1e-11 of the force, a thousand times the bits); within it of the bound an
         ! entry keeps its state.  Near the limit of a strength reduction most entries
         ! lie on the bound, and a narrower band flipped a few of them between stick and
         ! slip at every iteration on round-off alone (rock_block_crack6: 50 iterations
         ! at the converged state of the step before)
         band = max(64.0_wp*epsilon(1.0_wp)*abs(trial), self%kt(i)*slip_noise)
         ! a sticking entry whose trial force exceeds the bound within the band sticks
         if (self%state(i) == tangent_stick .and. r%state == tangent_slip) then
            rs = self%laws(pair(i))%law%return_map(trial - sign(band, trial), normal(i), area(i), closed(i))
            if (rs%state == tangent_stick) r = tangential_response_t(trial, tangent_stick, 1.0_wp, 0.0_wp)
         end if
         ! An entry that closes in the iteration slips in its first solve closed, with
         ! the bound of its normal force: its trial force only measures how far it
         ! moved in the solve that closed it, which the line search cut short where it
         ! started to penetrate.  Stuck there, a node at the corner of a sliding block
         ! was dragged open again by the block and closed again, a few per cent further
         ! each time (24 iterations on the inclined joint, 3 with this rule); the
         ! next update decides from a trial force that has seen it move closed.
         ! a slipping entry whose trial force lies on the bound (to round-off) keeps
         ! slipping: at the start of an increment its committed multiplier is exactly
         ! the bound, and taking it for stick flipped every slipping node of the dam to
         ! stick and back (29 changes and a factorization more per step)
         if (self%state(i) == tangent_slip .and. r%state == tangent_stick) then
            rs = self%laws(pair(i))%law%return_map(trial + sign(band, trial), normal(i), area(i), closed(i))
            if (rs%state == tangent_slip) r = rs
         end if
         ! a slipping entry whose slip reversed from one solve to the next sticks: with
         ! the direction of its force frozen, each solve overshot the point where it
         ! holds (the k = 2 Hertz disc with exact stick alternated between +-mu N on
         ! five nodes for 50 iterations); stuck, the next update decides from there
         if (closing_slips .and. self%state(i) == tangent_slip .and. r%state == tangent_slip .and. &
             r%force*self%force(i) < 0.0_wp) then
            r = tangential_response_t(r%force, tangent_stick, 1.0_wp, 0.0_wp)
         end if
         if (closing_slips .and. self%state(i) == tangent_open .and. r%state == tangent_stick .and. &
             .not. self%laws(pair(i))%law%exact()) then
            r = self%laws(pair(i))%law%return_map(sign(huge(1.0_wp), trial), normal(i), area(i), closed(i))
         end if
         if (self%laws(pair(i))%law%frictional() .and. r%state /= self%state(i) .and. &
             (r%state == tangent_stick .or. r%state == tangent_slip)) nchanged = nchanged + 1
         self%state(i) = r%state
         self%force(i) = r%force
         ! an open entry carries no tangential force (its anchor stays where the
         ! increment started: its trial force on closing is its tangential motion in
         ! the increment)
         if (r%state == tangent_open) self%lambda(i) = 0.0_wp
         self%normal(i) = normal(i)
         self%dnormal(i) = r%dnormal
      end do
   end subroutine update

   !> Uzawa update of the exact-stick entries (settle) at the current iterate.  Returns, from before the update, the largest tangential force
   !> change kt |s - anchor| of a sticking entry (what the update corrects) and its
   !> elastic slip |s - anchor| relative to `length` (the local element size).
   pure subroutine augment(self, pair, length, noise, change, elastic_slip)
      class(friction_state_t), intent(inout) :: self
      integer, intent(in) :: pair(:)
      real(wp), intent(in) :: length(:)
      !> the round-off of the forces: a change within it counts as none
      real(wp), intent(in) :: noise
      real(wp), intent(out) :: change, elastic_slip
      integer :: i
      change = 0.0_wp
      elastic_slip = 0.0_wp
      do i = 1, size(pair)
         if (.not. self%laws(pair(i))%law%exact()) cycle
         if (self%state(i) == tangent_stick) then
            change = max(change, self%kt(i)*abs(self%slip(i) - self%anchor(i)) - noise)
            elastic_slip = max(elastic_slip, abs(self%slip(i) - self%anchor(i))/length(i))
         end if
         call settle(self, i)
      end do
   end subroutine augment

   !> The end of a converged increment: the history the next one starts from.  A
   !> stick slope keeps lambda = 0 and moves the anchor by the slip beyond the
   !> elastic one, s - T/kt; exact stick takes lambda = T anchored at s; an open
   !> entry carries nothing and re-anchors where it is.
   pure subroutine commit(self, pair)
      class(friction_state_t), intent(inout) :: self
      integer, intent(in) :: pair(:)
      integer :: i
      do i = 1, size(pair)
         if (self%laws(pair(i))%law%exact()) then
            ! the multiplier at the anchor where the increment ends
            call settle(self, i)
            self%anchor(i) = self%slip(i)
         else if (self%kt(i) > 0.0_wp .and. (self%state(i) == tangent_stick .or. &
                                              self%state(i) == tangent_slip)) then
            self%lambda(i) = 0.0_wp
            self%anchor(i) = self%slip(i) - self%force(i)/self%kt(i)
         else
            self%lambda(i) = 0.0_wp
            self%anchor(i) = self%slip(i)
         end if
      end do
   end subroutine commit

   !> The Uzawa update of entry i: lambda <- T, the anchor kept (the slip at the start
   !> of the increment), so that the next solves drive a sticking entry's elastic slip
   !> s - anchor to zero while a slipping one's trial force lambda + kt (s - anchor)
   !> stays beyond the bound by its slip in this increment (re-anchoring it at every
   !> update would put its trial force on the bound, where stick and slip alternate
   !> on round-off); an open or frictionless entry carries nothing.
   pure subroutine settle(self, i)
      type(friction_state_t), intent(inout) :: self
      integer, intent(in) :: i
      if (self%state(i) == tangent_stick .or. self%state(i) == tangent_slip) then
         self%lambda(i) = self%force(i)
      else
         self%lambda(i) = 0.0_wp
      end if
   end subroutine settle
end module vemcontact_contact_tangential
