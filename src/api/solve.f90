!> The solve of a model as the program does it, for the program and the library alike:
!> fracture growth, a loading history, earthquake cycles or one solve, continued from an
!> earlier run's end when a restart state is given (--resume).
module ddc_api_solve
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results
    use ddc_model_restart, only: restart_state
    use ddc_run_model, only: run_model, prepare_model_body
    use ddc_history_solve, only: solve_history
    use ddc_history_fluid_growth, only: solve_fluid_growth
    use ddc_growth_driver, only: grow_fractures, growth_progress
    use ddc_cycle_driver, only: run_cycles, cycle_writer
    implicit none
    private

    public :: solve_model

contains

    !> Grow the model's fractures (&growth), follow its loading history (&load_path), run
    !> its earthquake cycles (&cycle), or solve it once.
    subroutine solve_model(model, results, error, progress, restart, writer)
        !> A validated model; growth adds its new elements
        type(model_type), intent(inout) :: model
        !> The results
        type(model_results), intent(out) :: results
        !> Allocated when the solve fails
        type(error_type), allocatable, intent(out) :: error
        !> Called after every growth step
        procedure(growth_progress), optional :: progress
        !> The end of an earlier run of a growth model, a loading history or a cycle run to go
        !> on from
        type(restart_state), intent(in), optional :: restart
        !> Writes the result file of a cycle run so far (its checkpoints, a run that stops)
        procedure(cycle_writer), optional :: writer

        call prepare_model_body(model, error)
        if (allocated(error)) return
        if (model%growth%active .and. model%fluid%active) then
            if (present(restart)) then
                call set_error(error, exit_bad_input, '--resume: a hydraulic fracture '// &
                               '(&growth with &fluid) cannot be resumed (the file does '// &
                               'not hold the fluid''s state)')
                return
            end if
            call solve_fluid_growth(model, results, error)
        else if (model%growth%active) then
            call grow_fractures(model, results, error, progress, restart)
        else if (model%cycle%active) then
            if (present(restart)) then
                call run_cycles(model, results, error, writer, restart%results%cycle)
            else
                call run_cycles(model, results, error, writer)
            end if
        else if (allocated(model%load_path%vertex)) then
            call solve_history(model, results, error, restart=restart)
        else
            call run_model(model, results, error)
        end if
    end subroutine solve_model

end module ddc_api_solve
