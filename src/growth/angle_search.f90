!> The pieces of the work criterion's angle searches (docs/theory/growth.md#the-work-criterion)
!> that a tip's kink search (ddc_growth_trials) and a flaw's first crack (ddc_growth_flaw_search)
!> share: a solved trial and how it is judged (efficiency, state, candidate under the work
!> mode, the share of its work from slip of frictional faces), the best candidate of a
!> grid, the successive-parabola refinement's vertex and bracket, and the kinked-crack
!> estimate of a tip's best angle that seeds its search.
module ddc_growth_angle_search
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_model_types, only: model_type, condition_contact, work_mode_opening
    use ddc_model_results, only: model_results, state_open, state_slip, trial_stuck, &
        trial_slipping, trial_opening
    use ddc_growth_work, only: external_work, slip_work
    implicit none
    private

    public :: trial_point, best_candidate, parabola_vertex, narrow_bracket
    public :: judge_trial, kink_estimate, refine_tolerance, max_refinements

    !> The refinement stops when the next vertex lies within refine_tolerance of the best
    !> trial (the angle is then known to 0.5 degree) [rad]
    real(wp), parameter :: refine_tolerance = 0.25_wp * pi / 180.0_wp
    !> Largest number of refining solves per search
    integer, parameter :: max_refinements = 8

    !> The kinked-crack estimate's grid spacing [rad]
    real(wp), parameter :: estimate_spacing = 0.01_wp * pi / 180.0_wp

    !> One solved trial: its angle [rad], efficiency [stress unit * length unit], whether it
    !> is a candidate (a new element opens, or under work_mode = 'any' slips) and the share of
    !> its work change done through slip of frictional faces [-].
    type :: trial_point
        real(wp) :: angle = 0.0_wp, efficiency = 0.0_wp
        logical :: candidate = .false.
        real(wp) :: slip_share = 0.0_wp
    end type trial_point

contains

    !> The first candidate of largest efficiency (0 when there is none).
    pure integer function best_candidate(points) result(b)
        !> The trials
        type(trial_point), intent(in) :: points(:)
        integer :: j

        b = 0
        do j = 1, size(points)
            if (.not. points(j)%candidate) cycle
            if (b == 0) then
                b = j
            else if (points(j)%efficiency > points(b)%efficiency) then
                b = j
            end if
        end do
    end function best_candidate

    !> The vertex of the parabola through the trials l < m < r, clamped to [l, r]; found is
    !> .false. when the three lie on a line (no vertex).
    pure subroutine parabola_vertex(l, m, r, vertex, found)
        !> The bracket: m the best, l and r its neighbours
        type(trial_point), intent(in) :: l, m, r
        !> The vertex's angle [rad]
        real(wp), intent(out) :: vertex
        !> Whether there is one
        logical, intent(out) :: found
        real(wp) :: denominator

        vertex = m%angle
        denominator = (m%angle - l%angle) * (m%efficiency - r%efficiency) - &
                      (m%angle - r%angle) * (m%efficiency - l%efficiency)
        found = abs(denominator) > 0.0_wp
        if (.not. found) return
        vertex = m%angle - 0.5_wp * ((m%angle - l%angle)**2 * (m%efficiency - r%efficiency) - &
                                     (m%angle - r%angle)**2 * (m%efficiency - l%efficiency)) / &
                 denominator
        vertex = max(l%angle, min(r%angle, vertex))
    end subroutine parabola_vertex

    !> Keep the three best trials around the maximum once the vertex v is solved: v becomes
    !> the middle when it beats m, else the bound on its side.
    pure subroutine narrow_bracket(l, m, r, v)
        !> The bracket l < m < r, m the best
        type(trial_point), intent(inout) :: l, m, r
        !> The solved vertex (a candidate)
        type(trial_point), intent(in) :: v

        if (v%efficiency > m%efficiency) then
            if (v%angle < m%angle) then
                r = m
            else
                l = m
            end if
            m = v
        else if (v%angle < m%angle) then
            l = v
        else
            r = v
        end if
    end subroutine narrow_bracket

    !> Judge a solved trial of length `length` grown from a base of work w_before: its
    !> efficiency, candidate and slip share (point; its angle is the caller's) and state. The
    !> slip share is the part of the work change done through the slip of frictional faces
    !> that slip in the trial (new ones, and old ones from their slip in the base).
    pure subroutine judge_trial(grown, solved, origin, base_ds, w_before, length, work_mode, &
                                point, state)
        !> The trial's model and its solution
        type(model_type), intent(in) :: grown
        type(model_results), intent(in) :: solved
        !> The element of the base each element comes from, 0 for a new one, shape (n)
        integer, intent(in) :: origin(:)
        !> The base's shear DDs [length unit], shape (base n)
        real(wp), intent(in) :: base_ds(:)
        !> W_ext of the base [stress unit * length unit], and the new fracture's length
        real(wp), intent(in) :: w_before, length
        !> work_mode_any or work_mode_opening
        integer, intent(in) :: work_mode
        !> The trial (its efficiency, candidate and slip_share are set)
        type(trial_point), intent(inout) :: point
        !> trial_stuck, trial_slipping or trial_opening
        integer, intent(out) :: state
        logical :: contact(size(origin)), rubbing(size(origin))
        real(wp) :: change, slip_change(size(origin))
        integer :: k

        change = external_work(grown, solved%elements%ds, solved%elements%dn) - w_before
        point%efficiency = change / length
        state = new_elements_state(grown, solved, origin)
        point%candidate = state == trial_opening .or. &
            (state == trial_slipping .and. work_mode /= work_mode_opening)
        contact = grown%elements%condition == condition_contact
        associate (s => solved%elements)
            point%slip_share = 0.0_wp
            if (change > 0.0_wp) then
                rubbing = contact .and. s%state == state_slip .and. grown%elements%mu > 0.0_wp
                ! The slip each element adds to its base element's (all of a new one's)
                slip_change = s%ds
                do k = 1, size(origin)
                    if (origin(k) > 0) slip_change(k) = s%ds(k) - base_ds(origin(k))
                end do
                point%slip_share = slip_work(grown, slip_change, rubbing) / change
            end if
        end associate
    end subroutine judge_trial

    !> The kinked-crack estimate of a tip's best angle [rad] within +-range: the largest
    !> energy release rate of an infinitesimal kink whose K are the parent tip's stress
    !> factors at the kink angle (Nuismer 1975), a closed kink releasing only its shear:
    !> the maximum of max(k_tt, 0)^2 + k_rt^2 on a 0.01 degree grid (the first of equal
    !> ones), with max(K_I, 0) as the MTS angle takes it (faces pressed into each other
    !> open nothing); 0 when both K vanish.
    pure real(wp) function kink_estimate(k1, k2, range) result(theta)
        !> The tip's K_I and K_II [stress unit * length unit**0.5]
        real(wp), intent(in) :: k1, k2
        !> The largest kink angle either way [rad]
        real(wp), intent(in) :: range
        real(wp) :: t, c, s, k_tt, k_rt, g, best, k1_open
        integer :: j, n

        theta = 0.0_wp
        best = 0.0_wp
        k1_open = max(k1, 0.0_wp)
        n = floor(range / estimate_spacing)
        do j = -n - 1, n + 1
            t = max(-range, min(range, j * estimate_spacing))
            c = cos(0.5_wp * t)
            s = sin(t)
            k_tt = c * (k1_open * c**2 - 1.5_wp * k2 * s)
            k_rt = 0.5_wp * c * (k1_open * s + k2 * (3.0_wp * cos(t) - 1.0_wp))
            g = max(k_tt, 0.0_wp)**2 + k_rt**2
            if (g > best) then
                best = g
                theta = t
            end if
        end do
    end function kink_estimate

    !> trial_opening when a new element opens, else trial_slipping when one slips, else
    !> trial_stuck (a TWODD-style element opens with D_n < 0 and slips with D_s /= 0).
    pure integer function new_elements_state(grown, solved, origin) result(state)
        !> The trial's model
        type(model_type), intent(in) :: grown
        !> Its solution
        type(model_results), intent(in) :: solved
        !> The element of the base each element comes from, 0 for a new one, shape (n)
        integer, intent(in) :: origin(:)
        logical :: fresh(size(origin)), contact(size(origin))

        fresh = origin == 0
        contact = grown%elements%condition == condition_contact
        associate (s => solved%elements)
            if (any(fresh .and. ((contact .and. s%state == state_open) .or. &
                                 (.not. contact .and. s%dn < 0.0_wp)))) then
                state = trial_opening
            else if (any(fresh .and. ((contact .and. s%state == state_slip) .or. &
                                      (.not. contact .and. s%ds /= 0.0_wp)))) then
                state = trial_slipping
            else
                state = trial_stuck
            end if
        end associate
    end function new_elements_state

end module ddc_growth_angle_search
