!> Writes a benchmark deck: the unit square meshed with the perturbed
!> barycentric-dual polygon mesh of an n x n grid (about n^2 cells, 2 n^2 nodes),
!> plane strain, self-weight, bottom fixed.  usage: make_polymesh_deck N DECK
program make_polymesh_deck
   use vemcontact_kinds, only: wp, ip
   use vemcontact_test_polymesh, only: dual_polymesh
   implicit none
   real(wp), allocatable :: x(:, :)
   integer(ip), allocatable :: ptr(:), conn(:)
   character(len=256) :: arg, path
   character(len=32) :: buf
   integer :: n, u, i, e, k
   call get_command_argument(1, arg)
   read (arg, *) n
   call get_command_argument(2, path)
   call dual_polymesh(n, 0.3_wp, 1, x, ptr, conn)
   open (newunit=u, file=trim(path), status='replace', action='write')
   write (u, '(a)') '** benchmark: perturbed dual polygon mesh of the unit square, self-weight'
   write (u, '(a)') '*NODE'
   do i = 1, size(x, 2)
      write (u, '(i0,2(a,es23.16))') i, ', ', x(1, i), ', ', x(2, i)
   end do
   write (u, '(a)') '*ELEMENT, TYPE=VPE, ELSET=ALL'
   do e = 1, size(ptr) - 1
      write (buf, '(i0)') e
      write (u, '(a)', advance='no') trim(buf)
      do k = ptr(e), ptr(e + 1) - 1
         write (buf, '(i0)') conn(k)
         write (u, '(a)', advance='no') ', '//trim(buf)
      end do
      write (u, '(a)') ''
   end do
   write (u, '(a)') '*NSET, NSET=BOTTOM'
   k = 0
   do i = 1, size(x, 2)
      if (x(2, i) < 1.0e-12_wp) then
         write (u, '(i0,a)', advance='no') i, ','
         k = k + 1
         if (mod(k, 16) == 0) write (u, '(a)') ''
      end if
   end do
   write (u, '(a)') ''
   write (u, '(a)') '*MATERIAL, NAME=ROCK'
   write (u, '(a)') '*ELASTIC'
   write (u, '(a)') '1.0e10, 0.3'
   write (u, '(a)') '*DENSITY'
   write (u, '(a)') '2400.'
   write (u, '(a)') '*SOLID SECTION, ELSET=ALL, MATERIAL=ROCK'
   write (u, '(a)') '*BOUNDARY'
   write (u, '(a)') 'BOTTOM, 1, 2'
   write (u, '(a)') '*STEP'
   write (u, '(a)') '*STATIC'
   write (u, '(a)') '*DLOAD'
   write (u, '(a)') 'ALL, GRAV, 9.81, 0., -1.'
   write (u, '(a)') '*END STEP'
   close (u)
end program make_polymesh_deck
