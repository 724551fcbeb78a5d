!> Linking (SPEC-GROWTH 1.6, SPEC-GROWTH 7): a tip whose next increment meets another fracture
!> ends on it (reason linked), on a vertex of it or on a vertex split into its element, and
!> is no tip any more; the DDs pass the junction; links that would cross a third element,
!> meet another tip or close a contour are refused (intersection); the kept (Newton) path
!> links as Lemke does.
module test_growth_link
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, condition_traction, condition_contact
    use ddc_contact_options, only: lcp_newton, lcp_lemke
    use ddc_model_results, only: model_results, growth_grew, growth_intersection, &
        growth_linked
    use ddc_mesh_checks, only: check_elements
    use ddc_growth_driver, only: grow_fractures
    use ddc_test_builders, only: straight_crack, polyline_model, join_fractures
    use test_growth, only: enable_growth, tip_records, difference, grow_on_one_and_two_threads
    implicit none
    private

    public :: collect_growth_link

    real(wp), parameter :: e_modulus = 50000.0_wp, nu = 0.25_wp

contains

    !> Cases of the suite.
    subroutine collect_growth_link(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('links_into_fault_on_a_vertex', test_fault_snap), &
                 new_test('links_into_fault_splitting_an_element', test_fault_split), &
                 new_test('echelon_links_into_one_fault', test_echelon), &
                 new_test('links_in_the_corrector', test_corrector_link), &
                 new_test('link_refused_at_a_tip', test_refused_at_tip), &
                 new_test('link_refused_by_a_third_element', test_refused_third), &
                 new_test('link_refused_head_on', test_refused_head_on), &
                 new_test('link_one_and_two_threads_agree', test_threads), &
                 new_test('link_on_the_kept_path', test_kept_path)]
    end subroutine collect_growth_link

    ! ---- helpers ------------------------------------------------------------------------

    !> The issue's echelon step (issue 24): west x -1.9 .. 0.1 at y 0.1, east x -0.1 .. 1.9 at
    !> y -0.1, 40 contact elements each (mu 0.6, Sf 0), right-lateral shear in a releasing
    !> step, toughness 0.5.
    function echelon() result(model)
        type(model_type) :: model
        type(model_type) :: east

        model = polyline_model([-1.9_wp, 0.1_wp], [0.1_wp, 0.1_wp], [40], condition_contact, &
                               0.0_wp, 0.0_wp, e_modulus, nu)
        east = polyline_model([-0.1_wp, 1.9_wp], [-0.1_wp, -0.1_wp], [40], condition_contact, &
                              0.0_wp, 0.0_wp, e_modulus, nu)
        call join_fractures(model, east)
        model%elements%mu = 0.6_wp
        model%elements%sf = 0.0_wp
        model%sxx = -15.5_wp
        model%syy = -6.5_wp
        model%sxy = 7.794_wp
        call enable_growth(model, 20, 0.5_wp)
    end function echelon

    !> A traction-free crack (x -1 .. 1, 40 elements) under syy = 10 growing straight along x
    !> towards a fault across its path at x = 1.25 from y = y0 to y0 + 1 (20 elements, may not
    !> grow), toughness 5.
    function crack_and_fault(y0) result(model)
        real(wp), intent(in) :: y0
        type(model_type) :: model
        type(model_type) :: fault

        model = straight_crack(40, 1.0_wp, 0.0_wp, condition_traction, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        fault = polyline_model([1.25_wp, 1.25_wp], [y0, y0 + 1.0_wp], [20], condition_traction, &
                               0.0_wp, 0.0_wp, e_modulus, nu)
        call join_fractures(model, fault)
        model%syy = 10.0_wp
        call enable_growth(model, 5, 5.0_wp)
        model%growth%fracture_grows(2) = .false.
    end function crack_and_fault

    !> The number of elements whose begin or end is (x, y) bit for bit.
    pure integer function elements_at(model, x, y)
        type(model_type), intent(in) :: model
        real(wp), intent(in) :: x, y

        associate (e => model%elements)
            elements_at = count(e%x_begin == x .and. e%y_begin == y) + &
                          count(e%x_end == x .and. e%y_end == y)
        end associate
    end function elements_at

    !> Whether a fracture is one ordered polyline: each element begins where the one before
    !> ends, bit for bit.
    pure logical function ordered(model, f)
        type(model_type), intent(in) :: model
        integer, intent(in) :: f
        integer :: k

        ordered = .true.
        associate (e => model%elements, r => model%fractures(f))
            do k = r%first_element + 1, r%last_element
                ordered = ordered .and. e%x_begin(k) == e%x_end(k - 1) .and. &
                          e%y_begin(k) == e%y_end(k - 1)
            end do
        end associate
    end function ordered

    !> The DDs pass a junction (x, y) where elements end and begin: with D = ds t + dn n of
    !> each element (t its direction, n the left normal), the D of the elements that end there
    !> add up to those of the elements that begin there (the discrete balance of a branch
    !> point, to 10 % of the largest |D|), and every |D| is not zero.
    subroutine check_junction(error, model, r, x, y, what)
        type(error_type), allocatable, intent(inout) :: error
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: r
        real(wp), intent(in) :: x, y
        character(len=*), intent(in) :: what
        real(wp) :: balance(2), d(2), largest, smallest
        integer :: k

        balance = 0.0_wp
        largest = 0.0_wp
        smallest = huge(1.0_wp)
        associate (e => model%elements)
            do k = 1, e%n
                if (.not. ((e%x_end(k) == x .and. e%y_end(k) == y) .or. &
                           (e%x_begin(k) == x .and. e%y_begin(k) == y))) cycle
                d = r%elements%ds(k) * [e%cos_beta(k), e%sin_beta(k)] + &
                    r%elements%dn(k) * [-e%sin_beta(k), e%cos_beta(k)]
                largest = max(largest, norm2(d))
                smallest = min(smallest, norm2(d))
                if (e%x_end(k) == x .and. e%y_end(k) == y) then
                    balance = balance + d
                else
                    balance = balance - d
                end if
            end do
        end associate
        call check(error, smallest > 1.0e-3_wp * largest .and. largest > 0.0_wp, &
                   what//': DDs at the junction not zero')
        call check(error, norm2(balance) <= 0.1_wp * largest, what//': DDs pass the junction')
    end subroutine check_junction

    ! ---- cases --------------------------------------------------------------------------

    !> The crack's end tip grows 1.0 -> 1.1 -> 1.2 and then would cross the fault at y = 0,
    !> a vertex of it: it links there (reason linked in step 3, length 0.05, straight on;
    !> it replaces the first version's test that the tip stops half an element short),
    !> the fault keeps its 20 elements, its vertex is the crack's last one, the tip has no
    !> record after linking and is no tip; the DDs pass the junction.
    subroutine test_fault_snap(error)
        type(error_type), allocatable, intent(out) :: error

        call link_into_fault(error, -0.5_wp, 20)
    end subroutine test_fault_snap

    !> As test_fault_snap with the fault from y = -0.525: the crossing at y = 0 is the middle
    !> of an element, which is split there (21 elements).
    subroutine test_fault_split(error)
        type(error_type), allocatable, intent(out) :: error

        call link_into_fault(error, -0.525_wp, 21)
    end subroutine test_fault_split

    !> The crack growing into the fault from y0, which has `fault_elements` after linking.
    subroutine link_into_fault(error, y0, fault_elements)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: y0
        integer, intent(in) :: fault_elements
        type(model_type) :: model
        type(model_results) :: r
        integer, allocatable :: rows(:)
        real(wp) :: px, py
        integer :: k

        model = crack_and_fault(y0)
        call grow_fractures(model, r, error)
        if (allocated(error)) return
        rows = tip_records(r, 1, 1)
        call check(error, size(rows), 3, 'records of the end tip')
        if (allocated(error)) return
        call check(error, r%growth%reason(rows(1)), growth_grew, 'step 1')
        call check(error, r%growth%reason(rows(2)), growth_grew, 'step 2')
        call check(error, r%growth%reason(rows(3)), growth_linked, 'step 3 links')
        ! Nearly straight on (a fault not symmetric about the crack's line turns it a little).
        call check(error, r%growth%length(rows(3)), 0.05_wp, 'link length', rel_tol=1.0e-3_wp)
        call check(error, r%growth%angle(rows(3)), 0.0_wp, 'straight on', abs_tol=1.0_wp)
        call check(error, size(tip_records(r, 1, 0)), 5, 'the begin tip grows on')
        associate (e => model%elements, f => model%fractures)
            k = f(1)%last_element
            px = e%x_end(k)
            py = e%y_end(k)
            call check(error, px, 1.25_wp, 'the link ends on the fault', rel_tol=1.0e-12_wp)
            call check(error, py, 0.0_wp, 'near y = 0', abs_tol=2.0e-3_wp)
            call check(error, f(2)%last_element - f(2)%first_element + 1, fault_elements, &
                       'elements of the fault')
            call check(error, ordered(model, 2), 'the fault is one ordered polyline')
            call check(error, elements_at(model, px, py), 3, &
                           'the link and two fault elements share the vertex')
        end associate
        call check(error, .not. any(abs(r%tips%x - px) < 1.0e-9_wp .and. &
                                    abs(r%tips%y - py) < 1.0e-9_wp), 'no tip at the link')
        call check_junction(error, model, r, px, py, 'fault')
        if (allocated(error)) return
        call check_elements(model%elements, model%fractures, error)
    end subroutine link_into_fault

    !> The issue's echelon step: both inner tips kink into the step (step 1); in step 2 the
    !> west one links to the east segment (it comes first; linking the east one too would
    !> close a contour around the block between them: refused, intersection). The network
    !> is one fault (west, the link, east beyond the link point); the outer tips arrest;
    !> the mesh is valid, the link vertex is no tip and the DDs pass the junction.
    subroutine test_echelon(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        integer, allocatable :: west_end(:), east_begin(:)
        real(wp) :: px, py
        integer :: k

        model = echelon()
        call grow_fractures(model, r, error)
        if (allocated(error)) return
        west_end = tip_records(r, 1, 1)
        east_begin = tip_records(r, 2, 0)
        call check(error, size(west_end), 2, 'records of the west inner tip')
        call check(error, size(east_begin), 2, 'records of the east inner tip')
        if (allocated(error)) return
        call check(error, r%growth%reason(west_end(1)), growth_grew, 'west kinks')
        call check(error, r%growth%reason(east_begin(1)), growth_grew, 'east kinks')
        call check(error, r%growth%angle(west_end(1)), r%growth%angle(east_begin(1)), &
                   'point-symmetric kinks', abs_tol=1.0e-9_wp)
        call check(error, r%growth%reason(west_end(2)), growth_linked, 'west links')
        call check(error, r%growth%reason(east_begin(2)), growth_intersection, &
                   'east refused: the contour would close')
        call check(error, r%growth%step(west_end(2)), 2, 'linked in step 2')
        associate (e => model%elements, f => model%fractures)
            k = f(1)%last_element
            px = e%x_end(k)
            py = e%y_end(k)
            call check(error, any(e%x_begin(f(2)%first_element:f(2)%last_element) == px .and. &
                                  e%y_begin(f(2)%first_element:f(2)%last_element) == py), &
                       'the link ends on a vertex of east')
            call check(error, py, -0.1_wp, 'on east', abs_tol=1.0e-12_wp)
            call check(error, ordered(model, 2), 'east is one ordered polyline')
        end associate
        call check(error, .not. any(abs(r%tips%x - px) < 1.0e-9_wp .and. &
                                    abs(r%tips%y - py) < 1.0e-9_wp), 'no tip at the link')
        call check(error, r%tips%n, 3, 'three tips: the outer ones and the refused one')
        call check_junction(error, model, r, px, py, 'echelon')
        if (allocated(error)) return
        call check_elements(model%elements, model%fractures, error)
    end subroutine test_echelon

    !> A traction-free crack under sxy kinks from both tips (MTS -70.5 degrees, corrected
    !> -74.9); below its end tip a strong fault (y = -0.121, x 0.6 .. 1.6, 20 contact
    !> elements that stick) leaves the predictor's path clear, but the first corrected angle
    !> takes the path within half an element of it: the tip links in the corrector (after
    !> one solve), to the fault's vertex below the tip; the begin tip is corrected with the
    !> link in its trials and grows; the mesh checks pass.
    subroutine test_corrector_link(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, fault
        type(model_results) :: r
        integer, allocatable :: rows(:)
        integer :: k

        model = straight_crack(40, 1.0_wp, 0.0_wp, condition_traction, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        fault = polyline_model([0.6_wp, 1.6_wp], [-0.121_wp, -0.121_wp], [20], &
                               condition_contact, 0.0_wp, 0.0_wp, e_modulus, nu)
        call join_fractures(model, fault)
        model%elements%mu = 0.6_wp
        model%elements%sf = 100.0_wp
        model%sxy = 10.0_wp
        call enable_growth(model, 1, 1.0_wp)
        model%growth%fracture_grows(2) = .false.
        call grow_fractures(model, r, error)
        if (allocated(error)) return
        rows = tip_records(r, 1, 1)
        call check(error, size(rows), 1, 'one record of the end tip')
        if (allocated(error)) return
        call check(error, r%growth%reason(rows(1)), growth_linked, 'the end tip links')
        call check(error, r%growth%corrections(rows(1)), 1, 'in the corrector, after one solve')
        rows = tip_records(r, 1, 0)
        call check(error, r%growth%reason(rows(1)), growth_grew, 'the begin tip grows')
        call check(error, r%growth%angle(rows(1)), -74.9_wp, 'corrected', abs_tol=0.5_wp)
        associate (e => model%elements, f => model%fractures)
            k = f(1)%last_element
            call check(error, e%y_end(k), -0.121_wp, 'the link ends on the fault', &
                       rel_tol=1.0e-12_wp)
            call check(error, elements_at(model, e%x_end(k), e%y_end(k)), 3, &
                       'on a vertex of it')
        end associate
        if (allocated(error)) return
        call check_elements(model%elements, model%fractures, error)
    end subroutine test_corrector_link

    !> A crack growing straight at the lower end of a fault that begins on its line (x 1.25,
    !> y 0 .. 1): the tips would meet, not link: the tip stops (intersection).
    subroutine test_refused_at_tip(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r
        integer, allocatable :: rows(:)

        model = crack_and_fault(0.0_wp)
        call grow_fractures(model, r, error)
        if (allocated(error)) return
        rows = tip_records(r, 1, 1)
        call check(error, r%growth%reason(rows(size(rows))), growth_intersection, &
                   'the tip stops')
        call check(error, count(r%growth%reason == growth_linked), 0, 'no link')
        call check(error, model%fractures(2)%last_element - model%fractures(2)%first_element &
                   + 1, 20, 'the fault keeps its elements')
    end subroutine test_refused_at_tip

    !> A crack along y = 0.06 growing towards a coarse fault (x 1.25, y -0.4 .. 0.4, two
    !> elements): it would cross it about 0.08 from its middle vertex, within a quarter
    !> element, so the link snaps to that vertex and runs down to it. Alone it links; with a
    !> short third fracture across the link's way (y = 0.035, 0.04 below the path: the path
    !> keeps clear of it) the link is refused (intersection); the fault keeps two elements.
    subroutine test_refused_third(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, fault, third
        type(model_results) :: r
        integer, allocatable :: rows(:)
        integer :: with_third

        do with_third = 0, 1
            model = polyline_model([-1.0_wp, 1.0_wp], [0.06_wp, 0.06_wp], [40], &
                                   condition_traction, 0.0_wp, 0.0_wp, e_modulus, nu)
            fault = polyline_model([1.25_wp, 1.25_wp], [-0.4_wp, 0.4_wp], [2], &
                                   condition_traction, 0.0_wp, 0.0_wp, e_modulus, nu)
            call join_fractures(model, fault)
            if (with_third == 1) then
                third = polyline_model([1.215_wp, 1.235_wp], [0.035_wp, 0.035_wp], [1], &
                                       condition_traction, 0.0_wp, 0.0_wp, e_modulus, nu)
                call join_fractures(model, third)
            end if
            model%syy = 10.0_wp
            call enable_growth(model, 4, 5.0_wp)
            model%growth%fracture_grows(2:) = .false.
            call grow_fractures(model, r, error)
            if (allocated(error)) return
            rows = tip_records(r, 1, 1)
            call check(error, size(rows), 3, 'it meets the fault in step 3')
            if (allocated(error)) return
            call check(error, r%growth%reason(rows(size(rows))), merge(growth_intersection, &
                       growth_linked, with_third == 1), 'the end tip''s last record')
            call check(error, model%fractures(2)%last_element - &
                       model%fractures(2)%first_element + 1, 2, 'the fault keeps two elements')
            if (allocated(error)) return
        end do
    end subroutine test_refused_third

    !> Two collinear cracks growing towards each other (x -1.2 .. -0.2 and 0.2 .. 1.2 under
    !> syy): in the step where their paths would meet, both stop (intersection), none links.
    subroutine test_refused_head_on(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, other
        type(model_results) :: r
        integer, allocatable :: rows(:)

        model = polyline_model([-1.2_wp, -0.2_wp], [0.0_wp, 0.0_wp], [20], condition_traction, &
                               0.0_wp, 0.0_wp, e_modulus, nu)
        other = polyline_model([0.2_wp, 1.2_wp], [0.0_wp, 0.0_wp], [20], condition_traction, &
                               0.0_wp, 0.0_wp, e_modulus, nu)
        call join_fractures(model, other)
        model%syy = 10.0_wp
        call enable_growth(model, 4, 3.0_wp)
        call grow_fractures(model, r, error)
        if (allocated(error)) return
        call check(error, count(r%growth%reason == growth_linked), 0, 'no link')
        rows = tip_records(r, 1, 1)
        call check(error, r%growth%reason(rows(size(rows))), growth_intersection, &
                   'west inner tip stops')
        rows = tip_records(r, 2, 0)
        call check(error, r%growth%reason(rows(size(rows))), growth_intersection, &
                   'east inner tip stops')
    end subroutine test_refused_head_on

    !> The echelon's link with 1 and 2 OpenMP threads: the same records and geometry.
    subroutine test_threads(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: one, two

        model = echelon()
        model%growth%steps = 3
        call grow_on_one_and_two_threads(model, one, two, error)
        if (allocated(error)) return
        call check(error, count(one%growth%reason == growth_linked), 1, 'one link')
    end subroutine test_threads

    !> The echelon on the growth solver's kept path (Newton: its linking step assembles and
    !> factorizes its trials whole, the split moves no base element) and with Lemke from
    !> scratch: the same records, geometry and DDs.
    subroutine test_kept_path(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: kept_model, lemke_model
        type(model_results) :: kept, lemke

        kept_model = echelon()
        kept_model%growth%steps = 3
        lemke_model = kept_model
        kept_model%solver%lcp_method = lcp_newton
        lemke_model%solver%lcp_method = lcp_lemke
        call grow_fractures(kept_model, kept, error)
        if (allocated(error)) return
        call grow_fractures(lemke_model, lemke, error)
        if (allocated(error)) return
        call check(error, kept%solver%method == 'newton', 'the kept path: Newton')
        call check(error, count(kept%growth%reason == growth_linked), 1, 'one link')
        call check(error, size(kept%growth%step), size(lemke%growth%step), 'records')
        call check(error, kept_model%elements%n, lemke_model%elements%n, 'elements')
        if (allocated(error)) return
        call check(error, all(kept%growth%reason == lemke%growth%reason), 'reasons')
        call check(error, difference(kept%growth%angle, lemke%growth%angle), 0.0_wp, &
                   'angles', abs_tol=1.0e-9_wp)
        call check(error, difference(kept_model%elements%x_end, lemke_model%elements%x_end), &
                   0.0_wp, 'x_end', abs_tol=1.0e-12_wp)
        call check(error, difference(kept%elements%ds, lemke%elements%ds), 0.0_wp, 'ds', &
                   abs_tol=1.0e-8_wp)
        call check(error, difference(kept%elements%dn, lemke%elements%dn), 0.0_wp, 'dn', &
                   abs_tol=1.0e-8_wp)
    end subroutine test_kept_path

end module test_growth_link
