!> The namelist groups of a ddc2d input file: their table (name, whether they repeat, and
!> their variables with types), and the scan of a file's text that finds them.
!>
!> The whole file is scanned for `&group` starts (case-insensitive, ignoring `!` comments and
!> quoted text) to count each group and reject unknown ones before anything is read: gfortran
!> reports a value of the wrong type in the last group as "End of file", the same as a
!> missing group, so the readers need to know which groups exist. The variable lists of the
!> table are the ones the messages print and the diagnosis of a bad group checks against;
!> tests/architecture/check_sources.py holds every reader's namelist statement to them.
module ddc_input_namelist_groups
    use ddc_error, only: exit_bad_input
    use ddc_text, only: newline, itoa, lower, join_integers
    implicit none
    private

    public :: group_spec, namelist_groups, group_record, message_list, add
    public :: scan_groups, group_line, group_label, group_prefix, is_name_character
    public :: g_model, g_remote_stress, g_fracture, g_grid, g_line, g_points, g_solver, &
        g_output, g_symmetry, g_sweep, g_pore_fluid, g_load_path, g_growth
    public :: g_initiation, g_injection, g_material, g_cycle, g_body, g_fluid

    !> One namelist group: its name, whether it may appear more than once, and its variables
    !> with their types ("name:c x:r n:i": c text, r real, i integer)
    type :: group_spec
        character(len=13) :: name
        logical :: repeatable
        character(len=480) :: variables
    end type group_spec

    !> Index of each group in namelist_groups
    integer, parameter :: g_model = 1, g_remote_stress = 2, g_fracture = 3, g_grid = 4, &
                          g_line = 5, g_points = 6, g_solver = 7, g_output = 8, g_symmetry = 9, &
                          g_sweep = 10, g_pore_fluid = 11, g_load_path = 12, g_growth = 13
    integer, parameter :: g_initiation = 14, g_injection = 15, g_material = 16, g_cycle = 17
    integer, parameter :: g_body = 18, g_fluid = 19

    !> Every group ddc2d knows (&sweep is read by ddc_input_sweep; the model reader skips it)
    type(group_spec), parameter :: namelist_groups(19) = [ &
        group_spec('model', .false., 'title:c youngs_modulus:r poissons_ratio:r '// &
                   'length_unit:c stress_unit:c time_unit:c domain:c interface_y:r'), &
        group_spec('remote_stress', .false., 'sxx:r syy:r sxy:r dsxx_dy:r dsyy_dy:r dsxy_dy:r'), &
        group_spec('fracture', .true., 'name:c x:r y:r elements:i mu:r sf:r pressure:r '// &
                   'condition:c bc_s:r bc_n:r elements_file:c tensile_strength:r '// &
                   'sf_residual:r mu_dynamic:r slip_weakening_distance:r shear_stiffness:r '// &
                   'normal_stiffness:r opening_weakening_distance:r diffusivity:r '// &
                   'transmissivity:r a:r b:r dc:r f0:r v0:r v_init:r sigma0:r tau0:r '// &
                   'residual_aperture:r'), &
        group_spec('grid', .true., 'name:c xmin:r xmax:r nx:i ymin:r ymax:r ny:i'), &
        group_spec('line', .true., 'name:c x_begin:r y_begin:r x_end:r y_end:r points:i'), &
        group_spec('points', .true., 'name:c file:c'), &
        group_spec('solver', .false., 'lcp_method:c open_cohesion:c block_size:i matrix:c '// &
                  'hmatrix_tolerance:r hmatrix_leaf_size:i hmatrix_eta:r k_method:c '// &
                  'k_zone_elements:i'), &
        group_spec('output', .false., 'file:c'), &
        group_spec('symmetry', .false., 'kind:c xsym:r ysym:r'), &
        group_spec('sweep', .false., 'combine:c parameters:c values_1:r values_2:r '// &
                   'values_3:r values_4:r values_5:r values_6:r'), &
        group_spec('pore_fluid', .false., 'p0:r dp_dy:r'), &
        group_spec('load_path', .false., 'sxx:r syy:r sxy:r dsxx_dy:r dsyy_dy:r dsxy_dy:r '// &
                   'p0:r steps:i time:r'), &
        group_spec('growth', .false., 'steps:i toughness:r increment:r element_length:r '// &
                   'tips:c fractures:c criterion:c max_corrections:i new_mu:r new_sf:r '// &
                   'angle_range:r angle_step:r work_threshold:r work_mode:c angle_search:c '// &
                   'new_tensile_strength:r new_sf_residual:r new_mu_dynamic:r '// &
                   'new_slip_weakening_distance:r new_opening_weakening_distance:r '// &
                   'new_shear_stiffness:r new_normal_stiffness:r'), &
        group_spec('initiation', .false., 'tensile_strength:r probe_distance:r flaw_x:r '// &
                   'flaw_y:r flaw_length:r'), &
        group_spec('injection', .true., 'name:c fracture:c x:r y:r overpressure:r rate:r '// &
                   'start:r stop:r'), &
        group_spec('material', .true., 'name:c youngs_modulus:r poissons_ratio:r'), &
        group_spec('cycle', .false., 'end_time:r tolerance:r shear_wave_speed:r '// &
                   'radiation_damping:r plate_rate:r seismic_threshold:r state_law:c '// &
                   'output_interval:r event_output_interval:r profile_spacing:r '// &
                   'checkpoint_interval:r'), &
        group_spec('body', .false., 'x:r y:r elements:i condition:c bc_s:r bc_n:r '// &
                   'bc_s_end:r bc_n_end:r'), &
        group_spec('fluid', .false., 'viscosity:r compressibility:r leak_off_coefficient:r')]

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
        !> An unknown group's name is this one's, misspelled (its absence is no news then)
        logical :: misspelled = .false.
    end type group_record

    !> Violations found so far, one per line.
    type :: message_list
        !> The lines, joined with newlines
        character(len=:), allocatable :: text
        !> Number of lines
        integer :: n = 0
        !> Exit code of the error they make: exit_bad_input, or exit_out_of_memory when an
        !> allocation for the input failed
        integer :: code = exit_bad_input
    end type message_list

contains

    !> Line of the first occurrence of the known group `name` in the text of an input
    !> file, 0 when it is absent (comments and quoted text are ignored).
    function group_line(text, name) result(line)
        !> Text of the input file
        character(len=*), intent(in) :: text
        !> Name of the group, without '&'
        character(len=*), intent(in) :: name
        !> Line number, 0 when the group is absent
        integer :: line
        type(group_record) :: groups(size(namelist_groups))
        type(message_list) :: ignored
        integer :: nobs, g

        line = 0
        g = group_index(name)
        if (g == 0) return
        call scan_groups(text, '', groups, nobs, ignored)
        if (groups(g)%count > 0) line = groups(g)%lines(1)
    end function group_line

    !> Count every group in text and note its lines; report unknown and repeated groups.
    subroutine scan_groups(text, path, groups, nobs, messages)
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Where each group of namelist_groups occurs, shape (size(namelist_groups))
        type(group_record), intent(inout) :: groups(:)
        !> Number of observation groups (grid, line, points)
        integer, intent(out) :: nobs
        !> Unknown and repeated groups are added here
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
                    g = group_index(name)
                    if (g == 0) then
                        known = 'known groups: &'//trim(namelist_groups(1)%name)
                        do k = 2, size(namelist_groups)
                            known = known//', &'//trim(namelist_groups(k)%name)
                        end do
                        k = nearest_group(name)
                        if (k > 0) then
                            groups(k)%misspelled = .true.
                            known = 'did you mean &'//trim(namelist_groups(k)%name)//'?; '//known
                        end if
                        call add(messages, path//' line '//itoa(line)//': &'//name// &
                                 ' is not a ddc2d group; '//known)
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
            if (.not. namelist_groups(g)%repeatable .and. groups(g)%count > 1) then
                call add(messages, path//': &'//trim(namelist_groups(g)%name)//' appears '// &
                         itoa(groups(g)%count)//' times (lines '// &
                         join_integers(groups(g)%lines)//'); give it at most once')
            end if
        end do
    end subroutine scan_groups

    !> "&fracture 2 'east' (line 14)" for repeatable groups, "&model (line 1)" otherwise.
    function group_label(group, ordinal, line, name) result(label)
        !> Index of the group in namelist_groups, its occurrence and the line it starts on
        integer, intent(in) :: group, ordinal, line
        !> The name given in the group ('' when none)
        character(len=*), intent(in) :: name
        !> The label
        character(len=:), allocatable :: label

        label = '&'//trim(namelist_groups(group)%name)
        if (namelist_groups(group)%repeatable) label = label//' '//itoa(ordinal)
        if (len_trim(name) > 0) label = label//" '"//trim(name)//"'"
        label = label//' (line '//itoa(line)//')'
    end function group_label

    !> "file: &group k (line n): ", the prefix of occurrence k of a group before its name
    !> is known.
    function group_prefix(path, group, info, k) result(prefix)
        !> Path of the input file
        character(len=*), intent(in) :: path
        !> Index of the group in namelist_groups, and the occurrence
        integer, intent(in) :: group, k
        !> Where the group occurs (scan_groups)
        type(group_record), intent(in) :: info
        !> The prefix
        character(len=:), allocatable :: prefix

        prefix = path//': '//group_label(group, k, info%lines(k), '')//': '
    end function group_prefix

    !> Append one line to the messages.
    subroutine add(messages, message)
        !> The messages so far
        type(message_list), intent(inout) :: messages
        !> The new line
        character(len=*), intent(in) :: message

        if (.not. allocated(messages%text)) messages%text = ''
        if (messages%n > 0) messages%text = messages%text//newline
        messages%text = messages%text//message
        messages%n = messages%n + 1
    end subroutine add

    !> True for the characters of a Fortran name: letters, digits and '_'.
    pure function is_name_character(c) result(yes)
        !> The character
        character(len=1), intent(in) :: c
        logical :: yes

        yes = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z') .or. &
              (c >= '0' .and. c <= '9') .or. c == '_'
    end function is_name_character

    !> Index of the group called name in namelist_groups, 0 when there is none. (A loop,
    !> not find_name: namelist_groups%name would be copied to a temporary on every call.)
    pure integer function group_index(name)
        character(len=*), intent(in) :: name
        integer :: g

        group_index = 0
        do g = 1, size(namelist_groups)
            if (trim(namelist_groups(g)%name) == trim(name)) then
                group_index = g
                return
            end if
        end do
    end function group_index

    !> The known group whose name differs from `name` by at most two letters (inserted,
    !> deleted or changed: &fractures, &modle), 0 when none does.
    pure integer function nearest_group(name)
        character(len=*), intent(in) :: name
        integer :: g, best, distance

        nearest_group = 0
        best = 3
        do g = 1, size(namelist_groups)
            distance = edit_distance(name, trim(namelist_groups(g)%name))
            if (distance < best) then
                best = distance
                nearest_group = g
            end if
        end do
    end function nearest_group

    !> The number of letters to insert, delete or change to make a into b (Levenshtein).
    pure integer function edit_distance(a, b)
        character(len=*), intent(in) :: a, b
        integer :: row(0:len(b)), i, j, diagonal, above

        row = [(j, j = 0, len(b))]
        do i = 1, len(a)
            diagonal = row(0)
            row(0) = i
            do j = 1, len(b)
                above = row(j)
                row(j) = min(row(j) + 1, row(j - 1) + 1, &
                             diagonal + merge(0, 1, a(i:i) == b(j:j)))
                diagonal = above
            end do
        end do
        edit_distance = row(len(b))
    end function edit_distance

end module ddc_input_namelist_groups
