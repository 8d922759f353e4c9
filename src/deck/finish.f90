!> Checks and resolution after the whole deck is read: exact-size arrays,
!> duplicate ids, element connectivity from user node ids to internal indices,
!> sorted sets, sections applied to elements (exactly one each), materials,
!> GRAV densities, contact pairs, and the steps.
module vemcontact_deck_finish
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, source_loc_t, string_t, etype_polygon, etype_polygon2, form_vem, form_fem, &
                               element_order
   use vemcontact_deck_state, only: deck_parser_t, err_at, loc_str
   use vemcontact_deck_loads, only: end_step, acc_to_step, trim_steps
   use vemcontact_deck_contact, only: finish_contact
   use vemcontact_deck_idmap, only: sort_unique
   use vemcontact_deck_fields, only: int_str, edit_distance
   implicit none
   private

   public :: finish_model

   !> Elements without a section reported one by one before a summary line.
   integer, parameter :: max_listed = 10

contains

   subroutine finish_model(p, model, path)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      character(len=*), intent(in) :: path
      integer :: k
      if (p%in_step) then
         call err_at(p, p%step_loc, 'the step is not closed by *END STEP')
         call end_step(p, model)
      end if
      if (allocated(p%warnings)) call move_alloc(p%warnings, model%warnings)
      if (.not. allocated(model%warnings)) allocate (model%warnings(0))
      allocate (model%files(p%src%nfiles))
      do k = 1, p%src%nfiles
         model%files(k)%s = p%src%files(k)%path
      end do
      if (p%nkeyword == 0) then
         call p%diag%report(path, 0, 'the deck is empty: it has no keyword lines')
         return
      end if
      call finish_nodes(p, model)
      call finish_elements(p, model)
      call finish_sets(p, model)
      call apply_sections(p, model)
      call check_grav(p, model)
      call finish_contact(p, model)
      call acc_to_step(p%init, model%initial)
      model%initial%name = 'initial'
      call trim_steps(p, model)
      ! after other errors (a failed *INCLUDE, a skipped block) these would be noise
      if (p%diag%count > 0) return
      if (model%nnode == 0) call p%diag%report(path, 0, 'the deck defines no nodes (*NODE)')
      if (model%nelem == 0) call p%diag%report(path, 0, 'the deck defines no elements (*ELEMENT)')
      if (p%nstep == 0) then
         call p%diag%report(path, 0, 'nothing to solve: the deck has no *STEP', &
                            help='add *STEP, *STATIC, loads and *END STEP after the model data')
      end if
   end subroutine finish_model

   subroutine finish_nodes(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer(ip) :: n, k, a, b
      n = model%nnode
      if (p%node_cap == 0) then
         allocate (model%node_id(0), model%x(2, 0), model%node_loc(0))
      else if (n < p%node_cap) then
         model%node_id = model%node_id(1:n)
         model%x = model%x(:, 1:n)
         model%node_loc = model%node_loc(1:n)
      end if
      call p%node_map%build(model%node_id)
      do k = 1, p%node_map%ndup
         a = p%node_map%dup(1, k)
         b = p%node_map%dup(2, k)
         call err_at(p, model%node_loc(b), 'duplicate node id '//int_str(model%node_id(b))// &
                     ' (first defined at '//loc_str(p, model%node_loc(a))//')')
      end do
   end subroutine finish_nodes

   subroutine finish_elements(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer(ip) :: n, k, a, b, e, i, idx
      n = model%nelem
      if (p%elem_cap == 0) then
         allocate (model%elem_id(0), model%elem_ptr(1), model%elem_conn(0), model%elem_type(0), &
                   model%elem_plane(0), model%elem_loc(0))
         model%elem_ptr(1) = 1
      else if (n < p%elem_cap .or. p%nconn < p%conn_cap) then
         model%elem_id = model%elem_id(1:n)
         model%elem_ptr = model%elem_ptr(1:n + 1)
         model%elem_conn = model%elem_conn(1:p%nconn)
         model%elem_type = model%elem_type(1:n)
         model%elem_plane = model%elem_plane(1:n)
         model%elem_loc = model%elem_loc(1:n)
      end if
      allocate (model%elem_form(n), model%elem_mat(n), model%elem_thick(n), model%elem_stab(n))
      model%elem_form = 0
      model%elem_mat = 0
      model%elem_thick = 1.0_wp
      model%elem_stab = 1.0_wp
      call p%elem_map%build(model%elem_id)
      do k = 1, p%elem_map%ndup
         a = p%elem_map%dup(1, k)
         b = p%elem_map%dup(2, k)
         call err_at(p, model%elem_loc(b), 'duplicate element id '//int_str(model%elem_id(b))// &
                     ' (first defined at '//loc_str(p, model%elem_loc(a))//')')
      end do
      do e = 1, n
         do i = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
            idx = p%node_map%lookup(model%elem_conn(i))
            if (idx == 0) then
               call err_at(p, model%elem_loc(e), 'element '//int_str(model%elem_id(e))// &
                           ' refers to undefined node '//int_str(model%elem_conn(i)))
               exit
            end if
            model%elem_conn(i) = idx
         end do
      end do
   end subroutine finish_elements

   subroutine finish_sets(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer :: k
      call pack_sets(model%nsets, p%nnset, p%nset_items)
      call pack_sets(model%elsets, p%nelset, p%elset_items)
   contains
      subroutine pack_sets(sets, nsets, items)
         use vemcontact_model, only: named_set_t
         use vemcontact_deck_state, only: item_list_t
         type(named_set_t), allocatable, intent(inout) :: sets(:)
         integer, intent(in) :: nsets
         type(item_list_t), allocatable, intent(inout) :: items(:)
         type(named_set_t), allocatable :: t(:)
         integer(ip) :: n
         allocate (t(nsets))
         do k = 1, nsets
            call move_alloc(sets(k)%name, t(k)%name)
            t(k)%loc = sets(k)%loc
            n = items(k)%n
            if (n > 0) then
               call sort_unique(items(k)%a, n)
               t(k)%items = items(k)%a(1:n)
            else
               allocate (t(k)%items(0))
            end if
         end do
         call move_alloc(t, sets)
      end subroutine pack_sets
   end subroutine finish_sets

   !> Resolve section materials and give every element exactly one section.
   subroutine apply_sections(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer, allocatable :: owner(:)
      logical, allocatable :: reported(:)
      integer :: s, m, nmissing, nbad, nfem, nstab
      integer(ip) :: i, e, nn, efirst, ebad, estab
      character(len=:), allocatable :: help
      allocate (owner(model%nelem), reported(p%nmat))
      owner = 0
      reported = .false.
      if (allocated(model%sections)) then
         model%sections = model%sections(1:p%nsec)
      else
         allocate (model%sections(0))
      end if
      if (allocated(model%materials)) then
         model%materials = model%materials(1:p%nmat)
      else
         allocate (model%materials(0))
      end if
      do s = 1, p%nsec
         associate (sec => model%sections(s))
            sec%imat = 0
            do m = 1, p%nmat
               if (model%materials(m)%name == sec%material) sec%imat = m
            end do
            if (sec%imat == 0) then
               help = ''
               do m = 1, p%nmat
                  if (edit_distance(sec%material, model%materials(m)%name) <= max(1, len(sec%material)/3)) &
                     help = 'did you mean '//model%materials(m)%name//'?'
               end do
               call err_at(p, sec%loc, 'undefined material '//sec%material, help)
            else if (.not. model%materials(sec%imat)%has_elastic .and. .not. reported(sec%imat)) then
               reported(sec%imat) = .true.
               call err_at(p, model%materials(sec%imat)%loc, 'material '//model%materials(sec%imat)%name// &
                           ' has no *ELASTIC constants', 'add *ELASTIC with E, nu after *MATERIAL')
            end if
            nbad = 0
            nfem = 0
            nstab = 0
            efirst = 0
            ebad = 0
            estab = 0
            do i = 1, p%sec_items(s)%n
               e = p%sec_items(s)%a(i)
               if (owner(e) /= 0) then
                  if (owner(e) /= s) then
                     nbad = nbad + 1
                     if (nbad == 1) efirst = e
                  end if
                  cycle
               end if
               owner(e) = s
               model%elem_mat(e) = sec%imat
               model%elem_thick(e) = sec%thickness
               model%elem_stab(e) = sec%stabilization
               if (sec%formulation /= 0) then
                  model%elem_form(e) = sec%formulation
               else if (model%elem_type(e) == etype_polygon .or. model%elem_type(e) == etype_polygon2) then
                  model%elem_form(e) = form_vem
               else
                  model%elem_form(e) = form_fem
               end if
               nn = model%elem_ptr(e + 1) - model%elem_ptr(e)
               ! FEM: 3 or 4 corners, with or without side nodes
               if (model%elem_form(e) == form_fem .and. nn/element_order(model%elem_type(e)) > 4) then
                  nfem = nfem + 1
                  if (nfem == 1) ebad = e
               end if
               ! the FEM kernels have no stabilisation: a factor there would be ignored silently
               if (model%elem_form(e) == form_fem .and. sec%has_stabilization) then
                  nstab = nstab + 1
                  if (nstab == 1) estab = e
               end if
            end do
            if (nbad > 0) then
               call err_at(p, sec%loc, 'element '//int_str(model%elem_id(efirst))//' already has a section (from '// &
                           loc_str(p, model%sections(owner(efirst))%loc)//')'//more(nbad - 1), &
                           'every element needs exactly one *SOLID SECTION')
            end if
            if (nstab > 0) then
               call err_at(p, sec%loc, 'STABILIZATION= on FEM element '//int_str(model%elem_id(estab))// &
                           more(nstab - 1)//': only the virtual element has a stabilisation', &
                           'use FORMULATION=VEM, or drop STABILIZATION= (CPE*/CPS* elements are FEM '// &
                           'unless the section says FORMULATION=VEM)')
            end if
            if (nfem > 0) then
               call err_at(p, sec%loc, 'FORMULATION=FEM on element '//int_str(model%elem_id(ebad))//' with '// &
                           int_str(model%elem_ptr(ebad + 1) - model%elem_ptr(ebad))//' nodes'//more(nfem - 1), &
                           'FEM needs triangles or quadrilaterals (3 or 4 corners, with or without side '// &
                           'nodes); use FORMULATION=VEM for polygons')
            end if
         end associate
      end do
      if (p%section_errors) return
      nmissing = 0
      do e = 1, model%nelem
         if (owner(e) /= 0) cycle
         nmissing = nmissing + 1
         if (nmissing <= max_listed) then
            call err_at(p, model%elem_loc(e), 'element '//int_str(model%elem_id(e))// &
                        ' has no section', 'assign one with *SOLID SECTION, ELSET=..., MATERIAL=...')
         end if
      end do
      if (nmissing > max_listed) then
         call p%diag%report(p%src%path(1), 0, int_str(nmissing - max_listed)// &
                            ' more elements have no section')
      end if
   contains
      function more(n) result(s)
         integer, intent(in) :: n
         character(len=:), allocatable :: s
         s = ''
         if (n > 0) s = ' (and '//int_str(n)//' more elements)'
      end function more
   end subroutine apply_sections

   !> GRAV needs the density of the element's material.
   subroutine check_grav(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      integer :: k, m
      type(source_loc_t) :: last
      last = source_loc_t(0, 0)
      do k = 1, p%ngrav
         m = model%elem_mat(p%grav(k)%elem)
         if (m == 0) cycle
         if (model%materials(m)%has_density) cycle
         if (p%grav(k)%loc%file == last%file .and. p%grav(k)%loc%line == last%line) cycle
         last = p%grav(k)%loc
         call err_at(p, last, 'GRAV on element '//int_str(model%elem_id(p%grav(k)%elem))// &
                     ' whose material '//model%materials(m)%name//' has no *DENSITY', &
                     'add *DENSITY to material '//model%materials(m)%name)
      end do
   end subroutine check_grav
end module vemcontact_deck_finish
