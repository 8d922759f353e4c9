!> *STRENGTH REDUCTION (vemcontact), the step procedure of a factor of safety by
!> strength reduction in place of *STATIC (docs/deck-reference.md,
!> docs/sliding-safety.md):
!>
!>   *STRENGTH REDUCTION [, INTERACTION=name] [, TOLERANCE=t] [, NSET=name]
!>   [first trial factor [, largest factor]]
!>
!> The step starts from the previous step's converged state and keeps its loads, so it
!> can be neither the first step nor carry loads of its own (end_step refuses them).
module vemcontact_deck_strength_reduction
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: model_t, procedure_strength_reduction
   use vemcontact_deck_state, only: deck_parser_t, err_here, field, get_real, loc_str, get_set, set_suggestion, here
   use vemcontact_deck_fields, only: keyword_line_t, split_fields, get_param, to_upper, squeeze
   use vemcontact_deck_numbers, only: parse_real, num_ok
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   implicit none
   private

   public :: read_strength_reduction, reducible

   character(len=*), parameter :: data_help = 'the optional data line is: first trial factor F (default: the '// &
                                              'estimate of the trial at F = 1), largest factor (default 100); '// &
                                              'both > 1, the first at most the largest'

contains

   !> Whether interaction k's friction can be reduced: Coulomb or Mohr-Coulomb
   !> (*FRICTION with mu > 0 or a cohesion, not ROUGH, which has no strength to divide).
   pure logical function reducible(model, k)
      type(model_t), intent(in) :: model
      integer, intent(in) :: k
      associate (it => model%interactions(k))
         reducible = it%has_friction .and. .not. it%rough .and. (it%mu > 0.0_wp .or. it%cohesion > 0.0_wp)
      end associate
   end function reducible

   !> Read *STRENGTH REDUCTION and its data line into the current step.
   subroutine read_strength_reduction(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=*), parameter :: one = 'a step has exactly one procedure: *STATIC, *GEOSTATIC (first step) '// &
                                           'or *STRENGTH REDUCTION (after the steps that build the state)'
      character(len=:), allocatable :: val
      logical :: found
      integer :: stat
      real(wp) :: t
      if (p%procedure_seen) then
         call err_here(p, '*STRENGTH REDUCTION in the step started at '//loc_str(p, p%step_loc)// &
                       ', which already has a procedure', one)
      else if (p%nstep == 0) then
         call err_here(p, '*STRENGTH REDUCTION in the first step: it needs the state of a previous step', &
                       'put it in a step after those that apply the loads (e.g. self-weight, then the reservoir); '// &
                       'it reduces the friction until that state can no longer be held')
      end if
      p%procedure_seen = .true.
      p%cur%procedure = procedure_strength_reduction
      call get_param(kw, 'INTERACTION', val, found)
      if (found) call read_interaction_name(p, model, val)
      if (.not. found) then
         if (.not. any([(reducible(model, stat) .and. used(p, model%interactions(stat)%name), stat=1, p%ninter)])) &
            call err_here(p, 'no surface interaction of a contact pair has friction to reduce', &
                          'add *FRICTION (mu, and COHESION=c if any) under the *SURFACE INTERACTION of the joint''s '// &
                          '*CONTACT PAIR')
      end if
      call get_param(kw, 'TOLERANCE', val, found)
      if (found) then
         call parse_real(squeeze(val), t, stat)
         if (stat /= num_ok .or. .not. (t > 0.0_wp .and. t < 0.5_wp)) then
            call err_here(p, 'TOLERANCE='//val//' must lie between 0 and 0.5', &
                          'the relative width (F_fail - F_ok)/F_ok at which the search stops, e.g. 1e-3')
         else
            p%cur%srm%tolerance = t
         end if
      end if
      call get_param(kw, 'NSET', val, found)
      if (found) call read_nset_name(p, model, to_upper(squeeze(val)))
      call read_factors(p)
   end subroutine read_strength_reduction

   !> INTERACTION=name: an interaction with Coulomb/Mohr-Coulomb friction.
   subroutine read_interaction_name(p, model, name)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      character(len=*), intent(in) :: name
      integer :: k
      do k = 1, p%ninter
         if (model%interactions(k)%name == name) p%cur%srm%interaction = k
      end do
      if (p%cur%srm%interaction == 0) then
         call err_here(p, 'undefined surface interaction '//name, &
                       'INTERACTION= names the *SURFACE INTERACTION whose friction is reduced')
      else if (.not. reducible(model, p%cur%srm%interaction)) then
         call err_here(p, 'surface interaction '//name//' has no friction to reduce', &
                       'it needs *FRICTION with mu > 0 or COHESION=c > 0 (ROUGH cannot be reduced)')
         p%cur%srm%interaction = 0
      else if (.not. used(p, name)) then
         call err_here(p, 'no *CONTACT PAIR uses the surface interaction '//name, &
                       'the strength reduction acts on the joints of the contact pairs with INTERACTION='//name)
         p%cur%srm%interaction = 0
      end if
   end subroutine read_interaction_name

   !> Whether a *CONTACT PAIR read so far uses the interaction `name`.
   pure logical function used(p, name)
      type(deck_parser_t), intent(in) :: p
      character(len=*), intent(in) :: name
      integer :: k
      used = .false.
      do k = 1, p%npair
         if (p%pair_refs(k)%interaction == name) used = .true.
      end do
   end function used

   !> NSET=name: the nodes of the characteristic displacement.
   subroutine read_nset_name(p, model, name)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      character(len=*), intent(in) :: name
      integer :: k
      call get_set(model%nsets, p%nset_items, p%nnset, name, here(p), .false., k)
      if (k == 0) then
         call err_here(p, 'undefined node set '//name, set_suggestion(model%nsets, p%nnset, name))
         return
      end if
      p%cur%srm%nset = k
   end subroutine read_nset_name

   !> The optional data line: first trial factor, largest factor.
   subroutine read_factors(p)
      type(deck_parser_t), intent(inout) :: p
      integer :: nline, k
      real(wp) :: v(2)
      logical :: ok, given(2)
      character(len=*), parameter :: what(2) = [character(len=20) :: 'first trial factor', 'largest factor']
      nline = 0
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         nline = nline + 1
         if (nline == 2) call err_here(p, '*STRENGTH REDUCTION takes at most one data line', data_help)
         if (nline > 1) cycle
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (p%f%n > 2) then
            call err_here(p, 'too many fields on the *STRENGTH REDUCTION data line', data_help)
            cycle
         end if
         v = [p%cur%srm%f_first, p%cur%srm%f_max]
         given = .false.
         ok = .true.
         do k = 1, p%f%n
            if (len_trim(field(p, k)) == 0) cycle
            call get_real(p, k, trim(what(k)), v(k), ok)
            if (.not. ok) exit
            given(k) = .true.
            if (.not. (v(k) > 1.0_wp)) then
               call err_here(p, 'the '//trim(what(k))//' '//field(p, k)//' must be larger than 1', data_help)
               ok = .false.
               exit
            end if
         end do
         if (.not. ok) cycle
         if (v(1) > v(2)) then
            call err_here(p, 'the first trial factor '//trim(fmt_real(v(1)))//' is larger than the largest factor '// &
                          trim(fmt_real(v(2))), data_help)
            cycle
         end if
         p%cur%srm%f_first = v(1)
         p%cur%srm%f_max = v(2)
         p%cur%srm%first_given = given(1)
      end do
   end subroutine read_factors

   pure function fmt_real(v) result(s)
      real(wp), intent(in) :: v
      character(len=24) :: s
      write (s, '(g0.6)') v
      s = adjustl(s)
   end function fmt_real
end module vemcontact_deck_strength_reduction
