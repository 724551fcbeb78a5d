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

    public :: pressure_history, flow_tracker, follow_flow, injected

    !> Pressure that diffuses on a geometry that may grow between the times it is asked for
    !> (a growth run along a loading history).
    type :: flow_tracker
        private
        !> The network of the geometry the state is on, and its number of elements (-1:
        !> none yet)
        type(flow_network) :: network
        type(flow_state) :: state
        integer :: elements = -1
    end type flow_tracker

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

    !> The pressure of the model's sources at `time` on the model's current geometry, into
    !> model%elements%flow_pressure: on the first call the network at rest at that time;
    !> then advanced from the time before. A grown geometry gets its network anew, each
    !> cell at its element's flow_pressure (an element carried over keeps its pressure, a new
    !> one took its tip element's), the sources' volumes and their time since the last event
    !> kept.
    subroutine follow_flow(tracker, model, time, error)
        !> The tracker
        type(flow_tracker), intent(inout) :: tracker
        !> A model with fluid sources; its elements' flow_pressure is set
        type(model_type), intent(inout) :: model
        !> The time [time unit], not before the last call's
        real(wp), intent(in) :: time
        !> Set when the diffusion's linear solve fails
        type(error_type), allocatable, intent(out) :: error
        type(flow_state) :: before
        integer :: k

        if (tracker%elements < 0) then
            tracker%network = build_network(model%elements)
            call start_flow(tracker%network, network_sources(model%elements, &
                            tracker%network, model%injections, time), time, tracker%state)
        else if (tracker%elements /= model%elements%n) then
            before = tracker%state
            tracker%network = build_network(model%elements)
            tracker%state%p = model%elements%flow_pressure(tracker%network%element)
            tracker%state%sources = network_sources(model%elements, tracker%network, &
                                                    model%injections, before%time)
            do k = 1, size(before%sources)
                tracker%state%sources(k)%start = before%sources(k)%start
                tracker%state%sources(k)%volume = before%sources(k)%volume
            end do
        end if
        tracker%elements = model%elements%n
        if (time > tracker%state%time) call advance_flow(tracker%network, tracker%state, &
                                                         time, error)
        if (allocated(error)) return
        model%elements%flow_pressure = element_pressure(tracker%network, tracker%state)
    end subroutine follow_flow

    !> The volume the sources let in so far [length^2].
    pure real(wp) function injected(tracker)
        !> The tracker
        type(flow_tracker), intent(in) :: tracker

        injected = sum(tracker%state%sources%volume)
    end function injected

end module ddc_flow_injection
