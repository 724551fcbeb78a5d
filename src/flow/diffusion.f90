!> Pressure that diffuses along the fracture network from its sources
!> (docs/theory/injection.md#integration-in-time): the storage of each cell times
!> the rate of change of its pressure equals what flows in through its connections plus its
!> sources, M dp/dt = -A p + Q, A the network's symmetric Laplacian (ddc_flow_network).
!>
!> A rate source adds its volume rate to the cells holding its point (split equally where the
!> point is an end shared by two); a pressure source holds those cells at its overpressure,
!> the flux that this takes entering as its volume; a stopped source is shut in (its cells
!> free again, with no flux in). Between two load times the pressure is advanced by
!> Crank-Nicolson steps (second order, and it conserves the stored volume exactly: the
!> injected volume is the stored one to the solver's tolerance), with two backward Euler
!> steps after every event (a source starting or stopping, which makes the pressure jump:
!> Rannacher's start-up damps the oscillation Crank-Nicolson keeps of a jump) and steps no
!> longer than step_fraction of the time since the event (the pressure is the smoother the
!> longer ago it was). Each step solves the symmetric positive definite system of the free
!> cells by the conjugate gradient method with a Jacobi preconditioner.
module ddc_flow_diffusion
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure
    use ddc_text, only: itoa, rtoa
    use ddc_model_types, only: source_overpressure
    use ddc_flow_network, only: flow_network, net_outflow
    implicit none
    private

    public :: flow_source, flow_state, start_flow, advance_flow, element_pressure, &
        stored_volume

    !> Longest step after an event, as a fraction of the time since it
    real(wp), parameter :: step_fraction = 0.05_wp
    !> First step after an event, as a fraction of the time to the next load time
    real(wp), parameter :: first_step_fraction = 1.0e-6_wp
    !> Relative residual at which the conjugate gradient method stops
    real(wp), parameter :: cg_tolerance = 1.0e-13_wp

    !> A source as the network sees it.
    type :: flow_source
        !> source_overpressure or source_rate (ddc_model_types)
        integer :: kind = 0
        !> Overpressure [stress unit] or rate [length^2 / time unit]
        real(wp) :: value = 0.0_wp
        !> When it acts [time unit]
        real(wp) :: start = 0.0_wp, stop = huge(1.0_wp)
        !> The cells holding its point, shape (1 or 2)
        integer, allocatable :: cells(:)
        !> Volume that entered through it so far [length^2]
        real(wp) :: volume = 0.0_wp
    end type flow_source

    !> The pressure of the network at one time.
    type :: flow_state
        !> The time [time unit]
        real(wp) :: time = 0.0_wp
        !> Pressure change of each cell [stress unit], shape (cells)
        real(wp), allocatable :: p(:)
        !> The sources, with the volume each let in
        type(flow_source), allocatable :: sources(:)
        !> Time of the last event (a source starting or stopping) [time unit], and the
        !> backward Euler steps still to take after it
        real(wp) :: event = 0.0_wp
        integer :: damping_steps = 0
    end type flow_state

contains

    !> The network at rest (no pressure change) at a time, with its sources; those that
    !> start then act from that time on.
    subroutine start_flow(network, sources, time, state)
        !> The network
        type(flow_network), intent(in) :: network
        !> Its sources
        type(flow_source), intent(in) :: sources(:)
        !> The starting time [time unit]
        real(wp), intent(in) :: time
        !> The state at that time
        type(flow_state), intent(out) :: state

        allocate (state%p(network%cells), source=0.0_wp)
        state%sources = sources
        state%time = time
        state%event = time
        call apply_events(network, state)
    end subroutine start_flow

    !> Advance the pressure to a later time.
    subroutine advance_flow(network, state, time, error)
        !> The network
        type(flow_network), intent(in) :: network
        !> The state; at `time` on return
        type(flow_state), intent(inout) :: state
        !> The time to reach [time unit]
        real(wp), intent(in) :: time
        !> Set when a step's linear system is not solved
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: next_event, dt, t_new
        integer :: k, steps

        do while (state%time < time)
            next_event = time
            do k = 1, size(state%sources)
                associate (s => state%sources(k))
                    if (s%start > state%time) next_event = min(next_event, s%start)
                    if (s%stop > state%time) next_event = min(next_event, s%stop)
                end associate
            end do
            dt = max(step_fraction * (state%time - state%event), &
                     first_step_fraction * (next_event - state%event))
            ! The remaining time in equal steps, none longer than dt; the last lands on it.
            steps = ceiling((next_event - state%time) / dt)
            t_new = next_event
            if (steps > 1) t_new = state%time + (next_event - state%time) / real(steps, wp)
            call take_step(network, state, t_new, error)
            if (allocated(error)) return
            if (state%time == next_event) call apply_events(network, state)
        end do
    end subroutine advance_flow

    !> Start and stop the sources whose time it is; a pressure source that starts puts the
    !> fluid that raises its cells to its pressure into them at once.
    subroutine apply_events(network, state)
        type(flow_network), intent(in) :: network
        type(flow_state), intent(inout) :: state
        integer :: k

        do k = 1, size(state%sources)
            associate (s => state%sources(k))
                if (s%start == state%time .or. s%stop == state%time) then
                    state%event = state%time
                    state%damping_steps = 2
                end if
                if (s%kind == source_overpressure .and. s%start == state%time .and. &
                    s%stop > state%time) then
                    s%volume = s%volume + sum(network%storage(s%cells) * &
                                              (s%value - state%p(s%cells)))
                    state%p(s%cells) = s%value
                end if
            end associate
        end do
    end subroutine apply_events

    !> One step to t_new: backward Euler while damping after an event, else Crank-Nicolson;
    !> the volume each source let in is added up.
    subroutine take_step(network, state, t_new, error)
        type(flow_network), intent(in) :: network
        type(flow_state), intent(inout) :: state
        real(wp), intent(in) :: t_new
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: theta, dt
        real(wp), dimension(network%cells) :: rhs, ap, rate_old, rate_new, p_new, flux
        logical :: held(network%cells)
        integer :: k

        theta = 0.5_wp
        if (state%damping_steps > 0) theta = 1.0_wp
        dt = t_new - state%time
        call rates(state, state%time, .false., rate_old)
        call rates(state, t_new, .true., rate_new)
        held = .false.
        do k = 1, size(state%sources)
            associate (s => state%sources(k))
                if (s%kind == source_overpressure .and. acts(s, t_new, .true.)) then
                    held(s%cells) = .true.
                end if
            end associate
        end do
        ap = net_outflow(network, state%p)
        rhs = network%storage / dt * state%p - (1.0_wp - theta) * ap + &
            (1.0_wp - theta) * rate_old + theta * rate_new
        p_new = state%p
        call solve_free(network, held, theta, dt, rhs, p_new, error)
        if (allocated(error)) then
            error%message = 'pressure diffusion from time '//rtoa(state%time)//' to '// &
                rtoa(t_new)//': '//error%message
            return
        end if
        ! Volumes: a rate source's exactly, a pressure source's the flux that held its cells.
        flux = network%storage / dt * (p_new - state%p) + &
            theta * net_outflow(network, p_new) + &
            (1.0_wp - theta) * ap
        do k = 1, size(state%sources)
            associate (s => state%sources(k))
                if (s%kind == source_overpressure) then
                    if (acts(s, t_new, .true.)) s%volume = s%volume + dt * sum(flux(s%cells))
                else
                    s%volume = s%volume + dt * s%value * &
                        (theta * merge(1.0_wp, 0.0_wp, acts(s, t_new, .true.)) + &
                         (1.0_wp - theta) * merge(1.0_wp, 0.0_wp, acts(s, state%time, .false.)))
                end if
            end associate
        end do
        state%p = p_new
        state%time = t_new
        state%damping_steps = max(state%damping_steps - 1, 0)
    end subroutine take_step

    !> Whether a source acts at time t, at the end of a step (after) or at its start.
    pure logical function acts(source, t, after)
        type(flow_source), intent(in) :: source
        real(wp), intent(in) :: t
        logical, intent(in) :: after

        if (after) then
            acts = source%start < t .and. t <= source%stop
        else
            acts = source%start <= t .and. t < source%stop
        end if
    end function acts

    !> The rate sources' volume rate into each cell at time t.
    pure subroutine rates(state, t, after, rate)
        type(flow_state), intent(in) :: state
        real(wp), intent(in) :: t
        logical, intent(in) :: after
        real(wp), intent(out) :: rate(:)
        integer :: k

        rate = 0.0_wp
        do k = 1, size(state%sources)
            associate (s => state%sources(k))
                if (s%kind == source_overpressure .or. .not. acts(s, t, after)) cycle
                rate(s%cells) = rate(s%cells) + s%value / real(size(s%cells), wp)
            end associate
        end do
    end subroutine rates

    !> Solve (M / dt + theta A) p = rhs for the free cells, the held ones at their value in
    !> p (on entry the start of the iteration), by preconditioned conjugate gradients.
    subroutine solve_free(network, held, theta, dt, rhs, p, error)
        type(flow_network), intent(in) :: network
        logical, intent(in) :: held(:)
        real(wp), intent(in) :: theta, dt, rhs(:)
        real(wp), intent(inout) :: p(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), dimension(size(p)) :: r, z, d, q, diagonal
        real(wp) :: rz, rz_old, alpha, norm_b
        integer :: c, iteration

        diagonal = network%storage / dt
        do c = 1, size(network%conductance)
            diagonal(network%pair(:, c)) = diagonal(network%pair(:, c)) + theta * &
                network%conductance(c)
        end do
        r = rhs - operator_of(p)
        where (held) r = 0.0_wp
        norm_b = norm2(merge(0.0_wp, rhs, held))
        if (norm_b == 0.0_wp) norm_b = 1.0_wp
        z = r / diagonal
        d = z
        rz = dot_product(r, z)
        do iteration = 1, 10 * size(p) + 100
            if (norm2(r) <= cg_tolerance * norm_b) return
            q = operator_of(d)
            where (held) q = 0.0_wp
            alpha = rz / dot_product(d, q)
            p = p + alpha * d
            r = r - alpha * q
            z = r / diagonal
            rz_old = rz
            rz = dot_product(r, z)
            d = z + rz / rz_old * d
        end do
        if (norm2(r) <= cg_tolerance * norm_b) return
        call set_error(error, exit_solver_failure, 'the conjugate gradient method left a '// &
                       'relative residual of '//rtoa(norm2(r) / norm_b)//' after '// &
                       itoa(iteration - 1)//' iterations')

    contains

        pure function operator_of(x) result(y)
            real(wp), intent(in) :: x(:)
            real(wp) :: y(size(x))

            y = network%storage / dt * x + theta * net_outflow(network, x)
        end function operator_of
    end subroutine solve_free

    !> The pressure change of every element: its cell's, 0 where it does not conduct.
    pure function element_pressure(network, state) result(p)
        !> The network
        type(flow_network), intent(in) :: network
        !> Its state
        type(flow_state), intent(in) :: state
        !> Pressure change of each element [stress unit], shape (n)
        real(wp) :: p(size(network%cell))

        p = 0.0_wp
        p(network%element) = state%p
    end function element_pressure

    !> The fluid the network stores: sum of storage times pressure change [length^2].
    pure real(wp) function stored_volume(network, state)
        !> The network
        type(flow_network), intent(in) :: network
        !> Its state
        type(flow_state), intent(in) :: state

        stored_volume = sum(network%storage * state%p)
    end function stored_volume

end module ddc_flow_diffusion
