!> The record of a cycle run as it grows (ddc_model_cycles' cycle_record,
!> docs/output-reference.md#cycle): the recorded elements along each fault, rows appended at
!> the recorded times, events appended as they end. The arrays grow by doubling.
module ddc_cycle_record
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set
    use ddc_model_cycles, only: cycle_record
    implicit none
    private

    public :: new_record, add_row, add_event, recorded_slip_rows

    !> Room for rows and events of a new record
    integer, parameter :: first_room = 1024

contains

    !> A record of the rate-and-state elements `rows` (in fault order within each fracture)
    !> for p observation points: the recorded elements are those whose extent holds the
    !> distances 0, spacing, 2 spacing, ... along their fracture from its first vertex, and
    !> the last element of each (every element for spacing 0).
    function new_record(elements, rows, spacing, points) result(record)
        !> The elements, geometry computed
        type(element_set), intent(in) :: elements
        !> The rate-and-state elements, shape (m)
        integer, intent(in) :: rows(:)
        !> Spacing of the recorded elements [length unit] (0: every element)
        real(wp), intent(in) :: spacing
        !> Number of observation points
        integer, intent(in) :: points
        type(cycle_record) :: record
        real(wp) :: start(size(rows)), along
        logical :: picked(size(rows))
        integer :: j

        ! Distance of each element's begin from its fracture's first rate-and-state element
        if (size(rows) > 0) start(1) = 0.0_wp
        do j = 2, size(rows)
            if (elements%fracture_id(rows(j - 1)) == elements%fracture_id(rows(j))) then
                start(j) = start(j - 1) + 2.0_wp * elements%half_length(rows(j - 1))
            else
                start(j) = 0.0_wp
            end if
        end do
        picked = spacing <= 0.0_wp
        do j = 1, size(rows)
            along = 2.0_wp * elements%half_length(rows(j))
            if (spacing > 0.0_wp) then
                ! A multiple of spacing in [start, start + length)
                picked(j) = ceiling(start(j) / spacing - 1.0e-9_wp) * spacing < &
                            start(j) + along * (1.0_wp - 1.0e-9_wp)
            end if
            if (j == size(rows)) then
                picked(j) = .true.
            else if (start(j + 1) == 0.0_wp) then
                picked(j) = .true.
            end if
        end do
        record%elements = rows
        record%profile = pack(rows, picked)
        record%distance = pack(start + elements%half_length(rows), picked)
        associate (r => size(record%profile), k => first_room)
            allocate (record%time(k), record%max_slip_rate(k), record%max_rate_element(k))
            allocate (record%slip(r, k), record%slip_rate(r, k), record%shear_traction(r, k), &
                      record%normal_traction(r, k), record%state(r, k))
            allocate (record%ux(points, k), record%uy(points, k), record%vx(points, k), &
                      record%vy(points, k))
            allocate (record%event_start(k), record%event_end(k), record%event_x(k), &
                      record%event_y(k), record%event_peak_rate(k), record%event_max_slip(k), &
                      record%event_moment(k), record%event_element(k), &
                      record%event_slip(r, k))
        end associate
    end function new_record

    !> The place in the rate-and-state elements of each recorded element, shape (r).
    pure function recorded_slip_rows(record) result(local)
        !> The record
        type(cycle_record), intent(in) :: record
        integer :: local(size(record%profile))
        integer :: j

        do j = 1, size(record%profile)
            local(j) = findloc(record%elements, record%profile(j), 1)
        end do
    end function recorded_slip_rows

    !> Append a row.
    subroutine add_row(record, time, max_rate, max_element, slip, rate, shear, normal, state, &
                       ux, uy, vx, vy)
        !> The record
        type(cycle_record), intent(inout) :: record
        !> Time [time], largest |slip rate| [length / time] and its element
        real(wp), intent(in) :: time, max_rate
        integer, intent(in) :: max_element
        !> Of the recorded elements: slip, slip rate, shear and normal traction, log10 state,
        !> shape (r)
        real(wp), intent(in) :: slip(:), rate(:), shear(:), normal(:), state(:)
        !> Displacement and velocity of the points, shape (p)
        real(wp), intent(in) :: ux(:), uy(:), vx(:), vy(:)

        if (record%rows == size(record%time)) call grow_rows(record)
        record%rows = record%rows + 1
        associate (k => record%rows)
            record%time(k) = time
            record%max_slip_rate(k) = max_rate
            record%max_rate_element(k) = max_element
            record%slip(:, k) = slip
            record%slip_rate(:, k) = rate
            record%shear_traction(:, k) = shear
            record%normal_traction(:, k) = normal
            record%state(:, k) = state
            record%ux(:, k) = ux
            record%uy(:, k) = uy
            record%vx(:, k) = vx
            record%vy(:, k) = vy
        end associate
    end subroutine add_row

    !> Append an event.
    subroutine add_event(record, start, finish, element, x, y, peak_rate, max_slip, moment, &
                         slip)
        !> The record
        type(cycle_record), intent(inout) :: record
        !> Start and end time [time]
        real(wp), intent(in) :: start, finish
        !> The element where it started and its midpoint [length]
        integer, intent(in) :: element
        real(wp), intent(in) :: x, y
        !> Largest slip rate [length / time], largest slip [length], moment per unit length
        !> [stress length]
        real(wp), intent(in) :: peak_rate, max_slip, moment
        !> Slip of the recorded elements [length], shape (r)
        real(wp), intent(in) :: slip(:)

        if (record%events == size(record%event_start)) call grow_events(record)
        record%events = record%events + 1
        associate (e => record%events)
            record%event_start(e) = start
            record%event_end(e) = finish
            record%event_element(e) = element
            record%event_x(e) = x
            record%event_y(e) = y
            record%event_peak_rate(e) = peak_rate
            record%event_max_slip(e) = max_slip
            record%event_moment(e) = moment
            record%event_slip(:, e) = slip
        end associate
    end subroutine add_event

    !> Twice the room for rows.
    subroutine grow_rows(record)
        type(cycle_record), intent(inout) :: record
        integer :: room

        room = max(2 * size(record%time), first_room)
        call grow_1d(record%time, room)
        call grow_1d(record%max_slip_rate, room)
        call grow_int(record%max_rate_element, room)
        call grow_2d(record%slip, room)
        call grow_2d(record%slip_rate, room)
        call grow_2d(record%shear_traction, room)
        call grow_2d(record%normal_traction, room)
        call grow_2d(record%state, room)
        call grow_2d(record%ux, room)
        call grow_2d(record%uy, room)
        call grow_2d(record%vx, room)
        call grow_2d(record%vy, room)
    end subroutine grow_rows

    !> Twice the room for events.
    subroutine grow_events(record)
        type(cycle_record), intent(inout) :: record
        integer :: room

        room = max(2 * size(record%event_start), first_room)
        call grow_1d(record%event_start, room)
        call grow_1d(record%event_end, room)
        call grow_1d(record%event_x, room)
        call grow_1d(record%event_y, room)
        call grow_1d(record%event_peak_rate, room)
        call grow_1d(record%event_max_slip, room)
        call grow_1d(record%event_moment, room)
        call grow_int(record%event_element, room)
        call grow_2d(record%event_slip, room)
    end subroutine grow_events

    subroutine grow_1d(values, room)
        real(wp), allocatable, intent(inout) :: values(:)
        integer, intent(in) :: room
        real(wp), allocatable :: more(:)

        allocate (more(room))
        more(:size(values)) = values
        call move_alloc(more, values)
    end subroutine grow_1d

    subroutine grow_int(values, room)
        integer, allocatable, intent(inout) :: values(:)
        integer, intent(in) :: room
        integer, allocatable :: more(:)

        allocate (more(room))
        more(:size(values)) = values
        call move_alloc(more, values)
    end subroutine grow_int

    subroutine grow_2d(values, room)
        real(wp), allocatable, intent(inout) :: values(:, :)
        integer, intent(in) :: room
        real(wp), allocatable :: more(:, :)

        allocate (more(size(values, 1), room))
        more(:, :size(values, 2)) = values
        call move_alloc(more, values)
    end subroutine grow_2d

end module ddc_cycle_record
