!> Influence of higher-order elements (docs/theory/tips.md#k-from-a-higher-order-re-solve).
!>
!> Such an element is a circular arc (curvature kappa, 0 for a straight element) of length
!> L = 2h, and its DD, in the arc's own (s, n) frame at each point, varies along it as
!> w(s) q(s): q quadratic, fixed by its values at three nodes (-2/3, 0 and 2/3 of h from
!> the midpoint m), and w a weight, 1 or, near a crack tip, sqrt(r(s) / r(m)) with r the
!> distance from the tip along the fracture (so the DD of a tip element varies as the
!> square root of r). An element with two tip weights (a one-element crack) takes their
!> product.
!>
!> Such an element is a superposition of constant-DD segments, which the model's kernel
!> serves (full plane or half-plane, with symmetry images). A constant DD vector on a
!> straight segment stresses the body as two dislocations at its ends, whatever the path
!> between them; so, with D(s) the DD vector in a fixed frame and y(s) the point at s,
!>     element = D(m) [y(0), y(L)] - int_0^m D'(t) [y(0), y(t)] dt + int_m^L D'(t) [y(t), y(L)] dt,
!> with [p, q] the constant segment from p to q, D' = dD/ds in the frame of each segment
!> (on an arc the frame turns: D' holds kappa times D besides the derivatives of the
!> components). The integrals are Gauss-Legendre sums: near a tip in t = tip + (m - tip) v^2,
!> where D' ~ 1/sqrt(r) becomes smooth in v; in pieces no longer than the receiver's
!> distance where it is close; and for a receiver on the element itself as a Cauchy
!> principal value, by points mirrored about the receiver (the stress of a segment at a
!> point on its line grows as the inverse of the distance to its end).
module ddc_influence_higher_order
    use ddc_kinds, only: wp
    use ddc_model_medium, only: elastic_medium
    use ddc_influence_kernel, only: face_negative
    use ddc_influence_assembly, only: kernel_function, image_transform, &
        segment_kernel_with_images, resolved_tractions
    implicit none
    private

    public :: weighted_element, arc_element, node_xi, nodal_basis, weight_at, point_at
    public :: element_tractions, gauss_8_x, gauss_8_w

    !> Positions of the three nodes, in half-lengths from the midpoint
    real(wp), parameter :: node_xi(3) = [-2.0_wp / 3.0_wp, 0.0_wp, 2.0_wp / 3.0_wp]

    !> Gauss-Legendre points and weights on [-1, 1]
    real(wp), parameter :: gauss_8_x(8) = [-0.9602898564975363_wp, -0.7966664774136267_wp, &
        -0.5255324099163290_wp, -0.1834346424956498_wp, 0.1834346424956498_wp, &
        0.5255324099163290_wp, 0.7966664774136267_wp, 0.9602898564975363_wp]
    real(wp), parameter :: gauss_8_w(8) = [0.1012285362903763_wp, 0.2223810344533745_wp, &
        0.3137066458778873_wp, 0.3626837833783620_wp, 0.3626837833783620_wp, &
        0.3137066458778873_wp, 0.2223810344533745_wp, 0.1012285362903763_wp]
    real(wp), parameter :: gauss_4_x(4) = [-0.8611363115940526_wp, -0.3399810435848563_wp, &
        0.3399810435848563_wp, 0.8611363115940526_wp]
    real(wp), parameter :: gauss_4_w(4) = [0.3478548451374538_wp, 0.6521451548625461_wp, &
        0.6521451548625461_wp, 0.3478548451374538_wp]

    !> A receiver at least this many element lengths away takes 4 points per half element
    real(wp), parameter :: far_distance = 4.0_wp
    !> At most this many pieces per interval
    integer, parameter :: max_pieces = 32
    !> Size of a quadrature rule: two halves in pieces, a principal-value window, one more
    !> interval beside it
    integer, parameter :: max_points = 3 * max_pieces * 8 + 16

    !> One element's geometry and weight.
    type :: weighted_element
        !> Begin point [length unit], tangent angle there [rad], curvature [1 / length unit]
        !> (positive turning counter-clockwise), arc length [length unit]
        real(wp) :: xb = 0.0_wp, yb = 0.0_wp, angle = 0.0_wp, curvature = 0.0_wp
        real(wp) :: length = 1.0_wp
        !> cos and sin of the angle (point_at runs at every quadrature point)
        real(wp) :: cos_angle = 1.0_wp, sin_angle = 0.0_wp
        !> Number of square-root factors of the weight (0, 1 or 2)
        integer :: factors = 0
        !> Factor f: r(s) = r0(f) + dr(f) s is the distance from its tip at s from the
        !> element's begin [length unit]; dr is +1 or -1
        real(wp) :: r0(2) = 0.0_wp, dr(2) = 0.0_wp
    end type weighted_element

    !> Points of a quadrature rule over t in [0, L].
    type :: quadrature_rule
        integer :: n = 0
        !> Position [length unit], weight [length unit] and sign (-1: segment [0, t], +1:
        !> segment [t, L])
        real(wp) :: t(max_points), w(max_points), side(max_points)
    end type quadrature_rule

contains

    !> The arc from (xb, yb) to (xe, ye) with the given curvature [1 / length unit] (0: the
    !> straight element), without weight.
    pure function arc_element(xb, yb, xe, ye, curvature) result(element)
        real(wp), intent(in) :: xb, yb, xe, ye, curvature
        type(weighted_element) :: element
        real(wp) :: chord, half_turn

        chord = hypot(xe - xb, ye - yb)
        half_turn = asin(min(1.0_wp, 0.5_wp * curvature * chord))
        element%xb = xb
        element%yb = yb
        element%curvature = curvature
        element%length = chord
        if (half_turn /= 0.0_wp) element%length = 2.0_wp * half_turn / curvature
        element%angle = atan2(ye - yb, xe - xb) - half_turn
        element%cos_angle = cos(element%angle)
        element%sin_angle = sin(element%angle)
    end function arc_element

    !> The point at arc length s from the element's begin, and the tangent's direction
    !> cosines there.
    pure subroutine point_at(element, s, x, y, c, sn)
        type(weighted_element), intent(in) :: element
        !> Arc length [length unit]
        real(wp), intent(in) :: s
        !> Point [length unit] and tangent
        real(wp), intent(out) :: x, y, c, sn
        real(wp) :: half, factor, cos_half, sin_half, cos_turn, sin_turn

        half = 0.5_wp * element%curvature * s
        associate (ca => element%cos_angle, sa => element%sin_angle)
            if (half == 0.0_wp) then
                x = element%xb + s * ca
                y = element%yb + s * sa
                c = ca
                sn = sa
                return
            end if
            ! The chord from the begin: length s sin(half) / half, at the angle of its
            ! midpoint (angle + half); the tangent turns by 2 half.
            sin_half = sin(half)
            cos_half = cos(half)
            if (abs(half) > 1.0e-4_wp) then
                factor = sin_half / half
            else
                factor = 1.0_wp - half**2 / 6.0_wp
            end if
            x = element%xb + s * factor * (ca * cos_half - sa * sin_half)
            y = element%yb + s * factor * (sa * cos_half + ca * sin_half)
            cos_turn = cos_half**2 - sin_half**2
            sin_turn = 2.0_wp * sin_half * cos_half
            c = ca * cos_turn - sa * sin_turn
            sn = sa * cos_turn + ca * sin_turn
        end associate
    end subroutine point_at

    !> The quadratic basis functions through the nodes and their derivatives at xi.
    pure subroutine nodal_basis(xi, n, dn)
        !> Position in half-lengths from the midpoint
        real(wp), intent(in) :: xi
        !> Values and derivatives d/dxi of the three basis functions
        real(wp), intent(out) :: n(3), dn(3)

        n = [1.125_wp * xi * (xi - 2.0_wp / 3.0_wp), 1.0_wp - 2.25_wp * xi**2, &
             1.125_wp * xi * (xi + 2.0_wp / 3.0_wp)]
        dn = [1.125_wp * (2.0_wp * xi - 2.0_wp / 3.0_wp), -4.5_wp * xi, &
              1.125_wp * (2.0_wp * xi + 2.0_wp / 3.0_wp)]
    end subroutine nodal_basis

    !> The weight w and its derivative dw/ds at s from the element's begin.
    pure subroutine weight_at(element, s, w, dw)
        type(weighted_element), intent(in) :: element
        !> Position [length unit]
        real(wp), intent(in) :: s
        !> w [-] and dw/ds [1 / length unit]
        real(wp), intent(out) :: w, dw
        real(wp) :: r, rm, log_derivative
        integer :: f

        w = 1.0_wp
        log_derivative = 0.0_wp
        do f = 1, element%factors
            r = element%r0(f) + element%dr(f) * s
            rm = element%r0(f) + element%dr(f) * 0.5_wp * element%length
            w = w * sqrt(r / rm)
            log_derivative = log_derivative + element%dr(f) / (2.0_wp * r)
        end do
        dw = w * log_derivative
    end subroutine weight_at

    !> Shear (row 1) and normal (row 2) traction at a receiver, on the plane (cr, sr), per
    !> unit nodal value: column 2 (k - 1) + c for node k and DD c (1 Ds, 2 Dn).
    pure subroutine element_tractions(kernel, images, medium, element, s_self, x, y, cr, sr, &
                                      block)
        !> The model's kernel and image transforms (ddc_influence_assembly)
        procedure(kernel_function) :: kernel
        type(image_transform), intent(in) :: images(:)
        !> The medium (its materials)
        type(elastic_medium), intent(in) :: medium
        !> The source element
        type(weighted_element), intent(in) :: element
        !> The receiver's arc length from the element's begin where it lies on the element
        !> [length unit]; negative elsewhere
        real(wp), intent(in) :: s_self
        !> Receiver [length unit] and its plane's direction cosines
        real(wp), intent(in) :: x, y, cr, sr
        !> Tractions per unit nodal value [stress unit / length unit], shape (2, 6)
        real(wp), intent(out) :: block(2, 6)
        type(quadrature_rule) :: rule
        real(wp) :: ts(2), tn(2), h, t, xi, w, dw, n(3), dn(3), value, slope, b(2)
        real(wp) :: p(2, 3), cb, sb, ct, st, along(2), cos_turn, sin_turn
        integer :: g, node, c

        h = 0.5_wp * element%length
        block = 0.0_wp
        call point_at(element, 0.0_wp, p(1, 1), p(2, 1), cb, sb)
        call point_at(element, element%length, p(1, 3), p(2, 3), cb, sb)
        ! D(m) on the chord: the chord is parallel to the arc's tangent at m, and only node 2
        ! is 1 there (the weight is 1 at m).
        call segment_tractions(p(:, 1), p(:, 3), ts, tn, along)
        block(1, 3:4) = ts
        block(2, 3:4) = tn
        call build_rule(element, s_self, x, y, rule)
        do g = 1, rule%n
            t = rule%t(g)
            call point_at(element, t, p(1, 2), p(2, 2), ct, st)
            if (rule%side(g) < 0.0_wp) then
                call segment_tractions(p(:, 1), p(:, 2), ts, tn, along)
            else
                call segment_tractions(p(:, 2), p(:, 3), ts, tn, along)
            end if
            ! The turn from the segment's frame to the arc's frame at t (tangent ct, st).
            cos_turn = ct * along(1) + st * along(2)
            sin_turn = st * along(1) - ct * along(2)
            xi = (t - h) / h
            call nodal_basis(xi, n, dn)
            call weight_at(element, t, w, dw)
            do node = 1, 3
                value = w * n(node)
                slope = dw * n(node) + w * dn(node) / h
                do c = 1, 2
                    ! dD/ds of this unknown in the arc's frame (the frame turns at kappa),
                    ! then in the segment's.
                    if (c == 1) then
                        b = [slope, element%curvature * value]
                    else
                        b = [-element%curvature * value, slope]
                    end if
                    b = [cos_turn * b(1) - sin_turn * b(2), sin_turn * b(1) + cos_turn * b(2)]
                    b = rule%side(g) * rule%w(g) * b
                    block(1, 2 * (node - 1) + c) = block(1, 2 * (node - 1) + c) + &
                                                   b(1) * ts(1) + b(2) * ts(2)
                    block(2, 2 * (node - 1) + c) = block(2, 2 * (node - 1) + c) + &
                                                   b(1) * tn(1) + b(2) * tn(2)
                end do
            end do
        end do

    contains

        !> Tractions at the receiver per unit Ds, Dn of the constant segment from a to e, and
        !> the segment's direction.
        pure subroutine segment_tractions(a, e, ts, tn, direction)
            real(wp), intent(in) :: a(2), e(2)
            real(wp), intent(out) :: ts(2), tn(2), direction(2)
            real(wp) :: length

            ! Not hypot: lengths of a model neither overflow nor underflow, and hypot's care
            ! took an eighth of a growth run with the re-solve.
            direction = e - a
            length = sqrt(direction(1)**2 + direction(2)**2)
            direction = direction / length
            call resolved_tractions(segment_kernel_with_images(kernel, x, y, &
                0.5_wp * (a(1) + e(1)), 0.5_wp * (a(2) + e(2)), 0.5_wp * length, &
                direction(1), direction(2), images, medium, face_negative), cr, sr, ts, tn)
        end subroutine segment_tractions
    end subroutine element_tractions

    !> The quadrature rule of the two integrals for one receiver.
    pure subroutine build_rule(element, s_self, x, y, rule)
        type(weighted_element), intent(in) :: element
        real(wp), intent(in) :: s_self, x, y
        type(quadrature_rule), intent(out) :: rule
        real(wp) :: l, m, d

        l = element%length
        m = 0.5_wp * l
        if (s_self < 0.0_wp) then
            call add_interval(element, 0.0_wp, m, -1.0_wp, distance_to(element, 0.0_wp, m, x, &
                              y), rule)
            call add_interval(element, m, l, 1.0_wp, distance_to(element, m, l, x, y), rule)
        else if (abs(s_self - m) <= 1.0e-9_wp * l) then
            d = 0.5_wp * m
            call add_mirrored(m, d, m, rule)
            call add_interval(element, 0.0_wp, m - d, -1.0_wp, d, rule)
            call add_interval(element, m + d, l, 1.0_wp, d, rule)
        else if (s_self > m) then
            d = 0.5_wp * min(s_self - m, l - s_self)
            call add_mirrored(s_self, d, m, rule)
            call add_interval(element, 0.0_wp, m, -1.0_wp, s_self - m, rule)
            call add_interval(element, m, s_self - d, 1.0_wp, d, rule)
            call add_interval(element, s_self + d, l, 1.0_wp, d, rule)
        else
            d = 0.5_wp * min(m - s_self, s_self)
            call add_mirrored(s_self, d, m, rule)
            call add_interval(element, 0.0_wp, s_self - d, -1.0_wp, d, rule)
            call add_interval(element, s_self + d, m, -1.0_wp, d, rule)
            call add_interval(element, m, l, 1.0_wp, m - s_self, rule)
        end if
    end subroutine build_rule

    !> Distance from (x, y) to the chord of the part of the element between s = a and s = b
    !> (the arc lies within a sagitta of it).
    pure real(wp) function distance_to(element, a, b, x, y)
        type(weighted_element), intent(in) :: element
        real(wp), intent(in) :: a, b, x, y
        real(wp) :: pa(2), pb(2), c, s, along, length, across

        call point_at(element, a, pa(1), pa(2), c, s)
        call point_at(element, b, pb(1), pb(2), c, s)
        length = sqrt((pb(1) - pa(1))**2 + (pb(2) - pa(2))**2)
        along = ((x - pa(1)) * (pb(1) - pa(1)) + (y - pa(2)) * (pb(2) - pa(2))) / length
        across = (-(x - pa(1)) * (pb(2) - pa(2)) + (y - pa(2)) * (pb(1) - pa(1))) / length
        along = along - min(max(along, 0.0_wp), length)
        distance_to = sqrt(along**2 + across**2)
    end function distance_to

    !> A principal-value window [s - d, s + d] about a receiver at s: Gauss points tau on
    !> [0, d], each used at s - tau and s + tau (the odd, singular part cancels in pairs).
    pure subroutine add_mirrored(s, d, m, rule)
        real(wp), intent(in) :: s, d, m
        type(quadrature_rule), intent(inout) :: rule
        real(wp) :: tau, t
        integer :: g, pair

        do g = 1, 8
            tau = 0.5_wp * d * (gauss_8_x(g) + 1.0_wp)
            do pair = -1, 1, 2
                t = s + pair * tau
                rule%n = rule%n + 1
                rule%t(rule%n) = t
                rule%w(rule%n) = 0.5_wp * d * gauss_8_w(g)
                rule%side(rule%n) = merge(-1.0_wp, 1.0_wp, t < m)
            end do
        end do
    end subroutine add_mirrored

    !> Gauss points on [a, b] for one side of the superposition: in v with t = e + (o - e)
    !> v^2 where a weight vanishes at an end e (o the other end), in as many pieces as the
    !> receiver's distance asks.
    pure subroutine add_interval(element, a, b, side, distance, rule)
        type(weighted_element), intent(in) :: element
        real(wp), intent(in) :: a, b, side, distance
        type(quadrature_rule), intent(inout) :: rule
        real(wp) :: e, o, v, width, t, jacobian, x, w
        integer :: pieces, p, g, points
        logical :: tip_a, tip_b, far

        if (b <= a) return
        tip_a = vanishes_at(element, a)
        tip_b = vanishes_at(element, b)
        far = distance >= far_distance * element%length
        points = merge(4, 8, far)
        if (far) then
            pieces = 1
        else
            pieces = min(max_pieces, max(1, ceiling(merge(2.0_wp, 1.0_wp, tip_a .or. tip_b) * &
                                                    (b - a) / max(distance, tiny(1.0_wp)))))
        end if
        e = merge(b, a, tip_b)
        o = merge(a, b, tip_b)
        width = 1.0_wp / pieces
        do p = 1, pieces
            do g = 1, points
                call gauss_point(g, points, x, w)
                v = width * (p - 1 + 0.5_wp * (x + 1.0_wp))
                rule%n = rule%n + 1
                if (tip_a .or. tip_b) then
                    t = e + (o - e) * v**2
                    jacobian = 2.0_wp * abs(o - e) * v
                else
                    t = a + (b - a) * v
                    jacobian = b - a
                end if
                rule%t(rule%n) = t
                rule%w(rule%n) = 0.5_wp * width * w * jacobian
                rule%side(rule%n) = side
            end do
        end do
    end subroutine add_interval

    !> Whether a factor of the weight is zero at s (a tip there).
    pure logical function vanishes_at(element, s)
        type(weighted_element), intent(in) :: element
        real(wp), intent(in) :: s
        integer :: f

        vanishes_at = .false.
        do f = 1, element%factors
            if (abs(element%r0(f) + element%dr(f) * s) <= 1.0e-9_wp * element%length) then
                vanishes_at = .true.
            end if
        end do
    end function vanishes_at

    !> Point g of the Gauss-Legendre rule of `points` (4 or 8) points on [-1, 1], and its
    !> weight.
    pure subroutine gauss_point(g, points, x, w)
        integer, intent(in) :: g, points
        real(wp), intent(out) :: x, w

        if (points == 4) then
            x = gauss_4_x(g)
            w = gauss_4_w(g)
        else
            x = gauss_8_x(g)
            w = gauss_8_w(g)
        end if
    end subroutine gauss_point

end module ddc_influence_higher_order
