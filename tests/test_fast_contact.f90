!> The fast contact method ('newton', active set on the stiffness system) against the
!> reference Lemke (suite `fast_contact`): every contact case of the contact and
!> frictional suites, seeded random kinked and stepping faults, and the fallback to Lemke.
!> Same states, DDs within 1e-8 relative (to the largest DD of the model).
module test_fast_contact
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, condition_contact, condition_traction
    use ddc_model_results, only: model_results, state_open, state_slip, state_stick
    use ddc_run_model, only: run_model
    use ddc_constants, only: pi
    use ddc_influence_assembly, only: assemble_influence, row_traction
    use ddc_model_loads, only: resolve_remote_stress
    use ddc_contact_result, only: contact_result, contact_stress_scale
    use ddc_contact_formulation, only: solve_contact
    use ddc_contact_options, only: solver_options, parse_solver_options, option_code, &
        open_cohesion_names, lcp_lemke, lcp_newton
    use ddc_test_builders, only: polyline_model, join_fractures
    use ddc_contact_reduced_factors, only: reduced_factors, set_system, solve_system, &
        last_action, counts_of, action_factorized, action_updated, action_reused
    use ddc_contact_counts, only: factor_counts
    use ddc_contact_memory, only: lemke_bytes, newton_bytes
    use ddc_contact_active_set, only: starting_unknowns
    use ddc_error, only: exit_out_of_memory
    implicit none
    private

    public :: collect_fast_contact

    real(wp), parameter :: e_modulus = 50000.0_wp, nu = 0.25_wp
    !> Relative agreement of the DDs of both methods
    real(wp), parameter :: dd_tol = 1.0e-8_wp

contains

    !> Cases of the fast_contact suite.
    subroutine collect_fast_contact(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('paper_fault_slips_n500', test_paper_slip), &
                 new_test('paper_fault_sticks', test_paper_stick), &
                 new_test('ritz2012_loading_n100_sf0', test_ritz_loading), &
                 new_test('weak_patch_n400', test_weak_patch), &
                 new_test('fluid_pressure_cohesion_kept', test_pressure_kept), &
                 new_test('fluid_pressure_cohesion_lost', test_pressure_lost), &
                 new_test('kinked_stick_slip_open', test_kink), &
                 new_test('hydrofracture_next_to_fault', test_hydrofracture), &
                 new_test('random_kinked_faults', test_random_kinked), &
                 new_test('random_stepping_faults', test_random_stepping), &
                 new_test('fallback_to_lemke', test_fallback), &
                 new_test('reduced_system_updates', test_reduced_updates), &
                 new_test('reduced_update_sequence', test_reduced_update_sequence), &
                 new_test('fallback_without_memory', test_fallback_without_memory), &
                 new_test('reduced_system_outgrows_memory', test_outgrows_memory), &
                 new_test('bad_method', test_bad_method)]
    end subroutine collect_fast_contact

    ! ------------------------------------------------------------------ comparison

    !> Run the model with Lemke and with newton; newton must not fall back, and states and
    !> DDs must agree. Returns the Lemke results in ref when present.
    subroutine compare_methods(model, error, label, ref)
        type(model_type), intent(in) :: model
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: label
        type(model_results), intent(out), optional :: ref
        type(model_type) :: m
        type(model_results) :: r_lemke, r_newton
        real(wp) :: scale

        m = model
        m%solver%lcp_method = lcp_lemke
        call run_model(m, r_lemke, error)
        if (allocated(error)) then
            error%message = label//' (lemke): '//error%message
            return
        end if
        m%solver%lcp_method = lcp_newton
        call run_model(m, r_newton, error)
        if (allocated(error)) then
            error%message = label//' (newton): '//error%message
            return
        end if
        call check(error, r_lemke%solver%method == 'lemke', label//': method lemke')
        call check(error, r_newton%solver%method == 'newton', label//': method newton, &
            &fallback: '//r_newton%solver%fallback)
        call check(error, r_newton%solver%newton_iterations > 0, label//': iterations')
        call check(error, all(r_newton%elements%state == r_lemke%elements%state), &
            label//': same states')
        scale = max(maxval(abs(r_lemke%elements%ds)), maxval(abs(r_lemke%elements%dn)), &
            tiny(1.0_wp))
        call check(error, maxval(abs(r_newton%elements%ds - r_lemke%elements%ds)), 0.0_wp, &
            label//': ds', abs_tol=dd_tol * scale)
        call check(error, maxval(abs(r_newton%elements%dn - r_lemke%elements%dn)), 0.0_wp, &
            label//': dn', abs_tol=dd_tol * scale)
        call check(error, r_newton%solver%certificate_max_complementarity <= &
            r_newton%solver%certificate_tolerance .and. r_newton%solver%certificate_min_z >= &
            -r_newton%solver%certificate_tolerance .and. r_newton%solver%certificate_min_w >= &
            -r_newton%solver%certificate_tolerance, label//': newton certificate')
        if (present(ref)) ref = r_lemke
    end subroutine compare_methods

    !> A contact fault along a polyline with uniform mu, Sf and p and the given loading.
    function loaded_polyline(x, y, counts, mu, sf, p, sxx, syy, sxy) result(model)
        real(wp), intent(in) :: x(:), y(:)
        integer, intent(in) :: counts(:)
        real(wp), intent(in) :: mu, sf, p, sxx, syy, sxy
        type(model_type) :: model

        model = polyline_model(x, y, counts, condition_contact, 0.0_wp, 0.0_wp, e_modulus, nu)
        model%elements%mu = mu
        model%elements%sf = sf
        model%elements%pressure = p
        model%sxx = sxx
        model%syy = syy
        model%sxy = sxy
    end function loaded_polyline

    ! ------------------------------------------------------------------ the suites' cases

    subroutine test_paper_slip(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_methods(loaded_polyline([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [500], &
            0.6_wp, 1.0_wp, 0.0_wp, -143.75_wp, -81.25_wp, 54.13_wp), error, 'paper slip')
    end subroutine test_paper_slip

    !> mu = 0.7 (frictional suite) at N = 500 and the contact suite's all-stick case.
    subroutine test_paper_stick(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_methods(loaded_polyline([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [500], &
            0.7_wp, 1.0_wp, 0.0_wp, -143.75_wp, -81.25_wp, 54.13_wp), error, 'paper stick')
        if (allocated(error)) return
        call compare_methods(loaded_polyline([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [100], &
            0.8_wp, 1.0_wp, 0.0_wp, -143.75_wp, -81.25_wp, 54.13_wp), error, 'all stick')
    end subroutine test_paper_stick

    !> The paper's reference loading: 100 elements, mu = 0.6, Sf = 0 (degenerate LCP).
    subroutine test_ritz_loading(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_methods(loaded_polyline([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [100], &
            0.6_wp, 0.0_wp, 0.0_wp, -143.75_wp, -81.25_wp, 54.13_wp), error, 'ritz2012')
    end subroutine test_ritz_loading

    subroutine test_weak_patch(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: ref

        model = loaded_polyline([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [400], 0.6_wp, 0.0_wp, &
            0.0_wp, 0.0_wp, -10.0_wp, 9.0_wp)
        model%elements%sf = merge(0.0_wp, 6.0_wp, abs(model%elements%x_mid) < 0.4_wp)
        call compare_methods(model, error, 'weak patch', ref)
        if (allocated(error)) return
        call check(error, count(ref%elements%state == state_stick) > 0 .and. &
            count(ref%elements%state == state_slip) > 0, 'weak patch: stick and slip')
    end subroutine test_weak_patch

    subroutine test_pressure_kept(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_methods(pressurized('kept'), error, 'pressure kept')
    end subroutine test_pressure_kept

    subroutine test_pressure_lost(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r

        call compare_methods(pressurized('lost'), error, 'pressure lost')
        if (allocated(error)) return
        model = pressurized('lost')
        model%solver%lcp_method = lcp_newton
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, r%solver%lcp_solves, 2, 'newton solves (second after cohesion lost)')
    end subroutine test_pressure_lost

    !> Fluid pressure 12 above the normal compression 10 (both suites' pressure case).
    function pressurized(cohesion) result(model)
        character(len=*), intent(in) :: cohesion
        type(model_type) :: model

        model = loaded_polyline([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [100], 0.6_wp, 2.0_wp, &
            12.0_wp, 0.0_wp, -10.0_wp, 5.0_wp)
        model%solver%open_cohesion = option_code(cohesion, open_cohesion_names)
    end function pressurized

    !> The kink of both suites: flat then 35 degrees up, Sf = 0, p = 17.5.
    subroutine test_kink(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: ref

        call compare_methods(kinked(), error, 'kink', ref)
        if (allocated(error)) return
        call check(error, count(ref%elements%state == state_stick) > 0 .and. &
            count(ref%elements%state == state_slip) > 0 .and. &
            count(ref%elements%state == state_open) > 0, 'kink: stick, slip and open')
    end subroutine test_kink

    function kinked() result(model)
        type(model_type) :: model
        real(wp), parameter :: b = 35.0_wp * pi / 180.0_wp

        model = loaded_polyline([-1.0_wp, 0.0_wp, cos(b)], [0.0_wp, 0.0_wp, sin(b)], [30, 30], &
            0.6_wp, 0.0_wp, 17.5_wp, -5.0_wp, -20.0_wp, 0.5_wp)
    end function kinked

    !> A pressurized fracture with a traction condition (condensed) beside a fault.
    subroutine test_hydrofracture(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, fault

        model = polyline_model([0.0_wp, 0.0_wp], [0.3_wp, 1.1_wp], [40], condition_traction, &
            0.0_wp, -30.0_wp, e_modulus, nu)
        fault = loaded_polyline([-1.0_wp, 1.0_wp], [-0.2_wp, -0.2_wp], [60], 0.6_wp, 0.0_wp, &
            0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp)
        call join_fractures(model, fault)
        model%sxx = -10.0_wp
        model%syy = -20.0_wp
        model%sxy = 13.0_wp
        call compare_methods(model, error, 'hydrofracture')
    end subroutine test_hydrofracture

    ! ------------------------------------------------------------------ random geometries

    !> Next value of a 64-bit linear congruential generator, uniform in [0, 1).
    function uniform(state) result(u)
        integer(int64), intent(inout) :: state
        real(wp) :: u

        state = ieor(state, ishft(state, 13))
        state = ieor(state, ishft(state, -7))
        state = ieor(state, ishft(state, 17))
        u = real(ibits(state, 11, 52), wp) / 2.0_wp**52
    end function uniform

    !> Uniform in [lo, hi).
    function between(state, lo, hi) result(v)
        integer(int64), intent(inout) :: state
        real(wp), intent(in) :: lo, hi
        real(wp) :: v

        v = lo + (hi - lo) * uniform(state)
    end function between

    !> Random loading near the friction limit, friction, strength and a fluid pressure near
    !> the normal stress on the elements beyond a random x (seeded state).
    subroutine random_loading(model, state)
        type(model_type), intent(inout) :: model
        integer(int64), intent(inout) :: state
        real(wp) :: p, cut

        model%syy = between(state, -30.0_wp, -10.0_wp)
        model%sxx = model%syy * between(state, 0.3_wp, 1.0_wp)
        model%sxy = sign(between(state, 0.2_wp, 0.6_wp) * abs(model%syy), &
            between(state, -1.0_wp, 1.0_wp))
        model%elements%mu = between(state, 0.3_wp, 0.7_wp)
        model%elements%sf = merge(between(state, 0.0_wp, 2.0_wp), 0.0_wp, &
            uniform(state) < 0.5_wp)
        p = between(state, 0.5_wp, 1.1_wp) * abs(model%syy)
        cut = between(state, -0.5_wp, 0.8_wp)
        model%elements%pressure = merge(p, 0.0_wp, model%elements%x_mid > cut)
    end subroutine random_loading

    !> Eight seeded faults with two kinks each (random angles and element counts).
    subroutine test_random_kinked(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        integer(int64) :: state
        real(wp) :: x(4), y(4), angle
        integer :: trial, k, counts(3)

        counts = 0

        state = 20240611_int64
        do trial = 1, 8
            x(1) = -1.0_wp
            y(1) = 0.0_wp
            angle = between(state, -0.5_wp, 0.5_wp)
            do k = 2, 4
                x(k) = x(k - 1) + between(state, 0.4_wp, 0.9_wp) * cos(angle)
                y(k) = y(k - 1) + between(state, 0.4_wp, 0.9_wp) * sin(angle)
                angle = angle + between(state, -0.9_wp, 0.9_wp)
            end do
            model = polyline_model(x, y, [(10 + int(20 * uniform(state)), k = 1, 3)], &
                condition_contact, 0.0_wp, 0.0_wp, e_modulus, nu)
            call random_loading(model, state)
            call compare_counting(model, 'random kinked', trial, counts, error)
            if (allocated(error)) return
        end do
        call check(error, all(counts > 0), 'random kinked: stick, slip and open all seen')
    end subroutine test_random_kinked

    !> Eight seeded stepping (en echelon) pairs of parallel faults with random overlap
    !> (negative: a gap) and offset.
    subroutine test_random_stepping(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, other
        integer(int64) :: state
        real(wp) :: overlap, offset
        integer :: trial, counts(3)

        counts = 0

        state = 77123_int64
        do trial = 1, 8
            overlap = between(state, -0.2_wp, 0.3_wp)
            offset = between(state, 0.05_wp, 0.3_wp)
            model = polyline_model([-1.0_wp, 0.5_wp * overlap], [0.0_wp, 0.0_wp], &
                [20 + int(20 * uniform(state))], condition_contact, 0.0_wp, 0.0_wp, &
                e_modulus, nu)
            other = polyline_model([-0.5_wp * overlap, 1.0_wp], [offset, offset], &
                [20 + int(20 * uniform(state))], condition_contact, 0.0_wp, 0.0_wp, &
                e_modulus, nu)
            call join_fractures(model, other)
            call random_loading(model, state)
            call compare_counting(model, 'random stepping', trial, counts, error)
            if (allocated(error)) return
        end do
        call check(error, all(counts > 0), 'random stepping: stick, slip and open all seen')
    end subroutine test_random_stepping

    !> compare_methods on trial k of a series, adding the numbers of stick, slip and open
    !> elements to counts.
    subroutine compare_counting(model, series, k, counts, error)
        type(model_type), intent(in) :: model
        character(len=*), intent(in) :: series
        integer, intent(in) :: k
        integer, intent(inout) :: counts(3)
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: r
        character(len=60) :: label

        write (label, '(a,1x,i0)') series, k
        call compare_methods(model, error, trim(label), r)
        if (allocated(error)) return
        counts = counts + [count(r%elements%state == state_stick), &
            count(r%elements%state == state_slip), count(r%elements%state == state_open)]
    end subroutine compare_counting

    ! ------------------------------------------------------------------ fallback

    !> With an iteration limit of 1 newton cannot settle the kink's states: the solve falls
    !> back to Lemke, says why, and gives Lemke's result.
    subroutine test_fallback(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(contact_result) :: fast, ref
        real(wp), allocatable :: a(:, :), ss(:), sn(:)

        call kinked_system(model, a, ss, sn)
        associate (e => model%elements)
            call solve_contact(a, ss, sn, e%mu, e%sf, e%pressure, &
                               solver_options(lcp_method=lcp_lemke), ref, error)
            if (allocated(error)) return
            call solve_contact(a, ss, sn, e%mu, e%sf, e%pressure, &
                               solver_options(lcp_method=lcp_newton), fast, error, &
                               max_iterations=1)
            if (allocated(error)) return
        end associate
        call check(error, fast%method == 'lemke', 'method after fallback: '//fast%method)
        call check(error, index(fast%fallback, 'no convergence within 1 iterations') > 0, &
            'fallback reason: '//fast%fallback)
        call check(error, fast%pivots > 0 .and. fast%iterations == 1, 'pivots and iterations')
        call check(error, all(fast%state == ref%state), 'states as Lemke')
        ! The fallback runs the same Lemke code on the same data: identical by construction.
        call check(error, maxval(abs(fast%ds - ref%ds)), 0.0_wp, 'ds as Lemke', &
            abs_tol=0.0_wp)
    end subroutine test_fallback

    !> The reduced system of the active-set method on the kink's influence matrix: a few
    !> states changed (unknowns added and removed, a coefficient changed) are solved
    !> through a low-rank update of the kept factors, unchanged ones with the factors
    !> themselves, and the solutions equal those of a fresh factorization within 1e-12.
    subroutine test_reduced_updates(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(reduced_factors) :: kept, fresh
        type(factor_counts) :: counts
        real(wp), allocatable :: a(:, :), x(:), y(:), coef(:), ss(:), sn(:)
        integer, allocatable :: unknown(:), partner(:)
        integer :: n, k, i

        call kinked_system(model, a, ss, sn)
        n = model%elements%n
        ! Base: Ds of elements 1..40 slipping (coefficient mu), Dn of 41..60 open.
        unknown = [(i, i = 1, 40), (n + i, i = 41, 60)]
        partner = [(n + i, i = 1, 40), (n + i, i = 41, 60)]
        coef = [(0.6_wp, i = 1, 40), (0.0_wp, i = 41, 60)]
        call set_system(kept, a, unknown, partner, coef, 'base', error)
        if (allocated(error)) return
        call check(error, last_action(kept), action_factorized, 'first: a factorization')
        if (allocated(error)) return
        call set_system(kept, a, unknown, partner, coef, 'same', error)
        if (allocated(error)) return
        call check(error, last_action(kept), action_reused, 'unchanged: the factors reused')
        ! Element 3 leaves, element 41 slips too, element 7 slips the other way, Dn of 20
        ! opens: 2 changed base rows, 2 added unknowns.
        unknown = [(i, i = 1, 2), (i, i = 4, 40), 41, (n + i, i = 41, 60), n + 20]
        partner = [(n + i, i = 1, 2), (n + i, i = 4, 40), n + 41, (n + i, i = 41, 60), n + 20]
        coef = [(0.6_wp, i = 1, 2), (0.6_wp, i = 4, 40), 0.6_wp, (0.0_wp, i = 41, 60), 0.0_wp]
        coef(6) = -0.6_wp
        if (allocated(error)) return
        call set_system(kept, a, unknown, partner, coef, 'changed', error)
        if (allocated(error)) return
        call check(error, last_action(kept), action_updated, 'a few changes: an update')
        if (allocated(error)) return
        call set_system(fresh, a, unknown, partner, coef, 'fresh', error)
        if (allocated(error)) return
        do k = 1, 3
            x = [(sin(real(k * i, wp)), i = 1, size(unknown))]
            y = x
            call solve_system(kept, x)
            call solve_system(fresh, y)
            call check(error, maxval(abs(x - y)), 0.0_wp, 'update = fresh factorization', &
                       abs_tol=1.0e-12_wp * maxval(abs(y)))
        end do
        counts = counts_of(kept)
        call check(error, counts%factorizations == 1 .and. counts%updates == 1 .and. &
                   counts%reuses == 1, 'counts of factorizations, updates and reuses')
    end subroutine test_reduced_updates

    !> A sequence of updates of one base, as between Newton iterations: the changed base
    !> rows change from one system to the next (rows kept, dropped, new, a coefficient
    !> flipped back) while added unknowns stay, leave and come (their J^-1 B0 and the Z of
    !> the rows that stay are kept); every solve equals a fresh factorization within 1e-12,
    !> and the base is factorized once.
    subroutine test_reduced_update_sequence(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(reduced_factors) :: kept, fresh
        real(wp), allocatable :: a(:, :), x(:), y(:), ss(:), sn(:)
        ! Per system: Ds of 1..45 in (0: out), its coefficient's sign; Dn of 41..60, 20 in
        integer, parameter :: systems = 6
        integer :: shear(45, 0:systems)
        logical :: dn20(0:systems), dn41(0:systems)
        type(factor_counts) :: counts
        integer :: n, i, k, m

        call kinked_system(model, a, ss, sn)
        n = model%elements%n
        shear(:, 0) = [spread(1, 1, 40), spread(0, 1, 5)]
        shear(:, 1:systems) = spread(shear(:, 0), 2, systems)
        dn20 = .false.
        dn41 = .true.
        ! 1: 3 leaves, 41 and 42 slip; 2: and 7 flips; 3: 3 back, 10 leaves, Dn 20 opens;
        ! 4: 7 back, 12 flips, 41 sticks; 5: only the added 42 and Dn 20; 6: Dn 41 closes.
        shear([3, 41, 42], 1) = [0, 1, 1]
        shear([3, 7, 41, 42], 2) = [0, -1, 1, 1]
        shear([10, 7, 41, 42], 3) = [0, -1, 1, 1]
        dn20(3:5) = .true.
        shear([10, 12, 42], 4) = [0, -1, 1]
        shear(42, 5) = 1
        shear(42, 6) = 1
        dn41(6) = .false.
        call set_kinked(kept, 0)
        if (allocated(error)) return
        do k = 1, systems
            call set_kinked(kept, k)
            if (allocated(error)) return
            call check(error, last_action(kept), action_updated, 'system '//achar(48 + k)// &
                       ': an update')
            call set_kinked(fresh, k)
            if (allocated(error)) return
            x = [(cos(real(k * i, wp)), i = 1, m)]
            y = x
            call solve_system(kept, x)
            call solve_system(fresh, y)
            call check(error, maxval(abs(x - y)), 0.0_wp, 'system '//achar(48 + k)// &
                       ': update = fresh factorization', abs_tol=1.0e-12_wp * maxval(abs(y)))
            call check(error, last_action(fresh), action_factorized, 'fresh factors')
            if (allocated(error)) return
            fresh = reduced_factors()
        end do
        counts = counts_of(kept)
        call check(error, counts%factorizations == 1 .and. counts%updates == systems, &
                   'one factorization, then only updates')

    contains

        !> Set system k of the sequence on sys.
        subroutine set_kinked(sys, k)
            type(reduced_factors), intent(inout) :: sys
            integer, intent(in) :: k
            integer, allocatable :: unknown(:), partner(:), ds(:), dn(:)
            real(wp), allocatable :: coef(:)
            integer :: j

            ds = pack([(j, j = 1, 45)], shear(:, k) /= 0)
            dn = [(j, j = 42, 60)]
            if (dn41(k)) dn = [41, dn]
            if (dn20(k)) dn = [dn, 20]
            unknown = [ds, n + dn]
            m = size(unknown)
            partner = n + [ds, dn]
            coef = [0.6_wp * real(shear(ds, k), wp), spread(0.0_wp, 1, size(dn))]
            call set_system(sys, a, unknown, partner, coef, 'sequence', error)
        end subroutine set_kinked

    end subroutine test_reduced_update_sequence

    !> The same fallback when the memory left cannot hold Lemke's LCP: it does not start,
    !> the solve stops with exit_out_of_memory saying why Newton failed and what Lemke
    !> would need.
    subroutine test_fallback_without_memory(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(contact_result) :: fast
        type(error_type), allocatable :: solve_error
        real(wp), allocatable :: a(:, :), ss(:), sn(:)

        call kinked_system(model, a, ss, sn)
        associate (e => model%elements)
            call solve_contact(a, ss, sn, e%mu, e%sf, e%pressure, solver_options( &
                lcp_method=lcp_newton, work_bytes=lemke_bytes(e%n) - 1.0_wp), fast, &
                solve_error, max_iterations=1)
        end associate
        call check(error, allocated(solve_error), 'the fallback must not start')
        if (allocated(error)) return
        call check(error, solve_error%code, exit_out_of_memory, 'exit code')
        call check(error, index(solve_error%message, 'no convergence within 1 iterations') > 0 &
            .and. index(solve_error%message, 'the fallback to Lemke would need about') > 0, &
            'message: '//solve_error%message)
    end subroutine test_fallback_without_memory

    !> Memory for the kink's first reduced system (the states of the remote stress) but not
    !> for the larger ones its iterations reach: newton stops cleanly (exit_out_of_memory)
    !> before allocating it, and does not fall back to Lemke (which needs more).
    subroutine test_outgrows_memory(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(contact_result) :: fast
        type(error_type), allocatable :: solve_error
        real(wp), allocatable :: a(:, :), ss(:), sn(:)
        integer :: first

        call kinked_system(model, a, ss, sn)
        associate (e => model%elements)
            first = starting_unknowns(ss, sn + e%pressure, e%mu, e%sf, &
                                      contact_stress_scale(ss, sn, e%sf, e%pressure))
            call solve_contact(a, ss, sn, e%mu, e%sf, e%pressure, solver_options( &
                lcp_method=lcp_newton, work_bytes=newton_bytes(e%n, first)), fast, solve_error)
        end associate
        call check(error, allocated(solve_error), 'a reduced system larger than the first '// &
                   'must not be allocated')
        if (allocated(error)) return
        call check(error, solve_error%code, exit_out_of_memory, 'exit code')
        call check(error, index(solve_error%message, 'ask for a reduced system of ') > 0 .and. &
            index(solve_error%message, ' is left here') > 0, 'message: '//solve_error%message)
        ! With the memory of the largest system it solves.
        deallocate (solve_error)
        associate (e => model%elements)
            call solve_contact(a, ss, sn, e%mu, e%sf, e%pressure, solver_options( &
                lcp_method=lcp_newton, work_bytes=newton_bytes(e%n)), fast, solve_error)
        end associate
        call check(error, .not. allocated(solve_error) .and. fast%method == 'newton', &
                   'enough memory: newton solves')
    end subroutine test_outgrows_memory

    !> The kink, its influence matrix and its resolved remote stress.
    subroutine kinked_system(model, a, ss, sn)
        type(model_type), intent(out) :: model
        real(wp), allocatable, intent(out) :: a(:, :), ss(:), sn(:)
        integer, allocatable :: rows(:)
        integer :: n

        model = kinked()
        n = model%elements%n
        allocate (a(2 * n, 2 * n), ss(n), sn(n))
        rows = spread(row_traction, 1, n)
        call assemble_influence(model%elements, e_modulus / (2.0_wp * (1.0_wp + nu)), nu, &
            rows, rows, a)
        call resolve_remote_stress(model%elements, model%sxx, model%syy, model%sxy, ss, sn)
    end subroutine kinked_system

    !> A method other than auto, lemke or newton is bad input.
    subroutine test_bad_method(error)
        type(error_type), allocatable, intent(out) :: error
        type(solver_options) :: options

        call parse_solver_options('path', 'kept', options, error)
        call check(error, allocated(error), 'method = path must be an error')
        if (allocated(error)) then
            if (index(error%message, "'path'") > 0) deallocate (error)
        end if
    end subroutine test_bad_method

end module test_fast_contact
