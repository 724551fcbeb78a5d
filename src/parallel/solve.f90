!> The distributed solve of one model (collective): the system assembled block-cyclically
!> (each process computes its own blocks), the TWODD-style elements solved with ScaLAPACK's
!> LU, and the contact elements by the active-set Newton method of ddc_contact_formulation
!> on the distributed stiffness operator, certified and checked like a serial solution.
!> Lemke's method is not distributed: a Newton failure is an error that says what to try.
module ddc_parallel_solve
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure
    use ddc_text, only: rtoa
    use ddc_model_types, only: element_set
    use ddc_model_results, only: solver_record, state_free
    use ddc_contact_options, only: solver_options
    use ddc_contact_result, only: contact_result
    use ddc_contact_formulation, only: solve_contact_with
    use ddc_contact_fault_law, only: fault_law
    use ddc_linalg_lu, only: influence_hint, residual_tol
    use ddc_solve_elastic, only: row_kinds, given_values
    use ddc_solve_frictional, only: record_contact, fault_law_of
    use ddc_parallel_context, only: parallel_context
    use ddc_parallel_matrix, only: multiply_whole
    use ddc_parallel_stiffness, only: distributed_stiffness, assemble_stiffness
    implicit none
    private

    public :: solve_distributed

    !> What a failed distributed contact solve can try instead
    character(len=*), parameter :: no_lemke_hint = "; Lemke's method, which the serial "// &
        "build falls back to, is not distributed: run the model on one process with "// &
        "lcp_method = 'lemke' (mpiexec -n 1) or with the serial build"
    !> Where a singular system of TWODD-style elements is, in a model with contact elements
    character(len=*), parameter :: among_free = &
        ' (among the elements with TWODD-style conditions)'

contains

    !> Solve for the DDs of every element on the processes (collective; every process gets
    !> the same DDs, states and record).
    subroutine solve_distributed(context, elements, shear_modulus, nu, remote_shear, &
                                 remote_normal, options, ds, dn, state, record, error, &
                                 law)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> Elements with geometry computed; contact elements carry their total pressure
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Remote stress resolved on each element [stress unit], shape (n)
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        !> Options of the contact solver (the method is the Newton method)
        type(solver_options), intent(in) :: options
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(out) :: ds(:), dn(:)
        !> Element states (state_free for TWODD-style elements), shape (n)
        integer, intent(out) :: state(:)
        !> Method, residual, certificate and timings are filled in
        type(solver_record), intent(inout) :: record
        !> Set when the model has no solution or the solver failed
        type(error_type), allocatable, intent(out) :: error
        !> The fault law of every element with the values in force at the end (contact
        !> models; the strength laws are refused on more than one process, but
        !> open_cohesion = 'lost' is not)
        type(fault_law), intent(out), optional :: law
        type(distributed_stiffness) :: stiffness
        type(contact_result) :: res
        type(fault_law) :: contact_law
        type(error_type), allocatable :: ill_conditioned
        integer, allocatable :: shear_row(:), normal_row(:)
        real(wp), allocatable :: given(:), b_free(:), x_free(:), shift(:)
        real(wp) :: flops, residual
        integer :: n, nc, nf
        integer(int64) :: t0, t1, rate

        n = elements%n
        call system_clock(t0, rate)
        allocate (shear_row(n), normal_row(n))
        call row_kinds(elements%condition, shear_row, normal_row)
        call assemble_stiffness(context, elements, shear_modulus, nu, shear_row, normal_row, &
                                stiffness, error)
        if (allocated(error)) return
        call system_clock(t1)
        record%seconds_assembly = real(t1 - t0, wp) / real(rate, wp)
        record%counts%seconds = 0.0_wp
        nc = size(stiffness%contact_elements)
        nf = size(stiffness%free_elements)
        flops = 0.0_wp
        residual = 0.0_wp

        ! The free DDs with the contact DDs at zero.
        allocate (b_free(2 * nf), x_free(2 * nf))
        if (nf > 0) then
            given = given_values(elements, shear_row, normal_row, remote_shear, remote_normal, &
                                 stiffness%free_elements)
            b_free(1::2) = given(1:nf)
            b_free(2::2) = given(nf + 1:)
            call stiffness%solve_free(b_free, x_free, 'influence matrix', error, &
                                      record%counts%seconds, flops, ill_conditioned)
            if (allocated(error)) then
                error%message = error%message//influence_hint
                if (nc > 0) error%message = error%message//among_free
                return
            end if
            residual = free_residual(context, stiffness, spread(0.0_wp, 1, 2 * nc), x_free, &
                                     b_free)
            ! A hole (closed contour) is numerically singular but consistent.
            if (allocated(ill_conditioned) .and. .not. residual <= residual_tol) then
                call set_error(error, exit_solver_failure, ill_conditioned%message// &
                               influence_hint//' (relative residual '//rtoa(residual)//')')
                if (nc > 0) error%message = error%message//among_free
                return
            end if
        end if

        state = state_free
        if (nc == 0) then
            record%method = 'lu'
            record%counts%flops = flops
            record%equilibrium_residual = residual
        else
            ! The contact elements see the free ones at x_F0: shift = S_r,C + K_CF x_F0.
            associate (contact => stiffness%contact_elements)
                shift = [remote_shear(contact), remote_normal(contact)]
                stiffness%free_dd = x_free
                call stiffness%multiply(spread(0.0_wp, 1, 2 * nc), shift)
                stiffness%free_dd = 0.0_wp
                contact_law = fault_law_of(elements, contact)
                call solve_contact_with(stiffness, shift(1:nc), shift(nc + 1:), contact_law, &
                                        elements%pressure(contact), options, res, error)
                if (allocated(error)) then
                    error%message = error%message//no_lemke_hint
                    return
                end if
                call record_contact(res, flops, record)
                if (present(law)) then
                    law = fault_law_of(elements)
                    call law%place_in_force(contact_law, contact)
                end if
                ds(contact) = res%ds
                dn(contact) = res%dn
                state(contact) = res%state
                if (nf > 0) then
                    x_free = x_free + stiffness%free_dd
                    record%equilibrium_residual = max(record%equilibrium_residual, &
                        free_residual(context, stiffness, [res%ds, res%dn], x_free, b_free))
                end if
            end associate
        end if
        ds(stiffness%free_elements) = x_free(1::2)
        dn(stiffness%free_elements) = x_free(2::2)
    end subroutine solve_distributed

    !> ||K_F,: x - b_F|| / ||b_F||: the free rows against the unfactored system (collective).
    function free_residual(context, stiffness, x_contact, x_free, b_free) result(residual)
        type(parallel_context), intent(in) :: context
        type(distributed_stiffness), intent(in) :: stiffness
        real(wp), intent(in) :: x_contact(:), x_free(:), b_free(:)
        real(wp) :: residual
        real(wp), allocatable :: x(:), y(:)

        allocate (x(stiffness%system%columns), y(stiffness%system%rows), source=0.0_wp)
        x(stiffness%contact_unknowns) = x_contact
        x(stiffness%free_unknowns) = x_free
        call multiply_whole(context, stiffness%system, x, y)
        residual = norm2(y(stiffness%free_unknowns) - b_free) / max(norm2(b_free), tiny(1.0_wp))
    end function free_residual

end module ddc_parallel_solve
