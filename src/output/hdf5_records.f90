!> The records of a run in the result file (ddc_output_hdf5's layout): /history, /growth
!> and the growth record's per-element column in /elements, one dataset per column of the
!> record's list (ddc_model_records) with its units or coding.
module ddc_output_hdf5_records
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_text, only: allocated_text
    use ddc_model_types, only: model_type, load_path_names, growth_tips_names, &
        growth_criterion_names, growth_criterion_work, work_mode_names, angle_search_names
    use ddc_model_results, only: history_record, growth_record, growth_end_names
    use ddc_model_loads, only: work_threshold_of
    use ddc_model_records, only: record_column, record_column_action, &
        for_each_history_column, for_each_growth_column, reason_coding, column_loads, &
        column_path_records, column_elements, column_work_records, column_trials, units_text, &
        trial_dataset
    use ddc_output_hdf5_handles, only: h5_object, create_group, close_group
    use ddc_output_hdf5_write, only: write_real_1d, write_int_1d, write_real_dataset, &
        write_int_dataset, write_string_1d, write_attribute
    implicit none
    private

    public :: write_history, write_growth, write_growth_elements
    public :: column_writer, set_up

    !> Writes each column it is handed into a group: every allocated column of the group's
    !> kinds.
    type, extends(record_column_action) :: column_writer
        !> The group the datasets go to, and /growth/trials (criterion 'work')
        type(h5_object) :: group, trials
        !> Unit names of the model
        character(len=:), allocatable :: length, stress, time
        !> Which load quantities the load path varies (load_path_names), shape (7)
        logical :: varies(size(load_path_names)) = .false.
        !> The model has a load path
        logical :: load_path = .false.
        !> Write the per-element columns (the group is /elements) instead of the others
        logical :: elements = .false.
        !> Write the work criterion's columns (the trials into group trials)
        logical :: work = .false.
        !> The trials are the tips' (/growth/trials), not the flaws' (ddc_model_records'
        !> trial_dataset)
        logical :: tip_trials = .false.
        !> Set when a write fails
        type(error_type), allocatable :: error
    contains
        procedure :: on_reals => write_reals
        procedure :: on_integers => write_integers
        procedure :: on_real_table => write_real_table
        procedure :: on_integer_table => write_integer_table
        procedure :: on_strings => write_strings
    end type column_writer

contains

    !> /history: the load the path varies, DDs, states, tractions, K and how each step was
    !> solved, at every step of a loading history; the increments of each leg.
    subroutine write_history(root, model, history, error)
        !> The file
        type(h5_object), intent(in) :: root
        !> The model that was solved
        type(model_type), intent(in) :: model
        !> Its loading history
        type(history_record), intent(in) :: history
        !> Set when a write fails (nothing is written when it is set already)
        type(error_type), allocatable, intent(inout) :: error
        type(column_writer) :: writer
        type(history_record) :: columns

        call create_group(root, 'history', writer%group, error)
        if (allocated(error)) return
        call set_up(writer, model)
        ! The list hands out columns to change: the writer gets a copy of them.
        columns = history
        call for_each_history_column(columns, writer)
        call write_int_1d(writer%group, 'leg_steps', model%load_path%steps, writer%error)
        call close_group(writer%group, writer%error)
        call move_alloc(writer%error, error)
    end subroutine write_history

    !> /growth: one record per tip per step of a fracture growth run, and its settings.
    subroutine write_growth(root, model, record, error)
        !> The file
        type(h5_object), intent(in) :: root
        !> The model that was solved (its input geometry and &growth options)
        type(model_type), intent(in) :: model
        !> Its growth record
        type(growth_record), intent(in) :: record
        !> Set when a write fails (nothing is written when it is set already)
        type(error_type), allocatable, intent(inout) :: error
        type(column_writer) :: writer
        type(growth_record) :: columns

        call create_group(root, 'growth', writer%group, error)
        if (allocated(error)) return
        call set_up(writer, model)
        writer%work = model%growth%criterion == growth_criterion_work
        writer%tip_trials = .true.
        if (writer%work) then
            call create_group(writer%group, 'trials', writer%trials, writer%error)
            call write_attribute(writer%group, 'work_threshold', work_threshold_of( &
                model%growth, model%youngs_modulus, model%poissons_ratio), writer%error)
            call write_attribute(writer%group, 'work_mode', &
                                 trim(work_mode_names(model%growth%work_mode)), writer%error)
            call write_attribute(writer%group, 'angle_search', &
                                 trim(angle_search_names(model%growth%angle_search)), writer%error)
        end if
        columns = record
        call for_each_growth_column(columns, writer)
        if (writer%work) call close_group(writer%trials, writer%error)
        associate (group => writer%group, o => model%growth)
            call write_attribute(group, 'toughness', o%toughness, writer%error)
            ! 0: the default (per tip: twice / once the tip element's length)
            call write_attribute(group, 'increment', o%increment, writer%error)
            call write_attribute(group, 'element_length', o%element_length, writer%error)
            call write_attribute(group, 'tips', trim(growth_tips_names(o%tips)), writer%error)
            call write_attribute(group, 'criterion', trim(growth_criterion_names(o%criterion)), &
                                 writer%error)
            call write_attribute(group, 'max_corrections', o%max_corrections, writer%error)
            call write_attribute(group, 'fractures', growing_fractures(model), writer%error)
            call write_attribute(group, 'steps', o%steps, writer%error)
            call write_attribute(group, 'steps_taken', record%steps_taken, writer%error)
            call write_attribute(group, 'end_reason', trim(growth_end_names(record%end_reason)), &
                                 writer%error)
            ! Only a run that stopped at a failed step has it.
            if (allocated(record%failure)) call write_attribute(group, 'failure', &
                                                                record%failure, writer%error)
            call write_attribute(group, 'reason_coding', reason_coding(), writer%error)
        end associate
        call close_group(writer%group, writer%error)
        call move_alloc(writer%error, error)
    end subroutine write_growth

    !> The growth record's columns of one value per element of the final geometry, into
    !> /elements.
    subroutine write_growth_elements(elements, model, record, error)
        !> The group /elements
        type(h5_object), intent(in) :: elements
        !> The model that was solved
        type(model_type), intent(in) :: model
        !> Its growth record
        type(growth_record), intent(in) :: record
        !> Set when a write fails (nothing is written when it is set already)
        type(error_type), allocatable, intent(inout) :: error
        type(column_writer) :: writer
        type(growth_record) :: columns

        writer%group = elements
        writer%elements = .true.
        call set_up(writer, model)
        call move_alloc(error, writer%error)
        columns = record
        call for_each_growth_column(columns, writer)
        call move_alloc(writer%error, error)
    end subroutine write_growth_elements

    !> The writer's view of the model: units, load path.
    subroutine set_up(writer, model)
        !> The writer
        type(column_writer), intent(inout) :: writer
        !> The model that was solved
        type(model_type), intent(in) :: model

        writer%length = allocated_text(model%length_unit)
        writer%stress = allocated_text(model%stress_unit)
        writer%time = allocated_text(model%time_unit)
        writer%load_path = allocated(model%load_path%vertex)
        writer%varies = model%load_path%varies
    end subroutine set_up

    !> Whether the writer writes a column (allocated, of its group, in the file of this
    !> model).
    pure logical function writes(writer, column, there)
        !> The writer
        type(column_writer), intent(in) :: writer
        !> The column
        type(record_column), intent(in) :: column
        !> Whether the column is allocated
        logical, intent(in) :: there

        writes = there .and. (column%kind == column_elements .eqv. writer%elements)
        if (column%kind == column_path_records) writes = writes .and. writer%load_path
        if (column%kind == column_work_records .or. column%kind == column_trials) then
          writes = writes .and. writer%work
        end if
    end function writes

    !> The group a column of one value per step, record or trial goes to.
    function group_of(writer, column) result(group)
        !> The writer
        type(column_writer), intent(in) :: writer
        !> The column
        type(record_column), intent(in) :: column
        type(h5_object) :: group

        group = writer%group
        if (column%kind == column_trials) group = writer%trials
    end function group_of

    !> The dataset of a column in its group.
    pure function dataset_of(writer, column) result(name)
        !> The writer
        type(column_writer), intent(in) :: writer
        !> The column
        type(record_column), intent(in) :: column
        character(len=:), allocatable :: name

        name = column%name
        if (column%kind == column_trials) name = trial_dataset(column%name, writer%tip_trials)
    end function dataset_of

    !> The units attribute of a real column.
    pure function units_of(writer, column) result(units)
        !> The writer
        type(column_writer), intent(in) :: writer
        !> The column
        type(record_column), intent(in) :: column
        character(len=:), allocatable :: units

        units = units_text(column%units, writer%stress, writer%length, writer%time)
    end function units_of

    !> A real column of one value per step or record.
    subroutine write_reals(action, column, values)
        !> The writer
        class(column_writer), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        real(wp), allocatable, intent(inout) :: values(:)

        if (.not. writes(action, column, allocated(values))) return
        call write_real_1d(group_of(action, column), dataset_of(action, column), values, &
                           units_of(action, column), action%error)
    end subroutine write_reals

    !> An integer column of one value per step or record, with its coding.
    subroutine write_integers(action, column, values)
        !> The writer
        class(column_writer), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        integer, allocatable, intent(inout) :: values(:)

        if (.not. writes(action, column, allocated(values))) return
        call write_int_1d(group_of(action, column), dataset_of(action, column), values, &
                          action%error, column%coding)
    end subroutine write_integers

    !> A real column of rows and steps; the load: one dataset per quantity the path varies
    !> (the remote stress always).
    subroutine write_real_table(action, column, values)
        !> The writer
        class(column_writer), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        real(wp), allocatable, intent(inout) :: values(:, :)
        real(wp), allocatable :: row(:)
        character(len=:), allocatable :: units
        integer :: q

        if (.not. writes(action, column, allocated(values))) return
        if (column%kind /= column_loads) then
            call write_real_dataset(action%group, column%name, reshape(values, [size(values)]), &
                                    shape(values), units_of(action, column), action%error)
            return
        end if
        do q = 1, size(load_path_names)
            if (q > 3 .and. .not. action%varies(q)) cycle
            units = units_of(action, column)
            ! The gradients d/dy
            if (q >= 4 .and. q <= 6) units = units//'/'//action%length
            ! A row is strided: copied here, not as a hidden temporary
            row = values(q, :)
            call write_real_1d(action%group, trim(load_path_names(q)), row, units, action%error)
        end do
    end subroutine write_real_table

    !> An integer column of rows and steps, with its coding.
    subroutine write_integer_table(action, column, values)
        !> The writer
        class(column_writer), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        integer, allocatable, intent(inout) :: values(:, :)

        if (.not. writes(action, column, allocated(values))) return
        call write_int_dataset(action%group, column%name, reshape(values, [size(values)]), &
                               shape(values), action%error, column%coding)
    end subroutine write_integer_table

    !> A string column of one value per step.
    ! allow(C072): the strings have the lengths of history_record
    subroutine write_strings(action, column, values)
        !> The writer
        class(column_writer), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        character(len=*), allocatable, intent(inout) :: values(:)

        if (.not. writes(action, column, allocated(values))) return
        call write_string_1d(action%group, column%name, values, action%error)
    end subroutine write_strings

    !> Names of the fractures whose tips may grow, comma separated.
    function growing_fractures(model) result(names)
        type(model_type), intent(in) :: model
        character(len=:), allocatable :: names
        integer :: f

        names = ''
        do f = 1, size(model%fractures)
            if (.not. model%growth%fracture_grows(f)) cycle
            if (len(names) > 0) names = names//', '
            names = names//allocated_text(model%fractures(f)%name)
        end do
    end function growing_fractures

end module ddc_output_hdf5_records
