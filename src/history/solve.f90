!> Incremental quasi-static loading along a load path (SPEC-EARTH section 3).
!>
!> The influence matrix is assembled, the TWODD-style elements condensed out and the LCP
!> matrix M built once (one inverse of A); every step changes q only: its load and the
!> total slip of the previous step. Each step is solved by Lemke's method (the active-set
!> Newton method stays a one-shot solver), warm-started from the previous step's basis
!> when that basis is still feasible (0 pivots), certified and checked for equilibrium.
!> A step that fails is an error naming the step; nothing is returned as a result.
!>
!> The last step's element results, tips and fields are those of run_model for the model
!> at the last load with every element's DDs prescribed (condition_prescribed_dd), so that
!> field evaluation is shared with one-shot solves; states and the solver record are the
!> history's.
module ddc_history_solve
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, condition_contact, condition_prescribed_dd, &
        load_path_names
    use ddc_model_results, only: model_results, history_record
    use ddc_model_loads, only: resolve_remote_stress, total_pressure
    use ddc_contact_result, only: contact_result, contact_stress_scale
    use ddc_contact_paper_lcp, only: contact_lcp, build_contact_lcp, solve_contact_increment
    use ddc_solve_frictional, only: condensed_contact, condense_contact, contact_load, &
        complete_dds, record_contact
    use ddc_history_path, only: path_loads, apply_load
    use ddc_run_model, only: run_model
    use ddc_model_loads, only: shear_modulus_of
    use ddc_text, only: itoa, rtoa
    implicit none
    private

    public :: solve_history

contains

    !> Solve a model along its load path; results hold the last step and the history.
    !> On success the model's remote stress, gradients and pore pressure p0 are those of
    !> the last step (the state /elements and the fields describe).
    subroutine solve_history(model, results, error, max_pivots)
        !> A validated model with a load path and at least one contact element
        type(model_type), intent(inout) :: model
        !> The last step's element results, tips and fields, and every step's history
        type(model_results), intent(out) :: results
        !> Allocated when a step fails (exit_solver_failure, naming the step) or the model
        !> has no path or no contact element (exit_bad_input)
        type(error_type), allocatable, intent(out) :: error
        !> Pivot limit of each Lemke solve (tests; default that of solve_lcp_lemke)
        integer, intent(in), optional :: max_pivots
        type(condensed_contact) :: sys
        type(contact_lcp) :: lcp
        type(contact_result) :: res, built
        type(model_type) :: at_load
        type(history_record) :: h
        real(wp), allocatable :: loads(:, :), shear(:, :), normal(:, :), shift(:, :)
        real(wp), allocatable :: y_load(:, :), pressure(:, :), sf_eff(:), ds_previous(:), v(:)
        integer, allocatable :: basis(:)
        integer :: n, nc, k, nsteps, pivots, solves
        real(wp) :: sigma0, seconds_lcp
        integer(int64) :: t_start, t0, t1, rate

        if (.not. allocated(model%load_path%vertex)) then
            call set_error(error, exit_bad_input, 'loading history: the model has no load path')
            return
        end if
        if (.not. any(model%elements%condition == condition_contact)) then
            call set_error(error, exit_bad_input, 'loading history: a load path needs '// &
                'contact elements (without them the response is elastic: superpose)')
            return
        end if
        call system_clock(t_start, rate)
        n = model%elements%n
        call condense_contact(model%elements, shear_modulus_of(model), model%poissons_ratio, &
                              sys, results%solver, error)
        if (allocated(error)) return
        nc = sys%nc

        ! The load of every step on the contact elements, and the history's stress scale.
        loads = path_loads(model%load_path)
        nsteps = size(loads, 2)
        allocate (shear(n, nsteps), normal(n, nsteps), shift(2 * nc, nsteps), &
                  y_load(2 * sys%nf, nsteps), pressure(nc, nsteps))
        sigma0 = 0.0_wp
        do k = 1, nsteps
            call resolve_remote_stress(model%elements, loads(1, k), loads(2, k), loads(3, k), &
                                       shear(:, k), normal(:, k), loads(4:6, k))
            call contact_load(sys, model%elements, shear(:, k), normal(:, k), shift(:, k), &
                              y_load(:, k))
            v = total_pressure(model%elements, [loads(7, k), model%pore_fluid(2)])
            pressure(:, k) = v(sys%contact)
            sigma0 = max(sigma0, contact_stress_scale(shift(1:nc, k), shift(nc + 1:, k), &
                model%elements%sf(sys%contact), pressure(:, k)))
        end do

        call build_contact_lcp(sys%a, model%elements%mu(sys%contact), lcp, built, error)
        if (allocated(error)) return

        allocate (h%ds(n, nsteps), h%dn(n, nsteps), h%state(n, nsteps), h%pivots(nsteps), &
                  h%certificate_min_z(nsteps), h%certificate_min_w(nsteps), &
                  h%certificate_max_complementarity(nsteps), h%equilibrium_residual(nsteps))
        h%load = loads
        sf_eff = model%elements%sf(sys%contact)
        allocate (ds_previous(nc), basis(3 * nc))
        ds_previous = 0.0_wp
        basis = 0
        pivots = 0
        solves = 0
        call system_clock(t0, rate)
        do k = 1, nsteps
            call solve_contact_increment(lcp, shift(1:nc, k), shift(nc + 1:, k), sf_eff, &
                                         pressure(:, k), model%solver%open_cohesion, &
                                         ds_previous, sigma0, basis, res, error, max_pivots)
            if (allocated(error)) then
                error%message = 'loading history: step '//itoa(k)//' of '//itoa(nsteps)// &
                    ' ('//load_text(loads(:, k), model%load_path%varies)//') failed: '// &
                    error%message//'; no result is written'
                return
            end if
            ds_previous = res%ds
            pivots = pivots + res%pivots
            solves = solves + res%solves
            h%equilibrium_residual(k) = maxval(res%equilibrium_residual)
            call complete_dds(sys, model%elements, shear(:, k), normal(:, k), res, &
                              y_load(:, k), h%ds(:, k), h%dn(:, k), h%state(:, k), &
                              h%equilibrium_residual(k))
            h%pivots(k) = res%pivots
            h%certificate_min_z(k) = res%certificate%min_z
            h%certificate_min_w(k) = res%certificate%min_w
            h%certificate_max_complementarity(k) = res%certificate%max_complementarity
        end do
        call system_clock(t1)
        seconds_lcp = real(t1 - t0, wp) / real(rate, wp)

        ! The last step: tractions, face displacements, tips and fields for its DDs.
        at_load = apply_load(model, loads(:, nsteps))
        at_load%elements%condition = condition_prescribed_dd
        at_load%elements%bc_s = h%ds(:, nsteps)
        at_load%elements%bc_n = h%dn(:, nsteps)
        call finish_last_step(at_load, results, error)
        if (allocated(error)) return
        results%elements%state = h%state(:, nsteps)
        call record_contact(res, sys%flops, results%solver)
        results%solver%seconds_factorization = results%solver%seconds_factorization + &
            built%seconds_factorization
        results%solver%factorization_flops = results%solver%factorization_flops + &
            built%factorization_flops
        results%solver%pivots = pivots
        results%solver%lcp_solves = solves
        results%solver%seconds_lcp = seconds_lcp
        results%solver%equilibrium_residual = maxval(h%equilibrium_residual)
        results%history = h
        model = apply_load(model, loads(:, nsteps))
        call system_clock(t1)
        results%solver%seconds_total = real(t1 - t_start, wp) / real(rate, wp)
    end subroutine solve_history

    !> run_model on the model with prescribed DDs: its element results, tips and fields
    !> go into results; the solver record keeps the history's assembly and factorization
    !> times and adds the field time.
    subroutine finish_last_step(at_load, results, error)
        type(model_type), intent(in) :: at_load
        type(model_results), intent(inout) :: results
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: last

        call run_model(at_load, last, error)
        if (allocated(error)) return
        results%elements = last%elements
        results%tips = last%tips
        call move_alloc(last%fields, results%fields)
        results%solver%threads = last%solver%threads
        results%solver%seconds_fields = last%solver%seconds_fields
    end subroutine finish_last_step

    !> 'sxy = 10, p0 = 3' for the quantities a path varies (all seven when none is marked).
    function load_text(load, varies) result(text)
        real(wp), intent(in) :: load(:)
        logical, intent(in) :: varies(:)
        character(len=:), allocatable :: text
        integer :: i

        text = ''
        do i = 1, size(load)
            if (.not. varies(i) .and. any(varies)) cycle
            if (len(text) > 0) text = text//', '
            text = text//trim(load_path_names(i))//' = '//rtoa(load(i))
        end do
    end function load_text

end module ddc_history_solve
