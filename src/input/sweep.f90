!> Read the &sweep group of a namelist input file (docs/sweeps-and-slurm.md): the parameters to vary
!> on top of the base model written in the same file, and their value lists.
!>
!>     &sweep combine = 'product',
!>            parameters = 'mu', 'remote_angle',
!>            values_1 = 0.2, 0.4, 0.6, 0.8, 1.0,
!>            values_2 = -90, -60, -30, 0, 30, 60 /
!>
!> `parameters` names up to max_parameters parameters (see ddc_sweep_tasks for the names);
!> `values_<p>` lists the values of parameter p. combine = 'product' (default) makes one
!> task per combination, the last parameter varying fastest; combine = 'zip' makes task k
!> from the k-th value of every list (all lists of the same length). Every problem is
!> reported at once, one line each, naming the file, the group and the variable.
module ddc_input_sweep
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, load_path_names, source_overpressure
    use ddc_input_text_file, only: read_text_file, open_namelist
    use ddc_text, only: itoa, rtoa, lower, add_message, messages_error, join_integers
    use ddc_input_namelist_groups, only: group_line
    use ddc_input_namelist_diagnosis, only: group_problem
    use ddc_sweep_tasks, only: sweep_definition, combine_names, combine_product, combine_zip, &
        max_parameters, max_tasks, parse_parameter, check_value, target_sxx, target_syy, &
        target_sxy, target_s1, target_s3, target_angle, target_overpressure, target_rate, &
        target_diffusivity, target_transmissivity
    implicit none
    private

    public :: read_sweep, max_values

    !> Largest number of values of one parameter
    integer, parameter :: max_values = 10000
    !> Sentinel of values the user did not give
    real(wp), parameter :: unset_real = huge(1.0_wp)

contains

    !> Read the &sweep group of the file at path, validated against the base model read
    !> from the same file. found is false (and nothing else set) when there is no &sweep.
    subroutine read_sweep(path, model, definition, found, error)
        !> Path of the input file, as given on the command line
        character(len=*), intent(in) :: path
        !> The base model (read from the same file)
        type(model_type), intent(in) :: model
        !> The sweep read
        type(sweep_definition), intent(out) :: definition
        !> The file has a &sweep group
        logical, intent(out) :: found
        !> Allocated with exit_bad_input when the group is bad, one line per problem
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text, prefix, messages
        character(len=16) :: combine
        character(len=64) :: parameters(max_parameters)
        real(wp), allocatable :: values_1(:), values_2(:), values_3(:), values_4(:), &
                                 values_5(:), values_6(:), lists(:, :)
        character(len=512) :: iomsg
        integer :: unit, stat, line, nbad
        namelist /sweep/ combine, parameters, values_1, values_2, values_3, values_4, &
            values_5, values_6

        found = .false.
        call read_text_file(path, text, error)
        if (allocated(error)) return
        line = group_line(text, 'sweep')
        if (line == 0) return
        found = .true.
        prefix = path//': &sweep (line '//itoa(line)//'): '

        combine = 'product'
        parameters = ''
        allocate (values_1(max_values), values_2(max_values), values_3(max_values), &
                  values_4(max_values), values_5(max_values), values_6(max_values))
        values_1 = unset_real
        values_2 = unset_real
        values_3 = unset_real
        values_4 = unset_real
        values_5 = unset_real
        values_6 = unset_real
        call open_namelist(path, text, unit, error)
        if (allocated(error)) return
        read (unit, nml=sweep, iostat=stat, iomsg=iomsg)
        close (unit)
        if (stat /= 0) then
            call set_error(error, exit_bad_input, &
                           group_problem(text, path, 'sweep', stat, iomsg))
            return
        end if

        lists = reshape([values_1, values_2, values_3, values_4, values_5, values_6], &
                        [max_values, max_parameters])
        messages = ''
        nbad = 0
        call build(prefix, combine, parameters, lists, size(model%fractures), &
                   source_count(model), definition, messages, nbad)
        if (nbad == 0) call check_load_path(prefix, model, definition, messages, nbad)
        if (nbad == 0) call check_flow(prefix, model, definition, messages, nbad)
        if (nbad > 0) call messages_error(messages, nbad, 'problems', error)
        definition%where = prefix
    end subroutine read_sweep

    !> A remote stress component that a &load_path gives at its vertices cannot be swept:
    !> the path would override the task's value (sxx, syy, sxy, or all three for the
    !> principal stresses).
    subroutine check_load_path(prefix, model, definition, messages, nbad)
        character(len=*), intent(in) :: prefix
        type(model_type), intent(in) :: model
        type(sweep_definition), intent(in) :: definition
        character(len=:), allocatable, intent(inout) :: messages
        integer, intent(inout) :: nbad
        logical :: sets(3)
        integer :: p, q

        if (.not. allocated(model%load_path%vertex)) return
        do p = 1, size(definition%targets)
            sets = [definition%targets(p) == target_sxx, definition%targets(p) == target_syy, &
                    definition%targets(p) == target_sxy]
            if (any(definition%targets(p) == [target_s1, target_s3, target_angle])) sets = .true.
            do q = 1, 3
                if (.not. (sets(q) .and. model%load_path%varies(q))) cycle
                call add_message(messages, nbad, prefix//'parameters('//itoa(p)//") = '"// &
                    trim(definition%names(p))//"' sets the remote "//trim(load_path_names(q))// &
                    ', which &load_path gives at every vertex: the path would override it '// &
                    '(sweep a quantity the path holds fixed)')
                exit
            end do
        end do
    end subroutine check_load_path

    !> Number of &injection sources of a model.
    pure integer function source_count(model)
        type(model_type), intent(in) :: model

        source_count = 0
        if (allocated(model%injections)) source_count = size(model%injections)
    end function source_count

    !> A swept overpressure or rate needs a source of that kind (source K of that kind, for
    !> injection(K)%...), a swept diffusivity or transmissivity elements that conduct (of
    !> fracture K, for fracture(K)%...): the model would not use the value otherwise.
    subroutine check_flow(prefix, model, definition, messages, nbad)
        character(len=*), intent(in) :: prefix
        type(model_type), intent(in) :: model
        type(sweep_definition), intent(in) :: definition
        character(len=:), allocatable, intent(inout) :: messages
        integer, intent(inout) :: nbad
        character(len=:), allocatable :: named, kind
        logical :: conducts(model%elements%n), pressure(source_count(model))
        integer :: p, k, first, last

        conducts = model%elements%diffusivity > 0.0_wp .and. &
                   model%elements%transmissivity > 0.0_wp
        do k = 1, size(pressure)
            pressure(k) = model%injections(k)%kind == source_overpressure
        end do
        do p = 1, size(definition%targets)
            named = prefix//'parameters('//itoa(p)//") = '"//trim(definition%names(p))//"': "
            select case (definition%targets(p))
            case (target_overpressure, target_rate)
                kind = 'a rate'
                if (definition%targets(p) == target_overpressure) kind = 'an overpressure'
                k = definition%sources(p)
                if (k > 0) then
                    if (pressure(k) .neqv. definition%targets(p) == target_overpressure) then
                        call add_message(messages, nbad, named//'&injection '//itoa(k)// &
                                         " '"//model%injections(k)%name//"' does not give "//kind)
                    end if
                else if (.not. any(pressure .eqv. &
                                   definition%targets(p) == target_overpressure)) then
                    call add_message(messages, nbad, named//'no &injection gives '//kind)
                end if
            case (target_diffusivity, target_transmissivity)
                first = 1
                last = model%elements%n
                k = definition%fractures(p)
                if (k > 0) then
                    first = model%fractures(k)%first_element
                    last = model%fractures(k)%last_element
                end if
                if (.not. any(conducts(first:last))) then
                    if (k > 0) then
                        call add_message(messages, nbad, named//'fracture '//itoa(k)//" '"// &
                            model%fractures(k)%name//"' does not conduct: give it "// &
                            'diffusivity and transmissivity in &fracture')
                    else
                        call add_message(messages, nbad, named//'no fracture conducts: '// &
                            'give diffusivity and transmissivity in &fracture')
                    end if
                end if
            case default
                ! not a flow parameter
            end select
        end do
    end subroutine check_flow

    !> Validate the group's values and build the sweep from them.
    subroutine build(prefix, combine, parameters, lists, nfractures, nsources, definition, &
                     messages, nbad)
        character(len=*), intent(in) :: prefix, combine
        character(len=*), intent(in) :: parameters(:)
        !> Value lists as read, column p for parameter p, unset_real where not given
        real(wp), intent(in) :: lists(:, :)
        !> Number of fractures and of &injection sources of the base model
        integer, intent(in) :: nfractures, nsources
        type(sweep_definition), intent(inout) :: definition
        character(len=:), allocatable, intent(inout) :: messages
        integer, intent(inout) :: nbad
        character(len=:), allocatable :: problem, name
        integer :: np, p, q, i, counts(size(parameters))
        real(wp) :: tasks

        definition%combine = 0
        do i = 1, size(combine_names)
            if (lower(trim(adjustl(combine))) == trim(combine_names(i))) definition%combine = i
        end do
        if (definition%combine == 0) then
            call add_message(messages, nbad, prefix//"combine = '"//trim(combine)// &
                             "' is not known; give 'product' or 'zip'")
        end if

        np = 0
        do while (np < size(parameters))
            if (len_trim(parameters(np + 1)) == 0) exit
            np = np + 1
        end do
        if (np == 0) then
            call add_message(messages, nbad, prefix//'parameters is empty: name at least '// &
                             'one parameter to sweep, e.g. parameters = '//"'mu'")
        end if
        if (any(len_trim(parameters(np + 1:)) > 0)) then
            call add_message(messages, nbad, prefix//'parameters('//itoa(np + 1)//') '// &
                             'is empty but a later name is given; give the names without gaps')
        end if
        allocate (definition%names(np), definition%targets(np), definition%fractures(np), &
                  definition%sources(np), definition%laws(np))
        do p = 1, size(parameters)
            counts(p) = count_values(lists(:, p), 'values_'//itoa(p), prefix, messages, nbad)
            if (p > np) then
                if (counts(p) > 0) call add_message(messages, nbad, prefix//'values_'// &
                    itoa(p)//' is given but parameters names '//itoa(np)//' parameter(s)')
                cycle
            end if
            name = lower(trim(adjustl(parameters(p))))
            definition%names(p) = name
            call parse_parameter(name, nfractures, nsources, definition%targets(p), &
                                 definition%fractures(p), definition%sources(p), &
                                 definition%laws(p), problem)
            if (len(problem) > 0) then
                call add_message(messages, nbad, prefix//'parameters('//itoa(p)//'): '//problem)
                cycle
            end if
            do q = 1, p - 1
                if (definition%targets(q) == definition%targets(p) .and. &
                    definition%fractures(q) == definition%fractures(p) .and. &
                    definition%sources(q) == definition%sources(p) .and. &
                    definition%laws(q) == definition%laws(p)) then
                    call add_message(messages, nbad, prefix//'parameters('//itoa(p)//") = '"// &
                        name//"' repeats parameters("//itoa(q)//'); sweep each parameter once')
                end if
            end do
            if (counts(p) == 0) then
                call add_message(messages, nbad, prefix//'values_'//itoa(p)//' is empty: '// &
                                 "give at least one value of '"//name//"'")
            end if
            do i = 1, counts(p)
                problem = check_value(definition%targets(p), definition%laws(p), lists(i, p))
                if (len(problem) > 0) then
                    call add_message(messages, nbad, prefix//'values_'//itoa(p)//'('// &
                        itoa(i)//') = '//rtoa(lists(i, p))//': '//name//' '//problem)
                    exit
                end if
            end do
        end do
        if (nbad > 0) return

        if (any(definition%targets == target_sxx .or. definition%targets == target_syy .or. &
                definition%targets == target_sxy) .and. &
            any(definition%targets == target_s1 .or. definition%targets == target_s3 .or. &
                definition%targets == target_angle)) then
            call add_message(messages, nbad, prefix//'sweep the remote stress either by '// &
                'components (sxx, syy, sxy) or by principal stresses (remote_s1, '// &
                'remote_s3, remote_angle), not both')
        end if
        if (definition%combine == combine_zip .and. any(counts(1:np) /= counts(1))) then
            call add_message(messages, nbad, prefix//"combine = 'zip' needs value lists of "// &
                             'one length; their lengths are '//join_integers(counts(1:np)))
        end if
        tasks = real(counts(1), wp)
        if (definition%combine == combine_product) tasks = product(real(counts(1:np), wp))
        if (tasks > real(max_tasks, wp)) then
            call add_message(messages, nbad, prefix//'the sweep has '//rtoa(tasks)// &
                             ' tasks, more than '//itoa(max_tasks))
        end if
        if (nbad > 0) return
        definition%counts = counts(1:np)
        definition%values = lists(1:maxval(counts(1:np)), 1:np)
        definition%tasks = nint(tasks)
    end subroutine build

    !> Number of leading given values of a list; a value after a gap is a problem.
    function count_values(values, name, prefix, messages, nbad) result(n)
        real(wp), intent(in) :: values(:)
        character(len=*), intent(in) :: name, prefix
        character(len=:), allocatable, intent(inout) :: messages
        integer, intent(inout) :: nbad
        integer :: n

        n = findloc(values == unset_real, .true., dim=1) - 1
        if (n < 0) n = size(values)
        if (any(values(n + 1:) /= unset_real)) then
            call add_message(messages, nbad, prefix//name//'('//itoa(n + 1)//') is not '// &
                'given but a later value is; give the values without gaps')
        end if
    end function count_values

end module ddc_input_sweep
