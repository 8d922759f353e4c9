!> Stress post-processing: nodal averaging of element stresses, principal
!> stresses and the von Mises equivalent stress.  Stress vectors are
!> `(xx, yy, zz, xy)`, tension positive.
module vemcontact_post_stress
   use vemcontact_kinds, only: wp, ip
   use vemcontact_model, only: model_t
   implicit none
   private

   public :: nodal_average, principal_stresses

contains

   !> Nodal stresses as the unweighted mean of the stresses of the elements
   !> that contain the node; a node in no element gets 0.
   !>
   !> Unweighted, as CalculiX averages its extrapolated element values: each
   !> element's (constant, projected) stress is an estimate of equal standing for
   !> the stress at its vertices.  Area weighting would let a large element,
   !> whose centroid is far from the node and whose constant stress is therefore
   !> the poorer estimate there, dominate its small neighbours; on graded VEM
   !> meshes (agglomerated polygons next to fine cells) that is the wrong way round.
   !> The average is per node, so nodes that are not shared between bodies never
   !> mix the bodies' stresses.
   !>
   !> `s_at` (optional, (4, size of elem_conn)): each element's own stress at
   !> each of its nodes (connectivity order), averaged instead of the element
   !> value: the stress of a second-order element varies over it (linear for
   !> the k = 2 virtual element), and its nodal values are better estimates at
   !> the nodes than its mean.
   subroutine nodal_average(model, s_elem, s_node, s_at)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: s_elem(:, :)    !< (4, nelem)
      real(wp), intent(out) :: s_node(:, :)   !< (4, nnode)
      real(wp), intent(in), optional :: s_at(:, :)
      integer(ip), allocatable :: count(:)
      integer(ip) :: e, k, n
      allocate (count(model%nnode), source=0_ip)
      s_node = 0.0_wp
      do e = 1, model%nelem
         do k = model%elem_ptr(e), model%elem_ptr(e + 1) - 1
            n = model%elem_conn(k)
            if (present(s_at)) then
               s_node(:, n) = s_node(:, n) + s_at(:, k)
            else
               s_node(:, n) = s_node(:, n) + s_elem(:, e)
            end if
            count(n) = count(n) + 1_ip
         end do
      end do
      do n = 1, model%nnode
         if (count(n) > 0) s_node(:, n) = s_node(:, n)/real(count(n), wp)
      end do
   end subroutine nodal_average

   !> In-plane principal stresses `s1 >= s3` of `(xx, yy, xy)` and the von Mises
   !> stress of the full state including `zz` (non-zero in plane strain).
   !> `s1`/`s3` deliberately leave out `zz`: they are the extreme normal stresses
   !> in the model plane, the quantity contact and crack checks look at; `zz` is
   !> available on its own in the stress vector.
   pure subroutine principal_stresses(s, s1, s3, mises)
      real(wp), intent(in) :: s(4)
      real(wp), intent(out) :: s1, s3, mises
      real(wp) :: centre, radius, dxy, dyz, dzx, m
      centre = 0.5_wp*(s(1) + s(2))
      ! hypot avoids overflow/underflow of the squares for extreme magnitudes
      radius = hypot(0.5_wp*(s(1) - s(2)), s(4))
      s1 = centre + radius
      s3 = centre - radius
      ! differences scaled by their largest magnitude, so that the squares neither
      ! overflow (stresses beyond 1e154) nor underflow (below 1e-154)
      m = max(abs(s(1) - s(2)), abs(s(2) - s(3)), abs(s(3) - s(1)), abs(s(4)))
      if (.not. (m > 0.0_wp)) then
         mises = m
         return
      end if
      dxy = (s(1) - s(2))/m
      dyz = (s(2) - s(3))/m
      dzx = (s(3) - s(1))/m
      mises = m*sqrt(0.5_wp*(dxy*dxy + dyz*dyz + dzx*dzx) + 3.0_wp*(s(4)/m)**2)
   end subroutine principal_stresses
end module vemcontact_post_stress
