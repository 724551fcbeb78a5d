!> The steps of the ddc2d program around the solve, shared by the serial program (main.f90)
!> and the MPI program (main_mpi.f90, whose first process runs them): before, the command
!> line, the model, the sweep task, the checks of the output paths and the echo; after, the
!> result files and the summary. Each step prints its own errors and returns an exit status,
!> go_on when the program continues; only the programs exit.
module ddc_app_driver
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, int64
    use, intrinsic :: iso_c_binding, only: c_int
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_success, exit_bad_input, exit_stopped_early
    use ddc_version, only: program_name, program_version, git_commit
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results
    use ddc_input_namelist, only: read_namelist_model
    use ddc_input_twodd_deck, only: read_twodd_deck
    use ddc_output_atomic, only: check_writable, check_free_space, resolve_target
    use ddc_output_file_system, only: ignore_file_size_signal
    use ddc_output_hdf5, only: write_results
    use ddc_output_twodd_tables, only: write_twodd_tables
    use ddc_text, only: itoa, prefix_lines
    use ddc_input_sweep, only: read_sweep
    use ddc_sweep_tasks, only: sweep_definition, task_label, task_file_name, check_task, &
        apply_task, task_problem, check_tasks
    use ddc_output_hdf5_read, only: output_is_complete, read_string_attribute
    use ddc_app_command_line, only: command_line_options, parse_command_line, usage_text, &
        action_version, action_help, task_number
    use ddc_app_report, only: print_model_summary, print_results_summary, field_warnings, &
        print_progress
    use ddc_progress, only: set_progress_handler
    use ddc_app_memory, only: check_model_memory, result_file_bytes, table_file_bytes
    use ddc_app_blas, only: check_blas_kernel, choose_blas_threads
    use ddc_app_wait_policy, only: check_wait_policy
    use ddc_app_resume_check, only: check_resume_file
    use ddc_model_fingerprint, only: model_fingerprint
    implicit none
    private

    public :: go_on, prepare_run, error_status, publish_results, finish_run, exit_program

    !> The status of a step after which the program goes on
    integer, parameter :: go_on = -1

    interface
        !> C exit(): the exit status without the compiler's STOP banner.
        subroutine c_exit(status) bind(C, name='exit')
            import :: c_int
            implicit none
            integer(c_int), value :: status
        end subroutine c_exit
    end interface

contains

    !> Everything before the solve: parse the command line (--version, --help), read the
    !> model, select a sweep task (--list; a task whose complete output exists is skipped),
    !> check that the output files can be written, echo the model and check that it fits in
    !> memory (for one process: a run on several holds a share of the matrix in each).
    subroutine prepare_run(options, model, status, processes)
        !> The parsed command line
        type(command_line_options), intent(out) :: options
        !> The model to solve
        type(model_type), intent(out) :: model
        !> go_on, or the exit status of the program (its message printed)
        integer, intent(out) :: status
        !> Number of processes of an MPI run (default 1)
        integer, intent(in), optional :: processes
        type(error_type), allocatable :: error
        character(len=:), allocatable :: blas_echo, openmp_echo, threads_echo

        ! A write beyond ulimit -f must fail and be reported, not kill us (SIGXFSZ).
        call ignore_file_size_signal()
        call parse_command_line(options, error)
        if (allocated(error)) then
            write (error_unit, '(a)') program_name//': error: '//error%message
            write (error_unit, '(a)') 'usage: ddc2d INPUT.nml [-o OUT.h5] [--res RES.txt] '// &
                '[--resume OLD.h5] | '// &
                'ddc2d SWEEP.nml --list | --task K [-o OUT.h5] | '// &
                'ddc2d --twodd DECK [-o OUT.h5] [--res RES.txt]   (ddc2d --help for more)'
            status = error%code
            return
        end if
        select case (options%action)
        case (action_version)
            write (output_unit, '(a)') program_name//' '//program_version//' (git '// &
                git_commit//')'
            status = exit_success
            return
        case (action_help)
            write (output_unit, '(a)') usage_text()
            status = exit_success
            return
        case default
            ! action_run: go on below
        end select
        if (allocated(options%resume_file) .and. present(processes)) then
            if (processes > 1) then
                call set_error(error, exit_bad_input, '--resume runs on one process '// &
                    '(mpiexec -n 1): growth and loading histories are not distributed')
                status = error_status(error)
                return
            end if
        end if
        ! Before anything is read: the serial program may run itself again here.
        call check_wait_policy(.not. present(processes), openmp_echo)
        call check_blas_kernel(.not. present(processes), blas_echo)

        if (options%twodd) then
            call read_twodd_deck(options%input_file, model, error)
        else
            call read_namelist_model(options%input_file, model, error)
        end if
        status = error_status(error)
        if (status /= go_on) return
        if (allocated(options%output_file)) model%output_file = options%output_file
        if (.not. options%twodd) then
            call prepare_sweep_task(options, model, status)
            if (status /= go_on) return
        end if
        ! The model as read: a growth run changes it, its result records this.
        model%fingerprint = model_fingerprint(model)
        if (allocated(options%resume_file)) then
            call check_resume_file(options%resume_file, model, error)
            status = error_status(error)
            if (status /= go_on) return
            call record_resume(options%resume_file, model)
        end if
        call check_writable(model%output_file, error)
        status = error_status(error)
        if (status /= go_on) return
        call check_free_space(model%output_file, result_file_bytes(model), error)
        status = error_status(error)
        if (status /= go_on) return
        if (allocated(options%res_file)) then
            call check_writable(options%res_file, error)
            status = error_status(error)
            if (status /= go_on) return
            call check_free_space(options%res_file, table_file_bytes(model), error)
            status = error_status(error)
            if (status /= go_on) return
        end if
        call choose_blas_threads(2 * model%elements%n, threads_echo)
        call print_model_summary(output_unit, model, units_given=.not. options%twodd)
        write (output_unit, '(a)') blas_echo
        write (output_unit, '(a)') threads_echo
        write (output_unit, '(a)') openmp_echo
        call set_progress_handler(print_progress)
        if (present(processes)) then
            if (processes > 1) then
                write (output_unit, '(a)') '  memory: not estimated for '//itoa(processes)// &
                    ' processes (each holds a share of the influence matrix)'
                return
            end if
        end if
        call check_model_memory(output_unit, model, error)
        status = error_status(error)
    end subroutine prepare_run

    !> Sweeps (docs/sweeps-and-slurm.md): --list prints the tasks (exit 0); otherwise the task
    !> from --task or SLURM_ARRAY_TASK_ID replaces the base model, or is skipped (exit 0) when
    !> its complete output exists. A file without &sweep runs as it is, unless --list or --task
    !> asked for a sweep.
    subroutine prepare_sweep_task(options, model, status)
        type(command_line_options), intent(in) :: options
        type(model_type), intent(inout) :: model
        integer, intent(out) :: status
        type(sweep_definition) :: sweep
        type(error_type), allocatable :: error
        logical :: found, exists
        integer :: task
        character(len=:), allocatable :: problem, final_path

        call read_sweep(options%input_file, model, sweep, found, error)
        status = error_status(error)
        if (status /= go_on) return
        if (found .and. allocated(options%resume_file)) then
            call set_error(error, exit_bad_input, options%input_file//' is a sweep (&sweep): '// &
                           '--resume continues one growth run or loading history, not a '// &
                           'sweep task')
            status = error_status(error)
            return
        end if
        if (.not. found) then
            if (options%list .or. options%task >= 0) then
                call set_error(error, exit_bad_input, options%input_file//' has no &sweep '// &
                               'group: --list and --task are for parameter sweeps')
            end if
            status = error_status(error)
            return
        end if
        if (options%list) then
            ! Every task's model, before anything is submitted; the output folder is made by
            ! the job (submit-sweep creates its --output-dir) and checked by each task.
            call check_tasks(model, sweep, error)
            status = error_status(error)
            if (status /= go_on) return
            write (output_unit, '(a)') 'tasks: '//itoa(sweep%tasks)
            do task = 0, sweep%tasks - 1
                write (output_unit, '(a)') 'task '//itoa(task)//': '//task_label(sweep, task) &
                    //' -> '//task_file_name(model%output_file, task, sweep%tasks)
            end do
            status = exit_success
            return
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
            status = error_status(error)
            if (status /= go_on) return
        end if
        call check_task(sweep, task, error)
        status = error_status(error)
        if (status /= go_on) return
        problem = task_problem(model, sweep, task)
        if (len(problem) > 0) call set_error(error, exit_bad_input, problem)
        status = error_status(error)
        if (status /= go_on) return
        call apply_task(model, sweep, task)
        write (output_unit, '(a)') 'sweep task '//itoa(task)//' of '//itoa(sweep%tasks)// &
            ': '//task_label(sweep, task)
        ! Before anything opens the task file: a FIFO there would block the completeness check.
        call resolve_target(model%output_file, final_path, error)
        status = error_status(error)
        if (status /= go_on) return
        if (output_is_complete(model%output_file)) then
            write (output_unit, '(a)') 'task '//itoa(task)//': complete output '// &
                model%output_file//' exists; skipped'
            status = exit_success
            return
        end if
        inquire (file=model%output_file, exist=exists)
        if (exists) write (output_unit, '(a)') 'task '//itoa(task)//': output '// &
            model%output_file//' is incomplete or unreadable; running the task again'
    end subroutine prepare_sweep_task

    !> Record in the model the file a resumed run continues and when it was written (its root
    !> attribute created), for the result's root attributes.
    subroutine record_resume(path, model)
        !> The earlier run's result file (--resume), checked
        character(len=*), intent(in) :: path
        !> The model
        type(model_type), intent(inout) :: model
        type(error_type), allocatable :: read_error
        character(len=:), allocatable :: created

        call read_string_attribute(path, '/', 'created', created, read_error)
        if (allocated(read_error)) created = 'unknown'
        model%resumed_from = path
        model%resumed_from_created = created
    end subroutine record_resume

    !> Print the error, if any: its exit code, else go_on.
    function error_status(error) result(status)
        !> The error of the last step (unallocated when it succeeded)
        type(error_type), allocatable, intent(in) :: error
        !> error%code, or go_on
        integer :: status

        status = go_on
        if (.not. allocated(error)) return
        write (error_unit, '(a)') program_name//': error: '//error%message
        status = error%code
    end function error_status

    !> Everything after the solve: write the result file (and the TWODD tables of --res),
    !> then print the summary.
    subroutine publish_results(options, model, results, status)
        !> The parsed command line
        type(command_line_options), intent(in) :: options
        !> The model solved
        type(model_type), intent(in) :: model
        !> Its results; the output time is recorded
        type(model_results), intent(inout) :: results
        !> exit_success, or the exit status of a failed write (its message printed)
        integer, intent(out) :: status
        type(error_type), allocatable :: error
        character(len=:), allocatable :: warnings
        integer(int64) :: t0, t1, rate

        call system_clock(t0, rate)
        call write_results(model%output_file, model, results, error)
        status = error_status(error)
        if (status /= go_on) return
        if (allocated(options%res_file)) then
            call write_twodd_tables(options%res_file, model, results, error)
            status = error_status(error)
            if (status /= go_on) return
        end if
        call system_clock(t1)
        results%solver%seconds_output = real(t1 - t0, wp) / real(rate, wp)
        call print_results_summary(output_unit, model, results)
        warnings = field_warnings(model, results)
        if (len(warnings) > 0) write (error_unit, '(a)') prefix_lines(program_name// &
            ': warning: ', warnings)
        status = exit_success
    end subroutine publish_results

    !> After the solve: the results published, also those of a run that stopped early
    !> (exit_stopped_early: the steps it completed), then its error printed.
    subroutine finish_run(options, model, results, error, status)
        !> The parsed command line
        type(command_line_options), intent(in) :: options
        !> The model solved
        type(model_type), intent(in) :: model
        !> Its results
        type(model_results), intent(inout) :: results
        !> The solve's error, if any
        type(error_type), allocatable, intent(in) :: error
        !> The exit status of the program
        integer, intent(out) :: status

        if (allocated(error)) then
            if (error%code /= exit_stopped_early) then
                status = error_status(error)
                return
            end if
        end if
        call publish_results(options, model, results, status)
        if (status == exit_success .and. allocated(error)) status = error_status(error)
    end subroutine finish_run

    !> Flush and exit with the given status.
    subroutine exit_program(status)
        !> The exit status
        integer, intent(in) :: status

        flush (output_unit)
        flush (error_unit)
        call c_exit(int(status, c_int))
    end subroutine exit_program

end module ddc_app_driver
