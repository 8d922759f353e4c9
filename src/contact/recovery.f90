!> The contact pressure of a SURFACE TO SURFACE pair on the slave face's own sides.
!>
!> The node insertion splits each first-order side of the slave face at the master's
!> nodes.  Where the faces are one curve that changes nothing, but where a curved body
!> meets another one (a disc on a block) its mesh is a polygon: each vertex is a corner
!> of the interface, and an elastic body pressed by a corner of turn theta carries a
!> pressure peak of order E* theta there (logarithmic in the distance to the corner),
!> which the inserted nodes next to the vertex resolve and NODE TO SURFACE, which
!> spreads each vertex's force over the vertex's own tributary length, does not.  On
!> the paper's Hertz 1155 the disc's vertices read +2.3 % to +3.9 % above Hertz's
!> p0 sqrt(1 - x^2/a^2) and the inserted nodes between them -0.7 % to -1.8 %: an
!> O(h) polygon error, not a property of the smooth contact (docs/contact-formulation.md).
!>
!> The pressure reported is therefore the L2 projection with lumped weights onto the
!> piecewise linear functions of the slave face's own nodes (before the insertion): the
!> nodal forces F_j of the split face are gathered to the ends a, b of the original
!> side they lie on with the weights (1 - t, t) of the hat functions (t the arc-length
!> position on the side), p_i = sum_j psi_i(x_j) F_j / sum_j psi_i(x_j) w_j (w_j the
!> tributary length times thickness), and each inserted node takes the linear
!> interpolation of its side's end values.  A uniform pressure (F_j = p w_j) is
!> reproduced exactly on any interface, kinked ones included, and the reported
!> pressures times their areas add up to the forces (sum_j p_j w_j = sum_j F_j) when
!> the sums run over the closed nodes only, which is how they run here: an open node
!> reports 0 and gives no weight, although its value may enter its neighbours'
!> interpolation.
module vemcontact_contact_recovery
   use vemcontact_kinds, only: wp, ip
   implicit none
   private

   public :: side_pressure

contains

   !> Pressures p of the slave entries `node` (forces f, weights w = tributary length
   !> times thickness, active) of a face with sides edge(:, k) = (a, b) in element
   !> orientation after the insertion; `new(n)` is true for the nodes inserted into
   !> this face.  An entry not on a split side keeps f / w, and so does an entry with
   !> keep (a force that a support shares, which is not the face's to spread): it
   !> neither gathers its neighbours' forces nor ends their sides.
   pure function side_pressure(x, edge, new, node, f, w, active, keep) result(p)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: edge(:, :), node(:)
      logical, intent(in) :: new(:), active(:), keep(:)
      real(wp), intent(in) :: f(:), w(:)
      real(wp) :: p(size(node))
      integer(ip), allocatable :: next(:), prev(:), ent(:), ia(:), ib(:)
      real(wp), allocatable :: t(:), fc(:), wc(:), pc(:)
      integer :: k, j
      allocate (next(size(x, 2)), prev(size(x, 2)), ent(size(x, 2)), source=0_ip)
      do k = 1, size(edge, 2)
         if (next(edge(1, k)) == 0) next(edge(1, k)) = edge(2, k)
         if (prev(edge(2, k)) == 0) prev(edge(2, k)) = edge(1, k)
      end do
      do j = 1, size(node)
         if (.not. keep(j)) ent(node(j)) = int(j, ip)
      end do
      allocate (ia(size(node)), ib(size(node)), source=0_ip)
      allocate (t(size(node)), source=0.0_wp)
      do j = 1, size(node)
         if (new(node(j)) .and. .not. keep(j)) call side_ends(node(j), ia(j), ib(j), t(j))
      end do
      ! gather the closed entries' forces and weights to the original nodes
      allocate (fc(size(node)), wc(size(node)), pc(size(node)), source=0.0_wp)
      do j = 1, size(node)
         if (.not. active(j)) cycle
         if (ia(j) > 0) then
            fc(ia(j)) = fc(ia(j)) + (1.0_wp - t(j))*f(j)
            wc(ia(j)) = wc(ia(j)) + (1.0_wp - t(j))*w(j)
            fc(ib(j)) = fc(ib(j)) + t(j)*f(j)
            wc(ib(j)) = wc(ib(j)) + t(j)*w(j)
         else
            fc(j) = fc(j) + f(j)
            wc(j) = wc(j) + w(j)
         end if
      end do
      where (wc > 0.0_wp) pc = fc/wc
      do j = 1, size(node)
         p(j) = 0.0_wp
         if (.not. active(j)) cycle
         if (ia(j) > 0) then
            p(j) = (1.0_wp - t(j))*pc(ia(j)) + t(j)*pc(ib(j))
         else
            p(j) = pc(j)
         end if
      end do
   contains
      !> The entries a, b of the original nodes that end the split side through the
      !> inserted node s, and s's arc-length position t on it; a = b = 0 when either
      !> end is missing (an open end of the face), not a slave entry or kept.
      pure subroutine side_ends(s, a, b, ts)
         integer(ip), intent(in) :: s
         integer(ip), intent(out) :: a, b
         real(wp), intent(out) :: ts
         integer(ip) :: q, r
         real(wp) :: la, lb
         a = 0
         b = 0
         ts = 0.0_wp
         la = 0.0_wp
         q = s
         do
            r = prev(q)
            if (r == 0 .or. r == s) return
            la = la + hypot(x(1, q) - x(1, r), x(2, q) - x(2, r))
            q = r
            if (.not. new(q)) exit
         end do
         a = ent(q)
         lb = 0.0_wp
         q = s
         do
            r = next(q)
            if (r == 0 .or. r == s) then
               a = 0
               return
            end if
            lb = lb + hypot(x(1, q) - x(1, r), x(2, q) - x(2, r))
            q = r
            if (.not. new(q)) exit
         end do
         b = ent(q)
         if (a == 0 .or. b == 0 .or. .not. (la + lb > 0.0_wp)) then
            a = 0
            b = 0
            return
         end if
         ts = la/(la + lb)
      end subroutine side_ends
   end function side_pressure

end module vemcontact_contact_recovery
