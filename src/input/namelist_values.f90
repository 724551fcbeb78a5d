!> Checks of the values read from a namelist group, each adding one line per violation to
!> the messages: values the user did not give (the unset sentinels the readers set before
!> every read), NaN and Inf, physical ranges (ddc_model_limits), array lengths and gaps; and
!> the per-segment arrays broadcast to every segment.
module ddc_input_namelist_values
    use ddc_kinds, only: wp
    use ddc_text, only: itoa, rtoa, counted
    use ddc_model_limits, only: within_limits, limits_text, range_problem, quantity_any
    use ddc_input_namelist_groups, only: message_list, add
    implicit none
    private

    public :: unset_real, unset_integer, text_length
    public :: check_scalar, count_given, count_given_integers, check_length, check_range
    public :: broadcast, broadcast_integers, default_name

    !> Sentinels of values the user did not give
    real(wp), parameter :: unset_real = huge(1.0_wp)
    integer, parameter :: unset_integer = -huge(1)

    !> Length of character variables in the groups
    integer, parameter :: text_length = 1024

contains

    !> Check a scalar real: a missing required value, NaN, Inf, a magnitude beyond the limits
    !> or a value outside its quantity's range is an error. Return true when the value is
    !> given and within its limits (the caller may keep it even when outside its range, so
    !> that later checks see it).
    function check_scalar(value, name, required, prefix, messages, quantity) result(ok)
        !> The value read
        real(wp), intent(in) :: value
        !> Name of the variable, and "file: &group (line n): "
        character(len=*), intent(in) :: name, prefix
        !> The value must be given
        logical, intent(in) :: required
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        !> Physical range of the value (ddc_model_limits; default quantity_any)
        integer, intent(in), optional :: quantity
        logical :: ok
        character(len=:), allocatable :: problem

        ok = .false.
        if (value == unset_real) then
            if (required) call add(messages, prefix//name//' is required')
            return
        end if
        ok = within_limits(value)
        problem = range_problem(quantity_any, value)
        if (present(quantity)) problem = range_problem(quantity, value)
        if (len(problem) > 0) call add(messages, prefix//name//' = '//rtoa(value)//' '//problem)
    end function check_scalar

    !> Number of leading given entries of a namelist array; a given entry after an unset
    !> one, and NaN or Inf, are errors.
    function count_given(values, name, prefix, messages) result(n)
        real(wp), intent(in) :: values(:)
        character(len=*), intent(in) :: name, prefix
        type(message_list), intent(inout) :: messages
        integer :: n
        integer :: i

        n = leading_given(values /= unset_real, name, prefix, messages)
        do i = 1, n
            if (.not. within_limits(values(i))) then
                call add(messages, prefix//name//'('//itoa(i)//') = '//rtoa(values(i))// &
                         limits_text)
                exit
            end if
        end do
    end function count_given

    !> Number of leading given entries of an integer namelist array; gaps are errors.
    function count_given_integers(values, name, prefix, messages) result(n)
        integer, intent(in) :: values(:)
        character(len=*), intent(in) :: name, prefix
        type(message_list), intent(inout) :: messages
        integer :: n

        n = leading_given(values /= unset_integer, name, prefix, messages)
    end function count_given_integers

    !> Number of leading given entries of a namelist array (given(i): entry i is set); a
    !> given entry after an unset one is an error.
    function leading_given(given, name, prefix, messages) result(n)
        logical, intent(in) :: given(:)
        character(len=*), intent(in) :: name, prefix
        type(message_list), intent(inout) :: messages
        integer :: n
        integer :: i

        n = 0
        do while (n < size(given))
            if (.not. given(n + 1)) exit
            n = n + 1
        end do
        do i = n + 2, size(given)
            if (given(i)) then
                call add(messages, prefix//name//'('//itoa(i)//') is given but '//name// &
                         '('//itoa(n + 1)//') is not; give the values without gaps')
                exit
            end if
        end do
    end function leading_given

    !> A per-segment array must have 1 value (for every segment) or one per segment.
    !> Return true when its length fits (an absent array fits: its default applies).
    function check_length(n, nseg, name, prefix, messages) result(ok)
        integer, intent(in) :: n, nseg
        character(len=*), intent(in) :: name, prefix
        type(message_list), intent(inout) :: messages
        logical :: ok

        ok = n == 0 .or. n == 1 .or. n == nseg
        if (.not. ok) then
            call add(messages, prefix//name//' has '//counted(n, 'value', 'values')// &
                     '; give 1 (for every segment) or '//itoa(nseg)//' (one per segment)')
        end if
    end function check_length

    !> Every value within the limits must lie in its quantity's range (the first violation
    !> is reported; values beyond the limits are count_given's).
    subroutine check_range(values, name, quantity, prefix, messages)
        !> The values given
        real(wp), intent(in) :: values(:)
        !> Name of the variable, and "file: &group (line n): "
        character(len=*), intent(in) :: name, prefix
        !> Physical range of the values (ddc_model_limits)
        integer, intent(in) :: quantity
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        integer :: i

        do i = 1, size(values)
            if (.not. within_limits(values(i))) cycle
            if (len(range_problem(quantity, values(i))) > 0) then
                call add(messages, prefix//name//'('//itoa(i)//') = '//rtoa(values(i))//' '// &
                         range_problem(quantity, values(i)))
                exit
            end if
        end do
    end subroutine check_range

    !> Per-segment values from 1 or nseg given values (or the default when none given).
    pure function broadcast(values, nseg, default) result(out)
        real(wp), intent(in) :: values(:)
        integer, intent(in) :: nseg
        real(wp), intent(in) :: default
        real(wp) :: out(nseg)

        if (size(values) == 0) then
            out = default
        else if (size(values) == 1) then
            out = values(1)
        else
            out = values(1:nseg)
        end if
    end function broadcast

    !> Per-segment counts from 1 or nseg given values.
    pure function broadcast_integers(values, nseg) result(out)
        integer, intent(in) :: values(:)
        integer, intent(in) :: nseg
        integer :: out(nseg)

        if (size(values) == 1) then
            out = values(1)
        else
            out = values(1:nseg)
        end if
    end function broadcast_integers

    !> The given name, or <kind>_<ordinal>.
    function default_name(name, kind, ordinal) result(out)
        character(len=*), intent(in) :: name, kind
        integer, intent(in) :: ordinal
        character(len=:), allocatable :: out

        if (len_trim(name) > 0) then
            out = trim(adjustl(name))
        else
            out = kind//'_'//itoa(ordinal)
        end if
    end function default_name

end module ddc_input_namelist_values
