!> The solve of the serial program, and of the MPI program when its first process solves
!> alone (a model that needs what is not distributed, or one process): a resumed run
!> (--resume), fracture growth, a loading history or one solve.
module ddc_app_solve
    use ddc_error, only: error_type
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results
    use ddc_model_restart, only: restart_state
    use ddc_api_solve, only: solve_model
    use ddc_output_restart_read, only: read_restart
    use ddc_app_command_line, only: command_line_options
    use ddc_app_report, only: print_growth_step
    use ddc_output_hdf5, only: write_results
    implicit none
    private

    public :: solve_on_one_process

contains

    !> Solve the model on this process: continued from --resume's file when given, else by
    !> growing its fractures, along its loading history or in one solve.
    subroutine solve_on_one_process(options, model, results, error)
        !> The command line (its resume file)
        type(command_line_options), intent(in) :: options
        !> The model; growth adds its new elements
        type(model_type), intent(inout) :: model
        !> The results
        type(model_results), intent(out) :: results
        !> Allocated when the solve fails
        type(error_type), allocatable, intent(out) :: error
        type(restart_state) :: restart

        if (allocated(options%resume_file)) then
            ! The file was checked in prepare_run: complete, this version, this model.
            call read_restart(options%resume_file, restart, error)
            if (allocated(error)) return
            call solve_model(model, results, error, print_growth_step, restart, write_so_far)
        else
            call solve_model(model, results, error, print_growth_step, writer=write_so_far)
        end if
    end subroutine solve_on_one_process

    !> The result file of a cycle run so far: a checkpoint, or the run that stopped.
    subroutine write_so_far(model, results, error)
        !> The model
        type(model_type), intent(in) :: model
        !> Its results so far
        type(model_results), intent(in) :: results
        !> Set when the file cannot be written
        type(error_type), allocatable, intent(out) :: error

        call write_results(model%output_file, model, results, error)
    end subroutine write_so_far

end module ddc_app_solve
