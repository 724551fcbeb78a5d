!> The model fingerprint (ddc_model_fingerprint, --resume): the same for the same input read
!> twice and for inputs that differ only in &growth steps or the length of &load_path;
!> different when a value that determines the result changes.
module test_fingerprint
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type
    use ddc_model_fingerprint, only: model_fingerprint, recorded_fingerprint, fingerprint_length
    use ddc_contact_options, only: lcp_lemke
    use ddc_input_namelist, only: read_namelist_model
    implicit none
    private

    public :: collect_fingerprint

    character(len=*), parameter :: data_dir = 'data/fingerprint/'

contains

    !> Cases of the fingerprint suite.
    subroutine collect_fingerprint(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('same_input_read_twice', test_read_twice), &
                 new_test('growth_steps_not_hashed', test_growth_steps), &
                 new_test('load_path_length_not_hashed', test_path_length), &
                 new_test('result_values_hashed', test_values_hashed), &
                 new_test('names_and_machine_not_hashed', test_not_hashed), &
                 new_test('recorded_fingerprint_kept', test_recorded)]
    end subroutine collect_fingerprint

    !> The fingerprint of an input file of data_dir.
    function fingerprint_of(name, error) result(text)
        character(len=*), intent(in) :: name
        type(error_type), allocatable, intent(inout) :: error
        character(len=fingerprint_length) :: text
        type(model_type) :: model

        text = ''
        call read_namelist_model(data_dir//name, model, error)
        if (.not. allocated(error)) text = model_fingerprint(model)
    end function fingerprint_of

    subroutine test_read_twice(error)
        type(error_type), allocatable, intent(out) :: error

        call check_same('growth.nml', 'growth.nml', 'same input, same fingerprint', error)
    end subroutine test_read_twice

    subroutine test_growth_steps(error)
        type(error_type), allocatable, intent(out) :: error

        call check_same('growth.nml', 'growth_steps.nml', '4 or 9 growth steps', error)
    end subroutine test_growth_steps

    !> A path and its longer continuation (which also varies p0 from its fixed value on).
    subroutine test_path_length(error)
        type(error_type), allocatable, intent(out) :: error

        call check_same('history.nml', 'history_longer.nml', 'a longer path', error)
    end subroutine test_path_length

    !> Two input files of data_dir have the same fingerprint, of sixteen hex digits.
    subroutine check_same(first_file, second_file, label, error)
        character(len=*), intent(in) :: first_file, second_file, label
        type(error_type), allocatable, intent(out) :: error
        character(len=fingerprint_length) :: first, second

        first = fingerprint_of(first_file, error)
        if (allocated(error)) return
        second = fingerprint_of(second_file, error)
        if (allocated(error)) return
        call check(error, first == second, label//': same fingerprint')
        if (allocated(error)) return
        call check(error, verify(first, '0123456789ABCDEF') == 0, 'sixteen hex digits: '//first)
    end subroutine check_same

    !> mu of one element, one grid point, the LCP method, the toughness, whether there is a
    !> load path: each changes the fingerprint.
    subroutine test_values_hashed(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, changed
        character(len=fingerprint_length) :: base

        call read_namelist_model(data_dir//'growth.nml', model, error)
        if (allocated(error)) return
        base = model_fingerprint(model)
        changed = model
        changed%elements%mu(10) = 0.5_wp
        call check(error, model_fingerprint(changed) /= base, 'mu of element 10')
        if (allocated(error)) return
        changed = model
        changed%observations(1)%x(2) = changed%observations(1)%x(2) + 1.0e-9_wp
        call check(error, model_fingerprint(changed) /= base, 'a grid point')
        if (allocated(error)) return
        changed = model
        changed%solver%lcp_method = lcp_lemke
        call check(error, model_fingerprint(changed) /= base, 'lcp_method')
        if (allocated(error)) return
        changed = model
        changed%growth%toughness = 15.0_wp
        call check(error, model_fingerprint(changed) /= base, 'toughness')
        if (allocated(error)) return
        changed = model
        allocate (changed%load_path%vertex(7, 1))
        call check(error, model_fingerprint(changed) /= base, 'a load path')
    end subroutine test_values_hashed

    !> Title, file names and this machine's memory limit do not change the fingerprint.
    subroutine test_not_hashed(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, changed

        call read_namelist_model(data_dir//'growth.nml', model, error)
        if (allocated(error)) return
        changed = model
        changed%title = 'another title'
        changed%output_file = 'elsewhere.h5'
        changed%input_file = 'elsewhere.nml'
        changed%solver%work_bytes = 1.0e9_wp
        call check(error, model_fingerprint(changed) == model_fingerprint(model), &
                   'title, file names, work_bytes')
    end subroutine test_not_hashed

    !> recorded_fingerprint returns the one recorded before a run changed the model.
    subroutine test_recorded(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        character(len=fingerprint_length) :: before

        call read_namelist_model(data_dir//'growth.nml', model, error)
        if (allocated(error)) return
        before = model_fingerprint(model)
        call check(error, recorded_fingerprint(model) == before, 'none recorded: computed')
        if (allocated(error)) return
        model%fingerprint = before
        model%elements%x_end(1) = model%elements%x_end(1) + 0.1_wp
        call check(error, recorded_fingerprint(model) == before, 'recorded one kept')
        if (allocated(error)) return
        call check(error, model_fingerprint(model) /= before, 'the changed model differs')
    end subroutine test_recorded

end module test_fingerprint
