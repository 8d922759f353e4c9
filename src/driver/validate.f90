!> Geometric checks of the elements after reading: every problem is reported with
!> the file:line where the element was defined, all of them in one go.
module vemcontact_driver_validate
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, append_message, err_input
   use vemcontact_model, only: model_t, location_string
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_is_simple, polygon_diameter
   implicit none
   private

   public :: validate_elements

   !> Most messages listed before the rest are only counted.
   integer, parameter :: max_messages = 50

contains

   subroutine validate_elements(model, error)
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: xy(:, :)
      real(wp) :: area, h
      integer :: e, n, nerr, i, j
      integer(ip) :: first
      character(len=:), allocatable :: what
      character(len=24) :: id
      nerr = 0
      allocate (xy(2, max(3, maxval(model%elem_ptr(2:) - model%elem_ptr(:model%nelem), mask=model%nelem > 0))))
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         n = model%elem_ptr(e + 1) - first
         if (n < 3) then
            what = 'has fewer than 3 nodes'
         else
            what = ''
            associate (conn => model%elem_conn(first:first + n - 1))
               outer: do i = 1, n - 1
                  do j = i + 1, n
                     if (conn(i) == conn(j)) then
                        write (id, '(i0)') model%node_id(conn(i))
                        what = 'uses node '//trim(id)//' twice'
                        exit outer
                     end if
                  end do
               end do outer
               if (len(what) == 0) then
                  xy(:, :n) = model%x(:, conn)
                  area = polygon_signed_area(xy(:, :n))
                  h = polygon_diameter(xy(:, :n))
                  if (collinear(xy(:, :n), h)) then
                     what = 'has zero area (its nodes are collinear or coincide)'
                  else if (.not. polygon_is_simple(xy(:, :n))) then
                     what = 'is self-intersecting (its sides cross or touch)'
                  else if (area <= 0.0_wp) then
                     what = 'is clockwise: list its nodes counter-clockwise (side numbering and '// &
                            'surfaces depend on the order, so it is not reversed silently)'
                  end if
               end if
            end associate
         end if
         if (len(what) > 0) then
            nerr = nerr + 1
            if (nerr <= max_messages) then
               write (id, '(i0)') model%elem_id(e)
               call append_message(error, location_string(model, model%elem_loc(e))// &
                                   ': error: element '//trim(id)//' '//what, err_input)
            end if
         end if
      end do
      if (nerr > max_messages) then
         write (id, '(i0)') nerr - max_messages
         call append_message(error, '... and '//trim(id)//' more element errors', err_input)
      end if
   end subroutine validate_elements

   !> All vertices within 1e-12 diameters of one line (far above round-off of the
   !> coordinates, far below any real element's height).
   pure logical function collinear(xy, h)
      real(wp), intent(in) :: xy(:, :), h
      real(wp) :: d(2), len_d
      integer :: far, i
      collinear = .true.
      if (h <= 0.0_wp) return
      far = maxloc(norm2(xy - spread(xy(:, 1), 2, size(xy, 2)), dim=1), 1)
      d = xy(:, far) - xy(:, 1)
      len_d = norm2(d)
      do i = 1, size(xy, 2)
         if (abs(d(1)*(xy(2, i) - xy(2, 1)) - d(2)*(xy(1, i) - xy(1, 1)))/len_d > 1.0e-12_wp*h) then
            collinear = .false.
            return
         end if
      end do
   end function collinear
end module vemcontact_driver_validate
