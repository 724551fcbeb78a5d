!> Fault strength beyond Coulomb (issue 26), end to end through run_model and solve_history:
!> a tensile strength lost on opening and a cohesion that drops to its residual value after
!> slip, slip weakening and elastic joints, held to the Coulomb cracks and springs they
!> reduce to, Newton against Lemke, and the loading history that remembers what was lost.
module test_strength
    use ddc_kinds, only: wp
    use ddc_contact_options, only: lcp_lemke, lcp_newton, solver_options
    use ddc_contact_result, only: contact_result
    use ddc_contact_formulation, only: solve_contact
    use ddc_influence_assembly, only: assemble_influence, row_traction
    use ddc_model_loads, only: resolve_remote_stress
    use ddc_error, only: exit_solver_failure
    use ddc_linalg_lu, only: lu_factor, lu_solve
    use ddc_model_types, only: rigid_joint
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, condition_contact
    use ddc_model_results, only: model_results, state_stick, state_slip, state_open
    use ddc_run_model, only: run_model
    use ddc_history_solve, only: solve_history
    use ddc_test_builders, only: straight_crack, kinked_contact_fault
    implicit none
    private

    public :: collect_strength

    real(wp), parameter :: e_modulus = 50000.0_wp, nu = 0.25_wp, g = e_modulus / 2.5_wp
    !> Tolerance of comparisons of two solves of the same LCP [-]
    real(wp), parameter :: tight = 1.0e-10_wp

contains

    !> Cases of the strength suite.
    subroutine collect_strength(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('tension_below_t_stays_closed', test_below_t), &
                 new_test('tension_above_t_is_coulomb_crack', test_above_t), &
                 new_test('tension_above_apex_opens', test_apex), &
                 new_test('defaults_bit_for_bit', test_defaults), &
                 new_test('peak_not_reached_keeps_cohesion', test_peak_holds), &
                 new_test('slip_drops_to_residual_coulomb_crack', test_residual_uniform), &
                 new_test('strong_patch_fails_progressively', test_progressive), &
                 new_test('kink_newton_equals_lemke', test_kink_methods), &
                 new_test('history_keeps_lost_tensile_strength', test_history_tensile), &
                 new_test('history_keeps_residual_cohesion', test_history_residual), &
                 new_test('weakening_dc0_is_coulomb_mu_dynamic', test_weakening_dc0), &
                 new_test('weakening_fixed_point_newton_lemke', test_weakening_fixed_point), &
                 new_test('weakening_history_accumulates_slip', test_weakening_history), &
                 new_test('weakening_not_converged_names_element', test_weakening_limit), &
                 new_test('joint_slipping_total_dd_is_coulomb', test_joint_slip), &
                 new_test('joint_sticking_is_spring_crack', test_joint_stick), &
                 new_test('stiff_joint_recovers_rigid', test_joint_stiff), &
                 new_test('joint_kink_newton_equals_lemke', test_joint_methods), &
                 new_test('joint_monotonic_path_equals_one_shot', test_joint_history)]
    end subroutine collect_strength

    !> Straight crack of half-length 1, n elements, mu = 0.6, uniform Sf, under syy, sxy.
    function straight_fault(n, sf, syy, sxy) result(model)
        integer, intent(in) :: n
        real(wp), intent(in) :: sf, syy, sxy
        type(model_type) :: model

        model = straight_crack(n, 1.0_wp, 0.0_wp, condition_contact, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%elements%mu = 0.6_wp
        model%elements%sf = sf
        model%syy = syy
        model%sxy = sxy
        model%solver%lcp_method = lcp_lemke
    end function straight_fault

    !> Relative difference of two DD sets, measured against the larger magnitude.
    pure real(wp) function dd_difference(a, b)
        real(wp), intent(in) :: a(:), b(:)

        dd_difference = maxval(abs(a - b)) / max(maxval(abs(a)), maxval(abs(b)), tiny(1.0_wp))
    end function dd_difference

    !> Remote tension 3 below T = 4 (apex Sf/mu = 10): every element stays closed and
    !> carries the tension; T stays in force.
    subroutine test_below_t(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r

        model = straight_fault(40, 6.0_wp, 3.0_wp, 0.0_wp)
        model%elements%tensile_strength = 4.0_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_stick), 40, 'closed, sticking')
        call check(error, maxval(abs(r%elements%dn)), 0.0_wp, 'no opening', abs_tol=0.0_wp)
        call check(error, r%elements%normal_traction(20), 3.0_wp, 'carries the tension', &
                   rel_tol=1.0e-12_wp)
        call check(error, minval(r%elements%tensile_in_force), 4.0_wp, 'T in force', &
                   rel_tol=1.0e-15_wp)
    end subroutine test_below_t

    !> Remote tension 5 above T = 4: the crack opens at T, loses it and opens as the Coulomb
    !> crack (T = 0) does: DDs within 1e-10, a second solve, T lost on every element, and
    !> the centre opening within 0.5 % of 2(1-nu) p a / G.
    subroutine test_above_t(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r, coulomb

        model = straight_fault(100, 6.0_wp, 5.0_wp, 0.0_wp)
        call run_model(model, coulomb, error)
        if (allocated(error)) return
        model%elements%tensile_strength = 4.0_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_open), 100, 'open elements')
        call check(error, r%solver%lcp_solves, 2, 'solves (the second after T was lost)')
        call check(error, dd_difference(r%elements%dn, coulomb%elements%dn), 0.0_wp, &
                   'dn as the Coulomb crack', abs_tol=tight)
        call check(error, maxval(r%elements%tensile_in_force), 0.0_wp, 'T lost', &
                   abs_tol=0.0_wp)
        call check(error, maxval(-r%elements%dn), 2.0_wp * (1.0_wp - nu) * 5.0_wp / g, &
                   'centre opening', rel_tol=5.0e-3_wp)
    end subroutine test_above_t

    !> T = 4 above the apex Sf/mu = 2 (Sf = 1.2): tension 1.5 stays closed, tension 3 opens
    !> (the shear strength vanishes at 2) and the crack opens as the Coulomb crack.
    subroutine test_apex(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r, coulomb

        model = straight_fault(40, 1.2_wp, 1.5_wp, 0.0_wp)
        model%elements%tensile_strength = 4.0_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_open), 0, 'closed below the apex')
        call check(error, minval(r%elements%tensile_in_force), 2.0_wp, 'T capped at the apex', &
                   rel_tol=1.0e-14_wp)
        model%syy = 3.0_wp
        if (allocated(error)) return
        call run_model(model, r, error)
        if (allocated(error)) return
        model%elements%tensile_strength = 0.0_wp
        call run_model(model, coulomb, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_open), 40, 'open above the apex')
        call check(error, dd_difference(r%elements%dn, coulomb%elements%dn), 0.0_wp, &
                   'dn as the Coulomb crack', abs_tol=tight)
    end subroutine test_apex

    !> T = 0 and sf_residual = sf given explicitly solve the kinked fault of the frictional
    !> suite bit for bit as the defaults do, with each method.
    subroutine test_defaults(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r, given
        integer :: method

        do method = 1, 2
            model = kinked_fault()
            if (method == 2) model%solver%lcp_method = lcp_newton
            call run_model(model, r, error)
            if (allocated(error)) return
            model%elements%tensile_strength = 0.0_wp
            model%elements%sf_residual = model%elements%sf
            call run_model(model, given, error)
            if (allocated(error)) return
            call check(error, maxval(abs(r%elements%ds - given%elements%ds)), 0.0_wp, 'ds', &
                       abs_tol=0.0_wp)
            call check(error, maxval(abs(r%elements%dn - given%elements%dn)), 0.0_wp, 'dn', &
                       abs_tol=0.0_wp)
            call check(error, r%solver%lcp_solves, given%solver%lcp_solves, 'solves')
        end do
    end subroutine test_defaults

    !> The paper's loading on a fault of peak cohesion 6 (tau_s = 54.75 > 54.13): it
    !> sticks, so its residual cohesion 0 (which would let it slip) never applies.
    subroutine test_peak_holds(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r

        model = paper_fault(6.0_wp)
        model%elements%sf_residual = 0.0_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_stick), 100, 'sticking elements')
        call check(error, minval(r%elements%sf_in_force), 6.0_wp, 'cohesion intact', &
                   rel_tol=0.0_wp)
    end subroutine test_peak_holds

    !> The paper's test (Sf = 1 slips, dtau = 4.38) with residual cohesion 0: every element
    !> slips and drops its cohesion, and the result is the Coulomb crack with Sf = 0.
    subroutine test_residual_uniform(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r, coulomb

        model = paper_fault(0.0_wp)
        call run_model(model, coulomb, error)
        if (allocated(error)) return
        model%elements%sf = 1.0_wp
        model%elements%sf_residual = 0.0_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_slip), 100, 'slipping elements')
        call check(error, r%solver%lcp_solves, 2, 'solves (the second at residual strength)')
        call check(error, dd_difference(r%elements%ds, coulomb%elements%ds), 0.0_wp, &
                   'ds as the Coulomb crack with Sf = 0', abs_tol=tight)
        call check(error, maxval(r%elements%sf_in_force), 0.0_wp, 'cohesion dropped', &
                   abs_tol=0.0_wp)
    end subroutine test_residual_uniform

    !> The weak patch of SPEC.md 7 (Sf = 0 on |x| < 0.4, 6 beyond, tau = 9, s_n = -10)
    !> slips to a_s = 0.566 with intact strength. With residual cohesion 0 on the strong
    !> part, the elements at the slip front drop theirs, the front moves on, and the whole
    !> fault fails (9 > 6 = mu |s_n|): the Coulomb crack with Sf = 0, over several solves;
    !> the Newton method finds the same states and DDs.
    subroutine test_progressive(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r, coulomb, newton

        model = straight_fault(200, 0.0_wp, -10.0_wp, 9.0_wp)
        call run_model(model, coulomb, error)
        if (allocated(error)) return
        model%elements%sf = merge(0.0_wp, 6.0_wp, abs(model%elements%x_mid) < 0.4_wp)
        model%elements%sf_residual = 0.0_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_slip), 200, 'every element slips')
        call check(error, r%solver%lcp_solves > 2, 'the front moved over several solves')
        call check(error, dd_difference(r%elements%ds, coulomb%elements%ds), 0.0_wp, &
                   'ds as the Coulomb crack with Sf = 0', abs_tol=tight)
        model%solver%lcp_method = lcp_newton
        if (allocated(error)) return
        call run_model(model, newton, error)
        if (allocated(error)) return
        call check(error, all(newton%elements%state == r%elements%state), 'newton states')
        call check(error, dd_difference(newton%elements%ds, r%elements%ds), 0.0_wp, &
                   'newton ds', abs_tol=1.0e-9_wp)
    end subroutine test_progressive

    !> The kinked fault with cohesion 2 (residual 0.5) and T = 1 on the inclined part,
    !> whose far half has less fluid pressure: near the kink it opens (T lost, opening
    !> spreading over several solves), the far half stays closed and keeps T (capped at
    !> the apex 0.5/0.6 once slipped). Newton and Lemke agree on states, DDs and the
    !> strengths in force.
    subroutine test_kink_methods(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: lemke, newton
        real(wp) :: scale

        integer :: i

        model = kinked_fault()
        model%elements%sf = 2.0_wp
        model%elements%sf_residual = 0.5_wp
        model%elements%pressure(46:60) = 12.0_wp
        model%elements%tensile_strength = [(0.0_wp, i = 1, 30), (1.0_wp, i = 1, 30)]
        call run_model(model, lemke, error)
        if (allocated(error)) return
        model%solver%lcp_method = lcp_newton
        call run_model(model, newton, error)
        if (allocated(error)) return
        call check(error, count(lemke%elements%state == state_open) > 0, 'some elements open')
        call check(error, count(lemke%elements%state == state_slip) > 0, 'some elements slip')
        call check(error, count(lemke%elements%tensile_in_force > 0.0_wp) > 0, &
                   'some elements keep T')
        call check(error, all(newton%elements%state == lemke%elements%state), 'states')
        scale = maxval(abs([lemke%elements%ds, lemke%elements%dn]))
        call check(error, maxval(abs(newton%elements%ds - lemke%elements%ds)), 0.0_wp, 'ds', &
                   abs_tol=1.0e-9_wp * scale)
        call check(error, maxval(abs(newton%elements%dn - lemke%elements%dn)), 0.0_wp, 'dn', &
                   abs_tol=1.0e-9_wp * scale)
        call check(error, all(newton%elements%tensile_in_force == lemke%elements%tensile_in_force &
                   .and. newton%elements%sf_in_force == lemke%elements%sf_in_force), &
                   'strengths in force')
    end subroutine test_kink_methods

    !> Remote tension 0 -> 5 -> 3 with T = 4: closed at 3 on the way up, open at 5 (T
    !> lost), and still open at 3 on the way down, as the Coulomb crack (T = 0) at 3.
    subroutine test_history_tensile(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, one_shot
        type(model_results) :: r, coulomb
        integer :: k

        model = straight_fault(40, 6.0_wp, 0.0_wp, 0.0_wp)
        model%elements%tensile_strength = 4.0_wp
        one_shot = model
        call set_path(model, 2, [0.0_wp, 5.0_wp, 3.0_wp], [5, 2])
        call solve_history(model, r, error)
        if (allocated(error)) return
        one_shot%syy = 3.0_wp
        one_shot%elements%tensile_strength = 0.0_wp
        call run_model(one_shot, coulomb, error)
        if (allocated(error)) return
        associate (h => r%history)
            k = 4
            call check(error, h%load(2, k), 3.0_wp, 'syy going up', abs_tol=1.0e-12_wp)
            call check(error, count(h%state(:, k) == state_open), 0, 'closed at 3 going up')
            call check(error, count(h%state(:, 6) == state_open), 40, 'open at 5')
            call check(error, count(h%state(:, 8) == state_open), 40, 'open at 3 going down')
            call check(error, dd_difference(h%dn(:, 8), coulomb%elements%dn), 0.0_wp, &
                       'dn at 3 as the Coulomb crack', abs_tol=tight)
        end associate
        call check(error, maxval(r%elements%tensile_in_force), 0.0_wp, 'T lost', &
                   abs_tol=0.0_wp)
    end subroutine test_history_tensile

    !> SPEC-EARTH 3's cycle sxy 0 -> 10 -> -10 -> 10 (s_n = -10, mu = 0.6) on a fault of
    !> peak cohesion 2 and residual 0: no slip at 7 (below the peak 8) where the Coulomb
    !> fault (Sf = 0) slips; once slipped the fault follows the Coulomb fault's play
    !> operator: the same DDs at the end of the cycle.
    subroutine test_history_residual(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, coulomb_model
        type(model_results) :: r, coulomb

        model = straight_fault(40, 2.0_wp, -10.0_wp, 0.0_wp)
        model%elements%sf_residual = 0.0_wp
        coulomb_model = straight_fault(40, 0.0_wp, -10.0_wp, 0.0_wp)
        call solve_cycles(model, coulomb_model, r, coulomb, error)
        if (allocated(error)) return
        associate (h => r%history, hc => coulomb%history)
            call check(error, h%load(3, 8), 7.0_wp, 'sxy going up', abs_tol=1.0e-12_wp)
            call check(error, maxval(abs(h%ds(:, 8))), 0.0_wp, 'no slip at 7 going up', &
                       abs_tol=0.0_wp)
            call check(error, maxval(abs(hc%ds(:, 8))) > 0.0_wp, 'the Coulomb fault slips at 7')
            call check(error, dd_difference(h%ds(:, 51), hc%ds(:, 51)), 0.0_wp, &
                       'ds at the end of the cycle', abs_tol=tight)
        end associate
        call check(error, maxval(r%elements%sf_in_force), 0.0_wp, 'cohesion dropped', &
                   abs_tol=0.0_wp)
    end subroutine test_history_residual

    !> The paper's test (mu = 0.6, Sf = 1) with mu_dynamic = 0.5 and d_c = 0: every element
    !> slips and drops to 0.5 at once; the result is the Coulomb crack with mu = 0.5.
    subroutine test_weakening_dc0(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r, coulomb

        model = paper_fault(1.0_wp)
        model%elements%mu = 0.5_wp
        call run_model(model, coulomb, error)
        if (allocated(error)) return
        model%elements%mu = 0.6_wp
        model%elements%mu_dynamic = 0.5_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_slip), 100, 'slipping elements')
        call check(error, r%solver%lcp_solves, 2, 'solves (the second at mu_dynamic)')
        call check(error, dd_difference(r%elements%ds, coulomb%elements%ds), 0.0_wp, &
                   'ds as the Coulomb crack with mu = 0.5', abs_tol=tight)
        call check(error, maxval(abs(r%elements%mu_in_force - 0.5_wp)), 0.0_wp, &
                   'friction in force', abs_tol=0.0_wp)
    end subroutine test_weakening_dc0

    !> The paper's test with mu_dynamic = 0.5 over d_c = 4e-4 (slip reaches about 9e-4 at
    !> the centre, less towards the tips): at the fixed point every element's friction is
    !> the law at its own slip, mu - 0.1 min(|Ds| / d_c, 1), within 1e-9; the slip lies
    !> between the Coulomb cracks of mu = 0.6 and 0.5; the Newton method agrees.
    subroutine test_weakening_fixed_point(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r, newton, strong, weak
        real(wp), parameter :: d_c = 4.0e-4_wp
        real(wp), allocatable :: law(:)

        model = paper_fault(1.0_wp)
        call run_model(model, strong, error)
        if (allocated(error)) return
        model%elements%mu = 0.5_wp
        call run_model(model, weak, error)
        if (allocated(error)) return
        model%elements%mu = 0.6_wp
        model%elements%mu_dynamic = 0.5_wp
        model%elements%slip_weakening_distance = d_c
        call run_model(model, r, error)
        if (allocated(error)) return
        law = 0.6_wp - 0.1_wp * min(abs(r%elements%ds) / d_c, 1.0_wp)
        call check(error, maxval(abs(r%elements%mu_in_force - law)), 0.0_wp, &
                   'friction = law at the slip', abs_tol=1.0e-9_wp)
        call check(error, count(r%elements%mu_in_force < 0.5_wp + 1.0e-12_wp) > 0 .and. &
                   count(r%elements%mu_in_force > 0.5_wp + 1.0e-3_wp) > 0, &
                   'fully weakened at the centre, partly towards the tips')
        call check(error, r%solver%lcp_solves > 2, 'a fixed point over several solves')
        call check(error, all(abs(r%elements%ds) >= abs(strong%elements%ds) .and. &
                   abs(r%elements%ds) <= abs(weak%elements%ds)), &
                   'slip between the Coulomb cracks of mu and mu_dynamic')
        model%solver%lcp_method = lcp_newton
        if (allocated(error)) return
        call run_model(model, newton, error)
        if (allocated(error)) return
        call check(error, all(newton%elements%state == r%elements%state), 'newton states')
        call check(error, dd_difference(newton%elements%ds, r%elements%ds), 0.0_wp, &
                   'newton ds', abs_tol=1.0e-9_wp)
    end subroutine test_weakening_fixed_point

    !> Shear cycled 0 -> 10 -> -10 -> 10 (s_n = -10, mu = 0.6, mu_dynamic = 0.3, d_c = 0):
    !> once slipped the fault holds 3 MPa, so at the end (after slipping back and forth)
    !> it has the DDs of the Coulomb fault with mu = 0.3 cycled the same way, and it has
    !> not slipped at 5 (below 6) on the first leg.
    subroutine test_weakening_history(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, coulomb_model
        type(model_results) :: r, coulomb

        model = straight_fault(40, 0.0_wp, -10.0_wp, 0.0_wp)
        model%elements%mu_dynamic = 0.3_wp
        coulomb_model = straight_fault(40, 0.0_wp, -10.0_wp, 0.0_wp)
        coulomb_model%elements%mu = 0.3_wp
        call solve_cycles(model, coulomb_model, r, coulomb, error)
        if (allocated(error)) return
        associate (h => r%history, hc => coulomb%history)
            call check(error, h%load(3, 6), 5.0_wp, 'sxy going up', abs_tol=1.0e-12_wp)
            call check(error, maxval(abs(h%ds(:, 6))), 0.0_wp, 'no slip at 5 going up', &
                       abs_tol=0.0_wp)
            call check(error, dd_difference(h%ds(:, 51), hc%ds(:, 51)), 0.0_wp, &
                       'ds at the end of the cycle', abs_tol=tight)
        end associate
        call check(error, maxval(abs(r%elements%mu_in_force - 0.3_wp)), 0.0_wp, &
                   'friction dropped', abs_tol=0.0_wp)
    end subroutine test_weakening_history

    !> A slip-weakening fixed point that needs more solves than allowed is an error
    !> (exit_solver_failure) naming an element, not a result.
    subroutine test_weakening_limit(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(model_type) :: model
        type(contact_result) :: res
        real(wp), allocatable :: a(:, :), ss(:), sn(:), zero(:)
        integer, allocatable :: rows(:)
        integer :: n

        model = paper_fault(1.0_wp)
        n = model%elements%n
        allocate (a(2 * n, 2 * n), ss(n), sn(n), zero(n))
        zero = 0.0_wp
        rows = spread(row_traction, 1, n)
        call assemble_influence(model%elements, g, nu, rows, rows, a)
        call resolve_remote_stress(model%elements, model%sxx, model%syy, model%sxy, ss, sn)
        call solve_contact(a, ss, sn, model%elements%mu, model%elements%sf, zero, &
                           solver_options(lcp_method=lcp_lemke), res, failure, &
                           mu_dynamic=spread(0.5_wp, 1, n), &
                           slip_weakening_distance=spread(4.0e-4_wp, 1, n), max_solves=3)
        call check(error, allocated(failure), 'an error')
        if (allocated(error)) return
        call check(error, failure%code, exit_solver_failure, 'exit code')
        call check(error, index(failure%message, 'no quasi-static solution') > 0 .and. &
                   index(failure%message, 'friction of element') > 0, failure%message)
    end subroutine test_weakening_limit

    !> The paper's test (every element slips) with shear stiffness 1e8 MPa/m (normal
    !> rigid): the slipping faces carry tau_s whatever their compliance, so the total DDs
    !> are those of the Coulomb crack (1e-10); the plastic slip is smaller by tau_s / k_s
    !> (5e-7 m, 0.15 % of the peak slip; a softer joint sticks near the tips).
    subroutine test_joint_slip(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r, coulomb

        model = paper_fault(1.0_wp)
        call run_model(model, coulomb, error)
        if (allocated(error)) return
        model%elements%shear_stiffness = 1.0e8_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_slip), 100, 'slipping elements')
        call check(error, dd_difference(r%elements%ds, coulomb%elements%ds), 0.0_wp, &
                   'total ds as the Coulomb crack', abs_tol=tight)
        call check(error, maxval(abs(r%elements%dn)), 0.0_wp, 'rigid normal', abs_tol=0.0_wp)
    end subroutine test_joint_slip

    !> A sticking joint (mu = 5) of shear stiffness k = 2e5 MPa/m under the paper's loading:
    !> its faces are springs, s_s = -k Ds, so Ds solves (A_ss + k I) Ds = -s_r (an
    !> independent LU solve) within 1e-10; with kn = 5e5 MPa/m Dn solves the normal block
    !> likewise (the straight crack decouples the blocks).
    subroutine test_joint_stick(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        real(wp), allocatable :: a(:, :), ss(:), sn(:), b(:, :)
        integer, allocatable :: rows(:), ipiv(:)
        integer :: n, i

        model = paper_fault(1.0_wp)
        model%elements%mu = 5.0_wp
        model%elements%shear_stiffness = 2.0e5_wp
        model%elements%normal_stiffness = 5.0e5_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_stick), 100, 'sticking elements')
        n = model%elements%n
        allocate (a(2 * n, 2 * n), ss(n), sn(n), ipiv(2 * n))
        rows = spread(row_traction, 1, n)
        call assemble_influence(model%elements, g, nu, rows, rows, a)
        call resolve_remote_stress(model%elements, model%sxx, model%syy, model%sxy, ss, sn)
        do i = 1, n
            a(i, i) = a(i, i) + 2.0e5_wp
            a(n + i, n + i) = a(n + i, n + i) + 5.0e5_wp
        end do
        b = reshape(-[ss, sn], [2 * n, 1])
        if (allocated(error)) return
        call lu_factor(a, ipiv, 'spring crack', error)
        if (allocated(error)) return
        call lu_solve(a, ipiv, b)
        call check(error, dd_difference(r%elements%ds, b(1:n, 1)), 0.0_wp, 'ds', abs_tol=tight)
        call check(error, dd_difference(r%elements%dn, b(n + 1:, 1)), 0.0_wp, 'dn', &
                   abs_tol=tight)
        call check(error, minval(r%elements%dn) > 0.0_wp, 'the compressed joint overlaps')
    end subroutine test_joint_stick

    !> Stiffness 1e15 MPa/m (A_ii about 1e6 here) recovers the rigid kinked fault: the same
    !> states and DDs within 1e-8.
    subroutine test_joint_stiff(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: rigid, stiff

        model = kinked_fault()
        call run_model(model, rigid, error)
        if (allocated(error)) return
        model%elements%shear_stiffness = 1.0e15_wp
        model%elements%normal_stiffness = 1.0e15_wp
        call run_model(model, stiff, error)
        if (allocated(error)) return
        call check(error, all(stiff%elements%state == rigid%elements%state), 'states')
        call check(error, dd_difference([stiff%elements%ds, stiff%elements%dn], &
                   [rigid%elements%ds, rigid%elements%dn]), 0.0_wp, 'DDs', abs_tol=1.0e-8_wp)
    end subroutine test_joint_stiff

    !> The kinked fault with joints of stiffness 2e5 (shear) and 1e6 (normal) MPa/m on the
    !> flat part (rigid elsewhere): stick, slip and open at once; Newton agrees with Lemke.
    subroutine test_joint_methods(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: lemke, newton
        real(wp) :: scale

        model = kinked_fault()
        model%elements%shear_stiffness = merge(2.0e5_wp, rigid_joint, &
                                               model%elements%y_mid < 1.0e-12_wp)
        model%elements%normal_stiffness = merge(1.0e6_wp, rigid_joint, &
                                                model%elements%y_mid < 1.0e-12_wp)
        call run_model(model, lemke, error)
        if (allocated(error)) return
        model%solver%lcp_method = lcp_newton
        call run_model(model, newton, error)
        if (allocated(error)) return
        call check(error, count(lemke%elements%state == state_stick) > 0 .and. &
                   count(lemke%elements%state == state_slip) > 0 .and. &
                   count(lemke%elements%state == state_open) > 0, 'stick, slip and open')
        call check(error, all(newton%elements%state == lemke%elements%state), 'states')
        scale = maxval(abs([lemke%elements%ds, lemke%elements%dn]))
        call check(error, maxval(abs(newton%elements%ds - lemke%elements%ds)), 0.0_wp, 'ds', &
                   abs_tol=1.0e-9_wp * scale)
        call check(error, maxval(abs(newton%elements%dn - lemke%elements%dn)), 0.0_wp, 'dn', &
                   abs_tol=1.0e-9_wp * scale)
    end subroutine test_joint_methods

    !> The paper's fault with joints (k_s = 1e5, k_n = 1e6 MPa/m) loaded along a path of
    !> sxy 0 -> 54.13 in 10 steps ends where the one-shot solve at 54.13 is (1e-9): the
    !> history holds the plastic slip, and outputs the total DDs.
    subroutine test_joint_history(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, one_shot
        type(model_results) :: r, direct

        model = paper_fault(1.0_wp)
        model%elements%shear_stiffness = 1.0e5_wp
        model%elements%normal_stiffness = 1.0e6_wp
        one_shot = model
        call run_model(one_shot, direct, error)
        if (allocated(error)) return
        call set_path(model, 3, [0.0_wp, 54.13_wp], [10])
        call solve_history(model, r, error)
        if (allocated(error)) return
        call check(error, all(r%elements%state == direct%elements%state), 'states')
        call check(error, dd_difference(r%elements%ds, direct%elements%ds), 0.0_wp, 'ds', &
                   abs_tol=1.0e-9_wp)
        call check(error, dd_difference(r%elements%dn, direct%elements%dn), 0.0_wp, 'dn', &
                   abs_tol=1.0e-9_wp)
    end subroutine test_joint_history

    !> Both models along SPEC-EARTH 3's cycle of sxy, 0 -> 10 -> -10 -> 10 (steps of 1).
    subroutine solve_cycles(model, coulomb_model, r, coulomb, error)
        type(model_type), intent(inout) :: model, coulomb_model
        type(model_results), intent(out) :: r, coulomb
        type(error_type), allocatable, intent(out) :: error

        call set_path(model, 3, [0.0_wp, 10.0_wp, -10.0_wp, 10.0_wp], [10, 20, 20])
        call set_path(coulomb_model, 3, [0.0_wp, 10.0_wp, -10.0_wp, 10.0_wp], [10, 20, 20])
        call solve_history(model, r, error)
        if (allocated(error)) return
        call solve_history(coulomb_model, coulomb, error)
    end subroutine solve_cycles

    !> A path of remote stress component q (2 syy, 3 sxy) through the given vertices.
    subroutine set_path(model, q, values, steps)
        type(model_type), intent(inout) :: model
        integer, intent(in) :: q
        real(wp), intent(in) :: values(:)
        integer, intent(in) :: steps(:)
        integer :: i

        allocate (model%load_path%vertex(7, size(values)))
        do i = 1, size(values)
            model%load_path%vertex(:, i) = [model%sxx, model%syy, model%sxy, 0.0_wp, 0.0_wp, &
                                            0.0_wp, 0.0_wp]
            model%load_path%vertex(q, i) = values(i)
        end do
        model%load_path%steps = steps
        model%load_path%varies = .false.
        model%load_path%varies(q) = .true.
    end subroutine set_path

    !> The paper's fault (100 elements, mu = 0.6) and loading with cohesion sf.
    function paper_fault(sf) result(model)
        real(wp), intent(in) :: sf
        type(model_type) :: model

        model = straight_fault(100, sf, -81.25_wp, 54.13_wp)
        model%sxx = -143.75_wp
    end function paper_fault

    !> The frictional suite's kinked fault: stick, slip and open at once (Lemke).
    function kinked_fault() result(model)
        type(model_type) :: model

        model = kinked_contact_fault()
        model%solver%lcp_method = lcp_lemke
    end function kinked_fault

end module test_strength
