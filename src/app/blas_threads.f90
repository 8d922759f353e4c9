!> The number of BLAS threads of the run (OpenBLAS, which CHOLMOD's supernodal
!> factorization calls).  OpenBLAS starts one thread per core; on a machine
!> whose cores are busy with other work its threads spend their time waking
!> and yielding, and two threads factorize more slowly than one
!> (docs/performance.md, "BLAS threads"), and on an unloaded one a second thread
!> gained 1 %.  The thread count changes the round-off of the factorization, so a
!> run that chose it from the machine's load would not repeat its own results to
!> the bit.  Unless the user chose (--blas-threads N, or OPENBLAS_NUM_THREADS /
!> GOTO_NUM_THREADS / OMP_NUM_THREADS in the environment) the run therefore uses
!> one thread; `--blas-threads auto` uses the cores that are idle when it starts:
!> the cores online minus the one-minute load average, rounded, at least 1.
module vemcontact_app_blas_threads
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: auto_blas_threads, set_blas_threads

   interface
      function c_cores_online() result(n) bind(C, name='vc_cores_online')
         import :: c_int
         integer(c_int) :: n
      end function c_cores_online
      function c_load_average() result(l) bind(C, name='vc_load_average')
         import :: c_double
         real(c_double) :: l
      end function c_load_average
      function c_set_blas_threads(n) result(nset) bind(C, name='vc_set_blas_threads')
         import :: c_int
         integer(c_int), value :: n
         integer(c_int) :: nset
      end function c_set_blas_threads
   end interface

contains

   !> Threads for `cores` cores of which `load` (one-minute load average) are
   !> busy: the idle ones, rounded, at least 1 (all of them when the load is unknown, < 0).
   pure integer function auto_blas_threads(cores, load) result(n)
      integer, intent(in) :: cores
      real(wp), intent(in) :: load
      if (load < 0.0_wp) then
         n = max(1, cores)
      else
         n = max(1, min(cores, nint(real(cores, wp) - load)))
      end if
   end function auto_blas_threads

   !> Set the BLAS threads: `requested` (> 0), auto_blas_threads (`requested` < 0,
   !> --blas-threads auto), else the environment's choice is kept, else one.  `note`: one line for the log saying what was chosen and why.
   subroutine set_blas_threads(requested, note)
      integer, intent(in) :: requested
      character(len=:), allocatable, intent(out) :: note
      character(len=*), parameter :: vars(3) = [character(len=20) :: 'OPENBLAS_NUM_THREADS', &
                                                'GOTO_NUM_THREADS', 'OMP_NUM_THREADS']
      character(len=64) :: buf
      integer :: k, length, n, cores
      real(wp) :: load
      if (requested == 0) then
         do k = 1, size(vars)
            call get_environment_variable(trim(vars(k)), length=length)
            if (length > 0) then
               call get_environment_variable(trim(vars(k)), buf)
               note = 'BLAS threads: as '//trim(vars(k))//'='//trim(buf)//' says'
               return
            end if
         end do
      end if
      cores = int(c_cores_online())
      load = real(c_load_average(), wp)
      if (requested > 0) then
         n = requested
         write (buf, '(a,i0,a)') 'BLAS threads ', n, ' (--blas-threads)'
      else if (requested < 0) then
         n = auto_blas_threads(cores, load)
         write (buf, '(a,i0,a,i0,a,f0.2,a)') 'BLAS threads ', n, ' (auto: ', cores, ' cores, load average ', &
            load, ')'
      else
         n = 1
         buf = 'BLAS threads 1 (the default: --blas-threads N or auto for more)'
      end if
      note = trim(buf)
      if (c_set_blas_threads(int(n, c_int)) == 0) note = note//'; not set: the BLAS is not OpenBLAS'
   end subroutine set_blas_threads
end module vemcontact_app_blas_threads
