!> /growth/initiations (docs/output-reference.md#growthinitiations): one row per new fracture a
!> growth run with &initiation started inside the rock, and the group's settings; under
!> criterion 'work' with flaw points also each start's efficiency and every trial of the
!> flaws' first cracks (/growth/initiations/flaw_trials).
module ddc_output_hdf5_initiations
    use ddc_error, only: error_type
    use ddc_model_types, only: model_type
    use ddc_model_initiations, only: initiation_record
    use ddc_model_records, only: for_each_initiation_column
    use ddc_output_hdf5_handles, only: h5_object, create_group, close_group
    use ddc_output_hdf5_write, only: write_attribute
    use ddc_output_hdf5_records, only: column_writer, set_up
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
        type(column_writer) :: writer
        type(initiation_record) :: columns

        if (.not. allocated(record%kind)) return
        call create_group(root, 'growth/initiations', writer%group, error)
        if (allocated(error)) return
        call set_up(writer, model)
        ! The flaws' searches (criterion 'work' with flaw points) allocate the trials.
        writer%work = allocated(record%trials%step)
        if (writer%work) call create_group(writer%group, 'flaw_trials', writer%trials, &
                                           writer%error)
        columns = record
        call for_each_initiation_column(columns, writer)
        if (writer%work) call close_group(writer%trials, writer%error)
        associate (o => model%initiation, group => writer%group)
            call write_attribute(group, 'tensile_strength', o%tensile_strength, writer%error)
            call write_attribute(group, 'probe_distance', o%probe_distance, writer%error)
            ! 0: the growth increment
            call write_attribute(group, 'flaw_length', o%flaw_length, writer%error)
            call write_attribute(group, 'flaws', size(o%flaw_x), writer%error)
            ! How close the last check that started nothing came (it has no row).
            if (record%largest_step > 0) then
                call write_attribute(group, 'largest_tension', record%largest_tension, &
                                     writer%error)
                call write_attribute(group, 'largest_tension_x', record%largest_x, writer%error)
                call write_attribute(group, 'largest_tension_y', record%largest_y, writer%error)
                call write_attribute(group, 'largest_tension_step', record%largest_step, &
                                     writer%error)
            end if
        end associate
        call close_group(writer%group, writer%error)
        call move_alloc(writer%error, error)
    end subroutine write_initiations

end module ddc_output_hdf5_initiations
