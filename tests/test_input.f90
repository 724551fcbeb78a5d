!> Tests of the input layer: text files, CSV files and the namelist model reader.
!> Data files are under tests/data/input/ (the tests run in tests/).
module test_input
    use ddc_kinds, only: wp
    use ddc_contact_options, only: lcp_lemke, lcp_auto, cohesion_lost, cohesion_kept
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_error, only: exit_bad_input
    use ddc_model_types, only: model_type, condition_contact, condition_traction, &
        observation_grid, observation_line, observation_points, rigid_joint
    use ddc_input_text_file, only: read_text_file
    use ddc_input_csv, only: read_csv
    use ddc_input_namelist, only: read_namelist_model
    implicit none
    private
    public :: collect_input, check_bad_input

    character(len=*), parameter :: data = 'data/input/'
    character(len=*), parameter :: element_header(7) = [character(len=8) :: 'x_begin', &
        'y_begin', 'x_end', 'y_end', 'mu', 'sf', 'pressure']
    real(wp), parameter :: tight = 1.0e-14_wp

contains

    !> Cases of the input suite.
    subroutine collect_input(tests)
        !> The cases
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [ &
            new_test('text_file_missing', test_text_file_missing), &
            new_test('text_file_empty', test_text_file_empty), &
            new_test('text_file_binary', test_text_file_binary), &
            new_test('csv_elements', test_csv_elements), &
            new_test('csv_points_without_header', test_csv_points_without_header), &
            new_test('csv_bad_lines', test_csv_bad_lines), &
            new_test('csv_wrong_header', test_csv_wrong_header), &
            new_test('csv_no_rows', test_csv_no_rows), &
            new_test('namelist_good_elements', test_good_elements), &
            new_test('namelist_good_observations', test_good_observations), &
            new_test('namelist_good_defaults', test_good_defaults), &
            new_test('namelist_good_output_and_defaults', test_good_output), &
            new_test('bad_elastic_all_at_once', test_bad_elastic), &
            new_test('bad_mu', test_bad_mu), &
            new_test('bad_sf', test_bad_sf), &
            new_test('namelist_good_strength', test_good_strength), &
            new_test('bad_strength', test_bad_strength), &
            new_test('bad_strength_csv', test_bad_strength_csv), &
            new_test('bad_strength_with_growth', test_bad_strength_growth), &
            new_test('bad_block_size', test_bad_block_size), &
            new_test('bad_nan_and_inf', test_bad_nan), &
            new_test('bad_strength_nan', test_bad_strength_nan), &
            new_test('bad_vertices', test_bad_vertices), &
            new_test('bad_xy_length', test_bad_xy_length), &
            new_test('bad_segment_array', test_bad_segment_array), &
            new_test('bad_elements', test_bad_elements), &
            new_test('bad_condition', test_bad_condition), &
            new_test('bad_grid', test_bad_grid), &
            new_test('bad_line', test_bad_line), &
            new_test('bad_missing_csv', test_bad_missing_csv), &
            new_test('bad_points_csv', test_bad_points_csv), &
            new_test('bad_no_fracture', test_bad_no_fracture), &
            new_test('bad_unknown_group', test_bad_unknown_group), &
            new_test('bad_misspelled_variable', test_bad_misspelled), &
            new_test('bad_type_in_last_group', test_bad_type_last), &
            new_test('bad_type_in_middle_group', test_bad_type_middle), &
            new_test('bad_missing_model', test_bad_missing_model), &
            new_test('bad_several_groups', test_bad_several_groups), &
            new_test('bad_gap', test_bad_gap), &
            new_test('bad_duplicate_names', test_bad_duplicate_names), &
            new_test('bad_both_geometries', test_bad_both_geometry), &
            new_test('bad_crossing_mesh', test_bad_crossing), &
            new_test('bad_missing_input_file', test_bad_missing_input), &
            new_test('bad_load_path_length', test_bad_load_path_length) &
            ]
    end subroutine collect_input

    ! ---- helpers ------------------------------------------------------------------------

    !> Read path, expect exit_bad_input with a message holding the file and each fragment.
    subroutine check_bad_input(error, path, fragments, lines)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: path
        character(len=*), intent(in) :: fragments(:)
        !> Expected number of message lines, when given
        integer, intent(in), optional :: lines
        type(model_type) :: model
        type(error_type), allocatable :: read_error
        integer :: i

        call read_namelist_model(path, model, read_error)
        call check(error, allocated(read_error), path//': no error reported')
        if (allocated(error)) return
        call check(error, read_error%code, exit_bad_input, path//': error code')
        call check(error, index(read_error%message, path) > 0, &
                   'the message does not name the file: '//read_error%message)
        do i = 1, size(fragments)
            call check(error, index(read_error%message, trim(fragments(i))) > 0, &
                       "the message lacks '"//trim(fragments(i))//"': "//read_error%message)
        end do
        if (present(lines)) then
            call check(error, count_lines(read_error%message), lines, &
                       'lines in the message: '//read_error%message)
        end if
    end subroutine check_bad_input

    !> Number of lines of a message.
    pure function count_lines(text) result(n)
        character(len=*), intent(in) :: text
        integer :: n
        integer :: i

        n = 1
        do i = 1, len(text)
            if (text(i:i) == achar(10)) n = n + 1
        end do
    end function count_lines

    !> Read a good file; fail with the reader's message when it reports an error.
    subroutine read_good(error, path, model)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: path
        type(model_type), intent(out) :: model
        type(error_type), allocatable :: read_error

        call read_namelist_model(path, model, read_error)
        if (allocated(read_error)) then
            call check(error, .false., path//' was rejected: '//read_error%message)
        end if
    end subroutine read_good

    ! ---- text files ---------------------------------------------------------------------

    subroutine test_text_file_missing(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        type(error_type), allocatable :: read_error

        call read_text_file(data//'no_such_file.nml', text, read_error)
        call check(error, allocated(read_error), 'missing file accepted')
        if (allocated(error)) return
        call check(error, read_error%code, exit_bad_input, 'error code')
        call check(error, index(read_error%message, data//'no_such_file.nml') > 0, &
                   'path in message: '//read_error%message)
    end subroutine test_text_file_missing

    subroutine test_text_file_empty(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        type(error_type), allocatable :: read_error

        call read_text_file(data//'empty.nml', text, read_error)
        call check(error, allocated(read_error), 'empty file accepted')
        if (allocated(error)) return
        call check(error, read_error%code, exit_bad_input, 'error code')
        call check(error, index(read_error%message, 'empty') > 0, read_error%message)
    end subroutine test_text_file_empty

    subroutine test_text_file_binary(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        type(error_type), allocatable :: read_error

        call read_text_file(data//'binary.nml', text, read_error)
        call check(error, allocated(read_error), 'binary file accepted')
        if (allocated(error)) return
        call check(error, read_error%code, exit_bad_input, 'error code')
        call check(error, index(read_error%message, data//'binary.nml') > 0, read_error%message)
        ! a good file comes back whole, newlines included
        deallocate (read_error)
        call read_text_file(data//'bad_sf.nml', text, read_error)
        call check(error, .not. allocated(read_error), 'good text file rejected')
        call check(error, index(text, achar(10)//'&fracture') > 0, 'text lacks its newlines')
    end subroutine test_text_file_binary

    ! ---- CSV ----------------------------------------------------------------------------

    subroutine test_csv_elements(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: values(:,:)
        integer, allocatable :: lines(:)
        type(error_type), allocatable :: read_error

        call read_csv(data//'csv/elements.csv', element_header, values, read_error, lines)
        if (allocated(read_error)) then
            call check(error, .false., read_error%message)
            return
        end if
        call check(error, size(values, 1), 7, 'columns')
        call check(error, size(values, 2), 2, 'rows')
        if (allocated(error)) return
        call check(error, values(1, 1), -3.0_wp, 'x_begin(1)', abs_tol=tight)
        call check(error, values(4, 2), 1.0_wp, 'y_end(2)', abs_tol=tight)
        call check(error, values(6, 2), 0.1_wp, 'sf(2)', rel_tol=tight)
        call check(error, values(7, 2), 2.0_wp, 'pressure(2)', abs_tol=tight)
        call check(error, lines(1), 4, 'line of row 1')
        call check(error, lines(2), 5, 'line of row 2')
    end subroutine test_csv_elements

    subroutine test_csv_points_without_header(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: values(:,:)
        type(error_type), allocatable :: read_error

        call read_csv(data//'csv/points.csv', [character(len=1) :: 'x', 'y'], values, read_error)
        if (allocated(read_error)) then
            call check(error, .false., read_error%message)
            return
        end if
        call check(error, size(values, 2), 2, 'rows')
        if (allocated(error)) return
        call check(error, values(1, 1), 0.5_wp, 'x(1)', abs_tol=tight)
        call check(error, values(2, 2), 4.5_wp, 'y(2)', abs_tol=tight)
    end subroutine test_csv_points_without_header

    subroutine test_csv_bad_lines(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: values(:,:)
        type(error_type), allocatable :: read_error
        character(len=*), parameter :: path = data//'csv/bad_elements.csv'

        call read_csv(path, element_header, values, read_error)
        call check(error, allocated(read_error), 'bad CSV accepted')
        if (allocated(error)) return
        call check(error, read_error%code, exit_bad_input, 'error code')
        call check(error, index(read_error%message, path//' line 3: 6 fields, expected 7') > 0, &
                   'missing field: '//read_error%message)
        call check(error, index(read_error%message, &
                   path//" line 4: field 3 'abc' is not a number") > 0, &
                   'non-number: '//read_error%message)
        call check(error, index(read_error%message, path//' line 5: 8 fields') > 0, &
                   'extra field: '//read_error%message)
        call check(error, index(read_error%message, &
                   path//" line 6: field 5 'nan' is not a finite number") > 0, &
                   'NaN: '//read_error%message)
        call check(error, count_lines(read_error%message), 4, 'all bad lines reported')
    end subroutine test_csv_bad_lines

    subroutine test_csv_wrong_header(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: values(:,:)
        type(error_type), allocatable :: read_error

        call read_csv(data//'csv/points.csv', element_header, values, read_error)
        call check(error, allocated(read_error), 'wrong header accepted')
        if (allocated(error)) return
        call check(error, index(read_error%message, 'points.csv line 1') > 0 .and. &
                   index(read_error%message, 'x_begin,y_begin,x_end') > 0, read_error%message)
    end subroutine test_csv_wrong_header

    subroutine test_csv_no_rows(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: values(:,:)
        type(error_type), allocatable :: read_error

        call read_csv(data//'csv/header_only.csv', element_header, values, read_error)
        call check(error, allocated(read_error), 'CSV without rows accepted')
        if (allocated(error)) return
        call check(error, read_error%code, exit_bad_input, 'error code')
        call check(error, index(read_error%message, 'header_only.csv: no data rows') > 0, &
                   read_error%message)
    end subroutine test_csv_no_rows

    ! ---- good namelists -----------------------------------------------------------------

    !> Polyline subdivision, per-segment broadcasting, CSV elements, TWODD-style condition.
    subroutine test_good_elements(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        real(wp), parameter :: third = 1.0_wp / 3.0_wp
        real(wp) :: expected_sf(5)
        integer :: i

        call read_good(error, data//'good_polyline.nml', model)
        if (allocated(error)) return
        call check(error, model%elements%n, 11, 'number of elements')
        call check(error, size(model%fractures), 3, 'number of fractures')
        if (allocated(error)) return
        call check(error, model%fractures(1)%name == 'kinked', 'name of fracture 1')
        call check(error, model%fractures(2)%name == 'fracture_2', 'default name of fracture 2')
        call check(error, model%fractures(3)%name == 'crack', 'name of fracture 3')
        call check(error, model%fractures(1)%first_element, 1, 'fracture 1 first')
        call check(error, model%fractures(1)%last_element, 5, 'fracture 1 last')
        call check(error, model%fractures(2)%first_element, 6, 'fracture 2 first')
        call check(error, model%fractures(2)%last_element, 7, 'fracture 2 last')
        call check(error, model%fractures(3)%first_element, 8, 'fracture 3 first')
        call check(error, model%fractures(3)%last_element, 11, 'fracture 3 last')
        ! segment 1: 2 elements on (0,0)-(1,0); segment 2: 3 elements on (1,0)-(2,1)
        call check(error, model%elements%x_end(1), 0.5_wp, 'x_end(1)', abs_tol=tight)
        call check(error, model%elements%x_begin(2), 0.5_wp, 'x_begin(2)', abs_tol=tight)
        call check(error, model%elements%x_end(2), 1.0_wp, 'x_end(2)', abs_tol=tight)
        call check(error, model%elements%x_end(3), 1.0_wp + third, 'x_end(3)', abs_tol=tight)
        call check(error, model%elements%y_end(3), third, 'y_end(3)', abs_tol=tight)
        call check(error, model%elements%y_begin(5), 2.0_wp * third, 'y_begin(5)', abs_tol=tight)
        call check(error, model%elements%x_end(5), 2.0_wp, 'x_end(5)', abs_tol=0.0_wp)
        call check(error, model%elements%y_end(5), 1.0_wp, 'y_end(5)', abs_tol=0.0_wp)
        ! derived geometry
        call check(error, model%elements%half_length(1), 0.25_wp, 'half_length(1)', &
                   abs_tol=tight)
        call check(error, model%elements%cos_beta(4), sqrt(0.5_wp), 'cos_beta(4)', &
                   abs_tol=tight)
        call check(error, model%elements%x_mid(4), 1.5_wp, 'x_mid(4)', abs_tol=tight)
        ! broadcasting: mu one value, sf one per segment, pressure default 0
        expected_sf = [1.0_wp, 1.0_wp, 2.0_wp, 2.0_wp, 2.0_wp]
        do i = 1, 5
            call check(error, model%elements%mu(i), 0.6_wp, 'mu', abs_tol=tight)
            call check(error, model%elements%sf(i), expected_sf(i), 'sf', abs_tol=tight)
            call check(error, model%elements%pressure(i), 0.0_wp, 'pressure', abs_tol=0.0_wp)
            call check(error, model%elements%condition(i), condition_contact, 'condition')
            call check(error, model%elements%fracture_id(i), 1, 'fracture_id')
        end do
        ! CSV elements (path relative to the input file's folder)
        call check(error, model%elements%x_begin(6), -3.0_wp, 'csv x_begin(1)', abs_tol=tight)
        call check(error, model%elements%y_end(7), 1.0_wp, 'csv y_end(2)', abs_tol=tight)
        call check(error, model%elements%mu(7), 0.4_wp, 'csv mu(2)', abs_tol=tight)
        call check(error, model%elements%sf(7), 0.1_wp, 'csv sf(2)', abs_tol=tight)
        call check(error, model%elements%pressure(7), 2.0_wp, 'csv pressure(2)', abs_tol=tight)
        call check(error, model%elements%fracture_id(7), 2, 'csv fracture_id')
        ! TWODD-style condition with bc defaults
        call check(error, model%elements%condition(8), condition_traction, 'condition(8)')
        call check(error, model%elements%bc_n(11), 1.5_wp, 'bc_n(11)', abs_tol=tight)
        call check(error, model%elements%bc_s(11), 0.0_wp, 'bc_s(11)', abs_tol=0.0_wp)
        call check(error, model%elements%x_end(8), 0.25_wp, 'x_end(8)', abs_tol=tight)
        call check(error, model%elements%mu(8), 0.0_wp, 'mu(8)', abs_tol=0.0_wp)
    end subroutine test_good_elements

    !> Grids (x fastest), lines, point lists, in file order, with default names.
    subroutine test_good_observations(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        real(wp), parameter :: grid_x(6) = [-1.0_wp, 0.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp]
        real(wp), parameter :: grid_y(6) = [2.0_wp, 2.0_wp, 2.0_wp, 3.0_wp, 3.0_wp, 3.0_wp]
        integer :: i

        call read_good(error, data//'good_polyline.nml', model)
        if (allocated(error)) return
        call check(error, size(model%observations), 3, 'number of observation sets')
        if (allocated(error)) return
        associate (grid => model%observations(1), line => model%observations(2), &
                   points => model%observations(3))
            call check(error, grid%name == 'map', 'grid name')
            call check(error, grid%kind, observation_grid, 'grid kind')
            call check(error, grid%nx, 3, 'grid nx')
            call check(error, grid%ny, 2, 'grid ny')
            call check(error, size(grid%x), 6, 'grid points')
            if (allocated(error)) return
            do i = 1, 6
                call check(error, grid%x(i), grid_x(i), 'grid x', abs_tol=tight)
                call check(error, grid%y(i), grid_y(i), 'grid y', abs_tol=tight)
            end do
            call check(error, line%name == 'line_1', 'default line name: '//line%name)
            call check(error, line%kind, observation_line, 'line kind')
            call check(error, line%nx, 3, 'line points')
            if (allocated(error)) return
            call check(error, line%x(2), 1.0_wp, 'line x(2)', abs_tol=tight)
            call check(error, line%y(2), -1.5_wp, 'line y(2)', abs_tol=tight)
            call check(error, line%x(3), 2.0_wp, 'line x(3)', abs_tol=0.0_wp)
            call check(error, points%name == 'points_1', 'default points name: '//points%name)
            call check(error, points%kind, observation_points, 'points kind')
            call check(error, points%nx, 2, 'points count')
            if (allocated(error)) return
            call check(error, points%x(2), 1.5_wp, 'points x(2)', abs_tol=tight)
            call check(error, points%y(2), 4.5_wp, 'points y(2)', abs_tol=tight)
        end associate
    end subroutine test_good_observations

    !> Model values, solver options, units, default output name, input text.
    subroutine test_good_defaults(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model

        call read_good(error, data//'good_polyline.nml', model)
        if (allocated(error)) return
        call check(error, model%title == 'good polyline', 'title: '//model%title)
        call check(error, model%youngs_modulus, 50000.0_wp, 'E', rel_tol=tight)
        call check(error, model%poissons_ratio, 0.25_wp, 'nu', rel_tol=tight)
        call check(error, model%sxx, -10.0_wp, 'sxx', rel_tol=tight)
        call check(error, model%syy, -20.0_wp, 'syy', rel_tol=tight)
        call check(error, model%sxy, 5.0_wp, 'sxy', rel_tol=tight)
        call check(error, model%length_unit == 'km', 'length unit')
        call check(error, model%stress_unit == 'MPa', 'stress unit')
        call check(error, model%solver%lcp_method == lcp_lemke, 'lcp_method')
        call check(error, model%solver%open_cohesion == cohesion_lost, 'open_cohesion')
        call check(error, model%block_size, 32, 'block_size')
        call check(error, model%output_file == 'good_polyline.h5', &
                   'default output file: '//model%output_file)
        call check(error, model%input_file == data//'good_polyline.nml', 'input file')
        call check(error, index(model%input_text, "&solver lcp_method = 'lemke'") > 0, &
                   'input text')
    end subroutine test_good_defaults

    !> &output relative to the input folder; defaults of title, units, solver; a line whose
    !> ends coincide has one point; a grid with nx = 1 uses xmin.
    subroutine test_good_output(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model

        call read_good(error, data//'good_output.nml', model)
        if (allocated(error)) return
        call check(error, model%output_file == data//'out/result.h5', &
                   'output file: '//model%output_file)
        call check(error, model%title == 'good_output', 'default title: '//model%title)
        call check(error, model%length_unit == 'm', 'default length unit')
        call check(error, model%stress_unit == 'MPa', 'default stress unit')
        call check(error, model%solver%lcp_method == lcp_auto, 'default lcp_method')
        call check(error, model%solver%open_cohesion == cohesion_kept, 'default open_cohesion')
        call check(error, model%block_size, 64, 'default block_size')
        call check(error, model%sxx, 0.0_wp, 'default sxx', abs_tol=0.0_wp)
        call check(error, model%elements%n, 1, 'elements')
        call check(error, model%elements%sf(1), 0.0_wp, 'default sf', abs_tol=0.0_wp)
        call check(error, model%fractures(1)%name == 'fracture_1', 'default fracture name')
        call check(error, size(model%observations), 2, 'observation sets')
        if (allocated(error)) return
        call check(error, model%observations(1)%name == 'probe', 'line name')
        call check(error, model%observations(1)%nx, 1, 'one point on a line of zero length')
        call check(error, model%observations(2)%name == 'grid_1', 'default grid name')
        call check(error, model%observations(2)%nx, 1, 'grid nx')
        call check(error, model%observations(2)%ny, 3, 'grid ny')
        if (allocated(error)) return
        call check(error, model%observations(2)%x(3), 5.0_wp, 'grid x', abs_tol=0.0_wp)
        call check(error, model%observations(2)%y(2), 0.0_wp, 'grid y(2)', abs_tol=tight)
    end subroutine test_good_output

    ! ---- bad namelists ------------------------------------------------------------------

    subroutine test_bad_elastic(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_elastic.nml', [character(len=40) :: &
                             '&model (line 1): youngs_modulus', 'must be positive', &
                             'poissons_ratio = 0.5', '(-1, 0.5)'], lines=2)
    end subroutine test_bad_elastic

    subroutine test_bad_mu(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_mu.nml', [character(len=40) :: &
                             "&fracture 1 'f' (line 2)", 'mu(2) =', 'must be >= 0'], lines=1)
    end subroutine test_bad_mu

    subroutine test_bad_block_size(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_block_size.nml', [character(len=40) :: &
                             '&solver (line 3)', 'block_size = 0', 'must be at least 1'], &
                             lines=1)
    end subroutine test_bad_block_size

    subroutine test_bad_sf(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_sf.nml', [character(len=40) :: &
                             '&fracture 1 (line 2)', 'sf(1) =', 'must be >= 0'], lines=1)
    end subroutine test_bad_sf

    !> tensile_strength and sf_residual per segment and from CSV columns, with defaults.
    subroutine test_good_strength(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model

        call read_good(error, data//'good_strength.nml', model)
        if (allocated(error)) return
        associate (e => model%elements)
            call check(error, e%n, 12, 'number of elements')
            if (allocated(error)) return
            call check(error, e%tensile_strength(2), 0.5_wp, 'T segment 1', abs_tol=0.0_wp)
            call check(error, e%tensile_strength(5), 1.5_wp, 'T segment 2', abs_tol=0.0_wp)
            call check(error, e%sf_residual(1), 0.25_wp, 'sf_residual broadcast', abs_tol=0.0_wp)
            call check(error, e%sf_residual(5), 0.25_wp, 'sf_residual broadcast', abs_tol=0.0_wp)
            call check(error, e%sf_residual(6), 0.5_wp, 'csv sf_residual(1)', abs_tol=0.0_wp)
            call check(error, e%sf_residual(7), 0.1_wp, 'csv sf_residual(2)', abs_tol=0.0_wp)
            call check(error, e%tensile_strength(7), 0.0_wp, 'csv T default', abs_tol=0.0_wp)
            call check(error, e%pressure(7), 2.0_wp, 'csv pressure(2)', abs_tol=0.0_wp)
            call check(error, e%tensile_strength(9), 0.0_wp, 'T default', abs_tol=0.0_wp)
            call check(error, min(e%sf(9), e%sf_residual(9)), e%sf(9), &
                       'sf_residual default: sf', abs_tol=0.0_wp)
            call check(error, min(e%mu(9), e%mu_dynamic(9)), e%mu(9), &
                       'mu_dynamic default: mu', abs_tol=0.0_wp)
            call check(error, e%slip_weakening_distance(9), 0.0_wp, 'd_c default', &
                       abs_tol=0.0_wp)
            call check(error, e%mu_dynamic(10), 0.4_wp, 'mu_dynamic segment 1', abs_tol=0.0_wp)
            call check(error, e%mu_dynamic(12), 0.5_wp, 'mu_dynamic segment 2', abs_tol=0.0_wp)
            call check(error, e%slip_weakening_distance(11), 0.001_wp, 'd_c broadcast', &
                       abs_tol=0.0_wp)
            call check(error, e%shear_stiffness(12), 1.0e4_wp, 'k_s', abs_tol=0.0_wp)
            call check(error, e%normal_stiffness(10), 2.0e4_wp, 'k_n segment 1', abs_tol=0.0_wp)
            call check(error, e%normal_stiffness(11), 3.0e4_wp, 'k_n segment 2', abs_tol=0.0_wp)
            call check(error, e%shear_stiffness(9) >= rigid_joint .and. &
                       e%normal_stiffness(9) >= rigid_joint, 'rigid by default')
        end associate
    end subroutine test_good_strength

    subroutine test_bad_strength(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_strength.nml', [character(len=48) :: &
                             "&fracture 1 'f' (line 2)", 'tensile_strength(1) = ', &
                             'must be >= 0', 'sf_residual = 3', 'exceeds sf = 1', &
                             'on segment 2', 'mu_dynamic = 0.7', 'exceeds mu = 0.6', &
                             'slip_weakening_distance(1) = -0.1', 'shear_stiffness(1) = -5', &
                             'normal_stiffness(1) = 0', 'must be positive'], lines=6)
    end subroutine test_bad_strength

    subroutine test_bad_strength_csv(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_strength_csv.nml', [character(len=48) :: &
                             'bad_strength.csv line 2: tensile_strength = ', 'must be >= 0', &
                             'bad_strength.csv line 3: sf_residual = 1.5', 'exceeds sf = 1', &
                             'line 2: mu_dynamic = 0.8', 'exceeds mu = 0.6', &
                             'line 3: slip_weakening_distance = -1'], lines=4)
    end subroutine test_bad_strength_csv

    subroutine test_bad_strength_growth(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_strength_growth.nml', [character(len=60) :: &
                             'the joint stiffnesses are not honoured by', &
                             'fracture growth'], lines=1)
    end subroutine test_bad_strength_growth

    subroutine test_bad_nan(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_nan.nml', [character(len=40) :: &
                             '&remote_stress (line 2): sxx', 'x(2) = NaN', &
                             'not a finite number'], lines=2)
    end subroutine test_bad_nan

    !> NaN or Inf in mu or sf beside a residual strength: one message each, not a trap in the
    !> comparison of the residual with the intact value (found by the fuzz test).
    subroutine test_bad_strength_nan(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_strength_nan.nml', [character(len=40) :: &
                             "&fracture 1 'f' (line 2)", 'mu(1) = NaN', 'sf(2) = Inf', &
                             'not a finite number'], lines=2)
    end subroutine test_bad_strength_nan

    subroutine test_bad_vertices(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_vertices.nml', [character(len=40) :: &
                             '&fracture 1', 'x and y give 1 vertices', 'at least 2'])
    end subroutine test_bad_vertices

    subroutine test_bad_xy_length(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_xy_length.nml', [character(len=40) :: &
                             '&fracture 1', 'x has 3 values but y has 2'])
    end subroutine test_bad_xy_length

    subroutine test_bad_segment_array(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_segment_array.nml', [character(len=60) :: &
                             '&fracture 1', 'mu has 2 values; give 1', '3 (one per segment)'], &
                             lines=1)
    end subroutine test_bad_segment_array

    subroutine test_bad_elements(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_elements.nml', [character(len=40) :: &
                             '&fracture 1', 'elements(2) = 0 must be at least 1'], lines=1)
    end subroutine test_bad_elements

    subroutine test_bad_condition(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_condition.nml', [character(len=40) :: &
                             '&fracture 1', "condition = 'slippery'", "'mixed_us_sn'"], lines=1)
    end subroutine test_bad_condition

    subroutine test_bad_grid(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_grid.nml', [character(len=40) :: &
                             "&grid 1 'map' (line 3)", 'ny = 0 must be at least 1'], lines=1)
    end subroutine test_bad_grid

    subroutine test_bad_line(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_line.nml', [character(len=40) :: &
                             "&line 1 'profile'", 'points = 1 but the ends differ'], lines=1)
    end subroutine test_bad_line

    subroutine test_bad_missing_csv(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_missing_csv.nml', [character(len=60) :: &
                             '&fracture 1', 'elements_file', &
                             data//'csv/missing.csv: file not found'])
    end subroutine test_bad_missing_csv

    subroutine test_bad_points_csv(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_points_csv.nml', [character(len=60) :: &
                             "&points 1 'wells'", &
                             "csv/bad_points.csv line 3: field 2 'abc' is not a number", &
                             'csv/bad_points.csv line 4: 1 fields, expected 2'], lines=2)
    end subroutine test_bad_points_csv

    subroutine test_bad_no_fracture(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_no_fracture.nml', [character(len=40) :: &
                             'no &fracture group'], lines=1)
    end subroutine test_bad_no_fracture

    subroutine test_bad_unknown_group(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_unknown_group.nml', [character(len=60) :: &
                             'line 2: &fractures is not a ddc2d group', 'known groups: &model'], &
                             lines=1)
    end subroutine test_bad_unknown_group

    subroutine test_bad_misspelled(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_misspelled.nml', [character(len=80) :: &
                             "&model (line 1): unknown variable 'youngs_modulos'", &
                             'the variables of this group are: title, youngs_modulus'], lines=1)
    end subroutine test_bad_misspelled

    subroutine test_bad_type_last(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_type_last.nml', [character(len=80) :: &
                             '&grid 1 (line 3): nx = 2.5 is not an integer'], lines=1)
    end subroutine test_bad_type_last

    subroutine test_bad_type_middle(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_type_middle.nml', [character(len=80) :: &
                             "&model (line 1): youngs_modulus = 'stiff' is not a number"], &
                             lines=1)
    end subroutine test_bad_type_middle

    !> After a malformed &fracture the later ones are still diagnosed; an unquoted text.
    subroutine test_bad_several_groups(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_several_groups.nml', [character(len=70) :: &
                             "&fracture 1 (line 2): elements = 'two' is not an integer", &
                             "&fracture 2 (line 3): unknown variable 'bc_x'", &
                             "&solver (line 4): lcp_method = lemke needs quotes"], lines=3)
    end subroutine test_bad_several_groups

    subroutine test_bad_missing_model(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_missing_model.nml', [character(len=40) :: &
                             'the &model group is missing'], lines=1)
    end subroutine test_bad_missing_model

    subroutine test_bad_gap(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_gap.nml', [character(len=40) :: &
                             'x(3) is given but x(2) is not'])
    end subroutine test_bad_gap

    subroutine test_bad_duplicate_names(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_duplicate_names.nml', [character(len=80) :: &
                             "&line 1 'map' (line 4): name 'map' is already used by &grid 1"], &
                             lines=1)
    end subroutine test_bad_duplicate_names

    subroutine test_bad_both_geometry(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_both_geometry.nml', [character(len=60) :: &
                             'either x, y and elements or elements_file'], lines=1)
    end subroutine test_bad_both_geometry

    subroutine test_bad_crossing(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_crossing.nml', [character(len=60) :: &
                             "fracture 'east' element 2", "fracture 'north' element 1", &
                             'cross'], lines=1)
    end subroutine test_bad_crossing

    subroutine test_bad_missing_input(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'no_such_model.nml', [character(len=40) :: &
                             'file not found'], lines=1)
    end subroutine test_bad_missing_input

    !> One &load_path quantity with the wrong number of values: that message alone (it was
    !> given, so no 'give the load at each vertex' as well).
    subroutine test_bad_load_path_length(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad_input(error, data//'bad_load_path_length.nml', [character(len=40) :: &
            '&load_path', 'sxy has 2 values', 'one per vertex: 3'], lines=1)
    end subroutine test_bad_load_path_length

end module test_input
