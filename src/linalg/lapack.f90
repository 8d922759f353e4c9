!> Explicit interfaces to the LAPACK routines vemcontact calls (OpenBLAS provides them).
module vemcontact_linalg_lapack
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: dsyev

   interface
      !> Eigenvalues (ascending) and optionally eigenvectors of a real symmetric matrix.
      pure subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
         import :: wp
         character, intent(in) :: jobz, uplo
         integer, intent(in) :: n, lda, lwork
         real(wp), intent(inout) :: a(lda, *)
         real(wp), intent(out) :: w(*), work(*)
         integer, intent(out) :: info
      end subroutine dsyev
   end interface
end module vemcontact_linalg_lapack
