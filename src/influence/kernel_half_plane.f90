!> Crouch & Starfield half-plane kernel (free surface y = 0, body y < 0;
!> docs/theory/kernels.md#the-half-plane-kernel).
!>
!> The field of a constant-DD element in the half-plane is the full-plane field of the
!> element (ddc_influence_kernel) plus supplementary terms built from the functions F2..F9
!> evaluated in the frame of the image element (midpoint mirrored about y = 0, angle -beta).
!> Pure: no input, output or solver knowledge.
module ddc_influence_kernel_half_plane
    use ddc_kinds, only: wp
    use ddc_influence_kernel, only: dd_kernel, dd_kernel_global, kernel_functions, &
        face_positive
    use ddc_constants, only: pi
    implicit none
    private

    public :: dd_kernel_half_plane

contains

    !> F2..F9 at local point (x, y) of an element of half-length a: F2..F7 as the full-plane
    !> kernel, F8 = f,xyyy and F9 = f,yyyy.
    pure subroutine image_functions(x, y, a, nu, h)
        real(wp), intent(in) :: x, y, a, nu
        real(wp), intent(out) :: h(2:9)
        real(wp) :: con, xm, xp, r1s, r2s

        call kernel_functions(x, y, a, nu, face_positive, h(2:7))
        con = 1.0_wp / (4.0_wp * pi * (1.0_wp - nu))
        xm = x - a
        xp = x + a
        r1s = xm**2 + y**2
        r2s = xp**2 + y**2
        h(8) = 2.0_wp * con * y * ((y**2 - 3.0_wp * xm**2) / r1s**3 &
                                   - (y**2 - 3.0_wp * xp**2) / r2s**3)
        h(9) = 2.0_wp * con * (xm / r1s**2 - xp / r2s**2 &
                               + 4.0_wp * y**2 * (xp / r2s**3 - xm / r1s**3))
    end subroutine image_functions

    !> Global-frame displacement and stress at (x, y), y <= 0, for unit Ds and unit Dn on the
    !> element with midpoint (xm, ym), half-length a and direction (cosb, sinb), in the
    !> half-plane y < 0 with a traction-free surface y = 0.
    pure function dd_kernel_half_plane(x, y, xm, ym, a, cosb, sinb, shear_modulus, nu, face) &
        result(k)
        !> Observation point [length unit], y <= 0
        real(wp), intent(in) :: x, y
        !> Element midpoint [length unit], half-length [length unit], direction cosines
        real(wp), intent(in) :: xm, ym, a, cosb, sinb
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Face reported for a point on the element itself
        integer, intent(in) :: face
        type(dd_kernel) :: k
        real(wp) :: h(2:9), kappa, yb, xi, yi, g2
        real(wp) :: sb, cb, s2b, c2b, s3b, c3b, s4b, c4b
        real(wp) :: p2, q2, p3, q3, p4, q4

        k = dd_kernel_global(x, y, xm, ym, a, cosb, sinb, shear_modulus, nu, face)
        kappa = 3.0_wp - 4.0_wp * nu
        g2 = 2.0_wp * shear_modulus
        sb = sinb
        cb = cosb
        s2b = 2.0_wp * sb * cb
        c2b = cb**2 - sb**2
        s3b = s2b * cb + c2b * sb
        c3b = c2b * cb - s2b * sb
        s4b = 2.0_wp * s2b * c2b
        c4b = c2b**2 - s2b**2
        yb = -(x - xm) * sb + (y - ym) * cb
        xi = (x - xm) * cb - (y + ym) * sb
        yi = (x - xm) * sb + (y + ym) * cb
        call image_functions(xi, yi, a, nu, h)
        ! Recurring combinations of the image terms
        p2 = y * s2b - yb * sb
        q2 = y * c2b - yb * cb
        p3 = y * s3b - yb * s2b
        q3 = y * c3b - yb * c2b
        p4 = y * s4b - yb * s3b
        q4 = y * c4b - yb * c3b

        ! Unit Ds
        k%ux(1) = k%ux(1) + (1 - 2 * nu) * sb * h(2) - 2 * (1 - nu) * cb * h(3) &
                  + (kappa * p2 + 2 * y * s2b) * h(4) + (kappa * q2 - y * (1 - 2 * c2b)) * h(5) &
                  + 2 * y * p3 * h(6) - 2 * y * q3 * h(7)
        k%uy(1) = k%uy(1) - (1 - 2 * nu) * cb * h(2) - 2 * (1 - nu) * sb * h(3) &
                  - (kappa * q2 + y * (1 - 2 * c2b)) * h(4) + (kappa * p2 - 2 * y * s2b) * h(5) &
                  + 2 * y * q3 * h(6) + 2 * y * p3 * h(7)
        k%sxx(1) = k%sxx(1) + g2 * (h(4) - 3 * (c2b * h(4) - s2b * h(5)) &
                   + (2 * y * (cb - 3 * c3b) + 3 * yb * c2b) * h(6) &
                   + (2 * y * (sb - 3 * s3b) + 3 * yb * s2b) * h(7) &
                   - 2 * y * q4 * h(8) - 2 * y * p4 * h(9))
        k%syy(1) = k%syy(1) + g2 * (h(4) - (c2b * h(4) - s2b * h(5)) &
                   - (4 * y * sb * s2b - yb * c2b) * h(6) + (4 * y * sb * c2b + yb * s2b) * h(7) &
                   + 2 * y * q4 * h(8) + 2 * y * p4 * h(9))
        k%sxy(1) = k%sxy(1) + g2 * (s2b * h(4) + c2b * h(5) &
                   + (2 * y * sb * (1 + 4 * c2b) - yb * s2b) * h(6) &
                   + (2 * y * cb * (3 - 4 * c2b) + yb * c2b) * h(7) &
                   + 2 * y * p4 * h(8) - 2 * y * q4 * h(9))
        ! Unit Dn
        k%ux(2) = k%ux(2) + (1 - 2 * nu) * cb * h(2) + 2 * (1 - nu) * sb * h(3) &
                  - (kappa * q2 - y) * h(4) + kappa * p2 * h(5) &
                  - 2 * y * q3 * h(6) - 2 * y * p3 * h(7)
        k%uy(2) = k%uy(2) + (1 - 2 * nu) * sb * h(2) - 2 * (1 - nu) * cb * h(3) &
                  - kappa * p2 * h(4) - (kappa * q2 + y) * h(5) &
                  + 2 * y * p3 * h(6) - 2 * y * q3 * h(7)
        k%sxx(2) = k%sxx(2) + g2 * (h(5) + (2 * y * (sb - 2 * s3b) + 3 * yb * s2b) * h(6) &
                   - (2 * y * (cb - 2 * c3b) + 3 * yb * c2b) * h(7) &
                   - 2 * y * p4 * h(8) + 2 * y * q4 * h(9))
        k%syy(2) = k%syy(2) + g2 * (h(5) - (2 * y * sb - yb * s2b) * h(6) &
                   + (2 * y * cb - yb * c2b) * h(7) + 2 * y * p4 * h(8) - 2 * y * q4 * h(9))
        k%sxy(2) = k%sxy(2) + g2 * ((4 * y * sb * s2b + yb * c2b) * h(6) &
                   - (4 * y * sb * c2b - yb * s2b) * h(7) - 2 * y * q4 * h(8) - 2 * y * p4 * h(9))
    end function dd_kernel_half_plane

end module ddc_influence_kernel_half_plane
