!> Labels of the elements for the results: the element set of each element's
!> *SOLID SECTION and the part (connected body) it belongs to.
module vemcontact_post_labels
   use vemcontact_kinds, only: ip
   use vemcontact_model, only: model_t, find_set
   implicit none
   private

   public :: element_section_sets, element_parts

contains

   !> For every element, the index into model%elsets of the element set of the
   !> *SOLID SECTION that gives it its material (0 for none).  An element may be
   !> in many sets; this is the one that defines it, as the section is in the deck.
   pure function element_section_sets(model) result(eset)
      type(model_t), intent(in) :: model
      integer(ip), allocatable :: eset(:)
      integer :: s, k
      allocate (eset(model%nelem), source=0_ip)
      if (.not. (allocated(model%sections) .and. allocated(model%elsets))) return
      do s = 1, size(model%sections)
         if (.not. allocated(model%sections(s)%elset)) cycle
         k = find_set(model%elsets, model%sections(s)%elset)
         if (k > 0) eset(model%elsets(k)%items) = int(k, ip)
      end do
   end function element_section_sets

   !> Part of every element, from the part of each node (0 for nodes in no element):
   !> the nodes of an element are all in one part, its first node's.
   pure function element_parts(model, node_part) result(epart)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: node_part(:)
      integer(ip), allocatable :: epart(:)
      integer(ip) :: e
      allocate (epart(model%nelem))
      do e = 1, model%nelem
         epart(e) = node_part(model%elem_conn(model%elem_ptr(e)))
      end do
   end function element_parts
end module vemcontact_post_labels
