!> The &initiation group of a namelist input file
!> (docs/fracture-growth.md#new-fractures-inside-the-rock): new fractures inside the rock
!> of a growth run, tails beside contact elements and cracks at flaw points, where the
!> maximum tension reaches the rock's tensile strength. Sets the defaults, reads the group
!> if present and checks every value; it needs &growth.
module ddc_input_namelist_initiation
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type
    use ddc_model_limits, only: quantity_positive
    use ddc_text, only: itoa, rtoa
    use ddc_input_namelist_groups, only: group_record, message_list, add, group_prefix, &
        g_initiation, g_growth
    use ddc_input_namelist_diagnosis, only: report_malformed
    use ddc_input_namelist_values, only: unset_real, check_scalar, count_given
    implicit none
    private

    public :: read_initiation_group, check_flaw_points

    !> Largest number of flaw points
    integer, parameter :: max_flaws = 10000

contains

    !> &initiation tensile_strength, probe_distance, flaw_x, flaw_y, flaw_length / (optional).
    !> Read after &growth, which it needs.
    subroutine read_initiation_group(unit, text, path, groups, model, messages)
        !> Unit of the open input file
        integer, intent(in) :: unit
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Where every group occurs (scan_groups), shape (size(namelist_groups))
        type(group_record), intent(in) :: groups(:)
        !> model%initiation is set
        type(model_type), intent(inout) :: model
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        real(wp) :: tensile_strength, probe_distance, flaw_length
        real(wp), allocatable :: flaw_x(:), flaw_y(:)
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, nx, ny
        namelist /initiation/ tensile_strength, probe_distance, flaw_x, flaw_y, flaw_length

        associate (info => groups(g_initiation))
            if (info%count == 0) return
            allocate (flaw_x(max_flaws), flaw_y(max_flaws))
            tensile_strength = unset_real
            probe_distance = unset_real
            flaw_length = unset_real
            flaw_x = unset_real
            flaw_y = unset_real
            rewind (unit)
            read (unit, nml=initiation, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_initiation, info, 1, stat, iomsg, messages)
                return
            end if
            prefix = group_prefix(path, g_initiation, info, 1)
        end associate
        if (groups(g_growth)%count == 0 .and. .not. groups(g_growth)%misspelled) then
            call add(messages, prefix//'needs &growth: new fractures grow as fractures do')
        end if
        associate (o => model%initiation)
            o%active = .true.
            if (check_scalar(tensile_strength, 'tensile_strength', .true., prefix, messages, &
                             quantity_positive)) o%tensile_strength = tensile_strength
            if (check_scalar(probe_distance, 'probe_distance', .true., prefix, messages, &
                             quantity_positive)) o%probe_distance = probe_distance
            if (check_scalar(flaw_length, 'flaw_length', .false., prefix, messages, &
                             quantity_positive)) o%flaw_length = flaw_length
            nx = count_given(flaw_x, 'flaw_x', prefix, messages)
            ny = count_given(flaw_y, 'flaw_y', prefix, messages)
            if (nx /= ny) then
                call add(messages, prefix//'flaw_x gives '//itoa(nx)//' values and flaw_y '// &
                         itoa(ny)//': give one of each per flaw point')
            end if
            o%flaw_x = flaw_x(:min(nx, ny))
            o%flaw_y = flaw_y(:min(nx, ny))
            if (min(nx, ny) > 0 .and. o%flaw_length <= 0.0_wp .and. &
                model%growth%increment <= 0.0_wp) then
                call add(messages, prefix//'flaw_length is required when &growth gives no '// &
                         'increment (its default)')
            end if
        end associate
    end subroutine read_initiation_group

    !> Every flaw point must lie off the elements (a flaw on an element has no field of its
    !> own: it would start a tail there, not a new fracture).
    subroutine check_flaw_points(path, groups, model, messages)
        !> Path of the input file
        character(len=*), intent(in) :: path
        !> Where every group occurs (scan_groups)
        type(group_record), intent(in) :: groups(:)
        !> The model, its elements' geometry computed
        type(model_type), intent(in) :: model
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        integer :: i, j

        if (.not. model%initiation%active) return
        associate (o => model%initiation, e => model%elements)
            do i = 1, size(o%flaw_x)
                do j = 1, e%n
                    if (on_element(o%flaw_x(i) - e%x_mid(j), o%flaw_y(i) - e%y_mid(j), &
                                   e%half_length(j), e%cos_beta(j), e%sin_beta(j))) then
                        call add(messages, group_prefix(path, g_initiation, &
                                                        groups(g_initiation), 1)// &
                                 'flaw_x('//itoa(i)//'), flaw_y('//itoa(i)//') = '// &
                                 rtoa(o%flaw_x(i))//', '//rtoa(o%flaw_y(i))//' lies on '// &
                                 'element '//itoa(j)//': put flaw points off the fractures')
                        exit
                    end if
                end do
            end do
        end associate
    end subroutine check_flaw_points

    !> Whether the point (dx, dy) from an element's midpoint lies on it (its ends included),
    !> within round-off of its length.
    pure logical function on_element(dx, dy, a, cosb, sinb)
        real(wp), intent(in) :: dx, dy, a, cosb, sinb
        real(wp), parameter :: round_off = 1.0e-10_wp

        on_element = abs(-sinb * dx + cosb * dy) <= round_off * a .and. &
                     abs(cosb * dx + sinb * dy) <= a * (1.0_wp + round_off)
    end function on_element

end module ddc_input_namelist_initiation
