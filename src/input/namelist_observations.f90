!> The observation groups of a namelist input file (docs/input-reference.md): regular grids (&grid),
!> lines (&line, both ends counted) and point lists from a CSV (&points), in file order.
module ddc_input_namelist_observations
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, exit_out_of_memory
    use ddc_allocation, only: real_bytes
    use ddc_model_types, only: observation_set, observation_grid, observation_line, &
        observation_points
    use ddc_text, only: itoa, rtoa, prefix_lines, bytes_text
    use ddc_model_limits, only: within_limits
    use ddc_input_text_file, only: resolve
    use ddc_input_csv, only: read_csv
    use ddc_input_namelist_groups, only: namelist_groups, group_record, message_list, add, &
        group_label, g_grid, g_line, g_points
    use ddc_input_namelist_diagnosis, only: report_malformed
    use ddc_input_namelist_values, only: unset_real, unset_integer, text_length, check_scalar, &
        default_name
    implicit none
    private

    public :: observation_input, read_grid_groups, read_line_groups, read_points_groups
    public :: max_observation_points

    !> Largest number of points in one observation set
    integer, parameter :: max_observation_points = 100000000

    !> One observation set with the label of the group that made it.
    type :: observation_input
        !> The set (valid when its group had no problem)
        type(observation_set) :: set
        !> Group label for messages
        character(len=:), allocatable :: label
        !> The group had no problem
        logical :: valid = .false.
    end type observation_input

contains

    !> &grid name, xmin, xmax, nx, ymin, ymax, ny / (repeated)
    subroutine read_grid_groups(unit, text, path, info, observations, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(observation_input), intent(inout) :: observations(:)
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name
        real(wp) :: xmin, xmax, ymin, ymax
        integer :: nx, ny
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, k, i, j, nbefore, slot
        real(wp), allocatable :: xs(:), ys(:)
        logical :: ok_x, ok_y
        namelist /grid/ name, xmin, xmax, nx, ymin, ymax, ny

        if (info%count == 0) return
        rewind (unit)
        do k = 1, info%count
            name = ''
            xmin = unset_real
            xmax = unset_real
            ymin = unset_real
            ymax = unset_real
            nx = unset_integer
            ny = unset_integer
            read (unit, nml=grid, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_grid, info, k, stat, iomsg, messages)
                exit
            end if
            slot = info%slot(k)
            call start_observation(observations(slot), path, g_grid, info, k, name, &
                                   observation_grid, prefix)
            nbefore = messages%n
            ok_x = check_axis(xmin, xmax, nx, 'x', prefix, messages, xs)
            ok_y = check_axis(ymin, ymax, ny, 'y', prefix, messages, ys)
            if (ok_x .and. ok_y) then
                if (real(nx, wp) * real(ny, wp) > real(max_observation_points, wp)) then
                    call add(messages, prefix//'nx * ny = '//rtoa(real(nx, wp) * real(ny, wp))// &
                             ' points is more than '//itoa(max_observation_points))
                end if
            end if
            if (messages%n > nbefore) cycle
            observations(slot)%valid = .true.
            observations(slot)%set%nx = nx
            observations(slot)%set%ny = ny
            if (.not. allocated_points(observations(slot)%set, nx * ny, prefix, messages)) cycle
            do j = 1, ny
                do i = 1, nx
                    observations(slot)%set%x(i + (j - 1) * nx) = xs(i)
                    observations(slot)%set%y(i + (j - 1) * nx) = ys(j)
                end do
            end do
        end do
    end subroutine read_grid_groups

    !> &line name, x_begin, y_begin, x_end, y_end, points / (repeated)
    subroutine read_line_groups(unit, text, path, info, observations, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(observation_input), intent(inout) :: observations(:)
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name
        real(wp) :: x_begin, y_begin, x_end, y_end
        integer :: points
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, k, i, nbefore, slot, n
        logical :: ok, same
        real(wp) :: t
        namelist /line/ name, x_begin, y_begin, x_end, y_end, points

        if (info%count == 0) return
        rewind (unit)
        do k = 1, info%count
            name = ''
            x_begin = unset_real
            y_begin = unset_real
            x_end = unset_real
            y_end = unset_real
            points = unset_integer
            read (unit, nml=line, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_line, info, k, stat, iomsg, messages)
                exit
            end if
            slot = info%slot(k)
            call start_observation(observations(slot), path, g_line, info, k, name, &
                                   observation_line, prefix)
            nbefore = messages%n
            ok = check_scalar(x_begin, 'x_begin', .true., prefix, messages)
            ok = check_scalar(y_begin, 'y_begin', .true., prefix, messages) .and. ok
            ok = check_scalar(x_end, 'x_end', .true., prefix, messages) .and. ok
            ok = check_scalar(y_end, 'y_end', .true., prefix, messages) .and. ok
            same = .false.
            if (ok) same = x_begin == x_end .and. y_begin == y_end
            if (points == unset_integer) then
                if (.not. same) then
                    call add(messages, prefix//'points is required (the number of points'// &
                             ', both ends included)')
                end if
            else if (points < 1) then
                call add(messages, prefix//'points = '//itoa(points)//' must be at least 1')
            else if (points == 1 .and. ok .and. .not. same) then
                call add(messages, prefix//'points = 1 but the ends differ; give points >= 2 '// &
                         '(both ends count)')
            else if (points > max_observation_points) then
                call add(messages, prefix//'points = '//itoa(points)//' is more than '// &
                         itoa(max_observation_points))
            end if
            if (messages%n > nbefore) cycle
            observations(slot)%valid = .true.
            n = points
            if (same) n = 1
            observations(slot)%set%nx = n
            observations(slot)%set%ny = 1
            if (.not. allocated_points(observations(slot)%set, n, prefix, messages)) cycle
            observations(slot)%set%x(1) = x_begin
            observations(slot)%set%y(1) = y_begin
            do i = 2, n - 1
                t = real(i - 1, wp) / real(n - 1, wp)
                observations(slot)%set%x(i) = x_begin + t * (x_end - x_begin)
                observations(slot)%set%y(i) = y_begin + t * (y_end - y_begin)
            end do
            if (n > 1) then
                observations(slot)%set%x(n) = x_end
                observations(slot)%set%y(n) = y_end
            end if
        end do
    end subroutine read_line_groups

    !> &points name, file / (repeated; a CSV of x,y rows)
    subroutine read_points_groups(unit, text, path, dir, info, observations, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path, dir
        type(group_record), intent(in) :: info
        type(observation_input), intent(inout) :: observations(:)
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name, file
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        real(wp), allocatable :: rows(:,:)
        type(error_type), allocatable :: csv_error
        integer :: stat, k, slot
        namelist /points/ name, file

        if (info%count == 0) return
        rewind (unit)
        do k = 1, info%count
            name = ''
            file = ''
            read (unit, nml=points, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_points, info, k, stat, iomsg, messages)
                exit
            end if
            slot = info%slot(k)
            call start_observation(observations(slot), path, g_points, info, k, name, &
                                   observation_points, prefix)
            if (len_trim(file) == 0) then
                call add(messages, prefix//'file is required (a CSV of x,y rows)')
                cycle
            end if
            call read_csv(resolve(dir, trim(adjustl(file))), [character(len=1) :: 'x', 'y'], &
                          rows, csv_error)
            if (allocated(csv_error)) then
                call add(messages, prefix_lines(prefix//'file: ', csv_error%message))
                deallocate (csv_error)
                cycle
            end if
            if (size(rows, 2) > max_observation_points) then
                call add(messages, prefix//'more than '//itoa(max_observation_points)//' points')
                cycle
            end if
            observations(slot)%valid = .true.
            observations(slot)%set%nx = size(rows, 2)
            observations(slot)%set%ny = 1
            observations(slot)%set%x = rows(1, :)
            observations(slot)%set%y = rows(2, :)
        end do
    end subroutine read_points_groups

    !> Allocate the coordinates of n points; when they do not fit in memory, say so in the
    !> messages (with exit_out_of_memory) and return false.
    function allocated_points(set, n, prefix, messages) result(ok)
        type(observation_set), intent(inout) :: set
        integer, intent(in) :: n
        character(len=*), intent(in) :: prefix
        type(message_list), intent(inout) :: messages
        logical :: ok
        integer :: stat

        allocate (set%x(n), stat=stat)
        if (stat == 0) allocate (set%y(n), stat=stat)
        ok = stat == 0
        if (ok) return
        call add(messages, prefix//'not enough memory for the coordinates of its '//itoa(n)// &
                 ' points ('//bytes_text(2.0_wp * real_bytes * real(n, wp))//')')
        messages%code = exit_out_of_memory
    end function allocated_points

    !> Label, name (or <kind>_<k>), kind and message prefix of the observation set made by
    !> occurrence k of a &grid, &line or &points group.
    subroutine start_observation(observation, path, group, info, k, name, kind, prefix)
        type(observation_input), intent(inout) :: observation
        character(len=*), intent(in) :: path
        integer, intent(in) :: group, k
        type(group_record), intent(in) :: info
        !> The name given in the group ('' when none)
        character(len=*), intent(in) :: name
        !> observation_grid, observation_line or observation_points
        integer, intent(in) :: kind
        character(len=:), allocatable, intent(out) :: prefix

        observation%label = group_label(group, k, info%lines(k), trim(adjustl(name)))
        observation%set%name = default_name(name, trim(namelist_groups(group)%name), k)
        observation%set%kind = kind
        prefix = path//': '//observation%label//': '
    end subroutine start_observation

    !> Check one axis of a grid and return its coordinates.
    function check_axis(vmin, vmax, n, axis, prefix, messages, coords) result(ok)
        real(wp), intent(in) :: vmin, vmax
        integer, intent(in) :: n
        character(len=*), intent(in) :: axis, prefix
        type(message_list), intent(inout) :: messages
        real(wp), allocatable, intent(out) :: coords(:)
        logical :: ok
        logical :: min_ok, max_ok
        integer :: i

        ok = .false.
        min_ok = check_scalar(vmin, axis//'min', .true., prefix, messages)
        max_ok = check_scalar(vmax, axis//'max', .false., prefix, messages)
        if (vmax /= unset_real .and. .not. within_limits(vmax)) return
        if (n == unset_integer) then
            call add(messages, prefix//'n'//axis//' is required (the number of grid lines)')
            return
        else if (n < 1) then
            call add(messages, prefix//'n'//axis//' = '//itoa(n)//' must be at least 1')
            return
        else if (n > max_observation_points) then
            call add(messages, prefix//'n'//axis//' = '//itoa(n)//' is more than '// &
                     itoa(max_observation_points))
            return
        end if
        if (n > 1 .and. .not. max_ok .and. vmax == unset_real) then
            call add(messages, prefix//axis//'max is required when n'//axis//' > 1')
            return
        end if
        if (.not. min_ok) return
        ok = .true.
        allocate (coords(n))
        coords(1) = vmin
        do i = 2, n - 1
            coords(i) = vmin + (vmax - vmin) * (real(i - 1, wp) / real(n - 1, wp))
        end do
        if (n > 1) coords(n) = vmax
    end function check_axis

end module ddc_input_namelist_observations
