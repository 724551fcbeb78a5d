!> The checked LU factorization of a distributed matrix (ScaLAPACK pdgetrf, then pdgecon),
!> with the rules and messages of the serial one (ddc_linalg_lu): an exactly singular
!> matrix, or one whose reciprocal condition number is not above rcond_min, is an error
!> naming the element and unknown of the zero or smallest pivot; and the solve (pdgetrs) of
!> a system whose right-hand side every process holds whole.
module ddc_parallel_lu
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_internal_error
    use ddc_text, only: itoa
    use ddc_linalg_lu, only: rcond_min, singular_error, numerically_singular_error
    use ddc_parallel_scalapack, only: pdgetrf, pdgetrs, pdgecon, pdlange
    use ddc_parallel_context, only: parallel_context
    use ddc_parallel_collective, only: min_location, sum_on_all
    use ddc_parallel_matrix, only: distributed_matrix, create_matrix, owner, local_index, &
        global_rows, global_columns
    implicit none
    private

    public :: distributed_lu, distributed_solve

contains

    !> LU factorization with partial pivoting in place, checked (collective).
    subroutine distributed_lu(context, matrix, ipiv, subject, error, element, shear, &
                              ill_conditioned)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> A square matrix on entry; its L and U factors on exit
        type(distributed_matrix), intent(inout) :: matrix
        !> Pivot indices (ScaLAPACK's), shape (local_rows + block)
        integer, allocatable, intent(out) :: ipiv(:)
        !> What the matrix is, for the message
        character(len=*), intent(in) :: subject
        !> Allocated when the matrix is (numerically) singular
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
        real(wp) :: anorm, rcond, query(1)
        integer :: m, info, iquery(1)

        m = matrix%rows
        allocate (ipiv(matrix%local_rows + context%block))
        if (m == 0) return
        allocate (work(max(1, matrix%local_columns)))
        anorm = pdlange('1', m, m, matrix%a, 1, 1, matrix%desc, work)
        call pdgetrf(m, m, matrix%a, 1, 1, matrix%desc, ipiv, info)
        if (info > 0) then
            call singular_error(error, subject, info, m, element, shear)
            return
        else if (info < 0) then
            call set_internal_error(error, 'distributed_lu', 'pdgetrf argument '// &
                                    itoa(-info)//' is wrong')
            return
        end if
        call pdgecon('1', m, matrix%a, 1, 1, matrix%desc, anorm, rcond, query, -1, iquery, -1, &
                     info)
        deallocate (work)
        allocate (work(max(1, int(query(1)))), iwork(max(1, iquery(1))))
        call pdgecon('1', m, matrix%a, 1, 1, matrix%desc, anorm, rcond, work, size(work), &
                     iwork, size(iwork), info)
        if (.not. rcond > rcond_min) then
            call numerically_singular_error(numerical, subject, smallest_pivot(context, matrix), &
                                            m, rcond, element, shear)
            if (present(ill_conditioned)) then
                call move_alloc(numerical, ill_conditioned)
            else
                call move_alloc(numerical, error)
            end if
        end if
    end subroutine distributed_lu

    !> The unknown k of the smallest |U(k, k)| (the lowest among equal ones; collective).
    function smallest_pivot(context, factors) result(k)
        type(parallel_context), intent(in) :: context
        type(distributed_matrix), intent(in) :: factors
        integer :: k
        real(wp) :: smallest
        integer :: lc, gc

        k = factors%rows + 1
        smallest = huge(1.0_wp)
        associate (columns => global_columns(context, factors))
            do lc = 1, factors%local_columns
                gc = columns(lc)
                if (owner(gc, context%block, context%rows) /= context%row) cycle
                associate (u => abs(factors%a(local_index(gc, context%block, context%rows), lc)))
                    if (u < smallest) then
                        smallest = u
                        k = gc
                    end if
                end associate
            end do
        end associate
        call min_location(context, smallest, k)
    end function smallest_pivot

    !> Solve A x = b with the factors of distributed_lu (collective).
    subroutine distributed_solve(context, factors, ipiv, b, x)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> The factors from distributed_lu
        type(distributed_matrix), intent(in) :: factors
        !> Pivot indices from distributed_lu
        integer, intent(in) :: ipiv(:)
        !> The right-hand side, whole on every process, shape (m)
        real(wp), intent(in) :: b(:)
        !> The solution, whole on every process, shape (m)
        real(wp), intent(out) :: x(:)
        type(distributed_matrix) :: rhs
        type(error_type), allocatable :: error
        integer :: info

        x = 0.0_wp
        if (factors%rows == 0) return
        ! A one-column matrix shaped like the factors' rows cannot be refused.
        call create_matrix(context, factors%rows, 1, rhs, error)
        if (rhs%local_columns > 0) rhs%a(1:rhs%local_rows, 1) = b(global_rows(context, rhs))
        ! With factors from distributed_lu and consistent shapes pdgetrs cannot fail.
        call pdgetrs('N', factors%rows, 1, factors%a, 1, 1, factors%desc, ipiv, rhs%a, 1, 1, &
                     rhs%desc, info)
        if (rhs%local_columns > 0) x(global_rows(context, rhs)) = rhs%a(1:rhs%local_rows, 1)
        call sum_on_all(context, x)
    end subroutine distributed_solve

end module ddc_parallel_lu
