!> Parameter sweeps (docs/sweeps-and-slurm.md): the tasks of a sweep, their parameter values, their
!> output file names, and the substitution of a task's values into the base model.
!>
!> A sweep drives the solver from outside: each task is the base model with a few values
!> replaced, solved and written like any model. Tasks are numbered from 0. With
!> combine_product the tasks run through every combination of the value lists, the last
!> parameter varying fastest (nested loops in the order the parameters are written); with
!> combine_zip task k takes the k-th value of every list.
!>
!> Sweepable parameters (names lower case, written without blanks):
!> - youngs_modulus, poissons_ratio;
!> - sxx, syy, sxy: remote stress components;
!> - remote_s1, remote_s3, remote_angle: the remote stress as principal stresses, s1
!>   along the axis at remote_angle degrees counter-clockwise from +x, s3 across it; the
!>   ones not swept keep the base model's values (s1 its most compressive principal
!>   stress, the angle in (-90, 90]); not combinable with sxx, syy, sxy;
!> - mu, sf, pressure and the strength laws (each law of ddc_model_laws by its name:
!>   tensile_strength, slip_weakening_distance ...): on every element of every fracture;
!> - fracture(K)%mu, fracture(K)%sf, fracture(K)%pressure, fracture(K)%<law>: on every
!>   element of fracture K (1-based, in input order);
!> - new_mu, new_sf and the strength laws of new elements (new_<name> of each law of
!>   ddc_model_laws: new_tensile_strength ...): what the new contact elements of a growth run
!>   take;
!> - overpressure, rate: of every &injection source of that kind; injection(K)%overpressure,
!>   injection(K)%rate: of source K (1-based, input order);
!> - diffusivity, transmissivity: of every element that conducts; fracture(K)%diffusivity,
!>   fracture(K)%transmissivity: of the elements of fracture K that conduct.
module ddc_sweep_tasks
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, growth_options, domain_half_plane, no_residual_drop, &
        strength_law_count, injection_source, source_overpressure, condition_contact
    use ddc_model_laws, only: strength_law, strength_laws, law_values, new_law_bound, &
        at_most_rule, law_index, set_law
    use ddc_text, only: itoa, lower, short_real, add_message, messages_error
    use ddc_model_limits, only: range_problem, quantity_any, quantity_youngs_modulus, &
        quantity_poissons_ratio, quantity_non_negative, quantity_positive
    implicit none
    private

    public :: sweep_definition, combine_product, combine_zip, combine_names
    public :: max_parameters, max_tasks
    public :: parse_parameter, check_value, task_values, task_label, task_file_name
    public :: check_task, apply_task, task_problem, check_tasks
    public :: target_sxx, target_syy, target_sxy, target_s1, target_s3, target_angle
    public :: target_overpressure, target_rate, target_diffusivity, target_transmissivity

    !> How the value lists make tasks
    integer, parameter :: combine_product = 1, combine_zip = 2
    !> Input names of the ways to combine, indexed by code
    character(len=*), parameter :: combine_names(2) = [character(len=7) :: 'product', 'zip']
    !> Largest number of swept parameters
    integer, parameter :: max_parameters = 6
    !> Largest number of tasks of one sweep
    integer, parameter :: max_tasks = 10000000

    !> What a parameter changes in the model
    integer, parameter :: target_youngs = 1, target_poisson = 2, target_sxx = 3, &
                          target_syy = 4, target_sxy = 5, target_s1 = 6, target_s3 = 7, &
                          target_angle = 8, target_mu = 9, target_sf = 10, target_pressure = 11, &
                          target_new_mu = 12, target_new_sf = 13
    !> A strength law of new elements, new_<name>, and one of the fractures' elements,
    !> <name> (which one: sweep_definition's laws)
    integer, parameter :: target_new_law = 14, target_law = 15
    !> The flow (docs/injection.md): the value of &injection sources of one kind (all, or
    !> injection(K): sweep_definition's sources), the hydraulic properties of the elements
    !> that conduct (all, or fracture(K)'s)
    integer, parameter :: target_overpressure = 16, target_rate = 17, &
                          target_diffusivity = 18, target_transmissivity = 19
    !> Names of the flow targets, indexed by target (per source: injection(K)%<name>, per
    !> fracture: fracture(K)%<name>)
    character(len=*), parameter :: flow_names(target_overpressure:target_transmissivity) = &
        [character(len=14) :: 'overpressure', 'rate', 'diffusivity', 'transmissivity']
    !> Names of the targets but the laws' and the flow's, indexed by target (per fracture:
    !> fracture(K)%<name>)
    character(len=*), parameter :: target_names(13) = [character(len=14) :: 'youngs_modulus', &
        'poissons_ratio', 'sxx', 'syy', 'sxy', 'remote_s1', 'remote_s3', 'remote_angle', 'mu', &
        'sf', 'pressure', 'new_mu', 'new_sf']

    real(wp), parameter :: degree = acos(-1.0_wp) / 180.0_wp

    !> A validated sweep: parameters, their value lists and how they combine.
    type :: sweep_definition
        !> combine_product or combine_zip
        integer :: combine = combine_product
        !> Parameter names as written (lower case, no blanks), shape (np)
        character(len=64), allocatable :: names(:)
        !> Target of each parameter (target_youngs ... target_new_law), shape (np)
        integer, allocatable :: targets(:)
        !> Fracture of each per-fracture parameter (1-based), 0 for all, shape (np)
        integer, allocatable :: fractures(:)
        !> Source of each injection(K)%... parameter (1-based), 0 for all, shape (np)
        integer, allocatable :: sources(:)
        !> Law of each parameter of target_new_law or target_law (its place in ddc_model_laws'
        !> list), 0 for
        !> the others, shape (np)
        integer, allocatable :: laws(:)
        !> Number of values of each parameter, shape (np)
        integer, allocatable :: counts(:)
        !> Value lists, column p holds counts(p) values, shape (max(counts), np)
        real(wp), allocatable :: values(:, :)
        !> Number of tasks
        integer :: tasks = 0
        !> Where the sweep was read, for messages: "file: &sweep (line n): "
        character(len=:), allocatable :: where
    end type sweep_definition

contains

    !> Parse a parameter name: its target, fracture, source and law; problem is '' when the
    !> name is good.
    subroutine parse_parameter(name, nfractures, nsources, target, fracture, source, law, &
                               problem)
        !> The name as written (case and blanks do not matter)
        character(len=*), intent(in) :: name
        !> Number of fractures and of &injection sources of the base model
        integer, intent(in) :: nfractures, nsources
        !> target_youngs ... target_transmissivity; 0 when the name is bad
        integer, intent(out) :: target
        !> Fracture number for fracture(K)%..., 0 otherwise
        integer, intent(out) :: fracture
        !> Source number for injection(K)%..., 0 otherwise
        integer, intent(out) :: source
        !> The law of new_<name> or <name> (its place in ddc_model_laws' list), 0 otherwise
        integer, intent(out) :: law
        !> Why the name is bad, '' when it is good
        character(len=:), allocatable, intent(out) :: problem
        type(strength_law) :: laws(strength_law_count)
        character(len=:), allocatable :: key
        integer :: stat, i

        key = squeeze(lower(name))
        target = 0
        fracture = 0
        source = 0
        law = 0
        problem = ''
        if (index(key, 'injection(') == 1) then
            call parse_source(name, key, nsources, source, problem)
            if (len(problem) > 0) return
        else if (index(key, 'fracture(') == 1) then
            call group_number(key, 'fracture', fracture, stat)
            if (stat /= 0) then
                problem = "'"//trim(name)//"' is not a sweep parameter: write fracture(K)%mu"// &
                          ' with K the fracture number (1-based)'
                return
            end if
            if (fracture < 1 .or. fracture > nfractures) then
                problem = "'"//trim(name)//"': the model has "//itoa(nfractures)// &
                          ' fracture(s); K must be 1 to '//itoa(nfractures)
                return
            end if
            if (all(key /= [character(len=14) :: 'mu', 'sf', 'pressure', 'diffusivity', &
                                                 'transmissivity']) .and. law_index(key) == 0) then
                problem = "'"//trim(name)//"': a fracture's sweep parameters are mu, sf, "// &
                          'pressure, diffusivity, transmissivity and the strength laws ('// &
                          law_names('')//')'
                return
            end if
        end if
        law = law_index(key)
        if (law > 0) target = target_law
        do i = 1, size(target_names)
            if (key == trim(target_names(i))) target = i
        end do
        do i = lbound(flow_names, 1), ubound(flow_names, 1)
            if (key == trim(flow_names(i))) target = i
        end do
        laws = strength_laws()
        do i = 1, size(laws)
            if (key == 'new_'//laws(i)%name) then
                target = target_new_law
                law = i
            end if
        end do
        if (target == 0) then
            problem = "'"//trim(name)//"' is not a sweep parameter; the parameters are: "// &
                      parameter_help()
        end if
    end subroutine parse_parameter

    !> injection(K)%overpressure or injection(K)%rate (key, lower case without blanks): K (1
    !> to nsources) in source and key the name after the %; problem is '' when it is good.
    subroutine parse_source(name, key, nsources, source, problem)
        !> The name as written, for the message
        character(len=*), intent(in) :: name
        !> The name squeezed; on return the part after the %
        character(len=:), allocatable, intent(inout) :: key
        !> Number of &injection sources of the base model
        integer, intent(in) :: nsources
        !> K, 0 when the name is bad
        integer, intent(out) :: source
        !> Why the name is bad, '' when it is good
        character(len=:), allocatable, intent(out) :: problem
        integer :: stat

        problem = ''
        call group_number(key, 'injection', source, stat)
        if (stat /= 0) then
            problem = "'"//trim(name)//"' is not a sweep parameter: write "// &
                      'injection(K)%overpressure with K the &injection group (1-based)'
        else if (source < 1 .or. source > nsources) then
            problem = "'"//trim(name)//"': the model has "//itoa(nsources)// &
                      ' &injection group(s); K must be 1 to '//itoa(nsources)
        else if (key /= 'overpressure' .and. key /= 'rate') then
            problem = "'"//trim(name)//"': a source's sweep parameters are overpressure "// &
                      'and rate'
        end if
    end subroutine parse_source

    !> K of a name <group>(K)%<rest> (key, lower case without blanks, starting with
    !> '<group>('): stat 0, k = K and key the rest when K is a number; stat nonzero else.
    subroutine group_number(key, group, k, stat)
        !> The name; on return the part after the % when K is a number
        character(len=:), allocatable, intent(inout) :: key
        !> The group's name
        character(len=*), intent(in) :: group
        !> K, 0 when it is no number
        integer, intent(out) :: k
        !> 0 when K is a number
        integer, intent(out) :: stat
        integer :: first, close_paren

        k = 0
        stat = 1
        first = len(group) + 2
        close_paren = index(key, ')%')
        if (close_paren > first) then
            if (verify(key(first:close_paren - 1), '0123456789') == 0) then
                read (key(first:close_paren - 1), *, iostat=stat) k
            end if
        end if
        if (stat == 0) key = key(close_paren + 2:)
    end subroutine group_number

    !> The list of parameter names, for messages.
    function parameter_help() result(help)
        character(len=:), allocatable :: help
        help = 'youngs_modulus, poissons_ratio, sxx, syy, sxy, remote_s1, remote_s3, '// &
            'remote_angle, mu, sf, pressure, '//law_names('')//', fracture(K)%mu, '// &
            'fracture(K)%sf, fracture(K)%pressure, fracture(K)%<law> (each of those), '// &
            'new_mu, new_sf, '//law_names('new_')//' (&growth), overpressure, rate, '// &
            'injection(K)%overpressure, injection(K)%rate (&injection), diffusivity, '// &
            'transmissivity, fracture(K)%diffusivity, fracture(K)%transmissivity'
    end function parameter_help

    !> 'tensile_strength, sf_residual, ...': the names of the strength laws, each after
    !> prefix.
    function law_names(prefix) result(names)
        character(len=*), intent(in) :: prefix
        character(len=:), allocatable :: names
        type(strength_law) :: laws(strength_law_count)
        integer :: k

        laws = strength_laws()
        names = ''
        do k = 1, size(laws)
            if (k > 1) names = names//', '
            names = names//prefix//laws(k)%name
        end do
    end function law_names

    !> Check a value of a parameter; problem is '' when it is acceptable.
    function check_value(target, law, value) result(problem)
        !> target_youngs ... target_transmissivity
        integer, intent(in) :: target
        !> The law of target_new_law or target_law (its place in ddc_model_laws' list)
        integer, intent(in) :: law
        !> The value
        real(wp), intent(in) :: value
        !> Why the value is bad, '' when it is good
        character(len=:), allocatable :: problem
        type(strength_law) :: laws(strength_law_count)

        select case (target)
        case (target_youngs)
            problem = range_problem(quantity_youngs_modulus, value)
        case (target_poisson)
            problem = range_problem(quantity_poissons_ratio, value)
        case (target_mu, target_sf, target_new_mu, target_new_sf)
            problem = range_problem(quantity_non_negative, value)
        case (target_new_law, target_law)
            laws = strength_laws()
            problem = range_problem(laws(law)%quantity, value)
        case (target_diffusivity, target_transmissivity)
            problem = range_problem(quantity_positive, value)
        case default
            problem = range_problem(quantity_any, value)
        end select
    end function check_value

    !> The parameter values of task (0-based), shape (np).
    pure function task_values(sweep, task) result(values)
        !> The sweep
        type(sweep_definition), intent(in) :: sweep
        !> Task number, 0 <= task < sweep%tasks
        integer, intent(in) :: task
        !> Value of each parameter
        real(wp) :: values(size(sweep%names))
        integer :: p, rest

        rest = task
        do p = size(sweep%names), 1, -1
            if (sweep%combine == combine_zip) then
                values(p) = sweep%values(task + 1, p)
            else
                values(p) = sweep%values(mod(rest, sweep%counts(p)) + 1, p)
                rest = rest / sweep%counts(p)
            end if
        end do
    end function task_values

    !> "mu = 0.2, remote_angle = -30": the parameters of a task.
    function task_label(sweep, task) result(label)
        !> The sweep
        type(sweep_definition), intent(in) :: sweep
        !> Task number, 0 <= task < sweep%tasks
        integer, intent(in) :: task
        !> The label
        character(len=:), allocatable :: label
        real(wp) :: values(size(sweep%names))
        integer :: p

        values = task_values(sweep, task)
        label = ''
        do p = 1, size(values)
            if (p > 1) label = label//', '
            label = label//trim(sweep%names(p))//' = '//short_real(values(p))
        end do
    end function task_label

    !> Output file of a task: base with _task<id> before its extension, the id zero-padded
    !> to the width of the largest task number (at least 4 digits): out.h5 -> out_task0007.h5.
    pure function task_file_name(base, task, tasks) result(name)
        !> Output file of the base model
        character(len=*), intent(in) :: base
        !> Task number (0-based)
        integer, intent(in) :: task
        !> Number of tasks of the sweep
        integer, intent(in) :: tasks
        !> The task's output file
        character(len=:), allocatable :: name
        character(len=24) :: digits
        integer :: dot, slash, width

        width = max(4, len_trim(itoa(max(tasks - 1, 0))))
        write (digits, '(i0.'//itoa(width)//')') task
        dot = index(base, '.', back=.true.)
        slash = index(base, '/', back=.true.)
        if (dot <= slash + 1) dot = len(base) + 1
        name = base(1:dot - 1)//'_task'//trim(digits)//base(dot:)
    end function task_file_name

    !> Refuse a task number outside 0 .. tasks-1.
    subroutine check_task(sweep, task, error)
        !> The sweep
        type(sweep_definition), intent(in) :: sweep
        !> The task asked for
        integer, intent(in) :: task
        !> Allocated with exit_bad_input when the task does not exist
        type(error_type), allocatable, intent(out) :: error

        if (task < 0 .or. task >= sweep%tasks) then
            call set_error(error, exit_bad_input, 'task '//itoa(task)//' is out of range: '// &
                           'the sweep has '//itoa(sweep%tasks)//' tasks, numbered 0 to '// &
                           itoa(sweep%tasks - 1))
        end if
    end subroutine check_task

    !> Make the base model task `task` of the sweep: substitute its values, record them
    !> in model%sweep and give the model the task's output file name. The remote stress
    !> components a &load_path holds fixed (those it does not give per vertex) take the
    !> task's values too.
    subroutine apply_task(model, sweep, task)
        !> The base model in, the task's model out
        type(model_type), intent(inout) :: model
        !> The sweep (validated against this model)
        type(sweep_definition), intent(in) :: sweep
        !> Task number, checked with check_task
        integer, intent(in) :: task
        real(wp) :: values(size(sweep%names)), stress(3)
        ! The elements that conduct in the base model: a swept diffusivity or transmissivity
        ! keeps the others (barriers) as they are.
        logical, allocatable :: conducts(:)
        type(strength_law) :: laws(strength_law_count)
        integer, allocatable :: rows(:)
        integer :: p, first, last, q, i

        conducts = model%elements%diffusivity > 0.0_wp .and. &
                   model%elements%transmissivity > 0.0_wp
        values = task_values(sweep, task)
        stress = task_stress(model, sweep, values)
        model%sxx = stress(1)
        model%syy = stress(2)
        model%sxy = stress(3)
        if (allocated(model%load_path%vertex)) then
            do q = 1, 3
                if (.not. model%load_path%varies(q)) model%load_path%vertex(q, :) = stress(q)
            end do
        end if
        do p = 1, size(values)
            call element_range(model, sweep, p, first, last)
            select case (sweep%targets(p))
            case (target_youngs)
                model%youngs_modulus = values(p)
            case (target_poisson)
                model%poissons_ratio = values(p)
            case (target_mu)
                model%elements%mu(first:last) = values(p)
            case (target_sf)
                model%elements%sf(first:last) = values(p)
            case (target_pressure)
                model%elements%pressure(first:last) = values(p)
            case (target_overpressure, target_rate)
                call set_sources(model%injections, sweep%targets(p), sweep%sources(p), &
                                 values(p))
            case (target_diffusivity)
                where (conducts(first:last)) model%elements%diffusivity(first:last) = values(p)
            case (target_transmissivity)
                where (conducts(first:last)) model%elements%transmissivity(first:last) = &
                    values(p)
            case (target_law)
                ! The laws act on contact elements alone (&fracture gives them to no other).
                laws = strength_laws()
                rows = pack([(i, i = first, last)], &
                            model%elements%condition(first:last) == condition_contact)
                call set_law(model%elements, laws(sweep%laws(p))%name, rows, &
                             spread(values(p), 1, size(rows)))
            case default
                ! the remote stress: task_stress
            end select
        end do
        model%growth = task_growth(model%growth, sweep, values)
        model%sweep%task = task
        model%sweep%tasks = sweep%tasks
        model%sweep%names = sweep%names
        model%sweep%values = values
        model%output_file = task_file_name(model%output_file, task, sweep%tasks)
    end subroutine apply_task

    !> Set the value of the sources of a swept overpressure or rate: source `source` (0: every
    !> source of that kind).
    pure subroutine set_sources(sources, target, source, value)
        !> The model's sources
        type(injection_source), intent(inout) :: sources(:)
        !> target_overpressure or target_rate
        integer, intent(in) :: target
        !> The source (1-based), 0 for all of that kind
        integer, intent(in) :: source
        !> The task's value
        real(wp), intent(in) :: value
        integer :: k

        do k = 1, size(sources)
            if (source /= 0 .and. k /= source) cycle
            if ((sources(k)%kind == source_overpressure) .eqv. &
                (target == target_overpressure)) sources(k)%value = value
        end do
    end subroutine set_sources

    !> The elements parameter p of the sweep sets: those of its fracture, or all.
    pure subroutine element_range(model, sweep, p, first, last)
        !> The base model
        type(model_type), intent(in) :: model
        !> The sweep
        type(sweep_definition), intent(in) :: sweep
        !> The parameter, 1 <= p <= np
        integer, intent(in) :: p
        !> First and last element it sets
        integer, intent(out) :: first, last

        first = 1
        last = model%elements%n
        if (sweep%fractures(p) > 0) then
            first = model%fractures(sweep%fractures(p))%first_element
            last = model%fractures(sweep%fractures(p))%last_element
        end if
    end subroutine element_range

    !> The remote stress (sxx, syy, sxy) of a task with the given parameter values: the
    !> base model's, with swept components or principal stresses replaced.
    pure function task_stress(model, sweep, values) result(stress)
        !> The base model
        type(model_type), intent(in) :: model
        !> The sweep
        type(sweep_definition), intent(in) :: sweep
        !> The task's value of each parameter, shape (np)
        real(wp), intent(in) :: values(:)
        !> sxx, syy, sxy [stress unit]
        real(wp) :: stress(3)
        real(wp) :: s1, s3, angle, c, s
        integer :: p

        stress = [model%sxx, model%syy, model%sxy]
        call principal_stresses(model%sxx, model%syy, model%sxy, s1, s3, angle)
        do p = 1, size(values)
            select case (sweep%targets(p))
            case (target_sxx)
                stress(1) = values(p)
            case (target_syy)
                stress(2) = values(p)
            case (target_sxy)
                stress(3) = values(p)
            case (target_s1)
                s1 = values(p)
            case (target_s3)
                s3 = values(p)
            case (target_angle)
                angle = values(p)
            case default
                ! not a remote stress parameter
            end select
        end do
        if (any(is_principal(sweep%targets))) then
            c = cos_degrees(angle)
            s = cos_degrees(angle - 90.0_wp)
            stress = [s1 * c**2 + s3 * s**2, s1 * s**2 + s3 * c**2, (s1 - s3) * s * c]
        end if
    end function task_stress

    !> Refuse a sweep with a task that cannot be solved (task_problem), every such task
    !> named at once (exit_bad_input); --list calls it before anything is submitted.
    subroutine check_tasks(model, sweep, error)
        !> The base model (read and checked)
        type(model_type), intent(in) :: model
        !> The sweep (validated against this model)
        type(sweep_definition), intent(in) :: sweep
        !> Allocated when a task cannot be solved, one line per task
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: messages, problem
        integer :: task, nbad

        messages = ''
        nbad = 0
        do task = 0, sweep%tasks - 1
            problem = task_problem(model, sweep, task)
            if (len(problem) > 0) call add_message(messages, nbad, problem)
        end do
        if (nbad > 0) call messages_error(messages, nbad, 'tasks that cannot run', error)
    end subroutine check_tasks

    !> Why task `task` cannot be solved, '' when it can: its remote stress breaks the
    !> half-plane rule (half_plane_problem), or its friction or cohesion falls below what
    !> the base model gives after slip (weakening_problem). The line names the file,
    !> &sweep, the task, its parameters and values, and what breaks the rule.
    function task_problem(model, sweep, task) result(problem)
        !> The base model (read and checked)
        type(model_type), intent(in) :: model
        !> The sweep (validated against this model)
        type(sweep_definition), intent(in) :: sweep
        !> Task number, 0 <= task < sweep%tasks
        integer, intent(in) :: task
        !> The problem, '' when there is none
        character(len=:), allocatable :: problem
        real(wp) :: values(size(sweep%names))

        values = task_values(sweep, task)
        problem = half_plane_problem(model, sweep, values)
        if (len(problem) == 0) problem = weakening_problem(model, sweep, values)
        if (len(problem) == 0) problem = new_law_problem(model, sweep, values)
        if (len(problem) > 0) problem = sweep%where//'task '//itoa(task)//' ('// &
            task_label(sweep, task)//'): '//problem
    end function task_problem

    !> In a half-plane the remote stress must keep the surface y = 0 traction-free
    !> (syy = sxy = 0), which a swept syy, sxy or principal stress breaks: the swept values
    !> that break it and the stress they give, '' when the rule holds.
    function half_plane_problem(model, sweep, values) result(problem)
        !> The base model (read and checked)
        type(model_type), intent(in) :: model
        !> The sweep (validated against this model)
        type(sweep_definition), intent(in) :: sweep
        !> The task's value of each parameter, shape (np)
        real(wp), intent(in) :: values(:)
        !> The problem, '' when there is none
        character(len=:), allocatable :: problem
        real(wp) :: stress(3)
        character(len=:), allocatable :: culprits
        integer :: p

        problem = ''
        if (model%elements%domain /= domain_half_plane) return
        stress = task_stress(model, sweep, values)
        if (stress(2) == 0.0_wp .and. stress(3) == 0.0_wp) return
        culprits = ''
        do p = 1, size(values)
            if (.not. any(sweep%targets(p) == [target_syy, target_sxy, target_s1, target_s3, &
                                               target_angle])) cycle
            if (len(culprits) > 0) culprits = culprits//', '
            culprits = culprits//trim(sweep%names(p))//' = '//short_real(values(p))
        end do
        problem = culprits//' gives the remote stress sxx = '//short_real(stress(1))// &
            ', syy = '//short_real(stress(2))//', sxy = '//short_real(stress(3))// &
            "; with &model domain = 'half_plane' syy and sxy must be 0 (the surface y = 0 "// &
            'is traction-free): sweep sxx, or the principal stresses only with '// &
            'remote_angle = 0 (s3 = 0) or 90 (s1 = 0)'
    end function half_plane_problem

    !> A swept mu below the mu_dynamic, or a swept sf below the sf_residual, that the base
    !> model (or the sweep) gives an element, or a swept mu_dynamic or sf_residual above its
    !> mu or sf: one model with these values is refused (the friction or cohesion after slip
    !> above the intact one is a mistake), so a sweep must not lower the residual to the
    !> swept value, or turn the weakening off, without a word. The first such element's
    !> fracture and values, '' when there is none.
    function weakening_problem(model, sweep, values) result(problem)
        !> The base model (read and checked)
        type(model_type), intent(in) :: model
        !> The sweep (validated against this model)
        type(sweep_definition), intent(in) :: sweep
        !> The task's value of each parameter, shape (np)
        real(wp), intent(in) :: values(:)
        !> The problem, '' when there is none
        character(len=:), allocatable :: problem
        real(wp), allocatable :: mu(:), sf(:), given(:, :)
        ! The parameter that set each element's mu, sf and laws (0: the base model's value)
        integer, allocatable :: mu_from(:), sf_from(:), law_from(:, :)
        type(strength_law) :: laws(strength_law_count)
        integer :: p, first, last, k

        mu = model%elements%mu
        sf = model%elements%sf
        given = law_values(model%elements)
        allocate (mu_from(size(mu)), sf_from(size(sf)), source=0)
        allocate (law_from(size(mu), strength_law_count), source=0)
        do p = 1, size(values)
            call element_range(model, sweep, p, first, last)
            select case (sweep%targets(p))
            case (target_mu)
                mu(first:last) = values(p)
                mu_from(first:last) = p
            case (target_sf)
                sf(first:last) = values(p)
                sf_from(first:last) = p
            case (target_law)
                associate (contact => model%elements%condition(first:last) == &
                           condition_contact)
                    where (contact) given(first:last, sweep%laws(p)) = values(p)
                    where (contact) law_from(first:last, sweep%laws(p)) = p
                end associate
            case default
                ! not a strength parameter
            end select
        end do
        laws = strength_laws()
        problem = ''
        do k = 1, size(laws)
            select case (laws(k)%at_most)
            case ('sf')
                problem = above_intact(given(:, k), sf, law_from(:, k), sf_from, laws(k))
            case ('mu')
                problem = above_intact(given(:, k), mu, law_from(:, k), mu_from, laws(k))
            case default
                ! no Coulomb value it may not exceed
            end select
            if (len(problem) > 0) return
        end do

    contains

        !> The first element with a swept residual or intact value whose residual (below
        !> no_residual_drop, the mark of none) exceeds its intact value.
        function above_intact(residual, intact, residual_from, from, law) result(problem)
            real(wp), intent(in) :: residual(:), intact(:)
            integer, intent(in) :: residual_from(:), from(:)
            type(strength_law), intent(in) :: law
            character(len=:), allocatable :: problem, fracture
            integer :: j, f

            problem = ''
            j = findloc((from > 0 .or. residual_from > 0) .and. residual < no_residual_drop &
                        .and. residual > intact, .true., 1)
            if (j == 0) return
            f = model%elements%fracture_id(j)
            fracture = ' of fracture '//itoa(f)//' '//model%fractures(f)%name//' ('// &
                at_most_rule(law)//'; one model with these values is refused too)'
            if (from(j) > 0) then
                problem = trim(sweep%names(from(j)))//' = '//short_real(values(from(j)))// &
                    ' is below '//law%name//' = '//short_real(residual(j))//fracture// &
                    ': sweep values of at least '//short_real(residual(j))//', or lower '// &
                    law%name
            else
                problem = trim(sweep%names(residual_from(j)))//' = '// &
                    short_real(residual(j))//' is above '//law%at_most//' = '// &
                    short_real(intact(j))//fracture//': sweep values of at most '// &
                    short_real(intact(j))//', or raise '//law%at_most
            end if
        end function above_intact

    end function weakening_problem

    !> The growth options of a task: new_mu, new_sf and the strength laws of new elements as
    !> the task sets them, the base model's where it does not.
    pure function task_growth(base, sweep, values) result(growth)
        !> The base model's growth options
        type(growth_options), intent(in) :: base
        !> The sweep (validated against this model)
        type(sweep_definition), intent(in) :: sweep
        !> The task's value of each parameter, shape (np)
        real(wp), intent(in) :: values(:)
        type(growth_options) :: growth
        integer :: p, k

        growth = base
        do p = 1, size(values)
            select case (sweep%targets(p))
            case (target_new_mu)
                growth%override_mu = .true.
                growth%new_mu = values(p)
            case (target_new_sf)
                growth%override_sf = .true.
                growth%new_sf = values(p)
            case (target_new_law)
                k = sweep%laws(p)
                growth%override_law(k) = .true.
                growth%new_law(k) = values(p)
            case default
                ! not a law of new elements
            end select
        end do
    end function task_growth

    !> A task that sets a law of new elements in a model without &growth, or whose new
    !> elements would take a residual cohesion or friction above the intact one (refused in
    !> &growth too): why, '' when there is no problem.
    function new_law_problem(model, sweep, values) result(problem)
        !> The base model (read and checked)
        type(model_type), intent(in) :: model
        !> The sweep (validated against this model)
        type(sweep_definition), intent(in) :: sweep
        !> The task's value of each parameter, shape (np)
        real(wp), intent(in) :: values(:)
        !> The problem, '' when there is none
        character(len=:), allocatable :: problem
        type(growth_options) :: g
        type(strength_law) :: laws(strength_law_count)
        real(wp) :: bound
        logical :: bounded
        integer :: k

        problem = ''
        if (.not. any(sweep%targets == target_new_mu .or. sweep%targets == target_new_sf .or. &
                      sweep%targets == target_new_law)) return
        if (.not. model%growth%active) then
            problem = 'the laws of new elements (new_mu, new_sf, new_tensile_strength ...) '// &
                      'need a &growth group'
            return
        end if
        g = task_growth(model%growth, sweep, values)
        laws = strength_laws()
        do k = 1, size(laws)
            call new_law_bound(g, laws(k), bounded, bound)
            if (.not. (g%override_law(k) .and. bounded)) cycle
            if (g%new_law(k) > bound) then
                problem = 'new_'//laws(k)%name//' = '//short_real(g%new_law(k))// &
                    ' exceeds new_'//laws(k)%at_most//' = '//short_real(bound)//' ('// &
                    at_most_rule(laws(k))//')'
                return
            end if
        end do
    end function new_law_problem

    !> True for the targets that describe the remote stress by principal stresses.
    elemental logical function is_principal(target)
        integer, intent(in) :: target

        is_principal = target == target_s1 .or. target == target_s3 .or. target == target_angle
    end function is_principal

    !> Principal stresses of (sxx, syy, sxy): s1 the most compressive (algebraically
    !> least), s3 the other, angle of the s1 axis from +x [degrees] in (-90, 90].
    pure subroutine principal_stresses(sxx, syy, sxy, s1, s3, angle)
        real(wp), intent(in) :: sxx, syy, sxy
        real(wp), intent(out) :: s1, s3, angle
        real(wp) :: centre, radius

        centre = 0.5_wp * (sxx + syy)
        radius = hypot(0.5_wp * (sxx - syy), sxy)
        s1 = centre - radius
        s3 = centre + radius
        angle = 0.0_wp
        if (radius > 0.0_wp) angle = 0.5_wp * atan2(-2.0_wp * sxy, syy - sxx) / degree
        if (angle <= -90.0_wp) angle = angle + 180.0_wp
    end subroutine principal_stresses

    !> Cosine of an angle in degrees, exact (0, +-1) at multiples of 90 degrees, so that
    !> axes along x and y give exactly zero shear.
    pure function cos_degrees(angle) result(c)
        real(wp), intent(in) :: angle
        real(wp) :: c
        real(wp) :: reduced

        reduced = modulo(angle, 360.0_wp)
        if (reduced == 90.0_wp .or. reduced == 270.0_wp) then
            c = 0.0_wp
        else if (reduced == 180.0_wp) then
            c = -1.0_wp
        else
            c = cos(reduced * degree)
        end if
    end function cos_degrees

    !> Text without blanks.
    pure function squeeze(text) result(out)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: out
        integer :: i

        out = ''
        do i = 1, len(text)
            if (text(i:i) /= ' ') out = out//text(i:i)
        end do
    end function squeeze

end module ddc_sweep_tasks
