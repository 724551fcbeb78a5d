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

    !> One element seen from one point, relative to the interface.
    type :: element_view
        !> The point and its conjugate
        complex(wp) :: z = (0.0_wp, 0.0_wp), zb = (0.0_wp, 0.0_wp)
        !> The element's ends, and their heights above the interface times 2i
        !> (z_k - conj(z_k))
        complex(wp) :: ends(2) = (0.0_wp, 0.0_wp), b(2) = (0.0_wp, 0.0_wp)
        !> Its midpoint, half-length, direction cosines
        real(wp) :: xm = 0.0_wp, ys = 0.0_wp, a = 0.0_wp, cosb = 1.0_wp, sinb = 0.0_wp
    end type element_view

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
        type(element_view) :: v
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
        v = view_of(x, yr, xm, ys, a, cosb, sinb)
        if (receiver == source) then
            k = dd_kernel_global(x, y, xm, ym, a, cosb, sinb, shear_moduli(source), &
                                 poissons_ratios(source), face)
            call add_image_part(v, shear_moduli(source), kappa(source), image_a, image_b, &
                                face, k)
        else
            k = dd_kernel([0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], &
                          [0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp])
            call add_transmitted_part(v, shear_moduli(source), kappa(source), &
                                      shear_moduli(other), kappa(other), image_a, image_b, &
                                      face, k)
        end if
    end function dd_kernel_bimaterial

    !> The element (midpoint (xm, ys), ys above the interface) seen from the point
    !> (x, yr), yr above the interface.
    pure function view_of(x, yr, xm, ys, a, cosb, sinb) result(v)
        real(wp), intent(in) :: x, yr, xm, ys, a, cosb, sinb
        type(element_view) :: v
        complex(wp) :: zm, e

        v%z = cmplx(x, yr, wp)
        v%zb = conjg(v%z)
        zm = cmplx(xm, ys, wp)
        e = cmplx(cosb, sinb, wp)
        v%ends = [zm - a * e, zm + a * e]
        v%b = v%ends - conjg(v%ends)
        v%xm = xm
        v%ys = ys
        v%a = a
        v%cosb = cosb
        v%sinb = sinb
    end function view_of

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

    !> The DD in the global frame (u(-) - u(+), complex) of unit Ds (c = 1) or unit Dn
    !> (c = 2), and gamma of the element's full-plane potentials in a material of shear
    !> modulus g_source and kappa_source.
    pure complex(wp) function gamma_of(v, c, g_source, kappa_source) result(gamma)
        type(element_view), intent(in) :: v
        integer, intent(in) :: c
        real(wp), intent(in) :: g_source, kappa_source
        complex(wp), parameter :: i = (0.0_wp, 1.0_wp)

        gamma = -i * g_source * merge((1.0_wp, 0.0_wp), i, c == 1) * &
                cmplx(v%cosb, v%sinb, wp) / (pi * (kappa_source + 1.0_wp))
    end function gamma_of

    !> The image part in the element's own material (shear modulus g, kappa): the field of
    !> Phi = image_a Omega_0 and Omega = image_b Phi_0. It needs Omega_0 at z and Phi_0 at
    !> conj(z) only, singular at the mirror images of the element's ends, which lie in the
    !> other material.
    pure subroutine add_image_part(v, g, kappa, image_a, image_b, face, k)
        type(element_view), intent(in) :: v
        real(wp), intent(in) :: g, kappa, image_a, image_b
        integer, intent(in) :: face
        type(dd_kernel), intent(inout) :: k
        complex(wp) :: s(2), m, gamma, gammab
        complex(wp) :: big_phi, big_phi_prime, small_phi, big_omega_b, small_omega_b
        integer :: c

        ! 1 / (z - conj(z_k)), and log((z - conj(z_1)) / (z - conj(z_2))) in the frame of
        ! the element's mirror image (midpoint (xm, -ys), direction (cosb, -sinb))
        s = 1.0_wp / (v%z - conjg(v%ends))
        m = log_ratio((real(v%z, wp) - v%xm) * v%cosb - (aimag(v%z) + v%ys) * v%sinb, &
                      (real(v%z, wp) - v%xm) * v%sinb + (aimag(v%z) + v%ys) * v%cosb, v%a, face)
        do c = 1, 2
            gamma = gamma_of(v, c, g, kappa)
            gammab = conjg(gamma)
            ! Omega_0, Omega_0' and omega_0 at z
            big_phi = image_a * (gamma * (s(1) - s(2)) + gammab * (v%b(1) * s(1)**2 - &
                                                                   v%b(2) * s(2)**2))
            big_phi_prime = image_a * (-gamma * (s(1)**2 - s(2)**2) - 2.0_wp * gammab * &
                                       (v%b(1) * s(1)**3 - v%b(2) * s(2)**3))
            small_phi = image_a * (gamma * m - gammab * (v%b(1) * s(1) - v%b(2) * s(2)))
            ! Phi_0 and phi_0 at conj(z): 1 / (conj(z) - z_k) is conj(s_k)
            big_omega_b = image_b * gamma * (conjg(s(1)) - conjg(s(2)))
            small_omega_b = image_b * gamma * conjg(m)
            call add_field(v, big_phi, big_phi_prime, small_phi, big_omega_b, small_omega_b, &
                           g, kappa, c, k)
        end do
    end subroutine add_image_part

    !> The field in the other material (shear modulus g, kappa) of an element whose own
    !> material has g_source, kappa_source: Phi = (1 + image_b) Phi_0 and
    !> Omega = (1 + image_a) Omega_0. It needs Phi_0 at z and Omega_0 at conj(z) only,
    !> singular at the element's ends, which lie in its own material.
    pure subroutine add_transmitted_part(v, g_source, kappa_source, g, kappa, image_a, &
                                         image_b, face, k)
        type(element_view), intent(in) :: v
        real(wp), intent(in) :: g_source, kappa_source, g, kappa, image_a, image_b
        integer, intent(in) :: face
        type(dd_kernel), intent(inout) :: k
        complex(wp) :: r(2), l, gamma, gammab
        complex(wp) :: big_phi, big_phi_prime, small_phi, big_omega_b, small_omega_b
        integer :: c

        ! 1 / (z - z_k), and log((z - z_1) / (z - z_2)) in the element's own frame
        r = 1.0_wp / (v%z - v%ends)
        l = log_ratio((real(v%z, wp) - v%xm) * v%cosb + (aimag(v%z) - v%ys) * v%sinb, &
                      -(real(v%z, wp) - v%xm) * v%sinb + (aimag(v%z) - v%ys) * v%cosb, v%a, &
                      face)
        do c = 1, 2
            gamma = gamma_of(v, c, g_source, kappa_source)
            gammab = conjg(gamma)
            ! Phi_0, Phi_0' and phi_0 at z
            big_phi = (1.0_wp + image_b) * gamma * (r(1) - r(2))
            big_phi_prime = -(1.0_wp + image_b) * gamma * (r(1)**2 - r(2)**2)
            small_phi = (1.0_wp + image_b) * gamma * l
            ! Omega_0 and omega_0 at conj(z): 1 / (conj(z) - conj(z_k)) is conj(r_k)
            big_omega_b = (1.0_wp + image_a) * (gamma * (conjg(r(1)) - conjg(r(2))) + &
                          gammab * (v%b(1) * conjg(r(1))**2 - v%b(2) * conjg(r(2))**2))
            small_omega_b = (1.0_wp + image_a) * (gamma * conjg(l) - gammab * &
                            (v%b(1) * conjg(r(1)) - v%b(2) * conjg(r(2))))
            call add_field(v, big_phi, big_phi_prime, small_phi, big_omega_b, small_omega_b, &
                           g, kappa, c, k)
        end do
    end subroutine add_transmitted_part

    !> Add to column c of k the field of Phi, Phi' and phi at z and Omega, omega at conj(z)
    !> in a material of shear modulus g and kappa: syy - i sxy, sxx + syy = 4 Re Phi and
    !> 2 G (ux + i uy).
    pure subroutine add_field(v, big_phi, big_phi_prime, small_phi, big_omega_b, &
                              small_omega_b, g, kappa, c, k)
        type(element_view), intent(in) :: v
        complex(wp), intent(in) :: big_phi, big_phi_prime, small_phi, big_omega_b, &
            small_omega_b
        real(wp), intent(in) :: g, kappa
        integer, intent(in) :: c
        type(dd_kernel), intent(inout) :: k
        complex(wp) :: t, u

        t = big_phi + big_omega_b + (v%z - v%zb) * conjg(big_phi_prime)
        u = (kappa * small_phi - small_omega_b - (v%z - v%zb) * conjg(big_phi)) / (2.0_wp * g)
        k%ux(c) = k%ux(c) + real(u, wp)
        k%uy(c) = k%uy(c) + aimag(u)
        k%sxx(c) = k%sxx(c) + 4.0_wp * real(big_phi, wp) - real(t, wp)
        k%syy(c) = k%syy(c) + real(t, wp)
        k%sxy(c) = k%sxy(c) - aimag(t)
    end subroutine add_field

end module ddc_influence_kernel_bimaterial
