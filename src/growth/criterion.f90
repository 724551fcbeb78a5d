!> The growth criterion of a model (&growth criterion;
!> docs/theory/growth.md#the-maximum-tangential-stress-criterion): the one place that
!> reads growth_options%criterion. Each procedure dispatches on it:
!>
!> - assess_tip: what a tip's K say, its kink angle (the predictor, which the clearance
!>   checks and links see) and K_eq (which the toughness and the choice of tips see);
!> - kink_angles: the angles the step's growing tips take, with the solves that needs;
!> - flaw_direction: the direction of a new fracture at a flaw point (&initiation).
!>
!> growth_criterion_mts: the maximum tangential stress (ddc_growth_mts), corrected for
!> local symmetry (ddc_growth_corrector). growth_criterion_work: the largest external work
!> per unit of new fracture (ddc_growth_trials); its predictor is straight ahead, every tip
!> that may grow is searched (searched_tip) and the search picks the most critical tip. A
!> criterion the growth code does not know is an internal error (the input reader accepts
!> only the names of growth_criterion_names).
!> Beside them the choice of the most critical tip by K_eq.
module ddc_growth_criterion
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_internal_error
    use ddc_text, only: itoa
    use ddc_model_types, only: model_type, growth_options, growth_criterion_mts, &
        growth_criterion_work, growth_tips_most_critical
    use ddc_model_results, only: model_results
    use ddc_growth_solver, only: growth_solver
    use ddc_growth_kinks, only: step_kinks
    use ddc_growth_mts, only: mts_angle, equivalent_k
    use ddc_growth_corrector, only: correct_kinks
    use ddc_growth_trials, only: search_kinks
    implicit none
    private

    public :: assess_tip, kink_angles, most_critical, flaw_direction, searched_tip, picks_by_k

    !> K_eq within this fraction of the largest count as tied for the most critical tip
    real(wp), parameter :: tie_tolerance = 1.0e-9_wp

contains

    !> The kink angle and K_eq of a tip with K_I, K_II under the model's criterion.
    subroutine assess_tip(options, k1, k2, theta, k_eq, error)
        !> The growth options (criterion)
        type(growth_options), intent(in) :: options
        !> Stress intensity factors of the tip [stress unit * length unit**0.5]
        real(wp), intent(in) :: k1, k2
        !> Kink angle, counter-clockwise from the tip's outward direction [rad]
        real(wp), intent(out) :: theta
        !> Equivalent mode-I factor [stress unit * length unit**0.5]
        real(wp), intent(out) :: k_eq
        !> Set (internal error) for a criterion this code does not know
        type(error_type), allocatable, intent(out) :: error

        theta = 0.0_wp
        k_eq = 0.0_wp
        select case (options%criterion)
        case (growth_criterion_mts)
            theta = mts_angle(k1, k2)
            k_eq = equivalent_k(k1, k2, theta)
        case (growth_criterion_work)
            ! K_eq at the MTS angle for the record; the search starts straight ahead.
            k_eq = equivalent_k(k1, k2, mts_angle(k1, k2))
        case default
            call unknown_criterion('assess_tip', options%criterion, error)
        end select
    end subroutine assess_tip

    !> The direction of a flaw's first crack under the model's criterion, from the maximum
    !> tension at the flaw point (the field without a crack there). MTS opens it against
    !> that tension: perpendicular to it. So does 'work': a short open crack draws the work
    !> pi a^2 (1 - nu^2) |t|^2 / E from the traction t across it, largest across the maximum
    !> tension.
    subroutine flaw_direction(options, tension_direction, along, error)
        !> The growth options (criterion)
        type(growth_options), intent(in) :: options
        !> Unit direction of the maximum tension at the flaw point
        real(wp), intent(in) :: tension_direction(2)
        !> Unit direction of the crack
        real(wp), intent(out) :: along(2)
        !> Set (internal error) for a criterion this code does not know
        type(error_type), allocatable, intent(out) :: error

        select case (options%criterion)
        case (growth_criterion_mts, growth_criterion_work)
            along = [-tension_direction(2), tension_direction(1)]
        case default
            along = tension_direction
            call unknown_criterion('flaw_direction', options%criterion, error)
        end select
    end subroutine flaw_direction

    !> The applied kink angles of the step's growing tips under the model's criterion; their
    !> reasons, solves and links, and the last trial solved (ddc_growth_kinks).
    subroutine kink_angles(solver, model, before, created, options, kinks, error)
        !> The solves of the run (the base: model)
        type(growth_solver), intent(inout) :: solver
        !> The model before growing (without observations)
        type(model_type), intent(in) :: model
        !> Its solution
        type(model_results), intent(in) :: before
        !> Growth step that created each element of model, shape (n)
        integer, intent(in) :: created(:)
        !> The growth options (criterion, and what it reads)
        type(growth_options), intent(in) :: options
        !> The step's kinks (each at its predictor angle on entry)
        type(step_kinks), intent(inout) :: kinks
        !> Set when a solve fails, or (internal error) for an unknown criterion
        type(error_type), allocatable, intent(out) :: error

        select case (options%criterion)
        case (growth_criterion_mts)
            call correct_kinks(solver, model, created, options, kinks, error)
        case (growth_criterion_work)
            call search_kinks(solver, model, before, created, options, kinks, error)
        case default
            call unknown_criterion('kink_angles', options%criterion, error)
        end select
    end subroutine kink_angles

    !> Whether a tip that may grow is searched in this step: under 'mts' when it is critical
    !> (K_eq >= toughness), under 'work' always (its trials decide).
    pure logical function searched_tip(options, k_eq)
        !> The growth options (criterion, toughness)
        type(growth_options), intent(in) :: options
        !> K_eq of the tip [stress unit * length unit**0.5]
        real(wp), intent(in) :: k_eq

        searched_tip = options%criterion == growth_criterion_work .or. &
            k_eq >= options%toughness
    end function searched_tip

    !> Whether tips = 'most_critical' picks its tip by K_eq before the kinks are turned (not
    !> under 'work', whose search picks it by efficiency).
    pure logical function picks_by_k(options)
        !> The growth options (criterion, tips)
        type(growth_options), intent(in) :: options

        picks_by_k = options%tips == growth_tips_most_critical .and. &
            options%criterion /= growth_criterion_work
    end function picks_by_k

    !> The error of a criterion code that `where` has no case for.
    subroutine unknown_criterion(where, criterion, error)
        character(len=*), intent(in) :: where
        integer, intent(in) :: criterion
        type(error_type), allocatable, intent(out) :: error

        call set_internal_error(error, where, 'growth criterion '//itoa(criterion)// &
                                ' has no case')
    end subroutine unknown_criterion

    !> The most critical of the eligible tips: the largest K_eq; among K_eq within
    !> tie_tolerance (relative) of the largest, the lowest index. 0 when none is eligible.
    pure integer function most_critical(k_eq, eligible)
        !> K_eq of every tip, shape (tips)
        real(wp), intent(in) :: k_eq(:)
        !> Which tips may be chosen, shape (tips)
        logical, intent(in) :: eligible(:)
        real(wp) :: largest
        integer :: i

        most_critical = 0
        if (.not. any(eligible)) return
        largest = maxval(k_eq, mask=eligible)
        do i = 1, size(k_eq)
            if (eligible(i) .and. k_eq(i) >= largest - tie_tolerance * abs(largest)) then
                most_critical = i
                return
            end if
        end do
    end function most_critical

end module ddc_growth_criterion
