!> *EQUATION (CalculiX/Abaqus): linear multi-point constraints.  Each
!> equation is a line with its number of terms N, then N terms (node, dof,
!> coefficient), at most four to a line (CalculiX reads 12 fields per line);
!> sum coef u = 0, and the first term's dof is the dependent one, which the
!> solver eliminates (vemcontact_driver_equations).  A node field may also name
!> a node set of one node (Abaqus/CAE writes reference points that way).
module vemcontact_deck_equations
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, equation_t, dof_value_t
   use vemcontact_deck_state, only: deck_parser_t, here, err_here, err_at, field, get_int, get_real, &
                                    node_index, get_set, set_suggestion, ref_kind, ref_id, ref_name, loc_str
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: split_fields, int_str, to_upper
   implicit none
   private

   public :: read_equation, check_equations

contains

   !> *EQUATION: its data lines, one equation after the other.
   subroutine read_equation(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(equation_t) :: eq
      integer(ip) :: nterm
      integer :: k, got, nf
      logical :: ok, bad
      call advance(p)
      do while (p%src%kind == line_data)
         call split_fields(p%src%text(1:p%src%length), p%f)
         nf = nonblank_fields(p)
         if (nf /= 1) then
            call err_here(p, '*EQUATION: expected the number of terms alone on this line, found '// &
                          int_str(nf)//' fields')
            call advance(p)
            cycle
         end if
         call get_int(p, 1, 'number of terms', nterm, ok)
         if (ok .and. nterm < 1) then
            call err_here(p, 'the number of terms of an equation must be at least 1, found '//field(p, 1))
            ok = .false.
         end if
         if (.not. ok) then
            call advance(p)
            cycle
         end if
         eq = equation_t(loc=here(p))
         allocate (eq%node(nterm), eq%dof(nterm), eq%coef(nterm))
         got = 0
         bad = .false.
         do while (got < nterm)
            call advance(p)
            if (p%src%kind /= line_data) exit
            call split_fields(p%src%text(1:p%src%length), p%f)
            nf = nonblank_fields(p)
            if (mod(nf, 3) /= 0 .or. nf == 0 .or. got + nf/3 > nterm) then
               call err_here(p, '*EQUATION: a term line holds node, dof, coefficient triples ('// &
                             int_str(nterm - got)//' terms still expected), found '//int_str(nf)//' fields')
               bad = .true.
               exit
            end if
            do k = 1, nf/3
               got = got + 1
               call read_term(p, model, 3*k - 2, eq, got, ok)
               if (.not. ok) bad = .true.
            end do
         end do
         if (got < nterm .and. .not. bad) then
            call err_at(p, eq%loc, 'the equation has '//int_str(nterm)//' terms, found '//int_str(got))
            bad = .true.
         end if
         if (.not. bad) call add_equation(model, eq)
         if (p%src%kind == line_data) call advance(p)
      end do
   end subroutine read_equation

   !> Fields of the current line without the empty ones a trailing comma leaves.
   integer function nonblank_fields(p) result(n)
      type(deck_parser_t), intent(in) :: p
      n = p%f%n
      do while (n > 0)
         if (len_trim(field(p, n)) > 0) exit
         n = n - 1
      end do
   end function nonblank_fields

   !> Term `it` of `eq` from fields k, k+1, k+2 of the current line.
   subroutine read_term(p, model, k, eq, it, ok)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer, intent(in) :: k, it
      type(equation_t), intent(inout) :: eq
      logical, intent(out) :: ok
      integer :: kind, kset
      integer(ip) :: id, dof
      character(len=:), allocatable :: name
      ok = .false.
      call ref_kind(p, k, kind, id, 'node')
      if (kind == ref_id) then
         eq%node(it) = node_index(p, model, id)
         if (eq%node(it) == 0) then
            call err_here(p, 'undefined node '//field(p, k)//' in *EQUATION', &
                          'nodes must be defined before the equations that use them')
            return
         end if
      else if (kind == ref_name) then
         name = to_upper(trim(adjustl(field(p, k))))
         call get_set(model%nsets, p%nset_items, p%nnset, name, here(p), .false., kset)
         if (kset == 0) then
            call err_here(p, 'undefined node set '//name//' in *EQUATION', &
                          set_suggestion(model%nsets, p%nnset, name))
            return
         end if
         if (p%nset_items(kset)%n /= 1) then
            call err_here(p, 'node set '//name//' of an *EQUATION term must hold exactly one node, it holds '// &
                          int_str(p%nset_items(kset)%n), 'write one equation per node')
            return
         end if
         eq%node(it) = p%nset_items(kset)%a(1)
      else
         return
      end if
      call get_int(p, k + 1, 'degree of freedom', dof, ok)
      if (.not. ok) return
      if (dof < 1 .or. dof > 2) then
         call err_here(p, 'degree of freedom '//field(p, k + 1)//' in *EQUATION: a 2D model has dofs 1 (x) '// &
                       'and 2 (y)')
         ok = .false.
         return
      end if
      eq%dof(it) = int(dof)
      call get_real(p, k + 2, 'coefficient', eq%coef(it), ok, required=.true.)
      if (.not. ok) return
      if (it == 1 .and. .not. abs(eq%coef(1)) > 0.0_wp) then
         call err_here(p, 'the first term of an equation (its dependent dof) needs a non-zero coefficient')
         ok = .false.
      end if
   end subroutine read_term

   subroutine add_equation(model, eq)
      type(model_t), intent(inout) :: model
      type(equation_t), intent(in) :: eq
      type(equation_t), allocatable :: t(:)
      integer :: n
      if (.not. allocated(model%equations)) allocate (model%equations(0))
      n = size(model%equations)
      allocate (t(n + 1))
      t(1:n) = model%equations
      t(n + 1) = eq
      call move_alloc(t, model%equations)
   end subroutine add_equation

   !> After the deck: a dependent dof is dependent in one equation only and not
   !> prescribed by *BOUNDARY, and no equation names a dof twice (the elimination
   !> relies on it).  A dependent dof may be a term of other equations, as in
   !> CalculiX: the solver substitutes it.
   subroutine check_equations(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      integer, allocatable :: owner(:)
      integer :: q, i, j, s
      integer(ip) :: d
      if (.not. allocated(model%equations)) return
      allocate (owner(2*model%nnode))
      owner = 0
      do q = 1, size(model%equations)
         associate (eq => model%equations(q))
            d = 2*eq%node(1) - 2 + eq%dof(1)
            if (owner(d) > 0) then
               call err_at(p, eq%loc, 'dof '//int_str(eq%dof(1))//' of node '//int_str(model%node_id(eq%node(1)))// &
                           ' is dependent in two equations (also at '// &
                           loc_str(p, model%equations(owner(d))%loc)//')')
            end if
            owner(d) = q
            do i = 1, size(eq%node)
               do j = i + 1, size(eq%node)
                  if (eq%node(i) == eq%node(j) .and. eq%dof(i) == eq%dof(j)) then
                     call err_at(p, eq%loc, 'the equation names dof '//int_str(eq%dof(i))//' of node '// &
                                 int_str(model%node_id(eq%node(i)))//' twice')
                  end if
               end do
            end do
         end associate
      end do
      call check_boundary(model%initial%boundary)
      if (allocated(model%steps)) then
         do s = 1, size(model%steps)
            call check_boundary(model%steps(s)%boundary)
         end do
      end if
   contains
      subroutine check_boundary(b)
         type(dof_value_t), intent(in), allocatable :: b(:)
         integer :: k, q
         if (.not. allocated(b)) return
         do k = 1, size(b)
            q = owner(2*b(k)%node - 2 + b(k)%dof)
            if (q > 0) call err_at(p, model%equations(q)%loc, 'the dependent dof (first term) of the equation, '// &
                                   'dof '//int_str(b(k)%dof)//' of node '//int_str(model%node_id(b(k)%node))// &
                                   ', is also prescribed by *BOUNDARY', &
                                   'make another dof of the equation its first term')
         end do
      end subroutine check_boundary
   end subroutine check_equations
end module vemcontact_deck_equations
