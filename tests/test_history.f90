!> Loading history (SPEC-EARTH section 3): the play operator on a straight crack, monotonic
!> paths against one-shot solves, unloading and reloading on the weak-patch fault, the
!> certificate of every step, a failing step, and the &load_path reader.
module test_history
    use ddc_kinds, only: wp
    use ddc_contact_options, only: lcp_lemke, lcp_newton
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_error, only: exit_solver_failure, exit_bad_input
    use ddc_model_types, only: model_type, condition_contact, condition_traction
    use ddc_model_results, only: model_results, state_stick, state_slip
    use ddc_run_model, only: run_model
    use ddc_history_solve, only: solve_history
    use ddc_input_namelist, only: read_namelist_model
    use ddc_test_builders, only: straight_crack, polyline_model
    use ddc_constants, only: pi
    use ddc_contact_lemke, only: solve_lcp_lemke
    implicit none
    private

    public :: collect_history

    real(wp), parameter :: e_modulus = 50000.0_wp, nu = 0.25_wp
    !> Tolerance of the comparisons with the play operator and with one-shot solves
    real(wp), parameter :: tight = 1.0e-10_wp
    character(len=*), parameter :: data_dir = 'data/history/'

contains

    !> Cases of the history suite.
    subroutine collect_history(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('play_operator_n200', test_play_operator), &
                 new_test('monotonic_path_equals_one_shot_straight', test_monotonic_straight), &
                 new_test('monotonic_path_equals_one_shot_weak_patch', test_monotonic_patch), &
                 new_test('reloading_restores_loaded_state_weak_patch', test_reload_patch), &
                 new_test('failing_step_is_named', test_failing_step), &
                 new_test('lemke_warm_start', test_lemke_warm_start), &
                 new_test('play_operator_newton_equals_lemke', test_play_newton), &
                 new_test('kinked_pore_pressure_newton_equals_lemke', test_kinked_newton), &
                 new_test('weak_patch_growth_low_rank_updates', test_patch_updates), &
                 new_test('newton_failure_falls_back_to_lemke', test_step_fallback), &
                 new_test('per_step_tractions_and_k', test_step_tractions), &
                 new_test('load_path_input_good', test_input_good), &
                 new_test('load_path_input_bad', test_input_bad)]
    end subroutine collect_history

    !> A path of remote shear sxy through the given vertices, steps per leg.
    subroutine set_shear_path(model, sxy, steps)
        type(model_type), intent(inout) :: model
        real(wp), intent(in) :: sxy(:)
        integer, intent(in) :: steps(:)
        integer :: i

        allocate (model%load_path%vertex(7, size(sxy)))
        do i = 1, size(sxy)
            model%load_path%vertex(:, i) = [model%sxx, model%syy, sxy(i), 0.0_wp, 0.0_wp, &
                                            0.0_wp, 0.0_wp]
        end do
        model%load_path%steps = steps
        model%load_path%varies = .false.
        model%load_path%varies(3) = .true.
    end subroutine set_shear_path

    !> Straight fault of half-length 1 under s_n = -10, mu = 0.6, uniform Sf.
    function straight_fault(n, sf) result(model)
        integer, intent(in) :: n
        real(wp), intent(in) :: sf
        type(model_type) :: model

        model = straight_crack(n, 1.0_wp, 0.0_wp, condition_contact, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%elements%mu = 0.6_wp
        model%elements%sf = sf
        model%syy = -10.0_wp
        model%solver%lcp_method = lcp_lemke
    end function straight_fault

    !> The weak patch of SPEC.md 7: Sf = 0 for |x| < 0.4, Sf = 6 beyond.
    function weak_patch_fault(n) result(model)
        integer, intent(in) :: n
        type(model_type) :: model

        model = straight_fault(n, 0.0_wp)
        model%elements%sf = merge(0.0_wp, 6.0_wp, abs(model%elements%x_mid) < 0.4_wp)
    end function weak_patch_fault

    !> Relative difference of two DD sets, measured against the larger magnitude.
    pure real(wp) function dd_difference(a, b)
        real(wp), intent(in) :: a(:), b(:)

        dd_difference = maxval(abs(a - b)) / max(maxval(abs(a)), maxval(abs(b)), tiny(1.0_wp))
    end function dd_difference

    !> SPEC-EARTH 3: N = 200, a = 1, s_n = -10, mu = 0.6, Sf = 0, sxy 0 -> 10 -> -10 -> 10
    !> in 0.5 steps. Every step is y_k times the discrete unit-drop profile (the same mesh,
    !> traction-free, unit remote shear) within 1e-10 of the peak, with the play operator
    !> y_k = max(tau_k - 6, min(tau_k + 6, y_(k-1))); no slip before 6; the plateau from
    !> 10 down to -2 sticks; centre slip 3.0075e-4 at 10; the certificate of every step
    !> passes and /elements equal the last step.
    subroutine test_play_operator(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, unit_drop
        type(model_results) :: r, u
        real(wp), parameter :: tau_s = 6.0_wp
        real(wp), allocatable :: tau(:)
        real(wp) :: y, worst, scale
        integer :: k, nsteps, peak

        model = straight_fault(200, 0.0_wp)
        call set_shear_path(model, [0.0_wp, 10.0_wp, -10.0_wp, 10.0_wp], [20, 40, 40])
        call solve_history(model, r, error)
        if (allocated(error)) return
        unit_drop = straight_crack(200, 1.0_wp, 0.0_wp, condition_traction, 0.0_wp, 0.0_wp, &
                                   e_modulus, nu)
        unit_drop%sxy = 1.0_wp
        call run_model(unit_drop, u, error)
        if (allocated(error)) return

        associate (h => r%history)
            nsteps = size(h%ds, 2)
            call check(error, nsteps, 101, 'steps (start + 100 increments)')
            tau = h%load(3, :)
            scale = maxval(abs(u%elements%ds))
            y = 0.0_wp
            worst = 0.0_wp
            do k = 1, nsteps
                y = max(tau(k) - tau_s, min(tau(k) + tau_s, y))
                worst = max(worst, maxval(abs(h%ds(:, k) - y * u%elements%ds)) / &
                            (max(abs(y), 1.0_wp) * scale))
                if (abs(tau(k)) < tau_s) then
                    if (k <= 20) call check(error, all(h%state(:, k) == state_stick), &
                        'stick before 6 MPa')
                end if
            end do
            write (*, '(a,es10.3)') '    play operator: worst relative error over all steps ', &
                worst
            call check(error, worst, 0.0_wp, 'every step against the play operator', &
                       abs_tol=tight)
            ! Exactly zero by construction: no slip increment is basic while the fault sticks.
            call check(error, maxval(abs(h%ds(:, 1:13))), 0.0_wp, 'no slip up to 6 MPa', &
                       abs_tol=0.0_wp)
            call check(error, all(h%state(:, 14) == state_slip), 'every element slips at 6.5')
            peak = 100
            call check(error, -h%ds(peak, 21), 3.0075e-4_wp, 'centre slip at 10 MPa', &
                       rel_tol=1.0e-4_wp)
            ! Unloading from 10 (step 21) down to -1.5 (step 44): every element sticks with
            ! the slip of step 21; the state at -2 (step 45) is on the friction limit.
            do k = 22, 44
                call check(error, all(h%state(:, k) == state_stick), 'plateau sticks')
                call check(error, dd_difference(h%ds(:, k), h%ds(:, 21)), 0.0_wp, &
                           'plateau slip', abs_tol=tight)
            end do
            call check(error, abs(tau(41)) < epsilon(1.0_wp) .and. &
                       maxval(abs(h%ds(:, 41))) > 0.0_wp, 'residual slip at zero load')
            call check(error, size(h%certificate_max_complementarity), nsteps, &
                       'certificate per step')
            call check(error, maxval(h%certificate_max_complementarity) <= &
                       r%solver%certificate_tolerance .and. minval(h%certificate_min_z) >= &
                       -r%solver%certificate_tolerance .and. minval(h%certificate_min_w) >= &
                       -r%solver%certificate_tolerance, 'certificate of every step passed')
            write (*, '(a,es10.3,a,i0)') '    largest complementarity ', &
                maxval(h%certificate_max_complementarity), ', total pivots ', sum(h%pivots)
            call check(error, maxval(h%equilibrium_residual) <= 1.0e-8_wp, &
                       'equilibrium of every step')
            call check(error, count(h%pivots > 0) < nsteps / 4, &
                       'the previous basis serves most steps (warm start)')
            ! The same values copied: exact.
            call check(error, maxval(abs(r%elements%ds - h%ds(:, nsteps))), 0.0_wp, &
                       '/elements hold the last step', abs_tol=0.0_wp)
            call check(error, model%sxy, 10.0_wp, 'the model is left at the last load', &
                       abs_tol=0.0_wp)
        end associate
    end subroutine test_play_operator

    !> One model along sxy 0 -> 9 in k steps and in one shot: the same DDs within 1e-10.
    subroutine check_monotonic(error, model, steps, label)
        type(error_type), allocatable, intent(inout) :: error
        type(model_type), intent(in) :: model
        integer, intent(in) :: steps
        character(len=*), intent(in) :: label
        type(model_type) :: path_model, one_shot
        type(model_results) :: r, s
        real(wp) :: diff

        path_model = model
        call set_shear_path(path_model, [0.0_wp, 9.0_wp], [steps])
        call solve_history(path_model, r, error)
        if (allocated(error)) return
        one_shot = model
        one_shot%sxy = 9.0_wp
        call run_model(one_shot, s, error)
        if (allocated(error)) return
        diff = max(dd_difference(r%elements%ds, s%elements%ds), &
                   dd_difference(r%elements%dn, s%elements%dn))
        write (*, '(a,es10.3)') '    '//label//': path against one shot ', diff
        call check(error, diff, 0.0_wp, label//': DDs', abs_tol=tight)
        call check(error, all(r%elements%state == s%elements%state), label//': states')
    end subroutine check_monotonic

    !> Straight fault, Sf = 1: 9 increments against one shot.
    subroutine test_monotonic_straight(error)
        type(error_type), allocatable, intent(out) :: error

        call check_monotonic(error, straight_fault(100, 1.0_wp), 9, 'straight fault')
    end subroutine test_monotonic_straight

    !> Weak-patch fault (N = 200): 9 increments against one shot.
    subroutine test_monotonic_patch(error)
        type(error_type), allocatable, intent(out) :: error

        call check_monotonic(error, weak_patch_fault(200), 9, 'weak patch')
    end subroutine test_monotonic_patch

    !> Weak patch: 0 -> 9 -> 6 -> 9; unloading by 3 sticks everywhere and reloading by 3
    !> restores the loaded state within 1e-10.
    subroutine test_reload_patch(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        real(wp) :: diff
        integer :: k

        model = weak_patch_fault(200)
        call set_shear_path(model, [0.0_wp, 9.0_wp, 6.0_wp, 9.0_wp], [6, 3, 3])
        call solve_history(model, r, error)
        if (allocated(error)) return
        associate (h => r%history)
            k = size(h%ds, 2)
            call check(error, k, 13, 'steps')
            call check(error, count(h%state(:, 7) == state_slip) > 0, 'slip at 9')
            call check(error, all(h%state(:, 8:9) == state_stick), 'unloading sticks')
            diff = max(dd_difference(h%ds(:, k), h%ds(:, 7)), &
                       dd_difference(h%dn(:, k), h%dn(:, 7)))
            write (*, '(a,es10.3)') '    reloaded against loaded ', diff
            call check(error, diff, 0.0_wp, 'reloaded state = loaded state', abs_tol=tight)
            call check(error, all(h%state(:, k) == h%state(:, 7)), 'states restored')
            call check(error, dd_difference(h%ds(:, 10), h%ds(:, 7)), 0.0_wp, &
                       'unloaded slip = loaded slip', abs_tol=tight)
        end associate
    end subroutine test_reload_patch

    !> A pivot limit that a later step needs more than: the error names that step, has the
    !> solver's exit code and no results are returned as complete.
    subroutine test_failing_step(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, base
        type(model_results) :: r
        type(error_type), allocatable :: step_error
        integer, parameter :: limit = 150
        integer :: k
        character(len=40) :: expected

        ! Start unloaded (q = 0: no pivots), compress, then shear to slip.
        base = straight_fault(100, 0.0_wp)
        base%syy = 0.0_wp
        call set_shear_path(base, [0.0_wp, 0.0_wp, 10.0_wp], [1, 20])
        base%load_path%vertex(2, 2:) = -10.0_wp
        base%load_path%varies(2) = .true.
        model = base
        call solve_history(model, r, error)
        if (allocated(error)) return
        k = findloc(r%history%pivots > limit, .true., 1)
        call check(error, k > 1, 'a later step needs more pivots than the limit')
        if (allocated(error)) return
        write (expected, '(a,i0,a,i0)') 'step ', k, ' of ', size(r%history%pivots)
        model = base
        call solve_history(model, r, step_error, max_pivots=limit)
        call check(error, allocated(step_error), 'the step fails')
        if (allocated(error)) return
        write (*, '(a)') '    '//step_error%message
        call check(error, step_error%code, exit_solver_failure, 'exit code')
        call check(error, index(step_error%message, trim(expected)) > 0, &
                   'message names '//trim(expected)//': '//step_error%message)
        call check(error, .not. allocated(r%history%ds), 'no history returned')
    end subroutine test_failing_step

    !> Lemke's warm start on a P-matrix LCP: the final basis of one q serves a nearby q
    !> with 0 pivots and the same solution as a cold start; a basis infeasible for the new
    !> q (or not complementary) falls back to the cold start.
    subroutine test_lemke_warm_start(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: m(3, 3), q(3), z(3), w(3), zc(3), wc(3)
        integer :: basis(3), next(3), pivots

        m = reshape([4.0_wp, 1.0_wp, 0.5_wp, 1.0_wp, 3.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, &
                     2.0_wp], [3, 3])
        q = [-1.0_wp, 2.0_wp, -3.0_wp]
        call solve_lcp_lemke(m, q, z, w, pivots, error, basis=basis)
        if (allocated(error)) return
        call check(error, pivots > 0, 'cold start pivots')
        q = [-1.2_wp, 2.1_wp, -2.9_wp]
        if (allocated(error)) return
        call solve_lcp_lemke(m, q, zc, wc, pivots, error)
        if (allocated(error)) return
        call solve_lcp_lemke(m, q, z, w, pivots, error, warm_basis=basis, basis=next)
        if (allocated(error)) return
        call check(error, pivots, 0, 'warm start pivots')
        call check(error, maxval(abs(z - zc)) + maxval(abs(w - wc)), 0.0_wp, &
                   'warm = cold solution', abs_tol=1.0e-14_wp)
        call check(error, all(next == basis), 'the basis is returned')
        q = [1.0_wp, -2.0_wp, 3.0_wp]
        if (allocated(error)) return
        call solve_lcp_lemke(m, q, zc, wc, pivots, error)
        if (allocated(error)) return
        call solve_lcp_lemke(m, q, z, w, pivots, error, warm_basis=basis)
        if (allocated(error)) return
        call check(error, pivots > 0, 'infeasible basis: cold start')
        call check(error, maxval(abs(z - zc)), 0.0_wp, 'same solution', abs_tol=1.0e-14_wp)
        call solve_lcp_lemke(m, q, z, w, pivots, error, warm_basis=[1, 4, 2])
        if (allocated(error)) return
        call check(error, pivots > 0, 'non-complementary basis: cold start')
    end subroutine test_lemke_warm_start

    !> A pore-pressure cycle read from a file: 15 steps, p0 varies, sxy ramps then holds.
    subroutine test_input_good(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        type(error_type), allocatable :: read_error

        call read_namelist_model(data_dir//'good.nml', model, read_error)
        if (allocated(read_error)) then
            call check(error, .false., 'good.nml rejected: '//read_error%message)
            return
        end if
        call check(error, all(model%load_path%varies .eqv. [.false., .false., .true., &
                   .false., .false., .false., .true.]), 'sxy and p0 vary')
        call check(error, maxval(abs(model%load_path%vertex(2, :) + 10.0_wp)), 0.0_wp, &
                   'syy held at its &remote_stress value', abs_tol=0.0_wp)
        if (allocated(error)) return
        call solve_history(model, r, error)
        if (allocated(error)) return
        call check(error, size(r%history%ds, 2), 15, 'steps')
        call check(error, r%history%load(7, 10), 5.0_wp, 'p0 at the top of the cycle', &
                   abs_tol=0.0_wp)
        ! s_n' = -10 + 5 = -5 at p0 = 5: tau_s = 3 < 4, the fault slips; before, it sticks.
        call check(error, all(r%history%state(:, 5) == state_stick), 'sticks at p0 = 0')
        call check(error, all(r%history%state(:, 10) == state_slip), 'slips at p0 = 5')
        call check(error, maxval(abs(r%history%ds(:, 15))) > 0.0_wp, &
                   'slip kept after the pressure drops')
    end subroutine test_input_good

    !> Bad &load_path groups: exit_bad_input, the file, the group and the variable named.
    subroutine test_input_bad(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad(error, 'bad_counts.nml', [character(len=60) :: '&load_path', &
            'steps(2) must be at least 1', 'sxy has 3 values', 'p0 has 2 values'])
        call check_bad(error, 'bad_no_steps.nml', [character(len=60) :: 'steps is required'])
        call check_bad(error, 'bad_no_contact.nml', [character(len=60) :: &
            'a load path needs contact elements', 'at least one of sxx'])
        call check_bad(error, 'bad_malformed.nml', [character(len=60) :: '&load_path', 'sxz'])
    end subroutine test_input_bad

    !> Solve a history with Lemke and with Newton: every step solved by the method asked
    !> (no fallback), the same states at every step, DDs within 1e-10 of the largest.
    subroutine compare_methods(model, label, lemke, newton, error)
        type(model_type), intent(in) :: model
        character(len=*), intent(in) :: label
        type(model_results), intent(out) :: lemke, newton
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: m
        real(wp) :: diff

        m = model
        m%solver%lcp_method = lcp_lemke
        call solve_history(m, lemke, error)
        if (allocated(error)) return
        m = model
        m%solver%lcp_method = lcp_newton
        call solve_history(m, newton, error)
        if (allocated(error)) return
        call check(error, all(lemke%history%method == 'lemke'), label//': Lemke every step')
        call check(error, all(newton%history%method == 'newton'), label// &
                   ': Newton every step, no fallback: '//newton%solver%fallback)
        call check(error, all(newton%history%state == lemke%history%state), &
                   label//': the same states at every step')
        diff = max(dd_difference(reshape(newton%history%ds, [size(newton%history%ds)]), &
                                 reshape(lemke%history%ds, [size(lemke%history%ds)])), &
                   dd_difference(reshape(newton%history%dn, [size(newton%history%dn)]), &
                                 reshape(lemke%history%dn, [size(lemke%history%dn)])))
        write (*, '(a,es10.3,a,4(i0,a))') '    '//label//': Newton against Lemke ', diff, &
            ' (factorizations ', newton%solver%counts%factorizations, ', low-rank updates ', &
            newton%solver%counts%updates, ', reuses ', newton%solver%counts%reuses, &
            ', pivots ', lemke%solver%pivots, ')'
        call check(error, diff, 0.0_wp, label//': DDs of every step', abs_tol=tight)
    end subroutine compare_methods

    !> The play-operator path by Newton equals Lemke's; the Newton method factorizes only
    !> where the slip starts (each sense once) and reuses the factors at every other
    !> slipping step (the steps where every element sticks have no unknown to solve for).
    subroutine test_play_newton(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: lemke, newton

        model = straight_fault(200, 0.0_wp)
        call set_shear_path(model, [0.0_wp, 10.0_wp, -10.0_wp, 10.0_wp], [20, 40, 40])
        call compare_methods(model, 'play operator', lemke, newton, error)
        if (allocated(error)) return
        call check(error, newton%solver%counts%factorizations <= 4, 'a few factorizations')
        call check(error, newton%solver%counts%reuses >= 30, &
                   'the factors of unchanged states reused')
        call check(error, newton%solver%pivots, 0, 'no Lemke pivot')
    end subroutine test_play_newton

    !> The kinked fault under pore-pressure cycles (input/kinked_fault_pore_pressure_cycle):
    !> slip couples to normal stress; Newton equals Lemke at every step.
    subroutine test_kinked_newton(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: lemke, newton
        real(wp), parameter :: b = 35.0_wp * pi / 180.0_wp
        real(wp), parameter :: p0(5) = [0.0_wp, 16.0_wp, 0.0_wp, 20.0_wp, 0.0_wp]
        integer :: i

        model = polyline_model([-1.0_wp, 0.0_wp, cos(b)], [0.0_wp, 0.0_wp, sin(b)], &
                               [40, 40], condition_contact, 0.0_wp, 0.0_wp, e_modulus, nu)
        model%elements%mu = 0.6_wp
        model%sxx = -20.0_wp
        model%syy = -30.0_wp
        model%sxy = 10.0_wp
        allocate (model%load_path%vertex(7, 5))
        do i = 1, 5
            model%load_path%vertex(:, i) = [model%sxx, model%syy, model%sxy, 0.0_wp, 0.0_wp, &
                                            0.0_wp, p0(i)]
        end do
        model%load_path%steps = [16, 16, 20, 20]
        model%load_path%varies = .false.
        model%load_path%varies(7) = .true.
        call compare_methods(model, 'kinked fault, pore pressure', lemke, newton, error)
        if (allocated(error)) return
        call check(error, count(lemke%history%state == state_slip) > 0 .and. &
                   count(lemke%history%state == state_stick) > 0, 'stick and slip seen')
    end subroutine test_kinked_newton

    !> The weak patch loaded slowly: the slip zone grows by a few elements per step, which
    !> the Newton method follows by low-rank updates of its factors, not new ones; the same
    !> states and DDs as Lemke.
    subroutine test_patch_updates(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: lemke, newton

        model = weak_patch_fault(200)
        model%elements%sf = 6.0_wp * max(0.0_wp, min(1.0_wp, (abs(model%elements%x_mid) - &
                                                              0.2_wp) / 0.6_wp))
        call set_shear_path(model, [0.0_wp, 9.0_wp], [30])
        call compare_methods(model, 'graded weak patch', lemke, newton, error)
        if (allocated(error)) return
        call check(error, newton%solver%counts%updates > 5, 'low-rank updates')
        call check(error, newton%solver%counts%factorizations < newton%solver%counts%updates, &
                   'fewer new factorizations than updates')
    end subroutine test_patch_updates

    !> With one Newton iteration allowed, every step whose states change falls back to Lemke
    !> (recorded per step and in the solver record) and the history is Lemke's.
    subroutine test_step_fallback(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: lemke, mixed
        integer :: k, fallbacks
        real(wp) :: diff

        model = straight_fault(100, 0.0_wp)
        call set_shear_path(model, [0.0_wp, 10.0_wp, -10.0_wp], [10, 20])
        call solve_history(model, lemke, error)
        if (allocated(error)) return
        model = straight_fault(100, 0.0_wp)
        call set_shear_path(model, [0.0_wp, 10.0_wp, -10.0_wp], [10, 20])
        model%solver%lcp_method = lcp_newton
        call solve_history(model, mixed, error, max_iterations=1)
        if (allocated(error)) return
        fallbacks = 0
        do k = 1, size(mixed%history%method)
            if (mixed%history%method(k) == 'lemke') then
                fallbacks = fallbacks + 1
                call check(error, index(mixed%history%fallback(k), &
                           'no convergence within 1 iterations') > 0, 'reason of the fallback')
            else
                call check(error, len_trim(mixed%history%fallback(k)) == 0, 'no reason')
            end if
        end do
        write (*, '(a,i0,a)') '    ', fallbacks, ' steps fell back: '//mixed%solver%fallback
        call check(error, fallbacks > 0 .and. fallbacks < size(mixed%history%method), &
                   'some steps fell back to Lemke, not all')
        call check(error, index(mixed%solver%fallback, 'steps fell back') > 0, &
                   'the solver record says so')
        call check(error, all(mixed%history%state == lemke%history%state), 'states')
        diff = dd_difference(reshape(mixed%history%ds, [size(mixed%history%ds)]), &
                             reshape(lemke%history%ds, [size(lemke%history%ds)]))
        call check(error, diff, 0.0_wp, 'DDs as Lemke', abs_tol=tight)
    end subroutine test_step_fallback

    !> /history tractions and K: the last step's equal /elements and /tips; at every step
    !> the shear traction of a slipping element is on its friction limit and K follows the
    !> tip elements' DDs.
    subroutine test_step_tractions(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        real(wp) :: factor, scale
        integer :: k, nsteps, tip

        model = straight_fault(100, 0.0_wp)
        model%solver%lcp_method = lcp_newton
        call set_shear_path(model, [0.0_wp, 10.0_wp], [10])
        call solve_history(model, r, error)
        if (allocated(error)) return
        associate (h => r%history)
            nsteps = size(h%ds, 2)
            call check(error, size(h%shear_traction, 1), 100, 'tractions of every element')
            call check(error, size(h%k1, 1), r%tips%n, 'K of every tip')
            call check(error, size(h%k2, 2), nsteps, 'K at every step')
            scale = maxval(abs(h%shear_traction))
            call check(error, maxval(abs(h%shear_traction(:, nsteps) - &
                       r%elements%shear_traction)), 0.0_wp, 'last step = /elements', &
                       abs_tol=1.0e-12_wp * scale)
            call check(error, maxval(abs(h%normal_traction(:, nsteps) - &
                       r%elements%normal_traction)), 0.0_wp, 'last step = /elements', &
                       abs_tol=1.0e-12_wp * scale)
            call check(error, maxval(abs(h%k2(:, nsteps) - r%tips%k2)), 0.0_wp, &
                       'last K = /tips', abs_tol=1.0e-12_wp * maxval(abs(r%tips%k2)))
            do k = 1, nsteps
                if (all(h%state(:, k) == state_slip)) call check(error, &
                    maxval(abs(abs(h%shear_traction(:, k)) - 6.0_wp)), 0.0_wp, &
                    'slip on the friction limit (mu 10 MPa)', abs_tol=1.0e-9_wp)
                do tip = 1, r%tips%n
                    factor = -(e_modulus / (2.0_wp * (1.0_wp + nu))) / (2.0_wp * (1.0_wp - nu) &
                        * sqrt(model%elements%half_length(r%tips%element(tip))))
                    call check(error, h%k2(tip, k), factor * h%ds(r%tips%element(tip), k), &
                               'K_II of a tip', rel_tol=1.0e-14_wp, abs_tol=1.0e-300_wp)
                end do
            end do
        end associate
    end subroutine test_step_tractions

    !> Read a bad file: exit_bad_input and every fragment in the message.
    subroutine check_bad(error, file, fragments)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: fragments(:)
        type(model_type) :: model
        type(error_type), allocatable :: read_error
        integer :: i

        call read_namelist_model(data_dir//file, model, read_error)
        call check(error, allocated(read_error), file//' accepted')
        if (allocated(error)) return
        call check(error, read_error%code, exit_bad_input, file//': exit code')
        do i = 1, size(fragments)
            call check(error, index(read_error%message, trim(fragments(i))) > 0, &
                       file//": no '"//trim(fragments(i))//"' in: "//read_error%message)
        end do
    end subroutine check_bad

end module test_history
