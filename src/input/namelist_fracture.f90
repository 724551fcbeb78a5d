!> The &fracture groups of a namelist input file (docs/input-reference.md#fracture): one per
!> fracture, given as a polyline (x, y, elements per segment, per-segment values) or as a CSV of
!> elements (elements_file); validated and expanded to elements.
module ddc_input_namelist_fracture
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_types, only: condition_names, condition_contact, no_residual_drop, rigid_joint
    use ddc_model_limits, only: range_problem, quantity_non_negative, quantity_positive, &
                                within_limits
    use ddc_text, only: itoa, rtoa, lower, find_name, quoted_list, prefix_lines, counted
    use ddc_input_text_file, only: resolve
    use ddc_input_csv, only: read_csv
    use ddc_mesh_polyline, only: polyline_elements, expand_per_segment
    use ddc_input_namelist_groups, only: group_record, message_list, add, group_label, g_fracture
    use ddc_input_namelist_diagnosis, only: report_malformed
    use ddc_input_namelist_values, only: unset_real, unset_integer, text_length, count_given, &
        count_given_integers, check_length, check_range, broadcast, broadcast_integers, &
        default_name
    implicit none
    private

    public :: fracture_input, read_fracture_groups, max_vertices, max_elements

    !> Largest number of polyline vertices of one &fracture (size of the namelist arrays)
    integer, parameter :: max_vertices = 100000
    !> Largest number of elements in a model
    integer, parameter :: max_elements = 1000000

    !> One fracture as read, expanded to elements (valid when its group had no problem).
    type :: fracture_input
        !> Name given by the user, or fracture_<k>
        character(len=:), allocatable :: name
        !> Group label for messages
        character(len=:), allocatable :: label
        !> The group had no problem: the arrays below are set
        logical :: valid = .false.
        !> Condition code of every element (ddc_model_types)
        integer :: condition = condition_contact
        !> Element end points [length unit], shape (elements)
        real(wp), allocatable :: x_begin(:), y_begin(:), x_end(:), y_end(:)
        !> Per-element values (docs/input-reference.md#fracture), shape (elements)
        real(wp), allocatable :: mu(:), sf(:), pressure(:), bc_s(:), bc_n(:)
        !> Tensile strength and residual cohesion (no_residual_drop where not given),
        !> shape (elements) [stress unit]
        real(wp), allocatable :: tensile_strength(:), sf_residual(:)
        !> Dynamic friction (no_residual_drop where not given) [-] and slip-weakening
        !> distance [length unit], shape (elements)
        real(wp), allocatable :: mu_dynamic(:), slip_weakening_distance(:)
        !> Opening over which the tensile strength falls to 0 [length unit], shape (elements)
        real(wp), allocatable :: opening_weakening_distance(:)
        !> Joint stiffnesses (rigid_joint where not given) [stress unit / length unit],
        !> shape (elements)
        real(wp), allocatable :: shear_stiffness(:), normal_stiffness(:)
    end type fracture_input

contains

    !> &fracture name, x, y, elements, mu, sf, pressure, condition, bc_s, bc_n,
    !> elements_file, tensile_strength, sf_residual, mu_dynamic, slip_weakening_distance,
    !> shear_stiffness, normal_stiffness, opening_weakening_distance / (repeated, one per
    !> fracture)
    subroutine read_fracture_groups(unit, text, path, dir, info, fractures, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path, dir
        type(group_record), intent(in) :: info
        type(fracture_input), allocatable, intent(out) :: fractures(:)
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name, condition, elements_file
        real(wp), allocatable :: x(:), y(:), mu(:), sf(:), pressure(:), bc_s(:), bc_n(:)
        real(wp), allocatable :: tensile_strength(:), sf_residual(:), seg_t(:), seg_sfr(:)
        real(wp), allocatable :: mu_dynamic(:), slip_weakening_distance(:), seg_mud(:), seg_dc(:)
        real(wp), allocatable :: shear_stiffness(:), normal_stiffness(:), seg_ks(:), seg_kn(:)
        real(wp), allocatable :: opening_weakening_distance(:), seg_do(:)
        logical, allocatable :: csv_given(:)
        integer, allocatable :: elements(:)
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix, csv_path
        real(wp), allocatable :: rows(:,:), seg_mu(:), seg_sf(:), seg_pressure(:), &
                                 seg_bc_s(:), seg_bc_n(:)
        integer, allocatable :: counts(:), row_lines(:)
        type(error_type), allocatable :: csv_error
        integer :: stat, k, i, nx, ny, ne, nmu, nsf, npr, nbs, nbn, nseg, nbefore, cond
        integer :: nt, nsr, nmd, ndc, nks, nkn, ndo
        logical :: from_csv, geometry_ok
        namelist /fracture/ name, x, y, elements, mu, sf, pressure, condition, bc_s, bc_n, &
            elements_file, tensile_strength, sf_residual, mu_dynamic, slip_weakening_distance, &
            shear_stiffness, normal_stiffness, opening_weakening_distance

        allocate (fractures(info%count))
        if (info%count == 0) return
        allocate (x(max_vertices), y(max_vertices), mu(max_vertices), sf(max_vertices), &
                  pressure(max_vertices), bc_s(max_vertices), bc_n(max_vertices), &
                  elements(max_vertices), tensile_strength(max_vertices), &
                  sf_residual(max_vertices), mu_dynamic(max_vertices), &
                  slip_weakening_distance(max_vertices), shear_stiffness(max_vertices), &
                  normal_stiffness(max_vertices), opening_weakening_distance(max_vertices))
        rewind (unit)
        do k = 1, info%count
            name = ''
            condition = 'contact'
            elements_file = ''
            x = unset_real
            y = unset_real
            mu = unset_real
            sf = unset_real
            pressure = unset_real
            bc_s = unset_real
            bc_n = unset_real
            tensile_strength = unset_real
            sf_residual = unset_real
            mu_dynamic = unset_real
            slip_weakening_distance = unset_real
            shear_stiffness = unset_real
            normal_stiffness = unset_real
            opening_weakening_distance = unset_real
            elements = unset_integer
            read (unit, nml=fracture, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_fracture, info, k, stat, iomsg, messages)
                exit
            end if
            fractures(k)%name = default_name(name, 'fracture', k)
            fractures(k)%label = group_label(g_fracture, k, info%lines(k), trim(adjustl(name)))
            prefix = path//': '//fractures(k)%label//': '
            nbefore = messages%n

            nx = count_given(x, 'x', prefix, messages)
            ny = count_given(y, 'y', prefix, messages)
            ne = count_given_integers(elements, 'elements', prefix, messages)
            nmu = count_given(mu, 'mu', prefix, messages)
            nsf = count_given(sf, 'sf', prefix, messages)
            npr = count_given(pressure, 'pressure', prefix, messages)
            nbs = count_given(bc_s, 'bc_s', prefix, messages)
            nbn = count_given(bc_n, 'bc_n', prefix, messages)
            nt = count_given(tensile_strength, 'tensile_strength', prefix, messages)
            nsr = count_given(sf_residual, 'sf_residual', prefix, messages)
            nmd = count_given(mu_dynamic, 'mu_dynamic', prefix, messages)
            ndc = count_given(slip_weakening_distance, 'slip_weakening_distance', prefix, messages)
            nks = count_given(shear_stiffness, 'shear_stiffness', prefix, messages)
            nkn = count_given(normal_stiffness, 'normal_stiffness', prefix, messages)
            ndo = count_given(opening_weakening_distance, 'opening_weakening_distance', prefix, &
                              messages)

            cond = find_name(lower(trim(adjustl(condition))), condition_names)
            if (cond == 0) then
                call add(messages, prefix//"condition = '"//trim(adjustl(condition))// &
                         "' is not one of "//quoted_list(condition_names))
            end if
            from_csv = len_trim(elements_file) > 0
            geometry_ok = .false.
            nseg = 0
            if (from_csv) then
                if (nx > 0 .or. ny > 0 .or. ne > 0) then
                    call add(messages, prefix//'give either x, y and elements or '// &
                             'elements_file, not both')
                end if
                if (nmu > 0 .or. nsf > 0 .or. npr > 0 .or. nt > 0 .or. nsr > 0 .or. &
                    nmd > 0 .or. ndc > 0 .or. nks > 0 .or. nkn > 0 .or. ndo > 0) then
                    call add(messages, prefix//'mu, sf, pressure and the strength laws come '// &
                             'from elements_file; do not give them in the group as well')
                end if
                csv_path = resolve(dir, trim(adjustl(elements_file)))
                call read_csv(csv_path, [character(len=8) :: 'x_begin', 'y_begin', 'x_end', &
                              'y_end', 'mu', 'sf', 'pressure'], rows, csv_error, row_lines, &
                              [character(len=26) :: 'tensile_strength', 'sf_residual', &
                              'mu_dynamic', 'slip_weakening_distance', 'shear_stiffness', &
                              'normal_stiffness', 'opening_weakening_distance'], &
                              csv_given, most_rows=max_elements)
                if (allocated(csv_error)) then
                    call add(messages, prefix_lines(prefix//'elements_file: ', csv_error%message))
                    deallocate (csv_error)
                else
                    nseg = size(rows, 2)
                    geometry_ok = nseg <= max_elements
                    if (.not. geometry_ok) then
                        call add(messages, prefix//'elements_file '//csv_path//' has '// &
                                 itoa(nseg)//' rows; at most '//itoa(max_elements)//' elements')
                    end if
                    do i = 1, nseg
                        if (len(range_problem(quantity_non_negative, rows(5, i))) > 0) then
                            call add(messages, prefix//'elements_file '//csv_path//' line '// &
                                     itoa(row_lines(i))//': mu = '//rtoa(rows(5, i))//' '// &
                                     range_problem(quantity_non_negative, rows(5, i)))
                        end if
                        if (len(range_problem(quantity_non_negative, rows(6, i))) > 0) then
                            call add(messages, prefix//'elements_file '//csv_path//' line '// &
                                     itoa(row_lines(i))//': sf = '//rtoa(rows(6, i))//' '// &
                                     range_problem(quantity_non_negative, rows(6, i)))
                        end if
                        if (csv_given(1)) call check_law_row(8, 'tensile_strength')
                        if (csv_given(2)) call check_law_row(9, 'sf_residual')
                        if (csv_given(3)) call check_law_row(10, 'mu_dynamic')
                        if (csv_given(4)) call check_law_row(11, 'slip_weakening_distance')
                        if (csv_given(5)) call check_law_row(12, 'shear_stiffness')
                        if (csv_given(6)) call check_law_row(13, 'normal_stiffness')
                        if (csv_given(7)) call check_law_row(14, 'opening_weakening_distance')
                    end do
                    if (.not. csv_given(1)) rows(8, :) = 0.0_wp
                    if (.not. csv_given(2)) rows(9, :) = no_residual_drop
                    if (.not. csv_given(3)) rows(10, :) = no_residual_drop
                    if (.not. csv_given(4)) rows(11, :) = 0.0_wp
                    if (.not. csv_given(5)) rows(12, :) = rigid_joint
                    if (.not. csv_given(6)) rows(13, :) = rigid_joint
                    if (.not. csv_given(7)) rows(14, :) = 0.0_wp
                end if
            else
                if (nx /= ny) then
                    call add(messages, prefix//'x has '//counted(nx, 'value', 'values')// &
                             ' but y has '//itoa(ny)//'; give one x and one y per vertex')
                else if (nx < 2) then
                    call add(messages, prefix//'x and y give '// &
                             counted(nx, 'vertex', 'vertices')//'; a fracture needs at '// &
                             'least 2 (or an elements_file)')
                else
                    nseg = nx - 1
                    geometry_ok = .true.
                end if
                if (ne == 0) then
                    call add(messages, prefix//'elements is required (the number of '// &
                             'elements on each segment)')
                    geometry_ok = .false.
                else if (geometry_ok) then
                    geometry_ok = check_length(ne, nseg, 'elements', prefix, messages)
                end if
                if (geometry_ok) then
                    counts = broadcast_integers(elements(1:ne), nseg)
                    do i = 1, ne
                        if (elements(i) < 1) then
                            call add(messages, prefix//'elements('//itoa(i)//') = '// &
                                     itoa(elements(i))//' must be at least 1')
                            geometry_ok = .false.
                        else if (elements(i) > max_elements) then
                            call add(messages, prefix//'elements('//itoa(i)//') = '// &
                                     itoa(elements(i))//' is more than the '// &
                                     itoa(max_elements)//' elements a model may have')
                            geometry_ok = .false.
                        end if
                    end do
                    if (geometry_ok) then
                        if (sum(real(counts, wp)) > real(max_elements, wp)) then
                            call add(messages, prefix//'elements give more than the '// &
                                     itoa(max_elements)//' elements a model may have')
                            geometry_ok = .false.
                        end if
                    end if
                end if
            end if

            if (cond == condition_contact) then
                if (.not. from_csv) then
                    if (nmu == 0) then
                        call add(messages, prefix//"mu is required for condition 'contact'")
                    end if
                    call check_range(mu(1:nmu), 'mu', quantity_non_negative, prefix, messages)
                    call check_range(sf(1:nsf), 'sf', quantity_non_negative, prefix, messages)
                    call check_range(tensile_strength(1:nt), 'tensile_strength', &
                                     quantity_non_negative, prefix, messages)
                    call check_range(sf_residual(1:nsr), 'sf_residual', quantity_non_negative, &
                                     prefix, messages)
                    call check_range(mu_dynamic(1:nmd), 'mu_dynamic', quantity_non_negative, &
                                     prefix, messages)
                    call check_range(slip_weakening_distance(1:ndc), 'slip_weakening_distance', &
                                     quantity_non_negative, prefix, messages)
                    call check_range(opening_weakening_distance(1:ndo), &
                                     'opening_weakening_distance', quantity_non_negative, &
                                     prefix, messages)
                    call check_range(shear_stiffness(1:nks), 'shear_stiffness', &
                                     quantity_positive, prefix, messages)
                    call check_range(normal_stiffness(1:nkn), 'normal_stiffness', &
                                     quantity_positive, prefix, messages)
                end if
                if (nbs > 0 .or. nbn > 0) then
                    call add(messages, prefix//'bc_s and bc_n are for the TWODD-style '// &
                             "conditions, not for condition 'contact'")
                end if
            else if (cond /= 0) then
                if (.not. from_csv .and. (nmu > 0 .or. nsf > 0 .or. npr > 0 .or. nt > 0 .or. &
                    nsr > 0 .or. nmd > 0 .or. ndc > 0 .or. nks > 0 .or. nkn > 0 .or. &
                    ndo > 0)) then
                    call add(messages, prefix//"mu, sf, pressure and the strength laws are "// &
                             "for condition "// &
                             "'contact', not for condition '"//trim(condition_names(cond))//"'")
                end if
            end if

            if (geometry_ok) then
                if (.not. from_csv) then
                    if (check_length(nmu, nseg, 'mu', prefix, messages)) then
                        seg_mu = broadcast(mu(1:nmu), nseg, 0.0_wp)
                    end if
                    if (check_length(nsf, nseg, 'sf', prefix, messages)) then
                        seg_sf = broadcast(sf(1:nsf), nseg, 0.0_wp)
                    end if
                    if (check_length(npr, nseg, 'pressure', prefix, messages)) then
                        seg_pressure = broadcast(pressure(1:npr), nseg, 0.0_wp)
                    end if
                    if (check_length(nt, nseg, 'tensile_strength', prefix, messages)) then
                        seg_t = broadcast(tensile_strength(1:nt), nseg, 0.0_wp)
                    end if
                    if (check_length(nsr, nseg, 'sf_residual', prefix, messages)) then
                        seg_sfr = broadcast(sf_residual(1:nsr), nseg, no_residual_drop)
                        if (allocated(seg_sf)) call check_residual(seg_sf, seg_sfr, &
                                                                   'segment', 'sf')
                    end if
                    if (check_length(nmd, nseg, 'mu_dynamic', prefix, messages)) then
                        seg_mud = broadcast(mu_dynamic(1:nmd), nseg, no_residual_drop)
                        if (allocated(seg_mu)) call check_residual(seg_mu, seg_mud, &
                                                                   'segment', 'mu')
                    end if
                    if (check_length(ndc, nseg, 'slip_weakening_distance', prefix, &
                                     messages)) then
                        seg_dc = broadcast(slip_weakening_distance(1:ndc), nseg, 0.0_wp)
                    end if
                    if (check_length(ndo, nseg, 'opening_weakening_distance', prefix, &
                                     messages)) then
                        seg_do = broadcast(opening_weakening_distance(1:ndo), nseg, 0.0_wp)
                    end if
                    if (check_length(nks, nseg, 'shear_stiffness', prefix, messages)) then
                        seg_ks = broadcast(shear_stiffness(1:nks), nseg, rigid_joint)
                    end if
                    if (check_length(nkn, nseg, 'normal_stiffness', prefix, messages)) then
                        seg_kn = broadcast(normal_stiffness(1:nkn), nseg, rigid_joint)
                    end if
                end if
                if (check_length(nbs, nseg, 'bc_s', prefix, messages)) then
                    seg_bc_s = broadcast(bc_s(1:nbs), nseg, 0.0_wp)
                end if
                if (check_length(nbn, nseg, 'bc_n', prefix, messages)) then
                    seg_bc_n = broadcast(bc_n(1:nbn), nseg, 0.0_wp)
                end if
            end if
            if (messages%n > nbefore) cycle

            ! Valid: expand to elements.
            fractures(k)%valid = .true.
            fractures(k)%condition = cond
            if (from_csv) then
                fractures(k)%x_begin = rows(1, :)
                fractures(k)%y_begin = rows(2, :)
                fractures(k)%x_end = rows(3, :)
                fractures(k)%y_end = rows(4, :)
                fractures(k)%mu = rows(5, :)
                fractures(k)%sf = rows(6, :)
                fractures(k)%pressure = rows(7, :)
                fractures(k)%tensile_strength = rows(8, :)
                fractures(k)%sf_residual = rows(9, :)
                fractures(k)%mu_dynamic = rows(10, :)
                fractures(k)%slip_weakening_distance = rows(11, :)
                fractures(k)%shear_stiffness = rows(12, :)
                fractures(k)%normal_stiffness = rows(13, :)
                fractures(k)%opening_weakening_distance = rows(14, :)
                fractures(k)%bc_s = seg_bc_s
                fractures(k)%bc_n = seg_bc_n
            else
                call polyline_elements(x(1:nx), y(1:ny), counts, fractures(k)%x_begin, &
                                       fractures(k)%y_begin, fractures(k)%x_end, &
                                       fractures(k)%y_end)
                fractures(k)%mu = expand_per_segment(seg_mu, counts)
                fractures(k)%sf = expand_per_segment(seg_sf, counts)
                fractures(k)%pressure = expand_per_segment(seg_pressure, counts)
                fractures(k)%tensile_strength = expand_per_segment(seg_t, counts)
                fractures(k)%sf_residual = expand_per_segment(seg_sfr, counts)
                fractures(k)%mu_dynamic = expand_per_segment(seg_mud, counts)
                fractures(k)%slip_weakening_distance = expand_per_segment(seg_dc, counts)
                fractures(k)%shear_stiffness = expand_per_segment(seg_ks, counts)
                fractures(k)%normal_stiffness = expand_per_segment(seg_kn, counts)
                fractures(k)%opening_weakening_distance = expand_per_segment(seg_do, counts)
                fractures(k)%bc_s = expand_per_segment(seg_bc_s, counts)
                fractures(k)%bc_n = expand_per_segment(seg_bc_n, counts)
            end if
        end do

    contains

        !> The law in column c of CSV row i is not negative (a stiffness positive; and
        !> sf_residual <= sf, mu_dynamic <= mu).
        subroutine check_law_row(c, name)
            integer, intent(in) :: c
            character(len=*), intent(in) :: name
            integer :: quantity

            quantity = quantity_non_negative
            if (c == 12 .or. c == 13) quantity = quantity_positive
            if (len(range_problem(quantity, rows(c, i))) > 0) then
                call add(messages, prefix//'elements_file '//csv_path//' line '// &
                         itoa(row_lines(i))//': '//name//' = '//rtoa(rows(c, i))//' '// &
                         range_problem(quantity, rows(c, i)))
            else if (c == 9) then
                call check_residual(rows(6, i:i), rows(9, i:i), 'elements_file '//csv_path// &
                                    ' line '//itoa(row_lines(i))//':', 'sf')
            else if (c == 10) then
                call check_residual(rows(5, i:i), rows(10, i:i), 'elements_file '//csv_path// &
                                    ' line '//itoa(row_lines(i))//':', 'mu')
            end if
        end subroutine check_law_row

        !> A residual cohesion (intact = 'sf') or a dynamic friction (intact = 'mu') above the
        !> intact one is a mistake, not a strengthening.
        subroutine check_residual(intact, residual, where, intact_name)
            real(wp), intent(in) :: intact(:), residual(:)
            character(len=*), intent(in) :: where, intact_name
            character(len=:), allocatable :: name, what
            integer :: j

            name = 'sf_residual'
            what = ' (the cohesion after slip must not exceed the intact one)'
            if (intact_name == 'mu') then
                name = 'mu_dynamic'
                what = ' (the friction after slip must not exceed the static one)'
            end if
            do j = 1, size(residual)
                ! NaN and Inf are reported by count_given; compared here they would trap
                if (.not. (within_limits(residual(j)) .and. within_limits(intact(j)))) cycle
                if (residual(j) > intact(j) .and. residual(j) < no_residual_drop) then
                    if (where == 'segment') then
                        call add(messages, prefix//name//' = '//rtoa(residual(j))// &
                                 ' exceeds '//intact_name//' = '//rtoa(intact(j))// &
                                 ' on segment '//itoa(j)//what)
                    else
                        call add(messages, prefix//where//' '//name//' = '// &
                                 rtoa(residual(j))//' exceeds '//intact_name//' = '// &
                                 rtoa(intact(j))//what)
                    end if
                    return
                end if
            end do
        end subroutine check_residual

    end subroutine read_fracture_groups

end module ddc_input_namelist_fracture
