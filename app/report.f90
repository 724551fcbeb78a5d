!> What the program tells the user on standard output: the effective model with notes on
!> implausible input, and a summary of the results.
module ddc_app_report
    use, intrinsic :: iso_fortran_env, only: output_unit
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, rigid_joint, tensile_cap, condition_names, &
        observation_kind_names, symmetry_none, symmetry_names, domain_names, &
        domain_half_plane, domain_bimaterial, load_path_names, source_overpressure, &
        growth_tips_names, growth_criterion_names, growth_criterion_work, strength_law_count, &
        work_mode_names, angle_search_names, work_mode_any
    use ddc_model_laws, only: strength_law, strength_laws
    use ddc_model_records, only: units_one, units_text
    use ddc_model_results, only: model_results, state_names, point_near, point_on_element, &
        point_outside_body, &
        growth_reason_names, growth_end_names, growth_subcritical, growth_intersection, &
        growth_surface, growth_linked, growth_closed, growth_waiting, growth_enclosing, &
        growth_interface, growth_grew
    use ddc_model_plausibility, only: plausibility_notes, depth_range
    use ddc_model_strength_fronts, only: instant_drop_notes, cohesive_zone_warnings
    use ddc_model_loads, only: work_threshold_of
    use ddc_model_medium, only: medium_of, upper_remote_stress
    use ddc_growth_summary, only: tip_summary, summarize_tips, linked_fracture
    use ddc_app_report_cycle, only: print_cycle_options, print_cycle_summary
    use ddc_contact_options, only: lcp_method_names, open_cohesion_names
    use ddc_text, only: short_real, itoa, prefix_lines, join_integers
    use ddc_output_provenance, only: describe_run, provenance_line
    use ddc_history_path, only: load_text
    implicit none
    private

    public :: print_model_summary, print_results_summary, print_growth_step, field_warnings
    public :: print_progress

contains

    !> Echo the effective model: material, domain, remote stress and its gradients, pore
    !> fluid, symmetry, fractures, observations, loading history, solver, output; then the
    !> notes on implausible input (ddc_model_plausibility).
    subroutine print_model_summary(unit, model, units_given)
        !> Unit to write to
        integer, intent(in) :: unit
        !> The model as read
        type(model_type), intent(in) :: model
        !> The stress unit was chosen by the user (false for a TWODD deck: no strain note)
        logical, intent(in) :: units_given
        character(len=:), allocatable :: stress, gradient, notes
        real(wp) :: deepest, highest
        integer :: i, first

        stress = ' '//model%stress_unit
        gradient = ' '//model%stress_unit//'/'//model%length_unit
        call depth_range(model, deepest, highest)
        write (unit, '(a)') 'ddc2d model: '//model%title
        if (model%elements%domain == domain_bimaterial) then
            write (unit, '(a)') '  lower material: youngs_modulus = '// &
                short_real(model%youngs_modulus)//stress//', poissons_ratio = '// &
                short_real(model%poissons_ratio)
            write (unit, '(a)') '  upper material: youngs_modulus = '// &
                short_real(model%upper_youngs_modulus)//stress//', poissons_ratio = '// &
                short_real(model%upper_poissons_ratio)
        else
            write (unit, '(a)') '  youngs_modulus = '//short_real(model%youngs_modulus)// &
                stress//', poissons_ratio = '//short_real(model%poissons_ratio)
        end if
        if (model%elements%domain == domain_half_plane) then
            write (unit, '(a)') '  domain: half_plane (free surface y = 0, the body y < 0)'
        else if (model%elements%domain == domain_bimaterial) then
            associate (upper => upper_remote_stress(medium_of(model), &
                                                    [model%sxx, model%syy, model%sxy]))
                write (unit, '(a)') '  domain: bimaterial (two bonded half-planes, interface '// &
                    'y = '//short_real(model%interface_y)//'; the remote stress below is '// &
                    "the lower material's, the upper one's sxx = "//short_real(upper(1))// &
                    stress//')'
            end associate
        else
            write (unit, '(a)') '  domain: '//trim(domain_names(model%elements%domain))
        end if
        write (unit, '(a)') '  remote stress sxx, syy, sxy = '//triple([model%sxx, model%syy, &
            model%sxy])//stress//trim(merge(' at y = 0', '         ', &
            any(model%stress_gradient /= 0.0_wp)))
        if (any(model%stress_gradient /= 0.0_wp)) then
            write (unit, '(a)') '  remote stress gradients dsxx_dy, dsyy_dy, dsxy_dy = '// &
                triple(model%stress_gradient)//gradient
            write (unit, '(a)') '    at y = '//short_real(deepest)//' '//model%length_unit// &
                ' (the deepest point of the model): sxx, syy, sxy = '// &
                triple([model%sxx, model%syy, model%sxy] + model%stress_gradient * deepest)// &
                stress
        end if
        if (any(model%pore_fluid /= 0.0_wp)) then
            write (unit, '(a)') '  pore fluid p0 = '//short_real(model%pore_fluid(1))// &
                stress//', dp_dy = '//short_real(model%pore_fluid(2))//gradient// &
                ', inside every contact element'
            if (model%pore_fluid(2) /= 0.0_wp) write (unit, '(a)') '    at y = '// &
                short_real(deepest)//' '//model%length_unit//': p = '// &
                short_real(model%pore_fluid(1) + model%pore_fluid(2) * deepest)//stress
        else
            write (unit, '(a)') '  pore fluid: none'
        end if
        write (unit, '(a)') '  symmetry: '//trim(symmetry_names(model%elements%symmetry%kind))// &
            trim(symmetry_lines())
        if (allocated(model%body)) then
            write (unit, '(a)') '  body: '//itoa(size(model%body%x))//' sides, '// &
                itoa(sum(model%body%elements))//' elements of three nodes '// &
                '(docs/finite-bodies.md)'
        end if
        do i = 1, size(model%fractures)
            first = model%fractures(i)%first_element
            write (unit, '(a,i0,a,a,a,i0,a,a)') '  fracture ', i, ' ', model%fractures(i)%name, &
                ': ', model%fractures(i)%last_element - first + 1, ' elements, condition ', &
                trim(condition_names(model%elements%condition(first)))
            call print_strength(first, model%fractures(i)%last_element)
        end do
        if (allocated(model%observations)) then
            do i = 1, size(model%observations)
                write (unit, '(a,a,a,a,a,i0,a)') '  ', trim(observation_kind_names( &
                    model%observations(i)%kind)), ' ', model%observations(i)%name, ': ', &
                    size(model%observations(i)%x), ' points'
            end do
        end if
        if (allocated(model%load_path%vertex)) call print_load_path()
        write (unit, '(a,a,a,a)') '  solver: lcp_method = ', &
            trim(lcp_method_names(model%solver%lcp_method)), ', open_cohesion = ', &
            trim(open_cohesion_names(model%solver%open_cohesion))
        if (model%growth%active) call print_growth_options(unit, model)
        if (model%cycle%active) call print_cycle_options(unit, model)
        write (unit, '(a)') '  output: '//model%output_file
        if (allocated(model%resumed_from)) write (unit, '(a)') '  resumed from '// &
            model%resumed_from//' (written '//model%resumed_from_created//')'
        notes = plausibility_notes(model, units_given)
        if (len(notes) > 0) write (unit, '(a)') prefix_lines('note: ', notes)
        notes = instant_drop_notes(model)
        if (len(notes) > 0) write (unit, '(a)') prefix_lines('note: ', notes)
        notes = cohesive_zone_warnings(model)
        if (len(notes) > 0) write (unit, '(a)') prefix_lines('warning: ', notes)

    contains

        !> The strength beyond Coulomb of elements first:last, when any is not the default.
        subroutine print_strength(first, last)
            integer, intent(in) :: first, last

            associate (t => model%elements%tensile_strength(first:last), &
                       t_in => tensile_cap(model%elements%tensile_strength(first:last), &
                                           model%elements%sf(first:last), &
                                           model%elements%mu(first:last)), &
                       sf => model%elements%sf(first:last), &
                       sfr => min(model%elements%sf(first:last), &
                                  model%elements%sf_residual(first:last)), &
                       dc => model%elements%slip_weakening_distance(first:last))
                if (any(t > 0.0_wp)) call print_tensile_strength(t, t_in, &
                    model%elements%opening_weakening_distance(first:last))
                if (any(sfr < sf .and. dc > 0.0_wp)) then
                    write (unit, '(a)') '    sf_residual '//short_real(minval(sfr))//' .. '// &
                        short_real(maxval(sfr))//stress//' (the cohesion falls to it as '// &
                        'the slip grows to slip_weakening_distance '// &
                        short_real(minval(dc, mask=sfr < sf))//' .. '// &
                        short_real(maxval(dc, mask=sfr < sf))//' '//model%length_unit//')'
                else if (any(sfr < sf)) then
                    write (unit, '(a)') '    sf_residual '//short_real(minval(sfr))//' .. '// &
                        short_real(maxval(sfr))//stress// &
                        ' (the cohesion once the element has slipped)'
                end if
            end associate
            associate (mu => model%elements%mu(first:last), &
                       mud => min(model%elements%mu(first:last), &
                                  model%elements%mu_dynamic(first:last)), &
                       dc => model%elements%slip_weakening_distance(first:last))
                if (any(mud < mu)) write (unit, '(a)') '    mu_dynamic '// &
                    short_real(minval(mud))//' .. '//short_real(maxval(mud))// &
                    ', slip_weakening_distance '//short_real(minval(dc))//' .. '// &
                    short_real(maxval(dc))//' '//model%length_unit// &
                    ' (friction falls from mu to mu_dynamic as the slip grows to it)'
            end associate
            associate (ks => model%elements%shear_stiffness(first:last), &
                       kn => model%elements%normal_stiffness(first:last))
                if (any(ks < rigid_joint) .or. any(kn < rigid_joint)) write (unit, '(a)') &
                    '    elastic joint: shear_stiffness '//stiffness_range(ks)// &
                    ', normal_stiffness '//stiffness_range(kn)//stress//'/'// &
                    model%length_unit
            end associate
        end subroutine print_strength

        !> The tensile strength in force, and the given one where the cap at the Coulomb apex
        !> sf/mu lowers it (the plausibility notes say on which elements).
        subroutine print_tensile_strength(given, in_force, d_o)
            real(wp), intent(in) :: given(:), in_force(:), d_o(:)
            character(len=:), allocatable :: line

            line = '    tensile_strength '//short_real(minval(in_force))//' .. '// &
                short_real(maxval(in_force))//stress
            if (any(in_force < given)) then
                line = line//' in force (given '//short_real(minval(given))//' .. '// &
                    short_real(maxval(given))//stress//', capped at sf/mu;'
            else
                line = line//' (capped at sf/mu;'
            end if
            if (any(d_o > 0.0_wp .and. given > 0.0_wp)) then
                write (unit, '(a)') line//' falls to 0 as the opening grows to '// &
                    'opening_weakening_distance '// &
                    short_real(minval(d_o, mask=given > 0.0_wp))//' .. '// &
                    short_real(maxval(d_o, mask=given > 0.0_wp))//' '//model%length_unit//')'
            else
                write (unit, '(a)') line//' lost once the element opens)'
            end if
        end subroutine print_tensile_strength

        !> 'min .. max' of stiffnesses, 'rigid' for rigid contact.
        function stiffness_range(k) result(text)
            real(wp), intent(in) :: k(:)
            character(len=:), allocatable :: text

            if (all(k >= rigid_joint)) then
                text = 'rigid'
            else
                text = short_real(minval(k))//' .. '
                if (any(k >= rigid_joint)) then
                    text = text//'rigid'
                else
                    text = text//short_real(maxval(k))
                end if
            end if
        end function stiffness_range

        !> ' (xsym = .., ysym = ..): image elements implicit', or '' without symmetry.
        function symmetry_lines() result(text)
            character(len=:), allocatable :: text

            text = ''
            if (model%elements%symmetry%kind == symmetry_none) return
            text = ' (xsym = '//short_real(model%elements%symmetry%xsym)//', ysym = '// &
                short_real(model%elements%symmetry%ysym)//'): image elements implicit'
        end function symmetry_lines

        !> The path: steps per leg and the vertices of every quantity it varies.
        subroutine print_load_path()
            integer :: q, v

            write (unit, '(a)') '  loading history: '//itoa(1 + sum(model%load_path%steps))// &
                ' steps, legs of '//join_integers(model%load_path%steps)//' increments'
            do q = 1, size(load_path_names)
                if (.not. model%load_path%varies(q)) cycle
                write (unit, '(a)', advance='no') '    '//trim(load_path_names(q))//' at the '// &
                    'vertices:'
                do v = 1, size(model%load_path%vertex, 2)
                    write (unit, '(a)', advance='no') ' '//short_real(model%load_path%vertex(q, v))
                end do
                write (unit, '(a)') ''
            end do
            if (allocated(model%load_path%time)) then
                write (unit, '(a)', advance='no') '    time at the vertices:'
                do v = 1, size(model%load_path%time)
                    write (unit, '(a)', advance='no') ' '//short_real(model%load_path%time(v))
                end do
                write (unit, '(a)') ' '//model%time_unit
            end if
            if (allocated(model%injections)) call print_injections()
            ! Said here, before a user relies on --resume to go on with the path
            if (.not. model%growth%active .and. (any(model%elements%shear_stiffness < &
                rigid_joint) .or. any(model%elements%normal_stiffness < rigid_joint))) then
                write (unit, '(a)') '    --resume cannot continue this history: its elastic '// &
                    'joints'' memory is their plastic slip, which the result file does not hold'
            end if
        end subroutine print_load_path

        !> One line per fluid source.
        subroutine print_injections()
            integer :: k
            character(len=:), allocatable :: what, when

            do k = 1, size(model%injections)
                associate (s => model%injections(k))
                    if (s%kind == source_overpressure) then
                        what = 'overpressure '//short_real(s%value)//' '//model%stress_unit
                    else
                        what = 'rate '//short_real(s%value)//' '//model%length_unit//'^2/'// &
                            model%time_unit
                    end if
                    when = ''
                    if (s%start /= -huge(1.0_wp)) when = ' from '//short_real(s%start)
                    if (s%stop /= huge(1.0_wp)) when = when//' until '//short_real(s%stop)
                    write (unit, '(a)') '    injection '//s%name//' on '// &
                        model%fractures(s%fracture_id)%name//' at ('//short_real(s%x)//', '// &
                        short_real(s%y)//'): '//what//when
                end associate
            end do
            if (model%fluid%active) write (unit, '(a)') '    coupled flow (&fluid): '// &
                'viscosity '//short_real(model%fluid%viscosity)//' '//model%stress_unit// &
                ' '//model%time_unit//', compressibility '// &
                short_real(model%fluid%compressibility)//' 1/'//model%stress_unit// &
                ', leak-off coefficient '//short_real(model%fluid%leak_off_coefficient)
        end subroutine print_injections

    end subroutine print_model_summary

    !> One line of progress on standard output, flushed at once (the progress handler of
    !> ddc_progress).
    subroutine print_progress(line)
        !> The line
        character(len=*), intent(in) :: line

        write (output_unit, '(a)') '  '//line
        flush (output_unit)
    end subroutine print_progress

    !> Echo the effective &growth options.
    subroutine print_growth_options(unit, model)
        integer, intent(in) :: unit
        type(model_type), intent(in) :: model
        character(len=:), allocatable :: names, units
        type(strength_law) :: laws(strength_law_count)
        integer :: f

        associate (g => model%growth)
            write (unit, '(a,i0,a,g0,1x,a)') '  growth: at most ', g%steps, &
                ' steps, toughness = ', g%toughness, model%stress_unit//' '// &
                model%length_unit//'^0.5'
            if (g%increment > 0.0_wp) then
                write (unit, '(a,g0,1x,a)') '    increment = ', g%increment, model%length_unit
            else
                write (unit, '(a)') '    increment = 2 x the tip element length (default)'
            end if
            if (g%element_length > 0.0_wp) then
                write (unit, '(a,g0,1x,a)') '    element_length = ', g%element_length, &
                    model%length_unit
            else
                write (unit, '(a)') '    element_length = the tip element length (default)'
            end if
            write (unit, '(a,a,a,a,a,i0)') "    tips = '", trim(growth_tips_names(g%tips)), &
                "', criterion = '", trim(growth_criterion_names(g%criterion)), &
                "', max_corrections = ", g%max_corrections
            if (g%criterion == growth_criterion_work) then
                write (unit, '(a,g0,a,g0,a)') '    angle_range = ', g%angle_range, &
                    ' degrees, angle_step = ', g%angle_step, ' degrees'
                write (unit, '(a)') "    work_mode = '"//trim(work_mode_names(g%work_mode))// &
                    "', angle_search = '"//trim(angle_search_names(g%angle_search))//"'"
                if (g%work_threshold > 0.0_wp) then
                    write (unit, '(a,g0,1x,a)') '    work_threshold = ', g%work_threshold, &
                        model%stress_unit//' '//model%length_unit
                else
                    write (unit, '(a,g0,1x,a)') '    work_threshold = ', work_threshold_of(g, &
                        model%youngs_modulus, model%poissons_ratio), model%stress_unit//' '// &
                        model%length_unit//' (default: 2 toughness^2 (1 - nu^2) / E)'
                end if
            end if
            names = ''
            do f = 1, size(model%fractures)
                if (.not. g%fracture_grows(f)) cycle
                if (len(names) > 0) names = names//', '
                names = names//model%fractures(f)%name
            end do
            write (unit, '(a)') '    fractures that may grow: '//names
            if (g%override_mu) write (unit, '(a,g0)') '    new contact elements: mu = ', g%new_mu
            if (g%override_sf) write (unit, '(a,g0,1x,a)') '    new contact elements: sf = ', &
                g%new_sf, model%stress_unit
            laws = strength_laws()
            do f = 1, size(laws)
                if (.not. g%override_law(f)) cycle
                ! A ratio echoes without units
                units = ''
                if (laws(f)%units /= units_one) units = units_text(laws(f)%units, &
                    model%stress_unit, model%length_unit)
                write (unit, '(a,g0,1x,a)') '    new contact elements: '//laws(f)%name// &
                    ' = ', g%new_law(f), units
            end do
        end associate
        if (model%initiation%active) call print_initiation_options(unit, model)
    end subroutine print_growth_options

    !> Echo the effective &initiation options.
    subroutine print_initiation_options(unit, model)
        integer, intent(in) :: unit
        type(model_type), intent(in) :: model
        integer :: p

        associate (o => model%initiation)
            write (unit, '(a,g0,1x,a,a,g0,1x,a)') '  initiation: tensile_strength = ', &
                o%tensile_strength, model%stress_unit, ', probe_distance = ', &
                o%probe_distance, model%length_unit
            do p = 1, size(o%flaw_x)
                write (unit, '(a,i0,a,g0,a,g0)') '    flaw ', p, ' at ', o%flaw_x(p), ', ', &
                    o%flaw_y(p)
            end do
            if (size(o%flaw_x) == 0) return
            if (o%flaw_length > 0.0_wp) then
                write (unit, '(a,g0,1x,a)') '    flaw_length = ', o%flaw_length, &
                    model%length_unit
            else
                write (unit, '(a)') '    flaw_length = the growth increment (default)'
            end if
        end associate
    end subroutine print_initiation_options

    !> One line per new fracture a growth run started inside the rock.
    subroutine print_initiations(unit, model, results)
        integer, intent(in) :: unit
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: results
        integer :: i

        associate (r => results%initiations)
            if (.not. allocated(r%kind)) return
            write (unit, '(a,i0,a)') 'initiation: ', size(r%kind), ' new fracture(s)'
            do i = 1, size(r%kind)
                write (unit, '(2x,a,a,i0,a,i0,a,es12.5,a,es12.5,a,es12.5,1x,a,a,f8.2,a)') &
                    model%fractures(r%fracture_id(i))%name, ': step ', r%step(i), &
                    ', load step ', r%load_step(i), ', at (', r%x(i), ', ', r%y(i), &
                    '), tension ', r%tension(i), model%stress_unit, ', direction ', &
                    r%angle(i), ' degrees'
            end do
            if (r%largest_step > 0) write (unit, '(2x,a,i0,a,es12.5,1x,a,a,es12.5,a,es12.5,a)') &
                'none started in step ', r%largest_step, ': largest probed tension ', &
                r%largest_tension, model%stress_unit, ' at (', r%largest_x, ', ', r%largest_y, ')'
        end associate
    end subroutine print_initiations

    !> One line per growth step on standard output, flushed (a long run shows progress).
    subroutine print_growth_step(step, growing, largest_k_eq, solves, seconds, elapsed)
        !> The step, and the number of tips that grew in it
        integer, intent(in) :: step, growing
        !> The largest K_eq of the step's tips [stress unit * length unit**0.5]
        real(wp), intent(in) :: largest_k_eq
        !> Solves of the model in the step
        integer, intent(in) :: solves
        !> Wall time of the step, and since the run started [s]
        real(wp), intent(in) :: seconds, elapsed

        write (output_unit, '(a,i0,a,i0,a,es11.4,a,i0,a,f8.3,a,f9.3,a)') 'growth step ', &
            step, ': ', growing, ' tip(s) grew, largest K_eq ', largest_k_eq, ', ', solves, &
            ' solve(s),', seconds, ' s, ', elapsed, ' s in all'
        flush (output_unit)
    end subroutine print_growth_step

    !> Each tip of a growth run: where it ended, how far it grew and why it stopped.
    subroutine print_growth_summary(unit, model, results)
        integer, intent(in) :: unit
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: results
        type(tip_summary), allocatable :: tips(:)
        character(len=*), parameter :: ends(0:1) = [character(len=5) :: 'begin', 'end']
        integer :: i, width

        call print_initiations(unit, model, results)
        call summarize_tips(results%growth, tips)
        write (unit, '(a,i0,a,a)') 'growth: ', results%growth%steps_taken, &
            ' step(s) with growth; ended: ', trim(growth_end_names(results%growth%end_reason))
        width = len('fracture')
        do i = 1, size(tips)
            width = max(width, len(model%fractures(tips(i)%fracture_id)%name))
        end do
        write (unit, '(2x,a,2x,a5,2x,a5,2x,a14,2x,a11,2x,a)') 'fracture'//repeat(' ', &
            width - len('fracture')), 'tip', 'steps', 'path length', 'K_eq / K_Ic', &
            'stopped because'
        do i = 1, size(tips)
            write (unit, '(2x,a,2x,a5,2x,i5,2x,es14.6,2x,f11.4,2x,a)') &
                model%fractures(tips(i)%fracture_id)%name//repeat(' ', width - &
                len(model%fractures(tips(i)%fracture_id)%name)), ends(tips(i)%end), &
                tips(i)%steps_grown, tips(i)%path_length, &
                tips(i)%last_k_eq / model%growth%toughness, &
                stop_text(tips(i)%last_reason)//ends_on(tips(i))
        end do
        call print_friction_note()
        if (allocated(results%history%element_count)) call print_load_steps()

    contains

        !> Under 'work': a note when kinks grew with most of their work done through slip of
        !> frictional faces (docs/fracture-growth.md#the-work-criterion).
        subroutine print_friction_note()
            logical, allocatable :: frictional(:)

            if (.not. allocated(results%growth%slip_share)) return
            associate (g => results%growth)
                if (size(g%slip_share) /= size(g%reason)) return
                ! Only a tip that grew has a share (NaN where no trial counted, and in the
                ! records of a file written before the share, which a run resumed)
                frictional = g%reason == growth_grew .and. .not. ieee_is_nan(g%slip_share)
                where (frictional) frictional = g%slip_share > 0.5_wp
                if (.not. any(frictional)) return
                write (unit, '(a)') '  note: '//itoa(count(frictional))//' of '// &
                    itoa(count(g%reason == growth_grew))//' kinks grew with most of their '// &
                    'work change done through slip of frictional faces (/growth/slip_share '// &
                    'up to '//short_real(0.01_wp * anint(100 * maxval(g%slip_share, &
                    mask=frictional)))//'): there the efficiency is work of the loads that '// &
                    'friction partly dissipates, not twice an energy release rate'// &
                    trim(merge(" (work_mode = 'opening' grows only kinks that open)", &
                               '                                                   ', &
                               model%growth%work_mode == work_mode_any))
            end associate
        end subroutine print_friction_note

        !> Per load step of a loading history: the load and each tip that grew, by how much.
        subroutine print_load_steps()
            character(len=:), allocatable :: line
            real(wp) :: grown, before
            integer :: k, t

            associate (h => results%history)
                do k = 1, size(h%element_count)
                    line = ''
                    do t = 1, size(h%tip_fracture_id)
                        before = 0.0_wp
                        if (k > 1) before = h%grown_length(t, k - 1)
                        grown = h%grown_length(t, k) - before
                        if (grown <= 0.0_wp) cycle
                        if (len(line) > 0) line = line//','
                        line = line//' '//model%fractures(h%tip_fracture_id(t))%name//' '// &
                            trim(ends(h%tip_end(t)))//' +'//short_real(grown)
                    end do
                    if (len(line) == 0) line = ' nothing grew'
                    write (unit, '(a)') '  load step '//itoa(k)//' ('// &
                        load_text(h%load(:, k), model%load_path%varies)//'):'//line
                end do
            end associate
        end subroutine print_load_steps

        !> ' NAME' of the fracture a linked tip ends on (else nothing).
        function ends_on(tip) result(text)
            type(tip_summary), intent(in) :: tip
            character(len=:), allocatable :: text
            integer :: f

            text = ''
            if (tip%last_reason /= growth_linked) return
            f = linked_fracture(model, tip%fracture_id, tip%end)
            if (f > 0) text = ' '//model%fractures(f)%name
        end function ends_on

    end subroutine print_growth_summary

    !> Why a tip stopped, from the reason of its last record.
    pure function stop_text(reason) result(text)
        integer, intent(in) :: reason
        character(len=:), allocatable :: text

        select case (reason)
        case (growth_subcritical)
            text = 'arrested: K_eq < toughness'
        case (growth_intersection)
            text = 'intersection: next to another element'
        case (growth_surface)
            text = 'surface: broke through the free surface'
        case (growth_linked)
            text = 'linked: ends on fracture'
        case (growth_closed)
            text = 'closed: the kink closes (K_I = 0)'
        case (growth_enclosing)
            text = 'enclosing: a link would enclose a block'
        case (growth_interface)
            text = 'interface: stopped before the interface of the two materials'
        case (growth_waiting)
            text = 'step limit (critical, waiting for a more critical tip)'
        case default
            text = 'step limit (grew in the last step: '//trim(growth_reason_names(reason))//')'
        end select
    end function stop_text
    !> "a b c" of three numbers.
    function triple(values) result(text)
        real(wp), intent(in) :: values(3)
        character(len=:), allocatable :: text

        text = short_real(values(1))//' '//short_real(values(2))//' '//short_real(values(3))
    end function triple

    !> Summary of the results: states, peak DDs, tips with K, timings.
    subroutine print_results_summary(unit, model, results)
        !> Unit to write to
        integer, intent(in) :: unit
        !> The model solved
        type(model_type), intent(in) :: model
        !> Its results
        type(model_results), intent(in) :: results
        integer :: i, state

        associate (e => results%elements, s => results%solver)
            if (s%processes > 0) then
                write (unit, '(a,a,3(a,i0),a,i0,a,i0,a,es10.3)') 'solved with ', s%method, &
                    ' on ', s%processes, ' process(es) (grid ', s%process_grid(1), ' x ', &
                    s%process_grid(2), ', block size ', s%block_size, '), ', s%threads, &
                    ' thread(s) each; equilibrium residual ', s%equilibrium_residual
            else if (s%lcp_solves > 1 .and. .not. allocated(model%load_path%vertex) .and. &
                     .not. model%growth%active) then
                ! One model whose strengths in force changed: the fixed point's solves.
                write (unit, '(a,a,a,i0,a,i0,a,es10.3)') 'solved with ', s%method, ' in ', &
                    s%lcp_solves, ' solves (strengths in force) on ', s%threads, &
                    ' thread(s); equilibrium residual ', s%equilibrium_residual
            else
                write (unit, '(a,a,a,i0,a,es10.3)') 'solved with ', s%method, ' on ', &
                    s%threads, ' thread(s); equilibrium residual ', s%equilibrium_residual
            end if
            do state = 0, 3
                if (count(e%state == state) > 0) write (unit, '(2x,a,a,i0)') &
                    trim(state_names(state)), ' elements: ', count(e%state == state)
            end do
            if (size(e%ds) > 0) then
                write (unit, '(a,es12.5,1x,a)') '  peak |ds| = ', maxval(abs(e%ds)), &
                    model%length_unit
                write (unit, '(a,es12.5,1x,a)') '  peak opening = ', max(0.0_wp, maxval(-e%dn)), &
                    model%length_unit
            end if
            if (results%tips%n > 0 .and. allocated(results%tips%k_method)) then
                write (unit, '(a)') '  K: '//k_method_text(results%tips%k_method)
            end if
            do i = 1, results%tips%n
                write (unit, '(a,i0,a,2(es12.5,1x),a,es12.5,a,es12.5,1x,a)') '  tip ', i, &
                    ' at ', results%tips%x(i), results%tips%y(i), ' K_I = ', &
                    results%tips%k1(i), ', K_II = ', results%tips%k2(i), &
                    model%stress_unit//' '//model%length_unit//'^1/2'
                if (results%tips%graded(i) == 1) write (unit, '(a)') '    (graded mesh at '// &
                    'this tip: the elements near it differ in length, K is less accurate)'
            end do
            if (allocated(results%fields)) then
                do i = 1, size(results%fields)
                    associate (o => model%observations(i), flag => results%fields(i)%flag)
                        write (unit, '(a)') '  '//trim(observation_kind_names(o%kind))//' '// &
                            o%name//': '//itoa(size(flag))//' points, '// &
                            itoa(count(flag == point_on_element))//' on an element (NaN), '// &
                            itoa(count(flag == point_near))//' within one element length '// &
                            'of an element centre (reduced accuracy)'//trim(outside_text(flag))
                    end associate
                end do
            end if
            write (unit, '(a,6(f0.3,a))') '  seconds: assembly ', s%seconds_assembly, &
                ', factorization ', s%counts%seconds, ', lcp ', s%seconds_lcp, &
                ', fields ', s%seconds_fields, ', output ', s%seconds_output, ', total ', &
                s%seconds_total + s%seconds_output, ''
            write (unit, '(a)') '  '//provenance_line(describe_run())
        end associate
        if (allocated(results%growth%step)) call print_growth_summary(unit, model, results)
        if (allocated(results%cycle%elements)) call print_cycle_summary(unit, model, &
                                                                        results%cycle)
        write (unit, '(a)') 'wrote '//model%output_file
    end subroutine print_results_summary

    !> Warnings on the fields, one per line ('' when there are none): an observation set
    !> whose every point lies on an element, so that all its values are NaN.
    function field_warnings(model, results) result(warnings)
        !> The model solved
        type(model_type), intent(in) :: model
        !> Its results
        type(model_results), intent(in) :: results
        !> The warnings, newline-separated
        character(len=:), allocatable :: warnings
        integer :: i

        warnings = ''
        if (.not. allocated(results%fields)) return
        do i = 1, size(results%fields)
            associate (o => model%observations(i), flag => results%fields(i)%flag)
                if (size(flag) == 0 .or. .not. all(flag == point_on_element)) cycle
                if (len(warnings) > 0) warnings = warnings//new_line('a')
                warnings = warnings//'every point of '//trim(observation_kind_names(o%kind))// &
                    " '"//o%name//"' lies on an element: all its values are NaN (move it "// &
                    'off the fractures)'
            end associate
        end do
    end function field_warnings

    !> The echo's words for /tips k_method.
    pure function k_method_text(k_method) result(text)
        character(len=*), intent(in) :: k_method
        character(len=:), allocatable :: text

        if (index(k_method, 'higher_order') == 1) then
            ! 'higher_order' and what its coupling left, in brackets
            text = 'local higher-order re-solve'//k_method(len('higher_order') + 1:)// &
                   ' (docs/theory/tips.md#the-local-re-solve)'
        else
            ! 'tip_element' and its reason in brackets
            text = 'tip element'//k_method(len('tip_element') + 1:)// &
                   ' (docs/theory/tips.md#k-from-the-tip-element)'
        end if
    end function k_method_text

    !> ', n outside the body (NaN)' where points lie outside a finite body, else ''.
    function outside_text(flag) result(text)
        integer, intent(in) :: flag(:)
        character(len=:), allocatable :: text

        text = ''
        if (any(flag == point_outside_body)) text = ', '//itoa(count(flag == &
            point_outside_body))//' outside the body or on its boundary (NaN)'
    end function outside_text

end module ddc_app_report
