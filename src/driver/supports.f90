!> Detection of parts of the model that are not held against rigid-body motion.
!> A singular stiffness matrix is found before factorization and explained in
!> terms of the model (which part, which motion), rather than surfacing as a
!> zero pivot or a garbage solution.  A part is a set of elements connected
!> through shared nodes.  Its supports suppress rigid motion u = (a - w*y, b + w*x)
!> iff the constraint rows [1, 0, -y] (x fixed) and [0, 1, x] (y fixed) have rank 3.
module vemcontact_driver_supports
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, append_message, err_model
   use vemcontact_model, only: model_t, location_string
   use vemcontact_linalg_lapack, only: dsyev
   use vemcontact_contact_spring, only: spring_t
   use vemcontact_driver_equations, only: constraint_set_t
   implicit none
   private

   public :: find_parts, check_supports, unused_nodes

contains

   !> Label each node with its part (0 for nodes in no element); nparts parts.
   subroutine find_parts(model, part, nparts)
      type(model_t), intent(in) :: model
      integer(ip), allocatable, intent(out) :: part(:)
      integer(ip), intent(out) :: nparts
      integer(ip), allocatable :: parent(:)
      integer(ip) :: e, k, r1, r2, i
      allocate (parent(model%nnode))
      parent = [(i, i=1, model%nnode)]
      do e = 1, model%nelem
         r1 = root(model%elem_conn(model%elem_ptr(e)))
         do k = model%elem_ptr(e) + 1, model%elem_ptr(e + 1) - 1
            r2 = root(model%elem_conn(k))
            if (r1 /= r2) parent(r2) = r1
         end do
      end do
      allocate (part(model%nnode), source=0_ip)
      nparts = 0
      ! number the roots, then every used node takes its root's number
      do e = 1, model%nelem
         do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
            r1 = root(model%elem_conn(k))
            if (part(r1) == 0) then
               nparts = nparts + 1
               part(r1) = nparts
            end if
         end do
      end do
      do e = 1, model%nelem
         do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
            i = model%elem_conn(k)
            part(i) = part(root(i))
         end do
      end do
   contains
      integer(ip) function root(node) result(r)
         integer(ip), intent(in) :: node
         integer(ip) :: nxt, cur
         r = node
         do while (parent(r) /= r)
            r = parent(r)
         end do
         cur = node       ! path compression
         do while (parent(cur) /= r)
            nxt = parent(cur)
            parent(cur) = r
            cur = nxt
         end do
      end function root
   end subroutine find_parts

   !> Mask of nodes that belong to no element.
   pure function unused_nodes(model) result(unused)
      type(model_t), intent(in) :: model
      logical, allocatable :: unused(:)
      allocate (unused(model%nnode), source=.true.)
      unused(model%elem_conn) = .false.
   end function unused_nodes

   !> Error naming every part that its fixed dofs and contact springs do not hold.
   !> The rigid motions of all parts are the unknowns (3 per part, in coordinates
   !> centred on and scaled by each part's box, so the test is independent of units);
   !> a fixed dof is a constraint row on its part, an active spring with normal n at
   !> x a row n.(r_p(x) - r_q(x)) = 0 coupling the slave's part p and the master's
   !> part q.  A null vector of the rows is a mechanism: the parts with a share of
   !> it float.  Frictionless springs hold only along n, so a body resting on a
   !> frictionless plane is rightly reported as free to slide.  With `cs`, the
   !> linear constraints (*EQUATION, *TIE) resolved to independent dofs: their
   !> dependent dofs (held in `fixed`, since they are eliminated) are no supports; each
   !> equation u_d = sum a_j u_j is a row coupling the parts of its dofs instead, so a
   !> part held only through another part's equations is held, and a part whose
   !> dependent dofs hang on a floating part floats with it.  With `sliding` (the
   !> springs are those of a frictional contact iteration, where a slipping entry
   !> holds only along n), a part that its joints touch and that floats slides on
   !> them: every entry that could hold it along the joint slips at its strength, so
   !> the loads need more shear than the joints carry and no equilibrium exists.
   subroutine check_supports(model, part, nparts, fixed, error, springs, cs, sliding)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: part(:), nparts
      logical, intent(in) :: fixed(:)
      type(error_t), allocatable, intent(out) :: error
      type(spring_t), intent(in), optional :: springs(:)
      type(constraint_set_t), intent(in), optional :: cs
      logical, intent(in), optional :: sliding
      real(wp), allocatable :: lo(:, :), hi(:, :), ctc(:, :), ev(:), work(:), c(:, :), sc(:)
      integer(ip), allocatable :: nelem(:), first_elem(:)
      real(wp) :: r(6), v(3), share
      integer :: p, q, i, e, k, info, m, cols(6), nr
      logical, allocatable :: reported(:), held(:)
      character(len=200) :: buf
      character(len=:), allocatable :: motion
      if (nparts == 0) return
      m = 3*nparts
      allocate (lo(2, nparts), source=huge(1.0_wp))
      allocate (hi(2, nparts), source=-huge(1.0_wp))
      allocate (nelem(nparts), source=0_ip)
      allocate (first_elem(nparts), source=0_ip)
      do i = 1, model%nnode
         p = part(i)
         if (p == 0) cycle
         lo(:, p) = min(lo(:, p), model%x(:, i))
         hi(:, p) = max(hi(:, p), model%x(:, i))
      end do
      do e = 1, model%nelem
         p = part(model%elem_conn(model%elem_ptr(e)))
         nelem(p) = nelem(p) + 1
         if (first_elem(p) == 0) first_elem(p) = e
      end do
      allocate (c(2, nparts), sc(nparts))
      c = 0.5_wp*(lo + hi)
      sc = max(maxval(hi - lo, dim=1), tiny(1.0_wp))
      allocate (ctc(m, m), source=0.0_wp)
      held = fixed
      if (present(cs)) then
         if (cs%n > 0) held(cs%dep) = .false.
      end if
      do i = 1, model%nnode
         p = part(i)
         if (p == 0) cycle
         if (held(2*i - 1)) call add_row([1.0_wp, 0.0_wp, -(model%x(2, i) - c(2, p))/sc(p)], [3*p - 2, 3*p - 1, 3*p], 3)
         if (held(2*i)) call add_row([0.0_wp, 1.0_wp, (model%x(1, i) - c(1, p))/sc(p)], [3*p - 2, 3*p - 1, 3*p], 3)
      end do
      if (present(cs)) call equation_rows(model, part, c, sc, cs, ctc)
      if (present(springs)) then
         do k = 1, size(springs)
            p = springs(k)%part_slave
            q = springs(k)%part_master
            if (p == q .or. p == 0 .or. q == 0) cycle   ! a joint inside one body holds nothing
            associate (x => springs(k)%x, n => springs(k)%normal)
               r(1:3) = [n(1), n(2), (-n(1)*(x(2) - c(2, p)) + n(2)*(x(1) - c(1, p)))/sc(p)]
               r(4:6) = -[n(1), n(2), (-n(1)*(x(2) - c(2, q)) + n(2)*(x(1) - c(1, q)))/sc(q)]
            end associate
            cols = [3*p - 2, 3*p - 1, 3*p, 3*q - 2, 3*q - 1, 3*q]
            call add_row(r, cols, 6)
         end do
      end if
      allocate (ev(m), work(max(1, 3*m)))
      call dsyev('V', 'U', m, ctc, m, ev, work, size(work), info)
      if (info /= 0) return
      allocate (reported(nparts), source=.false.)
      ! rows are O(1): an eigenvalue below 1e-10 of the largest (at least 1) is a
      ! null vector (exactly zero in exact arithmetic)
      do k = 1, m
         if (ev(k) > 1.0e-10_wp*max(ev(m), 1.0_wp)) exit
         do p = 1, nparts
            v = ctc(3*p - 2:3*p, k)
            share = norm2(v)
            if (share < 1.0e-3_wp .or. reported(p)) cycle
            reported(p) = .true.
            nr = count(held(2*pack([(i, i=1, model%nnode)], part == p) - 1)) + &
                 count(held(2*pack([(i, i=1, model%nnode)], part == p)))
            if (nr == 0 .and. .not. touched(p) .and. .not. tied(p)) then
               motion = 'it has no support at all (no *BOUNDARY on any of its nodes'
               if (allocated(model%pairs)) then
                  if (size(model%pairs) > 0) motion = motion//' and no closed contact'
               end if
               motion = motion//')'
            else if (abs(v(3)) < 1.0e-8_wp*share) then
               write (buf, '(a,2(es10.3,a))') 'it can translate freely along (', v(1)/norm2(v(1:2)), ',', &
                  v(2)/norm2(v(1:2)), ')'
               motion = trim(buf)
            else
               write (buf, '(a,2(g0.6,a))') 'it can rotate freely about the point (', &
                  c(1, p) - v(2)/v(3)*sc(p), ', ', c(2, p) + v(1)/v(3)*sc(p), ')'
               motion = trim(buf)
            end if
            if (present(sliding)) then
               if (sliding .and. touched(p)) then
                  write (buf, '(a,i0,a,i0,a,i0,a,i0)') 'error: no equilibrium: the bodies slide on their '// &
                     'frictional joints: part ', p, ' of ', nparts, ' (', nelem(p), &
                     ' elements, among them element ', model%elem_id(first_elem(p))
                  call append_message(error, trim(buf)//' defined at '// &
                                      location_string(model, model%elem_loc(first_elem(p)))//'): '//motion// &
                                      ' with every node of its joints that could hold it slipping at the '// &
                                      'strength c A + mu N'//new_line('a')//'  = help: the joints cannot '// &
                                      'carry the shear of the loads; raise their friction or cohesion, or '// &
                                      'lower the loads (*STRENGTH REDUCTION gives the factor of safety of '// &
                                      'a joint that holds)', err_model)
                  cycle
               end if
            end if
            write (buf, '(a,i0,a,i0,a,i0,a,i0)') 'error: the model is not held: part ', p, ' of ', nparts, &
               ' (', nelem(p), ' elements, among them element ', model%elem_id(first_elem(p))
            call append_message(error, trim(buf)//' defined at '// &
                                location_string(model, model%elem_loc(first_elem(p)))//') floats: '//motion// &
                                '. Add *BOUNDARY conditions that hold it.', err_model)
         end do
      end do
   contains
      subroutine add_row(vals, idx, nv)
         real(wp), intent(in) :: vals(:)
         integer, intent(in) :: idx(:), nv
         integer :: a, b
         do b = 1, nv
            do a = 1, nv
               ctc(idx(a), idx(b)) = ctc(idx(a), idx(b)) + vals(a)*vals(b)
            end do
         end do
      end subroutine add_row
      logical function tied(pp)
         integer, intent(in) :: pp
         tied = .false.
         if (present(cs)) tied = in_equations(part, pp, cs)
      end function tied
      logical function touched(pp)
         integer, intent(in) :: pp
         integer :: kk
         touched = .false.
         if (.not. present(springs)) return
         do kk = 1, size(springs)
            if (springs(kk)%part_slave == pp .or. springs(kk)%part_master == pp) then
               touched = .true.
               return
            end if
         end do
      end function touched
   end subroutine check_supports

   !> Add to ctc the rows of the equations of `cs`: the rigid motion of the dependent
   !> dof's part at its node minus the weighted motions of its terms' parts at theirs
   !> (rows over all 3 nparts unknowns, in check_supports' scaled coordinates c, sc).
   pure subroutine equation_rows(model, part, c, sc, cs, ctc)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: part(:)
      real(wp), intent(in) :: c(:, :), sc(:)
      type(constraint_set_t), intent(in) :: cs
      real(wp), intent(inout) :: ctc(:, :)
      real(wp), allocatable :: row(:)
      integer, allocatable :: nz(:)
      integer :: q, j, a, b
      allocate (row(size(ctc, 1)))
      do q = 1, cs%n
         row = 0.0_wp
         call add_motion(row, int(cs%dep(q)), 1.0_wp)
         do j = cs%ptr(q), cs%ptr(q + 1) - 1
            call add_motion(row, int(cs%dof(j)), -cs%a(j))
         end do
         nz = pack([(j, j=1, size(row))], row /= 0.0_wp)
         do b = 1, size(nz)
            do a = 1, size(nz)
               ctc(nz(a), nz(b)) = ctc(nz(a), nz(b)) + row(nz(a))*row(nz(b))
            end do
         end do
      end do
   contains
      !> row += w times the rigid motion (translations, rotation) of the part of dof
      !> `dof` along that dof, at its node.
      pure subroutine add_motion(row, dof, w)
         real(wp), intent(inout) :: row(:)
         integer, intent(in) :: dof
         real(wp), intent(in) :: w
         integer :: node, pp
         node = (dof + 1)/2
         pp = part(node)
         if (pp == 0) return
         if (mod(dof, 2) == 1) then
            row(3*pp - 2) = row(3*pp - 2) + w
            row(3*pp) = row(3*pp) - w*(model%x(2, node) - c(2, pp))/sc(pp)
         else
            row(3*pp - 1) = row(3*pp - 1) + w
            row(3*pp) = row(3*pp) + w*(model%x(1, node) - c(1, pp))/sc(pp)
         end if
      end subroutine add_motion
   end subroutine equation_rows

   !> Whether part pp has a dof in an equation of `cs`.
   pure logical function in_equations(part, pp, cs) result(yes)
      integer(ip), intent(in) :: part(:)
      integer, intent(in) :: pp
      type(constraint_set_t), intent(in) :: cs
      integer :: q, j
      yes = .false.
      do q = 1, cs%n
         if (part((cs%dep(q) + 1)/2) == pp) yes = .true.
         do j = cs%ptr(q), cs%ptr(q + 1) - 1
            if (part((cs%dof(j) + 1)/2) == pp) yes = .true.
         end do
         if (yes) return
      end do
   end function in_equations
end module vemcontact_driver_supports
