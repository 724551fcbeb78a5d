!> The influence matrix of a grown model from that of the model before growing
!> (docs/theory/growth.md#solving-a-grown-model-cheaply). Growth only adds elements:
!> ddc_growth_extension keeps every old element bit for bit and only moves it to a new index, so the
!> influences among the old elements do not change. Their block moves to the new places and only the
!> rows and columns of the new elements are computed: 4 n_new n kernel entries instead of 4 n^2.
module ddc_growth_influence
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use ddc_kinds, only: wp
    use ddc_model_medium, only: elastic_medium
    use ddc_influence_assembly, only: fill_influence_block
    use ddc_influence_body, only: body_block_correction
    use ddc_solve_elastic, only: row_kinds
    implicit none
    private

    public :: grow_influence, unknown_map, new_elements

contains

    !> The [s; n] index in the grown model of every [s; n] index of the model before.
    pure function unknown_map(moved_to, n) result(new_index)
        !> The index in the grown model of each old element, shape (n_old)
        integer, intent(in) :: moved_to(:)
        !> Number of elements of the grown model
        integer, intent(in) :: n
        !> New index of old unknown g, shape (2 n_old)
        integer :: new_index(2 * size(moved_to))

        new_index = [moved_to, n + moved_to]
    end function unknown_map

    !> The elements of the grown model that the model before did not have, in order.
    pure function new_elements(moved_to, n) result(fresh)
        !> The index in the grown model of each old element, shape (n_old)
        integer, intent(in) :: moved_to(:)
        !> Number of elements of the grown model
        integer, intent(in) :: n
        !> Their indices
        integer :: fresh(n - size(moved_to))
        logical :: old(n)
        integer :: i

        old = .false.
        old(moved_to) = .true.
        fresh = pack([(i, i = 1, n)], .not. old)
    end function new_elements

    !> The influence matrix of the grown model: the old block moved to its new places
    !> (unless `placed`: the matrix holds it there already, from an earlier trial of the
    !> same step), the rows and columns of the new elements computed. Every row is a traction
    !> row or as row_kinds says of the element's condition.
    subroutine grow_influence(old, moved_to, medium, placed, grown, finite)
        !> Influence matrix of the model before growing, [s; n], shape (2 n_old, 2 n_old)
        !> [stress / length]
        real(wp), intent(in) :: old(:, :)
        !> The index in the grown model of each old element, shape (n_old)
        integer, intent(in) :: moved_to(:)
        !> The medium of the grown model, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> grown holds the old block at the places of moved_to already
        logical, intent(in) :: placed
        !> Influence matrix of the grown model, [s; n], shape (2n, 2n) [stress / length]
        real(wp), intent(inout) :: grown(:, :)
        !> Every new entry is finite
        logical, intent(out) :: finite
        integer :: fresh(medium%elements%n - size(moved_to)), every(medium%elements%n)
        integer, allocatable :: place(:), shear_row(:), normal_row(:)
        integer :: n, i, l

        n = medium%elements%n
        fresh = new_elements(moved_to, n)
        every = [(i, i = 1, n)]
        allocate (shear_row(n), normal_row(n))
        call row_kinds(medium%elements%condition, shear_row, normal_row)
        if (.not. placed) then
            place = unknown_map(moved_to, n)
            ! Each thread owns whole columns: disjoint writes.
            !$omp parallel do default(none) schedule(static) private(l) shared(old, grown, place)
            do l = 1, size(place)
                grown(place, place(l)) = old(:, l)
            end do
            !$omp end parallel do
        end if
        ! The new elements' columns (every row), then their rows against the old columns.
        call fill_influence_block(medium, shear_row, normal_row, every, every, n + every, fresh, &
                                  fresh, n + fresh, grown)
        call fill_influence_block(medium, shear_row, normal_row, fresh, fresh, n + fresh, &
                                  moved_to, moved_to, n + moved_to, grown)
        if (allocated(medium%body)) then
            ! In a finite body the new rows and columns take the body's answer too.
            call body_block_correction(medium, shear_row, normal_row, every, fresh, grown)
            call body_block_correction(medium, shear_row, normal_row, fresh, moved_to, grown)
        end if
        finite = all(ieee_is_finite(grown(:, [fresh, n + fresh]))) .and. &
            all(ieee_is_finite(grown([fresh, n + fresh], :)))
    end subroutine grow_influence

end module ddc_growth_influence
