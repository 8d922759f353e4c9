!> Abaqus/CAE's deck structure, flattened into one model: *PART ... *END PART,
!> *ASSEMBLY ... *END ASSEMBLY with *INSTANCE ... *END INSTANCE, and the
!> no-op keywords *PREPRINT and *RESTART.
!>
!> A part's keywords are read straight into the model, with its node and element
!> ids shifted past the ids read before it (parts number from 1 each) and its set
!> names qualified by the part's name (the parser prefixes NSET=/ELSET=).  Its
!> *INSTANCE then moves its nodes (translation, then rotation about an axis
!> parallel to z) and renames its sets "instance.set", the names the assembly
!> and the steps use (`Part-1-1.Set-1`).  Each part is instanced exactly once:
!> a part without an instance, or with two, is refused with one message each.
module vemcontact_deck_assembly
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t
   use vemcontact_deck_state, only: deck_parser_t, part_ref_t, here, err_here, err_at, warn_here, refuse_here, &
                                    get_real, field, loc_str
   use vemcontact_deck_lines, only: advance
   use vemcontact_deck_source, only: line_data
   use vemcontact_deck_fields, only: keyword_line_t, get_param, has_param, split_fields, int_str
   implicit none
   private

   public :: read_part, end_part, read_assembly, end_assembly, read_instance, end_instance, &
             read_noop, instance_offsets, check_parts, qualify_in_part

   real(wp), parameter :: pi = 4.0_wp*atan(1.0_wp)

contains

   !> *PART, NAME=name: the keywords up to *END PART define the part.
   subroutine read_part(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      type(keyword_line_t), intent(in) :: kw
      type(part_ref_t) :: part
      character(len=:), allocatable :: name
      logical :: found
      integer :: k
      if (p%cur_part > 0) then
         call err_here(p, '*PART inside the part '//p%parts(p%cur_part)%name//' (started at '// &
                       loc_str(p, p%parts(p%cur_part)%loc)//'): it has no *END PART')
         call end_part(p, model)
      end if
      if (p%in_assembly) then
         call err_here(p, '*PART inside *ASSEMBLY', 'parts go before the *ASSEMBLY')
         return
      end if
      call get_param(kw, 'NAME', name, found)
      if (.not. allocated(p%parts)) allocate (p%parts(0))
      do k = 1, size(p%parts)
         if (p%parts(k)%name == name) then
            call err_here(p, 'part '//name//' already defined at '//loc_str(p, p%parts(k)%loc))
            return
         end if
      end do
      part%name = name
      part%instance = ''
      part%loc = here(p)
      part%first_node = model%nnode + 1
      part%first_elem = model%nelem + 1
      if (model%nnode > 0) part%node_offset = maxval(model%node_id(1:model%nnode))
      if (model%nelem > 0) part%elem_offset = maxval(model%elem_id(1:model%nelem))
      p%parts = [p%parts, part]
      p%cur_part = size(p%parts)
      p%node_offset = part%node_offset
      p%elem_offset = part%elem_offset
   end subroutine read_part

   !> *END PART: the part's nodes and elements are those read since its *PART.
   subroutine end_part(p, model)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(in) :: model
      if (p%cur_part == 0) then
         call err_here(p, '*END PART without a matching *PART')
         return
      end if
      p%parts(p%cur_part)%last_node = model%nnode
      p%parts(p%cur_part)%last_elem = model%nelem
      p%cur_part = 0
      p%node_offset = 0
      p%elem_offset = 0
   end subroutine end_part

   !> The name NSET=/ELSET= give inside a part: "part.name" (the instance renames it).
   pure function qualify_in_part(p, name) result(q)
      type(deck_parser_t), intent(in) :: p
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: q
      q = name
      if (p%cur_part > 0) q = p%parts(p%cur_part)%name//'.'//name
   end function qualify_in_part

   !> *ASSEMBLY [, NAME=name].
   subroutine read_assembly(p)
      type(deck_parser_t), intent(inout) :: p
      if (p%cur_part > 0) then
         call err_here(p, '*ASSEMBLY inside the part '//p%parts(p%cur_part)%name//': it has no *END PART')
         p%cur_part = 0
         p%node_offset = 0
         p%elem_offset = 0
      end if
      if (p%in_assembly) call err_here(p, 'a second *ASSEMBLY before *END ASSEMBLY')
      p%in_assembly = .true.
   end subroutine read_assembly

   !> *END ASSEMBLY.
   subroutine end_assembly(p)
      type(deck_parser_t), intent(inout) :: p
      if (.not. p%in_assembly) call err_here(p, '*END ASSEMBLY without a matching *ASSEMBLY')
      if (p%cur_instance > 0) call err_here(p, 'the *INSTANCE before *END ASSEMBLY has no *END INSTANCE')
      p%in_assembly = .false.
      p%cur_instance = 0
   end subroutine end_assembly

   !> *INSTANCE, NAME=name, PART=part; data lines (optional): the translation
   !> x, y [, z], then the rotation ax, ay, az, bx, by, bz, angle (degrees, about
   !> the axis from a to b, right-handed), as Abaqus writes them.  The translation
   !> is applied first.
   subroutine read_instance(p, model, kw)
      type(deck_parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: model
      type(keyword_line_t), intent(in) :: kw
      character(len=:), allocatable :: name, pname
      logical :: found, ok
      integer :: k, kp, nline
      real(wp) :: v(7), shift(2), c, s, dz
      real(wp), allocatable :: x(:, :)
      call get_param(kw, 'NAME', name, found)
      call get_param(kw, 'PART', pname, found)
      kp = 0
      if (allocated(p%parts)) then
         do k = 1, size(p%parts)
            if (p%parts(k)%name == pname) kp = k
            if (p%parts(k)%instance == name) then
               call err_here(p, 'instance '//name//' already defined (of part '//p%parts(k)%name//')')
               call skip_lines(p)
               return
            end if
         end do
      end if
      if (.not. p%in_assembly) call err_here(p, '*INSTANCE outside *ASSEMBLY ... *END ASSEMBLY')
      if (kp == 0) then
         call err_here(p, 'undefined part '//pname, 'a *PART, NAME='//pname//' must come before its instance')
         call skip_lines(p)
         return
      end if
      if (len(p%parts(kp)%instance) > 0) then
         call refuse_here(p, 'a second instance of part '//pname//' (the first is '//p%parts(kp)%instance//')', &
                          'vemcontact flattens each part into its one instance: copy the part for a second one')
         return
      end if
      p%parts(kp)%instance = name
      p%cur_instance = kp
      call rename_sets(model, p%parts(kp)%name, name)
      associate (pt => p%parts(kp))
         x = model%x(:, pt%first_node:pt%last_node)
      end associate
      nline = 0
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
         nline = nline + 1
         call split_fields(p%src%text(1:p%src%length), p%f)
         v = 0.0_wp
         if (nline == 1) then
            if (p%f%n < 2 .or. p%f%n > 3) then
               call err_here(p, '*INSTANCE translation line: expected x, y [, z], found '//int_str(p%f%n)//' fields')
               cycle
            end if
            do k = 1, p%f%n
               call get_real(p, k, 'translation component', v(k), ok)
               if (.not. ok) exit
            end do
            if (.not. ok) cycle
            if (abs(v(3)) > 0.0_wp) then
               call err_here(p, 'a translation in z ('//field(p, 3)//') leaves the plane of a 2D model')
               cycle
            end if
            shift = v(1:2)
            x(1, :) = x(1, :) + shift(1)
            x(2, :) = x(2, :) + shift(2)
         else if (nline == 2) then
            if (p%f%n /= 7) then
               call err_here(p, '*INSTANCE rotation line: expected ax, ay, az, bx, by, bz, angle, found '// &
                             int_str(p%f%n)//' fields')
               cycle
            end if
            do k = 1, 7
               call get_real(p, k, 'rotation field', v(k), ok)
               if (.not. ok) exit
            end do
            if (.not. ok) cycle
            dz = v(6) - v(3)
            if (abs(v(4) - v(1)) > 0.0_wp .or. abs(v(5) - v(2)) > 0.0_wp .or. .not. abs(dz) > 0.0_wp) then
               call err_here(p, 'the rotation axis of a 2D instance must be parallel to z (a and b differ '// &
                             'in z only)')
               cycle
            end if
            c = cos(sign(1.0_wp, dz)*v(7)*pi/180.0_wp)
            s = sin(sign(1.0_wp, dz)*v(7)*pi/180.0_wp)
            call rotate(x, v(1:2), c, s)
         else
            call err_here(p, '*INSTANCE takes at most two data lines (translation, rotation)')
         end if
      end do
      associate (pt => p%parts(kp))
         model%x(:, pt%first_node:pt%last_node) = x
      end associate
   end subroutine read_instance

   !> Rotate the points x about the point a by the angle with cosine c and sine s.
   pure subroutine rotate(x, a, c, s)
      real(wp), intent(inout) :: x(:, :)
      real(wp), intent(in) :: a(2), c, s
      real(wp) :: dx, dy
      integer :: i
      do i = 1, size(x, 2)
         dx = x(1, i) - a(1)
         dy = x(2, i) - a(2)
         x(1, i) = a(1) + c*dx - s*dy
         x(2, i) = a(2) + s*dx + c*dy
      end do
   end subroutine rotate

   !> Sets "part.x" become "instance.x".
   subroutine rename_sets(model, part, instance)
      type(model_t), intent(inout) :: model
      character(len=*), intent(in) :: part, instance
      integer :: k
      if (allocated(model%nsets)) then
         do k = 1, size(model%nsets)
            if (.not. allocated(model%nsets(k)%name)) cycle
            if (index(model%nsets(k)%name, part//'.') == 1) &
               model%nsets(k)%name = instance//model%nsets(k)%name(len(part) + 1:)
         end do
      end if
      if (allocated(model%elsets)) then
         do k = 1, size(model%elsets)
            if (.not. allocated(model%elsets(k)%name)) cycle
            if (index(model%elsets(k)%name, part//'.') == 1) &
               model%elsets(k)%name = instance//model%elsets(k)%name(len(part) + 1:)
         end do
      end if
      if (allocated(model%sections)) then
         do k = 1, size(model%sections)
            if (.not. allocated(model%sections(k)%elset)) cycle
            if (index(model%sections(k)%elset, part//'.') == 1) &
               model%sections(k)%elset = instance//model%sections(k)%elset(len(part) + 1:)
         end do
      end if
   end subroutine rename_sets

   !> *END INSTANCE.
   subroutine end_instance(p)
      type(deck_parser_t), intent(inout) :: p
      if (p%cur_instance == 0) call err_here(p, '*END INSTANCE without a matching *INSTANCE')
      p%cur_instance = 0
   end subroutine end_instance

   !> The id offsets of INSTANCE=name on *NSET and *ELSET in the assembly (the ids of
   !> its data lines are the part's own); ok false (reported) for an unknown instance.
   subroutine instance_offsets(p, kw, ok)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t), intent(in) :: kw
      logical, intent(out) :: ok
      character(len=:), allocatable :: name
      logical :: found
      integer :: k
      ok = .true.
      call get_param(kw, 'INSTANCE', name, found)
      if (.not. found) return
      if (allocated(p%parts)) then
         do k = 1, size(p%parts)
            if (p%parts(k)%instance == name) then
               p%node_offset = p%parts(k)%node_offset
               p%elem_offset = p%parts(k)%elem_offset
               return
            end if
         end do
      end if
      call err_here(p, 'undefined instance '//name, 'an *INSTANCE, NAME='//name//' must come first')
      ok = .false.
   end subroutine instance_offsets

   !> *PREPRINT (Abaqus' printout of the input) and *RESTART, WRITE (restart
   !> files): accepted with a note, they change no result.  *RESTART, READ would
   !> continue another analysis: refused.
   subroutine read_noop(p, kw, name)
      type(deck_parser_t), intent(inout) :: p
      type(keyword_line_t), intent(in) :: kw
      character(len=*), intent(in) :: name
      if (name == 'RESTART' .and. has_param(kw, 'READ')) then
         call refuse_here(p, '*RESTART, READ (continuing an analysis from a restart file)')
         return
      end if
      if (name == 'PREPRINT') then
         call warn_here(p, '*PREPRINT is accepted and ignored (it controls Abaqus'' printed echo of the input)')
      else
         call warn_here(p, '*RESTART is accepted and ignored: vemcontact writes no restart file')
      end if
      call skip_lines(p)
   end subroutine read_noop

   !> After the deck: every part instanced (its nodes and elements are in the
   !> model only through its instance), no part or assembly left open.
   subroutine check_parts(p)
      type(deck_parser_t), intent(inout) :: p
      integer :: k
      if (p%cur_part > 0) call err_at(p, p%parts(p%cur_part)%loc, 'the part has no *END PART')
      if (.not. allocated(p%parts)) return
      do k = 1, size(p%parts)
         if (len(p%parts(k)%instance) == 0) &
            call err_at(p, p%parts(k)%loc, 'part '//p%parts(k)%name//' has no *INSTANCE', &
                        'vemcontact models the instances of the assembly; remove the part or instance it')
      end do
   end subroutine check_parts

   subroutine skip_lines(p)
      type(deck_parser_t), intent(inout) :: p
      do
         call advance(p)
         if (p%src%kind /= line_data) exit
      end do
   end subroutine skip_lines
end module vemcontact_deck_assembly
