!> The kernel of a constant-DD element in one of two bonded elastic half-planes: the lower
!> material below y = interface_y, the upper above (docs/theory/bimaterial.md).
!>
!> In the material of the element its field is the full-plane field of the element in that
!> material (ddc_influence_kernel) plus an image part; in the other material it is the
!> full-plane field's complex potentials scaled. Both follow from the element's full-plane
!> potentials Phi_0, Omega_0 in Muskhelishvili's form and two constants of the materials
!> (image_a, image_b below), and are summed here in complex arithmetic. An element lying
!> on the interface is the common limit of an element just above and just below it: it is
!> taken in the material of the point. A point on the interface belongs to the lower
!> material, except a point on an element lying there, which belongs to the side of the
!> face asked for. Pure: no input, output or solver knowledge.
module ddc_influence_kernel_bimaterial
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_influence_kernel, only: dd_kernel, dd_kernel_global
    implicit none
    private

    public :: dd_kernel_bimaterial, material_lower, material_upper

    !> Index of each material in the arrays of moduli and ratios
    integer, parameter :: material_lower = 1, material_upper = 2

    !> The rational and logarithmic functions of one element at one point z (relative to
    !> the interface), from which its potentials follow (docs/theory/bimaterial.md).
    type :: segment_functions
        !> The point and its conjugate
        complex(wp) :: z = (0.0_wp, 0.0_wp), zb = (0.0_wp, 0.0_wp)
        !> 1 / (z - z_k) and 1 / (z - conj(z_k)) for the ends k = 1, 2
        complex(wp) :: r(2) = (0.0_wp, 0.0_wp), s(2) = (0.0_wp, 0.0_wp)
        !> z_k - conj(z_k): twice i times the ends' heights above the interface
        complex(wp) :: b(2) = (0.0_wp, 0.0_wp)
        !> log((z - z_1) / (z - z_2)) and log((z - conj(z_1)) / (z - conj(z_2)))
        complex(wp) :: l = (0.0_wp, 0.0_wp), m = (0.0_wp, 0.0_wp)
    end type segment_functions

contains

    !> Global-frame displacement and stress at (x, y) for unit Ds and unit Dn on the element
    !> with midpoint (xm, ym), half-length a and direction (cosb, sinb), in two bonded
    !> half-planes: the element does not cross the interface y = interface_y.
    pure function dd_kernel_bimaterial(x, y, xm, ym, a, cosb, sinb, shear_moduli, &
                                       poissons_ratios, interface_y, face) result(k)
        !> Observation point [length unit]
        real(wp), intent(in) :: x, y
        !> Element midpoint [length unit], half-length [length unit], direction cosines
        real(wp), intent(in) :: xm, ym, a, cosb, sinb
        !> Shear modulus [stress unit] and Poisson's ratio [-] of the lower and the upper
        !> material (material_lower, material_upper)
        real(wp), intent(in) :: shear_moduli(2), poissons_ratios(2)
        !> Height of the interface [length unit]
        real(wp), intent(in) :: interface_y
        !> Face reported for a point on the element itself
        integer, intent(in) :: face
        type(dd_kernel) :: k
        type(segment_functions) :: f
        real(wp) :: yr, ys, kappa(2), image_a, image_b
        integer :: receiver, source, other
        logical :: lies_on

        yr = y - interface_y
        ys = ym - interface_y
        lies_on = ys == 0.0_wp .and. sinb == 0.0_wp
        if (yr > 0.0_wp) then
            receiver = material_upper
        else if (yr < 0.0_wp .or. .not. lies_on .or. abs((x - xm) * cosb) >= a) then
            receiver = material_lower
        else
            ! On the element itself, which lies on the interface: the face's side.
            receiver = merge(material_upper, material_lower, real(face, wp) * cosb > 0.0_wp)
        end if
        if (lies_on) then
            source = receiver
        else
            source = merge(material_upper, material_lower, ys > 0.0_wp)
        end if
        other = 3 - source
        kappa = 3.0_wp - 4.0_wp * poissons_ratios
        associate (gs => shear_moduli(source), go => shear_moduli(other), ks => kappa(source), &
                   ko => kappa(other))
            image_a = (go - gs) / (gs + ks * go)
            image_b = (ks * go - ko * gs) / (go + ko * gs)
        end associate
        f = functions_at(x, yr, xm, ys, a, cosb, sinb, face)
        if (receiver == source) then
            k = dd_kernel_global(x, y, xm, ym, a, cosb, sinb, shear_moduli(source), &
                                 poissons_ratios(source), face)
            call add_potentials(f, cosb, sinb, shear_moduli(source), kappa(source), &
                                [0.0_wp, image_a], [image_b, 0.0_wp], shear_moduli(source), &
                                kappa(source), k)
        else
            k = dd_kernel([0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], &
                          [0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp])
            call add_potentials(f, cosb, sinb, shear_moduli(source), kappa(source), &
                                [1.0_wp + image_b, 0.0_wp], [0.0_wp, 1.0_wp + image_a], &
                                shear_moduli(other), kappa(other), k)
        end if
    end function dd_kernel_bimaterial

    !> The functions of the element (midpoint (xm, ys), ys above the interface) at the point
    !> (x, yr), yr above the interface.
    pure function functions_at(x, yr, xm, ys, a, cosb, sinb, face) result(f)
        real(wp), intent(in) :: x, yr, xm, ys, a, cosb, sinb
        integer, intent(in) :: face
        type(segment_functions) :: f
        complex(wp) :: zm, e, ends(2)

        f%z = cmplx(x, yr, wp)
        f%zb = conjg(f%z)
        zm = cmplx(xm, ys, wp)
        e = cmplx(cosb, sinb, wp)
        ends = [zm - a * e, zm + a * e]
        f%r = 1.0_wp / (f%z - ends)
        f%s = 1.0_wp / (f%z - conjg(ends))
        f%b = ends - conjg(ends)
        ! The element in its own frame, and its mirror image (midpoint (xm, -ys), direction
        ! (cosb, -sinb)) in its frame: each logarithm is cut along its segment only.
        f%l = log_ratio((x - xm) * cosb + (yr - ys) * sinb, -(x - xm) * sinb + (yr - ys) * cosb, &
                        a, face)
        f%m = log_ratio((x - xm) * cosb - (yr + ys) * sinb, (x - xm) * sinb + (yr + ys) * cosb, &
                        a, face)
    end function functions_at

    !> log((w + a) / (w - a)) at w = xl + i yl, a segment of half-length a in its own frame:
    !> the principal branch, cut along the segment, where the one-sided limit of the face
    !> (face_positive: yl -> 0+) is taken, as the full-plane kernel's F3 does.
    pure complex(wp) function log_ratio(xl, yl, a, face)
        real(wp), intent(in) :: xl, yl, a
        integer, intent(in) :: face
        real(wp) :: angle

        if (yl == 0.0_wp .and. abs(xl) < a) then
            angle = -real(face, wp) * pi
        else
            angle = atan2(yl, xl + a) - atan2(yl, xl - a)
        end if
        log_ratio = cmplx(0.5_wp * (log((xl + a)**2 + yl**2) - log((xl - a)**2 + yl**2)), &
                          angle, wp)
    end function log_ratio

    !> Add to k the field of the potentials Phi = p(1) Phi_0 + p(2) Omega_0 and
    !> Omega = q(1) Phi_0 + q(2) Omega_0, where Phi_0, Omega_0 are the element's full-plane
    !> potentials in its own material (shear modulus g_source, kappa_source), in a material
    !> of shear modulus g and kappa = 3 - 4 nu, per unit Ds and unit Dn.
    pure subroutine add_potentials(f, cosb, sinb, g_source, kappa_source, p, q, g, kappa, k)
        type(segment_functions), intent(in) :: f
        real(wp), intent(in) :: cosb, sinb, g_source, kappa_source, p(2), q(2), g, kappa
        type(dd_kernel), intent(inout) :: k
        complex(wp), parameter :: i = (0.0_wp, 1.0_wp)
        complex(wp) :: gamma, gammab, d, phi0(3), omega0(3), phi0b(2), omega0b(2)
        complex(wp) :: big_phi, big_phi_prime, small_phi, big_omega_b, small_omega_b, t, u
        real(wp) :: syy
        integer :: c

        do c = 1, 2
            ! The DD in the global frame (u(-) - u(+), complex), unit Ds then unit Dn
            d = merge((1.0_wp, 0.0_wp), i, c == 1) * cmplx(cosb, sinb, wp)
            gamma = -i * g_source * d / (pi * (kappa_source + 1.0_wp))
            gammab = conjg(gamma)
            ! Phi_0, Phi_0', phi_0 and Omega_0, Omega_0', omega_0 at z
            phi0 = [gamma * (f%r(1) - f%r(2)), -gamma * (f%r(1)**2 - f%r(2)**2), gamma * f%l]
            omega0 = [gamma * (f%s(1) - f%s(2)) + gammab * (f%b(1) * f%s(1)**2 - &
                                                            f%b(2) * f%s(2)**2), &
                      -gamma * (f%s(1)**2 - f%s(2)**2) - 2.0_wp * gammab * &
                      (f%b(1) * f%s(1)**3 - f%b(2) * f%s(2)**3), &
                      gamma * f%m - gammab * (f%b(1) * f%s(1) - f%b(2) * f%s(2))]
            ! Phi_0, phi_0 and Omega_0, omega_0 at conj(z): 1 / (conj(z) - z_k) is
            ! conj(s_k), 1 / (conj(z) - conj(z_k)) is conj(r_k)
            phi0b = [gamma * (conjg(f%s(1)) - conjg(f%s(2))), gamma * conjg(f%m)]
            omega0b = [gamma * (conjg(f%r(1)) - conjg(f%r(2))) + gammab * &
                       (f%b(1) * conjg(f%r(1))**2 - f%b(2) * conjg(f%r(2))**2), &
                       gamma * conjg(f%l) - gammab * (f%b(1) * conjg(f%r(1)) - &
                                                      f%b(2) * conjg(f%r(2)))]
            big_phi = p(1) * phi0(1) + p(2) * omega0(1)
            big_phi_prime = p(1) * phi0(2) + p(2) * omega0(2)
            small_phi = p(1) * phi0(3) + p(2) * omega0(3)
            big_omega_b = q(1) * phi0b(1) + q(2) * omega0b(1)
            small_omega_b = q(1) * phi0b(2) + q(2) * omega0b(2)
            ! syy - i sxy, sxx + syy = 4 Re Phi, 2 G (ux + i uy)
            t = big_phi + big_omega_b + (f%z - f%zb) * conjg(big_phi_prime)
            syy = real(t, wp)
            u = (kappa * small_phi - small_omega_b - (f%z - f%zb) * conjg(big_phi)) / (2.0_wp * g)
            k%ux(c) = k%ux(c) + real(u, wp)
            k%uy(c) = k%uy(c) + aimag(u)
            k%sxx(c) = k%sxx(c) + 4.0_wp * real(big_phi, wp) - syy
            k%syy(c) = k%syy(c) + syy
            k%sxy(c) = k%sxy(c) - aimag(t)
        end do
    end subroutine add_potentials

end module ddc_influence_kernel_bimaterial
