!> Displacement and mixed conditions: a circular hole of radius r0 under internal pressure p,
!> u_r = p r0^2 / (2 G r), s_rr = -p r0^2 / r^2, s_tt = p r0^2 / r^2 (Lame).
module test_hole
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, observation_set, observation_points, &
        condition_traction, condition_displacement, condition_mixed_us_sn, condition_mixed_ss_un
    use ddc_model_results, only: model_results
    use ddc_run_model, only: run_model
    use ddc_test_builders, only: circular_hole
    implicit none
    private

    public :: collect_hole

    real(wp), parameter :: e_modulus = 200.0_wp, nu = 0.3_wp, g = e_modulus / 2.6_wp
    real(wp), parameter :: p = 5.0_wp, r0 = 1.0_wp
    integer, parameter :: n = 400

contains

    !> Cases of the hole suite.
    subroutine collect_hole(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('traction', test_traction), &
                 new_test('displacement', test_displacement), &
                 new_test('mixed_us_sn', test_mixed_us_sn), &
                 new_test('mixed_ss_un', test_mixed_ss_un)]
    end subroutine collect_hole

    !> Solve the hole model and compare u_r, s_rr and s_tt at r = 1.5, 2 and 4 r0 on three
    !> rays, within 0.5 % of the largest exact value at that radius (N = 400 elements), and
    !> the face displacement of the body side of every element within 0.5 % of p r0 / 2G.
    subroutine check_lame(error, model)
        type(error_type), allocatable, intent(inout) :: error
        type(model_type), intent(inout) :: model
        type(model_results) :: r
        real(wp), parameter :: radii(3) = [1.5_wp, 2.0_wp, 4.0_wp]
        real(wp), parameter :: angles(3) = [0.1_wp, 1.3_wp, 4.0_wp]
        real(wp) :: xs(9), ys(9), c, s, ur, srr, stt, exact
        integer :: i, j, k

        do j = 1, 3
            do i = 1, 3
                xs(3 * (j - 1) + i) = radii(i) * r0 * cos(angles(j))
                ys(3 * (j - 1) + i) = radii(i) * r0 * sin(angles(j))
            end do
        end do
        deallocate (model%observations)
        allocate (model%observations(1))
        model%observations(1) = observation_set(name='rays', kind=observation_points, nx=9, &
                                                ny=1, x=xs, y=ys)
        call run_model(model, r, error)
        if (allocated(error)) return
        associate (f => r%fields(1))
            do k = 1, 9
                c = cos(atan2(ys(k), xs(k)))
                s = sin(atan2(ys(k), xs(k)))
                ur = f%ux(k) * c + f%uy(k) * s
                srr = f%sxx(k) * c**2 + 2 * f%sxy(k) * s * c + f%syy(k) * s**2
                stt = f%sxx(k) * s**2 - 2 * f%sxy(k) * s * c + f%syy(k) * c**2
                exact = p * r0**2 / hypot(xs(k), ys(k))**2
                call check(error, srr, -exact, 's_rr', abs_tol=5.0e-3_wp * exact)
                call check(error, stt, exact, 's_tt', abs_tol=5.0e-3_wp * exact)
                call check(error, ur, p * r0**2 / (2 * g * hypot(xs(k), ys(k))), 'u_r', &
                           rel_tol=5.0e-3_wp)
            end do
        end associate
        ! The body is on the negative face; its normal n points into the hole.
        call check(error, maxval(abs(r%elements%un_minus + p * r0 / (2 * g))), 0.0_wp, &
                   'un(-) = -u_r(r0)', abs_tol=5.0e-3_wp * p * r0 / (2 * g))
        call check(error, maxval(abs(r%elements%normal_traction + p)), 0.0_wp, &
                   's_n = -p on the wall', abs_tol=5.0e-3_wp * p)
    end subroutine check_lame

    !> Pressure given as traction: s_s = 0, s_n = -p.
    subroutine test_traction(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model

        model = circular_hole(n, r0, condition_traction, 0.0_wp, -p, e_modulus, nu)
        call check_lame(error, model)
    end subroutine test_traction

    !> The exact wall displacement given: u_s = 0, u_n = -p r0 / (2 G).
    subroutine test_displacement(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model

        model = circular_hole(n, r0, condition_displacement, 0.0_wp, -p * r0 / (2 * g), &
                              e_modulus, nu)
        call check_lame(error, model)
    end subroutine test_displacement

    !> u_s = 0 and s_n = -p.
    subroutine test_mixed_us_sn(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model

        model = circular_hole(n, r0, condition_mixed_us_sn, 0.0_wp, -p, e_modulus, nu)
        call check_lame(error, model)
    end subroutine test_mixed_us_sn

    !> s_s = 0 and u_n = -p r0 / (2 G).
    subroutine test_mixed_ss_un(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model

        model = circular_hole(n, r0, condition_mixed_ss_un, 0.0_wp, -p * r0 / (2 * g), &
                              e_modulus, nu)
        call check_lame(error, model)
    end subroutine test_mixed_ss_un

end module test_hole
