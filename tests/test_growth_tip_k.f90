!> K on grown tips (SPEC-GROWTH 1.4b and 7): the tip-zone calibration against closed forms.
!> A straight traction-free crack (half-length 1, 40 elements of 0.05) under syy = 10 grows
!> straight with increments from 1/50 to 4 times its element length and with new elements
!> twice as long as its tip element: K_I within 1 % of s sqrt(pi a) at every step (before:
!> up to 3.6x), both tips alike, `graded` 0 after calibration; K_II of a graded static
!> mesh under shear; the calibration factor itself; one and two threads.
module test_growth_tip_k
    use omp_lib, only: omp_set_num_threads, omp_get_max_threads
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, condition_traction
    use ddc_model_results, only: model_results, growth_grew
    use ddc_growth_driver, only: grow_fractures
    use ddc_growth_tip_zone, only: graded_factor, zone_size, calibrate_tips
    use ddc_run_model, only: run_model
    use ddc_test_builders, only: straight_crack, polyline_model
    use ddc_text, only: itoa
    implicit none
    private

    public :: collect_growth_tip_k

    real(wp), parameter :: e_modulus = 50000.0_wp, nu = 0.25_wp, s = 10.0_wp

contains

    !> Cases of the suite.
    subroutine collect_growth_tip_k(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('graded_factor_closed_forms', test_factor), &
                 new_test('mode_i_k_every_increment', test_mode_i_increments), &
                 new_test('mode_ii_k_graded_static_mesh', test_mode_ii_static), &
                 new_test('graded_k_one_and_two_threads', test_threads)]
    end subroutine collect_growth_tip_k

    !> The mode-I crack with growth: 5 steps, toughness 1 (every step critical).
    function mode_i_crack(increment, element_length) result(model)
        real(wp), intent(in) :: increment, element_length
        type(model_type) :: model

        model = straight_crack(40, 1.0_wp, 0.0_wp, condition_traction, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%syy = s
        model%growth%active = .true.
        model%growth%steps = 5
        model%growth%toughness = 1.0_wp
        model%growth%increment = increment
        model%growth%element_length = element_length
        allocate (model%growth%fracture_grows(1))
        model%growth%fracture_grows = .true.
    end function mode_i_crack

    !> Equal lengths: exactly 1 (no solve). One element of 1/50 at the tip of 0.05 m
    !> elements: the uncalibrated estimate is 3.6213 times the uniform mesh's 0.9969 (the
    !> design study's collinear solve and ddc2d agree on both), so f = 0.2753 within 0.5 %.
    !> The zone reaches eight lengths of its largest element.
    subroutine test_factor(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: f

        f = graded_factor(spread(0.05_wp, 1, 30), error)
        if (allocated(error)) return
        call check(error, f, 1.0_wp, 'equal lengths', abs_tol=0.0_wp)
        f = graded_factor([0.001_wp, spread(0.05_wp, 1, 60)], error)
        if (allocated(error)) return
        call check(error, f, 0.9969_wp / 3.6213_wp, 'one element of L/50', rel_tol=5.0e-3_wp)
        call check(error, zone_size(spread(1.0_wp, 1, 20)), 8, 'uniform zone: 8 elements')
        call check(error, zone_size([0.1_wp, spread(1.0_wp, 1, 20)]), 9, &
                   'a small tip element: 8 lengths of the large ones behind it')
    end subroutine test_factor

    !> Increments 0.001 (L/50), 0.025 and 0.075 in one new element each, 0.2 (4 L) in two
    !> elements of 0.1, and increment 0.1 with element_length 0.2 (one element of 0.1, 2 L):
    !> K_I of both tips within 1 % of s sqrt(pi a) at every step (a from the record's tip),
    !> the two tips alike (point symmetry), straight growth, final `graded` 0.
    subroutine test_mode_i_increments(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: increments(5) = [0.001_wp, 0.025_wp, 0.075_wp, 0.2_wp, 0.1_wp]
        real(wp), parameter :: lengths(5) = [0.001_wp, 0.025_wp, 0.075_wp, 0.1_wp, 0.2_wp]
        type(model_type) :: model
        type(model_results) :: r
        integer :: i, k
        real(wp) :: exact

        do i = 1, size(increments)
            model = mode_i_crack(increments(i), lengths(i))
            call grow_fractures(model, r, error)
            if (allocated(error)) return
            associate (g => r%growth)
                call check(error, size(g%step), 10, 'records, case '//itoa(i))
                if (allocated(error)) return
                call check(error, all(g%reason == growth_grew), 'every step grows, case '//itoa(i))
                do k = 1, size(g%step)
                    exact = s * sqrt(pi * abs(g%x(k)))
                    call check(error, g%k1(k), exact, 'K_I, case '//itoa(i)//' record '// &
                               itoa(k), rel_tol=1.0e-2_wp)
                end do
                do k = 1, size(g%step), 2
                    call check(error, g%k1(k), g%k1(k + 1), 'both tips alike, case '//itoa(i), &
                               rel_tol=1.0e-9_wp)
                end do
            end associate
            call check(error, maxval(abs(model%elements%y_begin)), 0.0_wp, 'straight', &
                       abs_tol=1.0e-12_wp)
            call check(error, r%tips%k1(2), s * sqrt(pi * r%tips%x(2)), 'final K_I, case '// &
                       itoa(i), rel_tol=1.0e-2_wp)
            call check(error, all(r%tips%graded == 0), 'calibrated: not graded, case '//itoa(i))
            if (allocated(error)) return
        end do
    end subroutine test_mode_i_increments

    !> K_II on a static mesh with graded tips (5 elements of 0.001 at each end of the 40
    !> elements of 0.05) under sxy = 10: calibrated within 1 % of s sqrt(pi a) (13 % high
    !> uncalibrated); a zone that turns 30 degrees is flagged graded.
    subroutine test_mode_ii_static(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        real(wp), parameter :: d = 0.005_wp
        real(wp) :: exact

        model = polyline_model([-1.0_wp - d, -1.0_wp, 1.0_wp, 1.0_wp + d], [0.0_wp, 0.0_wp, &
                               0.0_wp, 0.0_wp], [5, 40, 5], condition_traction, 0.0_wp, &
                               0.0_wp, e_modulus, nu)
        model%sxy = s
        call run_model(model, r, error)
        if (allocated(error)) return
        exact = s * sqrt(pi * (1.0_wp + d))
        call check(error, abs(r%tips%k2(2) / exact - 1.0_wp) > 0.05_wp, &
                   'uncalibrated K_II is off')
        if (allocated(error)) return
        call calibrate_tips(model, r%tips, error)
        if (allocated(error)) return
        call check(error, r%tips%k2(1), exact, 'calibrated K_II (begin)', rel_tol=1.0e-2_wp)
        call check(error, r%tips%k2(2), exact, 'calibrated K_II (end)', rel_tol=1.0e-2_wp)
        call check(error, all(r%tips%graded == 0), 'straight zone: not graded')
        ! The same tip zone turned by 30 degrees at x = 1.
        model = polyline_model([-1.0_wp - d, -1.0_wp, 1.0_wp, 1.0_wp + d * cos(pi / 6.0_wp)], &
                               [0.0_wp, 0.0_wp, 0.0_wp, d * sin(pi / 6.0_wp)], [5, 40, 5], &
                               condition_traction, 0.0_wp, 0.0_wp, e_modulus, nu)
        model%sxy = s
        if (allocated(error)) return
        call run_model(model, r, error)
        if (allocated(error)) return
        call calibrate_tips(model, r%tips, error)
        if (allocated(error)) return
        call check(error, r%tips%graded(1), 0, 'straight end: not graded')
        call check(error, r%tips%graded(2), 1, 'kinked zone of unequal elements: graded')
    end subroutine test_mode_ii_static

    !> The run with increment 1/50 of the element length on one and on two threads: the
    !> same records to round-off; two runs on two threads bit for bit.
    subroutine test_threads(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: one, two, again
        integer :: threads

        threads = omp_get_max_threads()
        model = mode_i_crack(0.001_wp, 0.001_wp)
        call omp_set_num_threads(1)
        call grow_fractures(model, one, error)
        if (allocated(error)) then
            call omp_set_num_threads(threads)
            return
        end if
        model = mode_i_crack(0.001_wp, 0.001_wp)
        call omp_set_num_threads(2)
        call grow_fractures(model, two, error)
        if (.not. allocated(error)) then
            model = mode_i_crack(0.001_wp, 0.001_wp)
            call grow_fractures(model, again, error)
        end if
        call omp_set_num_threads(threads)
        if (allocated(error)) return
        call check(error, maxval(abs(one%growth%k1 - two%growth%k1)), 0.0_wp, &
                   'K_I, 1 vs 2 threads', abs_tol=1.0e-10_wp * maxval(abs(one%growth%k1)))
        call check(error, all(two%growth%k1 == again%growth%k1) .and. &
                   all(two%tips%k1 == again%tips%k1), 'two runs on 2 threads bit for bit')
    end subroutine test_threads

end module test_growth_tip_k
