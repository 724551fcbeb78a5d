!> ddc2d: read a model, solve it, write the results. With app/ the only place that prints
!> errors and sets the exit status.
program ddc2d
    use ddc_error, only: error_type
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results
    use ddc_run_model, only: run_model
    use ddc_history_solve, only: solve_history
    use ddc_growth_driver, only: grow_fractures
    use ddc_app_report, only: print_growth_step
    use ddc_model_restart, only: restart_state
    use ddc_output_restart_read, only: read_restart
    use ddc_app_command_line, only: command_line_options
    use ddc_app_driver, only: go_on, prepare_run, error_status, publish_results, exit_program
    implicit none

    type(command_line_options) :: options
    type(model_type) :: model
    type(model_results) :: results
    type(error_type), allocatable :: error
    type(restart_state) :: restart
    integer :: status

    call prepare_run(options, model, status)
    if (status /= go_on) call exit_program(status)
    if (allocated(options%resume_file)) then
        ! The file was checked in prepare_run: complete, this version, this model.
        call read_restart(options%resume_file, restart, error)
        if (.not. allocated(error)) then
            if (model%growth%active) then
                call grow_fractures(model, results, error, print_growth_step, restart)
            else
                call solve_history(model, results, error, restart=restart)
            end if
        end if
    else if (model%growth%active) then
        call grow_fractures(model, results, error, print_growth_step)
    else if (allocated(model%load_path%vertex)) then
        call solve_history(model, results, error)
    else
        call run_model(model, results, error)
    end if
    status = error_status(error)
    if (status /= go_on) call exit_program(status)
    call publish_results(options, model, results, status)
    call exit_program(status)
end program ddc2d
