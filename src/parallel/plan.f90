!> What of a model the MPI build distributes, decided once on the root: what a contact run
!> on the distributed operator cannot do (run_refusal, ddc_run_contact_run) is refused with
!> more than one process (exit_bad_input, naming what to do); with one process such a model
!> runs as in the serial build.
module ddc_parallel_plan
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_text, only: itoa, newline, prefix_lines
    use ddc_model_types, only: model_type, condition_contact
    use ddc_contact_options, only: lcp_auto
    use ddc_contact_formulation, only: auto_newton_min_elements
    use ddc_model_capabilities, only: run_refusal, operator_distributed
    implicit none
    private

    public :: plan_run

contains

    !> Whether the model runs distributed; with one process, also the models the serial
    !> build would solve by Lemke's method ('lemke', or 'auto' below
    !> auto_newton_min_elements contact elements) run serially, which is the same answer.
    subroutine plan_run(model, processes, distributed, error)
        !> The model as read
        type(model_type), intent(in) :: model
        !> Number of processes
        integer, intent(in) :: processes
        !> The model runs on every process (else on the root alone)
        logical, intent(out) :: distributed
        !> Allocated (exit_bad_input) when the model needs what is not distributed and
        !> processes > 1: one line per feature
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: refused

        refused = run_refusal(model, operator_distributed)
        if (processes > 1) then
            distributed = .true.
            if (len(refused) > 0) call set_error(error, exit_bad_input, model%input_file// &
                ': with '//itoa(processes)//' processes ddc2d cannot solve (run it on one '// &
                'process (mpiexec -n 1) or with the serial build):'//newline// &
                prefix_lines('  ', refused))
        else
            distributed = len(refused) == 0 .and. .not. (model%solver%lcp_method == lcp_auto &
                .and. count(model%elements%condition == condition_contact) > 0 .and. &
                count(model%elements%condition == condition_contact) < auto_newton_min_elements)
        end if
    end subroutine plan_run

end module ddc_parallel_plan
