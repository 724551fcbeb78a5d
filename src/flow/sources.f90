!> The model's fluid sources (&injection) as the network sees them: the cells that hold each
!> source's point, and when it acts (from the path's first time when it gives no start).
module ddc_flow_sources
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, injection_source
    use ddc_mesh_ends, only: elements_at_point
    use ddc_flow_network, only: flow_network
    use ddc_flow_diffusion, only: flow_source
    implicit none
    private

    public :: network_sources

contains

    !> The sources on the network (every point on a conducting element: the input's check).
    pure function network_sources(elements, network, injections, first_time) result(sources)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Their network
        type(flow_network), intent(in) :: network
        !> The model's sources
        type(injection_source), intent(in) :: injections(:)
        !> The first time of the loading history [time unit]
        real(wp), intent(in) :: first_time
        type(flow_source) :: sources(size(injections))
        integer :: k

        ! Whole constructors: gfortran leaves the default values of an array function result
        ! unset (the volume came out uninitialised under valgrind).
        do k = 1, size(injections)
            associate (given => injections(k))
                sources(k) = flow_source(kind=given%kind, value=given%value, &
                                         start=max(given%start, first_time), stop=given%stop, &
                                         cells=network%cell(elements_at_point(elements, &
                                         given%fracture_id, given%x, given%y)), volume=0.0_wp)
            end associate
        end do
    end function network_sources

end module ddc_flow_sources
