!> What a resumed run (--resume; docs/theory/earth.md#what-a-step-hands-on) takes from the complete
!> result file of an earlier run of the same model: the geometry it ended with, that geometry's
!> results (DDs, states, tractions, face displacements, tips), its growth record and loading
!> history, as the file holds them (ddc_output_restart_read reads it; ddc_growth_driver
!> and ddc_history_solve go on from it).
module ddc_model_restart
    use ddc_kinds, only: wp
    use ddc_model_results, only: model_results
    implicit none
    private

    public :: restart_state

    !> The end of an earlier run.
    type :: restart_state
        !> Its final results: elements, tips; growth (records, created_step, steps_taken,
        !> end_reason) of a growth run; history of a loading history, with columns (n, k)
        !> and k1, k2 of the final tips, shape (tips, k)
        type(model_results) :: results
        !> End points of the final geometry's elements [length unit], shape (n)
        real(wp), allocatable :: x_begin(:), y_begin(:), x_end(:), y_end(:)
        !> Fracture of each element, shape (n); first and last element of each fracture,
        !> shape (fractures)
        integer, allocatable :: fracture_id(:), first_element(:), last_element(:)
    end type restart_state

end module ddc_model_restart
