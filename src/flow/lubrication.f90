!> Fluid that flows through the fractures it opens (docs/theory/fluid-driven-fractures.md):
!> lubrication flow on the network of the conducting elements (ddc_flow_network), one cell
!> per element, in the hydraulic aperture w = w_res + max(opening, 0), with the
!> transmissivity w^3 / (12 eta) of parallel plates.
!>
!> A time step from t_n to t_n+1 is backward Euler on the fluid's mass, each cell's
!> balance
!>
!>     R_i = V_i(t_n+1) - V_i(t_n) + dt sum_j c_ij (p_i - p_j) - Q_i + L_i = 0,
!>
!> V_i = 2 h_i w_i (1 + c p_i) the fluid stored (at the density of pressure change 0; c the
!> compressibility), c_ij the connections' conductances for the apertures at t_n+1, Q_i what
!> the rate sources let in over the step (exactly: their rate times the part of the step
!> they act), L_i the Carter leak-off of an open cell. A pressure source's cells hold its
!> pressure instead (their row: p_i - dp); what flows in there is its volume. The opening
!> comes from the contact solve (ddc_history_coupled_flow); this module gives the balance,
!> its Jacobian for a given response of the openings to the pressure, and takes a solved
!> step. Summed over the cells the connections cancel: a solved step conserves the volume
!> to its residual.
module ddc_flow_lubrication
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, injection_source, fluid_options, &
        source_overpressure
    use ddc_flow_network, only: flow_network, build_network, net_outflow
    use ddc_flow_diffusion, only: flow_source
    use ddc_flow_sources, only: network_sources
    implicit none
    private

    public :: lubrication_flow, start_lubrication, cell_balance, balance_jacobian, &
        take_lubrication_step, held_pressure, along_flux, element_values, carry_lubrication

    !> The flow and its state at one time.
    type :: lubrication_flow
        !> The conducting cells and their connections (conductances those of `aperture`)
        type(flow_network) :: network
        !> The fluid
        type(fluid_options) :: fluid
        !> Residual aperture of each cell [length unit], shape (cells)
        real(wp), allocatable :: residual_aperture(:)
        !> The sources, with the volume each let in so far
        type(flow_source), allocatable :: sources(:)
        !> The time [time unit]
        real(wp) :: time = 0.0_wp
        !> Pressure change [stress unit], hydraulic aperture [length unit] and fluid stored
        !> [length^2] of each cell, shape (cells)
        real(wp), allocatable :: p(:), aperture(:), stored(:)
        !> When each cell first opened (huge: not yet): Carter's t0 [time unit], shape (cells)
        real(wp), allocatable :: wet_since(:)
        !> The fluid stored at the start and the volume leaked off since [length^2]
        real(wp) :: stored_initial = 0.0_wp, leaked = 0.0_wp
    end type lubrication_flow

contains

    !> The flow at rest at `time`: pressure change 0, the apertures of the openings given
    !> (the equilibrium without it).
    subroutine start_lubrication(elements, fluid, injections, time, opening, flow)
        !> Elements with geometry computed and residual_aperture set
        type(element_set), intent(in) :: elements
        !> The fluid (&fluid)
        type(fluid_options), intent(in) :: fluid
        !> The sources (&injection)
        type(injection_source), intent(in) :: injections(:)
        !> The first time [time unit]
        real(wp), intent(in) :: time
        !> Opening of every element at rest [length unit], shape (n)
        real(wp), intent(in) :: opening(:)
        !> The flow
        type(lubrication_flow), intent(out) :: flow
        type(element_set) :: conducting

        ! The network's topology: the conducting elements, any positive diffusivity.
        conducting = elements
        conducting%transmissivity = merge(1.0_wp, 0.0_wp, elements%residual_aperture > 0.0_wp)
        conducting%diffusivity = conducting%transmissivity
        flow%network = build_network(conducting)
        flow%fluid = fluid
        flow%residual_aperture = elements%residual_aperture(flow%network%element)
        flow%sources = network_sources(elements, flow%network, injections, time)
        flow%time = time
        allocate (flow%p(flow%network%cells), source=0.0_wp)
        allocate (flow%wet_since(flow%network%cells), source=huge(1.0_wp))
        flow%aperture = hydraulic_aperture(flow, opening(flow%network%element))
        call set_conductance(flow, flow%network, flow%aperture)
        flow%stored = stored_volume(flow, flow%p, flow%aperture)
        flow%stored_initial = sum(flow%stored)
    end subroutine start_lubrication

    !> The flow of a geometry grown from the flow's (fluid-driven growth): each element that
    !> was there keeps its cell's pressure, aperture, storage and leak-off clock; a new
    !> element is rock just broken, its residual aperture holding the rock's fluid at rest
    !> (pressure change 0; counted in the fluid stored at the start). The sources keep their
    !> times and volumes.
    subroutine carry_lubrication(flow, elements, injections, origin, grown)
        !> The flow on the geometry before
        type(lubrication_flow), intent(in) :: flow
        !> The grown elements, geometry computed
        type(element_set), intent(in) :: elements
        !> The sources (&injection)
        type(injection_source), intent(in) :: injections(:)
        !> The element before of each grown element (0: new), shape (n)
        integer, intent(in) :: origin(:)
        !> The flow on the grown geometry, at the flow's time
        type(lubrication_flow), intent(out) :: grown
        integer :: i, k, before

        call start_lubrication(elements, flow%fluid, injections, flow%time, &
                               spread(0.0_wp, 1, elements%n), grown)
        grown%stored_initial = flow%stored_initial
        grown%leaked = flow%leaked
        do i = 1, grown%network%cells
            before = origin(grown%network%element(i))
            if (before > 0) then
                k = flow%network%cell(before)
                grown%p(i) = flow%p(k)
                grown%aperture(i) = flow%aperture(k)
                grown%stored(i) = flow%stored(k)
                grown%wet_since(i) = flow%wet_since(k)
            else
                grown%stored_initial = grown%stored_initial + grown%stored(i)
            end if
        end do
        call set_conductance(grown, grown%network, grown%aperture)
        do k = 1, size(flow%sources)
            grown%sources(k)%start = flow%sources(k)%start
            grown%sources(k)%volume = flow%sources(k)%volume
        end do
    end subroutine carry_lubrication

    !> w_res + max(opening, 0) of each cell.
    pure function hydraulic_aperture(flow, opening) result(aperture)
        type(lubrication_flow), intent(in) :: flow
        !> Opening of each cell [length unit], shape (cells)
        real(wp), intent(in) :: opening(:)
        real(wp) :: aperture(size(opening))

        aperture = flow%residual_aperture + max(opening, 0.0_wp)
    end function hydraulic_aperture

    !> The conductance of every connection for the cells' apertures: parallel plates of the
    !> mean aperture of the two cells, w^3 / (12 eta), over the distance between their
    !> midpoints (to the end on the interior of the second cell: its distance from that
    !> cell's midpoint). The mean, not the harmonic mean of the cells' transmissivities:
    !> a cell that just opened beside an open one takes the fluid in through the aperture
    !> between them, not through its own residual one.
    pure subroutine set_conductance(flow, network, aperture)
        type(lubrication_flow), intent(in) :: flow
        !> The network whose conductance is set
        type(flow_network), intent(inout) :: network
        !> Hydraulic aperture of each cell [length unit], shape (cells)
        real(wp), intent(in) :: aperture(:)
        real(wp) :: distance
        integer :: c

        do c = 1, size(network%conductance)
            associate (a => network%pair(1, c), b => network%pair(2, c))
                distance = network%half_length(a) + network%half_length(b)
                if (network%node(c) == 0) distance = network%half_length(a) + network%gap(c)
                network%conductance(c) = (0.5_wp * (aperture(a) + aperture(b)))**3 / &
                    (12.0_wp * flow%fluid%viscosity * distance)
            end associate
        end do
    end subroutine set_conductance

    !> 2 h w (1 + c p) of each cell.
    pure function stored_volume(flow, p, aperture) result(v)
        type(lubrication_flow), intent(in) :: flow
        real(wp), intent(in) :: p(:), aperture(:)
        real(wp) :: v(size(p))

        v = 2.0_wp * flow%network%half_length * aperture * &
            (1.0_wp + flow%fluid%compressibility * p)
    end function stored_volume

    !> The cells held by a pressure source that acts at the end of the step to t_new, and
    !> the pressure each holds (0 elsewhere).
    pure subroutine held_pressure(flow, t_new, held, value)
        type(lubrication_flow), intent(in) :: flow
        real(wp), intent(in) :: t_new
        logical, intent(out) :: held(:)
        real(wp), intent(out) :: value(:)
        integer :: k

        held = .false.
        value = 0.0_wp
        do k = 1, size(flow%sources)
            associate (s => flow%sources(k))
                if (s%kind == source_overpressure .and. s%start <= t_new .and. &
                    t_new <= s%stop) then
                    held(s%cells) = .true.
                    value(s%cells) = s%value
                end if
            end associate
        end do
    end subroutine held_pressure

    !> Each cell's balance over the step to t_new for pressure p and openings `opening`
    !> (the rows of held cells: p - their pressure), the leak-off of each cell over the
    !> step, and the volume the sources let in over it (a pressure source's: what its
    !> cells take).
    pure subroutine cell_balance(flow, t_new, p, opening, residual, leak, injected, rounding)
        !> The flow at t_n
        type(lubrication_flow), intent(in) :: flow
        !> The end of the step [time unit]
        real(wp), intent(in) :: t_new
        !> Pressure change [stress unit] and opening [length unit] of each cell at t_new,
        !> shape (cells)
        real(wp), intent(in) :: p(:), opening(:)
        !> The balance of each cell [length^2] (held cells: [stress unit]), shape (cells)
        real(wp), intent(out) :: residual(:)
        !> Volume leaked off from each cell over the step [length^2], shape (cells)
        real(wp), intent(out) :: leak(:)
        !> Volume the sources let in over the step [length^2]
        real(wp), intent(out) :: injected
        !> The rounding error of the free cells' balances summed: the size of their terms
        !> times the machine epsilon [length^2]
        real(wp), intent(out) :: rounding
        type(flow_network) :: network
        real(wp) :: aperture(size(p)), value(size(p)), rates(size(p)), stored(size(p))
        real(wp) :: flux_size(size(p))
        logical :: held(size(p))
        integer :: c

        aperture = hydraulic_aperture(flow, opening)
        network = flow%network
        call set_conductance(flow, network, aperture)
        leak = leaked_in_step(flow, t_new, opening)
        rates = rate_volume(flow, t_new)
        stored = stored_volume(flow, p, aperture)
        residual = stored - flow%stored + (t_new - flow%time) * net_outflow(network, p) - &
            rates + leak
        call held_pressure(flow, t_new, held, value)
        injected = sum(rates) + sum(residual, mask=held)
        where (held) residual = p - value
        flux_size = 0.0_wp
        do c = 1, size(network%conductance)
            associate (a => network%pair(1, c), b => network%pair(2, c))
                flux_size([a, b]) = flux_size([a, b]) + network%conductance(c) * &
                    (abs(p(a)) + abs(p(b)))
            end associate
        end do
        rounding = epsilon(1.0_wp) * sum(stored + flow%stored + (t_new - flow%time) * &
                                         flux_size + abs(rates) + leak, mask=.not. held)
    end subroutine cell_balance

    !> Carter's leak-off over the step, 2 C_L / sqrt(t - t0) per unit length on each cell
    !> open at its end (t0: when it first opened, the step's start for one that opens now).
    pure function leaked_in_step(flow, t_new, opening) result(leak)
        type(lubrication_flow), intent(in) :: flow
        real(wp), intent(in) :: t_new, opening(:)
        real(wp) :: leak(size(opening)), t0

        integer :: i

        leak = 0.0_wp
        if (flow%fluid%leak_off_coefficient == 0.0_wp) return
        do i = 1, size(opening)
            if (.not. opening(i) > 0.0_wp) cycle
            t0 = min(flow%wet_since(i), flow%time)
            ! 2 C_L / sqrt(t - t0) over the cell's length 2 h, integrated over the step.
            leak(i) = 8.0_wp * flow%fluid%leak_off_coefficient * flow%network%half_length(i) &
                * (sqrt(t_new - t0) - sqrt(flow%time - t0))
        end do
    end function leaked_in_step

    !> What the rate sources let into each cell over the step to t_new [length^2]: the
    !> rate times the part of the step it acts, split equally between the cells at its point.
    pure function rate_volume(flow, t_new) result(q)
        type(lubrication_flow), intent(in) :: flow
        real(wp), intent(in) :: t_new
        real(wp) :: q(flow%network%cells), acting
        integer :: k

        q = 0.0_wp
        do k = 1, size(flow%sources)
            associate (s => flow%sources(k))
                if (s%kind == source_overpressure) cycle
                acting = max(min(t_new, s%stop) - max(flow%time, s%start), 0.0_wp)
                q(s%cells) = q(s%cells) + s%value * acting / real(size(s%cells), wp)
            end associate
        end do
    end function rate_volume

    !> The Jacobian of cell_balance in the pressure, for the response of the open cells'
    !> openings to the pressure (d opening_i / d p_j; zero rows for closed cells): storage,
    !> flow through the connections, and the change of both with the aperture (the
    !> conductances' by differences).
    pure subroutine balance_jacobian(flow, t_new, p, opening, open, response, jacobian)
        !> The flow at t_n
        type(lubrication_flow), intent(in) :: flow
        !> The end of the step [time unit]
        real(wp), intent(in) :: t_new
        !> Pressure change and opening of each cell, shape (cells)
        real(wp), intent(in) :: p(:), opening(:)
        !> Whether each cell is taken as open (its aperture moves with the opening)
        logical, intent(in) :: open(:)
        !> d opening_i / d p_j [length unit / stress unit], shape (cells, cells)
        real(wp), intent(in) :: response(:, :)
        !> d R_i / d p_j, shape (cells, cells)
        real(wp), intent(out) :: jacobian(:, :)
        type(flow_network) :: network, shifted
        real(wp) :: aperture(size(p)), dt, base(size(p)), bumped(size(p)), value(size(p))
        real(wp) :: d_balance_d_aperture(size(p), size(p)), delta
        logical :: held(size(p))
        integer :: c, k

        dt = t_new - flow%time
        aperture = hydraulic_aperture(flow, opening)
        network = flow%network
        call set_conductance(flow, network, aperture)
        jacobian = 0.0_wp
        do c = 1, size(network%conductance)
            associate (a => network%pair(1, c), b => network%pair(2, c), &
                       g => dt * network%conductance(c))
                jacobian(a, a) = jacobian(a, a) + g
                jacobian(b, b) = jacobian(b, b) + g
                jacobian(a, b) = jacobian(a, b) - g
                jacobian(b, a) = jacobian(b, a) - g
            end associate
        end do
        do k = 1, size(p)
            jacobian(k, k) = jacobian(k, k) + 2.0_wp * network%half_length(k) * aperture(k) * &
                flow%fluid%compressibility
        end do
        ! d R / d w of the open cells: storage on the diagonal, the fluxes by differences.
        d_balance_d_aperture = 0.0_wp
        base = dt * net_outflow(network, p)
        do k = 1, size(p)
            if (.not. open(k)) cycle
            d_balance_d_aperture(k, k) = 2.0_wp * network%half_length(k) * &
                (1.0_wp + flow%fluid%compressibility * p(k))
            if (dt == 0.0_wp) cycle
            delta = 1.0e-7_wp * aperture(k)
            shifted = network
            aperture(k) = aperture(k) + delta
            call set_conductance(flow, shifted, aperture)
            aperture(k) = aperture(k) - delta
            bumped = dt * net_outflow(shifted, p)
            d_balance_d_aperture(:, k) = d_balance_d_aperture(:, k) + (bumped - base) / delta
        end do
        jacobian = jacobian + matmul(d_balance_d_aperture, response)
        call held_pressure(flow, t_new, held, value)
        do k = 1, size(p)
            if (.not. held(k)) cycle
            jacobian(k, :) = 0.0_wp
            jacobian(k, k) = 1.0_wp
        end do
    end subroutine balance_jacobian

    !> Take the solved step to t_new: pressure, apertures, storage, leak-off, and the volume
    !> each source let in (a rate source's exactly; a pressure source's what its cells
    !> took: their storage change, their net outflow and their leak-off).
    pure subroutine take_lubrication_step(flow, t_new, p, opening)
        !> The flow; at t_new on return
        type(lubrication_flow), intent(inout) :: flow
        !> The end of the step [time unit]
        real(wp), intent(in) :: t_new
        !> The step's solution: pressure change and opening of each cell, shape (cells)
        real(wp), intent(in) :: p(:), opening(:)
        real(wp) :: leak(size(p)), aperture(size(p)), stored(size(p)), taken(size(p))
        real(wp) :: acting, value(size(p))
        logical :: held(size(p))
        integer :: k

        aperture = hydraulic_aperture(flow, opening)
        leak = leaked_in_step(flow, t_new, opening)
        stored = stored_volume(flow, p, aperture)
        call set_conductance(flow, flow%network, aperture)
        call held_pressure(flow, t_new, held, value)
        taken = stored - flow%stored + (t_new - flow%time) * net_outflow(flow%network, p) + &
            leak
        do k = 1, size(flow%sources)
            associate (s => flow%sources(k))
                if (s%kind == source_overpressure) then
                    if (all(held(s%cells))) s%volume = s%volume + sum(taken(s%cells))
                else
                    acting = max(min(t_new, s%stop) - max(flow%time, s%start), 0.0_wp)
                    s%volume = s%volume + s%value * acting
                end if
            end associate
        end do
        where (opening > 0.0_wp .and. flow%wet_since == huge(1.0_wp)) flow%wet_since = flow%time
        flow%leaked = flow%leaked + sum(leak)
        flow%p = p
        flow%aperture = aperture
        flow%stored = stored
        flow%time = t_new
    end subroutine take_lubrication_step

    !> The flux along each cell at its midpoint, -T dp/ds in the direction of its element
    !> (first vertex to last): the mean of what leaves through its end and what enters
    !> through its beginning [length^2 / time unit].
    pure function along_flux(flow) result(q)
        type(lubrication_flow), intent(in) :: flow
        real(wp) :: q(flow%network%cells), f
        integer :: c, j

        q = 0.0_wp
        do c = 1, size(flow%network%conductance)
            associate (pair => flow%network%pair(:, c), side => flow%network%end_side(:, c))
                f = flow%network%conductance(c) * (flow%p(pair(1)) - flow%p(pair(2)))
                do j = 1, 2
                    ! Out through its end (side 2) counts along, through its beginning against.
                    if (side(j) == 2) q(pair(j)) = q(pair(j)) + 0.5_wp * f
                    if (side(j) == 1) q(pair(j)) = q(pair(j)) - 0.5_wp * f
                    f = -f
                end do
            end associate
        end do
    end function along_flux

    !> A value of every cell on the elements (fill elsewhere), shape (n).
    pure function element_values(flow, cell_values, n, fill) result(values)
        type(lubrication_flow), intent(in) :: flow
        real(wp), intent(in) :: cell_values(:)
        integer, intent(in) :: n
        real(wp), intent(in) :: fill
        real(wp) :: values(n)

        values = fill
        values(flow%network%element) = cell_values
    end function element_values

end module ddc_flow_lubrication
