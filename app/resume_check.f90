!> Whether a result file can be continued by a model (--resume OLD.h5;
!> docs/theory/earth.md#what-a-step-hands-on): it is a complete ddc2d result of this program
!> version (or a cycle run's checkpoint), of a model with the same fingerprint
!> (ddc_model_fingerprint: the same input apart from &growth steps, the load path and &cycle
!> end_time), and a growth run and/or loading history or a cycle run as the model is; a cycle
!> run that stopped (an effective normal stress at zero) does not go on; a loading history's
!> steps are the first steps of the model's path:
!>
!>     |load_new(q, j) - load_old(q, j)| <= 1e-12 * max_j(|load_old(q, j)|, |load_new(q, j)|)
!>
!> for every quantity q of load_path_names and every step j of the earlier run. Every
!> refusal is exit_bad_input with one message naming the file; nothing is written. Another
!> model is named by the first group and variable written differently in the two inputs
!> (ddc_app_input_difference), the fingerprints where the texts read alike.
module ddc_app_resume_check
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_version, only: program_name, program_version
    use ddc_model_types, only: model_type, load_path_names
    use ddc_model_fingerprint, only: recorded_fingerprint
    use ddc_history_path, only: path_loads, path_step_count
    use ddc_output_atomic, only: resolve_target
    use ddc_output_file_system, only: path_kind, kind_missing
    use ddc_output_hdf5_read, only: is_hdf5_file, output_is_complete, read_string_attribute, &
        read_real_dataset, has_dataset
    use ddc_model_cycles, only: cycle_end_names, cycle_running, cycle_end_time
    use ddc_text, only: itoa, rtoa, counted
    use ddc_app_input_difference, only: input_difference
    implicit none
    private

    public :: check_resume_file

    !> Relative tolerance of the loads of the earlier run's steps [-]
    real(wp), parameter :: load_tolerance = 1.0e-12_wp

contains

    !> Refuse (exit_bad_input) a result file the model cannot continue.
    subroutine check_resume_file(path, model, error)
        !> The earlier run's result file (--resume)
        character(len=*), intent(in) :: path
        !> The validated model, its fingerprint recorded (model%fingerprint)
        type(model_type), intent(in) :: model
        !> Allocated with exit_bad_input and one message naming path when it does not fit
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: read_error
        character(len=:), allocatable :: prefix, final_path, description, value, input, change
        logical :: growth_run, history_run, cycle_run
        integer :: kind

        prefix = '--resume '//path//': '
        input = 'the input'
        if (allocated(model%input_file)) input = model%input_file
        if (.not. (model%growth%active .or. allocated(model%load_path%vertex) .or. &
                   model%cycle%active)) then
            call refuse('--resume continues a growth run, a loading history or a cycle run, '// &
                        'and '//input//' has none of &growth, &load_path, &cycle')
            return
        end if
        call resolve_target(path, final_path, read_error)
        call path_kind(final_path, kind, description)
        if (allocated(read_error)) then
            call refuse('is a '//description//', not a result file')
            return
        else if (kind == kind_missing) then
            call refuse('does not exist')
            return
        end if
        if (.not. is_hdf5_file(path)) then
            call refuse('is not an HDF5 file (or not readable)')
            return
        end if
        cycle_run = has_dataset(path, '/cycle/time')
        ! A cycle run's checkpoint is complete but for its end: it goes on.
        if (.not. (output_is_complete(path) .or. (cycle_run .and. model%cycle%active))) then
            call refuse('is incomplete: the run that wrote it did not finish (no complete = 1)')
            return
        end if
        call read_string_attribute(path, '/', 'version', value, read_error)
        if (allocated(read_error)) value = 'an unknown version'
        if (value /= program_version) then
            call refuse('was written by '//program_name//' '//value//', this is '// &
                        program_version//': resume with the version that wrote it')
            return
        end if
        growth_run = has_dataset(path, '/growth/step')
        history_run = has_dataset(path, '/history/sxx')
        if (model%cycle%active .or. cycle_run) then
            call check_cycle_run()
        else if (.not. (growth_run .or. history_run)) then
            call refuse('holds neither a growth run (/growth) nor a loading history '// &
                        '(/history): there is nothing to continue')
        else if (growth_run .and. .not. model%growth%active) then
            call refuse('is a growth run, and '//input//' has no &growth')
        else if (model%growth%active .and. .not. growth_run) then
            call refuse('is not a growth run (no /growth), and '//input//' has &growth')
        else if (history_run .and. .not. allocated(model%load_path%vertex)) then
            call refuse('holds a loading history, and '//input//' has no &load_path')
        else if (allocated(model%load_path%vertex) .and. .not. history_run) then
            call refuse('holds no loading history (/history), and '//input//' has a &load_path')
        end if
        if (allocated(error)) return
        call read_string_attribute(path, '/', 'model_fingerprint', value, read_error)
        if (allocated(read_error)) value = 'none'
        if (value /= recorded_fingerprint(model)) then
            change = changed_input(path, model)
            if (len(change) > 0) then
                call refuse('is the result of another model: '//change//' (only &growth '// &
                            'steps, the length of &load_path and &cycle end_time may change)')
            else
                call refuse('is the result of another model: its fingerprint is '//value// &
                            ', that of '//input//' is '//recorded_fingerprint(model)// &
                            ' (only &growth steps, the length of &load_path and &cycle '// &
                            'end_time may change)')
            end if
            return
        end if
        if (history_run) call check_path_prefix(path, model, prefix, input, error)

    contains

        subroutine refuse(message)
            character(len=*), intent(in) :: message

            call set_error(error, exit_bad_input, prefix//message)
        end subroutine refuse

        !> A cycle run goes on from a cycle run that reached its end time or a checkpoint.
        subroutine check_cycle_run()
            type(error_type), allocatable :: failed
            character(len=:), allocatable :: reason

            if (.not. cycle_run) then
                call refuse('is not a cycle run (no /cycle), and '//input//' has &cycle')
                return
            else if (.not. model%cycle%active) then
                call refuse('is a cycle run, and '//input//' has no &cycle')
                return
            end if
            call read_string_attribute(path, '/cycle', 'end_reason', reason, failed)
            if (allocated(failed)) reason = 'unknown'
            if (reason /= trim(cycle_end_names(cycle_running)) .and. &
                reason /= trim(cycle_end_names(cycle_end_time))) call refuse('is a cycle run '// &
                "that stopped (end_reason '"//reason//"'): it cannot go on")
        end subroutine check_cycle_run
    end subroutine check_resume_file

    !> Which group and variable of the input differ from the earlier run's (its root
    !> attribute input_text; ddc_app_input_difference), '' when that cannot be said.
    function changed_input(path, model) result(change)
        character(len=*), intent(in) :: path
        type(model_type), intent(in) :: model
        character(len=:), allocatable :: change, old_text
        type(error_type), allocatable :: read_error

        change = ''
        if (.not. allocated(model%input_text)) return
        call read_string_attribute(path, '/', 'input_text', old_text, read_error)
        if (allocated(read_error)) return
        ! A long input is the dataset /input_text, and the attribute only says so.
        if (index(old_text, 'the input (') == 1) return
        change = input_difference(old_text, model%input_text)
    end function changed_input

    !> The earlier run's loads are the first steps of the model's path.
    subroutine check_path_prefix(path, model, prefix, input, error)
        character(len=*), intent(in) :: path, prefix, input
        type(model_type), intent(in) :: model
        type(error_type), allocatable, intent(inout) :: error
        type(error_type), allocatable :: read_error
        real(wp), allocatable :: loads(:, :), old(:)
        real(wp) :: fixed(7), scale
        integer :: q, j, steps

        steps = 0
        ! Allocated first: gfortran -Og warns of the descriptor of a bare assignment here.
        allocate (loads(size(load_path_names), path_step_count(model%load_path)))
        loads = path_loads(model%load_path)
        fixed = [model%sxx, model%syy, model%sxy, model%stress_gradient, model%pore_fluid(1)]
        do q = 1, size(load_path_names)
            ! A quantity the earlier path did not vary held the model's (hashed) value.
            call read_real_dataset(path, '/history/'//trim(load_path_names(q)), old, &
                                   read_error)
            if (allocated(read_error)) then
                if (q <= 3) then
                    call set_error(error, exit_bad_input, prefix//'its loading history '// &
                                   'cannot be read: '//read_error%message)
                    return
                end if
                old = spread(fixed(q), 1, steps)
            end if
            if (q == 1) then
                steps = size(old)
                if (size(loads, 2) < steps) then
                    call set_error(error, exit_bad_input, prefix//'the &load_path of '// &
                        input//' has '//itoa(size(loads, 2))//' steps, fewer than the '// &
                        itoa(steps)//' of the earlier run: a resumed path is at least as long')
                    return
                end if
            end if
            if (size(old) /= steps) then
                call set_error(error, exit_bad_input, prefix//'its loading history has '// &
                               counted(size(old), 'value', 'values')//' of '// &
                               trim(load_path_names(q))//', not one per step ('// &
                               itoa(steps)//')')
                return
            end if
            scale = max(maxval(abs(old(1:steps))), maxval(abs(loads(q, 1:steps))))
            do j = 1, steps
                if (abs(loads(q, j) - old(j)) > load_tolerance * scale) then
                    call set_error(error, exit_bad_input, prefix//'step '//itoa(j)// &
                        ' of the &load_path of '//input//' has '//trim(load_path_names(q))// &
                        ' = '//rtoa(loads(q, j))//', the earlier run had '//rtoa(old(j))// &
                        ': the path may only go on after the earlier run''s '//itoa(steps)// &
                        ' steps')
                    return
                end if
            end do
        end do
    end subroutine check_path_prefix

end module ddc_app_resume_check
