!> One step of flow coupled to opening (docs/theory/fluid-driven-fractures.md#the-coupled-step):
!> the pressure change of the conducting cells and the contact solution of the model that
!> it loads, found together. The lubrication balance of every cell (ddc_flow_lubrication) is
!> a function of the pressure through the openings the contact run solves for it; Newton's
!> method on the pressure (docs/theory/fluid-driven-fractures.md#newtons-method-on-the-pressure),
!> each iterate one contact solve from the step's starting memory (the friction memory and
!> strengths in force of the step before), its Jacobian the balance's for the response of
!> the open cells' openings (the inverse of their block of the contact stiffness, the other
!> elements held). Where a step does not lower the balance, the open set of its end is tried
!> next, then the iterate's own step is halved; a step that does not settle is taken again
!> in sub-steps. The step is converged when the volume left unbalanced is below
!> balance_tolerance of the volume injected, or, where no step lowers it any more, within
!> the rounding of its terms or below stalled_tolerance of the volume injected.
module ddc_history_coupled_flow
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure
    use ddc_text, only: itoa, rtoa
    use ddc_contact_states, only: state_open, state_slip
    use ddc_contact_result, only: contact_result
    use ddc_contact_fault_law, only: fault_law
    use ddc_solve_operator, only: elastic_load
    use ddc_run_contact_run, only: contact_run, contact_step
    use ddc_linalg_lu, only: lu_factor, lu_solve
    use ddc_model_types, only: model_type
    use ddc_flow_lubrication, only: lubrication_flow, start_lubrication, cell_balance, &
        balance_jacobian, take_lubrication_step, held_pressure
    implicit none
    private

    public :: start_coupled_flow, coupled_flow_step, response_cache

    !> Linearized states of a contact element beside state_open: held (stuck, or a cell
    !> taken as closed), slipping (times the sign of its shear traction)
    integer, parameter :: linear_held = 0, linear_slip = 2

    !> The open cells' response d opening / d p last made on a geometry, and the contact
    !> elements' linearized states it is for (linear_states: a fixed geometry and states
    !> give the same response: the steps of a history and the trials of a growth step share
    !> it)
    type :: response_cache
        integer, allocatable :: states(:)
        real(wp), allocatable :: response(:, :)
    end type response_cache

    !> The volume a converged step leaves unbalanced (the sum of the cells' |balance|), as
    !> a fraction of the volume injected by its end; and what it may leave, as a multiple
    !> of the balances' rounding, where no Newton step lowers it any more (a fluid of low
    !> viscosity: the fluxes through the connections are large terms that cancel)
    real(wp), parameter :: balance_tolerance = 1.0e-10_wp, rounding_cells = 1.0e3_wp
    !> What a step may leave unbalanced where no Newton step lowers it any more or the
    !> iterations are spent, as a fraction of the volume injected
    real(wp), parameter :: stalled_tolerance = 1.0e-8_wp
    !> Newton iterations of a step, and halvings of one iteration's step
    integer, parameter :: max_iterations = 40, max_halvings = 8
    !> Open sets tried for one Newton step; sub-steps a step may be cut into
    integer, parameter :: max_guesses = 6, max_pieces = 64

contains

    !> The flow at rest at the first time: the openings of the equilibrium without it (a
    !> solve that leaves the run's memory as it was).
    subroutine start_coupled_flow(run, model, load, time, flow, error)
        !> The prepared run, before its first step
        type(contact_run), intent(inout) :: run
        !> The model (&fluid, &injection)
        type(model_type), intent(in) :: model
        !> The load of the first step without the flow's pressure
        type(elastic_load), intent(in) :: load
        !> The first time [time unit]
        real(wp), intent(in) :: time
        !> The flow at rest
        type(lubrication_flow), intent(out) :: flow
        !> Set when the solve fails
        type(error_type), allocatable, intent(out) :: error
        type(contact_step) :: solution
        type(fault_law) :: law

        law = run%law_in_force()
        call run%step(load, solution, error)
        if (allocated(error)) return
        call start_lubrication(model%elements, model%fluid, model%injections, time, &
                               -solution%dn, flow)
        call run%hold(spread(0.0_wp, 1, model%elements%n), law)
    end subroutine start_coupled_flow

    !> The step to t_new: pressure and contact solution together; the flow moves on to
    !> t_new and the run's memory is the solution's. A step whose Newton iteration does not
    !> settle is taken again in 2, 4, ... sub-steps (at most max_pieces): the shorter the
    !> step, the more the storage outweighs the change of the flow with the aperture.
    subroutine coupled_flow_step(run, load, t_new, flow, ds_before, solution, iterations, &
                                 unbalanced, error, cache)
        !> The prepared run, its memory that of the step before
        type(contact_run), intent(inout) :: run
        !> The step's load without the flow's pressure
        type(elastic_load), intent(in) :: load
        !> The step's time [time unit]
        real(wp), intent(in) :: t_new
        !> The flow at the step before; at t_new on return
        type(lubrication_flow), intent(inout) :: flow
        !> The total slip of every element the step before left [length unit], shape (n)
        real(wp), intent(in) :: ds_before(:)
        !> The step's contact solution
        type(contact_step), intent(out) :: solution
        !> Newton iterations taken, over the sub-steps
        integer, intent(out) :: iterations
        !> The largest volume a sub-step left unbalanced, as a fraction of the volume injected
        real(wp), intent(out) :: unbalanced
        !> Set when a contact solve fails or the step does not converge
        type(error_type), allocatable, intent(out) :: error
        !> The responses of this geometry made so far (one of its own when absent)
        type(response_cache), intent(inout), optional, target :: cache
        type(response_cache), target :: own_cache
        type(response_cache), pointer :: responses
        type(lubrication_flow) :: start
        type(fault_law) :: law_start
        real(wp), allocatable :: ds(:)
        real(wp) :: t_start, t_piece, piece_unbalanced
        integer :: pieces, j, piece_iterations
        logical :: converged

        responses => own_cache
        if (present(cache)) responses => cache
        start = flow
        law_start = run%law_in_force()
        t_start = flow%time
        pieces = 1
        do
            iterations = 0
            unbalanced = 0.0_wp
            ds = ds_before
            do j = 1, pieces
                t_piece = t_start + (t_new - t_start) * real(j, wp) / real(pieces, wp)
                if (j == pieces) t_piece = t_new
                call solve_step(run, load, t_piece, flow, ds, solution, piece_iterations, &
                                piece_unbalanced, converged, responses, error)
                if (allocated(error)) return
                iterations = iterations + piece_iterations
                unbalanced = max(unbalanced, piece_unbalanced)
                if (.not. converged) exit
                ds = solution%ds
            end do
            if (converged) return
            if (pieces >= max_pieces) then
                call set_error(error, exit_solver_failure, 'coupled flow: the step to time '// &
                               rtoa(t_new)//' did not converge in '//itoa(max_pieces)// &
                               ' sub-steps (the volume left unbalanced is '// &
                               rtoa(piece_unbalanced)//' of the injected); try shorter '// &
                               'time steps')
                return
            end if
            pieces = 2 * pieces
            flow = start
            call run%hold(ds_before, law_start)
        end do
    end subroutine coupled_flow_step

    !> One backward Euler step to t_new by Newton's method (the module's comment); not
    !> converged after max_iterations.
    subroutine solve_step(run, load, t_new, flow, ds_before, solution, iterations, &
                          unbalanced, converged, cache, error)
        type(contact_run), intent(inout) :: run
        type(elastic_load), intent(in) :: load
        real(wp), intent(in) :: t_new
        type(lubrication_flow), intent(inout) :: flow
        real(wp), intent(in) :: ds_before(:)
        type(contact_step), intent(out) :: solution
        integer, intent(out) :: iterations
        real(wp), intent(out) :: unbalanced
        !> The step converged (the flow moved on to t_new)
        logical, intent(out) :: converged
        type(response_cache), intent(inout) :: cache
        type(error_type), allocatable, intent(out) :: error
        type(fault_law) :: law_before
        type(error_type), allocatable :: ill_conditioned
        real(wp), dimension(flow%network%cells) :: p, trial, residual, value, opening
        real(wp) :: dp(flow%network%cells, 1), injected
        real(wp), allocatable :: jacobian(:, :)
        integer, allocatable :: pivots(:)
        logical :: held(flow%network%cells)
        real(wp) :: norm, trial_norm, factor, stress_scale, rounding
        real(wp), dimension(flow%network%cells) :: trial_residual, first_step
        real(wp) :: first_factor
        type(contact_step) :: trial_solution
        integer, allocatable :: guess(:), trial_states(:)
        integer :: halving, attempt
        logical :: stalled

        law_before = run%law_in_force()
        associate (e => flow%network%element)
            stress_scale = max(maxval(abs(load%normal(e))), maxval(abs(load%shear(e))), &
                               maxval(abs(load%pressure(e))), tiny(1.0_wp))
        end associate
        call held_pressure(flow, t_new, held, value)
        p = merge(value, flow%p, held)
        converged = .false.
        call evaluate(p, solution, residual, norm)
        if (allocated(error)) return
        stalled = .false.
        allocate (jacobian(size(p), size(p)), pivots(size(p)))
        do iterations = 0, max_iterations
            unbalanced = norm / volume_scale()
            if (unbalanced <= balance_tolerance) exit
            ! No step lowers the balance any more (or the iterations are spent), and what is
            ! left is rounding, or below the volume a step may leave (a fluid of low
            ! viscosity: large flux terms cancel).
            if ((stalled .or. iterations == max_iterations) .and. &
                (norm <= rounding_cells * rounding .or. unbalanced <= stalled_tolerance)) exit
            if (iterations == max_iterations) return
            ! The states of the linearization: the iterate's, then, while a step does not
            ! lower the balance, those of the step's end (an active set that settles).
            guess = linear_states(run, flow, solution%state(flow%network%element) == &
                                  state_open, solution%contact)
            opening = -solution%dn(flow%network%element)
            do attempt = 1, max_guesses
                call newton_step(guess)
                if (allocated(error)) return
                ! The iterate's own step: the one to halve when no guess lowers the balance.
                if (attempt == 1) then
                    first_step = dp(:, 1)
                    first_factor = factor
                end if
                call evaluate(trial, trial_solution, trial_residual, trial_norm)
                if (allocated(error)) return
                if (trial_norm < norm) exit
                trial_states = linear_states(run, flow, trial_solution%state( &
                    flow%network%element) == state_open, trial_solution%contact)
                if (all(trial_states == guess)) exit
                guess = trial_states
            end do
            if (.not. trial_norm < norm) then
                factor = first_factor
                do halving = 1, max_halvings
                    factor = 0.5_wp * factor
                    trial = p + factor * first_step
                    call evaluate(trial, trial_solution, trial_residual, trial_norm)
                    if (allocated(error)) return
                    if (trial_norm < norm) exit
                end do
            end if
            solution = trial_solution
            residual = trial_residual
            stalled = .not. trial_norm < norm
            p = trial
            norm = trial_norm
        end do
        call take_lubrication_step(flow, t_new, p, -solution%dn(flow%network%element))
        converged = .true.

    contains

        !> The Newton step from p for the cells open in `open_cells`, into dp, factor and
        !> trial (a trust region: no cell's pressure moves by more than the stresses at
        !> stake; from closed cells that store little, Newton's step would overshoot by
        !> orders).
        subroutine newton_step(states)
            !> The contact elements' linearized states (linear_states)
            integer, intent(in) :: states(:)
            logical :: open_cells(flow%network%cells)

            open_cells = states(contact_index(run, flow)) == state_open
            if (.not. known(states)) then
                call opening_response(run, flow, states, cache%response, error)
                if (allocated(error)) return
                cache%states = states
            end if
            call balance_jacobian(flow, t_new, p, opening, open_cells, cache%response, &
                                  jacobian)
            ! Closed cells of a small residual aperture store and pass little: an ill-
            ! conditioned Jacobian still gives the step (the balance judges it).
            call lu_factor(jacobian, pivots, 'the coupled flow''s Jacobian', error, &
                           ill_conditioned=ill_conditioned)
            if (allocated(error)) return
            dp(:, 1) = -residual
            call lu_solve(jacobian, pivots, dp)
            factor = min(1.0_wp, max(stress_scale, maxval(abs(p))) / maxval(abs(dp)))
            trial = p + factor * dp(:, 1)
        end subroutine newton_step

        !> Whether the cache holds the response of these linearized states.
        logical function known(states)
            integer, intent(in) :: states(:)

            known = .false.
            if (.not. allocated(cache%states)) return
            if (size(cache%states) /= size(states)) return
            known = all(cache%states == states)
        end function known

        !> The contact solution for pressure q from the step's starting memory, the cells'
        !> balance and the volume it leaves (held cells apart).
        subroutine evaluate(q, solved, balance, volume)
            real(wp), intent(in) :: q(:)
            type(contact_step), intent(out) :: solved
            real(wp), intent(out) :: balance(:), volume
            type(elastic_load) :: loaded
            real(wp) :: leak(size(q))

            loaded = load
            associate (e => flow%network%element)
                loaded%pressure(e) = loaded%pressure(e) + q
            end associate
            call run%hold(ds_before, law_before)
            call run%step(loaded, solved, error)
            if (allocated(error)) then
                error%message = 'coupled flow, time '//rtoa(t_new)//': '//error%message
                return
            end if
            call cell_balance(flow, t_new, q, -solved%dn(flow%network%element), balance, leak, &
                              injected, rounding)
            volume = sum(abs(balance), mask=.not. held)
        end subroutine evaluate

        !> What the step must balance: the volume injected by its end, at least 1e-3 of the
        !> fluid stored at the start (rounding in the storage of a network at rest).
        real(wp) function volume_scale()
            volume_scale = max(sum(abs(flow%sources%volume)) + abs(injected), &
                               1.0e-3_wp * flow%stored_initial)
        end function volume_scale
    end subroutine solve_step

    !> The index in the run's contact set of each cell's element, shape (cells).
    function contact_index(run, flow) result(index)
        type(contact_run), intent(in) :: run
        type(lubrication_flow), intent(in) :: flow
        integer :: index(flow%network%cells)
        integer, allocatable :: contact_of(:)
        integer :: i

        allocate (contact_of(size(flow%network%cell)), source=0)
        contact_of(run%operator%contact) = [(i, i = 1, run%operator%nc)]
        index = contact_of(flow%network%element)
    end function contact_index

    !> The linearized state of every contact element (its index in the run's contact set):
    !> open (the cells of open_cells, and contact elements outside the network that the
    !> iterate leaves open), slipping forward or backward (the iterate's slipping elements
    !> that are not taken as open: linear_slip times the sign of their shear traction), or
    !> held (stuck, or a cell taken as closed).
    function linear_states(run, flow, open_cells, contact) result(states)
        type(contact_run), intent(in) :: run
        type(lubrication_flow), intent(in) :: flow
        !> Whether each cell is taken as open, shape (cells)
        logical, intent(in) :: open_cells(:)
        !> The iterate's contact solution
        type(contact_result), intent(in) :: contact
        integer, allocatable :: states(:)
        integer :: cell_of(flow%network%cells), i

        allocate (states(run%operator%nc), source=linear_held)
        where (contact%state == state_open) states = state_open
        where (contact%state == state_slip) states = merge(linear_slip, -linear_slip, &
                                                           contact%shear_traction >= 0.0_wp)
        cell_of = contact_index(run, flow)
        do i = 1, flow%network%cells
            if (open_cells(i)) then
                states(cell_of(i)) = state_open
            else if (states(cell_of(i)) == state_open) then
                states(cell_of(i)) = linear_held
            end if
        end do
    end function linear_states

    !> The open cells' opening response d opening_i / d p_j (shape (cells, cells)) of the
    !> linearized contact problem: open elements free in shear and normal, their normal
    !> traction -p; slipping ones free in shear, their shear traction on the friction line
    !> ts = s mu (-tn - p) (s the sign of their shear traction); the others held. Where
    !> cells slip beside open ones (a fracture's flank, a fault beside a junction) their slip
    !> moves the openings too.
    subroutine opening_response(run, flow, states, response, error)
        type(contact_run), intent(in) :: run
        type(lubrication_flow), intent(in) :: flow
        !> The contact elements' linearized states (linear_states), shape (nc)
        integer, intent(in) :: states(:)
        real(wp), allocatable, intent(out) :: response(:, :)
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: opened(:), rows(:), pivots(:), free_shear(:), &
            free_normal(:), cells(:), position(:)
        integer :: cell_of(flow%network%cells)
        real(wp), allocatable :: block(:, :), columns(:, :), mu(:)
        type(fault_law) :: law
        integer :: nc, m, i, j, k, r
        logical, allocatable :: in_network(:)

        allocate (response(flow%network%cells, flow%network%cells), source=0.0_wp)
        associate (op => run%operator)
            if (.not. associated(op%matrix)) then
                call set_error(error, exit_solver_failure, 'coupled flow needs the dense '// &
                               'contact stiffness')
                return
            end if
            nc = op%nc
            cell_of = contact_index(run, flow)
            ! The open cells first, in cell order; then the other open and slipping elements.
            opened = pack([(i, i = 1, flow%network%cells)], states(cell_of) == state_open)
            m = size(opened)
            if (m == 0) return
            allocate (in_network(nc), source=.false.)
            in_network(cell_of(opened)) = .true.
            free_normal = [cell_of(opened), &
                           pack([(i, i = 1, nc)], states == state_open .and. .not. in_network)]
            free_shear = [free_normal, pack([(i, i = 1, nc)], abs(states) == linear_slip)]
            rows = [free_shear, nc + free_normal]
            block = op%matrix(rows, rows)
            ! The friction in force of the contact elements (the law holds every element's).
            law = run%law_in_force()
            mu = law%mu_in_force(op%contact)
            do r = size(free_normal) + 1, size(free_shear)
                j = free_shear(r)
                block(r, :) = block(r, :) + sign(mu(j), real(states(j), wp)) * &
                              op%matrix(nc + j, rows)
            end do
            ! A column per cell that is open or slips: a unit pressure change in it. An open
            ! element's normal row sits as far into the normal rows as its shear row into
            ! the shear rows (free_normal begins free_shear).
            allocate (position(nc), source=0)
            position(free_shear) = [(r, r = 1, size(free_shear))]
            cells = pack([(i, i = 1, flow%network%cells)], position(cell_of) > 0)
            allocate (columns(size(rows), size(cells)), source=0.0_wp)
            do k = 1, size(cells)
                j = cell_of(cells(k))
                if (states(j) == state_open) then
                    columns(size(free_shear) + position(j), k) = 1.0_wp
                else
                    columns(position(j), k) = sign(mu(j), real(states(j), wp))
                end if
            end do
            allocate (pivots(size(rows)))
            call lu_factor(block, pivots, 'the open cells'' contact stiffness', error)
            if (allocated(error)) return
            call lu_solve(block, pivots, columns)
            response(opened, cells) = columns(size(free_shear) + 1:size(free_shear) + m, :)
        end associate
    end subroutine opening_response

end module ddc_history_coupled_flow
