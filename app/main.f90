!> ddc2d: read a model, solve it, write the results. The only place that prints errors and
!> sets the exit status.
program ddc2d
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, int64
    use, intrinsic :: iso_c_binding, only: c_int
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_success, exit_bad_input
    use ddc_version, only: program_name, program_version, git_commit
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results
    use ddc_input_namelist, only: read_namelist_model
    use ddc_input_twodd_deck, only: read_twodd_deck
    use ddc_output_atomic, only: check_writable
    use ddc_output_hdf5, only: write_results
    use ddc_output_twodd_tables, only: write_twodd_tables
    use ddc_run_model, only: run_model
    use ddc_history_solve, only: solve_history
    use ddc_growth_driver, only: grow_fractures
    use ddc_input_sweep, only: read_sweep
    use ddc_sweep_tasks, only: sweep_definition, task_label, task_file_name, check_task, &
        apply_task, task_problem, check_tasks, output_is_complete
    use ddc_app_command_line, only: command_line_options, parse_command_line, usage_text, &
        action_version, action_help, task_number
    use ddc_app_report, only: print_model_summary, print_results_summary, print_growth_step, &
        field_warnings
    use ddc_app_memory, only: check_model_memory
    use ddc_text, only: itoa, prefix_lines
    implicit none

    interface
        !> C exit(): the exit status without the compiler's STOP banner.
        subroutine c_exit(status) bind(C, name='exit')
            import :: c_int
            implicit none
            integer(c_int), value :: status
        end subroutine c_exit
    end interface

    type(command_line_options) :: options
    type(model_type) :: model
    type(model_results) :: results
    type(error_type), allocatable :: error
    integer(int64) :: t0, t1, rate
    character(len=:), allocatable :: warnings

    call parse_command_line(options, error)
    if (allocated(error)) then
        write (error_unit, '(a)') program_name//': error: '//error%message
        write (error_unit, '(a)') 'usage: ddc2d INPUT.nml [-o OUT.h5] [--res RES.txt] | '// &
            'ddc2d SWEEP.nml --list | --task K [-o OUT.h5] | '// &
            'ddc2d --twodd DECK [-o OUT.h5] [--res RES.txt]   (ddc2d --help for more)'
        call finish(error%code)
    end if
    select case (options%action)
    case (action_version)
        write (output_unit, '(a)') program_name//' '//program_version//' (git '//git_commit//')'
        call finish(exit_success)
    case (action_help)
        write (output_unit, '(a)') usage_text()
        call finish(exit_success)
    case default
        ! action_run: go on below
    end select

    if (options%twodd) then
        call read_twodd_deck(options%input_file, model, error)
    else
        call read_namelist_model(options%input_file, model, error)
    end if
    call stop_on(error)
    if (allocated(options%output_file)) model%output_file = options%output_file
    if (.not. options%twodd) call prepare_sweep_task(options, model)
    call check_writable(model%output_file, error)
    call stop_on(error)
    if (allocated(options%res_file)) then
        call check_writable(options%res_file, error)
        call stop_on(error)
    end if
    call print_model_summary(output_unit, model, units_given=.not. options%twodd)
    call check_model_memory(output_unit, model, error)
    call stop_on(error)

    if (allocated(model%load_path%vertex)) then
        call solve_history(model, results, error)
    else if (model%growth%active) then
        call grow_fractures(model, results, error, print_growth_step)
    else
        call run_model(model, results, error)
    end if
    call stop_on(error)
    call system_clock(t0, rate)
    call write_results(model%output_file, model, results, error)
    call stop_on(error)
    if (allocated(options%res_file)) then
        call write_twodd_tables(options%res_file, model, results, error)
        call stop_on(error)
    end if
    call system_clock(t1)
    results%solver%seconds_output = real(t1 - t0, wp) / real(rate, wp)
    call print_results_summary(output_unit, model, results)
    warnings = field_warnings(model, results)
    if (len(warnings) > 0) write (error_unit, '(a)') prefix_lines(program_name// &
        ': warning: ', warnings)
    call finish(exit_success)

contains

    !> Sweeps (SPEC section 6): --list prints the tasks and exits; otherwise the task from
    !> --task or SLURM_ARRAY_TASK_ID replaces the base model, or is skipped (exit 0) when
    !> its complete output exists. A file without &sweep runs as it is, unless --list or
    !> --task asked for a sweep.
    subroutine prepare_sweep_task(options, model)
        type(command_line_options), intent(in) :: options
        type(model_type), intent(inout) :: model
        type(sweep_definition) :: sweep
        type(error_type), allocatable :: error
        logical :: found, exists
        integer :: task
        character(len=:), allocatable :: problem

        call read_sweep(options%input_file, model, sweep, found, error)
        call stop_on(error)
        if (.not. found) then
            if (options%list .or. options%task >= 0) then
                call set_error(error, exit_bad_input, options%input_file//' has no &sweep '// &
                               'group: --list and --task are for parameter sweeps')
            end if
            call stop_on(error)
            return
        end if
        if (options%list) then
            ! Every task's model, before anything is submitted; the output folder is made by
            ! the job (submit-sweep creates its --output-dir) and checked by each task.
            call check_tasks(model, sweep, error)
            call stop_on(error)
            write (output_unit, '(a)') 'tasks: '//itoa(sweep%tasks)
            do task = 0, sweep%tasks - 1
                write (output_unit, '(a)') 'task '//itoa(task)//': '//task_label(sweep, task) &
                    //' -> '//task_file_name(model%output_file, task, sweep%tasks)
            end do
            call finish(exit_success)
        end if
        task = options%task
        if (task < 0) then
            if (.not. allocated(options%environment_task)) then
                call set_error(error, exit_bad_input, options%input_file//' is a sweep of '// &
                    itoa(sweep%tasks)//' tasks: give --task K (0 to '//itoa(sweep%tasks - 1)// &
                    ') or --list, or submit it as a job array with scripts/submit-sweep')
            else
                task = task_number(options%environment_task, 'SLURM_ARRAY_TASK_ID='// &
                                   options%environment_task, error)
            end if
            call stop_on(error)
        end if
        call check_task(sweep, task, error)
        call stop_on(error)
        problem = task_problem(model, sweep, task)
        if (len(problem) > 0) call set_error(error, exit_bad_input, problem)
        call stop_on(error)
        call apply_task(model, sweep, task)
        write (output_unit, '(a)') 'sweep task '//itoa(task)//' of '//itoa(sweep%tasks)// &
            ': '//task_label(sweep, task)
        if (output_is_complete(model%output_file)) then
            write (output_unit, '(a)') 'task '//itoa(task)//': complete output '// &
                model%output_file//' exists; skipped'
            call finish(exit_success)
        end if
        inquire (file=model%output_file, exist=exists)
        if (exists) write (output_unit, '(a)') 'task '//itoa(task)//': output '// &
            model%output_file//' is incomplete or unreadable; running the task again'
    end subroutine prepare_sweep_task

    !> Print the error, if any, and exit with its code.
    subroutine stop_on(error)
        type(error_type), allocatable, intent(in) :: error

        if (.not. allocated(error)) return
        write (error_unit, '(a)') program_name//': error: '//error%message
        call finish(error%code)
    end subroutine stop_on

    !> Flush and exit with the given status.
    subroutine finish(status)
        integer, intent(in) :: status

        flush (output_unit)
        flush (error_unit)
        call c_exit(int(status, c_int))
    end subroutine finish

end program ddc2d
