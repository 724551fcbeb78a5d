!> What a contact run (docs/ARCHITECTURE.md#the-contact-run) can do with a model, by the
!> kind of elastic operator it solves on: the one answer to the input's check of &solver
!> matrix, the choice of matrix = 'auto' and the MPI build's plan. A feature a kind of
!> operator cannot carry is one line here.
module ddc_model_capabilities
    use ddc_kinds, only: wp
    use ddc_text, only: newline
    use ddc_model_types, only: model_type, condition_contact, condition_rate_state, rigid_joint
    use ddc_model_element_laws, only: fault_law_of
    use ddc_contact_options, only: lcp_lemke, matrix_hierarchical
    use ddc_contact_fault_law, only: fault_law
    implicit none
    private

    public :: run_refusal, operator_dense, operator_hierarchical, operator_distributed

    !> The kinds of elastic operator a run solves on: dense in this process, hierarchical,
    !> distributed over MPI processes
    integer, parameter :: operator_dense = 1, operator_hierarchical = 2, &
        operator_distributed = 3

contains

    !> What a run on an operator of the given kind cannot do with a model ('' when it can):
    !> the one answer to the input's check, the choice of 'auto' and the MPI build's plan.
    pure function run_refusal(model, kind) result(what)
        !> The model
        type(model_type), intent(in) :: model
        !> operator_dense, operator_hierarchical or operator_distributed
        integer, intent(in) :: kind
        character(len=:), allocatable :: what
        logical :: contact

        what = ''
        associate (e => model%elements)
            ! A cycle run's rate-and-state elements are its operator's contact elements.
            contact = any(e%condition == condition_contact .or. &
                          e%condition == condition_rate_state)
            select case (kind)
            case (operator_hierarchical)
                if (contact .and. any(e%condition /= condition_contact .and. &
                                      e%condition /= condition_rate_state)) then
                    call add('contact elements beside elements of other conditions')
                else if (contact .and. model%solver%lcp_method == lcp_lemke) then
                    call add("lcp_method = 'lemke' (its tableau is dense)")
                else if (model%growth%active) then
                    call add('fracture growth (&growth)')
                else if (elastic(e%shear_stiffness) .or. elastic(e%normal_stiffness)) then
                    call add('elastic joints')
                else if (allocated(model%body)) then
                    call add('a finite body (&body)')
                else if (model%fluid%active) then
                    call add('coupled flow (&fluid: its Jacobian reads the dense matrix)')
                end if
            case (operator_distributed)
                if (model%solver%lcp_method == lcp_lemke) call add("&solver lcp_method = "// &
                    "'lemke' (Lemke's tableau is not distributed; 'newton' and 'auto' are)")
                if (allocated(model%load_path%vertex)) call add('&load_path (loading '// &
                    'histories are not distributed)')
                if (model%growth%active) call add('&growth (fracture growth is not '// &
                    'distributed)')
                if (model%solver%matrix == matrix_hierarchical) call add("&solver matrix "// &
                    "= 'hierarchical' (hmat-oss is sequential; the distributed solve is dense)")
                if (beyond_coulomb()) call add('&fracture tensile_strength, sf_residual, '// &
                    'mu_dynamic or a joint stiffness (strength beyond Coulomb is not '// &
                    'distributed)')
                if (model%cycle%active) call add('&cycle (earthquake cycles are not '// &
                    'distributed)')
                if (allocated(model%body)) call add('&body (a finite body is not distributed)')
            case default
                ! A dense operator in this process solves every model.
                continue
            end select
        end associate

    contains

        pure subroutine add(feature)
            character(len=*), intent(in) :: feature

            if (len(what) > 0) what = what//newline
            what = what//feature
        end subroutine add

        pure logical function elastic(stiffness)
            real(wp), allocatable, intent(in) :: stiffness(:)

            elastic = .false.
            if (allocated(stiffness)) elastic = any(stiffness < rigid_joint)
        end function elastic

        pure logical function beyond_coulomb()
            type(fault_law) :: law

            law = fault_law_of(model%elements)
            beyond_coulomb = law%beyond_coulomb()
        end function beyond_coulomb
    end function run_refusal

end module ddc_model_capabilities
