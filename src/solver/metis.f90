!> Interoperability with METIS 5 (idx_t = 32-bit): nested-dissection ordering
!> of a graph with METIS_NodeND, k-way partition with METIS_PartGraphKway.  The
!> graph is checked and copied to 0-based int32 arrays (c_graph); the caller's
!> arrays are never shifted.
module vemcontact_solver_metis
   use, intrinsic :: iso_c_binding, only: c_int, c_int32_t, c_ptr, c_null_ptr
   use, intrinsic :: ieee_exceptions, only: ieee_get_halting_mode, ieee_set_halting_mode, &
      ieee_set_flag, ieee_usual
   use vemcontact_kinds, only: ip, i8
   use vemcontact_error, only: error_t, fatal_error, err_internal, err_solver
   implicit none
   private

   public :: metis_nodend, metis_partition

   integer(c_int), parameter :: metis_noptions = 40   ! METIS_NOPTIONS in metis.h
   integer(c_int), parameter :: metis_ok = 1
   integer(c_int), parameter :: metis_error_input = -2
   integer(c_int), parameter :: metis_error_memory = -3

   interface
      integer(c_int) function metis_setdefaultoptions_c(options) bind(c, name='METIS_SetDefaultOptions')
         import :: c_int, c_int32_t
         integer(c_int32_t), intent(out) :: options(*)
      end function metis_setdefaultoptions_c

      integer(c_int) function metis_nodend_c(nvtxs, xadj, adjncy, vwgt, options, perm, iperm) &
         bind(c, name='METIS_NodeND')
         import :: c_int, c_int32_t, c_ptr
         integer(c_int32_t), intent(in) :: nvtxs
         integer(c_int32_t), intent(in) :: xadj(*), adjncy(*)
         type(c_ptr), value :: vwgt
         integer(c_int32_t), intent(in) :: options(*)
         integer(c_int32_t), intent(out) :: perm(*), iperm(*)
      end function metis_nodend_c

      integer(c_int) function metis_partgraphkway_c(nvtxs, ncon, xadj, adjncy, vwgt, vsize, adjwgt, nparts, &
                                                    tpwgts, ubvec, options, objval, part) &
         bind(c, name='METIS_PartGraphKway')
         import :: c_int, c_int32_t, c_ptr
         integer(c_int32_t), intent(in) :: nvtxs, ncon
         integer(c_int32_t), intent(in) :: xadj(*), adjncy(*)
         type(c_ptr), value :: vwgt, vsize, adjwgt
         integer(c_int32_t), intent(in) :: nparts
         type(c_ptr), value :: tpwgts, ubvec
         integer(c_int32_t), intent(in) :: options(*)
         integer(c_int32_t), intent(out) :: objval
         integer(c_int32_t), intent(out) :: part(*)
      end function metis_partgraphkway_c
   end interface

contains

   !> `part(i)` in 0..nparts-1, the part of vertex i of the graph (`n` vertices,
   !> 1-based CSR `xadj(n+1)`, `adjncy`, symmetric, no self loops) by METIS's k-way
   !> partitioning with its default options (deterministic: the same graph gives the
   !> same parts on every process).  One part, or a graph without edges: vertices
   !> in nparts consecutive blocks of equal size.
   subroutine metis_partition(n, xadj, adjncy, nparts, part, error)
      integer(ip), intent(in) :: n
      integer(i8), intent(in) :: xadj(:)
      integer(ip), intent(in) :: adjncy(:)
      integer, intent(in) :: nparts
      integer(ip), intent(out) :: part(:)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: what = 'METIS_PartGraphKway'
      integer(c_int32_t), allocatable :: xadj0(:), adj0(:), part0(:)
      integer(c_int32_t) :: options(metis_noptions), objval
      integer(ip) :: i
      integer(c_int) :: st
      logical :: halting(size(ieee_usual))

      if (size(part) /= n .or. nparts < 1) then
         call fatal_error(error, what//': part has the wrong length or no parts', err_internal)
         return
      end if
      call c_graph(n, xadj, adjncy, what, xadj0, adj0, error)
      if (allocated(error) .or. n == 0) return
      if (nparts == 1 .or. size(adj0) == 0 .or. n <= nparts) then
         part = [(int((int(i - 1, i8)*nparts)/n, ip), i=1, n)]
         return
      end if
      allocate (part0(n))
      ! as in metis_nodend: METIS's floating-point flags carry no meaning for us
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      st = metis_setdefaultoptions_c(options)
      if (st == metis_ok) st = metis_partgraphkway_c(int(n, c_int32_t), 1_c_int32_t, xadj0, adj0, c_null_ptr, &
                                                     c_null_ptr, c_null_ptr, int(nparts, c_int32_t), c_null_ptr, &
                                                     c_null_ptr, options, objval, part0)
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
      if (st == metis_ok) then
         part = int(part0, ip)
      else
         call status_error(st, what, error)
      end if
   end subroutine metis_partition

   !> Fill-reducing nested-dissection order of the graph with `n` vertices and
   !> 1-based CSR adjacency (`xadj(n+1)`, `adjncy`), which must be symmetric and
   !> free of self loops.  On return `perm(k)` is the vertex eliminated k-th.
   subroutine metis_nodend(n, xadj, adjncy, perm, error)
      integer(ip), intent(in) :: n
      integer(i8), intent(in) :: xadj(:)
      integer(ip), intent(in) :: adjncy(:)
      integer(ip), intent(out) :: perm(:)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: what = 'METIS_NodeND'
      integer(c_int32_t), allocatable :: xadj0(:), adj0(:), perm0(:), iperm0(:)
      integer(c_int32_t) :: options(metis_noptions)
      integer(ip) :: i
      integer(c_int) :: st
      logical :: halting(size(ieee_usual))

      if (size(perm) /= n) then
         call fatal_error(error, what//': perm has the wrong length', err_internal)
         return
      end if
      call c_graph(n, xadj, adjncy, what, xadj0, adj0, error)
      if (allocated(error) .or. n == 0) return
      if (size(adj0) == 0) then
         perm = [(i, i=1, n)]
         return
      end if
      allocate (perm0(n), iperm0(n))
      ! METIS computes balance ratios in floating point and may raise IEEE flags
      ! that the Debug build would trap on; they carry no meaning for us.
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      st = metis_setdefaultoptions_c(options)
      if (st == metis_ok) st = metis_nodend_c(int(n, c_int32_t), xadj0, adj0, c_null_ptr, options, perm0, iperm0)
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
      if (st == metis_ok) then
         perm = int(perm0, ip) + 1
      else
         call status_error(st, what, error)
      end if
   end subroutine metis_nodend

   !> The graph (`n` vertices, 1-based CSR `xadj(n+1)`, `adjncy`) checked (pointers
   !> non-decreasing, neighbours in range, no self loops, within 32-bit METIS) and
   !> copied 0-based for METIS; `what` names the caller in messages.
   subroutine c_graph(n, xadj, adjncy, what, xadj0, adj0, error)
      integer(ip), intent(in) :: n
      integer(i8), intent(in) :: xadj(:)
      integer(ip), intent(in) :: adjncy(:)
      character(len=*), intent(in) :: what
      integer(c_int32_t), allocatable, intent(out) :: xadj0(:), adj0(:)
      type(error_t), allocatable, intent(out) :: error
      integer(i8) :: nadj, p
      integer(ip) :: i
      character(len=24) :: buf
      if (size(xadj, kind=i8) /= int(n, i8) + 1) then
         call fatal_error(error, what//': xadj has the wrong length', err_internal)
         return
      end if
      if (n == 0) return
      nadj = xadj(n + 1) - 1
      if (xadj(1) /= 1 .or. nadj > huge(0_c_int32_t) .or. size(adjncy, kind=i8) < nadj) then
         call fatal_error(error, what//': adjacency pointers invalid or too many edges for 32-bit METIS', &
                          err_internal)
         return
      end if
      do i = 1, n
         if (xadj(i + 1) < xadj(i)) then
            write (buf, '(i0)') i
            call fatal_error(error, what//': xadj decreases at vertex '//trim(buf), err_internal)
            return
         end if
         do p = xadj(i), xadj(i + 1) - 1
            if (adjncy(p) < 1 .or. adjncy(p) > n .or. adjncy(p) == i) then
               write (buf, '(i0)') i
               call fatal_error(error, what//': neighbour out of range or self loop at vertex '//trim(buf), &
                                err_internal)
               return
            end if
         end do
      end do
      xadj0 = int(xadj - 1, c_int32_t)
      adj0 = int(adjncy(1:nadj) - 1, c_int32_t)
   end subroutine c_graph

   !> The error of METIS's status `st` (not METIS_OK) in the call `what`.
   subroutine status_error(st, what, error)
      integer(c_int), intent(in) :: st
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(out) :: error
      character(len=24) :: buf
      select case (st)
      case (metis_error_memory)
         call fatal_error(error, what//': out of memory', err_solver)
      case (metis_error_input)
         call fatal_error(error, what//': METIS rejected the graph', err_internal)
      case default
         write (buf, '(i0)') st
         call fatal_error(error, what//' failed with status '//trim(buf), err_solver)
      end select
   end subroutine status_error
end module vemcontact_solver_metis
