!> Uplift: the water pressure inside a joint (*UPLIFT), on both of its faces.
!>
!> The pressure is evaluated at each slave node from the head distribution along the
!> joint (linear from the heel to the toe, or through a drain line; with a crack open
!> from the heel, the headwater over the crack and the distribution restarted at its
!> tip), and applied exactly where the contact pressure acts: at the slave entry, over
!> its tributary area CNAREA, along the entry's normal, pushing the slave node away
!> from its master point and the master nodes (with the weights 1 - xi, xi) the other
!> way.  The two faces so carry equal and opposite forces, and the reported CPRESS
!> (the effective contact pressure) plus CFLUIDP (this pressure) is the total normal
!> stress of the joint node by node.  On a NODE TO SURFACE pair the force of a slave
!> node is the pressure on the halves of its own wet slave sides, each along its own
!> normal (slave_face_vectors): at a kink of the joint the sum of the two sides'
!> forces, not the tributary length along one master segment's normal, so that the
!> water's resultant and its line of action on each face are right on a polyline joint
!> (on a straight one the two are the same).
module vemcontact_contact_uplift
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, uplift_t, pair_surface_to_surface
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_surfaces, only: slave_edges
   implicit none
   private

   public :: joint_position, uplift_head, uplift_pressure, uplift_of_entries, crack_front, add_uplift_forces, &
             slave_face_vectors

contains

   !> Position of point x along the heel-toe chord of `up`: 0 at the heel, 1 at the
   !> toe, clipped to [0, 1] (a point is taken at its projection on the chord).
   pure real(wp) function joint_position(up, x) result(s)
      type(uplift_t), intent(in) :: up
      real(wp), intent(in) :: x(2)
      s = dot_product(x - up%heel, up%toe - up%heel)/dot_product(up%toe - up%heel, up%toe - up%heel)
      s = min(1.0_wp, max(0.0_wp, s))
   end function joint_position

   !> Head (elevation of the water surface) at position s of the joint when water
   !> fills a crack from the heel to s_tip (0: none): the headwater over the crack;
   !> beyond it linear to the tailwater at the toe, through the drain head
   !> tail + (1 - E)(head - tail) at the drain line while the crack has not passed it
   !> (a crack beyond the drain line leaves the drains without effect).
   pure real(wp) function uplift_head(up, s, s_tip) result(h)
      type(uplift_t), intent(in) :: up
      real(wp), intent(in) :: s, s_tip
      real(wp) :: sd, hd
      if (s <= s_tip .or. s_tip >= 1.0_wp) then
         h = up%head_heel
         return
      end if
      sd = -1.0_wp
      if (up%drained) sd = joint_position(up, up%drain)
      if (sd > s_tip) then
         hd = up%head_toe + (1.0_wp - up%effectiveness)*(up%head_heel - up%head_toe)
         if (s <= sd) then
            h = up%head_heel + (hd - up%head_heel)*(s - s_tip)/(sd - s_tip)
         else
            h = hd + (up%head_toe - hd)*(s - sd)/(1.0_wp - sd)
         end if
      else
         h = up%head_heel + (up%head_toe - up%head_heel)*(s - s_tip)/(1.0_wp - s_tip)
      end if
   end function uplift_head

   !> Water pressure gamma_w max(0, head - y) at the joint point x (y up); for a
   !> *PRESSURE PENETRATION the fluid pressure where the joint is wetted; both times
   !> the part in force (up%factor).
   pure real(wp) function uplift_pressure(up, x, s_tip) result(p)
      type(uplift_t), intent(in) :: up
      real(wp), intent(in) :: x(2), s_tip
      if (up%pair > 0) then
         ! *PRESSURE PENETRATION: p on the wetted part (distance from the exposed node
         ! up to s_tip, negative when nothing entered), none beyond
         p = up%factor*merge(up%fluid_pressure, 0.0_wp, norm2(x - up%heel) <= s_tip)
         return
      end if
      p = up%factor*up%gamma*max(0.0_wp, uplift_head(up, joint_position(up, x), s_tip) - x(2))
   end function uplift_pressure

   !> The uplift in force on each slave entry of `contact`: the index into `uplifts`
   !> of its pair's interaction (of its pair for a *PRESSURE PENETRATION, which wins
   !> when both name the same joint), 0 for none.
   pure function uplift_of_entries(model, contact, uplifts) result(k)
      type(model_t), intent(in) :: model
      type(contact_state_t), intent(in) :: contact
      type(uplift_t), intent(in) :: uplifts(:)
      integer, allocatable :: k(:)
      integer :: i, j
      allocate (k(contact%n), source=0)
      do i = 1, contact%n
         do j = 1, size(uplifts)
            if (uplifts(j)%pair > 0) then
               if (contact%pair(i) == uplifts(j)%pair) k(i) = j
            else if (model%pairs(contact%pair(i))%interaction == uplifts(j)%interaction) then
               k(i) = j
            end if
         end do
      end do
   end function uplift_of_entries

   !> Pressure penetration: the position of the last slave node of uplift `j` open
   !> contiguously from the heel (0 when the node nearest the heel is closed), with
   !> the number of those open nodes and of all the uplift's nodes.  A node is open
   !> when its contact is not active (Abaqus' criterion with zero critical pressure).
   !> For a *PRESSURE PENETRATION (up%pair > 0) the nodes are taken in order of their
   !> distance from the exposed slave node (a straight joint: along it), a node is open
   !> while its contact pressure is at or below the critical pressure, and s_tip is
   !> the distance of the last wetted node, -1 when the exposed node itself is closed.
   pure subroutine crack_front(model, contact, which, j, up, s_tip, nopen, nall, arc)
      type(model_t), intent(in) :: model
      type(contact_state_t), intent(in) :: contact
      integer, intent(in) :: which(:), j
      type(uplift_t), intent(in) :: up
      real(wp), intent(out) :: s_tip
      integer, intent(out) :: nopen, nall
      !> the crack's length along the joint: from the heel to the first open slave node,
      !> then along the slave nodes in order to the crack tip (0 when none is open);
      !> on a kinked joint longer than the tip's projection on the heel-toe line
      real(wp), intent(out), optional :: arc
      real(wp), allocatable :: s(:)
      real(wp) :: x_last(2), length
      logical, allocatable :: open(:), done(:)
      integer :: i, m, next
      nall = count(which == j)
      allocate (s(contact%n), open(contact%n), done(contact%n))
      do i = 1, contact%n
         if (up%pair > 0) then
            s(i) = norm2(model%x(:, contact%node(i)) - up%heel)
            open(i) = .not. contact%active(i) .or. entry_pressure(contact, i) <= up%critical_pressure
         else
            s(i) = joint_position(up, model%x(:, contact%node(i)))
            open(i) = .not. contact%active(i)
         end if
      end do
      done = which /= j
      s_tip = merge(-1.0_wp, 0.0_wp, up%pair > 0)
      nopen = 0
      length = 0.0_wp
      x_last = up%heel
      ! the uplift's nodes in order from the heel, until the first closed one
      do m = 1, nall
         next = minloc(s, mask=.not. done, dim=1)
         done(next) = .true.
         if (.not. open(next)) exit
         nopen = nopen + 1
         s_tip = s(next)
         length = length + norm2(model%x(:, contact%node(next)) - x_last)
         x_last = model%x(:, contact%node(next))
      end do
      if (present(arc)) arc = length
   end subroutine crack_front

   !> The effective contact pressure of entry i (CPRESS): its normal force over CNAREA.
   pure real(wp) function entry_pressure(contact, i) result(pc)
      type(contact_state_t), intent(in) :: contact
      integer, intent(in) :: i
      pc = 0.0_wp
      if (.not. contact%active(i) .or. contact%iseg(i) == 0) return
      if (allocated(contact%balanced)) then
         pc = contact%balanced(i)/(contact%length(i)*contact%thick(i))
      else
         pc = contact%normal_force(i)/(contact%length(i)*contact%thick(i))
      end if
   end function entry_pressure

   !> Add to f the uplift's forces on both faces and set each entry's pressure
   !> (cfluidp, 0 where no uplift acts) for the crack fronts s_tip(j) of the uplifts;
   !> the pairing (segment, xi, normal) is the contact state's current one.  An entry
   !> without a master segment (beyond the master's ends) carries none.
   pure subroutine add_uplift_forces(model, contact, uplifts, which, s_tip, f, cfluidp, face)
      type(model_t), intent(in) :: model
      type(contact_state_t), intent(in) :: contact
      type(uplift_t), intent(in) :: uplifts(:)
      integer, intent(in) :: which(:)
      real(wp), intent(in) :: s_tip(:)
      real(wp), intent(inout) :: f(:)
      real(wp), intent(out) :: cfluidp(:)
      !> per entry, the slave face's vector (slave_face_vectors); an entry whose vector is
      !> zero, or all without it, take the tributary length along the entry's normal
      real(wp), intent(in), optional :: face(:, :)
      integer(ip) :: nodes(3)
      real(wp) :: force(2), w(3)
      integer :: i, k
      cfluidp = 0.0_wp
      do i = 1, contact%n
         if (which(i) == 0) cycle
         cfluidp(i) = uplift_pressure(uplifts(which(i)), model%x(:, contact%node(i)), s_tip(which(i)))
         if (contact%iseg(i) == 0) cycle
         nodes = [contact%node(i), contact%pairs(contact%pair(i))%seg(:, contact%iseg(i))]
         force = cfluidp(i)*contact%length(i)*contact%thick(i)*contact%normal(:, i)
         if (present(face)) then
            if (any(face(:, i) /= 0.0_wp)) force = cfluidp(i)*contact%thick(i)*face(:, i)
         end if
         w = [1.0_wp, -(1.0_wp - contact%xi(i)), -contact%xi(i)]
         do k = 1, 3
            f(2*nodes(k) - 1:2*nodes(k)) = f(2*nodes(k) - 1:2*nodes(k)) + w(k)*force
         end do
      end do
   end subroutine add_uplift_forces

   !> Per entry of a NODE TO SURFACE pair with uplift (which > 0): the sum over the
   !> slave sides at its node whose both ends carry uplift of half the side's length
   !> times its unit normal, pointing out of the master (the side of the slave the
   !> water pushes); zero elsewhere (add_uplift_forces then takes the tributary length
   !> along the entry's normal: SURFACE TO SURFACE pairs, whose faces the insertion of
   !> nodes splits).  On a straight joint it is the tributary length times the normal.
   pure subroutine slave_face_vectors(model, contact, which, v, error)
      type(model_t), intent(in) :: model
      type(contact_state_t), intent(in) :: contact
      integer, intent(in) :: which(:)
      real(wp), allocatable, intent(out) :: v(:, :)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: edge(:, :), edge_elem(:)
      integer, allocatable :: edge_side(:), entry(:)
      real(wp) :: t(2), h(2)
      integer :: p, i, k, a, b
      allocate (v(2, contact%n), source=0.0_wp)
      allocate (entry(model%nnode))
      do p = 1, size(model%pairs)
         if (model%pairs(p)%formulation == pair_surface_to_surface) cycle
         if (.not. any(which > 0 .and. contact%pair == p)) cycle
         call slave_edges(model, model%pairs(p), edge, edge_elem, edge_side, error)
         if (allocated(error)) return
         entry = 0
         do i = 1, contact%n
            if (contact%pair(i) == p .and. which(i) > 0) entry(contact%node(i)) = i
         end do
         do k = 1, size(edge, 2)
            a = entry(edge(1, k))
            b = entry(edge(2, k))
            if (a == 0 .or. b == 0) cycle
            t = model%x(:, edge(2, k)) - model%x(:, edge(1, k))
            h = 0.5_wp*[t(2), -t(1)]
            v(:, a) = v(:, a) + h
            v(:, b) = v(:, b) + h
         end do
      end do
      ! the sides' orientation is their elements': turn each vector out of the master
      do i = 1, contact%n
         if (dot_product(v(:, i), contact%normal(:, i)) < 0.0_wp) v(:, i) = -v(:, i)
      end do
   end subroutine slave_face_vectors
end module vemcontact_contact_uplift
