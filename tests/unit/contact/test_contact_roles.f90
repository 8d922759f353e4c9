!> The role rule of node-to-surface pairs (role_choice): the softer face is the slave
!> when the moduli differ by more than stiffness_contrast, whatever the meshes; with
!> moduli alike the finer face is, once the master's sides are shorter than the slave's
!> spacing by more than mesh_contrast; no moduli: the mesh alone.
program test_contact_roles
   use vemcontact_kinds, only: wp
   use vemcontact_testing, only: checker_t
   use vemcontact_contact_roles, only: role_choice, roles_keep, roles_swap, stiffness_contrast, mesh_contrast
   implicit none
   type(checker_t) :: t
   real(wp), parameter :: h = 0.2_wp

   ! the Hertz decks: a soft, fine disc as the master of a stiff block
   call t%equal(role_choice(1.0e6_wp, 1.0e3_wp, h, h/3.4_wp), roles_swap, 'soft, fine master: swap')
   ! a stiff, fine disc as the slave of a soft, coarse block: stiffness first
   call t%equal(role_choice(1.0e6_wp, 1.0e3_wp, h/3.4_wp, h), roles_swap, 'soft, coarse master: swap')
   ! the soft, coarse block as the slave of a stiff, fine disc: as written
   call t%equal(role_choice(1.0e3_wp, 1.0e6_wp, h, h/3.4_wp), roles_keep, 'stiff, fine master: keep')
   ! the rules disagree at a small contrast (a slave 3x stiffer, 3.4x finer): as written
   ! (+8.3 % on the Hertz decks, +16.6 % exchanged)
   call t%equal(role_choice(3.0_wp, 1.0_wp, h/3.4_wp, h), roles_keep, 'slave 3x stiffer and finer: keep')
   ! ... and at 10x the stiffness wins (+25 % as written, +8.2 % exchanged)
   call t%equal(role_choice(10.0_wp, 1.0_wp, h/3.4_wp, h), roles_swap, 'slave 10x stiffer and finer: swap')
   ! moduli alike: the mesh decides, beyond mesh_contrast only
   call t%equal(role_choice(1.0_wp, 1.0_wp, h, h/3.0_wp), roles_swap, 'alike, 3x finer master: swap')
   call t%equal(role_choice(1.0_wp, 1.0_wp, h, h/1.5_wp), roles_keep, 'alike, 1.5x finer master (2 vs 3): keep')
   call t%equal(role_choice(1.0_wp, 1.0_wp, h/3.0_wp, h), roles_keep, 'alike, coarser master: keep')
   ! the edges of "alike": just inside stiffness_contrast the mesh decides
   call t%equal(role_choice(0.99_wp*stiffness_contrast, 1.0_wp, h, h), roles_keep, &
                'slave slightly stiffer, same mesh: keep')
   call t%equal(role_choice(1.01_wp*stiffness_contrast, 1.0_wp, h, h), roles_swap, &
                'slave stiffer than the contrast: swap')
   call t%equal(role_choice(1.0_wp, 1.01_wp*stiffness_contrast, h, h/(2.0_wp*mesh_contrast)), roles_keep, &
                'master stiffer than the contrast, much finer: keep')
   ! no material on one side: the mesh alone
   call t%equal(role_choice(0.0_wp, 1.0_wp, h, h/(1.01_wp*mesh_contrast)), roles_swap, 'no modulus, finer master: swap')
   call t%equal(role_choice(0.0_wp, 0.0_wp, h, h/(0.99_wp*mesh_contrast)), roles_keep, &
                'no modulus, master within the contrast: keep')
   call t%finish()
end program test_contact_roles
