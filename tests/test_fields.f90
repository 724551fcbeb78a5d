!> Fields around a pressurized crack against Westergaard's solution (SPEC section 7),
!> and the flags of points on or near elements.
module test_fields
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, condition_traction, observation_set, &
        observation_points, symmetry_none, symmetry_both
    use ddc_model_results, only: model_results, field_result, point_clear, point_near, &
        point_on_element
    use ddc_run_model, only: run_model
    use ddc_post_fields, only: evaluate_field
    use ddc_test_builders, only: straight_crack, kinked_network
    implicit none
    private

    public :: collect_fields

    real(wp), parameter :: e_modulus = 1000.0_wp, nu = 0.25_wp, g = e_modulus / 2.5_wp
    real(wp), parameter :: p = 2.0_wp, a = 1.0_wp

contains

    !> Cases of the fields suite.
    subroutine collect_fields(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('westergaard_pressurized_n500', test_westergaard), &
                 new_test('point_flags', test_point_flags), &
                 new_test('fast_fields_equal_general', test_fast_fields)]
    end subroutine collect_fields

    !> Westergaard / Pollard & Segall (1987) field of a crack |x| < a under internal pressure
    !> p, no remote stress: the biaxial-tension solution Z = p z / sqrt(z^2 - a^2) minus the
    !> uniform biaxial stress p (and its displacement), plane strain.
    subroutine westergaard(x, y, u, s)
        real(wp), intent(in) :: x, y
        !> ux, uy and sxx, syy, sxy
        real(wp), intent(out) :: u(2), s(3)
        complex(wp) :: z, root, zw, dzw, zbar

        z = cmplx(x, y, wp)
        root = sqrt(z - a) * sqrt(z + a)
        zw = p * z / root
        dzw = -p * a**2 / root**3
        zbar = p * root
        s(1) = real(zw) - y * aimag(dzw) - p
        s(2) = real(zw) + y * aimag(dzw) - p
        s(3) = -y * real(dzw)
        u(1) = ((1.0_wp - 2.0_wp * nu) * real(zbar) - y * aimag(zw)) / (2.0_wp * g) &
               - p * (1.0_wp - 2.0_wp * nu) * x / (2.0_wp * g)
        u(2) = (2.0_wp * (1.0_wp - nu) * aimag(zbar) - y * real(zw)) / (2.0_wp * g) &
               - p * (1.0_wp - 2.0_wp * nu) * y / (2.0_wp * g)
    end subroutine westergaard

    !> N = 500: within 0.5 % in stress and 0.7 % in displacement on a regular grid of step
    !> 0.25 a over [-2a, 2a]^2, at the points at least 0.2 a from the tips and off the crack,
    !> errors relative to the peak of the exact field over those points (here p). Off this
    !> grid the stress error can be slightly larger: 0.52 % of p at (0.9, -0.274), 0.29 a
    !> from a tip; it halves when N doubles (checked against N = 1000 .. 4000).
    subroutine test_westergaard(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        real(wp) :: u(2, 289), s(3, 289), xs(289), ys(289), x, y, stress_scale, disp_scale
        integer :: i, j, np

        np = 0
        do j = 0, 16
            do i = 0, 16
                x = -2.0_wp * a + 0.25_wp * a * i
                y = -2.0_wp * a + 0.25_wp * a * j
                if (hypot(x - a, y) < 0.2_wp * a .or. hypot(x + a, y) < 0.2_wp * a) cycle
                if (j == 8 .and. abs(x) <= a) cycle
                np = np + 1
                xs(np) = x
                ys(np) = y
                call westergaard(x, y, u(:, np), s(:, np))
            end do
        end do
        stress_scale = maxval(abs(s(:, :np)))
        disp_scale = maxval(abs(u(:, :np)))
        model = straight_crack(500, a, 0.0_wp, condition_traction, 0.0_wp, -p, e_modulus, nu)
        deallocate (model%observations)
        allocate (model%observations(1))
        model%observations(1) = observation_set(name='points', kind=observation_points, nx=np, &
                                                ny=1, x=xs(:np), y=ys(:np))
        call run_model(model, r, error)
        if (allocated(error)) return
        associate (f => r%fields(1))
            call check(error, maxval(abs(f%sxx(:np) - s(1, :np))) / stress_scale, 0.0_wp, &
                       'sxx error / peak stress', abs_tol=5.0e-3_wp)
            call check(error, maxval(abs(f%syy(:np) - s(2, :np))) / stress_scale, 0.0_wp, &
                       'syy error / peak stress', abs_tol=5.0e-3_wp)
            call check(error, maxval(abs(f%sxy(:np) - s(3, :np))) / stress_scale, 0.0_wp, &
                       'sxy error / peak stress', abs_tol=5.0e-3_wp)
            call check(error, maxval(abs(f%ux(:np) - u(1, :np))) / disp_scale, 0.0_wp, &
                       'ux error / peak displacement', abs_tol=7.0e-3_wp)
            call check(error, maxval(abs(f%uy(:np) - u(2, :np))) / disp_scale, 0.0_wp, &
                       'uy error / peak displacement', abs_tol=7.0e-3_wp)
        end associate
    end subroutine test_westergaard

    !> Points on an element or at its end are flagged and NaN; points within one element
    !> length of a centre are flagged near; others are clear and finite.
    subroutine test_point_flags(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        real(wp), parameter :: xs(5) = [0.05_wp, 1.0_wp, 0.5_wp, 0.31_wp, 0.3_wp]
        real(wp), parameter :: ys(5) = [0.0_wp, 0.0_wp, 0.15_wp, 0.1_wp, 2.0_wp]
        integer, parameter :: expected(5) = [point_on_element, point_on_element, point_near, &
                                             point_near, point_clear]
        integer :: i

        ! Ten elements of length 0.2 on (-1, 0)-(1, 0).
        model = straight_crack(10, a, 0.0_wp, condition_traction, 0.0_wp, -p, e_modulus, nu)
        deallocate (model%observations)
        allocate (model%observations(1))
        model%observations(1) = observation_set(name='points', kind=observation_points, nx=5, &
                                                ny=1, x=xs, y=ys)
        call run_model(model, r, error)
        if (allocated(error)) return
        do i = 1, 5
            call check(error, r%fields(1)%flag(i), expected(i), 'flag of a point')
            call check(error, ieee_is_nan(r%fields(1)%sxx(i)) .eqv. &
                       (expected(i) == point_on_element), 'NaN exactly on flagged-on points')
        end do
    end subroutine test_point_flags

    !> The full-plane path (fused, vectorized sum over the elements and their images) gives
    !> the general kernel's fields within 1e-12 of each quantity's largest value, and the
    !> same flags exactly, on a grid around a kinked network, at its midpoints and ends
    !> and at points near it, with every symmetry.
    subroutine test_fast_fields(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(field_result) :: fast, general
        real(wp), allocatable :: x(:), y(:), ds(:), dn(:)
        real(wp) :: d
        integer :: i, j, sym, n
        character(len=40) :: label

        do sym = symmetry_none, symmetry_both
            model = kinked_network(sym)
            n = model%elements%n
            ds = [(1.0e-3_wp * sin(real(i, wp)), i = 1, n)]
            dn = [(-5.0e-4_wp * cos(2.0_wp * i), i = 1, n)]
            associate (e => model%elements)
                x = [((-0.2_wp + 0.07_wp * i, i = 0, 31), j = 0, 24), e%x_mid, e%x_begin, &
                     e%x_end, e%x_mid + 0.01_wp * e%sin_beta, e%x_begin - 1.0e-12_wp]
                y = [((-0.55_wp + 0.065_wp * j, i = 0, 31), j = 0, 24), e%y_mid, e%y_begin, &
                     e%y_end, e%y_mid - 0.01_wp * e%cos_beta, e%y_begin]
            end associate
            call evaluate_field(model%elements, g, nu, [-1.0_wp, -2.0_wp, 0.5_wp], ds, dn, x, &
                                y, fast, [0.1_wp, 0.2_wp, 0.0_wp])
            call evaluate_field(model%elements, g, nu, [-1.0_wp, -2.0_wp, 0.5_wp], ds, dn, x, &
                                y, general, [0.1_wp, 0.2_wp, 0.0_wp], general=.true.)
            write (label, '(a,i0)') 'symmetry ', sym
            call check(error, all(fast%flag == general%flag), trim(label)//': same flags')
            call check(error, count(fast%flag == point_on_element) >= 3 * n .and. &
                       count(fast%flag == point_near) > n, trim(label)//': on and near points')
            call check(error, all(ieee_is_nan(fast%sxx) .eqv. (fast%flag == point_on_element)), &
                       trim(label)//': NaN exactly on the elements')
            if (allocated(error)) return
            d = max(field_difference(fast%ux, general%ux, fast%flag), &
                    field_difference(fast%uy, general%uy, fast%flag))
            write (*, '(a,es10.3)') '    '//trim(label)//': displacement ', d
            call check(error, d, 0.0_wp, trim(label)//': displacement', abs_tol=1.0e-12_wp)
            d = max(field_difference(fast%sxx, general%sxx, fast%flag), &
                    field_difference(fast%syy, general%syy, fast%flag), &
                    field_difference(fast%sxy, general%sxy, fast%flag))
            write (*, '(a,es10.3)') '    '//trim(label)//': stress ', d
            call check(error, d, 0.0_wp, trim(label)//': stress', abs_tol=1.0e-12_wp)
            ! Two computations (the fast path is taken): round-off differs somewhere.
            call check(error, d > 0.0_wp, trim(label)//': the full-plane path is its own')
        end do
    end subroutine test_fast_fields

    !> Largest difference off the elements relative to the largest |b| there.
    pure real(wp) function field_difference(a, b, flag) result(d)
        real(wp), intent(in) :: a(:), b(:)
        integer, intent(in) :: flag(:)
        logical :: off(size(flag))

        off = flag /= point_on_element
        d = maxval(abs(a - b), off) / maxval(abs(b), off)
    end function field_difference

end module test_fields
