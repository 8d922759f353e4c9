!> The rules of the contact iteration (vemcontact_contact_iteration), one pure
!> function each, so that each can be tested alone (tests/unit/contact/test_contact_rules.f90):
!>
!> * `line_search_step`: how far to go along a solve that closes new nodes;
!> * `hold_nodes`: closed nodes that only the re-pairing opened stay closed one solve;
!> * `is_cycle`: when the iterates repeat an earlier one;
!> * `conditioning_verdict`: when the factor is too ill-conditioned to trust;
!> * `residual_norm`: the convergence measure;
!> * `matrix_key_t`, `key_of`, `same_key`: when the factor can be reused;
!> * `near_key`: when the factor of a nearby pairing can serve as a solver;
!> * `nonconvergence_hint`: what a run that did not converge can change.
!>
!> docs/contact-robustness.md tells how each was found and measured.
module vemcontact_contact_rules
   use vemcontact_kinds, only: wp, ip
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_linalg_norms, only: safe_norm2
   use vemcontact_contact_friction, only: tangent_stick
   implicit none
   private

   public :: line_search_step, needs_line_search, hold_nodes, is_cycle
   public :: conditioning_verdict, conditioning_hint, residual_norm
   public :: matrix_key_t, key_of, same_key, near_key, stick_flips, nonconvergence_hint

   !> CHOLMOD's reciprocal condition estimate below which results lose accuracy
   !> (relative errors of about eps/rcond: 1e-7 and worse) and a warning is logged,
   !> and below which the run stops: at 1e-12 the round-off in the contact gaps
   !> exceeds the overclosures, so the active set only cycles on noise (seen in a
   !> penalty sweep on two blocks, K from 1e2 to 1e18 E/h: relative pressure errors
   !> 1e-14, 1e-10, 2e-6 and 4e-4 at K = 1e2, 1e6, 1e8 and 1e10 E/h, then cycling;
   !> postprocess/tests/test_contact.py locks this in).
   real(wp), parameter, public :: rcond_warn = 1.0e-9_wp, rcond_stop = 1.0e-12_wp
   !> The stop when closed springs stiffer than the elastic entries set the
   !> conditioning.  The contact pressure is K times an overclosure that is a tiny
   !> difference of displacements, so it loses accuracy faster than the displacements:
   !> in the penalty sweep (docs/stability-penalty.md, blocks, K h/E = 1e0..1e16) the
   !> pressure error is 7e-7 at rcond 4e-10, 9e-4 at 4e-11 and 6e-2 at 4e-12 (the
   !> tributary mean on non-matching meshes 3e-3 at 6e-11), while the displacement
   !> estimate eps/rcond says 5e-5.  Stopping below 1e-10 keeps every answer given
   !> within 1e-3.  Weaker springs (a contrast of materials) keep rcond_stop: there the
   !> answers stay exact down to it (docs/stability-contact.md).
   real(wp), parameter, public :: rcond_stop_penalty = 1.0e-10_wp
   !> Sufficient-decrease constant of the contact line search.  On the Hertz decks
   !> (inputs/hertz_*) and the refined meshes of bench/hertz_refined.toml, c = 0.15 to
   !> 0.3 gives 3-4 iterations everywhere; the exact minimum (c = 0.5) gives 5 on the
   !> paper decks (growth by one node per iteration), the longest decreasing step
   !> (c = 1e-4, about 2 t*) 5 on the refined ones (docs/contact-robustness.md).
   real(wp), parameter, public :: armijo = 0.25_wp
   !> The largest move of an active entry's projection (xi, in segment lengths) for
   !> which the factor of the old pairing still serves the new one as the
   !> preconditioner of GMRES (near_key): the contact matrix then differs by at most
   !> this fraction of the springs; GMRES stalls early where that is too much.
   real(wp), parameter, public :: pairing_drift = 0.1_wp

   !> The most products by the condensed compliance (one solve with the factor each)
   !> of one multiplier step of HARD contact (multiplier_step of
   !> vemcontact_contact_iteration).  In exact arithmetic conjugate gradients end
   !> after as many steps as the compliance has distinct eigenvalues; the modes that
   !> the springs dominate (k c >> 1) cluster near 1/k, and only the few that a
   !> stiffer body carries stand apart: 1-6 steps were measured on the decks of
   !> docs/contact-robustness.md.  The limit only caps a step that round-off keeps
   !> from ending: the outer iteration goes on from where it stopped.
   integer, parameter, public :: multiplier_cg_limit = 30
   !> K h/E of a LINEAR pair with finite sliding above which the contact iteration
   !> may need more than 10 iterations: on the paper's seven interface decks (free
   !> sides, the blocks slide) 4-6 iterations up to 1e5, 5-12 at 1e6, 6-17 at 1e7,
   !> 12-37 or none at 1e8, against 6-7 with HARD (docs/contact-robustness.md, "Stiff
   !> penalties with finite sliding"): the help of a run that did not converge
   !> recommends HARD above it.
   real(wp), parameter, public :: sliding_penalty_limit = 1.0e5_wp

   !> conditioning_verdict: trust the factor, warn (once), stop
   integer, parameter, public :: cond_ok = 0, cond_warn = 1, cond_stop = 2, cond_stop_penalty = 3

   !> The most stick/slip changes alone for which the factor of the old states still
   !> serves the new matrix as GMRES's preconditioner (stick_flips): each change is a
   !> rank-one term, which GMRES resolves in about one iteration (gmres_maxit = 30).
   integer, parameter, public :: max_stick_flips = 12

   !> What the contact part of the matrix depends on: the active set and, for the
   !> active entries, the pairing, the springs and which entries stick (their
   !> tangential springs).
   type :: matrix_key_t
      logical, allocatable :: active(:), stick(:)
      integer(ip), allocatable :: iseg(:)
      !> kt: the tangential springs (a step's *CHANGE FRICTION can change them)
      real(wp), allocatable :: xi(:), normal(:, :), k(:), kt(:)
   end type matrix_key_t

contains

   !> Whether the solve from u0 (frozen gaps g0) to u1 (frozen gaps g1) needs the line
   !> search: a node outside the solve's active set penetrates at u1, or the active set
   !> is not the set of closed gaps at u0.  Gaps are shifted, g - lambda/k, so that a
   !> HARD entry's force max(0, lambda - k g) is k <-g>.  Without new contact the
   !> energy decreases all the way (opening springs only lower it): the full step.
   pure logical function needs_line_search(active, g0, g1) result(needs)
      logical, intent(in) :: active(:)
      real(wp), intent(in) :: g0(:), g1(:)
      needs = any(active .neqv. g0 <= 0.0_wp) .or. any(.not. active .and. g1 < 0.0_wp)
   end function needs_line_search

   !> Length t in (0, 1] of the step from u0 to u1 on the penalty energy along it,
   !>   E(t) = t a + t^2 b / 2 + sum_s k_s/2 (<-(g0_s + t h_s)>^2 - <-g0_s>^2),
   !> with a = d.(K u0 - f_ext), b = d.K d (d = u1 - u0, free dofs), the frozen gaps
   !> g0 at u0 and their change h along d (entries without a partner: h = 0).  With
   !> the pairing frozen the gaps are linear in t: E is convex and piecewise
   !> quadratic, and the solve minimized it with u0's springs only.  When nodes
   !> outside that set penetrate at u1 the full step overshoots: in the first
   !> iteration of a curved contact one node holds the whole load, the body sinks far,
   !> and the next active set is twice the true one, peeled back one ring per
   !> iteration.  The step is then cut to the longest t past the minimum t* of E with
   !> sufficient decrease, E(t) <= E(0) + c t E'(0), c = `armijo` (about 1.5 t*, so
   !> that the newly closing nodes penetrate a little: at t* alone the active set
   !> grows one node per iteration from below on coarse meshes).
   pure real(wp) function line_search_step(a, b, k, g0, h) result(t)
      real(wp), intent(in) :: a, b
      real(wp), intent(in) :: k(:), g0(:), h(:)
      real(wp) :: lo, hi, e0
      integer :: it
      t = 1.0_wp
      ! E'(1) <= 0: the minimum along the line is at or beyond the full step;
      ! E'(0) >= 0: no descent (round-off at convergence), keep the solve
      if (slope(1.0_wp) <= 0.0_wp .or. slope(0.0_wp) >= 0.0_wp) return
      ! E' is continuous, piecewise linear and nondecreasing: bisect to its root
      lo = 0.0_wp
      hi = 1.0_wp
      do it = 1, 60
         t = 0.5_wp*(lo + hi)
         if (slope(t) > 0.0_wp) then
            hi = t
         else
            lo = t
         end if
      end do
      ! the longest step with sufficient decrease between the minimum and 1:
      ! E(t) - c t E'(0) is convex, <= 0 at the minimum
      e0 = slope(0.0_wp)
      if (energy(1.0_wp) <= armijo*e0) then
         t = 1.0_wp
         return
      end if
      lo = hi
      hi = 1.0_wp
      do it = 1, 60
         t = 0.5_wp*(lo + hi)
         if (energy(t) <= armijo*t*e0) then
            lo = t
         else
            hi = t
         end if
      end do
      t = lo
   contains
      pure real(wp) function energy(s)
         real(wp), intent(in) :: s
         energy = s*a + 0.5_wp*s*s*b + 0.5_wp*sum(k*(min(g0 + s*h, 0.0_wp)**2 - min(g0, 0.0_wp)**2))
      end function energy
      pure real(wp) function slope(s)
         real(wp), intent(in) :: s
         slope = a + s*b + sum(k*h*min(g0 + s*h, 0.0_wp))
      end function slope
   end function line_search_step

   !> The closed nodes to hold closed for one more solve: closed with the pairing they
   !> were solved with (frozen gap <= 0) but opened by the new pairing, and not held
   !> the last time.  Their opening comes from the pairing update (the frozen gaps are
   !> exact to O(|du|^2/h) only), which with a stiff penalty exceeds the overclosure
   !> p/K: on Hertz at K h/E >= 1e5 a large step opened up to three edge nodes this way,
   !> and the next solves closed them again one per iteration (8 iterations at 1e8, 5
   !> with the hold).  At most once in a row per node, and it counts as a change, so
   !> that no run converges on a hold.
   pure function hold_nodes(active, frozen_gap, gap, held) result(hold)
      logical, intent(in) :: active(:), held(:)
      real(wp), intent(in) :: frozen_gap(:), gap(:)
      logical :: hold(size(active))
      hold = active .and. frozen_gap <= 0.0_wp .and. gap > 0.0_wp .and. .not. held
   end function hold_nodes

   !> The earlier iteration (0 .. it-1) whose active set and gaps the current ones
   !> repeat, 0 if none (iteration 0 is the start).  Gaps repeat within the round-off
   !> of the solves: about eps/rcond of the overclosures plus the rounding of the
   !> displacements for the open gaps (umax the largest displacement).  Returning to
   !> an earlier active set alone is no cycle: every step lowers the penalty energy of
   !> its pairing, so the iterate is a different one; with stiff springs a node at the
   !> edge of a curved contact opens after a large step and closes again from a
   !> near-converged state (docs/contact-robustness.md).
   pure integer function is_cycle(history, gaps, active, gap, it, rc_min, umax) result(j)
      logical, intent(in) :: history(:, 0:), active(:)
      real(wp), intent(in) :: gaps(:, 0:), gap(:)
      integer, intent(in) :: it
      real(wp), intent(in) :: rc_min, umax
      real(wp) :: tol
      integer :: k
      do k = 0, it - 1
         tol = 10.0_wp*epsilon(1.0_wp)*(max(0.0_wp, -minval(gaps(:, k)), -minval(gap))/rc_min + umax)
         if (all(history(:, k) .eqv. active) .and. all(abs(gaps(:, k) - gap) <= tol)) then
            j = k
            return
         end if
      end do
      j = -1
   end function is_cycle

   !> Whether to trust a factor with CHOLMOD's reciprocal condition estimate rc (< 0:
   !> none available); `ratio` is the stiffest closed spring over the largest elastic
   !> diagonal entry.  The springs are the culprit only when they are stiffer than the
   !> elastic entries: weaker springs (a soft body on a stiff one: 5e-10 at contrast
   !> 1e-12, docs/stability-contact.md) point at the materials instead.
   pure integer function conditioning_verdict(rc, ratio, contact_closed) result(v)
      real(wp), intent(in) :: rc, ratio
      logical, intent(in) :: contact_closed
      logical :: penalty_bound
      v = cond_ok
      if (rc < 0.0_wp) return
      penalty_bound = contact_closed .and. ratio >= 1.0_wp
      if (penalty_bound .and. rc < rcond_stop_penalty) then
         v = cond_stop_penalty
      else if (rc < rcond_stop) then
         v = cond_stop
      else if (rc < rcond_warn) then
         v = cond_warn
      end if
   end function conditioning_verdict

   !> The help line when the penalty sets the conditioning.
   pure function conditioning_hint(ratio) result(s)
      real(wp), intent(in) :: ratio
      character(len=:), allocatable :: s
      character(len=16) :: b
      write (b, '(es9.2)') ratio
      s = '  = help: the stiffest closed contact spring is '//trim(adjustl(b))//' times the largest '// &
          'elastic stiffness entry; lower the penalty slope K on *SURFACE BEHAVIOR (K*h/E of 10 to 1e4 '// &
          'already keeps the overclosure below 1e-4 of the element size h), or use PRESSURE-OVERCLOSURE=HARD'
   end function conditioning_hint

   !> The help of a run whose contact iteration did not converge within MAXIT, naming
   !> only what the run can change: a run with finite sliding (`sliding`: NODE TO
   !> SURFACE without SMALL SLIDING) can fix its pairing; a LINEAR penalty with
   !> finite sliding stiffer than sliding_penalty_limit (`ratio`, K h/E) can be
   !> replaced by HARD; HARD (`hard`) can be given a stiffer augmentation.
   pure function nonconvergence_hint(sliding, hard, ratio) result(s)
      logical, intent(in) :: sliding, hard
      real(wp), intent(in) :: ratio
      character(len=:), allocatable :: s
      character(len=16) :: b
      s = '; raise MAXIT on *CONTACT CONTROLS'
      if (sliding) s = s//new_line('a')//'  = help: node-to-segment contact with finite sliding re-pairs '// &
                       'the nodes at every iteration and can alternate where they face master vertices; '// &
                       'TYPE=SURFACE TO SURFACE (VEM bodies) or SMALL SLIDING keep the pairing fixed'
      if (ratio > sliding_penalty_limit) then
         write (b, '(es9.2)') ratio
         s = s//new_line('a')//'  = help: the penalty slope is K h/E = '//trim(adjustl(b))//'; with finite '// &
             'sliding the iteration takes at most about 10 iterations up to K h/E = 1e5 and more '// &
             'beyond: lower K, or use PRESSURE-OVERCLOSURE=HARD (no overclosure; 6-7 iterations '// &
             'on interfaces that take 12-37 at K h/E = 1e8)'
      end if
      if (hard) s = s//new_line('a')//'  = help: PRESSURE-OVERCLOSURE=HARD updates its multipliers at '// &
                    'every iteration; a larger STIFFNESS SCALE FACTOR on *CONTACT CONTROLS makes each '// &
                    'update correct more'
   end function nonconvergence_hint

   !> Normwise backward error |r| / (|K| |u| + |f| + |f_c|) of the equilibrium, with |K|
   !> estimated by the largest elastic diagonal entry kmax plus the stiffest closed
   !> spring kc: meaningful also when the problem is driven by prescribed
   !> displacements and carries no load.
   pure real(wp) function residual_norm(r, u, f, fc, kmax, kc) result(rel)
      real(wp), intent(in) :: r(:), u(:), f(:), fc(:), kmax, kc
      real(wp) :: scale
      scale = (kmax + kc)*safe_norm2(u) + safe_norm2(f) + safe_norm2(fc)
      rel = 0.0_wp
      if (scale > 0.0_wp) rel = safe_norm2(r)/scale
   end function residual_norm

   !> The matrix key of the current contact state.
   pure function key_of(contact) result(key)
      type(contact_state_t), intent(in) :: contact
      type(matrix_key_t) :: key
      key%active = contact%active
      key%iseg = contact%iseg
      key%xi = contact%xi
      key%normal = contact%normal
      key%k = contact%k
      key%stick = sticking(contact)
      key%kt = stick_springs(contact)
   end function key_of

   !> The entries' tangential springs (none before the tangential state exists).
   pure function stick_springs(contact) result(kt)
      type(contact_state_t), intent(in) :: contact
      real(wp) :: kt(contact%n)
      kt = 0.0_wp
      if (allocated(contact%fric%kt)) kt = contact%fric%kt
   end function stick_springs

   !> Which entries stick (none before the tangential state exists).
   pure function sticking(contact) result(st)
      type(contact_state_t), intent(in) :: contact
      logical :: st(contact%n)
      st = .false.
      if (allocated(contact%fric%state)) st = contact%fric%state == tangent_stick
   end function sticking

   !> Whether the contact part of the matrix is that of `key`: the same active set
   !> and, for the active entries, the same pairing and springs.
   pure logical function same_key(key, contact) result(same)
      type(matrix_key_t), intent(in) :: key
      type(contact_state_t), intent(in) :: contact
      ! the same numbers: the matrix assembled from them is the same
      same = near_key(key, contact, 0.0_wp)
   end function same_key

   !> Whether the contact part of the matrix is close to that of `key`: the same
   !> active set, springs, segments and normals, and projections xi that moved by at
   !> most `drift` (a fraction of the segment) for the active entries.
   pure logical function near_key(key, contact, drift) result(near)
      type(matrix_key_t), intent(in) :: key
      type(contact_state_t), intent(in) :: contact
      real(wp), intent(in) :: drift
      logical :: st(contact%n)
      real(wp) :: kt(contact%n)
      integer :: i
      near = allocated(key%active)
      if (.not. near) return
      near = size(key%active) == contact%n
      if (.not. near) return
      near = all(key%active .eqv. contact%active)
      if (.not. near) return
      st = sticking(contact)
      kt = stick_springs(contact)
      do i = 1, contact%n
         if (.not. contact%active(i)) cycle
         near = key%iseg(i) == contact%iseg(i) .and. abs(key%xi(i) - contact%xi(i)) <= drift .and. &
                identical(key%k(i), contact%k(i)) .and. all(identical(key%normal(:, i), contact%normal(:, i))) .and. &
                (key%stick(i) .eqv. st(i)) .and. identical(key%kt(i), kt(i))
         if (.not. near) return
      end do
   end function near_key

   !> The number of active entries whose stick state differs from `key`'s when the
   !> rest of the contact matrix is the same (active set, pairing, springs); -1
   !> otherwise.  A matrix that differs by a few stick/slip changes alone is solved with
   !> the old factor as GMRES's preconditioner instead of a new factorization.
   pure integer function stick_flips(key, contact) result(m)
      type(matrix_key_t), intent(in) :: key
      type(contact_state_t), intent(in) :: contact
      real(wp) :: kt(contact%n)
      integer :: i
      m = -1
      if (.not. allocated(key%active)) return
      if (size(key%active) /= contact%n) return
      if (.not. all(key%active .eqv. contact%active)) return
      kt = stick_springs(contact)
      do i = 1, contact%n
         if (.not. contact%active(i)) cycle
         if (.not. (key%iseg(i) == contact%iseg(i) .and. identical(key%xi(i), contact%xi(i)) .and. &
                    identical(key%k(i), contact%k(i)) .and. all(identical(key%normal(:, i), contact%normal(:, i))) &
                    .and. identical(key%kt(i), kt(i)))) return
      end do
      m = count(contact%active .and. (key%stick .neqv. sticking(contact)))
   end function stick_flips

   !> a and b are the same number (neither is less or greater).
   elemental logical function identical(a, b)
      real(wp), intent(in) :: a, b
      identical = .not. (a < b .or. a > b)
   end function identical
end module vemcontact_contact_rules
