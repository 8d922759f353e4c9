!> Checks of the contact pairs before any contact state is built, against decks that
!> make the contact meaningless:
!>
!> - a slave face on an element of its own master face (`1, S1` written for `2, S1`):
!>   the body's own thickness would be taken for an overclosure and squeezed out;
!> - an initial overclosure larger than `max_overclosure` times the length of the
!>   master side a slave node projects onto.  No physical contact starts so: two
!>   meshes of one curved interface overlap by at most the sagitta of a side,
!>   h^2 / (8 R) for sides of length h on a radius R, which is below a quarter of h
!>   for any curve meshed with sides shorter than twice its radius; a shrink fit
!>   interferes by a small fraction of the element size.  A larger overclosure is a
!>   slave face on the wrong body, or behind the master face.
!>
!> Each problem names the *CONTACT PAIR line, and for the overclosure the slave node,
!> the master side's nodes (user ids) and the value.
module vemcontact_driver_contact_checks
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, append_message, err_input
   use vemcontact_model, only: model_t, location_string
   use vemcontact_contact_surfaces, only: master_segments, slave_nodes, slave_edges
   use vemcontact_contact_search, only: segment_grid_t, build_segment_grid, closest_segments
   use vemcontact_contact_geometry, only: length2
   implicit none
   private

   public :: check_contact_pairs

   !> Largest initial overclosure accepted, relative to the master side's length
   !> (see the module's comment).
   real(wp), parameter, public :: max_overclosure = 0.25_wp

contains

   !> Refuse pairs whose slave and master share an element and pairs that start with
   !> an overclosure beyond max_overclosure (all problems reported at once).
   subroutine check_contact_pairs(model, error)
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: error
      integer :: p
      if (.not. allocated(model%pairs)) return
      do p = 1, size(model%pairs)
         call check_pair(model, p, error)
      end do
   end subroutine check_contact_pairs

   subroutine check_pair(model, p, error)
      type(model_t), intent(in) :: model
      integer, intent(in) :: p
      type(error_t), allocatable, intent(inout) :: error
      type(error_t), allocatable :: err
      integer(ip), allocatable :: seg(:, :), seg_elem(:), edge(:, :), edge_elem(:), node(:), iseg(:)
      integer, allocatable :: seg_side(:), edge_side(:)
      real(wp), allocatable :: length(:), thick(:), xi(:), gap(:), normal(:, :)
      real(wp) :: radius, h, worst
      type(segment_grid_t) :: grid
      integer(ip) :: nex
      integer :: i, j, k, iworst
      character(len=:), allocatable :: where, names
      character(len=200) :: buf
      where = location_string(model, model%pairs(p)%loc)
      names = model%surfaces(model%pairs(p)%slave)%name//' on '//model%surfaces(model%pairs(p)%master)%name
      call master_segments(model, model%pairs(p), seg, seg_elem, seg_side, err)
      if (allocated(err)) return
      call slave_edges(model, model%pairs(p), edge, edge_elem, edge_side, err)
      if (allocated(err)) return
      ! a slave side on an element that has a master side
      do i = 1, size(edge_elem)
         do j = 1, size(seg_elem)
            if (edge_elem(i) /= seg_elem(j)) cycle
            write (buf, '(a,i0,a,i0,a,i0,a)') 'element ', model%elem_id(seg_elem(j)), ' has both a slave side (S', &
               edge_side(i), ') and a master side (S', seg_side(j), ')'
            call append_message(error, where//': error: contact pair '//names//': '//trim(buf)// &
                                ': a body cannot be in contact with itself across an element'// &
                                new_line('a')//'   = help: the slave and the master are faces of two '// &
                                'bodies (or of the two sides of a joint); check the element ids of the *SURFACE '// &
                                'data lines', err_input)
            return
         end do
      end do
      ! the overclosure at the undeformed state
      call slave_nodes(model, model%pairs(p), node, length, thick, nex, err)
      if (allocated(err) .or. size(node) == 0 .or. size(seg, 2) == 0) return
      radius = 0.0_wp
      do k = 1, size(seg, 2)
         radius = max(radius, 2.0_wp*length2(model%x(:, seg(2, k)) - model%x(:, seg(1, k))))
      end do
      call build_segment_grid(model%x, seg, radius, grid, err)
      if (allocated(err)) return
      allocate (iseg(size(node)), xi(size(node)), gap(size(node)), normal(2, size(node)))
      call closest_segments(grid, model%x, seg, node, radius, iseg, xi, gap, normal)
      ! the node with the largest overclosure relative to its master side's length
      worst = max_overclosure
      iworst = 0
      do i = 1, size(node)
         if (iseg(i) < 1 .or. .not. (gap(i) < 0.0_wp)) cycle
         h = length2(model%x(:, seg(2, iseg(i))) - model%x(:, seg(1, iseg(i))))
         if (-gap(i) > worst*h) then
            worst = -gap(i)/h
            iworst = i
         end if
      end do
      if (iworst == 0) return
      i = iworst
      write (buf, '(a,i0,a,es10.3,a,i0,a,i0,a,f0.2,a)') 'slave node ', model%node_id(node(i)), &
         ' starts with an overclosure of ', -gap(i), ' behind the master side from node ', &
         model%node_id(seg(1, iseg(i))), ' to node ', model%node_id(seg(2, iseg(i))), ' (', worst, &
         ' times its length)'
      call append_message(error, where//': error: contact pair '//names//': '//trim(buf)// &
                          new_line('a')//'   = help: no contact starts that deep (at most a quarter of the '// &
                          'side: the sagitta of a meshed curve); is the slave face on the wrong body, or '// &
                          'the master face behind it?', err_input)
   end subroutine check_pair
end module vemcontact_driver_contact_checks
