!> Solved models in a half-plane, with depth-dependent stress, pore fluid and prescribed DDs
!> (SPEC-EARTH sections 1 and 2). Bad-input files are under tests/data/half_plane/.
module test_half_plane
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, observation_set, observation_line, &
        condition_traction, condition_contact, condition_prescribed_dd, domain_half_plane, &
        symmetry_x
    use ddc_model_results, only: model_results, state_open, point_clear, point_near, &
        point_on_element
    use ddc_influence_kernel, only: dd_kernel, face_positive
    use ddc_constants, only: pi
    use ddc_influence_kernel_half_plane, only: dd_kernel_half_plane
    use ddc_input_namelist, only: read_namelist_model
    use ddc_test_builders, only: polyline_model, join_fractures
    use test_input, only: check_bad_input
    use ddc_run_model, only: run_model
    implicit none
    private

    public :: collect_half_plane

    character(len=*), parameter :: data = 'data/half_plane/'
    !> The crack of SPEC-EARTH 2: E, nu, ends, remote stress gradient
    real(wp), parameter :: e_rock = 50000.0_wp, nu_rock = 0.25_wp
    real(wp), parameter :: y_bottom = -3000.0_wp, y_top = -1000.0_wp
    real(wp), parameter :: lithostatic(3) = [0.025_wp, 0.025_wp, 0.0_wp]

contains

    !> Cases of the half_plane suite.
    subroutine collect_half_plane(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('surface_breaking_crack_k1', test_surface_breaking), &
                 new_test('linear_load_opening_and_k', test_linear_load), &
                 new_test('linear_load_partial_closure', test_partial_closure), &
                 new_test('deep_crack_tends_to_full_plane', test_deep_crack), &
                 new_test('traction_free_surface_solved', test_free_surface), &
                 new_test('prescribed_dd_surface_displacement', test_prescribed_surface), &
                 new_test('prescribed_dd_with_contact_and_traction', test_prescribed_mixed), &
                 new_test('symmetry_x_in_half_plane', test_symmetry_x), &
                 new_test('pore_fluid_example_open_near_surface', test_pore_fluid_example), &
                 new_test('bad_element_above_surface', test_bad_above), &
                 new_test('bad_uniform_syy', test_bad_syy), &
                 new_test('bad_uniform_sxy', test_bad_sxy), &
                 new_test('bad_nan_gradient', test_bad_nan_gradient), &
                 new_test('bad_point_symmetry_y_element_on_surface', test_bad_point)]
    end subroutine collect_half_plane

    ! ---- helpers ------------------------------------------------------------------------

    !> Solve a model; a solver error fails the test.
    subroutine solve(error, model, results)
        type(error_type), allocatable, intent(inout) :: error
        type(model_type), intent(in) :: model
        type(model_results), intent(out) :: results
        type(error_type), allocatable :: run_error

        call run_model(model, results, run_error)
        if (allocated(run_error)) call check(error, .false., 'run_model: '//run_error%message)
    end subroutine solve

    !> A line of n points along y = y0 from x0 to x1, as the model's only observation set.
    subroutine observe_line(model, x0, x1, y0, n)
        type(model_type), intent(inout) :: model
        real(wp), intent(in) :: x0, x1, y0
        integer, intent(in) :: n
        integer :: i

        model%observations = [observation_set(name='line', kind=observation_line, nx=n, ny=1, &
            x=[(x0 + (x1 - x0) * real(i, wp) / real(n - 1, wp), i = 0, n - 1)], &
            y=[(y0, i = 1, n)])]
    end subroutine observe_line

    !> The vertical crack of SPEC-EARTH 2 (full plane, N = 400) with the lithostatic gradient.
    function linear_load_crack(condition) result(model)
        integer, intent(in) :: condition
        type(model_type) :: model

        model = polyline_model([0.0_wp, 0.0_wp], [y_bottom, y_top], [400], condition, 0.0_wp, &
                               0.0_wp, e_rock, nu_rock)
        model%stress_gradient = lithostatic
    end function linear_load_crack

    !> Index of the tip at height y (within 1e-9), 0 when absent.
    integer function tip_at(results, y)
        type(model_results), intent(in) :: results
        real(wp), intent(in) :: y

        tip_at = findloc(abs(results%tips%y - y) <= 1.0e-9_wp * max(1.0_wp, abs(y)), .true., 1)
    end function tip_at

    ! ---- solved models ------------------------------------------------------------------

    !> Vertical crack from the surface to depth a under pressure p: the mouth is no tip, the
    !> one tip has K_I within 3e-4 of 1.12138 p sqrt(pi a) (SPEC-EARTH 1, N = 400).
    subroutine test_surface_breaking(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        real(wp), parameter :: a = 2.0_wp, p = 3.0_wp

        model = polyline_model([0.0_wp, 0.0_wp], [0.0_wp, -a], [400], condition_traction, &
                               0.0_wp, -p, 1000.0_wp, 0.25_wp)
        model%elements%domain = domain_half_plane
        call solve(error, model, results)
        if (allocated(error)) return
        call check(error, results%tips%n, 1, 'tips (the mouth is not one)')
        call check(error, results%tips%y(1), -a, 'tip depth', abs_tol=1.0e-12_wp)
        call check(error, results%tips%k1(1) / (p * sqrt(pi * a)), 1.12138_wp, &
                   'K_I / (p sqrt(pi a))', abs_tol=3.0e-4_wp)
        write (*, '(a,f10.6)') '    K_I / (p sqrt(pi a)) =', results%tips%k1(1) / (p * sqrt(pi * a))
    end subroutine test_surface_breaking

    !> SPEC-EARTH 2: net opening load A + B s; maximum opening, opening at the centre and
    !> the opening profile over |s| <= 0.6 a (relative to the maximum) within 0.2 %, both tip
    !> K within 0.2 %. (Constant elements: the profile error grows towards the tips, to 1 %
    !> of the maximum on the tip elements.)
    subroutine test_linear_load(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        real(wp), parameter :: big_a = 30.0_wp, big_b = 0.025_wp, a = 1000.0_wp
        real(wp) :: g, s(400), exact(400), w(400), k_top, k_bottom, profile_error

        model = linear_load_crack(condition_traction)
        model%elements%bc_n = -80.0_wp
        call solve(error, model, results)
        if (allocated(error)) return
        g = e_rock / (2.0_wp * (1.0_wp + nu_rock))
        s = model%elements%y_mid + 2000.0_wp
        exact = 2.0_wp * (1.0_wp - nu_rock) / g * sqrt(a**2 - s**2) * (big_a + big_b * s / 2.0_wp)
        w = -results%elements%dn
        call check(error, maxval(w), maxval(exact), 'maximum opening', rel_tol=2.0e-3_wp)
        call check(error, w(200), exact(200), 'opening at the centre', rel_tol=2.0e-3_wp)
        profile_error = maxval(abs(w - exact), mask=abs(s) <= 0.6_wp * a) / maxval(exact)
        call check(error, profile_error, 0.0_wp, 'opening error over |s| <= 0.6 a / max', &
                   abs_tol=2.0e-3_wp)
        call check(error, results%tips%n, 2, 'tips')
        if (allocated(error)) return
        k_top = results%tips%k1(tip_at(results, y_top))
        k_bottom = results%tips%k1(tip_at(results, y_bottom))
        call check(error, k_top, sqrt(pi * a) * (big_a + big_b * a / 2.0_wp), 'K_top', &
                   rel_tol=2.0e-3_wp)
        call check(error, k_bottom, sqrt(pi * a) * (big_a - big_b * a / 2.0_wp), 'K_bottom', &
                   rel_tol=2.0e-3_wp)
        write (*, '(a,es10.3,a,es10.3,a,es10.3,a,f9.3,a,f9.3)') '    w_max error', &
            maxval(w) / maxval(exact) - 1.0_wp, ', centre', w(200) / exact(200) - 1.0_wp, &
            ', profile', profile_error, ', K_top =', k_top, ', K_bottom =', k_bottom
    end subroutine test_linear_load

    !> SPEC-EARTH 2 with contact (pressure 40): open from the top down to y = -1800 within
    !> one element, closed below; w_max and K_top within 0.5 %.
    subroutine test_partial_closure(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        real(wp) :: g, b, y_open, w_max, k_top
        integer :: last_open

        model = linear_load_crack(condition_contact)
        model%elements%mu = 0.6_wp
        model%elements%pressure = 40.0_wp
        call solve(error, model, results)
        if (allocated(error)) return
        ! Elements run upward: the open ones must be the last ones, every element below the
        ! boundary closed.
        last_open = findloc(results%elements%state /= state_open, .true., 1, back=.true.)
        call check(error, last_open > 0 .and. last_open < 400, 'open and closed elements')
        if (allocated(error)) return
        call check(error, all(results%elements%state(last_open + 1:) == state_open), &
                   'open from the boundary up to the top')
        call check(error, .not. any(results%elements%state(:last_open) == state_open), &
                   'closed below the boundary')
        y_open = model%elements%y_end(last_open)
        call check(error, y_open, -1800.0_wp, 'open/closed boundary', abs_tol=5.0_wp)
        g = e_rock / (2.0_wp * (1.0_wp + nu_rock))
        b = 400.0_wp
        w_max = maxval(-results%elements%dn)
        call check(error, w_max, 1.299_wp * (1.0_wp - nu_rock) * 0.025_wp * b**2 / g, 'w_max', &
                   rel_tol=5.0e-3_wp)
        k_top = results%tips%k1(tip_at(results, y_top))
        call check(error, k_top, 0.025_wp * b * sqrt(pi * b), 'K_top', rel_tol=5.0e-3_wp)
        write (*, '(a,i0,a,f9.2,a,f9.6,a,f9.3)') '    open elements ', 400 - last_open, &
            ' down to y =', y_open, ', w_max =', w_max, ', K_top =', k_top
    end subroutine test_partial_closure

    !> A pressurized inclined crack 1000 lengths deep: the half-plane DDs equal the
    !> full-plane ones to 1e-5 (the surface acts at order (a / depth)^2 = 1e-6).
    subroutine test_deep_crack(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: full, half
        real(wp) :: scale

        model = polyline_model([-0.8_wp, 0.8_wp], [-2000.6_wp, -1999.4_wp], [40], &
                               condition_traction, 0.5_wp, -1.0_wp, 1000.0_wp, 0.3_wp)
        call solve(error, model, full)
        model%elements%domain = domain_half_plane
        call solve(error, model, half)
        if (allocated(error)) return
        scale = maxval(abs(full%elements%dn))
        call check(error, maxval(abs(half%elements%dn - full%elements%dn)) / scale, 0.0_wp, &
                   'Dn difference', abs_tol=1.0e-5_wp)
        call check(error, maxval(abs(half%elements%ds - full%elements%ds)) / scale, 0.0_wp, &
                   'Ds difference', abs_tol=1.0e-5_wp)
        call check(error, maxval(abs(half%elements%dn - full%elements%dn)) / scale > 0.0_wp, &
                   'the half-plane kernel was used')
    end subroutine test_deep_crack

    !> A surface-breaking dipping crack under pressure with lithostatic stress and constant
    !> horizontal compression: on y = 0, syy and sxy vanish (1e-10 of the load); the mouth
    !> is the only point flagged on an element, every other surface point is finite.
    subroutine test_free_surface(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        integer :: i

        model = polyline_model([0.0_wp, 1.0_wp, 1.5_wp], [0.0_wp, -1.0_wp, -2.5_wp], [30, 30], &
                               condition_traction, 0.0_wp, -5.0_wp, 1000.0_wp, 0.25_wp)
        model%elements%domain = domain_half_plane
        model%sxx = -2.0_wp
        model%stress_gradient = [0.02_wp, 0.027_wp, 0.0_wp]
        call observe_line(model, -4.0_wp, 4.0_wp, 0.0_wp, 81)
        call solve(error, model, results)
        if (allocated(error)) return
        associate (f => results%fields(1))
            do i = 1, 81
                if (i == 41) then
                    call check(error, f%flag(i), point_on_element, 'the mouth (0, 0) flag')
                    cycle
                end if
                call check(error, f%flag(i) == point_clear .or. f%flag(i) == point_near, &
                           'surface point is not on an element')
                call check(error, f%syy(i), 0.0_wp, 'syy on the surface', abs_tol=5.0e-10_wp)
                call check(error, f%sxy(i), 0.0_wp, 'sxy on the surface', abs_tol=5.0e-10_wp)
                call check(error, abs(f%uy(i)) > 0.0_wp, 'surface uplift is finite, non-zero')
            end do
            write (*, '(a,es10.3)') '    max |syy|,|sxy| on the surface =', &
                max(maxval(abs(f%syy(:40))), maxval(abs(f%syy(42:))), &
                    maxval(abs(f%sxy(:40))), maxval(abs(f%sxy(42:))))
        end associate
    end subroutine test_free_surface

    !> A buried dipping fault with prescribed uniform slip: DDs as given, surface
    !> displacement equal to the kernel sum and the same for nu = 0.25 and 0.4.
    subroutine test_prescribed_surface(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results(2)
        type(dd_kernel) :: k
        real(wp), parameter :: nus(2) = [0.25_wp, 0.4_wp]
        real(wp) :: ux, uy, scale
        integer :: m, i, j

        do m = 1, 2
            model = polyline_model([-1.0_wp, 1.0_wp], [-2.0_wp, -1.0_wp], [20], &
                                   condition_prescribed_dd, 1.0_wp, 0.0_wp, 100.0_wp, nus(m))
            model%elements%domain = domain_half_plane
            call observe_line(model, -5.0_wp, 5.0_wp, 0.0_wp, 41)
            call solve(error, model, results(m))
            if (allocated(error)) return
            call check(error, maxval(abs(results(m)%elements%ds - 1.0_wp)), 0.0_wp, 'Ds', &
                       abs_tol=1.0e-13_wp)
            call check(error, maxval(abs(results(m)%elements%dn)), 0.0_wp, 'Dn', &
                       abs_tol=1.0e-13_wp)
        end do
        associate (f => results(1)%fields(1), e => model%elements)
            scale = maxval(abs(f%uy))
            do i = 1, 41
                ux = 0.0_wp
                uy = 0.0_wp
                do j = 1, e%n
                    k = dd_kernel_half_plane(model%observations(1)%x(i), 0.0_wp, e%x_mid(j), &
                                             e%y_mid(j), e%half_length(j), e%cos_beta(j), &
                                             e%sin_beta(j), 40.0_wp, 0.25_wp, face_positive)
                    ux = ux + k%ux(1)
                    uy = uy + k%uy(1)
                end do
                call check(error, f%ux(i), ux, 'ux = kernel sum', abs_tol=1.0e-12_wp * scale)
                call check(error, f%uy(i), uy, 'uy = kernel sum', abs_tol=1.0e-12_wp * scale)
                call check(error, results(2)%fields(1)%ux(i), f%ux(i), 'ux independent of nu', &
                           abs_tol=1.0e-12_wp * scale)
                call check(error, results(2)%fields(1)%uy(i), f%uy(i), 'uy independent of nu', &
                           abs_tol=1.0e-12_wp * scale)
            end do
        end associate
    end subroutine test_prescribed_surface

    !> A contact crack, a pressurized traction crack and a prescribed-DD fault in one model:
    !> with zero prescribed DDs the others are as without the fault; with slip, the fault's
    !> DDs are as given and the contact crack responds.
    subroutine test_prescribed_mixed(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: base, mixed
        type(model_results) :: r_base, r_zero, r_slip
        integer :: nb

        base = polyline_model([-1.0_wp, 1.0_wp], [-3.0_wp, -3.0_wp], [20], condition_contact, &
                              0.0_wp, 0.0_wp, 1000.0_wp, 0.25_wp)
        base%elements%mu = 0.5_wp
        call join_fractures(base, polyline_model([2.0_wp, 3.0_wp], [-3.0_wp, -4.0_wp], [10], &
                            condition_traction, 0.0_wp, -1.0_wp, 1000.0_wp, 0.25_wp))
        base%elements%domain = domain_half_plane
        base%sxx = -1.0_wp
        base%stress_gradient = [0.3_wp, 0.5_wp, 0.0_wp]
        nb = base%elements%n
        mixed = base
        call join_fractures(mixed, polyline_model([-1.0_wp, 0.5_wp], [-1.0_wp, -2.5_wp], [15], &
                            condition_prescribed_dd, 0.0_wp, 0.0_wp, 1000.0_wp, 0.25_wp))
        call solve(error, base, r_base)
        call solve(error, mixed, r_zero)
        if (allocated(error)) return
        call check(error, maxval(abs(r_zero%elements%ds(:nb) - r_base%elements%ds)), 0.0_wp, &
                   'Ds with a zero prescribed fault', abs_tol=1.0e-12_wp)
        call check(error, maxval(abs(r_zero%elements%dn(:nb) - r_base%elements%dn)), 0.0_wp, &
                   'Dn with a zero prescribed fault', abs_tol=1.0e-12_wp)
        mixed%elements%bc_s(nb + 1:) = 0.01_wp
        mixed%elements%bc_n(nb + 1:) = -0.002_wp
        call solve(error, mixed, r_slip)
        if (allocated(error)) return
        call check(error, maxval(abs(r_slip%elements%ds(nb + 1:) - 0.01_wp)), 0.0_wp, &
                   'prescribed Ds', abs_tol=1.0e-14_wp)
        call check(error, maxval(abs(r_slip%elements%dn(nb + 1:) + 0.002_wp)), 0.0_wp, &
                   'prescribed Dn', abs_tol=1.0e-14_wp)
        call check(error, all(r_slip%elements%state(nb + 1:) == 0), 'prescribed state free')
        call check(error, maxval(abs(r_slip%elements%ds(:20) - r_base%elements%ds(:20))) > &
                   1.0e-6_wp, 'the contact crack responds to the prescribed slip')
        ! The traction crack keeps its traction condition.
        call check(error, maxval(abs(r_slip%elements%normal_traction(21:nb) + 1.0_wp)), 0.0_wp, &
                   'traction crack normal traction', abs_tol=1.0e-9_wp)
    end subroutine test_prescribed_mixed

    !> Symmetry about x = 0 in a half-plane equals the explicit mirrored model.
    subroutine test_symmetry_x(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: sym, explicit
        type(model_results) :: r_sym, r_explicit
        real(wp) :: scale

        sym = polyline_model([1.0_wp, 2.0_wp], [-1.0_wp, -2.0_wp], [20], condition_traction, &
                             0.3_wp, -1.0_wp, 1000.0_wp, 0.25_wp)
        sym%elements%domain = domain_half_plane
        explicit = sym
        sym%elements%symmetry%kind = symmetry_x
        call join_fractures(explicit, polyline_model([-1.0_wp, -2.0_wp], [-1.0_wp, -2.0_wp], &
                            [20], condition_traction, -0.3_wp, -1.0_wp, 1000.0_wp, 0.25_wp))
        call solve(error, sym, r_sym)
        call solve(error, explicit, r_explicit)
        if (allocated(error)) return
        scale = maxval(abs(r_explicit%elements%dn))
        call check(error, maxval(abs(r_sym%elements%dn - r_explicit%elements%dn(:20))) / scale, &
                   0.0_wp, 'Dn', abs_tol=1.0e-12_wp)
        call check(error, maxval(abs(r_sym%elements%ds - r_explicit%elements%ds(:20))) / scale, &
                   0.0_wp, 'Ds', abs_tol=1.0e-12_wp)
    end subroutine test_symmetry_x

    !> The example input/vertical_fracture_pore_pressure.nml: read (domain, gradients, pore
    !> fluid), solved: open at the surface, closed at the bottom.
    subroutine test_pore_fluid_example(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        type(error_type), allocatable :: read_error
        integer :: n

        call read_namelist_model('../input/vertical_fracture_pore_pressure.nml', model, &
                                 read_error)
        call check(error, .not. allocated(read_error), 'example is read')
        if (allocated(error)) return
        call check(error, model%elements%domain, domain_half_plane, 'domain')
        call check(error, model%pore_fluid(2), -0.0098_wp, 'dp_dy', abs_tol=1.0e-15_wp)
        call check(error, model%stress_gradient(2), 0.026_wp, 'dsyy_dy', abs_tol=1.0e-15_wp)
        call solve(error, model, results)
        if (allocated(error)) return
        n = model%elements%n
        call check(error, results%elements%state(1), state_open, 'element at the surface open')
        call check(error, results%elements%state(n) /= state_open, 'deepest element closed')
        call check(error, results%tips%n, 1, 'one tip (the mouth is none)')
    end subroutine test_pore_fluid_example

    ! ---- bad input ----------------------------------------------------------------------

    subroutine test_bad_above(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_above_surface.nml', [character(len=40) :: &
                        "&fracture 1 'fault'", 'element 3', 'above the free surface'])
    end subroutine test_bad_above

    subroutine test_bad_syy(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_uniform_syy.nml', [character(len=40) :: &
                             'syy = -10', 'must all be 0', 'traction-free at the surface y = 0'])
    end subroutine test_bad_syy

    subroutine test_bad_sxy(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_uniform_sxy.nml', [character(len=40) :: 'sxy = 2', &
                        'traction-free at the surface y = 0'])
    end subroutine test_bad_sxy

    subroutine test_bad_nan_gradient(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_nan_gradient.nml', [character(len=40) :: &
                        'dsxx_dy = NaN', 'dp_dy = NaN', 'is not a finite number'])
    end subroutine test_bad_nan_gradient

    subroutine test_bad_point(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_point_above_surface.nml', [character(len=48) :: &
                        "&line 1 'profile'", 'point 3 (y = 0.5', 'is above the free surface', &
                        "&symmetry kind = 'y' is not available", &
                        "&fracture 2 'flat'", 'element 1 lies on the free surface'])
    end subroutine test_bad_point

end module test_half_plane
