!> The processes of a distributed run (MPI build): MPI itself, and the BLACS process grid of
!> the block-cyclic matrices (rows x columns, as square as possible, row-major: process
!> (r, c) of the grid is MPI rank r * columns + c of MPI_COMM_WORLD).
module ddc_parallel_context
    use, intrinsic :: ieee_exceptions, only: ieee_get_halting_mode, ieee_set_halting_mode, &
        ieee_all
    use mpi_f08, only: MPI_Comm, mpi_comm_world, mpi_init, mpi_finalize, mpi_comm_rank, &
        mpi_comm_size
    use ddc_error, only: error_type, set_internal_error
    use ddc_parallel_scalapack, only: blacs_get, blacs_gridinit, blacs_gridinfo, &
        blacs_gridexit, blacs_exit
    implicit none
    private

    public :: parallel_context, root, start_parallel, open_grid, stop_parallel, grid_shape

    !> The process that reads the input and writes the output
    integer, parameter :: root = 0

    !> The processes of a run and their grid.
    type :: parallel_context
        !> The communicator of every process of the run
        type(MPI_Comm) :: comm
        !> This process and the number of processes
        integer :: rank = root, processes = 1
        !> BLACS context of the grid (-1 before open_grid)
        integer :: grid = -1
        !> Rows and columns of the grid, and this process's row and column (0-based)
        integer :: rows = 1, columns = 1, row = 0, column = 0
        !> Rows and columns of each block of the distributed matrices
        integer :: block = 64
    end type parallel_context

contains

    !> Start MPI. Floating-point traps (the debug build's -ffpe-trap) are off while MPI starts:
    !> the library's own start-up code divides by zero under some launchers (srun --mpi=pmix).
    subroutine start_parallel(context)
        !> This process and the number of processes
        type(parallel_context), intent(out) :: context
        logical :: halting(size(ieee_all))

        call ieee_get_halting_mode(ieee_all, halting)
        call ieee_set_halting_mode(ieee_all, .false.)
        call mpi_init()
        call ieee_set_halting_mode(ieee_all, halting)
        context%comm = mpi_comm_world
        call mpi_comm_rank(context%comm, context%rank)
        call mpi_comm_size(context%comm, context%processes)
    end subroutine start_parallel

    !> Rows x columns of the grid of p processes: rows the largest divisor of p not above
    !> sqrt(p) (2: 1 x 2, 4: 2 x 2, 6: 2 x 3, 7: 1 x 7).
    pure subroutine grid_shape(p, rows, columns)
        !> Number of processes
        integer, intent(in) :: p
        !> Shape of the grid, rows <= columns, rows * columns = p
        integer, intent(out) :: rows, columns

        rows = max(1, int(sqrt(real(p))))
        do while (rows * rows > p)
            rows = rows - 1
        end do
        do while (mod(p, rows) /= 0)
            rows = rows - 1
        end do
        columns = p / rows
    end subroutine grid_shape

    !> Open the BLACS grid of every process (collective).
    subroutine open_grid(context, block, error)
        !> The processes; the grid is set
        type(parallel_context), intent(inout) :: context
        !> Rows and columns of each block (at least 1)
        integer, intent(in) :: block
        !> Set when BLACS numbers the processes otherwise than MPI (exit_internal_error)
        type(error_type), allocatable, intent(out) :: error

        context%block = block
        call grid_shape(context%processes, context%rows, context%columns)
        call blacs_get(-1, 0, context%grid)
        call blacs_gridinit(context%grid, 'R', context%rows, context%columns)
        call blacs_gridinfo(context%grid, context%rows, context%columns, context%row, &
                            context%column)
        if (context%row * context%columns + context%column /= context%rank) then
            call set_internal_error(error, 'open_grid', 'the BLACS grid is not row-major '// &
                                    'in MPI_COMM_WORLD')
        end if
    end subroutine open_grid

    !> Close the grid (when open) and end MPI.
    subroutine stop_parallel(context)
        !> The processes
        type(parallel_context), intent(inout) :: context

        if (context%grid >= 0) then
            call blacs_gridexit(context%grid)
            context%grid = -1
            ! 1: BLACS leaves MPI running; mpi_finalize ends it.
            call blacs_exit(1)
        end if
        call mpi_finalize()
    end subroutine stop_parallel

end module ddc_parallel_context
