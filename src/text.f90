!> Small text helpers shared by every layer: a capped list of problem lines joined with
!> newlines, numbers and lists as text, ASCII lower case, lookup of a name in a list, C
!> strings as Fortran text.
module ddc_text
    use, intrinsic :: iso_c_binding, only: c_char, c_null_char
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    implicit none
    private

    public :: newline, max_messages, add_message, messages_error, itoa, rtoa, short_real, lower
    public :: join_integers, prefix_lines, quoted_list, find_name, bytes_text, seconds_text
    public :: from_c_chars, allocated_text, counted

    !> Separator of the lines of a message
    character(len=*), parameter :: newline = achar(10)
    !> At most this many problems are listed in one message
    integer, parameter :: max_messages = 20

contains

    !> Append a line to the messages (up to max_messages of them) and count it.
    subroutine add_message(messages, nbad, message)
        !> Lines so far, joined with newlines ('' when none)
        character(len=:), allocatable, intent(inout) :: messages
        !> Number of problems so far, listed or not
        integer, intent(inout) :: nbad
        !> The new line
        character(len=*), intent(in) :: message

        nbad = nbad + 1
        if (nbad > max_messages) return
        if (len(messages) > 0) messages = messages//newline
        messages = messages//message
    end subroutine add_message

    !> Turn the collected messages into an exit_bad_input error, with a last line
    !> "... and N more <what>" when some were not listed.
    subroutine messages_error(messages, nbad, what, error)
        !> Lines collected by add_message
        character(len=*), intent(in) :: messages
        !> Number of problems counted by add_message (> 0)
        integer, intent(in) :: nbad
        !> Plural noun of the problems, e.g. 'bad lines'
        character(len=*), intent(in) :: what
        !> The error made
        type(error_type), allocatable, intent(out) :: error

        if (nbad > max_messages) then
            call set_error(error, exit_bad_input, messages//newline//'... and '// &
                           itoa(nbad - max_messages)//' more '//what)
        else
            call set_error(error, exit_bad_input, messages)
        end if
    end subroutine messages_error

    !> Integer as text without blanks.
    pure function itoa(i) result(out)
        !> The integer
        integer, intent(in) :: i
        character(len=:), allocatable :: out
        character(len=24) :: buffer

        write (buffer, '(i0)') i
        out = trim(buffer)
    end function itoa

    !> "1 value", "3 values": a count with its noun in the number it needs.
    pure function counted(n, singular, plural) result(out)
        !> The count
        integer, intent(in) :: n
        !> The noun for one, and for any other count
        character(len=*), intent(in) :: singular, plural
        !> The count and the noun
        character(len=:), allocatable :: out

        if (n == 1) then
            out = itoa(n)//' '//singular
        else
            out = itoa(n)//' '//plural
        end if
    end function counted

    !> Real as short text (NaN and Inf spelled out).
    pure function rtoa(x) result(out)
        !> The number
        real(wp), intent(in) :: x
        character(len=:), allocatable :: out
        character(len=32) :: buffer

        write (buffer, '(g0.6)') x
        out = trim(adjustl(buffer))
    end function rtoa

    !> A duration as '1.23 s'.
    pure function seconds_text(seconds) result(out)
        !> The duration [s]
        real(wp), intent(in) :: seconds
        character(len=:), allocatable :: out
        character(len=24) :: buffer

        write (buffer, '(f0.2)') seconds
        out = trim(buffer)//' s'
        if (out(1:1) == '.') out = '0'//out
    end function seconds_text

    !> A real as short text for people: integers without a point (-30, 30000), others to 8
    !> significant digits without trailing zeros, in fixed notation from 1e-4 to 1e9 (0.2,
    !> 0.0265, 19.62) and in exponent notation beyond (1.5E-05, 1.28E+12).
    pure function short_real(x) result(out)
        !> The number
        real(wp), intent(in) :: x
        character(len=:), allocatable :: out
        character(len=40) :: buffer
        integer :: e, decimals

        if (x == anint(x) .and. abs(x) < 1.0e9_wp) then
            write (buffer, '(i0)') nint(x, kind=8)
            out = trim(buffer)
        else if (abs(x) >= 1.0e-4_wp .and. abs(x) < 1.0e9_wp) then
            decimals = max(0, 7 - floor(log10(abs(x))))
            write (buffer, '(f0.'//itoa(decimals)//')') x
            out = trim_zeros(buffer)
            ! f0.d writes no zero before the point
            if (out(1:1) == '.') out = '0'//out
            if (out(1:2) == '-.') out = '-0'//out(2:)
        else
            write (buffer, '(es15.7)') x
            buffer = adjustl(buffer)
            e = scan(buffer, 'Ee')
            out = trim(buffer)
            if (e > 1) out = trim_zeros(buffer(1:e - 1))//trim(buffer(e:))
        end if
    end function short_real

    !> A decimal number without trailing zeros (and without a trailing point).
    pure function trim_zeros(text) result(out)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: out

        out = trim(adjustl(text))
        if (index(out, '.') == 0) return
        do while (out(len(out):len(out)) == '0')
            out = out(1:len(out) - 1)
        end do
        if (out(len(out):len(out)) == '.') out = out(1:len(out) - 1)
    end function trim_zeros

    !> A memory size for people, in decimal units to two significant digits: '640 bytes',
    !> '1.3 TB', '24 GB'.
    pure function bytes_text(bytes) result(out)
        !> The size [bytes]
        real(wp), intent(in) :: bytes
        character(len=:), allocatable :: out
        character(len=*), parameter :: units(4) = [character(len=2) :: 'kB', 'MB', 'GB', 'TB']
        real(wp) :: value
        integer :: k

        if (.not. bytes >= 1000.0_wp) then
            out = short_real(anint(max(bytes, 0.0_wp)))//' bytes'
            return
        end if
        value = bytes
        k = 0
        do while (value >= 999.5_wp .and. k < size(units))
            value = value / 1000.0_wp
            k = k + 1
        end do
        if (value < 9.95_wp) then
            value = anint(value * 10.0_wp) / 10.0_wp
        else
            value = anint(value)
        end if
        out = short_real(value)//' '//trim(units(k))
    end function bytes_text

    !> Lower-case copy of s (ASCII).
    pure function lower(s) result(out)
        !> The text
        character(len=*), intent(in) :: s
        character(len=len(s)) :: out
        integer :: i, code

        do i = 1, len(s)
            code = iachar(s(i:i))
            if (code >= iachar('A') .and. code <= iachar('Z')) then
                out(i:i) = achar(code + 32)
            else
                out(i:i) = s(i:i)
            end if
        end do
    end function lower


    !> "1, 9, 12": integers joined with commas.
    function join_integers(values) result(out)
        !> The integers
        integer, intent(in) :: values(:)
        !> The text
        character(len=:), allocatable :: out
        integer :: i

        out = ''
        do i = 1, size(values)
            if (i > 1) out = out//', '
            out = out//itoa(values(i))
        end do
    end function join_integers

    !> Prefix every line of text.
    pure function prefix_lines(prefix, text) result(out)
        character(len=*), intent(in) :: prefix, text
        character(len=:), allocatable :: out
        integer :: start, eol

        out = ''
        start = 1
        do
            eol = index(text(start:), newline)
            if (eol == 0) then
                out = out//prefix//text(start:)
                exit
            end if
            out = out//prefix//text(start:start + eol - 1)
            start = start + eol
        end do
    end function prefix_lines

    !> "'a', 'b', 'c'"
    function quoted_list(list) result(out)
        character(len=*), intent(in) :: list(:)
        character(len=:), allocatable :: out
        integer :: i

        out = "'"//trim(list(1))//"'"
        do i = 2, size(list)
            out = out//", '"//trim(list(i))//"'"
        end do
    end function quoted_list

    !> Index of name in list (exact match after trimming), 0 when absent.
    pure function find_name(name, list) result(found)
        character(len=*), intent(in) :: name
        character(len=*), intent(in) :: list(:)
        integer :: found
        integer :: i

        found = 0
        do i = 1, size(list)
            if (trim(list(i)) == trim(name)) then
                found = i
                return
            end if
        end do
    end function find_name

    !> The value of an optional string, '' when it is not allocated.
    pure function allocated_text(value) result(string)
        !> The string
        character(len=:), allocatable, intent(in) :: value
        !> Its value or ''
        character(len=:), allocatable :: string

        if (allocated(value)) then
            string = value
        else
            string = ''
        end if
    end function allocated_text

    !> A Fortran string from C characters, cut at the first NUL.
    pure function from_c_chars(chars) result(text)
        !> The characters, NUL-terminated or filling the array
        character(kind=c_char), intent(in) :: chars(:)
        !> The text before the NUL
        character(len=:), allocatable :: text
        integer :: i, n

        n = size(chars)
        do i = 1, size(chars)
            if (chars(i) == c_null_char) then
                n = i - 1
                exit
            end if
        end do
        allocate (character(len=n) :: text)
        do i = 1, n
            text(i:i) = chars(i)
        end do
    end function from_c_chars

end module ddc_text
