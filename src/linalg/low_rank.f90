!> Low-rank blocks of a linear map from pairs of values to pairs (ddc_linalg_block_rows): a
!> block of rows and columns whose entries are smooth in both (the field of sources far from
!> its receivers) held as U V^T, found by adaptive cross approximation (Bebendorf 2000:
!> partial pivoting, one row and one column of the block a rank) and checked: where the
!> caller has the whole block, by its products with probes; where it computes entries on
!> demand (pair_entries), by rows and columns sampled from the block.
module ddc_linalg_low_rank
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    implicit none
    private

    public :: low_rank_block, approximate, add_low_rank_times, pair_entries, approximate_entries

    !> Probes of the remainder's check
    integer, parameter :: probe_count = 8
    !> Pairs of rows and pairs of columns sampled by the remainder's check on demand
    integer, parameter :: sample_pairs = 4

    !> Rows and columns of a map of pairs (their places in y and x of add_low_rank_times) and
    !> the block's entries U V^T: U shape (2 rows, rank), V shape (2 columns, rank); the pair
    !> of a row or column is two consecutive entries
    type :: low_rank_block
        integer, allocatable :: row(:), column(:)
        real(wp), allocatable :: u(:, :), v(:, :)
    end type low_rank_block

    !> A block whose entries are computed on demand, two rows or two columns at a time (a
    !> receiver's two tractions, a source's two DDs); it may keep work for later pairs.
    type, abstract :: pair_entries
    contains
        !> Rows 2 i - 1 and 2 i, shape (2, columns)
        procedure(pair_of_lines), deferred :: row_pair
        !> Columns 2 i - 1 and 2 i, shape (rows, 2)
        procedure(pair_of_lines), deferred :: column_pair
    end type pair_entries

    abstract interface
        subroutine pair_of_lines(this, i, values)
            import :: pair_entries, wp
            implicit none
            class(pair_entries), intent(inout) :: this
            integer, intent(in) :: i
            real(wp), intent(out) :: values(:, :)
        end subroutine pair_of_lines
    end interface

    !> The pairs of rows or of columns of a pair_entries block computed so far.
    type :: pair_cache
        !> Each pair's slot (0: not computed), shape (pairs)
        integer, allocatable :: slot(:)
        !> The pairs computed, shape (length, 2, slots)
        real(wp), allocatable :: values(:, :, :)
        integer :: count = 0
    end type pair_cache

contains

    !> U V^T within `tolerance` of the dense matrix a in the Frobenius norm, relative to a's:
    !> cross approximation until its own estimate of the remainder is below it, then the
    !> remainder checked by its products with probes; where it is not below, the cross
    !> approximation goes on from the row where they are largest. rank = min(m, n) at most
    !> (then exact).
    subroutine approximate(a, tolerance, u, v)
        !> The block, shape (m, n)
        real(wp), intent(in) :: a(:, :)
        !> Relative tolerance [-]
        real(wp), intent(in) :: tolerance
        !> The factors, shape (m, rank) and (n, rank)
        real(wp), allocatable, intent(out) :: u(:, :), v(:, :)
        real(wp), allocatable :: uu(:, :), vv(:, :), row(:), column(:)
        logical, allocatable :: used(:)
        real(wp) :: a_norm, approximation_norm2, step_norm, pivot
        integer :: m, n, rank, i, j
        logical :: checked

        m = size(a, 1)
        n = size(a, 2)
        allocate (uu(m, min(m, n)), vv(n, min(m, n)))
        allocate (used(m), source=.false.)
        ! (not norm2: its scaling against overflow costs a division an entry)
        a_norm = sqrt(sum(a**2))
        rank = 0
        approximation_norm2 = 0.0_wp
        i = maxloc(sum(abs(a), 2), 1)
        do while (a_norm > 0.0_wp .and. rank < min(m, n))
            row = a(i, :) - matmul(vv(:, :rank), uu(i, :rank))
            used(i) = .true.
            j = maxloc(abs(row), 1)
            pivot = row(j)
            if (pivot == 0.0_wp) then
                ! The row is in the approximation already: another unused one.
                if (all(used)) exit
                i = findloc(used, .false., 1)
                cycle
            end if
            column = a(:, j) - matmul(uu(:, :rank), vv(j, :rank))
            call add_cross(uu, vv, rank, column, row / pivot, approximation_norm2, step_norm)
            checked = .false.
            if (step_norm <= tolerance * sqrt(max(approximation_norm2, 0.0_wp))) then
                call check_remainder(checked, i)
                if (checked) exit
            else
                i = maxloc(abs(uu(:, rank)), 1, mask=.not. used)
                if (i == 0) i = maxloc(abs(uu(:, rank)), 1)
            end if
        end do
        u = uu(:, :rank)
        v = vv(:, :rank)

    contains

        !> Whether the remainder R is within the tolerance, from its products with
        !> probe_count fixed vectors of +-1 w (the mean of |R w|^2 is |R|_F^2), and the row
        !> where they are largest.
        subroutine check_remainder(within, largest)
            logical, intent(out) :: within
            integer, intent(out) :: largest
            real(wp) :: probes(n, probe_count), product(m, probe_count)
            real(wp) :: projected(rank, probe_count)
            integer(int64) :: state
            integer :: k, p

            state = 12345_int64
            do p = 1, probe_count
                do k = 1, n
                    state = modulo(1103515245_int64 * state + 12345_int64, 2147483648_int64)
                    probes(k, p) = merge(1.0_wp, -1.0_wp, state >= 1073741824_int64)
                end do
            end do
            projected = matmul(transpose(vv(:, :rank)), probes)
            product = matmul(a, probes) - matmul(uu(:, :rank), projected)
            within = sqrt(sum(product**2) / probe_count) <= tolerance * a_norm
            largest = maxloc(sum(abs(product), 2), 1)
        end subroutine check_remainder
    end subroutine approximate

    !> y(:, block%row) += U V^T x(:, block%column), x and y pairs, shape (2, :).
    pure subroutine add_low_rank_times(block, x, y)
        type(low_rank_block), intent(in) :: block
        real(wp), intent(in) :: x(:, :)
        real(wp), intent(inout) :: y(:, :)
        real(wp) :: w(size(block%u, 2))
        real(wp) :: product(size(block%u, 1))

        if (size(w) == 0) return
        w = matmul(reshape(x(:, block%column), [size(block%v, 1)]), block%v)
        product = matmul(block%u, w)
        y(:, block%row) = y(:, block%row) + reshape(product, [2, size(block%row)])
    end subroutine add_low_rank_times

    !> U V^T within `tolerance` of the block `entries` of m x n entries (m and n even) in
    !> the Frobenius norm, relative to the approximation's: cross approximation from the
    !> rows and columns it asks for, then the remainder checked on sample_pairs pairs of
    !> rows and of columns spread over the block (their mean square scaled to the block);
    !> where it is not within, the cross approximation goes on from the sampled row where
    !> it is largest. Not found (u and v not allocated) where the rank reaches the size at
    !> which U and V hold as many entries as the block.
    subroutine approximate_entries(entries, m, n, tolerance, u, v)
        !> The block (it may keep what it computes for the pairs it is asked for next)
        class(pair_entries), intent(inout) :: entries
        integer, intent(in) :: m, n
        !> Relative tolerance [-]
        real(wp), intent(in) :: tolerance
        !> The factors, shape (m, rank) and (n, rank); not allocated where not found
        real(wp), allocatable, intent(out) :: u(:, :), v(:, :)
        type(pair_cache) :: rows, columns
        real(wp), allocatable :: uu(:, :), vv(:, :), row(:), column(:)
        logical :: used(m)
        real(wp) :: approximation_norm2, step_norm, pivot
        integer :: rank, max_rank, i, j
        logical :: within

        max_rank = int(int(m, int64) * n / (m + n))
        allocate (uu(m, min(max_rank, 16)), vv(n, min(max_rank, 16)))
        allocate (rows%slot(m / 2), columns%slot(n / 2), source=0)
        used = .false.
        rank = 0
        approximation_norm2 = 0.0_wp
        within = .false.
        i = 2 * ((m / 2 + 1) / 2) - 1
        do while (rank < max_rank)
            row = line_of(rows, i, n, .true.) - matmul(vv(:, :rank), uu(i, :rank))
            used(i) = .true.
            j = maxloc(abs(row), 1)
            pivot = row(j)
            if (pivot == 0.0_wp) then
                ! The row is in the approximation already: check the rest.
                call check_remainder(within, i)
                if (within) exit
                cycle
            end if
            column = line_of(columns, j, m, .false.) - matmul(uu(:, :rank), vv(j, :rank))
            if (rank == size(uu, 2)) call widen()
            call add_cross(uu, vv, rank, column, row / pivot, approximation_norm2, step_norm)
            if (step_norm <= tolerance * sqrt(max(approximation_norm2, 0.0_wp))) then
                call check_remainder(within, i)
                if (within) exit
            else
                i = maxloc(abs(uu(:, rank)), 1, mask=.not. used)
                if (i == 0) then
                    call check_remainder(within, i)
                    if (within) exit
                end if
            end if
        end do
        if (.not. within) return
        u = uu(:, :rank)
        v = vv(:, :rank)

    contains

        !> Room in U and V for twice the rank (at most max_rank): they grow as it does.
        subroutine widen()
            real(wp), allocatable :: wider(:, :)

            allocate (wider(m, min(max_rank, 2 * rank)))
            wider(:, :rank) = uu(:, :rank)
            call move_alloc(wider, uu)
            allocate (wider(n, min(max_rank, 2 * rank)))
            wider(:, :rank) = vv(:, :rank)
            call move_alloc(wider, vv)
        end subroutine widen

        !> Row (is_row) or column i of the block, of `length` entries, from its pair in the
        !> cache (computed there where it is not yet).
        function line_of(cache, i, length, is_row) result(values)
            type(pair_cache), intent(inout) :: cache
            integer, intent(in) :: i, length
            logical, intent(in) :: is_row
            real(wp) :: values(length)

            call ensure(cache, (i + 1) / 2, length, is_row)
            values = cache%values(:, 2 - mod(i, 2), cache%slot((i + 1) / 2))
        end function line_of

        !> Pair p of rows (is_row) or columns computed into the cache, where it is not yet.
        subroutine ensure(cache, p, length, is_row)
            type(pair_cache), intent(inout) :: cache
            integer, intent(in) :: p, length
            logical, intent(in) :: is_row
            real(wp), allocatable :: wider(:, :, :)
            real(wp) :: pair(2, length)

            if (cache%slot(p) > 0) return
            if (.not. allocated(cache%values)) allocate (cache%values(length, 2, 8))
            if (cache%count == size(cache%values, 3)) then
                allocate (wider(length, 2, 2 * cache%count))
                wider(:, :, :cache%count) = cache%values
                call move_alloc(wider, cache%values)
            end if
            cache%count = cache%count + 1
            cache%slot(p) = cache%count
            if (is_row) then
                call entries%row_pair(p, pair)
                cache%values(:, :, cache%count) = transpose(pair)
            else
                call entries%column_pair(p, cache%values(:, :, cache%count))
            end if
        end subroutine ensure

        !> Whether the remainder R is within the tolerance on the sampled rows and columns,
        !> each set's mean square scaled to the whole block, and the row to go on from (the
        !> sampled row where R is largest, or the row of the largest entry of a sampled
        !> column; 0 where R vanishes on them).
        subroutine check_remainder(within, next)
            logical, intent(out) :: within
            integer, intent(out) :: next
            real(wp) :: residual(max(m, n)), row_sum, column_sum, largest, bound
            integer :: k, p, q

            row_sum = 0.0_wp
            column_sum = 0.0_wp
            largest = 0.0_wp
            next = 0
            do k = 1, min(sample_pairs, m / 2)
                p = sample(k, m / 2)
                do q = 2 * p - 1, 2 * p
                    residual(:n) = line_of(rows, q, n, .true.) - &
                                   matmul(vv(:, :rank), uu(q, :rank))
                    row_sum = row_sum + sum(residual(:n)**2)
                    if (.not. used(q) .and. maxval(abs(residual(:n))) > largest) then
                        largest = maxval(abs(residual(:n)))
                        next = q
                    end if
                end do
            end do
            do k = 1, min(sample_pairs, n / 2)
                p = sample(k, n / 2)
                do q = 2 * p - 1, 2 * p
                    residual(:m) = line_of(columns, q, m, .false.) - &
                                   matmul(uu(:, :rank), vv(q, :rank))
                    column_sum = column_sum + sum(residual(:m)**2)
                    if (maxval(abs(residual(:m)), mask=.not. used) > largest) then
                        largest = maxval(abs(residual(:m)), mask=.not. used)
                        next = maxloc(abs(residual(:m)), 1, mask=.not. used)
                    end if
                end do
            end do
            bound = tolerance**2 * max(approximation_norm2, 0.0_wp)
            within = row_sum * real(m, wp) / (2 * min(sample_pairs, m / 2)) <= bound .and. &
                     column_sum * real(n, wp) / (2 * min(sample_pairs, n / 2)) <= bound
            if (.not. within .and. next == 0) next = findloc(used, .false., 1)
            if (.not. within .and. next == 0) within = .true.
        end subroutine check_remainder
    end subroutine approximate_entries

    !> Append the cross (column, row) as rank `rank` + 1 of U and V, and its share to the
    !> approximation's squared Frobenius norm; step_norm: the cross's own norm.
    pure subroutine add_cross(uu, vv, rank, column, row, norm2_sum, step_norm)
        real(wp), intent(inout) :: uu(:, :), vv(:, :)
        integer, intent(inout) :: rank
        real(wp), intent(in) :: column(:), row(:)
        real(wp), intent(inout) :: norm2_sum
        real(wp), intent(out) :: step_norm

        rank = rank + 1
        uu(:, rank) = column
        vv(:, rank) = row
        step_norm = sqrt(sum(uu(:, rank)**2) * sum(vv(:, rank)**2))
        norm2_sum = norm2_sum + step_norm**2 + 2.0_wp * &
            sum(matmul(uu(:, rank), uu(:, :rank - 1)) * matmul(vv(:, rank), vv(:, :rank - 1)))
    end subroutine add_cross

    !> The k-th of sample_pairs pairs among `pairs`: one in each of sample_pairs equal
    !> stretches, at a fixed pseudo-random place in it.
    pure integer function sample(k, pairs)
        integer, intent(in) :: k, pairs
        integer, parameter :: place(sample_pairs) = [37, 71, 13, 59]
        integer :: stretch

        stretch = max(1, pairs / sample_pairs)
        sample = min(pairs, (k - 1) * stretch + 1 + mod(place(k), stretch))
    end function sample

end module ddc_linalg_low_rank
