!> What the contact solves of every driver share beside the contact run
!> (ddc_run_contact_run): the fault law of a model's (contact) elements, read from their
!> per-element arrays (fault_law_of), whether a solve can change the strengths in force
!> (strengths_change), and the solver record of a contact solution (record_contact).
module ddc_solve_frictional
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set
    use ddc_model_results, only: solver_record
    use ddc_contact_result, only: contact_result
    use ddc_contact_options, only: solver_options, cohesion_lost
    use ddc_contact_fault_law, only: fault_law, new_fault_law
    implicit none
    private

    public :: fault_law_of, strengths_change, record_contact

contains

    !> The fault law of the elements `subset` (default: every element), from the model's
    !> per-element arrays.
    pure function fault_law_of(elements, subset) result(law)
        !> The model's elements
        type(element_set), intent(in) :: elements
        !> Indices of the elements, shape (m)
        integer, intent(in), optional :: subset(:)
        type(fault_law) :: law
        integer, allocatable :: pick(:)
        integer :: i

        if (present(subset)) then
            pick = subset
        else
            pick = [(i, i = 1, elements%n)]
        end if
        associate (e => elements)
            law = new_fault_law(e%mu(pick), e%sf(pick), &
                tensile_strength=e%tensile_strength(pick), sf_residual=e%sf_residual(pick), &
                mu_dynamic=e%mu_dynamic(pick), &
                slip_weakening_distance=e%slip_weakening_distance(pick), &
                opening_weakening_distance=e%opening_weakening_distance(pick), &
                shear_stiffness=e%shear_stiffness(pick), normal_stiffness=e%normal_stiffness(pick))
        end associate
    end function fault_law_of

    !> Whether a strength in force can change in a solve of the model: its law goes beyond
    !> Coulomb's, or open elements lose their cohesion (open_cohesion = 'lost'). A loading
    !> history records the strengths of each step only then.
    pure logical function strengths_change(elements, options)
        !> The model's elements
        type(element_set), intent(in) :: elements
        !> Its solver options
        type(solver_options), intent(in) :: options
        type(fault_law) :: law

        law = fault_law_of(elements)
        strengths_change = law%beyond_coulomb() .or. options%open_cohesion == cohesion_lost
    end function strengths_change

    !> Fill the solver record from a contact solution.
    subroutine record_contact(res, flops, record)
        !> The contact solution
        type(contact_result), intent(in) :: res
        !> Nominal flops of the factorizations outside the contact solve (the condensation)
        real(wp), intent(in) :: flops
        !> Method, pivots, counts, certificate, residual, flops and LCP time are set; the
        !> factorization time is added to
        type(solver_record), intent(inout) :: record
        real(wp) :: seconds

        record%method = res%method
        record%fallback = res%fallback
        record%newton_iterations = res%iterations
        seconds = record%counts%seconds
        record%counts = res%counts
        record%counts%flops = res%counts%flops + flops
        record%counts%seconds = seconds + res%counts%seconds
        record%pivots = res%pivots
        record%lcp_solves = res%solves
        record%certificate_min_z = res%certificate%min_z
        record%certificate_min_w = res%certificate%min_w
        record%certificate_max_complementarity = res%certificate%max_complementarity
        record%certificate_tolerance = res%certificate%tolerance
        record%seconds_lcp = res%seconds_lcp
        record%equilibrium_residual = maxval(res%equilibrium_residual)
    end subroutine record_contact
end module ddc_solve_frictional
