!> *TIE: the constraints that bond a slave surface to a master surface.  Where the
!> interface nodes were inserted into both faces (virtual elements:
!> vemcontact_contact_insertion, insert_tie_nodes), each slave node has a master
!> node at the same point and its two dofs are tied to it, u_s - u_m = 0: the two
!> traces, interpolated on the same nodes, are one field, so a tied patch of any
!> two meshes passes the patch test.  Where one face is of FEM elements, its
!> corners were inserted into the other (insert_fem_corners) and the virtual face's
!> nodes are tied to the FEM face by closest points, the faces' roles swapped when
!> the deck names the virtual face the master (tie_t%reverse: the slave face's
!> sides as a contact pair's, slave_edges; a held node of the virtual face then
!> holds the FEM node it lies on instead): every FEM node is a
!> node of the virtual face, whose trace becomes the FEM face's.  Other slave nodes
!> (every node of a tie of two FEM faces, and slave nodes that found no partner) are
!> tied as CalculiX ties them: projected onto the closest side of the master face
!> (the straight side, or the quadratic curve through a second-order side's three
!> nodes), each dof tied to the face there, u_s - sum_j N_j(xi) u_j = 0, N_j the
!> side's shape functions; a master node between two slave nodes is then not held, and the
!> traces coincide only where every master node is also a slave node.  The
!> constraints join the *EQUATION ones (vemcontact_driver_equations eliminates
!> them), so a tie costs no penalty and keeps the system positive definite.
!> Skipped: slave nodes that are nodes of the master face, and slave dofs that a
!> *BOUNDARY prescribes or an *EQUATION makes dependent (CalculiX drops those
!> ties too).  A slave node farther from its master point than the position
!> tolerance (default 5 % of the mean master side) is an error.
module vemcontact_driver_tie
   use vemcontact_kinds, only: wp, ip
   use vemcontact_error, only: error_t, fatal_error, append_message, err_input
   use vemcontact_model, only: model_t, equation_t, dof_value_t, source_loc_t, surface_node, location_string, &
                               element_side
   use vemcontact_contact_insertion, only: snap_rel
   use vemcontact_contact_surfaces, only: slave_edges
   use vemcontact_model, only: contact_pair_t
   implicit none
   private

   public :: tie_equations

   integer, parameter :: max_listed = 20

contains

   !> The equations of every tie of the model (none without ties).
   subroutine tie_equations(model, eqs, error)
      type(model_t), intent(in) :: model
      type(equation_t), allocatable, intent(out) :: eqs(:)
      type(error_t), allocatable, intent(out) :: error
      logical, allocatable :: taken(:)
      integer :: t, neq
      allocate (eqs(0))
      if (.not. allocated(model%ties)) return
      allocate (taken(2*model%nnode), source=.false.)
      call mark_boundary(model%initial%boundary, taken)
      if (allocated(model%steps)) then
         do t = 1, size(model%steps)
            call mark_boundary(model%steps(t)%boundary, taken)
         end do
      end if
      if (allocated(model%equations)) then
         do t = 1, size(model%equations)
            taken(2*model%equations(t)%node(1) - 2 + model%equations(t)%dof(1)) = .true.
         end do
      end if
      neq = 0
      do t = 1, size(model%ties)
         call tie_one(model, t, taken, eqs, neq, error)
         if (allocated(error)) return
      end do
      eqs = eqs(1:neq)
   end subroutine tie_equations

   pure subroutine mark_boundary(b, taken)
      type(dof_value_t), allocatable, intent(in) :: b(:)
      logical, intent(inout) :: taken(:)
      integer :: k
      if (.not. allocated(b)) return
      do k = 1, size(b)
         if (b(k)%dof <= 2) taken(2*b(k)%node - 2 + b(k)%dof) = .true.
      end do
   end subroutine mark_boundary

   !> The equations of tie t appended to eqs(1:neq).
   subroutine tie_one(model, t, taken, eqs, neq, error)
      type(model_t), intent(in) :: model
      integer, intent(in) :: t
      logical, intent(inout) :: taken(:)
      type(equation_t), allocatable, intent(inout) :: eqs(:)
      integer, intent(inout) :: neq
      type(error_t), allocatable, intent(out) :: error
      integer(ip), allocatable :: faces(:, :), slaves(:)
      logical, allocatable :: on_master(:)
      real(wp) :: tol, dist, best, xi, bxi, w(3)
      integer :: k, f, bf, nf, d, nbad, m, j
      integer(ip) :: s
      character(len=24) :: b1, b2, b3
      character(len=:), allocatable :: which, other
      ! reverse: the master face (virtual elements, which took the FEM slave face's
      ! nodes) is tied to the slave face
      if (model%ties(t)%reverse) then
         call slave_faces(model, t, faces, error)
         if (allocated(error)) return
         slaves = slave_nodes(model, model%ties(t)%master)
         which = 'master face node '
         other = ' from the slave surface'
      else
         call master_faces(model, model%ties(t)%master, faces)
         slaves = slave_nodes(model, model%ties(t)%slave)
         which = 'slave node '
         other = ' from the master surface'
      end if
      nf = size(faces, 2)
      allocate (on_master(model%nnode), source=.false.)
      do f = 1, nf
         do j = 1, 3
            if (faces(j, f) > 0) on_master(faces(j, f)) = .true.
         end do
      end do
      tol = model%ties(t)%tolerance
      if (tol < 0.0_wp) then
         tol = 0.0_wp
         do f = 1, nf
            tol = tol + norm2(model%x(:, faces(2, f)) - model%x(:, faces(1, f)))
         end do
         tol = 0.05_wp*tol/max(nf, 1)
      end if
      nbad = 0
      ! node to node: the partners of the insertion, whose faces are the same curve
      if (allocated(model%ties(t)%partner)) then
         do k = 1, size(model%ties(t)%partner, 2)
            s = model%ties(t)%partner(1, k)
            if (on_master(s)) cycle
            on_master(s) = .true.   ! tied here: not again by its closest point
            call check_distance(norm2(model%x(:, s) - model%x(:, model%ties(t)%partner(2, k))))
            do d = 1, 2
               if (taken(2*s - 2 + d)) cycle
               taken(2*s - 2 + d) = .true.
               call push(eqs, neq, s, d, model%ties(t)%partner(2:2, k), [1.0_wp], model%ties(t)%loc)
            end do
         end do
      end if
      do k = 1, size(slaves)
         s = slaves(k)
         if (on_master(s)) cycle
         best = huge(1.0_wp)
         bf = 0
         bxi = 0.0_wp
         do f = 1, nf
            call project(model%x(:, s), model, faces(:, f), xi, dist)
            if (dist < best) then
               best = dist
               bf = f
               bxi = xi
            end if
         end do
         if (bf == 0) cycle
         call check_distance(best)
         if (best > tol) cycle
         m = merge(3, 2, faces(3, bf) > 0)
         w(1:m) = shape(bxi, m)
         do d = 1, 2
            if (taken(2*s - 2 + d)) then
               ! reverse: a held master node at a FEM node holds that node instead
               if (model%ties(t)%reverse) call hold_fem_node(d)
               cycle
            end if
            taken(2*s - 2 + d) = .true.
            call push(eqs, neq, s, d, faces(1:m, bf), w(1:m), model%ties(t)%loc)
         end do
      end do
      if (nbad > max_listed) then
         write (b1, '(i0)') nbad - max_listed
         call append_message(error, '... and '//trim(b1)//' more')
      end if
   contains
      !> An error for slave node s at `dist` from its master point beyond the tolerance.
      subroutine check_distance(dist)
         real(wp), intent(in) :: dist
         if (.not. dist > tol) return
         nbad = nbad + 1
         write (b1, '(i0)') model%node_id(s)
         write (b2, '(es10.3)') dist
         write (b3, '(es10.3)') tol
         if (nbad <= max_listed) call append_message(error, location_string(model, model%ties(t)%loc)// &
            ': error: '//which//trim(b1)//' of *TIE '//model%ties(t)%name//' is '//trim(adjustl(b2))// &
            other//', beyond the position tolerance '//trim(adjustl(b3)), err_input)
      end subroutine check_distance

      !> Dof d of node s (held) lies on an end node of face bf (within snap_rel of the
      !> side): that node's dof d tied to s's, when nothing else prescribes it.
      subroutine hold_fem_node(d)
         integer, intent(in) :: d
         integer(ip) :: fn
         if (bxi <= snap_rel) then
            fn = faces(1, bf)
         else if (bxi >= 1.0_wp - snap_rel) then
            fn = faces(2, bf)
         else
            return
         end if
         if (taken(2*fn - 2 + d)) return
         taken(2*fn - 2 + d) = .true.
         call push(eqs, neq, fn, d, [s], [1.0_wp], model%ties(t)%loc)
      end subroutine hold_fem_node
   end subroutine tie_one

   !> Master faces (a, b, side node or 0) of surface `surf`.
   subroutine master_faces(model, surf, faces)
      type(model_t), intent(in) :: model
      integer, intent(in) :: surf
      integer(ip), allocatable, intent(out) :: faces(:, :)
      integer :: k, ns
      integer(ip) :: abc(3)
      associate (sf => model%surfaces(surf))
         allocate (faces(3, size(sf%elem)))
         do k = 1, size(sf%elem)
            call element_side(model, sf%elem(k), sf%side(k), abc, ns)
            faces(:, k) = abc
         end do
      end associate
   end subroutine master_faces

   !> The sides (a, b, side node or 0) of the slave face of tie t: an element
   !> surface's facets, or the mesh boundary sides that a node surface's nodes span
   !> (slave_edges, as for a contact pair).
   subroutine slave_faces(model, t, faces, error)
      type(model_t), intent(in) :: model
      integer, intent(in) :: t
      integer(ip), allocatable, intent(out) :: faces(:, :)
      type(error_t), allocatable, intent(out) :: error
      type(contact_pair_t) :: pair
      integer(ip), allocatable :: edge(:, :), eelem(:)
      integer, allocatable :: eside(:)
      integer :: k, ns
      pair%slave = model%ties(t)%slave
      pair%master = model%ties(t)%master
      call slave_edges(model, pair, edge, eelem, eside, error)
      if (allocated(error)) return
      allocate (faces(3, size(eelem)))
      do k = 1, size(eelem)
         call element_side(model, eelem(k), eside(k), faces(:, k), ns)
      end do
   end subroutine slave_faces

   !> The nodes of the slave surface, unique: of its sides (side nodes included) or
   !> its node list.
   function slave_nodes(model, surf) result(nodes)
      type(model_t), intent(in) :: model
      integer, intent(in) :: surf
      integer(ip), allocatable :: nodes(:)
      logical, allocatable :: mark(:)
      integer :: k, ns, j
      integer(ip) :: abc(3), i
      associate (sf => model%surfaces(surf))
         if (sf%kind == surface_node) then
            nodes = sf%nodes
            return
         end if
         allocate (mark(model%nnode), source=.false.)
         do k = 1, size(sf%elem)
            call element_side(model, sf%elem(k), sf%side(k), abc, ns)
            do j = 1, 3
               if (abc(j) > 0) mark(abc(j)) = .true.
            end do
         end do
      end associate
      nodes = pack([(i, i=1, model%nnode)], mark)
   end function slave_nodes

   !> Closest point of face (a, b, m) to x: parameter xi in [0, 1] (0 at a, 1 at
   !> b) and distance; the quadratic curve through a, m, b when m > 0 (Newton
   !> from the chord's projection).
   pure subroutine project(x, model, face, xi, dist)
      real(wp), intent(in) :: x(2)
      type(model_t), intent(in) :: model
      integer(ip), intent(in) :: face(3)
      real(wp), intent(out) :: xi, dist
      real(wp) :: a(2), b(2), c(2), p(2), dp(2), ddp(2), g, h
      integer :: it
      a = model%x(:, face(1))
      b = model%x(:, face(2))
      xi = dot_product(x - a, b - a)/max(dot_product(b - a, b - a), tiny(1.0_wp))
      xi = min(1.0_wp, max(0.0_wp, xi))
      if (face(3) > 0) then
         c = model%x(:, face(3))
         do it = 1, 20
            p = (1 - xi)*(1 - 2*xi)*a + xi*(2*xi - 1)*b + 4*xi*(1 - xi)*c
            dp = (4*xi - 3)*a + (4*xi - 1)*b + (4 - 8*xi)*c
            ddp = 4*a + 4*b - 8*c
            g = dot_product(p - x, dp)
            h = dot_product(dp, dp) + dot_product(p - x, ddp)
            if (.not. h > 0.0_wp) exit
            xi = min(1.0_wp, max(0.0_wp, xi - g/h))
            if (abs(g/h) < 1.0e-14_wp) exit
         end do
         p = (1 - xi)*(1 - 2*xi)*a + xi*(2*xi - 1)*b + 4*xi*(1 - xi)*c
      else
         p = a + xi*(b - a)
      end if
      dist = norm2(x - p)
   end subroutine project

   !> Shape functions of a side at xi: (1 - xi, xi) or the quadratic (a, b, m).
   pure function shape(xi, m) result(w)
      real(wp), intent(in) :: xi
      integer, intent(in) :: m
      real(wp) :: w(m)
      if (m == 3) then
         w = [(1 - xi)*(1 - 2*xi), xi*(2*xi - 1), 4*xi*(1 - xi)]
      else
         w = [1 - xi, xi]
      end if
   end function shape

   !> Append u(s, d) - sum w_j u(nodes_j, d) = 0, without terms of weight below 1e-12.
   subroutine push(eqs, neq, s, d, nodes, w, loc)
      type(equation_t), allocatable, intent(inout) :: eqs(:)
      integer, intent(inout) :: neq
      integer(ip), intent(in) :: s, nodes(:)
      integer, intent(in) :: d
      real(wp), intent(in) :: w(:)
      type(source_loc_t), intent(in) :: loc
      type(equation_t), allocatable :: t(:)
      logical, allocatable :: keep(:)
      integer :: nk
      keep = abs(w) > 1.0e-12_wp
      nk = count(keep)
      if (neq == size(eqs)) then
         allocate (t(max(16, 2*neq)))
         t(1:neq) = eqs(1:neq)
         call move_alloc(t, eqs)
      end if
      neq = neq + 1
      eqs(neq)%node = [s, pack(nodes, keep)]
      allocate (eqs(neq)%dof(nk + 1))
      eqs(neq)%dof = d
      eqs(neq)%coef = [1.0_wp, -pack(w, keep)]
      eqs(neq)%loc = loc
   end subroutine push
end module vemcontact_driver_tie
