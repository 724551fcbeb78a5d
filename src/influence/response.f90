!> Induced tractions and negative-face displacements at the element midpoints after a
!> solve, from the assembled influence matrix where its rows give them: one matrix-vector
!> product, in which a traction row is the induced traction and a displacement row the
!> face displacement (an identity row gives neither). What the rows do not give (the face
!> displacements of traction-row elements, most of them, and the tractions of displacement
!> and identity rows) is summed from the kernel: in the full plane by the fused sum over
!> every other source (ddc_influence_superposition) plus the element's own part (half its
!> DD on its negative face, G / (pi (1 - nu) a) times it in traction), in the half-plane
!> by the general kernel pair by pair. kernel_response sums everything that way, without a
!> matrix (a distributed run, which keeps no dense matrix). All equal the sums of the
!> general kernel over every pair within round-off (suite `kernel`).
module ddc_influence_response
    use ddc_kinds, only: wp
    use ddc_model_medium, only: elastic_medium
    use ddc_linalg_lapack, only: dgemv
    use ddc_influence_assembly, only: image_transform, image_transforms, kernel_function, &
        select_kernel, pair_influence, pair_at_midpoint, row_traction, row_displacement
    use ddc_influence_body, only: body_induced_at
    use ddc_influence_superposition, only: source_table, build_sources, superpose
    use ddc_constants, only: pi
    implicit none
    private

    public :: midpoint_response, kernel_response, listed_tractions

contains

    !> Induced tractions and negative-face displacements at every element midpoint.
    subroutine midpoint_response(medium, matrix, shear_row, normal_row, ds, dn, shear_traction, &
                                 normal_traction, us_minus, un_minus, general)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The influence matrix assembled with these row kinds (assemble_influence), shape
        !> (2n, 2n)
        real(wp), intent(in) :: matrix(:, :)
        !> Kind of the shear row and of the normal row of each element, shape (n)
        integer, intent(in) :: shear_row(:), normal_row(:)
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Induced shear and normal traction [stress unit], shape (n)
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        !> Negative-face displacement along s and n [length unit], shape (n)
        real(wp), intent(out) :: us_minus(:), un_minus(:)
        !> Sum everything with the general kernel, pair by pair, without the matrix (the
        !> reference of the tests; default false)
        logical, intent(in), optional :: general
        real(wp), allocatable :: dd(:), y(:), ts(:), tn(:), us(:), un(:)
        integer :: n, i
        logical :: reference

        n = medium%elements%n
        if (n == 0) return
        allocate (ts(n), tn(n), us(n), un(n))
        reference = .false.
        if (present(general)) reference = general
        if (reference) then
            call kernel_sums(medium, ds, dn, [(i, i = 1, n)], ts, tn, us, un, general=.true.)
            shear_traction = ts
            normal_traction = tn
            us_minus = us
            un_minus = un
            return
        end if
        dd = [ds, dn]
        allocate (y(2 * n))
        call dgemv('N', 2 * n, 2 * n, 1.0_wp, matrix, 2 * n, dd, 1, 0.0_wp, y, 1)
        ! Every element misses something from its rows (the face displacement of a traction
        ! row, the traction of the others); the kernel sums give both at the price of one.
        call kernel_sums(medium, ds, dn, [(i, i = 1, n)], ts, tn, us, un)
        shear_traction = merge(y(1:n), ts, shear_row == row_traction)
        normal_traction = merge(y(n + 1:), tn, normal_row == row_traction)
        us_minus = merge(y(1:n), us, shear_row == row_displacement)
        un_minus = merge(y(n + 1:), un, normal_row == row_displacement)
    end subroutine midpoint_response

    !> Induced tractions at the midpoints of the listed (distinct) elements: from their rows
    !> of the assembled matrix where those are traction rows, else from the general kernel.
    subroutine listed_tractions(medium, matrix, shear_row, normal_row, list, ds, dn, &
                                shear_traction, normal_traction)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The influence matrix assembled with these row kinds, shape (2n, 2n)
        real(wp), intent(in) :: matrix(:, :)
        !> Kind of the shear row and of the normal row of each element, shape (n)
        integer, intent(in) :: shear_row(:), normal_row(:)
        !> The elements wanted, shape (m)
        integer, intent(in) :: list(:)
        !> Displacement discontinuities of every element [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Induced shear and normal traction of the listed elements [stress unit], shape (m)
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        real(wp), allocatable :: ts(:), tn(:), us(:), un(:)
        integer, allocatable :: other(:)
        integer :: n, k, i

        n = medium%elements%n
        allocate (ts(n), tn(n), us(n), un(n))
        other = pack(list, shear_row(list) /= row_traction .or. normal_row(list) /= row_traction)
        if (size(other) > 0) call kernel_sums(medium, ds, dn, other, ts, tn, us, un)
        do k = 1, size(list)
            i = list(k)
            if (shear_row(i) == row_traction) then
                shear_traction(k) = dot_product(matrix(i, 1:n), ds) + &
                    dot_product(matrix(i, n + 1:), dn)
            else
                shear_traction(k) = ts(i)
            end if
            if (normal_row(i) == row_traction) then
                normal_traction(k) = dot_product(matrix(n + i, 1:n), ds) + &
                    dot_product(matrix(n + i, n + 1:), dn)
            else
                normal_traction(k) = tn(i)
            end if
        end do
    end subroutine listed_tractions

    !> Induced tractions and negative-face displacements at the element midpoints from the
    !> kernel alone, without a matrix: at every element, or at the elements first, first + 1,
    !> ... (one per output value; a distributed run splits the elements).
    subroutine kernel_response(medium, ds, dn, shear_traction, normal_traction, us_minus, &
                               un_minus, first)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Displacement discontinuities of every element [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Induced shear and normal traction [stress unit], shape (m) (n without first)
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        !> Negative-face displacement along s and n [length unit], shape (m)
        real(wp), intent(out) :: us_minus(:), un_minus(:)
        !> The element of the first output value (default 1)
        integer, intent(in), optional :: first
        real(wp), allocatable :: ts(:), tn(:), us(:), un(:)
        integer, allocatable :: range(:)
        integer :: offset, k

        offset = 0
        if (present(first)) offset = first - 1
        allocate (range(size(shear_traction)))
        do k = 1, size(range)
            range(k) = offset + k
        end do
        associate (n => medium%elements%n)
            allocate (ts(n), tn(n), us(n), un(n))
        end associate
        call kernel_sums(medium, ds, dn, range, ts, tn, us, un)
        shear_traction = ts(range)
        normal_traction = tn(range)
        us_minus = us(range)
        un_minus = un(range)
    end subroutine kernel_response

    !> Tractions and face displacements at the midpoints of the listed (distinct) elements,
    !> entries of the element-indexed outputs: the fused full-plane sum, or (half-plane, or
    !> general) the general kernel pair by pair.
    subroutine kernel_sums(medium, ds, dn, list, ts, tn, us, un, general)
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: ds(:), dn(:)
        integer, intent(in) :: list(:)
        real(wp), intent(inout) :: ts(:), tn(:), us(:), un(:)
        logical, intent(in), optional :: general
        procedure(kernel_function), pointer :: kernel
        logical :: use_general

        call select_kernel(medium, general, use_general, kernel)
        if (use_general) then
            call sums_with(kernel, medium, image_transforms(medium%elements%symmetry), ds, dn, &
                           list, ts, tn, us, un)
        else
            call fused_sums(medium, image_transforms(medium%elements%symmetry), ds, dn, list, ts, &
                            tn, us, un)
        end if
        if (allocated(medium%body)) call body_induced_at(medium, ds, dn, list, ts, tn, us, un)
    end subroutine kernel_sums

    !> The general kernel pair by pair (every pair, images included) at the listed midpoints.
    subroutine sums_with(kernel, medium, images, ds, dn, list, ts, tn, us, un)
        procedure(kernel_function) :: kernel
        type(elastic_medium), intent(in) :: medium
        type(image_transform), intent(in) :: images(:)
        real(wp), intent(in) :: ds(:), dn(:)
        integer, intent(in) :: list(:)
        real(wp), intent(inout) :: ts(:), tn(:), us(:), un(:)
        type(pair_influence) :: p
        real(wp) :: acc(4)
        integer :: k, i, j

        !$omp parallel do default(none) schedule(dynamic, 4) private(k, i, j, p, acc) &
        !$omp shared(medium, images, ds, dn, list, ts, tn, us, un)
        do k = 1, size(list)
            i = list(k)
            acc = 0.0_wp
            do j = 1, medium%elements%n
                p = pair_at_midpoint(kernel, medium, i, j, images)
                acc(1) = acc(1) + p%ts(1) * ds(j) + p%ts(2) * dn(j)
                acc(2) = acc(2) + p%tn(1) * ds(j) + p%tn(2) * dn(j)
                acc(3) = acc(3) + p%us(1) * ds(j) + p%us(2) * dn(j)
                acc(4) = acc(4) + p%un(1) * ds(j) + p%un(2) * dn(j)
            end do
            ts(i) = acc(1)
            tn(i) = acc(2)
            us(i) = acc(3)
            un(i) = acc(4)
        end do
        !$omp end parallel do
    end subroutine sums_with

    !> Full plane: the fused sum over every source but the element itself (superpose) at
    !> each listed midpoint, resolved in the element's frame, plus the element's own part:
    !> its negative face moves by half its DD (C&S: u(-) - u(+) = D) and its midpoint
    !> carries the traction G / (pi (1 - nu) a) D of its own DD.
    subroutine fused_sums(medium, images, ds, dn, list, ts, tn, us, un)
        type(elastic_medium), intent(in) :: medium
        type(image_transform), intent(in) :: images(:)
        real(wp), intent(in) :: ds(:), dn(:)
        integer, intent(in) :: list(:)
        real(wp), intent(inout) :: ts(:), tn(:), us(:), un(:)
        type(source_table) :: src
        real(wp) :: u(2), stress(3), c, s, own, shear_modulus, nu
        integer :: k, i

        shear_modulus = medium%shear_modulus
        nu = medium%poissons_ratio
        call build_sources(medium%elements, images, ds, dn, src)
        !$omp parallel do default(none) schedule(static) private(k, i, u, stress, c, s, own) &
        !$omp shared(medium, src, shear_modulus, nu, ds, dn, list, ts, tn, us, un)
        do k = 1, size(list)
            i = list(k)
            call superpose(src, shear_modulus, nu, medium%elements%x_mid(i), &
                           medium%elements%y_mid(i), i, u, stress)
            c = medium%elements%cos_beta(i)
            s = medium%elements%sin_beta(i)
            own = shear_modulus / (pi * (1.0_wp - nu) * medium%elements%half_length(i))
            ts(i) = -(stress(1) - stress(2)) * s * c + stress(3) * (c**2 - s**2) + own * ds(i)
            tn(i) = stress(1) * s**2 - 2.0_wp * stress(3) * s * c + stress(2) * c**2 + own * dn(i)
            us(i) = u(1) * c + u(2) * s + 0.5_wp * ds(i)
            un(i) = -u(1) * s + u(2) * c + 0.5_wp * dn(i)
        end do
        !$omp end parallel do
    end subroutine fused_sums

end module ddc_influence_response
