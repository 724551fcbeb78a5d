!> A dense matrix distributed block-cyclically over the process grid (ScaLAPACK's layout,
!> square blocks of the context's block size, first block on process (0, 0)), the index maps
!> between global and local rows and columns, and the product with a vector that every
!> process holds whole.
module ddc_parallel_matrix
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_internal_error
    use ddc_text, only: itoa
    use ddc_linalg_lapack, only: dgemv
    use ddc_parallel_scalapack, only: numroc, descinit
    use ddc_parallel_context, only: parallel_context
    use ddc_parallel_collective, only: sum_on_all
    implicit none
    private

    public :: distributed_matrix, create_matrix, owner, local_index, global_index
    public :: global_rows, global_columns, multiply_whole

    !> This process's part of a distributed matrix.
    type :: distributed_matrix
        !> Global rows and columns
        integer :: rows = 0, columns = 0
        !> ScaLAPACK descriptor
        integer :: desc(9) = 0
        !> Local rows and columns of this process
        integer :: local_rows = 0, local_columns = 0
        !> The local entries, shape (max(1, local_rows), local_columns)
        real(wp), allocatable :: a(:, :)
    end type distributed_matrix

contains

    !> A rows x columns matrix on the context's grid, entries zero.
    subroutine create_matrix(context, rows, columns, matrix, error)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> Global size
        integer, intent(in) :: rows, columns
        !> The matrix
        type(distributed_matrix), intent(out) :: matrix
        !> Set when ScaLAPACK refuses the descriptor (exit_internal_error)
        type(error_type), allocatable, intent(out) :: error
        integer :: info

        matrix%rows = rows
        matrix%columns = columns
        matrix%local_rows = numroc(rows, context%block, context%row, 0, context%rows)
        matrix%local_columns = numroc(columns, context%block, context%column, 0, &
                                      context%columns)
        call descinit(matrix%desc, rows, columns, context%block, context%block, 0, 0, &
                      context%grid, max(1, matrix%local_rows), info)
        if (info /= 0) then
            call set_internal_error(error, 'create_matrix', 'descinit argument '// &
                                    itoa(-info)//' is wrong')
            return
        end if
        allocate (matrix%a(max(1, matrix%local_rows), matrix%local_columns), source=0.0_wp)
    end subroutine create_matrix

    !> Process row (or column) holding global row (column) `global`.
    elemental integer function owner(global, block, processes)
        !> Global index (1-based)
        integer, intent(in) :: global
        !> Block size and number of process rows (columns)
        integer, intent(in) :: block, processes

        owner = mod((global - 1) / block, processes)
    end function owner

    !> Local index of global row (column) `global` on its owner.
    elemental integer function local_index(global, block, processes)
        !> Global index (1-based)
        integer, intent(in) :: global
        !> Block size and number of process rows (columns)
        integer, intent(in) :: block, processes

        local_index = ((global - 1) / (block * processes)) * block + mod(global - 1, block) + 1
    end function local_index

    !> Global index of local row (column) `local` of process row (column) `process`.
    elemental integer function global_index(local, block, processes, process)
        !> Local index (1-based)
        integer, intent(in) :: local
        !> Block size, number of process rows (columns) and the process row (column)
        integer, intent(in) :: block, processes, process

        global_index = ((local - 1) / block) * block * processes + process * block + &
            mod(local - 1, block) + 1
    end function global_index

    !> Global indices of this process's rows, shape (local_rows).
    function global_rows(context, matrix) result(rows)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> The matrix
        type(distributed_matrix), intent(in) :: matrix
        !> Global row of each local row
        integer :: rows(matrix%local_rows)
        integer :: i

        rows = global_index([(i, i = 1, matrix%local_rows)], context%block, context%rows, &
                            context%row)
    end function global_rows

    !> Global indices of this process's columns, shape (local_columns).
    function global_columns(context, matrix) result(columns)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> The matrix
        type(distributed_matrix), intent(in) :: matrix
        !> Global column of each local column
        integer :: columns(matrix%local_columns)
        integer :: i

        columns = global_index([(i, i = 1, matrix%local_columns)], context%block, &
                               context%columns, context%column)
    end function global_columns

    !> y = y + A x for vectors every process holds whole; every process gets the same y
    !> (collective).
    subroutine multiply_whole(context, matrix, x, y)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> The matrix A
        type(distributed_matrix), intent(in) :: matrix
        !> The vector, shape (columns)
        real(wp), intent(in) :: x(:)
        !> The result, shape (rows): A x is added
        real(wp), intent(inout) :: y(:)
        real(wp), allocatable :: part(:), ax(:)

        allocate (part(matrix%rows), source=0.0_wp)
        if (matrix%local_rows > 0 .and. matrix%local_columns > 0) then
            allocate (ax(matrix%local_rows))
            call dgemv('N', matrix%local_rows, matrix%local_columns, 1.0_wp, matrix%a, &
                       size(matrix%a, 1), x(global_columns(context, matrix)), 1, 0.0_wp, ax, 1)
            part(global_rows(context, matrix)) = ax
        end if
        call sum_on_all(context, part)
        y = y + part
    end subroutine multiply_whole

end module ddc_parallel_matrix
