!> Crack tips and their stress intensity factors (docs/theory/tips.md#k-from-the-tip-element).
module ddc_post_tips
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, symmetry_x, symmetry_y, symmetry_both, &
        domain_half_plane, element_end
    use ddc_model_results, only: tip_set
    use ddc_model_medium, only: elastic_medium, elastic_material, element_material
    use ddc_sorting, only: sorted_order, first_at_least
    implicit none
    private

    public :: find_tips, stress_intensity, tip_chain, end_neighbours, end_on_mirror, end_turn
    public :: walk_tip_zone, zone_size, max_zone

    !> End points closer than this fraction of the shorter element's length are shared.
    real(wp), parameter :: shared_end_tolerance = 1.0e-8_wp
    !> An element of the tip zone longer or shorter than the tip element (or the tip
    !> element's neighbour) by more than this fraction makes the tip graded
    real(wp), parameter :: graded_tolerance = 1.0e-2_wp
    !> The tip zone (docs/theory/tips.md#k-from-the-tip-element): the elements from the tip
    !> inward whose start lies within zone_reach lengths of the largest element so far, at
    !> most max_zone of them
    real(wp), parameter :: zone_reach = 8.0_wp
    integer, parameter :: max_zone = 64
    !> Relative margin that keeps a start at the zone's bound (a zone of equal elements) from
    !> depending on round-off
    real(wp), parameter :: zone_tie_tolerance = 1.0e-6_wp
    !> A zone whose direction turns more than this [cos] is not straight (10 degrees)
    real(wp), parameter :: straight_cos = 0.98480775301220806_wp

    !> The ends of every element sorted by x, for finding the elements at a point.
    type :: end_index
        !> x of the ends in ascending order, shape (2n) [length unit]
        real(wp), allocatable :: x(:)
        !> End number of each: k <= n is the begin of element k, else the end of k - n,
        !> shape (2n)
        integer, allocatable :: end(:)
    end type end_index

contains

    !> The sorted ends of the elements.
    pure function index_ends(elements) result(index)
        type(element_set), intent(in) :: elements
        type(end_index) :: index
        real(wp) :: x(2 * elements%n)

        x(1:elements%n) = elements%x_begin
        x(elements%n + 1:) = elements%x_end
        index%end = sorted_order(x)
        index%x = x(index%end)
    end function index_ends

    !> True when end `side` (1 begin, 2 end) of element i coincides with an end of another
    !> element, lies on a symmetry line (where it meets its own image) or, in a half-plane,
    !> on the free surface y = 0 (a crack mouth:
    !> docs/theory/tips.md#what-counts-as-a-tip).
    pure logical function end_is_shared(elements, index, i, side)
        type(element_set), intent(in) :: elements
        type(end_index), intent(in) :: index
        integer, intent(in) :: i, side
        real(wp) :: x, y

        call element_end(elements, i, side, x, y)
        end_is_shared = .true.
        if (end_on_mirror(elements, i, side)) return
        if (elements%domain == domain_half_plane .and. &
            abs(y) <= shared_end_tolerance * 2.0_wp * elements%half_length(i)) return
        end_is_shared = element_at_end(elements, index, i, side) > 0
    end function end_is_shared

    !> True when end `side` (1 begin, 2 end) of element i lies on a symmetry line, where the
    !> element meets its own image.
    pure logical function end_on_mirror(elements, i, side)
        type(element_set), intent(in) :: elements
        integer, intent(in) :: i, side
        real(wp) :: x, y, tol

        call element_end(elements, i, side, x, y)
        tol = shared_end_tolerance * 2.0_wp * elements%half_length(i)
        associate (sym => elements%symmetry)
            end_on_mirror = ((sym%kind == symmetry_x .or. sym%kind == symmetry_both) .and. &
                             abs(x - sym%xsym) <= tol) .or. &
                            ((sym%kind == symmetry_y .or. sym%kind == symmetry_both) .and. &
                             abs(y - sym%ysym) <= tol)
        end associate
    end function end_on_mirror

    !> The lowest-numbered other element with an end at end `side` (1 begin, 2 end) of
    !> element i; 0 if none.
    pure integer function element_at_end(elements, index, i, side)
        type(element_set), intent(in) :: elements
        type(end_index), intent(in) :: index
        integer, intent(in) :: i, side
        integer :: count, first_side

        call elements_at_end(elements, index, i, side, element_at_end, first_side, count)
    end function element_at_end

    !> The other elements with an end at end `side` (1 begin, 2 end) of element i: the
    !> lowest-numbered (0 if none), which of its ends is there, and how many there are.
    !> Only the ends within the tolerance in x are looked at.
    pure subroutine elements_at_end(elements, index, i, side, first, first_side, count)
        type(element_set), intent(in) :: elements
        type(end_index), intent(in) :: index
        integer, intent(in) :: i, side
        integer, intent(out) :: first, first_side, count
        real(wp) :: x, y, xe, ye, tol, window
        integer :: k, e, j, n

        n = elements%n
        call element_end(elements, i, side, x, y)
        ! Every pair tolerance is at most half this window (it takes the shorter element).
        window = shared_end_tolerance * 4.0_wp * elements%half_length(i)
        first = 0
        first_side = 0
        count = 0
        do k = first_at_least(index%x, x - window), size(index%x)
            if (index%x(k) > x + window) exit
            e = index%end(k)
            j = modulo(e - 1, n) + 1
            if (j == i) cycle
            call element_end(elements, j, merge(1, 2, e <= n), xe, ye)
            tol = shared_end_tolerance * 2.0_wp * &
                  min(elements%half_length(i), elements%half_length(j))
            if (hypot(xe - x, ye - y) > tol) cycle
            count = count + 1
            if (first == 0 .or. j < first) then
                first = j
                first_side = merge(1, 2, e <= n)
            end if
        end do
    end subroutine elements_at_end

    !> For every element end, the one other element that shares it (0 where none or more
    !> than one do) and which end of that element it is (1 begin, 2 end).
    pure subroutine end_neighbours(elements, neighbour, neighbour_side)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Neighbour and its end at each end (1 begin, 2 end) of each element, shape (2, n)
        integer, intent(out) :: neighbour(:, :), neighbour_side(:, :)
        type(end_index) :: index
        integer :: i, side, count

        index = index_ends(elements)
        do i = 1, elements%n
            do side = 1, 2
                call elements_at_end(elements, index, i, side, neighbour(side, i), &
                                     neighbour_side(side, i), count)
                if (count /= 1) neighbour(side, i) = 0
            end do
        end do
    end subroutine end_neighbours

    !> The angle [rad] by which the fracture turns from element i, left by its end `side`,
    !> into element j, entered by its end j_side (positive counter-clockwise).
    pure real(wp) function end_turn(elements, i, side, j, j_side)
        type(element_set), intent(in) :: elements
        integer, intent(in) :: i, side, j, j_side
        real(wp) :: a(2), b(2)

        a = [elements%cos_beta(i), elements%sin_beta(i)] * merge(1.0_wp, -1.0_wp, side == 2)
        b = [elements%cos_beta(j), elements%sin_beta(j)] * merge(1.0_wp, -1.0_wp, j_side == 1)
        end_turn = atan2(a(1) * b(2) - a(2) * b(1), dot_product(a, b))
    end function end_turn

    !> The chain of elements from a tip inward: the tip element, then each element that
    !> alone shares the previous one's inner end, up to a junction, the fracture's other
    !> end or a loop. Each element's end nearer the tip is recorded (1 begin, 2 end).
    pure subroutine tip_chain(elements, element, side, chain, near_side)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Tip element and the end at the tip (1 begin, 2 end)
        integer, intent(in) :: element, side
        !> Elements of the chain from the tip, and the end of each toward the tip
        integer, allocatable, intent(out) :: chain(:), near_side(:)
        type(end_index) :: index
        integer :: path(elements%n), sides(elements%n), m, next, next_side, count
        logical :: on_path(elements%n)

        index = index_ends(elements)
        m = 1
        path(1) = element
        sides(1) = side
        on_path = .false.
        on_path(element) = .true.
        do while (m < elements%n)
            call elements_at_end(elements, index, path(m), 3 - sides(m), next, next_side, &
                                 count)
            if (count /= 1) exit
            ! A closed loop ends where it began (marked: a search of the path would be
            ! quadratic in a long chain).
            if (on_path(next)) exit
            m = m + 1
            path(m) = next
            sides(m) = next_side
            on_path(next) = .true.
        end do
        chain = path(:m)
        near_side = sides(:m)
    end subroutine tip_chain

    !> Tips (element ends shared with no other element) with K_I and K_II from the tip
    !> element's DDs: K = -G D / (2 (1 - nu) sqrt(h)), h the tip element's half-length, G
    !> and nu those of the tip element's material.
    subroutine find_tips(medium, ds, dn, tips)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> The tips found, in element order (begin before end)
        type(tip_set), intent(out) :: tips

        call locate_tips(medium%elements, tips)
        call stress_intensity(medium, tips%element, ds, dn, tips%k1, tips%k2)
        tips%k_method = 'tip_element'
    end subroutine find_tips

    !> The tips of the elements, K allocated.
    subroutine locate_tips(elements, tips)
        type(element_set), intent(in) :: elements
        type(tip_set), intent(out) :: tips
        logical :: is_tip(2, elements%n)
        type(end_index) :: index
        integer :: i, side, k, neighbour
        real(wp), allocatable :: lengths(:)
        logical, allocatable :: straight(:)

        index = index_ends(elements)
        !$omp parallel do default(none) private(i, side) shared(elements, index, is_tip)
        do i = 1, elements%n
            do side = 1, 2
                is_tip(side, i) = .not. end_is_shared(elements, index, i, side)
            end do
        end do
        !$omp end parallel do

        tips%n = count(is_tip)
        allocate (tips%x(tips%n), tips%y(tips%n), tips%fracture_id(tips%n), &
                  tips%element(tips%n), tips%k1(tips%n), tips%k2(tips%n), tips%graded(tips%n), &
                  tips%side(tips%n))
        k = 0
        do i = 1, elements%n
            do side = 1, 2
                if (.not. is_tip(side, i)) cycle
                k = k + 1
                if (side == 1) then
                    tips%x(k) = elements%x_begin(i)
                    tips%y(k) = elements%y_begin(i)
                else
                    tips%x(k) = elements%x_end(i)
                    tips%y(k) = elements%y_end(i)
                end if
                tips%fracture_id(k) = elements%fracture_id(i)
                tips%element(k) = i
                tips%side(k) = side
                ! The neighbour shares the tip element's other end; the zone runs on along the
                ! fracture (a change of length several elements in changes K too).
                neighbour = element_at_end(elements, index, i, 3 - side)
                tips%graded(k) = 0
                if (neighbour > 0) then
                    if (abs(elements%half_length(neighbour) - elements%half_length(i)) > &
                        graded_tolerance * elements%half_length(i)) tips%graded(k) = 1
                end if
                call walk_tip_zone(elements, i, side, lengths, straight)
                if (any(abs(lengths(1:zone_size(lengths)) - lengths(1)) > &
                        graded_tolerance * lengths(1))) tips%graded(k) = 1
            end do
        end do
    end subroutine locate_tips

    !> K_I and K_II of tips from their elements' DDs: K = -G D / (2 (1 - nu) sqrt(h)), h the
    !> tip element's half-length, G and nu those of its material.
    pure subroutine stress_intensity(medium, element, ds, dn, k1, k2)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Tip element of each tip, shape (tips)
        integer, intent(in) :: element(:)
        !> Displacement discontinuities of every element [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Stress intensity factors [stress unit * length unit**0.5], shape (tips)
        real(wp), intent(out) :: k1(:), k2(:)
        type(elastic_material) :: material
        real(wp) :: factor
        integer :: k, i

        do k = 1, size(element)
            i = element(k)
            material = element_material(medium, i)
            factor = -material%shear_modulus / (2.0_wp * (1.0_wp - material%poissons_ratio) * &
                                                sqrt(medium%elements%half_length(i)))
            ! + 0 turns the -0 of an unloaded mode into 0 for printing.
            k1(k) = factor * dn(i) + 0.0_wp
            k2(k) = factor * ds(i) + 0.0_wp
        end do
    end subroutine stress_intensity

    !> The lengths of the elements from a tip inward along its fracture (at most max_zone,
    !> while consecutive elements share a vertex), and whether each keeps the tip element's
    !> direction within 10 degrees.
    pure subroutine walk_tip_zone(elements, element, side, lengths, straight)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Tip element and its tip end (tip_set%side: 1 begin, 2 end)
        integer, intent(in) :: element, side
        !> Lengths [length unit], from the tip element inward
        real(wp), allocatable, intent(out) :: lengths(:)
        !> Whether each keeps the tip element's direction
        logical, allocatable, intent(out) :: straight(:)
        integer :: i, next, step

        associate (e => elements)
            ! At an end tip the fracture runs on through lower indices, at a begin tip higher.
            step = merge(-1, 1, side == 2)
            allocate (lengths(0), straight(0))
            i = element
            do
                lengths = [lengths, 2.0_wp * e%half_length(i)]
                straight = [straight, e%cos_beta(i) * e%cos_beta(element) + &
                            e%sin_beta(i) * e%sin_beta(element) >= straight_cos]
                if (size(lengths) == max_zone) exit
                next = i + step
                if (next < 1 .or. next > e%n) exit
                if (e%fracture_id(next) /= e%fracture_id(i)) exit
                if (.not. joined(i, next)) exit
                i = next
            end do
        end associate

    contains

        !> Element a's inner end is element b's outer end (the fracture is one polyline).
        pure logical function joined(a, b)
            integer, intent(in) :: a, b
            real(wp) :: tolerance

            associate (e => elements)
                tolerance = 1.0e-8_wp * (e%half_length(a) + e%half_length(b))
                if (step == -1) then
                    joined = abs(e%x_begin(a) - e%x_end(b)) <= tolerance .and. &
                             abs(e%y_begin(a) - e%y_end(b)) <= tolerance
                else
                    joined = abs(e%x_end(a) - e%x_begin(b)) <= tolerance .and. &
                             abs(e%y_end(a) - e%y_begin(b)) <= tolerance
                end if
            end associate
        end function joined

    end subroutine walk_tip_zone

    !> Number of elements of the zone of lengths l_1 (tip), l_2, ...: up to the last i with
    !> l_1 + ... + l_(i-1) < zone_reach max(l_1 ... l_i) (a start at the bound, as in a zone
    !> of equal elements, counts as beyond it whatever its round-off).
    pure integer function zone_size(lengths)
        !> Lengths of the elements from the tip inward [length unit]
        real(wp), intent(in) :: lengths(:)
        real(wp) :: start, largest
        integer :: i

        zone_size = 1
        start = 0.0_wp
        largest = 0.0_wp
        do i = 1, size(lengths)
            largest = max(largest, lengths(i))
            if (start < (1.0_wp - zone_tie_tolerance) * zone_reach * largest) zone_size = i
            start = start + lengths(i)
        end do
    end function zone_size

end module ddc_post_tips
