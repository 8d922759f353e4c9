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

   !> What the checks gather on their way: the model's extent and thickness
   !> (log10), the stiffness bounds with the section of the least, the largest
   !> load force with its step, and the messages.
   type :: range_check_t
      real(wp) :: lext = 0.0_wp, lt = 0.0_wp
      real(wp) :: kmax = -huge(1.0_wp), kmin = huge(1.0_wp), fmax = -huge(1.0_wp)
      type(source_loc_t) :: kmin_loc, fmax_loc
      type(error_t), allocatable :: error
   end type range_check_t

contains

   !> Every magnitude check of the model; all problems in one error.
   subroutine validate_ranges(model, error)
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      type(range_check_t) :: c
      integer :: k

      c%lext = model_extent(model)
      call check_materials(model, c)
      call check_sections(model, c)
      call check_interactions(model, c)
      if (allocated(c%error)) then
         call move_alloc(c%error, error)
         return
      end if

      ! loads of every step: values, the forces they make, and the displacements
      call check_step_loads(model, model%initial, c)
      if (allocated(model%steps)) then
         do k = 1, size(model%steps)
            call check_step_loads(model, model%steps(k), c)
         end do
      end if
      if (.not. allocated(c%error) .and. c%fmax > -huge(1.0_wp) .and. c%kmin < huge(1.0_wp)) then
         call product(model, c, c%fmax - c%kmin, 'the displacement the loads make (largest force / '// &
                      'least stiffness, the stiffness of this section', c%kmin_loc)
         if (allocated(c%error)) call append_message(c%error, where(model, c%fmax_loc)// &
                                                     ': note: the largest force comes from the loads of this step', &
                                                     err_input)
      end if
      if (allocated(c%error)) call move_alloc(c%error, error)
   end subroutine validate_ranges

   !> log10 of the model's extent, the largest coordinate difference (at least the
   !> smallest positive one the checks of the elements allow).  Halves: the
   !> difference of two coordinates near the double range's end would overflow, and
   !> this check may run before the elements' own coordinate check.
   real(wp) function model_extent(model) result(lext)
      type(model_t), intent(in) :: model
      lext = 0.0_wp
      if (model%nnode > 0) lext = maxval(0.5_wp*maxval(model%x(:, 1:model%nnode), dim=2) - &
                                         0.5_wp*minval(model%x(:, 1:model%nnode), dim=2))
      lext = log10(max(lext, 0.5e-130_wp)) + log10(2.0_wp)
   end function model_extent

   !> Young's modulus and density of every material.
   subroutine check_materials(model, c)
      type(model_t), intent(in) :: model
      type(range_check_t), intent(inout) :: c
      integer :: m
      if (.not. allocated(model%materials)) return
      do m = 1, size(model%materials)
         associate (mat => model%materials(m))
            call one(model, c, mat%young, 'Young''s modulus of material '//mat%name, mat%loc)
            call one(model, c, mat%density, 'density of material '//mat%name, mat%loc)
         end associate
      end do
   end subroutine check_materials

   !> Thickness and STABILIZATION of every section, its stiffness and mass scales;
   !> keeps the stiffness bounds and the largest thickness.
   subroutine check_sections(model, c)
      type(model_t), intent(in) :: model
      type(range_check_t), intent(inout) :: c
      real(wp) :: thick_max, lk
      integer :: is
      thick_max = 0.0_wp
      if (allocated(model%sections)) then
         do is = 1, size(model%sections)
            associate (s => model%sections(is))
               call one(model, c, s%thickness, 'thickness of the section of '//s%elset, s%loc)
               call one(model, c, s%stabilization, 'STABILIZATION of the section of '//s%elset, s%loc)
               thick_max = max(thick_max, s%thickness)
               if (s%imat < 1 .or. .not. allocated(model%materials)) cycle
               if (s%imat > size(model%materials)) cycle
               associate (mat => model%materials(s%imat))
                  if (.not. (mat%young > 0.0_wp .and. s%thickness > 0.0_wp)) cycle
                  if (.not. within(mat%young) .or. .not. within(s%thickness) .or. &
                      .not. within(s%stabilization)) cycle
                  lk = log10(mat%young) + log10(s%thickness) + max(0.0_wp, lg(s%stabilization))
                  call product(model, c, lk, 'the stiffness of the section of '//s%elset// &
                               ' (E * thickness * STABILIZATION', s%loc)
                  c%kmax = max(c%kmax, lk)
                  if (lk < c%kmin) then
                     c%kmin = lk
                     c%kmin_loc = s%loc
                  end if
                  if (mat%density > 0.0_wp .and. within(mat%density)) &
                     call product(model, c, log10(mat%density) + log10(s%thickness) + 2.0_wp*c%lext, &
                                  'the mass of the section of '//s%elset//' (density * thickness * '// &
                                  'extent^2', s%loc)
               end associate
            end associate
         end do
      end if
      c%lt = lg(thick_max)
   end subroutine check_sections

   !> The penalty slope of every contact interaction and its contact stiffness.
   subroutine check_interactions(model, c)
      type(model_t), intent(in) :: model
      type(range_check_t), intent(inout) :: c
      integer :: k
      if (.not. allocated(model%interactions)) return
      do k = 1, size(model%interactions)
         associate (it => model%interactions(k))
            call one(model, c, it%penalty, 'the pressure-overclosure slope of '//it%name, it%loc)
            if (it%penalty > 0.0_wp .and. within(it%penalty)) &
               call product(model, c, log10(it%penalty) + c%lt + c%lext, 'the contact stiffness of '// &
                            it%name//' (slope * thickness * extent', it%loc)
         end associate
      end do
   end subroutine check_interactions

   !> The load values of one step and the forces they make (the largest kept).
   subroutine check_step_loads(model, st, c)
      type(model_t), intent(in) :: model
      type(step_t), intent(in) :: st
      type(range_check_t), intent(inout) :: c
      real(wp) :: lf
      integer :: j
      if (allocated(st%boundary)) then
         do j = 1, size(st%boundary)
            associate (b => st%boundary(j))
               call one(model, c, b%value, 'prescribed displacement', st%loc, node=b%node)
               if (abs(b%value) > 0.0_wp .and. within(b%value) .and. c%kmax > -huge(1.0_wp)) then
                  lf = lg(b%value) + c%kmax
                  call product(model, c, lf, 'the force of a prescribed displacement (stiffness * value', st%loc)
                  call keep(c, lf, st%loc)
               end if
            end associate
         end do
      end if
      if (allocated(st%cload)) then
         do j = 1, size(st%cload)
            call one(model, c, st%cload(j)%value, 'concentrated load', st%loc, node=st%cload(j)%node)
            if (abs(st%cload(j)%value) > 0.0_wp .and. within(st%cload(j)%value)) &
               call keep(c, lg(st%cload(j)%value), st%loc)
         end do
      end if
      if (allocated(st%dload)) then
         do j = 1, size(st%dload)
            associate (d => st%dload(j))
               call one(model, c, d%magnitude, 'distributed load', st%loc)
               if (.not. (abs(d%magnitude) > 0.0_wp .and. within(d%magnitude))) cycle
               select case (d%kind)
               case (dload_grav)
                  ! with the largest density: the mass check bounds density * t * L^2
                  lf = lg(d%magnitude) + lg(max_density(model)) + c%lt + 2.0_wp*c%lext
               case (dload_pressure, dload_hydrostatic)
                  lf = lg(d%magnitude) + c%lt + c%lext
               case default
                  cycle
               end select
               call product(model, c, lf, 'the force of a distributed load (magnitude * thickness * extent', &
                            st%loc)
               call keep(c, lf, st%loc)
            end associate
         end do
      end if
   end subroutine check_step_loads

   !> A value within 1e-130 .. 1e130 in magnitude, or 0.
   subroutine one(model, c, v, name, loc, node)
      type(model_t), intent(in) :: model
      type(range_check_t), intent(inout) :: c
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
      call append_message(c%error, where(model, loc)//': error: '//name//' = '// &
                          trim(adjustl(b(1:20)))//on//' is beyond 1e-130 .. 1e130 in magnitude: '// &
                          'choose units that bring it into range', err_input)
   end subroutine one

   !> An estimated product (log10) within 1e-250 .. 1e250.  `name` ends in an
   !> open parenthesis that the estimate closes.
   subroutine product(model, c, lp, name, loc)
      type(model_t), intent(in) :: model
      type(range_check_t), intent(inout) :: c
      real(wp), intent(in) :: lp
      character(len=*), intent(in) :: name
      type(source_loc_t), intent(in) :: loc
      character(len=16) :: b
      if (abs(lp) <= product_log) return
      write (b, '(f8.1)') lp
      call append_message(c%error, where(model, loc)//': error: '//name//' is about 1e'// &
                          trim(adjustl(b(1:index(b, '.') - 1)))//'), beyond 1e-250 .. 1e250: the '// &
                          'computation would over- or underflow; choose units that bring the values '// &
                          'into range', err_input)
   end subroutine product

   !> Keeps the largest load force (log10) and where it comes from.
   pure subroutine keep(c, lf, loc)
      type(range_check_t), intent(inout) :: c
      real(wp), intent(in) :: lf
      type(source_loc_t), intent(in) :: loc
      if (lf > c%fmax) then
         c%fmax = lf
         c%fmax_loc = loc
      end if
   end subroutine keep

   !> file:line of `loc`; loads before the first *STEP have none: the deck's name.
   function where(model, loc) result(w)
      type(model_t), intent(in) :: model
      type(source_loc_t), intent(in) :: loc
      character(len=:), allocatable :: w
      w = location_string(model, loc)
      if (loc%file < 1 .and. allocated(model%files)) then
         if (size(model%files) > 0) w = model%files(1)%s//' (before the first *STEP)'
      end if
   end function where

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
