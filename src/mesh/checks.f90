!> Geometric checks of a mesh: no zero-length, duplicate, overlapping or crossing elements.
!>
!> Elements may share end points (polyline vertices, branches, closed loops); any other
!> contact between two elements is an error. A T-junction must put a vertex at the branch
!> point. Tolerances are relative to the element lengths (1e-10) plus a few ulps of the
!> coordinates. Pairs are found with a sweep over the x-extents (sorted), so typical
!> meshes cost about N log N; the worst case stays O(N^2).
module ddc_mesh_checks
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_types, only: element_set, fracture_type, symmetry_x, symmetry_y, symmetry_both
    use ddc_text, only: add_message, messages_error, itoa, rtoa
    use ddc_sorting, only: sorted_order
    use ddc_mesh_segments, only: classify_pair, pair_ok, pair_duplicate, pair_overlap, &
        pair_cross, pair_t_first_end, pair_t_second_end
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    implicit none
    private

    public :: check_elements

    !> Relative tolerance on element lengths
    real(wp), parameter :: relative_tolerance = 1.0e-10_wp

contains

    !> Reject zero-length, duplicate, overlapping and crossing elements, and elements whose
    !> end touches another element's interior. The message names fractures and elements.
    subroutine check_elements(elements, fractures, error)
        !> The elements, with end points set
        type(element_set), intent(in) :: elements
        !> The fractures, for naming elements in messages
        type(fracture_type), intent(in) :: fractures(:)
        !> Allocated (code exit_bad_input) listing every problem found
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: length(:), tol(:), xmin(:), xmax(:), ymin(:), ymax(:)
        integer, allocatable :: order(:)
        logical, allocatable :: degenerate(:)
        character(len=:), allocatable :: messages
        real(wp) :: scale, extent, absolute_tol, pair_tol, tol_max
        integer :: n, i, j, a, b, kind, nbad

        n = elements%n
        messages = ''
        nbad = 0
        if (n == 0) return
        do i = 1, n
            if (.not. (ieee_is_finite(elements%x_begin(i)) .and. &
                       ieee_is_finite(elements%y_begin(i)) .and. &
                       ieee_is_finite(elements%x_end(i)) .and. &
                       ieee_is_finite(elements%y_end(i)))) then
                call add_message(messages, nbad, describe(i)// &
                                 ' has a coordinate that is NaN or Inf')
            end if
        end do
        if (nbad > 0) then
            call messages_error(messages, nbad, 'mesh problems', error)
            return
        end if

        allocate (length(n), tol(n), xmin(n), xmax(n), ymin(n), ymax(n), degenerate(n))
        length = hypot(elements%x_end - elements%x_begin, elements%y_end - elements%y_begin)
        xmin = min(elements%x_begin, elements%x_end)
        xmax = max(elements%x_begin, elements%x_end)
        ymin = min(elements%y_begin, elements%y_end)
        ymax = max(elements%y_begin, elements%y_end)
        scale = max(maxval(abs(xmin)), maxval(abs(xmax)), maxval(abs(ymin)), maxval(abs(ymax)))
        extent = max(maxval(xmax) - minval(xmin), maxval(ymax) - minval(ymin))
        absolute_tol = 16.0_wp * epsilon(1.0_wp) * scale
        tol = relative_tolerance * length + absolute_tol
        degenerate = length <= max(1.0e-12_wp * extent, absolute_tol)
        do i = 1, n
            if (degenerate(i)) then
                call add_message(messages, nbad, describe(i)//' has zero length')
            end if
        end do

        ! Sweep: sort by xmin, compare each element with those starting before it ends.
        order = sorted_order(xmin)
        tol_max = maxval(tol)
        do a = 1, n
            i = order(a)
            if (degenerate(i)) cycle
            do b = a + 1, n
                j = order(b)
                if (xmin(j) > xmax(i) + tol(i) + tol_max) exit
                if (degenerate(j)) cycle
                if (xmin(j) - tol(j) > xmax(i) + tol(i)) cycle
                if (ymin(j) - tol(j) > ymax(i) + tol(i)) cycle
                if (ymax(j) + tol(j) < ymin(i) - tol(i)) cycle
                pair_tol = max(tol(i), tol(j))
                kind = classify_pair(elements%x_begin(i), elements%y_begin(i), &
                                     elements%x_end(i), elements%y_end(i), &
                                     elements%x_begin(j), elements%y_begin(j), &
                                     elements%x_end(j), elements%y_end(j), pair_tol)
                if (kind /= pair_ok) call report_pair(min(i, j), max(i, j), i, kind)
            end do
        end do
        call check_symmetry_lines()
        if (nbad > 0) call messages_error(messages, nbad, 'mesh problems', error)

    contains

        !> With symmetry every element must lie on one side of each symmetry line (ends on
        !> the line are fine: the image continues the fracture); an element on the line or
        !> elements on both sides would overlap their images.
        subroutine check_symmetry_lines()
            associate (sym => elements%symmetry)
                if (sym%kind == symmetry_x .or. sym%kind == symmetry_both) call one_side( &
                    elements%x_begin - sym%xsym, elements%x_end - sym%xsym, 'x', sym%xsym)
                if (sym%kind == symmetry_y .or. sym%kind == symmetry_both) call one_side( &
                    elements%y_begin - sym%ysym, elements%y_end - sym%ysym, 'y', sym%ysym)
            end associate
        end subroutine check_symmetry_lines

        !> d1, d2: signed distances of the element ends from the line `axis` = position.
        subroutine one_side(d1, d2, axis, position)
            real(wp), intent(in) :: d1(:), d2(:), position
            character(len=*), intent(in) :: axis
            integer :: first_side, k, side

            first_side = 0
            do k = 1, n
                side = 0
                if (max(d1(k), d2(k)) > tol(k)) side = 1
                if (min(d1(k), d2(k)) < -tol(k)) side = side - 1
                if (side == 0) then
                    ! Both ends within tolerance of the line, or one on each side.
                    call add_message(messages, nbad, describe(k)//' lies on or crosses the '// &
                        'symmetry line '//axis//' = '//rtoa(position)//'; model one side only')
                else if (first_side == 0) then
                    first_side = k
                else if (sign(1.0_wp, d1(k) + d2(k)) /= sign(1.0_wp, d1(first_side) + &
                                                             d2(first_side))) then
                    call add_message(messages, nbad, describe(first_side)//' and '// &
                        describe(k)//' lie on opposite sides of the symmetry line '//axis// &
                        ' = '//rtoa(position)//'; model one side only')
                    return
                end if
            end do
        end subroutine one_side

        !> Append the message for the pair (first, second); kind refers to (i, other).
        subroutine report_pair(first, second, i_of_kind, kind)
            integer, intent(in) :: first, second, i_of_kind, kind
            integer :: touching, touched

            select case (kind)
            case (pair_duplicate)
                call add_message(messages, nbad, describe(first)//' and '//describe(second)// &
                                 ' are duplicates (same end points)')
            case (pair_overlap)
                call add_message(messages, nbad, describe(first)//' and '//describe(second)// &
                                 ' overlap (collinear and sharing a stretch)')
            case (pair_cross)
                call add_message(messages, nbad, describe(first)//' and '//describe(second)// &
                                 ' cross each other; put a vertex at the intersection')
            case (pair_t_first_end, pair_t_second_end)
                ! kind is relative to the order (i_of_kind, other) of classify_pair
                if ((kind == pair_t_first_end) .eqv. (i_of_kind == first)) then
                    touching = first
                    touched = second
                else
                    touching = second
                    touched = first
                end if
                call add_message(messages, nbad, 'an end of '//describe(touching)// &
                                 ' touches the interior of '//describe(touched)// &
                                 ' (T-junction): split the fracture with a vertex at the '// &
                                 'branch point so that the elements share it')
            case default
                ! pair_ok: nothing to report
            end select
        end subroutine report_pair

        !> "fracture 'name' element k (model element i)"
        function describe(element) result(text)
            integer, intent(in) :: element
            character(len=:), allocatable :: text
            integer :: f

            f = 0
            if (allocated(elements%fracture_id)) then
                if (element <= size(elements%fracture_id)) f = elements%fracture_id(element)
            end if
            if (f >= 1 .and. f <= size(fractures)) then
                if (allocated(fractures(f)%name)) then
                    text = "fracture '"//fractures(f)%name//"' element "// &
                           itoa(element - fractures(f)%first_element + 1)// &
                           ' (model element '//itoa(element)//')'
                    return
                end if
            end if
            text = 'element '//itoa(element)
        end function describe

    end subroutine check_elements

end module ddc_mesh_checks
