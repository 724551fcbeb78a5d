!> The growth criterion of a model (&growth criterion;
!> docs/theory/growth.md#the-maximum-tangential-stress-criterion): the one place that
!> reads growth_options%criterion. Each procedure dispatches on it:
!>
!> - assess_tip: what a tip's K say, its kink angle (the predictor, which the clearance
!>   checks and links see) and K_eq (which the toughness and the choice of tips see);
!> - kink_angles: the angles the step's growing tips take, with the solves that needs;
!> - assess_flaw: the direction of a new fracture at a flaw point (&initiation), and whether
!>   it starts.
!>
!> growth_criterion_mts: the maximum tangential stress (ddc_growth_mts), corrected for
!> local symmetry (ddc_growth_corrector). growth_criterion_work: the largest external work
!> per unit of new fracture (ddc_growth_trials); its predictor is straight ahead, every tip
!> that may grow is searched (searched_tip) and the search picks the most critical tip. A
!> criterion the growth code does not know is an internal error (the input reader accepts
!> only the names of growth_criterion_names).
!> Beside them the choice of the most critical tip by K_eq.
module ddc_growth_criterion
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_internal_error
    use ddc_text, only: itoa
    use ddc_model_types, only: model_type, growth_options, initiation_options, &
        growth_criterion_mts, growth_criterion_work, growth_tips_most_critical
    use ddc_model_initiations, only: initiation_record
    use ddc_model_loads, only: work_threshold_of
    use ddc_model_results, only: model_results
    use ddc_growth_solver, only: growth_solver
    use ddc_growth_kinks, only: step_kinks
    use ddc_growth_mts, only: mts_angle, equivalent_k
    use ddc_growth_corrector, only: correct_kinks
    use ddc_growth_trials, only: search_kinks
    use ddc_growth_flaw_search, only: search_flaw
    implicit none
    private

    public :: assess_tip, kink_angles, most_critical, assess_flaw, searched_tip, picks_by_k

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
            ! K_eq at the MTS angle for the record; no predictor (the search starts from the
            ! kinked-crack estimate, ddc_growth_trials).
            k_eq = equivalent_k(k1, k2, mts_angle(k1, k2))
        case default
            call unknown_criterion('assess_tip', options%criterion, error)
        end select
    end subroutine assess_tip

    !> How a flaw's first crack starts under the model's criterion: its direction, and its
    !> score (1 or more starts it; docs/fracture-growth.md#new-fractures-inside-the-rock). MTS
    !> opens it against the maximum tension at the flaw point (the field without a crack
    !> there), perpendicular to it, when that tension reaches the tensile strength: score
    !> tension / tensile_strength. 'work' searches its orientations (ddc_growth_flaw_search):
    !> score efficiency / work threshold of the best one that opens or slips.
    subroutine assess_flaw(solver, work, before, options, initiation, flaw, point, tension, &
                           tension_direction, step, record, along, score, efficiency, error)
        !> The solves of the run (the base: work)
        type(growth_solver), intent(inout) :: solver
        !> The current geometry (without observations), and its solution
        type(model_type), intent(in) :: work
        type(model_results), intent(in) :: before
        !> The growth options (criterion, and what it reads)
        type(growth_options), intent(in) :: options
        !> The initiation options
        type(initiation_options), intent(in) :: initiation
        !> The flaw's index and point [length unit]
        integer, intent(in) :: flaw
        real(wp), intent(in) :: point(2)
        !> The maximum tension at the point [stress unit], and its unit direction
        real(wp), intent(in) :: tension, tension_direction(2)
        !> The growth step of the check
        integer, intent(in) :: step
        !> The run's initiations ('work' appends the flaw's trials)
        type(initiation_record), intent(inout) :: record
        !> Unit direction of the crack
        real(wp), intent(out) :: along(2)
        !> How far past its threshold the flaw is (-huge when nothing can start)
        real(wp), intent(out) :: score
        !> Its efficiency under 'work' (NaN otherwise) [stress unit * length unit]
        real(wp), intent(out) :: efficiency
        !> Set when a trial's solve fails, or (internal error) for an unknown criterion
        type(error_type), allocatable, intent(out) :: error
        logical :: candidate

        along = [-tension_direction(2), tension_direction(1)]
        score = -huge(1.0_wp)
        efficiency = ieee_value(1.0_wp, ieee_quiet_nan)
        select case (options%criterion)
        case (growth_criterion_mts)
            score = tension / initiation%tensile_strength
        case (growth_criterion_work)
            call search_flaw(solver, work, before, options, initiation, flaw, point, step, &
                             record, along, efficiency, candidate, error)
            if (candidate) score = efficiency / work_threshold_of(options, &
                work%youngs_modulus, work%poissons_ratio)
        case default
            call unknown_criterion('assess_flaw', options%criterion, error)
        end select
    end subroutine assess_flaw

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
