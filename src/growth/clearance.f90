!> Where growth must stop (SPEC-GROWTH 1.6): new elements that would cross or touch
!> another element or come closer than half an element length to one, and in a half-plane
!> new elements that would come that close to the free surface y = 0 (or reach it).
!> Nothing is ever meshed across another fracture.
module ddc_growth_clearance
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, domain_half_plane
    use ddc_model_results, only: growth_intersection, growth_surface
    use ddc_growth_extension, only: tip_path, tip_element, path_element_length
    implicit none
    private

    public :: check_paths, segment_distance, path_clear

    !> New elements keep at least this fraction of their length from every other element
    !> and from the free surface
    real(wp), parameter :: clearance_fraction = 0.5_wp

    !> check_paths' code of a path that keeps clear (else a growth reason: growth_intersection
    !> or growth_surface)
    integer, parameter :: path_clear = 0

contains

    !> For every active path: path_clear when its new elements keep clear of every element of the
    !> model and of every other active path, growth_intersection when they do not,
    !> growth_surface when (in a half-plane) they keep clear of every element but not of
    !> the surface. The first new element may meet the tip element only at the tip: its
    !> far end must keep clear of the tip element.
    pure subroutine check_paths(model, paths, active, problem)
        !> The model before growing, geometry computed
        type(model_type), intent(in) :: model
        !> The candidate paths, one per growing tip
        type(tip_path), intent(in) :: paths(:)
        !> Which paths are candidates, shape (size(paths))
        logical, intent(in) :: active(:)
        !> path_clear, growth_intersection or growth_surface for each path (path_clear when
        !> not active)
        integer, intent(out) :: problem(:)
        real(wp) :: clearance(size(paths))
        integer :: p, q

        problem = path_clear
        do p = 1, size(paths)
            if (.not. active(p)) cycle
            clearance(p) = clearance_fraction * path_element_length(paths(p))
            if (hits_model(model, paths(p), clearance(p))) problem(p) = growth_intersection
        end do
        do p = 1, size(paths)
            if (.not. active(p)) cycle
            do q = p + 1, size(paths)
                if (.not. active(q)) cycle
                if (path_distance(paths(p), paths(q)) < max(clearance(p), clearance(q))) then
                    problem(p) = growth_intersection
                    problem(q) = growth_intersection
                end if
            end do
        end do
        if (model%elements%domain /= domain_half_plane) return
        do p = 1, size(paths)
            if (.not. active(p) .or. problem(p) /= path_clear) cycle
            if (any(paths(p)%y(1:) > -clearance(p))) problem(p) = growth_surface
        end do
    end subroutine check_paths

    !> True when a path's new elements come closer than `clearance` to an element of the
    !> model (its tip element excepted at the tip itself).
    pure logical function hits_model(model, path, clearance)
        type(model_type), intent(in) :: model
        type(tip_path), intent(in) :: path
        real(wp), intent(in) :: clearance
        integer :: k, j, parent
        real(wp) :: d

        parent = tip_element(model, path%fracture, path%end)
        hits_model = .true.
        associate (e => model%elements)
            do k = 1, path%n
                do j = 1, e%n
                    if (far_apart(path%x(k - 1), path%y(k - 1), path%x(k), path%y(k), &
                                  e%x_begin(j), e%y_begin(j), e%x_end(j), e%y_end(j), &
                                  clearance)) cycle
                    if (k == 1 .and. j == parent) then
                        d = point_segment_distance(path%x(1), path%y(1), e%x_begin(j), &
                                                   e%y_begin(j), e%x_end(j), e%y_end(j))
                    else
                        d = segment_distance(path%x(k - 1), path%y(k - 1), path%x(k), &
                                             path%y(k), e%x_begin(j), e%y_begin(j), &
                                             e%x_end(j), e%y_end(j))
                    end if
                    if (d < clearance) return
                end do
            end do
        end associate
        hits_model = .false.
    end function hits_model

    !> Smallest distance between the new elements of two paths.
    pure real(wp) function path_distance(a, b)
        type(tip_path), intent(in) :: a, b
        integer :: i, j

        path_distance = huge(1.0_wp)
        do i = 1, a%n
            do j = 1, b%n
                path_distance = min(path_distance, segment_distance(a%x(i - 1), a%y(i - 1), &
                    a%x(i), a%y(i), b%x(j - 1), b%y(j - 1), b%x(j), b%y(j)))
            end do
        end do
    end function path_distance

    !> True when the bounding boxes of two segments are more than `gap` apart.
    pure logical function far_apart(ax, ay, bx, by, cx, cy, dx, dy, gap)
        real(wp), intent(in) :: ax, ay, bx, by, cx, cy, dx, dy, gap

        far_apart = min(cx, dx) > max(ax, bx) + gap .or. max(cx, dx) < min(ax, bx) - gap .or. &
                    min(cy, dy) > max(ay, by) + gap .or. max(cy, dy) < min(ay, by) - gap
    end function far_apart

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

    !> Distance from the point (px, py) to the segment a-b.
    pure real(wp) function point_segment_distance(px, py, ax, ay, bx, by)
        real(wp), intent(in) :: px, py, ax, ay, bx, by
        real(wp) :: t, length2

        length2 = (bx - ax)**2 + (by - ay)**2
        t = 0.0_wp
        if (length2 > 0.0_wp) t = max(0.0_wp, min(1.0_wp, ((px - ax) * (bx - ax) + &
                                                           (py - ay) * (by - ay)) / length2))
        point_segment_distance = hypot(px - (ax + t * (bx - ax)), py - (ay + t * (by - ay)))
    end function point_segment_distance

    !> z component of the cross product of (ux, uy) and (vx, vy).
    pure real(wp) function cross(ux, uy, vx, vy)
        real(wp), intent(in) :: ux, uy, vx, vy

        cross = ux * vy - uy * vx
    end function cross

end module ddc_growth_clearance
