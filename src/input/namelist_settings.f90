!> The groups of a namelist input file that describe the whole model rather than one of
!> its parts (docs/input-reference.md): &model, &material, &remote_stress, &pore_fluid,
!> &solver, &symmetry, &output and &load_path. Each sets its defaults, then reads its group
!> if present and checks every value.
module ddc_input_namelist_settings
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_types, only: model_type, symmetry_none, symmetry_names, domain_names, &
        domain_half_plane, domain_bimaterial, load_path_names, default_block_size
    use ddc_model_limits, only: quantity_youngs_modulus, quantity_poissons_ratio, within_limits
    use ddc_contact_options, only: parse_solver_options, option_code, k_method_names, k_auto, &
        default_k_zone_elements
    use ddc_text, only: itoa, rtoa, lower, find_name, quoted_list, prefix_lines, counted
    use ddc_input_text_file, only: base_name, resolve
    use ddc_input_namelist_groups, only: group_record, message_list, add, group_prefix, &
        g_model, g_remote_stress, g_pore_fluid, g_solver, g_symmetry, g_output, g_load_path, &
        g_material
    use ddc_input_namelist_diagnosis, only: report_malformed
    use ddc_input_namelist_values, only: unset_real, unset_integer, text_length, check_scalar, &
        count_given, count_given_integers
    implicit none
    private

    public :: read_model_group, read_remote_stress_group, read_pore_fluid_group
    public :: read_solver_group, read_symmetry_group, read_output_group, read_load_path_group
    public :: read_material_groups

    !> Largest number of vertices of a &load_path, and of steps along it
    integer, parameter :: max_path_vertices = 10000, max_path_steps = 1000000

contains

    !> &model title, youngs_modulus, poissons_ratio, length_unit, stress_unit, time_unit,
    !> domain, interface_y / (the units are labels, stored in the output)
    subroutine read_model_group(unit, text, path, info, the_model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(model_type), intent(inout) :: the_model
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: title, length_unit, stress_unit, time_unit, domain
        real(wp) :: youngs_modulus, poissons_ratio, interface_y
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat
        namelist /model/ title, youngs_modulus, poissons_ratio, length_unit, stress_unit, &
            time_unit, domain, interface_y

        the_model%title = base_name(path, .false.)
        the_model%length_unit = 'm'
        the_model%stress_unit = 'MPa'
        the_model%time_unit = 's'
        if (info%count == 0) return
        title = ''
        youngs_modulus = unset_real
        poissons_ratio = unset_real
        length_unit = 'm'
        stress_unit = 'MPa'
        time_unit = 's'
        domain = 'full_plane'
        interface_y = unset_real
        rewind (unit)
        read (unit, nml=model, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_model, info, 1, stat, iomsg, messages)
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
        if (len_trim(time_unit) == 0) then
            call add(messages, prefix//'time_unit is empty')
        end if
        the_model%length_unit = trim(adjustl(length_unit))
        the_model%stress_unit = trim(adjustl(stress_unit))
        the_model%time_unit = trim(adjustl(time_unit))
        stat = find_name(lower(trim(adjustl(domain))), domain_names)
        if (stat == 0) then
            call add(messages, prefix//"domain = '"//trim(adjustl(domain))//"' is not one of "// &
                     quoted_list(domain_names))
        else
            the_model%elements%domain = stat
        end if

        if (the_model%elements%domain == domain_bimaterial) then
            ! The two materials come from the &material groups.
            if (youngs_modulus /= unset_real .or. poissons_ratio /= unset_real) then
                call add(messages, prefix//"youngs_modulus and poissons_ratio are not given "// &
                         "with domain = 'bimaterial': the two &material groups (name = "// &
                         "'upper' and 'lower') give them")
            end if
            if (check_scalar(interface_y, 'interface_y', .false., prefix, messages)) then
                the_model%interface_y = interface_y
            end if
            return
        end if
        if (interface_y /= unset_real) then
            call add(messages, prefix//"interface_y is given, but domain = '"// &
                     trim(domain_names(the_model%elements%domain))//"': the interface is "// &
                     "that of domain = 'bimaterial'")
        end if
        if (check_scalar(youngs_modulus, 'youngs_modulus', .true., prefix, messages, &
                         quantity_youngs_modulus)) the_model%youngs_modulus = youngs_modulus
        if (check_scalar(poissons_ratio, 'poissons_ratio', .true., prefix, messages, &
                         quantity_poissons_ratio)) the_model%poissons_ratio = poissons_ratio
    end subroutine read_model_group

    !> &material name, youngs_modulus, poissons_ratio / (two of them, name = 'upper' and
    !> 'lower', with &model domain = 'bimaterial' and only then): the materials above and
    !> below the interface (docs/theory/bimaterial.md).
    subroutine read_material_groups(unit, text, path, info, model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages
        character(len=*), parameter :: material_names(2) = [character(len=5) :: 'lower', &
            'upper']
        character(len=text_length) :: name
        real(wp) :: youngs_modulus, poissons_ratio
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, k, which, line(2)
        logical :: ok
        namelist /material/ name, youngs_modulus, poissons_ratio

        if (model%elements%domain /= domain_bimaterial) then
            if (info%count > 0) call add(messages, group_prefix(path, g_material, info, 1)// &
                "&material is for &model domain = 'bimaterial' (two bonded half-planes); "// &
                "one material is &model's youngs_modulus and poissons_ratio")
            return
        end if
        line = 0
        rewind (unit)
        do k = 1, info%count
            name = ''
            youngs_modulus = unset_real
            poissons_ratio = unset_real
            read (unit, nml=material, iostat=stat, iomsg=iomsg)
            if (stat /= 0) then
                call report_malformed(text, path, g_material, info, k, stat, iomsg, messages)
                return
            end if
            prefix = group_prefix(path, g_material, info, k)
            which = find_name(lower(trim(adjustl(name))), material_names)
            if (which == 0) then
                call add(messages, prefix//"name = '"//trim(adjustl(name))//"' is not one of "// &
                         quoted_list(material_names)//' (the material below and above '// &
                         'interface_y)')
                cycle
            end if
            if (line(which) > 0) then
                call add(messages, prefix//"name = '"//trim(material_names(which))// &
                         "' is given already (line "//itoa(line(which))//')')
                cycle
            end if
            line(which) = info%lines(k)
            ok = check_scalar(youngs_modulus, 'youngs_modulus', .true., prefix, messages, &
                              quantity_youngs_modulus)
            ok = check_scalar(poissons_ratio, 'poissons_ratio', .true., prefix, messages, &
                              quantity_poissons_ratio) .and. ok
            if (.not. ok) cycle
            if (which == 1) then
                model%youngs_modulus = youngs_modulus
                model%poissons_ratio = poissons_ratio
            else
                model%upper_youngs_modulus = youngs_modulus
                model%upper_poissons_ratio = poissons_ratio
            end if
        end do
        do which = 1, 2
            if (line(which) == 0) call add(messages, path//": &model domain = 'bimaterial' "// &
                "needs a &material group with name = '"//trim(material_names(which))//"'")
        end do
    end subroutine read_material_groups

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
            call report_malformed(text, path, g_remote_stress, info, 1, stat, iomsg, messages)
            return
        end if
        prefix = group_prefix(path, g_remote_stress, info, 1)
        if (check_scalar(sxx, 'sxx', .false., prefix, messages)) model%sxx = sxx
        if (check_scalar(syy, 'syy', .false., prefix, messages)) model%syy = syy
        if (check_scalar(sxy, 'sxy', .false., prefix, messages)) model%sxy = sxy
        if (check_scalar(dsxx_dy, 'dsxx_dy', .false., prefix, messages)) then
            model%stress_gradient(1) = dsxx_dy
        end if
        if (check_scalar(dsyy_dy, 'dsyy_dy', .false., prefix, messages)) then
            model%stress_gradient(2) = dsyy_dy
        end if
        if (check_scalar(dsxy_dy, 'dsxy_dy', .false., prefix, messages)) then
            model%stress_gradient(3) = dsxy_dy
        end if
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
        namelist /pore_fluid/ p0, dp_dy

        model%pore_fluid = 0.0_wp
        if (info%count == 0) return
        p0 = 0.0_wp
        dp_dy = 0.0_wp
        rewind (unit)
        read (unit, nml=pore_fluid, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_pore_fluid, info, 1, stat, iomsg, messages)
            return
        end if
        prefix = group_prefix(path, g_pore_fluid, info, 1)
        if (check_scalar(p0, 'p0', .false., prefix, messages)) model%pore_fluid(1) = p0
        if (check_scalar(dp_dy, 'dp_dy', .false., prefix, messages)) model%pore_fluid(2) = dp_dy
    end subroutine read_pore_fluid_group

    !> &solver lcp_method, open_cohesion, block_size, matrix, hmatrix_tolerance,
    !> hmatrix_leaf_size, hmatrix_eta, k_method / (block_size: of the distributed matrices
    !> of the MPI build, at least 1; the hmatrix_ settings: docs/theory/hierarchical.md;
    !> k_method: docs/theory/tips.md#choosing-the-method)
    subroutine read_solver_group(unit, text, path, info, model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages
        character(len=text_length) :: lcp_method, open_cohesion, matrix, k_method
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        type(error_type), allocatable :: problems
        integer :: stat, block_size, hmatrix_leaf_size, k_zone_elements
        real(wp) :: hmatrix_tolerance, hmatrix_eta
        namelist /solver/ lcp_method, open_cohesion, block_size, matrix, hmatrix_tolerance, &
            hmatrix_leaf_size, hmatrix_eta, k_method, k_zone_elements

        if (info%count == 0) return
        lcp_method = 'auto'
        open_cohesion = 'kept'
        matrix = 'auto'
        k_method = 'auto'
        k_zone_elements = default_k_zone_elements
        block_size = default_block_size
        hmatrix_tolerance = model%solver%hmatrix_tolerance
        hmatrix_leaf_size = model%solver%hmatrix_leaf_size
        hmatrix_eta = model%solver%hmatrix_eta
        rewind (unit)
        read (unit, nml=solver, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_solver, info, 1, stat, iomsg, messages)
            return
        end if
        prefix = group_prefix(path, g_solver, info, 1)
        call parse_solver_options(lcp_method, open_cohesion, matrix, model%solver, problems)
        if (allocated(problems)) call add(messages, prefix_lines(prefix, problems%message))
        model%solver%k_method = option_code(k_method, k_method_names)
        if (model%solver%k_method == 0) then
            model%solver%k_method = k_auto
            call add(messages, prefix//"k_method = '"//trim(adjustl(k_method))// &
                     "' is not one of 'auto', 'higher_order', 'tip_element'")
        end if
        if (k_zone_elements < 2) then
            call add(messages, prefix//'k_zone_elements = '//itoa(k_zone_elements)// &
                     ' must be at least 2')
        else
            model%solver%k_zone_elements = k_zone_elements
        end if
        if (block_size < 1) then
            call add(messages, prefix//'block_size = '//itoa(block_size)//' must be at least 1')
        else
            model%block_size = block_size
        end if
        ! The tolerance is relative to a block's norm: 1 or more keeps nothing of it.
        if (.not. (hmatrix_tolerance > 0.0_wp .and. hmatrix_tolerance < 1.0_wp)) then
            call add(messages, prefix//'hmatrix_tolerance = '//rtoa(hmatrix_tolerance)// &
                     ' must lie between 0 and 1 (exclusive)')
        else
            model%solver%hmatrix_tolerance = hmatrix_tolerance
        end if
        if (hmatrix_leaf_size < 2) then
            call add(messages, prefix//'hmatrix_leaf_size = '//itoa(hmatrix_leaf_size)// &
                     ' must be at least 2')
        else
            model%solver%hmatrix_leaf_size = hmatrix_leaf_size
        end if
        if (.not. hmatrix_eta > 0.0_wp .or. hmatrix_eta > huge(1.0_wp)) then
            call add(messages, prefix//'hmatrix_eta = '//rtoa(hmatrix_eta)//' must be positive')
        else
            model%solver%hmatrix_eta = hmatrix_eta
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
        namelist /symmetry/ kind, xsym, ysym

        model%elements%symmetry%kind = symmetry_none
        if (info%count == 0) return
        kind = 'none'
        xsym = 0.0_wp
        ysym = 0.0_wp
        rewind (unit)
        read (unit, nml=symmetry, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_symmetry, info, 1, stat, iomsg, messages)
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
        namelist /output/ file

        model%output_file = base_name(path, .false.)//'.h5'
        if (info%count == 0) return
        file = ''
        rewind (unit)
        read (unit, nml=output, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_output, info, 1, stat, iomsg, messages)
            return
        end if
        if (len_trim(file) > 0) model%output_file = resolve(dir, trim(adjustl(file)))
    end subroutine read_output_group

    !> &load_path sxx, syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy, p0, steps, time /
    !> (docs/loading-histories.md#the-input; optional): the load at the path's vertices (the first
    !> is the starting state), each quantity either absent (held at its &remote_stress or
    !> &pore_fluid value) or given at every vertex, steps(l) increments on leg l, and the time of
    !> each vertex (strictly increasing; a path may give times alone). Needs contact elements.
    subroutine read_load_path_group(unit, text, path, info, has_contact, model, messages)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: path
        type(group_record), intent(in) :: info
        !> The model has contact elements, or grows (a growing geometry does not superpose)
        logical, intent(in) :: has_contact
        type(model_type), intent(inout) :: model
        type(message_list), intent(inout) :: messages
        real(wp), allocatable :: sxx(:), syy(:), sxy(:), dsxx_dy(:), dsyy_dy(:), dsxy_dy(:), &
                                 p0(:), time(:), values(:, :), fixed(:)
        integer, allocatable :: steps(:)
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        integer :: stat, nlegs, nv, q, given, ntime
        logical :: ok, finite
        namelist /load_path/ sxx, syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy, p0, steps, time

        if (info%count == 0) return
        allocate (sxx(max_path_vertices), syy(max_path_vertices), sxy(max_path_vertices), &
                  dsxx_dy(max_path_vertices), dsyy_dy(max_path_vertices), &
                  dsxy_dy(max_path_vertices), p0(max_path_vertices), steps(max_path_vertices), &
                  time(max_path_vertices))
        sxx = unset_real
        syy = unset_real
        sxy = unset_real
        dsxx_dy = unset_real
        dsyy_dy = unset_real
        dsxy_dy = unset_real
        p0 = unset_real
        time = unset_real
        steps = unset_integer
        rewind (unit)
        read (unit, nml=load_path, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_load_path, info, 1, stat, iomsg, messages)
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
            ! A quantity given with the wrong number of values is given: one message only.
            if (stat > 0) given = given + 1
            if (stat == 0) then
                model%load_path%vertex(q, :) = fixed(q)
            else if (stat /= nv .and. nlegs > 0) then
                call add(messages, prefix//trim(load_path_names(q))//' has '// &
                         counted(stat, 'value', 'values')//'; give one per vertex: '// &
                         itoa(nv)//' (one more than steps)')
                ok = .false.
            else
                model%load_path%varies(q) = .true.
                model%load_path%vertex(q, :) = values(1:nv, q)
            end if
        end do
        ntime = count_given(time, 'time', prefix, messages)
        ! A NaN or Inf has its message from count_given; the path is not used then.
        finite = all(within_limits(time(1:ntime))) .and. &
            all(within_limits(values(1:nv, :)) .or. values(1:nv, :) == unset_real)
        ok = ok .and. finite
        if (ntime > 0 .and. ntime /= nv .and. nlegs > 0) then
            call add(messages, prefix//'time has '//counted(ntime, 'value', 'values')// &
                     '; give one per vertex: '//itoa(nv)//' (one more than steps)')
            ok = .false.
        else if (ntime > 1 .and. finite) then
            if (any(time(2:ntime) <= time(1:ntime - 1))) then
                call add(messages, prefix//'time('//itoa(findloc(time(2:ntime) <= &
                         time(1:ntime - 1), .true., 1) + 1)//') = '// &
                         rtoa(time(findloc(time(2:ntime) <= time(1:ntime - 1), .true., 1) + &
                         1))//' is not after the time before it: times must increase')
                ok = .false.
            end if
        end if
        if (given == 0 .and. ntime == 0) then
            call add(messages, prefix//'give the load at each vertex: at least one of sxx, '// &
                     'syy, sxy, dsxx_dy, dsyy_dy, dsxy_dy, p0 (or the time of each vertex)')
            ok = .false.
        end if
        if (.not. has_contact) then
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
            if (ntime > 0) model%load_path%time = time(1:nv)
        else
            deallocate (model%load_path%vertex)
        end if
    end subroutine read_load_path_group

end module ddc_input_namelist_settings
