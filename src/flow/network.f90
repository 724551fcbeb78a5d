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

    public :: flow_network, build_network, set_conductance, net_outflow

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
        !> Half-length of each cell's element [length unit], shape (cells)
        real(wp), allocatable :: half_length(:)
        !> What each connection is, for set_conductance: the junction node it goes through
        !> (0: the end of its first cell on the interior of its second), shape
        !> (connections); the distance of that end from the second cell's midpoint [length
        !> unit], shape (connections)
        integer, allocatable :: node(:)
        real(wp), allocatable :: gap(:)
        !> The end (1 begin, 2 end) of each of the two cells through which a connection goes
        !> (0: the second cell's interior), shape (2, connections)
        integer, allocatable :: end_side(:, :)
        !> The cells at each junction node: node_cell(node_first(g):node_first(g + 1) - 1),
        !> shape (nodes + 1) and (ends)
        integer, allocatable :: node_first(:), node_cell(:)
    end type flow_network

contains

    !> The network of the conducting elements.
    function build_network(elements) result(network)
        !> Elements with geometry computed and diffusivity, transmissivity set
        type(element_set), intent(in) :: elements
        type(flow_network) :: network
        integer :: group(2, elements%n), ends_in(2 * elements%n), first(2 * elements%n + 1)
        integer :: member(2 * elements%n), filled(2 * elements%n), size_of(2 * elements%n)
        integer :: member_side(2 * elements%n)
        logical :: conducts(elements%n)
        real(wp) :: distance
        integer :: i, side, g, groups, host, a, b, m, most
        integer, allocatable :: pair(:, :), node(:), end_side(:, :)
        real(wp), allocatable :: gap(:)

        conducts = elements%transmissivity > 0.0_wp .and. elements%diffusivity > 0.0_wp
        network%cells = count(conducts)
        network%element = pack([(i, i = 1, elements%n)], conducts)
        allocate (network%cell(elements%n), source=0)
        network%cell(network%element) = [(i, i = 1, network%cells)]
        network%half_length = elements%half_length(network%element)
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
        do i = 1, elements%n
            if (.not. conducts(i)) cycle
            do side = 1, 2
                g = group(side, i)
                ends_in(g) = ends_in(g) + 1
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
                member_side(first(g) + filled(g)) = side
                filled(g) = filled(g) + 1
            end do
        end do

        ! The cells at each node, every pair of them, and the ends on another element's
        ! interior.
        network%node_first = first(1:groups + 1)
        network%node_cell = network%cell(member(1:first(groups + 1) - 1))
        most = sum(ends_in(1:groups) * (ends_in(1:groups) - 1) / 2) + 2 * network%cells
        allocate (pair(2, most), node(most), gap(most), end_side(2, most))
        m = 0
        do g = 1, groups
            do a = first(g), first(g + 1) - 1
                do b = a + 1, first(g + 1) - 1
                    call connect(member(a), member(b), g, 0.0_wp, &
                                 [member_side(a), member_side(b)])
                end do
            end do
        end do
        do i = 1, elements%n
            if (.not. conducts(i)) cycle
            do side = 1, 2
                if (size_of(group(side, i)) > 1) cycle
                call end_on_interior(elements, i, side, host, distance)
                if (host == 0) cycle
                if (conducts(host)) call connect(i, host, 0, distance, [side, 0])
            end do
        end do
        network%pair = pair(:, 1:m)
        network%node = node(1:m)
        network%gap = gap(1:m)
        network%end_side = end_side(:, 1:m)
        call set_conductance(network, elements%transmissivity(network%element))

    contains

        subroutine connect(p, q, through, distance_from_host, sides)
            integer, intent(in) :: p, q, through, sides(2)
            real(wp), intent(in) :: distance_from_host

            m = m + 1
            pair(:, m) = [network%cell(p), network%cell(q)]
            node(m) = through
            gap(m) = distance_from_host
            end_side(:, m) = sides
        end subroutine connect
    end function build_network

    !> The conductance of every connection for the cells' transmissivities: at a junction
    !> node w_a w_b / sum_k w_k (w = T / h over the node's cells), an end on an interior
    !> 1 / (1 / w_a + d / T_b).
    pure subroutine set_conductance(network, transmissivity)
        !> The network; its conductance is set
        type(flow_network), intent(inout) :: network
        !> Transmissivity of each cell [length^3 / (stress time)], shape (cells)
        real(wp), intent(in) :: transmissivity(:)
        real(wp) :: w(network%cells), node_sum(size(network%node_first) - 1)
        integer :: g, c

        w = transmissivity / network%half_length
        do g = 1, size(node_sum)
            node_sum(g) = sum(w(network%node_cell(network%node_first(g): &
                                                  network%node_first(g + 1) - 1)))
        end do
        if (.not. allocated(network%conductance)) then
            allocate (network%conductance(size(network%node)))
        end if
        do c = 1, size(network%node)
            associate (a => network%pair(1, c), b => network%pair(2, c))
                if (network%node(c) > 0) then
                    network%conductance(c) = w(a) * w(b) / node_sum(network%node(c))
                else
                    network%conductance(c) = 1.0_wp / (1.0_wp / w(a) + network%gap(c) / &
                                                       transmissivity(b))
                end if
            end associate
        end do
    end subroutine set_conductance

    !> sum_j c_ij (p_i - p_j), A p: the net flux out of each cell [length^2 / time unit].
    pure function net_outflow(network, p) result(out)
        type(flow_network), intent(in) :: network
        real(wp), intent(in) :: p(:)
        real(wp) :: out(size(p)), f
        integer :: c

        out = 0.0_wp
        do c = 1, size(network%conductance)
            associate (a => network%pair(1, c), b => network%pair(2, c))
                f = network%conductance(c) * (p(a) - p(b))
                out(a) = out(a) + f
                out(b) = out(b) - f
            end associate
        end do
    end function net_outflow

end module ddc_flow_network
