!> The frozen system of a frictional contact state solved exactly with the factor
!> of another contact state of the same pairing, and the contact compliance that
!> the multipliers' Newton step needs, on the contact space
!> (docs/contact-formulation.md, "Solving the frictional system").
!>
!> Call K0 the matrix of the current factor, whose contact part is that of the
!> factor's key (vemcontact_contact_rules, matrix_key_t).  With the same pairing,
!> the frozen tangent J of any other contact state differs from K0 by a term of
!> rank at most two per entry whose springs or states differ:
!>
!>     J = K0 + sum_i [n_i t_i] M_i [n_i t_i]^T
!>
!> with n_i = n.A(xi), t_i = t.A(xi) the entry's normal and tangential rows (zero at
!> the fixed dofs) and the 2 x 2 matrix M_i: the change of the normal spring (k now
!> if active, minus k of the key if active then), of the tangential spring (kt if
!> it sticks now, minus the key's kt if it stuck then) and, for a slipping entry, -dT/dN k
!> in the row of t and the column of n (its force follows its normal force: the
!> unsymmetric part).  Each nonzero row d of M_i is a column b_{i,d} of U and the
!> row M_i(d, :) [n_i t_i]^T of V^T (r pairs in all), and the Sherman-Morrison-
!> Woodbury identity solves J x = f with two solves by K0 and a dense r x r system,
!> the capacitance I + V^T K0^-1 U:
!>
!>     w = K0^-1 f,   (I + V^T K0^-1 U) z = V^T w,   x = K0^-1 (f - U z).
!>
!> The capacitance needs the columns K0^-1 b_{i,d} only through their projections
!> on the contact rows: `compliance_cache_t` keeps, per factor, the projections of
!> the columns computed so far on every entry's normal and tangential rows (2 x n
!> numbers per column, where the column itself would take 8 MB at 1e6 unknowns),
!> and gains columns lazily.  The same projections give the compliance
!> H = B J^-1 B^T of any set of contact rows under J (contact_compliance), with
!> which the multipliers of HARD and of exact stick take a Newton step.
module vemcontact_contact_condensed
   use vemcontact_kinds, only: wp, ip
   use vemcontact_contact_active_set, only: contact_state_t
   use vemcontact_contact_rules, only: matrix_key_t
   use vemcontact_contact_friction, only: tangent_stick, tangent_slip
   use vemcontact_contact_geometry, only: relative_map
   use vemcontact_linalg_lapack, only: dgetrf, dgetrs
   implicit none
   private

   public :: compliance_cache_t, woodbury_t, same_pairing, scatter_rows, store_columns
   public :: build_woodbury, woodbury_rhs, woodbury_correction, contact_compliance

   !> The row directions of an entry: its normal row n.A(xi), its tangential row t.A(xi).
   integer, parameter, public :: row_normal = 1, row_tangent = 2

   !> The projections of the columns K0^-1 b_{i,d} computed with the current factor.
   type :: compliance_cache_t
      !> (direction, entry): the index of its column (0: not computed)
      integer, allocatable :: col(:, :)
      integer :: ncol = 0
      !> (entry, column): n_i . K0^-1 b and t_i . K0^-1 b
      real(wp), allocatable :: pn(:, :), pt(:, :)
   contains
      procedure :: reset
      procedure :: missing
   end type compliance_cache_t

   !> The low-rank difference J - K0 of one frozen system and its factored capacitance.
   type :: woodbury_t
      integer :: r = 0
      !> per pair a: the entry, the direction d of its column b_{i,d} in U, and the
      !> row M_i(d, :) (coefficients of n_i and t_i in its row of V^T)
      integer, allocatable :: entry(:), dir(:)
      real(wp), allocatable :: m(:, :)
      !> LU factors of the capacitance I + V^T K0^-1 U, and its pivots
      real(wp), allocatable :: cap(:, :)
      integer, allocatable :: ipiv(:)
   end type woodbury_t

contains

   !> Forget every column (a new factor).
   pure subroutine reset(self, n)
      class(compliance_cache_t), intent(inout) :: self
      integer, intent(in) :: n
      self%ncol = 0
      if (allocated(self%col)) deallocate (self%col)
      allocate (self%col(2, n), source=0)
      if (allocated(self%pn)) deallocate (self%pn, self%pt)
      allocate (self%pn(n, 0), self%pt(n, 0))
   end subroutine reset

   !> The (direction, entry) pairs of `need` whose column is not computed yet, as
   !> rows of a (2, m) array.
   pure function missing(self, need) result(list)
      class(compliance_cache_t), intent(in) :: self
      logical, intent(in) :: need(:, :)
      integer, allocatable :: list(:, :)
      integer :: i, d, m
      allocate (list(2, count(need .and. self%col == 0)))
      m = 0
      do i = 1, size(need, 2)
         do d = 1, 2
            if (.not. (need(d, i) .and. self%col(d, i) == 0)) cycle
            m = m + 1
            list(:, m) = [d, i]
         end do
      end do
   end function missing

   !> Whether every entry that is active now or was in the key has the key's
   !> pairing (segment, xi, normal): then the matrices differ by the terms M_i.
   pure logical function same_pairing(key, contact) result(same)
      type(matrix_key_t), intent(in) :: key
      type(contact_state_t), intent(in) :: contact
      integer :: i
      same = allocated(key%active) .and. allocated(contact%fric%state)
      if (same) same = size(key%active) == contact%n
      if (.not. same) return
      do i = 1, contact%n
         if (.not. (contact%active(i) .or. key%active(i))) cycle
         same = key%iseg(i) == contact%iseg(i) .and. key%iseg(i) > 0 .and. identical(key%xi(i), contact%xi(i)) &
                .and. identical(key%normal(1, i), contact%normal(1, i)) .and. &
                identical(key%normal(2, i), contact%normal(2, i))
         if (.not. same) return
      end do
   end function same_pairing

   !> The rows b_{i,1} = n.A(xi) and b_{i,2} = t.A(xi) of entry i on its three nodes
   !> (slave, segment start, segment end), with the entries of fixed dofs zeroed.
   pure subroutine entry_rows(contact, fixed, i, nodes, b)
      type(contact_state_t), intent(in) :: contact
      logical, intent(in) :: fixed(:)
      integer, intent(in) :: i
      integer(ip), intent(out) :: nodes(3)
      real(wp), intent(out) :: b(6, 2)
      integer :: j
      nodes = [contact%node(i), contact%pairs(contact%pair(i))%seg(:, contact%iseg(i))]
      b(:, row_normal) = matmul(contact%normal(:, i), relative_map(contact%xi(i)))
      b(:, row_tangent) = matmul([-contact%normal(2, i), contact%normal(1, i)], relative_map(contact%xi(i)))
      do j = 1, 3
         if (fixed(2*nodes(j) - 1)) b(2*j - 1, :) = 0.0_wp
         if (fixed(2*nodes(j))) b(2*j, :) = 0.0_wp
      end do
   end subroutine entry_rows

   !> The entries of x at an entry's three nodes.
   pure function gather(x, nodes) result(xe)
      real(wp), intent(in) :: x(:)
      integer(ip), intent(in) :: nodes(3)
      real(wp) :: xe(6)
      integer :: j
      do j = 1, 3
         xe(2*j - 1:2*j) = x(2*nodes(j) - 1:2*nodes(j))
      end do
   end function gather

   !> b(:, c) = the row list(1, c) of entry list(2, c), for the solves of new columns.
   pure subroutine scatter_rows(contact, fixed, list, b)
      type(contact_state_t), intent(in) :: contact
      logical, intent(in) :: fixed(:)
      integer, intent(in) :: list(:, :)
      real(wp), intent(out) :: b(:, :)
      integer(ip) :: nodes(3)
      real(wp) :: be(6, 2)
      integer :: c, j
      b = 0.0_wp
      do c = 1, size(list, 2)
         call entry_rows(contact, fixed, list(2, c), nodes, be)
         do j = 1, 3
            b(2*nodes(j) - 1:2*nodes(j), c) = b(2*nodes(j) - 1:2*nodes(j), c) + be(2*j - 1:2*j, list(1, c))
         end do
      end do
   end subroutine scatter_rows

   !> Keep the projections of the solved columns z(:, c) = K0^-1 b_list(:, c) on the
   !> rows of every entry with a master segment.
   pure subroutine store_columns(self, contact, fixed, list, z)
      type(compliance_cache_t), intent(inout) :: self
      type(contact_state_t), intent(in) :: contact
      logical, intent(in) :: fixed(:)
      integer, intent(in) :: list(:, :)
      real(wp), intent(in) :: z(:, :)
      real(wp), allocatable :: pn(:, :), pt(:, :)
      integer(ip) :: nodes(3)
      real(wp) :: be(6, 2), ze(6)
      integer :: c, i, m
      m = size(list, 2)
      allocate (pn(contact%n, self%ncol + m), pt(contact%n, self%ncol + m), source=0.0_wp)
      pn(:, 1:self%ncol) = self%pn
      pt(:, 1:self%ncol) = self%pt
      do i = 1, contact%n
         if (contact%iseg(i) <= 0) cycle
         call entry_rows(contact, fixed, i, nodes, be)
         do c = 1, m
            ze = gather(z(:, c), nodes)
            pn(i, self%ncol + c) = dot_product(be(:, row_normal), ze)
            pt(i, self%ncol + c) = dot_product(be(:, row_tangent), ze)
         end do
      end do
      do c = 1, m
         self%col(list(1, c), list(2, c)) = self%ncol + c
      end do
      self%ncol = self%ncol + m
      call move_alloc(pn, self%pn)
      call move_alloc(pt, self%pt)
   end subroutine store_columns

   !> The projection of the cached column of (direction d, entry j) on row e of entry i.
   pure real(wp) function proj(cache, e, i, d, j)
      type(compliance_cache_t), intent(in) :: cache
      integer, intent(in) :: e, i, d, j
      if (e == row_normal) then
         proj = cache%pn(i, cache%col(d, j))
      else
         proj = cache%pt(i, cache%col(d, j))
      end if
   end function proj

   !> The terms M_i by which the frozen tangent of `contact` differs from the
   !> factor's matrix (key), as the pairs of U and V (see the module); `need` marks
   !> the columns K0^-1 b_{i,d} of U.
   pure subroutine differing_rows(key, contact, wb, need)
      type(matrix_key_t), intent(in) :: key
      type(contact_state_t), intent(in) :: contact
      type(woodbury_t), intent(out) :: wb
      logical, intent(out) :: need(:, :)
      real(wp) :: m(2, 2, contact%n)
      logical :: on, was
      integer :: i, d, a
      m = 0.0_wp
      do i = 1, contact%n
         on = contact%active(i)
         was = key%active(i)
         m(1, 1, i) = merge(contact%k(i), 0.0_wp, on) - merge(key%k(i), 0.0_wp, was)
         ! the key's own springs: a *CHANGE FRICTION between them changes kt
         m(2, 2, i) = merge(contact%fric%kt(i), 0.0_wp, on .and. contact%fric%state(i) == tangent_stick) - &
                      merge(key%kt(i), 0.0_wp, was .and. key%stick(i))
         if (on .and. contact%fric%state(i) == tangent_slip) m(2, 1, i) = -contact%fric%dnormal(i)*contact%k(i)
      end do
      need = abs(m(:, 1, :)) > 0.0_wp .or. abs(m(:, 2, :)) > 0.0_wp
      wb%r = count(need)
      allocate (wb%entry(wb%r), wb%dir(wb%r), wb%m(2, wb%r))
      a = 0
      do i = 1, contact%n
         do d = 1, 2
            if (.not. need(d, i)) cycle
            a = a + 1
            wb%entry(a) = i
            wb%dir(a) = d
            wb%m(:, a) = m(d, :, i)
         end do
      end do
   end subroutine differing_rows

   !> The difference J - K0 of `contact`'s frozen tangent (its columns to `need`)
   !> and, when the cache holds them (`ready`), the LU factors of its capacitance;
   !> ok false when the capacitance is singular.
   pure subroutine build_woodbury(key, contact, cache, wb, need, ready, ok)
      type(matrix_key_t), intent(in) :: key
      type(contact_state_t), intent(in) :: contact
      type(compliance_cache_t), intent(in) :: cache
      type(woodbury_t), intent(out) :: wb
      logical, intent(out) :: need(:, :)
      logical, intent(in) :: ready
      logical, intent(out) :: ok
      integer :: a, b, e, info
      call differing_rows(key, contact, wb, need)
      ok = .true.
      if (.not. ready .or. wb%r == 0) return
      allocate (wb%cap(wb%r, wb%r), wb%ipiv(wb%r))
      ! row a, column b: M(d_a, :) [n t]^T K0^-1 b_{j_b, d_b}
      do b = 1, wb%r
         do a = 1, wb%r
            wb%cap(a, b) = 0.0_wp
            do e = 1, 2
               if (abs(wb%m(e, a)) > 0.0_wp) wb%cap(a, b) = wb%cap(a, b) + &
                  wb%m(e, a)*proj(cache, e, wb%entry(a), wb%dir(b), wb%entry(b))
            end do
         end do
         wb%cap(b, b) = wb%cap(b, b) + 1.0_wp
      end do
      call dgetrf(wb%r, wb%r, wb%cap, wb%r, wb%ipiv, info)
      ok = info == 0
   end subroutine build_woodbury

   !> z = (I + V^T K0^-1 U)^-1 V^T w for w = K0^-1 f.
   pure subroutine woodbury_rhs(wb, contact, fixed, w, z)
      type(woodbury_t), intent(in) :: wb
      type(contact_state_t), intent(in) :: contact
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: w(:)
      real(wp), intent(out) :: z(:)
      integer(ip) :: nodes(3)
      real(wp) :: be(6, 2)
      integer :: a, info
      do a = 1, wb%r
         call entry_rows(contact, fixed, wb%entry(a), nodes, be)
         z(a) = dot_product(matmul(be, wb%m(:, a)), gather(w, nodes))
      end do
      if (wb%r > 0) call dgetrs('N', wb%r, 1, wb%cap, wb%r, wb%ipiv, z, wb%r, info)
   end subroutine woodbury_rhs

   !> f = f - U z: the right-hand side of the second solve, x = K0^-1 (f - U z).
   pure subroutine woodbury_correction(wb, contact, fixed, z, f)
      type(woodbury_t), intent(in) :: wb
      type(contact_state_t), intent(in) :: contact
      logical, intent(in) :: fixed(:)
      real(wp), intent(in) :: z(:)
      real(wp), intent(inout) :: f(:)
      integer(ip) :: nodes(3)
      real(wp) :: be(6, 2)
      integer :: a, j
      do a = 1, wb%r
         call entry_rows(contact, fixed, wb%entry(a), nodes, be)
         do j = 1, 3
            f(2*nodes(j) - 1:2*nodes(j)) = f(2*nodes(j) - 1:2*nodes(j)) - z(a)*be(2*j - 1:2*j, wb%dir(a))
         end do
      end do
   end subroutine woodbury_correction

   !> H(p, q) = b_p . J^-1 b_q for the rows `list` (list(:, p) = [direction, entry],
   !> whose columns the cache holds), J = K0 + U V^T:
   !> b_p.K0^-1 b_q - b_p.K0^-1 U (I + V^T K0^-1 U)^-1 V^T K0^-1 b_q, where
   !> b_p.K0^-1 U = U^T K0^-1 b_p (K0 is symmetric).
   pure subroutine contact_compliance(wb, cache, list, h)
      type(woodbury_t), intent(in) :: wb
      type(compliance_cache_t), intent(in) :: cache
      integer, intent(in) :: list(:, :)
      real(wp), intent(out) :: h(:, :)
      real(wp), allocatable :: vz(:, :), bu(:, :)
      integer :: p, q, a, e, info, m
      m = size(list, 2)
      do q = 1, m
         do p = 1, m
            h(p, q) = proj(cache, list(1, p), list(2, p), list(1, q), list(2, q))
         end do
      end do
      if (wb%r == 0) return
      allocate (vz(wb%r, m), bu(m, wb%r), source=0.0_wp)
      do q = 1, m
         do a = 1, wb%r
            do e = 1, 2
               if (abs(wb%m(e, a)) > 0.0_wp) vz(a, q) = vz(a, q) + &
                  wb%m(e, a)*proj(cache, e, wb%entry(a), list(1, q), list(2, q))
            end do
         end do
      end do
      do a = 1, wb%r
         do p = 1, m
            bu(p, a) = proj(cache, wb%dir(a), wb%entry(a), list(1, p), list(2, p))
         end do
      end do
      call dgetrs('N', wb%r, m, wb%cap, wb%r, wb%ipiv, vz, wb%r, info)
      h = h - matmul(bu, vz)
   end subroutine contact_compliance

   !> a and b are the same number (neither is less or greater).
   elemental logical function identical(a, b)
      real(wp), intent(in) :: a, b
      identical = .not. (a < b .or. a > b)
   end function identical
end module vemcontact_contact_condensed
