!> Read a CSV file of numbers with a known header.
!>
!> The first non-comment line is the header (compared case-insensitively, spaces ignored);
!> every other line is one row of numbers. Blank lines and lines starting with `#` are
!> skipped. Every bad row is reported with the file and its line number.
module ddc_input_csv
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_input_text_file, only: read_text_file
    use ddc_text, only: newline, add_message, messages_error, itoa, lower
    use ddc_model_limits, only: within_limits, limits_text
    implicit none
    private

    public :: read_csv

contains

    !> Read the CSV file at path whose columns are header; values has shape (ncols, nrows).
    !> A two-column x,y file may omit its header line. The header may go on with any of
    !> the optional columns, in any order; their values follow those of header in values
    !> (0 where a column is absent, see given).
    subroutine read_csv(path, header, values, error, line_numbers, optional_header, given, &
                        most_rows)
        !> Path of the file
        character(len=*), intent(in) :: path
        !> Expected column names, in order
        character(len=*), intent(in) :: header(:)
        !> The numbers, shape (size(header) + size(optional_header), number of rows)
        real(wp), allocatable, intent(out) :: values(:,:)
        !> Allocated when the file is missing or any line is bad
        type(error_type), allocatable, intent(out) :: error
        !> Line number in the file of each row, shape (number of rows)
        integer, allocatable, intent(out), optional :: line_numbers(:)
        !> Names of columns the file may add after header
        character(len=*), intent(in), optional :: optional_header(:)
        !> Which optional columns the file has, shape (size(optional_header))
        logical, allocatable, intent(out), optional :: given(:)
        !> Most data rows accepted: the reading stops with an error at the row after them,
        !> so that a huge file costs no more memory than that many rows
        integer, intent(in), optional :: most_rows
        character(len=:), allocatable :: text, line, expected, messages
        integer, allocatable :: row_line(:), column(:)
        real(wp), allocatable :: row(:)
        integer :: ncols, nrows, max_rows, pos, line_no, nbad, i, nopt
        logical :: header_seen, header_optional, extended

        call read_text_file(path, text, error)
        if (allocated(error)) return

        ncols = size(header)
        nopt = 0
        if (present(optional_header)) nopt = size(optional_header)
        if (present(given)) allocate (given(nopt), source=.false.)
        expected = lower(trim(adjustl(header(1))))
        do i = 2, ncols
            expected = expected//','//lower(trim(adjustl(header(i))))
        end do
        ! column(k): where field k of a row goes in values
        column = [(i, i = 1, ncols)]
        header_optional = expected == 'x,y'
        ! Skip a UTF-8 byte order mark (spreadsheet exports).
        if (len(text) >= 3) then
            if (text(1:3) == char(239)//char(187)//char(191)) text = text(4:)
        end if

        max_rows = count_pieces(text, newline)
        if (present(most_rows)) max_rows = min(max_rows, most_rows)
        allocate (values(ncols + nopt, max_rows), row_line(max_rows))
        values = 0.0_wp
        nrows = 0
        nbad = 0
        messages = ''
        header_seen = .false.
        pos = 1
        line_no = 0
        do while (pos <= len(text))
            call next_line(text, pos, line)
            line_no = line_no + 1
            line = trim(adjustl(line))
            if (len(line) == 0) cycle
            if (line(1:1) == '#') cycle
            if (.not. header_seen) then
                header_seen = .true.
                if (normalized_header(line) == expected) cycle
                if (nopt > 0) then
                    call optional_columns(normalized_header(line), expected, optional_header, &
                                          column, ok=extended)
                    if (extended) then
                        if (present(given)) given = [(any(column == ncols + i), i = 1, nopt)]
                        cycle
                    end if
                    call set_error(error, exit_bad_input, path//' line '//itoa(line_no)// &
                        ": the header '"//line//"' is not the expected '"//expected// &
                        "' (optionally followed by any of "//join(optional_header)//")")
                    return
                end if
                if (.not. header_optional) then
                    call set_error(error, exit_bad_input, path//' line '//itoa(line_no)// &
                        ": the header '"//line//"' is not the expected '"//expected//"'")
                    return
                end if
            end if
            if (nrows == max_rows) then
                call set_error(error, exit_bad_input, path//' line '//itoa(line_no)// &
                    ': more than '//itoa(max_rows)//' data rows, the most accepted here')
                return
            end if
            nrows = nrows + 1
            row_line(nrows) = line_no
            allocate (row(size(column)))
            call parse_row(line, row, path//' line '//itoa(line_no)//': ', &
                           expected, messages, nbad)
            values(column, nrows) = row
            deallocate (row)
        end do

        if (nbad > 0) then
            call messages_error(messages, nbad, 'bad lines', error)
            return
        end if
        if (nrows == 0) then
            call set_error(error, exit_bad_input, path//': no data rows (expected columns '// &
                           expected//')')
            return
        end if
        values = values(:, 1:nrows)
        if (present(line_numbers)) line_numbers = row_line(1:nrows)
    end subroutine read_csv

    !> The columns of a header that is expected followed by optional columns (each once):
    !> column(k) is the index in values of field k; ok is false for any other header.
    subroutine optional_columns(header, expected, optional_header, column, ok)
        character(len=*), intent(in) :: header, expected
        character(len=*), intent(in) :: optional_header(:)
        integer, allocatable, intent(inout) :: column(:)
        logical, intent(out) :: ok
        character(len=:), allocatable :: rest, name
        integer :: comma, k, ncols

        ncols = size(column)
        ok = len(header) > len(expected) + 1
        if (.not. ok) return
        ok = header(1:len(expected) + 1) == expected//','
        if (.not. ok) return
        rest = header(len(expected) + 2:)//','
        do while (len(rest) > 0)
            comma = index(rest, ',')
            name = rest(1:comma - 1)
            rest = rest(comma + 1:)
            k = 0
            do comma = 1, size(optional_header)
                if (lower(trim(adjustl(optional_header(comma)))) == name) k = comma
            end do
            ok = k > 0
            if (ok) ok = .not. any(column == ncols + k)
            if (.not. ok) return
            column = [column, ncols + k]
        end do
    end subroutine optional_columns

    !> 'a, b, c'
    pure function join(names) result(text)
        character(len=*), intent(in) :: names(:)
        character(len=:), allocatable :: text
        integer :: i

        text = trim(adjustl(names(1)))
        do i = 2, size(names)
            text = text//', '//trim(adjustl(names(i)))
        end do
    end function join

    !> Parse one row into row; append a message for every bad field.
    subroutine parse_row(line, row, prefix, expected, messages, nbad)
        character(len=*), intent(in) :: line
        real(wp), intent(out) :: row(:)
        character(len=*), intent(in) :: prefix, expected
        character(len=:), allocatable, intent(inout) :: messages
        integer, intent(inout) :: nbad
        character(len=:), allocatable :: field
        integer :: nfields, start, comma, k, stat

        row = 0.0_wp
        nfields = count_pieces(line, ',')
        if (nfields /= size(row)) then
            call add_message(messages, nbad, prefix//itoa(nfields)//' fields, expected '// &
                             itoa(size(row))//' ('//expected//')')
            return
        end if
        start = 1
        do k = 1, nfields
            comma = index(line(start:), ',')
            if (comma == 0) then
                field = trim(adjustl(line(start:)))
            else
                field = trim(adjustl(line(start:start + comma - 2)))
                start = start + comma
            end if
            ! Tabs around a field are blanks too.
            field = strip(field)
            if (len(field) == 0) then
                call add_message(messages, nbad, prefix//'field '//itoa(k)//' is empty')
            else if (.not. is_number(field)) then
                if (is_nonfinite_word(field)) then
                    call add_message(messages, nbad, prefix//'field '//itoa(k)//" '"//field// &
                                     "' is not a finite number")
                else
                    call add_message(messages, nbad, prefix//'field '//itoa(k)//" '"//field// &
                                     "' is not a number")
                end if
            else
                read (field, *, iostat=stat) row(k)
                if (stat /= 0) then
                    call add_message(messages, nbad, prefix//'field '//itoa(k)//" '"//field// &
                                     "' is not a number")
                else if (.not. within_limits(row(k))) then
                    call add_message(messages, nbad, prefix//'field '//itoa(k)//" '"//field// &
                                     "'"//limits_text)
                    row(k) = 0.0_wp
                end if
            end if
        end do
    end subroutine parse_row

    !> Return the line starting at pos (without its newline or carriage return); move pos on.
    subroutine next_line(text, pos, line)
        character(len=*), intent(in) :: text
        integer, intent(inout) :: pos
        character(len=:), allocatable, intent(out) :: line
        integer :: eol

        eol = index(text(pos:), newline)
        if (eol == 0) then
            line = text(pos:)
            pos = len(text) + 1
        else
            line = text(pos:pos + eol - 2)
            pos = pos + eol
        end if
        if (len(line) > 0) then
            if (line(len(line):len(line)) == achar(13)) line = line(1:len(line) - 1)
        end if
    end subroutine next_line

    !> Number of pieces of text between separators: lines (an upper bound on the rows)
    !> for newline, fields of a line for ','.
    pure function count_pieces(text, separator) result(n)
        character(len=*), intent(in) :: text
        character(len=1), intent(in) :: separator
        integer :: n
        integer :: i

        n = 1
        do i = 1, len(text)
            if (text(i:i) == separator) n = n + 1
        end do
    end function count_pieces

    !> Header line in lower case without blanks, tabs or double quotes.
    pure function normalized_header(line) result(out)
        character(len=*), intent(in) :: line
        character(len=:), allocatable :: out
        integer :: i

        out = ''
        do i = 1, len(line)
            select case (line(i:i))
            case (' ', achar(9), '"')
            case default
                out = out//lower(line(i:i))
            end select
        end do
    end function normalized_header

    !> The string without leading and trailing blanks and tabs.
    pure function strip(s) result(out)
        character(len=*), intent(in) :: s
        character(len=:), allocatable :: out
        integer :: first, last

        first = verify(s, ' '//achar(9))
        last = verify(s, ' '//achar(9), back=.true.)
        if (first == 0) then
            out = ''
        else
            out = s(first:last)
        end if
    end function strip

    !> True when s is a decimal number: [sign] digits [. digits] [e|d [sign] digits].
    pure function is_number(s) result(ok)
        character(len=*), intent(in) :: s
        logical :: ok
        integer :: i, n, ndigits

        ok = .false.
        n = len(s)
        i = 1
        if (n == 0) return
        if (s(1:1) == '+' .or. s(1:1) == '-') i = 2
        ndigits = 0
        do while (i <= n)
            if (.not. is_digit(s(i:i))) exit
            ndigits = ndigits + 1
            i = i + 1
        end do
        if (i <= n) then
            if (s(i:i) == '.') then
                i = i + 1
                do while (i <= n)
                    if (.not. is_digit(s(i:i))) exit
                    ndigits = ndigits + 1
                    i = i + 1
                end do
            end if
        end if
        if (ndigits == 0) return
        if (i <= n) then
            if (index('eEdD', s(i:i)) == 0) return
            i = i + 1
            if (i <= n) then
                if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
            end if
            if (i > n) return
            do while (i <= n)
                if (.not. is_digit(s(i:i))) return
                i = i + 1
            end do
        end if
        ok = .true.
    end function is_number

    !> True for the spellings of NaN and infinity.
    pure function is_nonfinite_word(s) result(yes)
        character(len=*), intent(in) :: s
        logical :: yes
        character(len=:), allocatable :: t

        t = lower(s)
        if (len(t) > 0) then
            if (t(1:1) == '+' .or. t(1:1) == '-') t = t(2:)
        end if
        yes = t == 'nan' .or. t == 'inf' .or. t == 'infinity'
    end function is_nonfinite_word

    pure function is_digit(c) result(yes)
        character(len=1), intent(in) :: c
        logical :: yes

        yes = c >= '0' .and. c <= '9'
    end function is_digit

end module ddc_input_csv
