program vemcontact_main
   implicit none
   print '(a)', 'vemcontact: under construction'
end program vemcontact_main
