!> What differs between two namelist inputs, named by group and variable: the message of a
!> refused --resume says what changed rather than only that the fingerprints differ.
!>
!> The texts are compared as written (comments dropped, blanks collapsed, names in lower
!> case), the k-th group of a name with the k-th of that name in the other text; the
!> variables a resumed run may change (&growth steps, all of &load_path), the title and the
!> names of files (whose contents the fingerprint holds, not their names) are left out. A
!> value written differently but equal (0.5 and 5e-1) counts as a difference here; the
!> fingerprint decides whether the models differ, this only says where to look.
module ddc_app_input_difference
    use ddc_text, only: lower, itoa
    implicit none
    private

    public :: input_difference

    !> The characters of a Fortran name
    character(len=*), parameter :: name_characters = &
        'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'

    !> One `name = value` of a group
    type :: assignment
        character(len=:), allocatable :: name, value
    end type assignment

    !> One group: its name (lower case) and its assignments in order
    type :: group_text
        character(len=:), allocatable :: name
        type(assignment), allocatable :: values(:)
    end type group_text

contains

    !> The first difference of the inputs, as "&group variable: OLD before, NEW now" (the
    !> group's ordinal when the name repeats), or '' when none is seen.
    function input_difference(old_text, new_text) result(text)
        !> The earlier run's input and the input of this run
        character(len=*), intent(in) :: old_text, new_text
        !> The difference, one line
        character(len=:), allocatable :: text
        type(group_text), allocatable :: old(:), new(:)
        type(group_text) :: none
        integer :: i, k, j

        old = parse_groups(old_text)
        new = parse_groups(new_text)
        allocate (none%values(0))
        text = ''
        ! A group only one input has is compared with an empty one.
        do i = 1, size(new)
            k = matching_group(old, new, i)
            if (k == 0) then
                none%name = new(i)%name
                text = value_difference(none, new(i), group_label(new, i))
            else
                text = value_difference(old(k), new(i), group_label(new, i))
            end if
            if (len(text) > 0) return
        end do
        do j = 1, size(old)
            if (matching_group(new, old, j) > 0) cycle
            none%name = old(j)%name
            text = value_difference(old(j), none, group_label(old, j))
            if (len(text) > 0) return
        end do
    end function input_difference

    !> The first variable of group `a` or `b` whose value differs ('' when none).
    function value_difference(a, b, label) result(text)
        type(group_text), intent(in) :: a, b
        character(len=*), intent(in) :: label
        character(len=:), allocatable :: text, before
        integer :: i

        text = ''
        if (a%name == 'load_path') return
        do i = 1, size(b%values)
            if (.not. compared(b%name, b%values(i)%name)) cycle
            before = value_of(a, b%values(i)%name)
            if (before /= b%values(i)%value) then
                text = label//' '//b%values(i)%name//': '//shown(before)//' before, '// &
                    b%values(i)%value//' now'
                return
            end if
        end do
        do i = 1, size(a%values)
            if (.not. compared(a%name, a%values(i)%name)) cycle
            if (len(value_of(b, a%values(i)%name)) == 0) then
                text = label//' '//a%values(i)%name//': '//a%values(i)%value// &
                    ' before, not given now'
                return
            end if
        end do
    end function value_difference

    !> Whether a variable's value counts: not &growth steps (a resumed run may raise it), nor
    !> the title and file names (their contents count in the fingerprint, not their names).
    pure logical function compared(group, name)
        character(len=*), intent(in) :: group, name

        select case (group//' '//name)
        case ('growth steps', 'model title', 'output file', 'fracture elements_file', &
              'points file')
            compared = .false.
        case default
            compared = .true.
        end select
    end function compared

    !> 'not given' for an empty value, else the value.
    pure function shown(value) result(text)
        character(len=*), intent(in) :: value
        character(len=:), allocatable :: text

        text = value
        if (len(value) == 0) text = 'not given'
    end function shown

    !> The value of a variable in a group ('' when not given; the last one given counts).
    pure function value_of(group, name) result(value)
        type(group_text), intent(in) :: group
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: value
        integer :: i

        value = ''
        do i = 1, size(group%values)
            if (group%values(i)%name == name) value = group%values(i)%value
        end do
    end function value_of

    !> The group of `groups` that is the same ordinal of the same name as others(i) (0: none).
    pure integer function matching_group(groups, others, i) result(k)
        type(group_text), intent(in) :: groups(:), others(:)
        integer, intent(in) :: i
        integer :: ordinal, j

        ordinal = count([(others(j)%name == others(i)%name, j = 1, i)])
        k = 0
        do j = 1, size(groups)
            if (groups(j)%name /= others(i)%name) cycle
            ordinal = ordinal - 1
            if (ordinal == 0) then
                k = j
                return
            end if
        end do
    end function matching_group

    !> '&name', with ' 2' (its ordinal) when the name repeats.
    function group_label(groups, i) result(label)
        type(group_text), intent(in) :: groups(:)
        integer, intent(in) :: i
        character(len=:), allocatable :: label
        integer :: j

        label = '&'//groups(i)%name
        if (count([(groups(j)%name == groups(i)%name, j = 1, size(groups))]) > 1) then
            label = label//' '//itoa(count([(groups(j)%name == groups(i)%name, j = 1, i)]))
        end if
    end function group_label

    !> The groups of a namelist text: comments dropped, each `&name ... /` split into its
    !> assignments.
    function parse_groups(text) result(groups)
        character(len=*), intent(in) :: text
        type(group_text), allocatable :: groups(:)
        character(len=:), allocatable :: flat, name
        type(assignment), allocatable :: values(:)
        integer :: i, n, start

        flat = without_comments(text)
        allocate (groups(0))
        n = len(flat)
        i = 1
        do while (i <= n)
            if (flat(i:i) == '&') then
                start = i + 1
                i = start
                do while (i <= n)
                    if (verify(flat(i:i), name_characters) /= 0) exit
                    i = i + 1
                end do
                name = lower(flat(start:i - 1))
                call read_assignments(flat, i, values)
                groups = [groups, group_text(name, values)]
            else
                i = i + 1
            end if
        end do
    end function parse_groups

    !> The assignments of a group body from flat(i:) to its closing '/' (outside quotes);
    !> i is left after it.
    subroutine read_assignments(flat, i, values)
        character(len=*), intent(in) :: flat
        integer, intent(inout) :: i
        type(assignment), allocatable, intent(out) :: values(:)
        ! A structure constructor of a function result here is an internal error of gfortran 12
        type(assignment) :: item
        type(assignment), allocatable :: list(:)
        character(len=1) :: quote
        integer :: equals, name_end, name_start

        allocate (list(0))
        quote = ' '
        do while (i <= len(flat))
            if (quote /= ' ') then
                if (flat(i:i) == quote) quote = ' '
            else if (flat(i:i) == '"' .or. flat(i:i) == "'") then
                quote = flat(i:i)
            else if (flat(i:i) == '/') then
                i = i + 1
                exit
            else if (flat(i:i) == '=') then
                equals = i
                name_end = len_trim(flat(:equals - 1))
                ! A subscript belongs to the name: x(3) = 1
                if (name_end > 0) then
                    if (flat(name_end:name_end) == ')') name_end = index(flat(:name_end), '(', &
                                                                     back=.true.) - 1
                end if
                name_start = name_end
                do while (name_start > 1)
                    if (verify(flat(name_start - 1:name_start - 1), name_characters) /= 0) exit
                    name_start = name_start - 1
                end do
                if (size(list) > 0) list(size(list))%value = &
                    cleaned(list(size(list))%value(:max(0, len(list(size(list))%value) &
                    - (equals - name_start))))
                item%name = lower(trim(flat(name_start:equals - 1)))
                item%value = ''
                list = [list, item]
                i = i + 1
                cycle
            end if
            if (size(list) > 0) list(size(list))%value = list(size(list))%value// &
                flat(i:i)
            i = i + 1
        end do
        if (size(list) > 0) list(size(list))%value = cleaned(list(size(list))%value)
        call move_alloc(list, values)
    end subroutine read_assignments

    !> A value without surrounding blanks and separating commas, inner blanks collapsed.
    pure function cleaned(value) result(text)
        character(len=*), intent(in) :: value
        character(len=:), allocatable :: text
        integer :: i

        text = ''
        do i = 1, len(value)
            if (value(i:i) == ' ') then
                if (len(text) == 0) cycle
                if (text(len(text):len(text)) == ' ') cycle
            end if
            text = text//value(i:i)
        end do
        do while (len(text) > 0)
            if (scan(text(len(text):len(text)), ' ,') == 0) exit
            text = text(:len(text) - 1)
        end do
    end function cleaned

    !> The text on one line, `!` comments (outside quotes) dropped, line ends and tabs as blanks.
    pure function without_comments(text) result(flat)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: flat
        character(len=1) :: quote
        logical :: comment
        integer :: i

        allocate (character(len=len(text)) :: flat)
        quote = ' '
        comment = .false.
        do i = 1, len(text)
            flat(i:i) = text(i:i)
            if (text(i:i) == new_line('a') .or. text(i:i) == achar(13)) then
                comment = .false.
                quote = ' '
                flat(i:i) = ' '
            else if (comment) then
                flat(i:i) = ' '
            else if (quote /= ' ') then
                if (text(i:i) == quote) quote = ' '
            else if (text(i:i) == '!') then
                comment = .true.
                flat(i:i) = ' '
            else if (text(i:i) == '"' .or. text(i:i) == "'") then
                quote = text(i:i)
            else if (text(i:i) == achar(9)) then
                flat(i:i) = ' '
            end if
        end do
    end function without_comments

end module ddc_app_input_difference
