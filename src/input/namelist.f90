!> Read a ddc2d model from a namelist input file (SPEC section 6).
!>
!> The whole file is read first and scanned for `&group` starts (case-insensitive,
!> ignoring `!` comments and quoted text) to count each group and reject unknown ones.
!> Each group is then read the counted number of times with iostat and iomsg: a read
!> failure for a group known to exist means the group is malformed (gfortran reports a
!> value of the wrong type in the last group as "End of file"). Defaults are set to an
!> "unset" sentinel before every read, so given entries can be counted; every value is
!> validated NaN-safely and all violations are reported at once, one per line, each
!> naming the file, the group (with its ordinal and name when repeatable) and the
!> variable.
module ddc_input_namelist
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, fracture_type, observation_set, &
        condition_names, condition_contact, observation_grid, observation_line, &
        observation_points, observation_kind_names, symmetry_none, symmetry_names, &
        symmetry_x, domain_names, domain_half_plane, load_path_names
    use ddc_contact_options, only: parse_solver_options
    use ddc_input_text_file, only: read_text_file, base_name
    use ddc_input_csv, only: read_csv
    use ddc_text, only: newline, itoa, rtoa, lower
    use ddc_mesh_polyline, only: polyline_elements, expand_per_segment
    use ddc_mesh_geometry, only: allocate_elements, compute_geometry
    use ddc_mesh_checks, only: check_elements
    use ddc_model_limits, only: within_limits, limits_text
    implicit none
    private

    public :: read_namelist_model, namelist_group_names, group_line, group_problem
    public :: join_integers
    public :: max_vertices, max_elements, max_observation_points

    !> Names of the namelist groups ddc2d knows
    !> (&sweep is read by ddc_input_sweep; the model reader skips it)
    character(len=*), parameter :: namelist_group_names(12) = [character(len=13) :: &
        'model', 'remote_stress', 'fracture', 'grid', 'line', 'points', 'solver', 'output', &
        'symmetry', 'sweep', 'pore_fluid', 'load_path']
    integer, parameter :: g_model = 1, g_remote_stress = 2, g_fracture = 3, g_grid = 4, &
                          g_line = 5, g_points = 6, g_solver = 7, g_output = 8, g_symmetry = 9, &
                          g_pore_fluid = 11, g_load_path = 12
    !> Groups that may appear more than once
    logical, parameter :: repeatable(12) = [.false., .false., .true., .true., .true., &
                                            .true., .false., .false., .false., .false., .false., &
                                            .false.]
    !> Largest number of vertices of a &load_path, and of steps along it
    integer, parameter :: max_path_vertices = 10000, max_path_steps = 1000000

    !> Largest number of polyline vertices of one &fracture (size of the namelist arrays)
    integer, parameter :: max_vertices = 100000
    !> Largest number of elements in a model
    integer, parameter :: max_elements = 1000000
    !> Largest number of points in one observation set
    integer, parameter :: max_observation_points = 100000000

    !> Length of character variables in the groups
    integer, parameter :: text_length = 1024

    !> Sentinels of values the user did not give
    real(wp), parameter :: unset_real = huge(1.0_wp)
    integer, parameter :: unset_integer = -huge(1)

    !> Where the occurrences of one group are in the file.
    type :: group_record
        !> Number of occurrences
        integer :: count = 0
        !> Line of each occurrence
        integer, allocatable :: lines(:)
        !> First and last character of each occurrence in the text ('&' to '/')
        integer, allocatable :: starts(:), ends(:)
        !> Index in the model's observation list (grids, lines, points only)
        integer, allocatable :: slot(:)
    end type group_record

    !> Violations found so far, one per line.
    type :: message_list
        character(len=:), allocatable :: text
        integer :: n = 0
    end type message_list

    !> One validated fracture, expanded to elements.
    type :: fracture_input
        character(len=:), allocatable :: name
        !> Group label for messages
        character(len=:), allocatable :: label
        logical :: valid = .false.
        integer :: condition = condition_contact
        real(wp), allocatable :: x_begin(:), y_begin(:), x_end(:), y_end(:)
        real(wp), allocatable :: mu(:), sf(:), pressure(:), bc_s(:), bc_n(:)
    end type fracture_input

    !> One observation set with the label of the group that made it.
    type :: observation_input
        type(observation_set) :: set
        character(len=:), allocatable :: label
        logical :: valid = .false.
    end type observation_input

contains

    !> Read the namelist file at path into a complete model (elements with geometry,
    !> fractures, observations, solver options, output file, input text). Every problem
    !> is reported at once in error (code exit_bad_input), one line each.
    subroutine read_namelist_model(path, model, error)
        !> Path of the input file, as given on the command line
        character(len=*), intent(in) :: path
        !> The model read
        type(model_type), intent(out) :: model
        !> Allocated when the file is missing or bad
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text, dir
        type(group_record) :: groups(size(namelist_group_names))
        type(message_list) :: messages
        type(fracture_input), allocatable :: fractures(:)
        type(observation_input), allocatable :: observations(:)
        integer :: unit, stat, nobs
        character(len=512) :: iomsg

        call read_text_file(path, text, error)
        if (allocated(error)) return
        model%input_file = path
        model%input_text = text
        dir = folder_of(path)
        messages%text = ''

        call scan_groups(text, path, groups, nobs, messages)
        if (groups(g_model)%count == 0) then
            call add(messages, path//': the &model group is missing (it gives youngs_modulus'// &
                     ' and poissons_ratio)')
        end if
        if (groups(g_fracture)%count == 0) then
            call add(messages, path//': no &fracture group: a model needs at least one fracture')
        end if

        open (newunit=unit, file=path, status='old', action='read', form='formatted', &
              iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call set_error(error, exit_bad_input, path//': cannot open: '//trim(iomsg))
            return
        end if
        allocate (observations(nobs))
        call read_model_group(unit, text, path, groups(g_model), model, messages)
        call read_remote_stress_group(unit, text, path, groups(g_remote_stress), model, messages)
        call read_fracture_groups(unit, text, path, dir, groups(g_fracture), fractures, messages)
        call read_grid_groups(unit, text, path, groups(g_grid), observations, messages)
        call read_line_groups(unit, text, path, groups(g_line), observations, messages)
        call read_points_groups(unit, text, path, dir, groups(g_points), observations, messages)
        call read_solver_group(unit, text, path, groups(g_solver), model, messages)
        call read_output_group(unit, text, path, dir, groups(g_output), model, messages)
        call read_symmetry_group(unit, text, path, groups(g_symmetry), model, messages)
        call read_pore_fluid_group(unit, text, path, groups(g_pore_fluid), model, messages)
        call read_load_path_group(unit, text, path, groups(g_load_path), fractures, model, &
                                  messages)
        close (unit)

        call check_names(path, fractures, observations, messages)
        call check_half_plane(path, model, fractures, observations, messages)
        if (messages%n > 0) then
            call set_error(error, exit_bad_input, messages%text)
            return
        end if

        call build_model(fractures, observations, model)
        call check_elements(model%elements, model%fractures, error)
        if (allocated(error)) then
            error%message = prefix_lines(path//': ', error%message)
        end if
    end subroutine read_namelist_model

    ! ------------------------------------------------------------------------------------
    ! Scanning the text for groups
    ! ------------------------------------------------------------------------------------

    !> Line of the first occurrence of the known group `name` in the text of an input
    !> file, 0 when it is absent (comments and quoted text are ignored).
    function group_line(text, name) result(line)
        !> Text of the input file
        character(len=*), intent(in) :: text
        !> Name of the group, without '&'
        character(len=*), intent(in) :: name
        !> Line number, 0 when the group is absent
        integer :: line
        type(group_record) :: groups(size(namelist_group_names))
        type(message_list) :: ignored
        integer :: nobs, g

        line = 0
        g = find_name(name, namelist_group_names)
        if (g == 0) return
        call scan_groups(text, '', groups, nobs, ignored)
        if (groups(g)%count > 0) line = groups(g)%lines(1)
    end function group_line

    !> The message for a failed namelist read of the first occurrence of the known group
    !> `name` (present in text), naming the unknown variable or the bad value when found.
    function group_problem(text, path, name, stat, iomsg, spec) result(message)
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Name of the group, without '&'
        character(len=*), intent(in) :: name
        !> iostat and iomsg of the failed read
        integer, intent(in) :: stat
        character(len=*), intent(in) :: iomsg
        !> Variables of the group with their types: "name:c x:r n:i"
        character(len=*), intent(in) :: spec
        !> The message, one line
        character(len=:), allocatable :: message
        type(group_record) :: groups(size(namelist_group_names))
        type(message_list) :: ignored
        integer :: nobs, g

        g = find_name(name, namelist_group_names)
        call scan_groups(text, path, groups, nobs, ignored)
        message = malformed_message(group_prefix(path, g, groups(g), 1), stat, iomsg, spec, &
                                    text(groups(g)%starts(1):groups(g)%ends(1)))
    end function group_problem

    !> Count every group in text and note its lines; report unknown and repeated groups.
    subroutine scan_groups(text, path, groups, nobs, messages)
        character(len=*), intent(in) :: text, path
        type(group_record), intent(inout) :: groups(:)
        !> Number of observation groups (grid, line, points)
        integer, intent(out) :: nobs
        type(message_list), intent(inout) :: messages
        integer, allocatable :: found_group(:), found_line(:), found_start(:), found_end(:)
        character(len=:), allocatable :: name, known
        character(len=1) :: c, quote
        integer :: i, j, line, nfound, g, k, current
        logical :: in_group

        nfound = 1
        do i = 1, len(text)
            if (text(i:i) == '&') nfound = nfound + 1
        end do
        allocate (found_group(nfound), found_line(nfound), found_start(nfound), &
                  found_end(nfound))
        nfound = 0
        current = 0
        in_group = .false.
        quote = ' '
        line = 1
        i = 1
        do while (i <= len(text))
            c = text(i:i)
            if (c == newline) then
                line = line + 1
            else if (quote /= ' ') then
                if (c == quote) quote = ' '
            else if (c == '!') then
                j = index(text(i:), newline)
                if (j == 0) exit
                i = i + j - 1
                cycle
            else if (c == '&') then
                j = i + 1
                do while (j <= len(text))
                    if (.not. is_name_character(text(j:j))) exit
                    j = j + 1
                end do
                name = lower(text(i + 1:j - 1))
                if (name == 'end') then
                    if (in_group .and. current > 0) found_end(current) = j - 1
                    in_group = .false.
                    current = 0
                else if (len(name) > 0) then
                    if (in_group .and. current > 0) found_end(current) = i - 1
                    in_group = .true.
                    current = 0
                    g = find_name(name, namelist_group_names)
                    if (g == 0) then
                        known = '&'//trim(namelist_group_names(1))
                        do k = 2, size(namelist_group_names)
                            known = known//', &'//trim(namelist_group_names(k))
                        end do
                        call add(messages, path//' line '//itoa(line)//': &'//name// &
                                 ' is not a ddc2d group; known groups: '//known)
                    else
                        nfound = nfound + 1
                        found_group(nfound) = g
                        found_line(nfound) = line
                        found_start(nfound) = i
                        found_end(nfound) = len(text)
                        current = nfound
                    end if
                end if
                i = j
                cycle
            else if (in_group) then
                if (c == '"' .or. c == "'") then
                    quote = c
                else if (c == '/') then
                    in_group = .false.
                    if (current > 0) found_end(current) = i
                    current = 0
                end if
            end if
            i = i + 1
        end do

        nobs = 0
        do g = 1, size(groups)
            groups(g)%count = count(found_group(1:nfound) == g)
            allocate (groups(g)%lines(groups(g)%count), groups(g)%slot(groups(g)%count), &
                      groups(g)%starts(groups(g)%count), groups(g)%ends(groups(g)%count))
            groups(g)%count = 0
        end do
        do k = 1, nfound
            g = found_group(k)
            groups(g)%count = groups(g)%count + 1
            groups(g)%lines(groups(g)%count) = found_line(k)
            groups(g)%starts(groups(g)%count) = found_start(k)
            groups(g)%ends(groups(g)%count) = found_end(k)
            if (g == g_grid .or. g == g_line .or. g == g_points) then
                nobs = nobs + 1
                groups(g)%slot(groups(g)%count) = nobs
            else
                groups(g)%slot(groups(g)%count) = 0
            end if
        end do
        do g = 1, size(groups)
            if (.not. repeatable(g) .and. groups(g)%count > 1) then
                call add(messages, path//': &'//trim(namelist_group_names(g))//' appears '// &
                         itoa(groups(g)%count)//' times (lines '// &
                         join_integers(groups(g)%lines)//'); give it at most once')
            end if
        end do
    end subroutine scan_groups

    ! ------------------------------------------------------------------------------------
    ! The groups
    ! ------------------------------------------------------------------------------------

    !> &model title, youngs_modulus, poissons_ratio, length_unit, stress_unit /
    subroutine read_model_group(unit, text, path, info, the_model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(model_type), intent(inout) :: the_model
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: title, length_unit, stress_unit, domain
        real(wp) :: youngs_modulus, poissons_ratio
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'title:c youngs_modulus:r '// &
            'poissons_ratio:r length_unit:c stress_unit:c domain:c'
        namelist /model/ title, youngs_modulus, poissons_ratio, length_unit, stress_unit, domain

        the_model%title = base_name(path, .false.)
        the_model%length_unit = 'm'
        the_model%stress_unit = 'MPa'
        if (info%count == 0) return
        title = ''
        youngs_modulus = unset_real
        poissons_ratio = unset_real
        length_unit = 'm'
        stress_unit = 'MPa'
        domain = 'full_plane'
        rewind (unit)
        read (unit, nml=model, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_model, info, 1, stat, iomsg, variables, messages)
            return
        end if
        prefix = group_prefix(path, g_model, info, 1)
        if (len_trim(title) > 0) the_model%title = trim(adjustl(title))
        if (len_trim(length_unit) == 0) then
            call add(messages, prefix//'length_unit is empty')
        end if
        if (len_trim(stress_unit) == 0) then
            call add(messages, prefix//'stress_unit is empty')
        end if
        the_model%length_unit = trim(adjustl(length_unit))
        the_model%stress_unit = trim(adjustl(stress_unit))
        stat = find_name(lower(trim(adjustl(domain))), domain_names)
        if (stat == 0) then
            call add(messages, prefix//"domain = '"//trim(adjustl(domain))//"' is not one of "// &
                     quoted_list(domain_names))
        else
            the_model%elements%domain = stat
        end if

        if (check_scalar(youngs_modulus, 'youngs_modulus', .true., prefix, messages)) then
            if (youngs_modulus <= 0.0_wp) then
                call add(messages, prefix//'youngs_modulus = '//rtoa(youngs_modulus)// &
                         ' must be positive')
            end if
            the_model%youngs_modulus = youngs_modulus
        end if
        if (check_scalar(poissons_ratio, 'poissons_ratio', .true., prefix, messages)) then
            if (poissons_ratio <= -1.0_wp .or. poissons_ratio >= 0.5_wp) then
                call add(messages, prefix//'poissons_ratio = '//rtoa(poissons_ratio)// &
                         ' must lie in (-1, 0.5)')
            end if
            the_model%poissons_ratio = poissons_ratio
        end if
    end subroutine read_model_group

    !> &remote_stress sxx, syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy / (tension positive, default 0;
    !> the stress at depth y is s + ds_dy * y)
    subroutine read_remote_stress_group(unit, text, path, info, model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages
        real(wp) :: sxx, syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'sxx:r syy:r sxy:r dsxx_dy:r dsyy_dy:r '// &
            'dsxy_dy:r'
        namelist /remote_stress/ sxx, syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy

        model%sxx = 0.0_wp
        model%syy = 0.0_wp
        model%sxy = 0.0_wp
        if (info%count == 0) return
        sxx = 0.0_wp
        syy = 0.0_wp
        sxy = 0.0_wp
        dsxx_dy = 0.0_wp
        dsyy_dy = 0.0_wp
        dsxy_dy = 0.0_wp
        rewind (unit)
        read (unit, nml=remote_stress, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_remote_stress, info, 1, stat, iomsg, variables, &
                                  messages)
            return
        end if
        prefix = group_prefix(path, g_remote_stress, info, 1)
        if (check_scalar(sxx, 'sxx', .false., prefix, messages)) model%sxx = sxx
        if (check_scalar(syy, 'syy', .false., prefix, messages)) model%syy = syy
        if (check_scalar(sxy, 'sxy', .false., prefix, messages)) model%sxy = sxy
        if (check_scalar(dsxx_dy, 'dsxx_dy', .false., prefix, messages)) &
            model%stress_gradient(1) = dsxx_dy
        if (check_scalar(dsyy_dy, 'dsyy_dy', .false., prefix, messages)) &
            model%stress_gradient(2) = dsyy_dy
        if (check_scalar(dsxy_dy, 'dsxy_dy', .false., prefix, messages)) &
            model%stress_gradient(3) = dsxy_dy
    end subroutine read_remote_stress_group

    !> &pore_fluid p0, dp_dy / (fluid pressure p0 + dp_dy * y inside every contact element,
    !> compression positive, added to its pressure; default 0)
    subroutine read_pore_fluid_group(unit, text, path, info, model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages
        real(wp) :: p0, dp_dy
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'p0:r dp_dy:r'
        namelist /pore_fluid/ p0, dp_dy

        model%pore_fluid = 0.0_wp
        if (info%count == 0) return
        p0 = 0.0_wp
        dp_dy = 0.0_wp
        rewind (unit)
        read (unit, nml=pore_fluid, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_pore_fluid, info, 1, stat, iomsg, variables, &
                                  messages)
            return
        end if
        prefix = group_prefix(path, g_pore_fluid, info, 1)
        if (check_scalar(p0, 'p0', .false., prefix, messages)) model%pore_fluid(1) = p0
        if (check_scalar(dp_dy, 'dp_dy', .false., prefix, messages)) model%pore_fluid(2) = dp_dy
    end subroutine read_pore_fluid_group

    !> &load_path sxx, syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy, p0, steps / (SPEC-EARTH 3;
    !> optional): the load at the path's vertices (the first is the starting state), each
    !> quantity either absent (held at its &remote_stress or &pore_fluid value) or given at
    !> every vertex, and steps(l) increments on leg l. Needs contact elements.
    subroutine read_load_path_group(unit, text, path, info, fractures, model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(fracture_input), intent(in) :: fractures(:)
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages
        real(wp), allocatable :: sxx(:), syy(:), sxy(:), dsxx_dy(:), dsyy_dy(:), dsxy_dy(:), &
                                 p0(:), values(:, :), fixed(:)
        integer, allocatable :: steps(:)
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, nlegs, nv, q, given
        logical :: ok
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'sxx:r syy:r sxy:r dsxx_dy:r dsyy_dy:r '// &
            'dsxy_dy:r p0:r steps:i'
        namelist /load_path/ sxx, syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy, p0, steps

        if (info%count == 0) return
        allocate (sxx(max_path_vertices), syy(max_path_vertices), sxy(max_path_vertices), &
                  dsxx_dy(max_path_vertices), dsyy_dy(max_path_vertices), &
                  dsxy_dy(max_path_vertices), p0(max_path_vertices), steps(max_path_vertices))
        sxx = unset_real
        syy = unset_real
        sxy = unset_real
        dsxx_dy = unset_real
        dsyy_dy = unset_real
        dsxy_dy = unset_real
        p0 = unset_real
        steps = unset_integer
        rewind (unit)
        read (unit, nml=load_path, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_load_path, info, 1, stat, iomsg, variables, &
                                  messages)
            return
        end if
        prefix = group_prefix(path, g_load_path, info, 1)
        ok = .true.
        nlegs = count_given_integers(steps, 'steps', prefix, messages)
        if (nlegs == 0) then
            call add(messages, prefix//'steps is required: the number of increments on '// &
                     'each leg of the path (one value per leg)')
            ok = .false.
        else if (any(steps(1:nlegs) < 1)) then
            call add(messages, prefix//'steps('//itoa(findloc(steps(1:nlegs) < 1, .true., 1))// &
                     ') must be at least 1')
            ok = .false.
        else if (sum(real(steps(1:nlegs), wp)) > real(max_path_steps, wp)) then
            call add(messages, prefix//'steps add up to more than '//itoa(max_path_steps)// &
                     ' steps')
            ok = .false.
        end if
        nv = nlegs + 1
        values = reshape([sxx, syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy, p0], &
                         [max_path_vertices, 7])
        fixed = [model%sxx, model%syy, model%sxy, model%stress_gradient, model%pore_fluid(1)]
        allocate (model%load_path%vertex(7, nv))
        given = 0
        do q = 1, 7
            stat = count_given(values(:, q), trim(load_path_names(q)), prefix, messages)
            if (stat == 0) then
                model%load_path%vertex(q, :) = fixed(q)
            else if (stat /= nv .and. nlegs > 0) then
                call add(messages, prefix//trim(load_path_names(q))//' has '//itoa(stat)// &
                         ' values; give one per vertex: '//itoa(nv)//' (one more than steps)')
                ok = .false.
            else
                given = given + 1
                model%load_path%varies(q) = .true.
                model%load_path%vertex(q, :) = values(1:nv, q)
            end if
        end do
        if (given == 0) then
            call add(messages, prefix//'give the load at each vertex: at least one of sxx, '// &
                     'syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy, p0')
            ok = .false.
        end if
        if (.not. any(fractures%valid .and. fractures%condition == condition_contact)) then
            call add(messages, prefix//'a load path needs contact elements (condition = '// &
                     "'contact'): without them the response is elastic and loads superpose")
            ok = .false.
        end if
        if (ok .and. model%elements%domain == domain_half_plane) then
            if (any(model%load_path%vertex([2, 3, 6], :) /= 0.0_wp)) then
                call add(messages, prefix//"with &model domain = 'half_plane' syy, sxy and "// &
                         'dsxy_dy must be 0 at every vertex (traction-free surface y = 0)')
                ok = .false.
            end if
        end if
        if (ok) then
            model%load_path%steps = steps(1:nlegs)
        else
            deallocate (model%load_path%vertex)
        end if
    end subroutine read_load_path_group

    !> Half-plane rules (SPEC-EARTH 1): every vertex and field point at y <= 0, no element on
    !> the surface, a remote stress that is traction-free at y = 0, symmetry about x only.
    subroutine check_half_plane(path, model, fractures, observations, messages)
        character(len=*), intent(in) :: path
        type(model_type), intent(in) :: model
        type(fracture_input), intent(in) :: fractures(:)
        type(observation_input), intent(in) :: observations(:)
        type(message_list), intent(inout) :: messages
        character(len=:), allocatable :: prefix
        integer :: k, i

        if (model%elements%domain /= domain_half_plane) return
        prefix = path//": &model domain = 'half_plane': "
        if (model%syy /= 0.0_wp .or. model%sxy /= 0.0_wp .or. &
            model%stress_gradient(3) /= 0.0_wp) then
            call add(messages, prefix//'&remote_stress sxy = '//rtoa(model%sxy)//', syy = '// &
                     rtoa(model%syy)//', dsxy_dy = '//rtoa(model%stress_gradient(3))// &
                     ' must all be 0: the remote stress must be traction-free at the '// &
                     'surface y = 0 (give syy by its gradient dsyy_dy, sxx and dsxx_dy freely)')
        end if
        if (model%elements%symmetry%kind /= symmetry_none .and. &
            model%elements%symmetry%kind /= symmetry_x) then
            call add(messages, prefix//"&symmetry kind = '"// &
                     trim(symmetry_names(model%elements%symmetry%kind))//"' is not "// &
                     "available with a free surface; only kind = 'x' (a vertical line)")
        end if
        do k = 1, size(fractures)
            if (.not. fractures(k)%valid) cycle
            do i = 1, size(fractures(k)%y_begin)
                if (max(fractures(k)%y_begin(i), fractures(k)%y_end(i)) > 0.0_wp) then
                    call add(messages, path//': '//fractures(k)%label//': element '//itoa(i)// &
                             ' has a vertex above the free surface (y > 0) of the half-plane')
                    exit
                else if (fractures(k)%y_begin(i) == 0.0_wp .and. &
                         fractures(k)%y_end(i) == 0.0_wp) then
                    call add(messages, path//': '//fractures(k)%label//': element '//itoa(i)// &
                             ' lies on the free surface y = 0 of the half-plane')
                    exit
                end if
            end do
        end do
        do k = 1, size(observations)
            if (.not. observations(k)%valid) cycle
            i = findloc(observations(k)%set%y > 0.0_wp, .true., 1)
            if (i > 0) then
                call add(messages, path//': '//observations(k)%label//': point '//itoa(i)// &
                         ' (y = '//rtoa(observations(k)%set%y(i))//') is above the free '// &
                         'surface y = 0 of the half-plane')
            end if
        end do
    end subroutine check_half_plane

    !> &fracture name, x, y, elements, mu, sf, pressure, condition, bc_s, bc_n,
    !> elements_file / (repeated, one per fracture)
    subroutine read_fracture_groups(unit, text, path, dir, info, fractures, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path, dir
        type(group_record), intent(in) :: info
        type(fracture_input), allocatable, intent(out) :: fractures(:)
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name, condition, elements_file
        real(wp), allocatable :: x(:), y(:), mu(:), sf(:), pressure(:), bc_s(:), bc_n(:)
        integer, allocatable :: elements(:)
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'name:c x:r y:r elements:i mu:r sf:r '// &
            'pressure:r condition:c bc_s:r bc_n:r elements_file:c'
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix, csv_path
        real(wp), allocatable :: rows(:,:), seg_mu(:), seg_sf(:), seg_pressure(:), &
                                 seg_bc_s(:), seg_bc_n(:)
        integer, allocatable :: counts(:), row_lines(:)
        type(error_type), allocatable :: csv_error
        integer :: stat, k, i, nx, ny, ne, nmu, nsf, npr, nbs, nbn, nseg, nbefore, cond
        logical :: from_csv, geometry_ok
        namelist /fracture/ name, x, y, elements, mu, sf, pressure, condition, bc_s, bc_n, &
            elements_file

        allocate (fractures(info%count))
        if (info%count == 0) return
        allocate (x(max_vertices), y(max_vertices), mu(max_vertices), sf(max_vertices), &
                  pressure(max_vertices), bc_s(max_vertices), bc_n(max_vertices), &
                  elements(max_vertices))
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
            elements = unset_integer
            read (unit, nml=fracture, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_fracture, info, k, stat, iomsg, variables, &
                                      messages)
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
                if (nmu > 0 .or. nsf > 0 .or. npr > 0) then
                    call add(messages, prefix//'mu, sf and pressure come from elements_file;'// &
                             ' do not give them in the group as well')
                end if
                csv_path = resolve(dir, trim(adjustl(elements_file)))
                call read_csv(csv_path, [character(len=8) :: 'x_begin', 'y_begin', 'x_end', &
                              'y_end', 'mu', 'sf', 'pressure'], rows, csv_error, row_lines)
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
                        if (rows(5, i) < 0.0_wp) then
                            call add(messages, prefix//'elements_file '//csv_path//' line '// &
                                     itoa(row_lines(i))//': mu = '//rtoa(rows(5, i))// &
                                     ' must be >= 0')
                        end if
                        if (rows(6, i) < 0.0_wp) then
                            call add(messages, prefix//'elements_file '//csv_path//' line '// &
                                     itoa(row_lines(i))//': sf = '//rtoa(rows(6, i))// &
                                     ' must be >= 0')
                        end if
                    end do
                end if
            else
                if (nx /= ny) then
                    call add(messages, prefix//'x has '//itoa(nx)//' values but y has '// &
                             itoa(ny)//'; give one x and one y per vertex')
                else if (nx < 2) then
                    call add(messages, prefix//'x and y give '//itoa(nx)//' vertices; a '// &
                             'fracture needs at least 2 (or an elements_file)')
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
                    call check_non_negative(mu(1:nmu), 'mu', prefix, messages)
                    call check_non_negative(sf(1:nsf), 'sf', prefix, messages)
                end if
                if (nbs > 0 .or. nbn > 0) then
                    call add(messages, prefix//'bc_s and bc_n are for the TWODD-style '// &
                             "conditions, not for condition 'contact'")
                end if
            else if (cond /= 0) then
                if (.not. from_csv .and. (nmu > 0 .or. nsf > 0 .or. npr > 0)) then
                    call add(messages, prefix//"mu, sf and pressure are for condition "// &
                             "'contact', not for condition '"//trim(condition_names(cond))//"'")
                end if
            end if

            if (geometry_ok) then
                if (.not. from_csv) then
                    if (check_length(nmu, nseg, 'mu', prefix, messages)) &
                        seg_mu = broadcast(mu(1:nmu), nseg, 0.0_wp)
                    if (check_length(nsf, nseg, 'sf', prefix, messages)) &
                        seg_sf = broadcast(sf(1:nsf), nseg, 0.0_wp)
                    if (check_length(npr, nseg, 'pressure', prefix, messages)) &
                        seg_pressure = broadcast(pressure(1:npr), nseg, 0.0_wp)
                end if
                if (check_length(nbs, nseg, 'bc_s', prefix, messages)) &
                    seg_bc_s = broadcast(bc_s(1:nbs), nseg, 0.0_wp)
                if (check_length(nbn, nseg, 'bc_n', prefix, messages)) &
                    seg_bc_n = broadcast(bc_n(1:nbn), nseg, 0.0_wp)
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
                fractures(k)%bc_s = seg_bc_s
                fractures(k)%bc_n = seg_bc_n
            else
                call polyline_elements(x(1:nx), y(1:ny), counts, fractures(k)%x_begin, &
                                       fractures(k)%y_begin, fractures(k)%x_end, &
                                       fractures(k)%y_end)
                fractures(k)%mu = expand_per_segment(seg_mu, counts)
                fractures(k)%sf = expand_per_segment(seg_sf, counts)
                fractures(k)%pressure = expand_per_segment(seg_pressure, counts)
                fractures(k)%bc_s = expand_per_segment(seg_bc_s, counts)
                fractures(k)%bc_n = expand_per_segment(seg_bc_n, counts)
            end if
        end do
    end subroutine read_fracture_groups

    !> &grid name, xmin, xmax, nx, ymin, ymax, ny / (repeated)
    subroutine read_grid_groups(unit, text, path, info, observations, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(observation_input), intent(inout) :: observations(:)
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name
        real(wp) :: xmin, xmax, ymin, ymax
        integer :: nx, ny
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, k, i, j, nbefore, slot
        real(wp), allocatable :: xs(:), ys(:)
        logical :: ok_x, ok_y
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'name:c xmin:r xmax:r nx:i ymin:r ymax:r ny:i'
        namelist /grid/ name, xmin, xmax, nx, ymin, ymax, ny

        if (info%count == 0) return
        rewind (unit)
        do k = 1, info%count
            name = ''
            xmin = unset_real
            xmax = unset_real
            ymin = unset_real
            ymax = unset_real
            nx = unset_integer
            ny = unset_integer
            read (unit, nml=grid, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_grid, info, k, stat, iomsg, variables, &
                                      messages)
                exit
            end if
            slot = info%slot(k)
            call start_observation(observations(slot), path, g_grid, info, k, name, &
                                   observation_grid, prefix)
            nbefore = messages%n
            ok_x = check_axis(xmin, xmax, nx, 'x', prefix, messages, xs)
            ok_y = check_axis(ymin, ymax, ny, 'y', prefix, messages, ys)
            if (ok_x .and. ok_y) then
                if (real(nx, wp) * real(ny, wp) > real(max_observation_points, wp)) then
                    call add(messages, prefix//'nx * ny = '//rtoa(real(nx, wp) * real(ny, wp))// &
                             ' points is more than '//itoa(max_observation_points))
                end if
            end if
            if (messages%n > nbefore) cycle
            observations(slot)%valid = .true.
            observations(slot)%set%nx = nx
            observations(slot)%set%ny = ny
            allocate (observations(slot)%set%x(nx * ny), observations(slot)%set%y(nx * ny))
            do j = 1, ny
                do i = 1, nx
                    observations(slot)%set%x(i + (j - 1) * nx) = xs(i)
                    observations(slot)%set%y(i + (j - 1) * nx) = ys(j)
                end do
            end do
        end do
    end subroutine read_grid_groups

    !> &line name, x_begin, y_begin, x_end, y_end, points / (repeated)
    subroutine read_line_groups(unit, text, path, info, observations, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(observation_input), intent(inout) :: observations(:)
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name
        real(wp) :: x_begin, y_begin, x_end, y_end
        integer :: points
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, k, i, nbefore, slot, n
        logical :: ok, same
        real(wp) :: t
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'name:c x_begin:r y_begin:r x_end:r '// &
            'y_end:r points:i'
        namelist /line/ name, x_begin, y_begin, x_end, y_end, points

        if (info%count == 0) return
        rewind (unit)
        do k = 1, info%count
            name = ''
            x_begin = unset_real
            y_begin = unset_real
            x_end = unset_real
            y_end = unset_real
            points = unset_integer
            read (unit, nml=line, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_line, info, k, stat, iomsg, variables, &
                                      messages)
                exit
            end if
            slot = info%slot(k)
            call start_observation(observations(slot), path, g_line, info, k, name, &
                                   observation_line, prefix)
            nbefore = messages%n
            ok = check_scalar(x_begin, 'x_begin', .true., prefix, messages)
            ok = check_scalar(y_begin, 'y_begin', .true., prefix, messages) .and. ok
            ok = check_scalar(x_end, 'x_end', .true., prefix, messages) .and. ok
            ok = check_scalar(y_end, 'y_end', .true., prefix, messages) .and. ok
            same = .false.
            if (ok) same = x_begin == x_end .and. y_begin == y_end
            if (points == unset_integer) then
                if (.not. same) then
                    call add(messages, prefix//'points is required (the number of points'// &
                             ', both ends included)')
                end if
            else if (points < 1) then
                call add(messages, prefix//'points = '//itoa(points)//' must be at least 1')
            else if (points == 1 .and. ok .and. .not. same) then
                call add(messages, prefix//'points = 1 but the ends differ; give points >= 2 '// &
                         '(both ends count)')
            else if (points > max_observation_points) then
                call add(messages, prefix//'points = '//itoa(points)//' is more than '// &
                         itoa(max_observation_points))
            end if
            if (messages%n > nbefore) cycle
            observations(slot)%valid = .true.
            n = points
            if (same) n = 1
            observations(slot)%set%nx = n
            observations(slot)%set%ny = 1
            allocate (observations(slot)%set%x(n), observations(slot)%set%y(n))
            observations(slot)%set%x(1) = x_begin
            observations(slot)%set%y(1) = y_begin
            do i = 2, n - 1
                t = real(i - 1, wp) / real(n - 1, wp)
                observations(slot)%set%x(i) = x_begin + t * (x_end - x_begin)
                observations(slot)%set%y(i) = y_begin + t * (y_end - y_begin)
            end do
            if (n > 1) then
                observations(slot)%set%x(n) = x_end
                observations(slot)%set%y(n) = y_end
            end if
        end do
    end subroutine read_line_groups

    !> &points name, file / (repeated; a CSV of x,y rows)
    subroutine read_points_groups(unit, text, path, dir, info, observations, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path, dir
        type(group_record), intent(in) :: info
        type(observation_input), intent(inout) :: observations(:)
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: name, file
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        real(wp), allocatable :: rows(:,:)
        type(error_type), allocatable :: csv_error
        integer :: stat, k, slot
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'name:c file:c'
        namelist /points/ name, file

        if (info%count == 0) return
        rewind (unit)
        do k = 1, info%count
            name = ''
            file = ''
            read (unit, nml=points, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_points, info, k, stat, iomsg, variables, &
                                      messages)
                exit
            end if
            slot = info%slot(k)
            call start_observation(observations(slot), path, g_points, info, k, name, &
                                   observation_points, prefix)
            if (len_trim(file) == 0) then
                call add(messages, prefix//'file is required (a CSV of x,y rows)')
                cycle
            end if
            call read_csv(resolve(dir, trim(adjustl(file))), [character(len=1) :: 'x', 'y'], &
                          rows, csv_error)
            if (allocated(csv_error)) then
                call add(messages, prefix_lines(prefix//'file: ', csv_error%message))
                deallocate (csv_error)
                cycle
            end if
            if (size(rows, 2) > max_observation_points) then
                call add(messages, prefix//'more than '//itoa(max_observation_points)//' points')
                cycle
            end if
            observations(slot)%valid = .true.
            observations(slot)%set%nx = size(rows, 2)
            observations(slot)%set%ny = 1
            observations(slot)%set%x = rows(1, :)
            observations(slot)%set%y = rows(2, :)
        end do
    end subroutine read_points_groups

    !> &solver lcp_method, open_cohesion /
    subroutine read_solver_group(unit, text, path, info, model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: lcp_method, open_cohesion
        character(len=512) :: iomsg
        type(error_type), allocatable :: problems
        integer :: stat
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'lcp_method:c open_cohesion:c'
        namelist /solver/ lcp_method, open_cohesion

        if (info%count == 0) return
        lcp_method = 'auto'
        open_cohesion = 'kept'
        rewind (unit)
        read (unit, nml=solver, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_solver, info, 1, stat, iomsg, variables, messages)
            return
        end if
        call parse_solver_options(lcp_method, open_cohesion, model%solver, problems)
        if (allocated(problems)) then
            call add(messages, prefix_lines(group_prefix(path, g_solver, info, 1), &
                                            problems%message))
        end if
    end subroutine read_solver_group

    !> &symmetry kind, xsym, ysym / (optional; TWODD's KSYM: kind 'none', 'x' (mirror about
    !> the line x = xsym), 'y' (about y = ysym) or 'both'; image elements are implicit)
    subroutine read_symmetry_group(unit, text, path, info, model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: kind
        real(wp) :: xsym, ysym
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, k
        logical :: ok
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'kind:c xsym:r ysym:r'
        namelist /symmetry/ kind, xsym, ysym

        model%elements%symmetry%kind = symmetry_none
        if (info%count == 0) return
        kind = 'none'
        xsym = 0.0_wp
        ysym = 0.0_wp
        rewind (unit)
        read (unit, nml=symmetry, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_symmetry, info, 1, stat, iomsg, variables, &
                                  messages)
            return
        end if
        prefix = group_prefix(path, g_symmetry, info, 1)
        k = find_name(lower(trim(adjustl(kind))), symmetry_names)
        if (k == 0) then
            call add(messages, prefix//"kind = '"//trim(adjustl(kind))// &
                     "' is not one of 'none', 'x', 'y', 'both'")
        end if
        ok = check_scalar(xsym, 'xsym', .false., prefix, messages)
        ok = check_scalar(ysym, 'ysym', .false., prefix, messages) .and. ok
        if (k == 0 .or. .not. ok) return
        ! The kinds are numbered in the order of their names.
        model%elements%symmetry%kind = k
        model%elements%symmetry%xsym = xsym
        model%elements%symmetry%ysym = ysym
    end subroutine read_symmetry_group

    !> &output file / (relative to the input file's folder; default: the input file's
    !> base name with extension .h5, in the current folder)
    subroutine read_output_group(unit, text, path, dir, info, model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path, dir
        type(group_record), intent(in) :: info
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: file
        character(len=512) :: iomsg
        integer :: stat
        !> Variables of the group and their types (c text, r real, i integer)
        character(len=*), parameter :: variables = 'file:c'
        namelist /output/ file

        model%output_file = base_name(path, .false.)//'.h5'
        if (info%count == 0) return
        file = ''
        rewind (unit)
        read (unit, nml=output, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_output, info, 1, stat, iomsg, variables, messages)
            return
        end if
        if (len_trim(file) > 0) model%output_file = resolve(dir, trim(adjustl(file)))
    end subroutine read_output_group

    ! ------------------------------------------------------------------------------------
    ! Assembling the model
    ! ------------------------------------------------------------------------------------

    !> Reject duplicate names of fractures and of observation sets, and bad set names.
    subroutine check_names(path, fractures, observations, messages)
        character(len=*), intent(in) :: path
        type(fracture_input), intent(in) :: fractures(:)
        type(observation_input), intent(in) :: observations(:)
        type(message_list), intent(inout) :: messages
        integer :: i, j

        do i = 1, size(fractures)
            if (.not. allocated(fractures(i)%name)) cycle
            do j = 1, i - 1
                if (.not. allocated(fractures(j)%name)) cycle
                if (fractures(i)%name == fractures(j)%name) then
                    call add(messages, path//': '//fractures(i)%label//": name '"// &
                             fractures(i)%name//"' is already used by "//fractures(j)%label)
                    exit
                end if
            end do
        end do
        do i = 1, size(observations)
            if (.not. allocated(observations(i)%set%name)) cycle
            if (index(observations(i)%set%name, '/') > 0 .or. &
                observations(i)%set%name == '.') then
                call add(messages, path//': '//observations(i)%label//": name '"// &
                         observations(i)%set%name//"' may not contain '/' or be '.'")
            end if
            do j = 1, i - 1
                if (.not. allocated(observations(j)%set%name)) cycle
                if (observations(i)%set%name == observations(j)%set%name) then
                    call add(messages, path//': '//observations(i)%label//": name '"// &
                             observations(i)%set%name//"' is already used by "// &
                             observations(j)%label)
                    exit
                end if
            end do
        end do
    end subroutine check_names

    !> Put the validated fractures and observation sets into the model.
    subroutine build_model(fractures, observations, model)
        type(fracture_input), intent(in) :: fractures(:)
        type(observation_input), intent(in) :: observations(:)
        type(model_type), intent(inout) :: model
        integer :: k, n, first, last

        n = 0
        do k = 1, size(fractures)
            n = n + size(fractures(k)%x_begin)
        end do
        call allocate_elements(model%elements, n)
        allocate (model%elements%x_mid(n), model%elements%y_mid(n), &
                  model%elements%half_length(n), model%elements%cos_beta(n), &
                  model%elements%sin_beta(n))
        allocate (model%fractures(size(fractures)))
        last = 0
        do k = 1, size(fractures)
            first = last + 1
            last = last + size(fractures(k)%x_begin)
            model%fractures(k)%name = fractures(k)%name
            model%fractures(k)%first_element = first
            model%fractures(k)%last_element = last
            model%elements%x_begin(first:last) = fractures(k)%x_begin
            model%elements%y_begin(first:last) = fractures(k)%y_begin
            model%elements%x_end(first:last) = fractures(k)%x_end
            model%elements%y_end(first:last) = fractures(k)%y_end
            model%elements%fracture_id(first:last) = k
            model%elements%condition(first:last) = fractures(k)%condition
            model%elements%bc_s(first:last) = fractures(k)%bc_s
            model%elements%bc_n(first:last) = fractures(k)%bc_n
            model%elements%mu(first:last) = fractures(k)%mu
            model%elements%sf(first:last) = fractures(k)%sf
            model%elements%pressure(first:last) = fractures(k)%pressure
        end do
        call compute_geometry(model%elements)

        allocate (model%observations(size(observations)))
        do k = 1, size(observations)
            model%observations(k) = observations(k)%set
        end do
    end subroutine build_model

    ! ------------------------------------------------------------------------------------
    ! Validation helpers
    ! ------------------------------------------------------------------------------------

    !> Message for a group that exists but could not be read: our own diagnosis of the
    !> group text (unknown variable, value of the wrong type) plus gfortran's iomsg.
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
        if (len(problem) > 0) then
            message = prefix//problem//' (gfortran: '//trim(iomsg)//')'
            if (index(problem, 'unknown variable') == 1) then
                message = message//'; the variables of this group are: '//spec_names(spec)
            end if
            return
        end if
        message = prefix//'cannot be read (gfortran: '//trim(iomsg)//'): '
        if (stat < 0) then
            message = message//'a value of the wrong type, or a group not closed by /'
        else
            message = message//'a misspelled variable, a value of the wrong type or a '// &
                      'missing quote'
        end if
        message = message//'; the variables of this group are: '//spec_names(spec)
    end function malformed_message

    !> "file: &group k (line n): ", the prefix of occurrence k of a group before its name
    !> is known.
    function group_prefix(path, group, info, k) result(prefix)
        character(len=*), intent(in) :: path
        integer, intent(in) :: group, k
        type(group_record), intent(in) :: info
        character(len=:), allocatable :: prefix

        prefix = path//': '//group_label(group, k, info%lines(k), '')//': '
    end function group_prefix

    !> Report occurrence k of a group that could not be read; for a repeatable group also
    !> diagnose the occurrences after it, which are then not read.
    subroutine report_malformed(text, path, group, info, k, stat, iomsg, spec, messages)
        character(len=*), intent(in) :: text, path
        integer, intent(in) :: group, k
        type(group_record), intent(in) :: info
        !> iostat and iomsg of the failed read
        integer, intent(in) :: stat
        character(len=*), intent(in) :: iomsg
        !> Variables of the group with their types: "name:c x:r n:i"
        character(len=*), intent(in) :: spec
        type(message_list), intent(inout) :: messages

        call add(messages, malformed_message(group_prefix(path, group, info, k), stat, iomsg, &
                 spec, text(info%starts(k):info%ends(k))))
        if (repeatable(group)) call diagnose_rest(text, path, group, info, spec, k + 1, messages)
    end subroutine report_malformed

    !> Label, name (or <kind>_<k>), kind and message prefix of the observation set made by
    !> occurrence k of a &grid, &line or &points group.
    subroutine start_observation(observation, path, group, info, k, name, kind, prefix)
        type(observation_input), intent(inout) :: observation
        character(len=*), intent(in) :: path
        integer, intent(in) :: group, k
        type(group_record), intent(in) :: info
        !> The name given in the group ('' when none)
        character(len=*), intent(in) :: name
        !> observation_grid, observation_line or observation_points
        integer, intent(in) :: kind
        character(len=:), allocatable, intent(out) :: prefix

        observation%label = group_label(group, k, info%lines(k), trim(adjustl(name)))
        observation%set%name = default_name(name, trim(namelist_group_names(group)), k)
        observation%set%kind = kind
        prefix = path//': '//observation%label//': '
    end subroutine start_observation

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
            end select
        end do
    end function diagnose_group

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

    !> Check a scalar real: NaN or Inf is an error; so is a missing required value.
    !> Return true when the value is given and finite.
    function check_scalar(value, name, required, prefix, messages) result(ok)
        real(wp), intent(in) :: value
        character(len=*), intent(in) :: name, prefix
        logical, intent(in) :: required
        type(message_list), intent(inout) :: messages
        logical :: ok

        ok = .false.
        if (value == unset_real) then
            if (required) call add(messages, prefix//name//' is required')
        else if (.not. within_limits(value)) then
            call add(messages, prefix//name//' = '//rtoa(value)//limits_text)
        else
            ok = .true.
        end if
    end function check_scalar

    !> Number of leading given entries of a namelist array; a given entry after an unset
    !> one, and NaN or Inf, are errors.
    function count_given(values, name, prefix, messages) result(n)
        real(wp), intent(in) :: values(:)
        character(len=*), intent(in) :: name, prefix
        type(message_list), intent(inout) :: messages
        integer :: n
        integer :: i

        n = 0
        do while (n < size(values))
            if (values(n + 1) == unset_real) exit
            n = n + 1
        end do
        do i = n + 2, size(values)
            if (values(i) /= unset_real) then
                call add(messages, prefix//name//'('//itoa(i)//') is given but '//name// &
                         '('//itoa(n + 1)//') is not; give the values without gaps')
                exit
            end if
        end do
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
        integer :: i

        n = 0
        do while (n < size(values))
            if (values(n + 1) == unset_integer) exit
            n = n + 1
        end do
        do i = n + 2, size(values)
            if (values(i) /= unset_integer) then
                call add(messages, prefix//name//'('//itoa(i)//') is given but '//name// &
                         '('//itoa(n + 1)//') is not; give the values without gaps')
                exit
            end if
        end do
    end function count_given_integers

    !> A per-segment array must have 1 value (for every segment) or one per segment.
    !> Return true when its length fits (an absent array fits: its default applies).
    function check_length(n, nseg, name, prefix, messages) result(ok)
        integer, intent(in) :: n, nseg
        character(len=*), intent(in) :: name, prefix
        type(message_list), intent(inout) :: messages
        logical :: ok

        ok = n == 0 .or. n == 1 .or. n == nseg
        if (.not. ok) then
            call add(messages, prefix//name//' has '//itoa(n)//' values; give 1 (for every '// &
                     'segment) or '//itoa(nseg)//' (one per segment)')
        end if
    end function check_length

    !> Every finite value must be >= 0 (the first violation is reported).
    subroutine check_non_negative(values, name, prefix, messages)
        real(wp), intent(in) :: values(:)
        character(len=*), intent(in) :: name, prefix
        type(message_list), intent(inout) :: messages
        integer :: i

        do i = 1, size(values)
            if (.not. within_limits(values(i))) cycle
            if (values(i) < 0.0_wp) then
                call add(messages, prefix//name//'('//itoa(i)//') = '//rtoa(values(i))// &
                         ' must be >= 0')
                exit
            end if
        end do
    end subroutine check_non_negative

    !> Check one axis of a grid and return its coordinates.
    function check_axis(vmin, vmax, n, axis, prefix, messages, coords) result(ok)
        real(wp), intent(in) :: vmin, vmax
        integer, intent(in) :: n
        character(len=*), intent(in) :: axis, prefix
        type(message_list), intent(inout) :: messages
        real(wp), allocatable, intent(out) :: coords(:)
        logical :: ok
        logical :: min_ok, max_ok
        integer :: i

        ok = .false.
        min_ok = check_scalar(vmin, axis//'min', .true., prefix, messages)
        max_ok = check_scalar(vmax, axis//'max', .false., prefix, messages)
        if (vmax /= unset_real .and. .not. within_limits(vmax)) return
        if (n == unset_integer) then
            call add(messages, prefix//'n'//axis//' is required (the number of grid lines)')
            return
        else if (n < 1) then
            call add(messages, prefix//'n'//axis//' = '//itoa(n)//' must be at least 1')
            return
        else if (n > max_observation_points) then
            call add(messages, prefix//'n'//axis//' = '//itoa(n)//' is more than '// &
                     itoa(max_observation_points))
            return
        end if
        if (n > 1 .and. .not. max_ok .and. vmax == unset_real) then
            call add(messages, prefix//axis//'max is required when n'//axis//' > 1')
            return
        end if
        if (.not. min_ok) return
        ok = .true.
        allocate (coords(n))
        coords(1) = vmin
        do i = 2, n - 1
            coords(i) = vmin + (vmax - vmin) * (real(i - 1, wp) / real(n - 1, wp))
        end do
        if (n > 1) coords(n) = vmax
    end function check_axis

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

    ! ------------------------------------------------------------------------------------
    ! Small text helpers
    ! ------------------------------------------------------------------------------------

    !> Append one line to the messages.
    subroutine add(messages, message)
        type(message_list), intent(inout) :: messages
        character(len=*), intent(in) :: message

        if (.not. allocated(messages%text)) messages%text = ''
        if (messages%n > 0) messages%text = messages%text//newline
        messages%text = messages%text//message
        messages%n = messages%n + 1
    end subroutine add

    !> "&fracture 2 'east' (line 14)" for repeatable groups, "&model (line 1)" otherwise.
    function group_label(group, ordinal, line, name) result(label)
        integer, intent(in) :: group, ordinal, line
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: label

        label = '&'//trim(namelist_group_names(group))
        if (repeatable(group)) label = label//' '//itoa(ordinal)
        if (len_trim(name) > 0) label = label//" '"//trim(name)//"'"
        label = label//' (line '//itoa(line)//')'
    end function group_label

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

    !> Folder of a path including its trailing '/', or '' when there is none.
    pure function folder_of(path) result(dir)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: dir
        integer :: slash

        slash = index(path, '/', back=.true.)
        dir = path(1:slash)
    end function folder_of

    !> A path written in the input file, relative to the input file's folder.
    pure function resolve(dir, file) result(path)
        character(len=*), intent(in) :: dir, file
        character(len=:), allocatable :: path

        if (len(file) > 0) then
            if (file(1:1) == '/') then
                path = file
                return
            end if
        end if
        path = dir//file
    end function resolve

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

    pure function is_name_character(c) result(yes)
        character(len=1), intent(in) :: c
        logical :: yes

        yes = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z') .or. &
              (c >= '0' .and. c <= '9') .or. c == '_'
    end function is_name_character

end module ddc_input_namelist
