!> *AMPLITUDE (CalculiX): a named piecewise linear function of time, and the
!> AMPLITUDE= parameter of *BOUNDARY, *CLOAD, *DLOAD and *DSLOAD that makes a load
!> follow it.  An amplitude is defined before the loads that name it (CalculiX
!> reads the deck in order).
module vemcontact_deck_amplitude
   use vemcontact_kinds, only: wp
   use vemcontact_model, only: model_t, amplitude_t
   use vemcontact_deck_state, only: deck_parser_t, err_here, here, get_real, loc_str
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: keyword_line_t, split_fields, get_param
   implicit none
   private

   public :: read_amplitude, load_amplitude

contains

   !> *AMPLITUDE, NAME=name [, TIME=TOTAL TIME | STEP TIME]: data lines of pairs
   !> t1, a1, t2, a2, ... (at most four pairs a line, CalculiX), times increasing.
   subroutine read_amplitude(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      type(amplitude_t) :: a
      type(amplitude_t), allocatable :: grown(:)
      character(len=:), allocatable :: val
      real(wp), allocatable :: v(:)
      real(wp) :: x
      logical :: found, ok, bad
      integer :: k, n
      call get_param(kw, 'NAME', a%name, found)
      call get_param(kw, 'TIME', val, found)
      a%total_time = found .and. val == 'TOTALTIME'
      a%loc = here(p)
      if (.not. allocated(model%amplitudes)) allocate (model%amplitudes(0))
      bad = .false.
      do k = 1, size(model%amplitudes)
         if (model%amplitudes(k)%name /= a%name) cycle
         call err_here(p, 'amplitude '//a%name//' is already defined at '//loc_str(p, model%amplitudes(k)%loc))
         bad = .true.
      end do
      allocate (v(0))
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (mod(p%f%n, 2) /= 0 .or. p%f%n > 8) then
            call err_here(p, '*AMPLITUDE data lines hold pairs of time and value: t1, a1, t2, a2, ... '// &
                          '(at most four pairs a line)')
            bad = .true.
            cycle
         end if
         do k = 1, p%f%n
            call get_real(p, k, merge('amplitude time ', 'amplitude value', mod(k, 2) == 1), x, ok, required=.true.)
            if (.not. ok) then
               bad = .true.
               exit
            end if
            v = [v, x]
         end do
         n = size(v)/2
         if (n < 2 .or. bad) cycle
         if (any(v(3:2*n - 1:2) <= v(1:2*n - 3:2))) then
            call err_here(p, 'the times of amplitude '//a%name//' must increase')
            bad = .true.
         end if
      end do
      if (bad) return
      if (size(v) == 0) then
         call err_here(p, 'amplitude '//a%name//' has no points: give pairs of time and value')
         return
      end if
      n = size(v)/2
      a%t = v(1:2*n - 1:2)
      a%a = v(2:2*n:2)
      allocate (grown(size(model%amplitudes) + 1))
      grown(:size(model%amplitudes)) = model%amplitudes
      grown(size(grown)) = a
      call move_alloc(grown, model%amplitudes)
   end subroutine read_amplitude

   !> p%amp for the load keyword line `kw`: the index of the amplitude its AMPLITUDE=
   !> names (0 without it); an unknown name is an error at the keyword line.
   subroutine load_amplitude(p, model, kw, kname)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=*), intent(in) :: kname
      character(len=:), allocatable :: name, known
      logical :: found
      integer :: k
      p%amp = 0
      call get_param(kw, 'AMPLITUDE', name, found)
      if (.not. found) return
      known = ''
      if (allocated(model%amplitudes)) then
         do k = 1, size(model%amplitudes)
            if (model%amplitudes(k)%name == name) then
               p%amp = k
               return
            end if
            known = known//' '//model%amplitudes(k)%name
         end do
      end if
      if (len(known) == 0) known = ' (none)'
      call err_here(p, 'unknown amplitude '//name//' on '//kname, &
                    'define it with *AMPLITUDE, NAME='//name//' before this line; amplitudes defined so far:'//known)
   end subroutine load_amplitude
end module vemcontact_deck_amplitude
