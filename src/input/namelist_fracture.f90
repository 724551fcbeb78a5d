!> The &fracture groups of a namelist input file (docs/input-reference.md#fracture): one per
!> fracture, given as a polyline (x, y, elements per segment, per-segment values) or as a CSV of
!> elements (elements_file); validated and expanded to elements.
module ddc_input_namelist_fracture
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_types, only: condition_names, condition_contact, no_residual_drop, &
        strength_law_count, condition_rate_state
    use ddc_model_rate_state, only: rate_state_value, rate_state_count, rate_state_values
    use ddc_model_laws, only: strength_law, strength_laws, at_most_rule
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
        default_name, check_scalar
    implicit none
    private

    public :: fracture_input, read_fracture_groups, max_vertices, max_elements

    !> Largest number of polyline vertices of one &fracture (size of the namelist arrays)
    integer, parameter :: max_vertices = 100000
    !> Largest number of elements in a model
    integer, parameter :: max_elements = 1000000
    !> The columns of an elements_file before those of the strength laws (x_begin, y_begin,
    !> x_end, y_end, mu, sf, pressure)
    integer, parameter :: law_column = 7

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
        !> The strength laws beyond Coulomb, column k law k of the list (ddc_model_laws; its
        !> default where not given), shape (elements, strength_law_count)
        real(wp), allocatable :: laws(:, :)
        !> The values of rate-and-state elements, column k value k of the list
        !> (ddc_model_rate_state; 0 for other conditions), shape (elements, rate_state_count)
        real(wp), allocatable :: rate_state(:, :)
        !> Hydraulic diffusivity and transmissivity (0 where not given: no flow), shape
        !> (elements)
        real(wp), allocatable :: diffusivity(:), transmissivity(:)
        !> Aperture of the closed faces for coupled flow (&fluid) [length unit]; 0: the
        !> fracture does not conduct
        real(wp) :: residual_aperture = 0.0_wp
    end type fracture_input

contains

    !> &fracture name, x, y, elements, mu, sf, pressure, condition, bc_s, bc_n,
    !> elements_file, tensile_strength, sf_residual, mu_dynamic, slip_weakening_distance,
    !> shear_stiffness, normal_stiffness, opening_weakening_distance, a, b, dc, f0, v0, v_init,
    !> sigma0, tau0, residual_aperture / (repeated, one per fracture)
    subroutine read_fracture_groups(unit, text, path, dir, info, fractures, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path, dir
        type(group_record), intent(in) :: info
        type(fracture_input), allocatable, intent(out) :: fractures(:)
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name, condition, elements_file
        real(wp), allocatable :: x(:), y(:), mu(:), sf(:), pressure(:), bc_s(:), bc_n(:)
        real(wp), allocatable :: diffusivity(:), transmissivity(:), seg_diffusivity(:), &
            seg_transmissivity(:)
        ! The strength laws' variables
        real(wp), allocatable :: tensile_strength(:), sf_residual(:), mu_dynamic(:), &
            slip_weakening_distance(:), shear_stiffness(:), normal_stiffness(:), &
            opening_weakening_distance(:)
        ! The values of rate-and-state elements, as read (column k value k of the list), how
        ! many of each were given, and per segment
        real(wp), allocatable :: a(:), b(:), dc(:), f0(:), v0(:), v_init(:), sigma0(:), &
            tau0(:), rs_values(:, :), seg_rs(:, :)
        type(rate_state_value) :: rs_list(rate_state_count)
        integer :: nrs(rate_state_count)
        ! The laws: what the list says of each, their values as read and per segment (column k
        ! law k), how many values of each were given, which the CSV gives
        type(strength_law) :: laws(strength_law_count)
        real(wp), allocatable :: law_values(:, :), seg_laws(:, :)
        character(len=text_length) :: law_names(strength_law_count)
        integer :: nlaw(strength_law_count)
        logical, allocatable :: csv_given(:)
        integer, allocatable :: elements(:)
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix, csv_path
        real(wp), allocatable :: rows(:,:), seg_mu(:), seg_sf(:), seg_pressure(:), &
                                 seg_bc_s(:), seg_bc_n(:)
        integer, allocatable :: counts(:), row_lines(:)
        type(error_type), allocatable :: csv_error
        integer :: stat, k, i, j, nx, ny, ne, nmu, nsf, npr, nbs, nbn, nseg, nbefore, cond
        integer :: ndiff, ntrans, hydraulic_column
        real(wp) :: residual_aperture
        logical :: from_csv, geometry_ok
        namelist /fracture/ name, x, y, elements, mu, sf, pressure, condition, bc_s, bc_n, &
            elements_file, tensile_strength, sf_residual, mu_dynamic, slip_weakening_distance, &
            shear_stiffness, normal_stiffness, opening_weakening_distance, diffusivity, &
            transmissivity, a, b, dc, f0, v0, v_init, sigma0, tau0, residual_aperture

        allocate (fractures(info%count))
        if (info%count == 0) return
        laws = strength_laws()
        rs_list = rate_state_values()
        do j = 1, size(laws)
            law_names(j) = laws(j)%name
        end do
        allocate (x(max_vertices), y(max_vertices), mu(max_vertices), sf(max_vertices), &
                  pressure(max_vertices), bc_s(max_vertices), bc_n(max_vertices), &
                  elements(max_vertices), tensile_strength(max_vertices), &
                  sf_residual(max_vertices), mu_dynamic(max_vertices), &
                  slip_weakening_distance(max_vertices), shear_stiffness(max_vertices), &
                  normal_stiffness(max_vertices), opening_weakening_distance(max_vertices), &
                  a(max_vertices), b(max_vertices), dc(max_vertices), f0(max_vertices), &
                  v0(max_vertices), v_init(max_vertices), sigma0(max_vertices), &
                  tau0(max_vertices), diffusivity(max_vertices), transmissivity(max_vertices))
        ! The CSV's optional columns: the laws, then the hydraulic properties.
        hydraulic_column = law_column + size(laws)
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
            a = unset_real
            b = unset_real
            dc = unset_real
            f0 = unset_real
            v0 = unset_real
            v_init = unset_real
            sigma0 = unset_real
            tau0 = unset_real
            diffusivity = unset_real
            transmissivity = unset_real
            residual_aperture = unset_real
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
            ndiff = count_given(diffusivity, 'diffusivity', prefix, messages)
            ntrans = count_given(transmissivity, 'transmissivity', prefix, messages)
            call check_range(diffusivity(1:ndiff), 'diffusivity', quantity_positive, prefix, &
                             messages)
            call check_range(transmissivity(1:ntrans), 'transmissivity', quantity_positive, &
                             prefix, messages)
            if ((ndiff > 0) .neqv. (ntrans > 0)) call add(messages, prefix//'give both '// &
                'diffusivity and transmissivity (a fracture without them does not conduct)')
            if (check_scalar(residual_aperture, 'residual_aperture', .false., prefix, messages, &
                             quantity_non_negative)) then
                fractures(k)%residual_aperture = residual_aperture
            end if
            ! In the order of the list of the laws (the CTest architecture holds it to that)
            law_values = reshape([tensile_strength, sf_residual, mu_dynamic, &
                                  slip_weakening_distance, opening_weakening_distance, &
                                  shear_stiffness, normal_stiffness], &
                                 [max_vertices, strength_law_count])
            do j = 1, size(laws)
                nlaw(j) = count_given(law_values(:, j), laws(j)%name, prefix, messages)
            end do
            ! In the order of the list of the rate-and-state values
            rs_values = reshape([a, b, dc, f0, v0, v_init, sigma0, tau0], &
                                [max_vertices, rate_state_count])
            do j = 1, rate_state_count
                nrs(j) = count_given(rs_values(:, j), rs_list(j)%name, prefix, messages)
            end do

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
                if (nmu > 0 .or. nsf > 0 .or. npr > 0 .or. any(nlaw > 0) .or. any(nrs > 0)) then
                    call add(messages, prefix//'mu, sf, pressure, the strength laws and the '// &
                             'rate-and-state values come from elements_file; do not give '// &
                             'them in the group as well')
                end if
                csv_path = resolve(dir, trim(adjustl(elements_file)))
                if (ndiff > 0 .or. ntrans > 0) then
                    call add(messages, prefix//'diffusivity and transmissivity come from '// &
                             'elements_file; do not give them in the group as well')
                end if
                if (cond == condition_rate_state) then
                    call read_rate_state_csv()
                else
                    call read_csv(csv_path, [character(len=8) :: 'x_begin', 'y_begin', &
                                  'x_end', 'y_end', 'mu', 'sf', 'pressure'], rows, csv_error, &
                                  row_lines, [character(len=text_length) :: law_names, &
                                  'diffusivity', 'transmissivity'], csv_given, &
                                  most_rows=max_elements)
                end if
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
                    if (cond == condition_rate_state) then
                        call check_rate_state_rows()
                    else
                        call check_contact_rows()
                        call check_hydraulic_rows()
                    end if
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
                    do j = 1, size(laws)
                        call check_range(law_values(1:nlaw(j), j), laws(j)%name, &
                                         laws(j)%quantity, prefix, messages)
                    end do
                end if
                if (nbs > 0 .or. nbn > 0) then
                    call add(messages, prefix//'bc_s and bc_n are for the TWODD-style '// &
                             "conditions, not for condition 'contact'")
                end if
            else if (cond /= 0) then
                if (.not. from_csv .and. (nmu > 0 .or. nsf > 0 .or. npr > 0 .or. &
                                          any(nlaw > 0))) then
                    call add(messages, prefix//"mu, sf, pressure and the strength laws are "// &
                             "for condition "// &
                             "'contact', not for condition '"//trim(condition_names(cond))//"'")
                end if
            end if
            call check_rate_state_group()

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
                    if (allocated(seg_laws)) deallocate (seg_laws)
                    allocate (seg_laws(nseg, size(laws)))
                    do j = 1, size(laws)
                        if (.not. check_length(nlaw(j), nseg, laws(j)%name, prefix, &
                                               messages)) cycle
                        seg_laws(:, j) = broadcast(law_values(1:nlaw(j), j), nseg, &
                                                   laws(j)%default)
                        select case (laws(j)%at_most)
                        case ('sf')
                            if (allocated(seg_sf)) call check_residual(seg_sf, seg_laws(:, j), &
                                                                       'segment', laws(j))
                        case ('mu')
                            if (allocated(seg_mu)) call check_residual(seg_mu, seg_laws(:, j), &
                                                                       'segment', laws(j))
                        case default
                            ! no Coulomb value it may not exceed
                        end select
                    end do
                end if
                if (check_length(nbs, nseg, 'bc_s', prefix, messages)) then
                    seg_bc_s = broadcast(bc_s(1:nbs), nseg, 0.0_wp)
                end if
                if (check_length(nbn, nseg, 'bc_n', prefix, messages)) then
                    seg_bc_n = broadcast(bc_n(1:nbn), nseg, 0.0_wp)
                end if
                if (allocated(seg_rs)) deallocate (seg_rs)
                allocate (seg_rs(nseg, rate_state_count))
                do j = 1, rate_state_count
                    if (check_length(nrs(j), nseg, rs_list(j)%name, prefix, messages)) then
                        seg_rs(:, j) = broadcast(rs_values(1:nrs(j), j), nseg, 0.0_wp)
                    end if
                end do
                if (check_length(ndiff, nseg, 'diffusivity', prefix, messages)) then
                    seg_diffusivity = broadcast(diffusivity(1:ndiff), nseg, 0.0_wp)
                end if
                if (check_length(ntrans, nseg, 'transmissivity', prefix, messages)) then
                    seg_transmissivity = broadcast(transmissivity(1:ntrans), nseg, 0.0_wp)
                end if
            end if
            if (messages%n > nbefore) cycle

            ! Valid: expand to elements.
            fractures(k)%valid = .true.
            fractures(k)%condition = cond
            if (from_csv .and. cond == condition_rate_state) then
                fractures(k)%x_begin = rows(1, :)
                fractures(k)%y_begin = rows(2, :)
                fractures(k)%x_end = rows(3, :)
                fractures(k)%y_end = rows(4, :)
                fractures(k)%rate_state = transpose(rows(5:, :))
                allocate (fractures(k)%mu(nseg), fractures(k)%sf(nseg), &
                          fractures(k)%pressure(nseg), source=0.0_wp)
                allocate (fractures(k)%laws(nseg, size(laws)))
                do j = 1, size(laws)
                    fractures(k)%laws(:, j) = laws(j)%default
                end do
                fractures(k)%bc_s = seg_bc_s
                fractures(k)%bc_n = seg_bc_n
                allocate (fractures(k)%diffusivity(nseg), fractures(k)%transmissivity(nseg), &
                          source=0.0_wp)
            else if (from_csv) then
                fractures(k)%x_begin = rows(1, :)
                fractures(k)%y_begin = rows(2, :)
                fractures(k)%x_end = rows(3, :)
                fractures(k)%y_end = rows(4, :)
                fractures(k)%mu = rows(5, :)
                fractures(k)%sf = rows(6, :)
                fractures(k)%pressure = rows(7, :)
                fractures(k)%laws = transpose(rows(law_column + 1:hydraulic_column, :))
                fractures(k)%diffusivity = rows(hydraulic_column + 1, :)
                fractures(k)%transmissivity = rows(hydraulic_column + 2, :)
                fractures(k)%bc_s = seg_bc_s
                fractures(k)%bc_n = seg_bc_n
                allocate (fractures(k)%rate_state(nseg, rate_state_count), source=0.0_wp)
            else
                call polyline_elements(x(1:nx), y(1:ny), counts, fractures(k)%x_begin, &
                                       fractures(k)%y_begin, fractures(k)%x_end, &
                                       fractures(k)%y_end)
                fractures(k)%mu = expand_per_segment(seg_mu, counts)
                fractures(k)%sf = expand_per_segment(seg_sf, counts)
                fractures(k)%pressure = expand_per_segment(seg_pressure, counts)
                allocate (fractures(k)%laws(size(fractures(k)%mu), size(laws)))
                do j = 1, size(laws)
                    fractures(k)%laws(:, j) = expand_per_segment(seg_laws(:, j), counts)
                end do
                fractures(k)%bc_s = expand_per_segment(seg_bc_s, counts)
                fractures(k)%bc_n = expand_per_segment(seg_bc_n, counts)
                allocate (fractures(k)%rate_state(size(fractures(k)%mu), rate_state_count))
                do j = 1, rate_state_count
                    fractures(k)%rate_state(:, j) = expand_per_segment(seg_rs(:, j), counts)
                end do
                fractures(k)%diffusivity = expand_per_segment(seg_diffusivity, counts)
                fractures(k)%transmissivity = expand_per_segment(seg_transmissivity, counts)
            end if
        end do

    contains

        !> Every row of an elements_file of contact (or TWODD-style) elements: mu and sf not
        !> negative, each law within its range and bound; a law not given takes its default.
        subroutine check_contact_rows()
            integer :: r, l

            do r = 1, nseg
                if (len(range_problem(quantity_non_negative, rows(5, r))) > 0) then
                    call add(messages, prefix//'elements_file '//csv_path//' line '// &
                             itoa(row_lines(r))//': mu = '//rtoa(rows(5, r))//' '// &
                             range_problem(quantity_non_negative, rows(5, r)))
                end if
                if (len(range_problem(quantity_non_negative, rows(6, r))) > 0) then
                    call add(messages, prefix//'elements_file '//csv_path//' line '// &
                             itoa(row_lines(r))//': sf = '//rtoa(rows(6, r))//' '// &
                             range_problem(quantity_non_negative, rows(6, r)))
                end if
                do l = 1, size(laws)
                    if (csv_given(l)) call check_law_row(l, r)
                end do
            end do
            do l = 1, size(laws)
                if (.not. csv_given(l)) rows(law_column + l, :) = laws(l)%default
            end do
        end subroutine check_contact_rows

        !> An elements_file of rate-and-state elements: the end points, then a, b, dc, f0,
        !> v0, v_init, sigma0, tau0 (the list's order).
        subroutine read_rate_state_csv()
            character(len=8) :: header(4 + rate_state_count)
            integer :: l

            header(1:4) = [character(len=8) :: 'x_begin', 'y_begin', 'x_end', 'y_end']
            do l = 1, rate_state_count
                header(4 + l) = rs_list(l)%name
            end do
            call read_csv(csv_path, header, rows, csv_error, row_lines, most_rows=max_elements)
        end subroutine read_rate_state_csv

        !> Every value of every row of a rate-and-state elements_file within its range.
        subroutine check_rate_state_rows()
            integer :: l, r

            do r = 1, nseg
                do l = 1, rate_state_count
                    associate (given => rows(4 + l, r))
                        if (len(range_problem(rs_list(l)%quantity, given)) > 0) then
                            call add(messages, prefix//'elements_file '//csv_path//' line '// &
                                     itoa(row_lines(r))//': '//rs_list(l)%name//' = '// &
                                     rtoa(given)//' '//range_problem(rs_list(l)%quantity, given))
                            return
                        end if
                    end associate
                end do
            end do
        end subroutine check_rate_state_rows

        !> A rate-and-state fracture gives every value of the list (or its elements_file
        !> does) and no TWODD-style value; no other fracture gives any of them.
        subroutine check_rate_state_group()
            integer :: l

            if (cond /= condition_rate_state) then
                if (any(nrs > 0)) call add(messages, prefix//'a, b, dc, f0, v0, v_init, '// &
                    "sigma0 and tau0 are for condition 'rate_state'")
                return
            end if
            if (nbs > 0 .or. nbn > 0) call add(messages, prefix//'bc_s and bc_n are for '// &
                "the TWODD-style conditions, not for condition 'rate_state'")
            if (from_csv) return
            do l = 1, rate_state_count
                if (nrs(l) == 0) then
                    call add(messages, prefix//rs_list(l)%name//" is required for condition "// &
                             "'rate_state'")
                else
                    call check_range(rs_values(1:nrs(l), l), rs_list(l)%name, &
                                     rs_list(l)%quantity, prefix, messages)
                end if
            end do
        end subroutine check_rate_state_group
        !> The CSV's hydraulic columns: both or neither, positive; 0 (no flow) when absent.
        subroutine check_hydraulic_rows()
            integer :: c, row
            character(len=*), parameter :: names(2) = ['diffusivity   ', 'transmissivity']

            if (csv_given(size(laws) + 1) .neqv. csv_given(size(laws) + 2)) then
                call add(messages, prefix//'elements_file '//csv_path//': give both '// &
                         'diffusivity and transmissivity columns, or neither')
            end if
            do c = 1, 2
                if (.not. csv_given(size(laws) + c)) then
                    rows(hydraulic_column + c, :) = 0.0_wp
                    cycle
                end if
                do row = 1, nseg
                    if (len(range_problem(quantity_positive, rows(hydraulic_column + c, &
                                                                   row))) == 0) cycle
                    call add(messages, prefix//'elements_file '//csv_path//' line '// &
                             itoa(row_lines(row))//': '//trim(names(c))//' = '// &
                             rtoa(rows(hydraulic_column + c, row))//' '// &
                             range_problem(quantity_positive, rows(hydraulic_column + c, row)))
                end do
            end do
        end subroutine check_hydraulic_rows

        !> Law l in CSV row i is within its range, and not above the Coulomb value it may not
        !> exceed (law%at_most: sf_residual <= sf, mu_dynamic <= mu).
        subroutine check_law_row(l, i)
            integer, intent(in) :: l, i
            character(len=:), allocatable :: where

            associate (law => laws(l), given => rows(law_column + l, i))
                where = 'elements_file '//csv_path//' line '//itoa(row_lines(i))//':'
                if (len(range_problem(law%quantity, given)) > 0) then
                    call add(messages, prefix//where//' '//law%name//' = '//rtoa(given)//' '// &
                             range_problem(law%quantity, given))
                else if (law%at_most == 'sf') then
                    call check_residual(rows(6, i:i), rows(law_column + l, i:i), where, law)
                else if (law%at_most == 'mu') then
                    call check_residual(rows(5, i:i), rows(law_column + l, i:i), where, law)
                end if
            end associate
        end subroutine check_law_row

        !> A value after slip (a residual cohesion, a dynamic friction) above the Coulomb value
        !> it falls from (law%at_most) is a mistake, not a strengthening.
        subroutine check_residual(intact, residual, where, law)
            real(wp), intent(in) :: intact(:), residual(:)
            character(len=*), intent(in) :: where
            type(strength_law), intent(in) :: law
            integer :: j

            do j = 1, size(residual)
                ! NaN and Inf are reported by count_given; compared here they would trap
                if (.not. (within_limits(residual(j)) .and. within_limits(intact(j)))) cycle
                if (residual(j) > intact(j) .and. residual(j) < no_residual_drop) then
                    if (where == 'segment') then
                        call add(messages, prefix//law%name//' = '//rtoa(residual(j))// &
                                 ' exceeds '//law%at_most//' = '//rtoa(intact(j))// &
                                 ' on segment '//itoa(j)//' ('//at_most_rule(law)//')')
                    else
                        call add(messages, prefix//where//' '//law%name//' = '// &
                                 rtoa(residual(j))//' exceeds '//law%at_most//' = '// &
                                 rtoa(intact(j))//' ('//at_most_rule(law)//')')
                    end if
                    return
                end if
            end do
        end subroutine check_residual

    end subroutine read_fracture_groups

end module ddc_input_namelist_fracture
