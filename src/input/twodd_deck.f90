!> Reader of classic TWODD decks (Crouch & Starfield 1983, ch. 5;
!> docs/compatibility.md#twodd-decks).
!>
!> A deck is list-directed, one record after the other: a title line; `NUMBS, NUMOS, KSYM`;
!> `PR, E, XSYM, YSYM`; `PXX, PYY, PXY`; NUMBS segment records `NUM, XBEG, YBEG, XEND,
!> YEND, KODE, BVS, BVN`; NUMOS observation records `XBEG, YBEG, XEND, YEND, NUMPB`. As in
!> Fortran list-directed input, blank lines are skipped and a record may continue on the
!> next line; values after the last one a record needs are ignored, and so are lines after
!> the last record. The deck produces the same model_type as the namelist reader: one
!> fracture `segment_<k>` per segment, one observation line `line_<k>` per observation
!> record (NUMPB interior points plus both ends; one point when the ends coincide).
!> Every problem is reported with the file name and the line number.
module ddc_input_twodd_deck
    use ddc_model_limits, only: within_limits, range_problem, quantity_poissons_ratio, &
        quantity_youngs_modulus
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, observation_line, condition_traction, &
        condition_mixed_ss_un
    use ddc_input_text_file, only: read_text_file, base_name
    use ddc_mesh_polyline, only: polyline_elements
    use ddc_mesh_geometry, only: allocate_elements, compute_geometry
    use ddc_mesh_checks, only: check_elements
    use ddc_text, only: itoa, rtoa
    use ddc_allocation, only: allocation_failed, real_bytes
    implicit none
    private

    public :: read_twodd_deck

    !> Largest element count of one segment and point count of one observation line
    integer, parameter :: max_count = 1000000

    !> One line of the deck.
    type :: deck_line
        character(len=:), allocatable :: text
    end type deck_line

    !> The deck's lines and the reading position.
    type :: deck_cursor
        !> File name, for messages
        character(len=:), allocatable :: path
        !> The lines of the file
        type(deck_line), allocatable :: lines(:)
        !> Index of the last line consumed
        integer :: last = 0
    end type deck_cursor

    !> One segment record.
    type :: segment_record
        integer :: num = 0, kode = 0, line = 0
        real(wp) :: xbeg = 0.0_wp, ybeg = 0.0_wp, xend = 0.0_wp, yend = 0.0_wp
        real(wp) :: bvs = 0.0_wp, bvn = 0.0_wp
    end type segment_record

contains

    !> Read the TWODD deck at path into a complete model (elements with geometry,
    !> fractures, observation lines, symmetry, solver defaults, output file, input text).
    subroutine read_twodd_deck(path, model, error)
        !> Path of the deck, as given on the command line
        character(len=*), intent(in) :: path
        !> The model read
        type(model_type), intent(out) :: model
        !> Allocated (exit_bad_input) when the file is missing or malformed, naming the line
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text, record
        type(deck_cursor) :: deck
        type(segment_record), allocatable :: segments(:)
        integer :: numbs, numos, ksym, k, first_line, stat
        real(wp) :: pr, e, xsym, ysym, pxx, pyy, pxy
        character(len=256) :: iomsg

        call read_text_file(path, text, error)
        if (allocated(error)) return
        model%input_file = path
        model%input_text = text
        deck%path = path
        call split_lines(text, deck%lines)

        ! Title: the first line as it stands (TWODD reads it with an A format).
        deck%last = 1
        model%title = trim(adjustl(deck%lines(1)%text))
        if (len(model%title) == 0) model%title = base_name(path, .false.)

        ! NUMBS, NUMOS, KSYM
        do
            call next_record(deck, 'NUMBS, NUMOS, KSYM', record, first_line, error)
            if (allocated(error)) return
            read (record, *, iostat=stat, iomsg=iomsg) numbs, numos, ksym
            if (.not. continued(deck, stat, record)) exit
        end do
        if (stat /= 0) then
            call bad_record(error, deck, first_line, 'NUMBS, NUMOS, KSYM (three integers)', &
                            stat, iomsg)
            return
        end if
        if (numbs < 1) then
            call fail(error, deck, first_line, 'NUMBS = '//itoa(numbs)// &
                      ' must be at least 1 (the number of boundary segments)')
            return
        end if
        if (numbs > max_count) then
            call fail(error, deck, first_line, 'NUMBS = '//itoa(numbs)//' is too large')
            return
        end if
        if (numos < 0 .or. numos > max_count) then
            call fail(error, deck, first_line, 'NUMOS = '//itoa(numos)// &
                      ' must be 0 or more (the number of observation lines)')
            return
        end if
        if (ksym < 1 .or. ksym > 4) then
            call fail(error, deck, first_line, 'KSYM = '//itoa(ksym)//' must be 1 (none), '// &
                      '2 (about x = XSYM), 3 (about y = YSYM) or 4 (both)')
            return
        end if

        ! PR, E, XSYM, YSYM
        do
            call next_record(deck, 'PR, E, XSYM, YSYM', record, first_line, error)
            if (allocated(error)) return
            read (record, *, iostat=stat, iomsg=iomsg) pr, e, xsym, ysym
            if (.not. continued(deck, stat, record)) exit
        end do
        if (stat /= 0) then
            call bad_record(error, deck, first_line, 'PR, E, XSYM, YSYM (four reals)', stat, &
                            iomsg)
            return
        end if
        if (.not. all(within_limits([pr, e, xsym, ysym]))) then
            call fail(error, deck, first_line, 'PR, E, XSYM, YSYM must be finite numbers '// &
                      'of magnitude 0 or 1e-50 .. 1e50')
            return
        end if
        if (len(range_problem(quantity_poissons_ratio, pr)) > 0) then
            call fail(error, deck, first_line, "Poisson's ratio PR = "//rtoa(pr)//' '// &
                      range_problem(quantity_poissons_ratio, pr))
            return
        end if
        if (len(range_problem(quantity_youngs_modulus, e)) > 0) then
            call fail(error, deck, first_line, "Young's modulus E = "//rtoa(e)//' '// &
                      range_problem(quantity_youngs_modulus, e))
            return
        end if

        ! PXX, PYY, PXY
        do
            call next_record(deck, 'PXX, PYY, PXY', record, first_line, error)
            if (allocated(error)) return
            read (record, *, iostat=stat, iomsg=iomsg) pxx, pyy, pxy
            if (.not. continued(deck, stat, record)) exit
        end do
        if (stat /= 0) then
            call bad_record(error, deck, first_line, 'PXX, PYY, PXY (three reals)', stat, iomsg)
            return
        end if
        if (.not. all(within_limits([pxx, pyy, pxy]))) then
            call fail(error, deck, first_line, 'PXX, PYY, PXY must be finite numbers '// &
                      'of magnitude 0 or 1e-50 .. 1e50')
            return
        end if

        model%poissons_ratio = pr
        model%youngs_modulus = e
        model%sxx = pxx
        model%syy = pyy
        model%sxy = pxy
        ! KSYM 1-4 are the codes symmetry_none, symmetry_x, symmetry_y, symmetry_both
        model%elements%symmetry%kind = ksym
        model%elements%symmetry%xsym = xsym
        model%elements%symmetry%ysym = ysym

        allocate (segments(numbs))
        do k = 1, numbs
            call read_segment(deck, k, numbs, segments(k), error)
            if (allocated(error)) return
        end do
        call build_elements(segments, model)
        call read_observations(deck, numos, model, error)
        if (allocated(error)) return

        model%length_unit = 'm'
        model%stress_unit = 'Pa'
        model%time_unit = 's'
        model%output_file = base_name(path, .false.)//'.h5'

        call check_elements(model%elements, model%fractures, error)
        if (allocated(error)) error%message = path//': '//error%message
    end subroutine read_twodd_deck

    !> Read segment record k (NUM, XBEG, YBEG, XEND, YEND, KODE, BVS, BVN) and validate it.
    subroutine read_segment(deck, k, numbs, segment, error)
        type(deck_cursor), intent(inout) :: deck
        integer, intent(in) :: k, numbs
        type(segment_record), intent(out) :: segment
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: record, what
        character(len=256) :: iomsg
        integer :: stat, first_line

        what = 'boundary segment '//itoa(k)//' of '//itoa(numbs)// &
               ' (NUM, XBEG, YBEG, XEND, YEND, KODE, BVS, BVN)'
        do
            call next_record(deck, what, record, first_line, error)
            if (allocated(error)) return
            read (record, *, iostat=stat, iomsg=iomsg) segment%num, segment%xbeg, &
                segment%ybeg, segment%xend, segment%yend, segment%kode, segment%bvs, segment%bvn
            if (.not. continued(deck, stat, record)) exit
        end do
        segment%line = first_line
        if (stat /= 0) then
            call bad_record(error, deck, first_line, what// &
                            ': NUM and KODE integers, the others reals', stat, iomsg)
            return
        end if
        associate (s => segment)
            if (s%num < 1 .or. s%num > max_count) then
                call fail(error, deck, first_line, 'segment '//itoa(k)//': NUM = '// &
                          itoa(s%num)//' must be at least 1 (the number of elements)')
            else if (s%kode < condition_traction .or. s%kode > condition_mixed_ss_un) then
                call fail(error, deck, first_line, 'segment '//itoa(k)//': KODE = '// &
                          itoa(s%kode)//' must be 1 (tractions), 2 (displacements), '// &
                          '3 (us and sigma_n) or 4 (sigma_s and un)')
            else if (.not. all(within_limits([s%xbeg, s%ybeg, s%xend, s%yend, s%bvs, &
                                               s%bvn]))) then
                call fail(error, deck, first_line, 'segment '//itoa(k)// &
                          ': coordinates and boundary values must be finite numbers '// &
                          'of magnitude 0 or 1e-50 .. 1e50')
            else if (s%xbeg == s%xend .and. s%ybeg == s%yend) then
                call fail(error, deck, first_line, 'segment '//itoa(k)// &
                          ': its ends coincide (zero length)')
            end if
        end associate
    end subroutine read_segment

    !> Elements of every segment, one fracture per segment.
    subroutine build_elements(segments, model)
        type(segment_record), intent(in) :: segments(:)
        type(model_type), intent(inout) :: model
        real(wp), allocatable :: xb(:), yb(:), xe(:), ye(:)
        integer :: k, first, last

        call allocate_elements(model%elements, sum(segments%num))
        allocate (model%fractures(size(segments)))
        last = 0
        do k = 1, size(segments)
            associate (s => segments(k))
                first = last + 1
                last = last + s%num
                call polyline_elements([s%xbeg, s%xend], [s%ybeg, s%yend], [s%num], xb, yb, &
                                       xe, ye)
                model%elements%x_begin(first:last) = xb
                model%elements%y_begin(first:last) = yb
                model%elements%x_end(first:last) = xe
                model%elements%y_end(first:last) = ye
                model%elements%fracture_id(first:last) = k
                model%elements%condition(first:last) = s%kode
                model%elements%bc_s(first:last) = s%bvs
                model%elements%bc_n(first:last) = s%bvn
                ! Component by component: gfortran 12 leaks the temporary of a structure
                ! constructor with an allocatable character component.
                model%fractures(k)%name = 'segment_'//itoa(k)
                model%fractures(k)%first_element = first
                model%fractures(k)%last_element = last
            end associate
        end do
        model%elements%mu = 0.0_wp
        model%elements%sf = 0.0_wp
        model%elements%pressure = 0.0_wp
        call compute_geometry(model%elements)
    end subroutine build_elements

    !> Observation records: lines of NUMPB interior points plus both ends.
    subroutine read_observations(deck, numos, model, error)
        type(deck_cursor), intent(inout) :: deck
        integer, intent(in) :: numos
        type(model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: record, what
        character(len=256) :: iomsg
        real(wp) :: xb, yb, xe, ye, t
        integer :: k, i, n, numpb, stat, first_line

        allocate (model%observations(numos))
        do k = 1, numos
            what = 'observation line '//itoa(k)//' of '//itoa(numos)// &
                   ' (XBEG, YBEG, XEND, YEND, NUMPB)'
            do
                call next_record(deck, what, record, first_line, error)
                if (allocated(error)) return
                read (record, *, iostat=stat, iomsg=iomsg) xb, yb, xe, ye, numpb
                if (.not. continued(deck, stat, record)) exit
            end do
            if (stat /= 0) then
                call bad_record(error, deck, first_line, what// &
                                ': four reals and an integer', stat, iomsg)
                return
            end if
            if (.not. all(within_limits([xb, yb, xe, ye]))) then
                call fail(error, deck, first_line, 'observation line '//itoa(k)// &
                          ': coordinates must be finite numbers of magnitude 0 or '// &
                          '1e-50 .. 1e50')
                return
            end if
            if (numpb < 0 .or. numpb > max_count) then
                call fail(error, deck, first_line, 'observation line '//itoa(k)// &
                          ': NUMPB = '//itoa(numpb)//' must be 0 or more '// &
                          '(the number of points between the ends)')
                return
            end if
            n = numpb + 2
            if (xb == xe .and. yb == ye) n = 1
            associate (o => model%observations(k))
                o%name = 'line_'//itoa(k)
                o%kind = observation_line
                o%nx = n
                o%ny = 1
                allocate (o%x(n), stat=stat)
                if (stat == 0) allocate (o%y(n), stat=stat)
                if (stat /= 0) then
                    call allocation_failed(error, deck%path//': observation line '//itoa(k)// &
                        ' of '//itoa(n)//' points', 2.0_wp * real_bytes * real(n, wp))
                    return
                end if
                o%x(1) = xb
                o%y(1) = yb
                do i = 2, n - 1
                    t = real(i - 1, wp) / real(n - 1, wp)
                    o%x(i) = xb + t * (xe - xb)
                    o%y(i) = yb + t * (ye - yb)
                end do
                if (n > 1) then
                    o%x(n) = xe
                    o%y(n) = ye
                end if
            end associate
        end do
    end subroutine read_observations

    ! ------------------------------------------------------------------------------------
    ! Records and messages
    ! ------------------------------------------------------------------------------------

    !> Split a text into lines (LF or CRLF; a final line without LF counts).
    pure subroutine split_lines(text, lines)
        character(len=*), intent(in) :: text
        type(deck_line), allocatable, intent(out) :: lines(:)
        integer :: start, eol, n, k

        n = 0
        do k = 1, len(text)
            if (text(k:k) == achar(10)) n = n + 1
        end do
        if (len(text) > 0) then
            if (text(len(text):len(text)) /= achar(10)) n = n + 1
        end if
        allocate (lines(max(n, 1)))
        lines(1)%text = ''
        start = 1
        do k = 1, n
            eol = index(text(start:), achar(10))
            if (eol == 0) then
                eol = len(text) + 1
            else
                eol = start + eol - 1
            end if
            lines(k)%text = text(start:eol - 1)
            if (len(lines(k)%text) > 0) then
                if (lines(k)%text(len(lines(k)%text):) == achar(13)) then
                    lines(k)%text = lines(k)%text(:len(lines(k)%text) - 1)
                end if
            end if
            start = eol + 1
        end do
    end subroutine split_lines

    !> The next non-blank line after the cursor; an error when the deck has ended.
    subroutine next_record(deck, what, record, first_line, error)
        type(deck_cursor), intent(inout) :: deck
        !> What the record holds, for the message
        character(len=*), intent(in) :: what
        character(len=:), allocatable, intent(out) :: record
        integer, intent(out) :: first_line
        type(error_type), allocatable, intent(out) :: error

        do while (deck%last < size(deck%lines))
            deck%last = deck%last + 1
            if (len_trim(deck%lines(deck%last)%text) > 0) then
                record = deck%lines(deck%last)%text
                first_line = deck%last
                return
            end if
        end do
        first_line = size(deck%lines) + 1
        record = ''
        call set_error(error, exit_bad_input, deck%path//': line '//itoa(first_line)// &
                       ': the deck ends too early: expected '//what)
    end subroutine next_record

    !> After a list-directed read of a record: true when it ran out of values and another
    !> non-blank line follows, which is then appended (a record may span lines).
    logical function continued(deck, stat, record)
        type(deck_cursor), intent(inout) :: deck
        integer, intent(in) :: stat
        character(len=:), allocatable, intent(inout) :: record
        integer :: k

        continued = .false.
        if (stat >= 0) return
        do k = deck%last + 1, size(deck%lines)
            if (len_trim(deck%lines(k)%text) > 0) then
                record = record//' '//deck%lines(k)%text
                deck%last = k
                continued = .true.
                return
            end if
        end do
    end function continued

    !> Error for a record that cannot be read.
    subroutine bad_record(error, deck, line, what, stat, iomsg)
        type(error_type), allocatable, intent(out) :: error
        type(deck_cursor), intent(in) :: deck
        integer, intent(in) :: line, stat
        character(len=*), intent(in) :: what, iomsg

        if (stat < 0) then
            call fail(error, deck, line, 'too few values for '//what// &
                      ' (the deck ends before the record is complete)')
        else
            call fail(error, deck, line, 'cannot read '//what//': a value is not a number '// &
                      'of the expected type (gfortran: '//trim(iomsg)//'): "'// &
                      trim(deck%lines(line)%text)//'"')
        end if
    end subroutine bad_record

    !> Error with the file name and line number.
    subroutine fail(error, deck, line, message)
        type(error_type), allocatable, intent(out) :: error
        type(deck_cursor), intent(in) :: deck
        integer, intent(in) :: line
        character(len=*), intent(in) :: message

        call set_error(error, exit_bad_input, deck%path//': line '//itoa(line)//': '//message)
    end subroutine fail

end module ddc_input_twodd_deck
