!> The pieces of the work criterion's angle searches (docs/theory/growth.md#the-work-criterion)
!> that a tip's kink search (ddc_growth_trials) and a flaw's first crack (ddc_growth_flaw_search)
!> share: a solved trial, the best candidate of a grid, the successive-parabola refinement's
!> vertex and bracket, and the state of a trial's new elements.
module ddc_growth_angle_search
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_model_types, only: model_type, condition_contact
    use ddc_model_results, only: model_results, state_open, state_slip, trial_stuck, &
        trial_slipping, trial_opening
    implicit none
    private

    public :: trial_point, best_candidate, parabola_vertex, narrow_bracket, new_elements_state
    public :: refine_tolerance, max_refinements

    !> The refinement stops when the next vertex lies within refine_tolerance of the best
    !> trial (the angle is then known to 0.5 degree) [rad]
    real(wp), parameter :: refine_tolerance = 0.25_wp * pi / 180.0_wp
    !> Largest number of refining solves per search
    integer, parameter :: max_refinements = 8

    !> One solved trial: its angle [rad], efficiency [stress unit * length unit] and whether
    !> its new elements open or slip (a candidate).
    type :: trial_point
        real(wp) :: angle = 0.0_wp, efficiency = 0.0_wp
        logical :: candidate = .false.
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
