!> The same results with 1 and 2 OpenMP threads, bit for bit (README, Threads): every OpenMP
!> loop writes disjoint results, each summed in a fixed order.
module test_threads
    use omp_lib, only: omp_set_num_threads, omp_get_max_threads
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, observation_set, observation_grid, condition_traction
    use ddc_model_results, only: model_results
    use ddc_run_model, only: run_model
    use ddc_test_builders, only: straight_crack
    implicit none
    private

    public :: collect_threads

contains

    !> Cases of the threads suite.
    subroutine collect_threads(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('one_and_two_threads_agree', test_agree)]
    end subroutine collect_threads

    !> Largest difference relative to the largest magnitude.
    pure real(wp) function difference(a, b)
        real(wp), intent(in) :: a(:), b(:)

        difference = maxval(abs(a - b)) / max(maxval(abs(a)), tiny(1.0_wp))
    end function difference

    !> An inclined crack under a general remote stress with a 30 x 20 grid.
    subroutine test_agree(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: one, two
        integer :: saved, i, j

        model = straight_crack(300, 1.0_wp, 0.5_wp, condition_traction, 0.3_wp, -1.0_wp, &
                               100.0_wp, 0.2_wp)
        model%sxx = -2.0_wp
        model%syy = -1.0_wp
        model%sxy = 0.7_wp
        deallocate (model%observations)
        allocate (model%observations(1))
        model%observations(1) = observation_set(name='grid', kind=observation_grid, nx=30, &
            ny=20, x=[((-1.5_wp + 0.1_wp * i, i = 0, 29), j = 0, 19)], &
            y=[((-1.0_wp + 0.1_wp * j + 0.013_wp, i = 0, 29), j = 0, 19)])
        saved = omp_get_max_threads()
        call omp_set_num_threads(1)
        call run_model(model, one, error)
        if (allocated(error)) return
        call omp_set_num_threads(2)
        call run_model(model, two, error)
        call omp_set_num_threads(saved)
        if (allocated(error)) return
        call check(error, two%solver%threads, 2, 'threads recorded')
        call check(error, difference(one%elements%ds, two%elements%ds), 0.0_wp, 'ds', &
                   abs_tol=0.0_wp)
        call check(error, difference(one%elements%dn, two%elements%dn), 0.0_wp, 'dn', &
                   abs_tol=0.0_wp)
        call check(error, difference(one%elements%us_minus, two%elements%us_minus), 0.0_wp, &
                   'us(-)', abs_tol=0.0_wp)
        call check(error, difference(one%fields(1)%sxx, two%fields(1)%sxx), 0.0_wp, 'sxx', &
                   abs_tol=0.0_wp)
        call check(error, difference(one%fields(1)%uy, two%fields(1)%uy), 0.0_wp, 'uy', &
                   abs_tol=0.0_wp)
        call check(error, difference(one%tips%k1, two%tips%k1), 0.0_wp, 'k1', abs_tol=0.0_wp)
    end subroutine test_agree

end module test_threads
