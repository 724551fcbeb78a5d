!> Influence matrices of a set of constant-DD elements.
!>
!> Unknowns are ordered in blocks [Ds(1:n); Dn(1:n)], rows [shear rows; normal rows]. A row
!> is a traction row (stress resolved on element i, tension positive), a displacement row
!> (displacement of the negative face of element i in its s, n frame) or an identity row
!> (the DD of element i itself: prescribed DDs).
!>
!> The kernel of the medium (full plane, half-plane:
!> docs/theory/kernels.md#the-half-plane-kernel, or two bonded half-planes:
!> docs/theory/bimaterial.md) is chosen once per model by select_kernel and passed down as a
!> procedure argument: the loops hold no branch on it. Every kernel takes the medium, whose
!> materials it needs.
!>
!> Two paths fill the matrix. The general one evaluates the whole kernel (displacement and
!> stress, any domain) at every pair. The full-plane path fills the traction rows, by far
!> the most common, from the stress part alone (rational in the coordinates: no logarithm or
!> angle), one column at a time in a loop over the receivers that vectorizes, the stress of
!> the source resolved directly on the receiver's plane (relative angle); the other rows of
!> that path come from the general kernel. Both give the same matrix within round-off
!> (suite `kernel` compares them).
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
        symmetry_both, domain_half_plane, domain_bimaterial, domain_full_plane
    use ddc_model_medium, only: elastic_medium
    use ddc_influence_kernel, only: dd_kernel, dd_kernel_global, dd_stress_global, &
        face_negative
    use ddc_influence_kernel_half_plane, only: dd_kernel_half_plane
    use ddc_influence_kernel_bimaterial, only: dd_kernel_bimaterial
    use ddc_constants, only: pi
    implicit none
    private

    public :: assemble_influence, fill_influence_block, pair_at_midpoint
    public :: row_traction, row_displacement, row_identity
    public :: image_transform, image_transforms, image_of, kernel_with_images
    public :: segment_kernel_with_images, resolved_tractions
    public :: kernel_function, select_kernel, full_plane_kernel

    abstract interface
        !> Interface of a kernel of a medium: full_plane_kernel, full_plane_stress,
        !> half_plane_kernel or bimaterial_kernel.
        pure function kernel_function(x, y, xm, ym, a, cosb, sinb, medium, face) result(k)
            import :: wp, dd_kernel, elastic_medium
            implicit none
            !> Observation point, element midpoint, half-length [length unit]
            real(wp), intent(in) :: x, y, xm, ym, a
            !> Element direction cosines
            real(wp), intent(in) :: cosb, sinb
            !> The medium (its materials)
            type(elastic_medium), intent(in) :: medium
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

    !> Whether the general path (the kernel pair by pair) serves, and its kernel: always
    !> outside the full plane (the fast paths are full-plane only), in the full plane when
    !> asked.
    subroutine select_kernel(medium, general, use_general, kernel, stress_only)
        !> The medium (the domain of its elements is used)
        type(elastic_medium), intent(in) :: medium
        !> Take the general path even in the full plane (tests; absent: false)
        logical, intent(in), optional :: general
        !> Whether the general path serves
        logical, intent(out) :: use_general
        !> Associated with the kernel of the medium's domain
        procedure(kernel_function), pointer, intent(out) :: kernel
        !> The caller needs stresses only: in the full plane full_plane_stress (absent: false)
        logical, intent(in), optional :: stress_only

        use_general = medium%elements%domain /= domain_full_plane
        if (present(general)) use_general = use_general .or. general
        select case (medium%elements%domain)
        case (domain_half_plane)
            kernel => half_plane_kernel
        case (domain_bimaterial)
            kernel => bimaterial_kernel
        case default
            kernel => full_plane_kernel
            if (present(stress_only)) then
                if (stress_only) kernel => full_plane_stress
            end if
        end select
    end subroutine select_kernel

    !> The full-plane kernel (dd_kernel_global) in the medium's material.
    pure function full_plane_kernel(x, y, xm, ym, a, cosb, sinb, medium, face) result(k)
        real(wp), intent(in) :: x, y, xm, ym, a, cosb, sinb
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: face
        type(dd_kernel) :: k

        k = dd_kernel_global(x, y, xm, ym, a, cosb, sinb, medium%shear_modulus, &
                             medium%poissons_ratio, face)
    end function full_plane_kernel

    !> The stress part of the full-plane kernel (dd_stress_global) in the medium's material.
    pure function full_plane_stress(x, y, xm, ym, a, cosb, sinb, medium, face) result(k)
        real(wp), intent(in) :: x, y, xm, ym, a, cosb, sinb
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: face
        type(dd_kernel) :: k

        k = dd_stress_global(x, y, xm, ym, a, cosb, sinb, medium%shear_modulus, &
                             medium%poissons_ratio, face)
    end function full_plane_stress

    !> The half-plane kernel (dd_kernel_half_plane) in the medium's material.
    pure function half_plane_kernel(x, y, xm, ym, a, cosb, sinb, medium, face) result(k)
        real(wp), intent(in) :: x, y, xm, ym, a, cosb, sinb
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: face
        type(dd_kernel) :: k

        k = dd_kernel_half_plane(x, y, xm, ym, a, cosb, sinb, medium%shear_modulus, &
                                 medium%poissons_ratio, face)
    end function half_plane_kernel

    !> The kernel of two bonded half-planes (dd_kernel_bimaterial): the medium's lower and
    !> upper material, its interface.
    pure function bimaterial_kernel(x, y, xm, ym, a, cosb, sinb, medium, face) result(k)
        real(wp), intent(in) :: x, y, xm, ym, a, cosb, sinb
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: face
        type(dd_kernel) :: k

        k = dd_kernel_bimaterial(x, y, xm, ym, a, cosb, sinb, &
                                 [medium%shear_modulus, medium%upper%shear_modulus], &
                                 [medium%poissons_ratio, medium%upper%poissons_ratio], &
                                 medium%interface_y, face)
    end function bimaterial_kernel

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
        call mirror_segment(t, xm, ym, cosb, sinb)
    end subroutine image_of

    !> A segment's midpoint and direction cosines mirrored by transform t, in place.
    pure subroutine mirror_segment(t, xm, ym, cosb, sinb)
        !> The image transform
        type(image_transform), intent(in) :: t
        !> Midpoint [length unit] and direction cosines
        real(wp), intent(inout) :: xm, ym, cosb, sinb

        if (t%mirror_x) then
            xm = 2.0_wp * t%xsym - xm
            cosb = -cosb
        end if
        if (t%mirror_y) then
            ym = 2.0_wp * t%ysym - ym
            sinb = -sinb
        end if
    end subroutine mirror_segment

    !> Global-frame kernel of element j plus its images at (x, y), per unit Ds and Dn of j.
    pure function kernel_with_images(kernel, x, y, medium, j, images, face) result(k)
        !> The kernel of the model (from select_kernel)
        procedure(kernel_function) :: kernel
        !> Point [length unit]
        real(wp), intent(in) :: x, y
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Element index
        integer, intent(in) :: j
        !> Image transforms from image_transforms (empty without symmetry)
        type(image_transform), intent(in) :: images(:)
        !> Face reported for a point on an element (face_negative or face_positive)
        integer, intent(in) :: face
        !> Displacement and stress per unit Ds (index 1) and Dn (index 2) of element j
        type(dd_kernel) :: k

        associate (e => medium%elements)
            k = segment_kernel_with_images(kernel, x, y, e%x_mid(j), e%y_mid(j), &
                                           e%half_length(j), e%cos_beta(j), e%sin_beta(j), &
                                           images, medium, face)
        end associate
    end function kernel_with_images

    !> Global-frame kernel at (x, y) of a constant-DD segment plus its images, per unit Ds
    !> and Dn of the segment.
    pure function segment_kernel_with_images(kernel, x, y, xm, ym, a, cosb, sinb, images, &
                                             medium, face) result(k)
        !> The kernel of the model (from select_kernel)
        procedure(kernel_function) :: kernel
        !> Point, segment midpoint and half-length [length unit]
        real(wp), intent(in) :: x, y, xm, ym, a
        !> Segment direction cosines
        real(wp), intent(in) :: cosb, sinb
        !> Image transforms from image_transforms (empty without symmetry)
        type(image_transform), intent(in) :: images(:)
        !> The medium (its materials)
        type(elastic_medium), intent(in) :: medium
        !> Face reported for a point on the segment (face_negative or face_positive)
        integer, intent(in) :: face
        !> Displacement and stress per unit Ds (index 1) and Dn (index 2)
        type(dd_kernel) :: k
        type(dd_kernel) :: ki
        real(wp) :: xi, yi, ci, si, f(2)
        integer :: t

        k = kernel(x, y, xm, ym, a, cosb, sinb, medium, face)
        do t = 1, size(images)
            xi = xm
            yi = ym
            ci = cosb
            si = sinb
            call mirror_segment(images(t), xi, yi, ci, si)
            ki = kernel(x, y, xi, yi, a, ci, si, medium, face)
            f = [images(t)%sign_s, 1.0_wp]
            k%ux = k%ux + f * ki%ux
            k%uy = k%uy + f * ki%uy
            k%sxx = k%sxx + f * ki%sxx
            k%syy = k%syy + f * ki%syy
            k%sxy = k%sxy + f * ki%sxy
        end do
    end function segment_kernel_with_images

    !> The shear and normal traction, per unit Ds (index 1) and Dn (index 2), of a kernel's
    !> stress on the plane with direction cosines (c, s).
    pure subroutine resolved_tractions(k, c, s, ts, tn)
        !> Global-frame kernel
        type(dd_kernel), intent(in) :: k
        !> Direction cosines of the plane
        real(wp), intent(in) :: c, s
        !> Shear and normal traction [stress unit / length unit]
        real(wp), intent(out) :: ts(2), tn(2)

        ts = -(k%sxx - k%syy) * s * c + k%sxy * (c**2 - s**2)
        tn = k%sxx * s**2 - 2.0_wp * k%sxy * s * c + k%syy * c**2
    end subroutine resolved_tractions

    !> Influence of element j (and its images) on the midpoint of element i, resolved in
    !> i's s, n frame.
    pure function pair_at_midpoint(kernel, medium, i, j, images) result(p)
        !> The kernel of the model (from select_kernel)
        procedure(kernel_function) :: kernel
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Receiver and source element
        integer, intent(in) :: i, j
        !> Image transforms from image_transforms (empty without symmetry)
        type(image_transform), intent(in) :: images(:)
        !> Tractions and negative-face displacements per unit Ds and Dn of j
        type(pair_influence) :: p
        type(dd_kernel) :: k
        real(wp) :: c, s

        k = kernel_with_images(kernel, medium%elements%x_mid(i), medium%elements%y_mid(i), &
                               medium, j, images, face_negative)
        c = medium%elements%cos_beta(i)
        s = medium%elements%sin_beta(i)
        call resolved_tractions(k, c, s, p%ts, p%tn)
        p%us = k%ux * c + k%uy * s
        p%un = -k%ux * s + k%uy * c
    end function pair_at_midpoint

    !> Fill the 2n x 2n influence matrix; each row is a traction, displacement or identity
    !> row.
    subroutine assemble_influence(medium, shear_row, normal_row, matrix, general)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Kind of the shear row and of the normal row of each element, shape (n)
        integer, intent(in) :: shear_row(:), normal_row(:)
        !> Influence matrix, shape (2n, 2n)
        real(wp), intent(out) :: matrix(:, :)
        !> Take the general path even in the full plane (tests; default false)
        logical, intent(in), optional :: general
        integer, allocatable :: every(:)
        integer :: i

        allocate (every(medium%elements%n))
        do i = 1, medium%elements%n
            every(i) = i
        end do
        call fill_influence_block(medium, shear_row, normal_row, every, every, &
                                  medium%elements%n + every, every, every, &
                                  medium%elements%n + every, matrix, general)
    end subroutine assemble_influence

    !> Fill any block of the influence matrix: the rows of some elements against the DDs of
    !> some elements, each placed where the caller says (a distributed matrix fills its local
    !> part; assemble_influence the whole matrix in the [s; n] ordering). The entry of the
    !> shear row of element row_element(k) against Ds of element col_element(l) goes to
    !> block(row_s(k), col_s(l)); row_n and col_n place the normal rows and the Dn columns. A
    !> place 0 means that row or column is not in the block; entries nowhere placed are left
    !> as they are. Each pair of elements is evaluated once, whatever the ordering.
    subroutine fill_influence_block(medium, shear_row, normal_row, row_element, row_s, row_n, &
                                    col_element, col_s, col_n, block, general)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
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
        !> Take the general path even in the full plane (tests; default false)
        logical, intent(in), optional :: general
        procedure(kernel_function), pointer :: kernel
        logical :: use_general

        call select_kernel(medium, general, use_general, kernel)
        if (use_general) then
            call fill_with(kernel, medium, image_transforms(medium%elements%symmetry), shear_row, &
                           normal_row, row_element, row_s, row_n, col_element, col_s, col_n, &
                           block)
        else
            call fill_full_plane(medium, image_transforms(medium%elements%symmetry), shear_row, &
                                 normal_row, row_element, row_s, row_n, col_element, col_s, &
                                 col_n, block)
        end if
    end subroutine fill_influence_block

    !> fill_influence_block with the kernel and the image transforms given.
    subroutine fill_with(kernel, medium, images, shear_row, normal_row, row_element, row_s, &
                         row_n, col_element, col_s, col_n, block)
        procedure(kernel_function) :: kernel
        type(elastic_medium), intent(in) :: medium
        type(image_transform), intent(in) :: images(:)
        integer, intent(in) :: shear_row(:), normal_row(:)
        integer, intent(in) :: row_element(:), row_s(:), row_n(:)
        integer, intent(in) :: col_element(:), col_s(:), col_n(:)
        real(wp), intent(inout) :: block(:, :)
        integer :: i, j, k, l

        ! Each thread owns whole columns (those of col_element(l)): disjoint writes.
        !$omp parallel do default(none) schedule(static) private(i, j, k, l) &
        !$omp shared(medium, shear_row, normal_row, row_element, row_s, row_n, col_element, &
        !$omp        col_s, col_n, block, images)
        do l = 1, size(col_element)
            j = col_element(l)
            do k = 1, size(row_element)
                i = row_element(k)
                call place_pair(pair_at_midpoint(kernel, medium, i, j, images), i == j, &
                                shear_row(i), normal_row(i), row_s(k), row_n(k), col_s(l), &
                                col_n(l), block)
            end do
        end do
        !$omp end parallel do
    end subroutine fill_with

    !> The entries of one pair (receiver row k, source column l) for the rows' kinds, where
    !> the placement says (0: not in the block); self: the receiver is the source.
    pure subroutine place_pair(p, self, shear_kind, normal_kind, row_s, row_n, col_s, col_n, &
                               block)
        type(pair_influence), intent(in) :: p
        logical, intent(in) :: self
        integer, intent(in) :: shear_kind, normal_kind, row_s, row_n, col_s, col_n
        real(wp), intent(inout) :: block(:, :)
        real(wp) :: v(2)

        if (row_s > 0) then
            select case (shear_kind)
            case (row_traction)
                v = p%ts
            case (row_displacement)
                v = p%us
            case default
                v = [merge(1.0_wp, 0.0_wp, self), 0.0_wp]
            end select
            if (col_s > 0) block(row_s, col_s) = v(1)
            if (col_n > 0) block(row_s, col_n) = v(2)
        end if
        if (row_n > 0) then
            select case (normal_kind)
            case (row_traction)
                v = p%tn
            case (row_displacement)
                v = p%un
            case default
                v = [0.0_wp, merge(1.0_wp, 0.0_wp, self)]
            end select
            if (col_s > 0) block(row_n, col_s) = v(1)
            if (col_n > 0) block(row_n, col_n) = v(2)
        end if
    end subroutine place_pair

    !> The full-plane path: the traction rows of each source column from traction_column
    !> (the receivers' geometry gathered once; each thread owns whole columns), the other
    !> rows from the general kernel.
    subroutine fill_full_plane(medium, images, shear_row, normal_row, row_element, row_s, &
                               row_n, col_element, col_s, col_n, block)
        type(elastic_medium), intent(in) :: medium
        type(image_transform), intent(in) :: images(:)
        integer, intent(in) :: shear_row(:), normal_row(:)
        integer, intent(in) :: row_element(:), row_s(:), row_n(:)
        integer, intent(in) :: col_element(:), col_s(:), col_n(:)
        real(wp), intent(inout) :: block(:, :)
        real(wp), allocatable :: xr(:), yr(:), cr(:), sr(:), ts_s(:), tn_s(:), ts_n(:), tn_n(:)
        integer, allocatable :: traction_s(:), traction_n(:), other(:)
        real(wp) :: xm, ym, cosb, sinb
        real(wp) :: shear_modulus, nu
        integer :: i, j, k, l, t, r

        shear_modulus = medium%shear_modulus
        nu = medium%poissons_ratio
        r = size(row_element)
        xr = medium%elements%x_mid(row_element)
        yr = medium%elements%y_mid(row_element)
        cr = medium%elements%cos_beta(row_element)
        sr = medium%elements%sin_beta(row_element)
        ! Receivers whose shear / normal row is a traction row in the block, and the others.
        traction_s = pack([(k, k = 1, r)], row_s > 0 .and. shear_row(row_element) == row_traction)
        traction_n = pack([(k, k = 1, r)], row_n > 0 .and. normal_row(row_element) == &
                          row_traction)
        other = pack([(k, k = 1, r)], shear_row(row_element) /= row_traction .or. &
                     normal_row(row_element) /= row_traction)
        !$omp parallel default(none) private(i, j, k, l, t, xm, ym, cosb, sinb, ts_s, tn_s, &
        !$omp     ts_n, tn_n) shared(medium, images, shear_modulus, nu, shear_row, normal_row, &
        !$omp     row_element, row_s, row_n, col_element, col_s, col_n, block, xr, yr, cr, sr, &
        !$omp     traction_s, traction_n, other, r)
        allocate (ts_s(r), tn_s(r), ts_n(r), tn_n(r))
        !$omp do schedule(static)
        do l = 1, size(col_element)
            j = col_element(l)
            ts_s = 0.0_wp
            tn_s = 0.0_wp
            ts_n = 0.0_wp
            tn_n = 0.0_wp
            call traction_column(medium%elements%x_mid(j), medium%elements%y_mid(j), &
                medium%elements%half_length(j), medium%elements%cos_beta(j), &
                medium%elements%sin_beta(j), 1.0_wp, xr, yr, cr, sr, shear_modulus, nu, ts_s, &
                tn_s, ts_n, tn_n)
            do t = 1, size(images)
                call image_of(medium%elements, j, images(t), xm, ym, cosb, sinb)
                call traction_column(xm, ym, medium%elements%half_length(j), cosb, sinb, &
                    images(t)%sign_s, xr, yr, cr, sr, shear_modulus, nu, ts_s, tn_s, ts_n, tn_n)
            end do
            if (col_s(l) > 0) block(row_s(traction_s), col_s(l)) = ts_s(traction_s)
            if (col_n(l) > 0) block(row_s(traction_s), col_n(l)) = ts_n(traction_s)
            if (col_s(l) > 0) block(row_n(traction_n), col_s(l)) = tn_s(traction_n)
            if (col_n(l) > 0) block(row_n(traction_n), col_n(l)) = tn_n(traction_n)
            do k = 1, size(other)
                i = row_element(other(k))
                call place_pair(pair_at_midpoint(full_plane_kernel, medium, i, j, images), &
                                i == j, shear_row(i), normal_row(i), row_s(other(k)), &
                                row_n(other(k)), col_s(l), col_n(l), block)
            end do
        end do
        !$omp end do
        !$omp end parallel
    end subroutine fill_full_plane

    !> Add the full-plane tractions that unit Ds (sign_s times it) and unit Dn of one
    !> source element cause at the receivers' midpoints, resolved on each receiver's plane:
    !> the stress part of Crouch & Starfield's kernel (F4..F7) in the source's frame and
    !> the traction on the plane at the relative angle. No receiver may be at a source end.
    pure subroutine traction_column(xm, ym, a, cosb, sinb, sign_s, x, y, cosr, sinr, &
                                    shear_modulus, nu, ts_s, tn_s, ts_n, tn_n)
        !> Source midpoint, half-length [length unit], direction cosines, factor on its Ds
        real(wp), intent(in) :: xm, ym, a, cosb, sinb, sign_s
        !> Receiver midpoints [length unit] and direction cosines, shape (n)
        real(wp), contiguous, intent(in) :: x(:), y(:), cosr(:), sinr(:)
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Shear and normal traction per unit Ds and per unit Dn, added to, shape (n)
        !> [stress unit / length unit]
        real(wp), contiguous, intent(inout) :: ts_s(:), tn_s(:), ts_n(:), tn_n(:)
        real(wp) :: con, g2, dx, dy, xl, yl, xa, xb, r1, r2, inv, i1, i2, f4, f5, f6, f7
        real(wp) :: ct, st, cc, ss, cs, sxx, syy, sxy
        integer :: i

        con = 1.0_wp / (4.0_wp * pi * (1.0_wp - nu))
        g2 = 2.0_wp * shear_modulus
        !$omp simd private(dx, dy, xl, yl, xa, xb, r1, r2, inv, i1, i2, f4, f5, f6, f7, ct, st, &
        !$omp              cc, ss, cs, sxx, syy, sxy)
        do i = 1, size(x)
            dx = x(i) - xm
            dy = y(i) - ym
            xl = dx * cosb + dy * sinb
            yl = -dx * sinb + dy * cosb
            xa = xl - a
            xb = xl + a
            r1 = xa**2 + yl**2
            r2 = xb**2 + yl**2
            inv = 1.0_wp / (r1 * r2)
            i1 = r2 * inv
            i2 = r1 * inv
            f4 = con * (yl * i1 - yl * i2)
            f5 = con * (xa * i1 - xb * i2)
            f6 = con * ((xa**2 - yl**2) * i1**2 - (xb**2 - yl**2) * i2**2)
            f7 = 2.0_wp * con * yl * (xa * i1**2 - xb * i2**2)
            ! The receiver's direction in the source's frame.
            ct = cosr(i) * cosb + sinr(i) * sinb
            st = sinr(i) * cosb - cosr(i) * sinb
            cc = ct**2
            ss = st**2
            cs = st * ct
            ! Unit Ds (C&S eq. 5.2.5)
            sxx = g2 * (2.0_wp * f4 + yl * f6)
            syy = g2 * (-yl * f6)
            sxy = g2 * (-f5 + yl * f7)
            ts_s(i) = ts_s(i) + sign_s * (-(sxx - syy) * cs + sxy * (cc - ss))
            tn_s(i) = tn_s(i) + sign_s * (sxx * ss - 2.0_wp * sxy * cs + syy * cc)
            ! Unit Dn
            sxx = g2 * (-f5 + yl * f7)
            syy = g2 * (-f5 - yl * f7)
            sxy = g2 * (-yl * f6)
            ts_n(i) = ts_n(i) + (-(sxx - syy) * cs + sxy * (cc - ss))
            tn_n(i) = tn_n(i) + (sxx * ss - 2.0_wp * sxy * cs + syy * cc)
        end do
    end subroutine traction_column

end module ddc_influence_assembly
