!> Elastic solve for TWODD-style conditions (traction, displacement, mixed) and prescribed
!> DDs (identity rows: such elements take no unknowns in effect but act on the others).
module ddc_solve_elastic
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, set_internal_error, exit_solver_failure
    use ddc_model_types, only: element_set, condition_displacement, condition_mixed_us_sn, &
        condition_mixed_ss_un, condition_contact, condition_prescribed_dd
    use ddc_model_medium, only: elastic_medium
    use ddc_influence_assembly, only: assemble_influence, row_traction, row_displacement, &
        row_identity
    use ddc_influence_body, only: body_matrix_correction
    use ddc_linalg_lu, only: lu_factor, lu_solve, influence_hint, residual_tol
    use ddc_text, only: rtoa, itoa, seconds_text
    use ddc_progress, only: report_progress, reports_phases
    use ddc_allocation, only: allocation_failed, real_bytes
    implicit none
    private

    public :: solve_elastic, row_kinds, given_values

contains

    !> Row kinds of each element's shear and normal equation from its condition.
    pure subroutine row_kinds(condition, shear_row, normal_row)
        !> Condition code of each element, shape (n)
        integer, intent(in) :: condition(:)
        !> row_traction, row_displacement or row_identity, shape (n)
        integer, intent(out) :: shear_row(:), normal_row(:)

        where (condition == condition_displacement .or. condition == condition_mixed_us_sn)
            shear_row = row_displacement
        elsewhere (condition == condition_prescribed_dd)
            shear_row = row_identity
        elsewhere
            shear_row = row_traction
        end where
        where (condition == condition_displacement .or. condition == condition_mixed_ss_un)
            normal_row = row_displacement
        elsewhere (condition == condition_prescribed_dd)
            normal_row = row_identity
        elsewhere
            normal_row = row_traction
        end where
    end subroutine row_kinds

    !> Right-hand side of the given elements' rows, ordered [s; n]: traction rows take the
    !> given total traction minus the remote part; displacement rows take the given
    !> negative-face displacement and identity rows the given DD (remote stress adds none).
    pure function given_values(elements, shear_row, normal_row, remote_shear, remote_normal, &
                               subset) result(b)
        !> All elements
        type(element_set), intent(in) :: elements
        !> Row kinds of every element, shape (n)
        integer, intent(in) :: shear_row(:), normal_row(:)
        !> Remote stress resolved on every element [stress unit], shape (n)
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        !> Elements whose rows are wanted
        integer, intent(in) :: subset(:)
        real(wp) :: b(2 * size(subset))

        b(:size(subset)) = elements%bc_s(subset) - merge(remote_shear(subset), 0.0_wp, &
                                                         shear_row(subset) == row_traction)
        b(size(subset) + 1:) = elements%bc_n(subset) - merge(remote_normal(subset), 0.0_wp, &
                                                             normal_row(subset) == row_traction)
    end function given_values

    !> Solve for Ds, Dn of elements whose conditions are all TWODD-style (no contact).
    subroutine solve_elastic(medium, remote_shear, remote_normal, ds, dn, residual, &
                             seconds_assembly, seconds_factorization, matrix, error)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Remote stress resolved on each element [stress unit], shape (n)
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(out) :: ds(:), dn(:)
        !> Relative residual |K x - b| / |b| against the unfactored system
        real(wp), intent(out) :: residual
        !> Wall time of assembly and factorization + solve [s]
        real(wp), intent(out) :: seconds_assembly, seconds_factorization
        !> The influence matrix assembled with the rows of row_kinds (unfactored), shape
        !> (2n, 2n)
        real(wp), allocatable, intent(out) :: matrix(:, :)
        !> Set when the system is singular
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: factors(:, :), rhs(:, :), given(:)
        integer, allocatable :: shear_row(:), normal_row(:), ipiv(:)
        type(error_type), allocatable :: ill_conditioned
        integer :: n, i, stat
        integer(int64) :: t0, t1, t2, rate

        n = medium%elements%n
        if (any(medium%elements%condition == condition_contact)) then
            call set_internal_error(error, 'solve_elastic', 'called with contact elements')
            return
        end if
        call system_clock(t0, rate)
        allocate (shear_row(n), normal_row(n), rhs(2 * n, 1), ipiv(2 * n))
        allocate (matrix(2 * n, 2 * n), stat=stat)
        if (stat == 0) allocate (factors(2 * n, 2 * n), stat=stat)
        if (stat /= 0) then
            call allocation_failed(error, 'the influence matrix of '//itoa(n)// &
                                   ' elements and its LU factors', &
                                   2.0_wp * real_bytes * (2.0_wp * real(n, wp))**2)
            return
        end if
        call row_kinds(medium%elements%condition, shear_row, normal_row)
        call assemble_influence(medium, shear_row, normal_row, matrix)
        if (allocated(medium%body)) call body_matrix_correction(medium, shear_row, normal_row, &
                                                                matrix)
        rhs(:, 1) = given_values(medium%elements, shear_row, normal_row, remote_shear, &
                                 remote_normal, [(i, i = 1, n)])
        call system_clock(t1)
        if (reports_phases(n)) call report_progress('assembly done in '// &
            seconds_text(real(t1 - t0, wp) / real(rate, wp))//' ('//itoa(2 * n)//' x '// &
            itoa(2 * n)//' influence matrix)')

        factors(:, :) = matrix
        call lu_factor(factors, ipiv, 'influence matrix', error, ill_conditioned=ill_conditioned)
        if (allocated(error)) then
            error%message = error%message//influence_hint
            return
        end if
        given = rhs(:, 1)
        call lu_solve(factors, ipiv, rhs)
        call system_clock(t2)
        if (reports_phases(n)) call report_progress('LU factorization and solve done in '// &
            seconds_text(real(t2 - t1, wp) / real(rate, wp)))

        residual = norm2(matmul(matrix, rhs(:, 1)) - given) / max(norm2(given), tiny(1.0_wp))
        ! A hole (closed contour) is numerically singular but consistent: its residual is small.
        if (allocated(ill_conditioned) .and. .not. residual <= residual_tol) then
            call set_error(error, exit_solver_failure, ill_conditioned%message// &
                           influence_hint//' (relative residual '//rtoa(residual)//')')
            return
        end if
        ds = rhs(1:n, 1)
        dn = rhs(n + 1:, 1)
        seconds_assembly = real(t1 - t0, wp) / real(rate, wp)
        seconds_factorization = real(t2 - t1, wp) / real(rate, wp)
    end subroutine solve_elastic

end module ddc_solve_elastic
