!> Parsing results of the contact and staging keywords: *SURFACE, *SURFACE INTERACTION,
!> *SURFACE BEHAVIOR, *CONTACT PAIR, *CONTACT CONTROLS, *DLOAD HP<k> and *GEOSTATIC,
!> from tests/data/deck/contact.inp (run from tests/unit); the defaults from basic.inp.
program test_deck_contact
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, surface_element, surface_node, dload_grav, dload_hydrostatic, &
                               procedure_static, procedure_geostatic
   use vemcontact_deck_reader, only: read_deck
   implicit none
   type(checker_t) :: t
   character(len=*), parameter :: data = '../data/deck/'
   real(wp), parameter :: tol = 1.0e-15_wp   ! values are read exactly: only rounding of the literal

   call test_contact()
   call test_defaults()
   call t%finish()

contains

   subroutine test_contact()
      type(model_t) :: m
      type(error_t), allocatable :: err
      integer :: k
      call read_deck(data//'contact.inp', m, err)
      call t%check(.not. allocated(err), 'contact.inp reads without error')
      if (allocated(err)) then
         print '(a)', err%message
         return
      end if
      ! *SURFACE
      call t%equal(size(m%surfaces), 3, 'three surfaces')
      if (size(m%surfaces) /= 3) return
      associate (s => m%surfaces(1))
         call t%check(s%name == 'LOWER_TOP', 'surface name upper case')
         call t%equal(s%kind, surface_element, 'default TYPE=ELEMENT')
         call t%check(all(s%elem == [1, 2]), 'an element set adds one facet per element, in set order')
         call t%check(all(s%side == [3, 3]), 'S3 on every element of the set')
         call t%equal(s%loc%line, 31, 'surface location is its keyword line')
         call t%check(.not. allocated(s%nodes), 'an element surface has no node list')
      end associate
      associate (s => m%surfaces(2))
         call t%check(s%name == 'UPPER_BOT', 'mixed-case name and TYPE=ELEMENT')
         call t%equal(s%kind, surface_element, 'TYPE=ELEMENT')
         call t%check(all(s%elem == [3]), 'element id 10 is internal element 3')
         call t%check(all(s%side == [1]), 'lower-case s1 is side 1')
      end associate
      associate (s => m%surfaces(3))
         call t%equal(s%kind, surface_node, 'TYPE=NODE')
         call t%check(all(s%nodes == [7, 8, 9]), 'node surface from a set and ids: sorted and unique')
         call t%check(.not. allocated(s%elem), 'a node surface has no facets')
      end associate
      ! *SURFACE INTERACTION / *SURFACE BEHAVIOR
      call t%equal(size(m%interactions), 2, 'two interactions')
      if (size(m%interactions) /= 2) return
      call t%check(m%interactions(1)%name == 'SOFT' .and. m%interactions(2)%name == 'HARD', 'interaction names')
      call t%close(m%interactions(1)%penalty, 1.0e5_wp, tol, 'penalty K with blank c0 and zero sigma_inf')
      call t%close(m%interactions(2)%penalty, 2.0e6_wp, tol, 'penalty K alone')
      call t%check(all(m%interactions%has_behavior), 'both have *SURFACE BEHAVIOR')
      call t%equal(m%interactions(2)%loc%line, 42, 'interaction location')
      ! *CONTACT PAIR
      call t%equal(size(m%pairs), 3, 'two data lines and a second *CONTACT PAIR: three pairs')
      if (size(m%pairs) /= 3) return
      call t%check(all(m%pairs%slave == [3, 2, 1]), 'slave surfaces')
      call t%check(all(m%pairs%master == [1, 1, 2]), 'master surfaces')
      call t%check(all(m%pairs%interaction == [1, 1, 2]), 'interactions')
      call t%check(all(m%pairs%loc%line == [46, 47, 49]), 'a pair is located at its data line')
      ! *CONTACT CONTROLS
      call t%equal(m%controls%max_iterations, 25, 'MAXIT')
      call t%close(m%controls%residual_tol, 1.0e-6_wp, tol, 'TOLERANCE')
      ! *GEOSTATIC and *STATIC
      call t%equal(size(m%steps), 2, 'two steps')
      if (size(m%steps) /= 2) return
      call t%equal(m%steps(1)%procedure, procedure_geostatic, 'first step is geostatic')
      call t%equal(m%steps(2)%procedure, procedure_static, 'second step is static')
      call t%check(all(m%steps(1)%dload%kind == dload_grav), 'geostatic step keeps its loads')
      ! *DLOAD HP<k>
      associate (d => m%steps(2)%dload)
         call t%equal(size(d), 3, 'HP on a set of two and on one element')
         if (size(d) /= 3) return
         call t%check(all(d%kind == dload_hydrostatic), 'hydrostatic kind')
         call t%check(all(d%elem == [1, 2, 3]), 'elements of the HP loads')
         call t%check(all(d%side == [4, 4, 2]), 'HP4 and hp2 sides')
         call t%close(d(1)%magnitude, 0.0098_wp, tol, 'HP magnitude')
         do k = 1, 2
            call t%close(d(k)%dir(1), 2.0_wp, tol, 'dir(1) is the free-surface height y_zero')
            call t%close(d(k)%dir(2), 0.0_wp, tol, 'dir(2) is the reference height y_ref')
         end do
         call t%close(d(3)%dir(1), 10.0_wp, tol, 'integer-looking y_zero')
         call t%close(d(3)%dir(2), -1.0_wp, tol, 'negative y_ref')
      end associate
   end subroutine test_contact

   !> A deck without contact keywords: empty contact arrays, default controls, static steps.
   subroutine test_defaults()
      type(model_t) :: m
      type(error_t), allocatable :: err
      call read_deck(data//'basic.inp', m, err)
      call t%check(.not. allocated(err), 'basic.inp reads without error')
      if (allocated(err)) return
      call t%check(allocated(m%surfaces) .and. allocated(m%interactions) .and. allocated(m%pairs), &
                   'contact arrays allocated')
      call t%equal(size(m%surfaces) + size(m%interactions) + size(m%pairs), 0, 'and empty')
      call t%equal(m%controls%max_iterations, 50, 'default MAXIT')
      call t%close(m%controls%residual_tol, 1.0e-10_wp, tol, 'default TOLERANCE')
      call t%check(all(m%steps%procedure == procedure_static), '*STATIC steps')
      call t%equal(size(m%steps), 2, 'two steps in basic.inp')
   end subroutine test_defaults
end program test_deck_contact
