!> Public entry point of the deck reader.
!> Decks use Abaqus/CalculiX keyword syntax; docs/deck-reference.md lists every
!> keyword.  All errors of a deck are collected and returned in one `error_t`
!> whose message has one fpm/rustc-style entry per problem (file:line, the
!> offending text and a hint).
module vemcontact_deck_reader
   use vemcontact_model, only: model_t
   use vemcontact_error, only: error_t, fatal_error, err_io, err_input
   use vemcontact_deck_state, only: deck_parser_t
   use vemcontact_deck_source, only: push_ok, push_not_text
   use vemcontact_deck_parser, only: parse_lines
   use vemcontact_deck_finish, only: finish_model
   implicit none
   private

   public :: read_deck

contains

   !> Read the deck `path` (and the files it includes) into `model`.
   !> On return `error` is allocated exactly when the deck has problems; `model`
   !> is then incomplete and must not be used.
   subroutine read_deck(path, model, error)
      character(len=*), intent(in) :: path
      type(model_t), intent(out) :: model
      type(error_t), allocatable, intent(out) :: error
      type(deck_parser_t) :: p
      character(len=:), allocatable :: msg
      integer :: stat
      call p%src%push_file(path, stat, msg)
      if (stat /= push_ok) then
         ! a file that cannot be read: a file error; one that is no deck: bad input
         call fatal_error(error, path//': error: '//msg, merge(err_input, err_io, stat == push_not_text))
         return
      end if
      call parse_lines(p, model)
      ! a refused deck is incomplete: its follow-on errors would only hide the one message
      if (.not. p%refused) call finish_model(p, model, p%src%path(1))
      call p%diag%finish(error)
   end subroutine read_deck
end module vemcontact_deck_reader
