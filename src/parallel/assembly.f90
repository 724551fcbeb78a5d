!> The influence matrix of a model distributed over the processes: each process computes only
!> its own blocks, with the one influence fill of ddc_influence_assembly. Unknowns and rows
!> are interleaved element by element (global index 2i - 1: Ds of element i and its shear
!> row; 2i: Dn and the normal row), so that with an even block size the four entries of a
!> pair of elements lie on one process and each pair is evaluated once.
module ddc_parallel_assembly
    use ddc_error, only: error_type
    use ddc_model_medium, only: elastic_medium
    use ddc_influence_assembly, only: fill_influence_block
    use ddc_parallel_context, only: parallel_context
    use ddc_parallel_matrix, only: distributed_matrix, create_matrix, global_rows, &
        global_columns
    implicit none
    private

    public :: assemble_distributed, shear_unknown, normal_unknown

contains

    !> Global index of the shear DD (and the shear row) of element i.
    elemental integer function shear_unknown(i)
        !> The element
        integer, intent(in) :: i

        shear_unknown = 2 * i - 1
    end function shear_unknown

    !> Global index of the normal DD (and the normal row) of element i.
    elemental integer function normal_unknown(i)
        !> The element
        integer, intent(in) :: i

        normal_unknown = 2 * i
    end function normal_unknown

    !> Assemble the 2n x 2n system of the model, rows as the row kinds say (collective).
    subroutine assemble_distributed(context, medium, shear_row, normal_row, matrix, error)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Kind of the shear row and of the normal row of each element, shape (n)
        integer, intent(in) :: shear_row(:), normal_row(:)
        !> The system, interleaved
        type(distributed_matrix), intent(out) :: matrix
        !> Set when the matrix cannot be created (exit_internal_error)
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: row_element(:), row_s(:), row_n(:)
        integer, allocatable :: col_element(:), col_s(:), col_n(:)

        call create_matrix(context, 2 * medium%elements%n, 2 * medium%elements%n, matrix, error)
        if (allocated(error)) return
        call local_elements(global_rows(context, matrix), row_element, row_s, row_n)
        call local_elements(global_columns(context, matrix), col_element, col_s, col_n)
        call fill_influence_block(medium, shear_row, normal_row, row_element, row_s, row_n, &
                                  col_element, col_s, col_n, matrix%a)
    end subroutine assemble_distributed

    !> The elements of some local rows (or columns) in interleaved order, and the local
    !> index of each one's shear and normal row (0 where that row is elsewhere).
    pure subroutine local_elements(global, element, shear, normal)
        !> Global index of each local row, increasing
        integer, intent(in) :: global(:)
        !> The elements, shape (e)
        integer, allocatable, intent(out) :: element(:)
        !> Local index of each one's shear and normal row, shape (e)
        integer, allocatable, intent(out) :: shear(:), normal(:)
        integer :: k, e, i
        logical :: new

        allocate (element(size(global)), shear(size(global)), normal(size(global)))
        e = 0
        do k = 1, size(global)
            i = (global(k) + 1) / 2
            new = e == 0
            if (.not. new) new = element(e) /= i
            if (new) then
                e = e + 1
                element(e) = i
                shear(e) = 0
                normal(e) = 0
            end if
            if (global(k) == shear_unknown(i)) then
                shear(e) = k
            else
                normal(e) = k
            end if
        end do
        element = element(1:e)
        shear = shear(1:e)
        normal = normal(1:e)
    end subroutine local_elements

end module ddc_parallel_assembly
