!> A new distributed matrix made of chosen rows and columns of another on the same grid:
!> J(k, l) = A(rows(k), columns(l)) + coef(k) A(partner(k), columns(l)), the reduced systems
!> of the active-set Newton method. Every process knows the index lists, so each works out
!> alone what it sends to whom and what it receives from whom; the values travel in one
!> MPI_Alltoallv per panel of columns (panels bound the buffers to a few MB per process).
!> The entries equal those the serial method forms from the dense matrix, bit for bit.
module ddc_parallel_redistribute
    use mpi_f08, only: mpi_alltoallv, mpi_double_precision
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_parallel_context, only: parallel_context
    use ddc_parallel_matrix, only: distributed_matrix, create_matrix, owner, local_index
    implicit none
    private

    public :: gather_submatrix

    !> Values a process sends or receives per panel, at most (about 8 MB)
    integer, parameter :: panel_values = 1048576

contains

    !> J(k, l) = A(rows(k), columns(l)) + coef(k) A(partner(k), columns(l)) (no second term
    !> where partner(k) is 0 or coef(k) is 0), distributed like A (collective).
    subroutine gather_submatrix(context, a, rows, partner, coef, columns, j, error)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> The matrix A
        type(distributed_matrix), intent(in) :: a
        !> Rows of A for each row of J, and the partner rows (0: none), shape (m)
        integer, intent(in) :: rows(:), partner(:)
        !> Factor of each partner row, shape (m)
        real(wp), intent(in) :: coef(:)
        !> Columns of A for each column of J, shape (mc)
        integer, intent(in) :: columns(:)
        !> The new matrix, m x mc
        type(distributed_matrix), intent(out) :: j
        !> Set when the matrix cannot be created (exit_internal_error)
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: term_k(:), term_row(:)
        real(wp), allocatable :: term_w(:)
        integer :: m, k, t, width, first

        m = size(rows)
        call create_matrix(context, m, size(columns), j, error)
        if (allocated(error)) return
        if (identity(rows, columns, partner, coef, a%rows)) then
            ! The whole of A in its own order: the same distribution.
            j%a = a%a
            return
        end if

        ! Terms: row k of J is 1 * A(rows(k), :), plus coef(k) * A(partner(k), :).
        allocate (term_k(2 * m), term_row(2 * m), term_w(2 * m))
        t = 0
        do k = 1, m
            t = t + 1
            term_k(t) = k
            term_row(t) = rows(k)
            term_w(t) = 1.0_wp
            if (partner(k) > 0 .and. coef(k) /= 0.0_wp) then
                t = t + 1
                term_k(t) = k
                term_row(t) = partner(k)
                term_w(t) = coef(k)
            end if
        end do
        ! The same panels on every process: about panel_values values per process each.
        width = max(1, int(min(real(size(columns), wp), real(panel_values, wp) * &
                               real(context%processes, wp) / real(max(t, 1), wp))))
        do first = 1, size(columns), width
            call move_panel(context, a, term_k(1:t), term_row(1:t), term_w(1:t), columns, &
                            first, min(size(columns), first + width - 1), j)
        end do
    end subroutine gather_submatrix

    !> Whether J is A itself: every row and column in order, no partner terms.
    pure logical function identity(rows, columns, partner, coef, n)
        integer, intent(in) :: rows(:), columns(:), partner(:), n
        real(wp), intent(in) :: coef(:)
        integer :: k

        identity = size(rows) == n .and. size(columns) == n
        if (.not. identity) return
        do k = 1, n
            if (rows(k) /= k .or. columns(k) /= k .or. &
                (partner(k) > 0 .and. coef(k) /= 0.0_wp)) then
                identity = .false.
                return
            end if
        end do
    end function identity

    !> Move the terms of the columns first..last of J (collective). A sender goes through its
    !> columns l of A in the panel, then its terms t; a receiver through its columns l of J,
    !> then its terms t: for each pair of processes both meet the pairs (l, t) in the same
    !> order. Processes are numbered row-major on the grid (ddc_parallel_context).
    subroutine move_panel(context, a, term_k, term_row, term_w, columns, first, last, j)
        type(parallel_context), intent(in) :: context
        type(distributed_matrix), intent(in) :: a
        integer, intent(in) :: term_k(:), term_row(:)
        real(wp), intent(in) :: term_w(:)
        integer, intent(in) :: columns(:), first, last
        type(distributed_matrix), intent(inout) :: j
        ! Sent terms: the grid row they go to (times the grid's columns) and their local row
        ! in A; sent columns: the grid column they go to (+ 1) and their local column in A.
        integer, allocatable :: send_terms(:), to_row(:), row_in_a(:)
        integer, allocatable :: send_columns(:), to_column(:), column_in_a(:)
        ! Received terms and columns: where they come from and their local row / column in J.
        integer, allocatable :: receive_terms(:), from_row(:), row_in_j(:)
        integer, allocatable :: receive_columns(:), from_column(:), column_in_j(:)
        integer, allocatable :: send_count(:), send_at(:), receive_count(:), receive_at(:)
        integer, allocatable :: next(:)
        real(wp), allocatable :: send(:), receive(:)
        integer :: nb, pr, pc, t, l, i, to, from

        nb = context%block
        pr = context%rows
        pc = context%columns
        send_terms = pack([(t, t = 1, size(term_k))], owner(term_row, nb, pr) == context%row)
        to_row = owner(term_k(send_terms), nb, pr) * pc
        row_in_a = local_index(term_row(send_terms), nb, pr)
        send_columns = pack([(l, l = first, last)], &
                            owner(columns(first:last), nb, pc) == context%column)
        to_column = owner(send_columns, nb, pc) + 1
        column_in_a = local_index(columns(send_columns), nb, pc)
        receive_terms = pack([(t, t = 1, size(term_k))], owner(term_k, nb, pr) == context%row)
        from_row = owner(term_row(receive_terms), nb, pr) * pc
        row_in_j = local_index(term_k(receive_terms), nb, pr)
        receive_columns = pack([(l, l = first, last)], &
                               owner([(l, l = first, last)], nb, pc) == context%column)
        from_column = owner(columns(receive_columns), nb, pc) + 1
        column_in_j = local_index(receive_columns, nb, pc)

        allocate (send_count(context%processes), receive_count(context%processes), source=0)
        do i = 1, size(send_columns)
            do t = 1, size(send_terms)
                to = to_row(t) + to_column(i)
                send_count(to) = send_count(to) + 1
            end do
        end do
        do i = 1, size(receive_columns)
            do t = 1, size(receive_terms)
                from = from_row(t) + from_column(i)
                receive_count(from) = receive_count(from) + 1
            end do
        end do
        send_at = offsets(send_count)
        receive_at = offsets(receive_count)

        allocate (send(max(1, sum(send_count))), receive(max(1, sum(receive_count))))
        next = send_at
        do i = 1, size(send_columns)
            do t = 1, size(send_terms)
                to = to_row(t) + to_column(i)
                next(to) = next(to) + 1
                send(next(to)) = term_w(send_terms(t)) * a%a(row_in_a(t), column_in_a(i))
            end do
        end do
        call mpi_alltoallv(send, send_count, send_at, mpi_double_precision, receive, &
                           receive_count, receive_at, mpi_double_precision, context%comm)
        next = receive_at
        do i = 1, size(receive_columns)
            do t = 1, size(receive_terms)
                from = from_row(t) + from_column(i)
                next(from) = next(from) + 1
                j%a(row_in_j(t), column_in_j(i)) = j%a(row_in_j(t), column_in_j(i)) + &
                    receive(next(from))
            end do
        end do
    end subroutine move_panel

    !> Displacements (0-based) of consecutive pieces of the given sizes.
    pure function offsets(counts) result(at)
        integer, intent(in) :: counts(:)
        integer :: at(size(counts))
        integer :: i

        at(1) = 0
        do i = 2, size(counts)
            at(i) = at(i - 1) + counts(i - 1)
        end do
    end function offsets

end module ddc_parallel_redistribute
