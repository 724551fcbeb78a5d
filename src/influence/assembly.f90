!> Influence matrices and midpoint responses of a set of constant-DD elements.
!>
!> Unknowns are ordered in blocks [Ds(1:n); Dn(1:n)], rows [shear rows; normal rows]. A row
!> is a traction row (stress resolved on element i, tension positive), a displacement row
!> (displacement of the negative face of element i in its s, n frame) or an identity row
!> (the DD of element i itself: prescribed DDs).
!>
!> The kernel (full plane or half-plane, SPEC-EARTH 1) is chosen once per model by
!> select_kernel and passed down as a procedure argument: the loops hold no branch on it.
!>
!> Symmetry (TWODD KSYM 2-4, Crouch & Starfield ch. 5): every element j has implicit images
!> mirrored about x = xsym, y = ysym or both. Mirrored with its end order kept, an element
!> (midpoint m, direction s) becomes (R m, R s); a single reflection (det R = -1) swaps the
!> faces, so the image carries (-Ds, Dn); the double reflection (a half turn) carries
!> (Ds, Dn). Only the given elements are unknowns; their columns sum the real element and
!> its images. Without symmetry the image list is empty and the loops cost nothing.
module ddc_influence_assembly
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, symmetry_options, symmetry_x, symmetry_y, &
        symmetry_both, domain_half_plane
    use ddc_influence_kernel, only: dd_kernel, dd_kernel_global, face_negative
    use ddc_influence_kernel_half_plane, only: dd_kernel_half_plane
    implicit none
    private

    public :: assemble_influence, fill_influence_block, midpoint_response
    public :: row_traction, row_displacement, row_identity
    public :: image_transform, image_transforms, image_of, kernel_with_images
    public :: kernel_function, select_kernel

    !> Interface of a kernel: dd_kernel_global or dd_kernel_half_plane.
    abstract interface
        pure function kernel_function(x, y, xm, ym, a, cosb, sinb, shear_modulus, nu, face) &
            result(k)
            import :: wp, dd_kernel
            implicit none
            !> Observation point, element midpoint, half-length [length unit]
            real(wp), intent(in) :: x, y, xm, ym, a
            !> Element direction cosines, shear modulus [stress unit], Poisson's ratio [-]
            real(wp), intent(in) :: cosb, sinb, shear_modulus, nu
            !> Face reported for a point on the element itself
            integer, intent(in) :: face
            !> Global-frame displacement and stress per unit Ds (1) and Dn (2)
            type(dd_kernel) :: k
        end function kernel_function
    end interface

    !> One implicit image of every element: reflection about x = xsym and/or y = ysym.
    type :: image_transform
        !> Mirror the x coordinate about x = xsym; mirror y about y = ysym
        logical :: mirror_x = .false., mirror_y = .false.
        !> Positions of the symmetry lines [length unit]
        real(wp) :: xsym = 0.0_wp, ysym = 0.0_wp
        !> Factor on Ds of the image (-1 for a single reflection, +1 for both); Dn keeps
        !> its sign
        real(wp) :: sign_s = 1.0_wp
    end type image_transform

    !> Kinds of matrix rows
    integer, parameter :: row_traction = 1, row_displacement = 2, row_identity = 3

    !> Influence of unit Ds and Dn on element j at the midpoint of element i, in i's frame.
    type, public :: pair_influence
        !> Shear and normal traction per unit (Ds, Dn) [stress unit / length unit]
        real(wp) :: ts(2), tn(2)
        !> Negative-face displacement along s and n per unit (Ds, Dn) [-]
        real(wp) :: us(2), un(2)
    end type pair_influence

contains

    !> The kernel of the elements' domain: the only place the choice is made.
    subroutine select_kernel(elements, kernel)
        !> Elements (their domain is used)
        type(element_set), intent(in) :: elements
        !> Associated with dd_kernel_half_plane or dd_kernel_global
        procedure(kernel_function), pointer, intent(out) :: kernel

        if (elements%domain == domain_half_plane) then
            kernel => dd_kernel_half_plane
        else
            kernel => dd_kernel_global
        end if
    end subroutine select_kernel

    !> The images implied by a symmetry option: none, one (x or y) or three (both).
    pure function image_transforms(symmetry) result(images)
        !> Symmetry of the model
        type(symmetry_options), intent(in) :: symmetry
        !> The image transforms, shape (0), (1) or (3)
        type(image_transform), allocatable :: images(:)

        associate (xs => symmetry%xsym, ys => symmetry%ysym)
            select case (symmetry%kind)
            case (symmetry_x)
                images = [image_transform(.true., .false., xs, ys, -1.0_wp)]
            case (symmetry_y)
                images = [image_transform(.false., .true., xs, ys, -1.0_wp)]
            case (symmetry_both)
                images = [image_transform(.true., .false., xs, ys, -1.0_wp), &
                          image_transform(.false., .true., xs, ys, -1.0_wp), &
                          image_transform(.true., .true., xs, ys, 1.0_wp)]
            case default
                allocate (images(0))
            end select
        end associate
    end function image_transforms

    !> Midpoint and direction cosines of the image of element j under transform t.
    pure subroutine image_of(elements, j, t, xm, ym, cosb, sinb)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Element index
        integer, intent(in) :: j
        !> The image transform
        type(image_transform), intent(in) :: t
        !> Image midpoint [length unit] and direction cosines
        real(wp), intent(out) :: xm, ym, cosb, sinb

        xm = elements%x_mid(j)
        ym = elements%y_mid(j)
        cosb = elements%cos_beta(j)
        sinb = elements%sin_beta(j)
        if (t%mirror_x) then
            xm = 2.0_wp * t%xsym - xm
            cosb = -cosb
        end if
        if (t%mirror_y) then
            ym = 2.0_wp * t%ysym - ym
            sinb = -sinb
        end if
    end subroutine image_of

    !> Global-frame kernel of element j plus its images at (x, y), per unit Ds and Dn of j.
    pure function kernel_with_images(kernel, x, y, elements, j, images, shear_modulus, nu, &
                                     face) result(k)
        !> The kernel of the model (from select_kernel)
        procedure(kernel_function) :: kernel
        !> Point [length unit]
        real(wp), intent(in) :: x, y
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Element index
        integer, intent(in) :: j
        !> Image transforms from image_transforms (empty without symmetry)
        type(image_transform), intent(in) :: images(:)
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Face reported for a point on an element (face_negative or face_positive)
        integer, intent(in) :: face
        !> Displacement and stress per unit Ds (index 1) and Dn (index 2) of element j
        type(dd_kernel) :: k
        type(dd_kernel) :: ki
        real(wp) :: xm, ym, cosb, sinb, f(2)
        integer :: t

        k = kernel(x, y, elements%x_mid(j), elements%y_mid(j), elements%half_length(j), &
                   elements%cos_beta(j), elements%sin_beta(j), shear_modulus, nu, face)
        do t = 1, size(images)
            call image_of(elements, j, images(t), xm, ym, cosb, sinb)
            ki = kernel(x, y, xm, ym, elements%half_length(j), cosb, sinb, shear_modulus, nu, &
                        face)
            f = [images(t)%sign_s, 1.0_wp]
            k%ux = k%ux + f * ki%ux
            k%uy = k%uy + f * ki%uy
            k%sxx = k%sxx + f * ki%sxx
            k%syy = k%syy + f * ki%syy
            k%sxy = k%sxy + f * ki%sxy
        end do
    end function kernel_with_images

    !> Influence of element j (and its images) on the midpoint of element i, resolved in
    !> i's s, n frame.
    pure function pair_at_midpoint(kernel, elements, i, j, images, shear_modulus, nu) result(p)
        procedure(kernel_function) :: kernel
        type(element_set), intent(in) :: elements
        integer, intent(in) :: i, j
        type(image_transform), intent(in) :: images(:)
        real(wp), intent(in) :: shear_modulus, nu
        type(pair_influence) :: p
        type(dd_kernel) :: k
        real(wp) :: c, s

        k = kernel_with_images(kernel, elements%x_mid(i), elements%y_mid(i), elements, j, &
                               images, shear_modulus, nu, face_negative)
        c = elements%cos_beta(i)
        s = elements%sin_beta(i)
        p%ts = -(k%sxx - k%syy) * s * c + k%sxy * (c**2 - s**2)
        p%tn = k%sxx * s**2 - 2.0_wp * k%sxy * s * c + k%syy * c**2
        p%us = k%ux * c + k%uy * s
        p%un = -k%ux * s + k%uy * c
    end function pair_at_midpoint

    !> Fill the 2n x 2n influence matrix; each row is a traction, displacement or identity
    !> row.
    subroutine assemble_influence(elements, shear_modulus, nu, shear_row, normal_row, matrix)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Kind of the shear row and of the normal row of each element, shape (n)
        integer, intent(in) :: shear_row(:), normal_row(:)
        !> Influence matrix, shape (2n, 2n)
        real(wp), intent(out) :: matrix(:, :)
        integer, allocatable :: every(:)
        integer :: i

        allocate (every(elements%n))
        do i = 1, elements%n
            every(i) = i
        end do
        call fill_influence_block(elements, shear_modulus, nu, shear_row, normal_row, every, &
                                  every, elements%n + every, every, every, elements%n + every, &
                                  matrix)
    end subroutine assemble_influence

    !> Fill any block of the influence matrix: the rows of some elements against the DDs of
    !> some elements, each placed where the caller says (a distributed matrix fills its local
    !> part; assemble_influence the whole matrix in the [s; n] ordering). The entry of the
    !> shear row of element row_element(k) against Ds of element col_element(l) goes to
    !> block(row_s(k), col_s(l)); row_n and col_n place the normal rows and the Dn columns. A
    !> place 0 means that row or column is not in the block; entries nowhere placed are left
    !> as they are. Each pair of elements is evaluated once, whatever the ordering.
    subroutine fill_influence_block(elements, shear_modulus, nu, shear_row, normal_row, &
                                    row_element, row_s, row_n, col_element, col_s, col_n, block)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Kind of the shear row and of the normal row of each element, shape (n)
        integer, intent(in) :: shear_row(:), normal_row(:)
        !> Elements whose rows are in the block, shape (r)
        integer, intent(in) :: row_element(:)
        !> Row of the block for each one's shear row and normal row (0: not in it), shape (r)
        integer, intent(in) :: row_s(:), row_n(:)
        !> Elements whose DDs are in the block, shape (c)
        integer, intent(in) :: col_element(:)
        !> Column of the block for each one's Ds and Dn (0: not in it; every non-zero
        !> column appears once), shape (c)
        integer, intent(in) :: col_s(:), col_n(:)
        !> The block: rows and columns as placed, shape (at least max(row_s, row_n), at
        !> least max(col_s, col_n))
        real(wp), intent(inout) :: block(:, :)
        procedure(kernel_function), pointer :: kernel

        call select_kernel(elements, kernel)
        call fill_with(kernel, elements, image_transforms(elements%symmetry), shear_modulus, nu, &
                       shear_row, normal_row, row_element, row_s, row_n, col_element, col_s, &
                       col_n, block)
    end subroutine fill_influence_block

    !> fill_influence_block with the kernel and the image transforms given.
    subroutine fill_with(kernel, elements, images, shear_modulus, nu, shear_row, normal_row, &
                         row_element, row_s, row_n, col_element, col_s, col_n, block)
        procedure(kernel_function) :: kernel
        type(element_set), intent(in) :: elements
        type(image_transform), intent(in) :: images(:)
        real(wp), intent(in) :: shear_modulus, nu
        integer, intent(in) :: shear_row(:), normal_row(:)
        integer, intent(in) :: row_element(:), row_s(:), row_n(:)
        integer, intent(in) :: col_element(:), col_s(:), col_n(:)
        real(wp), intent(inout) :: block(:, :)
        type(pair_influence) :: p
        real(wp) :: v(2)
        integer :: i, j, k, l

        ! Each thread owns whole columns (those of col_element(l)): disjoint writes.
        !$omp parallel do default(none) schedule(static) private(i, j, k, l, p, v) &
        !$omp shared(elements, shear_modulus, nu, shear_row, normal_row, row_element, row_s, &
        !$omp        row_n, col_element, col_s, col_n, block, images)
        do l = 1, size(col_element)
            j = col_element(l)
            do k = 1, size(row_element)
                i = row_element(k)
                p = pair_at_midpoint(kernel, elements, i, j, images, shear_modulus, nu)
                if (row_s(k) > 0) then
                    select case (shear_row(i))
                    case (row_traction)
                        v = p%ts
                    case (row_displacement)
                        v = p%us
                    case default
                        v = [merge(1.0_wp, 0.0_wp, i == j), 0.0_wp]
                    end select
                    if (col_s(l) > 0) block(row_s(k), col_s(l)) = v(1)
                    if (col_n(l) > 0) block(row_s(k), col_n(l)) = v(2)
                end if
                if (row_n(k) > 0) then
                    select case (normal_row(i))
                    case (row_traction)
                        v = p%tn
                    case (row_displacement)
                        v = p%un
                    case default
                        v = [0.0_wp, merge(1.0_wp, 0.0_wp, i == j)]
                    end select
                    if (col_s(l) > 0) block(row_n(k), col_s(l)) = v(1)
                    if (col_n(l) > 0) block(row_n(k), col_n(l)) = v(2)
                end if
            end do
        end do
        !$omp end parallel do
    end subroutine fill_with

    !> Induced tractions and negative-face displacements at the element midpoints: at every
    !> element, or at the elements first, first + 1, ... (one per output value; a
    !> distributed run splits the elements).
    subroutine midpoint_response(elements, shear_modulus, nu, ds, dn, shear_traction, &
                                 normal_traction, us_minus, un_minus, first)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Displacement discontinuities of every element [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Induced shear and normal traction [stress unit], shape (m) (n without first)
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        !> Negative-face displacement along s and n [length unit], shape (m)
        real(wp), intent(out) :: us_minus(:), un_minus(:)
        !> The element of the first output value (default 1)
        integer, intent(in), optional :: first
        procedure(kernel_function), pointer :: kernel
        integer :: offset

        offset = 0
        if (present(first)) offset = first - 1
        call select_kernel(elements, kernel)
        call response_with(kernel, elements, image_transforms(elements%symmetry), shear_modulus, &
                           nu, ds, dn, offset, shear_traction, normal_traction, us_minus, un_minus)
    end subroutine midpoint_response

    !> midpoint_response with the kernel, the image transforms and the element before the
    !> first output value given.
    subroutine response_with(kernel, elements, images, shear_modulus, nu, ds, dn, offset, &
                             shear_traction, normal_traction, us_minus, un_minus)
        procedure(kernel_function) :: kernel
        type(element_set), intent(in) :: elements
        type(image_transform), intent(in) :: images(:)
        real(wp), intent(in) :: shear_modulus, nu
        real(wp), intent(in) :: ds(:), dn(:)
        integer, intent(in) :: offset
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        real(wp), intent(out) :: us_minus(:), un_minus(:)
        type(pair_influence) :: p
        real(wp) :: ts, tn, us, un
        integer :: i, j, k

        !$omp parallel do default(none) schedule(static) private(i, j, k, p, ts, tn, us, un) &
        !$omp shared(elements, shear_modulus, nu, ds, dn, shear_traction, normal_traction, &
        !$omp        us_minus, un_minus, images, offset)
        do k = 1, size(shear_traction)
            i = offset + k
            ts = 0.0_wp
            tn = 0.0_wp
            us = 0.0_wp
            un = 0.0_wp
            do j = 1, elements%n
                p = pair_at_midpoint(kernel, elements, i, j, images, shear_modulus, nu)
                ts = ts + p%ts(1) * ds(j) + p%ts(2) * dn(j)
                tn = tn + p%tn(1) * ds(j) + p%tn(2) * dn(j)
                us = us + p%us(1) * ds(j) + p%us(2) * dn(j)
                un = un + p%un(1) * ds(j) + p%un(2) * dn(j)
            end do
            shear_traction(k) = ts
            normal_traction(k) = tn
            us_minus(k) = us
            un_minus(k) = un
        end do
        !$omp end parallel do
    end subroutine response_with

end module ddc_influence_assembly
