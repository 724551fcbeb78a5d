!> New fractures inside the rock (docs/fracture-growth.md#new-fractures-inside-the-rock): after
!> every solve of a growth run with &initiation, the maximum principal stress (tension positive,
!> effective where there is pore fluid) is probed at `probe_distance` beside both ends of every
!> contact element, on both sides, except in a tip's zone (the tip, and vertices closer to it
!> than its next increment or the probe distance: the tip's own growth decides there), and
!> at every flaw point that has not started yet. Where it reaches the tensile strength a new
!> fracture starts:
!> - a tail at the vertex, on the probe's side: one growth increment (in the increment's
!>   elements) perpendicular to the maximum tension at the probe, named `<parent>_tail<k>`;
!>   at most one per vertex and side;
!> - at a flaw point, a crack of `flaw_length` centred on it, named `flaw<k>`, as the
!>   criterion decides (ddc_growth_criterion's assess_flaw): under MTS where the tension there
!>   reaches the strength, perpendicular to it; under 'work' where the best of its
!>   orientations reaches the work threshold, in that orientation.
!> A new fracture whose elements would cross another element is not started; the next place
!> is tried.
!> When a check starts nothing, the largest tension it probed and where are kept (the last
!> such check's, in /growth/initiations): how far the rock was from a new fracture.
!> One new fracture starts per check (growth step): the one furthest past its threshold (the
!> largest score: tension / tensile strength, or a flaw's efficiency / work threshold under
!> 'work'); ties (within 1e-9 of the score, so that round-off does not decide) go to tails
!> before flaws, then the lowest fracture, element, end (begin first) and side (-1 first),
!> or the lowest flaw. The model is solved with it before anything else happens, and the
!> next check (the next growth step, at the same load until nothing grows or starts) may
!> start the next one.
module ddc_growth_initiation
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_error, only: error_type
    use ddc_text, only: itoa
    use ddc_model_types, only: model_type, growth_options, initiation_options, &
        fracture_type, condition_contact
    use ddc_model_results, only: model_results, field_result, point_on_element, &
        tip_set
    use ddc_model_initiations, only: initiation_record, initiation_tail, initiation_flaw
    use ddc_model_records, only: append_initiation, empty_initiation_record
    use ddc_model_medium, only: medium_of
    use ddc_mesh_checks, only: check_elements
    use ddc_post_fields, only: evaluate_field
    use ddc_growth_extension, only: tip_end_begin, tip_end_end
    use ddc_growth_new_fracture, only: flaw_path, add_fracture
    use ddc_growth_tips, only: growing_tip, locate_tip, increment_for
    use ddc_growth_solver, only: solve_grown, accept_trial
    use ddc_growth_run_state, only: growth_state
    use ddc_growth_load_steps, only: follow_growth
    use ddc_growth_criterion, only: assess_flaw
    implicit none
    private

    public :: start_fracture, probe_candidates, initiation_candidate, principal_tension

    !> Scores within this of each other are tied: decided by index, not by round-off
    real(wp), parameter :: tie_tolerance = 1.0e-9_wp
    !> Two vertices closer than this fraction of the probe distance are one
    real(wp), parameter :: same_point = 1.0e-6_wp

    !> A place where a new fracture may start, and the tension probed there.
    type :: initiation_candidate
        !> initiation_tail or initiation_flaw
        integer :: kind = initiation_tail
        !> A tail's parent fracture, element, end (tip_end_begin, tip_end_end) and side
        !> (+1 the side of the element normal, -1 the other); a flaw's index
        integer :: parent = 0, element = 0, end = 0, side = 0, flaw = 0
        !> Start point (vertex or flaw point) and probe point [length unit]
        real(wp) :: point(2) = 0.0_wp, probe(2) = 0.0_wp
        !> Maximum principal stress at the probe, tension positive [stress unit]
        real(wp) :: tension = 0.0_wp
        !> Unit direction of the maximum tension at the probe
        real(wp) :: tension_direction(2) = [1.0_wp, 0.0_wp]
        !> How far past its threshold (1 or more starts it): tension / tensile strength, or a
        !> flaw's as the criterion scores it
        real(wp) :: score = 0.0_wp
        !> A flaw's crack direction and efficiency (NaN but under 'work')
        real(wp) :: along(2) = [1.0_wp, 0.0_wp], efficiency = 0.0_wp
    end type initiation_candidate

contains

    !> Check the current solution for a new fracture and start the first one (the tie rule
    !> above): the grown model is solved and becomes the run's current geometry; its tips
    !> join run%tips. started is .false. when no probe reaches the tensile strength.
    subroutine start_fracture(run, growth, initiation, step, load_step, record, started, error)
        !> The run: geometry, solution, solver, tips
        type(growth_state), intent(inout) :: run
        !> The growth options (increment, element_length, new_mu, new_sf)
        type(growth_options), intent(in) :: growth
        !> The initiation options
        type(initiation_options), intent(in) :: initiation
        !> The growth step the check belongs to, and the load step
        integer, intent(in) :: step, load_step
        !> The initiations so far; the new one is appended
        type(initiation_record), intent(inout) :: record
        !> A new fracture started
        logical, intent(out) :: started
        !> Set when the solve of the new geometry fails or its mesh is bad
        type(error_type), allocatable, intent(out) :: error
        type(initiation_candidate), allocatable :: found(:)
        type(initiation_candidate) :: first
        type(model_type) :: trial
        type(model_results) :: solved
        integer, allocatable :: created(:), origin(:)
        real(wp), allocatable :: xs(:), ys(:)
        real(wp) :: along(2)
        integer :: i, f, n
        character(len=:), allocatable :: name
        logical, allocatable :: usable(:)

        started = .false.
        if (.not. allocated(record%kind)) call empty_initiation_record(record)
        found = probe_candidates(run%work, run%current, growth, initiation, record)
        do i = 1, size(found)
            associate (c => found(i))
                c%efficiency = ieee_value(1.0_wp, ieee_quiet_nan)
                c%score = c%tension / initiation%tensile_strength
                if (c%kind == initiation_flaw) then
                    call assess_flaw(run%solver, run%work, run%current, growth, initiation, &
                                     c%flaw, c%point, c%tension, c%tension_direction, step, &
                                     record, c%along, c%score, c%efficiency, error)
                    if (allocated(error)) return
                end if
            end associate
        end do
        allocate (usable(size(found)), source=.true.)
        n = run%work%elements%n
        do
            i = first_over(found, usable)
            if (i == 0) then
                call keep_largest(found, step, record)
                return
            end if
            first = found(i)
            if (first%kind == initiation_tail) then
                ! The crack runs perpendicular to the maximum tension.
                along = [-first%tension_direction(2), first%tension_direction(1)]
                call tail_path(run%work, growth, first, along, xs, ys)
                name = allocated_name(run%work%fractures(first%parent))//'_tail'// &
                       itoa(1 + count(record%parent == first%parent .and. &
                                      record%kind == initiation_tail))
            else
                along = first%along
                call flaw_path(growth, initiation, first%point, along, xs, ys)
                name = 'flaw'//itoa(first%flaw)
            end if
            call add_fracture(run%work, first%kind, first%element, xs, ys, name, growth, trial)
            ! A new fracture that would cross another is not meshed: the next place is tried.
            call check_elements(trial%elements, trial%fractures, error)
            if (.not. allocated(error)) exit
            deallocate (error)
            usable(i) = .false.
        end do
        f = size(trial%fractures)
        created = [run%created, spread(step, 1, size(xs) - 1)]
        origin = [(i, i = 1, n), spread(0, 1, size(xs) - 1)]
        call solve_grown(run%solver, trial, [(i, i = 1, n)], solved, error, origin)
        if (allocated(error)) then
            error%message = 'growth step '//itoa(step)//', new fracture '''//name//''': '// &
                            error%message
            return
        end if
        call accept_trial(run%solver)
        call follow_growth(run%history, origin)
        call move_alloc(created, run%created)
        run%work = trial
        run%current = solved
        call add_tips(run, f)
        call append_initiation(record, initiation_row(first, step, load_step, f, &
                                                      atan2(along(2), along(1)) * 180.0_wp / pi))
        started = .true.
    end subroutine start_fracture

    !> The row of /growth/initiations of a candidate that started new fracture f in this step,
    !> in the direction `angle` [degree].
    function initiation_row(first, step, load_step, f, angle) result(row)
        type(initiation_candidate), intent(in) :: first
        integer, intent(in) :: step, load_step, f
        real(wp), intent(in) :: angle
        type(initiation_record) :: row

        call empty_initiation_record(row, 1)
        row%kind(1) = first%kind
        row%step(1) = step
        row%load_step(1) = load_step
        row%fracture_id(1) = f
        row%parent(1) = first%parent
        row%element(1) = first%element
        row%flaw(1) = first%flaw
        row%side(1) = first%side
        row%x(1) = first%point(1)
        row%y(1) = first%point(2)
        row%probe_x(1) = first%probe(1)
        row%probe_y(1) = first%probe(2)
        row%tension(1) = first%tension
        row%angle(1) = angle
        row%efficiency(1) = first%efficiency
    end function initiation_row

    !> Every probe of the current solution (both sides of both ends of every contact element
    !> that are not a fracture tip and have not started a tail, and every flaw point that has
    !> not started), with its tension. Probe points on an element are left out.
    function probe_candidates(work, current, growth, initiation, record) result(found)
        !> The current geometry, its elements' geometry computed
        type(model_type), intent(in) :: work
        !> Its solution (DDs and tips)
        type(model_results), intent(in) :: current
        !> The growth options (the tips' increments)
        type(growth_options), intent(in) :: growth
        !> The initiation options
        type(initiation_options), intent(in) :: initiation
        !> The initiations so far (allocated, maybe empty)
        type(initiation_record), intent(in) :: record
        type(initiation_candidate), allocatable :: found(:)
        type(initiation_candidate), allocatable :: all(:)
        type(field_result) :: field
        real(wp) :: normal(2), vertex(2)
        real(wp), allocatable :: px(:), py(:)
        integer :: k, end, side, m, p
        logical, allocatable :: keep(:)

        allocate (all(4 * work%elements%n + size(initiation%flaw_x)))
        m = 0
        associate (e => work%elements, d => initiation%probe_distance)
            do k = 1, e%n
                if (e%condition(k) /= condition_contact) cycle
                normal = [-e%sin_beta(k), e%cos_beta(k)]
                do end = tip_end_begin, tip_end_end
                    if (locate_tip(current%tips, k, end) > 0) cycle
                    if (end == tip_end_begin) then
                        vertex = [e%x_begin(k), e%y_begin(k)]
                    else
                        vertex = [e%x_end(k), e%y_end(k)]
                    end if
                    if (started_at(record, vertex, d) .or. &
                        near_tip(work, current%tips, growth, vertex, d)) cycle
                    do side = -1, 1, 2
                        m = m + 1
                        all(m) = initiation_candidate(kind=initiation_tail, &
                                                      parent=e%fracture_id(k), element=k, &
                                                      end=end, side=side, point=vertex, &
                                                      probe=vertex + side * d * normal)
                    end do
                end do
            end do
        end associate
        do p = 1, size(initiation%flaw_x)
            if (any(record%flaw == p)) cycle
            m = m + 1
            all(m) = initiation_candidate(kind=initiation_flaw, flaw=p, &
                                          point=[initiation%flaw_x(p), initiation%flaw_y(p)], &
                                          probe=[initiation%flaw_x(p), initiation%flaw_y(p)])
        end do
        found = all(:m)
        if (m == 0) return
        ! Contiguous copies of the probe points (components of found are strided)
        px = [(found(k)%probe(1), k = 1, m)]
        py = [(found(k)%probe(2), k = 1, m)]
        call evaluate_field(medium_of(work), [work%sxx, work%syy, work%sxy], &
                            current%elements%ds, current%elements%dn, px, py, field, &
                            work%stress_gradient)
        allocate (keep(m))
        keep = field%flag /= point_on_element
        do k = 1, m
            if (.not. keep(k)) cycle
            call principal_tension(effective(work, found(k)%probe, &
                                             [field%sxx(k), field%syy(k), field%sxy(k)]), &
                                   found(k)%tension, found(k)%tension_direction)
        end do
        found = pack(found, keep)
    end function probe_candidates

    !> The stress a probe feels: total stress plus the pore pressure p0 + dp_dy y on its
    !> normal components (tension positive), where the model has pore fluid.
    pure function effective(work, point, stress) result(felt)
        type(model_type), intent(in) :: work
        real(wp), intent(in) :: point(2), stress(3)
        real(wp) :: felt(3), pressure

        pressure = work%pore_fluid(1) + work%pore_fluid(2) * point(2)
        felt = stress + [pressure, pressure, 0.0_wp]
    end function effective

    !> The largest tension of a check that started nothing (ties within tie_tolerance of it
    !> in the order of the tie rule), its step and probe point, into the record; nothing
    !> without probes.
    pure subroutine keep_largest(found, step, record)
        type(initiation_candidate), intent(in) :: found(:)
        integer, intent(in) :: step
        type(initiation_record), intent(inout) :: record
        real(wp) :: tolerance
        integer :: k, i

        if (size(found) == 0) return
        tolerance = tie_tolerance * maxval(abs(found%tension))
        k = 1
        do i = 2, size(found)
            if (found(i)%tension > found(k)%tension + tolerance .or. &
                (found(i)%tension >= found(k)%tension - tolerance .and. &
                 ranks_before(found(i), found(k)))) k = i
        end do
        record%largest_step = step
        record%largest_tension = found(k)%tension
        record%largest_x = found(k)%probe(1)
        record%largest_y = found(k)%probe(2)
    end subroutine keep_largest

    !> The maximum principal stress (tension positive) of (sxx, syy, sxy) and its unit
    !> direction (the one of the two opposite ones with a non-negative x, or +y).
    pure subroutine principal_tension(stress, tension, direction)
        !> sxx, syy, sxy [stress unit]
        real(wp), intent(in) :: stress(3)
        !> The maximum principal stress [stress unit]
        real(wp), intent(out) :: tension
        !> Its unit direction
        real(wp), intent(out) :: direction(2)
        real(wp) :: phi

        tension = 0.5_wp * (stress(1) + stress(2)) + &
                  hypot(0.5_wp * (stress(1) - stress(2)), stress(3))
        phi = 0.5_wp * atan2(2.0_wp * stress(3), stress(1) - stress(2))
        direction = [cos(phi), sin(phi)]
    end subroutine principal_tension

    !> Index of the usable candidate that starts first: the largest score of 1 or more, ties
    !> by index (module header); 0 when none reaches 1.
    pure integer function first_over(found, usable) result(best)
        type(initiation_candidate), intent(in) :: found(:)
        logical, intent(in) :: usable(:)
        integer :: k

        best = 0
        do k = 1, size(found)
            if (.not. usable(k) .or. .not. (found(k)%score >= 1.0_wp)) cycle
            if (best == 0) then
                best = k
            else if (found(k)%score > found(best)%score + tie_tolerance) then
                best = k
            else if (found(k)%score >= found(best)%score - tie_tolerance) then
                if (ranks_before(found(k), found(best))) best = k
            end if
        end do
    end function first_over

    !> Tie order: tails before flaws, then fracture, element, end, side (tails) or flaw.
    pure logical function ranks_before(a, b)
        type(initiation_candidate), intent(in) :: a, b
        integer :: ka(5), kb(5), i

        ka = [a%kind, a%parent, a%element, a%end, a%side + a%flaw]
        kb = [b%kind, b%parent, b%element, b%end, b%side + b%flaw]
        ranks_before = .false.
        do i = 1, 5
            if (ka(i) /= kb(i)) then
                ranks_before = ka(i) < kb(i)
                return
            end if
        end do
    end function ranks_before

    !> Whether a tail started at this vertex already (on either side: the other side's
    !> probe now sits beside the tail's own end), or a fracture started there.
    pure logical function started_at(record, vertex, distance)
        type(initiation_record), intent(in) :: record
        real(wp), intent(in) :: vertex(2), distance

        started_at = any(hypot(record%x - vertex(1), record%y - vertex(2)) <= &
                         same_point * distance)
    end function started_at

    !> Whether a vertex is in a tip's zone: not further from it than its next growth
    !> increment, or than the probe distance. The tip's own growth decides there (its next kink
    !> reaches that far), and a probe there would sample the tip's singular field, which puts
    !> the start next to the tip however fine the mesh. A vertex on the zone's edge (the old
    !> tip one increment behind, up to round-off) is in it.
    pure logical function near_tip(work, tips, growth, vertex, distance)
        type(model_type), intent(in) :: work
        type(tip_set), intent(in) :: tips
        type(growth_options), intent(in) :: growth
        real(wp), intent(in) :: vertex(2), distance
        real(wp) :: increment, element_length
        integer :: k, pieces

        near_tip = .false.
        do k = 1, tips%n
            call increment_for(growth, 2.0_wp * work%elements%half_length(tips%element(k)), &
                               increment, pieces, element_length)
            if (hypot(tips%x(k) - vertex(1), tips%y(k) - vertex(2)) <= &
                max(increment, distance) + same_point * distance) near_tip = .true.
        end do
    end function near_tip

    !> A tail's vertices: from the parent's vertex, one increment (of the parent element) into
    !> the probe's side along `along`, in the increment's elements.
    pure subroutine tail_path(work, growth, c, along, xs, ys)
        type(model_type), intent(in) :: work
        type(growth_options), intent(in) :: growth
        type(initiation_candidate), intent(in) :: c
        real(wp), intent(inout) :: along(2)
        real(wp), allocatable, intent(out) :: xs(:), ys(:)
        real(wp) :: length, element_length, normal(2)
        integer :: pieces, j

        associate (e => work%elements)
            normal = c%side * [-e%sin_beta(c%element), e%cos_beta(c%element)]
            call increment_for(growth, 2.0_wp * e%half_length(c%element), length, pieces, &
                               element_length)
        end associate
        if (dot_product(along, normal) < 0.0_wp) along = -along
        xs = [(c%point(1) + along(1) * length * j / pieces, j = 0, pieces)]
        ys = [(c%point(2) + along(2) * length * j / pieces, j = 0, pieces)]
    end subroutine tail_path

    !> The new fracture's tips join the run's growing tips: both ends of a flaw, the free end
    !> of a tail (whose other end is on its parent), where the solve reports them as tips.
    subroutine add_tips(run, f)
        type(growth_state), intent(inout) :: run
        integer, intent(in) :: f
        integer :: end, k

        do end = tip_end_begin, tip_end_end
            if (end == tip_end_begin) then
                k = run%work%fractures(f)%first_element
            else
                k = run%work%fractures(f)%last_element
            end if
            if (locate_tip(run%current%tips, k, end) == 0) cycle
            run%tips = [run%tips, growing_tip(fracture=f, end=end)]
        end do
    end subroutine add_tips

    !> The name of a fracture ('' when it has none).
    pure function allocated_name(fracture) result(name)
        type(fracture_type), intent(in) :: fracture
        character(len=:), allocatable :: name

        name = ''
        if (allocated(fracture%name)) name = fracture%name
    end function allocated_name

end module ddc_growth_initiation
