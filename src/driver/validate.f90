!> Geometric checks of the elements after reading: every problem is reported with
!> the file:line where the element was defined, all of them in one go.  Also the
!> warnings about answers that are valid but known to be poor (element_warnings):
!> nearly incompressible materials in plane strain (volumetric locking) and
!> non-convex quads run with the FEM.  The breakdown points behind the thresholds
!> are measured in docs/stability-elements.md (bench/stability/elements.py).
module vemcontact_driver_validate
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, append_message, err_input
   use vemcontact_model, only: model_t, location_string, string_t, find_set, plane_strain, form_fem, &
                               element_order, surface_element, pair_surface_to_surface
   use vemcontact_element_geometry, only: polygon_signed_area, polygon_diameter, polygon_defect, &
      polygon_max_angle, geom_rtol, defect_none, defect_coincident, defect_fold, defect_crossing
   use vemcontact_element_quad4, only: quad4_min_gauss_jacobian
   use vemcontact_element_vem2, only: vem2_side_tangent, vem2_side_bulge
   implicit none
   private

   public :: validate_elements, element_warnings

   !> Most messages listed before the rest are only counted.
   integer, parameter :: max_messages = 50

   !> Poisson's ratio above which plane-strain FEM elements get the locking
   !> warning.  Measured (docs/stability-elements.md, Timoshenko cantilever in
   !> plane strain, 32 x 8 quads): tip-deflection error of the Q4 0.9 % at
   !> nu = 0.3, 3.2 % at 0.45, 14 % at 0.49, 73 % at 0.4999; the CST 5 %, 11 %,
   !> 32 %, 84 %.  Beyond 0.45 the error has grown several fold, so the user is
   !> told.  The VEM does not lock (its stabilisation sees a capped lambda, see
   !> vem_lambda_cap): 0.3 % and 0.1 % at nu = 0.3 and 0.4999, so it gets no warning.
   real(wp), parameter, public :: nu_lock_warn = 0.45_wp

   !> Range of lengths the element and contact kernels are written for: squares and
   !> products of two coordinates (areas, cross products) must stay far from over-
   !> and underflow.  The scale sweep (docs/stability-contact.md) ran exact from
   !> 1e-150 to 1e150 m and crashed beyond 1e-160 and 1e160; 1e130 leaves a
   !> margin of 1e20 on both sides and is beyond any unit system a user would pick.
   real(wp), parameter, public :: coord_max = 1.0e130_wp, size_min = 1.0e-130_wp

   !> Most vertices of one element.  The VEM element matrix is dense, (2n)^2
   !> doubles, and its kernel costs O(n^3): a regular 2000-gon alone takes 5.7 s
   !> and 0.59 GB (1000: 1.3 s, 0.17 GB; Release), 10 000 vertices aborted an
   !> allocation and 30 000 exhausted 24 GB; beyond 2000 a polygon is better split.
   !> Checked before any geometry (whose checks are quadratic in n).
   integer, parameter, public :: max_element_nodes = 2000

contains

   subroutine validate_elements(model, error)
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      real(wp), allocatable :: xy(:, :)
      real(wp) :: h
      integer :: e, n, nerr, i, j, nc
      integer(ip) :: first
      character(len=:), allocatable :: what
      character(len=24) :: id
      nerr = 0
      do i = 1, model%nnode
         if (maxval(abs(model%x(:, i))) > coord_max) then
            nerr = nerr + 1
            if (nerr <= max_messages) then
               write (id, '(i0)') model%node_id(i)
               call append_message(error, location_string(model, model%node_loc(i))// &
                                   ': error: node '//trim(id)//' has a coordinate beyond '// &
                                   '1e130 in magnitude: choose a length unit that brings it into range', &
                                   err_input)
            end if
         end if
      end do
      if (nerr > 0) return
      allocate (xy(2, max(3, maxval(model%elem_ptr(2:) - model%elem_ptr(:model%nelem), mask=model%nelem > 0))))
      do e = 1, model%nelem
         first = model%elem_ptr(e)
         n = model%elem_ptr(e + 1) - first
         if (n < 3) then
            what = 'has fewer than 3 nodes'
         else if (n > max_element_nodes) then
            write (id, '(i0)') n
            what = 'has '//trim(id)//' nodes, more than the limit of 2000 for one element (its dense '// &
                   'stiffness matrix grows with the square of the node count): split it into smaller polygons'
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
               ! the polygon of a second-order element is its corners
               nc = n/element_order(model%elem_type(e))
               if (len(what) == 0) then
                  xy(:, :n) = model%x(:, conn)
                  h = polygon_diameter(xy(:, :nc))
                  if (h < size_min .and. h > 0.0_wp) then
                     what = 'is smaller than 1e-130 (its diameter): choose a length unit '// &
                            'that brings it into range'
                  else
                     what = shape_defect(model, conn(:nc), xy(:, :nc), h, model%elem_form(e))
                  end if
               end if
               if (len(what) == 0 .and. nc < n .and. model%elem_form(e) /= form_fem) then
                  what = side_node_defect(model, conn, xy(:, :n))
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

   !> '' when every side node of a second-order virtual element (corners
   !> xy(:, 1:n/2), side nodes after them) is near enough the middle of its
   !> side for the side's quadratic curve (vem2_side_tangent along the chord,
   !> vem2_side_bulge across it, of the chord's length); else what is wrong.
   function side_node_defect(model, conn, xy) result(what)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: conn(:)
      real(wp), intent(in) :: xy(:, :)
      character(len=:), allocatable :: what
      integer :: i, nc, j
      real(wp) :: off(2), len_side, along, across
      character(len=24) :: a, b, c
      what = ''
      nc = size(xy, 2)/2
      do i = 1, nc
         j = mod(i, nc) + 1
         len_side = norm2(xy(:, j) - xy(:, i))
         off = xy(:, nc + i) - 0.5_wp*(xy(:, i) + xy(:, j))
         along = abs(dot_product(off, xy(:, j) - xy(:, i)))/len_side**2
         across = norm2(off)/len_side
         if (along > vem2_side_tangent .or. across > vem2_side_bulge) then
            write (a, '(i0)') model%node_id(conn(nc + i))
            write (b, '(i0)') model%node_id(conn(i))
            write (c, '(i0)') model%node_id(conn(j))
            if (along > vem2_side_tangent) then
               what = 'has its side node '//trim(a)//' too far along side '//trim(b)//'-'//trim(c)// &
                      ' from its middle (by '//real_text(along)//' of the side''s length, at most '// &
                      real_text(vem2_side_tangent)//'): the side node of a second-order VEM side '// &
                      'belongs near its middle (nodes: the corners, then one node per side in order)'
            else
               what = 'has its side node '//trim(a)//' too far off side '//trim(b)//'-'//trim(c)// &
                      ' (by '//real_text(across)//' of the side''s length, at most '// &
                      real_text(vem2_side_bulge)//'): the side curves more than a half circle'
            end if
            return
         end if
      end do
   end function side_node_defect

   !> What is wrong with one element's shape ('' when nothing): zero area,
   !> coincident nodes (a zero-length side has no normal, and a pinched polygon
   !> has no interior around the pinch), folded or crossing sides, clockwise
   !> order, and for the FEM quad a bilinear map that folds at a Gauss point.
   !> `h`: the polygon's diameter.
   function shape_defect(model, conn, xy, h, form) result(what)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: conn(:)
      real(wp), intent(in) :: xy(:, :), h
      integer, intent(in) :: form
      character(len=:), allocatable :: what
      real(wp) :: dist, angle
      integer :: kind, i, j, n, at
      character(len=96) :: b
      n = size(xy, 2)
      what = ''
      if (collinear(xy, h)) then
         write (b, '(es9.2)') abs(polygon_signed_area(xy))/max(h*h, tiny(h))
         what = 'has zero area (its nodes are collinear or coincide; area/diameter^2 = '// &
                trim(adjustl(b))//')'
         return
      end if
      call polygon_defect(xy, kind, i, j, dist, h)
      if (kind == defect_none) then
         b = ''
      else
         ! formatted only for a defect: three internal writes cost more than the checks
         b = 'distance '//real_text(dist)//' for a diameter of '//real_text(h)//', below '// &
             real_text(geom_rtol)//' of it'
      end if
      select case (kind)
      case (defect_none)
      case (defect_coincident)
         if (j == i + 1 .or. (i == 1 .and. j == n)) then
            what = 'has a zero-length side: its nodes '//nid(i)//' and '//nid(j)//' coincide ('// &
                   trim(b)//'); a side of no length has no normal, merge the two nodes'
         else
            what = 'is self-intersecting: its nodes '//nid(i)//' and '//nid(j)//' coincide ('// &
                   trim(b)//'), so the polygon is pinched; split it there'
         end if
      case (defect_fold)
         what = 'is self-intersecting: its sides '//nid(prev(i))//'-'//nid(i)//' and '//nid(i)//'-'// &
                nid(next(i))//' fold back onto each other (zero angle at node '//nid(i)//')'
      case (defect_crossing)
         what = 'is self-intersecting: its sides '//nid(i)//'-'//nid(next(i))//' and '//nid(j)//'-'// &
                nid(next(j))//' cross or touch'
      case default
         what = 'has zero area (its nodes are collinear or coincide)'
      end select
      if (len(what) > 0) return
      if (polygon_signed_area(xy) <= 0.0_wp) then
         what = 'is clockwise: list its nodes counter-clockwise (side numbering and '// &
                'surfaces depend on the order, so it is not reversed silently)'
         return
      end if
      if (form == form_fem .and. n == 4) then
         if (.not. quad4_min_gauss_jacobian(xy) > 0.0_wp) then
            call polygon_max_angle(xy, angle, at)
            write (b, '(f6.1)') angle
            what = 'cannot be a FEM quad: it is non-convex (interior angle '//trim(adjustl(b))// &
                   ' deg at node '//nid(at)//') and its bilinear map folds over (Jacobian not positive '// &
                   'at a Gauss point); use FORMULATION=VEM, which takes non-convex polygons, or remesh'
         end if
      end if
   contains
      function nid(k) result(s)
         integer, intent(in) :: k
         character(len=:), allocatable :: s
         character(len=24) :: t
         write (t, '(i0)') model%node_id(conn(k))
         s = trim(t)
      end function nid
      pure integer function next(k)
         integer, intent(in) :: k
         next = modulo(k, n) + 1
      end function next
      pure integer function prev(k)
         integer, intent(in) :: k
         prev = modulo(k - 2, n) + 1
      end function prev
   end function shape_defect

   !> Warnings about valid input whose answer is known to be poor, one line each
   !> (to be written to the log and to stderr by the caller):
   !> - a section whose material has nu > nu_lock_warn on plane-strain FEM
   !>   elements: volumetric locking, with the factors measured;
   !> - FEM quads that are non-convex but whose Gauss points still see a positive
   !>   Jacobian (the bilinear map folds near the reflex corner; the patch test
   !>   still passes, but the element is far stiffer than its shape suggests).
   !> Only the first max_messages non-convex quads are named.
   function element_warnings(model) result(lines)
      type(model_t), intent(in) :: model
      type(string_t), allocatable :: lines(:)
      integer :: k, ks, imat, e, n, nq, nt, nv, nbad, at
      integer(ip) :: first
      real(wp) :: nu, angle, xy(2, 4)
      character(len=32) :: b, id
      character(len=:), allocatable :: s
      allocate (lines(0))
      if (allocated(model%sections) .and. allocated(model%materials)) then
         do k = 1, size(model%sections)
            imat = model%sections(k)%imat
            if (imat < 1 .or. imat > size(model%materials)) cycle
            nu = model%materials(imat)%poisson
            if (.not. nu > nu_lock_warn) cycle
            ks = 0
            if (allocated(model%elsets)) ks = find_set(model%elsets, model%sections(k)%elset)
            if (ks == 0) cycle
            nq = 0
            nt = 0
            nv = 0
            do e = 1, size(model%elsets(ks)%items)
               associate (el => model%elsets(ks)%items(e))
                  if (model%elem_plane(el) /= plane_strain .or. model%elem_mat(el) /= imat) cycle
                  n = model%elem_ptr(el + 1) - model%elem_ptr(el)
                  if (model%elem_form(el) == form_fem) then
                     if (n == 4) nq = nq + 1
                     if (n == 3) nt = nt + 1
                  else
                     nv = nv + 1
                  end if
               end associate
            end do
            if (nq + nt == 0) cycle
            write (b, '(f8.5)') nu
            s = location_string(model, model%sections(k)%loc)//': warning: element set '// &
                model%sections(k)%elset//' (material '//model%materials(imat)%name//', nu = '// &
                trim(adjustl(b))//', plane strain) is nearly incompressible: '
            s = s//lock_text_fem(nu, nq, nt)
            if (nv > 0) then
               write (b, '(i0)') nv
               s = s//' (its '//trim(b)//' VEM elements are fine)'
            end if
            lines = [lines, string_t(s)]
         end do
      end if
      nbad = 0
      do e = 1, model%nelem
         if (model%elem_form(e) /= form_fem) cycle
         first = model%elem_ptr(e)
         if (model%elem_ptr(e + 1) - first /= 4) cycle
         xy = model%x(:, model%elem_conn(first:first + 3))
         if (.not. polygon_signed_area(xy) > 0.0_wp) cycle
         ! every turn strictly to the left: no interior angle reaches 180 degrees (the
         ! test below would find none), decided without the Jacobians and arc tangents
         if (left_turns(xy)) cycle
         if (.not. quad4_min_gauss_jacobian(xy) > 0.0_wp) cycle     ! an error of validate_elements
         call polygon_max_angle(xy, angle, at)
         if (angle <= 180.0_wp) cycle
         nbad = nbad + 1
         if (nbad > max_messages) cycle
         write (id, '(i0)') model%elem_id(e)
         write (b, '(f6.1)') angle
         lines = [lines, string_t(location_string(model, model%elem_loc(e))//': warning: element '// &
                                  trim(id)//' is a non-convex FEM quad (interior angle '//trim(adjustl(b))// &
                                  ' deg): its bilinear map folds near that corner, so it is much stiffer '// &
                                  'than its shape; FORMULATION=VEM takes non-convex polygons')]
      end do
      if (nbad > max_messages) then
         write (id, '(i0)') nbad - max_messages
         lines = [lines, string_t('warning: ... and '//trim(id)//' more non-convex FEM quads')]
      end if
   end function element_warnings

   !> True when the polygon turns strictly left at every vertex (cross product of the
   !> sides into and out of it positive): counter-clockwise and strictly convex.
   pure logical function left_turns(xy)
      real(wp), intent(in) :: xy(:, :)
      real(wp) :: e1(2), e2(2)
      integer :: i, n
      n = size(xy, 2)
      left_turns = .false.
      do i = 1, n
         e1 = xy(:, i) - xy(:, modulo(i - 2, n) + 1)
         e2 = xy(:, modulo(i, n) + 1) - xy(:, i)
         if (.not. e1(1)*e2(2) - e1(2)*e2(1) > 0.0_wp) return
      end do
      left_turns = .true.
   end function left_turns

   !> Locking of the FEM elements at Poisson's ratio nu, from the measurements
   !> (plane-strain Timoshenko cantilever, 32 x 8 quads or the same split in
   !> triangles; docs/stability-elements.md), quoted at the upper end of the
   !> bracket nu falls in.
   pure function lock_text_fem(nu, nq, nt) result(s)
      real(wp), intent(in) :: nu
      integer, intent(in) :: nq, nt
      character(len=:), allocatable :: s, at, q, t
      character(len=16) :: a, c
      write (a, '(i0)') nq
      write (c, '(i0)') nt
      if (nu <= 0.49_wp) then
         at = '0.49'; q = '0.86'; t = '0.68'
      else if (nu <= 0.499_wp) then
         at = '0.499'; q = '0.48'; t = '0.28'
      else
         at = '0.4999'; q = '0.27'; t = '0.16'
      end if
      s = 'its '//trim(a)//' FEM quads and '//trim(c)//' FEM triangles lock (fully integrated '// &
          'bilinear quads and constant-strain triangles become far too stiff as nu -> 0.5): on a '// &
          'plane-strain cantilever the tip deflection is '//q//' of exact with quads and '//t// &
          ' with triangles at nu = '//at//' (0.99 and 0.95 at nu = 0.3), so displacements and '// &
          'stresses may be much too small; FORMULATION=VEM does not lock (1.00 at nu = 0.4999)'
   end function lock_text_fem

   !> A real in 3 significant digits, no padding: 0, 2.5e-11, 40.8.
   pure function real_text(v) result(s)
      real(wp), intent(in) :: v
      character(len=:), allocatable :: s
      character(len=24) :: b
      if (.not. abs(v) > 0.0_wp) then
         s = '0'
      else if (abs(v) >= 1.0e-2_wp .and. abs(v) < 1.0e4_wp) then
         write (b, '(g0.3)') v
         s = trim(adjustl(b))
      else
         write (b, '(es10.2e2)') v
         s = trim(adjustl(b))
      end if
   end function real_text

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
