!> The &cycle group of a namelist input file (docs/input-reference.md#cycle): earthquake
!> cycles on the model's rate-and-state elements (docs/earthquake-cycles.md). Sets the
!> defaults, reads the group if present and checks every value, and that the model is one a
!> cycle run takes: rate-and-state elements (and only with &cycle), no contact elements, no
!> &growth or &load_path, and an initial state on every rate-and-state element.
module ddc_input_namelist_cycle
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, condition_rate_state, condition_contact, &
        domain_bimaterial
    use ddc_model_cycles, only: state_law_names, radiation_damping_of
    use ddc_model_rate_state, only: rs_v_init, rs_tau0
    use ddc_model_loads, only: shear_modulus_of
    use ddc_model_limits, only: quantity_positive, quantity_non_negative
    use ddc_text, only: itoa, rtoa, lower, find_name, quoted_list
    use ddc_input_namelist_groups, only: group_record, message_list, add, group_prefix, &
        g_cycle, g_growth, g_load_path
    use ddc_input_namelist_diagnosis, only: report_malformed
    use ddc_input_namelist_values, only: unset_real, text_length, check_scalar
    use ddc_input_namelist_fracture, only: fracture_input
    implicit none
    private

    public :: read_cycle_group

contains

    !> &cycle end_time, tolerance, shear_wave_speed, radiation_damping, plate_rate,
    !> seismic_threshold, state_law, output_interval, event_output_interval,
    !> profile_spacing, checkpoint_interval / (optional; read after &model and the
    !> fractures, whose rate-and-state values it checks).
    subroutine read_cycle_group(unit, text, path, groups, fractures, model, messages)
        !> Unit of the open input file
        integer, intent(in) :: unit
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Where every group occurs (scan_groups), shape (size(namelist_groups))
        type(group_record), intent(in) :: groups(:)
        !> The fractures as read
        type(fracture_input), intent(in) :: fractures(:)
        !> model%cycle is set; &model must be read already
        type(model_type), intent(inout) :: model
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        real(wp) :: end_time, tolerance, shear_wave_speed, radiation_damping, plate_rate, &
            seismic_threshold, output_interval, event_output_interval, profile_spacing, &
            checkpoint_interval
        character(len=text_length) :: state_law
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        logical :: rate_state
        integer :: stat, law
        namelist /cycle/ end_time, tolerance, shear_wave_speed, radiation_damping, plate_rate, &
            seismic_threshold, state_law, output_interval, event_output_interval, &
            profile_spacing, checkpoint_interval

        rate_state = any(fractures%valid .and. fractures%condition == condition_rate_state)
        if (groups(g_cycle)%count == 0) then
            if (rate_state) call add(messages, path//": condition 'rate_state' needs a "// &
                                     '&cycle group (the earthquake-cycle run of its elements)')
            return
        end if
        associate (c => model%cycle)
            end_time = unset_real
            tolerance = c%tolerance
            shear_wave_speed = unset_real
            radiation_damping = unset_real
            plate_rate = c%plate_rate
            seismic_threshold = c%seismic_threshold
            state_law = 'aging'
            output_interval = unset_real
            event_output_interval = c%event_output_interval
            profile_spacing = c%profile_spacing
            checkpoint_interval = c%checkpoint_interval
            rewind (unit)
            read (unit, nml=cycle, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_cycle, groups(g_cycle), 1, stat, iomsg, &
                                      messages)
                return
            end if
            prefix = group_prefix(path, g_cycle, groups(g_cycle), 1)
            c%active = .true.
            if (check_scalar(end_time, 'end_time', .true., prefix, messages, &
                             quantity_positive)) c%end_time = end_time
            if (check_scalar(tolerance, 'tolerance', .false., prefix, messages, &
                             quantity_positive)) then
                if (tolerance < 1.0_wp) then
                    c%tolerance = tolerance
                else
                    call add(messages, prefix//'tolerance = '//rtoa(tolerance)// &
                             ' must be below 1 (a relative error)')
                end if
            end if
            call read_damping()
            if (check_scalar(plate_rate, 'plate_rate', .false., prefix, messages)) then
              c%plate_rate = plate_rate
            end if
            if (check_scalar(seismic_threshold, 'seismic_threshold', .false., prefix, &
                             messages, quantity_positive)) c%seismic_threshold = seismic_threshold
            law = find_name(lower(trim(adjustl(state_law))), state_law_names)
            if (law == 0) then
                call add(messages, prefix//"state_law = '"//trim(adjustl(state_law))// &
                         "' is not one of "//quoted_list(state_law_names))
            else
                c%state_law = law
            end if
            ! About 10^4 rows between events unless given (docs/input-reference.md#cycle)
            if (output_interval == unset_real .and. c%end_time > 0.0_wp) then
              output_interval = c%end_time / 1.0e4_wp
            end if
            if (check_scalar(output_interval, 'output_interval', .false., prefix, messages, &
                             quantity_non_negative)) c%output_interval = output_interval
            if (check_scalar(event_output_interval, 'event_output_interval', .false., prefix, &
                             messages, quantity_non_negative)) then
              c%event_output_interval = event_output_interval
            end if
            if (check_scalar(profile_spacing, 'profile_spacing', .false., prefix, messages, &
                             quantity_non_negative)) c%profile_spacing = profile_spacing
            if (check_scalar(checkpoint_interval, 'checkpoint_interval', .false., prefix, &
                             messages, quantity_non_negative)) then
              c%checkpoint_interval = checkpoint_interval
            end if
        end associate
        call check_cycle_model()

    contains

        !> Radiation damping: given, or G / (2 c_s) from the shear wave speed; one of the two.
        subroutine read_damping()
            associate (c => model%cycle)
                if (shear_wave_speed /= unset_real .and. radiation_damping /= unset_real) then
                    call add(messages, prefix//'give shear_wave_speed or radiation_damping, '// &
                             'not both')
                else if (shear_wave_speed /= unset_real) then
                    if (check_scalar(shear_wave_speed, 'shear_wave_speed', .false., prefix, &
                                     messages, quantity_positive)) then
                        c%shear_wave_speed = shear_wave_speed
                    end if
                else if (radiation_damping /= unset_real) then
                    if (check_scalar(radiation_damping, 'radiation_damping', .false., prefix, &
                                     messages, quantity_non_negative)) then
                      c%radiation_damping = radiation_damping
                    end if
                else
                    call add(messages, prefix//'shear_wave_speed or radiation_damping is '// &
                             'required (the radiation damping G / (2 c_s) of every '// &
                             'rate-and-state element)')
                end if
            end associate
        end subroutine read_damping

        !> What a cycle run takes: rate-and-state elements, none of condition 'contact', no
        !> growth or loading history, an initial state on every rate-and-state element.
        subroutine check_cycle_model()
            integer :: k

            ! A fracture that could not be read may be a rate-and-state one: its own message
            ! is enough.
            if (.not. rate_state .and. all(fractures%valid)) call add(messages, prefix// &
                "needs rate-and-state elements (a &fracture with condition = 'rate_state')")
            if (any(fractures%valid .and. fractures%condition == condition_contact)) then
              call add(messages, prefix//"does not take elements of condition 'contact' "// &
                         "(a cycle run's faults are its rate-and-state elements)")
            end if
            if (groups(g_growth)%count > 0) call add(messages, prefix//'does not combine '// &
                                                     'with &growth')
            if (groups(g_load_path)%count > 0) call add(messages, prefix//'does not '// &
                'combine with &load_path (the loading is back-slip at plate_rate)')
            if (model%elements%domain == domain_bimaterial) call add(messages, prefix// &
                "does not combine with domain = 'bimaterial' (one material: radiation "// &
                'damping and back-slip take one shear modulus)')
            do k = 1, size(fractures)
                if (.not. fractures(k)%valid) cycle
                if (fractures(k)%condition /= condition_rate_state) cycle
                call check_initial_state(fractures(k))
            end do
        end subroutine check_cycle_model

        !> The initial shear traction must drive the initial slip rate against the radiation
        !> damping: -tau0 - eta v_init of the sign of v_init, v_init not 0
        !> (docs/theory/cycles.md#initial-state).
        subroutine check_initial_state(fracture)
            type(fracture_input), intent(in) :: fracture
            real(wp) :: v, tau, drive
            integer :: i

            do i = 1, size(fracture%rate_state, 1)
                v = fracture%rate_state(i, rs_v_init)
                tau = fracture%rate_state(i, rs_tau0)
                drive = -tau - radiation_damping_of(model%cycle, shear_modulus_of(model)) * v
                if (v == 0.0_wp) then
                    call add(messages, prefix//fracture%label//': element '//itoa(i)// &
                             ' has v_init = 0: the initial state follows from a slip rate '// &
                             'that is not 0')
                    return
                else if (.not. drive * v > 0.0_wp) then
                    call add(messages, prefix//fracture%label//': element '//itoa(i)// &
                             ' has tau0 = '//rtoa(tau)//' and v_init = '//rtoa(v)// &
                             ', which give no initial state: -tau0 - eta v_init = '// &
                             rtoa(drive)//' must have the sign of v_init (a shear traction '// &
                             'in ddc2d''s sign, tension positive, drives a slip rate of '// &
                             'the opposite sign)')
                    return
                end if
            end do
        end subroutine check_initial_state

    end subroutine read_cycle_group

end module ddc_input_namelist_cycle
