!> An earthquake-cycle run (docs/earthquake-cycles.md, docs/theory/cycles.md): the model's
!> rate-and-state elements on one contact run, whose elastic operator (dense or
!> hierarchical) is prepared once and gives the products; slip and state advanced by an
!> embedded Runge-Kutta pair with error control from time 0 (or where an earlier run
!> stopped: --resume) to end_time; rows recorded at the output cadence, events catalogued,
!> progress reported, and the result file written every checkpoint_interval seconds by the
!> caller's writer. Where an effective normal stress reaches zero (or no step can advance
!> the time) the run stops: the writer keeps what was computed, and the error says which
!> element, when.
module ddc_cycle_driver
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure, exit_bad_input
    use ddc_text, only: itoa, short_real, allocated_text
    use ddc_model_types, only: model_type, condition_rate_state, condition_contact
    use ddc_model_cycles, only: cycle_record, cycle_end_time, cycle_normal_stress, &
        cycle_step_size
    use ddc_model_results, only: model_results, state_slip
    use ddc_model_medium, only: elastic_medium, medium_of
    use ddc_model_loads, only: shear_modulus_of
    use ddc_model_rate_state, only: rate_state_table, rate_state_count, rs_v_init
    use ddc_solve_operator, only: elastic_load
    use ddc_run_contact_run, only: contact_run
    use ddc_run_model, only: finish_model, wall_seconds
    use ddc_progress, only: report_progress
    use ddc_cycle_fault, only: rate_state_fault, new_fault
    use ddc_cycle_runge_kutta, only: embedded_pair, dormand_prince, attempt_step, next_step
    use ddc_cycle_stations, only: station_set, new_stations
    use ddc_cycle_record, only: new_record, add_row, add_event, recorded_slip_rows
    implicit none
    private

    public :: run_cycles, cycle_writer

    !> Wall-clock seconds between two progress lines
    real(wp), parameter :: progress_seconds = 10.0_wp
    !> Rejected steps in a row after which the time cannot advance
    integer, parameter :: rejection_limit = 200

    abstract interface
        !> Write the result file of a model and its results so far (a checkpoint, or the run
        !> that stopped).
        subroutine cycle_writer(model, results, error)
            import :: model_type, model_results, error_type
            implicit none
            !> The model
            type(model_type), intent(in) :: model
            !> Its results
            type(model_results), intent(in) :: results
            !> Set when the file cannot be written
            type(error_type), allocatable, intent(out) :: error
        end subroutine cycle_writer
    end interface

    !> What the loop of a run shares.
    type :: cycle_loop
        !> The contact run (its operator) and the fault on it
        type(contact_run) :: run
        type(rate_state_fault) :: fault
        !> The pair and its work space (n, stages)
        type(embedded_pair) :: pair
        real(wp), allocatable :: stages(:, :)
        !> State [slip; psi], its rate, the error scale of each component, shape (2 m)
        real(wp), allocatable :: y(:), first(:), scale(:)
        !> The observation points
        type(station_set) :: stations
        !> The place of each recorded element among the rate-and-state ones, shape (r)
        integer, allocatable :: recorded(:)
        !> The record (with where the run stands)
        type(cycle_record) :: record
        !> Wall-clock of the start, the last progress line and the last checkpoint [s]
        real(wp) :: started = 0.0_wp, reported = 0.0_wp, saved = 0.0_wp
    end type cycle_loop

contains

    !> Run the model's earthquake cycles to end_time, from time 0 or from the record of an
    !> earlier run of the same model (--resume).
    subroutine run_cycles(model, results, error, writer, restart)
        !> A validated cycle model (&cycle, rate-and-state elements alone)
        type(model_type), intent(in) :: model
        !> The results: the final state's element results, tips and fields, and /cycle
        type(model_results), intent(out) :: results
        !> Set when the run stopped before end_time, or its operator could not be made
        type(error_type), allocatable, intent(out) :: error
        !> Writes the result file: every checkpoint_interval, and when the run stops
        procedure(cycle_writer), optional :: writer
        !> The record of an earlier run to go on from
        type(cycle_record), intent(in), optional :: restart
        type(cycle_loop), target :: loop
        type(elastic_medium) :: medium
        type(error_type), allocatable :: failed
        integer :: lost, reason

        loop%started = wall_seconds()
        loop%reported = loop%started
        loop%saved = loop%started
        medium = medium_of(model)
        ! The rate-and-state elements are the operator's contact elements.
        where (medium%elements%condition == condition_rate_state) &
            medium%elements%condition = condition_contact
        call loop%run%prepare(medium, model%solver, error)
        if (allocated(error)) then
            call loop%run%finish()
            return
        end if
        call loop%run%operator%prepare_shear_products()
        call start(model, loop, error, restart)
        if (.not. allocated(error)) call integrate(model, loop, reason, lost, writer, error)
        if (allocated(error)) then
            call loop%run%finish()
            return
        end if
        loop%record%end_reason = reason
        if (reason == cycle_normal_stress) loop%record%end_element = loop%record%elements(lost)
        call fill_results(model, loop, results)
        if (reason /= cycle_end_time) then
            if (reason == cycle_normal_stress) then
                call set_error(error, exit_solver_failure, 'cycle: the effective normal '// &
                    'stress of element '//itoa(loop%record%elements(lost))//' reaches zero '// &
                    'at t = '//short_real(loop%record%now%time)//' '// &
                    allocated_text(model%time_unit)//' (rate-and-state friction needs it '// &
                    'positive); the result file keeps the run up to then')
            else
                call set_error(error, exit_solver_failure, 'cycle: no time step advances '// &
                    'the time at t = '//short_real(loop%record%now%time)//' '// &
                    allocated_text(model%time_unit)//' (the error control rejects every '// &
                    'step): the result file keeps the run up to then; a larger tolerance '// &
                    'may pass')
            end if
            if (present(writer)) then
                call writer(model, results, failed)
                if (allocated(failed)) error%message = error%message//'; but: '// &
                                                       failed%message
            end if
        end if
        call loop%run%finish()
    end subroutine run_cycles

    !> The fault, the points, the record and the state to start from: time 0, or the earlier
    !> run's end; the rate at the start. Error (bad input): an element whose initial values
    !> give no state (a sweep task's shear modulus may change the damping the input's check
    !> saw).
    subroutine start(model, loop, error, restart)
        type(model_type), intent(in) :: model
        type(cycle_loop), intent(inout), target :: loop
        type(error_type), allocatable, intent(out) :: error
        type(cycle_record), intent(in), optional :: restart
        real(wp), allocatable :: x(:), y(:), v_init(:)
        integer :: i, m, failure

        associate (op => loop%run%operator, c => model%cycle)
            m = op%nc
            loop%fault = new_fault(model%elements, op%contact, c, shear_modulus_of(model), op)
            allocate (x(0), y(0))
            if (allocated(model%observations)) then
                do i = 1, size(model%observations)
                    x = [x, model%observations(i)%x]
                    y = [y, model%observations(i)%y]
                end do
            end if
            loop%stations = new_stations(medium_of(model), op%contact, x, y)
            loop%pair = dormand_prince()
            allocate (loop%stages(2 * m, loop%pair%stages), loop%first(2 * m))
            ! Slip errors relative to L, state errors absolute (docs/theory/cycles.md#error-control)
            loop%scale = [loop%fault%dc, spread(1.0_wp, 1, m)]
            if (present(restart)) then
                loop%record = restart
                loop%y = [restart%now%slip, restart%now%state]
                loop%fault%v = restart%now%slip_rate
            else
                loop%record = new_record(model%elements, op%contact, c%profile_spacing, size(x))
                v_init = rate_state_column(model, op%contact)
                i = findloc((-loop%fault%tau0 - loop%fault%eta * v_init) * v_init > 0.0_wp, &
                            .false., 1)
                if (i > 0) then
                    call set_error(error, exit_bad_input, 'cycle: element '// &
                        itoa(op%contact(i))//': tau0 and v_init give no initial state with '// &
                        'the radiation damping '//short_real(loop%fault%eta)//' (-tau0 - '// &
                        'eta v_init must have the sign of v_init)')
                    return
                end if
                loop%y = loop%fault%initial(v_init)
                loop%record%now%step = 1.0e-3_wp * minval(loop%fault%dc / abs(v_init))
                loop%record%now%time = 0.0_wp
                loop%record%now%in_event = .false.
            end if
            loop%recorded = recorded_slip_rows(loop%record)
            call loop%fault%rates(loop%record%now%time, loop%y, loop%first, failure)
            if (.not. present(restart)) then
                loop%record%now%last_row = 0.0_wp
                call record_row(model, loop)
            end if
        end associate
    end subroutine start

    !> v_init of the rate-and-state elements `rows`, shape (m).
    pure function rate_state_column(model, rows) result(v)
        type(model_type), intent(in) :: model
        integer, intent(in) :: rows(:)
        real(wp) :: v(size(rows))
        real(wp) :: table(size(rows), rate_state_count)

        table = rate_state_table(model%elements, rows)
        v = table(:, rs_v_init)
    end function rate_state_column

    !> Advance from the record's time to end_time: steps accepted or rejected by the error
    !> control (a step where some effective normal stress would not be positive is
    !> rejected and quartered); events, rows, progress and checkpoints after every accepted
    !> step. reason: cycle_end_time, or why the run stopped (lost: the element).
    subroutine integrate(model, loop, reason, lost, writer, error)
        type(model_type), intent(in) :: model
        type(cycle_loop), intent(inout), target :: loop
        integer, intent(out) :: reason, lost
        procedure(cycle_writer), optional :: writer
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: snapshot
        real(wp), allocatable :: y_new(:), last(:)
        real(wp) :: h, norm, t
        integer :: failure, in_a_row

        lost = 0
        in_a_row = 0
        allocate (y_new(size(loop%y)), last(size(loop%y)))
        associate (c => model%cycle, now => loop%record%now, record => loop%record)
            do while (now%time < c%end_time)
                t = now%time
                h = min(now%step, c%end_time - t)
                call attempt_step(loop%pair, loop%fault, t, loop%y, loop%first, h, &
                                  loop%scale, c%tolerance, y_new, last, norm, failure, &
                                  loop%stages)
                if (failure > 0 .or. norm > 1.0_wp) then
                    record%rejected = record%rejected + 1
                    in_a_row = in_a_row + 1
                    if (failure > 0) then
                        lost = failure
                        now%step = 0.25_wp * h
                    else
                        now%step = next_step(loop%pair, h, norm)
                    end if
                    if (t + now%step > t .and. in_a_row < rejection_limit) cycle
                    reason = cycle_step_size
                    if (failure > 0) reason = cycle_normal_stress
                    return
                end if
                in_a_row = 0
                if (h == c%end_time - t) then
                    now%time = c%end_time
                else
                    now%time = t + h
                end if
                loop%y = y_new
                loop%first = last
                record%steps = record%steps + 1
                now%step = next_step(loop%pair, h, norm)
                call after_step(model, loop)
                if (present(writer) .and. c%checkpoint_interval > 0.0_wp) then
                    if (wall_seconds() - loop%saved >= c%checkpoint_interval) then
                        call fill_results(model, loop, snapshot)
                        call writer(model, snapshot, error)
                        if (allocated(error)) return
                        loop%saved = wall_seconds()
                    end if
                end if
            end do
        end associate
        reason = cycle_end_time
    end subroutine integrate

    !> After an accepted step: the event that starts, goes on or ends, the row when due,
    !> the progress line.
    subroutine after_step(model, loop)
        type(model_type), intent(in) :: model
        type(cycle_loop), intent(inout), target :: loop
        real(wp) :: vmax, interval
        integer :: imax
        logical :: seismic, due

        associate (c => model%cycle, now => loop%record%now, f => loop%fault, m => loop%fault%m)
            imax = maxloc(abs(f%v), 1)
            vmax = abs(f%v(imax))
            seismic = vmax >= c%seismic_threshold
            due = .false.
            if (seismic .and. .not. now%in_event) then
                now%in_event = .true.
                now%event_start = now%time
                now%event_element = imax
                now%event_peak_rate = vmax
                now%event_start_slip = loop%y(:m)
                due = .true.
                call report_progress('cycle: event '//itoa(loop%record%events + 1)// &
                    ' starts at t = '//short_real(now%time)//' '// &
                    allocated_text(model%time_unit)//' on element '// &
                    itoa(loop%record%elements(imax)))
            else if (now%in_event) then
                now%event_peak_rate = max(now%event_peak_rate, vmax)
                if (.not. seismic) then
                    call end_event(model, loop)
                    due = .true.
                end if
            end if
            interval = c%output_interval
            if (seismic) interval = c%event_output_interval
            due = due .or. now%time - now%last_row >= interval .or. now%time >= c%end_time
            if (due) call record_row(model, loop)
            if (wall_seconds() - loop%reported >= progress_seconds) then
                loop%reported = wall_seconds()
                call report_progress('cycle: t = '//short_real(now%time)//' '// &
                    allocated_text(model%time_unit)//', step '//itoa(loop%record%steps)// &
                    ', largest slip rate '//short_real(vmax)//', events '// &
                    itoa(loop%record%events))
            end if
        end associate
    end subroutine after_step

    !> Catalogue the event that ends now.
    subroutine end_event(model, loop)
        type(model_type), intent(in) :: model
        type(cycle_loop), intent(inout), target :: loop
        real(wp) :: slip(loop%fault%m)

        associate (now => loop%record%now, m => loop%fault%m, e => model%elements, &
                   rows => loop%record%elements)
            slip = loop%y(:m) - now%event_start_slip
            call add_event(loop%record, now%event_start, now%time, rows(now%event_element), &
                           e%x_mid(rows(now%event_element)), e%y_mid(rows(now%event_element)), &
                           now%event_peak_rate, maxval(abs(slip)), shear_modulus_of(model) * &
                           sum(abs(slip) * 2.0_wp * e%half_length(rows)), &
                           slip(loop%recorded))
            now%in_event = .false.
            call report_progress('cycle: event '//itoa(loop%record%events)//' ends at t = '// &
                short_real(now%time)//' '//allocated_text(model%time_unit)//', largest slip '// &
                short_real(maxval(abs(slip))))
        end associate
    end subroutine end_event

    !> Record a row at the current time (the fault's last evaluation is of this state).
    subroutine record_row(model, loop)
        type(model_type), intent(in) :: model
        type(cycle_loop), intent(inout), target :: loop
        real(wp) :: ux(loop%stations%p), uy(loop%stations%p), vx(loop%stations%p), &
            vy(loop%stations%p)
        integer :: imax

        associate (now => loop%record%now, f => loop%fault, m => loop%fault%m, &
                   r => loop%recorded, vp => model%cycle%plate_rate)
            call loop%stations%displacement(loop%y(:m) - vp * now%time, vp * now%time, ux, uy)
            call loop%stations%displacement(f%v - vp, vp, vx, vy)
            imax = maxloc(abs(f%v), 1)
            call add_row(loop%record, now%time, abs(f%v(imax)), loop%record%elements(imax), &
                         loop%y(r), f%v(r), f%shear(r), -f%sigma(r), &
                         log10(f%dc(r) / f%v0(r)) + loop%y(m + r) / log(10.0_wp), ux, uy, vx, vy)
            now%last_row = now%time
        end associate
    end subroutine record_row

    !> The results of the run so far: the record with where it stands, and the element
    !> results, tips and fields of its back-slip DDs (ds = slip - V_p t) under the initial
    !> tractions.
    subroutine fill_results(model, loop, results)
        type(model_type), intent(in) :: model
        type(cycle_loop), intent(inout), target :: loop
        type(model_results), intent(out) :: results
        type(elastic_load) :: load
        integer :: n

        n = model%elements%n
        associate (now => loop%record%now, m => loop%fault%m, f => loop%fault, &
                   rows => loop%record%elements, op => loop%run%operator)
            now%slip = loop%y(:m)
            now%state = loop%y(m + 1:)
            now%slip_rate = f%v
            if (.not. allocated(now%event_start_slip)) allocate (now%event_start_slip(m), &
                                                                 source=0.0_wp)
            loop%record%products = f%products
            loop%record%newton_iterations = f%newton_iterations
            loop%record%seconds = wall_seconds() - loop%started
            results%cycle = loop%record
            allocate (results%elements%ds(n), results%elements%dn(n), source=0.0_wp)
            allocate (results%elements%state(n), source=state_slip)
            results%elements%ds(rows) = now%slip - model%cycle%plate_rate * now%time
            allocate (load%shear(n), load%normal(n), load%pressure(n), source=0.0_wp)
            load%shear = model%elements%rs_tau0
            load%normal = -model%elements%rs_sigma0
            load%remote = [model%sxx, model%syy, model%sxy]
            load%gradient = model%stress_gradient
            results%solver%method = trim(loop%pair%name)
            results%solver%hierarchical = op%record%hierarchical
            results%solver%compression_ratio = op%record%compression_ratio
            results%solver%hmatrix_tolerance = op%record%hmatrix_tolerance
            results%solver%seconds_assembly = op%record%seconds_assembly
        end associate
        call finish_model(model, load, results, run=loop%run)
        results%solver%seconds_total = wall_seconds() - loop%started
    end subroutine fill_results

end module ddc_cycle_driver
