!> ddc2d: read a model, solve it, write the results. With app/ the only place that prints
!> errors and sets the exit status.
program ddc2d
    use ddc_error, only: error_type
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results
    use ddc_app_command_line, only: command_line_options
    use ddc_app_driver, only: go_on, prepare_run, finish_run, exit_program
    use ddc_app_solve, only: solve_on_one_process
    implicit none

    type(command_line_options) :: options
    type(model_type) :: model
    type(model_results) :: results
    type(error_type), allocatable :: error
    integer :: status

    call prepare_run(options, model, status)
    if (status /= go_on) call exit_program(status)
    call solve_on_one_process(options, model, results, error)
    call finish_run(options, model, results, error, status)
    call exit_program(status)
end program ddc2d
