!> The increments of the run as CalculiX's JOB.sta ("SUMMARY OF JOB INFORMATION"):
!> one line per converged increment with its step, its number in the step, the
!> attempt that converged (1 + the cut-backs before it), its iterations, and the
!> total time, step time and size at its end, in CalculiX's columns.  A run that
!> stops keeps the lines of the increments it completed, so the file shows where it
!> stopped.  ITRS is the contact iterations of the increment (1 for an increment
!> without contact, as CalculiX's linear increments).
module vemcontact_output_sta
   use vemcontact_kinds, only: wp
   use vemcontact_error, only: error_t
   use vemcontact_safe_file, only: safe_file_t
   implicit none
   private

   public :: sta_list_t

   !> One line of the file.
   type :: sta_line_t
      integer :: step = 0, increment = 0, attempt = 1, iterations = 1
      real(wp) :: total_time = 0.0_wp, step_time = 0.0_wp, increment_time = 0.0_wp
   end type sta_line_t

   !> The lines so far (capacity doubled as they come: O(1) per increment).
   type, public :: sta_list_t
      type(sta_line_t), allocatable :: lines(:)
      integer :: n = 0
   contains
      procedure :: add
      procedure :: write => write_sta
      procedure :: of_step
   end type sta_list_t

contains

   !> Record a converged increment.
   pure subroutine add(self, step, increment, attempt, iterations, total_time, step_time, increment_time)
      class(sta_list_t), intent(inout) :: self
      integer, intent(in) :: step, increment, attempt, iterations
      real(wp), intent(in) :: total_time, step_time, increment_time
      type(sta_line_t), allocatable :: t(:)
      if (.not. allocated(self%lines)) allocate (self%lines(16))
      if (self%n == size(self%lines)) then
         allocate (t(2*self%n))
         t(:self%n) = self%lines(:self%n)
         call move_alloc(t, self%lines)
      end if
      self%n = self%n + 1
      self%lines(self%n) = sta_line_t(step, increment, attempt, max(1, iterations), total_time, step_time, &
                                      increment_time)
   end subroutine add

   !> The lines of step `step`: their step times, increment sizes, attempts and iterations.
   pure subroutine of_step(self, step, step_time, increment_time, attempt, iterations)
      class(sta_list_t), intent(in) :: self
      integer, intent(in) :: step
      real(wp), allocatable, intent(out) :: step_time(:), increment_time(:)
      integer, allocatable, intent(out) :: attempt(:), iterations(:)
      integer :: k, m
      m = 0
      do k = 1, self%n
         if (self%lines(k)%step == step) m = m + 1
      end do
      allocate (step_time(m), increment_time(m), attempt(m), iterations(m))
      m = 0
      do k = 1, self%n
         if (self%lines(k)%step /= step) cycle
         m = m + 1
         step_time(m) = self%lines(k)%step_time
         increment_time(m) = self%lines(k)%increment_time
         attempt(m) = self%lines(k)%attempt
         iterations(m) = self%lines(k)%iterations
      end do
   end subroutine of_step

   !> The whole file at `path`, CalculiX's header and columns.
   subroutine write_sta(self, path, error)
      class(sta_list_t), intent(in) :: self
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: error
      type(safe_file_t) :: out
      character(len=120) :: line
      integer :: k
      call out%open(path, error)
      if (allocated(error)) return
      call out%write('SUMMARY OF JOB INFORMATION'//new_line('a'))
      call out%write('  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME'//new_line('a'))
      do k = 1, self%n
         associate (l => self%lines(k))
            write (line, '(i6,i11,i6,i6,3e14.6)') l%step, l%increment, l%attempt, l%iterations, &
               l%total_time, l%step_time, l%increment_time
         end associate
         call out%write(trim(line)//new_line('a'))
      end do
      ! a failed write is reported (file and reason) by the commit
      call out%commit(error)
   end subroutine write_sta
end module vemcontact_output_sta
