!> The one checked LU factorization of ddc2d: LAPACK dgetrf, then the reciprocal condition
!> number from dgecon. A matrix that is exactly singular, or whose reciprocal condition
!> number is not above rcond_min, is an error (exit_solver_failure) that names the element
!> and the unknown (shear or normal DD) of the smallest pivot; every dense factorization,
!> solve and inverse of the solvers goes through here.
!>
!> Some valid models have numerically singular matrices: a closed contour of TWODD-style
!> elements (a hole) has the rigid-body motions of its interior as near-null vectors, with a
!> right-hand side that is consistent with them. Callers that can check their solution
!> against the unfactored system (relative residual at most residual_tol) pass
!> ill_conditioned and turn it into an error only when that check fails.
!>
!> Unknowns are named by the [s; n] ordering of the influence matrices (unknown k of a
!> system of n elements is the shear DD of element k for k <= n, else the normal DD of
!> element k - n), or by the element and kind the caller gives for each unknown.
module ddc_linalg_lu
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure
    use ddc_text, only: itoa
    use ddc_allocation, only: allocation_failed, real_bytes
    use ddc_linalg_lapack, only: dgetrf, dgetrs, dgetri, dgecon, dlange
    implicit none
    private

    public :: lu_factor, lu_solve, lu_invert, rcond_min, residual_tol, influence_hint
    public :: singular_error, numerically_singular_error

    !> Largest reciprocal condition number called numerically singular
    real(wp), parameter :: rcond_min = 1.0e3_wp * epsilon(1.0_wp)
    !> Largest accepted relative residual of a solution against its unfactored system
    real(wp), parameter :: residual_tol = 1.0e-8_wp
    !> What a singular influence matrix usually means, for the callers' messages
    character(len=*), parameter :: influence_hint = &
        ': duplicate or overlapping elements, or no condition fixing it?'

contains

    !> LU factorization with partial pivoting in place (dgetrf), checked by dgecon.
    subroutine lu_factor(a, ipiv, subject, error, element, shear, ill_conditioned)
        !> Square matrix on entry; L and U factors on exit, shape (m, m)
        real(wp), intent(inout) :: a(:, :)
        !> Pivot indices, shape (m)
        integer, intent(out) :: ipiv(:)
        !> What the matrix is, for the message ("influence matrix")
        character(len=*), intent(in) :: subject
        !> Allocated when the matrix is (numerically) singular: "<subject> is singular at
        !> element 12 (normal unknown)"
        type(error_type), allocatable, intent(out) :: error
        !> Element of each unknown, shape (m) (default: the [s; n] ordering of m/2 elements)
        integer, intent(in), optional :: element(:)
        !> Whether each unknown is a shear DD, shape (m) (default: the [s; n] ordering)
        logical, intent(in), optional :: shear(:)
        !> When present, a numerically (not exactly) singular matrix is reported here instead
        !> of in error; the factors are then usable
        type(error_type), allocatable, intent(out), optional :: ill_conditioned
        type(error_type), allocatable :: numerical
        real(wp), allocatable :: work(:)
        integer, allocatable :: iwork(:)
        real(wp) :: anorm, rcond
        integer :: m, info, i, k

        m = size(a, 1)
        if (m == 0) return
        allocate (work(4 * m), iwork(m))
        anorm = dlange('1', m, m, a, m, work)
        call dgetrf(m, m, a, m, ipiv, info)
        if (info > 0) then
            call singular_error(error, subject, info, m, element, shear)
            return
        end if
        call dgecon('1', m, a, m, anorm, rcond, work, iwork, info)
        if (.not. rcond > rcond_min) then
            ! dgetrf permutes rows only: the smallest pivot U(k, k) names unknown k.
            k = 1
            do i = 2, m
                if (abs(a(i, i)) < abs(a(k, k))) k = i
            end do
            call numerically_singular_error(numerical, subject, k, m, rcond, element, shear)
            if (present(ill_conditioned)) then
                call move_alloc(numerical, ill_conditioned)
            else
                call move_alloc(numerical, error)
            end if
        end if
    end subroutine lu_factor

    !> Solve A X = B with the factors from lu_factor (dgetrs); B is overwritten by X.
    subroutine lu_solve(lu, ipiv, b)
        !> LU factors from lu_factor, shape (m, m)
        real(wp), intent(in) :: lu(:, :)
        !> Pivot indices from lu_factor, shape (m)
        integer, intent(in) :: ipiv(:)
        !> Right-hand sides on entry, solutions on exit, shape (m, nrhs)
        real(wp), intent(inout) :: b(:, :)
        integer :: info

        ! With factors from lu_factor and consistent shapes dgetrs cannot fail.
        call dgetrs('N', size(lu, 1), size(b, 2), lu, size(lu, 1), ipiv, b, size(b, 1), info)
    end subroutine lu_solve

    !> The inverse of a matrix from its checked LU factorization (dgetri).
    subroutine lu_invert(a, inverse, subject, error)
        !> The matrix, shape (m, m)
        real(wp), intent(in) :: a(:, :)
        !> Its inverse, shape (m, m)
        real(wp), allocatable, intent(out) :: inverse(:, :)
        !> What the matrix is, for the message
        character(len=*), intent(in) :: subject
        !> Allocated when the matrix is (numerically) singular (exit_solver_failure) or the
        !> inverse does not fit in memory (exit_out_of_memory)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: work(:)
        integer, allocatable :: ipiv(:)
        integer :: m, info, lwork, stat

        m = size(a, 1)
        allocate (ipiv(m))
        allocate (inverse(m, m), stat=stat)
        if (stat /= 0) then
            call allocation_failed(error, 'the inverse of the '//subject, &
                                   real_bytes * real(m, wp)**2)
            return
        end if
        inverse(:, :) = a
        call lu_factor(inverse, ipiv, subject, error)
        if (allocated(error) .or. m == 0) return
        allocate (work(1))
        call dgetri(m, inverse, m, ipiv, work, -1, info)
        lwork = max(int(work(1)), m)
        deallocate (work)
        allocate (work(lwork), stat=stat)
        if (stat /= 0) then
            call allocation_failed(error, 'the work space of the inverse of the '//subject, &
                                   real_bytes * real(lwork, wp))
            return
        end if
        ! With nonsingular factors dgetri cannot fail.
        call dgetri(m, inverse, m, ipiv, work, lwork, info)
    end subroutine lu_invert

    !> "<subject> is singular at element 12 (normal unknown)": a zero pivot at unknown k.
    subroutine singular_error(error, subject, k, m, element, shear)
        !> The error (exit_solver_failure)
        type(error_type), allocatable, intent(out) :: error
        !> What the matrix is
        character(len=*), intent(in) :: subject
        !> The unknown of the zero pivot and the number of unknowns
        integer, intent(in) :: k, m
        !> Element of each unknown, shape (m) (default: the [s; n] ordering of m/2 elements)
        integer, intent(in), optional :: element(:)
        !> Whether each unknown is a shear DD, shape (m) (default: the [s; n] ordering)
        logical, intent(in), optional :: shear(:)

        call set_error(error, exit_solver_failure, subject//' is singular at '// &
                       unknown_name(k, m, element, shear))
    end subroutine singular_error

    !> "<subject> is numerically singular near element 12 (normal unknown) (reciprocal
    !> condition number 1.0E-17)": the smallest pivot at unknown k.
    subroutine numerically_singular_error(error, subject, k, m, rcond, element, shear)
        !> The error (exit_solver_failure)
        type(error_type), allocatable, intent(out) :: error
        !> What the matrix is
        character(len=*), intent(in) :: subject
        !> The unknown of the smallest pivot and the number of unknowns
        integer, intent(in) :: k, m
        !> The reciprocal condition number
        real(wp), intent(in) :: rcond
        !> Element of each unknown, shape (m) (default: the [s; n] ordering of m/2 elements)
        integer, intent(in), optional :: element(:)
        !> Whether each unknown is a shear DD, shape (m) (default: the [s; n] ordering)
        logical, intent(in), optional :: shear(:)
        character(len=12) :: rcond_text

        write (rcond_text, '(es10.3)') rcond
        call set_error(error, exit_solver_failure, subject//' is numerically singular near '// &
                       unknown_name(k, m, element, shear)//' (reciprocal condition number '// &
                       trim(adjustl(rcond_text))//')')
    end subroutine numerically_singular_error

    !> "element 12 (normal unknown)" for unknown k of m.
    function unknown_name(k, m, element, shear) result(name)
        integer, intent(in) :: k, m
        integer, intent(in), optional :: element(:)
        logical, intent(in), optional :: shear(:)
        character(len=:), allocatable :: name
        integer :: e
        logical :: is_shear

        e = modulo(k - 1, max(m / 2, 1)) + 1
        is_shear = k <= m / 2
        if (present(element)) e = element(k)
        if (present(shear)) is_shear = shear(k)
        name = 'element '//itoa(e)//' ('//trim(merge('shear ', 'normal', is_shear))//' unknown)'
    end function unknown_name

end module ddc_linalg_lu
