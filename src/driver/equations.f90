!> Linear multi-point constraints (*EQUATION, CalculiX's meaning): sum_i c_i u_i = 0
!> over the terms of an equation, the first term's dof dependent.  They are
!> eliminated by the transformation u = T v, v the other dofs: with
!> u_d = sum_j a_j u_j (a_j = -c_j / c_1), the stiffness becomes T^T K T,
!>    K_ij + a_i K_dj + K_id a_j + a_i K_dd a_j   (i, j other than d),
!> and the loads T^T f, f_i + a_i f_d.  T^T K T stays symmetric positive
!> definite on the free dofs, so CHOLMOD's Cholesky factorization applies as
!> without constraints; the row and column of d are emptied and d is held like a
!> fixed dof (value 0), and after the solve u_d is recovered from the equation.
!> A dependent dof may be a term of another equation (CalculiX's oneel.inp chains
!> u3y = u4y, u4y = u7y): `resolve_equations` first substitutes every dependent
!> term by its own equation until each dependent dof is written in independent
!> dofs only (a cycle is an error).  The resolved equations are then eliminated
!> one after the other; none refers to another's dependent dof, so the product
!> of their transformations is the whole T.  Since T^T K T couples the
!> independent dofs of an equation with each other and with every neighbour of
!> the dependent node, `equation_pairs` adds those node pairs to the pattern.
!> Reactions K u - f at the fixed dofs are those of T^T K T, since T^T (K u - f)
!> equals K u - f at every dof but d, where the residual is zero.
module vemcontact_driver_equations
   use vemcontact_kinds, only: wp, ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_internal, err_input
   use vemcontact_model, only: model_t, equation_t, location_string
   use vemcontact_driver_tie, only: tie_equations
   use vemcontact_sparse_matrix, only: sym_csc_t
   use vemcontact_sparse_pattern, only: block_offset
   use vemcontact_contact_search, only: merge_node_pairs
   implicit none
   private

   public :: constraint_set_t, resolve_equations, equation_graph, eliminate_equations, transform_loads, &
             recover_dependent, dependent_dofs

   !> The terms of one equation while it is resolved.
   type :: term_list_t
      integer(ip), allocatable :: dof(:)
      real(wp), allocatable :: a(:)
   end type term_list_t

   !> The resolved equations: u(dep(q)) = sum over p in ptr(q) .. ptr(q+1)-1 of
   !> a(p) u(dof(p)), no dof(p) dependent.
   type :: constraint_set_t
      integer :: n = 0
      integer(ip), allocatable :: dep(:)
      integer, allocatable :: ptr(:)
      integer(ip), allocatable :: dof(:)
      real(wp), allocatable :: a(:)
   end type constraint_set_t

contains

   !> Resolve the model's equations into `cs`: each dependent dof in terms of
   !> independent dofs only, substituting dependent terms by their equations.
   subroutine resolve_equations(model, cs, error)
      type(model_t), intent(in) :: model
      type(constraint_set_t), intent(out) :: cs
      type(error_t), allocatable, intent(out) :: error
      integer, allocatable :: owner(:)
      type(term_list_t), allocatable :: rows(:)
      type(equation_t), allocatable :: eqs(:), tied(:)
      integer :: q, i, pass, nq, r, k
      logical :: changed
      call tie_equations(model, tied, error)
      if (allocated(error)) return
      if (allocated(model%equations)) then
         eqs = [model%equations, tied]
      else
         eqs = tied
      end if
      nq = size(eqs)
      if (nq == 0) then
         allocate (cs%dep(0), cs%ptr(1), cs%dof(0), cs%a(0))
         cs%ptr(1) = 1
         return
      end if
      allocate (owner(2*model%nnode), rows(nq), cs%dep(nq))
      owner = 0
      do q = 1, nq
         associate (eq => eqs(q))
            cs%dep(q) = 2*eq%node(1) - 2 + eq%dof(1)
            owner(cs%dep(q)) = q
            rows(q)%dof = [(2*eq%node(i) - 2 + eq%dof(i), i=2, size(eq%node))]
            rows(q)%a = [(-eq%coef(i)/eq%coef(1), i=2, size(eq%node))]
         end associate
      end do
      do pass = 1, nq + 1
         changed = .false.
         do q = 1, nq
            k = 1
            do while (k <= size(rows(q)%dof))
               r = owner(rows(q)%dof(k))
               if (r == q) then
                  call fatal_error(error, location_string(model, eqs(q)%loc)// &
                                   ': error: the equation''s dependent dof depends on itself through the '// &
                                   '*EQUATION chain', err_input)
                  return
               end if
               if (r > 0) then
                  call substitute(rows(q), k, rows(r))
                  changed = .true.
               else
                  k = k + 1
               end if
            end do
         end do
         if (.not. changed) exit
      end do
      if (changed) then
         call fatal_error(error, location_string(model, eqs(1)%loc)// &
                          ': error: the *EQUATION constraints depend on each other in a cycle', err_input)
         return
      end if
      cs%n = nq
      allocate (cs%ptr(nq + 1))
      cs%ptr(1) = 1
      do q = 1, nq
         cs%ptr(q + 1) = cs%ptr(q) + size(rows(q)%dof)
      end do
      allocate (cs%dof(cs%ptr(nq + 1) - 1), cs%a(cs%ptr(nq + 1) - 1))
      do q = 1, nq
         cs%dof(cs%ptr(q):cs%ptr(q + 1) - 1) = rows(q)%dof
         cs%a(cs%ptr(q):cs%ptr(q + 1) - 1) = rows(q)%a
      end do
   end subroutine resolve_equations

   !> Replace term k of `row` (a dependent dof) by a(k) times the terms of `by`,
   !> adding coefficients of a dof already in `row`.
   pure subroutine substitute(row, k, by)
      type(term_list_t), intent(inout) :: row
      integer, intent(in) :: k
      type(term_list_t), intent(in) :: by
      real(wp) :: c
      integer :: i, j
      c = row%a(k)
      row%dof = [row%dof(:k - 1), row%dof(k + 1:)]
      row%a = [row%a(:k - 1), row%a(k + 1:)]
      do i = 1, size(by%dof)
         j = findloc(row%dof, by%dof(i), dim=1)
         if (j > 0) then
            row%a(j) = row%a(j) + c*by%a(i)
         else
            row%dof = [row%dof, by%dof(i)]
            row%a = [row%a, c*by%a(i)]
         end if
      end do
   end subroutine substitute

   !> The node graph adj_ptr/adj (CSR, symmetric, sorted) grown by the couplings
   !> T^T K T makes: the independent nodes of each equation with each other and
   !> with the neighbours of its dependent node, repeated until no pair is new (a
   !> later equation's dependent node may gain neighbours from an earlier one).
   subroutine equation_graph(nnode, cs, adj_ptr, adj, error)
      integer(ip), intent(in) :: nnode
      type(constraint_set_t), intent(in) :: cs
      integer(i8), allocatable, intent(inout) :: adj_ptr(:)
      integer(ip), allocatable, intent(inout) :: adj(:)
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: pairs(:, :), adj2(:)
      integer(i8), allocatable :: ptr2(:)
      integer(ip) :: nd, a
      integer(i8) :: k
      integer :: q, i, j, np, pass
      if (cs%n == 0) return
      do pass = 1, 100
         allocate (pairs(2, 64))
         np = 0
         do q = 1, cs%n
            nd = (cs%dep(q) + 1)/2
            do i = cs%ptr(q), cs%ptr(q + 1) - 1
               a = (cs%dof(i) + 1)/2
               call add(a, nd)
               do j = cs%ptr(q), cs%ptr(q + 1) - 1
                  call add(a, (cs%dof(j) + 1)/2)
               end do
               do k = adj_ptr(nd), adj_ptr(nd + 1) - 1
                  call add(a, adj(k))
               end do
            end do
         end do
         if (np == 0) return
         call merge_node_pairs(nnode, adj_ptr, adj, pairs(:, :np), ptr2, adj2, error)
         if (allocated(error)) return
         deallocate (pairs)
         call move_alloc(ptr2, adj_ptr)
         call move_alloc(adj2, adj)
      end do
      call fatal_error(error, 'internal error: the pattern of the *EQUATION constraints does not settle', &
                       err_internal)
   contains
      !> Record the pair (x, y) unless it is a self pair or already in the graph.
      subroutine add(x, y)
         integer(ip), intent(in) :: x, y
         integer(ip), allocatable :: t(:, :)
         integer(i8) :: kk
         if (x == y) return
         do kk = adj_ptr(x), adj_ptr(x + 1) - 1
            if (adj(kk) == y) return
         end do
         if (np == size(pairs, 2)) then
            allocate (t(2, 2*np))
            t(:, 1:np) = pairs(:, 1:np)
            call move_alloc(t, pairs)
         end if
         np = np + 1
         pairs(:, np) = [x, y]
      end subroutine add
   end subroutine equation_graph

   !> The dependent dof of every equation (held like fixed dofs with value 0 in the solve).
   pure function dependent_dofs(cs, ndof) result(dep)
      type(constraint_set_t), intent(in) :: cs
      integer, intent(in) :: ndof
      logical :: dep(ndof)
      integer :: q
      dep = .false.
      do q = 1, cs%n
         dep(cs%dep(q)) = .true.
      end do
   end function dependent_dofs

   !> k <- T^T k T, equation by equation.  Linear in k: on several processes each
   !> passes its share of the matrix, and the eliminated shares add up to T^T K T.  The pattern and
   !> its node graph adj_ptr/adj must come from equation_graph (the rows of column d
   !> below its diagonal are found through the neighbours of d's node, so the work
   !> is that of the couplings, not of the matrix size).  `ok` false if an entry is
   !> missing from the pattern.
   subroutine eliminate_equations(cs, k, adj_ptr, adj, ok)
      type(constraint_set_t), intent(in) :: cs
      type(sym_csc_t), intent(inout) :: k
      integer(i8), intent(in) :: adj_ptr(:)
      integer(ip), intent(in) :: adj(:)
      logical, intent(out) :: ok
      real(wp), allocatable :: col(:)
      integer(ip), allocatable :: rows(:)
      integer(ip) :: d, r
      integer(i8) :: p
      integer :: q, nr, i, jj
      real(wp) :: kdd
      ok = .true.
      if (cs%n == 0) return
      allocate (col(k%n), rows(k%n))
      do q = 1, cs%n
         d = cs%dep(q)
         ! column d of the full symmetric matrix (rows r /= d), then zero it
         nr = 0
         do p = k%col_ptr(d), k%col_ptr(d + 1) - 2
            nr = nr + 1
            rows(nr) = k%row_idx(p)
            col(nr) = k%val(p)
            k%val(p) = 0.0_wp
         end do
         if (mod(d, 2) == 1) call take(d + 1)
         do p = adj_ptr((d + 1)/2), adj_ptr((d + 1)/2 + 1) - 1
            if (adj(p) <= (d + 1)/2) cycle
            call take(2*adj(p) - 1)
            call take(2*adj(p))
         end do
         kdd = k%val(k%col_ptr(d + 1) - 1)
         do i = cs%ptr(q), cs%ptr(q + 1) - 1
            ! a_i K_dr (+ K_rd a_i on the same stored entry when r is the term's dof)
            do jj = 1, nr
               r = rows(jj)
               call add_to(cs%dof(i), r, cs%a(i)*col(jj)*merge(2.0_wp, 1.0_wp, cs%dof(i) == r))
               if (.not. ok) return
            end do
            ! a_i K_dd a_j, each unordered pair of terms once
            do jj = i, cs%ptr(q + 1) - 1
               call add_to(cs%dof(i), cs%dof(jj), cs%a(i)*kdd*cs%a(jj)*1.0_wp)
               if (.not. ok) return
            end do
         end do
      end do
   contains
      !> Entry (d, j), j > d, into the list of column d's rows, and zero it.
      subroutine take(jj)
         integer(ip), intent(in) :: jj
         integer(i8) :: pp
         pp = find(k, d, jj)
         if (pp <= 0) return
         nr = nr + 1
         rows(nr) = jj
         col(nr) = k%val(pp)
         k%val(pp) = 0.0_wp
      end subroutine take

      !> k(x, y) += v for the symmetric pair (one stored entry).
      subroutine add_to(x, y, v)
         integer(ip), intent(in) :: x, y
         real(wp), intent(in) :: v
         integer(i8) :: pp
         pp = find(k, min(x, y), max(x, y))
         if (pp <= 0) then
            ok = .false.
            return
         end if
         k%val(pp) = k%val(pp) + v
      end subroutine add_to
   end subroutine eliminate_equations

   !> Position of entry (r, c), r <= c, in the upper-triangle matrix; 0 if absent.
   pure integer(i8) function find(k, r, c)
      type(sym_csc_t), intent(in) :: k
      integer(ip), intent(in) :: r, c
      integer(i8) :: off, first
      integer(ip) :: rn, cn
      rn = (r + 1)/2
      cn = (c + 1)/2
      off = block_offset(k, rn, cn)
      find = 0
      if (off < 0) return
      ! column c's entries of node rn: its x row, then its y row (the y row of the
      ! diagonal block of column 2 cn - 1 lies below the diagonal and is not stored)
      first = k%col_ptr(c) + off
      if (mod(r, 2) == 0) first = first + 1
      if (first >= k%col_ptr(c + 1)) return
      if (k%row_idx(first) == r) find = first
   end function find

   !> f <- T^T f: the load on each dependent dof moved to the dofs it depends on.
   pure subroutine transform_loads(cs, f)
      type(constraint_set_t), intent(in) :: cs
      real(wp), intent(inout) :: f(:)
      integer :: q, i
      do q = 1, cs%n
         do i = cs%ptr(q), cs%ptr(q + 1) - 1
            f(cs%dof(i)) = f(cs%dof(i)) + cs%a(i)*f(cs%dep(q))
         end do
         f(cs%dep(q)) = 0.0_wp
      end do
   end subroutine transform_loads

   !> u_d = sum_j a_j u_j of every equation (its terms are independent dofs).
   pure subroutine recover_dependent(cs, u)
      type(constraint_set_t), intent(in) :: cs
      real(wp), intent(inout) :: u(:)
      integer :: q, i
      do q = 1, cs%n
         u(cs%dep(q)) = 0.0_wp
         do i = cs%ptr(q), cs%ptr(q + 1) - 1
            u(cs%dep(q)) = u(cs%dep(q)) + cs%a(i)*u(cs%dof(i))
         end do
      end do
   end subroutine recover_dependent
end module vemcontact_driver_equations
