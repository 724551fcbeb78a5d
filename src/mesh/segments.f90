!> The geometry of two straight segments, for the mesh checks (ddc_mesh_checks: how two
!> elements meet, within a tolerance) and for growth (ddc_growth_clearance: distances,
!> crossings and nearness of new elements, exact).
!>
!> A segment is given by its end points a-b [length unit]. Every procedure is pure.
module ddc_mesh_segments
    use ddc_kinds, only: wp
    implicit none
    private

    public :: classify_pair, pair_ok, pair_duplicate, pair_overlap, pair_cross, &
              pair_t_first_end, pair_t_second_end
    public :: segment_distance, point_segment_distance, crossing_fraction, far_apart

    !> How two segments meet (classify_pair): not at all or at a shared end (pair_ok), with
    !> the same ends, collinear along a stretch, crossing inside both, or with an end of the
    !> first (second) inside the other (a T-junction)
    integer, parameter :: pair_ok = 0, pair_duplicate = 1, pair_overlap = 2, &
                          pair_cross = 3, pair_t_first_end = 4, pair_t_second_end = 5

contains

    !> How the segments P = p0-p1 and Q = q0-q1 (both of non-zero length) meet, ends within
    !> `tol` counting as one point: pair_ok, pair_duplicate, pair_overlap, pair_cross,
    !> pair_t_first_end (an end of P inside Q) or pair_t_second_end.
    pure function classify_pair(p0x, p0y, p1x, p1y, q0x, q0y, q1x, q1y, tol) result(kind)
        !> End points of P and of Q [length unit]
        real(wp), intent(in) :: p0x, p0y, p1x, p1y, q0x, q0y, q1x, q1y
        !> Distance below which points coincide [length unit]
        real(wp), intent(in) :: tol
        integer :: kind
        real(wp) :: dx, dy, ex, ey, lp, lq, dq0, dq1, dp0, dp1, denominator, t, u
        real(wp) :: ux, uy, tp(2), tq(2), overlap
        logical :: s00, s01, s10, s11, shared, p_end, q_end

        kind = pair_ok
        s00 = hypot(p0x - q0x, p0y - q0y) <= tol
        s01 = hypot(p0x - q1x, p0y - q1y) <= tol
        s10 = hypot(p1x - q0x, p1y - q0y) <= tol
        s11 = hypot(p1x - q1x, p1y - q1y) <= tol
        if ((s00 .and. s11) .or. (s01 .and. s10)) then
            kind = pair_duplicate
            return
        end if
        shared = s00 .or. s01 .or. s10 .or. s11

        dx = p1x - p0x
        dy = p1y - p0y
        ex = q1x - q0x
        ey = q1y - q0y
        lp = hypot(dx, dy)
        lq = hypot(ex, ey)
        ! Signed distances of each segment's ends from the other segment's line.
        dq0 = cross(dx, dy, q0x - p0x, q0y - p0y) / lp
        dq1 = cross(dx, dy, q1x - p0x, q1y - p0y) / lp
        dp0 = cross(ex, ey, p0x - q0x, p0y - q0y) / lq
        dp1 = cross(ex, ey, p1x - q0x, p1y - q0y) / lq

        if ((abs(dq0) <= tol .and. abs(dq1) <= tol) .or. &
            (abs(dp0) <= tol .and. abs(dp1) <= tol)) then
            ! Collinear: measure the common stretch along the longer element.
            if (lp >= lq) then
                ux = dx / lp
                uy = dy / lp
            else
                ux = ex / lq
                uy = ey / lq
            end if
            tp = [0.0_wp, (p1x - p0x) * ux + (p1y - p0y) * uy]
            tq = [(q0x - p0x) * ux + (q0y - p0y) * uy, (q1x - p0x) * ux + (q1y - p0y) * uy]
            overlap = min(maxval(tp), maxval(tq)) - max(minval(tp), minval(tq))
            if (overlap > tol) kind = pair_overlap
            return
        end if

        ! Not collinear: each segment must reach the other's line for any contact.
        if ((dq0 > tol .and. dq1 > tol) .or. (dq0 < -tol .and. dq1 < -tol)) return
        if ((dp0 > tol .and. dp1 > tol) .or. (dp0 < -tol .and. dp1 < -tol)) return
        ! Two straight elements meet at most once: at a shared vertex that is allowed.
        if (shared) return
        denominator = cross(dx, dy, ex, ey)
        if (denominator == 0.0_wp) return
        ! Intersection of the lines, as distances along P and along Q.
        t = cross(q0x - p0x, q0y - p0y, ex, ey) / denominator * lp
        u = cross(q0x - p0x, q0y - p0y, dx, dy) / denominator * lq
        if (t < -tol .or. t > lp + tol .or. u < -tol .or. u > lq + tol) return
        p_end = t <= tol .or. t >= lp - tol
        q_end = u <= tol .or. u >= lq - tol
        if (p_end) then
            kind = pair_t_first_end
        else if (q_end) then
            kind = pair_t_second_end
        else
            kind = pair_cross
        end if
    end function classify_pair

    !> Smallest distance between the segments a-b and c-d [length unit]; 0 when they cross
    !> or touch.
    pure real(wp) function segment_distance(ax, ay, bx, by, cx, cy, dx, dy)
        !> End points of the two segments [length unit]
        real(wp), intent(in) :: ax, ay, bx, by, cx, cy, dx, dy
        real(wp) :: o1, o2, o3, o4

        o1 = cross(bx - ax, by - ay, cx - ax, cy - ay)
        o2 = cross(bx - ax, by - ay, dx - ax, dy - ay)
        o3 = cross(dx - cx, dy - cy, ax - cx, ay - cy)
        o4 = cross(dx - cx, dy - cy, bx - cx, by - cy)
        if (((o1 > 0.0_wp .and. o2 < 0.0_wp) .or. (o1 < 0.0_wp .and. o2 > 0.0_wp)) .and. &
            ((o3 > 0.0_wp .and. o4 < 0.0_wp) .or. (o3 < 0.0_wp .and. o4 > 0.0_wp))) then
            segment_distance = 0.0_wp
            return
        end if
        ! Not crossing: the closest pair involves an end point of one of them.
        segment_distance = min(point_segment_distance(ax, ay, cx, cy, dx, dy), &
                               point_segment_distance(bx, by, cx, cy, dx, dy), &
                               point_segment_distance(cx, cy, ax, ay, bx, by), &
                               point_segment_distance(dx, dy, ax, ay, bx, by))
    end function segment_distance

    !> Distance from the point (px, py) to the segment a-b [length unit].
    pure real(wp) function point_segment_distance(px, py, ax, ay, bx, by)
        !> The point and the segment's end points [length unit]
        real(wp), intent(in) :: px, py, ax, ay, bx, by
        real(wp) :: t, length2

        length2 = (bx - ax)**2 + (by - ay)**2
        t = 0.0_wp
        if (length2 > 0.0_wp) t = max(0.0_wp, min(1.0_wp, ((px - ax) * (bx - ax) + &
                                                           (py - ay) * (by - ay)) / length2))
        point_segment_distance = hypot(px - (ax + t * (bx - ax)), py - (ay + t * (by - ay)))
    end function point_segment_distance

    !> Where segment a-b crosses the line through c-d, as a fraction of a-b in [0, 1]
    !> (segments known to cross or touch; 0 when they are parallel).
    pure real(wp) function crossing_fraction(ax, ay, bx, by, cx, cy, dx, dy)
        !> End points of the two segments [length unit]
        real(wp), intent(in) :: ax, ay, bx, by, cx, cy, dx, dy
        real(wp) :: denominator

        denominator = cross(bx - ax, by - ay, dx - cx, dy - cy)
        crossing_fraction = 0.0_wp
        if (denominator /= 0.0_wp) crossing_fraction = max(0.0_wp, min(1.0_wp, &
            cross(cx - ax, cy - ay, dx - cx, dy - cy) / denominator))
    end function crossing_fraction

    !> True when the bounding boxes of the segments a-b and c-d are more than `gap` apart.
    pure logical function far_apart(ax, ay, bx, by, cx, cy, dx, dy, gap)
        !> End points of the two segments [length unit]
        real(wp), intent(in) :: ax, ay, bx, by, cx, cy, dx, dy
        !> The gap [length unit]
        real(wp), intent(in) :: gap

        far_apart = min(cx, dx) > max(ax, bx) + gap .or. max(cx, dx) < min(ax, bx) - gap .or. &
                    min(cy, dy) > max(ay, by) + gap .or. max(cy, dy) < min(ay, by) - gap
    end function far_apart

    !> z component of the cross product of (ux, uy) and (vx, vy): ux vy - uy vx.
    pure real(wp) function cross(ux, uy, vx, vy)
        !> The two vectors [length unit]
        real(wp), intent(in) :: ux, uy, vx, vy

        cross = ux * vy - uy * vx
    end function cross

end module ddc_mesh_segments
