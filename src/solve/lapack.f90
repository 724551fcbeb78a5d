!> Thin wrappers with explicit interfaces over the LAPACK routines ddc2d uses.
module ddc_solve_lapack
    use ddc_kinds, only: wp
    implicit none
    private

    public :: lu_factor, lu_solve

    interface
        subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: wp
            integer, intent(in) :: m, n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgetrf
        subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            character(len=1), intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(in) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgetrs
    end interface

contains

    !> LU factorization with partial pivoting in place (DGETRF).
    !> info > 0: U(info, info) is exactly zero, the matrix is singular.
    subroutine lu_factor(a, ipiv, info)
        !> Square matrix on entry; L and U factors on exit, shape (n, n)
        real(wp), intent(inout) :: a(:, :)
        !> Pivot indices, shape (n)
        integer, intent(out) :: ipiv(:)
        !> LAPACK status: 0 success, > 0 index of the zero pivot
        integer, intent(out) :: info

        call dgetrf(size(a, 1), size(a, 2), a, size(a, 1), ipiv, info)
    end subroutine lu_factor

    !> Solve A X = B with the factors from lu_factor (DGETRS); B is overwritten by X.
    subroutine lu_solve(lu, ipiv, b)
        !> LU factors from lu_factor, shape (n, n)
        real(wp), intent(in) :: lu(:, :)
        !> Pivot indices from lu_factor, shape (n)
        integer, intent(in) :: ipiv(:)
        !> Right-hand sides on entry, solutions on exit, shape (n, nrhs)
        real(wp), intent(inout) :: b(:, :)
        integer :: info

        ! With valid factors and consistent shapes DGETRS cannot fail.
        call dgetrs('N', size(lu, 1), size(b, 2), lu, size(lu, 1), ipiv, b, size(b, 1), info)
    end subroutine lu_solve

end module ddc_solve_lapack
