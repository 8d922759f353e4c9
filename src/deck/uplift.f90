!> *UPLIFT (vemcontact, in a step): the water pressure inside the joints of one
!> surface interaction, as dam-safety guidelines prescribe it (docs/deck-reference.md,
!> docs/sliding-safety.md).
!>
!>   *UPLIFT, INTERACTION=name, UNIT WEIGHT=gamma_w [, PENETRATION]
!>   x_heel, y_heel, headwater elevation
!>   x_toe, y_toe, tailwater elevation
!>   [x_drain, y_drain [, E]]             drain line; E = 2/3 (USBR's rule) by default
!>
!> Heads are elevations of the water surface (y up), so a reservoir level is written
!> as it is surveyed; the pressure at a joint point of elevation y is
!> gamma_w max(0, head - y).  A later step's *UPLIFT of the same interaction
!> replaces the earlier one.
module vemcontact_deck_uplift
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: model_t, uplift_t
   use vemcontact_deck_state, only: deck_parser_t, here, err_here, err_at, field, get_real
   use vemcontact_deck_fields, only: keyword_line_t, split_fields, get_param, has_param, squeeze
   use vemcontact_deck_numbers, only: parse_real, num_ok
   use vemcontact_deck_lines, only: advance, skip_data
   use vemcontact_deck_source, only: line_data
   implicit none
   private

   public :: read_uplift, push

   character(len=*), parameter :: data_help = 'the data lines are: x_heel, y_heel, headwater elevation; '// &
                                              'x_toe, y_toe, tailwater elevation; and optionally '// &
                                              'x_drain, y_drain [, drain effectiveness E]'

contains

   !> Read one *UPLIFT and its data lines into the current step.
   subroutine read_uplift(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      type(keyword_line_t), intent(in) :: kw
      type(uplift_t) :: up
      character(len=:), allocatable :: name, val
      logical :: found, ok, used
      integer :: k, nline, stat
      real(wp) :: v(3)
      up%loc = here(p)
      call get_param(kw, 'INTERACTION', name, found)
      up%interaction = 0
      do k = 1, p%ninter
         if (model%interactions(k)%name == name) up%interaction = k
      end do
      if (up%interaction == 0) then
         call err_here(p, 'undefined surface interaction '//name, &
                       '*UPLIFT names the *SURFACE INTERACTION of the contact pairs whose joints hold water')
         call skip_data(p)
         return
      end if
      used = .false.
      do k = 1, p%npair
         if (p%pair_refs(k)%interaction == name) used = .true.
      end do
      if (.not. used) then
         call err_here(p, 'no *CONTACT PAIR uses the surface interaction '//name, &
                       'the uplift acts on the joints of the contact pairs with INTERACTION='//name)
         call skip_data(p)
         return
      end if
      call get_param(kw, 'UNITWEIGHT', val, found)
      call parse_real(squeeze(val), up%gamma, stat)
      if (stat /= num_ok .or. .not. up%gamma > 0.0_wp) then
         call err_here(p, 'UNIT WEIGHT = '//val//' must be a positive number', &
                       'the unit weight of water in the deck''s units, e.g. 9810 (N/m^3) or 9.81 (kN/m^3)')
         call skip_data(p)
         return
      end if
      up%penetration = has_param(kw, 'PENETRATION')
      nline = 0
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         nline = nline + 1
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (nline > 3) then
            call err_here(p, 'too many *UPLIFT data lines', data_help)
            cycle
         end if
         if ((nline < 3 .and. p%f%n /= 3) .or. (nline == 3 .and. (p%f%n < 2 .or. p%f%n > 3))) then
            call err_here(p, 'wrong number of fields on *UPLIFT data line '//achar(iachar('0') + nline), data_help)
            cycle
         end if
         call get_real(p, 1, 'x', v(1), ok, required=.true.)
         if (ok) call get_real(p, 2, 'y', v(2), ok, required=.true.)
         v(3) = 2.0_wp/3.0_wp
         if (ok .and. (nline < 3 .or. p%f%n == 3)) call get_real(p, 3, line_what(nline), v(3), ok, required=.true.)
         if (.not. ok) cycle
         select case (nline)
         case (1)
            up%heel = v(1:2)
            up%head_heel = v(3)
         case (2)
            up%toe = v(1:2)
            up%head_toe = v(3)
         case (3)
            if (v(3) < 0.0_wp .or. v(3) > 1.0_wp) then
               call err_here(p, 'drain effectiveness E = '//field(p, 3)//' must lie between 0 and 1', &
                             'the head at the drain is tail + (1 - E)(head - tail); USBR''s rule is E = 2/3')
               cycle
            end if
            up%drained = .true.
            up%drain = v(1:2)
            up%effectiveness = v(3)
         end select
      end do
      if (nline < 2) then
         call err_at(p, up%loc, '*UPLIFT needs two data lines (heel, toe)', data_help)
         return
      end if
      if (.not. norm2(up%toe - up%heel) > 0.0_wp) then
         call err_at(p, up%loc, '*UPLIFT: the heel and the toe are the same point', &
                     'the heel is where the headwater enters the joint, the toe where the tailwater stands')
         return
      end if
      if (up%drained) then
         if (.not. (s_of(up%drain) > 0.0_wp .and. s_of(up%drain) < 1.0_wp)) then
            call err_at(p, up%loc, '*UPLIFT: the drain line must lie between the heel and the toe', data_help)
            return
         end if
      end if
      call push(p%cur%uplift, up)
   contains
      function line_what(n) result(s)
         integer, intent(in) :: n
         character(len=:), allocatable :: s
         select case (n)
         case (1)
            s = 'headwater elevation'
         case (2)
            s = 'tailwater elevation'
         case default
            s = 'drain effectiveness'
         end select
      end function line_what

      !> Position of x along the heel-toe chord, 0 at the heel, 1 at the toe.
      pure real(wp) function s_of(x)
         real(wp), intent(in) :: x(2)
         s_of = dot_product(x - up%heel, up%toe - up%heel)/dot_product(up%toe - up%heel, up%toe - up%heel)
      end function s_of
   end subroutine read_uplift

   !> Append `up`, replacing an entry of the same interaction and contact pair.
   subroutine push(list, up)
      type(uplift_t), allocatable, intent(inout) :: list(:)
      type(uplift_t), intent(in) :: up
      integer :: k
      if (.not. allocated(list)) allocate (list(0))
      do k = 1, size(list)
         if (list(k)%interaction == up%interaction .and. list(k)%pair == up%pair) then
            list(k) = up
            return
         end if
      end do
      list = [list, up]
   end subroutine push
end module vemcontact_deck_uplift
