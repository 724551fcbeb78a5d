!> The elastic solve of TWODD-style elements on a hierarchical matrix
!> (docs/theory/hierarchical.md): the influence matrix assembled block by block into
!> hmat-oss (compressed where groups of elements are well separated), H-LU factorized and
!> solved; the residual is that of the compressed matrix. The rows and the right-hand side
!> are those of the dense solve (ddc_solve_elastic).
module ddc_solve_hierarchical
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, set_internal_error, exit_solver_failure
    use ddc_model_types, only: element_set, condition_contact
    use ddc_model_medium, only: elastic_medium, remote_stress_at
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_influence_assembly, only: fill_influence_block, row_traction, row_displacement, &
        image_transform, image_transforms, kernel_with_images, kernel_function, select_kernel
    use ddc_influence_kernel, only: dd_kernel, face_positive
    use ddc_influence_superposition, only: source_table, build_sources, flag_at
    use ddc_model_results, only: field_result, point_on_element
    use ddc_linalg_hmatrix, only: hmatrix, block_source, hmatrix_settings
    use ddc_linalg_lu, only: residual_tol, influence_hint
    use ddc_contact_options, only: solver_options
    use ddc_solve_elastic, only: row_kinds, given_values
    use ddc_text, only: rtoa, itoa, seconds_text
    use ddc_progress, only: report_progress, reports_phases
    implicit none
    private

    public :: solve_hierarchical, influence_source, new_influence_source, unknown_points
    public :: hierarchical_response, hierarchical_field, settings_of, report_assembly
    public :: max_refinements, refined_residual

    !> Steps of refinement at most, and the relative residual at which they stop: far below
    !> what the solve accepts (residual_tol), a few steps above round-off
    integer, parameter :: max_refinements = 10
    real(wp), parameter :: refined_residual = 1.0e-12_wp
    !> The matrices whose products are results (midpoint responses, fields) are compressed
    !> this much more finely than hmatrix_tolerance: a product sums the blocks' errors, which
    !> no refinement corrects
    real(wp), parameter :: product_refinement = 1.0e-2_wp

    !> The influence matrix of a set of elements, unknowns [Ds(1:n); Dn(1:n)] and rows
    !> [shear rows; normal rows] as in ddc_influence_assembly.
    type, extends(block_source) :: influence_source
        type(elastic_medium), pointer :: medium => null()
        integer, allocatable :: shear_row(:), normal_row(:)
    contains
        procedure :: fill => fill_influence
    end type influence_source

    !> Displacement (ux, uy) and stress (sxx, syy, sxy) at observation points per unit DD:
    !> row 5 (p - 1) + q is quantity q at point p, columns [Ds; Dn] of the elements.
    type, extends(block_source) :: field_source
        type(elastic_medium), pointer :: medium => null()
        real(wp), allocatable :: x(:), y(:)
        !> Flag of each point (a point on an element gets no kernel: it is NaN there)
        integer, allocatable :: flag(:)
        type(image_transform), allocatable :: images(:)
        procedure(kernel_function), pointer, nopass :: kernel => null()
    contains
        procedure :: fill => fill_field
    end type field_source

contains

    !> Solve for Ds, Dn of elements whose conditions are all TWODD-style (no contact).
    subroutine solve_hierarchical(medium, remote_shear, remote_normal, options, ds, dn, &
                                  residual, compression_ratio, seconds_assembly, &
                                  seconds_factorization, error)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in), target :: medium
        !> Remote stress resolved on each element [stress unit], shape (n)
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        !> The hmatrix_ settings of &solver
        type(solver_options), intent(in) :: options
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(out) :: ds(:), dn(:)
        !> Relative residual |A x - b| / |b| with the compressed matrix A
        real(wp), intent(out) :: residual
        !> Reals stored over those of the dense matrix
        real(wp), intent(out) :: compression_ratio
        !> Wall time of assembly (with compression) and factorization + solve [s]
        real(wp), intent(out) :: seconds_assembly, seconds_factorization
        !> Set when hmat-oss fails or the residual is too large
        type(error_type), allocatable, intent(out) :: error
        type(influence_source) :: source
        type(hmatrix) :: matrix, factors
        real(wp), allocatable :: points(:, :), rhs(:, :), correction(:, :), product(:), given(:)
        integer :: n, i, step
        integer(int64) :: t0, t1, t2, rate

        n = medium%elements%n
        if (any(medium%elements%condition == condition_contact)) then
            call set_internal_error(error, 'solve_hierarchical', 'called with contact elements')
            return
        end if
        call system_clock(t0, rate)
        source = new_influence_source(medium)
        points = unknown_points(medium%elements)
        call matrix%assemble(points, source, settings_of(options), error)
        if (allocated(error)) return
        compression_ratio = matrix%stored_fraction()
        allocate (rhs(2 * n, 1), correction(2 * n, 1), product(2 * n))
        rhs(:, 1) = given_values(medium%elements, source%shear_row, source%normal_row, &
                                 remote_shear, remote_normal, [(i, i = 1, n)])
        call system_clock(t1)
        call report_assembly(n, real(t1 - t0, wp) / real(rate, wp), compression_ratio)

        ! The residual needs the unfactored matrix: the factors overwrite a copy.
        call factors%copy_of(matrix, error)
        if (allocated(error)) return
        call factors%factor(error)
        if (allocated(error)) error%message = error%message//influence_hint
        given = rhs(:, 1)
        if (.not. allocated(error)) call factors%solve(rhs, error)
        ! Refinement against the compressed matrix: H-LU is only as accurate as its
        ! recompressions (hmatrix_tolerance).
        residual = huge(1.0_wp)
        do step = 1, max_refinements
            if (allocated(error)) exit
            call matrix%multiply(rhs(:, 1), product, error)
            if (allocated(error)) exit
            correction(:, 1) = given - product
            residual = norm2(correction(:, 1)) / max(norm2(given), tiny(1.0_wp))
            if (residual <= refined_residual) exit
            call factors%solve(correction, error)
            rhs = rhs + correction
        end do
        ! Before the original, whose cluster tree the copy shares
        call factors%release()
        if (allocated(error)) return
        call system_clock(t2)
        if (reports_phases(n)) call report_progress('H-LU factorization and solve done in '// &
            seconds_text(real(t2 - t1, wp) / real(rate, wp)))
        if (.not. residual <= residual_tol) then
            call set_error(error, exit_solver_failure, 'the hierarchical solve has a relative '// &
                           'residual of '//rtoa(residual)//' (more than '//rtoa(residual_tol)// &
                           ') after '//itoa(max_refinements)//' refinements; a smaller '// &
                           '&solver hmatrix_tolerance, or'//influence_hint)
            return
        end if
        ds = rhs(1:n, 1)
        dn = rhs(n + 1:, 1)
        seconds_assembly = real(t1 - t0, wp) / real(rate, wp)
        seconds_factorization = real(t2 - t1, wp) / real(rate, wp)
    end subroutine solve_hierarchical

    !> Induced tractions and negative-face displacements at the element midpoints (as
    !> ddc_influence_response's kernel_response) by products with two hierarchical matrices,
    !> one of traction rows and one of displacement rows: O(N log N) instead of the O(N^2)
    !> sums, to product_refinement times hmatrix_tolerance.
    subroutine hierarchical_response(medium, ds, dn, options, shear_traction, normal_traction, &
                                     us_minus, un_minus, error)
        type(elastic_medium), intent(in), target :: medium
        real(wp), intent(in) :: ds(:), dn(:)
        type(solver_options), intent(in) :: options
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        real(wp), intent(out) :: us_minus(:), un_minus(:)
        !> Set when hmat-oss fails (the caller then sums directly)
        type(error_type), allocatable, intent(out) :: error
        type(influence_source) :: source
        type(hmatrix) :: matrix
        real(wp), allocatable :: points(:, :), product(:)
        integer :: n, kind

        n = medium%elements%n
        source = new_influence_source(medium)
        points = unknown_points(medium%elements)
        allocate (product(2 * n))
        do kind = 1, 2
            source%shear_row = merge(row_traction, row_displacement, kind == 1)
            source%normal_row = source%shear_row
            call matrix%assemble(points, source, settings_of(options, product_refinement), &
                                 error)
            if (allocated(error)) return
            call matrix%multiply([ds, dn], product, error)
            if (allocated(error)) return
            if (kind == 1) then
                shear_traction = product(1:n)
                normal_traction = product(n + 1:)
            else
                us_minus = product(1:n)
                un_minus = product(n + 1:)
            end if
        end do
    end subroutine hierarchical_response

    !> Fields at the points (x, y), as ddc_post_fields' evaluate_field gives them, the
    !> elements' part by the product with a rectangular hierarchical matrix (O((P + N)
    !> log) instead of O(P N)), to product_refinement times hmatrix_tolerance; the flags
    !> from the cell index of the elements (ddc_influence_superposition).
    subroutine hierarchical_field(medium, remote, gradient, ds, dn, x, y, options, field, error)
        type(elastic_medium), intent(in), target :: medium
        !> Remote stress and its gradient d/dy [stress unit], [stress unit / length unit]
        real(wp), intent(in) :: remote(3), gradient(3)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Observation points [length unit], shape (np)
        real(wp), intent(in) :: x(:), y(:)
        type(solver_options), intent(in) :: options
        type(field_result), intent(out) :: field
        !> Set when hmat-oss fails (the caller then sums directly)
        type(error_type), allocatable, intent(out) :: error
        type(field_source) :: source
        type(source_table) :: cells
        type(hmatrix) :: matrix
        real(wp), allocatable :: rows(:, :), product(:)
        real(wp) :: nan, stress(3)
        logical :: use_general
        integer :: np, ip

        np = size(x)
        allocate (field%ux(np), field%uy(np), field%sxx(np), field%syy(np), field%sxy(np), &
                  field%flag(np))
        if (np == 0) return
        source%medium => medium
        source%x = x
        source%y = y
        source%images = image_transforms(medium%elements%symmetry)
        call select_kernel(medium, .true., use_general, source%kernel)
        call build_sources(medium%elements, source%images, ds, dn, cells)
        allocate (source%flag(np))
        !$omp parallel do default(none) private(ip) shared(cells, x, y, source, np)
        do ip = 1, np
            source%flag(ip) = flag_at(cells, x(ip), y(ip))
        end do
        !$omp end parallel do
        field%flag = source%flag
        allocate (rows(2, 5 * np), product(5 * np))
        rows(1, :) = [(x((ip + 4) / 5), ip = 1, 5 * np)]
        rows(2, :) = [(y((ip + 4) / 5), ip = 1, 5 * np)]
        call matrix%assemble_rectangular(rows, unknown_points(medium%elements), source, &
                                         settings_of(options, product_refinement), error)
        if (allocated(error)) return
        call matrix%multiply([ds, dn], product, error)
        if (allocated(error)) return
        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        !$omp parallel do default(none) private(ip, stress) shared(medium, y, field, product, &
        !$omp    remote, gradient, nan, np)
        do ip = 1, np
            if (field%flag(ip) == point_on_element) then
                field%ux(ip) = nan
                field%uy(ip) = nan
                field%sxx(ip) = nan
                field%syy(ip) = nan
                field%sxy(ip) = nan
            else
                stress = remote_stress_at(medium, remote, gradient, y(ip))
                field%ux(ip) = product(5 * ip - 4)
                field%uy(ip) = product(5 * ip - 3)
                field%sxx(ip) = product(5 * ip - 2) + stress(1)
                field%syy(ip) = product(5 * ip - 1) + stress(2)
                field%sxy(ip) = product(5 * ip) + stress(3)
            end if
        end do
        !$omp end parallel do
    end subroutine hierarchical_field

    !> block(k, l): quantity of row rows(k) per unit DD of column cols(l) (0 at a point on
    !> an element, whose field is NaN).
    subroutine fill_field(source, rows, cols, block)
        class(field_source), intent(in) :: source
        integer, intent(in) :: rows(:), cols(:)
        real(wp), intent(out) :: block(:, :)
        type(dd_kernel) :: k
        real(wp) :: values(5, 2)
        integer :: n, kk, l, point, element, last_point, last_element

        n = source%medium%elements%n
        last_point = 0
        last_element = 0
        ! Columns outer, rows inner: a point's five rows lie together, so each pair of
        ! point and element is evaluated about once.
        do l = 1, size(cols)
            element = modulo(cols(l) - 1, n) + 1
            do kk = 1, size(rows)
                point = (rows(kk) - 1) / 5 + 1
                if (source%flag(point) == point_on_element) then
                    values = 0.0_wp
                else if (point /= last_point .or. element /= last_element) then
                    k = kernel_with_images(source%kernel, source%x(point), source%y(point), &
                                           source%medium, element, source%images, face_positive)
                    values(:, 1) = [k%ux(1), k%uy(1), k%sxx(1), k%syy(1), k%sxy(1)]
                    values(:, 2) = [k%ux(2), k%uy(2), k%sxx(2), k%syy(2), k%sxy(2)]
                    last_point = point
                    last_element = element
                end if
                block(kk, l) = values(modulo(rows(kk) - 1, 5) + 1, merge(1, 2, cols(l) <= n))
            end do
        end do
    end subroutine fill_field

    !> The progress line of an assembly of n elements' hierarchical matrix (for large n).
    subroutine report_assembly(n, seconds, compression_ratio)
        integer, intent(in) :: n
        real(wp), intent(in) :: seconds, compression_ratio

        if (reports_phases(n)) call report_progress('hierarchical assembly done in '// &
            seconds_text(seconds)//' ('//itoa(2 * n)//' unknowns, '// &
            rtoa(100.0_wp * compression_ratio)//' % of the dense matrix)')
    end subroutine report_assembly

    !> The hierarchical matrix settings of &solver, the tolerance scaled by `finer`
    !> (default 1).
    pure function settings_of(options, finer) result(settings)
        type(solver_options), intent(in) :: options
        real(wp), intent(in), optional :: finer
        type(hmatrix_settings) :: settings

        settings = hmatrix_settings(options%hmatrix_tolerance, options%hmatrix_leaf_size, &
                                    options%hmatrix_eta)
        if (present(finer)) settings%tolerance = finer * settings%tolerance
    end function settings_of

    !> The influence matrix of the medium's elements, rows as their conditions say
    !> (row_kinds).
    function new_influence_source(medium) result(source)
        type(elastic_medium), intent(in), target :: medium
        type(influence_source) :: source

        source%medium => medium
        associate (n => medium%elements%n)
            allocate (source%shear_row(n), source%normal_row(n))
        end associate
        call row_kinds(medium%elements%condition, source%shear_row, source%normal_row)
    end function new_influence_source

    !> Where the unknowns [Ds; Dn] sit: both at their element's midpoint, shape (2, 2n).
    pure function unknown_points(elements) result(points)
        type(element_set), intent(in) :: elements
        real(wp) :: points(2, 2 * elements%n)

        points(1, :) = [elements%x_mid, elements%x_mid]
        points(2, :) = [elements%y_mid, elements%y_mid]
    end function unknown_points

    !> block(k, l): the entry of unknown rows(k) against unknown cols(l).
    subroutine fill_influence(source, rows, cols, block)
        class(influence_source), intent(in) :: source
        integer, intent(in) :: rows(:), cols(:)
        real(wp), intent(out) :: block(:, :)
        integer :: n, k
        integer :: row_element(size(rows)), row_s(size(rows)), row_n(size(rows))
        integer :: col_element(size(cols)), col_s(size(cols)), col_n(size(cols))

        n = source%medium%elements%n
        ! Unknown u <= n is Ds of element u, else Dn of element u - n: each row (column) of
        ! the block is one element's shear or normal row (Ds or Dn column), the other 0.
        do k = 1, size(rows)
            row_element(k) = modulo(rows(k) - 1, n) + 1
            row_s(k) = merge(k, 0, rows(k) <= n)
            row_n(k) = merge(0, k, rows(k) <= n)
        end do
        do k = 1, size(cols)
            col_element(k) = modulo(cols(k) - 1, n) + 1
            col_s(k) = merge(k, 0, cols(k) <= n)
            col_n(k) = merge(0, k, cols(k) <= n)
        end do
        block = 0.0_wp
        call fill_influence_block(source%medium, source%shear_row, source%normal_row, &
                                  row_element, row_s, row_n, col_element, col_s, col_n, block)
    end subroutine fill_influence

end module ddc_solve_hierarchical
