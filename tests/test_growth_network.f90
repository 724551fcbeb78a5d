!> Growth results that do not depend on the discretization (SPEC-GROWTH 1.4 and 7): closed
!> kinks do not grow (reason closed), so the wings of a sliding flaw do not zig-zag once they
!> close and arrest at the same length, in the same direction, for increments 0.05, 0.1 and
!> 0.2; with tips = 'most_critical' a closed tip hands over to the next critical one.
module test_growth_network
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, condition_contact, growth_tips_most_critical
    use ddc_model_results, only: model_results, growth_grew, growth_corrector_failed, &
        growth_closed, growth_waiting, growth_arrested
    use ddc_growth_driver, only: grow_fractures
    use ddc_test_builders, only: polyline_model
    use ddc_text, only: itoa
    implicit none
    private

    public :: collect_growth_network

    real(wp), parameter :: e_modulus = 50000.0_wp, nu = 0.25_wp
    real(wp), parameter :: degrees = 180.0_wp / pi

contains

    !> Cases of the suite.
    subroutine collect_growth_network(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('closed_wings_do_not_zigzag', test_no_zigzag), &
                 new_test('closed_kink_does_not_grow', test_closed_reason), &
                 new_test('closed_most_critical_hands_over', test_closed_most_critical), &
                 new_test('wing_arrest_converges', test_wing_convergence)]
    end subroutine collect_growth_network

    !> The wing flaw of SPEC-GROWTH 7: a 2 m frictional flaw at 45 degrees to sigma_1
    !> (sxx = -5, syy = -100), mu = 0.6, Sf = 0, 40 elements; toughness, increment given.
    function wing_flaw(toughness, increment) result(model)
        real(wp), intent(in) :: toughness, increment
        type(model_type) :: model
        real(wp), parameter :: c = 0.70710678118654752_wp

        model = polyline_model([-c, c], [-c, c], [40], condition_contact, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%elements%mu = 0.6_wp
        model%elements%sf = 0.0_wp
        model%sxx = -5.0_wp
        model%syy = -100.0_wp
        model%growth%active = .true.
        model%growth%steps = 60
        model%growth%toughness = toughness
        model%growth%increment = increment
        model%growth%override_sf = .true.
        model%growth%new_sf = 0.0_wp
        allocate (model%growth%fracture_grows(1))
        model%growth%fracture_grows = .true.
    end function wing_flaw

    !> Rows of the end tip's records.
    function end_rows(r) result(rows)
        type(model_results), intent(in) :: r
        integer, allocatable :: rows(:)
        integer :: i

        rows = pack([(i, i = 1, size(r%growth%step))], r%growth%end == 1)
    end function end_rows

    !> Increments 0.1 and 0.2 (the first version zig-zagged at +-70.53 after the wings
    !> closed, and with 0.2 never arrested): no tip grows after step 1 with K_I = 0, the
    !> applied angles after step 2 keep one sign, and the run arrests.
    subroutine test_no_zigzag(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: increments(2) = [0.1_wp, 0.2_wp]
        type(model_type) :: model
        type(model_results) :: r
        integer, allocatable :: rows(:)
        integer :: i, k
        logical :: grew

        do i = 1, size(increments)
            model = wing_flaw(2.0_wp, increments(i))
            call grow_fractures(model, r, error)
            if (allocated(error)) return
            associate (g => r%growth)
                call check(error, g%end_reason, growth_arrested, 'arrested')
                do k = 1, size(g%step)
                    grew = g%reason(k) == growth_grew .or. g%reason(k) == growth_corrector_failed
                    call check(error, .not. (g%step(k) > 1 .and. grew .and. g%k1(k) <= 0.0_wp), &
                               'no closed tip grows after step 1 (record '//itoa(k)//')')
                end do
                rows = end_rows(r)
                do k = 3, size(rows)
                    if (ieee_is_nan(g%angle(rows(k)))) cycle
                    call check(error, sign(1.0_wp, g%angle(rows(k))) == &
                               sign(1.0_wp, g%angle(rows(2))), 'angles keep one sign (step '// &
                               itoa(k)//')')
                end do
            end associate
            if (allocated(error)) return
        end do
    end subroutine test_no_zigzag

    !> Toughness 0.1 (increment 0.1): after 11 steps both tips are critical (K_I > 0 at the
    !> old tip) but the kink at the MTS angle closes: reason closed after one solve, no
    !> growth (length 0, angle NaN), and the run ends arrested (the next step would repeat
    !> the same geometry).
    subroutine test_closed_reason(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        integer :: last, n_before, k

        model = wing_flaw(0.1_wp, 0.1_wp)
        n_before = 40
        call grow_fractures(model, r, error)
        if (allocated(error)) return
        associate (g => r%growth)
            call check(error, g%end_reason, growth_arrested, 'arrested')
            last = maxval(g%step)
            call check(error, g%steps_taken, last - 1, 'the last step grew nothing')
            call check(error, count(g%step == last), 2, 'both tips have a record in the last step')
            if (allocated(error)) return
            do k = size(g%step) - 1, size(g%step)
                call check(error, g%reason(k), growth_closed, 'reason closed')
                call check(error, g%k1(k) > 0.0_wp, 'the old tip is open')
                call check(error, g%k_eq(k) >= 0.1_wp, 'the tip is critical')
                call check(error, g%length(k), 0.0_wp, 'no growth', abs_tol=0.0_wp)
                call check(error, ieee_is_nan(g%angle(k)), 'no applied angle')
                ! The kink at the MTS angle, then at four halved angles towards straight
                ! ahead (the old tip is open): every one closed.
                call check(error, g%corrections(k), 5, 'five solves: every kink closed')
            end do
            call check(error, model%elements%n, n_before + 2 * 2 * g%steps_taken, &
                       'two elements per tip per step that grew')
        end associate
    end subroutine test_closed_reason

    !> tips = 'most_critical' on the same flaw: a step whose most critical tip closes tries
    !> the next critical tip in the same step, so no tip still waits when the run arrests.
    subroutine test_closed_most_critical(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        integer :: last

        model = wing_flaw(0.1_wp, 0.1_wp)
        model%growth%tips = growth_tips_most_critical
        call grow_fractures(model, r, error)
        if (allocated(error)) return
        associate (g => r%growth)
            call check(error, g%end_reason, growth_arrested, 'arrested')
            last = maxval(g%step)
            call check(error, count(g%step == last .and. g%reason == growth_closed), 2, &
                       'both tips closed in the last step')
            call check(error, count(g%step == last .and. g%reason == growth_waiting), 0, &
                       'no tip waits in the last step')
        end associate
    end subroutine test_closed_most_critical

    !> SPEC-GROWTH 7: the wings' arrest length (per wing) within 10 % and their final
    !> direction within 5 degrees for increments 0.05, 0.1 and 0.2. Without going back from
    !> a closed corrected trial the wings stop at 0.8 m for 0.1 and 0.2 against 0.95 m.
    subroutine test_wing_convergence(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: increments(3) = [0.05_wp, 0.1_wp, 0.2_wp]
        type(model_type) :: model
        type(model_results) :: r
        real(wp) :: length(3), direction(3)
        integer :: i, n
        integer, allocatable :: rows(:)

        do i = 1, size(increments)
            model = wing_flaw(2.0_wp, increments(i))
            call grow_fractures(model, r, error)
            if (allocated(error)) return
            call check(error, r%growth%end_reason, growth_arrested, 'arrested, increment '// &
                       itoa(i))
            rows = end_rows(r)
            length(i) = sum(r%growth%length(rows))
            n = model%elements%n
            direction(i) = atan2(model%elements%y_end(n) - model%elements%y_begin(n), &
                                 model%elements%x_end(n) - model%elements%x_begin(n)) * degrees
        end do
        if (allocated(error)) return
        call check(error, length(1) > 0.5_wp, 'the wings grow')
        call check(error, maxval(length) <= 1.1_wp * minval(length), &
                   'arrest lengths within 10 %: '//lengths_text())
        call check(error, maxval(direction) - minval(direction) <= 5.0_wp, &
                   'final directions within 5 degrees')
        ! The wings turn towards sigma_1 (y, 90 degrees).
        call check(error, direction(1), 90.0_wp, 'final direction', abs_tol=10.0_wp)

    contains

        function lengths_text() result(text)
            character(len=:), allocatable :: text
            character(len=60) :: buffer

            write (buffer, '(3(f8.4))') length
            text = trim(buffer)
        end function lengths_text

    end subroutine test_wing_convergence

end module test_growth_network
