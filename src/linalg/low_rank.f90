!> Low-rank blocks of a linear map from pairs of values to pairs (ddc_linalg_block_rows): a
!> block of rows and columns whose entries are smooth in both (the field of sources far from
!> its receivers) held as U V^T, found by adaptive cross approximation (Bebendorf 2000:
!> partial pivoting, one row and one column of the block a rank) and checked by products of
!> the whole block, which the caller has, with probes.
module ddc_linalg_low_rank
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    implicit none
    private

    public :: low_rank_block, approximate, add_low_rank_times

    !> Probes of the remainder's check
    integer, parameter :: probe_count = 8

    !> Rows and columns of a map of pairs (their places in y and x of add_low_rank_times) and
    !> the block's entries U V^T: U shape (2 rows, rank), V shape (2 columns, rank); the pair
    !> of a row or column is two consecutive entries
    type :: low_rank_block
        integer, allocatable :: row(:), column(:)
        real(wp), allocatable :: u(:, :), v(:, :)
    end type low_rank_block

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
            rank = rank + 1
            uu(:, rank) = column
            vv(:, rank) = row / pivot
            step_norm = sqrt(sum(uu(:, rank)**2) * sum(vv(:, rank)**2))
            approximation_norm2 = approximation_norm2 + step_norm**2 + 2.0_wp * &
                sum(matmul(uu(:, rank), uu(:, :rank - 1)) * matmul(vv(:, rank), vv(:, :rank - 1)))
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

end module ddc_linalg_low_rank
