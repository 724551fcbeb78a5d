!> /growth/initiations (docs/output-reference.md#growthinitiations): one row per new fracture a
!> growth run with &initiation started inside the rock, and the group's settings; under
!> criterion 'work' with flaw points also each start's efficiency and every trial of the
!> flaws' first cracks (/growth/initiations/flaw_trials).
module ddc_output_hdf5_initiations
    use ddc_error, only: error_type
    use ddc_text, only: allocated_text
    use ddc_model_types, only: model_type
    use ddc_model_initiations, only: initiation_record
    use ddc_model_results, only: trial_state_coding
    use ddc_output_hdf5_handles, only: h5_object, create_group, close_group
    use ddc_output_hdf5_write, only: write_real_1d, write_int_1d, write_attribute
    implicit none
    private

    public :: write_initiations

contains

    !> /growth/initiations; /growth must exist.
    subroutine write_initiations(root, model, record, error)
        !> The file
        type(h5_object), intent(in) :: root
        !> The model that was solved (units, &initiation options)
        type(model_type), intent(in) :: model
        !> The new fractures it started
        type(initiation_record), intent(in) :: record
        !> Set when a write fails (nothing is written when it is set already)
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: group, trials
        character(len=:), allocatable :: length, stress, work

        if (.not. allocated(record%kind)) return
        length = allocated_text(model%length_unit)
        stress = allocated_text(model%stress_unit)
        call create_group(root, 'growth/initiations', group, error)
        call write_int_1d(group, 'kind', record%kind, error, coding='1 tail, 2 flaw')
        call write_int_1d(group, 'step', record%step, error)
        call write_int_1d(group, 'load_step', record%load_step, error)
        call write_int_1d(group, 'fracture_id', record%fracture_id, error)
        call write_int_1d(group, 'parent', record%parent, error, coding='0 none (a flaw)')
        call write_int_1d(group, 'element', record%element, error, coding='0 none (a flaw)')
        call write_int_1d(group, 'flaw', record%flaw, error, coding='0 none (a tail)')
        call write_int_1d(group, 'side', record%side, error, coding='+1 the side of the '// &
                          'element normal (-sin beta, cos beta), -1 the other, 0 a flaw')
        call write_real_1d(group, 'x', record%x, length, error)
        call write_real_1d(group, 'y', record%y, length, error)
        call write_real_1d(group, 'probe_x', record%probe_x, length, error)
        call write_real_1d(group, 'probe_y', record%probe_y, length, error)
        call write_real_1d(group, 'tension', record%tension, stress, error)
        call write_real_1d(group, 'angle', record%angle, 'degree', error)
        ! The flaws' searches (criterion 'work' with flaw points) allocate the trials.
        if (allocated(record%trial_step)) then
            work = stress//' '//length
            call write_real_1d(group, 'efficiency', record%efficiency, work, error)
            call create_group(group, 'flaw_trials', trials, error)
            call write_int_1d(trials, 'step', record%trial_step, error)
            call write_int_1d(trials, 'flaw', record%trial_flaw, error)
            call write_real_1d(trials, 'angle', record%trial_angle, 'degree', error)
            call write_real_1d(trials, 'efficiency', record%trial_efficiency, work, error)
            call write_int_1d(trials, 'state', record%trial_state, error, &
                              coding=trial_state_coding)
            call close_group(trials, error)
        end if
        associate (o => model%initiation)
            call write_attribute(group, 'tensile_strength', o%tensile_strength, error)
            call write_attribute(group, 'probe_distance', o%probe_distance, error)
            ! 0: the growth increment
            call write_attribute(group, 'flaw_length', o%flaw_length, error)
            call write_attribute(group, 'flaws', size(o%flaw_x), error)
        end associate
        ! How close the last check that started nothing came (it has no row).
        if (record%largest_step > 0) then
            call write_attribute(group, 'largest_tension', record%largest_tension, error)
            call write_attribute(group, 'largest_tension_x', record%largest_x, error)
            call write_attribute(group, 'largest_tension_y', record%largest_y, error)
            call write_attribute(group, 'largest_tension_step', record%largest_step, error)
        end if
        call close_group(group, error)
    end subroutine write_initiations

end module ddc_output_hdf5_initiations
