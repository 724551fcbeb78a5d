!> The echo of a cycle run's options and the summary of its record (docs/earthquake-cycles.md):
!> what the program prints of &cycle before the run and of /cycle after it.
module ddc_app_report_cycle
    use ddc_kinds, only: wp
    use ddc_text, only: itoa, short_real, counted, allocated_text
    use ddc_model_types, only: model_type
    use ddc_model_cycles, only: cycle_record, state_law_names, cycle_end_names, &
        radiation_damping_of
    use ddc_model_loads, only: shear_modulus_of
    implicit none
    private

    public :: print_cycle_options, print_cycle_summary

contains

    !> The options of &cycle as the run takes them.
    subroutine print_cycle_options(unit, model)
        !> The unit written to
        integer, intent(in) :: unit
        !> A cycle model
        type(model_type), intent(in) :: model
        character(len=:), allocatable :: time, rate, damping

        time = allocated_text(model%time_unit)
        rate = model%length_unit//'/'//time
        associate (c => model%cycle)
            damping = short_real(radiation_damping_of(c, shear_modulus_of(model)))//' '// &
                model%stress_unit//' '//time//'/'//model%length_unit
            if (c%shear_wave_speed > 0.0_wp) damping = damping//' (G / (2 c_s), c_s = '// &
                short_real(c%shear_wave_speed)//' '//rate//')'
            write (unit, '(a)') '  cycle: to t = '//short_real(c%end_time)//' '//time// &
                ', tolerance '//short_real(c%tolerance)//', '//trim(state_law_names( &
                c%state_law))//' law, plate rate '//short_real(c%plate_rate)//' '//rate
            write (unit, '(a)') '    radiation damping '//damping//', seismic from '// &
                short_real(c%seismic_threshold)//' '//rate
            write (unit, '(a)') '    rows every '//short_real(c%output_interval)//' '//time// &
                ' (in events '//short_real(c%event_output_interval)//'), elements every '// &
                short_real(c%profile_spacing)//' '//model%length_unit//', checkpoint every '// &
                short_real(c%checkpoint_interval)//' s'
        end associate
    end subroutine print_cycle_options

    !> How the run went: events, steps, products, rows, how it ended.
    subroutine print_cycle_summary(unit, model, record)
        !> The unit written to
        integer, intent(in) :: unit
        !> The model
        type(model_type), intent(in) :: model
        !> Its record
        type(cycle_record), intent(in) :: record
        character(len=:), allocatable :: time

        time = allocated_text(model%time_unit)
        write (unit, '(a)') '  cycle: '//counted(record%events, 'event', 'events')//' to t = '// &
            short_real(record%now%time)//' '//time//' ('//trim(cycle_end_names( &
            record%end_reason))//'), '//itoa(record%steps)//' steps ('//itoa(record%rejected)// &
            ' rejected), '//itoa(record%products)//' products, '//itoa(record%rows)// &
            ' rows, '//short_real(record%seconds)//' s'
    end subroutine print_cycle_summary

end module ddc_app_report_cycle
