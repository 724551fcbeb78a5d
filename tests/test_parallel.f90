!> Tests of the pure parts of the MPI build (suite built only with DDC2D_MPI): the
!> block-cyclic index maps against ScaLAPACK's own, the process grid, the split of items
!> over processes and the displacements of the v-collectives. No MPI is started.
module test_parallel
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_text, only: itoa
    use ddc_parallel_scalapack, only: numroc, indxg2p, indxg2l, indxl2g
    use ddc_parallel_matrix, only: owner, local_index, global_index
    use ddc_parallel_context, only: grid_shape
    use ddc_parallel_collective, only: split_range, offsets
    implicit none
    private
    public :: collect_parallel

contains

    !> Cases of the parallel suite.
    subroutine collect_parallel(tests)
        !> The cases
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [ &
            new_test('index_maps_match_scalapack', test_index_maps), &
            new_test('grid_shape', test_grid_shape), &
            new_test('split_range', test_split_range), &
            new_test('offsets', test_offsets) &
            ]
    end subroutine collect_parallel

    !> owner, local_index and global_index equal ScaLAPACK's indxg2p, indxg2l and indxl2g,
    !> and each process's count of indices equals numroc, for odd and even block sizes.
    subroutine test_index_maps(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: blocks(6) = [1, 2, 3, 8, 15, 64], n = 300
        integer :: b, procs, g, p, count(0:3)
        character(len=:), allocatable :: at

        do b = 1, size(blocks)
            do procs = 1, 4
                count = 0
                do g = 1, n
                    at = ' (block '//itoa(blocks(b))//', '//itoa(procs)//' processes, index '// &
                        itoa(g)//')'
                    p = owner(g, blocks(b), procs)
                    call check(error, p, indxg2p(g, blocks(b), 0, 0, procs), 'owner'//at)
                    call check(error, local_index(g, blocks(b), procs), &
                               indxg2l(g, blocks(b), 0, 0, procs), 'local index'//at)
                    call check(error, global_index(local_index(g, blocks(b), procs), &
                               blocks(b), procs, p), g, 'global of local'//at)
                    call check(error, global_index(local_index(g, blocks(b), procs), &
                               blocks(b), procs, p), indxl2g(local_index(g, blocks(b), procs), &
                               blocks(b), p, 0, procs), 'indxl2g'//at)
                    if (allocated(error)) return
                    count(p) = count(p) + 1
                end do
                do p = 0, procs - 1
                    call check(error, count(p), numroc(n, blocks(b), p, 0, procs), &
                               'numroc of process '//itoa(p))
                end do
            end do
        end do
    end subroutine test_index_maps

    !> Grids as square as possible: rows <= columns, rows the largest divisor up to sqrt(p).
    subroutine test_grid_shape(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: p(7) = [1, 2, 4, 6, 7, 8, 16], rows(7) = [1, 1, 2, 2, 1, 2, 4]
        integer :: i, r, c

        do i = 1, size(p)
            call grid_shape(p(i), r, c)
            call check(error, r, rows(i), 'rows of '//itoa(p(i)))
            call check(error, c, p(i) / rows(i), 'columns of '//itoa(p(i)))
        end do
        do i = 1, 64
            call grid_shape(i, r, c)
            call check(error, r * c == i .and. r <= c, 'grid of '//itoa(i)//': '//itoa(r)// &
                       ' x '//itoa(c))
        end do
    end subroutine test_grid_shape

    !> n items over `parts` parts: consecutive, all covered, sizes differing by at most one.
    subroutine test_split_range(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, parts, part, first, last, next

        do n = 0, 20
            do parts = 1, 5
                next = 1
                do part = 0, parts - 1
                    call split_range(n, parts, part, first, last)
                    call check(error, first, next, 'first of part '//itoa(part)//' of '// &
                               itoa(n)//' items in '//itoa(parts))
                    call check(error, last - first + 1 == n / parts .or. &
                               last - first + 1 == n / parts + 1, 'size of part '//itoa(part))
                    if (allocated(error)) return
                    next = last + 1
                end do
                call check(error, next, n + 1, 'every item of '//itoa(n)//' in a part')
            end do
        end do
    end subroutine test_split_range

    !> Displacements of pieces: 0, then the running sum.
    subroutine test_offsets(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: at(4)

        at = offsets([3, 0, 5, 2])
        call check(error, all(at == [0, 3, 3, 8]), 'offsets of 3, 0, 5, 2')
    end subroutine test_offsets

end module test_parallel
