!> The record of an earthquake-cycle run in the result file (ddc_output_hdf5's layout,
!> docs/output-reference.md#cycle): /cycle with its rows, recorded elements, observation
!> points and events, /cycle/resume (where the run stands, for --resume), and the values of
!> the rate-and-state elements in /elements.
module ddc_output_hdf5_cycle
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_text, only: allocated_text
    use ddc_model_types, only: model_type
    use ddc_model_cycles, only: cycle_record, cycle_resume, state_law_names, cycle_end_names, &
        radiation_damping_of
    use ddc_model_loads, only: shear_modulus_of
    use ddc_model_rate_state, only: rate_state_value, rate_state_count, rate_state_values, &
        rate_state_table, rate_state_units
    use ddc_output_hdf5_handles, only: h5_object, create_group, close_group
    use ddc_output_hdf5_write, only: write_real_1d, write_int_1d, write_real_dataset, &
        write_attribute
    implicit none
    private

    public :: write_cycle, write_rate_state

contains

    !> The model's unit names: length, stress, time.
    pure subroutine unit_names(model, length, stress, time)
        type(model_type), intent(in) :: model
        character(len=:), allocatable, intent(out) :: length, stress, time

        length = allocated_text(model%length_unit)
        stress = allocated_text(model%stress_unit)
        time = allocated_text(model%time_unit)
    end subroutine unit_names

    !> /elements/<value> of every rate-and-state value (ddc_model_rate_state; 0 on elements
    !> of other conditions).
    subroutine write_rate_state(group, model, error)
        !> /elements
        type(h5_object), intent(in) :: group
        !> The model
        type(model_type), intent(in) :: model
        !> Set when a write fails
        type(error_type), allocatable, intent(inout) :: error
        type(rate_state_value) :: values(rate_state_count)
        character(len=:), allocatable :: length, stress, time
        real(wp), allocatable :: table(:, :)
        integer :: k, i

        call unit_names(model, length, stress, time)
        values = rate_state_values()
        table = rate_state_table(model%elements, [(i, i = 1, model%elements%n)])
        do k = 1, rate_state_count
            call write_real_1d(group, values(k)%name, table(:, k), &
                               rate_state_units(values(k)%units, stress, length, time), error)
        end do
    end subroutine write_rate_state

    !> /cycle: the options as attributes, how the run ended and what it took; the rows, the
    !> recorded elements, the observation points' series, the events; /cycle/resume.
    subroutine write_cycle(root, model, record, error)
        !> The file
        type(h5_object), intent(in) :: root
        !> The model that was run
        type(model_type), intent(in) :: model
        !> Its record
        type(cycle_record), intent(in) :: record
        !> Set when a write fails (nothing is written when it is set already)
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: group
        character(len=:), allocatable :: length, stress, time, rate
        real(wp), allocatable :: px(:), py(:)
        integer :: k, e, r, p, i

        if (allocated(error)) return
        call unit_names(model, length, stress, time)
        rate = length//'/'//time
        k = record%rows
        e = record%events
        r = size(record%profile)
        p = size(record%ux, 1)
        call create_group(root, 'cycle', group, error)
        if (allocated(error)) return
        associate (c => model%cycle)
            call write_attribute(group, 'time_unit', time, error)
            call write_attribute(group, 'end_time', c%end_time, error)
            call write_attribute(group, 'tolerance', c%tolerance, error)
            call write_attribute(group, 'radiation_damping', &
                                 radiation_damping_of(c, shear_modulus_of(model)), error)
            call write_attribute(group, 'shear_wave_speed', c%shear_wave_speed, error)
            call write_attribute(group, 'plate_rate', c%plate_rate, error)
            call write_attribute(group, 'seismic_threshold', c%seismic_threshold, error)
            call write_attribute(group, 'state_law', trim(state_law_names(c%state_law)), error)
            call write_attribute(group, 'output_interval', c%output_interval, error)
            call write_attribute(group, 'event_output_interval', c%event_output_interval, &
                                 error)
            call write_attribute(group, 'profile_spacing', c%profile_spacing, error)
        end associate
        call write_attribute(group, 'end_reason', trim(cycle_end_names(record%end_reason)), &
                             error)
        call write_attribute(group, 'end_element', record%end_element, error)
        call write_attribute(group, 'steps', record%steps, error)
        call write_attribute(group, 'rejected_steps', record%rejected, error)
        call write_attribute(group, 'products', record%products, error)
        call write_attribute(group, 'newton_iterations', real(record%newton_iterations, wp), &
                             error)
        call write_attribute(group, 'seconds', record%seconds, error)
        call write_int_1d(group, 'elements', record%elements, error)
        call write_int_1d(group, 'profile', record%profile, error)
        call write_real_1d(group, 'distance', record%distance, length, error)
        call write_real_1d(group, 'time', record%time(:k), time, error)
        call write_real_1d(group, 'max_slip_rate', record%max_slip_rate(:k), rate, error)
        call write_int_1d(group, 'max_rate_element', record%max_rate_element(:k), error)
        call write_table('slip', record%slip, r, k, length)
        call write_table('slip_rate', record%slip_rate, r, k, rate)
        call write_table('shear_traction', record%shear_traction, r, k, stress)
        call write_table('normal_traction', record%normal_traction, r, k, stress)
        call write_table('state', record%state, r, k, 'log10 '//time)
        allocate (px(0), py(0))
        if (allocated(model%observations)) then
            do i = 1, size(model%observations)
                px = [px, model%observations(i)%x]
                py = [py, model%observations(i)%y]
            end do
        end if
        call write_real_1d(group, 'point_x', px, length, error)
        call write_real_1d(group, 'point_y', py, length, error)
        call write_table('ux', record%ux, p, k, length)
        call write_table('uy', record%uy, p, k, length)
        call write_table('vx', record%vx, p, k, rate)
        call write_table('vy', record%vy, p, k, rate)
        call write_real_1d(group, 'event_start', record%event_start(:e), time, error)
        call write_real_1d(group, 'event_end', record%event_end(:e), time, error)
        call write_int_1d(group, 'event_element', record%event_element(:e), error)
        call write_real_1d(group, 'event_x', record%event_x(:e), length, error)
        call write_real_1d(group, 'event_y', record%event_y(:e), length, error)
        call write_real_1d(group, 'event_peak_rate', record%event_peak_rate(:e), rate, error)
        call write_real_1d(group, 'event_max_slip', record%event_max_slip(:e), length, error)
        call write_real_1d(group, 'event_moment', record%event_moment(:e), stress//' '// &
                           length, error)
        call write_table('event_slip', record%event_slip, r, e, length)
        call write_resume(group, record%now, rate, length, error)
        call close_group(group, error)

    contains

        !> Columns 1..columns of a table (rows, room), shaped (columns, rows) in h5py.
        subroutine write_table(name, values, rows, columns, units)
            character(len=*), intent(in) :: name
            real(wp), intent(in) :: values(:, :)
            integer, intent(in) :: rows, columns
            character(len=*), intent(in) :: units

            call write_real_dataset(group, name, reshape(values(:, :columns), [rows * columns]), &
                                    [rows, columns], units, error)
        end subroutine write_table
    end subroutine write_cycle

    !> /cycle/resume: where the run stands (docs/output-reference.md#cycle).
    subroutine write_resume(parent, now, rate, length, error)
        type(h5_object), intent(in) :: parent
        type(cycle_resume), intent(in) :: now
        character(len=*), intent(in) :: rate, length
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: group

        call create_group(parent, 'resume', group, error)
        if (allocated(error)) return
        call write_attribute(group, 'time', now%time, error)
        call write_attribute(group, 'step', now%step, error)
        call write_attribute(group, 'last_row', now%last_row, error)
        call write_attribute(group, 'in_event', merge(1, 0, now%in_event), error)
        call write_attribute(group, 'event_start', now%event_start, error)
        call write_attribute(group, 'event_peak_rate', now%event_peak_rate, error)
        call write_attribute(group, 'event_element', now%event_element, error)
        call write_real_1d(group, 'slip', now%slip, length, error)
        call write_real_1d(group, 'state', now%state, '1', error)
        call write_real_1d(group, 'slip_rate', now%slip_rate, rate, error)
        call write_real_1d(group, 'event_start_slip', now%event_start_slip, length, error)
        call close_group(group, error)
    end subroutine write_resume

end module ddc_output_hdf5_cycle
