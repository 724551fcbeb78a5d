!> A loading history's steps (docs/theory/earth.md#loading-histories): the load at every step of a
!> path.
!>
!> Step 1 is the path's first vertex (the starting state); leg l from vertex l to l + 1
!> adds steps(l) equal increments, the last of which lands on vertex l + 1 exactly.
module ddc_history_path
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, load_path_type, load_path_names
    use ddc_text, only: rtoa
    implicit none
    private

    public :: path_step_count, path_loads, path_times, load_at, apply_load, load_text

contains

    !> Number of steps of a path: 1 (the starting state) plus every increment.
    pure integer function path_step_count(path)
        !> The path
        type(load_path_type), intent(in) :: path

        path_step_count = 1 + sum(path%steps)
    end function path_step_count

    !> The load at every step, shape (7, path_step_count(path)), rows as load_path_names.
    pure function path_loads(path) result(loads)
        !> The path
        type(load_path_type), intent(in) :: path
        !> The loads [stress unit; stress unit / length unit for the gradients]
        real(wp), allocatable :: loads(:, :)
        integer :: leg, j, k

        allocate (loads(size(path%vertex, 1), path_step_count(path)))
        loads(:, 1) = path%vertex(:, 1)
        k = 1
        do leg = 1, size(path%steps)
            do j = 1, path%steps(leg)
                k = k + 1
                loads(:, k) = load_at(path%vertex(:, leg), path%vertex(:, leg + 1), j, &
                                      path%steps(leg))
            end do
        end do
    end function path_loads

    !> The time of every step of a path with a time axis, the steps of a leg evenly spaced
    !> (its last on the leg's end), shape (path_step_count(path)) [time unit].
    pure function path_times(path) result(times)
        !> The path (path%time allocated)
        type(load_path_type), intent(in) :: path
        real(wp), allocatable :: times(:)
        integer :: leg, j, k

        allocate (times(path_step_count(path)))
        times(1) = path%time(1)
        k = 1
        do leg = 1, size(path%steps)
            do j = 1, path%steps(leg)
                k = k + 1
                times(k) = path%time(leg) + (path%time(leg + 1) - path%time(leg)) * &
                    real(j, wp) / real(path%steps(leg), wp)
                if (j == path%steps(leg)) times(k) = path%time(leg + 1)
            end do
        end do
    end function path_times

    !> The load after j of steps increments from vertex a to vertex b (b itself at j = steps).
    pure function load_at(a, b, j, steps) result(load)
        !> The leg's first and last vertex, shape (7)
        real(wp), intent(in) :: a(:), b(:)
        !> Increment and number of increments on the leg
        integer, intent(in) :: j, steps
        !> The load, shape (7)
        real(wp) :: load(size(a))

        if (j == steps) then
            load = b
        else
            load = a + (b - a) * (real(j, wp) / real(steps, wp))
        end if
    end function load_at

    !> A copy of the model at one load: remote stress, gradients and pore pressure p0
    !> replaced (dp_dy and everything else kept).
    pure function apply_load(model, load) result(loaded)
        !> The model
        type(model_type), intent(in) :: model
        !> The load, rows as load_path_names, shape (7)
        real(wp), intent(in) :: load(:)
        !> The model at that load
        type(model_type) :: loaded

        loaded = model
        loaded%sxx = load(1)
        loaded%syy = load(2)
        loaded%sxy = load(3)
        loaded%stress_gradient = load(4:6)
        loaded%pore_fluid(1) = load(7)
    end function apply_load

    !> 'sxy = 10, p0 = 3' for the quantities a path varies (all seven when none is marked).
    !> With a time: 't = 2.5 s' first, and only the quantities the path varies.
    function load_text(load, varies, time, time_unit) result(text)
        real(wp), intent(in) :: load(:)
        logical, intent(in) :: varies(:)
        !> The step's time and the time unit's name (a path with a time axis)
        real(wp), intent(in), optional :: time
        character(len=*), intent(in), optional :: time_unit
        character(len=:), allocatable :: text
        integer :: i

        text = ''
        if (present(time) .and. present(time_unit)) text = 't = '//rtoa(time)//' '//time_unit
        do i = 1, size(load)
            if (.not. varies(i) .and. (any(varies) .or. present(time))) cycle
            if (len(text) > 0) text = text//', '
            text = text//trim(load_path_names(i))//' = '//rtoa(load(i))
        end do
    end function load_text

end module ddc_history_path
