!> Whether the run is to stop now (SIGINT or SIGTERM received: vemcontact_interrupt),
!> agreed by every process of a distributed run: the signal may reach one process
!> only (`kill` of one pid) or the processes at different moments, yet all of them
!> must leave the analysis at the same safe point, or the others would wait for
!> ever in the next collective operation.  One process: a look at a flag.
module vemcontact_solver_stop
   use vemcontact_kinds, only: wp
   use vemcontact_interrupt, only: stop_signal, sigint_number, sigterm_number
   use vemcontact_solver_petsc, only: petsc_sum
   implicit none
   private

   public :: agreed_stop_signal

contains

   !> The signal that stops the run (0: go on), the same decision on every process:
   !> this process's own signal, else the one another process received.  Must be
   !> called by every process at the same point (an MPI_Allreduce when distributed).
   integer function agreed_stop_signal() result(signo)
      real(wp) :: x(2)
      logical :: ok
      signo = stop_signal()
      x = [merge(1.0_wp, 0.0_wp, signo == sigint_number()), merge(1.0_wp, 0.0_wp, signo == sigterm_number())]
      call petsc_sum(x, ok)
      if (.not. ok .or. signo > 0) return
      if (x(2) > 0.0_wp) then
         signo = sigterm_number()
      else if (x(1) > 0.0_wp) then
         signo = sigint_number()
      end if
   end function agreed_stop_signal
end module vemcontact_solver_stop
