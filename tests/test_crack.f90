!> Straight cracks against closed forms (SPEC section 7): DDs, K_I, K_II.
module test_crack
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, condition_traction
    use ddc_model_results, only: model_results
    use ddc_run_model, only: run_model
    use ddc_constants, only: pi
    use ddc_test_builders, only: straight_crack, polyline_model
    implicit none
    private

    public :: collect_crack

    real(wp), parameter :: e_modulus = 50000.0_wp, nu = 0.25_wp, g = e_modulus / 2.5_wp

contains

    !> Cases of the crack suite.
    subroutine collect_crack(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('pressurized_n500', test_pressurized), &
                 new_test('sheared_n500', test_sheared), &
                 new_test('inclined_30_degrees_uniaxial', test_inclined), &
                 new_test('graded_tip_flagged', test_graded_tip)]
    end subroutine collect_crack

    !> Solve a model, turning a solver error into a test failure.
    subroutine solve(model, results, error)
        type(model_type), intent(in) :: model
        type(model_results), intent(out) :: results
        type(error_type), allocatable, intent(out) :: error

        call run_model(model, results, error)
    end subroutine solve

    !> Along an n-element crack of half-length 1 loaded by a uniform traction drop `drop`:
    !> the centre DD sits about 0.5/n above 2(1-nu) drop / G, off-centre elements follow the
    !> ellipse, and K at both tips is drop sqrt(pi) within 0.05 %.
    subroutine check_elliptic(error, d, k, drop, n, label)
        type(error_type), allocatable, intent(inout) :: error
        real(wp), intent(in) :: d(:), k(:), drop
        integer, intent(in) :: n
        character(len=*), intent(in) :: label
        real(wp) :: x, exact, centre_ratio
        integer :: i

        exact = 2.0_wp * (1.0_wp - nu) * drop / g
        ! Elements n/2 and n/2 + 1 have midpoints at -+1/n; the closed form there:
        centre_ratio = abs(d(n / 2)) / (exact * sqrt(1.0_wp - (1.0_wp / n)**2))
        call check(error, centre_ratio, 1.0_wp + 0.5_wp / n, label//' centre ratio', &
                   abs_tol=0.1_wp / n)
        ! Away from the tips the constant-element excess grows like 0.5 / (n (1 - x^2)).
        do i = n / 10, n - n / 10
            x = -1.0_wp + (2 * i - 1) / real(n, wp)
            call check(error, abs(d(i)), exact * sqrt(1.0_wp - x**2), label//' profile', &
                       rel_tol=0.6_wp / (n * (1.0_wp - x**2)))
        end do
        call check(error, k(1), drop * sqrt(pi), label//' K at the left tip', rel_tol=5.0e-4_wp)
        call check(error, k(2), drop * sqrt(pi), label//' K at the right tip', rel_tol=5.0e-4_wp)
    end subroutine check_elliptic

    !> Crack under internal pressure p: opening ellipse, K_I = p sqrt(pi a), no shear.
    subroutine test_pressurized(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: r
        integer, parameter :: n = 500
        real(wp), parameter :: p = 10.0_wp

        call solve(straight_crack(n, 1.0_wp, 0.0_wp, condition_traction, 0.0_wp, -p, &
                                  e_modulus, nu), r, error)
        if (allocated(error)) return
        call check(error, r%tips%n, 2, 'number of tips')
        if (allocated(error)) return
        call check(error, maxval(r%elements%dn) < 0.0_wp, 'dn < 0 (opening) on every element')
        call check_elliptic(error, r%elements%dn, r%tips%k1, p, n, 'opening')
        call check(error, maxval(abs(r%elements%ds)), 0.0_wp, 'no slip', abs_tol=1.0e-15_wp)
        call check(error, maxval(abs(r%tips%k2)), 0.0_wp, 'K_II', abs_tol=1.0e-12_wp)
        call check(error, all(r%tips%graded == 0), 'equal elements: no tip is graded')
    end subroutine test_pressurized

    !> Traction-free crack under remote shear sxy: Ds < 0 along +x, K_II = sxy sqrt(pi a) > 0.
    subroutine test_sheared(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        integer, parameter :: n = 500
        real(wp), parameter :: tau = 4.0_wp

        model = straight_crack(n, 1.0_wp, 0.0_wp, condition_traction, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%sxy = tau
        call solve(model, r, error)
        if (allocated(error)) return
        call check(error, maxval(r%elements%ds) < 0.0_wp, 'ds < 0 under sxy > 0 on every element')
        call check_elliptic(error, r%elements%ds, r%tips%k2, tau, n, 'slip')
        call check(error, maxval(abs(r%tips%k1)), 0.0_wp, 'K_I', abs_tol=1.0e-12_wp)
        call check(error, maxval(abs(r%elements%shear_traction)), 0.0_wp, &
                   'traction-free faces', abs_tol=1.0e-10_wp * tau)
    end subroutine test_sheared

    !> Crack at b = 30 degrees to a uniaxial tension sigma (along y):
    !> K_I = sigma sin^2 b sqrt(pi a), K_II = sigma sin b cos b sqrt(pi a), within 0.1 %.
    subroutine test_inclined(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        real(wp), parameter :: sigma = 7.0_wp, b = pi / 6.0_wp, a = 2.0_wp

        ! The crack makes angle b with the load axis y, so angle pi/2 - b with x.
        model = straight_crack(500, a, pi / 2.0_wp - b, condition_traction, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%syy = sigma
        call solve(model, r, error)
        if (allocated(error)) return
        call check(error, r%tips%k1(1), sigma * sin(b)**2 * sqrt(pi * a), 'K_I tip 1', &
                   rel_tol=1.0e-3_wp)
        call check(error, r%tips%k1(2), sigma * sin(b)**2 * sqrt(pi * a), 'K_I tip 2', &
                   rel_tol=1.0e-3_wp)
        call check(error, r%tips%k2(1), sigma * sin(b) * cos(b) * sqrt(pi * a), 'K_II tip 1', &
                   rel_tol=1.0e-3_wp)
        call check(error, r%tips%k2(2), sigma * sin(b) * cos(b) * sqrt(pi * a), 'K_II tip 2', &
                   rel_tol=1.0e-3_wp)
    end subroutine test_inclined

    !> Twenty elements of 0.075 then one of 0.5 at the right tip: only that tip is graded.
    subroutine test_graded_tip(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_results) :: r

        call solve(polyline_model([-1.0_wp, 0.5_wp, 1.0_wp], [0.0_wp, 0.0_wp, 0.0_wp], &
                                  [20, 1], condition_traction, 0.0_wp, -1.0_wp, e_modulus, nu), &
                   r, error)
        if (allocated(error)) return
        call check(error, r%tips%n, 2, 'number of tips')
        if (allocated(error)) return
        call check(error, r%tips%graded(1), 0, 'left tip (equal elements)')
        call check(error, r%tips%graded(2), 1, 'right tip (0.5 next to 0.075)')
    end subroutine test_graded_tip

end module test_crack
