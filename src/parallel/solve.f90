!> The elastic operator of a medium distributed over the processes (ddc_solve_operator,
!> collective): the system assembled block-cyclically (each process computes its own
!> blocks), the free elements' DDs solved with ScaLAPACK's LU, and A the contact elements'
!> rows and columns with the free unknowns condensed inside ddc_parallel_stiffness, on which
!> the contact run's Newton method works (certified and checked like a serial solution).
!> Lemke's method is not distributed: a Newton failure is an error that says what to try.
module ddc_parallel_solve
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure
    use ddc_text, only: rtoa
    use ddc_model_medium, only: elastic_medium
    use ddc_model_results, only: solver_record
    use ddc_linalg_lu, only: influence_hint, residual_tol
    use ddc_solve_elastic, only: row_kinds, given_values
    use ddc_solve_operator, only: elastic_operator, elastic_load, free_part
    use ddc_parallel_context, only: parallel_context
    use ddc_parallel_matrix, only: multiply_whole
    use ddc_parallel_stiffness, only: distributed_stiffness, assemble_stiffness
    implicit none
    private

    public :: distributed_operator, new_distributed_operator

    !> What a failed distributed contact solve can try instead
    character(len=*), parameter :: no_lemke_hint = "; Lemke's method, which the serial "// &
        "build falls back to, is not distributed: run the model on one process with "// &
        "lcp_method = 'lemke' (mpiexec -n 1) or with the serial build"
    !> Where a singular system of TWODD-style elements is, in a model with contact elements
    character(len=*), parameter :: among_free = &
        ' (among the elements with TWODD-style conditions)'

    !> A medium's operator on the processes.
    type, extends(elastic_operator) :: distributed_operator
        !> Row kinds of every element (ddc_solve_elastic), shape (n)
        integer, allocatable :: shear_row(:), normal_row(:)
        !> The free rows' relative residual with every contact DD at zero
        real(wp) :: free_residual = 0.0_wp
    contains
        procedure :: load_contact => distributed_load_contact
        procedure :: complete => distributed_complete
        procedure :: release => distributed_release
    end type distributed_operator

contains

    !> Assemble the medium's system on the processes (timed into operator%record).
    subroutine new_distributed_operator(context, medium, operator, error)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> The medium, geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The operator
        type(distributed_operator), intent(out) :: operator
        !> Set when the assembly fails
        type(error_type), allocatable, intent(out) :: error
        integer :: n
        integer(int64) :: t0, t1, rate

        n = medium%elements%n
        call system_clock(t0, rate)
        allocate (operator%shear_row(n), operator%normal_row(n))
        call row_kinds(medium%elements%condition, operator%shear_row, operator%normal_row)
        allocate (distributed_stiffness :: operator%stiffness)
        select type (s => operator%stiffness)
        type is (distributed_stiffness)
            call assemble_stiffness(context, medium, operator%shear_row, operator%normal_row, &
                                    s, error)
            if (allocated(error)) return
            operator%contact = s%contact_elements
            operator%free = s%free_elements
        end select
        operator%nc = size(operator%contact)
        operator%nf = size(operator%free)
        operator%hint = no_lemke_hint
        call system_clock(t1)
        operator%record%seconds_assembly = real(t1 - t0, wp) / real(rate, wp)
        operator%record%counts%seconds = 0.0_wp
    end subroutine new_distributed_operator

    !> The free DDs with the contact DDs at zero (K_FF x_F0 = b_F, factorized and timed
    !> here), and shift = S_r,C + K_CF x_F0.
    subroutine distributed_load_contact(this, medium, load, shift, kept, error)
        class(distributed_operator), intent(inout) :: this
        type(elastic_medium), intent(in) :: medium
        type(elastic_load), intent(in) :: load
        real(wp), intent(out) :: shift(:)
        type(free_part), intent(out) :: kept
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: ill_conditioned
        real(wp), allocatable :: b_free(:)
        integer :: nc, nf

        nc = this%nc
        nf = this%nf
        allocate (kept%dd(2 * nf))
        select type (s => this%stiffness)
        type is (distributed_stiffness)
            if (nf > 0) then
                b_free = free_values(this, medium, load)
                call s%solve_free(b_free, kept%dd, 'influence matrix', error, &
                                  this%record%counts%seconds, this%flops, ill_conditioned)
                if (allocated(error)) then
                    error%message = error%message//influence_hint
                    if (nc > 0) error%message = error%message//among_free
                    return
                end if
                this%free_residual = free_residual(s, spread(0.0_wp, 1, 2 * nc), kept%dd, &
                                                   b_free)
                ! A hole (closed contour) is numerically singular but consistent.
                if (allocated(ill_conditioned) .and. .not. this%free_residual <= &
                    residual_tol) then
                    call set_error(error, exit_solver_failure, ill_conditioned%message// &
                                   influence_hint//' (relative residual '// &
                                   rtoa(this%free_residual)//')')
                    if (nc > 0) error%message = error%message//among_free
                    return
                end if
            end if
            ! The contact elements see the free ones at x_F0: shift = S_r,C + K_CF x_F0.
            shift = [load%shear(this%contact), load%normal(this%contact)]
            if (nc > 0) then
                s%free_dd = kept%dd
                call s%multiply(spread(0.0_wp, 1, 2 * nc), shift)
                s%free_dd = 0.0_wp
            end if
        end select
    end subroutine distributed_load_contact

    !> The free DDs x_F0 + the correction the last reduced solve left (the contact DDs'
    !> share), checked against the free rows.
    subroutine distributed_complete(this, medium, load, x_contact, kept, ds, dn, record, &
                                    error)
        class(distributed_operator), intent(inout) :: this
        type(elastic_medium), intent(in) :: medium
        type(elastic_load), intent(in) :: load
        real(wp), intent(in) :: x_contact(:)
        type(free_part), intent(in) :: kept
        real(wp), intent(out) :: ds(:), dn(:)
        type(solver_record), intent(inout) :: record
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: x_free(2 * this%nf)

        x_free = kept%dd
        if (this%nc == 0) then
            record%counts%flops = this%flops
            record%equilibrium_residual = this%free_residual
        else
            ds(this%contact) = x_contact(1:this%nc)
            dn(this%contact) = x_contact(this%nc + 1:)
            if (this%nf > 0) then
                select type (s => this%stiffness)
                type is (distributed_stiffness)
                    x_free = x_free + s%free_dd
                    record%equilibrium_residual = max(record%equilibrium_residual, &
                        free_residual(s, x_contact, x_free, free_values(this, medium, load)))
                end select
            end if
        end if
        ds(this%free) = x_free(1::2)
        dn(this%free) = x_free(2::2)
    end subroutine distributed_complete

    !> The given values of the free rows, ordered as the operator's free unknowns.
    function free_values(this, medium, load) result(b_free)
        type(distributed_operator), intent(in) :: this
        type(elastic_medium), intent(in) :: medium
        type(elastic_load), intent(in) :: load
        real(wp) :: b_free(2 * this%nf)
        real(wp) :: given(2 * this%nf)

        given = given_values(medium%elements, this%shear_row, this%normal_row, load%shear, &
                             load%normal, this%free)
        b_free(1::2) = given(1:this%nf)
        b_free(2::2) = given(this%nf + 1:)
    end function free_values

    !> The distributed matrices are freed with the operator.
    subroutine distributed_release(this)
        class(distributed_operator), intent(inout) :: this

        if (allocated(this%stiffness)) deallocate (this%stiffness)
    end subroutine distributed_release

    !> ||K_F,: x - b_F|| / ||b_F||: the free rows against the unfactored system (collective).
    function free_residual(stiffness, x_contact, x_free, b_free) result(residual)
        type(distributed_stiffness), intent(in) :: stiffness
        real(wp), intent(in) :: x_contact(:), x_free(:), b_free(:)
        real(wp) :: residual
        real(wp), allocatable :: x(:), y(:)

        allocate (x(stiffness%system%columns), y(stiffness%system%rows), source=0.0_wp)
        x(stiffness%contact_unknowns) = x_contact
        x(stiffness%free_unknowns) = x_free
        call multiply_whole(stiffness%context, stiffness%system, x, y)
        residual = norm2(y(stiffness%free_unknowns) - b_free) / max(norm2(b_free), tiny(1.0_wp))
    end function free_residual

end module ddc_parallel_solve
