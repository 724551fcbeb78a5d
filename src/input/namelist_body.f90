!> The &body group of a namelist input file (docs/finite-bodies.md): the closed polygon of a
!> finite body, its elements per side, and each side's condition with its given values at
!> the side's first vertex and (optionally) at its next. Once the fractures exist,
!> check_body_model holds them and the rest of the model to what a body solves.
module ddc_input_namelist_body
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, condition_traction, condition_displacement, &
        condition_mixed_us_sn, condition_mixed_ss_un, condition_names, domain_full_plane, &
        condition_contact, condition_prescribed_dd, symmetry_none
    use ddc_model_body, only: finite_body, set_body_geometry, inside_body
    use ddc_contact_options, only: matrix_hierarchical, k_higher_order
    use ddc_text, only: lower, find_name, quoted_list, itoa
    use ddc_mesh_segments, only: segment_distance
    use ddc_input_namelist_groups, only: group_record, message_list, add, group_label, g_body
    use ddc_input_namelist_diagnosis, only: report_malformed
    use ddc_input_namelist_values, only: unset_real, unset_integer, count_given, &
        count_given_integers, check_length, broadcast, broadcast_integers
    implicit none
    private

    public :: read_body_group, check_body_model

    !> At most this many sides
    integer, parameter :: max_sides = 10000
    !> The conditions a side may take
    integer, parameter :: side_conditions(4) = [condition_traction, condition_displacement, &
        condition_mixed_us_sn, condition_mixed_ss_un]

contains

    !> &body x, y, elements, condition, bc_s, bc_n, bc_s_end, bc_n_end / (at most one).
    subroutine read_body_group(unit, text, path, info, model, messages)
        !> Unit of the open input file
        integer, intent(in) :: unit
        !> Text and path of the input file
        character(len=*), intent(in) :: text, path
        !> Where the group occurs
        type(group_record), intent(in) :: info
        !> model%body is allocated when the group is there and valid
        type(model_type), intent(inout) :: model
        !> Violations are added here
        type(message_list), intent(inout) :: messages
        real(wp), allocatable :: x(:), y(:), bc_s(:), bc_n(:), bc_s_end(:), bc_n_end(:)
        integer, allocatable :: elements(:)
        character(len=13), allocatable :: condition(:)
        character(len=512) :: iomsg
        character(len=:), allocatable :: prefix
        type(finite_body) :: read
        integer :: stat, m, n_before, k, code
        namelist /body/ x, y, elements, condition, bc_s, bc_n, bc_s_end, bc_n_end

        if (info%count == 0) return
        allocate (x(max_sides), y(max_sides), bc_s(max_sides), bc_n(max_sides), &
                  bc_s_end(max_sides), bc_n_end(max_sides), elements(max_sides), &
                  condition(max_sides))
        x = unset_real
        y = unset_real
        bc_s = unset_real
        bc_n = unset_real
        bc_s_end = unset_real
        bc_n_end = unset_real
        elements = unset_integer
        condition = ''
        rewind (unit)
        read (unit, nml=body, iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            call report_malformed(text, path, g_body, info, 1, stat, iomsg, messages)
            return
        end if
        prefix = path//': '//group_label(g_body, 1, info%lines(1), '')//': '
        n_before = messages%n
        m = count_given(x, 'x', prefix, messages)
        if (count_given(y, 'y', prefix, messages) /= m) then
            call add(messages, prefix//'x and y must have the same number of values')
        else if (m < 3) then
            call add(messages, prefix//'x, y need at least 3 vertices (the closed polygon '// &
                     'of the body, its first vertex not repeated)')
        end if
        if (messages%n > n_before) return
        read%x = x(1:m)
        read%y = y(1:m)
        call read_sides()
        if (messages%n > n_before) return
        call check_polygon(read, prefix, messages)
        if (messages%n > n_before) return
        call set_body_geometry(read)
        model%body = read

    contains

        !> Elements, conditions and values per side.
        subroutine read_sides()
            integer :: n

            n = count_given_integers(elements, 'elements', prefix, messages)
            if (n == 0) then
                call add(messages, prefix//'elements is required: the number of elements of '// &
                         'each side (one value for every side, or one per side)')
            else if (check_length(n, m, 'elements', prefix, messages)) then
                read%elements = broadcast_integers(elements(1:n), m)
                if (any(read%elements < 1)) then
                    call add(messages, prefix//'elements must be at '// &
                             'least 1 on every side')
                end if
            end if
            n = count([(len_trim(condition(k)) > 0, k = 1, max_sides)])
            allocate (read%condition(m))
            read%condition = condition_traction
            if (check_length(n, m, 'condition', prefix, messages)) then
                do k = 1, n
                    code = find_name(lower(trim(adjustl(condition(k)))), condition_names)
                    if (all(side_conditions /= code)) then
                        call add(messages, prefix//"condition("//itoa(k)//") = '"// &
                                 trim(condition(k))//"' is not one of "// &
                                 quoted_list(condition_names(side_conditions)))
                        return
                    end if
                    if (n == 1) then
                        read%condition = code
                    else
                        read%condition(k) = code
                    end if
                end do
            end if
            read%bc_s = side_values(bc_s, 'bc_s', [(0.0_wp, k = 1, m)])
            read%bc_n = side_values(bc_n, 'bc_n', [(0.0_wp, k = 1, m)])
            read%bc_s_end = side_values(bc_s_end, 'bc_s_end', read%bc_s)
            read%bc_n_end = side_values(bc_n_end, 'bc_n_end', read%bc_n)
        end subroutine read_sides

        !> One value per side from 1 or m given ones, else the defaults.
        function side_values(values, name, defaults) result(out)
            real(wp), intent(in) :: values(:)
            character(len=*), intent(in) :: name
            real(wp), intent(in) :: defaults(:)
            real(wp) :: out(m)
            integer :: n

            out = defaults
            n = count_given(values, name, prefix, messages)
            if (n == 0) return
            if (check_length(n, m, name, prefix, messages)) out = broadcast(values(1:n), m, 0.0_wp)
        end function side_values
    end subroutine read_body_group

    !> The polygon is simple: no side of zero length, no two sides crossing or touching
    !> except neighbours at their common vertex, an area (vertices on one line enclose none).
    subroutine check_polygon(body, prefix, messages)
        type(finite_body), intent(in) :: body
        character(len=*), intent(in) :: prefix
        type(message_list), intent(inout) :: messages
        integer :: i, j, m
        real(wp) :: extent

        m = size(body%x)
        extent = max(maxval(body%x) - minval(body%x), maxval(body%y) - minval(body%y))
        do i = 1, m
            if (hypot(body%x(next(i)) - body%x(i), body%y(next(i)) - body%y(i)) == 0.0_wp) then
                call add(messages, prefix//'side '//itoa(i)//' has zero length (a repeated '// &
                         'vertex: give the first vertex once)')
                return
            end if
        end do
        do i = 1, m
            do j = i + 2, m
                if (i == 1 .and. j == m) cycle
                if (segment_distance(body%x(i), body%y(i), body%x(next(i)), body%y(next(i)), &
                                     body%x(j), body%y(j), body%x(next(j)), body%y(next(j))) &
                    <= 0.0_wp) then
                    call add(messages, prefix//'sides '//itoa(i)//' and '//itoa(j)//' cross: '// &
                             'the body must be one simple polygon')
                    return
                end if
            end do
        end do
        if (abs(sum(body%x * cshift(body%y, 1) - cshift(body%x, 1) * body%y)) <= &
            1.0e-12_wp * extent**2) then
            call add(messages, prefix//'x, y enclose no area: the body needs vertices off '// &
                     'one line')
        end if

    contains

        pure integer function next(i)
            integer, intent(in) :: i

            next = merge(1, i + 1, i == m)
        end function next
    end subroutine check_polygon

    !> What a finite body solves (docs/finite-bodies.md#what-a-body-solves): fractures
    !> strictly inside it, of conditions traction, contact or prescribed DD, in the full
    !> plane, without remote stress, symmetry, loading history, initiation, cycles or
    !> hierarchical matrices.
    subroutine check_body_model(path, model, messages)
        character(len=*), intent(in) :: path
        type(model_type), intent(in) :: model
        type(message_list), intent(inout) :: messages
        character(len=:), allocatable :: prefix
        real(wp) :: tolerance
        integer :: j

        if (.not. allocated(model%body)) return
        prefix = path//': &body: '
        if (model%elements%domain /= domain_full_plane) then
            call add(messages, prefix//"a finite body lies in the full plane (&model domain "// &
                     "= 'full_plane')")
        end if
        if (any([model%sxx, model%syy, model%sxy, model%stress_gradient] /= 0.0_wp)) then
            call add(messages, prefix//'a finite body is loaded through its boundary: give '// &
                     'no &remote_stress (its tractions are bc_s, bc_n of the sides)')
        end if
        if (model%elements%symmetry%kind /= symmetry_none) then
            call add(messages, prefix//'a finite body takes no &symmetry: give the whole body')
        end if
        if (allocated(model%load_path%time) .or. allocated(model%load_path%steps)) then
            call add(messages, prefix//'a finite body is solved at one load: no &load_path yet')
        end if
        if (model%initiation%active) then
            call add(messages, prefix//'no &initiation in a finite body yet (its fractures '// &
                     'grow from their tips: &growth)')
        end if
        if (model%cycle%active) call add(messages, prefix//'no &cycle in a finite body')
        if (model%solver%matrix == matrix_hierarchical) then
            call add(messages, prefix//"a finite body takes dense matrices: &solver matrix = "// &
                     "'dense' or 'auto'")
        end if
        if (model%solver%k_method == k_higher_order) then
            call add(messages, prefix//"K in a finite body comes from the tip element: "// &
                     "&solver k_method = 'auto' or 'tip_element'")
        end if
        associate (e => model%elements, body => model%body)
            tolerance = 1.0e-9_wp * max(maxval(body%x) - minval(body%x), &
                                        maxval(body%y) - minval(body%y))
            do j = 1, e%n
                if (all(e%condition(j) /= [condition_traction, condition_contact, &
                                           condition_prescribed_dd])) then
                    call add(messages, prefix//'element '//itoa(j)//' of the fractures has '// &
                             "condition '"//trim(condition_names(e%condition(j)))//"': in a "// &
                             "finite body a fracture is 'traction', 'contact' or "// &
                             "'prescribed_dd'")
                    return
                end if
                if (.not. (inside_body(body, e%x_mid(j) - e%half_length(j) * e%cos_beta(j), &
                                       e%y_mid(j) - e%half_length(j) * e%sin_beta(j), &
                                       tolerance) .and. &
                           inside_body(body, e%x_mid(j) + e%half_length(j) * e%cos_beta(j), &
                                       e%y_mid(j) + e%half_length(j) * e%sin_beta(j), &
                                       tolerance))) then
                    call add(messages, prefix//'element '//itoa(j)//' of the fractures '// &
                             'is not inside the body: every fracture lies strictly inside it')
                    return
                end if
            end do
        end associate
    end subroutine check_body_model

end module ddc_input_namelist_body
