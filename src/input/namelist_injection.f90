!> The &injection groups of a namelist input file (docs/injection.md#the-input): fluid
!> sources at points of the fractures, one group per source. Each holds a pressure change
!> (overpressure) or a volume rate (rate) at its point from its start time until its stop
!> time (a shut-in). The sources need a loading history with a time axis, and a fracture
!> that conducts at their point (checked once the elements exist: check_injection_points).
!> The &fluid group makes the flow follow the opening (docs/fluid-driven-fractures.md): the
!> fluid's viscosity, compressibility and leak-off (read_fluid_group), and the model it
!> needs (check_fluid_model).
module ddc_input_namelist_injection
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, source_overpressure, source_rate, &
        condition_contact, symmetry_none, rigid_joint, growth_criterion_mts, growth_tips_all
    use ddc_model_limits, only: quantity_positive, quantity_non_negative
    use ddc_contact_options, only: matrix_hierarchical, k_higher_order
    use ddc_text, only: rtoa, lower
    use ddc_mesh_ends, only: elements_at_point
    use ddc_input_namelist_groups, only: group_record, message_list, add, group_label, &
        group_prefix, g_injection, g_fluid
    use ddc_input_namelist_diagnosis, only: report_malformed
    use ddc_input_namelist_values, only: unset_real, check_scalar, text_length, default_name
    implicit none
    private

    public :: read_injection_groups, check_injection_points, read_fluid_group, &
        check_fluid_model

contains

    !> &injection name, fracture, x, y, overpressure, rate, start, stop / (repeated, one per
    !> source). Read after the fractures (their names) and the load path (its times).
    subroutine read_injection_groups(unit, text, path, info, fracture_names, model, messages)
        !> Unit of the open input file
        integer, intent(in) :: unit
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Where the groups occur
        type(group_record), intent(in) :: info
        !> Names of the fractures, in order, shape (fractures)
        character(len=*), intent(in) :: fracture_names(:)
        !> model%injections is set (size 0 without a group)
        type(model_type), intent(inout) :: model
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name, fracture
        real(wp) :: x, y, overpressure, rate, start, stop
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, k, j
        namelist /injection/ name, fracture, x, y, overpressure, rate, start, stop

        allocate (model%injections(info%count))
        if (info%count == 0) return
        rewind (unit)
        do k = 1, info%count
            name = ''
            fracture = ''
            x = unset_real
            y = unset_real
            overpressure = unset_real
            rate = unset_real
            start = unset_real
            stop = unset_real
            read (unit, nml=injection, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_injection, info, k, stat, iomsg, messages)
                exit
            end if
            prefix = path//': '//group_label(g_injection, k, info%lines(k), &
                                              trim(adjustl(name)))//': '
            associate (s => model%injections(k))
                s%name = default_name(name, 'injection', k)
                s%fracture_id = findloc([(lower(trim(adjustl(fracture_names(j)))) == &
                                         lower(trim(adjustl(fracture))), j = 1, &
                                         size(fracture_names))], .true., 1)
                if (len_trim(fracture) == 0) then
                    call add(messages, prefix//'fracture is required: the name of the '// &
                             'fracture the source is on')
                else if (s%fracture_id == 0) then
                    call add(messages, prefix//"fracture = '"//trim(adjustl(fracture))// &
                             "' names no &fracture")
                end if
                if (check_scalar(x, 'x', .true., prefix, messages)) s%x = x
                if (check_scalar(y, 'y', .true., prefix, messages)) s%y = y
                if ((overpressure == unset_real) .eqv. (rate == unset_real)) then
                    call add(messages, prefix//'give either overpressure (a pressure change '// &
                             'held at the point) or rate (a volume rate into it), one of them')
                else if (overpressure /= unset_real) then
                    s%kind = source_overpressure
                    if (check_scalar(overpressure, 'overpressure', .true., prefix, messages)) then
                        s%value = overpressure
                    end if
                else
                    s%kind = source_rate
                    if (check_scalar(rate, 'rate', .true., prefix, messages)) s%value = rate
                end if
                if (check_scalar(start, 'start', .false., prefix, messages)) s%start = start
                if (check_scalar(stop, 'stop', .false., prefix, messages)) s%stop = stop
                call check_times(s%start, s%stop)
            end associate
        end do

    contains

        !> A time axis, a start at or after its first time, a stop after the start.
        subroutine check_times(start_time, stop_time)
            real(wp), intent(in) :: start_time, stop_time

            if (.not. allocated(model%load_path%time)) then
                call add(messages, prefix//'a source needs a time axis: &load_path time, '// &
                         'one time per vertex')
                return
            end if
            associate (first => model%load_path%time(1))
                if (start_time /= -huge(1.0_wp) .and. start_time < first) then
                    call add(messages, prefix//'start = '//rtoa(start_time)//' is before '// &
                             'the first time of &load_path ('//rtoa(first)//')')
                end if
                if (stop_time <= max(start_time, first)) then
                    call add(messages, prefix//'stop = '//rtoa(stop_time)//' is not after '// &
                             'the start ('//rtoa(max(start_time, first))//')')
                end if
            end associate
        end subroutine check_times
    end subroutine read_injection_groups

    !> Every source's point lies on its fracture, on elements that conduct (diffusivity
    !> and transmissivity given; with &fluid a residual aperture).
    subroutine check_injection_points(path, info, model, messages)
        !> Path of the input file
        character(len=*), intent(in) :: path
        !> Where the groups occur
        type(group_record), intent(in) :: info
        !> The model, its elements' geometry computed
        type(model_type), intent(in) :: model
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        integer, allocatable :: at(:)
        character(len=:), allocatable :: prefix
        integer :: k

        do k = 1, size(model%injections)
            associate (s => model%injections(k), e => model%elements)
                prefix = path//': '//group_label(g_injection, k, info%lines(k), s%name)//': '
                at = elements_at_point(e, s%fracture_id, s%x, s%y)
                if (size(at) == 0) then
                    call add(messages, prefix//'x, y = '//rtoa(s%x)//', '//rtoa(s%y)// &
                             ' is not on fracture '''// &
                             model%fractures(s%fracture_id)%name//'''')
                else if (model%fluid%active) then
                    if (any(.not. e%residual_aperture(at) > 0.0_wp)) call add(messages, &
                        prefix//'fracture '''//model%fractures(s%fracture_id)%name// &
                        ''' does not conduct at x, y = '//rtoa(s%x)//', '//rtoa(s%y)// &
                        ': give its residual_aperture (&fluid)')
                else if (any(.not. (e%diffusivity(at) > 0.0_wp .and. &
                                    e%transmissivity(at) > 0.0_wp))) then
                    call add(messages, prefix//'fracture '''// &
                             model%fractures(s%fracture_id)%name//''' does not conduct at '// &
                             'x, y = '//rtoa(s%x)//', '//rtoa(s%y)//': give its '// &
                             'diffusivity and transmissivity')
                end if
            end associate
        end do
    end subroutine check_injection_points

    !> &fluid viscosity, compressibility, leak_off_coefficient / (at most once).
    subroutine read_fluid_group(unit, text, path, info, model, messages)
        !> Unit of the open input file
        integer, intent(in) :: unit
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Where the group occurs
        type(group_record), intent(in) :: info
        !> model%fluid is set
        type(model_type), intent(inout) :: model
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        real(wp) :: viscosity, compressibility, leak_off_coefficient
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat
        namelist /fluid/ viscosity, compressibility, leak_off_coefficient

        if (info%count == 0) return
        viscosity = unset_real
        compressibility = unset_real
        leak_off_coefficient = 0.0_wp
        rewind (unit)
        read (unit, nml=fluid, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_fluid, info, 1, stat, iomsg, messages)
            return
        end if
        prefix = group_prefix(path, g_fluid, info, 1)
        model%fluid%active = .true.
        if (check_scalar(viscosity, 'viscosity', .true., prefix, messages, &
                         quantity_positive)) model%fluid%viscosity = viscosity
        ! A closed fracture's faces do not move: its fluid is stored by compression alone.
        if (check_scalar(compressibility, 'compressibility', .true., prefix, messages, &
                         quantity_positive)) model%fluid%compressibility = compressibility
        if (check_scalar(leak_off_coefficient, 'leak_off_coefficient', .false., prefix, &
                         messages, quantity_non_negative)) then
            model%fluid%leak_off_coefficient = leak_off_coefficient
        end if
        if (.not. allocated(model%load_path%time)) call add(messages, prefix// &
            'coupled flow needs a time axis: &load_path time, one time per vertex')
    end subroutine read_fluid_group

    !> What coupled flow needs of the model once its elements exist: sources; conducting
    !> elements that are contact elements; no diffusivity or transmissivity (the flow
    !> follows from the aperture); none of the features it does not combine with. Without
    !> &fluid, no residual aperture.
    subroutine check_fluid_model(path, groups, model, messages)
        !> Path of the input file
        character(len=*), intent(in) :: path
        !> Where every group occurs
        type(group_record), intent(in) :: groups(:)
        !> The model, its elements' geometry computed
        type(model_type), intent(in) :: model
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        character(len=:), allocatable :: prefix
        integer :: k

        associate (e => model%elements)
            if (.not. model%fluid%active) then
                do k = 1, size(model%fractures)
                    associate (f => model%fractures(k))
                        if (any(e%residual_aperture(f%first_element:f%last_element) > &
                                0.0_wp)) call add(messages, path//': &fracture '''//f%name// &
                            ''': residual_aperture is for flow coupled to the opening: '// &
                            'give the fluid (&fluid viscosity, compressibility)')
                    end associate
                end do
                return
            end if
            prefix = group_prefix(path, g_fluid, groups(g_fluid), 1)
            do k = 1, size(model%fractures)
                associate (f => model%fractures(k))
                    if (any(e%diffusivity(f%first_element:f%last_element) > 0.0_wp)) then
                        call add(messages, prefix//'&fracture '''//f%name//''' gives '// &
                                 'diffusivity and transmissivity: with &fluid the flow '// &
                                 'follows from the aperture; give residual_aperture instead')
                    end if
                    if (any(e%residual_aperture(f%first_element:f%last_element) > 0.0_wp &
                            .and. e%condition(f%first_element:f%last_element) /= &
                            condition_contact)) then
                        call add(messages, prefix//'&fracture '''//f%name//''': only '// &
                                 'contact elements conduct (residual_aperture on a '// &
                                 'TWODD-style condition)')
                    end if
                end associate
            end do
            if (.not. any(e%residual_aperture > 0.0_wp)) call add(messages, prefix// &
                'no fracture conducts: give &fracture residual_aperture')
        end associate
        if (groups(g_injection)%count == 0) call add(messages, prefix//'coupled flow '// &
            'needs a source: &injection rate or overpressure')
        call refuse(model%growth%active .and. model%growth%criterion /= growth_criterion_mts, &
                    "&growth criterion = 'work' (fluid-driven growth takes K_I = K_Ic)")
        call refuse(model%growth%increment > 0.0_wp .or. model%growth%element_length > 0.0_wp, &
                    '&growth increment or element_length (fluid-driven growth adds one '// &
                    'element of the tip element''s length per step)')
        call refuse(model%growth%tips /= growth_tips_all, &
                    "&growth tips = 'most_critical' (every tip whose K_I reaches the "// &
                    'toughness grows)')
        call refuse(model%growth%active .and. model%solver%k_method == k_higher_order, &
                    "&growth and &solver k_method = 'higher_order' (a fluid-driven tip "// &
                    "meets the apparent toughness with the tip element's K_I)")
        call refuse(model%initiation%active, '&initiation')
        call refuse(model%cycle%active, '&cycle')
        call refuse(allocated(model%body), '&body')
        call refuse(model%elements%symmetry%kind /= symmetry_none, &
                    '&symmetry (give the whole model)')
        call refuse(model%solver%matrix == matrix_hierarchical, &
                    "&solver matrix = 'hierarchical' (coupled flow takes dense matrices)")
        call refuse(any(model%elements%shear_stiffness < rigid_joint .or. &
                        model%elements%normal_stiffness < rigid_joint), &
                    'elastic joints (shear_stiffness, normal_stiffness)')

    contains

        subroutine refuse(condition, what)
            logical, intent(in) :: condition
            character(len=*), intent(in) :: what

            if (condition) call add(messages, prefix//'coupled flow does not combine with '// &
                                    what)
        end subroutine refuse
    end subroutine check_fluid_model

end module ddc_input_namelist_injection
