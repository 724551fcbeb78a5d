!> Tests of the mesh layer: allocation and selection of element sets, polyline
!> subdivision and the geometric checks.
module test_mesh
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_error, only: exit_bad_input
    use ddc_text, only: itoa
    use ddc_model_types, only: element_set, fracture_type, element_array_action, &
        for_each_element_array, select_elements, symmetry_x, domain_half_plane
    use ddc_mesh_geometry, only: allocate_elements
    use ddc_mesh_polyline, only: polyline_elements, expand_per_segment
    use ddc_mesh_checks, only: check_elements
    implicit none
    private
    public :: collect_mesh

    real(wp), parameter :: tight = 1.0e-14_wp
    real(wp), parameter :: pi = 3.14159265358979323846_wp

    !> A mesh under construction: fractures appended one by one.
    type :: mesh_builder
        type(element_set) :: elements
        type(fracture_type), allocatable :: fractures(:)
    end type mesh_builder

    !> Numbers every per-element array of a set of n elements: element i of the k-th array
    !> gets 1000 k + i; with pick, checks that it holds 1000 k + pick(i) instead.
    type, extends(element_array_action) :: array_numbering
        !> Number of elements
        integer :: n = 0
        !> Arrays seen so far
        integer :: arrays = 0
        !> Element of the numbered set each element was selected from (checks when given)
        integer, allocatable :: pick(:)
        !> What was wrong, empty when nothing
        character(len=:), allocatable :: problem
    contains
        procedure :: on_reals => number_reals
        procedure :: on_integers => number_integers
    end type array_numbering

contains

    !> Cases of the mesh suite.
    subroutine collect_mesh(tests)
        !> The cases
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [ &
            new_test('allocate_and_select_every_array', test_allocate_and_select), &
            new_test('polyline_subdivision', test_polyline_subdivision), &
            new_test('expand_per_segment', test_expand_per_segment), &
            new_test('zero_length', test_zero_length), &
            new_test('duplicate', test_duplicate), &
            new_test('overlap', test_overlap), &
            new_test('overlap_folded_polyline', test_overlap_folded), &
            new_test('crossing', test_crossing), &
            new_test('t_junction', test_t_junction), &
            new_test('t_junction_within_tolerance', test_t_junction_tolerance), &
            new_test('near_miss_passes', test_near_miss), &
            new_test('closed_loop_passes', test_closed_loop), &
            new_test('branch_at_shared_vertex_passes', test_branch), &
            new_test('large_meshes_pass', test_large) &
            ]
    end subroutine collect_mesh

    ! ---- element sets -------------------------------------------------------------------

    !> allocate_elements sizes every array of the one list, select_elements copies every
    !> value of the picked elements (repeats too) and keeps symmetry and domain.
    subroutine test_allocate_and_select(error)
        type(error_type), allocatable, intent(out) :: error
        type(element_set) :: elements, selected
        type(array_numbering) :: numbering, checking
        integer, parameter :: pick(5) = [3, 1, 3, 4, 2]

        call allocate_elements(elements, 4)
        elements%symmetry%kind = symmetry_x
        elements%symmetry%xsym = 2.5_wp
        elements%domain = domain_half_plane
        numbering%n = 4
        numbering%problem = ''
        call for_each_element_array(elements, numbering)
        call check(error, numbering%problem == '', 'allocate_elements:'//numbering%problem)
        call check(error, numbering%arrays >= 16, 'the list holds '// &
                   itoa(numbering%arrays)//' arrays, element_set has at least 16')

        call select_elements(elements, pick, selected)
        checking%n = size(pick)
        checking%pick = pick
        checking%problem = ''
        call for_each_element_array(selected, checking)
        call check(error, checking%problem == '', 'select_elements:'//checking%problem)
        call check(error, checking%arrays, numbering%arrays, 'arrays selected')
        call check(error, selected%n, size(pick), 'selected n')
        call check(error, selected%symmetry%kind, symmetry_x, 'selected symmetry')
        call check(error, selected%symmetry%xsym == 2.5_wp, 'selected xsym copied exactly')
        call check(error, selected%domain, domain_half_plane, 'selected domain')
    end subroutine test_allocate_and_select

    !> Number a real array, or check its numbers (array_numbering).
    subroutine number_reals(action, values)
        class(array_numbering), intent(inout) :: action
        real(wp), allocatable, intent(inout) :: values(:)
        integer, allocatable :: expected(:)
        integer :: length

        length = -1
        if (allocated(values)) length = size(values)
        call expected_numbers(action, length, expected)
        if (.not. allocated(expected)) return
        if (.not. allocated(action%pick)) then
            values = real(expected, wp)
        else if (any(values /= real(expected, wp))) then
            action%problem = action%problem//' real array '//itoa(action%arrays)// &
                             ' holds other values'
        end if
    end subroutine number_reals

    !> Number an integer array, or check its numbers (array_numbering).
    subroutine number_integers(action, values)
        class(array_numbering), intent(inout) :: action
        integer, allocatable, intent(inout) :: values(:)
        integer, allocatable :: expected(:)
        integer :: length

        length = -1
        if (allocated(values)) length = size(values)
        call expected_numbers(action, length, expected)
        if (.not. allocated(expected)) return
        if (.not. allocated(action%pick)) then
            values = expected
        else if (any(values /= expected)) then
            action%problem = action%problem//' integer array '//itoa(action%arrays)// &
                             ' holds other values'
        end if
    end subroutine number_integers

    !> The numbers of the next array; unallocated (and a problem noted) when the array is
    !> not allocated with n elements.
    subroutine expected_numbers(action, length, expected)
        type(array_numbering), intent(inout) :: action
        !> Size of the array, -1 when it is not allocated
        integer, intent(in) :: length
        integer, allocatable, intent(out) :: expected(:)
        integer :: i

        action%arrays = action%arrays + 1
        if (length < 0) then
            action%problem = action%problem//' array '//itoa(action%arrays)// &
                             ' is not allocated'
        else if (length /= action%n) then
            action%problem = action%problem//' array '//itoa(action%arrays)//' has '// &
                             itoa(length)//' elements'
        else if (allocated(action%pick)) then
            expected = 1000 * action%arrays + action%pick
        else
            expected = 1000 * action%arrays + [(i, i = 1, action%n)]
        end if
    end subroutine expected_numbers

    ! ---- helpers ------------------------------------------------------------------------

    !> Append a fracture along the polyline (x, y) with counts elements per segment.
    subroutine add_fracture(mesh, name, x, y, counts)
        type(mesh_builder), intent(inout) :: mesh
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: x(:), y(:)
        integer, intent(in) :: counts(:)
        real(wp), allocatable :: xb(:), yb(:), xe(:), ye(:)
        type(element_set) :: old, grown
        type(fracture_type) :: fracture
        integer :: n0, n

        call polyline_elements(x, y, counts, xb, yb, xe, ye)
        old = mesh%elements
        n0 = old%n
        n = n0 + size(xb)
        call allocate_elements(grown, n)
        if (n0 > 0) then
            grown%x_begin(1:n0) = old%x_begin
            grown%y_begin(1:n0) = old%y_begin
            grown%x_end(1:n0) = old%x_end
            grown%y_end(1:n0) = old%y_end
            grown%fracture_id(1:n0) = old%fracture_id
        end if
        mesh%elements = grown
        mesh%elements%x_begin(n0 + 1:) = xb
        mesh%elements%y_begin(n0 + 1:) = yb
        mesh%elements%x_end(n0 + 1:) = xe
        mesh%elements%y_end(n0 + 1:) = ye
        if (.not. allocated(mesh%fractures)) allocate (mesh%fractures(0))
        mesh%elements%fracture_id(n0 + 1:) = size(mesh%fractures) + 1
        fracture%name = name
        fracture%first_element = n0 + 1
        fracture%last_element = n
        mesh%fractures = [mesh%fractures, fracture]
    end subroutine add_fracture

    !> Append a closed circle of radius r around the origin: n elements, the last ending
    !> exactly on the first vertex.
    subroutine add_circle(mesh, name, r, n)
        type(mesh_builder), intent(inout) :: mesh
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: r
        integer, intent(in) :: n
        real(wp) :: x(n + 1), y(n + 1)
        integer :: i

        do i = 1, n
            x(i) = r * cos(2.0_wp * pi * real(i - 1, wp) / real(n, wp))
            y(i) = r * sin(2.0_wp * pi * real(i - 1, wp) / real(n, wp))
        end do
        x(n + 1) = x(1)
        y(n + 1) = y(1)
        call add_fracture(mesh, name, x, y, [(1, i = 1, n)])
    end subroutine add_circle

    !> Fractures 'a' and 'b' must be rejected with a message naming the first element of
    !> each and the problem.
    subroutine expect_pair_rejected(error, xa, ya, counts_a, xb, yb, counts_b, problem)
        type(error_type), allocatable, intent(inout) :: error
        real(wp), intent(in) :: xa(:), ya(:), xb(:), yb(:)
        integer, intent(in) :: counts_a(:), counts_b(:)
        character(len=*), intent(in) :: problem
        type(mesh_builder) :: mesh

        call add_fracture(mesh, 'a', xa, ya, counts_a)
        call add_fracture(mesh, 'b', xb, yb, counts_b)
        call expect_rejected(error, mesh, [character(len=60) :: "fracture 'a' element 1", &
                             "fracture 'b' element 1", problem])
    end subroutine expect_pair_rejected

    !> The checks must reject the mesh with a message holding every fragment.
    subroutine expect_rejected(error, mesh, fragments)
        type(error_type), allocatable, intent(inout) :: error
        type(mesh_builder), intent(in) :: mesh
        character(len=*), intent(in) :: fragments(:)
        type(error_type), allocatable :: check_error
        integer :: i

        call check_elements(mesh%elements, mesh%fractures, check_error)
        call check(error, allocated(check_error), 'bad mesh accepted')
        if (allocated(error)) return
        call check(error, check_error%code, exit_bad_input, 'error code')
        do i = 1, size(fragments)
            call check(error, index(check_error%message, trim(fragments(i))) > 0, &
                       "the message lacks '"//trim(fragments(i))//"': "//check_error%message)
        end do
    end subroutine expect_rejected

    !> The checks must accept the mesh.
    subroutine expect_accepted(error, mesh)
        type(error_type), allocatable, intent(inout) :: error
        type(mesh_builder), intent(in) :: mesh
        type(error_type), allocatable :: check_error

        call check_elements(mesh%elements, mesh%fractures, check_error)
        if (allocated(check_error)) then
            call check(error, .false., 'good mesh rejected: '//check_error%message)
        end if
    end subroutine expect_accepted

    ! ---- polyline -----------------------------------------------------------------------

    subroutine test_polyline_subdivision(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: xb(:), yb(:), xe(:), ye(:)
        integer :: i

        call polyline_elements([0.0_wp, 1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp, 2.0_wp], [2, 4], &
                               xb, yb, xe, ye)
        call check(error, size(xb), 6, 'number of elements')
        if (allocated(error)) return
        call check(error, xe(1), 0.5_wp, 'x_end(1)', abs_tol=tight)
        call check(error, xe(2), 1.0_wp, 'x_end(2) is the vertex', abs_tol=0.0_wp)
        call check(error, xb(3), 1.0_wp, 'x_begin(3) is the vertex', abs_tol=0.0_wp)
        call check(error, yb(3), 0.0_wp, 'y_begin(3) is the vertex', abs_tol=0.0_wp)
        call check(error, ye(3), 0.5_wp, 'y_end(3)', abs_tol=tight)
        call check(error, ye(5), 1.5_wp, 'y_end(5)', abs_tol=tight)
        call check(error, ye(6), 2.0_wp, 'last end is the last vertex', abs_tol=0.0_wp)
        do i = 1, 5
            call check(error, xe(i) == xb(i + 1) .and. ye(i) == yb(i + 1), &
                       'consecutive elements share their end point exactly')
        end do
    end subroutine test_polyline_subdivision

    subroutine test_expand_per_segment(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: per_element(:)

        allocate (per_element(5))
        per_element = expand_per_segment([0.5_wp, 0.7_wp], [2, 3])
        call check(error, size(per_element), 5, 'size')
        if (allocated(error)) return
        call check(error, per_element(2), 0.5_wp, 'element 2', abs_tol=0.0_wp)
        call check(error, per_element(3), 0.7_wp, 'element 3', abs_tol=0.0_wp)
        call check(error, per_element(5), 0.7_wp, 'element 5', abs_tol=0.0_wp)
    end subroutine test_expand_per_segment

    ! ---- checks: rejected ---------------------------------------------------------------

    subroutine test_zero_length(error)
        type(error_type), allocatable, intent(out) :: error
        type(mesh_builder) :: mesh

        call add_fracture(mesh, 'a', [0.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [2])
        call add_fracture(mesh, 'b', [0.0_wp, 1.0_wp, 1.0_wp], [1.0_wp, 1.0_wp, 1.0_wp], [1, 1])
        call expect_rejected(error, mesh, [character(len=60) :: &
                             "fracture 'b' element 2 (model element 4) has zero length"])
    end subroutine test_zero_length

    subroutine test_duplicate(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_pair_rejected(error, [0.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [1], &
                                  [1.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], [1], 'duplicates')
    end subroutine test_duplicate

    subroutine test_overlap(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_pair_rejected(error, [0.0_wp, 2.0_wp], [0.0_wp, 0.0_wp], [1], &
                                  [1.0_wp, 3.0_wp], [0.0_wp, 0.0_wp], [2], 'overlap')
    end subroutine test_overlap

    subroutine test_overlap_folded(error)
        type(error_type), allocatable, intent(out) :: error
        type(mesh_builder) :: mesh

        ! the polyline turns back on itself at the shared vertex (2, 0)
        call add_fracture(mesh, 'fold', [0.0_wp, 2.0_wp, 1.0_wp], [0.0_wp, 0.0_wp, 0.0_wp], &
                          [1, 1])
        call expect_rejected(error, mesh, [character(len=60) :: "fracture 'fold' element 1", &
                             "fracture 'fold' element 2", 'overlap'])
    end subroutine test_overlap_folded

    subroutine test_crossing(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_pair_rejected(error, [-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [1], &
                                  [0.1_wp, -0.1_wp], [-1.0_wp, 1.0_wp], [1], 'cross')
    end subroutine test_crossing

    subroutine test_t_junction(error)
        type(error_type), allocatable, intent(out) :: error
        type(mesh_builder) :: mesh

        call add_fracture(mesh, 'main', [-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [1])
        call add_fracture(mesh, 'splay', [0.0_wp, 0.5_wp], [0.0_wp, 1.0_wp], [3])
        call expect_rejected(error, mesh, [character(len=80) :: &
            "an end of fracture 'splay' element 1 (model element 2) touches the interior", &
            "fracture 'main' element 1", 'T-junction', 'vertex at the branch point'])
    end subroutine test_t_junction

    subroutine test_t_junction_tolerance(error)
        type(error_type), allocatable, intent(out) :: error
        type(mesh_builder) :: mesh

        ! the branch ends 1e-13 (relative to a length of 2) away from the main fault
        call add_fracture(mesh, 'main', [-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [1])
        call add_fracture(mesh, 'splay', [0.0_wp, 0.0_wp], [1.0_wp, 1.0e-13_wp], [1])
        call expect_rejected(error, mesh, [character(len=60) :: 'T-junction'])
    end subroutine test_t_junction_tolerance

    ! ---- checks: accepted ---------------------------------------------------------------

    subroutine test_near_miss(error)
        type(error_type), allocatable, intent(out) :: error
        type(mesh_builder) :: mesh

        ! a gap of 1e-6 is real geometry, not a touch; parallel neighbours too
        call add_fracture(mesh, 'main', [-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [4])
        call add_fracture(mesh, 'branch', [0.0_wp, 0.0_wp], [1.0e-6_wp, 1.0_wp], [2])
        call add_fracture(mesh, 'parallel', [-1.0_wp, 1.0_wp], [-1.0e-3_wp, -1.0e-3_wp], [4])
        ! collinear, end to end with a gap, and end to end sharing a vertex
        call add_fracture(mesh, 'gap', [1.5_wp, 2.0_wp], [0.0_wp, 0.0_wp], [1])
        call add_fracture(mesh, 'joined', [2.0_wp, 3.0_wp], [0.0_wp, 0.0_wp], [1])
        call expect_accepted(error, mesh)
    end subroutine test_near_miss

    subroutine test_closed_loop(error)
        type(error_type), allocatable, intent(out) :: error
        type(mesh_builder) :: mesh

        call add_circle(mesh, 'circle', 1.0_wp, 64)
        call expect_accepted(error, mesh)
    end subroutine test_closed_loop

    subroutine test_branch(error)
        type(error_type), allocatable, intent(out) :: error
        type(mesh_builder) :: mesh

        ! four fractures meeting at the origin, where each has a vertex
        call add_fracture(mesh, 'east', [0.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [2])
        call add_fracture(mesh, 'west', [-2.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], [3])
        call add_fracture(mesh, 'north_west', [0.0_wp, -1.0_wp], [0.0_wp, 1.0_wp], [2])
        call add_fracture(mesh, 'south_east', [1.0_wp, 0.0_wp], [-1.0_wp, 0.0_wp], [2])
        ! a kinked fault
        call add_fracture(mesh, 'kink', [3.0_wp, 4.0_wp, 5.0_wp], [0.0_wp, 0.0_wp, 1.0_wp], &
                          [5, 5])
        call expect_accepted(error, mesh)
    end subroutine test_branch

    !> 4000-element meshes: a circle and a vertical line (every element in one x-range,
    !> the sweep's worst case). Not timed here; the benchmark measures speed.
    subroutine test_large(error)
        type(error_type), allocatable, intent(out) :: error
        type(mesh_builder) :: circle, vertical
        integer, parameter :: n = 4000

        call add_circle(circle, 'circle', 10.0_wp, n)
        call expect_accepted(error, circle)
        call add_fracture(vertical, 'vertical', [5.0_wp, 5.0_wp], [0.0_wp, 1.0_wp], [n])
        call expect_accepted(error, vertical)
    end subroutine test_large

end module test_mesh
