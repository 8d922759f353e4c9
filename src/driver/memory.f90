!> Memory estimate before assembly: the global matrix holds, at most, the dense
!> block of every element, (2n)^2 entries for an element of n nodes, each a
!> value and a row index (12 bytes), and the pattern is built from the same
!> blocks.  When that bound exceeds the machine's memory (MemTotal of
!> /proc/meminfo; no check where it cannot be read) the run stops with a clear
!> message instead of an allocation abort or the kernel's out-of-memory killer.
!> The bound counts the entries elements share twice, so it errs on the large
!> side; it is compared with the total memory, not the memory free at the
!> moment, so that a busy machine never refuses a run that fits.
module vemcontact_driver_memory
   use vemcontact_kinds, only: wp, i8
   use vemcontact_error, only: error_t, fatal_error, err_model
   use vemcontact_model, only: model_t
   use vemcontact_driver_validate, only: max_element_nodes
   implicit none
   private

   public :: check_memory, matrix_bytes_bound

contains

   !> Stop when the matrix bound exceeds the machine's memory.
   subroutine check_memory(model, error)
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      integer(i8) :: need, have
      character(len=32) :: a, b
      need = matrix_bytes_bound(model)
      have = total_memory()
      if (have <= 0 .or. need <= have) return
      write (a, '(f0.1)') real(need, wp)/1.0e9_wp
      write (b, '(f0.1)') real(have, wp)/1.0e9_wp
      call fatal_error(error, 'error: the model''s matrix may need up to '//trim(a)//' GB (the dense '// &
                       'blocks of its elements: (2 n)^2 entries for an element of n nodes), more than the '// &
                       trim(b)//' GB of memory of this machine: use elements with fewer nodes or a larger '// &
                       'machine', err_model)
   end subroutine check_memory

   !> Bytes of the dense element blocks of the model (elements beyond the node
   !> limit are left to validate_elements, which refuses them).
   pure integer(i8) function matrix_bytes_bound(model) result(bytes)
      type(model_t), intent(in) :: model
      integer :: e
      integer(i8) :: n
      bytes = 0
      do e = 1, model%nelem
         n = int(model%elem_ptr(e + 1) - model%elem_ptr(e), i8)
         if (n > max_element_nodes) cycle
         bytes = bytes + 12_i8*(2_i8*n)**2
      end do
   end function matrix_bytes_bound

   !> MemTotal of /proc/meminfo in bytes, 0 when it cannot be read.
   function total_memory() result(bytes)
      integer(i8) :: bytes
      character(len=256) :: line
      integer :: unit, ios
      integer(i8) :: kib
      bytes = 0
      open (newunit=unit, file='/proc/meminfo', status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:9) == 'MemTotal:') then
            read (line(10:), *, iostat=ios) kib
            if (ios == 0) bytes = 1024_i8*kib
            exit
         end if
      end do
      close (unit)
   end function total_memory
end module vemcontact_driver_memory
