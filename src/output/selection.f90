!> Which result fields a step's files carry: the deck's output requests (*NODE FILE,
!> *EL FILE, *CONTACT FILE and the Abaqus forms) read through `output_requested`.
!> Without any request every field is written; the mesh and the labels (ids, material,
!> element set, part; the contact points' ids, coordinates, CNAREA, STATUS and PAIR)
!> are always written (docs/output-format.md, "Output requests").
module vemcontact_output_selection
   use vemcontact_model, only: model_t, output_requested
   implicit none
   private

   public :: step_selection

   !> The fields of one step: true = written.  The defaults (all true) are the
   !> selection of a deck without output requests.
   type, public :: field_selection_t
      logical :: u = .true.       !< U (point data; HDF5 U)
      logical :: rf = .true.      !< RF (point data; HDF5 RF, RF_total, RF_sets)
      logical :: s = .true.       !< S and its S1, S3, MISES (HDF5 S_element, S_node)
      logical :: e = .true.       !< E (HDF5 E_element, E_node)
      logical :: cpress = .true.  !< contact pressure
      logical :: copen = .true.   !< contact opening
      logical :: cslip = .true.   !< contact slip
   contains
      procedure :: contact => selection_contact
   end type field_selection_t

contains

   !> The selection of step `istep` of `model`.
   pure function step_selection(model, istep) result(sel)
      type(model_t), intent(in) :: model
      integer, intent(in) :: istep
      type(field_selection_t) :: sel
      sel%u = output_requested(model, istep, 'U')
      sel%rf = output_requested(model, istep, 'RF')
      sel%s = output_requested(model, istep, 'S')
      sel%e = output_requested(model, istep, 'E')
      sel%cpress = output_requested(model, istep, 'CPRESS')
      sel%copen = output_requested(model, istep, 'COPEN')
      sel%cslip = output_requested(model, istep, 'CSLIP')
   end function step_selection

   !> Some contact field is selected: the contact point set (VTU, CSV, HDF5 pair
   !> groups) is written.
   pure logical function selection_contact(self)
      class(field_selection_t), intent(in) :: self
      selection_contact = self%cpress .or. self%copen .or. self%cslip
   end function selection_contact
end module vemcontact_output_selection
