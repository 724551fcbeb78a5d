!> The fault law of a model's elements (ddc_contact_fault_law), read from their
!> per-element arrays: for every contact run (one-shot, loading history, growth, MPI), the
!> input's and the run's capability checks, and a resumed run's memory.
module ddc_model_element_laws
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, strength_law_count
    use ddc_model_laws, only: strength_law, strength_laws, law_values
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
        type(strength_law) :: laws(strength_law_count)
        real(wp), allocatable :: given(:, :)
        integer, allocatable :: pick(:)
        integer :: i, k

        if (present(subset)) then
            pick = subset
        else
            pick = [(i, i = 1, elements%n)]
        end if
        laws = strength_laws()
        given = law_values(elements)
        law = new_fault_law(elements%mu(pick), elements%sf(pick))
        do k = 1, size(laws)
            call law%set_given(laws(k)%name, given(pick, k))
        end do
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
