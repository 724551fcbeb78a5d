!> Tests of the frictional contact formulation (suite `contact`).
!>
!> Faults come from the test builders (ddc_test_builders) and the influence matrix from
!> ddc_influence_assembly, with every row a traction row.
module test_contact
    use ddc_kinds, only: wp
    use ddc_error, only: exit_solver_failure, exit_bad_input, exit_internal_error
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_constants, only: pi
    use ddc_influence_assembly, only: assemble_influence, row_traction
    use ddc_model_loads, only: resolve_remote_stress
    use ddc_model_types, only: model_type, condition_contact
    use ddc_test_builders, only: polyline_model, join_fractures
    use ddc_model_results, only: state_stick, state_slip, state_open
    use ddc_contact_options, only: solver_options, parse_solver_options, option_code, &
        open_cohesion_names, lcp_lemke
    use ddc_contact_result, only: contact_result
    use ddc_contact_formulation, only: solve_contact
    implicit none
    private
    public :: collect_contact

    !> Directory of the paper's reference case, relative to tests/
    character(len=*), parameter :: ritz_dir = 'reference/ritz2012/R2_straight_n100_mu0.6_sf0/'

    !> The paper's loading (SPEC section 7)
    real(wp), parameter :: youngs = 50000.0_wp, poisson = 0.25_wp
    real(wp), parameter :: paper_sxx = -143.75_wp, paper_syy = -81.25_wp, paper_sxy = 54.13_wp
    !> Loading of the kinked fault: remote stress and fluid pressure
    real(wp), parameter :: kink_sxx = -5.0_wp, kink_syy = -20.0_wp, kink_sxy = 0.5_wp
    real(wp), parameter :: kink_pressure = 17.5_wp

contains

    !> Cases of the contact suite.
    subroutine collect_contact(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [ &
            new_test('straight_all_slip', test_all_slip), &
            new_test('straight_all_stick', test_all_stick), &
            new_test('ritz2012_reference_n100', test_ritz_reference), &
            new_test('fluid_pressure_cohesion_kept', test_pressure_kept), &
            new_test('fluid_pressure_cohesion_lost', test_pressure_lost), &
            new_test('kinked_stick_slip_open', test_kink), &
            new_test('singular_influence_matrix', test_singular), &
            new_test('bad_open_cohesion', test_bad_cohesion), &
            new_test('inconsistent_sizes_are_an_internal_error', test_internal_error) &
            ]
    end subroutine collect_contact

    ! ------------------------------------------------------------------ builders

    !> A contact fault along a polyline: segment k from vertex k to k+1 with counts(k)
    !> equal elements, the paper's elastic constants.
    function contact_fault(x, y, counts) result(model)
        real(wp), intent(in) :: x(:), y(:)
        integer, intent(in) :: counts(:)
        type(model_type) :: model

        model = polyline_model(x, y, counts, condition_contact, 0.0_wp, 0.0_wp, youngs, poisson)
    end function contact_fault

    !> Build A (all rows traction rows) and the resolved remote stress, and solve.
    subroutine solve_model(model, sxx, syy, sxy, mu, sf, p, cohesion, res, error)
        type(model_type), intent(in) :: model
        real(wp), intent(in) :: sxx, syy, sxy, mu(:), sf(:), p(:)
        character(len=*), intent(in) :: cohesion
        type(contact_result), intent(out) :: res
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), ss(:), sn(:)
        integer, allocatable :: rows(:)
        integer :: n

        n = model%elements%n
        allocate (a(2 * n, 2 * n), ss(n), sn(n))
        rows = spread(row_traction, 1, n)
        call assemble_influence(model%elements, &
            shear_modulus(model%youngs_modulus, model%poissons_ratio), model%poissons_ratio, &
            rows, rows, a)
        call resolve_remote_stress(model%elements, sxx, syy, sxy, ss, sn)
        call solve_contact(a, ss, sn, mu, sf, p, solver_options(lcp_method=lcp_lemke, &
            open_cohesion=option_code(cohesion, open_cohesion_names)), res, error)
    end subroutine solve_model

    !> solve_model with the same mu, Sf and fluid pressure on every element.
    subroutine solve_uniform(model, sxx, syy, sxy, mu, sf, p, cohesion, res, error)
        type(model_type), intent(in) :: model
        real(wp), intent(in) :: sxx, syy, sxy, mu, sf, p
        character(len=*), intent(in) :: cohesion
        type(contact_result), intent(out) :: res
        type(error_type), allocatable, intent(out) :: error
        integer :: n

        n = model%elements%n
        call solve_model(model, sxx, syy, sxy, spread(mu, 1, n), spread(sf, 1, n), &
            spread(p, 1, n), cohesion, res, error)
    end subroutine solve_uniform

    pure real(wp) function shear_modulus(e, nu)
        real(wp), intent(in) :: e, nu
        shear_modulus = e / (2.0_wp * (1.0_wp + nu))
    end function shear_modulus

    !> Analytic slip or opening of a crack of half-length c under stress drop dtau:
    !> 2 (1 - nu) dtau / G sqrt(c^2 - x^2).
    elemental real(wp) function crack_profile(x, c, dtau, g, nu)
        real(wp), intent(in) :: x, c, dtau, g, nu
        crack_profile = 2.0_wp * (1.0_wp - nu) * dtau / g * sqrt(c**2 - x**2)
    end function crack_profile

    !> Certificate passed and equilibrium residual small.
    subroutine check_certified(error, res)
        type(error_type), allocatable, intent(inout) :: error
        type(contact_result), intent(in) :: res

        call check(error, res%certificate%passed, 'certificate fails')
        call check(error, res%certificate%min_z >= -1.0e-10_wp, 'scaled min z < -1e-10')
        call check(error, res%certificate%min_w >= -1.0e-10_wp, 'scaled min w < -1e-10')
        call check(error, res%certificate%max_complementarity, 0.0_wp, &
            'scaled complementarity', abs_tol=1.0e-10_wp)
        call check(error, maxval(res%equilibrium_residual), 0.0_wp, 'equilibrium residual', &
            abs_tol=1.0e-10_wp)
    end subroutine check_certified

    ! ------------------------------------------------------------------ cases

    !> The paper's test at N = 100 with Sf = 1: dtau = 54.13 - 1 - 0.6 * 81.25 = 4.38, every
    !> element slips, carries tau = 49.75, stays closed, and the slip follows the analytic
    !> profile (constant elements sit about 0.5/N high at the centre).
    subroutine test_all_slip(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(contact_result) :: res
        real(wp), allocatable :: exact(:)
        real(wp) :: g, centre
        integer :: n, i

        n = 100
        model = contact_fault([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [n])
        call solve_uniform(model, paper_sxx, paper_syy, paper_sxy, 0.6_wp, 1.0_wp, 0.0_wp, &
            'kept', res, error)
        if (allocated(error)) return
        call check_certified(error, res)
        g = shear_modulus(youngs, poisson)
        exact = -crack_profile(model%elements%x_mid, 1.0_wp, 4.38_wp, g, poisson)
        call check(error, count(res%state == state_slip), n, 'slipping elements')
        call check(error, res%pivots >= n .and. res%pivots <= 3 * n, 'pivot count out of range')
        do i = 1, n
            call check(error, res%dn(i), 0.0_wp, 'dn', abs_tol=1.0e-20_wp)
            call check(error, res%shear_traction(i), 49.75_wp, 'shear traction', &
                rel_tol=1.0e-10_wp)
            call check(error, res%normal_traction(i), paper_syy, 'normal traction', &
                rel_tol=1.0e-10_wp)
            if (abs(model%elements%x_mid(i)) < 0.5_wp) call check(error, res%ds(i), exact(i), &
                'ds', rel_tol=1.0e-2_wp)
        end do
        ! Centre: about 0.5 / N = 0.5 % above the analytic peak.
        centre = res%ds(n / 2) / exact(n / 2)
        call check(error, centre, 1.005_wp, 'centre ds / analytic', abs_tol=1.5e-3_wp)
    end subroutine test_all_slip

    !> mu = 0.7: tau = 1 + 0.7 * 81.25 = 57.875 > 54.13; every element sticks, DDs are
    !> exactly zero and the tractions are the remote ones.
    subroutine test_all_stick(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(contact_result) :: res
        integer :: n, i

        n = 100
        model = contact_fault([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [n])
        call solve_uniform(model, paper_sxx, paper_syy, paper_sxy, 0.7_wp, 1.0_wp, 0.0_wp, &
            'kept', res, error)
        if (allocated(error)) return
        call check_certified(error, res)
        call check(error, count(res%state == state_stick), n, 'sticking elements')
        ! Exactly zero by construction: Lemke leaves the DDs of sticking elements nonbasic.
        do i = 1, n
            call check(error, res%ds(i), 0.0_wp, 'ds', abs_tol=0.0_wp)
            call check(error, res%dn(i), 0.0_wp, 'dn', abs_tol=0.0_wp)
            call check(error, res%shear_traction(i), paper_sxy, 'shear traction', &
                rel_tol=1.0e-10_wp)
            call check(error, res%normal_traction(i), paper_syy, 'normal traction', &
                rel_tol=1.0e-10_wp)
        end do
    end subroutine test_all_stick

    !> The paper's code on 100 elements, mu = 0.6, Sf = 0 (a degenerate LCP: the third
    !> block of q is zero): Ds within 1e-8 relative, tractions within 1e-8.
    subroutine test_ritz_reference(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(contact_result) :: res
        real(wp) :: parm(12)
        real(wp), allocatable :: px(:), py(:), mu(:), sf(:), p(:), ref(:, :)
        integer :: n, i

        call read_column(ritz_dir//'px.csv', px, error)
        if (allocated(error)) return
        call read_column(ritz_dir//'py.csv', py, error)
        if (allocated(error)) return
        call read_column(ritz_dir//'mu.csv', mu, error)
        if (allocated(error)) return
        call read_column(ritz_dir//'sf.csv', sf, error)
        if (allocated(error)) return
        call read_parm(ritz_dir//'parm.csv', parm, error)
        if (allocated(error)) return
        n = size(px) - 1
        call check(error, size(mu), n, 'mu.csv rows')
        call check(error, size(sf), n, 'sf.csv rows')
        if (allocated(error)) return
        call read_reference(ritz_dir//'reference_elements.csv', n, ref, error)
        if (allocated(error)) return
        ! One element per polyline segment: the element ends are the paper's vertices.
        model = polyline_model(px, py, spread(1, 1, n), condition_contact, 0.0_wp, 0.0_wp, &
            parm(2), parm(1))
        p = spread(0.0_wp, 1, n)
        call solve_model(model, parm(3), parm(4), parm(5), mu, sf, p, &
            'kept', res, error)
        if (allocated(error)) return
        call check_certified(error, res)
        call check(error, count(res%state == state_slip), n, 'slipping elements')
        do i = 1, n
            ! Columns of reference_elements.csv: elem, xbeg, ybeg, xend, yend, xmid, ymid,
            ! Ds, Dn, Ss, Sn, mu, Sf.
            call check(error, res%ds(i), ref(8, i), 'ds', rel_tol=1.0e-8_wp)
            call check(error, res%dn(i), ref(9, i), 'dn', abs_tol=1.0e-15_wp)
            call check(error, res%shear_traction(i), ref(10, i), 'ss', rel_tol=1.0e-8_wp)
            call check(error, res%normal_traction(i), ref(11, i), 'sn', rel_tol=1.0e-8_wp)
        end do
    end subroutine test_ritz_reference

    !> A straight crack under sxx = syy = -10, sxy = 3 with fluid pressure p = 12 > 10:
    !> every element opens (S_n' = 0, total normal traction -p). With open_cohesion 'kept'
    !> an open element carries shear Sf = 2 and slips under the stress drop 3 - 2 = 1.
    subroutine test_pressure_kept(error)
        type(error_type), allocatable, intent(out) :: error
        call pressure_case(error, 'kept', 2.0_wp)
    end subroutine test_pressure_kept

    !> The same with 'lost': the open elements lose their cohesion and carry no shear; the
    !> stress drop is the full 3; a second LCP solve is needed.
    subroutine test_pressure_lost(error)
        type(error_type), allocatable, intent(out) :: error
        call pressure_case(error, 'lost', 0.0_wp)
    end subroutine test_pressure_lost

    subroutine pressure_case(error, cohesion, shear_carried)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: cohesion
        real(wp), intent(in) :: shear_carried
        type(model_type) :: model
        type(contact_result) :: res
        real(wp), allocatable :: opening(:), slip(:)
        real(wp) :: g
        integer :: n, i

        n = 50
        model = contact_fault([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [n])
        call solve_uniform(model, -10.0_wp, -10.0_wp, 3.0_wp, 0.6_wp, 2.0_wp, 12.0_wp, &
            cohesion, res, error)
        if (allocated(error)) return
        call check_certified(error, res)
        call check(error, count(res%state == state_open), n, 'open elements')
        if (cohesion == 'lost') then
            call check(error, res%solves, 2, 'LCP solves')
            call check(error, maxval(res%sf_effective) <= 0.0_wp, 'cohesion left')
        else
            call check(error, res%solves, 1, 'LCP solves')
        end if
        g = shear_modulus(youngs, poisson)
        opening = crack_profile(model%elements%x_mid, 1.0_wp, 2.0_wp, g, poisson)
        slip = -crack_profile(model%elements%x_mid, 1.0_wp, 3.0_wp - shear_carried, g, poisson)
        do i = 1, n
            call check(error, res%normal_traction(i), -12.0_wp, 'normal traction', &
                rel_tol=1.0e-10_wp)
            call check(error, res%shear_traction(i), shear_carried, 'shear traction', &
                abs_tol=1.0e-10_wp)
            if (abs(model%elements%x_mid(i)) < 0.5_wp) then
                call check(error, -res%dn(i), opening(i), 'opening', rel_tol=2.0e-2_wp)
                call check(error, res%ds(i), slip(i), 'ds', rel_tol=2.0e-2_wp)
            end if
        end do
    end subroutine pressure_case

    !> A kinked fault: a horizontal segment (-1, 0)-(0, 0) and a segment rising at 35
    !> degrees from the kink, 30 elements each, Sf = 0 (a degenerate LCP), mu = 0.6, fluid
    !> pressure on the whole fault. Stick, slip and open all appear and the certificate
    !> holds. Loading: sxx = -5, syy = -20, sxy = 0.5, p = 17.5. Resolved, the horizontal
    !> segment is closed (S_n' = -2.5) with |s_s| = 0.5 below tau = 1.5, and the inclined one
    !> is under net tension (S_n' = +1.97): it opens, and the stress it concentrates at the
    !> kink makes the horizontal segment slip over about two thirds of its length.
    subroutine test_kink(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(contact_result) :: res
        real(wp) :: b

        b = 35.0_wp * pi / 180.0_wp
        model = contact_fault([-1.0_wp, 0.0_wp, cos(b)], [0.0_wp, 0.0_wp, sin(b)], [30, 30])
        call solve_uniform(model, kink_sxx, kink_syy, kink_sxy, 0.6_wp, 0.0_wp, kink_pressure, &
            'kept', res, error)
        if (allocated(error)) return
        call check_certified(error, res)
        call check(error, count(res%state == state_stick) > 0, 'no element sticks')
        call check(error, count(res%state == state_slip) > 0, 'no element slips')
        call check(error, count(res%state == state_open) > 0, 'no element opens')
        call check(error, all(res%state(31:60) == state_open), 'inclined segment not all open')
        if (allocated(error)) return
        ! Open elements carry no normal effective stress and no shear (Sf = 0).
        call check(error, maxval(abs(res%normal_traction + kink_pressure), &
            mask=res%state == state_open), 0.0_wp, 'open S_n''', abs_tol=1.0e-9_wp)
        call check(error, maxval(abs(res%shear_traction), mask=res%state == state_open), &
            0.0_wp, 'open s_s', abs_tol=1.0e-9_wp)
    end subroutine test_kink

    !> Two coincident elements: A is singular, an error naming an element.
    subroutine test_singular(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(model_type) :: model, other
        type(contact_result) :: res
        real(wp), allocatable :: v(:)

        model = contact_fault([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [1])
        other = model
        call join_fractures(model, other)
        v = [0.6_wp, 0.6_wp]
        call solve_model(model, paper_sxx, paper_syy, paper_sxy, v, 0.0_wp * v, &
            0.0_wp * v, 'kept', res, failure)
        call check(error, allocated(failure), 'a singular influence matrix must be an error')
        if (allocated(error)) return
        call check(error, failure%code == exit_solver_failure, 'wrong code: '//failure%message)
        call check(error, index(failure%message, 'singular') > 0 .and. &
            index(failure%message, 'element 2 (') > 0, 'message: '//failure%message)
    end subroutine test_singular

    !> open_cohesion other than 'kept' or 'lost' is bad input.
    subroutine test_bad_cohesion(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(solver_options) :: options

        call parse_solver_options('lemke', 'keep', options, failure)
        call check(error, allocated(failure), 'open_cohesion = keep must be an error')
        if (allocated(error)) return
        call check(error, failure%code == exit_bad_input, 'wrong code: '//failure%message)
        call check(error, index(failure%message, 'open_cohesion') > 0, &
                   'message: '//failure%message)
    end subroutine test_bad_cohesion

    !> Arrays of inconsistent sizes are a broken contract inside ddc2d, not bad input: exit
    !> status 4 with a message naming the procedure.
    subroutine test_internal_error(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(contact_result) :: res
        real(wp) :: a(2, 2)

        a = reshape([1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 2])
        call solve_contact(a, [1.0_wp, 2.0_wp], [-1.0_wp], [0.6_wp], [0.0_wp], [0.0_wp], &
                           solver_options(), res, failure)
        call check(error, allocated(failure), 'inconsistent sizes must be an error')
        if (allocated(error)) return
        call check(error, failure%code, exit_internal_error, 'exit code')
        if (allocated(error)) return
        call check(error, index(failure%message, 'internal error in solve_contact') == 1, &
                   'message: '//failure%message)
    end subroutine test_internal_error

    ! ------------------------------------------------------------------ CSV reading

    !> One number per line.
    subroutine read_column(path, v, error)
        character(len=*), intent(in) :: path
        real(wp), allocatable, intent(out) :: v(:)
        type(error_type), allocatable, intent(inout) :: error
        real(wp) :: x
        integer :: unit, stat

        allocate (v(0))
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        call check(error, stat == 0, 'cannot open '//path)
        if (allocated(error)) return
        do
            read (unit, *, iostat=stat) x
            if (stat /= 0) exit
            v = [v, x]
        end do
        close (unit)
    end subroutine read_column

    !> parm.csv: one line of 12 numbers.
    subroutine read_parm(path, parm, error)
        character(len=*), intent(in) :: path
        real(wp), intent(out) :: parm(12)
        type(error_type), allocatable, intent(inout) :: error
        integer :: unit, stat

        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        call check(error, stat == 0, 'cannot open '//path)
        if (allocated(error)) return
        read (unit, *, iostat=stat) parm
        close (unit)
        call check(error, stat == 0, 'cannot read '//path)
    end subroutine read_parm

    !> reference_elements.csv: a header, then n rows of 13 numbers; ref(column, row).
    subroutine read_reference(path, n, ref, error)
        character(len=*), intent(in) :: path
        integer, intent(in) :: n
        real(wp), allocatable, intent(out) :: ref(:, :)
        type(error_type), allocatable, intent(inout) :: error
        integer :: unit, stat, i

        allocate (ref(13, n))
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        call check(error, stat == 0, 'cannot open '//path)
        if (allocated(error)) return
        read (unit, *, iostat=stat)
        do i = 1, n
            if (stat == 0) read (unit, *, iostat=stat) ref(:, i)
        end do
        close (unit)
        call check(error, stat == 0, 'cannot read '//path)
    end subroutine read_reference

end module test_contact
