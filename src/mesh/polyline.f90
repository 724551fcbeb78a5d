!> Elements along a polyline: equal elements on each segment, vertex to vertex.
!>
!> Independent of any input format: the namelist reader and the TWODD deck reader both
!> call it for their segments.
module ddc_mesh_polyline
    use ddc_kinds, only: wp
    implicit none
    private

    public :: polyline_elements, expand_per_segment

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

end module ddc_mesh_polyline
