!> Explicit interfaces to the LAPACK routines vemcontact calls (OpenBLAS provides them).
module vemcontact_linalg_lapack
   use vemcontact_kinds, only: wp
   implicit none
   private

   public :: dsyev, dgetrf, dgetrs, dpotrs

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
      !> LU factorization with partial pivoting of a general matrix.
      pure subroutine dgetrf(m, n, a, lda, ipiv, info)
         import :: wp
         integer, intent(in) :: m, n, lda
         real(wp), intent(inout) :: a(lda, *)
         integer, intent(out) :: ipiv(*), info
      end subroutine dgetrf
      !> Solve with the LU factors of dgetrf.
      pure subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
         import :: wp
         character, intent(in) :: trans
         integer, intent(in) :: n, nrhs, lda, ldb
         real(wp), intent(in) :: a(lda, *)
         integer, intent(in) :: ipiv(*)
         real(wp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dgetrs
      !> Solve A X = B with the Cholesky factor of A (uplo 'L': A = L L^T).
      pure subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
         import :: wp
         character, intent(in) :: uplo
         integer, intent(in) :: n, nrhs, lda, ldb
         real(wp), intent(in) :: a(lda, *)
         real(wp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dpotrs
   end interface
end module vemcontact_linalg_lapack
