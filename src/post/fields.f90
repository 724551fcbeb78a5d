!> Displacement and stress at observation points: remote stress plus every element's part.
!>
!> In the full plane every point is one fused, vectorized sum over the elements and their
!> symmetry images (ddc_influence_superposition: geometry and DDs precomputed, one pass for
!> the point's flag, one for its values); in the half-plane (and for tests) the general
!> kernel is summed pair by pair. Both paths flag points the same way (point_flag) and give
!> the same values within round-off (suite `fields`). Inside a finite body its boundary's
!> sources add their field; outside it there is no rock.
module ddc_post_fields
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set
    use ddc_model_medium, only: elastic_medium, remote_stress_at
    use ddc_model_results, only: field_result, point_clear, point_on_element, point_outside_body
    use ddc_model_body, only: inside_body
    use ddc_influence_body, only: body_state, body_field_at
    use ddc_influence_kernel, only: dd_kernel, face_positive
    use ddc_influence_assembly, only: image_transform, image_transforms, image_of, &
        kernel_with_images, kernel_function, select_kernel
    use ddc_influence_superposition, only: source_table, build_sources, point_flag, flag_at, &
        superpose
    implicit none
    private

    public :: evaluate_field

contains

    !> The worst flag of a point over element j and its images.
    pure function element_flag(x, y, elements, j, images) result(flag)
        real(wp), intent(in) :: x, y
        type(element_set), intent(in) :: elements
        integer, intent(in) :: j
        type(image_transform), intent(in) :: images(:)
        integer :: flag
        real(wp) :: xm, ym, cosb, sinb
        integer :: t

        flag = point_flag(x, y, elements%x_mid(j), elements%y_mid(j), elements%half_length(j), &
                          elements%cos_beta(j), elements%sin_beta(j))
        do t = 1, size(images)
            call image_of(elements, j, images(t), xm, ym, cosb, sinb)
            flag = max(flag, point_flag(x, y, xm, ym, elements%half_length(j), cosb, sinb))
        end do
    end function element_flag

    !> Fields at the points (x, y): displacement relative to the far field and total stress.
    !> With symmetry (elements%symmetry) the images of every element contribute and count
    !> for the flags. In a half-plane (elements%domain) a point on the free surface y = 0 is
    !> an ordinary point unless it lies on an element end; in two bonded half-planes a point
    !> takes the stress of its material (a point on the interface the lower one's).
    subroutine evaluate_field(medium, remote, ds, dn, x, y, field, gradient, general)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Remote stress (sxx, syy, sxy) [stress unit] (at y = 0 when a gradient is given; the
        !> lower material's in two bonded half-planes)
        real(wp), intent(in) :: remote(3)
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Observation points [length unit], shape (npoints)
        real(wp), intent(in) :: x(:), y(:)
        !> Fields at the points; a point on an element gets NaN and flag point_on_element
        type(field_result), intent(out) :: field
        !> d(sxx, syy, sxy)/dy of the remote stress [stress unit / length unit]; 0 if absent
        real(wp), intent(in), optional :: gradient(3)
        !> Sum the general kernel pair by pair even in the full plane (tests; default false)
        logical, intent(in), optional :: general
        procedure(kernel_function), pointer :: kernel
        real(wp) :: g(3)
        logical :: use_general

        g = 0.0_wp
        if (present(gradient)) g = gradient
        call select_kernel(medium, general, use_general, kernel)
        if (use_general) then
            call field_with(kernel, medium, remote, g, ds, dn, x, y, field)
        else
            call field_full_plane(medium%elements, medium%shear_modulus, medium%poissons_ratio, &
                                  remote, g, ds, dn, x, y, field)
        end if
        if (allocated(medium%body)) call add_body_field(medium, ds, dn, x, y, field)
    end subroutine evaluate_field

    !> The field of a finite body's boundary added at the points inside it; the points
    !> outside it (or on its boundary, within 1e-9 of its size) NaN, flag point_outside_body.
    subroutine add_body_field(medium, ds, dn, x, y, field)
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: ds(:), dn(:), x(:), y(:)
        type(field_result), intent(inout) :: field
        real(wp), allocatable :: z(:)
        real(wp) :: values(5), nan, tolerance
        integer :: ip

        allocate (z(size(medium%body%loaded)))
        z = body_state(medium, ds, dn)
        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        associate (body => medium%body)
            tolerance = 1.0e-9_wp * max(maxval(body%x) - minval(body%x), &
                                        maxval(body%y) - minval(body%y))
        end associate
        !$omp parallel do default(none) schedule(dynamic, 16) private(ip, values) &
        !$omp shared(medium, z, x, y, field, nan, tolerance)
        do ip = 1, size(x)
            if (.not. inside_body(medium%body, x(ip), y(ip), tolerance)) then
                field%flag(ip) = point_outside_body
                call store_point(field, ip, spread(nan, 1, 5))
            else if (field%flag(ip) /= point_on_element) then
                values = body_field_at(medium, z, x(ip), y(ip), .true.)
                call store_point(field, ip, [field%ux(ip), field%uy(ip), field%sxx(ip), &
                                             field%syy(ip), field%sxy(ip)] + values)
            end if
        end do
        !$omp end parallel do
    end subroutine add_body_field

    !> The full-plane path: per point, the worst flag over every source, then (off the
    !> elements) the fused sum of displacement and stress.
    subroutine field_full_plane(elements, shear_modulus, nu, remote, gradient, ds, dn, x, y, &
                                field)
        type(element_set), intent(in) :: elements
        real(wp), intent(in) :: shear_modulus, nu, remote(3), gradient(3)
        real(wp), intent(in) :: ds(:), dn(:)
        real(wp), intent(in) :: x(:), y(:)
        type(field_result), intent(out) :: field
        type(source_table) :: src
        real(wp) :: u(2), stress(3), nan
        integer :: ip, np

        np = size(x)
        call build_sources(elements, image_transforms(elements%symmetry), ds, dn, src)
        allocate (field%ux(np), field%uy(np), field%sxx(np), field%syy(np), field%sxy(np), &
                  field%flag(np))
        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        !$omp parallel do default(none) schedule(dynamic, 16) private(ip, u, stress) &
        !$omp shared(src, shear_modulus, nu, remote, gradient, x, y, field, np, nan)
        do ip = 1, np
            field%flag(ip) = flag_at(src, x(ip), y(ip))
            if (field%flag(ip) == point_on_element) then
                u = nan
                stress = nan
            else
                call superpose(src, shear_modulus, nu, x(ip), y(ip), 0, u, stress)
                stress = stress + remote + gradient * y(ip)
            end if
            call store_point(field, ip, [u, stress])
        end do
        !$omp end parallel do
    end subroutine field_full_plane

    !> evaluate_field with the kernel and the gradient given.
    subroutine field_with(kernel, medium, remote, gradient, ds, dn, x, y, field)
        procedure(kernel_function) :: kernel
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: remote(3), gradient(3)
        real(wp), intent(in) :: ds(:), dn(:)
        real(wp), intent(in) :: x(:), y(:)
        type(field_result), intent(out) :: field
        type(dd_kernel) :: k
        type(image_transform), allocatable :: images(:)
        real(wp) :: acc(5), nan
        integer :: ip, j, np, flag

        np = size(x)
        images = image_transforms(medium%elements%symmetry)
        allocate (field%ux(np), field%uy(np), field%sxx(np), field%syy(np), field%sxy(np), &
                  field%flag(np))
        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        !$omp parallel do default(none) schedule(dynamic, 16) private(ip, j, k, acc, flag) &
        !$omp shared(medium, remote, gradient, ds, dn, x, y, field, np, nan, images)
        do ip = 1, np
            field%flag(ip) = point_clear
            do j = 1, medium%elements%n
                flag = element_flag(x(ip), y(ip), medium%elements, j, images)
                field%flag(ip) = max(field%flag(ip), flag)
                if (flag == point_on_element) exit
            end do
            if (field%flag(ip) == point_on_element) then
                call store_point(field, ip, spread(nan, 1, 5))
                cycle
            end if
            acc = [0.0_wp, 0.0_wp, remote_stress_at(medium, remote, gradient, y(ip))]
            do j = 1, medium%elements%n
                k = kernel_with_images(kernel, x(ip), y(ip), medium, j, images, face_positive)
                acc(1) = acc(1) + k%ux(1) * ds(j) + k%ux(2) * dn(j)
                acc(2) = acc(2) + k%uy(1) * ds(j) + k%uy(2) * dn(j)
                acc(3) = acc(3) + k%sxx(1) * ds(j) + k%sxx(2) * dn(j)
                acc(4) = acc(4) + k%syy(1) * ds(j) + k%syy(2) * dn(j)
                acc(5) = acc(5) + k%sxy(1) * ds(j) + k%sxy(2) * dn(j)
            end do
            call store_point(field, ip, acc)
        end do
        !$omp end parallel do
    end subroutine field_with

    !> Point ip of a field: ux, uy, sxx, syy, sxy.
    pure subroutine store_point(field, ip, values)
        type(field_result), intent(inout) :: field
        integer, intent(in) :: ip
        real(wp), intent(in) :: values(5)

        field%ux(ip) = values(1)
        field%uy(ip) = values(2)
        field%sxx(ip) = values(3)
        field%syy(ip) = values(4)
        field%sxy(ip) = values(5)
    end subroutine store_point

end module ddc_post_fields
