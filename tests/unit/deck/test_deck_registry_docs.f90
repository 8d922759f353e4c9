!> The keyword registry and docs/deck-reference.md agree: every keyword the parser
!> registers has a `### ` heading in the reference naming it (`*NAME ...`), and every
!> keyword named in such a heading is registered.  Run from tests/unit.
program test_deck_registry_docs
   use vemcontact_testing, only: checker_t
   use vemcontact_deck_registry, only: keywords, find_keyword
   use vemcontact_deck_fields, only: squeeze
   implicit none
   type(checker_t) :: t
   character(len=*), parameter :: doc = '../../docs/deck-reference.md'
   character(len=40) :: documented(500)
   integer :: ndoc
   character(len=1000) :: line
   integer :: u, stat, k, a, b
   logical :: found

   ndoc = 0
   open (newunit=u, file=doc, status='old', action='read', iostat=stat)
   call t%check(stat == 0, 'docs/deck-reference.md opens')
   if (stat /= 0) call t%finish()
   do
      read (u, '(a)', iostat=stat) line
      if (stat /= 0) exit
      if (line(1:4) /= '### ') cycle
      ! every `*NAME` in the heading: NAME runs to the first comma, bracket or backtick
      a = index(line, '`*')
      do while (a > 0)
         b = a + 2
         do while (b <= len_trim(line))
            if (scan(line(b:b), ',[`') > 0) exit
            b = b + 1
         end do
         ndoc = min(ndoc + 1, size(documented))
         documented(ndoc) = line(a + 2:b - 1)
         k = index(line(b:), '`*')
         if (k == 0) exit
         a = b + k - 1
      end do
   end do
   close (u)
   call t%check(ndoc >= size(keywords), 'the reference documents at least as many keywords')
   do k = 1, size(keywords)
      found = .false.
      do a = 1, ndoc
         if (squeeze(trim(documented(a))) == squeeze(keywords(k)%name)) found = .true.
      end do
      call t%check(found, '*'//trim(keywords(k)%name)//' is documented in a ### heading')
   end do
   do a = 1, ndoc
      call t%check(find_keyword(squeeze(trim(documented(a)))) > 0, &
                   'documented *'//trim(documented(a))//' is registered')
   end do
   call t%finish()
end program test_deck_registry_docs
