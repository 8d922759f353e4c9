!> Handlers of the property keywords: *MATERIAL, *ELASTIC, *DENSITY and *SOLID SECTION.
!> Sections take the elements of their set as it is when the *SOLID SECTION line
!> is read (as CalculiX does); material names are resolved after the whole deck
!> is read, so a material may also be defined after the section that uses it.
module vemcontact_deck_props
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t, material_t, section_t, form_vem, form_fem
   use vemcontact_deck_state, only: deck_parser_t, item_list_t, here, err_here, get_real, get_set, &
                                    set_suggestion, loc_str, push_item, field, tidy_items
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: keyword_line_t, split_fields, get_param, squeeze
   use vemcontact_deck_numbers, only: parse_real, num_ok
   implicit none
   private

   public :: read_material, read_elastic, read_density, read_section, read_expansion

contains

   !> *MATERIAL, NAME=name (no data lines).
   subroutine read_material(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: name
      type(material_t), allocatable :: t(:)
      logical :: found
      integer :: k
      call get_param(kw, 'NAME', name, found)
      do k = 1, p%nmat
         if (model%materials(k)%name == name) then
            call err_here(p, 'duplicate material name '//name//' (first defined at '// &
                          loc_str(p, model%materials(k)%loc)//')')
            p%cur_mat = -1   ! its *ELASTIC and *DENSITY lines are read but dropped
            return
         end if
      end do
      if (.not. allocated(model%materials)) allocate (model%materials(4))
      if (p%nmat == size(model%materials)) then
         allocate (t(2*p%nmat))
         t(1:p%nmat) = model%materials(1:p%nmat)
         call move_alloc(t, model%materials)
      end if
      p%nmat = p%nmat + 1
      model%materials(p%nmat)%name = name
      model%materials(p%nmat)%loc = here(p)
      p%cur_mat = p%nmat
   end subroutine read_material

   !> Read the single data line of *ELASTIC or *DENSITY into p%f; ok = .false. (reported) if
   !> there is none or there are more (temperature tables are not supported).
   subroutine one_data_line(p, kname, expect, ok)
      type(deck_parser_t), intent(inout) :: p
      character(len=*), intent(in) :: kname, expect
      logical, intent(out) :: ok
      call advance(p)
      ok = p%src%kind == line_data
      if (.not. ok) then
         call err_here(p, kname//' needs a data line: '//expect)
         return
      end if
      call split_fields(p%src%text(1:p%src%length), p%f)
   end subroutine one_data_line

   !> Report and skip extra data lines after the one of *ELASTIC and *DENSITY.
   subroutine extra_lines(p, kname)
      type(deck_parser_t), intent(inout) :: p
      character(len=*), intent(in) :: kname
      logical :: first
      first = .true.
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         if (first) call err_here(p, kname//' takes one data line: temperature-dependent '// &
                                  'properties are not supported')
         first = .false.
      end do
   end subroutine extra_lines

   !> *ELASTIC [, TYPE=ISO]; data line: E, nu [, temperature (ignored)].
   subroutine read_elastic(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      real(wp) :: e, nu
      logical :: ok, ok_e, ok_nu
      if (p%cur_mat == 0) then
         call err_here(p, '*ELASTIC must follow a *MATERIAL', 'start the material with *MATERIAL, NAME=...')
      end if
      call one_data_line(p, '*ELASTIC', 'E, nu', ok)
      if (.not. ok) return
      if (p%f%n > 3) then
         call err_here(p, 'too many fields on the *ELASTIC data line: expected E, nu [, temperature]')
         ok = .false.
      end if
      if (ok) then
         ! E and nu are checked independently so that both problems are reported
         call get_real(p, 1, 'Young''s modulus E', e, ok_e, required=.true.)
         call get_real(p, 2, 'Poisson''s ratio nu', nu, ok_nu, required=.true.)
         if (ok_e .and. .not. e > 0.0_wp) then
            call err_here(p, 'Young''s modulus E = '//field(p, 1)//' must be positive')
            ok_e = .false.
         end if
         if (ok_nu .and. .not. (nu > -1.0_wp .and. nu < 0.5_wp)) then
            call err_here(p, 'Poisson''s ratio nu = '//field(p, 2)//' must satisfy -1 < nu < 0.5')
            ok_nu = .false.
         end if
         ok = ok_e .and. ok_nu
      end if
      if (ok .and. p%cur_mat > 0) then
         associate (m => model%materials(p%cur_mat))
            if (m%has_elastic) then
               call err_here(p, 'material '//m%name//' already has *ELASTIC')
            else
               m%young = e
               m%poisson = nu
               m%has_elastic = .true.
            end if
         end associate
      end if
      call extra_lines(p, '*ELASTIC')
   end subroutine read_elastic

   !> *DENSITY; data line: rho [, temperature (ignored)].
   subroutine read_density(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      real(wp) :: rho
      logical :: ok
      if (p%cur_mat == 0) then
         call err_here(p, '*DENSITY must follow a *MATERIAL', 'start the material with *MATERIAL, NAME=...')
      end if
      call one_data_line(p, '*DENSITY', 'rho', ok)
      if (.not. ok) return
      if (p%f%n > 2) then
         call err_here(p, 'too many fields on the *DENSITY data line: expected rho [, temperature]')
         ok = .false.
      end if
      if (ok) call get_real(p, 1, 'density', rho, ok, required=.true.)
      if (ok .and. .not. rho > 0.0_wp) then
         call err_here(p, 'density '//field(p, 1)//' must be positive')
         ok = .false.
      end if
      if (ok .and. p%cur_mat > 0) then
         associate (m => model%materials(p%cur_mat))
            if (m%has_density) then
               call err_here(p, 'material '//m%name//' already has *DENSITY')
            else
               m%density = rho
               m%has_density = .true.
            end if
         end associate
      end if
      call extra_lines(p, '*DENSITY')
   end subroutine read_density

   !> *EXPANSION [, TYPE=ISO] [, ZERO=T]: one data line `alpha [, temperature]`, the
   !> isotropic coefficient of thermal expansion (CalculiX and Abaqus).  ZERO (the
   !> temperature at which a temperature-dependent alpha is defined) changes nothing
   !> for a constant alpha and is accepted; temperature tables are not supported.
   subroutine read_expansion(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      real(wp) :: alpha
      logical :: ok
      if (p%cur_mat == 0) then
         call err_here(p, '*EXPANSION must follow a *MATERIAL', 'start the material with *MATERIAL, NAME=...')
      end if
      call one_data_line(p, '*EXPANSION', 'alpha', ok)
      if (.not. ok) return
      if (p%f%n > 2) then
         call err_here(p, 'too many fields on the *EXPANSION data line: expected alpha [, temperature]')
         ok = .false.
      end if
      if (ok) call get_real(p, 1, 'expansion coefficient', alpha, ok, required=.true.)
      if (ok .and. p%cur_mat > 0) then
         associate (m => model%materials(p%cur_mat))
            if (m%has_expansion) then
               call err_here(p, 'material '//m%name//' already has *EXPANSION')
            else
               m%expansion = alpha
               m%has_expansion = .true.
            end if
         end associate
      end if
      call extra_lines(p, '*EXPANSION')
   end subroutine read_expansion

   !> OFFSET= of *SOLID SECTION (CalculiX: the offset of a shell or beam section's
   !> reference surface, in units of the thickness): zero changes nothing for a
   !> plane element and is accepted; any other value is out of scope.
   subroutine check_offset(p, kw)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: text
      logical :: found
      real(wp) :: offset
      integer :: stat
      call get_param(kw, 'OFFSET', text, found)
      if (.not. found) return
      ! the registry has checked that it is a finite number
      call parse_real(squeeze(text), offset, stat)
      if (stat == num_ok .and. abs(offset) > 0.0_wp) &
         call err_here(p, '*SOLID SECTION, OFFSET='//text//' is not supported: vemcontact accepts '// &
                       'OFFSET=0 only (plane elements have no offset reference surface)')
   end subroutine check_offset

   !> *SOLID SECTION, ELSET=, MATERIAL= [, FORMULATION=VEM|FEM] [, STABILIZATION=tau] [, OFFSET=0];
   !> data line: [thickness].  STABILIZATION (vemcontact) scales the VEM stabilisation;
   !> its use on FEM elements is refused once formulations are known (finish).
   subroutine read_section(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: elset, mat, form, stab
      type(section_t), allocatable :: t(:)
      type(item_list_t), allocatable :: ti(:)
      logical :: found, ok, has_stab
      integer :: kset, k, nline, stat
      real(wp) :: thick, tau
      call get_param(kw, 'ELSET', elset, found)
      call get_param(kw, 'MATERIAL', mat, found)
      call get_param(kw, 'FORMULATION', form, found)
      call get_param(kw, 'STABILIZATION', stab, has_stab)
      call check_offset(p, kw)
      tau = 1.0_wp
      if (has_stab) then
         ! the registry has checked that it is a finite number
         call parse_real(squeeze(stab), tau, stat)
         if (stat /= num_ok) then
            has_stab = .false.
            tau = 1.0_wp
         else if (.not. tau > 0.0_wp) then
            call err_here(p, 'STABILIZATION = '//stab//' must be positive', &
                          'it scales the VEM stabilisation (hourglass) stiffness; default 1, '// &
                          'see docs/vem-stabilisation.md')
            tau = 1.0_wp
         end if
      end if
      call get_set(model%elsets, p%elset_items, p%nelset, elset, here(p), .false., kset)
      if (kset == 0) then
         call err_here(p, 'undefined element set '//elset, set_suggestion(model%elsets, p%nelset, elset))
         p%section_errors = .true.
      end if
      if (.not. allocated(model%sections)) allocate (model%sections(4), p%sec_items(4))
      if (p%nsec == size(model%sections)) then
         allocate (t(2*p%nsec), ti(2*p%nsec))
         t(1:p%nsec) = model%sections(1:p%nsec)
         do k = 1, p%nsec
            call move_alloc(p%sec_items(k)%a, ti(k)%a)
            ti(k)%n = p%sec_items(k)%n
         end do
         call move_alloc(t, model%sections)
         call move_alloc(ti, p%sec_items)
      end if
      p%nsec = p%nsec + 1
      associate (s => model%sections(p%nsec), items => p%sec_items(p%nsec))
         s%elset = elset
         s%material = mat
         s%loc = here(p)
         s%thickness = 1.0_wp
         s%formulation = 0
         s%stabilization = tau
         s%has_stabilization = has_stab
         if (form == 'VEM') s%formulation = form_vem
         if (form == 'FEM') s%formulation = form_fem
         items%n = 0
         if (kset > 0) then
            call tidy_items(p%elset_items(kset))
            do k = 1, p%elset_items(kset)%n
               call push_item(items, p%elset_items(kset)%a(k))
            end do
         end if
      end associate
      nline = 0
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         nline = nline + 1
         if (nline > 1) then
            if (nline == 2) call err_here(p, '*SOLID SECTION takes one data line (the thickness)')
            cycle
         end if
         call split_fields(p%src%text(1:p%src%length), p%f)
         if (p%f%n > 1) then
            call err_here(p, 'too many fields on the *SOLID SECTION data line: expected the thickness')
            cycle
         end if
         call get_real(p, 1, 'thickness', thick, ok)
         if (.not. ok) cycle
         ! a blank thickness keeps the default of 1, as in CalculiX
         if (p%f%last(1) < p%f%first(1)) cycle
         if (.not. thick > 0.0_wp) then
            call err_here(p, 'thickness '//field(p, 1)//' must be positive')
            cycle
         end if
         model%sections(p%nsec)%thickness = thick
      end do
   end subroutine read_section
end module vemcontact_deck_props
