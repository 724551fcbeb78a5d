!> Sparse rows of 2 x 2 blocks: a linear map from pairs of values (a DD's two components, say)
!> to pairs (a shear and a normal traction), held row by row, each with its own columns.
!> A row_builder gathers a row's blocks, adding those of a column given twice, and either
!> keeps the row or applies it at once (where keeping every row would not fit).
module ddc_linalg_block_rows
    use ddc_kinds, only: wp
    implicit none
    private

    public :: block_row, row_builder, row_times

    !> One row: its columns and their blocks, shape (entries) and (2, 2, entries)
    type :: block_row
        integer, allocatable :: column(:)
        real(wp), allocatable :: block(:, :, :)
    end type block_row

    !> The row being gathered.
    type :: row_builder
        private
        !> Each column's entry in the row (0: none yet), shape (columns)
        integer, allocatable :: slot(:)
        integer, allocatable :: column(:)
        real(wp), allocatable :: block(:, :, :)
        integer :: count = 0
    contains
        procedure :: start
        procedure :: add
        procedure :: take
        procedure :: apply
    end type row_builder

contains

    !> An empty row of `columns` columns.
    pure subroutine start(this, columns)
        class(row_builder), intent(inout) :: this
        integer, intent(in) :: columns

        if (allocated(this%slot)) deallocate (this%slot)
        allocate (this%slot(columns), source=0)
        if (.not. allocated(this%column)) allocate (this%column(64), this%block(2, 2, 64))
        this%count = 0
    end subroutine start

    !> Add a block at a column.
    pure subroutine add(this, column, block)
        class(row_builder), intent(inout) :: this
        integer, intent(in) :: column
        real(wp), intent(in) :: block(2, 2)
        integer, allocatable :: wider_column(:)
        real(wp), allocatable :: wider_block(:, :, :)
        integer :: e

        e = this%slot(column)
        if (e > 0) then
            this%block(:, :, e) = this%block(:, :, e) + block
            return
        end if
        if (this%count == size(this%column)) then
            allocate (wider_column(2 * this%count), wider_block(2, 2, 2 * this%count))
            wider_column(:this%count) = this%column
            wider_block(:, :, :this%count) = this%block
            call move_alloc(wider_column, this%column)
            call move_alloc(wider_block, this%block)
        end if
        this%count = this%count + 1
        this%column(this%count) = column
        this%block(:, :, this%count) = block
        this%slot(column) = this%count
    end subroutine add

    !> The gathered row; the builder starts the next one empty.
    pure subroutine take(this, gathered)
        class(row_builder), intent(inout) :: this
        type(block_row), intent(out) :: gathered

        allocate (gathered%column, source=this%column(:this%count))
        allocate (gathered%block, source=this%block(:, :, :this%count))
        call clear(this)
    end subroutine take

    !> The gathered row applied to pairs x, shape (2, columns); the builder starts the next
    !> one empty.
    pure subroutine apply(this, x, y)
        class(row_builder), intent(inout) :: this
        real(wp), intent(in) :: x(:, :)
        real(wp), intent(out) :: y(2)
        integer :: e

        y = 0.0_wp
        do e = 1, this%count
            y = y + block_times(this%block(:, :, e), x(:, this%column(e)))
        end do
        call clear(this)
    end subroutine apply

    !> A kept row applied to pairs x, shape (2, columns).
    pure function row_times(kept, x) result(y)
        type(block_row), intent(in) :: kept
        real(wp), intent(in) :: x(:, :)
        real(wp) :: y(2)
        integer :: e

        y = 0.0_wp
        do e = 1, size(kept%column)
            y = y + block_times(kept%block(:, :, e), x(:, kept%column(e)))
        end do
    end function row_times

    !> A block times a pair.
    pure function block_times(block, pair) result(y)
        real(wp), intent(in) :: block(2, 2), pair(2)
        real(wp) :: y(2)

        y(1) = block(1, 1) * pair(1) + block(1, 2) * pair(2)
        y(2) = block(2, 1) * pair(1) + block(2, 2) * pair(2)
    end function block_times

    !> Forget the gathered row (the columns it used are free again).
    pure subroutine clear(this)
        type(row_builder), intent(inout) :: this

        this%slot(this%column(:this%count)) = 0
        this%count = 0
    end subroutine clear

end module ddc_linalg_block_rows
