!> The values of rate-and-state elements (condition 'rate_state';
!> docs/theory/cycles.md#the-fault): a, b, dc (the characteristic slip L), f0, v0, the initial
!> slip rate v_init, the initial effective normal stress sigma0 (compression positive) and the
!> initial shear traction tau0 (ddc2d's sign: along the element direction, as a remote stress
!> resolves it), each a per-element array of element_set, 0 on elements of other conditions.
!>
!> for_each_rate_state is the one list of them, with what the places that handle them need:
!> the name (the &fracture variable, the elements_file column, the /elements dataset), the
!> range and the units. The &fracture reader, the allocation of the elements, /elements and
!> the cycle run go through it.
module ddc_model_rate_state
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set
    use ddc_model_limits, only: quantity_any, quantity_positive
    implicit none
    private

    public :: rate_state_value, rate_state_count, rate_state_values, rate_state_table
    public :: set_rate_state, clear_rate_state, rate_state_units
    public :: units_one, units_length, units_rate, units_stress
    public :: rs_a, rs_b, rs_dc, rs_f0, rs_v0, rs_v_init, rs_sigma0, rs_tau0

    !> Number of the values of a rate-and-state element
    integer, parameter :: rate_state_count = 8
    !> The place of each value in the list (the column of every table of them)
    integer, parameter :: rs_a = 1, rs_b = 2, rs_dc = 3, rs_f0 = 4, rs_v0 = 5, rs_v_init = 6, &
                          rs_sigma0 = 7, rs_tau0 = 8
    !> What a value measures: a number, a length, a slip rate (length / time), a stress
    integer, parameter :: units_one = 1, units_length = 2, units_rate = 3, units_stress = 4

    !> One value of a rate-and-state element.
    type :: rate_state_value
        !> Its name: the &fracture variable, the elements_file column, the /elements dataset
        character(len=:), allocatable :: name
        !> Its range: quantity_positive or quantity_any (ddc_model_limits)
        integer :: quantity = quantity_any
        !> units_one ... units_stress
        integer :: units = units_one
    end type rate_state_value

    !> What a routine does with every value: it extends this type and is handed each value
    !> with its per-element array by for_each_rate_state.
    type, abstract :: rate_state_action
    contains
        !> Act on one value and its per-element array
        procedure(act_on_value), deferred :: on_value
    end type rate_state_action

    abstract interface
        !> Act on one value and its per-element array, shape (n) or unallocated
        pure subroutine act_on_value(action, k, described, values)
            import :: rate_state_action, rate_state_value, wp
            implicit none
            !> The action and its data
            class(rate_state_action), intent(inout) :: action
            !> The value's place in the list
            integer, intent(in) :: k
            !> The value
            type(rate_state_value), intent(in) :: described
            !> Its array
            real(wp), allocatable, intent(inout) :: values(:)
        end subroutine act_on_value
    end interface

    !> Copies the values in and out of a table, column k value k.
    type, extends(rate_state_action) :: rate_state_copy
        !> The list's values
        type(rate_state_value) :: listed(rate_state_count)
        !> Into the table (or out of it into the elements `rows`)
        logical :: to_table = .true.
        !> The elements copied, shape (m)
        integer, allocatable :: rows(:)
        !> The table, shape (m, rate_state_count)
        real(wp), allocatable :: table(:, :)
    contains
        procedure :: on_value => copy_value
    end type rate_state_copy

contains

    !> The one list of the values of a rate-and-state element: the action gets each with its
    !> per-element array of element_set, once, in this order (that of the columns of every
    !> table of them).
    pure subroutine for_each_rate_state(elements, action)
        !> The set whose arrays the action gets
        type(element_set), intent(inout) :: elements
        !> What to do with each value
        class(rate_state_action), intent(inout) :: action

        call action%on_value(rs_a, described('a', quantity_positive, units_one), &
                             elements%rs_a)
        call action%on_value(rs_b, described('b', quantity_positive, units_one), &
                             elements%rs_b)
        call action%on_value(rs_dc, described('dc', quantity_positive, units_length), &
                             elements%rs_dc)
        call action%on_value(rs_f0, described('f0', quantity_any, units_one), elements%rs_f0)
        call action%on_value(rs_v0, described('v0', quantity_positive, units_rate), &
                             elements%rs_v0)
        call action%on_value(rs_v_init, described('v_init', quantity_any, units_rate), &
                             elements%rs_v_init)
        call action%on_value(rs_sigma0, described('sigma0', quantity_positive, units_stress), &
                             elements%rs_sigma0)
        call action%on_value(rs_tau0, described('tau0', quantity_any, units_stress), &
                             elements%rs_tau0)
    end subroutine for_each_rate_state

    !> One value of the list.
    pure function described(name, quantity, units) result(value)
        character(len=*), intent(in) :: name
        integer, intent(in) :: quantity, units
        type(rate_state_value) :: value

        value%name = name
        value%quantity = quantity
        value%units = units
    end function described

    !> The values in the order of the list.
    pure function rate_state_values() result(values)
        type(rate_state_value) :: values(rate_state_count)
        type(element_set) :: none
        type(rate_state_copy) :: copy

        allocate (copy%rows(0))
        call for_each_rate_state(none, copy)
        values = copy%listed
    end function rate_state_values

    !> The values of the elements `rows`, column k value k of the list, shape (m,
    !> rate_state_count).
    pure function rate_state_table(elements, rows) result(table)
        !> The elements, every array allocated
        type(element_set), intent(in) :: elements
        !> The elements wanted, shape (m)
        integer, intent(in) :: rows(:)
        real(wp), allocatable :: table(:, :)
        type(element_set) :: copy
        type(rate_state_copy) :: listing

        copy = elements
        listing%rows = rows
        allocate (listing%table(size(rows), rate_state_count))
        call for_each_rate_state(copy, listing)
        call move_alloc(listing%table, table)
    end function rate_state_table

    !> The elements `rows` take the values of a table, column k value k of the list.
    pure subroutine set_rate_state(elements, rows, table)
        !> The elements, every array allocated
        type(element_set), intent(inout) :: elements
        !> The elements set, shape (m)
        integer, intent(in) :: rows(:)
        !> Their values, shape (m, rate_state_count)
        real(wp), intent(in) :: table(:, :)
        type(rate_state_copy) :: setting

        setting%to_table = .false.
        setting%rows = rows
        setting%table = table
        call for_each_rate_state(elements, setting)
    end subroutine set_rate_state

    !> No rate-and-state values (0) on every element: what elements of other conditions hold.
    pure subroutine clear_rate_state(elements)
        !> The elements, every array allocated
        type(element_set), intent(inout) :: elements
        integer :: i

        call set_rate_state(elements, [(i, i = 1, elements%n)], &
                            spread(spread(0.0_wp, 1, elements%n), 2, rate_state_count))
    end subroutine clear_rate_state

    !> The units of a value as text, from the model's unit names.
    pure function rate_state_units(units, stress, length, time) result(text)
        !> units_one ... units_stress
        integer, intent(in) :: units
        !> The model's stress, length and time unit names
        character(len=*), intent(in) :: stress, length, time
        character(len=:), allocatable :: text

        select case (units)
        case (units_length)
            text = length
        case (units_rate)
            text = length//'/'//time
        case (units_stress)
            text = stress
        case default
            text = '1'
        end select
    end function rate_state_units

    !> Copy one value between its array and the table.
    pure subroutine copy_value(action, k, described, values)
        class(rate_state_copy), intent(inout) :: action
        integer, intent(in) :: k
        type(rate_state_value), intent(in) :: described
        real(wp), allocatable, intent(inout) :: values(:)

        action%listed(k) = described
        if (size(action%rows) == 0) return
        if (action%to_table) then
            action%table(:, k) = values(action%rows)
        else
            values(action%rows) = action%table(:, k)
        end if
    end subroutine copy_value

end module ddc_model_rate_state
