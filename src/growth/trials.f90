!> The search of the work criterion (docs/theory/growth.md#the-work-criterion): every growing tip
!> tries kinks of its increment within -angle_range .. +angle_range about its direction, one
!> tip's kink at a time, each solved with contact by the growth solver (a bordered update of the
!> kept factors where the model is on the kept path). The search climbs every angle_step from
!> the kinked-crack estimate of the best angle (and from straight ahead under work_mode = 'any')
!> and tries every angle_step of the range only when that finds no candidate, or under
!> angle_search = 'grid'. A trial's efficiency is E = (W_ext(trial) - W_ext(before)) / increment
!> (ddc_growth_work); a trial whose new elements neither open nor slip (under work_mode =
!> 'opening': none of which opens), or whose path does not keep clear, is no candidate.
!> The best candidate is refined between its neighbours by successive parabolas through the best
!> three trials until the next vertex lies within half the resolution (0.25 degree) of the best.
!> A tip without a candidate is closed; one whose best E reaches the threshold grows at its
!> angle; with tips = 'most_critical' only the largest E / threshold grows (the others that
!> reach it wait).
module ddc_growth_trials
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_error, only: error_type
    use ddc_text, only: itoa
    use ddc_model_types, only: model_type, growth_options, growth_tips_most_critical, &
        work_mode_any, angle_search_seeded
    use ddc_model_results, only: model_results, growth_grew, growth_subcritical, &
        growth_closed, growth_waiting, trial_blocked, trial_slipping
    use ddc_growth_solver, only: growth_solver, solve_grown
    use ddc_growth_extension, only: tip_path, make_path, extend_model, element_split
    use ddc_growth_clearance, only: check_paths, path_clear, link_parts
    use ddc_growth_kinks, only: step_kinks, step_links
    use ddc_model_loads, only: work_threshold_of
    use ddc_growth_work, only: external_work
    use ddc_model_trial_records, only: add_trial
    use ddc_growth_angle_search, only: trial_point, best_candidate, parabola_vertex, &
        narrow_bracket, judge_trial, kink_estimate, refine_tolerance, max_refinements
    implicit none
    private

    public :: search_kinks

    !> One degree [rad]
    real(wp), parameter :: degree = pi / 180.0_wp
    !> Degrees per radian (the trials' angles are recorded in degrees)
    real(wp), parameter :: to_degrees = 180.0_wp / pi
    !> Trial angles closer than this are one trial [rad]
    real(wp), parameter :: same_angle = 1.0e-9_wp

contains

    !> Search every growing tip of the step (their reasons growth_grew on entry). On return each
    !> has its applied angle, efficiency, solves and reason (growth_grew, growth_subcritical,
    !> growth_closed or growth_waiting); kinks%trials holds every trial and kinks%current is
    !> false (the grown model is still to be built and solved).
    subroutine search_kinks(solver, model, before, created, options, kinks, error)
        !> The solves of the run (the base: model)
        type(growth_solver), intent(inout) :: solver
        !> The model before growing (without observations)
        type(model_type), intent(in) :: model
        !> Its solution
        type(model_results), intent(in) :: before
        !> Growth step that created each element of model, shape (n)
        integer, intent(in) :: created(:)
        !> The growth options (trial angles, threshold, tips, new_mu, new_sf)
        type(growth_options), intent(in) :: options
        !> The step's kinks: the growing tips in; angles, efficiencies, reasons and trials out
        type(step_kinks), intent(inout) :: kinks
        !> Set when a solve fails
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: w_before, threshold, ratio(size(kinks%tip))
        integer :: i, best

        w_before = external_work(model, before%elements%ds, before%elements%dn)
        threshold = work_threshold_of(options, model%youngs_modulus, model%poissons_ratio)
        kinks%current = .false.
        ratio = -huge(1.0_wp)
        do i = 1, size(kinks%tip)
            call search_tip(solver, model, before%elements%ds, created, options, w_before, &
                            kinks, i, error)
            if (allocated(error)) return
            associate (k => kinks%tip(i))
                if (k%reason == growth_closed) cycle
                k%reason = merge(growth_grew, growth_subcritical, k%efficiency >= threshold)
                if (k%reason == growth_grew) ratio(i) = k%efficiency / threshold
            end associate
        end do
        if (options%tips /= growth_tips_most_critical) return
        ! The lowest index among equal ratios (maxloc's first).
        best = maxloc(ratio, dim=1)
        do i = 1, size(kinks%tip)
            if (i /= best .and. kinks%tip(i)%reason == growth_grew) then
              kinks%tip(i)%reason = growth_waiting
            end if
        end do
    end subroutine search_kinks

    !> The trials of tip i (angle_search = 'seeded'): under work_mode = 'any', where the
    !> kinked-crack estimate of the best angle lies more than a step from straight ahead and
    !> the straight kink slips, a climb from straight ahead (slipping kinks do most work near
    !> the plane); then a climb from the estimate, which stops early where it heads for the
    !> first one's maximum from below it; a straight kink that opens is climbed from last,
    !> where it beats what the climbs found. The whole grid when no climb finds a candidate,
    !> and always under angle_search = 'grid'. A trial solved once is not solved again. The
    !> tip's angle, efficiency and slip share are the best candidate's (reason growth_closed
    !> without one).
    subroutine search_tip(solver, model, base_ds, created, options, w_before, kinks, i, error)
        type(growth_solver), intent(inout) :: solver
        type(model_type), intent(in) :: model
        !> The shear DDs of its solution [length unit], shape (n)
        real(wp), intent(in) :: base_ds(:)
        integer, intent(in) :: created(:)
        type(growth_options), intent(in) :: options
        !> W_ext of the model before growing [stress unit * length unit]
        real(wp), intent(in) :: w_before
        type(step_kinks), intent(inout) :: kinks
        integer, intent(in) :: i
        type(error_type), allocatable, intent(out) :: error
        type(trial_point), allocatable :: solved(:)
        integer, allocatable :: solved_state(:)
        type(trial_point) :: best, found, straight
        real(wp) :: range, step, seed
        integer :: state
        logical :: climbed

        range = options%angle_range * degree
        step = options%angle_step * degree
        allocate (solved(0), solved_state(0))
        kinks%tip(i)%solves = 0
        best%candidate = .false.
        if (options%angle_search == angle_search_seeded) then
            seed = kink_estimate(kinks%tip(i)%k1, kinks%tip(i)%k2, range)
            straight%candidate = .false.
            climbed = .false.
            if (options%work_mode == work_mode_any .and. abs(seed) > step) then
                call trial(0.0_wp, straight, error, state)
                if (allocated(error)) return
                if (state == trial_slipping) then
                    call climb(0.0_wp, best, error)
                    if (allocated(error)) return
                    climbed = .true.
                end if
            end if
            call climb(seed, found, error, best)
            if (allocated(error)) return
            call keep_better(found)
            ! A straight kink that opens and beats the estimate's maximum is climbed from too.
            if (straight%candidate .and. .not. climbed) then
                if (.not. best%candidate .or. straight%efficiency > best%efficiency) then
                    call climb(0.0_wp, found, error)
                    if (allocated(error)) return
                    call keep_better(found)
                end if
            end if
        end if
        if (.not. best%candidate) then
            call search_grid(best, error)
            if (allocated(error)) return
        end if
        if (.not. best%candidate) then
            kinks%tip(i)%reason = growth_closed
            kinks%tip(i)%efficiency = ieee_value(1.0_wp, ieee_quiet_nan)
            kinks%tip(i)%slip_share = ieee_value(1.0_wp, ieee_quiet_nan)
            return
        end if
        kinks%tip(i)%theta = best%angle
        kinks%tip(i)%efficiency = best%efficiency
        kinks%tip(i)%slip_share = best%slip_share

    contains

        !> best becomes the found candidate where that is better.
        subroutine keep_better(found)
            type(trial_point), intent(in) :: found

            if (.not. found%candidate) return
            if (.not. best%candidate) then
                best = found
            else if (found%efficiency > best%efficiency) then
                best = found
            end if
        end subroutine keep_better

        !> From the seed and its neighbours a step either way, step on towards the best
        !> candidate until it lies between two trials (or at the range), then refine it;
        !> best%candidate is false when the three trials about the seed have none. Given a
        !> rival (an earlier climb's candidate), the climb stops without a candidate when the
        !> three trials about the seed are all below the rival and their best points the
        !> walk towards it: it would end in the rival's maximum.
        subroutine climb(seed, best, error, rival)
            real(wp), intent(in) :: seed
            type(trial_point), intent(out) :: best
            type(error_type), allocatable, intent(out) :: error
            type(trial_point), intent(in), optional :: rival
            type(trial_point) :: l, m, r
            integer :: b

            best%candidate = .false.
            call trial(seed, m, error)
            if (allocated(error)) return
            call trial(max(seed - step, -range), l, error)
            if (allocated(error)) return
            call trial(min(seed + step, range), r, error)
            if (allocated(error)) return
            if (present(rival)) then
                if (heads_below(l, m, r, rival)) return
            end if
            do
                b = best_candidate([l, m, r])
                if (b == 0) return
                if (b == 1 .and. l%angle > -range) then
                    r = m
                    m = l
                    call trial(max(m%angle - step, -range), l, error)
                else if (b == 3 .and. r%angle < range) then
                    l = m
                    m = r
                    call trial(min(m%angle + step, range), r, error)
                else
                    exit
                end if
                if (allocated(error)) return
            end do
            select case (b)
            case (1)
                best = l
            case (2)
                best = m
                if (l%candidate .and. r%candidate) call refine(l, m, r, best, error)
            case default
                best = r
            end select
        end subroutine climb

        !> Whether the walk from l, m, r heads towards the rival's angle from a best trial below
        !> the rival's efficiency (l or r the best candidate, the rival a candidate).
        pure logical function heads_below(l, m, r, rival)
            type(trial_point), intent(in) :: l, m, r, rival

            heads_below = .false.
            if (.not. rival%candidate) return
            select case (best_candidate([l, m, r]))
            case (1)
                heads_below = l%efficiency < rival%efficiency .and. rival%angle < m%angle
            case (3)
                heads_below = r%efficiency < rival%efficiency .and. rival%angle > m%angle
            case default
                ! m is the best, or none is a candidate: the climb stays or ends here
                heads_below = .false.
            end select
        end function heads_below

        !> Every trial angle of the range, then the refinement of the best candidate between
        !> its neighbours.
        subroutine search_grid(best, error)
            type(trial_point), intent(out) :: best
            type(error_type), allocatable, intent(out) :: error
            real(wp), allocatable :: angles(:)
            type(trial_point), allocatable :: grid(:)
            integer :: j, b

            best%candidate = .false.
            call trial_angles(range, step, angles)
            allocate (grid(size(angles)))
            do j = 1, size(angles)
                call trial(angles(j), grid(j), error)
                if (allocated(error)) return
            end do
            b = best_candidate(grid)
            if (b == 0) return
            best = grid(b)
            if (b > 1 .and. b < size(grid)) then
                if (grid(b - 1)%candidate .and. grid(b + 1)%candidate) then
                    call refine(grid(b - 1), grid(b), grid(b + 1), best, error)
                end if
            end if
        end subroutine search_grid

        !> Successive parabolas through the best trial m and its neighbours l < m < r
        !> (each a candidate): the vertex is solved when it lies more than refine_tolerance
        !> from m, and the three best around the maximum are kept; best is the best
        !> candidate found.
        subroutine refine(l0, m0, r0, best, error)
            type(trial_point), intent(in) :: l0, m0, r0
            type(trial_point), intent(inout) :: best
            type(error_type), allocatable, intent(out) :: error
            type(trial_point) :: l, m, r, v
            real(wp) :: vertex
            integer :: n
            logical :: found

            l = l0
            m = m0
            r = r0
            do n = 1, max_refinements
                call parabola_vertex(l, m, r, vertex, found)
                if (.not. found .or. abs(vertex - m%angle) <= refine_tolerance) exit
                call trial(vertex, v, error)
                if (allocated(error)) return
                if (.not. v%candidate) exit
                call narrow_bracket(l, m, r, v)
            end do
            best = m
        end subroutine refine

        !> The trial at angle theta: the one solved already, else solved now; and the state
        !> of its new elements.
        subroutine trial(theta, point, error, state)
            real(wp), intent(in) :: theta
            type(trial_point), intent(out) :: point
            type(error_type), allocatable, intent(out) :: error
            integer, intent(out), optional :: state
            integer :: j, found_state

            do j = 1, size(solved)
                if (abs(solved(j)%angle - theta) <= same_angle) then
                    point = solved(j)
                    if (present(state)) state = solved_state(j)
                    return
                end if
            end do
            call try_angle(theta, point, found_state, error)
            if (allocated(error)) return
            solved = [solved, point]
            solved_state = [solved_state, found_state]
            if (present(state)) state = found_state
        end subroutine trial

        !> Solve the tip's kink at angle theta (the step's links held) and record the trial.
        subroutine try_angle(theta, point, state, error)
            real(wp), intent(in) :: theta
            type(trial_point), intent(out) :: point
            integer, intent(out) :: state
            type(error_type), allocatable, intent(out) :: error
            type(tip_path) :: path(1)
            type(tip_path), allocatable :: link_paths(:)
            type(element_split), allocatable :: splits(:)
            integer :: problem(1)

            point%angle = theta
            state = trial_blocked
            associate (k => kinks%tip(i))
                path(1) = make_path(model, k%fracture, k%end, theta, k%length, k%pieces)
                call check_paths(model, path, [.true.], problem, fixed=kinks%fixed)
                if (problem(1) /= path_clear) then
                    point%efficiency = ieee_value(1.0_wp, ieee_quiet_nan)
                    call add_trial(kinks%trials, kinks%step, k%tip, theta * to_degrees, &
                                   point%efficiency, trial_blocked)
                    return
                end if
                call link_parts(step_links(kinks), link_paths, splits)
                call extend_model(model, created, [path, link_paths], kinks%step, options, &
                                  kinks%trial, kinks%trial_created, kinks%moved_to, splits, &
                                  kinks%origin)
                call solve_grown(solver, kinks%trial, kinks%moved_to, kinks%solved, error, &
                                 kinks%origin)
                k%solves = k%solves + 1
                if (allocated(error)) then
                    error%message = 'growth step '//itoa(kinks%step)//', work trial '// &
                                    itoa(k%solves)//': '//error%message
                    return
                end if
                call judge_trial(kinks%trial, kinks%solved, kinks%origin, base_ds, w_before, &
                                 k%length, options%work_mode, point, state)
                call add_trial(kinks%trials, kinks%step, k%tip, theta * to_degrees, &
                               point%efficiency, state)
            end associate
        end subroutine try_angle

    end subroutine search_tip

    !> The trial angles [rad]: 0, +-step, +-2 step, ... up to +-range, and +-range itself
    !> where it is no multiple of the step; ascending.
    pure subroutine trial_angles(range, step, angles)
        real(wp), intent(in) :: range, step
        real(wp), allocatable, intent(out) :: angles(:)
        integer :: n, j, m

        n = floor(range / step * (1.0_wp + 1.0e-9_wp))
        m = merge(1, 0, real(n, wp) * step < range * (1.0_wp - 1.0e-9_wp))
        allocate (angles(2 * (n + m) + 1))
        angles(m + 1:m + 2 * n + 1) = [(real(j, wp) * step, j = -n, n)]
        if (m == 1) then
            angles(1) = -range
            angles(size(angles)) = range
        end if
    end subroutine trial_angles

end module ddc_growth_trials
