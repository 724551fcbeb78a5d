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
    use ddc_model_results, only: history_record, growth_record, state_not_grown, &
        growth_reason_names, trial_state_coding
    implicit none
    private

    public :: record_column, record_column_action
    public :: for_each_history_column, for_each_growth_column
    public :: lay_out_history, empty_growth_record, reason_coding
    public :: column_loads, column_element_steps, column_tip_steps, column_steps, &
        column_growth_steps, column_growing_tips, column_growing_tip_steps, column_records, &
        column_path_records, column_elements, column_strength_steps, column_work_records, &
        column_trials, column_time_steps, column_flow_element_steps, column_flow_steps, &
        column_fracture_steps
    public :: units_none, units_length, units_stress, units_k, units_degree, units_one, units_work
    public :: units_stiffness, units_time, units_area, units_moment, units_text
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
                          column_flow_steps = 16, column_fracture_steps = 17

    !> What the values of a column (or of a strength law, ddc_model_laws) measure, for its
    !> units attribute: nothing (integers and strings), length, stress, stress intensity
    !> (stress * length**0.5), angle in degrees, a ratio, work per length (stress * length),
    !> a joint stiffness (stress / length), time, a volume per unit length out of the plane
    !> (length^2), a seismic moment per unit length out of the plane (stress * length^2)
    integer, parameter :: units_none = 0, units_length = 1, units_stress = 2, units_k = 3, &
                          units_degree = 4, units_one = 5, units_work = 6, units_stiffness = 7, &
                          units_time = 8, units_area = 9, units_moment = 10

    !> Coding of the element states (/elements/state and the history's)
    character(len=*), parameter :: state_coding = '0 free (TWODD-style condition), ' &
        //'1 stick, 2 slip, 3 open'
    !> Coding of the tip ends
    character(len=*), parameter :: tip_end_coding = '0 begin tip, 1 end tip'

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
        !> The stat of an allocation that failed (0: none)
        integer :: stat = 0
    contains
        procedure :: on_reals => lay_out_reals
        procedure :: on_integers => lay_out_integers
        procedure :: on_real_table => lay_out_real_table
        procedure :: on_integer_table => lay_out_integer_table
        procedure :: on_strings => lay_out_strings
    end type record_layout

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
    !> gets each column once, in the order of the file's datasets. A new column is declared in the
    !> type and listed here; the CTest architecture fails when a component is missing.
    subroutine for_each_growth_column(record, action)
        !> The record whose columns the action gets
        type(growth_record), intent(inout) :: record
        !> What to do with each column
        class(record_column_action), intent(inout) :: action

        call action%on_integers(column('step', column_records), record%step)
        call action%on_integers(column('load_step', column_path_records), record%load_step)
        call action%on_integers(column('fracture_id', column_records), record%fracture_id)
        call action%on_integers(column('end', column_records, coding=tip_end_coding), record%end)
        call action%on_reals(column('x', column_records, units_length), record%x)
        call action%on_reals(column('y', column_records, units_length), record%y)
        call action%on_reals(column('k1', column_records, units_k), record%k1)
        call action%on_reals(column('k2', column_records, units_k), record%k2)
        call action%on_reals(column('k_eq', column_records, units_k), record%k_eq)
        call action%on_reals(column('mts_angle', column_records, units_degree), record%mts_angle)
        call action%on_reals(column('angle', column_records, units_degree), record%angle)
        call action%on_integers(column('corrections', column_records), record%corrections)
        call action%on_reals(column('k2_after', column_records, units_k), record%k2_after)
        call action%on_reals(column('length', column_records, units_length), record%length)
        call action%on_integers(column('reason', column_records, coding=reason_coding()), &
                                record%reason)
        call action%on_reals(column('efficiency', column_work_records, units_work), &
                             record%efficiency)
        call action%on_reals(column('slip_share', column_work_records, units_one), &
                             record%slip_share)
        call action%on_integers(column('trial_step', column_trials), record%trial_step)
        call action%on_integers(column('trial_record', column_trials), record%trial_record)
        call action%on_reals(column('trial_angle', column_trials, units_degree), &
                             record%trial_angle)
        call action%on_reals(column('trial_efficiency', column_trials, units_work), &
                             record%trial_efficiency)
        call action%on_integers(column('trial_state', column_trials, coding=trial_state_coding), &
                                record%trial_state)
        call action%on_integers(column('created_step', column_elements, &
                                       coding='0 the input, k growth step k'), record%created_step)
    end subroutine for_each_growth_column

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
                               strengths, time, fractures)
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
        case (column_element_steps, column_strength_steps, column_flow_element_steps)
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
            column%kind == column_flow_element_steps) then
            origin = layout%origin
        else
            ! Rows added since (the ends of fractures started inside the rock) have none
            origin = [(merge(i, 0, i <= held), i = 1, rows)]
        end if
    end function origin_of

end module ddc_model_records
