!> Elements along a polyline: equal elements on each segment, vertex to vertex.
!>
!> Independent of any input format: the namelist reader and the TWODD deck reader both
!> call it for their segments.
module ddc_mesh_polyline
    use ddc_kinds, only: wp
    implicit none
    private

    public :: polyline_elements, expand_per_segment, crossing_fraction, split_at_height
    public :: snap_to_height

contains

    !> End points of the elements along the polyline (x, y) with counts(i) equal elements
    !> on segment i (from vertex i to vertex i + 1). Element ends at vertices are the
    !> vertices themselves (bit for bit), so consecutive segments share their end points.
    pure subroutine polyline_elements(x, y, counts, x_begin, y_begin, x_end, y_end)
        !> Vertex coordinates [length unit], shape (nv), nv >= 2
        real(wp), intent(in) :: x(:), y(:)
        !> Number of elements on each segment (>= 1), shape (nv - 1)
        integer, intent(in) :: counts(:)
        !> Element end points [length unit], shape (sum(counts))
        real(wp), allocatable, intent(out) :: x_begin(:), y_begin(:), x_end(:), y_end(:)
        integer :: segment, k, n, element
        real(wp) :: dx, dy, t0, t1

        n = sum(counts)
        allocate (x_begin(n), y_begin(n), x_end(n), y_end(n))
        element = 0
        do segment = 1, size(counts)
            dx = x(segment + 1) - x(segment)
            dy = y(segment + 1) - y(segment)
            do k = 1, counts(segment)
                element = element + 1
                t0 = real(k - 1, wp) / real(counts(segment), wp)
                t1 = real(k, wp) / real(counts(segment), wp)
                if (k == 1) then
                    x_begin(element) = x(segment)
                    y_begin(element) = y(segment)
                else
                    x_begin(element) = x(segment) + t0 * dx
                    y_begin(element) = y(segment) + t0 * dy
                end if
                if (k == counts(segment)) then
                    x_end(element) = x(segment + 1)
                    y_end(element) = y(segment + 1)
                else
                    x_end(element) = x(segment) + t1 * dx
                    y_end(element) = y(segment) + t1 * dy
                end if
            end do
        end do
    end subroutine polyline_elements

    !> Repeat a per-segment value on every element of its segment.
    pure function expand_per_segment(values, counts) result(per_element)
        !> One value per segment, shape (nseg)
        real(wp), intent(in) :: values(:)
        !> Number of elements on each segment, shape (nseg)
        integer, intent(in) :: counts(:)
        !> The values per element, shape (sum(counts))
        real(wp) :: per_element(sum(counts))
        integer :: segment, first

        first = 1
        do segment = 1, size(counts)
            per_element(first:first + counts(segment) - 1) = values(segment)
            first = first + counts(segment)
        end do
    end function expand_per_segment

    !> A height within tolerance of the line y = y_line put on it (exactly y_line).
    elemental subroutine snap_to_height(y, y_line, tolerance)
        !> The height [length unit]
        real(wp), intent(inout) :: y
        !> Height of the line, tolerance [length unit]
        real(wp), intent(in) :: y_line, tolerance

        if (abs(y - y_line) <= tolerance) y = y_line
    end subroutine snap_to_height

    !> Where an element from (yb) to (ye) crosses the line y = y_line, as the fraction of
    !> the way from its begin; -1 when it does not cross it (both ends on one side, or an
    !> end on the line).
    elemental real(wp) function crossing_fraction(yb, ye, y_line) result(t)
        !> Heights of the element's begin and end, of the line [length unit]
        real(wp), intent(in) :: yb, ye, y_line

        t = -1.0_wp
        if ((yb - y_line) * (ye - y_line) < 0.0_wp) t = (y_line - yb) / (ye - yb)
    end function crossing_fraction

    !> Split every element that crosses the line y = y_line into two that meet on it
    !> (exactly at y_line), in place; source(k) is the element the new element k comes from.
    pure subroutine split_at_height(x_begin, y_begin, x_end, y_end, y_line, source)
        !> Element end points [length unit], shape (n) on entry, (n + crossings) on return
        real(wp), allocatable, intent(inout) :: x_begin(:), y_begin(:), x_end(:), y_end(:)
        !> Height of the line [length unit]
        real(wp), intent(in) :: y_line
        !> The element each element comes from, shape (n + crossings)
        integer, allocatable, intent(out) :: source(:)
        real(wp) :: t(size(y_begin))
        real(wp), allocatable :: xb(:), yb(:), xe(:), ye(:)
        real(wp) :: x_cross
        integer :: i, k

        t = crossing_fraction(y_begin, y_end, y_line)
        allocate (source(size(t) + count(t >= 0.0_wp)))
        allocate (xb(size(source)), yb(size(source)), xe(size(source)), ye(size(source)))
        k = 0
        do i = 1, size(t)
            k = k + 1
            source(k) = i
            xb(k) = x_begin(i)
            yb(k) = y_begin(i)
            xe(k) = x_end(i)
            ye(k) = y_end(i)
            if (t(i) < 0.0_wp) cycle
            x_cross = x_begin(i) + t(i) * (x_end(i) - x_begin(i))
            xe(k) = x_cross
            ye(k) = y_line
            k = k + 1
            source(k) = i
            xb(k) = x_cross
            yb(k) = y_line
            xe(k) = x_end(i)
            ye(k) = y_end(i)
        end do
        call move_alloc(xb, x_begin)
        call move_alloc(yb, y_begin)
        call move_alloc(xe, x_end)
        call move_alloc(ye, y_end)
    end subroutine split_at_height

end module ddc_mesh_polyline
