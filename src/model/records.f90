!> The columns of the records a run keeps: every step of a loading history (history_record)
!> and every tip of every growth step (growth_record), each with what the result file needs
!> of it (dataset name, units, coding) and its kind (its rows and steps).
!>
!> for_each_history_column and for_each_growth_column are the one list of each record's
!> columns: the layout of a record (lay_out_history, empty_growth_record), the HDF5 writer
!> (ddc_output_hdf5_records) and the restart reader (ddc_output_restart_read) go through
!> them. A new column is declared in its type (ddc_model_results), listed here, and given
!> its values where the run computes them; the CTest architecture fails when a column is
!> missing from its list, and when the Python reader (python/src/ddc2d/reader.py) does not
!> know its dataset.
module ddc_model_records
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_text, only: itoa
    use ddc_model_types, only: load_path_names
    use ddc_model_results, only: history_record, tip_records, growth_record, state_not_grown, &
        growth_reason_names, trial_state_coding
    use ddc_model_trial_records, only: trial_records
    use ddc_model_initiations, only: initiation_record
    implicit none
    private

    public :: record_column, record_column_action
    public :: for_each_history_column, for_each_growth_column, for_each_initiation_column
    public :: lay_out_history, empty_growth_record, reason_coding, trial_dataset
    public :: lay_out_tip_rows, append_tip_rows, append_trial_rows, append_initiation, &
        empty_initiation_record
    public :: column_loads, column_element_steps, column_tip_steps, column_steps, &
        column_growth_steps, column_growing_tips, column_growing_tip_steps, column_records, &
        column_path_records, column_elements, column_strength_steps, column_work_records, &
        column_trials, column_time_steps, column_flow_element_steps, column_flow_steps, &
        column_fracture_steps, column_coupled_element_steps, column_coupled_steps
    public :: units_none, units_length, units_stress, units_k, units_degree, units_one, units_work
    public :: units_stiffness, units_time, units_area, units_moment, units_text, units_flux
    public :: state_coding

    !> Kinds of history columns, by their shape: the load (one row per quantity of
    !> load_path_names, k), per element (n, k), per tip (tips, k), per step (k); with fracture
    !> growth along a load path only: per step (k), per tip that may grow (tips), per tip that
    !> may grow and step (tips, k)
    integer, parameter :: column_loads = 1, column_element_steps = 2, column_tip_steps = 3, &
                          column_steps = 4, column_growth_steps = 5, column_growing_tips = 6, &
                          column_growing_tip_steps = 7
    !> Kinds of growth record columns: one value per record (k); one per record that the file
    !> holds along a load path only (1 without one); one per element of the final geometry
    !> (n, in /elements)
    integer, parameter :: column_records = 8, column_path_records = 9, column_elements = 10
    !> A history column per element (n, k) laid out only where the strengths in force can
    !> change (lay_out_history's strengths) or it is there already
    integer, parameter :: column_strength_steps = 11
    !> Growth record columns of the work criterion only: one value per record (k, in /growth);
    !> one per trial (t, in /growth/trials)
    integer, parameter :: column_work_records = 12, column_trials = 13
    !> History columns of a path with a time axis only: one value per step (k); of a model
    !> with fluid sources only (docs/injection.md#output): per element (n, k), per step
    !> (k), per fracture (fractures, k)
    integer, parameter :: column_time_steps = 14, column_flow_element_steps = 15, &
                          column_flow_steps = 16, column_fracture_steps = 17, &
                          column_coupled_element_steps = 18, column_coupled_steps = 19

    !> What the values of a column (or of a strength law, ddc_model_laws) measure, for its
    !> units attribute: nothing (integers and strings), length, stress, stress intensity
    !> (stress * length**0.5), angle in degrees, a ratio, work per length (stress * length),
    !> a joint stiffness (stress / length), time, a volume per unit length out of the plane
    !> (length^2), a seismic moment per unit length out of the plane (stress * length^2), a
    !> flux per unit length out of the plane (length^2 / time)
    integer, parameter :: units_none = 0, units_length = 1, units_stress = 2, units_k = 3, &
                          units_degree = 4, units_one = 5, units_work = 6, units_stiffness = 7, &
                          units_time = 8, units_area = 9, units_moment = 10, units_flux = 11

    !> Coding of the element states (/elements/state and the history's)
    character(len=*), parameter :: state_coding = '0 free (TWODD-style condition), ' &
        //'1 stick, 2 slip, 3 open'
    !> Coding of the tip ends
    character(len=*), parameter :: tip_end_coding = '0 begin tip, 1 end tip'
    !> Coding of the side a new fracture starts on
    character(len=*), parameter :: side_coding = '+1 the side of the element normal '// &
                                  '(-sin beta, cos beta), -1 the other, 0 a flaw'

    !> One column of a record: what the file needs of it and its kind.
    type :: record_column
        !> Dataset name (the name of the component)
        character(len=:), allocatable :: name
        !> column_loads ... column_elements
        integer :: kind = 0
        !> units_none ... units_work
        integer :: units = units_none
        !> Coding of an integer column; unallocated when it has none (passed on as an absent
        !> optional argument)
        character(len=:), allocatable :: coding
    end type record_column

    !> What a routine does with every column of a record: it extends this type with its data
    !> and is handed each column by for_each_history_column or for_each_growth_column (a
    !> growth record has 1-D real and integer columns only).
    type, abstract :: record_column_action
    contains
        !> Act on a real column of one value per step or record
        procedure(act_on_reals), deferred :: on_reals
        !> Act on an integer column of one value per step or record
        procedure(act_on_integers), deferred :: on_integers
        !> Act on a real column of rows and steps
        procedure(act_on_real_table), deferred :: on_real_table
        !> Act on an integer column of rows and steps
        procedure(act_on_integer_table), deferred :: on_integer_table
        !> Act on a string column of one value per step
        procedure(act_on_strings), deferred :: on_strings
    end type record_column_action

    abstract interface
        !> Act on a real column, shape (k) or unallocated
        subroutine act_on_reals(action, column, values)
            import :: record_column_action, record_column, wp
            implicit none
            !> The action and its data
            class(record_column_action), intent(inout) :: action
            !> What the column is
            type(record_column), intent(in) :: column
            !> Its values
            real(wp), allocatable, intent(inout) :: values(:)
        end subroutine act_on_reals

        !> Act on an integer column, shape (k) or unallocated
        subroutine act_on_integers(action, column, values)
            import :: record_column_action, record_column
            implicit none
            !> The action and its data
            class(record_column_action), intent(inout) :: action
            !> What the column is
            type(record_column), intent(in) :: column
            !> Its values
            integer, allocatable, intent(inout) :: values(:)
        end subroutine act_on_integers

        !> Act on a real column, shape (rows, k) or unallocated
        subroutine act_on_real_table(action, column, values)
            import :: record_column_action, record_column, wp
            implicit none
            !> The action and its data
            class(record_column_action), intent(inout) :: action
            !> What the column is
            type(record_column), intent(in) :: column
            !> Its values
            real(wp), allocatable, intent(inout) :: values(:, :)
        end subroutine act_on_real_table

        !> Act on an integer column, shape (rows, k) or unallocated
        subroutine act_on_integer_table(action, column, values)
            import :: record_column_action, record_column
            implicit none
            !> The action and its data
            class(record_column_action), intent(inout) :: action
            !> What the column is
            type(record_column), intent(in) :: column
            !> Its values
            integer, allocatable, intent(inout) :: values(:, :)
        end subroutine act_on_integer_table

        !> Act on a string column, shape (k) or unallocated
        ! allow(C072): the strings have the lengths of history_record
        subroutine act_on_strings(action, column, values)
            import :: record_column_action, record_column
            implicit none
            !> The action and its data
            class(record_column_action), intent(inout) :: action
            !> What the column is
            type(record_column), intent(in) :: column
            !> Its values
            character(len=*), allocatable, intent(inout) :: values(:)
        end subroutine act_on_strings
    end interface

    !> A record laid out anew (lay_out_history, empty_growth_record).
    type, extends(record_column_action) :: record_layout
        !> Rows of the element columns, of the tip columns; steps (records) of every column;
        !> the first steps kept
        integer :: rows = 0, tips = 0, steps = 0, kept = 0
        !> The row of the record that each element row takes (0: none), shape (rows)
        integer, allocatable :: origin(:)
        !> Lay out the columns of growth along a load path that are not there yet
        logical :: growth = .false.
        !> Lay out the columns of the strengths in force that are not there yet
        logical :: strengths = .false.
        !> Lay out the columns of a time axis, of the fluid sources (rows of the fracture
        !> columns: fractures), that are not there yet
        logical :: time = .false., flow = .false.
        integer :: fractures = 0
        !> Lay out the columns of coupled flow (&fluid) that are not there yet
        logical :: coupled = .false.
        !> The stat of an allocation that failed (0: none)
        integer :: stat = 0
    contains
        procedure :: on_reals => lay_out_reals
        procedure :: on_integers => lay_out_integers
        procedure :: on_real_table => lay_out_real_table
        procedure :: on_integer_table => lay_out_integer_table
        procedure :: on_strings => lay_out_strings
    end type record_layout

    !> The values of one column, kept by column_collector
    type :: real_values
        character(len=:), allocatable :: name
        real(wp), allocatable :: values(:)
    end type real_values
    type :: integer_values
        character(len=:), allocatable :: name
        integer, allocatable :: values(:)
    end type integer_values

    !> Collects the values of every 1-D column of rows it is handed (those keep marks; all
    !> when keep is unallocated), in the list's order, for column_appender.
    type, extends(record_column_action) :: column_collector
        logical, allocatable :: keep(:)
        type(real_values), allocatable :: reals(:)
        type(integer_values), allocatable :: integers(:)
        !> A column it was handed that is not of rows (none in a list of rows)
        character(len=:), allocatable :: refused
    contains
        procedure :: on_reals => collect_reals
        procedure :: on_integers => collect_integers
        procedure :: on_real_table => refuse_real_table
        procedure :: on_integer_table => refuse_integer_table
        procedure :: on_strings => refuse_strings
    end type column_collector

    !> Appends the collected values to the columns it is handed, in the list's order (a
    !> column collected unallocated is left as it is).
    type, extends(column_collector) :: column_appender
        integer :: real_at = 0, integer_at = 0
    contains
        procedure :: on_reals => append_reals
        procedure :: on_integers => append_integers
    end type column_appender

contains

    !> The one list of the columns of a history_record (docs/loading-histories.md#output,
    !> docs/fracture-growth.md#output): the action gets each column once, in the order of the
    !> file's datasets. A new column is declared in the type and listed here; the CTest
    !> architecture fails when a component is missing.
    subroutine for_each_history_column(history, action)
        !> The history whose columns the action gets
        type(history_record), intent(inout) :: history
        !> What to do with each column
        class(record_column_action), intent(inout) :: action

        call action%on_real_table(column('load', column_loads, units_stress), history%load)
        call action%on_real_table(column('ds', column_element_steps, units_length), history%ds)
        call action%on_real_table(column('dn', column_element_steps, units_length), history%dn)
        call action%on_integer_table(column('state', column_element_steps, &
                                            coding=history_state_coding(history)), history%state)
        call action%on_real_table(column('shear_traction', column_element_steps, units_stress), &
                                  history%shear_traction)
        call action%on_real_table(column('normal_traction', column_element_steps, &
                                         units_stress), history%normal_traction)
        call action%on_real_table(column('mu_in_force', column_strength_steps, units_one), &
                                  history%mu_in_force)
        call action%on_real_table(column('sf_in_force', column_strength_steps, units_stress), &
                                  history%sf_in_force)
        call action%on_real_table(column('tensile_strength_in_force', column_strength_steps, &
                                         units_stress), history%tensile_strength_in_force)
        call action%on_reals(column('time', column_time_steps, units_time), history%time)
        call action%on_real_table(column('pressure', column_flow_element_steps, units_stress), &
                                  history%pressure)
        call action%on_reals(column('injected_volume', column_flow_steps, units_area), &
                             history%injected_volume)
        call action%on_real_table(column('aperture', column_coupled_element_steps, &
                                         units_length), history%aperture)
        call action%on_real_table(column('flux', column_coupled_element_steps, units_flux), &
                                  history%flux)
        call action%on_reals(column('stored_volume', column_coupled_steps, units_area), &
                             history%stored_volume)
        call action%on_reals(column('leaked_volume', column_coupled_steps, units_area), &
                             history%leaked_volume)
        call action%on_reals(column('fluid_efficiency', column_coupled_steps, units_one), &
                             history%fluid_efficiency)
        call action%on_integers(column('flow_iterations', column_coupled_steps), &
                                history%flow_iterations)
        call action%on_reals(column('flow_residual', column_coupled_steps, units_one), &
                             history%flow_residual)
        call action%on_real_table(column('slipping_length', column_fracture_steps, &
                                         units_length), history%slipping_length)
        call action%on_real_table(column('front_begin', column_fracture_steps, units_length), &
                                  history%front_begin)
        call action%on_real_table(column('front_end', column_fracture_steps, units_length), &
                                  history%front_end)
        call action%on_real_table(column('moment', column_fracture_steps, units_moment), &
                                  history%moment)
        call action%on_real_table(column('k1', column_tip_steps, units_k), history%k1)
        call action%on_real_table(column('k2', column_tip_steps, units_k), history%k2)
        call action%on_strings(column('method', column_steps), history%method)
        call action%on_strings(column('fallback', column_steps), history%fallback)
        call action%on_integers(column('pivots', column_steps), history%pivots)
        call action%on_integers(column('newton_iterations', column_steps), &
                                history%newton_iterations)
        call action%on_reals(column('certificate_min_z', column_steps, units_one), &
                             history%certificate_min_z)
        call action%on_reals(column('certificate_min_w', column_steps, units_one), &
                             history%certificate_min_w)
        call action%on_reals(column('certificate_max_complementarity', column_steps, &
                                    units_one), history%certificate_max_complementarity)
        call action%on_reals(column('equilibrium_residual', column_steps, units_one), &
                             history%equilibrium_residual)
        call action%on_integers(column('element_count', column_growth_steps), &
                                history%element_count)
        call action%on_integers(column('tip_fracture_id', column_growing_tips), &
                                history%tip_fracture_id)
        call action%on_integers(column('tip_end', column_growing_tips, coding=tip_end_coding), &
                                history%tip_end)
        call action%on_real_table(column('grown_length', column_growing_tip_steps, &
                                         units_length), history%grown_length)
    end subroutine for_each_history_column

    !> The one list of the columns of a growth_record (docs/fracture-growth.md#output): the action
    !> gets each column once, in the order of the file's datasets: the tips' rows, the trials
    !> (/growth/trials, named by trial_dataset), the step that made each element.
    subroutine for_each_growth_column(record, action)
        !> The record whose columns the action gets
        type(growth_record), intent(inout) :: record
        !> What to do with each column
        class(record_column_action), intent(inout) :: action

        call for_each_tip_column(record%tip_records, action)
        call for_each_trial_column(record%trials, action)
        call action%on_integers(column('created_step', column_elements, &
                                       coding='0 the input, k growth step k'), record%created_step)
    end subroutine for_each_growth_column

    !> The one list of the columns of tip rows (/growth): the action gets each column once, in
    !> the order of the file's datasets. A new column is declared in the type and listed here;
    !> the CTest architecture fails when a component is missing.
    subroutine for_each_tip_column(rows, action)
        !> The rows whose columns the action gets
        type(tip_records), intent(inout) :: rows
        !> What to do with each column
        class(record_column_action), intent(inout) :: action

        call action%on_integers(column('step', column_records), rows%step)
        call action%on_integers(column('load_step', column_path_records), rows%load_step)
        call action%on_integers(column('fracture_id', column_records), rows%fracture_id)
        call action%on_integers(column('end', column_records, coding=tip_end_coding), rows%end)
        call action%on_reals(column('x', column_records, units_length), rows%x)
        call action%on_reals(column('y', column_records, units_length), rows%y)
        call action%on_reals(column('k1', column_records, units_k), rows%k1)
        call action%on_reals(column('k2', column_records, units_k), rows%k2)
        call action%on_reals(column('k_eq', column_records, units_k), rows%k_eq)
        call action%on_reals(column('mts_angle', column_records, units_degree), rows%mts_angle)
        call action%on_reals(column('angle', column_records, units_degree), rows%angle)
        call action%on_integers(column('corrections', column_records), rows%corrections)
        call action%on_reals(column('k2_after', column_records, units_k), rows%k2_after)
        call action%on_reals(column('length', column_records, units_length), rows%length)
        call action%on_integers(column('reason', column_records, coding=reason_coding()), &
                                rows%reason)
        call action%on_reals(column('efficiency', column_work_records, units_work), &
                             rows%efficiency)
        call action%on_reals(column('slip_share', column_work_records, units_one), &
                             rows%slip_share)
    end subroutine for_each_tip_column

    !> The one list of the columns of trials (named in the file by trial_dataset).
    subroutine for_each_trial_column(trials, action)
        !> The trials whose columns the action gets
        type(trial_records), intent(inout) :: trials
        !> What to do with each column
        class(record_column_action), intent(inout) :: action

        call action%on_integers(column('step', column_trials), trials%step)
        call action%on_integers(column('owner', column_trials), trials%owner)
        call action%on_reals(column('angle', column_trials, units_degree), trials%angle)
        call action%on_reals(column('efficiency', column_trials, units_work), trials%efficiency)
        call action%on_integers(column('state', column_trials, coding=trial_state_coding), &
                                trials%state)
    end subroutine for_each_trial_column

    !> The one list of the columns of /growth/initiations: the action gets each column once, in
    !> the order of the file's datasets; the flaws' trials go to flaw_trials.
    subroutine for_each_initiation_column(record, action)
        !> The record whose columns the action gets
        type(initiation_record), intent(inout) :: record
        !> What to do with each column
        class(record_column_action), intent(inout) :: action

        call action%on_integers(column('kind', column_records, coding='1 tail, 2 flaw'), &
                                record%kind)
        call action%on_integers(column('step', column_records), record%step)
        call action%on_integers(column('load_step', column_records), record%load_step)
        call action%on_integers(column('fracture_id', column_records), record%fracture_id)
        call action%on_integers(column('parent', column_records, coding='0 none (a flaw)'), &
                                record%parent)
        call action%on_integers(column('element', column_records, coding='0 none (a flaw)'), &
                                record%element)
        call action%on_integers(column('flaw', column_records, coding='0 none (a tail)'), &
                                record%flaw)
        call action%on_integers(column('side', column_records, coding=side_coding), record%side)
        call action%on_reals(column('x', column_records, units_length), record%x)
        call action%on_reals(column('y', column_records, units_length), record%y)
        call action%on_reals(column('probe_x', column_records, units_length), record%probe_x)
        call action%on_reals(column('probe_y', column_records, units_length), record%probe_y)
        call action%on_reals(column('tension', column_records, units_stress), record%tension)
        call action%on_reals(column('angle', column_records, units_degree), record%angle)
        call action%on_reals(column('efficiency', column_work_records, units_work), &
                             record%efficiency)
        call for_each_trial_column(record%trials, action)
    end subroutine for_each_initiation_column

    !> The dataset of a trial column in the file: in /growth/trials 'trial_' and the column's
    !> name (the owner 'trial_record'), in flaw_trials the name (the owner 'flaw').
    pure function trial_dataset(name, in_growth) result(dataset)
        !> The column's name (for_each_trial_column)
        character(len=*), intent(in) :: name
        !> Whether it is /growth/trials (else /growth/initiations/flaw_trials)
        logical, intent(in) :: in_growth
        character(len=:), allocatable :: dataset

        if (name /= 'owner') then
            dataset = name
        else if (in_growth) then
            dataset = 'record'
        else
            dataset = 'flaw'
        end if
        if (in_growth) dataset = 'trial_'//dataset
    end function trial_dataset

    !> Append the rows of `rows` that keep marks to `record`, every column.
    subroutine append_tip_rows(record, rows, keep)
        !> The record (its columns allocated)
        type(tip_records), intent(inout) :: record
        !> The rows, every column allocated
        type(tip_records), intent(in) :: rows
        !> Which rows to append, shape (rows)
        logical, intent(in) :: keep(:)
        type(tip_records) :: kept
        type(column_collector) :: collector
        type(column_appender) :: appender

        kept = rows
        collector%keep = keep
        call for_each_tip_column(kept, collector)
        call hand_over(collector, appender)
        call for_each_tip_column(record, appender)
    end subroutine append_tip_rows

    !> Append every trial of `trials` to `record` (its columns allocated by the first).
    subroutine append_trial_rows(record, trials)
        !> The trials appended to
        type(trial_records), intent(inout) :: record
        !> The trials appended, every column allocated
        type(trial_records), intent(in) :: trials
        type(trial_records) :: rows
        type(column_collector) :: collector
        type(column_appender) :: appender

        rows = trials
        call for_each_trial_column(rows, collector)
        call hand_over(collector, appender)
        call for_each_trial_column(record, appender)
    end subroutine append_trial_rows

    !> Append the new fracture `row` (a record of one row, trials unallocated) to `record`.
    subroutine append_initiation(record, row)
        !> The record (its columns allocated by the first)
        type(initiation_record), intent(inout) :: record
        !> The new fracture
        type(initiation_record), intent(in) :: row
        type(initiation_record) :: rows
        type(column_collector) :: collector
        type(column_appender) :: appender

        rows = row
        call for_each_initiation_column(rows, collector)
        call hand_over(collector, appender)
        call for_each_initiation_column(record, appender)
    end subroutine append_initiation

    !> The units attribute of values that measure `units` (units_none ... units_area) in
    !> a model of these unit names; '' for units_none.
    pure function units_text(units, stress, length, time) result(text)
        !> What the values measure
        integer, intent(in) :: units
        !> The model's stress and length unit names
        character(len=*), intent(in) :: stress, length
        !> The model's time unit name (default 's')
        character(len=*), intent(in), optional :: time
        character(len=:), allocatable :: text

        select case (units)
        case (units_length)
            text = length
        case (units_stress)
            text = stress
        case (units_k)
            text = stress//' '//length//'^0.5'
        case (units_degree)
            text = 'degree'
        case (units_one)
            text = '1'
        case (units_work)
            text = stress//' '//length
        case (units_stiffness)
            text = stress//'/'//length
        case (units_time)
            text = 's'
            if (present(time)) text = time
        case (units_area)
            text = length//'^2'
        case (units_moment)
            text = stress//' '//length//'^2'
        case (units_flux)
            text = length//'^2/s'
            if (present(time)) text = length//'^2/'//time
        case default
            text = ''
        end select
    end function units_text

    !> What a column is.
    pure function column(name, kind, units, coding) result(described)
        !> Dataset name
        character(len=*), intent(in) :: name
        !> column_loads ... column_elements
        integer, intent(in) :: kind
        !> units_none ... units_work (default units_none)
        integer, intent(in), optional :: units
        !> Coding of an integer column (default none)
        character(len=*), intent(in), optional :: coding
        type(record_column) :: described

        described%name = name
        described%kind = kind
        if (present(units)) described%units = units
        if (present(coding)) described%coding = coding
    end function column

    !> The coding of a history's element states: with growth, an element's rows before it
    !> was made hold state_not_grown.
    pure function history_state_coding(history) result(coding)
        !> The history
        type(history_record), intent(in) :: history
        character(len=:), allocatable :: coding

        coding = state_coding
        if (allocated(history%element_count)) coding = coding//', '//itoa(state_not_grown)// &
            ' not made yet'
    end function history_state_coding

    !> The coding of the growth reasons: '0 grew, 1 subcritical, ...'.
    pure function reason_coding() result(coding)
        character(len=:), allocatable :: coding
        integer :: r

        coding = ''
        do r = lbound(growth_reason_names, 1), ubound(growth_reason_names, 1)
            if (r > lbound(growth_reason_names, 1)) coding = coding//', '
            coding = coding//itoa(r)//' '//trim(growth_reason_names(r))
        end do
    end function reason_coding

    !> Lay a history out anew: room for `steps` steps in every column, the first `kept` steps
    !> of each kept; element columns of `rows` rows (row i takes row origin(i) of the
    !> history, by default its own; no row: NaN, state_not_grown), tip columns of `tips`
    !> rows, load columns of one row per quantity. The columns of growth along a load path are
    !> laid out when there or asked for; those of the tips that may grow are left as they are
    !> (the growth record gives them at the end); those of the strengths in force when there
    !> or asked for. Values not kept are NaN, 0 or blank.
    subroutine lay_out_history(history, rows, tips, steps, kept, stat, origin, growth, &
                               strengths, time, fractures, coupled)
        !> The history
        type(history_record), intent(inout) :: history
        !> Rows of the element columns and of the tip columns, steps of every column
        integer, intent(in) :: rows, tips, steps
        !> Steps kept (0: none; the history has at least these)
        integer, intent(in) :: kept
        !> 0, or the stat of an allocation that failed (the history is then incomplete)
        integer, intent(out) :: stat
        !> The row of the history that each element row takes (0: none), shape (rows)
        integer, intent(in), optional :: origin(:)
        !> Lay out the columns of growth along a load path too (default: when there)
        logical, intent(in), optional :: growth
        !> Lay out the columns of the strengths in force too (default: when there)
        logical, intent(in), optional :: strengths
        !> Lay out the column of a time axis too (default: when there)
        logical, intent(in), optional :: time
        !> Lay out the columns of the fluid sources too, for this many fractures (default:
        !> when there)
        integer, intent(in), optional :: fractures
        !> Lay out the columns of coupled flow too (default: when there)
        logical, intent(in), optional :: coupled
        type(record_layout) :: layout
        integer :: i

        layout%rows = rows
        layout%tips = tips
        layout%steps = steps
        layout%kept = kept
        if (present(origin)) then
            layout%origin = origin
        else
            layout%origin = [(i, i = 1, rows)]
        end if
        if (present(growth)) layout%growth = growth
        if (present(strengths)) layout%strengths = strengths
        if (present(time)) layout%time = time
        if (present(coupled)) layout%coupled = coupled
        if (present(fractures)) then
            layout%flow = .true.
            layout%fractures = fractures
        else if (allocated(history%moment)) then
            layout%fractures = size(history%moment, 1)
        end if
        call for_each_history_column(history, layout)
        stat = layout%stat
    end subroutine lay_out_history

    !> Allocate every per-record column of a growth record with no record.
    subroutine empty_growth_record(record)
        !> The record
        type(growth_record), intent(inout) :: record
        type(record_layout) :: layout

        call for_each_growth_column(record, layout)
    end subroutine empty_growth_record

    !> n rows of every tip column: reals NaN, integers 0.
    subroutine lay_out_tip_rows(rows, n)
        !> The rows
        type(tip_records), intent(out) :: rows
        !> How many
        integer, intent(in) :: n
        type(record_layout) :: layout

        layout%steps = n
        call for_each_tip_column(rows, layout)
        if (layout%stat /= 0) error stop 'lay_out_tip_rows: out of memory'
    end subroutine lay_out_tip_rows

    !> An initiation record without rows, or of n rows (reals NaN, integers 0); its trials
    !> unallocated (the flaws' searches allocate them).
    subroutine empty_initiation_record(record, n)
        !> The record
        type(initiation_record), intent(out) :: record
        !> Number of rows (absent: none)
        integer, intent(in), optional :: n
        type(record_layout) :: layout

        if (present(n)) layout%steps = n
        call for_each_initiation_column(record, layout)
        if (layout%stat /= 0) error stop 'empty_initiation_record: out of memory'
        if (allocated(record%trials%step)) deallocate (record%trials%step, &
            record%trials%owner, record%trials%angle, record%trials%efficiency, &
            record%trials%state)
    end subroutine empty_initiation_record

    !> Whether the layout lays out a column (allocated or not).
    pure logical function lays_out(layout, column, there)
        !> The layout
        type(record_layout), intent(in) :: layout
        !> The column
        type(record_column), intent(in) :: column
        !> Whether the column is allocated
        logical, intent(in) :: there

        select case (column%kind)
        case (column_growing_tips, column_growing_tip_steps, column_elements)
            lays_out = .false.
        case (column_growth_steps)
            lays_out = there .or. layout%growth
        case (column_strength_steps)
            lays_out = there .or. layout%strengths
        case (column_time_steps)
            lays_out = there .or. layout%time
        case (column_flow_element_steps, column_flow_steps, column_fracture_steps)
            lays_out = there .or. layout%flow
        case (column_coupled_element_steps, column_coupled_steps)
            lays_out = there .or. layout%coupled
        case default
            lays_out = .true.
        end select
        lays_out = lays_out .and. layout%stat == 0
    end function lays_out

    !> Rows of a table column as laid out: one per load quantity, element or tip.
    pure integer function table_rows(layout, column)
        !> The layout
        type(record_layout), intent(in) :: layout
        !> The column
        type(record_column), intent(in) :: column

        select case (column%kind)
        case (column_loads)
            table_rows = size(load_path_names)
        case (column_element_steps, column_strength_steps, column_flow_element_steps, &
              column_coupled_element_steps)
            table_rows = layout%rows
        case (column_fracture_steps)
            table_rows = layout%fractures
        case default
            table_rows = layout%tips
        end select
    end function table_rows

    !> The first kept values of a real column, in room for every step.
    subroutine lay_out_reals(action, column, values)
        !> The layout
        class(record_layout), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        real(wp), allocatable, intent(inout) :: values(:)
        real(wp), allocatable :: laid(:)
        integer :: stat

        if (.not. lays_out(action, column, allocated(values))) return
        allocate (laid(action%steps), stat=stat)
        action%stat = stat
        if (stat /= 0) return
        laid = ieee_value(1.0_wp, ieee_quiet_nan)
        if (allocated(values)) laid(1:action%kept) = values(1:action%kept)
        call move_alloc(laid, values)
    end subroutine lay_out_reals

    !> The first kept values of an integer column, in room for every step.
    subroutine lay_out_integers(action, column, values)
        !> The layout
        class(record_layout), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        integer, allocatable, intent(inout) :: values(:)
        integer, allocatable :: laid(:)
        integer :: stat

        if (.not. lays_out(action, column, allocated(values))) return
        allocate (laid(action%steps), source=0, stat=stat)
        action%stat = stat
        if (stat /= 0) return
        if (allocated(values)) laid(1:action%kept) = values(1:action%kept)
        call move_alloc(laid, values)
    end subroutine lay_out_integers

    !> The first kept steps of a real table, its element rows where the layout says.
    subroutine lay_out_real_table(action, column, values)
        !> The layout
        class(record_layout), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        real(wp), allocatable, intent(inout) :: values(:, :)
        real(wp), allocatable :: laid(:, :)
        integer, allocatable :: origin(:), made(:)
        integer :: i, stat

        if (.not. lays_out(action, column, allocated(values))) return
        allocate (laid(table_rows(action, column), action%steps), stat=stat)
        action%stat = stat
        if (stat /= 0) return
        laid = ieee_value(1.0_wp, ieee_quiet_nan)
        if (allocated(values) .and. action%kept > 0) then
            origin = origin_of(action, column, size(laid, 1), size(values, 1))
            made = pack([(i, i = 1, size(origin))], origin > 0)
            laid(made, 1:action%kept) = values(origin(made), 1:action%kept)
        end if
        call move_alloc(laid, values)
    end subroutine lay_out_real_table

    !> The first kept steps of an integer table, its element rows where the layout says.
    subroutine lay_out_integer_table(action, column, values)
        !> The layout
        class(record_layout), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        integer, allocatable, intent(inout) :: values(:, :)
        integer, allocatable :: laid(:, :)
        integer, allocatable :: origin(:), made(:)
        integer :: i, none, stat

        if (.not. lays_out(action, column, allocated(values))) return
        none = 0
        ! An element row before its element was made (growth)
        if (column%kind == column_element_steps) none = state_not_grown
        allocate (laid(table_rows(action, column), action%steps), source=none, stat=stat)
        action%stat = stat
        if (stat /= 0) return
        if (allocated(values) .and. action%kept > 0) then
            origin = origin_of(action, column, size(laid, 1), size(values, 1))
            made = pack([(i, i = 1, size(origin))], origin > 0)
            laid(made, 1:action%kept) = values(origin(made), 1:action%kept)
        end if
        call move_alloc(laid, values)
    end subroutine lay_out_integer_table

    !> The first kept values of a string column, in room for every step.
    ! allow(C072): the strings have the lengths of history_record
    subroutine lay_out_strings(action, column, values)
        !> The layout
        class(record_layout), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        character(len=*), allocatable, intent(inout) :: values(:)
        character(len=len(values)), allocatable :: laid(:)
        integer :: stat

        if (.not. lays_out(action, column, allocated(values))) return
        allocate (laid(action%steps), stat=stat)
        action%stat = stat
        if (stat /= 0) return
        laid = ''
        if (allocated(values)) laid(1:action%kept) = values(1:action%kept)
        call move_alloc(laid, values)
    end subroutine lay_out_strings

    !> The row of a table that each row of the laid out table takes (0: none).
    pure function origin_of(layout, column, rows, held) result(origin)
        !> The layout
        type(record_layout), intent(in) :: layout
        !> The table's column
        type(record_column), intent(in) :: column
        !> Rows of the laid out table, and of the table before
        integer, intent(in) :: rows, held
        integer :: origin(rows)
        integer :: i

        if (column%kind == column_element_steps .or. column%kind == column_strength_steps .or. &
            column%kind == column_flow_element_steps .or. &
            column%kind == column_coupled_element_steps) then
            origin = layout%origin
        else
            ! Rows added since (the ends of fractures started inside the rock) have none
            origin = [(merge(i, 0, i <= held), i = 1, rows)]
        end if
    end function origin_of

    !> The collected columns to the appender.
    subroutine hand_over(collector, appender)
        !> The collector (emptied)
        type(column_collector), intent(inout) :: collector
        !> The appender
        type(column_appender), intent(inout) :: appender

        if (allocated(collector%refused)) error stop 'append: a list of rows has a table'
        if (.not. allocated(collector%reals)) allocate (collector%reals(0))
        if (.not. allocated(collector%integers)) allocate (collector%integers(0))
        call move_alloc(collector%reals, appender%reals)
        call move_alloc(collector%integers, appender%integers)
    end subroutine hand_over

    !> Keep the rows of a real column that the collector keeps.
    subroutine collect_reals(action, column, values)
        !> The collector
        class(column_collector), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        real(wp), allocatable, intent(inout) :: values(:)
        type(real_values) :: kept

        if (.not. allocated(action%reals)) allocate (action%reals(0))
        kept%name = column%name
        if (allocated(values)) then
            kept%values = values
            if (allocated(action%keep)) kept%values = pack(values, action%keep)
        end if
        action%reals = [action%reals, kept]
    end subroutine collect_reals

    !> Keep the rows of an integer column that the collector keeps.
    subroutine collect_integers(action, column, values)
        !> The collector
        class(column_collector), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        integer, allocatable, intent(inout) :: values(:)
        type(integer_values) :: kept

        if (.not. allocated(action%integers)) allocate (action%integers(0))
        kept%name = column%name
        if (allocated(values)) then
            kept%values = values
            if (allocated(action%keep)) kept%values = pack(values, action%keep)
        end if
        action%integers = [action%integers, kept]
    end subroutine collect_integers

    !> Append the next collected real column (the same list: the same name).
    subroutine append_reals(action, column, values)
        !> The appender
        class(column_appender), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        real(wp), allocatable, intent(inout) :: values(:)

        action%real_at = action%real_at + 1
        associate (rows => action%reals(action%real_at))
            if (rows%name /= column%name) error stop 'append: the columns of two lists'
            if (.not. allocated(rows%values)) return
            if (.not. allocated(values)) allocate (values(0))
            values = [values, rows%values]
        end associate
    end subroutine append_reals

    !> Append the next collected integer column (the same list: the same name).
    subroutine append_integers(action, column, values)
        !> The appender
        class(column_appender), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        integer, allocatable, intent(inout) :: values(:)

        action%integer_at = action%integer_at + 1
        associate (rows => action%integers(action%integer_at))
            if (rows%name /= column%name) error stop 'append: the columns of two lists'
            if (.not. allocated(rows%values)) return
            if (.not. allocated(values)) allocate (values(0))
            values = [values, rows%values]
        end associate
    end subroutine append_integers

    !> A column that is not one value per row (a list of rows has none): noted, and the
    !> append stops (collected).
    subroutine refuse(action, column, there)
        !> The collector
        class(column_collector), intent(inout) :: action
        !> The column, and whether it is allocated
        type(record_column), intent(in) :: column
        logical, intent(in) :: there

        action%refused = column%name//trim(merge(' (allocated)', '            ', there))
    end subroutine refuse

    !> Rows have 1-D columns only.
    subroutine refuse_real_table(action, column, values)
        !> The collector
        class(column_collector), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        real(wp), allocatable, intent(inout) :: values(:, :)

        call refuse(action, column, allocated(values))
    end subroutine refuse_real_table

    !> Rows have 1-D columns only.
    subroutine refuse_integer_table(action, column, values)
        !> The collector
        class(column_collector), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        integer, allocatable, intent(inout) :: values(:, :)

        call refuse(action, column, allocated(values))
    end subroutine refuse_integer_table

    !> Rows have no string columns.
    ! allow(C072): the strings have the lengths of history_record
    subroutine refuse_strings(action, column, values)
        !> The collector
        class(column_collector), intent(inout) :: action
        !> The column
        type(record_column), intent(in) :: column
        !> Its values
        character(len=*), allocatable, intent(inout) :: values(:)

        call refuse(action, column, allocated(values))
    end subroutine refuse_strings

end module ddc_model_records
