!> The &growth group of a namelist input file (docs/fracture-growth.md#the-input): fracture growth
!> under the model's loading (fixed, or along its &load_path:
!> docs/theory/growth.md#growth-along-a-loading-history). Sets the defaults, reads the group if
!> present and checks every value; growth does not combine with &symmetry (every task of a &sweep
!> grows).
module ddc_input_namelist_growth
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, growth_options, growth_tips_names, &
        growth_criterion_names, symmetry_none, strength_law_count, work_mode_names, &
        angle_search_names
    use ddc_model_laws, only: strength_law, strength_laws, new_law_bound, at_most_rule
    use ddc_model_limits, only: quantity_positive, quantity_non_negative, within_limits, &
        limits_text
    use ddc_text, only: itoa, rtoa, lower, find_name, quoted_list
    use ddc_input_namelist_groups, only: group_record, message_list, add, group_prefix, &
        g_growth, g_symmetry
    use ddc_input_namelist_diagnosis, only: report_malformed
    use ddc_input_namelist_values, only: unset_real, unset_integer, text_length, check_scalar
    use ddc_input_namelist_fracture, only: fracture_input
    implicit none
    private

    public :: read_growth_group

    !> Largest number of growth steps, and of corrector solves per step
    integer, parameter :: max_growth_steps = 100000, max_corrector_solves = 100
    !> Largest number of names in `fractures`, and the length of each
    integer, parameter :: max_listed = 10000, name_length = 256

contains

    !> &growth steps, toughness, increment, element_length, tips, fractures, criterion,
    !> max_corrections, new_mu, new_sf, angle_range, angle_step, work_threshold, work_mode,
    !> angle_search, the strength
    !> laws of new elements (new_<name> of each law of ddc_model_laws) / (optional). Read
    !> after every other group: the fracture names and the other groups are checked
    !> against it.
    subroutine read_growth_group(unit, text, path, groups, known, model, messages)
        !> Unit of the open input file
        integer, intent(in) :: unit
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Where every group occurs (scan_groups), shape (size(namelist_groups))
        type(group_record), intent(in) :: groups(:)
        !> The fractures as read, for the names in `fractures`
        type(fracture_input), intent(in) :: known(:)
        !> model%growth is set; its symmetry must be read already
        type(model_type), intent(inout) :: model
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        integer :: steps, max_corrections
        real(wp) :: toughness, increment, element_length, new_mu, new_sf
        real(wp) :: angle_range, angle_step, work_threshold
        real(wp) :: new_tensile_strength, new_sf_residual, new_mu_dynamic, &
            new_slip_weakening_distance, new_opening_weakening_distance, new_shear_stiffness, &
            new_normal_stiffness
        character(len=text_length) :: tips, criterion, work_mode, angle_search
        character(len=name_length), allocatable :: fractures(:)
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, k
        namelist /growth/ steps, toughness, increment, element_length, tips, fractures, &
            criterion, max_corrections, new_mu, new_sf, angle_range, angle_step, &
            work_threshold, work_mode, angle_search, new_tensile_strength, new_sf_residual, &
            new_mu_dynamic, new_slip_weakening_distance, new_opening_weakening_distance, &
            new_shear_stiffness, &
            new_normal_stiffness

        associate (info => groups(g_growth))
            if (info%count == 0) return
            allocate (fractures(max_listed))
            steps = unset_integer
            toughness = unset_real
            increment = unset_real
            element_length = unset_real
            tips = 'all'
            fractures = ''
            criterion = 'mts'
            max_corrections = 8
            new_mu = unset_real
            new_sf = unset_real
            angle_range = 90.0_wp
            angle_step = 5.0_wp
            work_threshold = unset_real
            work_mode = 'any'
            angle_search = 'seeded'
            new_tensile_strength = unset_real
            new_sf_residual = unset_real
            new_mu_dynamic = unset_real
            new_slip_weakening_distance = unset_real
            new_opening_weakening_distance = unset_real
            new_shear_stiffness = unset_real
            new_normal_stiffness = unset_real
            rewind (unit)
            read (unit, nml=growth, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_growth, info, 1, stat, iomsg, messages)
                return
            end if
            prefix = group_prefix(path, g_growth, info, 1)
        end associate
        call check_combinations(prefix, groups, model, messages)

        associate (g => model%growth)
            g%active = .true.
            if (steps == unset_integer) then
                call add(messages, prefix//'steps is required: the largest number of '// &
                         'growth steps (>= 1)')
            else if (steps < 1 .or. steps > max_growth_steps) then
                call add(messages, prefix//'steps = '//itoa(steps)//' must lie in 1 .. '// &
                         itoa(max_growth_steps))
            else
                g%steps = steps
            end if
            if (check_scalar(toughness, 'toughness', .true., prefix, messages, &
                             quantity_positive)) g%toughness = toughness
            if (check_scalar(increment, 'increment', .false., prefix, messages, &
                             quantity_positive)) g%increment = increment
            if (check_scalar(element_length, 'element_length', .false., prefix, messages, &
                             quantity_positive)) g%element_length = element_length
            g%override_mu = check_scalar(new_mu, 'new_mu', .false., prefix, messages, &
                                         quantity_non_negative)
            if (g%override_mu) g%new_mu = new_mu
            g%override_sf = check_scalar(new_sf, 'new_sf', .false., prefix, messages, &
                                         quantity_non_negative)
            if (g%override_sf) g%new_sf = new_sf
            ! In the order of the list of the laws (the CTest architecture holds it to that)
            call check_new_laws([new_tensile_strength, new_sf_residual, new_mu_dynamic, &
                                 new_slip_weakening_distance, new_opening_weakening_distance, &
                                 new_shear_stiffness, new_normal_stiffness], prefix, g, messages)
            k = choice('tips', tips, growth_tips_names)
            if (k > 0) g%tips = k
            k = choice('criterion', criterion, growth_criterion_names)
            if (k > 0) g%criterion = k
            k = choice('work_mode', work_mode, work_mode_names)
            if (k > 0) g%work_mode = k
            k = choice('angle_search', angle_search, angle_search_names)
            if (k > 0) g%angle_search = k
            if (max_corrections < 0 .or. max_corrections > max_corrector_solves) then
                call add(messages, prefix//'max_corrections = '//itoa(max_corrections)// &
                         ' must lie in 0 .. '//itoa(max_corrector_solves)// &
                         ' (0 switches the local-symmetry corrector off)')
            else
                g%max_corrections = max_corrections
            end if
        end associate
        call check_work_search(prefix, angle_range, angle_step, work_threshold, model, &
                               messages)
        call select_fractures(fractures, known, prefix, model%growth%fracture_grows, messages)

    contains

        !> The index of a choice's value among its names (any case), or 0 with a message.
        integer function choice(name, value, names) result(k)
            character(len=*), intent(in) :: name, value
            character(len=*), intent(in) :: names(:)

            k = find_name(lower(trim(adjustl(value))), names)
            if (k == 0) call add(messages, prefix//name//" = '"//trim(adjustl(value))// &
                                 "' is not one of "//quoted_list(names))
        end function choice
    end subroutine read_growth_group

    !> The trial angles and threshold of criterion = 'work': 0 < angle_range < 180,
    !> angle_step > 0, work_threshold > 0 when given (0 in the options: the default from
    !> the toughness).
    subroutine check_work_search(prefix, angle_range, angle_step, work_threshold, model, &
                                 messages)
        character(len=*), intent(in) :: prefix
        real(wp), intent(in) :: angle_range, angle_step, work_threshold
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages

        ! NaN and Inf first: an ordered comparison with NaN traps where invalid operations do.
        if (.not. within_limits(angle_range)) then
            call add(messages, prefix//'angle_range = '//rtoa(angle_range)//limits_text)
        else if (.not. (angle_range > 0.0_wp .and. angle_range < 180.0_wp)) then
            call add(messages, prefix//'angle_range = '//rtoa(angle_range)// &
                     ' must lie in (0, 180) degrees')
        else
            model%growth%angle_range = angle_range
        end if
        if (.not. within_limits(angle_step)) then
            call add(messages, prefix//'angle_step = '//rtoa(angle_step)//limits_text)
        else if (.not. (angle_step > 0.0_wp)) then
            call add(messages, prefix//'angle_step = '//rtoa(angle_step)// &
                     ' must be positive [degree]')
        else
            model%growth%angle_step = angle_step
        end if
        if (check_scalar(work_threshold, 'work_threshold', .false., prefix, messages, &
                         quantity_positive)) model%growth%work_threshold = work_threshold
    end subroutine check_work_search

    !> The strength laws of new contact elements, in the order of the list (ddc_model_laws):
    !> each one given is kept (within its range), and a value after slip may not exceed the
    !> strength it falls from (new_sf, new_mu) when both are given.
    subroutine check_new_laws(values, prefix, g, messages)
        !> The values read (unset_real: not given), shape (strength_law_count)
        real(wp), intent(in) :: values(:)
        !> "file: &growth (line n): "
        character(len=*), intent(in) :: prefix
        !> override_law and new_law are set; override_mu, override_sf are read
        type(growth_options), intent(inout) :: g
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        type(strength_law) :: laws(strength_law_count)
        real(wp) :: bound
        logical :: bounded
        integer :: k

        laws = strength_laws()
        do k = 1, size(laws)
            g%override_law(k) = check_scalar(values(k), 'new_'//laws(k)%name, .false., &
                                             prefix, messages, laws(k)%quantity)
            if (g%override_law(k)) g%new_law(k) = values(k)
        end do
        do k = 1, size(laws)
            call new_law_bound(g, laws(k), bounded, bound)
            if (g%override_law(k) .and. bounded) then
                if (g%new_law(k) > bound) call add(messages, prefix//'new_'//laws(k)%name// &
                    ' = '//rtoa(g%new_law(k))//' exceeds new_'//laws(k)%at_most//' = '// &
                    rtoa(bound)//' ('//at_most_rule(laws(k))//')')
            end if
        end do

    end subroutine check_new_laws

    !> Growth with implicit image elements is not available.
    subroutine check_combinations(prefix, groups, model, messages)
        character(len=*), intent(in) :: prefix
        type(group_record), intent(in) :: groups(:)
        type(model_type), intent(in) :: model
        type(message_list), intent(inout) :: messages

        if (model%elements%symmetry%kind /= symmetry_none) then
            call add(messages, prefix//'cannot be combined with &symmetry (line '// &
                     itoa(groups(g_symmetry)%lines(1))//'): model the whole body, without '// &
                     'implicit image elements')
        end if
    end subroutine check_combinations

    !> Which fractures may grow: those named in `fractures` (each a known fracture, named
    !> once), or every fracture when none is named.
    subroutine select_fractures(names, known, prefix, grows, messages)
        !> The names given (blank: not given)
        character(len=*), intent(in) :: names(:)
        !> The fractures of the model
        type(fracture_input), intent(in) :: known(:)
        !> "file: &growth (line n): "
        character(len=*), intent(in) :: prefix
        !> Whether each fracture may grow, shape (size(known))
        logical, allocatable, intent(out) :: grows(:)
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        integer :: n, i, j, f

        allocate (grows(size(known)))
        n = 0
        do while (n < size(names))
            if (len_trim(names(n + 1)) == 0) exit
            n = n + 1
        end do
        if (n == 0) then
            grows = .true.
            return
        end if
        grows = .false.
        do i = n + 2, size(names)
            if (len_trim(names(i)) > 0) then
                call add(messages, prefix//'fractures('//itoa(i)//') is given but fractures('// &
                         itoa(n + 1)//') is not; give the names without gaps')
                exit
            end if
        end do
        do i = 1, n
            f = 0
            do j = 1, size(known)
                if (.not. allocated(known(j)%name)) cycle
                if (known(j)%name == trim(adjustl(names(i)))) f = j
            end do
            if (f == 0) then
                call add(messages, prefix//"fractures("//itoa(i)//") = '"// &
                         trim(adjustl(names(i)))//"' is not the name of a &fracture")
            else if (grows(f)) then
                call add(messages, prefix//"fractures("//itoa(i)//") = '"// &
                         trim(adjustl(names(i)))//"' is named twice")
            else
                grows(f) = .true.
            end if
        end do
    end subroutine select_fractures

end module ddc_input_namelist_growth
