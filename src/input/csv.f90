!> Read a CSV file of numbers with a known header.
!>
!> The first non-comment line is the header (compared case-insensitively, spaces ignored);
!> every other line is one row of numbers. Blank lines and lines starting with `#` are
!> skipped. Every bad row is reported with the file and its line number.
module ddc_input_csv
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_input_text_file, only: read_text_file
    use ddc_input_decimal, only: is_number, decimal_value
    use ddc_text, only: newline, add_message, messages_error, itoa, lower
    use ddc_model_limits, only: within_limits, limits_text
    implicit none
    private

    public :: read_csv

    !> What may surround a field
    character(len=*), parameter :: blanks = ' '//achar(9)

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
        integer :: ncols, nrows, max_rows, pos, first, last, line_no, nbad, i, nopt
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
        ! Rows are parsed where they lie in text, into one row buffer: a file of millions of
        ! rows spent most of its time allocating copies of each line and field.
        do while (pos <= len(text))
            call next_line(text, pos, first, last)
            line_no = line_no + 1
            if (last < first) cycle
            if (text(first:first) == '#') cycle
            if (.not. header_seen) then
                header_seen = .true.
                line = text(first:last)
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
            if (.not. allocated(row)) allocate (row(size(column)))
            call parse_row(text(first:last), row, path, line_no, expected, messages, nbad)
            values(column, nrows) = row
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

    !> Parse one row, line line_no of path, into row; append a message for every bad field.
    subroutine parse_row(line, row, path, line_no, expected, messages, nbad)
        character(len=*), intent(in) :: line
        real(wp), intent(out) :: row(:)
        character(len=*), intent(in) :: path
        integer, intent(in) :: line_no
        character(len=*), intent(in) :: expected
        character(len=:), allocatable, intent(inout) :: messages
        integer, intent(inout) :: nbad
        character(len=:), allocatable :: problem
        integer :: nfields, start, finish, comma, k

        row = 0.0_wp
        nfields = count_pieces(line, ',')
        if (nfields /= size(row)) then
            call add_message(messages, nbad, path//' line '//itoa(line_no)//': '// &
                             itoa(nfields)//' fields, expected '//itoa(size(row))//' ('// &
                             expected//')')
            return
        end if
        start = 1
        do k = 1, nfields
            comma = index(line(start:), ',')
            finish = len(line)
            if (comma > 0) finish = start + comma - 2
            call parse_field(line(start:finish), row(k), problem)
            if (allocated(problem)) call add_message(messages, nbad, path//' line '// &
                                                     itoa(line_no)//': field '//itoa(k)//problem)
            start = finish + 2
        end do
    end subroutine parse_row

    !> The number in a field, blanks and tabs around it ignored; problem, allocated when the
    !> field holds no finite number within the model's limits, says why (value is 0 then).
    subroutine parse_field(field, value, problem)
        character(len=*), intent(in) :: field
        real(wp), intent(out) :: value
        character(len=:), allocatable, intent(out) :: problem
        integer :: first, last

        value = 0.0_wp
        first = verify(field, blanks)
        if (first == 0) then
            problem = ' is empty'
            return
        end if
        last = verify(field, blanks, back=.true.)
        call parse_number(field(first:last), value, problem)
    end subroutine parse_field

    !> parse_field for a field without blanks around it.
    subroutine parse_number(field, value, problem)
        character(len=*), intent(in) :: field
        real(wp), intent(inout) :: value
        character(len=:), allocatable, intent(inout) :: problem
        integer :: stat

        if (.not. is_number(field)) then
            if (is_nonfinite_word(field)) then
                problem = " '"//field//"' is not a finite number"
            else
                problem = " '"//field//"' is not a number"
            end if
            return
        end if
        call decimal_value(field, value, stat)
        if (stat /= 0) then
            problem = " '"//field//"' is not a number"
        else if (.not. within_limits(value)) then
            problem = " '"//field//"'"//limits_text
            value = 0.0_wp
        end if
    end subroutine parse_number

    !> The line starting at pos is text(first:last), without its newline, a carriage return
    !> before that and the blanks around it (last < first for a blank line); move pos on.
    pure subroutine next_line(text, pos, first, last)
        character(len=*), intent(in) :: text
        integer, intent(inout) :: pos
        integer, intent(out) :: first, last
        integer :: eol, skip

        first = pos
        eol = index(text(pos:), newline)
        if (eol == 0) then
            last = len(text)
            pos = len(text) + 1
        else
            last = pos + eol - 2
            pos = pos + eol
        end if
        if (last >= first) then
            if (text(last:last) == achar(13)) last = last - 1
        end if
        skip = verify(text(first:last), ' ')
        if (skip == 0) then
            last = first - 1
        else
            first = first + skip - 1
            last = first - 1 + len_trim(text(first:last))
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

end module ddc_input_csv
