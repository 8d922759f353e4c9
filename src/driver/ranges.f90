!> Magnitude checks of the model's numbers before any kernel runs: values the
!> reader accepts one by one (thickness 1e307, E = 1e-307, ...) can still make
!> the products the kernels form overflow or underflow (a trap in the Debug
!> build, a misleading "singular" in Release).  The products are estimated in
!> log10, so the check itself cannot overflow:
!>
!> - each material or section value (E, density, thickness, STABILIZATION),
!>   penalty slope and load value lies within 1e-130 .. 1e130 in magnitude
!>   (0 allowed where the reader allows it);
!> - the stiffness scale E * thickness * max(1, STABILIZATION), the body force
!>   density * g * thickness * (model extent)^2, the side load
!>   pressure * thickness * extent, the contact stiffness penalty * thickness *
!>   extent, and the force of a prescribed displacement (stiffness * value) and
!>   the displacement a load makes (load / least stiffness) stay within
!>   1e-250 .. 1e250, leaving the kernels' own sums and ratios a margin of 1e50.
!>
!> Each problem names the file:line of what it comes from (the material, section,
!> contact interaction, or the *STEP of a load) and the value.
module vemcontact_driver_ranges
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, append_message, err_input
   use vemcontact_model, only: model_t, step_t, location_string, source_loc_t, dload_grav, &
                               dload_pressure, dload_hydrostatic
   implicit none
   private

   public :: validate_ranges

   !> log10 bounds: one value (1e130, as for coordinates in validate.f90: the
   !> scale sweep of postprocess/tests/test_stability_contact.py runs exact with
   !> moduli 1e103 on lengths 1e100), and an estimated product (1e250, leaving the
   !> kernels' sums and ratios a margin of 1e50 below the double range's 1e308).
   real(wp), parameter :: value_log = 130.0_wp, product_log = 250.0_wp

contains

   subroutine validate_ranges(model, error)
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      real(wp) :: lext, kmax, kmin, lk, fmax, thick_max, lt
      type(source_loc_t) :: kmin_loc, fmax_loc
      integer :: k, m, is
      character(len=:), allocatable :: what

      ! extent of the model: the largest coordinate difference (at least the
      ! smallest positive one the checks of the elements allow)
      ! (halves: the difference of two coordinates near the double range's end would
      ! overflow; this check may run before the elements' own coordinate check)
      lext = 0.0_wp
      if (model%nnode > 0) lext = maxval(0.5_wp*maxval(model%x(:, 1:model%nnode), dim=2) - &
                                         0.5_wp*minval(model%x(:, 1:model%nnode), dim=2))
      lext = log10(max(lext, 0.5e-130_wp)) + log10(2.0_wp)

      ! single values
      if (allocated(model%materials)) then
         do m = 1, size(model%materials)
            associate (mat => model%materials(m))
               what = 'material '//mat%name
               call one(mat%young, 'Young''s modulus of '//what, mat%loc)
               call one(mat%density, 'density of '//what, mat%loc)
            end associate
         end do
      end if
      thick_max = 0.0_wp
      kmax = -huge(1.0_wp)
      kmin = huge(1.0_wp)
      if (allocated(model%sections)) then
         do is = 1, size(model%sections)
            associate (s => model%sections(is))
               call one(s%thickness, 'thickness of the section of '//s%elset, s%loc)
               call one(s%stabilization, 'STABILIZATION of the section of '//s%elset, s%loc)
               thick_max = max(thick_max, s%thickness)
               if (s%imat < 1 .or. .not. allocated(model%materials)) cycle
               if (s%imat > size(model%materials)) cycle
               associate (mat => model%materials(s%imat))
                  if (.not. (mat%young > 0.0_wp .and. s%thickness > 0.0_wp)) cycle
                  if (.not. within(mat%young) .or. .not. within(s%thickness) .or. &
                      .not. within(s%stabilization)) cycle
                  lk = log10(mat%young) + log10(s%thickness) + max(0.0_wp, lg(s%stabilization))
                  call product(lk, 'the stiffness of the section of '//s%elset//' (E * thickness * '// &
                               'STABILIZATION', s%loc)
                  if (lk > kmax) kmax = lk
                  if (lk < kmin) then
                     kmin = lk
                     kmin_loc = s%loc
                  end if
                  if (mat%density > 0.0_wp .and. within(mat%density)) &
                     call product(log10(mat%density) + log10(s%thickness) + 2.0_wp*lext, &
                                  'the mass of the section of '//s%elset//' (density * thickness * '// &
                                  'extent^2', s%loc)
               end associate
            end associate
         end do
      end if
      lt = lg(thick_max)
      if (allocated(model%interactions)) then
         do k = 1, size(model%interactions)
            associate (it => model%interactions(k))
               call one(it%penalty, 'the pressure-overclosure slope of '//it%name, it%loc)
               if (it%penalty > 0.0_wp .and. within(it%penalty)) &
                  call product(log10(it%penalty) + lt + lext, 'the contact stiffness of '//it%name// &
                               ' (slope * thickness * extent', it%loc)
            end associate
         end do
      end if
      if (allocated(error)) return

      ! loads of every step: values, the forces they make, and the displacements
      fmax = -huge(1.0_wp)
      call step_loads(model%initial)
      if (allocated(model%steps)) then
         do k = 1, size(model%steps)
            call step_loads(model%steps(k))
         end do
      end if
      if (allocated(error)) return
      if (fmax > -huge(1.0_wp) .and. kmin < huge(1.0_wp)) then
         call product(fmax - kmin, 'the displacement the loads make (largest force / least stiffness, '// &
                      'the stiffness of this section', kmin_loc)
         if (allocated(error)) call append_message(error, where(fmax_loc)// &
                                                   ': note: the largest force comes from the loads of this step', &
                                                   err_input)
      end if

   contains

      !> The load values of one step, the forces they make (kept in fmax).
      subroutine step_loads(st)
         type(step_t), intent(in) :: st
         real(wp) :: lf
         integer :: j
         if (allocated(st%boundary)) then
            do j = 1, size(st%boundary)
               call one(st%boundary(j)%value, 'prescribed displacement', st%loc, node=st%boundary(j)%node)
               if (abs(st%boundary(j)%value) > 0.0_wp .and. within(st%boundary(j)%value) .and. &
                   kmax > -huge(1.0_wp)) then
                  lf = lg(st%boundary(j)%value) + kmax
                  call product(lf, 'the force of a prescribed displacement (stiffness * value', st%loc)
                  call keep(lf, st%loc)
               end if
            end do
         end if
         if (allocated(st%cload)) then
            do j = 1, size(st%cload)
               call one(st%cload(j)%value, 'concentrated load', st%loc, node=st%cload(j)%node)
               if (abs(st%cload(j)%value) > 0.0_wp .and. within(st%cload(j)%value)) &
                  call keep(lg(st%cload(j)%value), st%loc)
            end do
         end if
         if (allocated(st%dload)) then
            do j = 1, size(st%dload)
               associate (d => st%dload(j))
                  call one(d%magnitude, 'distributed load', st%loc)
                  if (.not. (abs(d%magnitude) > 0.0_wp .and. within(d%magnitude))) cycle
                  select case (d%kind)
                  case (dload_grav)
                     ! with the largest density: the mass check above bounds density * t * L^2
                     lf = lg(d%magnitude) + lg(max_density(model)) + lt + 2.0_wp*lext
                  case (dload_pressure, dload_hydrostatic)
                     lf = lg(d%magnitude) + lt + lext
                  case default
                     cycle
                  end select
                  call product(lf, 'the force of a distributed load (magnitude * thickness * extent', st%loc)
                  call keep(lf, st%loc)
               end associate
            end do
         end if
      end subroutine step_loads

      !> A value within 1e-130 .. 1e130 in magnitude, or 0.
      subroutine one(v, name, loc, node)
         real(wp), intent(in) :: v
         character(len=*), intent(in) :: name
         type(source_loc_t), intent(in) :: loc
         integer(ip), intent(in), optional :: node
         character(len=40) :: b
         character(len=:), allocatable :: on
         if (within(v)) return
         write (b, '(es10.2e3)') v
         on = ''
         if (present(node)) then
            write (b(21:40), '(i0)') model%node_id(node)
            on = ' at node '//trim(b(21:40))
         end if
         call append_message(error, where(loc)//': error: '//name//' = '// &
                             trim(adjustl(b(1:20)))//on//' is beyond 1e-130 .. 1e130 in magnitude: '// &
                             'choose units that bring it into range', err_input)
      end subroutine one

      !> An estimated product (log10) within 1e-250 .. 1e250.  `name` ends in an
      !> open parenthesis that the estimate closes.
      subroutine product(lp, name, loc)
         real(wp), intent(in) :: lp
         character(len=*), intent(in) :: name
         type(source_loc_t), intent(in) :: loc
         character(len=16) :: b
         if (abs(lp) <= product_log) return
         write (b, '(f8.1)') lp
         call append_message(error, where(loc)//': error: '//name//' is about 1e'// &
                             trim(adjustl(b(1:index(b, '.') - 1)))//'), beyond 1e-250 .. 1e250: the '// &
                             'computation would over- or underflow; choose units that bring the values '// &
                             'into range', err_input)
      end subroutine product

      subroutine keep(lf, loc)
         real(wp), intent(in) :: lf
         type(source_loc_t), intent(in) :: loc
         if (lf > fmax) then
            fmax = lf
            fmax_loc = loc
         end if
      end subroutine keep

      !> file:line of `loc`; loads before the first *STEP have none: the deck's name.
      function where(loc) result(w)
         type(source_loc_t), intent(in) :: loc
         character(len=:), allocatable :: w
         w = location_string(model, loc)
         if (loc%file < 1 .and. allocated(model%files)) then
            if (size(model%files) > 0) w = model%files(1)%s//' (before the first *STEP)'
         end if
      end function where
   end subroutine validate_ranges

   !> 0 or a finite magnitude within 1e-130 .. 1e130 (NaN is neither).
   pure logical function within(v)
      real(wp), intent(in) :: v
      real(wp) :: a
      a = abs(v)
      within = (a >= 10.0_wp**(-value_log) .and. a <= 10.0_wp**value_log) .or. .not. a > 0.0_wp
      if (within) within = a <= 10.0_wp**value_log
   end function within

   !> log10 |v| for a non-zero v within range, 0 otherwise.
   pure real(wp) function lg(v)
      real(wp), intent(in) :: v
      lg = 0.0_wp
      if (abs(v) > 0.0_wp .and. within(v)) lg = log10(abs(v))
   end function lg

   !> The largest density of the materials (1 when none is given).
   pure real(wp) function max_density(model)
      type(model_t), intent(in) :: model
      integer :: m
      max_density = 0.0_wp
      if (allocated(model%materials)) then
         do m = 1, size(model%materials)
            if (within(model%materials(m)%density)) max_density = max(max_density, model%materials(m)%density)
         end do
      end if
      if (.not. max_density > 0.0_wp) max_density = 1.0_wp
   end function max_density
end module vemcontact_driver_ranges
