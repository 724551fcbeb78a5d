!> Tests of the result file: atomic publication and the HDF5 layout.
module test_output
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
    use ddc_kinds, only: wp
    use ddc_contact_options, only: lcp_lemke, cohesion_kept
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_error, only: exit_io_failure
    use ddc_version, only: program_version, git_commit
    use ddc_model_types, only: model_type, condition_contact, condition_traction, &
        observation_grid, observation_line, no_residual_drop, &
        rigid_joint
    use ddc_model_results, only: model_results, state_free, state_stick, state_slip, &
        point_clear, point_near, point_on_element
    use ddc_mesh_geometry, only: allocate_elements, compute_geometry
    use ddc_output_atomic, only: partial_name, publish_file, remove_file, check_writable
    use ddc_output_hdf5, only: write_results
    use ddc_output_hdf5_read, only: read_real_dataset, read_int_dataset, &
        read_string_dataset, read_dataset_dims, read_string_attribute, read_real_attribute, &
        read_int_attribute
    implicit none
    private
    public :: collect_output

    !> Exact comparisons: the file must hold the very bits that were written
    real(wp), parameter :: exact = 0.0_wp

contains

    !> Cases of the output suite.
    subroutine collect_output(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [ &
            new_test('partial_name', test_partial_name), &
            new_test('remove_file', test_remove_file), &
            new_test('check_writable_ok', test_check_writable_ok), &
            new_test('check_writable_missing_folder', test_check_writable_missing_folder), &
            new_test('check_writable_folder', test_check_writable_folder), &
            new_test('publish_missing_folder', test_publish_missing_folder), &
            new_test('publish_replaces', test_publish_replaces), &
            new_test('write_missing_folder', test_write_missing_folder), &
            new_test('published_not_partial', test_published_not_partial), &
            new_test('root_attributes', test_root_attributes), &
            new_test('elements', test_elements), &
            new_test('element_units_and_codings', test_element_units), &
            new_test('fractures', test_fractures), &
            new_test('tips', test_tips), &
            new_test('no_tips', test_no_tips), &
            new_test('grid_field', test_grid_field), &
            new_test('line_field', test_line_field), &
            new_test('solver', test_solver), &
            new_test('rewrite_replaces', test_rewrite_replaces), &
            new_test('failure_midway_cleans_up', test_failure_midway), &
            new_test('empty_strings', test_empty_strings) &
        ]
    end subroutine collect_output

    ! ------------------------------------------------------------ atomic file handling

    subroutine test_partial_name(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, partial_name('out/run.h5') == 'out/run.h5.partial', &
            'partial_name appends .partial')
    end subroutine test_partial_name

    subroutine test_remove_file(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: path

        path = unique_path('remove')
        call touch(path)
        call check(error, exists(path), 'file created for the test')
        call remove_file(path)
        call check(error, .not. exists(path), 'remove_file deletes an existing file')
        call remove_file(path)  ! silent when missing
        call check(error, .not. exists(path), 'remove_file is silent on a missing file')
    end subroutine test_remove_file

    subroutine test_check_writable_ok(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: result_error
        character(len=:), allocatable :: path

        path = unique_path('writable')
        call check_writable(path, result_error)
        call check(error, .not. allocated(result_error), 'check_writable passes in /tmp')
        call check(error, .not. exists(partial_name(path)), 'no test file left behind')
        call check(error, .not. exists(path), 'no final file created')
    end subroutine test_check_writable_ok

    subroutine test_check_writable_missing_folder(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: result_error
        character(len=:), allocatable :: path

        path = unique_path('missing')//'/out.h5'
        call check_writable(path, result_error)
        call check(error, allocated(result_error), 'check_writable fails on a missing folder')
        if (allocated(error)) return
        call check(error, result_error%code, exit_io_failure, 'exit code')
        call check(error, index(result_error%message, path) > 0, &
            'message names the path: '//result_error%message)
        call check(error, index(result_error%message, 'does not exist') > 0, &
            'message names the missing folder: '//result_error%message)
    end subroutine test_check_writable_missing_folder

    subroutine test_check_writable_folder(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: result_error

        call check_writable('/tmp', result_error)
        call check(error, allocated(result_error), 'check_writable refuses a folder')
        if (allocated(error)) return
        call check(error, result_error%code, exit_io_failure, 'exit code')
    end subroutine test_check_writable_folder

    subroutine test_publish_missing_folder(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: result_error
        character(len=:), allocatable :: source, target

        source = unique_path('publish_source')
        target = unique_path('no_folder')//'/result.h5'
        call touch(source)
        call publish_file(source, target, result_error)
        call check(error, allocated(result_error), 'publish_file fails on a missing folder')
        if (.not. allocated(error)) then
            call check(error, result_error%code, exit_io_failure, 'exit code')
            call check(error, index(result_error%message, source) > 0 .and. &
                index(result_error%message, target) > 0, &
                'message names both paths: '//result_error%message)
            call check(error, index(result_error%message, 'does not exist') > 0, &
                'message gives the reason: '//result_error%message)
        end if
        call check(error, .not. exists(target), 'no final file')
        call remove_file(source)
    end subroutine test_publish_missing_folder

    subroutine test_publish_replaces(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: result_error
        character(len=:), allocatable :: source, target
        character(len=16) :: line
        integer :: unit, status

        source = unique_path('publish_new')
        target = unique_path('publish_old')
        call touch(target, 'old')
        call touch(source, 'new')
        call publish_file(source, target, result_error)
        call check(error, .not. allocated(result_error), 'publish_file succeeds')
        call check(error, .not. exists(source), 'temporary name gone')
        open (newunit=unit, file=target, status='old', action='read', iostat=status)
        call check(error, status == 0, 'final file exists')
        if (status == 0) then
            read (unit, '(a)', iostat=status) line
            close (unit)
            call check(error, status == 0 .and. line == 'new', 'final file replaced')
        end if
        call remove_file(target)
        call remove_file(source)
    end subroutine test_publish_replaces

    subroutine test_write_missing_folder(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: result_error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path

        call sample(model, results)
        path = unique_path('write_missing')//'/out.h5'
        call write_results(path, model, results, result_error)
        call check(error, allocated(result_error), 'write_results fails on a missing folder')
        if (.not. allocated(error)) then
            call check(error, result_error%code, exit_io_failure, 'exit code')
            call check(error, index(result_error%message, partial_name(path)) > 0, &
                'message names the file: '//result_error%message)
        end if
        call check(error, .not. exists(path), 'no final file')
        call check(error, .not. exists(partial_name(path)), 'no partial file')
    end subroutine test_write_missing_folder

    ! ---------------------------------------------------------------- the HDF5 layout

    subroutine test_published_not_partial(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: path

        call write_sample(path, error)
        if (allocated(error)) return
        call check(error, exists(path), 'result file published')
        call check(error, .not. exists(partial_name(path)), 'no .partial file left')
        call remove_file(path)
    end subroutine test_published_not_partial

    subroutine test_root_attributes(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path, value
        integer :: complete

        call write_sample(path, error, model, results)
        if (allocated(error)) return
        call check_string_attribute(error, path, '/', 'program', 'ddc2d')
        call check_string_attribute(error, path, '/', 'version', program_version)
        call check_string_attribute(error, path, '/', 'git_commit', git_commit)
        call check_string_attribute(error, path, '/', 'title', model%title)
        call check_string_attribute(error, path, '/', 'input_file', model%input_file)
        call check_string_attribute(error, path, '/', 'input_text', model%input_text)
        call check_string_attribute(error, path, '/', 'length_unit', 'm')
        call check_string_attribute(error, path, '/', 'stress_unit', 'MPa')
        call check_string_attribute(error, path, '/', 'open_cohesion', 'kept')
        call check_string_attribute(error, path, '/', 'lcp_method', 'lemke')
        call check_string_attribute(error, path, '/', 'conventions', 'stress tension ' &
            //'positive; Crouch & Starfield displacement discontinuities: ds = us(-) - ' &
            //'us(+), dn = un(-) - un(+), opening = -dn; positive face on the left of the ' &
            //'element direction')
        if (.not. allocated(error)) then
            call read_string_attribute(path, '/', 'created', value, error)
        end if
        if (.not. allocated(error)) then
            call check(error, len(value) == 20 .and. value(5:5) == '-' .and. &
                value(11:11) == 'T' .and. value(20:20) == 'Z', &
                'created is ISO 8601 UTC: '//value)
        end if
        call check_real_attribute(error, path, 'youngs_modulus', [50000.0_wp])
        call check_real_attribute(error, path, 'poissons_ratio', [0.25_wp])
        call check_real_attribute(error, path, 'shear_modulus', [20000.0_wp])
        call check_real_attribute(error, path, 'remote_stress', &
            [-143.75_wp, -81.25_wp, 54.13_wp])
        if (.not. allocated(error)) call read_int_attribute(path, '/', 'complete', &
            complete, error)
        call check(error, complete, 1, 'complete attribute')
        call remove_file(path)
    end subroutine test_root_attributes

    subroutine test_elements(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path

        call write_sample(path, error, model, results)
        if (allocated(error)) return
        associate (e => model%elements, r => results%elements)
            call check_real_dataset(error, path, '/elements/x_begin', e%x_begin, [3])
            call check_real_dataset(error, path, '/elements/y_begin', e%y_begin, [3])
            call check_real_dataset(error, path, '/elements/x_end', e%x_end, [3])
            call check_real_dataset(error, path, '/elements/y_end', e%y_end, [3])
            call check_real_dataset(error, path, '/elements/x_mid', e%x_mid, [3])
            call check_real_dataset(error, path, '/elements/y_mid', e%y_mid, [3])
            call check_real_dataset(error, path, '/elements/half_length', e%half_length, [3])
            call check_int_dataset(error, path, '/elements/fracture_id', e%fracture_id, [3])
            call check_int_dataset(error, path, '/elements/condition', e%condition, [3])
            call check_real_dataset(error, path, '/elements/bc_s', e%bc_s, [3])
            call check_real_dataset(error, path, '/elements/bc_n', e%bc_n, [3])
            call check_real_dataset(error, path, '/elements/ds', r%ds, [3])
            call check_real_dataset(error, path, '/elements/dn', r%dn, [3])
            call check_real_dataset(error, path, '/elements/opening', -r%dn, [3])
            call check_real_dataset(error, path, '/elements/shear_traction', &
                r%shear_traction, [3])
            call check_real_dataset(error, path, '/elements/normal_traction', &
                r%normal_traction, [3])
            call check_real_dataset(error, path, '/elements/us_minus', r%us_minus, [3])
            call check_real_dataset(error, path, '/elements/un_minus', r%un_minus, [3])
            call check_real_dataset(error, path, '/elements/us_plus', r%us_plus, [3])
            call check_real_dataset(error, path, '/elements/un_plus', r%un_plus, [3])
            call check_int_dataset(error, path, '/elements/state', r%state, [3])
            call check_real_dataset(error, path, '/elements/mu', e%mu, [3])
            call check_real_dataset(error, path, '/elements/sf', e%sf, [3])
            call check_real_dataset(error, path, '/elements/pressure', e%pressure, [3])
            call check_real_dataset(error, path, '/elements/tensile_strength', &
                                    e%tensile_strength, [3])
            call check_real_dataset(error, path, '/elements/sf_residual', &
                                    [0.25_wp, 0.1_wp, 0.0_wp], [3])
            call check_real_dataset(error, path, '/elements/sf_in_force', r%sf_in_force, [3])
            call check_real_dataset(error, path, '/elements/tensile_strength_in_force', &
                                    r%tensile_in_force, [3])
            call check_real_dataset(error, path, '/elements/mu_dynamic', &
                                    [0.4_wp, 0.6_wp, 0.0_wp], [3])
            call check_real_dataset(error, path, '/elements/slip_weakening_distance', &
                                    e%slip_weakening_distance, [3])
            call check_real_dataset(error, path, '/elements/mu_in_force', r%mu_in_force, [3])
            call check_real_dataset(error, path, '/elements/shear_stiffness', &
                                    e%shear_stiffness, [3])
        end associate
        call remove_file(path)
    end subroutine test_elements

    subroutine test_element_units(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: path

        call write_sample(path, error)
        if (allocated(error)) return
        call check_string_attribute(error, path, '/elements/x_mid', 'units', 'm')
        call check_string_attribute(error, path, '/elements/ds', 'units', 'm')
        call check_string_attribute(error, path, '/elements/opening', 'units', 'm')
        call check_string_attribute(error, path, '/elements/mu', 'units', '1')
        call check_string_attribute(error, path, '/elements/sf', 'units', 'MPa')
        call check_string_attribute(error, path, '/elements/tensile_strength', 'units', 'MPa')
        call check_string_attribute(error, path, '/elements/sf_in_force', 'units', 'MPa')
        call check_string_attribute(error, path, '/elements/slip_weakening_distance', 'units', &
                                    'm')
        call check_string_attribute(error, path, '/elements/mu_in_force', 'units', '1')
        call check_string_attribute(error, path, '/elements/normal_stiffness', 'units', 'MPa/m')
        call check_string_attribute(error, path, '/elements/shear_traction', 'units', 'MPa')
        call check_string_attribute(error, path, '/elements/bc_n', 'units', &
            'MPa or m (by condition)')
        call check_string_attribute(error, path, '/elements/state', 'coding', &
            '0 free (TWODD-style condition), 1 stick, 2 slip, 3 open')
        call check_string_attribute(error, path, '/elements/condition', 'coding', &
            '1 traction, 2 displacement, 3 mixed_us_sn, 4 mixed_ss_un, 5 contact, '// &
            '6 prescribed_dd')
        call remove_file(path)
    end subroutine test_element_units

    subroutine test_fractures(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: path
        character(len=16), allocatable :: names(:)

        call write_sample(path, error)
        if (allocated(error)) return
        call read_string_dataset(path, '/fractures/name', names, error)
        if (allocated(error)) return
        call check(error, size(names), 2, 'number of fracture names')
        if (allocated(error)) return
        call check(error, names(1) == 'main fault' .and. names(2) == 'splay', &
            'fracture names: '//names(1)//'|'//names(2))
        call check_int_dataset(error, path, '/fractures/first_element', [1, 3], [2])
        call check_int_dataset(error, path, '/fractures/last_element', [2, 3], [2])
        call remove_file(path)
    end subroutine test_fractures

    subroutine test_tips(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path

        call write_sample(path, error, model, results)
        if (allocated(error)) return
        call check_real_dataset(error, path, '/tips/x', results%tips%x, [2])
        call check_real_dataset(error, path, '/tips/y', results%tips%y, [2])
        call check_int_dataset(error, path, '/tips/fracture_id', results%tips%fracture_id, [2])
        call check_int_dataset(error, path, '/tips/element', results%tips%element, [2])
        call check_real_dataset(error, path, '/tips/k1', results%tips%k1, [2])
        call check_real_dataset(error, path, '/tips/k2', results%tips%k2, [2])
        call check_int_dataset(error, path, '/tips/graded', results%tips%graded, [2])
        call check_string_attribute(error, path, '/tips/k1', 'units', 'MPa m^0.5')
        call remove_file(path)
    end subroutine test_tips

    subroutine test_no_tips(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path

        call sample(model, results)
        results%tips%n = 0
        deallocate (results%tips%x, results%tips%y, results%tips%fracture_id, &
            results%tips%element, results%tips%k1, results%tips%k2, results%tips%graded)
        path = unique_path('no_tips')//'.h5'
        call write_or_fail(path, model, results, 'write_results', error)
        if (allocated(error)) return
        call check_real_dataset(error, path, '/tips/x', [real(wp) ::], [0])
        call check_real_dataset(error, path, '/tips/k2', [real(wp) ::], [0])
        call check_int_dataset(error, path, '/tips/element', [integer ::], [0])
        call remove_file(path)
    end subroutine test_no_tips

    subroutine test_grid_field(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path, value
        integer :: nx, ny

        call write_sample(path, error, model, results)
        if (allocated(error)) return
        associate (o => model%observations(1), f => results%fields(1))
            call check_real_dataset(error, path, '/fields/map/x', o%x, [3, 2])
            call check_real_dataset(error, path, '/fields/map/y', o%y, [3, 2])
            call check_real_dataset(error, path, '/fields/map/ux', f%ux, [3, 2])
            call check_real_dataset(error, path, '/fields/map/uy', f%uy, [3, 2])
            call check_real_dataset(error, path, '/fields/map/sxx', f%sxx, [3, 2])
            call check_real_dataset(error, path, '/fields/map/syy', f%syy, [3, 2])
            call check_real_dataset(error, path, '/fields/map/sxy', f%sxy, [3, 2])
            call check_int_dataset(error, path, '/fields/map/near_element', f%flag, [3, 2])
        end associate
        call check_string_attribute(error, path, '/fields/map', 'kind', 'grid')
        call check_string_attribute(error, path, '/fields/map/sxx', 'units', 'MPa')
        call check_string_attribute(error, path, '/fields/map/ux', 'units', 'm')
        if (.not. allocated(error)) call read_int_attribute(path, '/fields/map', 'nx', nx, &
            error)
        if (.not. allocated(error)) call read_int_attribute(path, '/fields/map', 'ny', ny, &
            error)
        call check(error, nx, 3, 'grid nx attribute')
        call check(error, ny, 2, 'grid ny attribute')
        if (.not. allocated(error)) call read_string_attribute(path, &
            '/fields/map/near_element', 'coding', value, error)
        call check(error, index(value, '2 on an element') > 0, 'near_element coding')
        call remove_file(path)
    end subroutine test_grid_field

    subroutine test_line_field(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path

        call write_sample(path, error, model, results)
        if (allocated(error)) return
        associate (o => model%observations(2), f => results%fields(2))
            call check_real_dataset(error, path, '/fields/profile/x', o%x, [4])
            call check_real_dataset(error, path, '/fields/profile/y', o%y, [4])
            call check_real_dataset(error, path, '/fields/profile/ux', f%ux, [4])
            call check_real_dataset(error, path, '/fields/profile/sxy', f%sxy, [4])
            call check_int_dataset(error, path, '/fields/profile/near_element', f%flag, [4])
        end associate
        call check_string_attribute(error, path, '/fields/profile', 'kind', 'line')
        call remove_file(path)
    end subroutine test_line_field

    subroutine test_solver(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: output(:), total(:)
        character(len=:), allocatable :: path
        integer :: value

        call write_sample(path, error)
        if (allocated(error)) return
        call check_string_attribute(error, path, '/solver', 'method', 'lemke')
        if (.not. allocated(error)) call read_int_attribute(path, '/solver', 'pivots', value, &
            error)
        call check(error, value, 5, 'pivots')
        if (.not. allocated(error)) call read_int_attribute(path, '/solver', 'threads', &
            value, error)
        call check(error, value, 2, 'threads')
        if (.not. allocated(error)) call read_int_attribute(path, '/solver', &
            'elements_slip', value, error)
        call check(error, value, 1, 'elements_slip')
        call check_real_attribute(error, path, 'equilibrium_residual', [1.5e-13_wp], &
            '/solver')
        call check_real_dataset(error, path, '/solver/seconds/assembly', [0.125_wp], &
            [integer ::])
        ! output: the writing of the file itself, measured by write_results; total adds it.
        if (.not. allocated(error)) call read_real_dataset(path, '/solver/seconds/output', &
            output, error)
        if (.not. allocated(error)) call read_real_dataset(path, '/solver/seconds/total', &
            total, error)
        if (allocated(error)) return
        call check(error, output(1) >= 0.0_wp .and. output(1) < 60.0_wp, 'seconds/output')
        call check(error, total(1), 2.5_wp + output(1), 'seconds/total', rel_tol=1.0e-14_wp)
        call check_string_attribute(error, path, '/solver/seconds/total', 'units', 's')
        call remove_file(path)
    end subroutine test_solver

    subroutine test_rewrite_replaces(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path

        call write_sample(path, error, model, results)
        if (allocated(error)) return
        results%elements%ds(2) = 42.0_wp
        call write_or_fail(path, model, results, 'second write_results', error)
        if (allocated(error)) return
        call check_real_dataset(error, path, '/elements/ds', results%elements%ds, [3])
        call check(error, .not. exists(partial_name(path)), 'no .partial file left')
        call remove_file(path)
    end subroutine test_rewrite_replaces

    subroutine test_failure_midway(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: write_error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path

        call sample(model, results)
        model%observations(2)%name = 'map'  ! a duplicate group: HDF5 fails midway
        path = unique_path('midway')//'.h5'
        call write_results(path, model, results, write_error)
        call check(error, allocated(write_error), 'write_results fails on a duplicate group')
        if (allocated(error)) return
        call check(error, write_error%code, exit_io_failure, 'exit code')
        call check(error, write_error%message == 'writing '//path//' failed: HDF5 could not '// &
            'create group /fields/map in '//partial_name(path), 'message: '//write_error%message)
        call check(error, .not. exists(path), 'no final file')
        call check(error, .not. exists(partial_name(path)), 'partial file removed')
    end subroutine test_failure_midway

    subroutine test_empty_strings(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: results
        character(len=:), allocatable :: path

        call sample(model, results)
        model%title = ''
        deallocate (model%input_text)
        path = unique_path('empty')//'.h5'
        call write_or_fail(path, model, results, 'write_results', error)
        if (allocated(error)) return
        call check_string_attribute(error, path, '/', 'title', '')
        call check_string_attribute(error, path, '/', 'input_text', '')
        call remove_file(path)
    end subroutine test_empty_strings

    ! ------------------------------------------------------------------------ helpers

    !> A small model and results: 3 elements on 2 fractures, 2 tips, a 3x2 grid, a line.
    subroutine sample(model, results)
        type(model_type), intent(out) :: model
        type(model_results), intent(out) :: results
        real(wp) :: nan
        integer :: i, k

        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        model%title = 'output test'
        model%youngs_modulus = 50000.0_wp
        model%poissons_ratio = 0.25_wp
        model%length_unit = 'm'
        model%stress_unit = 'MPa'
        model%sxx = -143.75_wp
        model%syy = -81.25_wp
        model%sxy = 54.13_wp
        model%input_file = 'input/test.nml'
        model%input_text = '&model title = ''output test'' /'//new_line('a') &
            //'&remote_stress sxx = -143.75 /'//new_line('a')
        model%solver%lcp_method = lcp_lemke
        model%solver%open_cohesion = cohesion_kept

        call allocate_elements(model%elements, 3)
        model%elements%x_begin = [-1.0_wp, 0.0_wp, 0.0_wp]
        model%elements%y_begin = [0.0_wp, 0.0_wp, 0.1_wp]
        model%elements%x_end = [0.0_wp, 1.0_wp, 1.0_wp / 3.0_wp]
        model%elements%y_end = [0.0_wp, 0.0_wp, 0.7_wp]
        model%elements%fracture_id = [1, 1, 2]
        model%elements%condition = [condition_contact, condition_contact, condition_traction]
        model%elements%bc_s = [0.0_wp, 0.0_wp, 1.0_wp / 7.0_wp]
        model%elements%bc_n = [0.0_wp, 0.0_wp, -2.5_wp]
        model%elements%mu = [0.6_wp, 0.6_wp, 0.0_wp]
        model%elements%sf = [1.0_wp, 0.1_wp, 0.0_wp]
        model%elements%pressure = [0.0_wp, 0.3_wp, 0.0_wp]
        model%elements%tensile_strength = [0.5_wp, 0.0_wp, 0.0_wp]
        model%elements%sf_residual = [0.25_wp, no_residual_drop, no_residual_drop]
        model%elements%mu_dynamic = [0.4_wp, no_residual_drop, no_residual_drop]
        model%elements%slip_weakening_distance = [1.0e-4_wp, 0.0_wp, 0.0_wp]
        model%elements%shear_stiffness = [1.0e4_wp, 2.0e4_wp, 3.0e4_wp]
        model%elements%normal_stiffness = rigid_joint
        call compute_geometry(model%elements)

        allocate (model%fractures(2))
        model%fractures(1)%name = 'main fault'
        model%fractures(1)%first_element = 1
        model%fractures(1)%last_element = 2
        model%fractures(2)%name = 'splay'
        model%fractures(2)%first_element = 3
        model%fractures(2)%last_element = 3

        allocate (model%observations(2))
        model%observations(1)%name = 'map'
        model%observations(1)%kind = observation_grid
        model%observations(1)%nx = 3
        model%observations(1)%ny = 2
        model%observations(1)%x = [0.0_wp, 0.5_wp, 1.0_wp, 0.0_wp, 0.5_wp, 1.0_wp]
        model%observations(1)%y = [-1.0_wp, -1.0_wp, -1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
        model%observations(2)%name = 'profile'
        model%observations(2)%kind = observation_line
        model%observations(2)%nx = 4
        model%observations(2)%ny = 1
        model%observations(2)%x = [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
        model%observations(2)%y = [-0.3_wp, -0.1_wp, 0.1_wp, 0.3_wp]

        associate (r => results%elements)
            r%ds = [-1.0e-4_wp, -2.0e-4_wp / 3.0_wp, 0.0_wp]
            r%dn = [0.0_wp, -1.0e-5_wp, 3.0e-6_wp]
            r%sf_in_force = [0.25_wp, 0.1_wp, 0.0_wp]
            r%tensile_in_force = [0.5_wp, 0.0_wp, 0.0_wp]
            r%mu_in_force = [0.5_wp, 0.6_wp, 0.0_wp]
            r%shear_traction = [10.1_wp, 9.9_wp, 1.0_wp / 7.0_wp]
            r%normal_traction = [-20.0_wp, -0.3_wp, -2.5_wp]
            r%us_minus = [-0.5e-4_wp, -1.0e-4_wp / 3.0_wp, 0.1_wp]
            r%un_minus = [0.0_wp, -0.5e-5_wp, 0.2_wp]
            r%us_plus = [0.5e-4_wp, 1.0e-4_wp / 3.0_wp, 0.3_wp]
            r%un_plus = [0.0_wp, 0.5e-5_wp, 0.4_wp]
            r%state = [state_stick, state_slip, state_free]
        end associate

        results%tips%n = 2
        results%tips%x = [-1.0_wp, 1.0_wp]
        results%tips%y = [0.0_wp, 0.0_wp]
        results%tips%fracture_id = [1, 1]
        results%tips%element = [1, 2]
        results%tips%k1 = [0.0_wp, 0.123_wp]
        results%tips%k2 = [7.763_wp, -1.0_wp / 3.0_wp]
        results%tips%graded = [0, 1]

        allocate (results%fields(2))
        do i = 1, 2
            associate (f => results%fields(i), n => size(model%observations(i)%x))
                f%ux = [(0.1_wp * i + 1.0e-3_wp * k, k = 1, n)]
                f%uy = [(-0.2_wp * i + 1.0e-3_wp * k, k = 1, n)]
                f%sxx = [(-143.75_wp + k / 3.0_wp, k = 1, n)]
                f%syy = [(-81.25_wp - k / 7.0_wp, k = 1, n)]
                f%sxy = [(54.13_wp + k, k = 1, n)]
                f%flag = [(point_clear, k = 1, n)]
            end associate
        end do
        ! Grid point 4 lies on element 1's end: flagged, values NaN; point 5 near.
        results%fields(1)%flag(4) = point_on_element
        results%fields(1)%flag(5) = point_near
        results%fields(1)%sxx(4) = nan
        results%fields(1)%ux(4) = nan

        results%solver%method = 'lemke'
        results%solver%threads = 2
        results%solver%pivots = 5
        results%solver%equilibrium_residual = 1.5e-13_wp
        results%solver%seconds_assembly = 0.125_wp
        results%solver%seconds_total = 2.5_wp
    end subroutine sample

    !> Write the sample to a unique file; the model and results used are returned.
    subroutine write_sample(path, error, model, results)
        character(len=:), allocatable, intent(out) :: path
        type(error_type), allocatable, intent(out) :: error
        type(model_type), intent(out), optional :: model
        type(model_results), intent(out), optional :: results
        type(model_type) :: model_local
        type(model_results) :: results_local

        call sample(model_local, results_local)
        path = unique_path('result')//'.h5'
        call write_or_fail(path, model_local, results_local, 'write_results failed', error)
        if (allocated(error)) return
        if (present(model)) model = model_local
        if (present(results)) results = results_local
    end subroutine write_sample

    !> Write model and results to path; a failure of write_results fails the test with
    !> "<label>: <message>".
    subroutine write_or_fail(path, model, results, label, error)
        character(len=*), intent(in) :: path
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: results
        character(len=*), intent(in) :: label
        type(error_type), allocatable, intent(inout) :: error
        type(error_type), allocatable :: write_error

        call write_results(path, model, results, write_error)
        if (allocated(write_error)) call check(error, .false., label//': '//write_error%message)
    end subroutine write_or_fail

    !> Compare a real dataset with expected values and Fortran dims, exactly (NaN = NaN).
    subroutine check_real_dataset(error, path, dataset, expected, dims)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: path, dataset
        real(wp), intent(in) :: expected(:)
        integer, intent(in) :: dims(:)
        real(wp), allocatable :: values(:)
        integer :: i

        if (allocated(error)) return
        call check_dims(error, path, dataset, dims)
        if (.not. allocated(error)) call read_real_dataset(path, dataset, values, error)
        if (allocated(error)) return
        call check(error, size(values), size(expected), dataset//' size')
        do i = 1, size(expected)
            if (ieee_is_nan(expected(i))) then
                call check(error, ieee_is_nan(values(i)), dataset//' keeps NaN')
            else
                call check(error, values(i), expected(i), dataset, abs_tol=exact)
            end if
        end do
    end subroutine check_real_dataset

    !> Compare an integer dataset with expected values and Fortran dims.
    subroutine check_int_dataset(error, path, dataset, expected, dims)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: path, dataset
        integer, intent(in) :: expected(:)
        integer, intent(in) :: dims(:)
        integer, allocatable :: values(:)
        integer :: i

        if (allocated(error)) return
        call check_dims(error, path, dataset, dims)
        if (.not. allocated(error)) call read_int_dataset(path, dataset, values, error)
        if (allocated(error)) return
        call check(error, size(values), size(expected), dataset//' size')
        do i = 1, size(expected)
            call check(error, values(i), expected(i), dataset)
        end do
    end subroutine check_int_dataset

    !> Compare the Fortran dims of a dataset.
    subroutine check_dims(error, path, dataset, expected)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: path, dataset
        integer, intent(in) :: expected(:)
        integer, allocatable :: dims(:)
        integer :: i

        if (allocated(error)) return
        call read_dataset_dims(path, dataset, dims, error)
        if (allocated(error)) return
        call check(error, size(dims), size(expected), dataset//' rank')
        if (allocated(error)) return
        do i = 1, size(expected)
            call check(error, dims(i), expected(i), dataset//' extent')
        end do
    end subroutine check_dims

    !> Compare a string attribute.
    subroutine check_string_attribute(error, path, object, name, expected)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: path, object, name, expected
        character(len=:), allocatable :: value

        if (allocated(error)) return
        call read_string_attribute(path, object, name, value, error)
        if (allocated(error)) return
        call check(error, value == expected .and. len(value) == len(expected), &
            object//' attribute '//name//' = "'//value//'", expected "'//expected//'"')
    end subroutine check_string_attribute

    !> Compare a real attribute (of the root unless object is given), exactly.
    subroutine check_real_attribute(error, path, name, expected, object)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: path, name
        real(wp), intent(in) :: expected(:)
        character(len=*), intent(in), optional :: object
        real(wp), allocatable :: values(:)
        integer :: i

        if (allocated(error)) return
        if (present(object)) then
            call read_real_attribute(path, object, name, values, error)
        else
            call read_real_attribute(path, '/', name, values, error)
        end if
        if (allocated(error)) return
        call check(error, size(values), size(expected), 'attribute '//name//' size')
        do i = 1, size(expected)
            call check(error, values(i), expected(i), 'attribute '//name, abs_tol=exact)
        end do
    end subroutine check_real_attribute

    !> A file name in /tmp unique to this run and call.
    function unique_path(label) result(path)
        character(len=*), intent(in) :: label
        character(len=:), allocatable :: path
        integer, save :: calls = 0
        integer(int64) :: ticks
        character(len=40) :: stamp

        calls = calls + 1
        call system_clock(ticks)
        write (stamp, '(i0,"_",i0)') ticks, calls
        path = '/tmp/ddc2d_test_output_'//trim(stamp)//'_'//label
    end function unique_path

    !> True when the file exists.
    function exists(path)
        character(len=*), intent(in) :: path
        logical :: exists

        inquire (file=path, exist=exists)
    end function exists

    !> Create a small file, with one line of text.
    subroutine touch(path, line)
        character(len=*), intent(in) :: path
        character(len=*), intent(in), optional :: line
        integer :: unit

        open (newunit=unit, file=path, status='replace', action='write')
        if (present(line)) then
            write (unit, '(a)') line
        else
            write (unit, '(a)') 'test'
        end if
        close (unit)
    end subroutine touch

end module test_output
