!> Incremental quasi-static loading along a load path (docs/theory/earth.md#loading-histories).
!>
!> The influence matrix is assembled and the TWODD-style elements condensed out once (or,
!> with &solver matrix = 'hierarchical', compressed: ddc_solve_hierarchical_stiffness, for
!> models of contact elements alone, by the Newton method); every
!> step is then one contact solve (ddc_contact_formulation, with &solver lcp_method and its
!> fallbacks, as a one-shot solve) for the step's load and the total slip of the step
!> before, with one dense stiffness operator and a contact_session that the steps share:
!> the Newton method starts from the previous step's states and reuses the operator's
!> factorization (two triangular solves when no state changes, a low-rank update when a few
!> do); Lemke builds the paper's LCP (one inverse of A) the first time it is needed and
!> starts from its previous basis. Every
!> step is certified and checked for equilibrium; a step that fails is an error naming the
!> step, and nothing is returned as a result. A step where the first method fails and the
!> other one solves it is recorded (/history method and fallback).
!>
!> Each step records DDs, states, tractions and the stress intensity factors of the tips
!> (found once; by the higher-order re-solve where it serves, assembled once:
!> docs/theory/tips.md#k-along-a-loading-history). The last step's element results, tips
!> and fields are those of finish_model (ddc_run_model) for the model at the last load.
module ddc_history_solve
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, element_set, condition_contact
    use ddc_model_results, only: model_results, history_record
    use ddc_model_records, only: lay_out_history
    use ddc_model_restart, only: restart_state
    use ddc_model_loads, only: resolve_remote_stress, total_pressure, shear_modulus_of
    use ddc_contact_result, only: contact_result, contact_stress_scale
    use ddc_contact_formulation, only: solve_contact_with, contact_session
    use ddc_contact_fault_law, only: fault_law
    use ddc_contact_stiffness, only: stiffness_operator, dense_stiffness
    use ddc_contact_options, only: matrix_hierarchical
    use ddc_solve_hierarchical_stiffness, only: hierarchical_stiffness, &
        new_hierarchical_stiffness
    use ddc_solve_joints, only: joint_system, joint_load, joint_dds, elastic_dds
    use ddc_solve_frictional, only: condensed_contact, condense_contact, contact_load, &
        complete_dds, record_contact, release_matrix, fault_law_of, strengths_change, &
        contact_only_system
    use ddc_influence_response, only: listed_tractions
    use ddc_post_tips, only: find_tips, stress_intensity
    use ddc_post_higher_order_k, only: higher_order_solver, prepare_higher_order, &
        higher_order_k, uses_higher_order
    use ddc_history_path, only: path_loads, apply_load, load_text
    use ddc_run_model, only: finish_model
    use ddc_progress, only: report_progress
    use ddc_text, only: itoa, seconds_text
    use ddc_allocation, only: allocation_failed, real_bytes
    implicit none
    private

    public :: solve_history

contains

    !> Solve a model along its load path; results hold the last step and the history.
    !> On success the model's remote stress, gradients and pore pressure p0 are those of
    !> the last step (the state /elements and the fields describe).
    subroutine solve_history(model, results, error, max_pivots, max_iterations, restart)
        !> A validated model with a load path and at least one contact element
        type(model_type), intent(inout) :: model
        !> The last step's element results, tips and fields, and every step's history
        type(model_results), intent(out) :: results
        !> Allocated when a step fails (exit_solver_failure, naming the step) or the model
        !> has no path or no contact element (exit_bad_input)
        type(error_type), allocatable, intent(out) :: error
        !> Pivot limit of each Lemke solve (tests; default that of solve_lcp_lemke)
        integer, intent(in), optional :: max_pivots
        !> Iteration limit of each Newton solve (tests; default that of solve_contact)
        integer, intent(in), optional :: max_iterations
        !> The end of an earlier run of the model along the first steps of its path to go on
        !> from (--resume; docs/theory/earth.md#what-a-step-hands-on): its steps are kept, the next
        !> ones start from its friction memory and the strengths in force at its end
        type(restart_state), intent(in), optional :: restart
        type(condensed_contact), target :: sys
        type(contact_session) :: session
        ! The tips' K by the higher-order re-solve: assembled once, factorized as states change
        type(higher_order_solver) :: k_solver
        logical :: higher_order
        character(len=:), allocatable :: why_not
        type(error_type), allocatable :: k_failed
        real(wp), allocatable :: mu(:)
        class(stiffness_operator), allocatable :: stiffness
        ! A hierarchical operator points at the elements: a copy that lives as long as it
        type(element_set), target :: kept
        logical :: hierarchical
        type(contact_result) :: res
        type(history_record) :: h
        type(fault_law) :: law
        real(wp), allocatable :: loads(:, :), shear(:, :), normal(:, :), shift(:, :)
        real(wp), allocatable :: y_load(:, :), pressure(:, :), ds_previous(:), v(:)
        real(wp), allocatable :: compliance(:), load_map(:, :)
        real(wp), allocatable, target :: a_joint(:, :)
        real(wp), pointer, contiguous :: a_solve(:, :)
        real(wp), allocatable :: matrix(:, :), no_dd(:), ts(:), tn(:)
        integer :: n, nc, k, nsteps, pivots, solves, iterations, fallbacks, first_fallback, stat
        integer :: done
        real(wp) :: sigma0, g, seconds_lcp, seconds_factorization, flops
        integer(int64) :: t_start, t0, t1, rate

        if (.not. allocated(model%load_path%vertex)) then
            call set_error(error, exit_bad_input, 'loading history: the model has no load path')
            return
        end if
        if (.not. any(model%elements%condition == condition_contact)) then
            call set_error(error, exit_bad_input, 'loading history: a load path needs '// &
                'contact elements (without them the response is elastic: superpose)')
            return
        end if
        call system_clock(t_start, rate)
        n = model%elements%n
        g = shear_modulus_of(model)
        hierarchical = model%solver%matrix == matrix_hierarchical
        if (hierarchical) then
            call contact_only_system(model%elements, sys)
            kept = model%elements
            allocate (hierarchical_stiffness :: stiffness)
            select type (stiffness)
            type is (hierarchical_stiffness)
                call new_hierarchical_stiffness(kept, g, model%poissons_ratio, model%solver, &
                                                stiffness, error)
                results%solver%hierarchical = .true.
                results%solver%compression_ratio = stiffness%a%stored_fraction()
                results%solver%hmatrix_tolerance = model%solver%hmatrix_tolerance
            end select
        else
            allocate (dense_stiffness :: stiffness)
            call condense_contact(model%elements, g, model%poissons_ratio, sys, &
                                  results%solver, error)
        end if
        if (allocated(error)) return
        nc = sys%nc

        ! The load of every step on the contact elements, and the history's stress scale.
        loads = path_loads(model%load_path)
        nsteps = size(loads, 2)
        allocate (shear(n, nsteps), stat=stat)
        if (stat == 0) allocate (normal(n, nsteps), stat=stat)
        if (stat == 0) allocate (shift(2 * nc, nsteps), stat=stat)
        if (stat == 0) allocate (y_load(2 * sys%nf, nsteps), stat=stat)
        if (stat == 0) allocate (pressure(nc, nsteps), stat=stat)
        if (stat /= 0) then
            call allocation_failed(error, 'the loads of '//itoa(n)//' elements at '// &
                                   itoa(nsteps)//' steps', real_bytes * 7.0_wp * &
                                   real(n, wp) * real(nsteps, wp))
            return
        end if
        sigma0 = 0.0_wp
        do k = 1, nsteps
            call resolve_remote_stress(model%elements, loads(1, k), loads(2, k), loads(3, k), &
                                       shear(:, k), normal(:, k), loads(4:6, k))
            call contact_load(sys, model%elements, shear(:, k), normal(:, k), shift(:, k), &
                              y_load(:, k))
            v = total_pressure(model%elements, [loads(7, k), model%pore_fluid(2)])
            pressure(:, k) = v(sys%contact)
            sigma0 = max(sigma0, contact_stress_scale(shift(1:nc, k), shift(nc + 1:, k), &
                model%elements%sf(sys%contact), pressure(:, k)))
        end do

        ! The tips, found once; their K at every step.
        allocate (no_dd(n), source=0.0_wp)
        call find_tips(model%elements, g, model%poissons_ratio, no_dd, no_dd, results%tips)
        call uses_higher_order(model%solver%k_method, model%growth%active, model%elements, &
                               results%tips, higher_order, why_not)
        if (higher_order) then
            call prepare_higher_order(model%elements, g, model%poissons_ratio, results%tips, &
                                      k_solver, k_failed)
            higher_order = .not. allocated(k_failed)
        end if
        allocate (ts(sys%nf), tn(sys%nf))
        ! The fault law and its values in force: what an element lost (tensile strength on
        ! opening, cohesion on slip) stays lost for the rest of the history.
        law = fault_law_of(model%elements, sys%contact)
        allocate (ds_previous(nc), source=0.0_wp)
        ! One operator for every step: the Newton method's factors live in it.
        ! Elastic joints: the contact problem of the plastic DDs (ddc_solve_joints); the
        ! slip a step holds is the plastic one.
        compliance = law%joint_compliance()
        if (.not. hierarchical) a_solve => sys%a
        if (any(compliance > 0.0_wp)) then
            call joint_system(sys%a, compliance, a_joint, load_map, error)
            if (allocated(error)) return
            do k = 1, nsteps
                call joint_load(load_map, pressure(:, k), shift(1:nc, k), shift(nc + 1:, k))
            end do
            deallocate (load_map)
            a_solve => a_joint
        end if
        done = 0
        if (present(restart)) then
            call resume_steps(error)
            if (allocated(error)) return
        end if
        call allocate_history(h, n, results%tips%n, nsteps, done, &
                              strengths_change(model%elements, model%solver), error)
        if (allocated(error)) return
        h%load = loads
        select type (stiffness)
        type is (dense_stiffness)
            stiffness%a => a_solve
        end select
        pivots = 0
        solves = 0
        iterations = 0
        fallbacks = 0
        first_fallback = 0
        seconds_factorization = 0.0_wp
        flops = 0.0_wp
        call system_clock(t0, rate)
        do k = done + 1, nsteps
            ! Lemke needs the dense matrix: the hierarchical operator goes without it.
            if (hierarchical) then
                call solve_contact_with(stiffness, shift(1:nc, k), shift(nc + 1:, k), law, &
                                        pressure(:, k), model%solver, res, error, &
                                        max_iterations=max_iterations, &
                                        ds_previous=ds_previous, session=session, &
                                        stress_scale=sigma0)
            else
                call solve_contact_with(stiffness, shift(1:nc, k), shift(nc + 1:, k), law, &
                                        pressure(:, k), model%solver, res, error, a=a_solve, &
                                        max_iterations=max_iterations, &
                                        ds_previous=ds_previous, session=session, &
                                        stress_scale=sigma0, max_pivots=max_pivots)
            end if
            if (allocated(error)) then
                error%message = 'loading history: step '//itoa(k)//' of '//itoa(nsteps)// &
                    ' ('//load_text(loads(:, k), model%load_path%varies)//') failed: '// &
                    error%message//'; no result is written'
                return
            end if
            ds_previous = res%ds
            if (any(compliance > 0.0_wp)) call joint_dds(compliance, pressure(:, k), &
                res%shear_traction, res%normal_traction, res%ds, res%dn)
            pivots = pivots + res%pivots
            solves = solves + res%solves
            iterations = iterations + res%iterations
            seconds_factorization = seconds_factorization + res%counts%seconds
            flops = flops + res%counts%flops
            h%equilibrium_residual(k) = maxval(res%equilibrium_residual)
            call complete_dds(sys, model%elements, shear(:, k), normal(:, k), res, &
                              y_load(:, k), h%ds(:, k), h%dn(:, k), h%state(:, k), &
                              h%equilibrium_residual(k))
            h%pivots(k) = res%pivots
            h%newton_iterations(k) = res%iterations
            h%method(k) = res%method
            h%fallback(k) = res%fallback
            if (len(res%fallback) > 0) then
                fallbacks = fallbacks + 1
                if (first_fallback == 0) first_fallback = k
            end if
            h%certificate_min_z(k) = res%certificate%min_z
            h%certificate_min_w(k) = res%certificate%min_w
            h%certificate_max_complementarity(k) = res%certificate%max_complementarity
            if (allocated(h%mu_in_force)) call record_strengths(h, k, law, sys%contact)
            ! Tractions S_r + A D: the contact solution's, the free elements' from their rows.
            h%shear_traction(sys%contact, k) = res%shear_traction
            h%normal_traction(sys%contact, k) = res%normal_traction
            if (sys%nf > 0) then
                call listed_tractions(model%elements, g, model%poissons_ratio, sys%matrix, &
                    sys%shear_row, sys%normal_row, sys%free, h%ds(:, k), h%dn(:, k), ts, tn)
                h%shear_traction(sys%free, k) = ts + shear(sys%free, k)
                h%normal_traction(sys%free, k) = tn + normal(sys%free, k)
            end if
            ! The tip element's K, replaced by the re-solve's where it serves (a step where
            ! it fails keeps them: the run's K method is then the tip element's throughout).
            call stress_intensity(model%elements, g, model%poissons_ratio, &
                                  results%tips%element, h%ds(:, k), h%dn(:, k), h%k1(:, k), &
                                  h%k2(:, k))
            if (higher_order) then
                if (.not. allocated(mu)) allocate (mu(n))
                if (allocated(h%mu_in_force)) then
                    mu = h%mu_in_force(:, k)
                else
                    mu = model%elements%mu
                end if
                call higher_order_k(k_solver, model%elements, g, model%poissons_ratio, &
                                    h%ds(:, k), h%dn(:, k), h%shear_traction(:, k), &
                                    h%normal_traction(:, k), mu, loads(1:3, k), &
                                    loads(4:6, k), h%state(:, k), results%tips, h%k1(:, k), &
                                    h%k2(:, k), k_failed)
                higher_order = .not. allocated(k_failed)
            end if
            call system_clock(t1)
            call report_progress(step_line(k, nsteps, loads(:, k), model%load_path%varies, &
                                           res, real(t1 - t_start, wp) / real(rate, wp)))
        end do
        call system_clock(t1)
        seconds_lcp = real(t1 - t0, wp) / real(rate, wp) - seconds_factorization

        ! The last step: tractions, face displacements, tips and fields for its DDs.
        call record_contact(res, sys%flops, results%solver)
        results%elements%ds = h%ds(:, nsteps)
        results%elements%dn = h%dn(:, nsteps)
        results%elements%state = h%state(:, nsteps)
        allocate (results%elements%sf_in_force(n), results%elements%tensile_in_force(n), &
                  results%elements%mu_in_force(n), source=0.0_wp)
        results%elements%mu_in_force(sys%contact) = law%mu_in_force
        results%elements%sf_in_force(sys%contact) = law%sf_in_force
        results%elements%tensile_in_force(sys%contact) = law%tensile_in_force
        select type (stiffness)
        type is (dense_stiffness)
            nullify (stiffness%a)
        type is (hierarchical_stiffness)
            call stiffness%release()
        end select
        call release_matrix(sys, matrix)
        if (higher_order) then
            call finish_model(apply_load(model, loads(:, nsteps)), shear(:, nsteps), &
                              normal(:, nsteps), results, matrix=matrix, higher_order=k_solver)
        else
            call finish_model(apply_load(model, loads(:, nsteps)), shear(:, nsteps), &
                              normal(:, nsteps), results, matrix=matrix)
        end if
        if (any(compliance > 0.0_wp)) call record_elastic_dds(pressure(:, nsteps))
        results%solver%counts%seconds = results%solver%counts%seconds + &
            seconds_factorization - res%counts%seconds
        results%solver%counts%flops = results%solver%counts%flops + flops - &
            res%counts%flops
        results%solver%pivots = pivots
        results%solver%lcp_solves = solves
        results%solver%newton_iterations = iterations
        results%solver%seconds_lcp = seconds_lcp
        results%solver%equilibrium_residual = maxval(h%equilibrium_residual)
        results%solver%fallback = ''
        if (fallbacks > 0) results%solver%fallback = itoa(fallbacks)//' of '//itoa(nsteps)// &
            ' steps fell back to the other method; the first, step '//itoa(first_fallback)// &
            ': '//trim(h%fallback(first_fallback))
        results%history = h
        model = apply_load(model, loads(:, nsteps))
        call system_clock(t1)
        results%solver%seconds_total = real(t1 - t_start, wp) / real(rate, wp)

    contains

        !> The elastic DDs of the joints at the last step (0 on the other elements).
        subroutine record_elastic_dds(p)
            !> Fluid pressure on the contact elements, shape (nc) [stress]
            real(wp), intent(in) :: p(:)
            real(wp) :: ds_e(nc), dn_e(nc)

            associate (e => results%elements)
                call elastic_dds(compliance, p, e%shear_traction(sys%contact), &
                                 e%normal_traction(sys%contact), ds_e, dn_e)
                allocate (e%ds_elastic(n), e%dn_elastic(n), source=0.0_wp)
                e%ds_elastic(sys%contact) = ds_e
                e%dn_elastic(sys%contact) = dn_e
            end associate
        end subroutine record_elastic_dds

        !> The first `done` steps from the earlier run, and its memory at their end: the slip
        !> of the contact elements, the strengths in force and the slip path (the sum of the
        !> slip increments, as the steps added it up).
        subroutine resume_steps(error)
            type(error_type), allocatable, intent(out) :: error
            integer :: j

            associate (old => restart%results%history, e => restart%results%elements)
                done = size(old%pivots)
                if (done >= nsteps) then
                    call set_error(error, exit_bad_input, '--resume: the earlier run ended '// &
                        'at the end of this load path: nothing is left to do; extend '// &
                        '&load_path to go on')
                    return
                end if
                if (any(compliance > 0.0_wp)) then
                    ! The memory of elastic joints is their plastic slip, which the file does
                    ! not hold.
                    call set_error(error, exit_bad_input, '--resume: a loading history of '// &
                        'elastic joints (shear_stiffness, normal_stiffness) cannot be resumed')
                    return
                end if
                h = old
                ds_previous = e%ds(sys%contact)
                law%sf_in_force = e%sf_in_force(sys%contact)
                law%tensile_in_force = e%tensile_in_force(sys%contact)
                law%mu_in_force = e%mu_in_force(sys%contact)
                do j = 1, done
                    if (j == 1) then
                        law%slip_path = abs(old%ds(sys%contact, 1))
                    else
                        law%slip_path = law%slip_path + abs(old%ds(sys%contact, j) - &
                                                            old%ds(sys%contact, j - 1))
                    end if
                end do
            end associate
        end subroutine resume_steps

    end subroutine solve_history

    !> Room for every step of a history of n elements and tips tips, the first `kept` steps
    !> of h kept (a resumed run's), with the strengths in force when asked for; error: it
    !> does not fit.
    subroutine allocate_history(h, n, tips, k, kept, strengths, error)
        type(history_record), intent(inout) :: h
        integer, intent(in) :: n, tips, k, kept
        logical, intent(in) :: strengths
        type(error_type), allocatable, intent(out) :: error
        integer :: stat

        call lay_out_history(h, n, tips, k, kept, stat, strengths=strengths)
        if (stat /= 0) call allocation_failed(error, 'the history of '//itoa(n)// &
                                              ' elements at '//itoa(k)//' steps', &
                                              real_bytes * merge(8.0_wp, 5.0_wp, strengths) &
                                              * real(n, wp) * real(k, wp))
    end subroutine allocate_history

    !> Step k's strengths in force: the law's, as the step's solve leaves them, on the
    !> contact elements, 0 on the others.
    pure subroutine record_strengths(h, k, law, contact)
        type(history_record), intent(inout) :: h
        integer, intent(in) :: k
        !> The law of the contact elements
        type(fault_law), intent(in) :: law
        !> Indices of the contact elements, shape (nc)
        integer, intent(in) :: contact(:)

        h%mu_in_force(:, k) = 0.0_wp
        h%sf_in_force(:, k) = 0.0_wp
        h%tensile_strength_in_force(:, k) = 0.0_wp
        h%mu_in_force(contact, k) = law%mu_in_force
        h%sf_in_force(contact, k) = law%sf_in_force
        h%tensile_strength_in_force(contact, k) = law%tensile_in_force
    end subroutine record_strengths

    !> 'step 12 of 101 (sxy = 10): newton, 1 iteration, 0.53 s' (the time since the start);
    !> 'newton, 9 iterations in 3 solves' where the strength fixed point (slip weakening,
    !> strength loss) solved more than once.
    function step_line(k, nsteps, load, varies, res, seconds) result(line)
        integer, intent(in) :: k, nsteps
        real(wp), intent(in) :: load(:), seconds
        logical, intent(in) :: varies(:)
        type(contact_result), intent(in) :: res
        character(len=:), allocatable :: line

        line = 'step '//itoa(k)//' of '//itoa(nsteps)//' ('//load_text(load, varies)//'): '// &
            res%method
        if (res%method == 'newton') then
            line = line//', '//itoa(res%iterations)//' iteration'
            if (res%iterations /= 1) line = line//'s'
        else
            line = line//', '//itoa(res%pivots)//' pivot'
            if (res%pivots /= 1) line = line//'s'
        end if
        if (res%solves > 1) line = line//' in '//itoa(res%solves)//' solves'
        if (len(res%fallback) > 0) line = line//' (fell back: '//res%fallback//')'
        line = line//', '//seconds_text(seconds)
    end function step_line

end module ddc_history_solve
