!> The PRINT requests of a step (*NODE PRINT, *EL PRINT, *CONTACT PRINT), which CalculiX
!> writes to its JOB.dat, as one CSV table per step, `JOB_print_NNNN.csv`
!> (docs/output-format.md): one row per value, columns
!> `variable,set,entity,id,component,value`.  `entity` is `node` or `element` for a value
!> of a node or element (user `id`), `total` for the sum over the set that TOTALS=YES or
!> ONLY asks for (`id` 0).  TOTALS applies to the nodal variables (U, RF); element and
!> contact values are always listed one by one.
module vemcontact_output_print
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t
   use vemcontact_model, only: model_t, output_node, output_element, output_contact, totals_no, totals_only, &
                               find_set
   use vemcontact_contact_table, only: contact_table_t
   use vemcontact_safe_file, only: safe_file_t
   implicit none
   private

   public :: has_print_requests, write_print_csv

contains

   !> Step `istep` has a PRINT request in force.
   pure logical function has_print_requests(model, istep)
      type(model_t), intent(in) :: model
      integer, intent(in) :: istep
      integer :: k
      has_print_requests = .false.
      if (.not. allocated(model%steps)) return
      if (istep < 1 .or. istep > size(model%steps)) return
      if (.not. allocated(model%steps(istep)%outputs)) return
      do k = 1, size(model%steps(istep)%outputs)
         if (model%steps(istep)%outputs(k)%print) has_print_requests = .true.
      end do
   end function has_print_requests

   !> Write the values that the PRINT requests of step `istep` select to `path`:
   !> displacements `u` and reactions `rf` (2, nnode), element stresses `s_elem` and
   !> strains `e_elem` (4, nelem: xx, yy, zz, xy, the strain's xy the engineering shear
   !> strain) and the contact results `tab` (when the model has contact).
   subroutine write_print_csv(path, model, istep, u, rf, s_elem, e_elem, error, tab)
      character(len=*), intent(in) :: path
      type(model_t), intent(in) :: model
      integer, intent(in) :: istep
      real(wp), intent(in) :: u(:, :), rf(:, :), s_elem(:, :), e_elem(:, :)
      type(error_t), allocatable, intent(out) :: error
      type(contact_table_t), intent(in), optional :: tab
      character(len=*), parameter :: node_comp(2) = ['1', '2'], elem_comp(4) = ['11', '22', '33', '12']
      type(safe_file_t) :: out
      integer :: k, j, ks, c
      integer(ip) :: i, n
      integer(ip), allocatable :: items(:)
      character(len=:), allocatable :: var, set
      call out%open(path, error)
      if (allocated(error)) return
      call out%write('variable,set,entity,id,component,value'//new_line('a'))
      do k = 1, size(model%steps(istep)%outputs)
         associate (r => model%steps(istep)%outputs(k))
            if (.not. r%print .or. .not. allocated(r%fields)) cycle
            set = r%set
            select case (r%category)
            case (output_node)
               ks = 0
               if (len(set) > 0) ks = find_set(model%nsets, set)
               if (ks > 0) then
                  items = model%nsets(ks)%items
               else
                  items = [(i, i=1, model%nnode)]
               end if
               do j = 1, size(r%fields)
                  var = r%fields(j)%s
                  if (var /= 'U' .and. var /= 'RF') cycle
                  if (r%totals /= totals_only) then
                     do n = 1, size(items, kind=ip)
                        i = items(n)
                        do c = 1, 2
                           call row(var, 'node', model%node_id(i), var//node_comp(c), node_value(var, c, i))
                        end do
                     end do
                  end if
                  if (r%totals /= totals_no) then
                     do c = 1, 2
                        call row(var, 'total', 0_ip, var//node_comp(c), node_total(var, c, items))
                     end do
                  end if
               end do
            case (output_element)
               ks = 0
               if (len(set) > 0) ks = find_set(model%elsets, set)
               if (ks > 0) then
                  items = model%elsets(ks)%items
               else
                  items = [(i, i=1, model%nelem)]
               end if
               do j = 1, size(r%fields)
                  var = r%fields(j)%s
                  if (var /= 'S' .and. var /= 'E') cycle
                  do n = 1, size(items, kind=ip)
                     i = items(n)
                     do c = 1, 4
                        if (var == 'S') then
                           call row(var, 'element', model%elem_id(i), var//elem_comp(c), s_elem(c, i))
                        else
                           call row(var, 'element', model%elem_id(i), var//elem_comp(c), e_elem(c, i))
                        end if
                     end do
                  end do
               end do
            case (output_contact)
               if (.not. present(tab)) cycle
               do j = 1, size(r%fields)
                  var = r%fields(j)%s
                  do n = 1, size(tab%node_id, kind=ip)
                     set = model%surfaces(model%pairs(tab%pair(n))%slave)%name
                     select case (var)
                     case ('COPEN')
                        call row(var, 'node', tab%node_id(n), var, tab%copen(n))
                     case ('CPRESS')
                        call row(var, 'node', tab%node_id(n), var, tab%cpress(n))
                        if (allocated(tab%cshear)) call row('CSHEAR', 'node', tab%node_id(n), 'CSHEAR', tab%cshear(n))
                        ! with *UPLIFT the water pressure in the joint, beside the effective CPRESS
                        if (allocated(tab%cfluidp)) &
                           call row('CFLUIDP', 'node', tab%node_id(n), 'CFLUIDP', tab%cfluidp(n))
                     case ('CSLIP')
                        call row(var, 'node', tab%node_id(n), var, tab%cslip(n))
                     end select
                  end do
               end do
            end select
         end associate
      end do
      ! a failed write is reported (file and reason) by the commit
      call out%commit(error)
   contains
      subroutine row(variable, entity, id, component, value)
         character(len=*), intent(in) :: variable, entity, component
         integer(ip), intent(in) :: id
         real(wp), intent(in) :: value
         character(len=24) :: idbuf, vbuf
         write (idbuf, '(i0)') id
         write (vbuf, '(es24.16e3)') value
         call out%write(variable//','//set//','//entity//','//trim(idbuf)//','//component//','//vbuf// &
                        new_line('a'))
      end subroutine row

      pure real(wp) function node_value(variable, comp, node)
         character(len=*), intent(in) :: variable
         integer, intent(in) :: comp
         integer(ip), intent(in) :: node
         if (variable == 'U') then
            node_value = u(comp, node)
         else
            node_value = rf(comp, node)
         end if
      end function node_value

      pure real(wp) function node_total(variable, comp, nodes)
         character(len=*), intent(in) :: variable
         integer, intent(in) :: comp
         integer(ip), intent(in) :: nodes(:)
         if (variable == 'U') then
            node_total = sum(u(comp, nodes))
         else
            node_total = sum(rf(comp, nodes))
         end if
      end function node_total
   end subroutine write_print_csv
end module vemcontact_output_print
