!> Displacement and stress at observation points: remote stress plus every element's part.
module ddc_post_fields
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set
    use ddc_model_results, only: field_result, point_clear, point_near, point_on_element
    use ddc_influence_kernel, only: dd_kernel, dd_kernel_global, face_positive
    implicit none
    private

    public :: evaluate_field

    !> A point closer to an element's line than this fraction of its half-length, within
    !> its extent, is on the element (the field is discontinuous or singular there).
    real(wp), parameter :: on_element_tolerance = 1.0e-10_wp

contains

    !> Where a point lies relative to one element: clear, near (within one element length
    !> of its centre, where TWODD skips points) or on it (including its ends).
    pure function point_flag(x, y, elements, j) result(flag)
        real(wp), intent(in) :: x, y
        type(element_set), intent(in) :: elements
        integer, intent(in) :: j
        integer :: flag
        real(wp) :: xl, yl, a

        a = elements%half_length(j)
        xl = (x - elements%x_mid(j)) * elements%cos_beta(j) + (y - elements%y_mid(j)) * elements%sin_beta(j)
        yl = -(x - elements%x_mid(j)) * elements%sin_beta(j) + (y - elements%y_mid(j)) * elements%cos_beta(j)
        if (abs(yl) <= on_element_tolerance * a .and. abs(xl) <= a * (1.0_wp + on_element_tolerance)) then
            flag = point_on_element
        else if (xl**2 + yl**2 < (2.0_wp * a)**2) then
            flag = point_near
        else
            flag = point_clear
        end if
    end function point_flag

    !> Fields at the points (x, y): displacement relative to the far field and total stress.
    subroutine evaluate_field(elements, shear_modulus, nu, remote, ds, dn, x, y, field)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Remote stress (sxx, syy, sxy) [stress unit]
        real(wp), intent(in) :: remote(3)
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Observation points [length unit], shape (npoints)
        real(wp), intent(in) :: x(:), y(:)
        !> Fields at the points; a point on an element gets NaN and flag point_on_element
        type(field_result), intent(out) :: field
        type(dd_kernel) :: k
        real(wp) :: acc(5), nan
        integer :: ip, j, np, flag

        np = size(x)
        allocate (field%ux(np), field%uy(np), field%sxx(np), field%syy(np), field%sxy(np), &
                  field%flag(np))
        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        !$omp parallel do default(none) schedule(dynamic, 16) private(ip, j, k, acc, flag) &
        !$omp shared(elements, shear_modulus, nu, remote, ds, dn, x, y, field, np, nan)
        do ip = 1, np
            field%flag(ip) = point_clear
            do j = 1, elements%n
                flag = point_flag(x(ip), y(ip), elements, j)
                field%flag(ip) = max(field%flag(ip), flag)
                if (flag == point_on_element) exit
            end do
            if (field%flag(ip) == point_on_element) then
                field%ux(ip) = nan
                field%uy(ip) = nan
                field%sxx(ip) = nan
                field%syy(ip) = nan
                field%sxy(ip) = nan
                cycle
            end if
            acc = [0.0_wp, 0.0_wp, remote]
            do j = 1, elements%n
                k = dd_kernel_global(x(ip), y(ip), elements%x_mid(j), elements%y_mid(j), &
                                     elements%half_length(j), elements%cos_beta(j), &
                                     elements%sin_beta(j), shear_modulus, nu, face_positive)
                acc(1) = acc(1) + k%ux(1) * ds(j) + k%ux(2) * dn(j)
                acc(2) = acc(2) + k%uy(1) * ds(j) + k%uy(2) * dn(j)
                acc(3) = acc(3) + k%sxx(1) * ds(j) + k%sxx(2) * dn(j)
                acc(4) = acc(4) + k%syy(1) * ds(j) + k%syy(2) * dn(j)
                acc(5) = acc(5) + k%sxy(1) * ds(j) + k%sxy(2) * dn(j)
            end do
            field%ux(ip) = acc(1)
            field%uy(ip) = acc(2)
            field%sxx(ip) = acc(3)
            field%syy(ip) = acc(4)
            field%sxy(ip) = acc(5)
        end do
        !$omp end parallel do
    end subroutine evaluate_field

end module ddc_post_fields
