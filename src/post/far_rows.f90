!> The far parts of the local K re-solve's kept rows in low rank
!> (docs/theory/tips.md#cost): the zones' load at a zone's nodes from the elements far from
!> it, and the outer correction at the elements far from a zone from its DDs, are the fields
!> of sources far from their receivers, smooth in both, and kept as low-rank blocks
!> (ddc_linalg_low_rank) instead of a block per element in each row.
module ddc_post_far_rows
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set
    use ddc_linalg_block_rows, only: block_row
    use ddc_linalg_low_rank, only: low_rank_block, approximate
    implicit none
    private

    public :: zone_cluster, zone_clusters, far_from, beyond_band, far_block, drop_far, append_near
    public :: far_tolerance

    !> An element is far from a cluster where its nearest point is at least this many of the
    !> cluster's radii from the cluster's centre (the cross approximation's rank then grows
    !> as the logarithm of the tolerance over that of this ratio)
    real(wp), parameter :: far_radii = 3.0_wp
    !> A block's low-rank form is within this of its entries (Frobenius norm, relative): far
    !> below the coupling's tolerance and K's accuracy, above the kernels' own rounding (the
    !> singular values of a far block at 16000 elements level off at 1e-13 to 4e-13 of the
    !> largest, 5e-12 of the block together; 1e-12 took ranks of 150 where 10 serve)
    real(wp), parameter :: far_tolerance = 1.0e-10_wp

    !> Zone elements that touch one another along their fractures.
    type :: zone_cluster
        !> Its zone elements (the re-solve's numbering)
        integer, allocatable :: member(:)
        !> The centre of its elements' ends [length unit] and the radius of the circle about
        !> it that holds them [length unit]
        real(wp) :: centre(2) = 0.0_wp, radius = 0.0_wp
    end type zone_cluster

contains

    !> The clusters of the zone elements `solved` (model numbering): elements whose
    !> midpoints are within the sum of their half-lengths of one another join.
    pure function zone_clusters(elements, solved) result(clusters)
        type(element_set), intent(in) :: elements
        integer, intent(in) :: solved(:)
        type(zone_cluster), allocatable :: clusters(:)
        integer :: root(size(solved)), l, k, c, nc
        real(wp) :: ends(2, 2 * size(solved))

        root = [(l, l = 1, size(solved))]
        associate (e => elements)
            do l = 1, size(solved)
                do k = l + 1, size(solved)
                    if (hypot(e%x_mid(solved(l)) - e%x_mid(solved(k)), &
                              e%y_mid(solved(l)) - e%y_mid(solved(k))) <= &
                        1.001_wp * (e%half_length(solved(l)) + e%half_length(solved(k)))) then
                        call join(root, l, k)
                    end if
                end do
            end do
            do l = 1, size(solved)
                root(l) = find(root, l)
            end do
            nc = count(root == [(l, l = 1, size(solved))])
            allocate (clusters(nc))
            c = 0
            do l = 1, size(solved)
                if (root(l) /= l) cycle
                c = c + 1
                associate (cl => clusters(c))
                    cl%member = pack([(k, k = 1, size(solved))], root == l)
                    ends(1, :2 * size(cl%member)) = [e%x_begin(solved(cl%member)), &
                                                      e%x_end(solved(cl%member))]
                    ends(2, :2 * size(cl%member)) = [e%y_begin(solved(cl%member)), &
                                                      e%y_end(solved(cl%member))]
                    cl%centre = sum(ends(:, :2 * size(cl%member)), 2) / (2 * size(cl%member))
                    cl%radius = maxval(hypot(ends(1, :2 * size(cl%member)) - cl%centre(1), &
                                             ends(2, :2 * size(cl%member)) - cl%centre(2)))
                end associate
            end do
        end associate

    contains

        pure integer function find(root, i)
            integer, intent(in) :: root(:), i

            find = i
            do while (root(find) /= find)
                find = root(find)
            end do
        end function find

        pure subroutine join(root, i, j)
            integer, intent(inout) :: root(:)
            integer, intent(in) :: i, j
            integer :: ri, rj

            ri = find(root, i)
            rj = find(root, j)
            if (ri /= rj) root(max(ri, rj)) = min(ri, rj)
        end subroutine join
    end function zone_clusters

    !> Whether each element is far from the cluster.
    pure function far_from(cluster, elements) result(far)
        type(zone_cluster), intent(in) :: cluster
        type(element_set), intent(in) :: elements
        logical :: far(elements%n)

        far = hypot(elements%x_mid - cluster%centre(1), elements%y_mid - cluster%centre(2)) - &
              elements%half_length >= far_radii * cluster%radius
    end function far_from

    !> Whether each element is more steps along its fracture from the cluster than its reach
    !> and two: beyond the band of neighbours whose recovered DDs its outer correction row
    !> compares (ddc_post_higher_order_k correction_row), whose stencils may end in the
    !> cluster's elements. A row's band ends abruptly: rows within it are not smooth in the
    !> receiver, and stay whole.
    pure function beyond_band(cluster, neighbour, reach, solved) result(beyond)
        type(zone_cluster), intent(in) :: cluster
        !> The neighbour of every element at each end (0: none), shape (2, n)
        integer, intent(in) :: neighbour(:, :)
        !> Each element's reach [elements], shape (n)
        integer, intent(in) :: reach(:)
        !> The zone elements (model numbering)
        integer, intent(in) :: solved(:)
        logical :: beyond(size(reach))
        integer :: steps(size(reach)), queue(size(reach)), head, tail, j, side, next, farthest

        farthest = maxval(reach) + 2
        steps = huge(1)
        tail = size(cluster%member)
        queue(:tail) = solved(cluster%member)
        steps(queue(:tail)) = 0
        head = 1
        do while (head <= tail)
            j = queue(head)
            head = head + 1
            if (steps(j) > farthest) cycle
            do side = 1, 2
                next = neighbour(side, j)
                if (next == 0) cycle
                if (steps(next) <= steps(j) + 1) cycle
                steps(next) = steps(j) + 1
                tail = tail + 1
                queue(tail) = next
            end do
        end do
        beyond = steps > reach + 2
    end function beyond_band

    !> The entries of rows `which` at the columns marked far as one low-rank block, where that
    !> is smaller than they are; the rows are left as they are (drop_far).
    subroutine far_block(rows, which, far, block, found)
        !> Every row of the map
        type(block_row), intent(in) :: rows(:)
        !> The rows of the block
        integer, intent(in) :: which(:)
        !> The columns of the block, shape (columns)
        logical, intent(in) :: far(:)
        type(low_rank_block), intent(out) :: block
        !> Whether the block is smaller than the entries (else it is empty)
        logical, intent(out) :: found
        real(wp), allocatable :: dense(:, :), u(:, :), v(:, :)
        integer, allocatable :: place(:), columns(:)
        logical :: used(size(far))
        integer :: r, e, p, m, n

        found = .false.
        used = .false.
        do r = 1, size(which)
            used(rows(which(r))%column) = .true.
        end do
        columns = pack([(e, e = 1, size(far))], used .and. far)
        m = 2 * size(which)
        n = 2 * size(columns)
        if (n == 0 .or. m == 0) return
        allocate (place(size(far)), source=0)
        place(columns) = [(p, p = 1, size(columns))]
        allocate (dense(m, n), source=0.0_wp)
        do r = 1, size(which)
            call scatter(rows(which(r)), dense(2 * r - 1:2 * r, :))
        end do
        call approximate(dense, far_tolerance, u, v)
        ! As blocks of 2 x 2 with a column index, the entries took 4.5 reals each.
        if (size(u, 2) * (m + n) >= m * n) return
        found = .true.
        block%row = which
        block%column = columns
        call move_alloc(u, block%u)
        call move_alloc(v, block%v)

    contains

        !> The row's entries at the block's columns into its two rows of the dense block.
        pure subroutine scatter(row, pair)
            type(block_row), intent(in) :: row
            real(wp), intent(inout) :: pair(:, :)
            integer :: k, at

            do k = 1, size(row%column)
                at = place(row%column(k))
                if (at > 0) pair(:, 2 * at - 1:2 * at) = row%block(:, :, k)
            end do
        end subroutine scatter
    end subroutine far_block

    !> The rows without the entries the blocks hold (blocks of disjoint columns, rows among
    !> these), each row copied once into arrays of its new size.
    subroutine drop_far(rows, blocks, columns)
        type(block_row), intent(inout) :: rows(:)
        type(low_rank_block), intent(in) :: blocks(:)
        !> The columns of the map
        integer, intent(in) :: columns
        integer :: owner(columns), b, r
        logical :: in_block(size(rows), size(blocks))

        owner = 0
        in_block = .false.
        do b = 1, size(blocks)
            owner(blocks(b)%column) = b
            in_block(blocks(b)%row, b) = .true.
        end do
        do r = 1, size(rows)
            if (any(in_block(r, :))) call keep_near(rows(r), in_block(r, :))
        end do

    contains

        !> The row without the entries of the blocks it is in.
        subroutine keep_near(row, its_blocks)
            type(block_row), intent(inout) :: row
            logical, intent(in) :: its_blocks(:)
            integer, allocatable :: near(:), column(:)
            real(wp), allocatable :: entries(:, :, :)
            logical :: keep(size(row%column))
            integer :: k

            do k = 1, size(row%column)
                keep(k) = owner(row%column(k)) == 0
                if (.not. keep(k)) keep(k) = .not. its_blocks(owner(row%column(k)))
            end do
            near = pack([(k, k = 1, size(row%column))], keep)
            ! (explicit bounds: gfortran 12 gives a vector-subscripted source's lower bound 0)
            allocate (column(size(near)), entries(2, 2, size(near)))
            column = row%column(near)
            entries = row%block(:, :, near)
            call move_alloc(column, row%column)
            call move_alloc(entries, row%block)
        end subroutine keep_near
    end subroutine drop_far

    !> A gathered piece of a row appended to the row, without its entries at the columns
    !> taken (into a low-rank block).
    pure subroutine append_near(row, piece, taken)
        type(block_row), intent(inout) :: row
        type(block_row), intent(in) :: piece
        !> The columns taken, shape (columns)
        logical, intent(in) :: taken(:)
        integer, allocatable :: near(:), column(:)
        real(wp), allocatable :: entries(:, :, :)
        integer :: k, count

        near = pack([(k, k = 1, size(piece%column))], .not. taken(piece%column))
        count = size(row%column)
        ! (explicit bounds: gfortran 12 gives a vector-subscripted source's lower bound 0)
        allocate (column(count + size(near)), entries(2, 2, count + size(near)))
        column(:count) = row%column
        entries(:, :, :count) = row%block
        column(count + 1:) = piece%column(near)
        entries(:, :, count + 1:) = piece%block(:, :, near)
        call move_alloc(column, row%column)
        call move_alloc(entries, row%block)
    end subroutine append_near

end module ddc_post_far_rows
