!> Fracture growth (docs/theory/growth.md#the-growth-step): quasi-static, one increment per
!> step, under the model's fixed loading. The driver owns the element set and asks
!> ddc_growth_solver for solves; each step
!>
!> 1. takes K_I, K_II of every tip that may grow from the solve of the current geometry,
!>    its kink angle and K_eq under the model's criterion (ddc_growth_criterion: the MTS
!>    angle);
!> 2. picks the growing tips (every critical tip, or the most critical one, ties to the
!>    lowest index), stops for good those whose new elements would not keep clear
!>    (ddc_growth_clearance), or links them to the fracture they meet (a linked tip ends on it
!>    for good and is no tip any more: docs/theory/growth.md#linking-and-stops);
!> 3. turns the kinks as the criterion does (ddc_growth_criterion: the local-symmetry
!>    corrector), adds the new elements (ddc_growth_kinks, ddc_growth_extension), checks
!>    the grown mesh (ddc_mesh_checks: never a crossing mesh) and solves it (or keeps the
!>    criterion's last solve when it is that geometry).
!>
!> Every solve goes through ddc_growth_solver, which grows the influence matrix and the
!> Newton method's factors from the step before where it can. What a step changes is in
!> one growth_state (geometry, solution, solver, tips), which grow_step takes and returns.
!>
!> A tip whose kink closes (K_I = 0) does not grow in that step but is tried again in the
!> next (another tip's growth may open it); with tips = 'most_critical' the next critical
!> tip is tried instead in the same step.
!>
!> The run ends when no tip is critical any more, or none of the critical ones grew in a
!> step (arrested: the next step would repeat it), or after `steps` steps (step_limit);
!> fields, tips and the summary are those of the final geometry. When the solve of a step
!> fails (no method solves its contact problem, or its memory runs out) the run ends before
!> that step (failed): its results are those of the steps completed, the failure is recorded
!> with them, and the error (exit_stopped_early) says which step and fracture failed.
!>
!> Under a loading history (docs/theory/growth.md#growth-along-a-loading-history) every load step is
!> solved from the friction memory of the one before (ddc_growth_solver keeps it), its fractures are
!> grown until none is critical (at most `steps` growth steps, else the run ends with step_limit),
!> and its end is recorded for /history (ddc_growth_load_steps); growth steps are numbered through
!> the whole run, and only a step in which a tip grew is one (the check that ends a load step
!> prints no line and takes no number). Within a growth step the solver's progress lines are
!> held (ddc_progress): its corrector solves are many and quick.
!>
!> A resumed run (--resume) starts from the end of an earlier one (ddc_growth_run_state)
!> and goes on where it stopped: in the load step it reached the step limit in, or with the
!> next load step.
module ddc_growth_driver
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_error, only: error_type, set_internal_error, set_error, exit_bad_input, &
        exit_solver_failure, exit_out_of_memory, exit_stopped_early
    use ddc_model_types, only: model_type, growth_options, initiation_options, has_sources
    use ddc_model_initiations, only: initiation_record
    use ddc_growth_initiation, only: start_fracture
    use ddc_model_results, only: model_results, tip_records, growth_record, growth_grew, &
        growth_subcritical, growth_corrector_failed, growth_closed, growth_waiting, &
        growth_arrested, growth_step_limit, growth_failed
    use ddc_model_restart, only: restart_state
    use ddc_growth_run_state, only: reason_stopped, step_tips, growth_state, start_run, resume_run
    use ddc_mesh_checks, only: check_elements
    use ddc_growth_solver, only: solve_grown, solve_loaded, accept_trial, final_results, &
        solves_done
    use ddc_growth_criterion, only: assess_tip, kink_angles, most_critical, searched_tip, &
        picks_by_k
    use ddc_growth_kinks, only: kink, step_kinks, grow_paths
    use ddc_growth_extension, only: tip_path, make_path, tip_element, tip_end_begin
    use ddc_growth_clearance, only: check_paths, path_clear, ends_on_link
    use ddc_growth_tips, only: growing_tip, fracture_tip, increment_for
    use ddc_growth_work, only: append_trials
    use ddc_model_records, only: append_tip_rows, append_trial_rows, lay_out_tip_rows
    use ddc_growth_load_steps, only: follow_growth, record_load_step, finish_load_steps
    use ddc_history_path, only: path_loads, apply_load, load_text
    use ddc_flow_injection, only: follow_flow, injected
    use ddc_progress, only: report_progress, hold_progress, release_progress
    use ddc_text, only: itoa, rtoa, seconds_text
    implicit none
    private

    public :: grow_fractures, growth_progress

    !> The solver's progress lines within a growth step are shown once it has run this long [s]
    real(wp), parameter :: progress_hold_seconds = 5.0_wp
    !> Degrees per radian: the records' angles are in degrees
    real(wp), parameter :: degrees = 180.0_wp / pi

    abstract interface
        !> Told after every growth step (the program prints a line and flushes it).
        subroutine growth_progress(step, growing, largest_k_eq, solves, seconds, elapsed)
            import :: wp
            implicit none
            !> The step, and the number of tips that grew in it
            integer, intent(in) :: step, growing
            !> The largest K_eq of the step's tips [stress unit * length unit**0.5]
            real(wp), intent(in) :: largest_k_eq
            !> Solves of the model in the step
            integer, intent(in) :: solves
            !> Wall time of the step, and since the run started [s]
            real(wp), intent(in) :: seconds, elapsed
        end subroutine growth_progress
    end interface

contains

    !> Grow the fractures of a model with &growth (along its load path when it has one). On
    !> return the model is the final geometry (at the last load) and results hold its
    !> solution, tips, fields, the growth record and the loading history.
    subroutine grow_fractures(model, results, error, progress, restart)
        !> A validated model with growth options; the grown model on return
        type(model_type), intent(inout) :: model
        !> The final geometry's results, results%growth and results%history
        type(model_results), intent(out) :: results
        !> Set when a solve fails (naming the step) or a contract is broken; a failed growth
        !> step is exit_stopped_early, with results of the steps before it
        type(error_type), allocatable, intent(out) :: error
        !> Called after every growth step
        procedure(growth_progress), optional :: progress
        !> The end of an earlier run of the model to go on from (--resume)
        type(restart_state), intent(in), optional :: restart
        type(error_type), allocatable :: failure
        type(growth_state) :: run
        type(growth_record) :: record
        type(initiation_record) :: initiations
        real(wp), allocatable :: loads(:, :)
        integer :: step, load_step, steps_before, start, first
        integer(int64) :: t_start, t_end, rate
        logical :: history, solved
        character(len=:), allocatable :: where

        call system_clock(t_start, rate)
        history = allocated(model%load_path%vertex)
        if (history) then
            loads = path_loads(model%load_path)
        else
            allocate (loads(7, 1), source=0.0_wp)
        end if
        if (present(restart) .and. model%initiation%active) then
            call set_error(error, exit_bad_input, '--resume: a run with &initiation cannot '// &
                           'be resumed: run it again from the start')
            return
        end if
        if (present(restart)) then
            call resume_run(model, restart, loads, run, record, step, start, first, error)
        else
            call start_run(model, loads, run, record, error)
            step = 0
            start = 1
            first = 0
        end if
        if (allocated(error)) return
        ! The current solution is that of the first load step's load (not so when a resumed
        ! run goes on with the next load step).
        solved = first > 0 .or. start == 1
        do load_step = start, size(loads, 2)
            if (history) then
                where = 'load step '//itoa(load_step)//' of '//itoa(size(loads, 2))//' ('// &
                    step_text(load_step)//')'
                if (.not. solved) then
                    run%work = apply_load(run%work, loads(:, load_step))
                    if (has_sources(model)) call follow_flow(run%flow, run%work, &
                                                             run%times(load_step), error)
                    if (.not. allocated(error)) call solve_loaded(run%solver, run%work, &
                                                                  run%current, error)
                    if (allocated(error)) then
                        error%message = where//': '//error%message//'; no result is written'
                        return
                    end if
                end if
                call report_progress(where)
            end if
            solved = .false.
            steps_before = record%steps_taken
            call grow_to_stability(run, model%growth, model%initiation, load_step, history, &
                                   step, first, record, initiations, error, progress, t_start)
            first = 0
            if (allocated(error)) then
                if (history) error%message = where//': '//error%message
                if (error%code /= exit_solver_failure .and. &
                    error%code /= exit_out_of_memory) then
                    return
                end if
                ! The run ends before the failed step; what it completed is its result.
                call move_alloc(error, failure)
                record%end_reason = growth_failed
                record%failure = failure%message
            end if
            if (history) then
                if (has_sources(model)) then
                    call record_load_step(run%history, run%work, run%current, &
                                          loads(:, load_step), error, run%times(load_step), &
                                          injected(run%flow))
                else if (allocated(run%times)) then
                    call record_load_step(run%history, run%work, run%current, &
                                          loads(:, load_step), error, run%times(load_step))
                else
                    call record_load_step(run%history, run%work, run%current, &
                                          loads(:, load_step), error)
                end if
                if (allocated(error)) return
                call report_load_step(record%steps_taken - steps_before)
            end if
            if (record%end_reason == growth_step_limit .or. allocated(failure)) exit
        end do

        model%elements = run%work%elements
        model%fractures = run%work%fractures
        if (model%initiation%active) then
            ! New fractures grow as the others do.
            model%growth%fracture_grows = [model%growth%fracture_grows, spread(.true., 1, &
                size(model%fractures) - size(model%growth%fracture_grows))]
        end if
        if (history) then
            model%sxx = run%work%sxx
            model%syy = run%work%syy
            model%sxy = run%work%sxy
            model%stress_gradient = run%work%stress_gradient
            model%pore_fluid = run%work%pore_fluid
        end if
        call final_results(run%solver, model, run%current, results)
        record%created_step = run%created
        if (history) call finish_load_steps(run%history, run%work, results%tips, run%tips, &
                                            record, results%history, error)
        if (allocated(error)) return
        results%growth = record
        if (model%initiation%active) results%initiations = initiations
        call system_clock(t_end)
        results%solver%seconds_total = real(t_end - t_start, wp) / real(rate, wp)
        if (allocated(failure)) then
            call set_error(error, exit_stopped_early, failure%message//'; the run stopped '// &
                'there: the result holds the '//itoa(record%steps_taken)//' growth step(s) '// &
                'before it (end_reason failed)')
            if (.not. model%initiation%active) error%message = error%message// &
                ', and --resume goes on from them'
        end if

    contains

        !> 'syy = -60' or 't = 2.5 s, syy = -60': what load step k is.
        function step_text(k) result(text)
            integer, intent(in) :: k
            character(len=:), allocatable :: text

            if (allocated(run%times)) then
                text = load_text(loads(:, k), model%load_path%varies, run%times(k), &
                                 model%time_unit)
            else
                text = load_text(loads(:, k), model%load_path%varies)
            end if
        end function step_text

        !> 'load step 3 of 20 (syy = -60): 2 growth steps, 1.2 grown, 3.5 s' (time since the start).
        subroutine report_load_step(steps_grown)
            integer, intent(in) :: steps_grown
            integer(int64) :: t_now

            call system_clock(t_now)
            call report_progress(where//': '//itoa(steps_grown)//' growth step'// &
                trim(merge('s', ' ', steps_grown /= 1))//', grown length '// &
                rtoa(sum(record%length, record%load_step == load_step))//' in all, '// &
                seconds_text(real(t_now - t_start, wp) / real(rate, wp)))
        end subroutine report_load_step

    end subroutine grow_fractures

    !> Grow the fractures at the current load until no tip is critical (end_reason
    !> growth_arrested) or for `steps` growth steps (growth_step_limit), after `first` growth
    !> steps of this load step done before; `step` counts the growth steps of the whole run.
    subroutine grow_to_stability(run, options, initiation, load_step, along_path, step, first, &
                                 record, initiations, error, progress, t_start)
        !> The run at the load step's start (its geometry solved at the step's load)
        type(growth_state), intent(inout) :: run
        !> The model's growth options
        type(growth_options), intent(in) :: options
        !> The model's initiation options (new fractures inside the rock)
        type(initiation_options), intent(in) :: initiation
        !> The load step (1 without a load path)
        integer, intent(in) :: load_step
        !> Growth along a load path (a check without growth is not reported)
        logical, intent(in) :: along_path
        !> The last growth step of the run so far
        integer, intent(inout) :: step
        !> Growth steps of this load step done before (a resumed run)
        integer, intent(in) :: first
        !> The run's growth record: the step's records appended, steps_taken and end_reason
        type(growth_record), intent(inout) :: record
        !> The new fractures started so far; this load step's appended
        type(initiation_record), intent(inout) :: initiations
        !> Set when a solve fails (naming the step) or a contract is broken
        type(error_type), allocatable, intent(out) :: error
        !> Called after every growth step
        procedure(growth_progress), optional :: progress
        !> system_clock at the run's start
        integer(int64), intent(in) :: t_start
        integer :: s, grown, solves_before, next
        integer(int64) :: t_step, rate
        logical :: started

        record%end_reason = growth_step_limit
        do s = first + 1, options%steps
            ! A step number is used up only when a tip grows; the records of a check in which
            ! none grew carry the number the next growth step will have.
            next = step + 1
            call system_clock(t_step, rate)
            solves_before = solves_done(run%solver)
            call hold_progress(progress_hold_seconds)
            ! A new fracture inside the rock starts before the tips are assessed (it is solved
            ! with them); it counts as growth of the step.
            started = .false.
            if (initiation%active) then
                call start_fracture(run, options, initiation, next, load_step, initiations, &
                                    started, error)
                if (allocated(error)) exit
            end if
            call evaluate_tips(run%work, run%current, run%tips, options, run%now, error)
            if (allocated(error)) exit
            grown = 0
            if (any(run%now%reason == growth_grew)) then
                do
                    call choose_growing(run%work, options, run%tips, run%now)
                    call grow_step(run, options, next, grown, error)
                    if (allocated(error)) exit
                    if (grown > 0 .or. .not. any(run%now%reason == growth_waiting)) exit
                    ! The most critical tip closed: the next one waiting tries in this step.
                    where (run%now%reason == growth_waiting) run%now%reason = growth_grew
                end do
                if (allocated(error)) then
                    call name_growing_tips(error%message)
                    exit
                end if
            end if
            if (started) grown = grown + 1
            call release_progress()
            call append_records(record, next, load_step, run%now)
            if (grown == 0) then
                ! Along a load path the load step's end line tells it; without one the check
                ! that ends the run is shown.
                if (.not. along_path) call report(0)
                record%end_reason = growth_arrested
                exit
            end if
            step = next
            call report(grown)
            record%steps_taken = record%steps_taken + 1
        end do
        call release_progress()

    contains

        !> 'growth step 6 (growing: fault begin, fault_tail1 end): ...' from a message that
        !> starts 'growth step 6'.
        subroutine name_growing_tips(message)
            character(len=:), allocatable, intent(inout) :: message
            character(len=:), allocatable :: prefix, names
            integer :: i

            prefix = 'growth step '//itoa(next)
            if (index(message, prefix) /= 1) return
            names = ''
            do i = 1, size(run%tips)
                associate (reason => run%now%reason(i))
                    if (.not. (reason == growth_grew .or. reason == growth_corrector_failed &
                               .or. ends_on_link(reason))) cycle
                end associate
                if (len(names) > 0) names = names//', '
                names = names//fracture_label(run%work, run%tips(i)%fracture)// &
                    trim(merge(' begin', ' end  ', run%tips(i)%end == tip_end_begin))
            end do
            if (len(names) > 0) message = prefix//' (growing: '//names//')'// &
                message(len(prefix) + 1:)
        end subroutine name_growing_tips

        !> Tell the caller how the step went.
        subroutine report(growing)
            integer, intent(in) :: growing
            integer(int64) :: t_now

            call system_clock(t_now)
            if (present(progress)) call progress(next, growing, maxval([0.0_wp, run%now%k_eq]), &
                                                 solves_done(run%solver) - solves_before, &
                                                 real(t_now - t_step, wp) / real(rate, wp), &
                                                 real(t_now - t_start, wp) / real(rate, wp))
        end subroutine report

    end subroutine grow_to_stability

    !> One step's growth of the growing tips (reason growth_grew on entry): turn their
    !> kinks as the criterion does, add the new elements and solve the grown model (or keep
    !> the criterion's last solve when it is that geometry), which becomes the run's current
    !> geometry. The tips' reasons, applied angles, lengths, solves and K_II after growing
    !> are set in run%now; tips that cannot grow any more are stopped.
    subroutine grow_step(run, options, step, grown, error)
        !> The run: its geometry, solution, solver, tips and their view of this step
        type(growth_state), intent(inout) :: run
        !> The model's growth options
        type(growth_options), intent(in) :: options
        !> The growth step
        integer, intent(in) :: step
        !> Number of tips that grew
        integer, intent(out) :: grown
        !> Set when a solve fails (naming the step) or the grown mesh is bad
        type(error_type), allocatable, intent(out) :: error
        type(step_kinks) :: kinks
        integer, allocatable :: which(:), linked(:)
        integer :: i, t, k

        grown = 0
        which = pack([(i, i = 1, size(run%tips))], run%now%reason == growth_grew)
        linked = pack([(i, i = 1, size(run%tips))], ends_on_link(run%now%reason))
        if (size(which) + size(linked) == 0) return
        kinks%step = step
        ! A copy, not run%now%link(linked) as an argument: gfortran's temporary of a vector
        ! subscript leaks the allocatable components of the links
        kinks%fixed = run%now%link(linked)
        do i = 1, size(linked)
            t = linked(i)
            grown = grown + 1
            run%now%angle(t) = run%now%link(t)%theta * degrees
            run%now%length(t) = run%now%link(t)%length
        end do
        allocate (kinks%tip(size(which)))
        do i = 1, size(which)
            kinks%tip(i) = tip_kink(run%work, options, run%tips(which(i)), run%now, which(i))
        end do
        call kink_angles(run%solver, run%work, run%current, run%created, options, kinks, error)
        if (allocated(error)) return
        call append_trial_rows(run%now%trials, kinks%trials)
        do i = 1, size(which)
            t = which(i)
            run%now%reason(t) = kinks%tip(i)%reason
            run%now%corrections(t) = kinks%tip(i)%solves
            run%now%efficiency(t) = kinks%tip(i)%efficiency
            run%now%slip_share(t) = kinks%tip(i)%slip_share
            if (kinks%tip(i)%reason == growth_grew .or. &
                kinks%tip(i)%reason == growth_corrector_failed) then
                grown = grown + 1
                run%now%angle(t) = kinks%tip(i)%theta * degrees
                run%now%length(t) = kinks%tip(i)%length
                run%tips(t)%element_length = regular_length(kinks%tip(i))
                run%tips(t)%kink_length = kinks%tip(i)%length
            else if (ends_on_link(kinks%tip(i)%reason)) then
                grown = grown + 1
                run%tips(t)%stopped = .true.
                run%now%angle(t) = kinks%tip(i)%link%theta * degrees
                run%now%length(t) = kinks%tip(i)%link%length
            else if (kinks%tip(i)%reason /= growth_closed) then
                run%tips(t)%stopped = .true.
            end if
        end do
        ! Nothing grew: the geometry and its solution stay.
        if (grown == 0) return
        if (.not. kinks%current) then
            call grow_paths(run%work, run%created, options, kinks)
            call solve_grown(run%solver, kinks%trial, kinks%moved_to, kinks%solved, error, &
                             kinks%origin)
            if (allocated(error)) then
                error%message = 'growth step '//itoa(step)//': '//error%message
                return
            end if
        end if
        call move_alloc(kinks%trial_created, run%created)
        run%work = kinks%trial
        run%current = kinks%solved
        call accept_trial(run%solver)
        call follow_growth(run%history, kinks%origin)
        call check_elements(run%work%elements, run%work%fractures, error)
        if (allocated(error)) then
            call set_internal_error(error, 'grow_fractures', 'growth step '//itoa(step)// &
                                    ' made a bad mesh: '//error%message)
            return
        end if
        do i = 1, size(which)
            t = which(i)
            ! A linked tip, or one through the surface, is no tip any more; one that did not
            ! grow has no new tip.
            if (run%now%length(t) <= 0.0_wp .or. ends_on_link(run%now%reason(t))) cycle
            call fracture_tip(run%work, run%current%tips, run%tips(t)%fracture, &
                              run%tips(t)%end, k, error)
            if (allocated(error)) return
            run%now%k2_after(t) = run%current%tips%k2(k)
        end do
    end subroutine grow_step

    !> A fracture's name, or 'fracture <f>' when it has none.
    pure function fracture_label(work, f) result(label)
        type(model_type), intent(in) :: work
        integer, intent(in) :: f
        character(len=:), allocatable :: label

        label = 'fracture '//itoa(f)
        if (.not. allocated(work%fractures(f)%name)) return
        if (len_trim(work%fractures(f)%name) > 0) label = trim(work%fractures(f)%name)
    end function fracture_label

    !> The element length a tip keeps after growing by kink k: 0 (its new tip element's)
    !> after a whole increment, the increment's element length after a shorter kink (whose
    !> element may be shorter).
    pure real(wp) function regular_length(k)
        type(kink), intent(in) :: k

        regular_length = 0.0_wp
        if (k%length < k%full_length) regular_length = k%element_length
    end function regular_length

    !> K, kink angle and K_eq (the criterion's) of every tip that may still grow; reason
    !> growth_subcritical (K_eq < toughness) or growth_grew (critical) for those,
    !> reason_stopped for the others.
    subroutine evaluate_tips(work, current, tips, options, now, error)
        type(model_type), intent(in) :: work
        type(model_results), intent(in) :: current
        type(growing_tip), intent(in) :: tips(:)
        type(growth_options), intent(in) :: options
        type(step_tips), intent(out) :: now
        type(error_type), allocatable, intent(out) :: error
        integer :: i, n, t

        n = size(tips)
        call lay_out_tip_rows(now%tip_records, n)
        allocate (now%theta(n), now%element(n), now%link(n))
        now%fracture_id = tips%fracture
        now%end = tips%end
        now%k1 = 0.0_wp
        now%k2 = 0.0_wp
        now%k_eq = 0.0_wp
        now%theta = 0.0_wp
        now%x = 0.0_wp
        now%y = 0.0_wp
        now%element = 0
        now%length = 0.0_wp
        now%efficiency = 0.0_wp
        now%slip_share = 0.0_wp
        now%reason = reason_stopped
        do i = 1, n
            if (tips(i)%stopped) cycle
            now%element(i) = tip_element(work, tips(i)%fracture, tips(i)%end)
            call fracture_tip(work, current%tips, tips(i)%fracture, tips(i)%end, t, error)
            if (allocated(error)) return
            now%x(i) = current%tips%x(t)
            now%y(i) = current%tips%y(t)
            now%k1(i) = current%tips%k1(t)
            now%k2(i) = current%tips%k2(t)
            call assess_tip(options, now%k1(i), now%k2(i), now%theta(i), now%k_eq(i), error)
            if (allocated(error)) return
            now%mts_angle(i) = now%theta(i) * degrees
            now%reason(i) = merge(growth_grew, growth_subcritical, &
                                  searched_tip(options, now%k_eq(i)))
        end do
    end subroutine evaluate_tips

    !> The critical tips that grow in this step: all of them, or the most critical one
    !> (the others wait); a tip whose predictor path (at its kink angle, the step's length)
    !> meets another fracture links to it (its link in now%link), one whose path would not
    !> keep clear otherwise stops for good (and with 'most_critical' the next most critical
    !> tip is tried). Reasons are updated.
    subroutine choose_growing(work, options, tips, now)
        type(model_type), intent(in) :: work
        type(growth_options), intent(in) :: options
        type(growing_tip), intent(inout) :: tips(:)
        type(step_tips), intent(inout) :: now
        type(tip_path) :: paths(size(tips))
        integer :: problem(size(tips)), i, best
        logical :: untried(size(tips))

        do i = 1, size(tips)
            if (now%reason(i) /= growth_grew) cycle
            paths(i) = predictor_path(work, options, tips(i), now, i)
        end do
        if (.not. picks_by_k(options)) then
            call check_paths(work, paths, now%reason == growth_grew, problem, now%link)
            call stop_blocked()
            return
        end if
        untried = now%reason == growth_grew
        do
            best = most_critical(now%k_eq, untried)
            if (best == 0) exit
            untried(best) = .false.
            call check_paths(work, paths, [(i == best, i = 1, size(tips))], problem, now%link)
            call stop_blocked()
            if (problem(best) == path_clear .or. ends_on_link(problem(best))) exit
        end do
        where (untried) now%reason = growth_waiting

    contains

        subroutine stop_blocked()
            do i = 1, size(tips)
                if (problem(i) == path_clear) cycle
                now%reason(i) = problem(i)
                tips(i)%stopped = .true.
            end do
        end subroutine stop_blocked

    end subroutine choose_growing

    !> Length and number of elements of a tip's increment: `increment` (default twice the
    !> tip element's length) in n = nint(increment / element_length) >= 1 equal elements
    !> (element_length default: the tip element's length). After a kink shorter than the
    !> increment the tip's element length is the one before it (tip%element_length).
    pure subroutine increment_of(options, work, tip, element, length, pieces, element_length)
        !> The growth options (increment, element_length)
        type(growth_options), intent(in) :: options
        !> The current geometry
        type(model_type), intent(in) :: work
        !> The tip, and its tip element
        type(growing_tip), intent(in) :: tip
        integer, intent(in) :: element
        !> Length of the increment [length unit]
        real(wp), intent(out) :: length
        !> Number of its elements
        integer, intent(out) :: pieces
        !> Length of the elements the tip grows by [length unit]
        real(wp), intent(out) :: element_length
        real(wp) :: tip_length

        tip_length = tip%element_length
        if (tip_length <= 0.0_wp) tip_length = 2.0_wp * work%elements%half_length(element)
        call increment_for(options, tip_length, length, pieces, element_length)
    end subroutine increment_of

    !> The path of tip i at its kink angle.
    function predictor_path(work, options, tip, now, i) result(path)
        type(model_type), intent(in) :: work
        type(growth_options), intent(in) :: options
        type(growing_tip), intent(in) :: tip
        type(step_tips), intent(in) :: now
        integer, intent(in) :: i
        type(tip_path) :: path
        real(wp) :: length, element_length
        integer :: pieces

        call increment_of(options, work, tip, now%element(i), length, pieces, element_length)
        path = make_path(work, tip%fracture, tip%end, now%theta(i), length, pieces)
    end function predictor_path

    !> Growing tip i as the criterion turns it: its K, K_eq, kink angle (the predictor) and
    !> increment.
    function tip_kink(work, options, tip, now, i) result(k)
        type(model_type), intent(in) :: work
        type(growth_options), intent(in) :: options
        type(growing_tip), intent(in) :: tip
        type(step_tips), intent(in) :: now
        integer, intent(in) :: i
        type(kink) :: k

        k%fracture = tip%fracture
        k%end = tip%end
        k%tip = i
        k%k1 = now%k1(i)
        k%k2 = now%k2(i)
        k%k_eq = now%k_eq(i)
        k%theta_predictor = now%theta(i)
        call increment_of(options, work, tip, now%element(i), k%length, k%pieces, &
                          k%element_length)
        k%full_length = k%length
        if (tip%kink_length > 0.0_wp) k%first_length = min(k%length, 2.0_wp * tip%kink_length)
    end function tip_kink

    !> Append the step's records: one per tip that could still grow at the step's start, and
    !> the step's trials.
    subroutine append_records(record, step, load_step, now)
        type(growth_record), intent(inout) :: record
        integer, intent(in) :: step, load_step
        type(step_tips), intent(in) :: now
        type(tip_records) :: rows
        logical :: keep(size(now%reason))

        keep = now%reason /= reason_stopped
        rows = now%tip_records
        rows%step = spread(step, 1, size(keep))
        rows%load_step = spread(load_step, 1, size(keep))
        call append_tip_rows(record%tip_records, rows, keep)
        if (allocated(now%trials%step)) call append_trials(record, keep, now%trials)
    end subroutine append_records

end module ddc_growth_driver
