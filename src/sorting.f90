!> Sorting and searching: the order that puts keys in ascending order (heap sort,
!> O(n log n), no recursion) and the first of sorted keys at or above a value (bisection).
module ddc_sorting
    use ddc_kinds, only: wp
    implicit none
    private

    public :: sorted_order, first_at_least

contains

    !> Indices that sort keys in ascending order (heap sort).
    pure function sorted_order(keys) result(order)
        !> The keys, shape (n)
        real(wp), intent(in) :: keys(:)
        !> keys(order) is ascending, shape (n)
        integer :: order(size(keys))
        integer :: n, i, last, tmp

        n = size(keys)
        order = [(i, i = 1, n)]
        do i = n / 2, 1, -1
            call sift_down(i, n)
        end do
        do last = n, 2, -1
            tmp = order(1)
            order(1) = order(last)
            order(last) = tmp
            call sift_down(1, last - 1)
        end do

    contains

        pure subroutine sift_down(start, end)
            integer, intent(in) :: start, end
            integer :: root, child, swap

            root = start
            do while (2 * root <= end)
                child = 2 * root
                if (child < end) then
                    if (keys(order(child + 1)) > keys(order(child))) child = child + 1
                end if
                if (keys(order(child)) <= keys(order(root))) return
                swap = order(root)
                order(root) = order(child)
                order(child) = swap
                root = child
            end do
        end subroutine sift_down

    end function sorted_order

    !> The first position k of ascending keys with keys(k) >= value (size + 1 if none).
    pure integer function first_at_least(keys, value)
        !> Keys in ascending order, shape (n)
        real(wp), intent(in) :: keys(:)
        !> The value looked for
        real(wp), intent(in) :: value
        integer :: lo, hi, mid

        lo = 1
        hi = size(keys) + 1
        do while (lo < hi)
            mid = (lo + hi) / 2
            if (keys(mid) < value) then
                lo = mid + 1
            else
                hi = mid
            end if
        end do
        first_at_least = lo
    end function first_at_least

end module ddc_sorting
