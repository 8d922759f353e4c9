program vemcontact_main
   implicit none
   print '(a)', 'vemcontact skeleton'
end program vemcontact_main
