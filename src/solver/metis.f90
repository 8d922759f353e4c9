!> Interoperability with METIS 5 (idx_t = 32-bit): nested-dissection ordering
!> of a graph with METIS_NodeND, k-way partition with METIS_PartGraphKway.  The graph is copied to 0-based int32 arrays;
!> the caller's arrays are never shifted.
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
      integer(c_int32_t), allocatable :: xadj0(:), adj0(:), part0(:)
      integer(c_int32_t) :: options(metis_noptions), nv, objval
      integer(i8) :: nadj
      integer(ip) :: i
      integer(c_int) :: st
      logical :: halting(size(ieee_usual))
      character(len=24) :: buf

      if (size(xadj, kind=i8) /= int(n, i8) + 1 .or. size(part) /= n .or. nparts < 1) then
         call fatal_error(error, 'METIS_PartGraphKway: xadj or part has the wrong length', err_internal)
         return
      end if
      if (n == 0) return
      nadj = xadj(n + 1) - 1
      if (xadj(1) /= 1 .or. nadj > huge(0_c_int32_t) .or. size(adjncy, kind=i8) < nadj) then
         call fatal_error(error, 'METIS_PartGraphKway: adjacency pointers invalid or too many edges '// &
            'for 32-bit METIS', err_internal)
         return
      end if
      if (nparts == 1 .or. nadj == 0 .or. n <= nparts) then
         part = [(int((int(i - 1, i8)*nparts)/n, ip), i=1, n)]
         return
      end if
      allocate (xadj0(n + 1), adj0(nadj), part0(n))
      xadj0 = int(xadj - 1, c_int32_t)
      adj0 = int(adjncy(1:nadj) - 1, c_int32_t)
      nv = int(n, c_int32_t)
      ! as in metis_nodend: METIS's floating-point flags carry no meaning for us
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      st = metis_setdefaultoptions_c(options)
      if (st == metis_ok) st = metis_partgraphkway_c(nv, 1_c_int32_t, xadj0, adj0, c_null_ptr, c_null_ptr, &
                                                     c_null_ptr, int(nparts, c_int32_t), c_null_ptr, c_null_ptr, &
                                                     options, objval, part0)
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
      select case (st)
      case (metis_ok)
         part = int(part0, ip)
      case (metis_error_memory)
         call fatal_error(error, 'METIS_PartGraphKway: out of memory', err_solver)
      case (metis_error_input)
         call fatal_error(error, 'METIS_PartGraphKway: METIS rejected the graph', err_internal)
      case default
         write (buf, '(i0)') st
         call fatal_error(error, 'METIS_PartGraphKway failed with status '//trim(buf), err_solver)
      end select
   end subroutine metis_partition

   !> Fill-reducing nested-dissection order of the graph with `n` vertices and
   !> 1-based CSR adjacency (`xadj(n+1)`, `adjncy`), which must be symmetric and
   !> free of self loops.  On return `perm(k)` is the vertex eliminated k-th.
   !> With no edges at all the natural order is returned without calling METIS.
   subroutine metis_nodend(n, xadj, adjncy, perm, error)
      integer(ip), intent(in) :: n
      integer(i8), intent(in) :: xadj(:)
      integer(ip), intent(in) :: adjncy(:)
      integer(ip), intent(out) :: perm(:)
      type(error_t), allocatable, intent(out) :: error
      integer(c_int32_t), allocatable :: xadj0(:), adj0(:), perm0(:), iperm0(:)
      integer(c_int32_t) :: options(metis_noptions), nv
      integer(i8) :: nadj, p
      integer(ip) :: i
      integer(c_int) :: st
      logical :: halting(size(ieee_usual))
      character(len=24) :: buf

      if (size(xadj, kind=i8) /= int(n, i8) + 1 .or. size(perm) /= n) then
         call fatal_error(error, 'METIS_NodeND: xadj or perm has the wrong length', err_internal)
         return
      end if
      if (n == 0) return
      nadj = xadj(n + 1) - 1
      if (xadj(1) /= 1 .or. nadj > huge(0_c_int32_t) .or. size(adjncy, kind=i8) < nadj) then
         call fatal_error(error, 'METIS_NodeND: adjacency pointers invalid or too many edges '// &
            'for 32-bit METIS', err_internal)
         return
      end if
      do i = 1, n
         if (xadj(i + 1) < xadj(i)) then
            write (buf, '(i0)') i
            call fatal_error(error, 'METIS_NodeND: xadj decreases at vertex '//trim(buf), err_internal)
            return
         end if
      end do
      do i = 1, n
         do p = xadj(i), xadj(i + 1) - 1
            if (adjncy(p) < 1 .or. adjncy(p) > n .or. adjncy(p) == i) then
               write (buf, '(i0)') i
               call fatal_error(error, 'METIS_NodeND: neighbour out of range or self loop at vertex '// &
                  trim(buf), err_internal)
               return
            end if
         end do
      end do
      if (nadj == 0) then
         perm = [(i, i=1, n)]
         return
      end if

      allocate (xadj0(n + 1), adj0(nadj), perm0(n), iperm0(n))
      xadj0 = int(xadj - 1, c_int32_t)
      adj0 = int(adjncy(1:nadj) - 1, c_int32_t)
      nv = int(n, c_int32_t)

      ! METIS computes balance ratios in floating point and may raise IEEE flags
      ! that the Debug build would trap on; they carry no meaning for us.
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      st = metis_setdefaultoptions_c(options)
      if (st == metis_ok) st = metis_nodend_c(nv, xadj0, adj0, c_null_ptr, options, perm0, iperm0)
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)

      select case (st)
      case (metis_ok)
         perm = int(perm0, ip) + 1
      case (metis_error_memory)
         call fatal_error(error, 'METIS_NodeND: out of memory', err_solver)
      case (metis_error_input)
         call fatal_error(error, 'METIS_NodeND: METIS rejected the graph', err_internal)
      case default
         write (buf, '(i0)') st
         call fatal_error(error, 'METIS_NodeND failed with status '//trim(buf), err_solver)
      end select
   end subroutine metis_nodend
end module vemcontact_solver_metis
