!> *TIE, NAME=name [, POSITION TOLERANCE=t] [, ADJUST=YES|NO]: surfaces bonded
!> together (CalculiX and Abaqus).  Data lines: slave surface, master surface.
!> The names are resolved once the whole deck is read; the constraints are made
!> by the driver (vemcontact_driver_tie).
module vemcontact_deck_tie
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: model_t, tie_t, surface_element, surface_node
   use vemcontact_deck_state, only: deck_parser_t, here, err_here, err_at, refuse_here, field
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: keyword_line_t, get_param, has_param, split_fields, to_upper, squeeze
   use vemcontact_deck_numbers, only: parse_real, num_ok
   implicit none
   private

   public :: read_tie, finish_ties

contains

   subroutine read_tie(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      type(tie_t) :: t
      character(len=:), allocatable :: name, tol, adjust
      logical :: found
      integer :: stat, nline
      if (has_param(kw, 'CYCLICSYMMETRY') .or. has_param(kw, 'MULTISTAGE') .or. has_param(kw, 'FLUIDPRESSURE')) then
         call refuse_here(p, 'a cyclic symmetry, multistage or fluid pressure *TIE')
         return
      end if
      call get_param(kw, 'NAME', name, found)
      t%name = name
      call get_param(kw, 'POSITIONTOLERANCE', tol, found)
      if (found) then
         call parse_real(squeeze(tol), t%tolerance, stat)
         if (stat /= num_ok .or. .not. t%tolerance > 0.0_wp) then
            call err_here(p, 'POSITION TOLERANCE = '//tol//' of *TIE must be a positive length')
            t%tolerance = -1.0_wp
         end if
      end if
      call get_param(kw, 'ADJUST', adjust, found)   ! accepted: nodes are tied where they are
      nline = 0
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         nline = nline + 1
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (p%f%n /= 2 .or. nline > 1) then
            call err_here(p, 'a *TIE takes one data line: slave surface, master surface')
            cycle
         end if
         t%slave_name = to_upper(squeeze(field(p, 1)))
         t%master_name = to_upper(squeeze(field(p, 2)))
         t%loc = here(p)
      end do
      if (nline == 0 .or. .not. allocated(t%slave_name)) return
      if (.not. allocated(model%ties)) allocate (model%ties(0))
      model%ties = [model%ties, t]
   end subroutine read_tie

   !> The surfaces of every tie, by name: the master of element sides, slave and
   !> master different.
   subroutine finish_ties(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer :: k
      if (.not. allocated(model%ties)) return
      do k = 1, size(model%ties)
         associate (t => model%ties(k))
            t%slave = find(t%slave_name)
            t%master = find(t%master_name)
            if (t%slave == 0) call err_at(p, t%loc, 'undefined slave surface '//t%slave_name)
            if (t%master == 0) then
               call err_at(p, t%loc, 'undefined master surface '//t%master_name)
            else if (model%surfaces(t%master)%kind /= surface_element) then
               call err_at(p, t%loc, 'the master surface '//t%master_name//' of a *TIE must be of TYPE=ELEMENT')
            else if (t%master == t%slave) then
               call err_at(p, t%loc, 'slave and master of the *TIE are the same surface '//t%master_name)
            end if
         end associate
      end do
   contains
      integer function find(name)
         character(len=*), intent(in) :: name
         integer :: j
         find = 0
         if (.not. allocated(model%surfaces)) return
         do j = 1, size(model%surfaces)
            if (model%surfaces(j)%name == name .and. (model%surfaces(j)%kind == surface_element .or. &
                                                      model%surfaces(j)%kind == surface_node)) find = j
         end do
      end function find
   end subroutine finish_ties
end module vemcontact_deck_tie
