!> The external work of a model's loads through its displacement discontinuities, and what the
!> work criterion compares it with (docs/theory/growth.md#the-work-criterion).
!>
!> Per unit thickness, with D = u^- - u^+ (Crouch & Starfield) and tension positive,
!> W_ext = - sum over elements of 2a (l_s D_s + l_n D_n), where the load (l_s, l_n) is the
!> traction the DDs must cancel: the resolved remote stress (with its gradient) plus, on a
!> contact element, its fluid pressure on the normal (pore fluid included), and minus the given
!> total traction on a traction row of a TWODD-style element. An open crack under tension
!> (l_n > 0, D_n < 0) or a crack slipping under its shear load gives W_ext > 0. Displacement
!> and prescribed-DD rows do no work at fixed load and do not count.
!>
!> Beside it how the trials of one growth step join the growth record (/growth/trials).
module ddc_growth_work
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, condition_contact, condition_traction, &
        condition_mixed_us_sn, condition_mixed_ss_un
    use ddc_model_results, only: growth_record
    use ddc_model_trial_records, only: trial_records
    use ddc_model_records, only: append_trial_rows
    use ddc_model_loads, only: resolve_remote_stress, total_pressure
    implicit none
    private

    public :: external_work, slip_work, append_trials

contains

    !> W_ext of a model with DDs ds, dn [stress unit * length unit] (per unit thickness).
    pure real(wp) function external_work(model, ds, dn) result(work)
        !> The model (geometry computed)
        type(model_type), intent(in) :: model
        !> Its DDs [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        real(wp) :: load_s(model%elements%n), load_n(model%elements%n)

        call work_loads(model, load_s, load_n)
        work = -sum(2.0_wp * model%elements%half_length * (load_s * ds + load_n * dn))
    end function external_work

    !> The shear part of W_ext on the elements of mask: the work of their slip
    !> [stress unit * length unit].
    pure real(wp) function slip_work(model, ds, mask) result(work)
        !> The model (geometry computed)
        type(model_type), intent(in) :: model
        !> Its shear DDs [length unit], shape (n)
        real(wp), intent(in) :: ds(:)
        !> The elements counted, shape (n)
        logical, intent(in) :: mask(:)
        real(wp) :: load_s(model%elements%n), load_n(model%elements%n)

        call work_loads(model, load_s, load_n)
        work = -sum(2.0_wp * model%elements%half_length * load_s * ds, mask=mask)
    end function slip_work

    !> The loads (l_s, l_n) that do work through each element's DDs [stress unit]: 0 on
    !> displacement and prescribed-DD rows.
    pure subroutine work_loads(model, load_s, load_n)
        type(model_type), intent(in) :: model
        real(wp), intent(out) :: load_s(:), load_n(:)

        call resolve_remote_stress(model%elements, model%sxx, model%syy, model%sxy, load_s, &
                                   load_n, model%stress_gradient)
        associate (e => model%elements)
            where (e%condition == condition_contact)
                load_n = load_n + total_pressure(e, model%pore_fluid)
            end where
            where (e%condition == condition_traction .or. e%condition == condition_mixed_ss_un)
                load_s = load_s - e%bc_s
            elsewhere (e%condition /= condition_contact)
                load_s = 0.0_wp
            end where
            where (e%condition == condition_traction .or. e%condition == condition_mixed_us_sn)
                load_n = load_n - e%bc_n
            elsewhere (e%condition /= condition_contact)
                load_n = 0.0_wp
            end where
        end associate
    end subroutine work_loads

    !> The step's trials in the growth record, each owned by its tip's record: the step's
    !> records are the last ones, one per tip that keep marks.
    subroutine append_trials(record, keep, trials)
        !> The growth record, the step's records appended
        type(growth_record), intent(inout) :: record
        !> Which of the step's tips have a record, shape (tips)
        logical, intent(in) :: keep(:)
        !> The step's trials (owner: the tip)
        type(trial_records), intent(in) :: trials
        type(trial_records) :: rows
        integer :: first, j

        first = size(record%step) - count(keep)
        rows = trials
        do j = 1, size(rows%owner)
            associate (tip => trials%owner(j))
                rows%owner(j) = merge(first + count(keep(1:tip)), 0, keep(tip))
            end associate
        end do
        call append_trial_rows(record%trials, rows)
    end subroutine append_trials

end module ddc_growth_work
