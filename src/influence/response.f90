!> Induced tractions and negative-face displacements at every element midpoint after a
!> solve, from the assembled influence matrix where its rows give them: one matrix-vector
!> product, in which a traction row is the induced traction and a displacement row the
!> face displacement (an identity row gives neither). What the rows do not give is summed
!> from the kernel: the face displacements of traction-row elements (most of them) by the
!> fused full-plane sum (ddc_influence_superposition; the general kernel in the
!> half-plane), the tractions of displacement and identity rows by the general kernel.
!> Both equal the sums of the general kernel over every pair within round-off.
module ddc_influence_response
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, domain_half_plane
    use ddc_linalg_lapack, only: dgemv
    use ddc_influence_assembly, only: image_transform, image_transforms, kernel_function, &
        select_kernel, pair_influence, pair_at_midpoint, row_traction, row_displacement
    use ddc_influence_superposition, only: source_table, build_sources, superpose
    implicit none
    private

    public :: midpoint_response, listed_tractions

contains

    !> Induced tractions and negative-face displacements at every element midpoint.
    subroutine midpoint_response(elements, shear_modulus, nu, matrix, shear_row, normal_row, &
                                 ds, dn, shear_traction, normal_traction, us_minus, un_minus, &
                                 general)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
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
        integer, allocatable :: no_traction(:), no_displacement(:)
        integer :: n, i

        n = elements%n
        if (n == 0) return
        allocate (ts(n), tn(n), us(n), un(n))
        if (present(general)) then
            if (general) then
                call general_sums(elements, shear_modulus, nu, ds, dn, [(i, i = 1, n)], ts, &
                                  tn, us, un)
                shear_traction = ts
                normal_traction = tn
                us_minus = us
                un_minus = un
                return
            end if
        end if
        dd = [ds, dn]
        allocate (y(2 * n))
        call dgemv('N', 2 * n, 2 * n, 1.0_wp, matrix, 2 * n, dd, 1, 0.0_wp, y, 1)
        no_traction = pack([(i, i = 1, n)], shear_row /= row_traction .or. &
                           normal_row /= row_traction)
        no_displacement = pack([(i, i = 1, n)], shear_row /= row_displacement .or. &
                               normal_row /= row_displacement)
        if (elements%domain == domain_half_plane) then
            call general_sums(elements, shear_modulus, nu, ds, dn, [(i, i = 1, n)], ts, tn, &
                              us, un)
        else
            call general_sums(elements, shear_modulus, nu, ds, dn, no_traction, ts, tn, us, un)
            call face_displacements(elements, nu, ds, dn, no_displacement, us, un)
        end if
        shear_traction = merge(y(1:n), ts, shear_row == row_traction)
        normal_traction = merge(y(n + 1:), tn, normal_row == row_traction)
        us_minus = merge(y(1:n), us, shear_row == row_displacement)
        un_minus = merge(y(n + 1:), un, normal_row == row_displacement)
    end subroutine midpoint_response

    !> Induced tractions at the midpoints of the listed (distinct) elements: from their rows
    !> of the assembled matrix where those are traction rows, else from the general kernel.
    subroutine listed_tractions(elements, shear_modulus, nu, matrix, shear_row, normal_row, &
                                list, ds, dn, shear_traction, normal_traction)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
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

        n = elements%n
        allocate (ts(n), tn(n), us(n), un(n))
        other = pack(list, shear_row(list) /= row_traction .or. normal_row(list) /= row_traction)
        if (size(other) > 0) call general_sums(elements, shear_modulus, nu, ds, dn, other, ts, &
                                               tn, us, un)
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

    !> Tractions and face displacements at the midpoints of the listed (distinct) elements
    !> from the general kernel (every pair, images included).
    subroutine general_sums(elements, shear_modulus, nu, ds, dn, list, ts, tn, us, un)
        type(element_set), intent(in) :: elements
        real(wp), intent(in) :: shear_modulus, nu, ds(:), dn(:)
        integer, intent(in) :: list(:)
        real(wp), intent(inout) :: ts(:), tn(:), us(:), un(:)
        procedure(kernel_function), pointer :: kernel
        type(image_transform), allocatable :: images(:)

        call select_kernel(elements, kernel)
        images = image_transforms(elements%symmetry)
        call sums_with(kernel, elements, images, shear_modulus, nu, ds, dn, list, ts, tn, us, un)
    end subroutine general_sums

    !> general_sums with the kernel and the image transforms given.
    subroutine sums_with(kernel, elements, images, shear_modulus, nu, ds, dn, list, ts, tn, &
                         us, un)
        procedure(kernel_function) :: kernel
        type(element_set), intent(in) :: elements
        type(image_transform), intent(in) :: images(:)
        real(wp), intent(in) :: shear_modulus, nu, ds(:), dn(:)
        integer, intent(in) :: list(:)
        real(wp), intent(inout) :: ts(:), tn(:), us(:), un(:)
        type(pair_influence) :: p
        real(wp) :: acc(4)
        integer :: k, i, j

        !$omp parallel do default(none) schedule(dynamic, 4) private(k, i, j, p, acc) &
        !$omp shared(elements, images, shear_modulus, nu, ds, dn, list, ts, tn, us, un)
        do k = 1, size(list)
            i = list(k)
            acc = 0.0_wp
            do j = 1, elements%n
                p = pair_at_midpoint(kernel, elements, i, j, images, shear_modulus, nu)
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

    !> Full plane: negative-face displacements at the midpoints of the listed elements by the
    !> fused sum over every other source, plus the element's own jump: its negative face
    !> moves by half its DD (C&S: u(-) - u(+) = D).
    subroutine face_displacements(elements, nu, ds, dn, list, us, un)
        type(element_set), intent(in) :: elements
        real(wp), intent(in) :: nu, ds(:), dn(:)
        integer, intent(in) :: list(:)
        real(wp), intent(inout) :: us(:), un(:)
        type(source_table) :: src
        real(wp) :: u(2), unused(3)
        integer :: k, i

        call build_sources(elements, image_transforms(elements%symmetry), ds, dn, src)
        !$omp parallel do default(none) schedule(static) private(k, i, u, unused) &
        !$omp shared(elements, src, nu, ds, dn, list, us, un)
        do k = 1, size(list)
            i = list(k)
            ! The shear modulus does not enter the displacement.
            call superpose(src, 1.0_wp, nu, elements%x_mid(i), elements%y_mid(i), i, u, unused)
            us(i) = u(1) * elements%cos_beta(i) + u(2) * elements%sin_beta(i) + 0.5_wp * ds(i)
            un(i) = -u(1) * elements%sin_beta(i) + u(2) * elements%cos_beta(i) + 0.5_wp * dn(i)
        end do
        !$omp end parallel do
    end subroutine face_displacements

end module ddc_influence_response
