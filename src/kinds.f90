!> Numeric kinds used everywhere in vemcontact.
!> `wp` is the working real precision (IEEE double), `ip` the integer kind of
!> node, element and degree-of-freedom indices, `i8` the kind of counts that can
!> exceed 2**31 (non-zeros of the global matrix, CHOLMOD's SuiteSparse_long).
module vemcontact_kinds
   use, intrinsic :: iso_fortran_env, only: real64, int32, int64
   implicit none
   private

   !> Working precision for all reals.
   integer, parameter, public :: wp = real64
   !> Integer kind for node, element and dof indices.
   integer, parameter, public :: ip = int32
   !> Integer kind for non-zero counts and offsets into sparse arrays.
   integer, parameter, public :: i8 = int64
end module vemcontact_kinds
