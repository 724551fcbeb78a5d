!> ddc2d built with MPI and ScaLAPACK (DDC2D_MPI): mpiexec -n P ddc2d MODEL.nml. The root
!> process reads and checks the input and alone writes the output; the model is solved on
!> every process (ddc_parallel_*), or, with one process, serially when it needs what is not
!> distributed. Every error ends every process with the same exit status after one message
!> from the root. With app/ the only place that prints errors and sets the exit status.
program ddc2d
    use ddc_error, only: error_type, exit_stopped_early
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results
    use ddc_run_model, only: run_model
    use ddc_app_command_line, only: command_line_options
    use ddc_app_driver, only: go_on, prepare_run, error_status, finish_run, exit_program
    use ddc_app_solve, only: solve_on_one_process
    use ddc_parallel_context, only: parallel_context, root, start_parallel, open_grid, &
        stop_parallel
    use ddc_parallel_collective, only: agree_on_error, share
    use ddc_parallel_model, only: share_model
    use ddc_parallel_plan, only: plan_run
    use ddc_parallel_run, only: distributed_engine
    implicit none

    type(parallel_context) :: context
    type(distributed_engine) :: engine
    type(command_line_options) :: options
    type(model_type) :: model
    type(model_results) :: results
    type(error_type), allocatable :: error, stopped
    integer :: status, on_every
    logical :: distributed

    call start_parallel(context)
    status = go_on
    if (context%rank == root) call prepare_run(options, model, status, context%processes)
    call share(context, status)
    if (status /= go_on) call leave(status)

    on_every = 0
    if (context%rank == root) then
        call plan_run(model, context%processes, distributed, error)
        if (distributed) on_every = 1
    end if
    call stop_on(error)
    call share(context, on_every)
    if (on_every == 1) then
        call share_model(context, model)
        call open_grid(context, model%block_size, error)
        call stop_on(error)
        engine%context = context
        call run_model(model, results, error, engine)
    else if (context%rank == root) then
        call solve_on_one_process(options, model, results, error)
        ! A run that stopped early has results to publish: not an error of every process.
        if (allocated(error)) then
            if (error%code == exit_stopped_early) call move_alloc(error, stopped)
        end if
    end if
    call stop_on(error)
    if (context%rank == root) then
        results%solver%processes = context%processes
        results%solver%process_grid = [context%rows, context%columns]
        results%solver%block_size = model%block_size
        call finish_run(options, model, results, stopped, status)
    end if
    call share(context, status)
    call leave(status)

contains

    !> When any process has an error, the root prints it and every process leaves with its
    !> exit status (collective).
    subroutine stop_on(error)
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        call agree_on_error(context, error)
        if (.not. allocated(error)) return
        if (context%rank == root) then
            status = error_status(error)
        else
            status = error%code
        end if
        call leave(status)
    end subroutine stop_on

    !> End MPI and exit with the given status (every process).
    subroutine leave(status)
        integer, intent(in) :: status

        call stop_parallel(context)
        call exit_program(status)
    end subroutine leave

end program ddc2d
