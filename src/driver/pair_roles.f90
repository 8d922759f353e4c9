!> The slave and master of each NODE TO SURFACE pair as node to segment contact needs
!> them: the softer and, with moduli alike, the finer face as the slave
!> (vemcontact_contact_roles).  A pair written the other way round is exchanged before
!> any contact state is built, and the log says so (a node-based slave surface serves as
!> the master through the element sides it covers, a surface added to the model); where
!> it is not (ROLES=KEEP; joint water, whose positions refer to the slave face;
!> friction, whose CSHEAR and CSLIP are signed along the master's tangent) the log warns
!> and names the better choices.
module vemcontact_driver_pair_roles
   use vemcontact_model, only: model_t, location_string, string_t, surface_element
   use vemcontact_error, only: error_t
   use vemcontact_text, only: int_text
   use vemcontact_contact_roles, only: pair_roles, role_advice_t, roles_swap, roles_warn, sides_surface
   implicit none
   private

   public :: choose_pair_roles

contains

   !> Exchange the surfaces of the pairs whose roles are the wrong way round; one log
   !> line per exchanged or warned pair in `lines`.
   subroutine choose_pair_roles(model, lines, error)
      type(model_t), intent(inout) :: model
      type(string_t), allocatable, intent(out) :: lines(:)
      type(error_t), allocatable, intent(out) :: error
      type(role_advice_t) :: advice
      character(len=:), allocatable :: where
      integer :: p, s
      allocate (lines(0))
      if (.not. allocated(model%pairs)) return
      do p = 1, size(model%pairs)
         advice = pair_roles(model, p, kept_by(model, p))
         where = location_string(model, model%pairs(p)%loc)
         select case (advice%action)
         case (roles_swap)
            if (model%surfaces(model%pairs(p)%slave)%kind /= surface_element) then
               model%surfaces = [model%surfaces, sides_surface(model, p, error)]
               if (allocated(error)) return
               model%pairs(p)%slave = size(model%surfaces)
            end if
            s = model%pairs(p)%slave
            model%pairs(p)%slave = model%pairs(p)%master
            model%pairs(p)%master = s
            model%pairs(p)%roles_swapped = .true.
            lines = [lines, string_t('  note: '//where//': contact pair '//int_text(p)//': '//advice%reason// &
                                     '; node to surface constrains the slave''s nodes, so '// &
                                     model%surfaces(model%pairs(p)%slave)%name//' is taken as the slave and '// &
                                     model%surfaces(model%pairs(p)%master)%name//' as the master (the pair''s '// &
                                     'contact results are on '//model%surfaces(model%pairs(p)%slave)%name//'''s nodes)')]
         case (roles_warn)
            lines = [lines, string_t('  warning: '//where//': contact pair '//int_text(p)//': '//advice%reason// &
                                     '; node-to-surface pressures will depend on the mesh ('//advice%kept_by// &
                                     '): make '//model%surfaces(model%pairs(p)%master)%name// &
                                     ' the slave or use TYPE=SURFACE TO SURFACE')]
         end select
      end do
   end subroutine choose_pair_roles

   !> What keeps pair p's roles as written ('' when nothing does): joint water names
   !> positions on the slave face (*UPLIFT of the pair's interaction in any step,
   !> *PRESSURE PENETRATION of the pair); friction in any step signs CSHEAR and CSLIP
   !> along the master's tangent.
   function kept_by(model, p) result(why)
      type(model_t), intent(in) :: model
      integer, intent(in) :: p
      character(len=:), allocatable :: why
      integer :: i, j, inter
      why = ''
      inter = model%pairs(p)%interaction
      if (inter > 0) then
         if (model%interactions(inter)%has_friction) why = 'friction keeps the roles as written'
      end if
      if (.not. allocated(model%steps)) return
      do i = 1, size(model%steps)
         if (allocated(model%steps(i)%friction_changes)) then
            if (any(model%steps(i)%friction_changes%interaction == inter)) why = 'friction keeps the roles as written'
         end if
         if (.not. allocated(model%steps(i)%uplift)) cycle
         do j = 1, size(model%steps(i)%uplift)
            if (model%steps(i)%uplift(j)%pair == p .or. model%steps(i)%uplift(j)%interaction == inter) &
               why = 'joint water on the pair keeps the roles as written'
         end do
      end do
   end function kept_by

end module vemcontact_driver_pair_roles
