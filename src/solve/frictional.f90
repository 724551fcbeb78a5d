!> Models with contact elements: TWODD-style elements are eliminated (static condensation)
!> so that the LCP covers the contact elements only (SPEC section 4).
!>
!> With the system K x = b split into free unknowns F (elements with TWODD conditions, rows
!> as their conditions say) and contact unknowns C (traction rows t_C = S_r,C + K_CC x_C +
!> K_CF x_F):  x_F = K_FF^-1 (b_F - K_FC x_C), so the contact elements see
!> A = K_CC - K_CF K_FF^-1 K_FC and the remote traction S_r,C + K_CF K_FF^-1 b_F.
module ddc_solve_frictional
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure
    use ddc_model_types, only: element_set, condition_contact
    use ddc_model_results, only: solver_record, state_free
    use ddc_influence_assembly, only: assemble_influence, row_traction
    use ddc_solve_elastic, only: row_kinds, given_values, singular_message
    use ddc_solve_lapack, only: lu_factor, lu_solve, dgemm
    use ddc_contact_formulation, only: contact_result, solve_contact
    implicit none
    private

    public :: solve_frictional

contains

    !> Solve a model with at least one contact element.
    subroutine solve_frictional(elements, shear_modulus, nu, remote_shear, remote_normal, &
                                open_cohesion, lcp_method, ds, dn, state, record, error)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Remote stress resolved on each element [stress unit], shape (n)
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        !> 'kept' or 'lost' (SPEC section 4)
        character(len=*), intent(in) :: open_cohesion
        !> 'auto', 'lemke' or 'newton' (SPEC section 4; ddc_contact_formulation)
        character(len=*), intent(in) :: lcp_method
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(out) :: ds(:), dn(:)
        !> Element states (state_free for TWODD-style elements), shape (n)
        integer, intent(out) :: state(:)
        !> Method, pivots, certificate, residual and timings are filled in
        type(solver_record), intent(inout) :: record
        !> Set when the model has no solution or the solver failed
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: matrix(:, :), a_contact(:, :), kff(:, :), y(:, :)
        real(wp), allocatable :: shift(:), x_contact(:), x_free(:), residual_free(:)
        integer, allocatable :: shear_row(:), normal_row(:), contact(:), free(:), cu(:), fu(:)
        integer, allocatable :: ipiv(:)
        type(contact_result) :: res
        integer :: n, nc, nf, info, i
        integer(8) :: t0, t1, t2, rate

        n = elements%n
        call system_clock(t0, rate)
        contact = pack([(i, i = 1, n)], elements%condition == condition_contact)
        free = pack([(i, i = 1, n)], elements%condition /= condition_contact)
        nc = size(contact)
        nf = size(free)
        ! Unknown indices in the full system, ordered [s; n] within each set.
        cu = [contact, n + contact]
        fu = [free, n + free]

        allocate (shear_row(n), normal_row(n), matrix(2 * n, 2 * n))
        call row_kinds(elements%condition, shear_row, normal_row)
        call assemble_influence(elements, shear_modulus, nu, shear_row, normal_row, matrix)
        call system_clock(t1)
        record%seconds_assembly = real(t1 - t0, wp) / real(rate, wp)

        shift = [remote_shear(contact), remote_normal(contact)]
        if (nf == 0) then
            ! Every element is a contact element: A is the whole matrix (no copy).
            call move_alloc(matrix, a_contact)
        else
            a_contact = matrix(cu, cu)
            ! y = K_FF^-1 [b_F, K_FC]
            kff = matrix(fu, fu)
            allocate (y(2 * nf, 1 + 2 * nc), ipiv(2 * nf))
            y(:, 1) = given_values(elements, shear_row, normal_row, remote_shear, &
                                   remote_normal, free)
            y(:, 2:) = matrix(fu, cu)
            call lu_factor(kff, ipiv, info)
            if (info > 0) then
                call set_error(error, exit_solver_failure, singular_message(nf, info, free)// &
                               ' (among the elements with TWODD-style conditions)')
                return
            end if
            call lu_solve(kff, ipiv, y)
            call dgemm('N', 'N', 2 * nc, 2 * nc, 2 * nf, -1.0_wp, matrix(cu, fu), 2 * nc, &
                       y(:, 2:), 2 * nf, 1.0_wp, a_contact, 2 * nc)
            shift = shift + matmul(matrix(cu, fu), y(:, 1))
        end if
        call system_clock(t2)
        record%seconds_factorization = real(t2 - t1, wp) / real(rate, wp)

        call solve_contact(a_contact, shift(1:nc), shift(nc + 1:), elements%mu(contact), &
                           elements%sf(contact), elements%pressure(contact), open_cohesion, &
                           res, error, method=lcp_method)
        if (allocated(error)) then
            if (nc < n) error%message = error%message// &
                ' (element numbers count the contact elements only)'
            return
        end if
        record%method = res%method
        record%fallback = res%fallback
        record%newton_iterations = res%iterations
        ! Condensation: LU of K_FF, its solve for 2 nc + 1 right-hand sides and the product.
        record%factorization_flops = res%factorization_flops + 2.0_wp / 3.0_wp * &
            real(2 * nf, wp)**3 + 2.0_wp * real(2 * nf, wp)**2 * real(2 * nc + 1, wp) + &
            2.0_wp * real(2 * nc, wp)**2 * real(2 * nf, wp)
        record%pivots = res%pivots
        record%lcp_solves = res%solves
        record%certificate_min_z = res%certificate%min_z
        record%certificate_min_w = res%certificate%min_w
        record%certificate_max_complementarity = res%certificate%max_complementarity
        record%certificate_tolerance = res%certificate%tolerance
        record%seconds_factorization = record%seconds_factorization + res%seconds_factorization
        record%seconds_lcp = res%seconds_lcp
        record%equilibrium_residual = maxval(res%equilibrium_residual)

        state = state_free
        state(contact) = res%state
        ds(contact) = res%ds
        dn(contact) = res%dn
        if (nf > 0) then
            x_contact = [res%ds, res%dn]
            x_free = y(:, 1) - matmul(y(:, 2:), x_contact)
            ds(free) = x_free(1:nf)
            dn(free) = x_free(nf + 1:)
            ! The free rows against the unfactored system.
            residual_free = matmul(matrix(fu, fu), x_free) + matmul(matrix(fu, cu), x_contact) &
                            - y(:, 1)
            record%equilibrium_residual = max(record%equilibrium_residual, &
                norm2(residual_free) / max(norm2(y(:, 1)), tiny(1.0_wp)))
        end if
    end subroutine solve_frictional
end module ddc_solve_frictional
