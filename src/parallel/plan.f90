!> What of a model the MPI build distributes, decided once on the root: every feature a
!> model can carry that the distributed solve does not is listed here and refused with more
!> than one process (exit_bad_input, naming what to do); with one process such a model runs
!> as in the serial build.
module ddc_parallel_plan
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_text, only: itoa, newline
    use ddc_model_types, only: model_type, condition_contact
    use ddc_contact_options, only: lcp_auto, lcp_lemke, matrix_hierarchical
    use ddc_contact_formulation, only: auto_newton_min_elements
    use ddc_contact_fault_law, only: fault_law
    use ddc_solve_frictional, only: fault_law_of
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
        type(fault_law) :: law
        character(len=*), parameter :: one = ': run it on one process (mpiexec -n 1) or '// &
            'with the serial build'

        refused = ''
        if (model%solver%lcp_method == lcp_lemke) call refuse("&solver lcp_method = 'lemke' "// &
            "(Lemke's tableau is not distributed; 'newton' and 'auto' are)")
        if (allocated(model%load_path%vertex)) call refuse('&load_path (loading histories '// &
            'are not distributed)')
        if (model%growth%active) call refuse('&growth (fracture growth is not distributed)')
        if (model%solver%matrix == matrix_hierarchical) call refuse("&solver matrix = "// &
            "'hierarchical' (hmat-oss is sequential; the distributed solve is dense)")
        law = fault_law_of(model%elements)
        if (law%beyond_coulomb()) call refuse('&fracture '// &
            'tensile_strength, sf_residual, mu_dynamic or a joint stiffness (strength '// &
            'beyond Coulomb is not distributed)')
        if (processes > 1) then
            distributed = .true.
            if (len(refused) > 0) call set_error(error, exit_bad_input, model%input_file// &
                ': with '//itoa(processes)//' processes ddc2d cannot solve'//refused)
        else
            distributed = len(refused) == 0 .and. .not. (model%solver%lcp_method == lcp_auto &
                .and. count(model%elements%condition == condition_contact) > 0 .and. &
                count(model%elements%condition == condition_contact) < auto_newton_min_elements)
        end if

    contains

        !> Add a feature that is not distributed.
        subroutine refuse(feature)
            character(len=*), intent(in) :: feature

            refused = refused//newline//'  '//feature//one
        end subroutine refuse
    end subroutine plan_run

end module ddc_parallel_plan
