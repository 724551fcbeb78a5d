!> What a growth run carries from one step to the next (ddc_growth_driver's state), and how a
!> run starts: from the input model solved at the first load, or from the end of an earlier
!> run (--resume, docs/theory/earth.md#what-a-step-hands-on: its geometry, solution, records, tips,
!> loading history and friction memory).
module ddc_growth_run_state
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, has_sources
    use ddc_model_results, only: model_results, tip_records, growth_record, growth_step_limit, &
        growth_failed, growth_end_names
    use ddc_model_trial_records, only: trial_records
    use ddc_model_records, only: empty_growth_record
    use ddc_model_restart, only: restart_state
    use ddc_history_path, only: apply_load, path_times
    use ddc_flow_injection, only: flow_tracker, follow_flow
    use ddc_growth_solver, only: growth_solver, solve_input, restore_memory
    use ddc_growth_clearance, only: tip_link
    use ddc_growth_tips, only: growing_tip, find_growing_tips
    use ddc_growth_load_steps, only: load_step_history, start_load_steps, resume_load_steps
    use ddc_growth_restart, only: resumed_geometry, resumed_tips, resumed_strengths
    implicit none
    private

    public :: reason_stopped, step_tips, growth_state, start_run, resume_run

    !> The reason of a tip that stopped for good in an earlier step: it has no record (the
    !> reasons of ddc_model_results, growth_grew ... growth_waiting, are not negative)
    integer, parameter :: reason_stopped = -1

    !> One step's view of the tips that may still grow: a row per tip (recorded unless its
    !> reason is reason_stopped), shape (tips) for every array.
    type, extends(tip_records) :: step_tips
        !> The criterion's kink angle (MTS) [rad] (mts_angle: the same in degrees)
        real(wp), allocatable :: theta(:)
        !> Element of the tip in the current geometry
        integer, allocatable :: element(:)
        !> The link of a tip that links in this step (reason growth_linked)
        type(tip_link), allocatable :: link(:)
        !> The work criterion's trials of the step (owner: the tip)
        type(trial_records) :: trials
    end type step_tips

    !> What a growth run carries from one step to the next.
    type :: growth_state
        !> The current geometry (without observations) and its solution
        type(model_type) :: work
        type(model_results) :: current
        !> The solves of the run (the current geometry is its base)
        type(growth_solver) :: solver
        !> Growth step that created each element of work (0: the input), shape (n)
        integer, allocatable :: created(:)
        !> The fracture ends that may grow, and this step's view of them
        type(growing_tip), allocatable :: tips(:)
        type(step_tips) :: now
        !> The loading history's columns (a run under a load path)
        type(load_step_history) :: history
        !> With fluid sources: the pressure that diffuses on the growing geometry, and the
        !> time of every load step [time unit], shape (load steps)
        type(flow_tracker) :: flow
        real(wp), allocatable :: times(:)
    end type growth_state

contains

    !> The start of a run: the input geometry at the first load, solved.
    subroutine start_run(model, loads, run, record, error)
        type(model_type), intent(in) :: model
        real(wp), intent(in) :: loads(:, :)
        type(growth_state), intent(out) :: run
        type(growth_record), intent(out) :: record
        type(error_type), allocatable, intent(out) :: error
        logical :: history

        history = allocated(model%load_path%vertex)
        run%work = model
        if (history) run%work = apply_load(model, loads(:, 1))
        if (allocated(model%load_path%time)) run%times = path_times(model%load_path)
        if (has_sources(model)) then
            call follow_flow(run%flow, run%work, run%times(1), error)
            if (allocated(error)) return
        end if
        ! Trial solves need no fields: they are evaluated once, on the final geometry.
        if (allocated(run%work%observations)) deallocate (run%work%observations)
        allocate (run%work%observations(0), run%created(run%work%elements%n))
        run%created = 0
        call empty_growth_record(record)
        call solve_input(run%solver, run%work, run%current, error, friction_memory=history)
        if (allocated(error)) then
            error%message = 'growth: solving the input geometry: '//error%message
            if (history) error%message = 'load step 1: '//error%message
            return
        end if
        run%tips = find_growing_tips(run%work, run%current%tips, model%growth%fracture_grows)
        if (history) call start_load_steps(run%history, run%work, size(loads, 2), error, &
                                           allocated(run%times), has_sources(model))
    end subroutine start_run

    !> A run resumed from the end of an earlier one (docs/theory/earth.md#what-a-step-hands-on): its
    !> final geometry, solution, records, tips, history and friction memory. It goes on in the load
    !> step where the earlier run reached the step limit or stopped at a failed step (start, after
    !> `first` growth steps of it), or with the load step after the one where it arrested (first =
    !> 0). Error (exit 2) when nothing is left to do.
    subroutine resume_run(model, restart, loads, run, record, step, start, first, error)
        type(model_type), intent(in) :: model
        type(restart_state), intent(in) :: restart
        real(wp), intent(in) :: loads(:, :)
        type(growth_state), intent(out) :: run
        type(growth_record), intent(out) :: record
        integer, intent(out) :: step, start, first
        type(error_type), allocatable, intent(out) :: error
        integer :: done
        logical :: history

        history = allocated(model%load_path%vertex)
        if (has_sources(model)) then
            call set_error(error, exit_bad_input, '--resume: a growth run with fluid '// &
                           'sources (&injection) cannot be resumed (the pressure that '// &
                           'diffused into the grown elements is not in the file): run it '// &
                           'again from the start')
            return
        end if
        if (allocated(model%load_path%time)) run%times = path_times(model%load_path)
        call resumed_geometry(model, restart, run%work, run%created, error)
        if (allocated(error)) return
        deallocate (run%work%observations)
        allocate (run%work%observations(0))
        run%current%elements = restart%results%elements
        run%current%tips = restart%results%tips
        run%current%solver = restart%results%solver
        run%tips = resumed_tips(model, restart)
        record = restart%results%growth
        ! Growth steps are numbered by the steps in which a tip grew
        step = record%steps_taken
        done = 1
        if (history) done = size(restart%results%history%pivots)
        start = done
        first = 0
        if (record%end_reason == growth_step_limit .or. record%end_reason == growth_failed) then
            ! Growth steps (evaluations) of the last load step so far (none when its first
            ! one failed)
            if (any(record%load_step == done)) then
                first = step - minval(record%step, record%load_step == done) + 1
            end if
            if (first >= model%growth%steps) call nothing_left('raise &growth steps to go on')
        else
            start = done + 1
            if (start > size(loads, 2)) then
                if (history) then
                    call nothing_left('extend &load_path to go on')
                else
                    ! At a fixed load no tip grows again: there is no way on.
                    call nothing_left('no tip can grow at this load; change the model')
                end if
            end if
        end if
        if (allocated(error)) return
        if (.not. history) return
        run%work = apply_load(run%work, loads(:, done))
        ! The last column's solve is that of the current solution.
        run%current%solver%pivots = restart%results%history%pivots(done)
        run%current%solver%newton_iterations = restart%results%history%newton_iterations(done)
        call restore_memory(run%solver, restart%results%elements%ds, &
                            resumed_strengths(run%work, restart))
        call resume_load_steps(run%history, run%work, restart, loads, size(loads, 2), &
                               start - 1, error)

    contains

        subroutine nothing_left(what)
            character(len=*), intent(in) :: what

            call set_error(error, exit_bad_input, '--resume: the earlier run ended ('// &
                           trim(growth_end_names(record%end_reason))//') where this model '// &
                           'ends too: nothing is left to do ('//what//')')
        end subroutine nothing_left

    end subroutine resume_run

end module ddc_growth_run_state
