!> Crouch & Starfield constant displacement discontinuity kernel (full plane).
!>
!> Displacement and stress at a point due to unit Ds and unit Dn on one straight element,
!> in the element's local frame (s along the element, n = s rotated +90 degrees, origin at
!> the midpoint). Crouch & Starfield (1983) eqs. 5.2.x with F2..F7 as in
!> docs/theory/kernels.md#the-kernel-of-one-element.
!> Pure: no input, output or solver knowledge.
module ddc_influence_kernel
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    implicit none
    private

    public :: dd_kernel_at, dd_kernel_global, dd_stress_global, kernel_functions
    public :: face_negative, face_positive, global_stress

    !> On the element itself (y = 0, |x| < a) the displacement jumps: which face to report
    integer, parameter :: face_negative = -1, face_positive = +1

    !> Local displacement and stress for unit Ds (index 1) and unit Dn (index 2).
    type, public :: dd_kernel
        !> Displacement per unit DD [-]
        real(wp) :: ux(2), uy(2)
        !> Stress per unit DD [stress unit / length unit]
        real(wp) :: sxx(2), syy(2), sxy(2)
    end type dd_kernel

contains

    !> The functions F2..F7 (docs/theory/kernels.md#the-kernel-of-one-element) at local point (x, y)
    !> of an element of half-length a. On the element (y = 0, |x| < a) F3 takes the value of the
    !> given face.
    pure subroutine kernel_functions(x, y, a, nu, face, f)
        !> Local coordinates of the point [length unit]
        real(wp), intent(in) :: x, y
        !> Element half-length [length unit]
        real(wp), intent(in) :: a
        !> Poisson's ratio
        real(wp), intent(in) :: nu
        !> face_negative or face_positive, used only on the element itself
        integer, intent(in) :: face
        !> F2 .. F7, shape (2:7)
        real(wp), intent(out) :: f(2:7)
        real(wp) :: con, xm, xp, r1s, r2s

        con = 1.0_wp / (4.0_wp * pi * (1.0_wp - nu))
        xm = x - a
        xp = x + a
        r1s = xm**2 + y**2
        r2s = xp**2 + y**2
        f(2) = con * 0.5_wp * (log(r1s) - log(r2s))
        if (y == 0.0_wp .and. abs(x) < a) then
            ! The jump of atan2 lies on the element: take the face's one-sided limit.
            f(3) = -real(face, wp) * con * pi
        else
            f(3) = -con * (atan2(y, xm) - atan2(y, xp))
        end if
        call stress_functions(x, y, a, nu, f(4:7))
    end subroutine kernel_functions

    !> F4..F7 alone (the stresses need no more): rational in the coordinates.
    pure subroutine stress_functions(x, y, a, nu, f)
        !> Local coordinates of the point [length unit]
        real(wp), intent(in) :: x, y
        !> Element half-length [length unit] and Poisson's ratio
        real(wp), intent(in) :: a, nu
        !> F4 .. F7, shape (4:7)
        real(wp), intent(out) :: f(4:7)
        real(wp) :: con, xm, xp, r1s, r2s

        con = 1.0_wp / (4.0_wp * pi * (1.0_wp - nu))
        xm = x - a
        xp = x + a
        r1s = xm**2 + y**2
        r2s = xp**2 + y**2
        f(4) = con * (y / r1s - y / r2s)
        f(5) = con * (xm / r1s - xp / r2s)
        f(6) = con * ((xm**2 - y**2) / r1s**2 - (xp**2 - y**2) / r2s**2)
        f(7) = 2.0_wp * con * y * (xm / r1s**2 - xp / r2s**2)
    end subroutine stress_functions

    !> Local displacement and stress at (x, y) for unit Ds and unit Dn (C&S eq. 5.2.5).
    !> The point must not be an element end (singular there).
    pure function dd_kernel_at(x, y, a, shear_modulus, nu, face) result(k)
        real(wp), intent(in) :: x, y, a, shear_modulus, nu
        integer, intent(in) :: face
        type(dd_kernel) :: k
        real(wp) :: f(2:7)

        call kernel_functions(x, y, a, nu, face, f)
        ! Unit Ds
        k%ux(1) = 2.0_wp * (1.0_wp - nu) * f(3) - y * f(5)
        k%uy(1) = (1.0_wp - 2.0_wp * nu) * f(2) - y * f(4)
        ! Unit Dn
        k%ux(2) = -(1.0_wp - 2.0_wp * nu) * f(2) - y * f(4)
        k%uy(2) = 2.0_wp * (1.0_wp - nu) * f(3) + y * f(5)
        call local_stress(f(4:7), y, shear_modulus, k)
    end function dd_kernel_at

    !> The stresses of C&S eq. 5.2.5 from F4..F7 at local y, into k.
    pure subroutine local_stress(f, y, shear_modulus, k)
        !> F4..F7
        real(wp), intent(in) :: f(4:7)
        !> Local y [length unit], shear modulus [stress unit]
        real(wp), intent(in) :: y, shear_modulus
        type(dd_kernel), intent(inout) :: k
        real(wp) :: g2

        g2 = 2.0_wp * shear_modulus
        ! Unit Ds
        k%sxx(1) = g2 * (2.0_wp * f(4) + y * f(6))
        k%syy(1) = g2 * (-y * f(6))
        k%sxy(1) = g2 * (-f(5) + y * f(7))
        ! Unit Dn
        k%sxx(2) = g2 * (-f(5) + y * f(7))
        k%syy(2) = g2 * (-f(5) - y * f(7))
        k%sxy(2) = g2 * (-y * f(6))
    end subroutine local_stress

    !> Global-frame displacement and stress at global point (x, y) for unit Ds and unit Dn on
    !> the element with midpoint (xm, ym), half-length a and direction (cosb, sinb).
    pure function dd_kernel_global(x, y, xm, ym, a, cosb, sinb, shear_modulus, nu, face) &
        result(k)
        !> Observation point [length unit]
        real(wp), intent(in) :: x, y
        !> Element midpoint [length unit], half-length [length unit], direction cosines
        real(wp), intent(in) :: xm, ym, a, cosb, sinb
        !> Shear modulus [stress unit] and Poisson's ratio
        real(wp), intent(in) :: shear_modulus, nu
        !> Face reported for a point on the element itself
        integer, intent(in) :: face
        type(dd_kernel) :: k
        type(dd_kernel) :: kl
        real(wp) :: xl, yl

        xl = (x - xm) * cosb + (y - ym) * sinb
        yl = -(x - xm) * sinb + (y - ym) * cosb
        kl = dd_kernel_at(xl, yl, a, shear_modulus, nu, face)
        k%ux = kl%ux * cosb - kl%uy * sinb
        k%uy = kl%ux * sinb + kl%uy * cosb
        call global_stress(kl, cosb, sinb, k)
    end function dd_kernel_global

    !> The stress part of dd_kernel_global (its displacements 0): F4..F7 alone, without the
    !> logarithms and angles of F2 and F3, for callers that need tractions only.
    pure function dd_stress_global(x, y, xm, ym, a, cosb, sinb, shear_modulus, nu, face) &
        result(k)
        !> Observation point [length unit]
        real(wp), intent(in) :: x, y
        !> Element midpoint [length unit], half-length [length unit], direction cosines
        real(wp), intent(in) :: xm, ym, a, cosb, sinb
        !> Shear modulus [stress unit] and Poisson's ratio
        real(wp), intent(in) :: shear_modulus, nu
        !> Face of a point on the element itself: it picks a displacement, and there is none
        !> here (the stress is the same on both faces)
        integer, intent(in) :: face
        type(dd_kernel) :: k
        type(dd_kernel) :: kl
        real(wp) :: xl, yl, f(4:7)

        xl = (x - xm) * cosb + (y - ym) * sinb
        yl = -(x - xm) * sinb + (y - ym) * cosb
        call stress_functions(xl, yl, a, nu, f)
        call local_stress(f, yl, shear_modulus, kl)
        ! No displacement, on either face.
        k%ux = real(0 * face, wp)
        k%uy = 0.0_wp
        call global_stress(kl, cosb, sinb, k)
    end function dd_stress_global

    !> The local stresses of kl in the global frame of an element with direction (cosb, sinb).
    pure subroutine global_stress(kl, cosb, sinb, k)
        type(dd_kernel), intent(in) :: kl
        real(wp), intent(in) :: cosb, sinb
        type(dd_kernel), intent(inout) :: k
        real(wp) :: c2, s2, cs

        c2 = cosb**2
        s2 = sinb**2
        cs = cosb * sinb
        k%sxx = kl%sxx * c2 - 2.0_wp * kl%sxy * cs + kl%syy * s2
        k%syy = kl%sxx * s2 + 2.0_wp * kl%sxy * cs + kl%syy * c2
        k%sxy = (kl%sxx - kl%syy) * cs + kl%sxy * (c2 - s2)
    end subroutine global_stress

end module ddc_influence_kernel
