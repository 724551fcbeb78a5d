!> Read the record of an earthquake-cycle run back from its result file (--resume of a cycle
!> run; docs/earthquake-cycles.md#checkpoints-and---resume): /cycle and /cycle/resume as
!> ddc_output_hdf5_cycle wrote them, bit for bit. The file was checked before
!> (app/resume_check: same version and model), so a dataset that is missing here is an
!> error of the file.
module ddc_output_cycle_read
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_io_failure
    use ddc_text, only: find_name, itoa
    use ddc_model_cycles, only: cycle_record, cycle_end_names
    use ddc_output_hdf5_read, only: read_real_dataset, read_int_dataset, read_dataset_dims, &
        read_string_attribute, read_int_attribute, read_real_attribute
    implicit none
    private

    public :: read_cycle_record

contains

    !> The record of the cycle run in the result file `path`.
    subroutine read_cycle_record(path, record, error)
        !> The result file
        character(len=*), intent(in) :: path
        !> Its record, with where the run stands
        type(cycle_record), intent(out) :: record
        !> Set (exit_io_failure, naming the file) when something cannot be read
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: reason
        real(wp), allocatable :: value(:)
        integer :: r, p, k, flag

        call read_int_dataset(path, '/cycle/elements', record%elements, error)
        if (.not. allocated(error)) call read_int_dataset(path, '/cycle/profile', &
                                                          record%profile, error)
        if (.not. allocated(error)) call read_real_dataset(path, '/cycle/distance', &
                                                           record%distance, error)
        if (allocated(error)) return
        call reals('time', record%time)
        call reals('max_slip_rate', record%max_slip_rate)
        if (.not. allocated(error)) call read_int_dataset(path, '/cycle/max_rate_element', &
                                                          record%max_rate_element, error)
        if (allocated(error)) return
        k = size(record%time)
        record%rows = k
        r = size(record%profile)
        call table('slip', r, k, record%slip)
        call table('slip_rate', r, k, record%slip_rate)
        call table('shear_traction', r, k, record%shear_traction)
        call table('normal_traction', r, k, record%normal_traction)
        call table('state', r, k, record%state)
        call columns_of('ux', p)
        call table('ux', p, k, record%ux)
        call table('uy', p, k, record%uy)
        call table('vx', p, k, record%vx)
        call table('vy', p, k, record%vy)
        call reals('event_start', record%event_start)
        call reals('event_end', record%event_end)
        call reals('event_x', record%event_x)
        call reals('event_y', record%event_y)
        call reals('event_peak_rate', record%event_peak_rate)
        call reals('event_max_slip', record%event_max_slip)
        call reals('event_moment', record%event_moment)
        if (.not. allocated(error)) call read_int_dataset(path, '/cycle/event_element', &
                                                          record%event_element, error)
        if (allocated(error)) return
        record%events = size(record%event_start)
        call table('event_slip', r, record%events, record%event_slip)
        if (.not. allocated(error)) call read_string_attribute(path, '/cycle', 'end_reason', &
                                                               reason, error)
        if (allocated(error)) return
        record%end_reason = find_name(reason, cycle_end_names) - 1
        call integer_attribute('/cycle', 'end_element', record%end_element)
        call integer_attribute('/cycle', 'steps', record%steps)
        call integer_attribute('/cycle', 'rejected_steps', record%rejected)
        call integer_attribute('/cycle', 'products', record%products)
        call real_attribute('/cycle', 'newton_iterations')
        if (allocated(value)) record%newton_iterations = nint(value(1), int64)
        call real_attribute('/cycle', 'seconds')
        if (allocated(value)) record%seconds = value(1)
        associate (now => record%now)
            call real_attribute('/cycle/resume', 'time')
            if (allocated(value)) now%time = value(1)
            call real_attribute('/cycle/resume', 'step')
            if (allocated(value)) now%step = value(1)
            call real_attribute('/cycle/resume', 'last_row')
            if (allocated(value)) now%last_row = value(1)
            call real_attribute('/cycle/resume', 'event_start')
            if (allocated(value)) now%event_start = value(1)
            call real_attribute('/cycle/resume', 'event_peak_rate')
            if (allocated(value)) now%event_peak_rate = value(1)
            call integer_attribute('/cycle/resume', 'event_element', now%event_element)
            call integer_attribute('/cycle/resume', 'in_event', flag)
            now%in_event = flag == 1
            call reals('resume/slip', now%slip)
            call reals('resume/state', now%state)
            call reals('resume/slip_rate', now%slip_rate)
            call reals('resume/event_start_slip', now%event_start_slip)
        end associate

    contains

        !> /cycle/<name>, 1-D.
        subroutine reals(name, values)
            character(len=*), intent(in) :: name
            real(wp), allocatable, intent(out) :: values(:)

            if (allocated(error)) then
                allocate (values(0))
                return
            end if
            call read_real_dataset(path, '/cycle/'//name, values, error)
        end subroutine reals

        !> The columns of the table /cycle/<name> (its second Fortran dimension).
        subroutine columns_of(name, count)
            character(len=*), intent(in) :: name
            integer, intent(out) :: count
            integer, allocatable :: dims(:)

            count = 0
            if (allocated(error)) return
            call read_dataset_dims(path, '/cycle/'//name, dims, error)
            if (.not. allocated(error)) count = dims(1)
        end subroutine columns_of

        !> /cycle/<name>, shape (rows, columns) in Fortran order.
        subroutine table(name, rows, columns, values)
            character(len=*), intent(in) :: name
            integer, intent(in) :: rows, columns
            real(wp), allocatable, intent(out) :: values(:, :)
            real(wp), allocatable :: flat(:)

            allocate (values(rows, columns))
            call reals(name, flat)
            if (allocated(error)) return
            if (size(flat) /= rows * columns) then
                call set_error(error, exit_io_failure, path//': /cycle/'//name//' has '// &
                               itoa(size(flat))//' values, not '//itoa(rows * columns))
                return
            end if
            values = reshape(flat, [rows, columns])
        end subroutine table

        subroutine integer_attribute(object, name, target_value)
            character(len=*), intent(in) :: object, name
            integer, intent(inout) :: target_value

            if (allocated(error)) return
            call read_int_attribute(path, object, name, target_value, error)
        end subroutine integer_attribute

        subroutine real_attribute(object, name)
            character(len=*), intent(in) :: object, name

            if (allocated(value)) deallocate (value)
            if (allocated(error)) return
            call read_real_attribute(path, object, name, value, error)
        end subroutine real_attribute
    end subroutine read_cycle_record

end module ddc_output_cycle_read
