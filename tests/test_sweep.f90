!> Tests of parameter sweeps: reading &sweep, task enumeration (product and zip),
!> substitution into the base model, output names, skip-if-complete and bad sweep input.
!> Input files are written to /tmp.
module test_sweep
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_error, only: exit_bad_input
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results
    use ddc_input_namelist, only: read_namelist_model
    use ddc_input_sweep, only: read_sweep
    use ddc_sweep_tasks, only: sweep_definition, combine_product, combine_zip, task_values, &
        task_label, task_file_name, check_task, apply_task
    use ddc_output_hdf5_read, only: output_is_complete
    use ddc_run_model, only: run_model
    use ddc_output_hdf5, only: write_results
    use ddc_output_atomic, only: remove_file
    implicit none
    private
    public :: collect_sweep

    !> A base model with two fractures (10 and 5 elements) under the paper's stresses
    character(len=*), parameter :: nl = new_line('a')
    character(len=*), parameter :: base_model = &
        "&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /"//nl// &
        "&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /"//nl// &
        "&fracture name = 'a', x = -1.0, 1.0, y = 0.0, 0.0, elements = 10, mu = 0.6, "// &
        "sf = 1.0 /"//nl// &
        "&fracture name = 'b', x = -1.0, 1.0, y = 2.0, 2.0, elements = 5, mu = 0.6, "// &
        "sf = 1.0 /"//nl
    real(wp), parameter :: tight = 1.0e-13_wp

contains

    !> Cases of the sweep suite.
    subroutine collect_sweep(tests)
        !> The cases
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [ &
            new_test('no_sweep_group', test_no_sweep), &
            new_test('enumeration_product', test_product), &
            new_test('enumeration_zip', test_zip), &
            new_test('substitution_fracture_and_elastic', test_substitution), &
            new_test('substitution_principal_stresses', test_principal), &
            new_test('substitution_components', test_components), &
            new_test('task_labels', test_labels), &
            new_test('output_names', test_names), &
            new_test('skip_if_complete', test_skip_if_complete), &
            new_test('bad_unknown_parameter', test_bad_unknown), &
            new_test('bad_empty_list', test_bad_empty), &
            new_test('bad_zip_lengths', test_bad_zip), &
            new_test('bad_values_and_names', test_bad_values), &
            new_test('bad_mixed_stress_descriptions', test_bad_mixed), &
            new_test('bad_misspelled_variable', test_bad_misspelled), &
            new_test('bad_task_out_of_range', test_bad_task) &
            ]
    end subroutine collect_sweep

    ! ------------------------------------------------------------------------------------
    ! Helpers
    ! ------------------------------------------------------------------------------------

    !> Write base_model plus sweep_text to a file in /tmp, read the model and the sweep.
    subroutine read_case(label, sweep_text, model, sweep, found, read_error, path)
        character(len=*), intent(in) :: label, sweep_text
        type(model_type), intent(out) :: model
        type(sweep_definition), intent(out) :: sweep
        logical, intent(out) :: found
        type(error_type), allocatable, intent(out) :: read_error
        character(len=:), allocatable, intent(out) :: path
        integer :: unit

        path = '/tmp/ddc2d_test_sweep_'//label//'.nml'
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') base_model//sweep_text
        close (unit)
        call read_namelist_model(path, model, read_error)
        if (allocated(read_error)) return
        call read_sweep(path, model, sweep, found, read_error)
    end subroutine read_case

    !> Read a good case; fail when it cannot be read or has no sweep.
    subroutine read_good(error, label, sweep_text, model, sweep)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: label, sweep_text
        type(model_type), intent(out) :: model
        type(sweep_definition), intent(out) :: sweep
        type(error_type), allocatable :: read_error
        character(len=:), allocatable :: path
        logical :: found

        call read_case(label, sweep_text, model, sweep, found, read_error, path)
        if (allocated(read_error)) then
            call check(error, .false., label//': unexpected error: '//read_error%message)
            return
        end if
        call check(error, found, label//': the &sweep group is found')
    end subroutine read_good

    !> The sweep must be refused with exit_bad_input and a message holding every fragment.
    subroutine check_bad(error, label, sweep_text, fragments)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: label, sweep_text
        character(len=*), intent(in) :: fragments(:)
        type(model_type) :: model
        type(sweep_definition) :: sweep
        type(error_type), allocatable :: read_error
        character(len=:), allocatable :: path
        logical :: found
        integer :: i

        call read_case(label, sweep_text, model, sweep, found, read_error, path)
        if (.not. allocated(read_error)) then
            call check(error, .false., label//': bad sweep accepted')
            return
        end if
        call check(error, read_error%code, exit_bad_input, label//': exit code')
        do i = 1, size(fragments)
            call check(error, index(read_error%message, trim(fragments(i))) > 0, &
                       label//": message '"//read_error%message//"' lacks '"// &
                       trim(fragments(i))//"'")
        end do
        call check(error, index(read_error%message, path//': &sweep (line 5): ') > 0, &
                   label//': the message names the file and the group: '//read_error%message)
    end subroutine check_bad

    ! ------------------------------------------------------------------------------------
    ! Enumeration
    ! ------------------------------------------------------------------------------------

    subroutine test_no_sweep(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(sweep_definition) :: sweep
        type(error_type), allocatable :: read_error
        character(len=:), allocatable :: path
        logical :: found

        call read_case('none', '', model, sweep, found, read_error, path)
        call check(error, .not. allocated(read_error), 'a file without &sweep reads')
        call check(error, .not. found, 'no &sweep group found')
    end subroutine test_no_sweep

    !> 3 x 2 product: the last parameter varies fastest.
    subroutine test_product(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(sweep_definition) :: sweep
        real(wp) :: v(2)
        integer :: k

        call read_good(error, 'product', "&sweep parameters = 'mu', 'sf', "// &
                       "values_1 = 0.2, 0.4, 0.6, values_2 = 0, 5 /", model, sweep)
        if (allocated(error)) return
        call check(error, sweep%combine, combine_product, 'default combine')
        call check(error, sweep%tasks, 6, 'tasks')
        do k = 0, 5
            v = task_values(sweep, k)
            call check(error, v(1), 0.2_wp * real(k / 2 + 1, wp), 'mu of a task', &
                       abs_tol=tight)
            call check(error, v(2), 5.0_wp * real(mod(k, 2), wp), 'sf of a task', &
                       abs_tol=tight)
        end do
    end subroutine test_product

    !> Zip: task k takes value k of every list.
    subroutine test_zip(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(sweep_definition) :: sweep
        real(wp) :: v(3)
        integer :: k

        call read_good(error, 'zip', "&sweep combine = 'ZIP', parameters = 'sxx', 'syy', "// &
                       "'sxy', values_1 = -1, -2, -3, -4, values_2 = -10, -20, -30, -40, "// &
                       "values_3 = 1, 2, 3, 4 /", model, sweep)
        if (allocated(error)) return
        call check(error, sweep%combine, combine_zip, 'combine')
        call check(error, sweep%tasks, 4, 'tasks')
        do k = 0, 3
            v = task_values(sweep, k)
            call check(error, v(1), -real(k + 1, wp), 'sxx of a task', abs_tol=tight)
            call check(error, v(2), -10.0_wp * real(k + 1, wp), 'syy of a task', abs_tol=tight)
            call check(error, v(3), real(k + 1, wp), 'sxy of a task', abs_tol=tight)
        end do
    end subroutine test_zip

    ! ------------------------------------------------------------------------------------
    ! Substitution
    ! ------------------------------------------------------------------------------------

    !> fracture(2)%mu changes fracture 2 only; sf every element; E and nu the model.
    subroutine test_substitution(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(sweep_definition) :: sweep

        call read_good(error, 'substitution', "&sweep parameters = 'Fracture(2)%MU', 'sf', "// &
                       "'youngs_modulus', 'poissons_ratio', 'pressure', combine = 'zip', "// &
                       "values_1 = 0.1, 0.9, values_2 = 2, 3, values_3 = 1e4, 2e4, "// &
                       "values_4 = 0.2, 0.3, values_5 = 0.5, 0.7 / ! a comment", model, sweep)
        if (allocated(error)) return
        model%output_file = 'out/base.h5'
        call apply_task(model, sweep, 1)
        call check(error, all(model%elements%mu(1:10) == 0.6_wp), 'fracture 1 keeps its mu')
        call check(error, all(model%elements%mu(11:15) == 0.9_wp), 'fracture 2 gets mu 0.9')
        call check(error, all(model%elements%sf == 3.0_wp), 'every element gets sf 3')
        call check(error, all(model%elements%pressure == 0.7_wp), 'every element gets p 0.7')
        call check(error, model%youngs_modulus, 2.0e4_wp, 'E', rel_tol=tight)
        call check(error, model%poissons_ratio, 0.3_wp, 'nu', rel_tol=tight)
        call check(error, model%sxx, -143.75_wp, 'sxx unchanged', rel_tol=tight)
        call check(error, model%sweep%task, 1, 'task recorded')
        call check(error, model%sweep%tasks, 2, 'tasks recorded')
        call check(error, model%sweep%names(1) == 'fracture(2)%mu', 'names recorded, lower case')
        call check(error, model%sweep%values(3), 2.0e4_wp, 'values recorded', rel_tol=tight)
        call check(error, model%output_file == 'out/base_task0001.h5', &
                   'output name of the task: '//model%output_file)
    end subroutine test_substitution

    !> remote_angle alone keeps the base principal stresses (-175, -50, s1 at -30 degrees).
    subroutine test_principal(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, base
        type(sweep_definition) :: sweep

        call read_good(error, 'principal', "&sweep parameters = 'remote_angle', "// &
                       "values_1 = -30, 0, 90 /", base, sweep)
        if (allocated(error)) return
        model = base
        call apply_task(model, sweep, 0)
        call check(error, model%sxx, -143.75_wp, 'sxx at -30 degrees', abs_tol=0.01_wp)
        call check(error, model%syy, -81.25_wp, 'syy at -30 degrees', abs_tol=0.01_wp)
        call check(error, model%sxy, 54.13_wp, 'sxy at -30 degrees', abs_tol=0.01_wp)
        model = base
        call apply_task(model, sweep, 1)
        call check(error, model%sxx, -175.0_wp, 'sxx at 0 degrees', abs_tol=0.01_wp)
        call check(error, model%syy, -50.0_wp, 'syy at 0 degrees', abs_tol=0.01_wp)
        call check(error, model%sxy, 0.0_wp, 'sxy at 0 degrees', abs_tol=1.0e-12_wp)
        model = base
        call apply_task(model, sweep, 2)
        call check(error, model%sxx, -50.0_wp, 'sxx at 90 degrees', abs_tol=0.01_wp)
        call check(error, model%syy, -175.0_wp, 'syy at 90 degrees', abs_tol=0.01_wp)
        call check(error, model%sxy, 0.0_wp, 'sxy at 90 degrees', abs_tol=1.0e-12_wp)

        call read_good(error, 'principal_all', "&sweep parameters = 'remote_s1', "// &
                       "'remote_s3', 'remote_angle', combine = 'zip', values_1 = -100, "// &
                       "values_2 = -20, values_3 = 45 /", model, sweep)
        if (allocated(error)) return
        call apply_task(model, sweep, 0)
        call check(error, model%sxx, -60.0_wp, 'sxx of s1 -100, s3 -20 at 45', rel_tol=tight)
        call check(error, model%syy, -60.0_wp, 'syy of s1 -100, s3 -20 at 45', rel_tol=tight)
        call check(error, model%sxy, -40.0_wp, 'sxy of s1 -100, s3 -20 at 45', rel_tol=tight)
    end subroutine test_principal

    !> Components replace the base values one by one.
    subroutine test_components(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(sweep_definition) :: sweep

        call read_good(error, 'components', "&sweep parameters = 'sxy', "// &
                       "values_1 = 10, 20 /", model, sweep)
        if (allocated(error)) return
        call apply_task(model, sweep, 1)
        call check(error, model%sxx, -143.75_wp, 'sxx kept', rel_tol=tight)
        call check(error, model%syy, -81.25_wp, 'syy kept', rel_tol=tight)
        call check(error, model%sxy, 20.0_wp, 'sxy swept', rel_tol=tight)
    end subroutine test_components

    ! ------------------------------------------------------------------------------------
    ! Names
    ! ------------------------------------------------------------------------------------

    subroutine test_labels(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(sweep_definition) :: sweep

        call read_good(error, 'labels', "&sweep parameters = 'mu', 'remote_angle', "// &
                       "values_1 = 0.2, 1.5e-5, 0.0265, values_2 = -30 /", model, sweep)
        if (allocated(error)) return
        call check(error, task_label(sweep, 0) == 'mu = 0.2, remote_angle = -30', &
                   'label of task 0: '//task_label(sweep, 0))
        call check(error, task_label(sweep, 1) == 'mu = 1.5E-05, remote_angle = -30', &
                   'label of task 1: '//task_label(sweep, 1))
        call check(error, task_label(sweep, 2) == 'mu = 0.0265, remote_angle = -30', &
                   'label of task 2: '//task_label(sweep, 2))
    end subroutine test_labels

    subroutine test_names(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, task_file_name('out/run.h5', 7, 25) == 'out/run_task0007.h5', &
                   'four digits at least: '//task_file_name('out/run.h5', 7, 25))
        call check(error, task_file_name('run.h5', 7, 12345) == 'run_task00007.h5', &
                   'width of the largest task: '//task_file_name('run.h5', 7, 12345))
        call check(error, task_file_name('run.h5', 9999, 10000) == 'run_task9999.h5', &
                   'largest task of 10000: '//task_file_name('run.h5', 9999, 10000))
        call check(error, task_file_name('a.b/run', 3, 4) == 'a.b/run_task0003', &
                   'no extension, dot in the folder: '//task_file_name('a.b/run', 3, 4))
        call check(error, task_file_name('a/.hidden', 0, 4) == 'a/.hidden_task0000', &
                   'a leading dot is no extension: '//task_file_name('a/.hidden', 0, 4))
    end subroutine test_names

    ! ------------------------------------------------------------------------------------
    ! Skip if complete
    ! ------------------------------------------------------------------------------------

    !> Missing and unreadable files are not complete; a written result is.
    subroutine test_skip_if_complete(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(sweep_definition) :: sweep
        type(model_results) :: results
        type(error_type), allocatable :: run_error
        character(len=*), parameter :: path = '/tmp/ddc2d_test_sweep_complete.h5'
        integer :: unit

        call remove_file(path)
        call check(error, .not. output_is_complete(path), 'a missing file is not complete')
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') 'not an HDF5 file'
        close (unit)
        call check(error, .not. output_is_complete(path), 'a corrupt file is not complete')

        call read_good(error, 'complete', "&sweep parameters = 'mu', values_1 = 0.1, 0.2 /", &
                       model, sweep)
        if (allocated(error)) return
        call apply_task(model, sweep, 1)
        call run_model(model, results, run_error)
        if (.not. allocated(run_error)) call write_results(path, model, results, run_error)
        if (allocated(run_error)) then
            call check(error, .false., 'solve and write: '//run_error%message)
            return
        end if
        call check(error, output_is_complete(path), 'a written result is complete')
        call remove_file(path)
    end subroutine test_skip_if_complete

    ! ------------------------------------------------------------------------------------
    ! Bad sweep input
    ! ------------------------------------------------------------------------------------

    subroutine test_bad_unknown(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad(error, 'unknown', "&sweep parameters = 'friction', values_1 = 0.2 /", &
                       [character(len=60) :: "parameters(1): 'friction' is not a sweep", &
                        'fracture(K)%mu'])
        call check_bad(error, 'bad_fracture', "&sweep parameters = 'fracture(3)%mu', "// &
                       "values_1 = 0.2 /", [character(len=60) :: "has 2 fracture(s)"])
        call check_bad(error, 'bad_property', "&sweep parameters = 'fracture(1)%bc_s', "// &
                       "values_1 = 0.2 /", [character(len=60) :: "are mu, sf and pressure"])
        call check_bad(error, 'no_parameters', "&sweep values_1 = 0.2 /", &
                       [character(len=60) :: 'parameters is empty', &
                        'values_1 is given but parameters names 0'])
    end subroutine test_bad_unknown

    subroutine test_bad_empty(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad(error, 'empty', "&sweep parameters = 'mu', 'sf', values_1 = 0.2 /", &
                       [character(len=60) :: "values_2 is empty: give at least one value of 'sf'"])
    end subroutine test_bad_empty

    subroutine test_bad_zip(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad(error, 'zip_lengths', "&sweep combine = 'zip', parameters = 'mu', "// &
                       "'sf', values_1 = 0.2, 0.4, values_2 = 1, 2, 3 /", &
                       [character(len=60) :: "combine = 'zip' needs value lists of one length", &
                        'lengths are 2, 3'])
        call check_bad(error, 'combine', "&sweep combine = 'cross', parameters = 'mu', "// &
                       "values_1 = 0.2 /", [character(len=60) :: "combine = 'cross' is not known"])
    end subroutine test_bad_zip

    !> Bad values and names are all reported at once.
    subroutine test_bad_values(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad(error, 'values', "&sweep parameters = 'mu', 'youngs_modulus', "// &
                       "'poissons_ratio', 'mu', values_1 = 0.2, -0.1, values_2 = 0, "// &
                       "values_3 = 0.5, values_4 = 1, values_5 = 3 /", &
                       [character(len=60) :: 'values_1(2) = -0.100000: mu must be >= 0', &
                        'youngs_modulus must be positive', &
                        'poissons_ratio must lie in (-1, 0.5)', &
                        "parameters(4) = 'mu' repeats parameters(1)", &
                        'values_5 is given but parameters names 4'])
        call check_bad(error, 'gaps', "&sweep parameters = 'mu', values_1(1) = 0.2, "// &
                       "values_1(3) = 0.4 /", [character(len=60) :: &
                       'values_1(2) is not given but a later value is'])
    end subroutine test_bad_values

    subroutine test_bad_mixed(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad(error, 'mixed', "&sweep parameters = 'sxx', 'remote_angle', "// &
                       "values_1 = -10, values_2 = 30 /", &
                       [character(len=60) :: 'either by components', 'not both'])
    end subroutine test_bad_mixed

    subroutine test_bad_misspelled(error)
        type(error_type), allocatable, intent(out) :: error

        call check_bad(error, 'misspelled', "&sweep parameter = 'mu', values_1 = 0.2 /", &
                       [character(len=60) :: "unknown variable 'parameter'", 'values_6'])
    end subroutine test_bad_misspelled

    subroutine test_bad_task(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(sweep_definition) :: sweep
        type(error_type), allocatable :: task_error

        call read_good(error, 'task_range', "&sweep parameters = 'mu', values_1 = 0.2, 0.4 /", &
                       model, sweep)
        if (allocated(error)) return
        call check_task(sweep, 1, task_error)
        call check(error, .not. allocated(task_error), 'task 1 of 2 exists')
        call check_task(sweep, 2, task_error)
        if (.not. allocated(task_error)) then
            call check(error, .false., 'task 2 of 2 accepted')
            return
        end if
        call check(error, task_error%code, exit_bad_input, 'exit code of task 2 of 2')
        call check(error, task_error%message == 'task 2 is out of range: the sweep has 2 '// &
                   'tasks, numbered 0 to 1', 'message: '//task_error%message)
        call check_task(sweep, -1, task_error)
        call check(error, allocated(task_error), 'task -1 refused')
    end subroutine test_bad_task

end module test_sweep
