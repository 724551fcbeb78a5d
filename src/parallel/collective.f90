!> Collective operations of a distributed run (MPI build): values the root shares with every
!> process, sums and maxima every process agrees on bit for bit, gathers of pieces computed
!> apart, and the decision on errors that keeps every process on the same path (an error on
!> any process is the error of every process, so no process waits for another that left).
module ddc_parallel_collective
    use mpi_f08, only: mpi_bcast, mpi_allreduce, mpi_reduce, mpi_gather, mpi_gatherv, &
        mpi_allgather, mpi_allgatherv, mpi_in_place, mpi_integer, mpi_double_precision, &
        mpi_logical, mpi_character, mpi_sum, mpi_max, mpi_min, mpi_land, mpi_minloc, &
        mpi_2double_precision
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_parallel_context, only: parallel_context, root
    implicit none
    private

    public :: agree_on_error, share, sum_on_all, max_on_all, all_true, min_location, split_range
    public :: gather_on_root, gather_on_all, offsets

    !> Broadcast from the root: scalars, allocatable 1-D arrays (allocated as on the root)
    !> and allocatable text.
    interface share
        module procedure share_integer, share_real, share_integers, share_reals, share_text
    end interface share

    !> The pieces of every process, in rank order, on the root (elsewhere an empty array).
    interface gather_on_root
        module procedure gather_reals_on_root, gather_integers_on_root
    end interface gather_on_root

contains

    !> Make an error of any process the error of every process: the message and code of the
    !> lowest rank that has one (collective).
    subroutine agree_on_error(context, error)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> This process's error on entry; the agreed one on exit
        type(error_type), allocatable, intent(inout) :: error
        character(len=:), allocatable :: message
        integer :: first, code

        first = context%processes
        if (allocated(error)) first = context%rank
        call mpi_allreduce(mpi_in_place, first, 1, mpi_integer, mpi_min, context%comm)
        if (first == context%processes) return
        code = 0
        message = ''
        if (context%rank == first) then
            code = error%code
            message = error%message
        end if
        call share_integer(context, code, first)
        call share_text(context, message, first)
        if (.not. allocated(error)) allocate (error)
        error%code = code
        error%message = message
    end subroutine agree_on_error

    !> Broadcast an integer from the root (or from process source).
    subroutine share_integer(context, value, source)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> The root's value on exit
        integer, intent(inout) :: value
        !> The sending process (default the root)
        integer, intent(in), optional :: source

        call mpi_bcast(value, 1, mpi_integer, sender(source), context%comm)
    end subroutine share_integer

    !> Broadcast a real from the root.
    subroutine share_real(context, value)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> The root's value on exit
        real(wp), intent(inout) :: value

        call mpi_bcast(value, 1, mpi_double_precision, root, context%comm)
    end subroutine share_real

    !> Broadcast an allocatable integer array from the root (unallocated stays so).
    subroutine share_integers(context, values)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> The root's array on exit
        integer, allocatable, intent(inout) :: values(:)
        integer :: n

        n = -1
        if (allocated(values)) n = size(values)
        call share_integer(context, n)
        if (n < 0) return
        if (context%rank /= root) then
            if (allocated(values)) deallocate (values)
            allocate (values(n))
        end if
        call mpi_bcast(values, n, mpi_integer, root, context%comm)
    end subroutine share_integers

    !> Broadcast an allocatable real array from the root (unallocated stays so).
    subroutine share_reals(context, values)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> The root's array on exit
        real(wp), allocatable, intent(inout) :: values(:)
        integer :: n

        n = -1
        if (allocated(values)) n = size(values)
        call share_integer(context, n)
        if (n < 0) return
        if (context%rank /= root) then
            if (allocated(values)) deallocate (values)
            allocate (values(n))
        end if
        call mpi_bcast(values, n, mpi_double_precision, root, context%comm)
    end subroutine share_reals

    !> Broadcast allocatable text from the root (or from process source).
    subroutine share_text(context, text, source)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> The root's text on exit
        character(len=:), allocatable, intent(inout) :: text
        !> The sending process (default the root)
        integer, intent(in), optional :: source
        integer :: n, from

        from = sender(source)
        n = 0
        if (allocated(text)) n = len(text)
        call mpi_bcast(n, 1, mpi_integer, from, context%comm)
        if (context%rank /= from) then
            if (allocated(text)) deallocate (text)
            allocate (character(len=n) :: text)
        end if
        if (n > 0) call mpi_bcast(text, n, mpi_character, from, context%comm)
    end subroutine share_text

    !> The process source when given, else the root.
    pure integer function sender(source)
        integer, intent(in), optional :: source

        sender = root
        if (present(source)) sender = source
    end function sender

    !> Sum a vector over the processes; every process gets the root's sum (collective).
    subroutine sum_on_all(context, values)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> This process's part on entry, the sum on exit
        real(wp), intent(inout) :: values(:)
        real(wp), allocatable :: part(:)

        allocate (part, source=values)
        call mpi_reduce(part, values, size(values), mpi_double_precision, mpi_sum, root, &
                        context%comm)
        call mpi_bcast(values, size(values), mpi_double_precision, root, context%comm)
    end subroutine sum_on_all

    !> The largest of a value over the processes (collective).
    function max_on_all(context, value) result(largest)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> This process's value
        real(wp), intent(in) :: value
        !> The largest value
        real(wp) :: largest

        call mpi_allreduce(value, largest, 1, mpi_double_precision, mpi_max, context%comm)
    end function max_on_all

    !> The smallest of a value over the processes and the index that goes with it (the
    !> lowest index among equal values; collective).
    subroutine min_location(context, value, index)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> This process's value on entry, the smallest on exit
        real(wp), intent(inout) :: value
        !> This process's index on entry, that of the smallest value on exit
        integer, intent(inout) :: index
        real(wp) :: pair(2), smallest(2)

        pair = [value, real(index, wp)]
        call mpi_allreduce(pair, smallest, 1, mpi_2double_precision, mpi_minloc, context%comm)
        value = smallest(1)
        index = nint(smallest(2))
    end subroutine min_location

    !> Whether a condition holds on every process (collective).
    function all_true(context, condition) result(every)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> The condition on this process
        logical, intent(in) :: condition
        !> Whether it holds on every process
        logical :: every

        call mpi_allreduce(condition, every, 1, mpi_logical, mpi_land, context%comm)
    end function all_true

    !> The items first..last of part `part` (0-based) of n items split into `parts` parts of
    !> sizes differing by at most one (first > last for an empty part).
    pure subroutine split_range(n, parts, part, first, last)
        !> Number of items, of parts, and the part
        integer, intent(in) :: n, parts, part
        !> Its first and last item
        integer, intent(out) :: first, last

        first = part * (n / parts) + min(part, mod(n, parts)) + 1
        last = first + n / parts - 1
        if (part < mod(n, parts)) last = last + 1
    end subroutine split_range

    !> Displacements (0-based) of consecutive pieces of the given sizes, as MPI's
    !> v-collectives take them.
    pure function offsets(counts) result(at)
        !> Size of each piece
        integer, intent(in) :: counts(:)
        !> Where each piece starts, 0 for the first
        integer :: at(size(counts))
        integer :: i

        at(1) = 0
        do i = 2, size(counts)
            at(i) = at(i - 1) + counts(i - 1)
        end do
    end function offsets

    !> Real pieces gathered on the root, in rank order (collective).
    subroutine gather_reals_on_root(context, piece, whole)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> This process's piece
        real(wp), intent(in) :: piece(:)
        !> The pieces in rank order on the root; empty elsewhere
        real(wp), allocatable, intent(out) :: whole(:)
        integer :: counts(context%processes), displs(context%processes)

        call mpi_gather(size(piece), 1, mpi_integer, counts, 1, mpi_integer, root, context%comm)
        displs = offsets(counts)
        if (context%rank == root) then
            allocate (whole(sum(counts)))
        else
            allocate (whole(0))
        end if
        call mpi_gatherv(piece, size(piece), mpi_double_precision, whole, counts, displs, &
                         mpi_double_precision, root, context%comm)
    end subroutine gather_reals_on_root

    !> Integer pieces gathered on the root, in rank order (collective).
    subroutine gather_integers_on_root(context, piece, whole)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> This process's piece
        integer, intent(in) :: piece(:)
        !> The pieces in rank order on the root; empty elsewhere
        integer, allocatable, intent(out) :: whole(:)
        integer :: counts(context%processes), displs(context%processes)

        call mpi_gather(size(piece), 1, mpi_integer, counts, 1, mpi_integer, root, context%comm)
        displs = offsets(counts)
        if (context%rank == root) then
            allocate (whole(sum(counts)))
        else
            allocate (whole(0))
        end if
        call mpi_gatherv(piece, size(piece), mpi_integer, whole, counts, displs, mpi_integer, &
                         root, context%comm)
    end subroutine gather_integers_on_root

    !> Real pieces gathered on every process, in rank order (collective).
    subroutine gather_on_all(context, piece, whole)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> This process's piece
        real(wp), intent(in) :: piece(:)
        !> The pieces in rank order, shape (sum of the pieces' sizes)
        real(wp), intent(out) :: whole(:)
        integer :: counts(context%processes), displs(context%processes)

        call mpi_allgather(size(piece), 1, mpi_integer, counts, 1, mpi_integer, context%comm)
        displs = offsets(counts)
        call mpi_allgatherv(piece, size(piece), mpi_double_precision, whole, counts, displs, &
                            mpi_double_precision, context%comm)
    end subroutine gather_on_all

end module ddc_parallel_collective
