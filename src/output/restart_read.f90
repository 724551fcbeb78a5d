!> Read the end of an earlier run from its complete result file (--resume;
!> docs/theory/earth.md#what-a-step-hands-on): the final geometry's end points and fracture ranges,
!> its element results and tips, the growth record and the loading history (every column of their
!> lists, ddc_model_records, that a resumed run goes on from) and the record of a cycle run
!> (ddc_output_cycle_read), bit for bit as written
!> (ddc_output_hdf5). The file was checked before (app/resume_check: complete, same version and
!> model), so a dataset that is missing here is an error of the file.
module ddc_output_restart_read
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_io_failure
    use ddc_model_results, only: growth_record, solver_record, growth_end_names
    use ddc_model_restart, only: restart_state
    use ddc_model_records, only: record_column, record_column_action, &
        for_each_history_column, for_each_growth_column, column_loads, column_growth_steps, &
        column_growing_tips, column_growing_tip_steps, column_records, column_path_records, &
        column_elements, column_strength_steps, column_work_records, column_trials, &
        column_time_steps, column_flow_element_steps, column_flow_steps, column_fracture_steps, &
        column_coupled_element_steps, column_coupled_steps, &
        trial_dataset
    use ddc_output_hdf5_read, only: read_real_dataset, read_int_dataset, read_string_dataset, &
        read_dataset_dims, read_string_attribute, read_int_attribute, read_real_attribute, &
        has_dataset
    use ddc_output_cycle_read, only: read_cycle_record
    implicit none
    private

    public :: read_restart

    !> Reads datasets of one result file; after a failure, nothing more.
    type, extends(record_column_action) :: restart_reader
        !> The result file
        character(len=:), allocatable :: path
        !> Set (exit_io_failure, naming the file and dataset) when a dataset cannot be read
        type(error_type), allocatable :: error
    contains
        procedure :: on_reals => read_real_column
        procedure :: on_integers => read_integer_column
        procedure :: on_real_table => read_real_table
        procedure :: on_integer_table => read_integer_table
        procedure :: on_strings => read_string_column
    end type restart_reader

contains

    !> The restart state of the result file `path`.
    subroutine read_restart(path, state, error)
        !> The earlier run's result file
        character(len=*), intent(in) :: path
        !> Its end
        type(restart_state), intent(out) :: state
        !> Set (exit_io_failure, naming the file) when a dataset cannot be read
        type(error_type), allocatable, intent(out) :: error
        type(restart_reader) :: reader

        reader%path = path
        call read_final_geometry(reader, state)
        call read_last_solve(reader, state%results%solver)
        if (has_dataset(path, '/growth/step')) call read_growth(reader, state%results%growth)
        if (has_dataset(path, '/history/pivots')) call for_each_history_column( &
            state%results%history, reader)
        call move_alloc(reader%error, error)
        if (.not. allocated(error) .and. has_dataset(path, '/cycle/time')) then
            call read_cycle_record(path, state%results%cycle, error)
        end if
    end subroutine read_restart

    !> The final geometry's end points and fracture ranges, its element results and tips.
    subroutine read_final_geometry(reader, state)
        !> The reader
        type(restart_reader), intent(inout) :: reader
        !> The restart state
        type(restart_state), intent(inout) :: state
        integer :: i, e

        call read_reals(reader, '/elements/x_begin', state%x_begin)
        call read_reals(reader, '/elements/y_begin', state%y_begin)
        call read_reals(reader, '/elements/x_end', state%x_end)
        call read_reals(reader, '/elements/y_end', state%y_end)
        call read_integers(reader, '/elements/fracture_id', state%fracture_id)
        call read_integers(reader, '/fractures/first_element', state%first_element)
        call read_integers(reader, '/fractures/last_element', state%last_element)
        associate (r => state%results%elements, path => reader%path)
            call read_reals(reader, '/elements/ds', r%ds)
            call read_reals(reader, '/elements/dn', r%dn)
            call read_integers(reader, '/elements/state', r%state)
            call read_reals(reader, '/elements/shear_traction', r%shear_traction)
            call read_reals(reader, '/elements/normal_traction', r%normal_traction)
            call read_reals(reader, '/elements/us_minus', r%us_minus)
            call read_reals(reader, '/elements/un_minus', r%un_minus)
            call read_reals(reader, '/elements/us_plus', r%us_plus)
            call read_reals(reader, '/elements/un_plus', r%un_plus)
            if (has_dataset(path, '/elements/sf_in_force')) then
                call read_reals(reader, '/elements/sf_in_force', r%sf_in_force)
                call read_reals(reader, '/elements/tensile_strength_in_force', &
                                r%tensile_in_force)
            end if
            if (has_dataset(path, '/elements/mu_in_force')) call read_reals(reader, &
                '/elements/mu_in_force', r%mu_in_force)
            if (has_dataset(path, '/elements/ds_k_memory')) call read_reals(reader, &
                '/elements/ds_k_memory', r%ds_k_memory)
        end associate
        associate (t => state%results%tips)
            call read_reals(reader, '/tips/x', t%x)
            call read_reals(reader, '/tips/y', t%y)
            call read_integers(reader, '/tips/fracture_id', t%fracture_id)
            call read_integers(reader, '/tips/element', t%element)
            call read_reals(reader, '/tips/k1', t%k1)
            call read_reals(reader, '/tips/k2', t%k2)
            call read_integers(reader, '/tips/graded', t%graded)
            if (allocated(reader%error)) return
            ! tip_set%side: 2 at the element's end point, 1 at its begin
            t%n = size(t%x)
            allocate (t%side(t%n))
            do i = 1, t%n
                e = t%element(i)
                t%side(i) = merge(2, 1, t%x(i) == state%x_end(e) .and. &
                                  t%y(i) == state%y_end(e))
            end do
        end associate
    end subroutine read_final_geometry

    !> How the last solve went (/solver: method, fallback, certificate, residual): the record
    !> of the final solution, should the resumed run not solve again.
    subroutine read_last_solve(reader, solver)
        !> The reader
        type(restart_reader), intent(inout) :: reader
        !> The solver record
        type(solver_record), intent(inout) :: solver

        if (allocated(reader%error)) return
        call read_string_attribute(reader%path, '/solver', 'method', solver%method, reader%error)
        if (.not. allocated(reader%error)) call read_string_attribute(reader%path, '/solver', &
            'fallback', solver%fallback, reader%error)
        if (allocated(reader%error)) then
            call reading_failed(reader, '/solver attributes')
            return
        end if
        call real_attribute('certificate_min_z', solver%certificate_min_z)
        call real_attribute('certificate_min_w', solver%certificate_min_w)
        call real_attribute('certificate_max_complementarity', &
                            solver%certificate_max_complementarity)
        call real_attribute('certificate_tolerance', solver%certificate_tolerance)
        call real_attribute('equilibrium_residual', solver%equilibrium_residual)

    contains

        !> A real attribute of /solver.
        subroutine real_attribute(name, target_value)
            character(len=*), intent(in) :: name
            real(wp), intent(inout) :: target_value
            real(wp), allocatable :: value(:)

            if (allocated(reader%error)) return
            call read_real_attribute(reader%path, '/solver', name, value, reader%error)
            if (allocated(reader%error)) then
                call reading_failed(reader, '/solver attribute '//name)
            else
                target_value = value(1)
            end if
        end subroutine real_attribute

    end subroutine read_last_solve

    !> The growth record: its columns, steps_taken and end_reason.
    subroutine read_growth(reader, record)
        !> The reader
        type(restart_reader), intent(inout) :: reader
        !> The growth record
        type(growth_record), intent(inout) :: record
        character(len=:), allocatable :: end_name
        integer :: i

        call for_each_growth_column(record, reader)
        if (allocated(reader%error)) return
        ! Without a load path the file has no load_step: every record is of load step 1.
        if (.not. allocated(record%load_step)) allocate (record%load_step(size(record%step)), &
                                                         source=1)
        ! Under another criterion than 'work' the file has no efficiency and no trials (and a
        ! file of 'work' written before 2026-12-06 no slip share: NaN, not known).
        if (.not. allocated(record%efficiency)) allocate (record%efficiency(size(record%step)), &
                                                          source=0.0_wp)
        if (.not. allocated(record%slip_share)) then
            allocate (record%slip_share(size(record%step)), source=0.0_wp)
            if (has_dataset(reader%path, '/growth/efficiency')) then
                record%slip_share = ieee_value(1.0_wp, ieee_quiet_nan)
            end if
        end if
        if (.not. allocated(record%trials%step)) allocate (record%trials%step(0), &
            record%trials%owner(0), record%trials%state(0), record%trials%angle(0), &
            record%trials%efficiency(0))
        call read_int_attribute(reader%path, '/growth', 'steps_taken', record%steps_taken, &
                                reader%error)
        if (allocated(reader%error)) return
        call read_string_attribute(reader%path, '/growth', 'end_reason', end_name, reader%error)
        if (allocated(reader%error)) return
        record%end_reason = findloc([(trim(growth_end_names(i)) == trim(end_name), &
                                      i = 1, size(growth_end_names))], .true., 1)
        if (record%end_reason == 0) call set_error(reader%error, exit_io_failure, &
            reader%path//': /growth end_reason '''//end_name//''' is not known')
    end subroutine read_growth

    !> Whether the reader reads a column: every column a resumed run goes on from (the loads
    !> follow from the model's path, the tips that may grow and their grown length from the
    !> growth record), those of growth along a load path, of the strengths in force, of time
    !> and of the fluid sources when the file has them.
    logical function reads(reader, column)
        !> The reader
        type(restart_reader), intent(in) :: reader
        !> The column
        type(record_column), intent(in) :: column

        reads = .false.
        if (allocated(reader%error)) return
        select case (column%kind)
        case (column_loads, column_growing_tips, column_growing_tip_steps)
            reads = .false.
        case (column_growth_steps, column_path_records, column_strength_steps, &
              column_work_records, column_trials, column_time_steps, &
              column_flow_element_steps, column_flow_steps, column_fracture_steps, &
              column_coupled_element_steps, column_coupled_steps)
            reads = has_dataset(reader%path, dataset_of(column))
        case default
            reads = .true.
        end select
    end function reads

    !> The path of a column's dataset in the file.
    pure function dataset_of(column) result(dataset)
        !> The column
        type(record_column), intent(in) :: column
        character(len=:), allocatable :: dataset

        select case (column%kind)
        case (column_elements)
            dataset = '/elements/'//column%name
        case (column_records, column_path_records, column_work_records)
            dataset = '/growth/'//column%name
        case (column_trials)
            dataset = '/growth/trials/'//trial_dataset(column%name, .true.)
        case default
            dataset = '/history/'//column%name
        end select
    end function dataset_of

    !> A real column of one value per step or record.
    subroutine read_real_column(action, column, values)
        !> The reader
        class(restart_reader), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        real(wp), allocatable, intent(inout) :: values(:)

        if (reads(action, column)) call read_reals(action, dataset_of(column), values)
    end subroutine read_real_column

    !> An integer column of one value per step or record.
    subroutine read_integer_column(action, column, values)
        !> The reader
        class(restart_reader), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        integer, allocatable, intent(inout) :: values(:)

        if (reads(action, column)) call read_integers(action, dataset_of(column), values)
    end subroutine read_integer_column

    !> A real column of rows and steps, shaped as the file's dataset.
    subroutine read_real_table(action, column, values)
        !> The reader
        class(restart_reader), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        real(wp), allocatable, intent(inout) :: values(:, :)
        real(wp), allocatable :: flat(:)
        integer :: dims(2)

        if (.not. reads(action, column)) return
        call read_reals(action, dataset_of(column), flat)
        call read_table_dims(action, dataset_of(column), dims)
        if (.not. allocated(action%error)) values = reshape(flat, dims)
    end subroutine read_real_table

    !> An integer column of rows and steps, shaped as the file's dataset.
    subroutine read_integer_table(action, column, values)
        !> The reader
        class(restart_reader), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        integer, allocatable, intent(inout) :: values(:, :)
        integer, allocatable :: flat(:)
        integer :: dims(2)

        if (.not. reads(action, column)) return
        call read_integers(action, dataset_of(column), flat)
        call read_table_dims(action, dataset_of(column), dims)
        if (.not. allocated(action%error)) values = reshape(flat, dims)
    end subroutine read_integer_table

    !> A string column of one value per step.
    ! allow(C072): the strings have the lengths of history_record
    subroutine read_string_column(action, column, values)
        !> The reader
        class(restart_reader), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        character(len=*), allocatable, intent(inout) :: values(:)

        if (.not. reads(action, column)) return
        if (allocated(values)) deallocate (values)
        call read_string_dataset(action%path, dataset_of(column), values, action%error)
        if (allocated(action%error)) call reading_failed(action, dataset_of(column))
    end subroutine read_string_column

    !> The values of a real dataset.
    subroutine read_reals(reader, dataset, values)
        !> The reader
        type(restart_reader), intent(inout) :: reader
        !> Path of the dataset in the file
        character(len=*), intent(in) :: dataset
        !> Its values, shape (size of the dataset)
        real(wp), allocatable, intent(inout) :: values(:)

        if (allocated(reader%error)) return
        if (allocated(values)) deallocate (values)
        call read_real_dataset(reader%path, dataset, values, reader%error)
        if (allocated(reader%error)) call reading_failed(reader, dataset)
    end subroutine read_reals

    !> The values of an integer dataset.
    subroutine read_integers(reader, dataset, values)
        !> The reader
        type(restart_reader), intent(inout) :: reader
        !> Path of the dataset in the file
        character(len=*), intent(in) :: dataset
        !> Its values, shape (size of the dataset)
        integer, allocatable, intent(inout) :: values(:)

        if (allocated(reader%error)) return
        if (allocated(values)) deallocate (values)
        call read_int_dataset(reader%path, dataset, values, reader%error)
        if (allocated(reader%error)) call reading_failed(reader, dataset)
    end subroutine read_integers

    !> The dims of a dataset of rows and steps (Fortran order); an error for another rank.
    subroutine read_table_dims(reader, dataset, dims)
        !> The reader
        type(restart_reader), intent(inout) :: reader
        !> Path of the dataset in the file
        character(len=*), intent(in) :: dataset
        !> Rows and steps
        integer, intent(out) :: dims(2)
        integer, allocatable :: extent(:)

        dims = 0
        if (allocated(reader%error)) return
        call read_dataset_dims(reader%path, dataset, extent, reader%error)
        if (.not. allocated(reader%error)) then
            if (size(extent) /= 2) then
                call set_error(reader%error, exit_io_failure, 'it is not a table (rows, steps)')
            else
                dims = extent
            end if
        end if
        if (allocated(reader%error)) call reading_failed(reader, dataset)
    end subroutine read_table_dims

    !> The reader's error names the file and the dataset.
    subroutine reading_failed(reader, dataset)
        !> The reader, its error set
        type(restart_reader), intent(inout) :: reader
        !> Path of the dataset in the file
        character(len=*), intent(in) :: dataset

        reader%error%code = exit_io_failure
        reader%error%message = '--resume '//reader%path//': reading '//dataset//': '// &
            reader%error%message
    end subroutine reading_failed

end module ddc_output_restart_read
