!> The TWODD deck reader, symmetry (KSYM 2-4) and the TWODD-style result tables:
!> reference decks against the double-precision TWODD print, symmetric decks against the
!> full models, KODE 2-4 decks against the Lame hole, malformed decks.
module test_twodd_deck
    use ddc_kinds, only: wp
    use ddc_contact_options, only: lcp_auto, cohesion_kept
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_error, only: set_error, exit_bad_input
    use ddc_model_types, only: model_type, element_set, symmetry_none, symmetry_both
    use ddc_model_results, only: model_results
    use ddc_run_model, only: run_model
    use ddc_model_loads, only: shear_modulus_of
    use ddc_input_twodd_deck, only: read_twodd_deck
    use ddc_input_namelist, only: read_namelist_model
    use ddc_influence_assembly, only: image_transform, image_transforms
    use ddc_mesh_geometry, only: allocate_elements, compute_geometry
    use ddc_output_twodd_tables, only: write_twodd_tables
    use test_twodd_reference, only: check_against_reference
    implicit none
    private

    public :: collect_twodd_deck

    character(len=*), parameter :: inputs = 'reference/twodd/inputs/'
    character(len=*), parameter :: wide_dir = 'reference/twodd/output_double_precision/'
    character(len=*), parameter :: data = 'data/twodd/'

contains

    !> Cases of the twodd_deck suite.
    subroutine collect_twodd_deck(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('reference_A1', test_reference_a1), &
                 new_test('reference_B1', test_reference_b1), &
                 new_test('deck_equals_namelist', test_deck_equals_namelist), &
                 new_test('half_crack_ksym2', test_half_crack), &
                 new_test('ksym2_equals_full', test_ksym2), &
                 new_test('ksym3_equals_full', test_ksym3), &
                 new_test('ksym4_equals_full', test_ksym4), &
                 new_test('hole_kode2', test_hole_kode2), &
                 new_test('hole_kode3', test_hole_kode3), &
                 new_test('hole_kode4', test_hole_kode4), &
                 new_test('bad_too_few_lines', test_bad_too_few_lines), &
                 new_test('bad_kode7', test_bad_kode7), &
                 new_test('bad_negative_count', test_bad_negative_count), &
                 new_test('bad_non_numeric', test_bad_non_numeric), &
                 new_test('bad_nan_numpb_symmetry', test_bad_other), &
                 new_test('res_tables_A1', test_res_a1), &
                 new_test('res_tables_B1', test_res_b1)]
    end subroutine collect_twodd_deck

    ! ------------------------------------------------------------------------------------
    ! Reference decks
    ! ------------------------------------------------------------------------------------

    !> Run a reference deck and compare with the double-precision TWODD print.
    subroutine compare_reference(error, name)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name
        type(model_type) :: model
        type(model_results) :: r

        call read_twodd_deck(inputs//name//'.f60.txt', model, error)
        if (allocated(error)) return
        call run_model(model, r, error)
        if (allocated(error)) return
        call check_against_reference(error, name, model, r)
    end subroutine compare_reference

    !> A1: crack under internal pressure 1.
    subroutine test_reference_a1(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_reference(error, 'A1_press_n20')
    end subroutine test_reference_a1

    !> B1: traction-free crack under remote shear.
    subroutine test_reference_b1(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_reference(error, 'B1_rshear_n20')
    end subroutine test_reference_b1

    !> The deck and its namelist translation give the same model.
    subroutine test_deck_equals_namelist(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: deck, nml
        integer :: k

        call read_twodd_deck(inputs//'A1_press_n20.f60.txt', deck, error)
        if (allocated(error)) return
        call read_namelist_model(data//'A1_press_n20.nml', nml, error)
        if (allocated(error)) return
        call check(error, deck%title == nml%title, 'title')
        call check(error, deck%elements%n, nml%elements%n, 'elements')
        if (allocated(error)) return
        call check(error, all(deck%elements%x_begin == nml%elements%x_begin) .and. &
                   all(deck%elements%x_end == nml%elements%x_end) .and. &
                   all(deck%elements%y_begin == nml%elements%y_begin) .and. &
                   all(deck%elements%condition == nml%elements%condition) .and. &
                   all(deck%elements%bc_n == nml%elements%bc_n), 'same elements')
        call check(error, deck%youngs_modulus, nml%youngs_modulus, 'E', rel_tol=0.0_wp, &
                   abs_tol=0.0_wp)
        call check(error, deck%poissons_ratio, nml%poissons_ratio, 'nu', abs_tol=0.0_wp)
        call check(error, size(deck%observations), size(nml%observations), 'observation sets')
        if (allocated(error)) return
        do k = 1, size(deck%observations)
            call check(error, deck%observations(k)%nx, nml%observations(k)%nx, 'line points')
            if (allocated(error)) return
            call check(error, all(deck%observations(k)%x == nml%observations(k)%x) .and. &
                       all(deck%observations(k)%y == nml%observations(k)%y), 'line coordinates')
        end do
        call check(error, deck%elements%symmetry%kind == symmetry_none, 'no symmetry')
        call check(error, deck%output_file == 'A1_press_n20.f60.h5', 'default output file')
        call check(error, deck%solver%lcp_method == lcp_auto .and. &
                   deck%solver%open_cohesion == cohesion_kept, 'solver defaults')
        call check(error, deck%fractures(1)%name == 'segment_1', 'fracture name')
        call check(error, index(deck%input_text, 'A1_pressurized_crack_a1_n20') == 1, &
                   'input text kept')
    end subroutine test_deck_equals_namelist

    ! ------------------------------------------------------------------------------------
    ! Symmetry
    ! ------------------------------------------------------------------------------------

    !> Half of A1 (0 <= x <= 1, 10 elements) with symmetry about x = 0 equals the right half
    !> of the full A1 run; one tip only, with the full model's K_I.
    subroutine test_half_crack(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: half, full
        type(model_results) :: rh, rf
        integer :: k

        call read_twodd_deck(data//'A1_half_ksym2.f60.txt', half, error)
        if (allocated(error)) return
        call read_twodd_deck(inputs//'A1_press_n20.f60.txt', full, error)
        if (allocated(error)) return
        call run_model(half, rh, error)
        if (allocated(error)) return
        call run_model(full, rf, error)
        if (allocated(error)) return
        call check(error, half%elements%n, 10, 'half elements')
        if (allocated(error)) return
        call check(error, maxval(abs(rh%elements%dn - rf%elements%dn(11:20))), 0.0_wp, &
                   'Dn half = full', abs_tol=1.0e-10_wp * maxval(abs(rf%elements%dn)))
        call check(error, maxval(abs(rh%elements%ds - rf%elements%ds(11:20))), 0.0_wp, &
                   'Ds half = full', abs_tol=1.0e-10_wp * maxval(abs(rf%elements%dn)))
        call check(error, maxval(abs(rh%elements%us_minus - rf%elements%us_minus(11:20))), &
                   0.0_wp, 'us(-) half = full', abs_tol=1.0e-10_wp)
        call check(error, maxval(abs(rh%elements%normal_traction + 1.0_wp)), 0.0_wp, &
                   'sigma_n = -1', abs_tol=1.0e-10_wp)
        call check(error, rh%tips%n, 1, 'one tip (the end at x = 0 meets its image)')
        if (allocated(error)) return
        call check(error, rh%tips%x(1), 1.0_wp, 'tip x', abs_tol=1.0e-14_wp)
        call check(error, rh%tips%k1(1), rf%tips%k1(2), 'K_I', rel_tol=1.0e-10_wp)
        do k = 1, 4
            call check(error, maxval(abs(rh%fields(k)%uy - rf%fields(k)%uy)), 0.0_wp, &
                       'field uy', abs_tol=1.0e-10_wp)
            call check(error, maxval(abs(rh%fields(k)%sxx - rf%fields(k)%sxx)), 0.0_wp, &
                       'field sxx', abs_tol=1.0e-10_wp)
            call check(error, maxval(abs(rh%fields(k)%sxy - rf%fields(k)%sxy)), 0.0_wp, &
                       'field sxy', abs_tol=1.0e-10_wp)
        end do
    end subroutine test_half_crack

    !> The full model of a symmetric one: the given elements, then for each image transform
    !> the mirrored elements. A single reflection reverses the end order so that the faces
    !> keep their sides: the image then has Ds' = -Ds, Dn' = Dn and given values
    !> (-bc_s, bc_n); the double reflection keeps order, signs and values.
    function full_model(model) result(full)
        type(model_type), intent(in) :: model
        type(model_type) :: full
        type(image_transform), allocatable :: images(:)
        type(element_set) :: empty
        real(wp) :: xb(model%elements%n), yb(model%elements%n), xe(model%elements%n)
        real(wp) :: ye(model%elements%n)
        integer :: n, t, first, last

        images = image_transforms(model%elements%symmetry)
        n = model%elements%n
        full = model
        full%elements = empty
        call allocate_elements(full%elements, n * (1 + size(images)))
        associate (e => model%elements, f => full%elements)
            f%x_begin(:n) = e%x_begin
            f%y_begin(:n) = e%y_begin
            f%x_end(:n) = e%x_end
            f%y_end(:n) = e%y_end
            f%bc_s(:n) = e%bc_s
            do t = 1, size(images)
                first = t * n + 1
                last = (t + 1) * n
                xb = e%x_begin
                yb = e%y_begin
                xe = e%x_end
                ye = e%y_end
                if (images(t)%mirror_x) then
                    xb = 2.0_wp * images(t)%xsym - xb
                    xe = 2.0_wp * images(t)%xsym - xe
                end if
                if (images(t)%mirror_y) then
                    yb = 2.0_wp * images(t)%ysym - yb
                    ye = 2.0_wp * images(t)%ysym - ye
                end if
                if (images(t)%sign_s < 0.0_wp) then
                    f%x_begin(first:last) = xe
                    f%y_begin(first:last) = ye
                    f%x_end(first:last) = xb
                    f%y_end(first:last) = yb
                else
                    f%x_begin(first:last) = xb
                    f%y_begin(first:last) = yb
                    f%x_end(first:last) = xe
                    f%y_end(first:last) = ye
                end if
                f%bc_s(first:last) = images(t)%sign_s * e%bc_s
            end do
            f%condition = [(e%condition, t = 0, size(images))]
            f%bc_n = [(e%bc_n, t = 0, size(images))]
            f%fracture_id = [(e%fracture_id, t = 0, size(images))]
            f%mu = 0.0_wp
            f%sf = 0.0_wp
            f%pressure = 0.0_wp
        end associate
        call compute_geometry(full%elements)
        full%elements%symmetry%kind = symmetry_none
    end function full_model

    !> A symmetric deck gives the same DDs (1e-10 relative), face displacements, tractions
    !> and fields as its full model solved without symmetry.
    subroutine compare_with_full(error, deck, nimages)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: deck
        integer, intent(in) :: nimages
        type(model_type) :: sym, full
        type(model_results) :: rs, rf
        type(image_transform), allocatable :: images(:)
        real(wp) :: scale
        integer :: n, t, k

        call read_twodd_deck(data//deck, sym, error)
        if (allocated(error)) return
        images = image_transforms(sym%elements%symmetry)
        call check(error, size(images), nimages, 'number of images')
        if (allocated(error)) return
        full = full_model(sym)
        call run_model(sym, rs, error)
        if (allocated(error)) return
        call run_model(full, rf, error)
        if (allocated(error)) return
        n = sym%elements%n
        scale = max(maxval(abs(rf%elements%ds)), maxval(abs(rf%elements%dn)))
        call check(error, maxval(abs(rs%elements%ds - rf%elements%ds(:n))), 0.0_wp, &
                   deck//' Ds', abs_tol=1.0e-10_wp * scale)
        call check(error, maxval(abs(rs%elements%dn - rf%elements%dn(:n))), 0.0_wp, &
                   deck//' Dn', abs_tol=1.0e-10_wp * scale)
        do t = 1, nimages
            call check(error, maxval(abs(images(t)%sign_s * rs%elements%ds - &
                                         rf%elements%ds(t * n + 1:(t + 1) * n))), 0.0_wp, &
                       deck//' image Ds', abs_tol=1.0e-10_wp * scale)
            call check(error, maxval(abs(rs%elements%dn - &
                                         rf%elements%dn(t * n + 1:(t + 1) * n))), 0.0_wp, &
                       deck//' image Dn', abs_tol=1.0e-10_wp * scale)
        end do
        call check(error, maxval(abs(rs%elements%us_minus - rf%elements%us_minus(:n))), &
                   0.0_wp, deck//' us(-)', abs_tol=1.0e-10_wp * scale)
        call check(error, maxval(abs(rs%elements%un_plus - rf%elements%un_plus(:n))), &
                   0.0_wp, deck//' un(+)', abs_tol=1.0e-10_wp * scale)
        call check(error, maxval(abs(rs%elements%shear_traction - &
                                     rf%elements%shear_traction(:n))), 0.0_wp, &
                   deck//' shear traction', abs_tol=1.0e-10_wp)
        call check(error, maxval(abs(rs%elements%normal_traction - &
                                     rf%elements%normal_traction(:n))), 0.0_wp, &
                   deck//' normal traction', abs_tol=1.0e-10_wp)
        call check(error, size(rs%fields), size(rf%fields), 'field sets')
        if (allocated(error)) return
        do k = 1, size(rs%fields)
            associate (a => rs%fields(k), b => rf%fields(k))
                call check(error, all(a%flag == b%flag), deck//' flags')
                call check(error, maxval(abs([a%ux - b%ux, a%uy - b%uy])), 0.0_wp, &
                           deck//' field displacement', abs_tol=1.0e-10_wp * scale)
                call check(error, maxval(abs([a%sxx - b%sxx, a%syy - b%syy, &
                                              a%sxy - b%sxy])), 0.0_wp, &
                           deck//' field stress', abs_tol=1.0e-10_wp)
            end associate
        end do
        ! Tips: those of the given elements in the full model (no end lies on a line here).
        call check(error, rs%tips%n * (1 + nimages), rf%tips%n, deck//' tips')
        if (allocated(error)) return
        call check(error, maxval(abs(rs%tips%k1 - rf%tips%k1(:rs%tips%n))), 0.0_wp, &
                   deck//' K_I', abs_tol=1.0e-10_wp)
    end subroutine compare_with_full

    !> KSYM = 2: about x = 0.
    subroutine test_ksym2(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_with_full(error, 'sym_ksym2.f60.txt', 1)
    end subroutine test_ksym2

    !> KSYM = 3: about y = -1.5.
    subroutine test_ksym3(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_with_full(error, 'sym_ksym3.f60.txt', 1)
    end subroutine test_ksym3

    !> KSYM = 4: about x = 0 and y = -1.5.
    subroutine test_ksym4(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_with_full(error, 'sym_ksym4.f60.txt', 3)
    end subroutine test_ksym4

    ! ------------------------------------------------------------------------------------
    ! KODE 2, 3, 4: a circular hole of radius 1 under internal pressure 5 (Lame), a quarter
    ! of 100 elements with KSYM = 4 (400 elements in all), E = 200, nu = 0.3.
    ! ------------------------------------------------------------------------------------

    !> u_r, s_rr, s_tt at the deck's observation points (two rays, r = 1.5 .. 4, one in
    !> the given quadrant and one in an image quadrant) within 0.5 % of Lame; the wall
    !> displacement and traction too.
    subroutine check_hole(error, deck)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: deck
        real(wp), parameter :: p = 5.0_wp
        type(model_type) :: model
        type(model_results) :: r
        real(wp) :: g, c, s, radius, ur, srr, stt, exact
        integer :: k, i

        call read_twodd_deck(data//deck, model, error)
        if (allocated(error)) return
        call check(error, model%elements%symmetry%kind == symmetry_both, 'KSYM = 4')
        if (allocated(error)) return
        call run_model(model, r, error)
        if (allocated(error)) return
        g = shear_modulus_of(model)
        call check(error, r%tips%n, 0, 'no tips: the arc ends lie on the symmetry lines')
        call check(error, size(r%fields), 2, 'two rays')
        if (allocated(error)) return
        do k = 1, 2
            associate (o => model%observations(k), f => r%fields(k))
                call check(error, size(o%x), 5, 'points per ray')
                if (allocated(error)) return
                do i = 1, 5
                    radius = hypot(o%x(i), o%y(i))
                    c = o%x(i) / radius
                    s = o%y(i) / radius
                    ur = f%ux(i) * c + f%uy(i) * s
                    srr = f%sxx(i) * c**2 + 2 * f%sxy(i) * s * c + f%syy(i) * s**2
                    stt = f%sxx(i) * s**2 - 2 * f%sxy(i) * s * c + f%syy(i) * c**2
                    exact = p / radius**2
                    call check(error, srr, -exact, deck//' s_rr', abs_tol=5.0e-3_wp * exact)
                    call check(error, stt, exact, deck//' s_tt', abs_tol=5.0e-3_wp * exact)
                    call check(error, ur, p / (2 * g * radius), deck//' u_r', rel_tol=5.0e-3_wp)
                end do
            end associate
        end do
        call check(error, maxval(abs(r%elements%un_minus + p / (2 * g))), 0.0_wp, &
                   deck//' un(-) = -u_r(r0)', abs_tol=5.0e-3_wp * p / (2 * g))
        call check(error, maxval(abs(r%elements%us_minus)), 0.0_wp, deck//' us(-) = 0', &
                   abs_tol=5.0e-3_wp * p / (2 * g))
        call check(error, maxval(abs(r%elements%normal_traction + p)), 0.0_wp, &
                   deck//' s_n = -p', abs_tol=5.0e-3_wp * p)
        call check(error, maxval(abs(r%elements%shear_traction)), 0.0_wp, &
                   deck//' s_s = 0', abs_tol=5.0e-3_wp * p)
    end subroutine check_hole

    !> KODE 2: u_s = 0, u_n = -p r0 / 2G given.
    subroutine test_hole_kode2(error)
        type(error_type), allocatable, intent(out) :: error

        call check_hole(error, 'hole_quarter_kode2.f60.txt')
    end subroutine test_hole_kode2

    !> KODE 3: u_s = 0, s_n = -p given.
    subroutine test_hole_kode3(error)
        type(error_type), allocatable, intent(out) :: error

        call check_hole(error, 'hole_quarter_kode3.f60.txt')
    end subroutine test_hole_kode3

    !> KODE 4: s_s = 0, u_n = -p r0 / 2G given.
    subroutine test_hole_kode4(error)
        type(error_type), allocatable, intent(out) :: error

        call check_hole(error, 'hole_quarter_kode4.f60.txt')
    end subroutine test_hole_kode4

    ! ------------------------------------------------------------------------------------
    ! Malformed decks
    ! ------------------------------------------------------------------------------------

    !> Reading the deck fails with exit_bad_input and a message holding every fragment.
    subroutine check_bad_deck(error, deck, fragments)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: deck
        character(len=*), intent(in) :: fragments(:)
        type(model_type) :: model
        type(error_type), allocatable :: read_error
        integer :: k

        call read_twodd_deck(data//deck, model, read_error)
        if (.not. allocated(read_error)) then
            call set_error(error, 1, deck//' was accepted')
            return
        end if
        call check(error, read_error%code, exit_bad_input, deck//' exit code')
        do k = 1, size(fragments)
            call check(error, index(read_error%message, trim(fragments(k))) > 0, &
                       deck//': message "'//read_error%message//'" lacks "'// &
                       trim(fragments(k))//'"')
        end do
    end subroutine check_bad_deck

    !> Four observation lines announced, one given: the deck ends at line 7.
    subroutine test_bad_too_few_lines(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_deck(error, 'bad_too_few_lines.f60.txt', [character(len=40) :: &
            'bad_too_few_lines.f60.txt', 'line 7', 'ends too early', 'observation line 2'])
    end subroutine test_bad_too_few_lines

    !> KODE 7 on line 5.
    subroutine test_bad_kode7(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_deck(error, 'bad_kode7.f60.txt', [character(len=40) :: &
            'bad_kode7.f60.txt', 'line 5', 'KODE = 7'])
    end subroutine test_bad_kode7

    !> NUM = -20 on line 5, and NUMBS = -1 on line 2.
    subroutine test_bad_negative_count(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_deck(error, 'bad_negative_count.f60.txt', [character(len=40) :: &
            'line 5', 'NUM = -20'])
        if (allocated(error)) return
        call check_bad_deck(error, 'bad_negative_numbs.f60.txt', [character(len=40) :: &
            'line 2', 'NUMBS = -1'])
    end subroutine test_bad_negative_count

    !> 'abc' for PXY on line 4.
    subroutine test_bad_non_numeric(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_deck(error, 'bad_non_numeric.f60.txt', [character(len=40) :: &
            'line 4', 'PXX, PYY, PXY', 'not a number'])
    end subroutine test_bad_non_numeric

    !> NaN coordinate, negative NUMPB, a segment across the symmetry line.
    subroutine test_bad_other(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_deck(error, 'bad_nan.f60.txt', [character(len=40) :: 'line 5', &
            'finite'])
        if (allocated(error)) return
        call check_bad_deck(error, 'bad_negative_numpb.f60.txt', [character(len=40) :: &
            'line 6', 'NUMPB = -3'])
        if (allocated(error)) return
        call check_bad_deck(error, 'bad_crosses_symmetry.f60.txt', [character(len=40) :: &
            "'segment_1'", 'symmetry line x'])
        if (allocated(error)) return
        call check_bad_deck(error, 'no_such_deck.f60.txt', [character(len=40) :: &
            'no_such_deck.f60.txt', 'not found'])
    end subroutine test_bad_other

    ! ------------------------------------------------------------------------------------
    ! TWODD-style tables
    ! ------------------------------------------------------------------------------------

    !> Numeric rows of one table of a TWODD print: the lines after `heading` that start
    !> with an integer and hold ncols numbers after it, until the next page mark.
    subroutine read_print_table(path, heading, ncols, table, error)
        character(len=*), intent(in) :: path, heading
        integer, intent(in) :: ncols
        real(wp), allocatable, intent(out) :: table(:, :)
        type(error_type), allocatable, intent(out) :: error
        character(len=1000) :: line
        real(wp) :: rows(ncols, 2000)
        integer :: unit, stat, n, number
        logical :: inside

        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) then
            call set_error(error, 1, 'cannot open '//path)
            return
        end if
        n = 0
        inside = .false.
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (index(line, heading) > 0) then
                inside = .true.
                cycle
            end if
            if (.not. inside) cycle
            if (trim(line) == '1') exit
            if (len_trim(line) == 0) cycle
            read (line, *, iostat=stat) number, rows(:, n + 1)
            if (stat /= 0) cycle
            n = n + 1
        end do
        close (unit)
        table = rows(:, :n)
    end subroutine read_print_table

    !> Write the --res tables of a reference deck, read them back and compare with the
    !> double-precision reference print: midpoints to 1e-9 and points to 1e-8 of each
    !> column's scale; the element data table to the print's own precision.
    subroutine compare_res(error, name)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name
        type(model_type) :: model
        type(model_results) :: r
        real(wp), allocatable :: ours(:, :), theirs(:, :)
        character(len=:), allocatable :: path
        character(len=256) :: tmp
        real(wp) :: scale
        integer :: k, stat, unit

        call read_twodd_deck(inputs//name//'.f60.txt', model, error)
        if (allocated(error)) return
        call run_model(model, r, error)
        if (allocated(error)) return
        call get_environment_variable('TMPDIR', tmp, status=stat)
        if (stat /= 0 .or. len_trim(tmp) == 0) tmp = '/tmp'
        path = trim(tmp)//'/ddc2d_test_twodd_'//name//'.RES.txt'
        call write_twodd_tables(path, model, r, error)
        if (allocated(error)) return

        call read_print_table(path, 'SIGMA-S   SIGMA-N', 12, ours, error)
        if (allocated(error)) return
        call read_print_table(wide_dir//name//'.RESf60.txt', 'SIGMA-S   SIGMA-N', 12, theirs, &
                              error)
        if (allocated(error)) return
        call check(error, size(ours, 2), 20, name//' midpoint rows')
        call check(error, size(theirs, 2), 20, name//' reference midpoint rows')
        if (allocated(error)) return
        do k = 1, 12
            scale = max(maxval(abs(theirs(k, :))), 1.0_wp)
            call check(error, maxval(abs(ours(k, :) - theirs(k, :))), 0.0_wp, &
                       name//' res midpoint column', abs_tol=1.0e-9_wp * scale)
        end do
        if (allocated(error)) return
        call read_print_table(path, 'SIGXY', 7, ours, error)
        if (allocated(error)) return
        call read_print_table(wide_dir//name//'.RESf60.txt', 'SIGXY', 7, theirs, error)
        if (allocated(error)) return
        call check(error, size(ours, 2), 26, name//' point rows')
        call check(error, size(theirs, 2), 26, name//' reference point rows')
        if (allocated(error)) return
        do k = 1, 7
            scale = maxval(abs(theirs(k, :)))
            call check(error, maxval(abs(ours(k, :) - theirs(k, :))), 0.0_wp, &
                       name//' res point column', abs_tol=1.0e-8_wp * scale)
        end do
        if (allocated(error)) return
        call read_print_table(path, 'UN OR SIGMA_N', 7, ours, error)
        if (allocated(error)) return
        call read_print_table(wide_dir//name//'.RESf60.txt', 'UN OR SIGMA_N', 7, theirs, error)
        if (allocated(error)) return
        call check(error, size(ours, 2), 20, name//' element data rows')
        if (allocated(error)) return
        call check(error, maxval(abs(ours - theirs)), 0.0_wp, name//' element data', &
                   abs_tol=1.0e-6_wp)
        open (newunit=unit, file=path, status='old', iostat=stat)
        if (stat == 0) close (unit, status='delete')
    end subroutine compare_res

    !> --res tables of A1.
    subroutine test_res_a1(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_res(error, 'A1_press_n20')
    end subroutine test_res_a1

    !> --res tables of B1.
    subroutine test_res_b1(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_res(error, 'B1_rshear_n20')
    end subroutine test_res_b1

end module test_twodd_deck
