!> Read a ddc2d model from a namelist input file (docs/input-reference.md).
!>
!> The whole file is read first and scanned for its groups (ddc_input_namelist_groups).
!> Each group is then read the counted number of times with iostat and iomsg by its reader
!> (ddc_input_namelist_settings, _fracture, _observations, _growth): a read failure for a
!> group known to exist means the group is malformed, and ddc_input_namelist_diagnosis says
!> why. Defaults are set to an "unset" sentinel before every read, so given entries can be
!> counted; every value is validated NaN-safely and all violations are reported at once, one
!> per line, each naming the file, the group (with its ordinal and name when repeatable) and
!> the variable.
module ddc_input_namelist
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error
    use ddc_model_capabilities, only: run_refusal, operator_hierarchical
    use ddc_model_types, only: model_type, condition_contact, symmetry_none, symmetry_names, &
        symmetry_x, domain_half_plane, domain_bimaterial, strength_law_count, &
        growth_criterion_work
    use ddc_model_laws, only: strength_law, strength_laws, set_law
    use ddc_model_rate_state, only: set_rate_state
    use ddc_text, only: itoa, rtoa, prefix_lines
    use ddc_version, only: with_hmatrix
    use ddc_input_text_file, only: read_text_file, open_namelist, folder_of
    use ddc_mesh_geometry, only: allocate_elements, compute_geometry
    use ddc_mesh_polyline, only: crossing_fraction, split_at_height, snap_to_height
    use ddc_mesh_checks, only: check_elements
    use ddc_input_namelist_groups, only: namelist_groups, group_record, message_list, add, &
        scan_groups, g_model, g_remote_stress, g_fracture, g_grid, g_line, g_points, g_solver, &
        g_output, g_symmetry, g_pore_fluid, g_load_path, g_growth, g_injection, g_material, &
        g_initiation, g_body, g_fluid
    use ddc_input_namelist_growth, only: read_growth_group
    use ddc_input_namelist_initiation, only: read_initiation_group, check_flaw_points
    use ddc_input_namelist_injection, only: read_injection_groups, check_injection_points, &
        read_fluid_group, check_fluid_model
    use ddc_input_namelist_body, only: read_body_group, check_body_model
    use ddc_input_namelist_values, only: text_length
    use ddc_input_namelist_settings, only: read_model_group, read_remote_stress_group, &
        read_pore_fluid_group, read_solver_group, read_symmetry_group, read_output_group, &
        read_load_path_group, read_material_groups
    use ddc_input_namelist_fracture, only: fracture_input, read_fracture_groups
    use ddc_input_namelist_cycle, only: read_cycle_group
    use ddc_contact_options, only: matrix_hierarchical
    use ddc_input_namelist_observations, only: observation_input, read_grid_groups, &
        read_line_groups, read_points_groups
    implicit none
    private

    public :: read_namelist_model

    !> An element that crosses the interface of two bonded half-planes closer to an end
    !> than this fraction of its length is refused (split there, it would leave a sliver)
    real(wp), parameter :: split_tolerance = 1.0e-6_wp

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
        type(group_record) :: groups(size(namelist_groups))
        type(message_list) :: messages
        type(fracture_input), allocatable :: fractures(:)
        type(observation_input), allocatable :: observations(:)
        integer :: unit, nobs

        call read_text_file(path, text, error)
        if (allocated(error)) return
        model%input_file = path
        model%input_text = text
        dir = folder_of(path)
        messages%text = ''

        call scan_groups(text, path, groups, nobs, messages)
        ! A misspelled group was reported as unknown: its absence is no news.
        if (groups(g_model)%count == 0 .and. .not. groups(g_model)%misspelled) then
            call add(messages, path//': the &model group is missing (it gives youngs_modulus'// &
                     ' and poissons_ratio)')
        end if
        if (groups(g_fracture)%count == 0 .and. .not. groups(g_fracture)%misspelled .and. &
            groups(g_body)%count == 0) then
            call add(messages, path//': no &fracture group: a model needs at least one '// &
                     'fracture (or a finite body, &body)')
        end if

        call open_namelist(path, text, unit, error)
        if (allocated(error)) return
        allocate (observations(nobs))
        call read_model_group(unit, text, path, groups(g_model), model, messages)
        call read_material_groups(unit, text, path, groups(g_material), model, messages)
        call read_remote_stress_group(unit, text, path, groups(g_remote_stress), model, messages)
        call read_fracture_groups(unit, text, path, dir, groups(g_fracture), fractures, messages)
        call read_grid_groups(unit, text, path, groups(g_grid), observations, messages)
        call read_line_groups(unit, text, path, groups(g_line), observations, messages)
        call read_points_groups(unit, text, path, dir, groups(g_points), observations, messages)
        call read_solver_group(unit, text, path, groups(g_solver), model, messages)
        call read_output_group(unit, text, path, dir, groups(g_output), model, messages)
        call read_symmetry_group(unit, text, path, groups(g_symmetry), model, messages)
        call read_pore_fluid_group(unit, text, path, groups(g_pore_fluid), model, messages)
        ! A fracture that could not be read may be a contact one: its own message is enough.
        ! A model that grows needs none: its geometry changes, so its loads do not superpose.
        call read_load_path_group(unit, text, path, groups(g_load_path), &
                                  groups(g_growth)%count > 0 .or. &
                                  any(.not. fractures%valid .or. &
                                      fractures%condition == condition_contact), model, messages)
        call read_growth_group(unit, text, path, groups, fractures, model, messages)
        call read_initiation_group(unit, text, path, groups, model, messages)
        call read_injection_groups(unit, text, path, groups(g_injection), &
                                   names_of(fractures), model, messages)
        call read_cycle_group(unit, text, path, groups, fractures, model, messages)
        call read_body_group(unit, text, path, groups(g_body), model, messages)
        call read_fluid_group(unit, text, path, groups(g_fluid), model, messages)
        close (unit)

        call check_names(path, fractures, observations, messages)
        call check_half_plane(path, model, fractures, observations, messages)
        call snap_to_interface(model, fractures)
        call check_bimaterial(path, model, fractures, groups, messages)
        if (messages%n > 0) then
            call set_error(error, messages%code, messages%text)
            return
        end if

        call build_model(fractures, observations, model)
        call check_flaw_points(path, groups, model, messages)
        call check_injection_points(path, groups(g_injection), model, messages)
        call check_fluid_model(path, groups, model, messages)
        call check_matrix(path, model, messages)
        call check_body_model(path, model, messages)
        if (messages%n > 0) then
            call set_error(error, messages%code, messages%text)
            return
        end if
        call check_elements(model%elements, model%fractures, error)
        if (allocated(error)) then
            error%message = prefix_lines(path//': ', error%message)
        end if
    end subroutine read_namelist_model

    !> The fractures' names ('' for a group that was not read).
    pure function names_of(fractures) result(names)
        type(fracture_input), intent(in) :: fractures(:)
        character(len=text_length) :: names(size(fractures))
        integer :: k

        names = ''
        do k = 1, size(fractures)
            if (allocated(fractures(k)%name)) names(k) = fractures(k)%name
        end do
    end function names_of

    !> matrix = 'hierarchical' on a model a hierarchical matrix does not solve
    !> (run_refusal: docs/theory/hierarchical.md#what-it-solves), or in a build
    !> without hmat-oss, is refused.
    subroutine check_matrix(path, model, messages)
        character(len=*), intent(in) :: path
        type(model_type), intent(in) :: model
        type(message_list), intent(inout) :: messages
        character(len=:), allocatable :: what

        if (model%solver%matrix /= matrix_hierarchical) return
        if (.not. with_hmatrix) then
            call add(messages, path//": &solver: matrix = 'hierarchical' needs hmat-oss, "// &
                     "and this ddc2d was built without it (CMake option DDC2D_HMATRIX=OFF): "// &
                     "use matrix = 'dense' or 'auto'")
            return
        end if
        what = run_refusal(model, operator_hierarchical)
        if (len(what) == 0) return
        call add(messages, path//": &solver: matrix = 'hierarchical' does not solve "//what// &
                 " yet: use matrix = 'dense' or 'auto'")
    end subroutine check_matrix

    !> Half-plane rules (docs/theory/earth.md#a-free-surface): every vertex and field point at
    !> y <= 0, no element on the surface, a remote stress that is traction-free at y = 0, symmetry
    !> about x only.
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

    !> Rules of two bonded half-planes
    !> (docs/theory/bimaterial.md#elements-and-points-at-the-interface): symmetry about a
    !> vertical line only (a line y = ysym would mirror one material into the other), no
    !> element crossing the interface within split_tolerance of its length from an end (it
    !> is split there), growth by MTS only (a tip stops before the interface) and no new
    !> fractures yet.
    subroutine check_bimaterial(path, model, fractures, groups, messages)
        character(len=*), intent(in) :: path
        type(model_type), intent(in) :: model
        type(fracture_input), intent(in) :: fractures(:)
        type(group_record), intent(in) :: groups(:)
        type(message_list), intent(inout) :: messages
        character(len=:), allocatable :: prefix
        integer :: k, i

        if (model%elements%domain /= domain_bimaterial) return
        prefix = path//": &model domain = 'bimaterial': "
        if (model%elements%symmetry%kind /= symmetry_none .and. &
            model%elements%symmetry%kind /= symmetry_x) then
            call add(messages, prefix//"&symmetry kind = '"// &
                     trim(symmetry_names(model%elements%symmetry%kind))//"' is not "// &
                     "available with two materials; only kind = 'x' (a vertical line)")
        end if
        if (groups(g_initiation)%count > 0) then
            call add(messages, prefix//'&initiation is not available yet with two '// &
                     'materials (docs/theory/bimaterial.md#growth)')
        end if
        if (groups(g_growth)%count > 0 .and. &
            model%growth%criterion == growth_criterion_work) then
            call add(messages, prefix//"&growth criterion = 'work' is not available yet "// &
                     "with two materials (its threshold takes one material): use 'mts' "// &
                     '(docs/theory/bimaterial.md#growth)')
        end if
        do k = 1, size(fractures)
            if (.not. fractures(k)%valid) cycle
            associate (t => crossing_fraction(fractures(k)%y_begin, fractures(k)%y_end, &
                                              model%interface_y))
                i = findloc(t >= 0.0_wp .and. min(t, 1.0_wp - t) < split_tolerance, .true., 1)
                if (i > 0) then
                    call add(messages, path//': '//fractures(k)%label//': element '//itoa(i)// &
                             ' crosses the interface y = '//rtoa(model%interface_y)// &
                             ' at a fraction '//rtoa(t(i))//' of its length: put its end '// &
                             'on the interface, or farther from it')
                end if
            end associate
        end do
    end subroutine check_bimaterial

    !> Two bonded half-planes: element ends within a few rounding steps of the largest
    !> coordinate from the interface are put on it (a vertex meant to lie there but made by
    !> dividing a polyline's segment is off by its rounding).
    subroutine snap_to_interface(model, fractures)
        type(model_type), intent(in) :: model
        type(fracture_input), intent(inout) :: fractures(:)
        real(wp) :: scale
        integer :: k

        if (model%elements%domain /= domain_bimaterial) return
        scale = abs(model%interface_y)
        do k = 1, size(fractures)
            if (.not. fractures(k)%valid) cycle
            associate (f => fractures(k))
                scale = max(scale, maxval(abs(f%x_begin)), maxval(abs(f%y_begin)), &
                            maxval(abs(f%x_end)), maxval(abs(f%y_end)))
            end associate
        end do
        do k = 1, size(fractures)
            if (.not. fractures(k)%valid) cycle
            call snap_to_height(fractures(k)%y_begin, model%interface_y, &
                                16.0_wp * epsilon(scale) * scale)
            call snap_to_height(fractures(k)%y_end, model%interface_y, &
                                16.0_wp * epsilon(scale) * scale)
        end do
    end subroutine snap_to_interface

    !> Split the elements of two bonded half-planes that cross the interface
    !> (split_at_height): both parts keep the element's values.
    pure subroutine split_at_interface(fracture, interface_y)
        type(fracture_input), intent(inout) :: fracture
        real(wp), intent(in) :: interface_y
        integer, allocatable :: source(:)

        call split_at_height(fracture%x_begin, fracture%y_begin, fracture%x_end, &
                             fracture%y_end, interface_y, source)
        if (size(source) == size(fracture%mu)) return
        fracture%mu = fracture%mu(source)
        fracture%sf = fracture%sf(source)
        fracture%pressure = fracture%pressure(source)
        fracture%bc_s = fracture%bc_s(source)
        fracture%bc_n = fracture%bc_n(source)
        fracture%laws = fracture%laws(source, :)
        fracture%diffusivity = fracture%diffusivity(source)
        fracture%transmissivity = fracture%transmissivity(source)
    end subroutine split_at_interface

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
        type(fracture_input), intent(inout) :: fractures(:)
        type(observation_input), intent(in) :: observations(:)
        type(model_type), intent(inout) :: model
        type(strength_law) :: laws(strength_law_count)
        integer :: k, n, first, last, i, j

        laws = strength_laws()
        n = 0
        do k = 1, size(fractures)
            if (model%elements%domain == domain_bimaterial) then
                call split_at_interface(fractures(k), model%interface_y)
            end if
            n = n + size(fractures(k)%x_begin)
        end do
        call allocate_elements(model%elements, n)
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
            model%elements%diffusivity(first:last) = fractures(k)%diffusivity
            model%elements%transmissivity(first:last) = fractures(k)%transmissivity
            model%elements%residual_aperture(first:last) = fractures(k)%residual_aperture
            do j = 1, size(laws)
                call set_law(model%elements, laws(j)%name, [(i, i = first, last)], &
                             fractures(k)%laws(:, j))
            end do
            call set_rate_state(model%elements, [(i, i = first, last)], fractures(k)%rate_state)
        end do
        call compute_geometry(model%elements)

        allocate (model%observations(size(observations)))
        do k = 1, size(observations)
            model%observations(k) = observations(k)%set
        end do
    end subroutine build_model

end module ddc_input_namelist
