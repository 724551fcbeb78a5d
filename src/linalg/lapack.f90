!> Explicit interfaces for the LAPACK and BLAS routines ddc2d calls.
!> Every module that calls LAPACK or BLAS takes the interface from here, so argument
!> mismatches are compile-time errors.
module ddc_linalg_lapack
    use ddc_kinds, only: wp
    implicit none
    private

    public :: dgetrf, dgetrs, dgetri, dgecon, dlange, dgemv, dger, dgemm, dtrmm, dtrsm, dlaswp, &
        dsyev

    interface
        !> LU factorization with partial pivoting of a general m x n matrix (LAPACK)
        subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: wp
            implicit none
            integer, intent(in) :: m, n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgetrf
        !> Solve A X = B or A^T X = B with the LU factors of dgetrf (LAPACK)
        subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            implicit none
            character(len=1), intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(in) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgetrs
        !> Inverse of a matrix from its LU factors (LAPACK)
        subroutine dgetri(n, a, lda, ipiv, work, lwork, info)
            import :: wp
            implicit none
            integer, intent(in) :: n, lda, lwork
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(wp), intent(inout) :: work(*)
            integer, intent(out) :: info
        end subroutine dgetri
        !> Reciprocal condition number of a matrix from its LU factors (LAPACK)
        subroutine dgecon(norm, n, a, lda, anorm, rcond, work, iwork, info)
            import :: wp
            implicit none
            character, intent(in) :: norm
            integer, intent(in) :: n, lda
            real(wp), intent(in) :: a(lda, *), anorm
            real(wp), intent(out) :: rcond
            real(wp), intent(inout) :: work(*)
            integer, intent(inout) :: iwork(*)
            integer, intent(out) :: info
        end subroutine dgecon
        !> One, infinity, Frobenius or max-abs norm of a general matrix (LAPACK)
        function dlange(norm, m, n, a, lda, work) result(val)
            import :: wp
            implicit none
            character, intent(in) :: norm
            integer, intent(in) :: m, n, lda
            real(wp), intent(in) :: a(lda, *)
            real(wp), intent(inout) :: work(*)
            real(wp) :: val
        end function dlange
        !> y = alpha op(A) x + beta y (BLAS level 2)
        subroutine dgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
            import :: wp
            implicit none
            character, intent(in) :: trans
            integer, intent(in) :: m, n, lda, incx, incy
            real(wp), intent(in) :: alpha, beta, a(lda, *), x(*)
            real(wp), intent(inout) :: y(*)
        end subroutine dgemv
        !> Rank-one update A = A + alpha x y^T (BLAS level 2)
        subroutine dger(m, n, alpha, x, incx, y, incy, a, lda)
            import :: wp
            implicit none
            integer, intent(in) :: m, n, incx, incy, lda
            real(wp), intent(in) :: alpha, x(*), y(*)
            real(wp), intent(inout) :: a(lda, *)
        end subroutine dger
        !> C = alpha op(A) op(B) + beta C (BLAS level 3)
        subroutine dgemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc)
            import :: wp
            implicit none
            character, intent(in) :: transa, transb
            integer, intent(in) :: m, n, k, lda, ldb, ldc
            real(wp), intent(in) :: alpha, beta, a(lda, *), b(ldb, *)
            real(wp), intent(inout) :: c(ldc, *)
        end subroutine dgemm
        !> Eigenvalues (ascending) and, with jobz = 'V', eigenvectors of a symmetric matrix
        subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
            import :: wp
            implicit none
            character, intent(in) :: jobz, uplo
            integer, intent(in) :: n, lda, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: w(*), work(*)
            integer, intent(out) :: info
        end subroutine dsyev
        !> B = alpha op(A) B or alpha B op(A), A triangular (BLAS level 3)
        subroutine dtrmm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb)
            import :: wp
            implicit none
            character, intent(in) :: side, uplo, transa, diag
            integer, intent(in) :: m, n, lda, ldb
            real(wp), intent(in) :: alpha, a(lda, *)
            real(wp), intent(inout) :: b(ldb, *)
        end subroutine dtrmm
        !> Solve op(A) X = alpha B or X op(A) = alpha B, A triangular; X overwrites B (BLAS
        !> level 3)
        subroutine dtrsm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb)
            import :: wp
            implicit none
            character, intent(in) :: side, uplo, transa, diag
            integer, intent(in) :: m, n, lda, ldb
            real(wp), intent(in) :: alpha, a(lda, *)
            real(wp), intent(inout) :: b(ldb, *)
        end subroutine dtrsm
        !> The row interchanges ipiv(k1:k2) applied to the columns of A in turn (LAPACK)
        subroutine dlaswp(n, a, lda, k1, k2, ipiv, incx)
            import :: wp
            implicit none
            integer, intent(in) :: n, lda, k1, k2, incx, ipiv(*)
            real(wp), intent(inout) :: a(lda, *)
        end subroutine dlaswp
    end interface

end module ddc_linalg_lapack
