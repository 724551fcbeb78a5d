!> Which element ends meet: the ends of a set of elements grouped by the point they share
!> (within a tolerance of the shorter element's length), and the elements whose interior an
!> end lies on (a T-junction). Pressure that flows along fractures passes where ends meet.
module ddc_mesh_ends
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, element_end
    use ddc_sorting, only: sorted_order, first_at_least
    use ddc_mesh_segments, only: point_segment_distance
    implicit none
    private

    public :: end_groups, end_on_interior, meeting_tolerance
    public :: elements_at_point

    !> Ends closer than this fraction of the shorter element's length meet
    real(wp), parameter :: meeting_tolerance = 1.0e-8_wp

contains

    !> The group of every element end: ends that meet (directly or through other ends) share
    !> a group number, an end that meets no other has a group of its own. Groups are
    !> numbered 1.. in order of their first end (begin of element 1, end of element 1, ...).
    pure subroutine end_groups(elements, group, count)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Group of end (side, i), shape (2, n)
        integer, intent(out) :: group(:, :)
        !> Number of groups
        integer, intent(out) :: count
        real(wp) :: x(2 * elements%n), y(2 * elements%n), length(2 * elements%n)
        real(wp) :: sorted_x(2 * elements%n)
        integer :: order(2 * elements%n), root(2 * elements%n), label(2 * elements%n)
        real(wp) :: window
        integer :: n, k, a, b, first, ra, rb

        n = elements%n
        x(1:n) = elements%x_begin
        x(n + 1:) = elements%x_end
        y(1:n) = elements%y_begin
        y(n + 1:) = elements%y_end
        length(1:n) = 2.0_wp * elements%half_length
        length(n + 1:) = length(1:n)
        order = sorted_order(x)
        sorted_x = x(order)
        root = [(k, k = 1, 2 * n)]
        window = 0.0_wp
        if (n > 0) window = meeting_tolerance * maxval(length)
        do k = 1, 2 * n
            a = order(k)
            first = first_at_least(sorted_x, x(a) - window)
            do b = first, k - 1
                if (.not. meet(a, order(b))) cycle
                ! Join the two trees: the larger root points at the smaller.
                ra = find(a)
                rb = find(order(b))
                if (ra /= rb) root(max(ra, rb)) = min(ra, rb)
            end do
        end do
        label = 0
        count = 0
        do k = 1, 2 * n
            a = find(k)
            if (label(a) == 0) then
                count = count + 1
                label(a) = count
            end if
            group(1 + (k - 1) / n, modulo(k - 1, n) + 1) = label(a)
        end do

    contains

        pure logical function meet(p, q)
            integer, intent(in) :: p, q

            meet = hypot(x(p) - x(q), y(p) - y(q)) <= meeting_tolerance * &
                min(length(p), length(q))
        end function meet

        pure integer function find(p) result(r)
            integer, intent(in) :: p

            r = p
            do while (root(r) /= r)
                r = root(r)
            end do
        end function find

    end subroutine end_groups

    !> The element (other than i) on whose interior end `side` of element i lies, and the
    !> distance of the end from that element's midpoint; 0 when it lies on none.
    pure subroutine end_on_interior(elements, i, side, host, distance)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Element and end (1 begin, 2 end)
        integer, intent(in) :: i, side
        !> The element whose interior holds the end (0: none)
        integer, intent(out) :: host
        !> Distance of the end from the host's midpoint [length unit]
        real(wp), intent(out) :: distance
        real(wp) :: x, y, tol
        integer :: j

        call element_end(elements, i, side, x, y)
        host = 0
        distance = 0.0_wp
        do j = 1, elements%n
            if (j == i) cycle
            tol = meeting_tolerance * 2.0_wp * min(elements%half_length(i), &
                                                   elements%half_length(j))
            if (point_segment_distance(x, y, elements%x_begin(j), elements%y_begin(j), &
                                       elements%x_end(j), elements%y_end(j)) > tol) cycle
            ! At an end of j the ends meet instead.
            if (hypot(x - elements%x_begin(j), y - elements%y_begin(j)) <= tol .or. &
                hypot(x - elements%x_end(j), y - elements%y_end(j)) <= tol) cycle
            host = j
            distance = hypot(x - elements%x_mid(j), y - elements%y_mid(j))
            return
        end do
    end subroutine end_on_interior

    !> The elements of a fracture that hold a point (within meeting_tolerance of their
    !> length): one, or two where the point is an end they share; none when it is off the
    !> fracture.
    pure function elements_at_point(elements, fracture_id, x, y) result(found)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> The fracture (1-based)
        integer, intent(in) :: fracture_id
        !> The point [length unit]
        real(wp), intent(in) :: x, y
        !> The elements holding it, in index order
        integer, allocatable :: found(:)
        logical :: holds(elements%n)
        integer :: j

        do j = 1, elements%n
            holds(j) = elements%fracture_id(j) == fracture_id
            if (holds(j)) holds(j) = point_segment_distance(x, y, elements%x_begin(j), &
                elements%y_begin(j), elements%x_end(j), elements%y_end(j)) <= &
                meeting_tolerance * 2.0_wp * elements%half_length(j)
        end do
        found = pack([(j, j = 1, elements%n)], holds)
    end function elements_at_point

end module ddc_mesh_ends
