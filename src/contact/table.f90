!> The contact results of one step: one row per slave entry of every pair, as
!> the contact state reports them (contact_state_t%table) and the writers of
!> src/output put them on disk (CSV, VTU, HDF5; docs/output-format.md).
module vemcontact_contact_table
   use vemcontact_kinds, only: wp, ip
   implicit none
   private

   public :: contact_table_t

   !> The slave nodes of one or more pairs and their results.
   type :: contact_table_t
      integer(ip), allocatable :: node_id(:)
      real(wp), allocatable :: x(:, :)        !< (2, n) undeformed coordinates
      real(wp), allocatable :: copen(:)
      real(wp), allocatable :: cpress(:)
      real(wp), allocatable :: cslip(:)
      !> the shear traction on the slave node along the master's unit tangent t = (-n_y, n_x)
      !> (the direction of its segments), the tangential force the solution balances per
      !> CNAREA; 0 for frictionless pairs
      real(wp), allocatable :: cshear(:)
      !> CNAREA (Abaqus' name): the slave node's undeformed tributary length times the
      !> thickness, the area CPRESS acts on (sum CPRESS * CNAREA = transmitted force)
      real(wp), allocatable :: cnarea(:)
      !> CFLUIDP: the water pressure in the joint (*UPLIFT), acting on both faces
      !> beside the effective contact pressure CPRESS; unallocated without uplift
      real(wp), allocatable :: cfluidp(:)
      !> 0 open, 1 closed (frictionless), 2 slid past the end of the master, 3 stick, 4 slip
      integer, allocatable :: status(:)
      integer, allocatable :: pair(:)
      integer(ip), allocatable :: node(:)     !< internal node index (for the driver)
   end type contact_table_t
end module vemcontact_contact_table
