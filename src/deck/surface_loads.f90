!> *DSLOAD (Abaqus): distributed loads on an element-based surface, so that a
!> deck names the loaded face (e.g. the upstream face of a dam written by the
!> mesher) instead of listing element sides.  Data lines:
!>   surface, P, p                      uniform pressure on every facet
!>   surface, HP, p, y_zero, y_ref      hydrostatic pressure (as *DLOAD HP<k>)
!> Each facet becomes the *DLOAD record of its element and side, so OP=MOD/NEW and
!> the load assembly are those of *DLOAD.
module vemcontact_deck_surface_loads
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: model_t, dload_t, dload_pressure, dload_hydrostatic, surface_element
   use vemcontact_deck_state, only: deck_parser_t, err_here, field, get_real, push_dload
   use vemcontact_deck_fields, only: keyword_line_t, split_fields, to_upper, squeeze
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_loads, only: get_op
   use vemcontact_deck_contact, only: find_surface
   implicit none
   private

   public :: read_dsload

contains

   subroutine read_dsload(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      logical :: is_new, ok
      integer :: k, i, kind
      real(wp) :: mag, yzero, yref
      character(len=:), allocatable :: name, label
      type(dload_t) :: rec
      call get_op(p, kw, '*DSLOAD', is_new)
      if (is_new) then
         p%cur%dnew = .true.
         p%cur%nd = 0
      end if
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         name = to_upper(squeeze(field(p, 1)))
         k = find_surface(model, p%nsurf, name)
         if (k == 0) then
            call err_here(p, 'undefined surface '//name, 'define it with *SURFACE, NAME='//name//', TYPE=ELEMENT')
            cycle
         end if
         if (model%surfaces(k)%kind /= surface_element) then
            call err_here(p, 'surface '//name//' is not a TYPE=ELEMENT surface: a distributed load needs element sides')
            cycle
         end if
         label = to_upper(squeeze(field(p, 2)))
         if (label == 'P') then
            if (p%f%n > 3) then
               call err_here(p, 'too many fields on a *DSLOAD P line: expected surface, P, p')
               cycle
            end if
            call get_real(p, 3, 'pressure', mag, ok, required=.true.)
            if (.not. ok) cycle
            kind = dload_pressure
            yzero = 0.0_wp
            yref = 0.0_wp
         else if (label == 'HP') then
            if (p%f%n > 5) then
               call err_here(p, 'too many fields on a *DSLOAD HP line: expected surface, HP, p, y_zero, y_ref')
               cycle
            end if
            call get_real(p, 3, 'hydrostatic pressure magnitude', mag, ok, required=.true.)
            if (ok) call get_real(p, 4, 'free-surface height y_zero (zero pressure)', yzero, ok, required=.true.)
            if (ok) call get_real(p, 5, 'reference height y_ref (where the pressure is the magnitude)', &
                                  yref, ok, required=.true.)
            if (.not. ok) cycle
            if (.not. yzero > yref) then
               call err_here(p, 'the free-surface height y_zero = '//field(p, 4)//' must lie above the '// &
                             'reference height y_ref = '//field(p, 5))
               cycle
            end if
            kind = dload_hydrostatic
         else
            call err_here(p, 'unsupported *DSLOAD label '//label, 'use P (uniform pressure) or HP (hydrostatic)')
            cycle
         end if
         associate (s => model%surfaces(k))
            do i = 1, size(s%elem)
               rec = dload_t(elem=s%elem(i), kind=kind, side=s%side(i), magnitude=mag, dir=[yzero, yref], &
                             amp=p%amp)
               call push_dload(p%cur%dload, p%cur%nd, rec)
            end do
         end associate
      end do
   end subroutine read_dsload
end module vemcontact_deck_surface_loads
