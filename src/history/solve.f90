!> Incremental quasi-static loading along a load path (docs/theory/earth.md#loading-histories).
!>
!> The influence matrix is assembled and the TWODD-style elements condensed out once (or,
!> with &solver matrix = 'hierarchical', compressed: ddc_solve_hierarchical_stiffness, for
!> models of contact elements alone, by the Newton method); every
!> step is then one contact solve (ddc_contact_formulation, with &solver lcp_method and its
!> fallbacks, as a one-shot solve) for the step's load and the total slip of the step
!> before, with one dense stiffness operator and a contact_session that the steps share:
!> the Newton method starts from the previous step's states and reuses the operator's
!> factorization (two triangular solves when no state changes, a low-rank update when a few
!> do); Lemke builds the paper's LCP (one inverse of A) the first time it is needed and
!> starts from its previous basis. Every
!> step is certified and checked for equilibrium; a step that fails is an error naming the
!> step, and nothing is returned as a result. A step where the first method fails and the
!> other one solves it is recorded (/history method and fallback).
!>
!> Each step records DDs, states, tractions and the stress intensity factors of the tips
!> (found once; by the higher-order re-solve where it serves, assembled once:
!> docs/theory/tips.md#k-along-a-loading-history). The last step's element results, tips
!> and fields are those of finish_model (ddc_run_model) for the model at the last load.
!> Incremental quasi-static loading along a load path (docs/theory/earth.md#loading-histories):
!> a loop of steps of one contact run (ddc_run_contact_run). The run is prepared once (the
!> influence matrix assembled and the TWODD-style elements condensed out, or with &solver
!> matrix = 'hierarchical' compressed, for models of contact elements alone, by the Newton
!> method); every step is one contact solve for the step's load from the total slip and the
!> strengths in force the step before left, with the methods and fallbacks of a one-shot
!> solve, on the session the steps share: the Newton method starts from the previous step's
!> states and reuses its factors (two triangular solves when no state changes, a low-rank
!> update when a few do); Lemke builds the paper's LCP (one inverse of A) the first time it
!> is needed and starts from its previous basis. Every step is certified and checked for
!> equilibrium with one stress scale, that of the largest load; a step that fails is an
!> error naming the step, and nothing is returned as a result. A step where the first
!> method fails and the other one solves it is recorded (/history method and fallback).
!>
!> Each step records DDs, states, tractions and the stress intensity factors of the tips
!> (found once; by the run's K method: docs/theory/tips.md#k-along-a-loading-history). The
!> last step's element results, tips and fields are those of finish_model (ddc_run_model)
!> for the model at the last load.
module ddc_history_solve
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, condition_contact, has_sources
    use ddc_model_results, only: model_results, history_record, element_results, &
        solver_record
    use ddc_model_records, only: lay_out_history
    use ddc_model_restart, only: restart_state
    use ddc_model_medium, only: medium_of
    use ddc_contact_result, only: contact_result
    use ddc_contact_fault_law, only: fault_law
    use ddc_solve_joints, only: elastic_dds
    use ddc_model_element_laws, only: strengths_change
    use ddc_solve_operator, only: elastic_load
    use ddc_post_tips, only: find_tips
    use ddc_history_path, only: path_loads, path_times, apply_load, load_text
    use ddc_flow_injection, only: pressure_history
    use ddc_flow_lubrication, only: lubrication_flow, along_flux, element_values
    use ddc_history_coupled_flow, only: start_coupled_flow, coupled_flow_step, response_cache
    use ddc_history_fronts, only: record_fronts, report_jumps
    use ddc_run_contact_run, only: contact_run, contact_step
    use ddc_run_model, only: finish_model, model_load
    use ddc_progress, only: report_progress
    use ddc_text, only: itoa, seconds_text
    use ddc_allocation, only: allocation_failed, real_bytes
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: solve_history

    !> Sums over the steps of a history: counts, time, fallbacks.
    type :: step_totals
        integer :: pivots = 0, solves = 0, iterations = 0, fallbacks = 0, first_fallback = 0
        integer :: steps = 0
        real(wp) :: seconds_factorization = 0.0_wp, flops = 0.0_wp
        !> Clock count at the first step
        integer(int64) :: t0 = 0
    contains
        procedure :: add => add_step
        procedure :: record => record_totals
    end type step_totals

contains

    !> Solve a model along its load path; results hold the last step and the history.
    !> On success the model's remote stress, gradients and pore pressure p0 are those of
    !> the last step (the state /elements and the fields describe).
    subroutine solve_history(model, results, error, max_pivots, max_iterations, restart)
        !> A validated model with a load path and at least one contact element
        type(model_type), intent(inout) :: model
        !> The last step's element results, tips and fields, and every step's history
        type(model_results), intent(out) :: results
        !> Allocated when a step fails (exit_solver_failure, naming the step) or the model
        !> has no path or no contact element (exit_bad_input)
        type(error_type), allocatable, intent(out) :: error
        !> Pivot limit of each Lemke solve (tests; default that of solve_lcp_lemke)
        integer, intent(in), optional :: max_pivots
        !> Iteration limit of each Newton solve (tests; default that of solve_contact)
        integer, intent(in), optional :: max_iterations
        !> The end of an earlier run of the model along the first steps of its path to go on
        !> from (--resume; docs/theory/earth.md#what-a-step-hands-on): its steps are kept, the next
        !> ones start from its friction memory and the strengths in force at its end
        type(restart_state), intent(in), optional :: restart
        type(contact_run), target :: run
        type(contact_step) :: solution
        type(history_record) :: h
        type(step_totals) :: totals
        type(element_results) :: solved
        real(wp), allocatable :: loads(:, :), times(:), flow_pressure(:, :), volume(:)
        real(wp), allocatable :: ds_before(:)
        type(lubrication_flow) :: flow
        type(response_cache) :: responses
        logical :: coupled
        real(wp) :: sigma0, scale
        integer :: n, k, nsteps, done
        integer(int64) :: t_start, t1, rate

        call check_path(model, error)
        if (allocated(error)) return
        call system_clock(t_start, rate)
        n = model%elements%n
        loads = path_loads(model%load_path)
        nsteps = size(loads, 2)
        if (allocated(model%load_path%time)) times = path_times(model%load_path)
        coupled = model%fluid%active
        if (coupled) then
            ! Found step by step, with the contact solution (coupled_flow_step).
            allocate (flow_pressure(n, nsteps), source=0.0_wp)
            allocate (volume(nsteps), source=0.0_wp)
        else if (has_sources(model)) then
            allocate (flow_pressure(n, nsteps), volume(nsteps))
            call pressure_history(model, times, flow_pressure, volume, error)
            if (allocated(error)) return
        end if
        if (coupled .and. present(restart)) then
            call set_error(error, exit_bad_input, '--resume: a run of coupled flow (&fluid) '// &
                           'cannot be resumed (the file does not hold the fluid''s state)')
            return
        end if
        call run%prepare(medium_of(model), model%solver, error)
        if (allocated(error)) return
        call run%take_steps(max_pivots, max_iterations)
        ! One stress scale for every step's certificate: that of the largest load (with
        ! coupled flow, unknown before the step: each step takes its own).
        if (.not. coupled) then
            sigma0 = 0.0_wp
            do k = 1, nsteps
                call run%stress_scale_of(load_at(k), scale, error)
                if (allocated(error)) return
                sigma0 = max(sigma0, scale)
            end do
            call run%set_stress_scale(sigma0)
        end if
        ! The tips, found once (their geometry); their K at every step.
        call find_tips(run%medium, spread(0.0_wp, 1, n), spread(0.0_wp, 1, n), results%tips)
        done = 0
        if (present(restart)) call resume_steps(run, restart, nsteps, h, done, error)
        if (.not. allocated(error)) call allocate_history(h, n, results%tips%n, nsteps, &
            done, strengths_change(model%elements, model%solver), error)
        if (.not. allocated(error)) call lay_out_time(h, model, n, nsteps, done, error)
        if (allocated(error)) return
        h%load = loads
        if (allocated(times)) h%time = times
        if (allocated(volume) .and. .not. coupled) then
            h%pressure = flow_pressure
            h%injected_volume = volume
        end if
        if (coupled) then
            call start_coupled_flow(run, model, load_at(1), times(1), flow, error)
            if (allocated(error)) return
            allocate (ds_before(n), source=0.0_wp)
        end if
        call system_clock(totals%t0)
        do k = done + 1, nsteps
            if (coupled) then
                call coupled_flow_step(run, load_at(k), times(k), flow, ds_before, solution, &
                                       h%flow_iterations(k), h%flow_residual(k), error, &
                                       responses)
                if (.not. allocated(error)) call record_flow(k)
            else
                call run%step(load_at(k), solution, error)
            end if
            if (allocated(error)) then
                error%message = 'loading history: step '//itoa(k)//' of '//itoa(nsteps)// &
                    ' ('//step_text(k)//') failed: '// &
                    error%message//'; no result is written'
                return
            end if
            call record_step(run, load_at(k), solution, k, h, solved, error)
            if (allocated(error)) return
            if (allocated(volume)) call record_fronts(model, run%medium%shear_modulus, k, h)
            if (allocated(volume)) call report_jumps(model, times, k, h)
            call totals%add(solution%contact, k)
            call run%tip_k(load_at(k), solved, model%growth%active, results%tips, &
                           h%k1(:, k), h%k2(:, k))
            call system_clock(t1)
            call report_progress(step_line(k, nsteps, step_text(k), solution%contact, &
                                           real(t1 - t_start, wp) / real(rate, wp)))
        end do

        ! The last step: tractions, face displacements, tips and fields for its DDs.
        model = apply_load(model, loads(:, nsteps))
        results%solver = run%record_of(solution)
        call move_alloc(solved%ds, results%elements%ds)
        call move_alloc(solved%dn, results%elements%dn)
        call move_alloc(solved%state, results%elements%state)
        call in_force_of(run, results%elements)
        call run%k_memory(results%elements%ds, results%elements%ds_k_memory)
        call finish_model(model, load_at(nsteps), results, run=run)
        call totals%record(h, solution%contact, results%solver)
        if (allocated(run%operator%load_map)) call record_elastic_dds()
        results%history = h
        call run%finish()
        call system_clock(t1)
        results%solver%seconds_total = real(t1 - t_start, wp) / real(rate, wp)

    contains

        !> Step j's flow: its pressure (which loads the step from now on), apertures, fluxes
        !> and volumes.
        subroutine record_flow(j)
            integer, intent(in) :: j

            flow_pressure(:, j) = element_values(flow, flow%p, n, 0.0_wp)
            h%pressure(:, j) = flow_pressure(:, j)
            h%aperture(:, j) = element_values(flow, flow%aperture, n, 0.0_wp)
            h%flux(:, j) = element_values(flow, along_flux(flow), n, 0.0_wp)
            h%injected_volume(j) = sum(flow%sources%volume)
            h%stored_volume(j) = sum(flow%stored) - flow%stored_initial
            h%leaked_volume(j) = flow%leaked
            h%fluid_efficiency(j) = 0.0_wp
            if (h%injected_volume(j) /= 0.0_wp) h%fluid_efficiency(j) = &
                h%stored_volume(j) / h%injected_volume(j)
            ds_before = solution%ds
        end subroutine record_flow

        !> 'sxy = 10' or 't = 2.5 s, sxy = 10': what step j is.
        function step_text(j) result(text)
            integer, intent(in) :: j
            character(len=:), allocatable :: text

            if (allocated(times)) then
                text = load_text(loads(:, j), model%load_path%varies, times(j), &
                                 model%time_unit)
            else
                text = load_text(loads(:, j), model%load_path%varies)
            end if
        end function step_text

        !> The load of step j.
        type(elastic_load) function load_at(j)
            integer, intent(in) :: j

            type(model_type) :: loaded

            loaded = apply_load(model, loads(:, j))
            ! The pressure that diffused from the sources acts inside the contact elements.
            if (allocated(flow_pressure)) loaded%elements%flow_pressure = flow_pressure(:, j)
            load_at = model_load(loaded)
        end function load_at

        !> The elastic DDs of the joints at the last step (0 on the other elements).
        subroutine record_elastic_dds()
            type(fault_law) :: law
            type(elastic_load) :: last

            law = run%law_in_force()
            last = load_at(nsteps)
            associate (e => results%elements)
                allocate (e%ds_elastic(n), e%dn_elastic(n))
                call elastic_dds(law%joint_compliance(), last%pressure, e%shear_traction, &
                                 e%normal_traction, e%ds_elastic, e%dn_elastic)
                where (model%elements%condition /= condition_contact)
                    e%ds_elastic = 0.0_wp
                    e%dn_elastic = 0.0_wp
                end where
            end associate
        end subroutine record_elastic_dds

    end subroutine solve_history

    !> Room for the columns of a time axis and of the fluid sources, where the model has
    !> them (the first `kept` steps kept).
    subroutine lay_out_time(h, model, n, nsteps, kept, error)
        type(history_record), intent(inout) :: h
        type(model_type), intent(in) :: model
        integer, intent(in) :: n, nsteps, kept
        type(error_type), allocatable, intent(out) :: error
        integer :: stat

        if (.not. allocated(model%load_path%time)) return
        if (has_sources(model)) then
            call lay_out_history(h, n, size(h%k1, 1), nsteps, kept, stat, time=.true., &
                                 fractures=size(model%fractures), coupled=model%fluid%active)
        else
            call lay_out_history(h, n, size(h%k1, 1), nsteps, kept, stat, time=.true.)
        end if
        if (stat /= 0) call allocation_failed(error, 'the flow history of '//itoa(n)// &
                                              ' elements at '//itoa(nsteps)//' steps', &
                                              real_bytes * real(n, wp) * real(nsteps, wp))
    end subroutine lay_out_time

    !> A load path needs contact elements (without them the response is elastic).
    subroutine check_path(model, error)
        type(model_type), intent(in) :: model
        type(error_type), allocatable, intent(out) :: error

        if (.not. allocated(model%load_path%vertex)) then
            call set_error(error, exit_bad_input, 'loading history: the model has no load path')
        else if (.not. any(model%elements%condition == condition_contact)) then
            call set_error(error, exit_bad_input, 'loading history: a load path needs '// &
                'contact elements (without them the response is elastic: superpose)')
        end if
    end subroutine check_path

    !> The first `done` steps of an earlier run, and its memory at their end as the run's:
    !> the slip of the contact elements, the strengths in force and the slip path (the sum of
    !> the slip increments, as the steps added it up).
    subroutine resume_steps(run, restart, nsteps, h, done, error)
        type(contact_run), intent(inout) :: run
        type(restart_state), intent(in) :: restart
        integer, intent(in) :: nsteps
        type(history_record), intent(out) :: h
        integer, intent(out) :: done
        type(error_type), allocatable, intent(out) :: error
        type(fault_law) :: law
        integer :: j

        associate (old => restart%results%history, e => restart%results%elements)
            done = size(old%pivots)
            if (done >= nsteps) then
                call set_error(error, exit_bad_input, '--resume: the earlier run ended '// &
                    'at the end of this load path: nothing is left to do; extend '// &
                    '&load_path to go on')
                return
            end if
            law = run%law_in_force()
            if (law%has_joints()) then
                ! The memory of elastic joints is their plastic slip, which the file does
                ! not hold.
                call set_error(error, exit_bad_input, '--resume: a loading history of '// &
                    'elastic joints (shear_stiffness, normal_stiffness) cannot be resumed')
                return
            end if
            h = old
            law%sf_in_force = e%sf_in_force
            law%tensile_in_force = e%tensile_in_force
            law%mu_in_force = e%mu_in_force
            law%slip_path = abs(old%ds(:, 1))
            do j = 2, done
                law%slip_path = law%slip_path + abs(old%ds(:, j) - old%ds(:, j - 1))
            end do
            call run%hold(e%ds, law)
            if (allocated(e%ds_k_memory)) call run%hold_k_memory(e%ds_k_memory)
        end associate
    end subroutine resume_steps

    !> Step k's DDs, states, tractions, strengths in force and solver record into h; solved
    !> is the step's element results for the tips' K (the friction in force where recorded).
    subroutine record_step(run, load, solution, k, h, solved, error)
        type(contact_run), intent(in) :: run
        type(elastic_load), intent(in) :: load
        type(contact_step), intent(in) :: solution
        integer, intent(in) :: k
        type(history_record), intent(inout) :: h
        type(element_results), intent(out) :: solved
        type(error_type), allocatable, intent(out) :: error
        type(fault_law) :: law

        associate (res => solution%contact)
            h%ds(:, k) = solution%ds
            h%dn(:, k) = solution%dn
            h%state(:, k) = solution%state
            h%equilibrium_residual(k) = solution%record%equilibrium_residual
            h%pivots(k) = res%pivots
            h%newton_iterations(k) = res%iterations
            h%method(k) = res%method
            h%fallback(k) = res%fallback
            h%certificate_min_z(k) = res%certificate%min_z
            h%certificate_min_w(k) = res%certificate%min_w
            h%certificate_max_complementarity(k) = res%certificate%max_complementarity
        end associate
        ! Tractions S_r + A D: the contact solution's, the free elements' from their rows.
        call run%free_tractions(load, solution, h%shear_traction(:, k), &
                                h%normal_traction(:, k), error)
        if (allocated(error)) return
        solved%ds = solution%ds
        solved%dn = solution%dn
        solved%state = solution%state
        solved%shear_traction = h%shear_traction(:, k)
        solved%normal_traction = h%normal_traction(:, k)
        if (allocated(h%mu_in_force)) then
            ! The strengths in force as the step's solve leaves them (0 off the contact
            ! elements).
            law = run%law_in_force()
            h%mu_in_force(:, k) = law%mu_in_force
            h%sf_in_force(:, k) = law%sf_in_force
            h%tensile_strength_in_force(:, k) = law%tensile_in_force
            solved%mu_in_force = law%mu_in_force
        end if
    end subroutine record_step

    !> The strengths in force the run's steps left (0 off the contact elements).
    pure subroutine in_force_of(run, elements)
        type(contact_run), intent(in) :: run
        type(element_results), intent(inout) :: elements
        type(fault_law) :: law

        law = run%law_in_force()
        elements%sf_in_force = law%sf_in_force
        elements%tensile_in_force = law%tensile_in_force
        elements%mu_in_force = law%mu_in_force
    end subroutine in_force_of

    !> Add step k's counts.
    subroutine add_step(totals, res, k)
        class(step_totals), intent(inout) :: totals
        type(contact_result), intent(in) :: res
        integer, intent(in) :: k

        totals%pivots = totals%pivots + res%pivots
        totals%solves = totals%solves + res%solves
        totals%iterations = totals%iterations + res%iterations
        totals%seconds_factorization = totals%seconds_factorization + res%counts%seconds
        totals%flops = totals%flops + res%counts%flops
        totals%steps = k
        if (len(res%fallback) > 0) then
            totals%fallbacks = totals%fallbacks + 1
            if (totals%first_fallback == 0) totals%first_fallback = k
        end if
    end subroutine add_step

    !> The run's solver record from the totals of its steps (the last step's res counted in
    !> record already), with a line on the steps that fell back.
    subroutine record_totals(totals, h, last, record)
        class(step_totals), intent(in) :: totals
        type(history_record), intent(in) :: h
        type(contact_result), intent(in) :: last
        type(solver_record), intent(inout) :: record
        integer(int64) :: t1, rate

        call system_clock(t1, rate)
        record%counts%seconds = record%counts%seconds + totals%seconds_factorization - &
            last%counts%seconds
        record%counts%flops = record%counts%flops + totals%flops - last%counts%flops
        record%pivots = totals%pivots
        record%lcp_solves = totals%solves
        record%newton_iterations = totals%iterations
        record%seconds_lcp = real(t1 - totals%t0, wp) / real(rate, wp) - &
            totals%seconds_factorization
        record%equilibrium_residual = maxval(h%equilibrium_residual)
        record%fallback = ''
        if (totals%fallbacks > 0) record%fallback = itoa(totals%fallbacks)//' of '// &
            itoa(totals%steps)//' steps fell back to the other method; the first, step '// &
            itoa(totals%first_fallback)//': '//trim(h%fallback(totals%first_fallback))
    end subroutine record_totals

    !> Room for every step of a history of n elements and tips tips, the first `kept` steps
    !> of h kept (a resumed run's), with the strengths in force when asked for; error: it
    !> does not fit.
    subroutine allocate_history(h, n, tips, k, kept, strengths, error)
        type(history_record), intent(inout) :: h
        integer, intent(in) :: n, tips, k, kept
        logical, intent(in) :: strengths
        type(error_type), allocatable, intent(out) :: error
        integer :: stat

        call lay_out_history(h, n, tips, k, kept, stat, strengths=strengths)
        if (stat /= 0) call allocation_failed(error, 'the history of '//itoa(n)// &
                                              ' elements at '//itoa(k)//' steps', &
                                              real_bytes * merge(8.0_wp, 5.0_wp, strengths) &
                                              * real(n, wp) * real(k, wp))
    end subroutine allocate_history

    !> 'step 12 of 101 (sxy = 10): newton, 1 iteration, 0.53 s' (the time since the start);
    !> 'newton, 9 iterations in 3 solves' where the strength fixed point (slip weakening,
    !> strength loss) solved more than once.
    function step_line(k, nsteps, what, res, seconds) result(line)
        integer, intent(in) :: k, nsteps
        !> What the step is (load_text)
        character(len=*), intent(in) :: what
        real(wp), intent(in) :: seconds
        type(contact_result), intent(in) :: res
        character(len=:), allocatable :: line

        line = 'step '//itoa(k)//' of '//itoa(nsteps)//' ('//what//'): '//res%method
        if (res%method == 'newton') then
            line = line//', '//itoa(res%iterations)//' iteration'
            if (res%iterations /= 1) line = line//'s'
        else
            line = line//', '//itoa(res%pivots)//' pivot'
            if (res%pivots /= 1) line = line//'s'
        end if
        if (res%solves > 1) line = line//' in '//itoa(res%solves)//' solves'
        if (len(res%fallback) > 0) line = line//' (fell back: '//res%fallback//')'
        line = line//', '//seconds_text(seconds)
    end function step_line

end module ddc_history_solve
