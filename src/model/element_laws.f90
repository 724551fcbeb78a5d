!> The fault law of a model's elements (ddc_contact_fault_law), read from their
!> per-element arrays: for every contact run (one-shot, loading history, growth, MPI), the
!> input's and the run's capability checks, and a resumed run's memory.
module ddc_model_element_laws
    use ddc_model_types, only: element_set
    use ddc_contact_options, only: solver_options, cohesion_lost
    use ddc_contact_fault_law, only: fault_law, new_fault_law
    implicit none
    private

    public :: fault_law_of, strengths_change

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

end module ddc_model_element_laws
