!> Fields of a straight element whose source varies along it as a quadratic: a displacement
!> discontinuity (DD) or a line load (a force per unit length), the two sources of a finite
!> body's boundary (docs/theory/finite-bodies.md).
!>
!> A source of density q(xi) on the element (local x from -a to a, y = 0) derives, as the
!> constant element of Crouch & Starfield (1983, eqs. 4.4.x and 5.2.5) does, from one
!> potential f = -1 / (4 pi (1 - nu)) int q(xi) ln r dxi: the displacements and stresses are
!> the same combinations of f, its derivatives and y for every density. The densities here
!> are the monomials (xi / a)^m, m = 0, 1, 2, whose potentials have closed forms (the
!> derivatives of m = 1, 2 by parts from those of m = 0); an element's three nodes (-2/3, 0
!> and 2/3 of a from the midpoint) combine them into the quadratic through nodal values.
!> The DD is u(-) - u(+) as for the constant elements (ddc_influence_kernel); a line load
!> is the force per unit length the element applies to the body, so the traction jumps by
!> it: sigma(-) n - sigma(+) n = p with n the local y axis.
!> Pure: no input, output or solver knowledge.
module ddc_influence_kernel_polynomial
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_influence_kernel, only: dd_kernel, global_stress
    implicit none
    private

    public :: potential, monomial_potentials, dd_fields, line_load_fields, node_fields
    public :: local_node_fields
    public :: body_node_xi, node_weights

    !> Positions of an element's three nodes, in half-lengths from its midpoint
    real(wp), parameter :: body_node_xi(3) = [-2.0_wp / 3.0_wp, 0.0_wp, 2.0_wp / 3.0_wp]
    !> Integral of each node's basis function over the element, in half-lengths
    real(wp), parameter :: node_weights(3) = [0.75_wp, 0.5_wp, 0.75_wp]
    !> The nodal basis in monomials: basis(k) = sum_m basis_monomials(m, k) (xi / a)^m
    real(wp), parameter :: basis_monomials(0:2, 3) = reshape([0.0_wp, -0.75_wp, 1.125_wp, &
        1.0_wp, 0.0_wp, -2.25_wp, 0.0_wp, 0.75_wp, 1.125_wp], [3, 3])

    !> The potential of one density and the derivatives the fields need.
    type :: potential
        real(wp) :: f = 0.0_wp, fx = 0.0_wp, fy = 0.0_wp, fxx = 0.0_wp, fxy = 0.0_wp
        real(wp) :: fyy = 0.0_wp, fxyy = 0.0_wp, fyyy = 0.0_wp
    end type potential

    !> Fields at one point of the three nodal sources of an element, DD and line load.
    type, public :: nodal_sources
        !> Global-frame displacement and stress per unit local component (1: s, 2: n) of the
        !> node's DD and of its line load
        type(dd_kernel) :: dd(3), load(3)
    end type nodal_sources

contains

    !> The potentials of the densities (xi / a)^m, m = 0, 1, 2, at local (x, y) of an element
    !> of half-length a; on the element itself (y = 0, |x| < a) those of the given face (+1:
    !> y > 0, -1: y < 0). Not at an element end.
    pure function monomial_potentials(x, y, a, nu, face) result(p)
        !> Local point [length unit], half-length [length unit], Poisson's ratio
        real(wp), intent(in) :: x, y, a, nu
        !> Face of a point on the element
        integer, intent(in) :: face
        type(potential) :: p(0:2)
        real(wp) :: x1, x2, r1, r2, angle, l1, l2, j, f1(8), c0

        x1 = x - a
        x2 = x + a
        r1 = x1**2 + y**2
        r2 = x2**2 + y**2
        if (y == 0.0_wp .and. abs(x) < a) then
            angle = real(face, wp) * pi
        else
            angle = atan2(y, x1) - atan2(y, x2)
        end if
        l1 = 0.5_wp * log(r1)
        l2 = 0.5_wp * log(r2)
        ! m = 0: int ln r dxi over the element
        p(0)%f = y * angle - x1 * l1 + x2 * l2 - 2.0_wp * a
        p(0)%fx = l2 - l1
        p(0)%fy = angle
        p(0)%fxx = x2 / r2 - x1 / r1
        p(0)%fxy = y / r2 - y / r1
        p(0)%fxyy = -((y**2 - x2**2) / r2**2 - (y**2 - x1**2) / r1**2)
        p(0)%fyyy = -(2.0_wp * x1 * y / r1**2 - 2.0_wp * x2 * y / r2**2)
        ! m = 1: int xi ln r dxi, each x-derivative by parts
        j = (0.5_wp * r2 * l2 - 0.25_wp * x2**2) - (0.5_wp * r1 * l1 - 0.25_wp * x1**2)
        f1(1) = x * p(0)%f - j
        f1(2) = p(0)%f - a * (l1 + l2)
        f1(3) = x * p(0)%fy + y * (l1 - l2)
        f1(4) = p(0)%fx - a * (x1 / r1 + x2 / r2)
        f1(5) = p(0)%fy - a * (y / r1 + y / r2)
        f1(6) = p(0)%fxx - a * ((y**2 - x1**2) / r1**2 + (y**2 - x2**2) / r2**2)
        f1(7) = p(0)%fxy + 2.0_wp * a * y * (x1 / r1**2 + x2 / r2**2)
        p(1) = potential(f1(1), f1(2), f1(3), f1(4), f1(5), -f1(4), -f1(6), -f1(7))
        ! m = 2: int xi^2 ln r dxi
        p(2)%f = x**2 * p(0)%f - 2.0_wp * x * j + cubic_part(x2, l2) - cubic_part(x1, l1) - &
                 y**3 * angle / 3.0_wp
        p(2)%fx = -a**2 * (l1 - l2) + 2.0_wp * f1(1)
        p(2)%fy = 2.0_wp * a * y - y**2 * angle + 2.0_wp * x * y * (l1 - l2) + x**2 * angle
        p(2)%fxx = -a**2 * (x1 / r1 - x2 / r2) + 2.0_wp * f1(2)
        p(2)%fxy = -a**2 * (y / r1 - y / r2) + 2.0_wp * f1(3)
        p(2)%fyy = -p(2)%fxx
        p(2)%fxyy = a**2 * ((y**2 - x1**2) / r1**2 - (y**2 - x2**2) / r2**2) - 2.0_wp * f1(4)
        p(2)%fyyy = a**2 * (-2.0_wp * x1 * y / r1**2 + 2.0_wp * x2 * y / r2**2) - &
                    2.0_wp * f1(5)
        p(0)%fyy = -p(0)%fxx
        ! The constant of the potential, and the densities in (xi / a)^m
        c0 = -1.0_wp / (4.0_wp * pi * (1.0_wp - nu))
        p(0) = scaled(p(0), c0)
        p(1) = scaled(p(1), c0 / a)
        p(2) = scaled(p(2), c0 / a**2)

    contains

        !> The part of int t^2 ln r dt at t that holds no angle.
        pure real(wp) function cubic_part(t, log_r)
            real(wp), intent(in) :: t, log_r

            cubic_part = t**3 / 3.0_wp * log_r - t**3 / 9.0_wp + y**2 * t / 3.0_wp
        end function cubic_part
    end function monomial_potentials

    !> Every value of a potential times c.
    pure function scaled(p, c) result(q)
        type(potential), intent(in) :: p
        real(wp), intent(in) :: c
        type(potential) :: q

        q = potential(c * p%f, c * p%fx, c * p%fy, c * p%fxx, c * p%fxy, c * p%fyy, &
                      c * p%fxyy, c * p%fyyy)
    end function scaled

    !> Local displacement and stress at local y per unit DD (1: s, 2: n) of the density of
    !> potential p (Crouch & Starfield eq. 5.2.5).
    pure function dd_fields(p, y, shear_modulus, nu) result(k)
        type(potential), intent(in) :: p
        real(wp), intent(in) :: y, shear_modulus, nu
        type(dd_kernel) :: k
        real(wp) :: g2

        g2 = 2.0_wp * shear_modulus
        k%ux = [2.0_wp * (1.0_wp - nu) * p%fy - y * p%fxx, &
                -(1.0_wp - 2.0_wp * nu) * p%fx - y * p%fxy]
        k%uy = [(1.0_wp - 2.0_wp * nu) * p%fx - y * p%fxy, &
                2.0_wp * (1.0_wp - nu) * p%fy - y * p%fyy]
        k%sxx = g2 * [2.0_wp * p%fxy + y * p%fxyy, p%fyy + y * p%fyyy]
        k%syy = g2 * [-y * p%fxyy, p%fyy - y * p%fyyy]
        k%sxy = g2 * [p%fyy + y * p%fyyy, -y * p%fxyy]
    end function dd_fields

    !> Local displacement and stress at local y per unit line load (1: s, 2: n) of the density
    !> of potential p (Crouch & Starfield eq. 4.4.x; the displacement up to a translation).
    pure function line_load_fields(p, y, shear_modulus, nu) result(k)
        type(potential), intent(in) :: p
        real(wp), intent(in) :: y, shear_modulus, nu
        type(dd_kernel) :: k
        real(wp) :: c

        c = 1.0_wp / (2.0_wp * shear_modulus)
        k%ux = c * [(3.0_wp - 4.0_wp * nu) * p%f + y * p%fy, -y * p%fx]
        k%uy = c * [-y * p%fx, (3.0_wp - 4.0_wp * nu) * p%f - y * p%fy]
        k%sxx = [(3.0_wp - 2.0_wp * nu) * p%fx + y * p%fxy, 2.0_wp * nu * p%fy + y * p%fyy]
        k%syy = [-(1.0_wp - 2.0_wp * nu) * p%fx - y * p%fxy, &
                 2.0_wp * (1.0_wp - nu) * p%fy - y * p%fyy]
        k%sxy = [2.0_wp * (1.0_wp - nu) * p%fy + y * p%fyy, &
                 (1.0_wp - 2.0_wp * nu) * p%fx - y * p%fxy]
    end function line_load_fields

    !> Global-frame fields at global (x, y) of the three nodal DDs and line loads of the
    !> element with midpoint (xm, ym), half-length a and direction (cosb, sinb).
    pure function node_fields(x, y, xm, ym, a, cosb, sinb, shear_modulus, nu, face) &
        result(fields)
        !> Point [length unit]; element midpoint, half-length [length unit], direction
        real(wp), intent(in) :: x, y, xm, ym, a, cosb, sinb
        !> Shear modulus [stress unit], Poisson's ratio
        real(wp), intent(in) :: shear_modulus, nu
        !> Face of a point on the element (+1: the side of its normal, -1: the other)
        integer, intent(in) :: face
        type(nodal_sources) :: fields

        fields = local_node_fields((x - xm) * cosb + (y - ym) * sinb, &
                                   -(x - xm) * sinb + (y - ym) * cosb, a, cosb, sinb, &
                                   shear_modulus, nu, face)
    end function node_fields

    !> node_fields at the point of local coordinates (xl, yl) (yl = 0 exactly on the
    !> element's line, for a point of the element itself).
    pure function local_node_fields(xl, yl, a, cosb, sinb, shear_modulus, nu, face) &
        result(fields)
        !> Local point, half-length [length unit]; the element's direction
        real(wp), intent(in) :: xl, yl, a, cosb, sinb
        !> Shear modulus [stress unit], Poisson's ratio
        real(wp), intent(in) :: shear_modulus, nu
        !> Face of a point on the element
        integer, intent(in) :: face
        type(nodal_sources) :: fields
        type(potential) :: p(0:2), node
        integer :: k

        p = monomial_potentials(xl, yl, a, nu, face)
        do k = 1, 3
            node = combined(p, basis_monomials(:, k))
            fields%dd(k) = to_global(dd_fields(node, yl, shear_modulus, nu))
            fields%load(k) = to_global(line_load_fields(node, yl, shear_modulus, nu))
        end do

    contains

        pure function to_global(local) result(k)
            type(dd_kernel), intent(in) :: local
            type(dd_kernel) :: k

            k%ux = local%ux * cosb - local%uy * sinb
            k%uy = local%ux * sinb + local%uy * cosb
            call global_stress(local, cosb, sinb, k)
        end function to_global
    end function local_node_fields

    !> The potential of the density sum_m w(m) (xi / a)^m.
    pure function combined(p, w) result(q)
        type(potential), intent(in) :: p(0:2)
        real(wp), intent(in) :: w(0:2)
        type(potential) :: q
        integer :: m

        do m = 0, 2
            q = potential(q%f + w(m) * p(m)%f, q%fx + w(m) * p(m)%fx, q%fy + w(m) * p(m)%fy, &
                          q%fxx + w(m) * p(m)%fxx, q%fxy + w(m) * p(m)%fxy, &
                          q%fyy + w(m) * p(m)%fyy, q%fxyy + w(m) * p(m)%fxyy, &
                          q%fyyy + w(m) * p(m)%fyyy)
        end do
    end function combined

end module ddc_influence_kernel_polynomial
