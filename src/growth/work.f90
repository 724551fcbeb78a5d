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
!> Beside it the trials of one growth step (trial_table) and how they join the growth record
!> (/growth/trials).
module ddc_growth_work
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, condition_contact, condition_traction, &
        condition_mixed_us_sn, condition_mixed_ss_un
    use ddc_constants, only: pi
    use ddc_model_results, only: growth_record
    use ddc_model_loads, only: resolve_remote_stress, total_pressure
    implicit none
    private

    public :: external_work, slip_work, trial_table, add_trial, append_table, append_trials

    !> The trials of the work criterion (k trials): the tip (fracture, end), its angle
    !> [rad], efficiency [stress unit * length unit] (NaN when blocked) and state, shape (k).
    type :: trial_table
        integer, allocatable :: fracture(:), end(:), state(:)
        real(wp), allocatable :: angle(:), efficiency(:)
    end type trial_table

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

    !> Append one trial to a table (allocated on first use).
    pure subroutine add_trial(table, fracture, end, angle, efficiency, state)
        !> The table
        type(trial_table), intent(inout) :: table
        !> The tip: fracture (1-based) and end
        integer, intent(in) :: fracture, end
        !> Trial angle [rad] and efficiency [stress unit * length unit]
        real(wp), intent(in) :: angle, efficiency
        !> trial_stuck ... trial_blocked
        integer, intent(in) :: state

        if (.not. allocated(table%fracture)) then
            allocate (table%fracture(0), table%end(0), table%state(0), table%angle(0), &
                      table%efficiency(0))
        end if
        table%fracture = [table%fracture, fracture]
        table%end = [table%end, end]
        table%state = [table%state, state]
        table%angle = [table%angle, angle]
        table%efficiency = [table%efficiency, efficiency]
    end subroutine add_trial

    !> Append a search's trials to the step's (a step may search more than once: with
    !> tips = 'most_critical' the next waiting tip is tried when the first did not grow).
    pure subroutine append_table(table, found)
        !> The step's trials
        type(trial_table), intent(inout) :: table
        !> One search's trials
        type(trial_table), intent(in) :: found
        integer :: j

        if (.not. allocated(found%fracture)) return
        do j = 1, size(found%fracture)
            call add_trial(table, found%fracture(j), found%end(j), found%angle(j), &
                           found%efficiency(j), found%state(j))
        end do
    end subroutine append_table

    !> The step's trials in the growth record, each with its tip's record: the tips' records
    !> of the step are the record's last count(keep), in the order of the tips.
    pure subroutine append_trials(record, step, fracture, end, keep, trials)
        !> The run's growth record, the step's records appended already
        type(growth_record), intent(inout) :: record
        !> The growth step
        integer, intent(in) :: step
        !> Fracture and end of every tip that may grow, and which have a record in this step,
        !> shape (tips)
        integer, intent(in) :: fracture(:), end(:)
        logical, intent(in) :: keep(:)
        !> The step's trials
        type(trial_table), intent(in) :: trials
        integer :: first, j, i, tip_record(size(trials%fracture))
        real(wp), parameter :: degrees = 180.0_wp / pi

        first = size(record%step) - count(keep)
        tip_record = 0
        do j = 1, size(tip_record)
            do i = 1, size(fracture)
                if (keep(i) .and. fracture(i) == trials%fracture(j) .and. &
                    end(i) == trials%end(j)) then
                    tip_record(j) = first + count(keep(1:i))
                end if
            end do
        end do
        record%trial_step = [record%trial_step, spread(step, 1, size(tip_record))]
        record%trial_record = [record%trial_record, tip_record]
        record%trial_angle = [record%trial_angle, trials%angle * degrees]
        record%trial_efficiency = [record%trial_efficiency, trials%efficiency]
        record%trial_state = [record%trial_state, trials%state]
    end subroutine append_trials

end module ddc_growth_work
