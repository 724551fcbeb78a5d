!> Hierarchical matrices (hmat-oss, docs/theory/hierarchical.md): a matrix whose blocks
!> between well-separated groups of unknowns are stored compressed (low rank, by ACA+);
!> products, and for a square one its H-LU factors and solves. The entries come from the caller, as
!> blocks, through an extension of block_source; hmatrix.c holds the C side.
!>
!> hmat-oss is sequential and its assembly calls back into Fortran: the source is reached
!> through a pointer handed to C for the assembly only (no module state).
module ddc_linalg_hmatrix
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_int, c_double, c_funptr, &
        c_funloc, c_loc, c_f_pointer, c_associated
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure
    implicit none
    private

    public :: hmatrix, block_source, hmatrix_settings

    !> What a hierarchical matrix is built from: the entries of any block of rows and
    !> columns of the matrix.
    type, abstract :: block_source
    contains
        procedure(fill_block), deferred :: fill
    end type block_source

    abstract interface
        !> block(k, l) = entry (rows(k), cols(l)) of the matrix (unknowns 1-based).
        subroutine fill_block(source, rows, cols, block)
            import :: block_source, wp
            implicit none
            class(block_source), intent(in) :: source
            integer, intent(in) :: rows(:), cols(:)
            real(wp), intent(out) :: block(:, :)
        end subroutine fill_block
    end interface

    !> How the matrix is clustered and compressed.
    type :: hmatrix_settings
        !> Relative accuracy of each compressed block (ACA+)
        real(wp) :: tolerance = 1.0e-6_wp
        !> Most unknowns in a leaf of the cluster tree (a dense block at most this square)
        integer :: leaf_size = 64
        !> Admissibility: two clusters are compressed when the smaller diameter is at most
        !> eta times their distance (Hackbusch's condition)
        real(wp) :: eta = 2.0_wp
    end type hmatrix_settings

    !> A hierarchical matrix, assembled, then factorized in place.
    type :: hmatrix
        private
        type(c_ptr) :: handle = c_null_ptr
        logical :: factorized = .false.
    contains
        procedure :: assemble
        procedure :: assemble_rectangular
        procedure :: copy_of
        procedure :: factor
        procedure :: solve
        procedure :: multiply
        procedure :: stored_fraction
        procedure :: release
        final :: finalize
    end type hmatrix

    !> The source during an assembly, reached from C by its address.
    type :: source_holder
        class(block_source), pointer :: source => null()
    end type source_holder

    interface
        function hmatrix_assemble_c(rows, row_coordinates, cols, col_coordinates, leaf_size, &
                                    eta, epsilon, fill, context) &
            bind(C, name='ddc2d_hmatrix_assemble') result(handle)
            import :: c_ptr, c_int, c_double, c_funptr
            implicit none
            integer(c_int), value :: rows, cols, leaf_size
            real(c_double), intent(in) :: row_coordinates(*)
            !> NULL (c_null_ptr) for a square matrix on the rows' points
            type(c_ptr), value :: col_coordinates
            real(c_double), value :: eta, epsilon
            type(c_funptr), value :: fill
            type(c_ptr), value :: context
            type(c_ptr) :: handle
        end function hmatrix_assemble_c

        function hmatrix_copy_c(handle) bind(C, name='ddc2d_hmatrix_copy') result(copy)
            import :: c_ptr
            implicit none
            type(c_ptr), value :: handle
            type(c_ptr) :: copy
        end function hmatrix_copy_c

        function hmatrix_factor_c(handle) bind(C, name='ddc2d_hmatrix_factor') result(status)
            import :: c_ptr, c_int
            implicit none
            type(c_ptr), value :: handle
            integer(c_int) :: status
        end function hmatrix_factor_c

        function hmatrix_solve_c(handle, b, nrhs) bind(C, name='ddc2d_hmatrix_solve') &
            result(status)
            import :: c_ptr, c_int, c_double
            implicit none
            type(c_ptr), value :: handle
            real(c_double), intent(inout) :: b(*)
            integer(c_int), value :: nrhs
            integer(c_int) :: status
        end function hmatrix_solve_c

        function hmatrix_multiply_c(handle, x, y) bind(C, name='ddc2d_hmatrix_multiply') &
            result(status)
            import :: c_ptr, c_int, c_double
            implicit none
            type(c_ptr), value :: handle
            real(c_double), intent(inout) :: x(*)
            real(c_double), intent(out) :: y(*)
            integer(c_int) :: status
        end function hmatrix_multiply_c

        subroutine hmatrix_sizes_c(handle, stored, dense) bind(C, name='ddc2d_hmatrix_sizes')
            import :: c_ptr, c_double
            implicit none
            type(c_ptr), value :: handle
            real(c_double), intent(out) :: stored, dense
        end subroutine hmatrix_sizes_c

        subroutine hmatrix_free_c(handle) bind(C, name='ddc2d_hmatrix_free')
            import :: c_ptr
            implicit none
            type(c_ptr), value :: handle
        end subroutine hmatrix_free_c
    end interface

contains

    !> Assemble the matrix of the unknowns at `points` from `source` (any earlier content
    !> released).
    subroutine assemble(matrix, points, source, settings, error)
        class(hmatrix), intent(inout) :: matrix
        !> Position of each unknown (x, y) [length unit], shape (2, order)
        real(wp), intent(in) :: points(:, :)
        !> The entries
        class(block_source), intent(in), target :: source
        type(hmatrix_settings), intent(in) :: settings
        !> Set when hmat-oss fails
        type(error_type), allocatable, intent(out) :: error

        ! No column points: the rows' cluster tree serves the columns too (as H-LU needs).
        call assemble_from(matrix, points, size(points, 2), c_null_ptr, source, settings, &
                           error)
    end subroutine assemble

    !> Assemble the rectangular matrix of the rows at `row_points` against the columns at
    !> `col_points` from `source` (for products only: no H-LU).
    subroutine assemble_rectangular(matrix, row_points, col_points, source, settings, error)
        class(hmatrix), intent(inout) :: matrix
        !> Position of each row's and each column's unknown (x, y) [length unit], shape
        !> (2, rows), (2, cols)
        real(wp), intent(in) :: row_points(:, :)
        real(wp), intent(in), target, contiguous :: col_points(:, :)
        class(block_source), intent(in), target :: source
        type(hmatrix_settings), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error

        call assemble_from(matrix, row_points, size(col_points, 2), c_loc(col_points), source, &
                           settings, error)
    end subroutine assemble_rectangular

    !> assemble and assemble_rectangular: columns at col_points (c_null_ptr: the rows').
    subroutine assemble_from(matrix, row_points, cols, col_points, source, settings, error)
        class(hmatrix), intent(inout) :: matrix
        real(wp), intent(in) :: row_points(:, :)
        integer, intent(in) :: cols
        type(c_ptr), intent(in) :: col_points
        class(block_source), intent(in), target :: source
        type(hmatrix_settings), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error
        type(source_holder), target :: holder

        call matrix%release()
        holder%source => source
        matrix%handle = hmatrix_assemble_c(int(size(row_points, 2), c_int), &
            real(reshape(row_points, [size(row_points)]), c_double), int(cols, c_int), &
            col_points, int(settings%leaf_size, c_int), real(settings%eta, c_double), &
            real(settings%tolerance, c_double), c_funloc(fill_from_source), c_loc(holder))
        if (.not. c_associated(matrix%handle)) call set_error(error, exit_solver_failure, &
            'hmat-oss could not assemble the hierarchical matrix')
    end subroutine assemble_from

    !> This matrix becomes a copy of `original` (assembled, not factorized), which shares
    !> the original's cluster tree: release the copy first.
    subroutine copy_of(matrix, original, error)
        class(hmatrix), intent(inout) :: matrix
        type(hmatrix), intent(in) :: original
        type(error_type), allocatable, intent(out) :: error

        call matrix%release()
        matrix%handle = hmatrix_copy_c(original%handle)
        if (.not. c_associated(matrix%handle)) then
            call set_error(error, exit_solver_failure, 'hmat-oss could not copy the '// &
                           'hierarchical matrix')
        end if
    end subroutine copy_of

    !> H-LU factorization in place.
    subroutine factor(matrix, error)
        class(hmatrix), intent(inout) :: matrix
        !> Set when the factorization fails (a singular matrix)
        type(error_type), allocatable, intent(out) :: error

        if (hmatrix_factor_c(matrix%handle) /= 0) then
            call set_error(error, exit_solver_failure, 'the H-LU factorization of the '// &
                           'hierarchical matrix failed')
            return
        end if
        matrix%factorized = .true.
    end subroutine factor

    !> b := A^-1 b by the H-LU factors (factor first).
    subroutine solve(matrix, b, error)
        class(hmatrix), intent(in) :: matrix
        !> Right-hand sides on entry, solutions on exit, shape (unknowns, nrhs)
        real(wp), intent(inout), contiguous :: b(:, :)
        type(error_type), allocatable, intent(out) :: error
        logical :: failed

        failed = .not. matrix%factorized
        if (.not. failed) failed = hmatrix_solve_c(matrix%handle, b, int(size(b, 2), c_int)) /= 0
        if (failed) call set_error(error, exit_solver_failure, 'the solve with the H-LU '// &
                                   'factors failed')
    end subroutine solve

    !> y = A x by the compressed matrix (before it is factorized).
    subroutine multiply(matrix, x, y, error)
        class(hmatrix), intent(in) :: matrix
        real(wp), intent(in) :: x(:)
        real(wp), intent(out) :: y(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: work(size(x))

        work = x
        if (matrix%factorized) then
            call set_error(error, exit_solver_failure, 'a product with the factors of a '// &
                           'hierarchical matrix')
        else if (hmatrix_multiply_c(matrix%handle, work, y) /= 0) then
            call set_error(error, exit_solver_failure, 'the product with the hierarchical '// &
                           'matrix failed')
        end if
    end subroutine multiply

    !> Reals stored over those of the dense matrix (the compression ratio).
    real(wp) function stored_fraction(matrix)
        class(hmatrix), intent(in) :: matrix
        real(c_double) :: stored, dense

        call hmatrix_sizes_c(matrix%handle, stored, dense)
        stored_fraction = real(stored, wp) / max(real(dense, wp), 1.0_wp)
    end function stored_fraction

    !> Free the matrix (nothing when there is none).
    subroutine release(matrix)
        class(hmatrix), intent(inout) :: matrix

        if (c_associated(matrix%handle)) call hmatrix_free_c(matrix%handle)
        matrix%handle = c_null_ptr
        matrix%factorized = .false.
    end subroutine release

    subroutine finalize(matrix)
        type(hmatrix), intent(inout) :: matrix

        call matrix%release()
    end subroutine finalize

    !> The filler hmat-oss calls (through hmatrix.c) during an assembly.
    subroutine fill_from_source(context, row_count, rows, col_count, cols, block) bind(C)
        type(c_ptr), value :: context
        integer(c_int), value :: row_count, col_count
        integer(c_int), intent(in) :: rows(row_count), cols(col_count)
        real(c_double), intent(out) :: block(row_count, col_count)
        type(source_holder), pointer :: holder

        call c_f_pointer(context, holder)
        call holder%source%fill(int(rows), int(cols), block)
    end subroutine fill_from_source

end module ddc_linalg_hmatrix
