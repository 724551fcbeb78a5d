!> The fracture network as a flow domain (docs/theory/injection.md#the-network): one cell per
!> element that conducts (positive diffusivity and transmissivity), the fluid stored in it
!> (storativity S = T / alpha times its length) and the connections through which it flows.
!>
!> Cells meet where their elements' ends meet: consecutive elements of a fracture, and every
!> junction (the ends of several fractures at one point). A junction node stores nothing, so
!> the fluxes into it sum to zero: with w_i = T_i / h_i (h_i the distance from the midpoint
!> of cell i to the junction, its half-length), the node's pressure is the w-weighted mean and
!> each pair of cells at it exchanges w_i w_j / sum_k w_k (p_j - p_i), the harmonic mean for
!> two cells. An end on the interior of another element (a fracture that ends on a fault)
!> connects the two cells through T_ij = 1 / (h_i / T_i + d / T_j), d the distance of the end
!> from the host's midpoint. Fracture ends and elements that do not conduct are no-flow.
module ddc_flow_network
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set
    use ddc_mesh_ends, only: end_groups, end_on_interior
    implicit none
    private

    public :: flow_network, build_network

    !> The cells, their storage and their connections.
    type :: flow_network
        !> Number of cells
        integer :: cells = 0
        !> The element of each cell, shape (cells)
        integer, allocatable :: element(:)
        !> The cell of each element, 0 where it does not conduct, shape (n)
        integer, allocatable :: cell(:)
        !> Fluid stored per unit pressure: storativity times length [length^2 / stress],
        !> shape (cells)
        real(wp), allocatable :: storage(:)
        !> The two cells of each connection, shape (2, connections)
        integer, allocatable :: pair(:, :)
        !> Flux per unit pressure difference of each connection [length^2 / (stress time)],
        !> shape (connections)
        real(wp), allocatable :: conductance(:)
    end type flow_network

contains

    !> The network of the conducting elements.
    function build_network(elements) result(network)
        !> Elements with geometry computed and diffusivity, transmissivity set
        type(element_set), intent(in) :: elements
        type(flow_network) :: network
        integer :: group(2, elements%n), ends_in(2 * elements%n), first(2 * elements%n + 1)
        integer :: member(2 * elements%n), filled(2 * elements%n), size_of(2 * elements%n)
        logical :: conducts(elements%n)
        real(wp) :: weight_sum(2 * elements%n), distance
        integer :: i, side, g, groups, host, a, b, m, most
        integer, allocatable :: pair(:, :)
        real(wp), allocatable :: conductance(:)

        conducts = elements%transmissivity > 0.0_wp .and. elements%diffusivity > 0.0_wp
        network%cells = count(conducts)
        network%element = pack([(i, i = 1, elements%n)], conducts)
        allocate (network%cell(elements%n), source=0)
        network%cell(network%element) = [(i, i = 1, network%cells)]
        associate (e => network%element)
            network%storage = elements%transmissivity(e) / elements%diffusivity(e) * &
                2.0_wp * elements%half_length(e)
        end associate

        ! The conducting ends of each group, listed group by group (counting sort).
        call end_groups(elements, group, groups)
        size_of = 0
        do i = 1, elements%n
            do side = 1, 2
                size_of(group(side, i)) = size_of(group(side, i)) + 1
            end do
        end do
        ends_in = 0
        weight_sum = 0.0_wp
        do i = 1, elements%n
            if (.not. conducts(i)) cycle
            do side = 1, 2
                g = group(side, i)
                ends_in(g) = ends_in(g) + 1
                weight_sum(g) = weight_sum(g) + weight(i)
            end do
        end do
        first(1) = 1
        do g = 1, groups
            first(g + 1) = first(g) + ends_in(g)
        end do
        filled = 0
        do i = 1, elements%n
            if (.not. conducts(i)) cycle
            do side = 1, 2
                g = group(side, i)
                member(first(g) + filled(g)) = i
                filled(g) = filled(g) + 1
            end do
        end do

        ! Every pair of cells at a junction node, and the ends on another element's interior.
        most = sum(ends_in(1:groups) * (ends_in(1:groups) - 1) / 2) + 2 * network%cells
        allocate (pair(2, most), conductance(most))
        m = 0
        do g = 1, groups
            do a = first(g), first(g + 1) - 1
                do b = a + 1, first(g + 1) - 1
                    call connect(member(a), member(b), weight(member(a)) * &
                                 weight(member(b)) / weight_sum(g))
                end do
            end do
        end do
        do i = 1, elements%n
            if (.not. conducts(i)) cycle
            do side = 1, 2
                if (size_of(group(side, i)) > 1) cycle
                call end_on_interior(elements, i, side, host, distance)
                if (host == 0) cycle
                if (conducts(host)) call connect(i, host, 1.0_wp / (1.0_wp / weight(i) + &
                                                 distance / elements%transmissivity(host)))
            end do
        end do
        network%pair = pair(:, 1:m)
        network%conductance = conductance(1:m)

    contains

        !> T_k / h_k of element k.
        pure real(wp) function weight(k)
            integer, intent(in) :: k

            weight = elements%transmissivity(k) / elements%half_length(k)
        end function weight

        subroutine connect(p, q, value)
            integer, intent(in) :: p, q
            real(wp), intent(in) :: value

            m = m + 1
            pair(:, m) = [network%cell(p), network%cell(q)]
            conductance(m) = value
        end subroutine connect
    end function build_network

end module ddc_flow_network
