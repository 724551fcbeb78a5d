!> Frictional faults solved end to end through run_model (SPEC section 7): the paper's
!> test, a weak patch in a strong fault, fluid pressure, a kinked fault, and a pressurized
!> fracture (TWODD condition) next to a frictional fault.
module test_frictional
    use ddc_kinds, only: wp
    use ddc_contact_options, only: option_code, open_cohesion_names, lcp_lemke, lcp_auto, &
        cohesion_lost
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_error, only: exit_solver_failure
    use ddc_model_types, only: model_type, condition_contact, condition_traction
    use ddc_model_results, only: model_results, state_stick, state_slip, state_open, state_free
    use ddc_run_model, only: run_model
    use ddc_constants, only: pi
    use ddc_test_builders, only: polyline_model, straight_crack, join_fractures, &
                                 kinked_contact_fault
    implicit none
    private

    public :: collect_frictional

    real(wp), parameter :: e_modulus = 50000.0_wp, nu = 0.25_wp, g = e_modulus / 2.5_wp

contains

    !> Cases of the frictional suite.
    subroutine collect_frictional(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('paper_fault_slips_n500', test_paper_slip), &
                 new_test('paper_fault_sticks_mu07', test_paper_stick), &
                 new_test('no_resolved_shear_sticks', test_no_shear), &
                 new_test('weak_patch_n400', test_weak_patch), &
                 new_test('fluid_pressure_opens_cohesion_kept', test_pressure_kept), &
                 new_test('fluid_pressure_opens_cohesion_lost', test_pressure_lost), &
                 new_test('kinked_fault_stick_slip_open', test_kink), &
                 new_test('hydrofracture_next_to_fault', test_mixed), &
                 new_test('acute_branch_lemke_ray_auto_newton', test_acute_branch)]
    end subroutine collect_frictional

    !> The paper's fault: 2 m long, contact with uniform mu and Sf, its remote stress.
    function paper_fault(n, mu, sf) result(model)
        integer, intent(in) :: n
        real(wp), intent(in) :: mu, sf
        type(model_type) :: model

        model = straight_crack(n, 1.0_wp, 0.0_wp, condition_contact, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%elements%mu = mu
        model%elements%sf = sf
        model%sxx = -143.75_wp
        model%syy = -81.25_wp
        model%sxy = 54.13_wp
    end function paper_fault

    !> mu = 0.6, Sf = 1: dtau = 4.38 MPa, every element slips, peak slip within 0.2 % of
    !> 3.285e-4 m and K_II within 0.1 % of 7.763 MPa m^1/2 at both tips.
    subroutine test_paper_slip(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: r

        call run_model(paper_fault(500, 0.6_wp, 1.0_wp), r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_slip), 500, 'slipping elements')
        call check(error, maxval(-r%elements%ds), 3.285e-4_wp, 'peak slip', rel_tol=2.0e-3_wp)
        call check(error, r%tips%k2(1), 7.763_wp, 'K_II left', rel_tol=1.0e-3_wp)
        call check(error, r%tips%k2(2), 7.763_wp, 'K_II right', rel_tol=1.0e-3_wp)
        call check(error, maxval(abs(r%elements%shear_traction - 49.75_wp)), 0.0_wp, &
                   'slip elements carry tau_s = Sf + mu |s_n|', abs_tol=1.0e-9_wp * 49.75_wp)
        call check(error, r%solver%certificate_max_complementarity <= &
                   r%solver%certificate_tolerance, 'certificate recorded and passed')
        call check(error, r%solver%pivots > 0 .or. r%solver%newton_iterations > 0, &
                   'pivots or Newton iterations recorded')
    end subroutine test_paper_slip

    !> mu = 0.7: tau_s = 1 + 0.7 * 81.25 = 57.9 > 54.13, every element sticks, DDs zero.
    subroutine test_paper_stick(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: r

        call run_model(paper_fault(500, 0.7_wp, 1.0_wp), r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_stick), 500, 'sticking elements')
        ! Exactly zero by construction: no DD of a sticking element is an unknown.
        call check(error, maxval(abs(r%elements%ds)), 0.0_wp, 'ds', abs_tol=0.0_wp)
        call check(error, maxval(abs(r%elements%dn)), 0.0_wp, 'dn', abs_tol=0.0_wp)
        call check(error, r%elements%shear_traction(250), 54.13_wp, 'shear traction = remote', &
                   rel_tol=1.0e-12_wp)
    end subroutine test_paper_stick

    !> A fault under principal stresses along its axes carries no shear: every element
    !> sticks, no slip, and the vanishing shear block is no reason to fail the equilibrium
    !> check.
    subroutine test_no_shear(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r

        model = paper_fault(20, 0.6_wp, 0.0_wp)
        model%sxy = 0.0_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_stick), 20, 'sticking elements')
        ! Exactly zero by construction: no DD of a sticking element is an unknown.
        call check(error, maxval(abs(r%elements%ds)), 0.0_wp, 'ds', abs_tol=0.0_wp)
    end subroutine test_no_shear

    !> Weak patch |x| < c = 0.4 (Sf = 0) in a strong fault (Sf = 6), mu = 0.6, s_n = -10,
    !> tau = 9: slip spreads to a_s = c / cos(pi/4) = 0.5657, within one element; elements
    !> beyond stick; slip elements on the strong part carry tau_p = 12; peak slip within
    !> 0.2 % of 1.00996e-4 (N = 400).
    subroutine test_weak_patch(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        real(wp), parameter :: c = 0.4_wp, a_s = c / cos(pi / 4.0_wp), h = 0.005_wp
        real(wp) :: edge
        integer :: i

        model = straight_crack(400, 1.0_wp, 0.0_wp, condition_contact, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%elements%mu = 0.6_wp
        model%elements%sf = merge(0.0_wp, 6.0_wp, abs(model%elements%x_mid) < c)
        model%syy = -10.0_wp
        model%sxy = 9.0_wp
        call run_model(model, r, error)
        if (allocated(error)) return
        associate (e => model%elements, state => r%elements%state)
            edge = maxval(abs(e%x_end), mask=state == state_slip .and. e%x_mid > 0.0_wp)
            call check(error, edge, a_s, 'slip zone edge', abs_tol=h)
            call check(error, all(state == state_stick .eqv. abs(e%x_mid) > edge), &
                       'stick beyond the slip zone, slip inside')
            do i = 1, e%n
                if (state(i) == state_slip .and. abs(e%x_mid(i)) > c) call check(error, &
                    r%elements%shear_traction(i), 12.0_wp, 'tau_p on slipping strong part', &
                    rel_tol=1.0e-9_wp)
            end do
        end associate
        call check(error, maxval(-r%elements%ds), 1.00996e-4_wp, 'peak slip', rel_tol=2.0e-3_wp)
    end subroutine test_weak_patch

    !> Fluid pressure 12 above the normal compression 10: every element opens with
    !> normal traction -p; with cohesion kept the faces carry shear up to Sf = 2.
    function pressurized_fault(cohesion) result(model)
        character(len=*), intent(in) :: cohesion
        type(model_type) :: model

        model = straight_crack(100, 1.0_wp, 0.0_wp, condition_contact, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%elements%mu = 0.6_wp
        model%elements%sf = 2.0_wp
        model%elements%pressure = 12.0_wp
        model%syy = -10.0_wp
        model%sxy = 5.0_wp
        model%solver%open_cohesion = option_code(cohesion, open_cohesion_names)
    end function pressurized_fault

    !> Open elements keep shear strength Sf (the paper's model).
    subroutine test_pressure_kept(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: r

        call run_model(pressurized_fault('kept'), r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_open), 100, 'open elements')
        call check(error, maxval(abs(r%elements%normal_traction + 12.0_wp)), 0.0_wp, &
                   's_n = -p on open faces', abs_tol=1.0e-9_wp * 12.0_wp)
        call check(error, maxval(abs(r%elements%shear_traction - 2.0_wp)), 0.0_wp, &
                   'open faces carry shear Sf', abs_tol=1.0e-9_wp * 12.0_wp)
    end subroutine test_pressure_kept

    !> Open elements lose cohesion and carry no shear.
    subroutine test_pressure_lost(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: r

        call run_model(pressurized_fault('lost'), r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_open), 100, 'open elements')
        call check(error, maxval(abs(r%elements%shear_traction)), 0.0_wp, &
                   'open faces carry no shear', abs_tol=1.0e-9_wp * 12.0_wp)
        call check(error, r%solver%lcp_solves, 2, 'LCP solves (second after cohesion lost)')
    end subroutine test_pressure_lost

    !> The kinked fault of kinked_contact_fault: the flat part is closed and partly sticks,
    !> partly slips; the inclined part opens. Certificate holds.
    subroutine test_kink(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r

        model = kinked_contact_fault()
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%elements%state == state_stick) > 0, 'some elements stick')
        call check(error, count(r%elements%state == state_slip) > 0, 'some elements slip')
        call check(error, count(r%elements%state == state_open) > 0, 'some elements open')
        call check(error, r%solver%certificate_min_z >= -r%solver%certificate_tolerance .and. &
                   r%solver%certificate_min_w >= -r%solver%certificate_tolerance .and. &
                   r%solver%certificate_max_complementarity <= r%solver%certificate_tolerance, &
                   'certificate holds')
        call check(error, r%solver%equilibrium_residual, 0.0_wp, 'equilibrium residual', &
                   abs_tol=1.0e-8_wp)
    end subroutine test_kink

    !> A hydrofracture given as a traction condition (s_n = -p, s_s = 0) beside a frictional
    !> fault, solved by condensation, equals the same model with the hydrofracture as a
    !> frictionless, cohesionless contact fracture under fluid pressure p (which opens
    !> everywhere, so its faces carry exactly -p and no shear), to 1e-8.
    subroutine test_mixed(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: mixed, all_contact
        type(model_results) :: r_mixed, r_contact
        real(wp), parameter :: p = 30.0_wp
        real(wp) :: scale

        mixed = two_fractures(condition_traction, p)
        all_contact = two_fractures(condition_contact, p)
        call run_model(mixed, r_mixed, error)
        if (allocated(error)) return
        call run_model(all_contact, r_contact, error)
        if (allocated(error)) return
        call check(error, all(r_mixed%elements%state(1:40) == state_free), &
                   'hydrofracture elements are free (TWODD condition)')
        call check(error, all(r_contact%elements%state(1:40) == state_open), &
                   'as contact, the hydrofracture opens everywhere')
        call check(error, count(r_mixed%elements%state(41:) == state_slip) > 0, &
                   'the fault slips')
        scale = maxval(abs([r_contact%elements%ds, r_contact%elements%dn]))
        call check(error, maxval(abs(r_mixed%elements%ds - r_contact%elements%ds)), 0.0_wp, &
                   'ds', abs_tol=1.0e-8_wp * scale)
        call check(error, maxval(abs(r_mixed%elements%dn - r_contact%elements%dn)), 0.0_wp, &
                   'dn', abs_tol=1.0e-8_wp * scale)
        call check(error, all(r_mixed%elements%state(41:) == r_contact%elements%state(41:)), &
                   'same fault states')
    end subroutine test_mixed

    !> A branch at 40 degrees below a fault under the paper's loading (84 elements): Lemke
    !> ends on a ray (exit 1); 'auto' then solves it with the Newton method, certified, and
    !> records why.
    subroutine test_acute_branch(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: ray
        type(model_type) :: model, branch
        type(model_results) :: r
        real(wp), parameter :: angle = -40.0_wp * pi / 180.0_wp

        model = polyline_model([-1.0_wp, 0.0_wp, 1.0_wp], [0.0_wp, 0.0_wp, 0.0_wp], [30, 30], &
                               condition_contact, 0.0_wp, 0.0_wp, e_modulus, nu)
        branch = polyline_model([0.0_wp, 0.8_wp * cos(angle)], [0.0_wp, 0.8_wp * sin(angle)], &
                                [24], condition_contact, 0.0_wp, 0.0_wp, e_modulus, nu)
        call join_fractures(model, branch)
        model%elements%mu = 0.6_wp
        model%elements%sf = 1.0_wp
        model%sxx = -143.75_wp
        model%syy = -81.25_wp
        model%sxy = 54.13_wp
        model%solver%lcp_method = lcp_lemke
        call run_model(model, r, ray)
        call check(error, allocated(ray), 'Lemke alone ends on a ray')
        if (allocated(error)) return
        call check(error, ray%code, exit_solver_failure, 'exit code of the ray')
        if (allocated(error)) return
        model%solver%lcp_method = lcp_auto
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, r%solver%method == 'newton', 'the Newton method produced the result')
        call check(error, index(r%solver%fallback, 'Lemke ended on a ray') > 0, &
                   'the reason is recorded')
        call check(error, count(r%elements%state == state_slip) > 0, 'the fault slips')
        call check(error, r%solver%certificate_max_complementarity <= &
                   r%solver%certificate_tolerance, 'certificate')
        if (allocated(error)) return
        ! Fluid pressure 60 opens the branch; with cohesion lost on opening the second
        ! round must stay with the Newton method (Lemke would end on the ray again).
        model%elements%pressure(61:) = 60.0_wp
        model%solver%open_cohesion = cohesion_lost
        call run_model(model, r, error)
        if (allocated(error)) return
        call check(error, r%solver%method == 'newton', 'Newton kept after cohesion was lost')
        call check(error, count(r%elements%state == state_open) > 0, 'the branch opens')
        call check(error, r%solver%lcp_solves >= 2, 'a second round after cohesion was lost')
    end subroutine test_acute_branch

    !> A vertical hydrofracture (40 elements, given condition) above a horizontal frictional
    !> fault (60 elements, mu = 0.6, Sf = 0); sxx = -10, syy = -20, sxy = 13.
    function two_fractures(hydro_condition, p) result(model)
        integer, intent(in) :: hydro_condition
        real(wp), intent(in) :: p
        type(model_type) :: model, fault

        model = polyline_model([0.0_wp, 0.0_wp], [0.3_wp, 1.1_wp], [40], hydro_condition, &
                               0.0_wp, -p, e_modulus, nu)
        if (hydro_condition == condition_contact) model%elements%pressure = p
        fault = polyline_model([-1.0_wp, 1.0_wp], [-0.2_wp, -0.2_wp], [60], condition_contact, &
                               0.0_wp, 0.0_wp, e_modulus, nu)
        fault%elements%mu = 0.6_wp
        call join_fractures(model, fault)
        model%sxx = -10.0_wp
        model%syy = -20.0_wp
        model%sxy = 13.0_wp
    end function two_fractures

end module test_frictional
