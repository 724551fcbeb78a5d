!> The pressure that the model's fluid sources make diffuse along its fractures at every
!> step of a loading history (docs/injection.md): the network of the conducting elements
!> (ddc_flow_network), at rest at the first time, advanced from step to step
!> (ddc_flow_diffusion). The flow does not depend on the slip, so the whole pressure history
!> is known before the first contact solve.
module ddc_flow_injection
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_types, only: model_type
    use ddc_flow_network, only: flow_network, build_network
    use ddc_flow_diffusion, only: flow_state, start_flow, advance_flow, element_pressure
    use ddc_flow_sources, only: network_sources
    implicit none
    private

    public :: pressure_history

contains

    !> The pressure change of every element and the injected volume at each time.
    subroutine pressure_history(model, times, pressure, volume, error)
        !> A model with fluid sources
        type(model_type), intent(in) :: model
        !> The times of the steps, increasing [time unit], shape (k)
        real(wp), intent(in) :: times(:)
        !> Pressure change of each element at each step [stress unit], shape (n, k)
        real(wp), intent(out) :: pressure(:, :)
        !> Volume the sources injected by each step [length^2], shape (k)
        real(wp), intent(out) :: volume(:)
        !> Set when the diffusion's linear solve fails
        type(error_type), allocatable, intent(out) :: error
        type(flow_network) :: network
        type(flow_state) :: state
        integer :: k

        network = build_network(model%elements)
        call start_flow(network, network_sources(model%elements, network, model%injections, &
                                                 times(1)), times(1), state)
        do k = 1, size(times)
            if (k > 1) call advance_flow(network, state, times(k), error)
            if (allocated(error)) return
            pressure(:, k) = element_pressure(network, state)
            volume(k) = sum(state%sources%volume)
        end do
    end subroutine pressure_history

end module ddc_flow_injection
