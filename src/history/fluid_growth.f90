!> Fluid-driven growth (docs/theory/fluid-driven-fractures.md#fluid-driven-growth):
!> fractures that lengthen as the fluid the sources inject fills them. Each growth step adds
!> one element straight ahead of every growing tip (the length fixed), and the time it takes
!> is solved for: the time at which the largest K_I of the growing tips, after a coupled
!> step of the flow and the contact run from the state before (ddc_history_coupled_flow),
!> reaches the apparent toughness of the front's velocity (ddc_flow_tip_asymptote). The
!> geometry grows on a run of its own (prepare), the flow carried over (carry_lubrication: a
!> new element is rock just broken, its residual aperture at rest). The first step finds the
!> time at which the initial fractures start to grow. The run ends after &growth steps, or
!> when the time passes the path's last.
module ddc_history_fluid_growth
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure, exit_stopped_early
    use ddc_text, only: itoa, rtoa
    use ddc_model_types, only: model_type, element_set, select_elements
    use ddc_mesh_geometry, only: compute_geometry
    use ddc_mesh_segments, only: classify_pair, pair_cross, pair_t_first_end, far_apart, &
        crossing_fraction, point_segment_distance
    use ddc_model_results, only: model_results, history_record, tip_set, state_not_grown
    use ddc_model_records, only: lay_out_history
    use ddc_model_medium, only: medium_of, elastic_medium
    use ddc_solve_operator, only: elastic_load
    use ddc_contact_fault_law, only: fault_law
    use ddc_post_tips, only: find_tips
    use ddc_history_path, only: path_loads, apply_load
    use ddc_run_contact_run, only: contact_run, contact_step
    use ddc_run_model, only: finish_model, model_load
    use ddc_flow_lubrication, only: lubrication_flow, carry_lubrication, along_flux, &
        element_values
    use ddc_history_coupled_flow, only: start_coupled_flow, coupled_flow_step, response_cache
    use ddc_flow_tip_asymptote, only: apparent_toughness, front_distance
    use ddc_progress, only: report_progress
    implicit none
    private

    public :: solve_fluid_growth

    !> K_I within this fraction of the apparent toughness ends the search for a step's time
    real(wp), parameter :: toughness_tolerance = 1.0e-6_wp
    !> A bracket of the step's time this fraction of the step wide holds a jump of K_I
    real(wp), parameter :: jump_tolerance = 1.0e-9_wp
    !> Trials of the search for a step's time
    integer, parameter :: max_secant = 100

    !> One recorded growth step on its geometry.
    type :: growth_column
        real(wp) :: time = 0.0_wp
        !> Every element's values, shape (n of the step)
        real(wp), allocatable :: ds(:), dn(:), pressure(:), aperture(:), flux(:)
        integer, allocatable :: state(:)
        !> The final geometry's element of each element of the step, shape (n of the step)
        integer, allocatable :: final(:)
        !> K of every tip of the step's geometry, its fracture and side (1 begin, 2 end)
        real(wp), allocatable :: k1(:), k2(:)
        integer, allocatable :: tip_fracture(:), tip_side(:)
        !> Where the front of each end of a growing fracture is, and where the end is
        !> [length unit], shape (growing ends: begin and end of each growing fracture)
        real(wp), allocatable :: front_x(:), front_y(:), end_x(:), end_y(:)
        real(wp) :: injected = 0.0_wp, stored = 0.0_wp, leaked = 0.0_wp, unbalanced = 0.0_wp
        integer :: iterations = 0, elements = 0
    end type growth_column

contains

    !> Grow the model's fractures by the fluid of its sources.
    subroutine solve_fluid_growth(model, results, error)
        !> A validated model with &fluid, &growth, sources and a time axis; the final
        !> geometry on return
        type(model_type), intent(inout) :: model
        !> The last step's results and the history of every step
        type(model_results), intent(out) :: results
        !> Set when a solve fails
        type(error_type), allocatable, intent(out) :: error
        type(contact_run), allocatable :: run
        type(lubrication_flow) :: flow
        type(contact_step) :: solution, kept_solution
        type(growth_column), allocatable :: columns(:)
        type(model_type) :: kept_model
        type(elastic_load) :: load
        character(len=:), allocatable :: failure
        real(wp), allocatable :: loads(:, :), ds(:)
        integer, allocatable :: origin(:), begin_grows(:), end_grows(:)
        real(wp) :: t_start, t_end, dt_guess, time, t_before
        integer :: step, k
        logical, allocatable :: fracture_grows(:)
        integer(int64) :: t_begin, t_done, rate

        call system_clock(t_begin, rate)
        loads = path_loads(model%load_path)
        associate (vertex_times => model%load_path%time)
            t_start = vertex_times(1)
            t_end = vertex_times(size(vertex_times))
        end associate
        model = apply_load(model, loads(:, 1))
        call growing_ends(model, begin_grows, end_grows)
        allocate (run)
        call run%prepare(medium_of(model), model%solver, error)
        if (failed()) return
        call run%take_steps()
        load = model_load(model)
        call start_coupled_flow(run, model, load, t_start, flow, error)
        if (failed()) return
        allocate (ds(model%elements%n), source=0.0_wp)
        allocate (columns(0))
        dt_guess = (t_end - t_start) / real(max(model%growth%steps, 1), wp)
        t_before = t_start
        allocate (fracture_grows(size(model%fractures)), source=.true.)
        if (allocated(model%growth%fracture_grows)) fracture_grows = model%growth%fracture_grows
        do step = 0, model%growth%steps
            if (step > 0) then
                ! Every tip stopped on another fracture: nothing grows any more.
                if (size(begin_grows) + size(end_grows) == 0) exit
                call grow_ends(model, begin_grows, end_grows, origin)
                call run_on_the_geometry(error)
                if (failed()) return
                block
                    type(lubrication_flow) :: before

                    before = flow
                    call carry_lubrication(before, model%elements, model%injections, origin, &
                                           flow)
                end block
                ds = carried(ds, origin)
                call run%hold(ds)
            end if
            call reach_toughness(run, load, flow, ds, dt_guess, model%growth%toughness, &
                                 step > 0, fracture_grows, begin_grows, end_grows, solution, &
                                 columns, error)
            if (allocated(error)) then
                error%message = 'fluid-driven growth, step '//itoa(step)//': '//error%message
                if (step == 0) then
                    error%message = error%message//'; no result is written'
                    call run%finish()
                    return
                end if
                ! The steps completed are the result: back to the last one's geometry (the
                ! columns are still on it).
                call move_alloc(error%message, failure)
                deallocate (error)
                call restore_last_step(error)
                if (failed()) return
                exit
            end if
            ! The steps before hold their rows on the geometry before: on the grown one now.
            if (step > 0) then
                do k = 1, size(columns) - 1
                    columns(k)%final = position_of(columns(k)%final, origin)
                end do
            end if
            kept_model = model
            kept_solution = solution
            time = flow%time
            dt_guess = max(time - t_before, epsilon(1.0_wp) * abs(time))
            t_before = time
            ds = solution%ds
            call report_progress('growth step '//itoa(step)//': t = '//rtoa(time)//', '// &
                                 itoa(model%elements%n)//' elements')
            if (time > t_end) exit
        end do
        call finish_results()
        if (allocated(failure)) then
            call set_error(error, exit_stopped_early, failure//'; the run stopped there: '// &
                           'the result holds the '//itoa(size(columns))//' step(s) before '// &
                           'it (root attribute stopped)')
            results%stopped = error%message
        end if

    contains

        !> Whether the solve failed; the run's memory is released when it did (a run on no
        !> geometry holds none).
        logical function failed()
            failed = allocated(error)
            if (failed) call run%finish()
        end function failed

        !> The model, the run and the solution of the last step completed.
        subroutine restore_last_step(error)
            type(error_type), allocatable, intent(out) :: error

            model = kept_model
            solution = kept_solution
            call run_on_the_geometry(error)
            if (allocated(error)) return
            call run%hold(solution%ds)
        end subroutine restore_last_step

        !> A new run (matrix and factors) and load on the model's geometry.
        subroutine run_on_the_geometry(error)
            type(error_type), allocatable, intent(out) :: error

            call run%finish()
            deallocate (run)
            allocate (run)
            call run%prepare(medium_of(model), model%solver, error)
            if (allocated(error)) return
            call run%take_steps()
            load = model_load(model)
        end subroutine run_on_the_geometry

        !> The last step's element results, tips and fields, and the history.
        subroutine finish_results()
            integer, allocatable :: grown(:)

            results%elements%ds = solution%ds
            results%elements%dn = solution%dn
            results%elements%state = solution%state
            results%solver = run%record_of(solution)
            call finish_model(model, load, results, run=run)
            grown = pack([(k, k = 1, size(fracture_grows))], fracture_grows)
            call history_of(columns, model, loads(:, 1), results%tips, &
                            [(grown(k / 2 + 1), k = 0, 2 * size(grown) - 1)], &
                            [(modulo(k, 2), k = 0, 2 * size(grown) - 1)], results%history)
            call run%finish()
            ! The run's time: every step's preparation and trials (the record of the
            ! solver is the last step's).
            call system_clock(t_done)
            results%solver%seconds_total = real(t_done - t_begin, wp) / real(rate, wp)
        end subroutine finish_results

    end subroutine solve_fluid_growth

    !> Find the time, after flow%time, at which the largest K_I of the growing tips reaches
    !> the apparent toughness; the flow and the run move on to it, and the step is recorded.
    subroutine reach_toughness(run, load, flow, ds, dt_guess, toughness, advancing, &
                               fracture_grows, begin_grows, end_grows, solution, columns, error)
        type(contact_run), intent(inout) :: run
        type(elastic_load), intent(in) :: load
        type(lubrication_flow), intent(inout) :: flow
        real(wp), intent(in) :: ds(:), dt_guess, toughness
        !> Whether the fronts moved on by their tip elements at this step (not at the first)
        logical, intent(in) :: advancing
        !> Whether each fracture grows, shape (fractures); the fractures whose beginning and
        !> whose end still grow
        logical, intent(in) :: fracture_grows(:)
        integer, intent(in) :: begin_grows(:), end_grows(:)
        type(contact_step), intent(out) :: solution
        type(growth_column), allocatable, intent(inout) :: columns(:)
        type(error_type), allocatable, intent(out) :: error
        type(lubrication_flow) :: start, trial
        type(fault_law) :: law
        real(wp) :: t0, t_lo, t_hi, f_lo, f_hi, t, f, unbalanced, e_prime
        real(wp) :: widths(2)
        integer :: iterations, count, side
        type(tip_set) :: tips
        type(response_cache) :: cache

        start = flow
        law = run%law_in_force()
        t0 = flow%time
        e_prime = 2.0_wp * run%medium%shear_modulus / (1.0_wp - run%medium%poissons_ratio)
        ! The step's start as if K_I were 0 there: no solve without time for the fluid to
        ! flow (a tip just linked to another fracture pulls it open before fluid can enter).
        t_lo = t0
        f_lo = -1.0_wp
        t = t0
        ! Secant steps from the step's start and its guess; regula falsi (Illinois)
        ! once the root is bracketed, doubling the step while it is not.
        t_hi = t0 + dt_guess
        f_hi = excess(t_hi)
        if (allocated(error)) return
        side = 0
        widths = huge(1.0_wp)
        do count = 1, max_secant
            if (abs(f_hi) <= toughness_tolerance) then
                t = t_hi
                exit
            end if
            if (f_hi < 0.0_wp) then
                ! Not bracketed yet: the secant's extrapolation, at most a doubling.
                t = t_hi + min((t_hi - t_lo) * (-f_hi) / (f_hi - f_lo), t_hi - t0)
                if (.not. f_hi > f_lo) t = t_hi + (t_hi - t0)
                t_lo = t_hi
                f_lo = f_hi
                t_hi = t
                f_hi = excess(t_hi)
                if (allocated(error)) return
                cycle
            end if
            ! K_I that jumps past the toughness (a tip element that opens at once) leaves a
            ! bracket that shrinks onto the jump: the step ends on its far side.
            if (t_hi - t_lo <= jump_tolerance * (t_hi - t0)) then
                t = t_hi
                exit
            end if
            t = (t_lo * f_hi - t_hi * f_lo) / (f_hi - f_lo)
            ! A bracket that two trials have not halved: regula falsi stalls on a steep
            ! or jumping K_I; bisect.
            if (t_hi - t_lo > 0.5_wp * widths(2)) t = 0.5_wp * (t_lo + t_hi)
            widths = [t_hi - t_lo, widths(1)]
            f = excess(t)
            if (allocated(error)) return
            if (abs(f) <= toughness_tolerance) exit
            if (f < 0.0_wp) then
                t_lo = t
                f_lo = f
                if (side == -1) f_hi = 0.5_wp * f_hi
                side = -1
            else
                t_hi = t
                f_hi = f
                if (side == 1) f_lo = 0.5_wp * f_lo
                side = 1
            end if
        end do
        if (count > max_secant) then
            call set_error(error, exit_solver_failure, 'the time at which K_I reaches '// &
                           'the toughness was not found in '//itoa(max_secant)// &
                           ' trials')
            return
        end if
        ! The trial kept is the last one solved: solve the root again when it was not.
        if (trial%time /= t) f = excess(t)
        if (allocated(error)) return
        flow = trial
        call record(t)

    contains

        !> The largest K_I / K_app - 1 of the growing tips after the coupled step to time,
        !> K_app the apparent toughness of the fronts' velocity over the step.
        real(wp) function excess(time)
            real(wp), intent(in) :: time
            real(wp), allocatable :: ratio(:)
            integer :: j, i

            trial = start
            call run%hold(ds, law)
            excess = -huge(1.0_wp)
            call coupled_flow_step(run, load, time, trial, ds, solution, iterations, &
                                   unbalanced, error, cache)
            if (allocated(error)) return
            call find_tips(run%medium, solution%ds, solution%dn, tips)
            allocate (ratio(tips%n))
            do j = 1, tips%n
                i = tips%element(j)
                associate (h => run%medium%elements%half_length(i))
                    ratio(j) = tips%k1(j) / apparent_toughness(toughness, e_prime, &
                        flow%fluid%viscosity, front_velocity(h, time - t0, advancing), h)
                end associate
            end do
            excess = maxval(ratio, mask=growing(tips)) - 1.0_wp
        end function excess

        !> Whether each tip still grows.
        function growing(found) result(grows)
            type(tip_set), intent(in) :: found
            logical :: grows(found%n)
            integer :: j

            do j = 1, found%n
                if (found%side(j) == 1) then
                    grows(j) = any(begin_grows == found%fracture_id(j))
                else
                    grows(j) = any(end_grows == found%fracture_id(j))
                end if
            end do
        end function growing

        subroutine record(time)
            real(wp), intent(in) :: time
            type(growth_column) :: column
            integer :: n, i

            n = run%medium%elements%n
            column%time = time
            column%ds = solution%ds
            column%dn = solution%dn
            column%state = solution%state
            column%pressure = element_values(flow, flow%p, n, 0.0_wp)
            column%aperture = element_values(flow, flow%aperture, n, 0.0_wp)
            column%flux = element_values(flow, along_flux(flow), n, 0.0_wp)
            column%final = [(i, i = 1, n)]
            column%k1 = tips%k1
            column%k2 = tips%k2
            column%tip_fracture = tips%fracture_id
            column%tip_side = tips%side
            call locate_fronts(run%medium, solution%dn, fracture_grows, begin_grows, end_grows, &
                               toughness, flow%fluid%viscosity, time - t0, advancing, column)
            column%injected = sum(flow%sources%volume)
            column%stored = sum(flow%stored) - flow%stored_initial
            column%leaked = flow%leaked
            column%iterations = iterations
            column%unbalanced = unbalanced
            column%elements = n
            columns = [columns, column]
        end subroutine record
    end subroutine reach_toughness

    !> Where the front of each end of a growing fracture is: the tip asymptote of the
    !> toughness and the front's velocity through the tip element's opening at its midpoint
    !> puts the front r from the midpoint, along the element
    !> (docs/theory/fluid-driven-fractures.md#the-fluid-driven-tip); an end that stopped on
    !> another fracture is its own front.
    pure subroutine locate_fronts(medium, dn, fracture_grows, begin_grows, end_grows, &
                                  toughness, viscosity, elapsed, advancing, column)
        type(elastic_medium), intent(in) :: medium
        !> Normal DD of every element [length unit]
        real(wp), intent(in) :: dn(:)
        logical, intent(in) :: fracture_grows(:)
        integer, intent(in) :: begin_grows(:), end_grows(:)
        real(wp), intent(in) :: toughness, viscosity
        !> The step's time [time unit]; whether the fronts moved on by their tip elements
        real(wp), intent(in) :: elapsed
        logical, intent(in) :: advancing
        !> Its front_x, front_y, end_x, end_y are set
        type(growth_column), intent(inout) :: column
        real(wp) :: e_prime, r, direction, x, y
        integer :: k, side, i

        allocate (column%front_x(0), column%front_y(0), column%end_x(0), column%end_y(0))
        e_prime = 2.0_wp * medium%shear_modulus / (1.0_wp - medium%poissons_ratio)
        associate (e => medium%elements)
            do k = 1, size(fracture_grows)
                if (.not. fracture_grows(k)) cycle
                do side = 1, 2
                    if (side == 1) then
                        i = medium_fracture_first(k)
                        x = e%x_begin(i)
                        y = e%y_begin(i)
                    else
                        i = medium_fracture_last(k)
                        x = e%x_end(i)
                        y = e%y_end(i)
                    end if
                    column%end_x = [column%end_x, x]
                    column%end_y = [column%end_y, y]
                    if ((side == 1 .and. any(begin_grows == k)) .or. &
                        (side == 2 .and. any(end_grows == k))) then
                        r = front_distance(-dn(i), toughness, e_prime, viscosity, &
                                           front_velocity(e%half_length(i), elapsed, advancing))
                        ! From the midpoint toward the end (side 2: the element's direction).
                        direction = merge(1.0_wp, -1.0_wp, side == 2)
                        x = e%x_mid(i) + direction * r * e%cos_beta(i)
                        y = e%y_mid(i) + direction * r * e%sin_beta(i)
                    end if
                    column%front_x = [column%front_x, x]
                    column%front_y = [column%front_y, y]
                end do
            end do
        end associate

    contains

        !> The first and last element of fracture k (its elements are consecutive).
        pure integer function medium_fracture_first(fracture)
            integer, intent(in) :: fracture

            medium_fracture_first = findloc(medium%elements%fracture_id, fracture, 1)
        end function medium_fracture_first

        pure integer function medium_fracture_last(fracture)
            integer, intent(in) :: fracture

            medium_fracture_last = findloc(medium%elements%fracture_id, fracture, 1, &
                                           back=.true.)
        end function medium_fracture_last
    end subroutine locate_fronts

    !> How fast a front moved on over a step of the time elapsed: by the length of its tip
    !> element, which is new when the fronts advanced (the front keeps its place beyond
    !> the tip element's end); 0 at the first step.
    pure real(wp) function front_velocity(half_length, elapsed, advancing)
        real(wp), intent(in) :: half_length, elapsed
        logical, intent(in) :: advancing

        front_velocity = 0.0_wp
        if (advancing) front_velocity = 2.0_wp * half_length / elapsed
    end function front_velocity

    !> The fractures whose ends grow: their first element grows at its beginning, their last
    !> at its end (fractures &growth names; all without the list).
    subroutine growing_ends(model, begin_grows, end_grows)
        type(model_type), intent(in) :: model
        integer, allocatable, intent(out) :: begin_grows(:), end_grows(:)
        integer :: k
        logical :: grows(size(model%fractures))

        grows = .true.
        if (allocated(model%growth%fracture_grows)) grows = model%growth%fracture_grows
        begin_grows = pack([(k, k = 1, size(model%fractures))], grows)
        end_grows = begin_grows
    end subroutine growing_ends

    !> One element straight ahead of each growing end, of the tip element's length; origin
    !> is the element before of each element (0: new). A new element that would cross
    !> another fracture ends on it, and that end grows no more: the fluid enters the other
    !> fracture there where it conducts (an end on an element's interior connects them).
    subroutine grow_ends(model, begin_grows, end_grows, origin)
        type(model_type), intent(inout) :: model
        integer, allocatable, intent(inout) :: begin_grows(:), end_grows(:)
        integer, allocatable, intent(out) :: origin(:)
        type(element_set) :: grown
        integer, allocatable :: pick(:)
        integer :: k, first, last, i, m
        logical :: stopped

        allocate (pick(0), origin(0))
        do k = 1, size(model%fractures)
            first = model%fractures(k)%first_element
            last = model%fractures(k)%last_element
            if (any(begin_grows == k)) then
                pick = [pick, first]
                origin = [origin, 0]
            end if
            pick = [pick, [(i, i = first, last)]]
            origin = [origin, [(i, i = first, last)]]
            if (any(end_grows == k)) then
                pick = [pick, last]
                origin = [origin, 0]
            end if
        end do
        call select_elements(model%elements, pick, grown)
        m = 0
        do k = 1, size(model%fractures)
            first = model%fractures(k)%first_element
            last = model%fractures(k)%last_element
            model%fractures(k)%first_element = m + 1
            if (any(begin_grows == k)) then
                m = m + 1
                grown%x_end(m) = model%elements%x_begin(first)
                grown%y_end(m) = model%elements%y_begin(first)
                call ahead(first, -1.0_wp, grown%x_end(m), grown%y_end(m), grown%x_begin(m), &
                           grown%y_begin(m))
                if (stopped) begin_grows = pack(begin_grows, begin_grows /= k)
            end if
            m = m + last - first + 1
            if (any(end_grows == k)) then
                m = m + 1
                grown%x_begin(m) = model%elements%x_end(last)
                grown%y_begin(m) = model%elements%y_end(last)
                call ahead(last, 1.0_wp, grown%x_begin(m), grown%y_begin(m), grown%x_end(m), &
                           grown%y_end(m))
                if (stopped) end_grows = pack(end_grows, end_grows /= k)
            end if
            model%fractures(k)%last_element = m
        end do
        call compute_geometry(grown)
        model%elements = grown

    contains

        !> The far end (x1, y1) of the new element from the end (x0, y0) of tip element i, as
        !> long as it and along it (direction 1) or against it (-1); stopped where it meets
        !> another fracture.
        subroutine ahead(i, direction, x0, y0, x1, y1)
            integer, intent(in) :: i
            real(wp), intent(in) :: direction, x0, y0
            real(wp), intent(out) :: x1, y1

            associate (e => model%elements)
                x1 = x0 + direction * (e%x_end(i) - e%x_begin(i))
                y1 = y0 + direction * (e%y_end(i) - e%y_begin(i))
            end associate
            call stop_at_fractures(model, k, x0, y0, x1, y1, stopped)
        end subroutine ahead
    end subroutine grow_ends

    !> A new element from (x0, y0) to (x1, y1) of fracture k that would cross or reach an
    !> element of another fracture ends on the first it meets instead.
    pure subroutine stop_at_fractures(model, k, x0, y0, x1, y1, stopped)
        type(model_type), intent(in) :: model
        integer, intent(in) :: k
        real(wp), intent(in) :: x0, y0
        real(wp), intent(inout) :: x1, y1
        logical, intent(out) :: stopped
        real(wp) :: nearest, fraction, tolerance
        integer :: j, kind

        nearest = 1.0_wp
        tolerance = 1.0e-8_wp * hypot(x1 - x0, y1 - y0)
        associate (e => model%elements)
            do j = 1, e%n
                if (e%fracture_id(j) == k) cycle
                if (far_apart(x0, y0, x1, y1, e%x_begin(j), e%y_begin(j), e%x_end(j), &
                              e%y_end(j), tolerance)) cycle
                kind = classify_pair(x0, y0, x1, y1, e%x_begin(j), e%y_begin(j), e%x_end(j), &
                                     e%y_end(j), tolerance)
                if (kind /= pair_cross .and. kind /= pair_t_first_end) cycle
                fraction = crossing_fraction(x0, y0, x1, y1, e%x_begin(j), e%y_begin(j), &
                                             e%x_end(j), e%y_end(j))
                nearest = min(nearest, fraction)
            end do
        end associate
        stopped = nearest < 1.0_wp .or. any_end_on_other()
        x1 = x0 + nearest * (x1 - x0)
        y1 = y0 + nearest * (y1 - y0)

    contains

        !> The new element's far end lies on another fracture (pair_t_first_end at 1).
        pure logical function any_end_on_other()
            integer :: i

            any_end_on_other = .false.
            associate (e => model%elements)
                do i = 1, e%n
                    if (e%fracture_id(i) == k) cycle
                    if (point_segment_distance(x1, y1, e%x_begin(i), e%y_begin(i), &
                                               e%x_end(i), e%y_end(i)) <= tolerance) then
                        any_end_on_other = .true.
                    end if
                end do
            end associate
        end function any_end_on_other
    end subroutine stop_at_fractures

    !> Values of the elements before on the grown geometry (0 on new elements).
    pure function carried(values, origin) result(grown)
        real(wp), intent(in) :: values(:)
        integer, intent(in) :: origin(:)
        real(wp) :: grown(size(origin))

        grown = 0.0_wp
        where (origin > 0) grown = values(max(origin, 1))
    end function carried

    !> Where each element before went (its index on the grown geometry).
    pure function position_of(before, origin) result(after)
        integer, intent(in) :: before(:), origin(:)
        integer :: after(size(before)), where_now(maxval(origin)), i

        where_now = 0
        do i = 1, size(origin)
            if (origin(i) > 0) where_now(origin(i)) = i
        end do
        after = where_now(before)
    end function position_of

    !> /history of the steps on the final geometry's rows (NaN and state_not_grown before an
    !> element was made), K of the growing tips.
    subroutine history_of(columns, model, load, final_tips, growing_fracture, growing_end, h)
        type(growth_column), intent(in) :: columns(:)
        type(model_type), intent(in) :: model
        !> The load of the path's first vertex (the growth's)
        real(wp), intent(in) :: load(:)
        !> The final geometry's tips: the rows of K (NaN where a step's geometry had no such
        !> tip)
        type(tip_set), intent(in) :: final_tips
        !> The fracture and end (0 begin, 1 end) of each end of a growing fracture, shape
        !> (growing ends)
        integer, intent(in) :: growing_fracture(:), growing_end(:)
        type(history_record), intent(out) :: h
        integer :: n, steps, k, stat, tips, row, j
        real(wp) :: nan

        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        n = model%elements%n
        steps = size(columns)
        call lay_out_history(h, n, final_tips%n, steps, 0, stat, growth=.true., &
                             time=.true., fractures=size(model%fractures), coupled=.true.)
        tips = size(columns(1)%front_x)
        allocate (h%grown_length(tips, steps))
        h%tip_fracture_id = growing_fracture
        h%tip_end = growing_end
        h%ds = nan
        h%dn = nan
        h%state = state_not_grown
        h%pressure = nan
        h%aperture = nan
        h%flux = nan
        h%k1 = nan
        h%k2 = nan
        do k = 1, steps
            associate (c => columns(k), f => columns(k)%final)
                h%time(k) = c%time
                h%load(:, k) = load
                h%ds(f, k) = c%ds
                h%dn(f, k) = c%dn
                h%state(f, k) = c%state
                h%pressure(f, k) = c%pressure
                h%aperture(f, k) = c%aperture
                h%flux(f, k) = c%flux
                do row = 1, final_tips%n
                    do j = 1, size(c%k1)
                        if (c%tip_fracture(j) /= final_tips%fracture_id(row) .or. &
                            c%tip_side(j) /= final_tips%side(row)) cycle
                        h%k1(row, k) = c%k1(j)
                        h%k2(row, k) = c%k2(j)
                    end do
                end do
                h%injected_volume(k) = c%injected
                h%stored_volume(k) = c%stored
                h%leaked_volume(k) = c%leaked
                h%fluid_efficiency(k) = 0.0_wp
                if (c%injected /= 0.0_wp) h%fluid_efficiency(k) = c%stored / c%injected
                h%flow_iterations(k) = c%iterations
                h%flow_residual(k) = c%unbalanced
                h%element_count(k) = c%elements
                ! From the fracture's end as given to the front, straight ahead.
                h%grown_length(:, k) = hypot(c%front_x - columns(1)%end_x, &
                                             c%front_y - columns(1)%end_y)
            end associate
        end do
    end subroutine history_of

end module ddc_history_fluid_growth
