!> Which surface of a NODE TO SURFACE pair is the slave.  Node to segment contact
!> constrains the slave's nodes only: the master's nodes between them are free to
!> overlap the slave face, and each slave node's force acts on the master as a point
!> load.  Both are harmless when the slave is the softer body and, for similar
!> stiffnesses, the finer mesh (Abaqus' and CalculiX's advice for choosing the slave);
!> the other way round the pressure is mesh-dependent and can be far off.  Measured on
!> the Hertz contact of a soft Voronoi disc and a stiff block, both node to surface,
!> HARD, finite sliding (docs/contact-formulation.md, "Which surface is the slave"):
!>
!> - the soft, finely meshed disc as the slave: peak +1.0 % of Hertz' p0;
!> - the disc as the master (1000x softer, its sides 3-4x shorter than the block's
!>   node spacing): +23 % (the block refined 2x and 4x: +32 % and +54 %);
!> - equal moduli, the disc as the master: +24 %;
!> - a stiff, fine disc as the slave of a soft, coarse block: +322 %; the block as the
!>   slave: +0.7 %.
!>
!> So the stiffness decides first, the mesh when the moduli are within
!> `stiffness_contrast` of each other.  pair_roles says whether a pair's roles should be
!> exchanged (the driver does it before the contact state is built, and reports it), or
!> only warned about: pairs with joint water (*UPLIFT, *PRESSURE PENETRATION) name
!> positions on their slave face, and frictional pairs sign CSHEAR and CSLIP along their
!> master's tangent (the caller says which, `kept_by`).  A node-based slave surface
!> becomes the master as the element sides it covers (sides_surface).
module vemcontact_contact_roles
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, contact_pair_t, surface_t, surface_element, pair_node_to_surface
   use vemcontact_contact_surfaces, only: master_segments, slave_edges
   use vemcontact_contact_search, only: median
   use vemcontact_contact_geometry, only: length2
   implicit none
   private

   public :: role_choice, pair_roles, role_advice_t, sides_surface
   public :: roles_keep, roles_swap, roles_warn

   integer, parameter :: roles_keep = 0   !< the slave is the softer or, alike, the finer surface
   integer, parameter :: roles_swap = 1   !< exchanging the surfaces makes it so
   integer, parameter :: roles_warn = 2   !< it should be exchanged and cannot be

   !> Moduli (E times thickness) within this factor of each other count as alike, and
   !> the mesh decides.  Measured where the two rules disagree (a stiff disc with sides
   !> 3.4x shorter than the soft block's spacing, the disc as the slave as written):
   !> at a contrast of 3 the roles as written give +8.3 % and exchanged +16.6 %, at 10
   !> +25 % and +8.2 %, at 1000 +322 % and +0.7 %; between 3 and 10 the softer body's
   !> deformation, not the meshes, starts to decide which side must carry the
   !> constraints.
   real(wp), parameter, public :: stiffness_contrast = 5.0_wp
   !> The master is too fine when its sides are shorter than the slave's node spacing
   !> by more than this factor: then master nodes lie between two slave nodes, free to
   !> overlap the slave face (on the Hertz decks with moduli alike, 5x and 7x: +24 %,
   !> +22 % as written, +9.7 %, +5.0 % exchanged).  Meshes that differ less are left as
   !> written: the non-matching interfaces of the patch tests (2 against 3 sides) and
   !> the mesher's two-wedge seams (1.6x), flat faces where the choice matters little.
   real(wp), parameter, public :: mesh_contrast = 2.0_wp

   !> What pair_roles measured and advises for one pair.
   type :: role_advice_t
      integer :: action = roles_keep
      real(wp) :: et_slave = 0.0_wp        !< median E * thickness next to the slave face
      real(wp) :: et_master = 0.0_wp       !< likewise next to the master face
      real(wp) :: h_slave = 0.0_wp         !< median node spacing of the slave face
      real(wp) :: h_master = 0.0_wp        !< median master segment length
      !> why the slave should be the other surface (empty when it should not)
      character(len=:), allocatable :: reason
      !> roles_warn: what keeps the roles as written
      character(len=:), allocatable :: kept_by
   end type role_advice_t

contains

   !> The role rule on its own: keep the slave when it is the softer surface (by more
   !> than stiffness_contrast), swap when the master is; with moduli alike, swap when
   !> the master's sides are finer than the slave's by more than mesh_contrast.
   !> Nonpositive stiffnesses (no material) leave the mesh to decide.
   pure integer function role_choice(et_slave, et_master, h_slave, h_master) result(action)
      real(wp), intent(in) :: et_slave, et_master, h_slave, h_master
      action = roles_keep
      if (et_slave > 0.0_wp .and. et_master > 0.0_wp) then
         if (et_master*stiffness_contrast < et_slave) then
            action = roles_swap
            return
         end if
         if (et_slave*stiffness_contrast < et_master) return
      end if
      if (h_master > 0.0_wp .and. h_master*mesh_contrast < h_slave) action = roles_swap
   end function role_choice

   !> The advice for pair p of the model (NODE TO SURFACE pairs only; others keep
   !> their roles).  A nonempty `kept_by` (what keeps the roles as written: joint
   !> water, friction) turns an exchange into a warning, and so does ROLES=KEEP.  Faces are measured where they face each other: the sides
   !> with their middle inside the other face's bounding box enlarged by the longest
   !> side of either, so that a long master that only partly lies under the slave is
   !> judged by that part.
   function pair_roles(model, p, kept_by) result(advice)
      type(model_t), intent(in) :: model
      integer, intent(in) :: p
      character(len=*), intent(in) :: kept_by
      type(role_advice_t) :: advice
      type(contact_pair_t) :: pair
      integer(ip), allocatable :: mseg(:, :), melem(:), sseg(:, :), selem(:)
      integer, allocatable :: mside(:), sside(:)
      type(error_t), allocatable :: error
      real(wp) :: reach
      advice%reason = ''
      pair = model%pairs(p)
      if (pair%formulation /= pair_node_to_surface) return
      call master_segments(model, pair, mseg, melem, mside, error)
      if (allocated(error)) return
      if (model%surfaces(pair%slave)%kind == surface_element) then
         ! the slave face's segments as a master would have them (second-order sides in
         ! two), so that both spacings count node to node
         pair%master = pair%slave
         call master_segments(model, pair, sseg, selem, sside, error)
      else
         call slave_edges(model, pair, sseg, selem, sside, error)
      end if
      if (allocated(error) .or. size(mseg, 2) == 0 .or. size(sseg, 2) == 0) return
      reach = max(maxval(lengths(model%x, mseg)), maxval(lengths(model%x, sseg)))
      call facing(model, mseg, melem, sseg, reach, advice%h_master, advice%et_master)
      call facing(model, sseg, selem, mseg, reach, advice%h_slave, advice%et_slave)
      advice%action = role_choice(advice%et_slave, advice%et_master, advice%h_slave, advice%h_master)
      if (advice%action == roles_keep) return
      advice%reason = reason_text(advice)
      if (len(kept_by) > 0) then
         advice%action = roles_warn
         advice%kept_by = kept_by
      else if (.not. pair%auto_roles) then
         advice%action = roles_warn
         advice%kept_by = 'ROLES=KEEP'
      end if
   end function pair_roles

   !> The element sides of pair p's slave face as a surface of TYPE=ELEMENT (the sides
   !> slave_edges finds: a node surface's boundary edges), named and located as the
   !> slave surface, so that it can serve as a master.
   function sides_surface(model, p, error) result(surf)
      type(model_t), intent(in) :: model
      integer, intent(in) :: p
      type(error_t), allocatable, intent(out) :: error
      type(surface_t) :: surf
      integer(ip), allocatable :: edge(:, :), edge_elem(:)
      integer, allocatable :: edge_side(:)
      call slave_edges(model, model%pairs(p), edge, edge_elem, edge_side, error)
      if (allocated(error)) return
      surf%name = model%surfaces(model%pairs(p)%slave)%name
      surf%loc = model%surfaces(model%pairs(p)%slave)%loc
      surf%kind = surface_element
      surf%elem = edge_elem
      surf%side = edge_side
   end function sides_surface

   !> Median length and median E * thickness of the segments seg whose middle lies in
   !> the bounding box of `other` enlarged by `reach` (all of them when none does).
   subroutine facing(model, seg, elem, other, reach, h, et)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: seg(:, :), elem(:), other(:, :)
      real(wp), intent(in) :: reach
      real(wp), intent(out) :: h, et
      real(wp) :: lo(2), hi(2), mid(2)
      real(wp), allocatable :: len(:), mod_(:)
      logical, allocatable :: near(:)
      integer :: k
      lo = min(minval(model%x(:, other(1, :)), dim=2), minval(model%x(:, other(2, :)), dim=2)) - reach
      hi = max(maxval(model%x(:, other(1, :)), dim=2), maxval(model%x(:, other(2, :)), dim=2)) + reach
      allocate (near(size(seg, 2)))
      do k = 1, size(seg, 2)
         mid = 0.5_wp*(model%x(:, seg(1, k)) + model%x(:, seg(2, k)))
         near(k) = all(mid >= lo) .and. all(mid <= hi)
      end do
      if (.not. any(near)) near = .true.
      len = pack(lengths(model%x, seg), near)
      h = median(len)
      et = 0.0_wp
      if (.not. (allocated(model%elem_mat) .and. allocated(model%elem_thick) .and. allocated(model%materials))) return
      allocate (mod_(size(seg, 2)), source=0.0_wp)
      do k = 1, size(seg, 2)
         if (model%elem_mat(elem(k)) > 0) &
            mod_(k) = model%materials(model%elem_mat(elem(k)))%young*model%elem_thick(elem(k))
      end do
      mod_ = pack(mod_, near .and. mod_ > 0.0_wp)
      if (size(mod_) > 0) et = median(mod_)
   end subroutine facing

   pure function lengths(x, seg) result(len)
      real(wp), intent(in) :: x(:, :)
      integer(ip), intent(in) :: seg(:, :)
      real(wp) :: len(size(seg, 2))
      integer :: k
      do k = 1, size(seg, 2)
         len(k) = length2(x(:, seg(2, k)) - x(:, seg(1, k)))
      end do
   end function lengths

   !> "the master is 1000x softer than the slave" or "the master's sides are 3.2x
   !> shorter than the slave's node spacing, with moduli alike"
   function reason_text(advice) result(s)
      type(role_advice_t), intent(in) :: advice
      character(len=:), allocatable :: s
      if (advice%et_slave > 0.0_wp .and. advice%et_master*stiffness_contrast < advice%et_slave) then
         s = 'the master is '//ratio_text(advice%et_slave/advice%et_master)//'x softer than the slave'
      else
         s = 'the master''s sides are '//ratio_text(advice%h_slave/advice%h_master)// &
             'x shorter than the slave''s node spacing'
      end if
   end function reason_text

   !> 3.2, 48 or 1.0e+06
   pure function ratio_text(r) result(s)
      real(wp), intent(in) :: r
      character(len=:), allocatable :: s
      character(len=32) :: buf
      if (r < 10.0_wp) then
         write (buf, '(f0.1)') r
      else if (r < 1.0e5_wp) then
         write (buf, '(i0)') nint(r)
      else
         write (buf, '(es8.1)') r
      end if
      s = trim(adjustl(buf))
   end function ratio_text
end module vemcontact_contact_roles
