!> The classic TWODD reference cases (tests/reference/twodd, double-precision build), written
!> as namelists (tests/data/twodd): element DDs, face displacements, boundary stresses and
!> interior points.
module test_twodd_reference
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_error, only: set_error
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results, point_clear
    use ddc_run_model, only: run_model
    use ddc_input_namelist, only: read_namelist_model
    implicit none
    private

    public :: collect_twodd_reference, check_against_reference

    character(len=*), parameter :: csv_dir = 'reference/twodd/csv/'

contains

    !> Cases of the twodd_reference suite.
    subroutine collect_twodd_reference(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('A1_pressurized_crack', test_a1), &
                 new_test('B1_remote_shear', test_b1)]
    end subroutine collect_twodd_reference

    !> Read a numeric CSV with one header line into table(ncols, nrows).
    subroutine read_reference_table(path, ncols, table, error)
        character(len=*), intent(in) :: path
        integer, intent(in) :: ncols
        real(wp), allocatable, intent(out) :: table(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: row(ncols), rows(ncols, 1000)
        integer :: unit, stat, n

        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) then
            call set_error(error, 1, 'cannot open reference file '//path)
            return
        end if
        read (unit, *)
        n = 0
        do
            read (unit, *, iostat=stat) row
            if (stat /= 0) exit
            n = n + 1
            rows(:, n) = row
        end do
        close (unit)
        table = rows(:, :n)
    end subroutine read_reference_table

    !> Run the namelist version of the deck and compare with the reference.
    subroutine compare_case(error, name)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name
        type(model_type) :: model
        type(model_results) :: r

        call read_namelist_model('data/twodd/'//name//'.nml', model, error)
        if (allocated(error)) return
        call run_model(model, r, error)
        if (allocated(error)) return
        call check_against_reference(error, name, model, r)
    end subroutine compare_case

    !> Compare a solved reference case (from its deck or its namelist) with the
    !> double-precision TWODD print (CSV copy): element columns and points to 1e-9 of
    !> each column's largest magnitude (or of the load for traction columns that vanish).
    subroutine check_against_reference(error, name, model, r)
        type(error_type), allocatable, intent(out) :: error
        !> Name of the case in tests/reference/twodd
        character(len=*), intent(in) :: name
        !> The model as read, and its results
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: r
        real(wp), allocatable :: elements(:, :), points(:, :), ours(:, :), x(:), y(:)
        character(len=8), parameter :: columns(12) = [character(len=8) :: 'DS', 'US(-)', &
            'US(+)', 'DN', 'UN(-)', 'UN(+)', 'UX(-)', 'UY(-)', 'UX(+)', 'UY(+)', 'SIGMA-S', &
            'SIGMA-N']
        character(len=5), parameter :: point_columns(5) = ['UX   ', 'UY   ', 'SIGXX', &
                                                          'SIGYY', 'SIGXY']
        real(wp) :: load, scale
        integer :: k

        call read_reference_table(csv_dir//name//'_elements.csv', 20, elements, error)
        if (allocated(error)) return
        call read_reference_table(csv_dir//name//'_points.csv', 8, points, error)
        if (allocated(error)) return
        call check(error, model%elements%n, size(elements, 2), 'element count')
        call check(error, size(r%fields), 4, 'observation lines')
        if (allocated(error)) return
        x = [(model%observations(k)%x, k = 1, 4)]
        y = [(model%observations(k)%y, k = 1, 4)]
        call check(error, size(x), size(points, 2), 'point count')
        if (allocated(error)) return
        call check(error, maxval(abs(x - points(2, :))), 0.0_wp, 'point x', abs_tol=1.0e-14_wp)
        call check(error, maxval(abs(y - points(3, :))), 0.0_wp, 'point y', abs_tol=1.0e-14_wp)
        call check(error, maxval(abs(model%elements%x_mid - elements(3, :))), 0.0_wp, &
                   'element centres', abs_tol=1.0e-14_wp)
        ours = element_columns(model, r)
        load = max(maxval(abs(model%elements%bc_s)), maxval(abs(model%elements%bc_n)), &
                   abs(model%sxx), abs(model%syy), abs(model%sxy))
        do k = 1, 12
            scale = maxval(abs(elements(8 + k, :)))
            if (k > 10) scale = max(scale, load)
            call check(error, maxval(abs(ours(:, k) - elements(8 + k, :))), 0.0_wp, &
                       name//' element '//trim(columns(k)), abs_tol=1.0e-9_wp * scale)
        end do
        associate (f => r%fields)
            ours = reshape([(f(k)%ux, k = 1, 4), (f(k)%uy, k = 1, 4), (f(k)%sxx, k = 1, 4), &
                            (f(k)%syy, k = 1, 4), (f(k)%sxy, k = 1, 4)], [size(points, 2), 5])
        end associate
        do k = 1, 5
            call check(error, maxval(abs(ours(:, k) - points(3 + k, :))), 0.0_wp, &
                       name//' point '//trim(point_columns(k)), &
                       abs_tol=1.0e-9_wp * maxval(abs(points(3 + k, :))))
        end do
        ! The reference decks keep clear of their elements: no point is flagged.
        call check(error, all([(all(r%fields(k)%flag == point_clear), k = 1, 4)]), &
                   'no flagged points')
    end subroutine check_against_reference

    !> The 12 midpoint columns of the TWODD print, shape (n, 12).
    function element_columns(model, r) result(table)
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: r
        real(wp), allocatable :: table(:, :)

        associate (e => r%elements, c => model%elements%cos_beta, s => model%elements%sin_beta)
            table = reshape([e%ds, e%us_minus, e%us_plus, e%dn, e%un_minus, e%un_plus, &
                             e%us_minus * c - e%un_minus * s, e%us_minus * s + e%un_minus * c, &
                             e%us_plus * c - e%un_plus * s, e%us_plus * s + e%un_plus * c, &
                             e%shear_traction, e%normal_traction], [model%elements%n, 12])
        end associate
    end function element_columns

    !> A1: crack under internal pressure 1 (KODE 1, total normal traction -1).
    subroutine test_a1(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_case(error, 'A1_press_n20')
    end subroutine test_a1

    !> B1: traction-free crack under remote shear sxy = 1.
    subroutine test_b1(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_case(error, 'B1_rshear_n20')
    end subroutine test_b1

end module test_twodd_reference
