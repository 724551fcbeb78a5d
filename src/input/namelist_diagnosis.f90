!> What is wrong with a namelist group that gfortran could not read: our own reading of the
!> group's text against its variables in the table (ddc_input_namelist_groups) finds an
!> unknown variable, a value of the wrong type, a quote left open (the quoted text runs into
!> the next variable) or a decimal comma (50000,5: gfortran takes the 5 for a name) and
!> names it, with gfortran's iomsg.
module ddc_input_namelist_diagnosis
    use ddc_kinds, only: wp
    use ddc_text, only: newline, lower, find_name
    use ddc_input_namelist_groups, only: namelist_groups, group_record, message_list, add, &
        scan_groups, group_prefix, is_name_character
    implicit none
    private

    public :: report_malformed, group_problem

contains

    !> The message for a failed namelist read of the first occurrence of the known group
    !> `name` (present in text), naming the unknown variable or the bad value when found.
    function group_problem(text, path, name, stat, iomsg) result(message)
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Name of the group, without '&'
        character(len=*), intent(in) :: name
        !> iostat and iomsg of the failed read
        integer, intent(in) :: stat
        character(len=*), intent(in) :: iomsg
        !> The message, one line
        character(len=:), allocatable :: message
        type(group_record) :: groups(size(namelist_groups))
        type(message_list) :: ignored
        integer :: nobs, g

        g = find_name(name, namelist_groups%name)
        call scan_groups(text, path, groups, nobs, ignored)
        message = malformed_message(group_prefix(path, g, groups(g), 1), stat, iomsg, &
                                    trim(namelist_groups(g)%variables), &
                                    text(groups(g)%starts(1):groups(g)%ends(1)))
    end function group_problem

    !> Report occurrence k of a group that could not be read; for a repeatable group also
    !> diagnose the occurrences after it, which are then not read.
    subroutine report_malformed(text, path, group, info, k, stat, iomsg, messages)
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Index of the group in namelist_groups, and the occurrence that failed
        integer, intent(in) :: group, k
        !> Where the group occurs (scan_groups)
        type(group_record), intent(in) :: info
        !> iostat and iomsg of the failed read
        integer, intent(in) :: stat
        character(len=*), intent(in) :: iomsg
        !> The diagnosis is added here
        type(message_list), intent(inout) :: messages
        character(len=:), allocatable :: spec

        spec = trim(namelist_groups(group)%variables)
        call add(messages, malformed_message(group_prefix(path, group, info, k), stat, iomsg, &
                 spec, text(info%starts(k):info%ends(k))))
        if (namelist_groups(group)%repeatable) then
            call diagnose_rest(text, path, group, info, spec, k + 1, messages)
        end if
    end subroutine report_malformed

    !> Message for a group that exists but could not be read: our own diagnosis of the
    !> group text (unknown variable, value of the wrong type, open quote, decimal comma),
    !> with gfortran's iomsg unless the diagnosis is an unknown variable.
    function malformed_message(prefix, stat, iomsg, spec, group_text) result(message)
        !> "file: &group k (line n): "
        character(len=*), intent(in) :: prefix
        !> iostat and iomsg of the failed read
        integer, intent(in) :: stat
        character(len=*), intent(in) :: iomsg
        !> Variables of the group with their types: "name:c x:r n:i"
        character(len=*), intent(in) :: spec
        !> Text of the group, from '&' to '/'
        character(len=*), intent(in) :: group_text
        character(len=:), allocatable :: message, problem

        problem = diagnose_group(group_text, spec)
        if (len(problem) == 0 .and. is_overflow(iomsg)) problem = decimal_comma(group_text, iomsg)
        if (index(problem, 'unknown variable') == 1) then
            ! gfortran names the object it was reading before the unknown name: not said.
            message = prefix//problem//'; the variables of this group are: '//spec_names(spec)
            return
        else if (len(problem) > 0) then
            message = prefix//problem//' (gfortran: '//trim(iomsg)//')'
            return
        end if
        message = prefix//'cannot be read (gfortran: '//trim(iomsg)//'): '
        if (is_overflow(iomsg)) then
            ! gfortran takes the values beyond an array's end for variable names.
            message = message//'more values than an array of this group holds (the limits '// &
                'are in docs/input-reference.md#size-limits)'
        else if (stat < 0) then
            message = message//'a value of the wrong type, or a group not closed by /'
        else
            message = message//'a misspelled variable, a value of the wrong type or a '// &
                      'missing quote'
        end if
        message = message//'; the variables of this group are: '//spec_names(spec)
    end function malformed_message

    !> True when gfortran met a number where it expected a variable name: values beyond
    !> the end of an array.
    pure function is_overflow(iomsg) result(overflow)
        character(len=*), intent(in) :: iomsg
        logical :: overflow
        character(len=*), parameter :: mark = 'Cannot match namelist object name '
        integer :: at

        overflow = .false.
        at = index(iomsg, mark)
        if (at == 0 .or. at + len(mark) > len_trim(iomsg)) return
        overflow = scan(iomsg(at + len(mark):at + len(mark)), '0123456789+-.') == 1
    end function is_overflow

    !> 'youngs_modulus = 50000,5 has a decimal comma: write 50000.5 ...' when the value
    !> gfortran took for a name (is_overflow) is the digits after a comma inside a number
    !> given to a variable; '' otherwise (values beyond an array's end).
    function decimal_comma(group_text, iomsg) result(problem)
        character(len=*), intent(in) :: group_text, iomsg
        character(len=:), allocatable :: problem, digits
        character(len=*), parameter :: mark = 'Cannot match namelist object name '
        character(len=*), parameter :: number = '0123456789.+-eEdD'
        character(len=*), parameter :: blank = ' '//achar(9)//achar(10)//achar(13)
        integer :: at, comma, first, last, equals, name_start

        problem = ''
        at = index(iomsg, mark) + len(mark)
        digits = trim(iomsg(at:))
        if (verify(digits, '0123456789') /= 0) return
        comma = index(group_text, ','//digits)
        do while (comma > 1)
            last = comma + len(digits)
            first = comma
            do while (first > 1)
                if (index(number, group_text(first - 1:first - 1)) == 0) exit
                first = first - 1
            end do
            equals = first - 1
            do while (equals > 1)
                if (index(blank, group_text(equals:equals)) == 0) exit
                equals = equals - 1
            end do
            if (first < comma .and. is_separated(last + 1) .and. group_text(equals:equals) == '=') &
                then
                name_start = equals - 1
                do while (name_start > 1)
                    if (index(blank, group_text(name_start:name_start)) == 0) exit
                    name_start = name_start - 1
                end do
                do while (name_start > 1)
                    if (.not. is_name_character(group_text(name_start - 1:name_start - 1))) exit
                    name_start = name_start - 1
                end do
                problem = trim(group_text(name_start:equals - 1))//' = '// &
                    group_text(first:last)//' has a decimal comma: write '// &
                    group_text(first:comma - 1)//'.'//digits//' (a comma separates values)'
                return
            end if
            at = index(group_text(comma + 1:), ','//digits)
            if (at == 0) exit
            comma = comma + at
        end do

    contains

        !> Position k ends the digits: a blank, separator, the group's end or its text's.
        pure logical function is_separated(k)
            integer, intent(in) :: k

            is_separated = k > len(group_text)
            if (.not. is_separated) is_separated = index(blank//',/!', group_text(k:k)) > 0
        end function is_separated

    end function decimal_comma

    !> After a failed read (the file position is then unreliable), diagnose the text of
    !> the remaining occurrences of a repeated group without reading them.
    subroutine diagnose_rest(text, path, group, info, spec, first, messages)
        character(len=*), intent(in) :: text, path, spec
        integer, intent(in) :: group, first
        type(group_record), intent(in) :: info
        type(message_list), intent(inout) :: messages
        character(len=:), allocatable :: problem
        integer :: k

        do k = first, info%count
            problem = diagnose_group(text(info%starts(k):info%ends(k)), spec)
            if (len(problem) > 0) then
                call add(messages, group_prefix(path, group, info, k)//problem)
            end if
        end do
    end subroutine diagnose_rest

    !> Find the first unknown variable or value of the wrong type in the text of a group
    !> ("&name var = value, ... /"); return '' when nothing is found.
    function diagnose_group(group_text, spec) result(problem)
        character(len=*), intent(in) :: group_text, spec
        character(len=:), allocatable :: problem
        character(len=*), parameter :: blanks = ' '//achar(9)//achar(10)//achar(13)//','
        character(len=*), parameter :: stops = blanks//"/!='"//'"('
        character(len=:), allocatable :: token, current, value
        character(len=1) :: kind, c, quote
        integer :: i, j, k, n, star, stat, int_value
        real(wp) :: real_value
        logical :: quoted

        problem = ''
        current = ''
        kind = ' '
        n = len(group_text)
        i = 2
        do while (i <= n)
            if (.not. is_name_character(group_text(i:i))) exit
            i = i + 1
        end do
        do
            ! skip blanks, separators and comments
            do while (i <= n)
                c = group_text(i:i)
                if (c == '!') then
                    j = index(group_text(i:), newline)
                    if (j == 0) then
                        i = n + 1
                    else
                        i = i + j
                    end if
                else if (index(blanks, c) > 0) then
                    i = i + 1
                else
                    exit
                end if
            end do
            if (i > n) return
            c = group_text(i:i)
            if (c == '/' .or. c == '&') return
            if (c == '=') then
                i = i + 1
                cycle
            end if
            quoted = c == "'" .or. c == '"'
            if (quoted) then
                quote = c
                j = i + 1
                do while (j <= n)
                    if (group_text(j:j) == quote) then
                        if (j < n) then
                            if (group_text(j + 1:j + 1) == quote) then
                                j = j + 2
                                cycle
                            end if
                        end if
                        exit
                    end if
                    j = j + 1
                end do
                token = group_text(i:min(j, n))
                i = j + 1
                problem = open_quote(token, j > n, current, spec)
                if (len(problem) > 0) return
            else
                j = i
                do while (j <= n)
                    if (index(stops, group_text(j:j)) > 0) exit
                    j = j + 1
                end do
                if (j == i) then
                    ! a lone '(' or similar: skip it
                    i = i + 1
                    cycle
                end if
                token = group_text(i:j - 1)
                i = j
                ! a name: an identifier, an optional subscript, then '='
                if (is_identifier(token)) then
                    k = i
                    if (k <= n) then
                        if (group_text(k:k) == '(') then
                            j = index(group_text(k:), ')')
                            if (j > 0) k = k + j
                        end if
                    end if
                    do while (k <= n)
                        if (index(' '//achar(9)//achar(10)//achar(13), group_text(k:k)) == 0) exit
                        k = k + 1
                    end do
                    if (k <= n) then
                        if (group_text(k:k) == '=') then
                            current = lower(token)
                            kind = spec_type(spec, current)
                            if (kind == ' ') then
                                problem = "unknown variable '"//token//"'"
                                return
                            end if
                            i = k + 1
                            cycle
                        end if
                    end if
                end if
            end if
            ! a value of the current variable
            if (len(current) == 0) then
                problem = "'"//token//"' is not a variable name"
                return
            end if
            value = token
            if (.not. quoted) then
                star = index(value, '*')
                if (star > 0) then
                    if (verify(value(1:star - 1), '0123456789') == 0) value = value(star + 1:)
                end if
                if (len(value) == 0) cycle
            end if
            select case (kind)
            case ('c')
                if (.not. quoted) then
                    problem = current//' = '//token//" needs quotes: "//current//" = '"// &
                              token//"'"
                    return
                end if
            case ('r')
                stat = 1
                if (.not. quoted) read (value, *, iostat=stat) real_value
                if (stat /= 0) then
                    problem = current//' = '//token//' is not a number'
                    return
                end if
            case ('i')
                stat = 1
                if (.not. quoted) read (value, *, iostat=stat) int_value
                if (stat /= 0) then
                    problem = current//' = '//token//' is not an integer'
                    return
                end if
            case default
                ! spec_type gives only 'c', 'r' or 'i' for a known variable
            end select
        end do
    end function diagnose_group

    !> A quoted value of variable `current` that is not closed: at the group's end
    !> (unclosed), or where the quoted text runs into a variable of the group (name = 'fault,
    !> x = ...: the quote after fault is missing, so the text runs on to the next quote); ''
    !> otherwise.
    function open_quote(token, unclosed, current, spec) result(problem)
        !> The quoted value, from its opening quote
        character(len=*), intent(in) :: token
        !> No closing quote before the group's end
        logical, intent(in) :: unclosed
        !> The variable it is given to, and the variables of the group ("name:c x:r")
        character(len=*), intent(in) :: current, spec
        character(len=:), allocatable :: problem
        integer :: at, name_end, name_start, next

        problem = ''
        at = index(token, '=')
        do while (at > 0)
            name_end = at - 1
            do while (name_end > 1)
                if (token(name_end:name_end) /= ' ') exit
                name_end = name_end - 1
            end do
            name_start = name_end
            do while (name_start > 2)
                if (.not. is_name_character(token(name_start - 1:name_start - 1))) exit
                name_start = name_start - 1
            end do
            if (name_start > 1 .and. is_identifier(token(name_start:name_end))) then
                if (spec_type(spec, lower(token(name_start:name_end))) /= ' ') then
                    problem = current//' = '//token(1:name_start - 1)//'...: a quote is '// &
                        'not closed: the quoted text runs into '//token(name_start:name_end)// &
                        ' = (close the quote)'
                    return
                end if
            end if
            next = index(token(at + 1:), '=')
            if (next == 0) exit
            at = at + next
        end do
        if (unclosed) problem = current//' = '//token(1:min(len(token), 24))//'...: a '// &
            'quote is not closed before the end of the group (close the quote)'
    end function open_quote

    !> "name, x, n" from the spec "name:c x:r n:i".
    function spec_names(spec) result(names)
        character(len=*), intent(in) :: spec
        character(len=:), allocatable :: names
        integer :: i

        names = ''
        do i = 1, len(spec)
            if (spec(i:i) == ':') cycle
            if (i > 1) then
                if (spec(i - 1:i - 1) == ':') cycle
            end if
            if (spec(i:i) == ' ') then
                names = names//', '
            else
                names = names//spec(i:i)
            end if
        end do
    end function spec_names

    !> Type letter of a variable in the spec ('c', 'r', 'i'), ' ' when it is not there.
    function spec_type(spec, name) result(kind)
        character(len=*), intent(in) :: spec, name
        character(len=1) :: kind
        integer :: at

        kind = ' '
        at = index(' '//spec//' ', ' '//name//':')
        if (at > 0) kind = spec(at + len(name) + 1:at + len(name) + 1)
    end function spec_type

    !> True for a Fortran name: a letter, then letters, digits or underscores.
    pure function is_identifier(token) result(yes)
        character(len=*), intent(in) :: token
        logical :: yes
        integer :: i

        yes = .false.
        if (len(token) == 0) return
        if (.not. ((token(1:1) >= 'a' .and. token(1:1) <= 'z') .or. &
                   (token(1:1) >= 'A' .and. token(1:1) <= 'Z'))) return
        do i = 2, len(token)
            if (.not. is_name_character(token(i:i))) return
        end do
        yes = .true.
    end function is_identifier

end module ddc_input_namelist_diagnosis
