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
    use ddc_parallel_collective, only: offsets
    use ddc_parallel_matrix, only: distributed_matrix, create_matrix, owner, local_index
    implicit none
    private

    public :: gather_submatrix

    !> Values a process sends or receives per panel, at most (about 8 MB)
    integer, parameter :: panel_values = 1048576

    !> The terms of J's rows that this process sends and receives (plan_terms).
    type :: term_plan
        !> Number of terms of all rows
        integer :: count = 0
        !> Sent terms: the grid row of their J row (times the grid's columns), their local
        !> row in A and in J (used where that row of J is here), their factor
        integer, allocatable :: to_row(:), row_in_a(:), row_in_j(:)
        real(wp), allocatable :: weight(:)
        !> Received terms: the grid row of their A row (times the grid's columns) and their
        !> local row in J
        integer, allocatable :: from_row(:), received_row_in_j(:)
    end type term_plan

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
        type(term_plan) :: terms
        real(wp), allocatable :: send(:), receive(:)
        integer :: width, first

        call create_matrix(context, size(rows), size(columns), j, error)
        if (allocated(error)) return
        if (identity(rows, columns, partner, coef, a%rows)) then
            ! The whole of A in its own order: the same distribution.
            j%a = a%a
            return
        end if
        call plan_terms(context, rows, partner, coef, terms)
        ! The same panels on every process: about panel_values values per process each.
        width = max(1, int(min(real(size(columns), wp), real(panel_values, wp) * &
                               real(context%processes, wp) / real(max(terms%count, 1), wp))))
        allocate (send(0), receive(0))
        do first = 1, size(columns), width
            call move_panel(context, a, terms, columns, first, &
                            min(size(columns), first + width - 1), send, receive, j)
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

    !> The terms of J's rows (row k: 1 * A(rows(k), :), then coef(k) * A(partner(k), :)) that
    !> this process sends (its process row holds their row of A) and receives (it holds their
    !> row of J).
    pure subroutine plan_terms(context, rows, partner, coef, terms)
        type(parallel_context), intent(in) :: context
        integer, intent(in) :: rows(:), partner(:)
        real(wp), intent(in) :: coef(:)
        type(term_plan), intent(out) :: terms
        integer, allocatable :: term_k(:), term_row(:), sent(:), received(:)
        real(wp), allocatable :: term_w(:)
        integer :: k, t, nb, pr, pc

        allocate (term_k(2 * size(rows)), term_row(2 * size(rows)), term_w(2 * size(rows)))
        t = 0
        do k = 1, size(rows)
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
        terms%count = t
        nb = context%block
        pr = context%rows
        pc = context%columns
        sent = pack([(k, k = 1, t)], owner(term_row(1:t), nb, pr) == context%row)
        terms%to_row = owner(term_k(sent), nb, pr) * pc
        terms%row_in_a = local_index(term_row(sent), nb, pr)
        terms%row_in_j = local_index(term_k(sent), nb, pr)
        terms%weight = term_w(sent)
        received = pack([(k, k = 1, t)], owner(term_k(1:t), nb, pr) == context%row)
        terms%from_row = owner(term_row(received), nb, pr) * pc
        terms%received_row_in_j = local_index(term_k(received), nb, pr)
    end subroutine plan_terms

    !> Move the terms of the columns first..last of J (collective). A sender goes through its
    !> columns l of A in the panel, then its terms t; a receiver through its columns l of J,
    !> then its terms t: for each pair of processes both meet the pairs (l, t) in the same
    !> order. Entries whose row and column of A and of J are all on this process are added
    !> in place. Processes are numbered row-major on the grid (ddc_parallel_context).
    subroutine move_panel(context, a, terms, columns, first, last, send, receive, j)
        type(parallel_context), intent(in) :: context
        type(distributed_matrix), intent(in) :: a
        type(term_plan), intent(in) :: terms
        integer, intent(in) :: columns(:), first, last
        real(wp), allocatable, intent(inout) :: send(:), receive(:)
        type(distributed_matrix), intent(inout) :: j
        ! Sent columns: the grid column they go to (+ 1), their local column in A and in J
        ! (when here); received columns: where they come from (+ 1), their local column in J.
        integer, allocatable :: sent(:), to_column(:), column_in_a(:), column_in_j(:)
        integer, allocatable :: received(:), from_column(:), received_column_in_j(:)
        integer, allocatable :: send_count(:), send_at(:), receive_count(:), receive_at(:)
        integer, allocatable :: next(:)
        integer :: nb, pc, t, l, i, to, from, me

        nb = context%block
        pc = context%columns
        me = context%rank + 1
        sent = pack([(l, l = first, last)], owner(columns(first:last), nb, pc) == context%column)
        to_column = owner(sent, nb, pc) + 1
        column_in_a = local_index(columns(sent), nb, pc)
        column_in_j = local_index(sent, nb, pc)
        received = pack([(l, l = first, last)], &
                        owner([(l, l = first, last)], nb, pc) == context%column)
        from_column = owner(columns(received), nb, pc) + 1
        received_column_in_j = local_index(received, nb, pc)

        allocate (send_count(context%processes), receive_count(context%processes), source=0)
        do i = 1, size(sent)
            do t = 1, size(terms%to_row)
                to = terms%to_row(t) + to_column(i)
                send_count(to) = send_count(to) + 1
            end do
        end do
        do i = 1, size(received)
            do t = 1, size(terms%from_row)
                from = terms%from_row(t) + from_column(i)
                receive_count(from) = receive_count(from) + 1
            end do
        end do
        send_count(me) = 0
        receive_count(me) = 0
        send_at = offsets(send_count)
        receive_at = offsets(receive_count)
        if (size(send) < sum(send_count)) then
            deallocate (send)
            allocate (send(sum(send_count)))
        end if
        if (size(receive) < sum(receive_count)) then
            deallocate (receive)
            allocate (receive(sum(receive_count)))
        end if

        next = send_at
        do i = 1, size(sent)
            do t = 1, size(terms%to_row)
                to = terms%to_row(t) + to_column(i)
                associate (value => terms%weight(t) * a%a(terms%row_in_a(t), column_in_a(i)))
                    if (to == me) then
                        j%a(terms%row_in_j(t), column_in_j(i)) = &
                            j%a(terms%row_in_j(t), column_in_j(i)) + value
                    else
                        next(to) = next(to) + 1
                        send(next(to)) = value
                    end if
                end associate
            end do
        end do
        call mpi_alltoallv(send, send_count, send_at, mpi_double_precision, receive, &
                           receive_count, receive_at, mpi_double_precision, context%comm)
        next = receive_at
        do i = 1, size(received)
            do t = 1, size(terms%from_row)
                from = terms%from_row(t) + from_column(i)
                if (from == me) cycle
                next(from) = next(from) + 1
                j%a(terms%received_row_in_j(t), received_column_in_j(i)) = &
                    j%a(terms%received_row_in_j(t), received_column_in_j(i)) + receive(next(from))
            end do
        end do
    end subroutine move_panel

end module ddc_parallel_redistribute
