!> A flaw's first crack under the work criterion
!> (docs/fracture-growth.md#new-fractures-inside-the-rock): a crack of flaw_length centred on
!> the flaw point is tried in every orientation of a half-turn (-90 .. 90 degrees from the x
!> axis, every angle_step; a crack and its reverse are one), each solved with contact by the
!> growth solver (a bordered update of the kept factors), with its efficiency
!> E = (W_ext(trial) - W_ext(before)) / flaw_length (ddc_growth_work). A trial whose new
!> elements neither open nor slip (under work_mode = 'opening': none of which opens), or
!> that would cross an element, is no candidate. The best
!> candidate is refined as a tip's kink is (ddc_growth_angle_search), the grid wrapping round
!> at +-90 degrees. Every trial goes to the run's initiation record.
module ddc_growth_flaw_search
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_error, only: error_type
    use ddc_text, only: itoa
    use ddc_model_types, only: model_type, growth_options, initiation_options
    use ddc_model_results, only: model_results, trial_blocked
    use ddc_model_initiations, only: initiation_record, initiation_flaw
    use ddc_model_trial_records, only: add_trial
    use ddc_mesh_checks, only: check_elements
    use ddc_growth_solver, only: growth_solver, solve_grown
    use ddc_growth_work, only: external_work
    use ddc_growth_new_fracture, only: flaw_path, add_fracture
    use ddc_growth_angle_search, only: trial_point, best_candidate, parabola_vertex, &
        narrow_bracket, judge_trial, refine_tolerance, max_refinements
    implicit none
    private

    public :: search_flaw

    real(wp), parameter :: degree = pi / 180.0_wp

contains

    !> The trials of flaw `flaw` at `point` on the current geometry; its best orientation and
    !> efficiency (NaN, and candidate .false., when no trial opens or slips).
    subroutine search_flaw(solver, work, before, growth, initiation, flaw, point, step, &
                           record, along, efficiency, candidate, error)
        !> The solves of the run (the base: work)
        type(growth_solver), intent(inout) :: solver
        !> The current geometry (without observations)
        type(model_type), intent(in) :: work
        !> Its solution
        type(model_results), intent(in) :: before
        !> The growth options (angle_step, new-element values, increment)
        type(growth_options), intent(in) :: growth
        !> The initiation options (flaw_length)
        type(initiation_options), intent(in) :: initiation
        !> The flaw's index, and its point [length unit]
        integer, intent(in) :: flaw
        real(wp), intent(in) :: point(2)
        !> The growth step of the check
        integer, intent(in) :: step
        !> The run's initiations: the trials are appended
        type(initiation_record), intent(inout) :: record
        !> Unit direction of the best crack
        real(wp), intent(out) :: along(2)
        !> Its efficiency [stress unit * length unit]
        real(wp), intent(out) :: efficiency
        !> Whether any trial opened or slipped
        logical, intent(out) :: candidate
        !> Set when a solve fails
        type(error_type), allocatable, intent(out) :: error
        type(trial_point), allocatable :: grid(:)
        type(trial_point) :: l, m, r, v
        real(wp) :: w_before, step_angle, vertex
        integer :: n, j, b, solves
        logical :: found

        w_before = external_work(work, before%elements%ds, before%elements%dn)
        step_angle = growth%angle_step * degree
        n = ceiling(pi / step_angle * (1.0_wp - 1.0e-9_wp))
        allocate (grid(n))
        solves = 0
        do j = 1, n
            call try_orientation(-0.5_wp * pi + (j - 1) * step_angle, grid(j), error)
            if (allocated(error)) return
        end do
        along = [1.0_wp, 0.0_wp]
        efficiency = ieee_value(1.0_wp, ieee_quiet_nan)
        b = best_candidate(grid)
        candidate = b > 0
        if (.not. candidate) return
        ! The neighbours across +-90 degrees are the same cracks turned by half a turn.
        m = grid(b)
        l = grid(modulo(b - 2, n) + 1)
        r = grid(modulo(b, n) + 1)
        if (b == 1) l%angle = l%angle - pi
        if (b == n) r%angle = r%angle + pi
        if (l%candidate .and. r%candidate .and. n > 2) then
            do j = 1, max_refinements
                call parabola_vertex(l, m, r, vertex, found)
                if (.not. found .or. abs(vertex - m%angle) <= refine_tolerance) exit
                call try_orientation(vertex, v, error)
                if (allocated(error)) return
                if (.not. v%candidate) exit
                call narrow_bracket(l, m, r, v)
            end do
        end if
        along = [cos(m%angle), sin(m%angle)]
        efficiency = m%efficiency

    contains

        !> Solve the flaw's crack at orientation theta [rad] and record the trial.
        subroutine try_orientation(theta, point_tried, error)
            real(wp), intent(in) :: theta
            type(trial_point), intent(out) :: point_tried
            type(error_type), allocatable, intent(out) :: error
            type(error_type), allocatable :: crossing
            type(model_type) :: trial
            type(model_results) :: solved
            real(wp), allocatable :: xs(:), ys(:)
            integer, allocatable :: origin(:)
            integer :: i, state

            point_tried%angle = theta
            point_tried%efficiency = ieee_value(1.0_wp, ieee_quiet_nan)
            call flaw_path(growth, initiation, point, [cos(theta), sin(theta)], xs, ys)
            call add_fracture(work, initiation_flaw, 0, xs, ys, 'flaw'//itoa(flaw), growth, &
                              trial)
            call check_elements(trial%elements, trial%fractures, crossing)
            if (allocated(crossing)) then
                call add_trial(record%trials, step, flaw, orientation_degrees(theta), &
                               point_tried%efficiency, trial_blocked)
                return
            end if
            origin = [(i, i = 1, work%elements%n), spread(0, 1, size(xs) - 1)]
            call solve_grown(solver, trial, [(i, i = 1, work%elements%n)], solved, error, &
                             origin)
            solves = solves + 1
            if (allocated(error)) then
                error%message = 'growth step '//itoa(step)//', flaw '//itoa(flaw)// &
                                ' trial '//itoa(solves)//': '//error%message
                return
            end if
            call judge_trial(trial, solved, origin, before%elements%ds, w_before, &
                             hypot(xs(size(xs)) - xs(1), ys(size(ys)) - ys(1)), &
                             growth%work_mode, point_tried, state)
            call add_trial(record%trials, step, flaw, orientation_degrees(theta), &
                           point_tried%efficiency, state)
        end subroutine try_orientation

    end subroutine search_flaw

    !> An orientation [rad] as the crack's angle from the x axis in [-90, 90) [degree].
    pure real(wp) function orientation_degrees(theta)
        real(wp), intent(in) :: theta

        orientation_degrees = modulo(theta / degree + 90.0_wp, 180.0_wp) - 90.0_wp
    end function orientation_degrees

end module ddc_growth_flaw_search
