!> ddc2d: read a model, solve it, write the results. The only place that prints errors and
!> sets the exit status.
program ddc2d
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use, intrinsic :: iso_c_binding, only: c_int
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, exit_success
    use ddc_version, only: program_name, program_version, git_commit
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results
    use ddc_model_types, only: symmetry_none
    use ddc_input_namelist, only: read_namelist_model
    use ddc_input_twodd_deck, only: read_twodd_deck
    use ddc_output_atomic, only: check_writable
    use ddc_output_hdf5, only: write_results
    use ddc_output_twodd_tables, only: write_twodd_tables
    use ddc_run, only: run_model
    use ddc_app_command_line, only: command_line_options, parse_command_line, usage_text, &
        action_version, action_help
    use ddc_app_report, only: print_model_summary, print_results_summary
    implicit none

    interface
        !> C exit(): the exit status without the compiler's STOP banner.
        subroutine c_exit(status) bind(C, name='exit')
            import :: c_int
            integer(c_int), value :: status
        end subroutine c_exit
    end interface

    type(command_line_options) :: options
    type(model_type) :: model
    type(model_results) :: results
    type(error_type), allocatable :: error
    integer(8) :: t0, t1, rate

    call parse_command_line(options, error)
    if (allocated(error)) then
        write (error_unit, '(a)') program_name//': error: '//error%message
        write (error_unit, '(a)') 'usage: ddc2d INPUT.nml [-o OUT.h5] [--res RES.txt] | '// &
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
    end select

    if (options%twodd) then
        call read_twodd_deck(options%input_file, model, error)
    else
        call read_namelist_model(options%input_file, model, error)
    end if
    call stop_on(error)
    if (allocated(options%output_file)) model%output_file = options%output_file
    call check_writable(model%output_file, error)
    call stop_on(error)
    if (allocated(options%res_file)) then
        call check_writable(options%res_file, error)
        call stop_on(error)
    end if
    call print_model_summary(output_unit, model)
    if (model%elements%symmetry%kind /= symmetry_none) then
        write (output_unit, '(a,i0,a,g0,a,g0,a)') '  symmetry KSYM = ', model%elements%symmetry%kind, &
            ' (xsym = ', model%elements%symmetry%xsym, ', ysym = ', model%elements%symmetry%ysym, &
            '): image elements implicit'
    end if

    call run_model(model, results, error)
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
    call finish(exit_success)

contains

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
