!> Result tables in the layout of the classic TWODD print (Crouch & Starfield 1983, ch. 5),
!> as produced by a double-precision TWODD build (tests/reference/twodd/
!> output_double_precision): a header block, the BOUNDARY ELEMENT DATA table, the
!> displacements and stresses at the element midpoints, then the observation points.
!>
!> Headings, column order and formats follow that print line for line (results in
!> es24.15), so `diff` against an old printout shows only differing numbers. One
!> addition: TWODD skips observation points within one element length of an element
!> centre; ddc2d computes them and appends ` *` to their row (` **` for a point on an
!> element or at its end, where the values are NaN), with a footnote after the table.
!> Models with conditions TWODD does not have (namelist input: KODE 5 contact, 6 prescribed
!> DDs) get a footnote after BOUNDARY ELEMENT DATA saying what those codes are, and with
!> contact elements a STATE column (free, stick, slip, open) after SIGMA-N; TWODD decks
!> keep the classic layout.
!> The file is written under a temporary name and renamed at the end (ddc_output_atomic).
module ddc_output_twodd_tables
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_io_failure
    use ddc_model_types, only: model_type, symmetry_x, symmetry_y, symmetry_both, &
        condition_mixed_ss_un, condition_contact, condition_prescribed_dd
    use ddc_model_results, only: model_results, point_near, point_on_element, state_names, &
        point_outside_body
    use ddc_output_atomic, only: partial_name, publish_file, remove_file, resolve_target, &
        explain_write_failure
    use ddc_constants, only: pi
    implicit none
    private

    public :: write_twodd_tables

contains

    !> Write the TWODD-style result tables of a solved model to path (atomically).
    subroutine write_twodd_tables(path, model, results, error)
        !> Path of the table file; replaced if it exists
        character(len=*), intent(in) :: path
        !> The model that was solved
        type(model_type), intent(in) :: model
        !> Its results (elements, fields)
        type(model_results), intent(in) :: results
        !> Allocated (exit_io_failure) when the file cannot be written
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: temporary, final_path
        character(len=512) :: iomsg
        integer :: unit, stat, close_stat
        integer(int64) :: written, size

        call resolve_target(path, final_path, error)
        if (allocated(error)) return
        temporary = partial_name(final_path)
        ! Stream access: its position counts the bytes written, to be checked against the
        ! file's size after closing (gfortran does not report a full disk on buffered writes).
        open (newunit=unit, file=temporary, status='replace', action='write', &
              form='formatted', access='stream', iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call set_error(error, exit_io_failure, 'cannot create '//temporary//': '// &
                           trim(iomsg))
            return
        end if
        call write_header(unit, model, stat, iomsg)
        if (stat == 0) call write_element_data(unit, model, stat, iomsg)
        if (stat == 0) call write_midpoints(unit, model, results, stat, iomsg)
        if (stat == 0) call write_points(unit, model, results, stat, iomsg)
        if (stat /= 0) then
            call set_error(error, exit_io_failure, 'cannot write '//temporary//': '// &
                           trim(iomsg))
            call explain_write_failure(final_path, temporary, error)
            ! Best effort: the write's failure is the one reported.
            close (unit, status='delete', iostat=close_stat)
            if (close_stat /= 0) call remove_file(temporary)
            return
        end if
        inquire (unit=unit, pos=written)
        close (unit, iostat=stat, iomsg=iomsg)
        size = -1_int64
        if (stat == 0) inquire (file=temporary, size=size, iostat=stat, iomsg=iomsg)
        if (stat == 0 .and. size /= written - 1_int64) then
            stat = 1
            write (iomsg, '(a,i0,a,i0,a)') 'only ', size, ' of its ', written - 1_int64, &
                ' bytes reached the disk'
        end if
        if (stat /= 0) then
            call set_error(error, exit_io_failure, 'cannot close '//temporary//': '// &
                           trim(iomsg))
            call explain_write_failure(final_path, temporary, error)
            call remove_file(temporary)
            return
        end if
        call publish_file(temporary, final_path, error)
        if (allocated(error)) call remove_file(temporary)
    end subroutine write_twodd_tables

    !> Title, counts, symmetry, elastic constants and field stress.
    ! allow(C072, C181): iomsg is the caller's buffer for the writes' iomsg=; stat is returned
    subroutine write_header(unit, model, stat, iomsg)
        integer, intent(in) :: unit
        type(model_type), intent(in) :: model
        integer, intent(out) :: stat
        character(len=*), intent(inout) :: iomsg
        integer :: nobs
        character(len=80) :: title

        nobs = 0
        if (allocated(model%observations)) nobs = size(model%observations)
        title = ''
        if (allocated(model%title)) title = model%title
        write (unit, '(a/25x,a80//)', iostat=stat, iomsg=iomsg) '1', title
        if (stat /= 0) return
        write (unit, '(a,i3/)', iostat=stat, iomsg=iomsg) ' NUMBER OF STRAIGHT-LINE '// &
            'SEGMENTS (EACH CONTAINING AT  LEAST ONE BOUNDARY ELEMENT) USED TO DEFINE '// &
            'BOUNDARIES =', size(model%fractures)
        if (stat /= 0) return
        write (unit, '(a,i3/)', iostat=stat, iomsg=iomsg) ' NUMBER OF STRAIGHT-LINE '// &
            'SEGMENTS USED TO SPECIFY OTHER LOCATION  (I.E., NOT ON A BOUNDARY) WHERE '// &
            'RESULTS ARE TO BE FOUND =', nobs
        if (stat /= 0) return
        select case (model%elements%symmetry%kind)
        case (symmetry_x)
            write (unit, '(a,es11.4,a/)', iostat=stat, iomsg=iomsg) ' THE LINE X =', &
                model%elements%symmetry%xsym, ' IS A LINE OF SYMMETRY.'
        case (symmetry_y)
            write (unit, '(a,es11.4,a/)', iostat=stat, iomsg=iomsg) ' THE LINE Y =', &
                model%elements%symmetry%ysym, ' IS A LINE OF SYMMETRY.'
        case (symmetry_both)
            write (unit, '(a,es11.4,a,es11.4,a/)', iostat=stat, iomsg=iomsg) &
                ' THE LINES X =', model%elements%symmetry%xsym, ' AND Y =', &
                model%elements%symmetry%ysym, &
                ' ARE LINES OF SYMMETRY.'
        case default
            write (unit, '(a/)', iostat=stat, iomsg=iomsg) ' NO SYMMETRY CONDITIONS IMPOSED.'
        end select
        if (stat /= 0) return
        write (unit, '(a,f6.2//a,e11.4//a,e20.4//a,e20.4//a,e11.4)', iostat=stat, &
               iomsg=iomsg) &
            " POISSON'S RATIO =", model%poissons_ratio, &
            " YOUNG'S MODULUS =", model%youngs_modulus, &
            ' XX-COMPONENT OF FIELD STRESS =', model%sxx, &
            ' YY-COMPONENT OF FIELD STRESS =', model%syy, &
            ' XY-COMPONENT OF FIELD STRESS =', model%sxy
    end subroutine write_header

    !> Element number, KODE, centre, length, angle [degrees] and the given values.
    ! allow(C072, C181): iomsg is the caller's buffer for the writes' iomsg=; stat is returned
    subroutine write_element_data(unit, model, stat, iomsg)
        integer, intent(in) :: unit
        type(model_type), intent(in) :: model
        integer, intent(out) :: stat
        character(len=*), intent(inout) :: iomsg
        integer :: i

        write (unit, '(a/a//a/)', iostat=stat, iomsg=iomsg) '1', &
            '     BOUNDARY ELEMENT DATA.', &
            '  ELEMENT      KODE  X (CENTER)  Y (CENTER)      LENGTH      ANGLE  '// &
            'US OR SIGMA_   UN OR SIGMA_N'
        if (stat /= 0) return
        associate (e => model%elements)
            do i = 1, e%n
                write (unit, '(2i9,3es24.15,es12.4,2es15.6)', iostat=stat, iomsg=iomsg) &
                    i, e%condition(i), e%x_mid(i), e%y_mid(i), 2.0_wp * e%half_length(i), &
                    atan2(e%sin_beta(i), e%cos_beta(i)) * 180.0_wp / pi, e%bc_s(i), e%bc_n(i)
                if (stat /= 0) return
            end do
            if (any(e%condition > condition_mixed_ss_un)) write (unit, '(a)', iostat=stat, &
                iomsg=iomsg) ''
            if (stat == 0 .and. any(e%condition == condition_contact)) write (unit, '(a)', &
                iostat=stat, iomsg=iomsg) ' KODE 5: FRICTIONAL CONTACT (NOT IN TWODD; MU, '// &
                'SF AND PRESSURE ARE IN THE HDF5 OUTPUT), ITS STATE IN THE LAST COLUMN OF '// &
                'THE MIDPOINT TABLE.'
            if (stat == 0 .and. any(e%condition == condition_prescribed_dd)) write (unit, &
                '(a)', iostat=stat, iomsg=iomsg) ' KODE 6: PRESCRIBED DS AND DN (NOT IN '// &
                'TWODD), GIVEN IN THE LAST TWO COLUMNS.'
        end associate
    end subroutine write_element_data

    !> DS, US(-), US(+), DN, UN(-), UN(+), UX(-), UY(-), UX(+), UY(+), SIGMA-S, SIGMA-N.
    ! allow(C072): iomsg is the caller's buffer for the write statements' iomsg=
    subroutine write_midpoints(unit, model, results, stat, iomsg)
        integer, intent(in) :: unit
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: results
        integer, intent(out) :: stat
        character(len=*), intent(inout) :: iomsg
        character(len=:), allocatable :: state_heading
        integer :: i
        logical :: contact

        contact = any(model%elements%condition == condition_contact)
        state_heading = trim(merge('     STATE', '          ', contact))
        write (unit, '(a/a//a/)', iostat=stat, iomsg=iomsg) '1', &
            '     DISPLACEMENTS AND STRESSES AT MIDPOINTS OF BO UNDARY ELEMENTS.', &
            '   ELEMENT        DS     US(-)     US(+)         DN     UN(-)     UN(+)     '// &
            'UX(-)     UY(-)     UX(+)     UY( +)   SIGMA-S   SIGMA-N'//state_heading
        if (stat /= 0) return
        associate (e => model%elements, r => results%elements)
            do i = 1, e%n
                associate (c => e%cos_beta(i), s => e%sin_beta(i))
                    write (unit, '(i10,12es24.15,a)', iostat=stat, iomsg=iomsg) i, r%ds(i), &
                        r%us_minus(i), r%us_plus(i), r%dn(i), r%un_minus(i), r%un_plus(i), &
                        r%us_minus(i) * c - r%un_minus(i) * s, &
                        r%us_minus(i) * s + r%un_minus(i) * c, &
                        r%us_plus(i) * c - r%un_plus(i) * s, &
                        r%us_plus(i) * s + r%un_plus(i) * c, &
                        r%shear_traction(i), r%normal_traction(i), &
                        trim(merge('  '//state_names(r%state(i)), repeat(' ', 7), contact))
                end associate
                if (stat /= 0) return
            end do
        end associate
    end subroutine write_midpoints

    !> Every observation point, numbered on through all sets, with its flag mark.
    ! allow(C072, C181): iomsg is the caller's buffer for the writes' iomsg=; stat is returned
    subroutine write_points(unit, model, results, stat, iomsg)
        integer, intent(in) :: unit
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: results
        integer, intent(out) :: stat
        character(len=*), intent(inout) :: iomsg
        integer :: k, i, number
        logical :: flagged

        write (unit, '(a/a//a/)', iostat=stat, iomsg=iomsg) '1', &
            '     DISPLACEMENTS AND STRESSES AT SPECIFIED POINT S IN THE BODY.', &
            '    POINT    X CO-ORD    Y CO-ORD          UX           UY      SIGXX      '// &
            'SIGYY      SIGXY'
        if (stat /= 0) return
        if (.not. allocated(results%fields)) return
        number = 0
        flagged = .false.
        do k = 1, size(results%fields)
            associate (o => model%observations(k), f => results%fields(k))
                do i = 1, size(o%x)
                    number = number + 1
                    write (unit, '(i9,7es24.15,a)', iostat=stat, iomsg=iomsg) number, o%x(i), &
                        o%y(i), f%ux(i), f%uy(i), f%sxx(i), f%syy(i), f%sxy(i), &
                        trim(mark(f%flag(i)))
                    if (stat /= 0) return
                    flagged = flagged .or. f%flag(i) >= point_near
                end do
            end associate
        end do
        if (flagged) then
            write (unit, '(/a/a)', iostat=stat, iomsg=iomsg) &
                '  *  WITHIN ONE ELEMENT LENGTH OF AN ELEMENT CENTRE: TWODD SKIPS SUCH '// &
                'POINTS; DDC2D COMPUTES THEM (REDUCED ACCURACY).', &
                ' **  ON AN ELEMENT OR AT ITS END: THE FIELD IS UNDEFINED THERE (NaN).'
        end if
    end subroutine write_points

    !> The mark appended to a point's row for its flag.
    pure function mark(flag) result(text)
        integer, intent(in) :: flag
        character(len=3) :: text

        select case (flag)
        case (point_near)
            text = '  *'
        case (point_on_element)
            text = ' **'
        case (point_outside_body)
            text = ' --'
        case default
            text = ''
        end select
    end function mark

end module ddc_output_twodd_tables
