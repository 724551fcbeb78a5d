!> The local-symmetry corrector (docs/theory/growth.md#the-local-symmetry-corrector). The MTS angle
!> from the tip element's K is only the predictor: with constant elements the K_II of a freshly
!> kinked tip element is inaccurate, and kinking by each step's MTS angle over-corrects the last
!> (wings zig-zag and never arrest). The applied angle is corrected until the new tip has
!> |K_II| <= tolerance (principle of local symmetry): secant iterations on K_II(theta), all
!> growing tips corrected together, one solve of the whole model per iteration.
!> A tip grows only as an opening-mode crack (docs/theory/growth.md#closed-kinks): when even its
!> shortest kink is closed (K_I = 0 on the new tip) it does not grow in this step (reason
!> growth_closed); when a corrected trial closes, the angle goes back halfway to the last
!> open trial (the secant may overshoot into a closing kink; giving up there would stop
!> the tip at a corrector artefact). A kink whose new tip is not critical is shortened to
!> the tip's stable length (docs/theory/growth.md#shorter-kinks). A tip not converged within
!> the solve budget grows at its MTS angle (reason growth_corrector_failed; that trial was
!> open). A corrected path that meets another fracture links (ddc_growth_clearance, reason
!> growth_linked), one that reaches the free surface breaks through it (reason
!> growth_surface); every later trial of the step holds the step's links, so the other tips
!> are corrected against the linked network.
module ddc_growth_corrector
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_error, only: error_type
    use ddc_model_types, only: model_type, growth_options, condition_contact
    use ddc_model_results, only: model_results, state_open, growth_grew, &
        growth_corrector_failed, growth_closed
    use ddc_growth_solver, only: growth_solver, solve_grown
    use ddc_growth_extension, only: tip_path, extend_model, element_split
    use ddc_growth_clearance, only: check_paths, path_clear, tip_link, link_parts, ends_on_link
    use ddc_growth_tips, only: fracture_tip
    use ddc_growth_mts, only: kink_slope
    use ddc_growth_kinks, only: kink, step_kinks, kink_path, step_links
    use ddc_text, only: itoa
    implicit none
    private

    public :: correct_kinks

    !> Largest change of the angle in one corrector iteration [rad] (15 degrees), and
    !> largest distance of the corrected angle from the MTS angle [rad] (45 degrees)
    real(wp), parameter :: max_step = pi / 12.0_wp, max_deviation = pi / 4.0_wp
    !> Halvings of the angle towards straight ahead when an open tip's kink at its MTS
    !> angle closes
    integer, parameter :: max_halvings = 4
    !> The corrector stops when the new tip's |K_II| <= corrector_tolerance
    !> max(K_eq, toughness)
    real(wp), parameter :: corrector_tolerance = 1.0e-3_wp
    !> The shortest kink, as a fraction of the length of the tip's new elements: a critical
    !> tip whose kinks are closed down to this length is closed
    real(wp), parameter :: min_kink_fraction = 1.0_wp / 64.0_wp
    !> Relative tolerance on kink lengths (halved lengths compared with the shortest)
    real(wp), parameter :: length_tolerance = 1.0e-9_wp
    !> The length search ends at an open kink whose new tip's K_I is within this fraction
    !> below the toughness (the tip then stops just past its stable length)
    real(wp), parameter :: stable_tolerance = 1.0e-3_wp

    !> The corrector's iteration on one kink (the kink holds its angle and reason).
    type :: secant
        !> The slope dK_II/dtheta to start the secant with [stress unit * length unit**0.5
        !> / rad] (positive), and the tolerance on the new tip's |K_II| [stress unit *
        !> length unit**0.5]
        real(wp) :: slope = 1.0_wp, tolerance = 0.0_wp
        !> The tip still grows (its path keeps clear), its angle is still corrected; the
        !> previous point of the secant exists; the last trial's new tip was open
        logical :: active = .true., correcting = .true., have_prev = .false., open = .true.
        !> K_I and K_II of its new tip at the current angle, and the previous point of the
        !> secant (angle [rad], K_II) [stress unit * length unit**0.5]
        real(wp) :: k1 = 0.0_wp, k2 = 0.0_wp, theta_prev = 0.0_wp, k2_prev = 0.0_wp
        !> The tip is open before growing (K_I > 0); its kink closed at the MTS angle, and
        !> how often the angle was halved since
        logical :: tip_open = .false., mts_closed = .false.
        integer :: halvings = 0
    end type secant

    !> The search of a kink's length between the longest kink known critical and the shortest
    !> known not to be (docs/theory/growth.md#shorter-kinks): Illinois regula falsi on
    !> K_I - K_Ic against sqrt(length) while the longer end is open, bisection while it is
    !> closed.
    type :: length_search
        !> The longest kink whose new tip is critical (0: none), K_I - K_Ic there
        !> [stress unit * length unit**0.5] (at 0 the infinitesimal kink's K_eq - K_Ic) and its
        !> corrected angle [rad]
        real(wp) :: lo = 0.0_wp, f_lo = 0.0_wp, theta_lo = 0.0_wp
        !> The shortest kink whose new tip is not critical (huge: none), K_I - K_Ic there and
        !> its angle; whether that kink is open (else closed, f_hi not used)
        real(wp) :: hi = huge(1.0_wp), f_hi = 0.0_wp, theta_hi = 0.0_wp
        logical :: hi_open = .false.
        !> The end the last trial replaced (-1 lo, 1 hi, 0 none): Illinois halves the other
        !> end's value when one end is replaced twice running with both ends open
        integer :: side = 0
        !> The search has ended: the kink keeps its length in the step's later rounds
        logical :: done = .false.
    end type length_search

contains

    !> Correct the kink angles of the step's growing tips (their predictor paths, at the MTS
    !> angles, must keep clear: check_paths). On return each kink has its applied angle,
    !> reason and solves (a corrected path that would not keep clear stops the tip). When
    !> kinks%current is true, kinks%trial (with trial_created, origin) and kinks%solved are
    !> the model grown at the applied angles and its solution; otherwise the grown model is
    !> still to be built and solved (grow_paths). Every trial holds the links of kinks%fixed.
    subroutine correct_kinks(solver, model, created, options, kinks, error)
        !> The solves of the run (the base: model)
        type(growth_solver), intent(inout) :: solver
        !> The model before growing (without observations)
        type(model_type), intent(in) :: model
        !> Growth step that created each element of model, shape (n)
        integer, intent(in) :: created(:)
        !> Growth options (toughness, max_corrections, new_mu, new_sf)
        type(growth_options), intent(in) :: options
        !> The step's kinks: the growing tips and the links made before in; their angles,
        !> reasons, solves and links, and the last trial solved out
        type(step_kinks), intent(inout) :: kinks
        !> Set when a solve fails
        type(error_type), allocatable, intent(out) :: error
        type(secant) :: iteration(size(kinks%tip))
        type(length_search) :: search(size(kinks%tip))
        type(tip_path) :: paths(size(kinks%tip))
        logical :: searching, moved
        integer :: i

        call start_kinks(kinks%tip, options%toughness, iteration)
        kinks%current = .false.
        if (options%max_corrections == 0) return
        do i = 1, size(kinks%tip)
            associate (k => kinks%tip(i))
                if (k%first_length > 0.0_wp) then
                    k%length = k%first_length
                    k%pieces = max(1, nint(k%length / k%element_length))
                end if
            end associate
            paths(i) = kink_path(model, kinks%tip(i))
            search(i)%f_lo = kinks%tip(i)%k_eq - options%toughness
        end do
        do
            call correct_round(solver, model, created, options, kinks, iteration, paths, error)
            if (allocated(error)) return
            call search_lengths(kinks%tip, iteration, search, options%toughness, searching, &
                                moved)
            if (searching .or. moved) kinks%current = .false.
            if (.not. (searching .or. moved)) exit
            call update_paths(model, kinks, iteration, paths)
            if (.not. searching) exit
        end do
        call open_above_toughness(kinks, options%toughness)
    end subroutine correct_kinks

    !> A tip whose K_I is at or above the toughness is never closed: where even its shortest
    !> kink closed (the compression across an element that short still beats the tip's
    !> tension), it grows by that kink at its MTS angle (growth_corrector_failed); the grown
    !> model is then still to be built.
    pure subroutine open_above_toughness(kinks, toughness)
        !> The step's kinks
        type(step_kinks), intent(inout) :: kinks
        !> Fracture toughness [stress unit * length unit**0.5]
        real(wp), intent(in) :: toughness
        integer :: i

        do i = 1, size(kinks%tip)
            associate (k => kinks%tip(i))
                if (k%reason /= growth_closed .or. k%k1 < toughness) cycle
                k%reason = growth_corrector_failed
                k%theta = k%theta_predictor
                kinks%current = .false.
            end associate
        end do
    end subroutine open_above_toughness

    !> One round of corrections at the kinks' current lengths: secant iterations of the
    !> kinks still corrected, all tips' trials solved together, at most max_corrections
    !> solves; then those not converged give up.
    subroutine correct_round(solver, model, created, options, kinks, iteration, paths, error)
        !> The solves of the run (the base: model)
        type(growth_solver), intent(inout) :: solver
        !> The model before growing (without observations)
        type(model_type), intent(in) :: model
        !> Growth step that created each element of model, shape (n)
        integer, intent(in) :: created(:)
        !> Growth options (max_corrections, new_mu, new_sf)
        type(growth_options), intent(in) :: options
        !> The step's kinks
        type(step_kinks), intent(inout) :: kinks
        !> Their iteration, shape (size(kinks%tip))
        type(secant), intent(inout) :: iteration(:)
        !> Their paths at the current angles and lengths, shape (size(kinks%tip))
        type(tip_path), intent(inout) :: paths(:)
        !> Set when a solve fails
        type(error_type), allocatable, intent(out) :: error
        type(tip_path), allocatable :: trial_paths(:)
        type(element_split), allocatable :: splits(:)
        logical :: changed
        integer :: solves

        solves = 0
        changed = .true.
        do while (solves < options%max_corrections)
            call trial_parts(kinks, iteration, paths, trial_paths, splits)
            call extend_model(model, created, trial_paths, kinks%step, options, kinks%trial, &
                              kinks%trial_created, kinks%moved_to, splits, kinks%origin)
            call solve_grown(solver, kinks%trial, kinks%moved_to, kinks%solved, error, &
                             kinks%origin)
            solves = solves + 1
            if (allocated(error)) then
                error%message = 'growth step '//itoa(kinks%step)//', corrector solve '// &
                                itoa(solves)//': '//error%message
                return
            end if
            call judge_trial(kinks, iteration, changed, error)
            if (allocated(error)) return
            if (.not. changed) exit
            ! Every tip closed or stopped: no trial is left to solve.
            if (.not. any(iteration%active)) return
            call update_paths(model, kinks, iteration, paths)
        end do
        kinks%current = .not. changed
        if (kinks%current) return
        call give_up(kinks%tip, iteration)
        call update_paths(model, kinks, iteration, paths)
    end subroutine correct_round

    !> The next round's kink lengths (docs/theory/growth.md#shorter-kinks). A kink whose new
    !> tip is critical at the increment is taken; otherwise its length is searched between
    !> the longest kink known critical and the shortest known not to be, down to
    !> min_kink_fraction of its new elements' length, and the tip grows by the kink that ends
    !> the search: the open one just past the stable length (K_I of its new tip within
    !> stable_tolerance below the toughness, or the bracket shorter than the shortest kink),
    !> else the longest critical one, else nothing (closed). The kinks not searched keep
    !> their angles and are no longer corrected. `searching`: some kink takes a new length and
    !> is corrected again from its MTS angle; `moved`: some kink went back to a length solved
    !> before.
    subroutine search_lengths(tips, iteration, search, toughness, searching, moved)
        !> The step's growing tips
        type(kink), intent(inout) :: tips(:)
        !> Their iteration, shape (size(tips))
        type(secant), intent(inout) :: iteration(:)
        !> Their length searches, shape (size(tips))
        type(length_search), intent(inout) :: search(:)
        !> Fracture toughness [stress unit * length unit**0.5]
        real(wp), intent(in) :: toughness
        logical, intent(out) :: searching, moved
        logical :: again(size(tips))
        integer :: i

        again = .false.
        moved = .false.
        do i = 1, size(tips)
            associate (k => tips(i), s => iteration(i), b => search(i))
                ! An ended search was not tried again: its last values are not new.
                if (b%done) cycle
                b%done = .true.
                if (k%reason == growth_closed) then
                    call replace_hi(b, k%length, .false., 0.0_wp, k%theta)
                else if (.not. s%active .or. k%reason == growth_corrector_failed) then
                    ! Stopped by its path (a link, the surface, another fracture), or not
                    ! corrected within the solves: it grows at its MTS angle at this length.
                    cycle
                else if (s%k1 >= toughness) then
                    if (k%length >= (1.0_wp - length_tolerance) * k%full_length) cycle
                    call replace_lo(b, k%length, s%k1 - toughness, k%theta)
                else
                    call replace_hi(b, k%length, .true., s%k1 - toughness, k%theta)
                    if (s%k1 >= (1.0_wp - stable_tolerance) * toughness) cycle
                end if
                if (b%hi - b%lo > min_kink_fraction * k%element_length * &
                    (1.0_wp + length_tolerance)) then
                    k%length = max(next_length(b, k%full_length), shortest_kink(k))
                    k%pieces = max(1, nint(k%length / k%element_length))
                    again(i) = .true.
                    b%done = .false.
                else if (b%hi_open) then
                    call take_kink(k, b%hi, b%theta_hi, moved)
                    s%active = .true.  ! its kink is part of every later trial
                else if (b%lo > 0.0_wp) then
                    call take_kink(k, b%lo, b%theta_lo, moved)
                    s%active = .true.
                else
                    k%reason = growth_closed
                end if
            end associate
        end do
        searching = any(again)
        do i = 1, size(tips)
            if (again(i)) then
                call start_kinks(tips(i:i), toughness, iteration(i:i))
            else
                iteration(i)%correcting = .false.
            end if
        end do
    end subroutine search_lengths

    !> The next length to try: twice the critical one (at most the increment) while no kink
    !> is known not to be critical, halfway while the longer end is closed, else Illinois
    !> regula falsi on K_I - K_Ic against sqrt(length) (K_I of a short kink falls about as
    !> the square root of its length), kept a tenth of the bracket from its ends.
    pure real(wp) function next_length(b, full_length)
        !> The length search
        type(length_search), intent(in) :: b
        !> The increment [length unit]
        real(wp), intent(in) :: full_length
        real(wp) :: x_lo, x_hi, x

        if (b%hi > full_length) then
            next_length = min(full_length, 2.0_wp * b%lo)
            return
        end if
        if (.not. b%hi_open .or. b%f_lo <= b%f_hi) then
            next_length = 0.5_wp * (b%lo + b%hi)
            return
        end if
        x_lo = sqrt(b%lo)
        x_hi = sqrt(b%hi)
        x = x_lo + (x_hi - x_lo) * b%f_lo / (b%f_lo - b%f_hi)
        x = max(x_lo + 0.1_wp * (x_hi - x_lo), min(x_hi - 0.1_wp * (x_hi - x_lo), x))
        next_length = x**2
    end function next_length

    !> A critical kink: the new shorter end of the search.
    pure subroutine replace_lo(b, length, f, theta)
        type(length_search), intent(inout) :: b
        real(wp), intent(in) :: length, f, theta

        if (b%side == -1 .and. b%hi_open) b%f_hi = 0.5_wp * b%f_hi
        b%side = -1
        b%lo = length
        b%f_lo = f
        b%theta_lo = theta
    end subroutine replace_lo

    !> A kink that is closed or not critical: the new longer end of the search.
    pure subroutine replace_hi(b, length, open, f, theta)
        type(length_search), intent(inout) :: b
        real(wp), intent(in) :: length, f, theta
        logical, intent(in) :: open

        if (b%side == 1 .and. b%hi_open .and. open) b%f_lo = 0.5_wp * b%f_lo
        b%side = 1
        b%hi = length
        b%hi_open = open
        b%f_hi = f
        b%theta_hi = theta
    end subroutine replace_hi

    !> The search ends with the kink of this length and angle (moved: it is not the one
    !> solved last).
    pure subroutine take_kink(k, length, theta, moved)
        type(kink), intent(inout) :: k
        real(wp), intent(in) :: length, theta
        logical, intent(inout) :: moved

        if (abs(k%length - length) > length_tolerance * length .or. k%theta /= theta) then
            moved = .true.
        end if
        k%length = length
        k%pieces = max(1, nint(k%length / k%element_length))
        k%theta = theta
        k%reason = growth_grew
    end subroutine take_kink

    !> The kinks at their predictor (MTS) angles, growing, and the start of their iteration:
    !> the first-order slope dK_II/dtheta (K_eq when that is not clearly positive) and the
    !> tolerance.
    pure subroutine start_kinks(tips, toughness, iteration)
        !> The growing tips
        type(kink), intent(inout) :: tips(:)
        !> Fracture toughness [stress unit * length unit**0.5]
        real(wp), intent(in) :: toughness
        !> Their iteration, shape (size(tips))
        type(secant), intent(out) :: iteration(:)
        integer :: i

        do i = 1, size(tips)
            associate (k => tips(i), s => iteration(i))
                k%theta = k%theta_predictor
                k%reason = growth_grew
                k%solves = 0
                s%tip_open = k%k1 > 0.0_wp
                s%slope = kink_slope(k%k1, k%k2, k%theta_predictor)
                if (s%slope < 0.1_wp * k%k_eq) s%slope = k%k_eq
                s%tolerance = corrector_tolerance * max(k%k_eq, toughness)
            end associate
        end do
    end subroutine start_kinks

    !> The new elements of the next trial: the paths of the tips still growing, then the
    !> links' paths, and the links' splits.
    pure subroutine trial_parts(kinks, iteration, paths, trial_paths, splits)
        !> The step's kinks
        type(step_kinks), intent(in) :: kinks
        !> Their iteration, shape (size(kinks%tip))
        type(secant), intent(in) :: iteration(:)
        !> Their paths at the current angles, shape (size(kinks%tip))
        type(tip_path), intent(in) :: paths(:)
        !> The trial's paths
        type(tip_path), allocatable, intent(out) :: trial_paths(:)
        !> The links' splits
        type(element_split), allocatable, intent(out) :: splits(:)
        type(tip_path), allocatable :: link_paths(:)
        integer :: j

        call link_parts(step_links(kinks), link_paths, splits)
        allocate (trial_paths(0))
        do j = 1, size(kinks%tip)
            if (iteration(j)%active) trial_paths = [trial_paths, paths(j)]
        end do
        trial_paths = [trial_paths, link_paths]
    end subroutine trial_parts

    !> The next angle of each kink still corrected from its new tip in the trial solved:
    !> back halfway to the last open trial when a corrected trial closed, halved towards
    !> straight ahead when the kink at its MTS angle closed, given up (growth_closed) when
    !> that does not open it, a secant step when |K_II| is above the tolerance. `changed`
    !> when any angle or reason changed.
    subroutine judge_trial(kinks, iteration, changed, error)
        !> The step's kinks, with the trial solved
        type(step_kinks), intent(inout) :: kinks
        !> Their iteration, shape (size(kinks%tip))
        type(secant), intent(inout) :: iteration(:)
        !> Some kink's angle or reason changed
        logical, intent(out) :: changed
        !> Set when a new tip is not found (a broken contract)
        type(error_type), allocatable, intent(out) :: error
        logical :: closed
        integer :: i

        changed = .false.
        do i = 1, size(kinks%tip)
            associate (k => kinks%tip(i), s => iteration(i))
                if (.not. s%active) cycle
                k%solves = k%solves + 1
                if (.not. s%correcting) cycle
                call new_tip(kinks%trial, kinks%solved, k, s%k1, s%k2, closed, error)
                if (allocated(error)) return
                s%open = .not. closed
                if (closed .and. s%have_prev) then
                    ! A corrected trial closed: halve the way back to the last open trial.
                    k%theta = 0.5_wp * (k%theta + s%theta_prev)
                    changed = .true.
                else if (closed .and. s%tip_open .and. s%halvings < max_halvings .and. &
                         k%length <= (1.0_wp + 2.0_wp * length_tolerance) * &
                         shortest_kink(k)) then
                    ! An open tip whose shortest kink closes (the remote compression across
                    ! a finite kink beats the tip's tension): search the open angles nearer
                    ! straight ahead. A longer kink that closes is shortened first: a short
                    ! enough kink at the MTS angle opens (Cotterell & Rice).
                    s%mts_closed = .true.
                    s%halvings = s%halvings + 1
                    k%theta = 0.5_wp * k%theta
                    changed = .true.
                else if (closed) then
                    ! The kink at its MTS angle is closed: it does not grow
                    ! (docs/theory/growth.md#closed-kinks).
                    s%correcting = .false.
                    s%active = .false.
                    k%reason = growth_closed
                    changed = .true.
                else if (abs(s%k2) > s%tolerance) then
                    changed = .true.
                    call secant_angle(k, s)
                end if
            end associate
        end do
    end subroutine judge_trial

    !> Out of solves: the tips not converged (or closed at their last trial) grow at their
    !> MTS angle when its trial was open; otherwise local symmetry is not reached with the
    !> kink open, and the tip does not grow (docs/theory/growth.md#closed-kinks).
    pure subroutine give_up(tips, iteration)
        !> The growing tips
        type(kink), intent(inout) :: tips(:)
        !> Their iteration, shape (size(tips))
        type(secant), intent(inout) :: iteration(:)
        integer :: i

        do i = 1, size(tips)
            associate (k => tips(i), s => iteration(i))
                if (s%active .and. s%correcting .and. &
                    (.not. s%open .or. abs(s%k2) > s%tolerance)) then
                    if (s%mts_closed) then
                        s%active = .false.
                        k%reason = growth_closed
                    else
                        k%reason = growth_corrector_failed
                        k%theta = k%theta_predictor
                    end if
                end if
            end associate
        end do
    end subroutine give_up

    !> Paths at the current angles; those that do not keep clear stop their tips, those
    !> that meet another fracture link.
    subroutine update_paths(model, kinks, iteration, paths)
        !> The model before growing
        type(model_type), intent(in) :: model
        !> The step's kinks
        type(step_kinks), intent(inout) :: kinks
        !> Their iteration, shape (size(kinks%tip))
        type(secant), intent(inout) :: iteration(:)
        !> Their paths, shape (size(kinks%tip))
        type(tip_path), intent(inout) :: paths(:)
        type(tip_link) :: links(size(paths))
        integer :: i, problem(size(paths))
        logical :: active(size(paths))

        do i = 1, size(kinks%tip)
            if (iteration(i)%active) paths(i) = kink_path(model, kinks%tip(i))
        end do
        active = iteration%active  ! a strided component: copied here, not as a temporary
        call check_paths(model, paths, active, problem, links, step_links(kinks))
        do i = 1, size(kinks%tip)
            if (problem(i) /= path_clear) then
                iteration(i)%active = .false.
                kinks%tip(i)%reason = problem(i)
            end if
            if (ends_on_link(problem(i))) kinks%tip(i)%link = links(i)
        end do
    end subroutine update_paths

    !> The shortest kink a length search tries [length unit]: min_kink_fraction of the tip's
    !> new elements' length (less a rounding tolerance).
    pure real(wp) function shortest_kink(k)
        !> The kink
        type(kink), intent(in) :: k

        shortest_kink = min_kink_fraction * k%element_length * (1.0_wp - length_tolerance)
    end function shortest_kink

    !> K_I and K_II of a kink's new tip in the grown model, and whether that tip is closed (a
    !> contact element that is not open, or another condition with K_I <= 0).
    subroutine new_tip(grown, solved, k, k1, k2, closed, error)
        !> The grown model and its solution
        type(model_type), intent(in) :: grown
        type(model_results), intent(in) :: solved
        !> The kink
        type(kink), intent(in) :: k
        !> K_I and K_II of its new tip [stress unit * length unit**0.5]
        real(wp), intent(out) :: k1, k2
        !> The new tip is closed
        logical, intent(out) :: closed
        !> Set when the new tip is not a tip of the solution
        type(error_type), allocatable, intent(out) :: error
        integer :: e, t

        k1 = 0.0_wp
        k2 = 0.0_wp
        closed = .false.
        call fracture_tip(grown, solved%tips, k%fracture, k%end, t, error)
        if (allocated(error)) return
        e = solved%tips%element(t)
        k1 = solved%tips%k1(t)
        k2 = solved%tips%k2(t)
        if (grown%elements%condition(e) == condition_contact) then
            closed = solved%elements%state(e) /= state_open
        else
            closed = solved%tips%k1(t) <= 0.0_wp
        end if
    end subroutine new_tip

    !> The next angle of a secant iteration on K_II(theta) = 0 from the kink's K_II at its
    !> current angle (the first step, and any step where the secant slope is not positive,
    !> uses the kink's slope): at most max_step from the last angle and max_deviation from
    !> the MTS angle. The current point becomes the previous one.
    pure subroutine secant_angle(k, s)
        !> The kink; its angle is updated
        type(kink), intent(inout) :: k
        !> Its iteration; the previous point is updated
        type(secant), intent(inout) :: s
        real(wp) :: slope, step

        slope = s%slope
        if (s%have_prev) then
            if (k%theta /= s%theta_prev) then
                if ((s%k2 - s%k2_prev) / (k%theta - s%theta_prev) > 0.0_wp) then
                    slope = (s%k2 - s%k2_prev) / (k%theta - s%theta_prev)
                end if
            end if
        end if
        s%have_prev = .true.
        s%theta_prev = k%theta
        s%k2_prev = s%k2
        step = max(-max_step, min(max_step, -s%k2 / slope))
        k%theta = max(k%theta_predictor - max_deviation, min(k%theta_predictor + &
                                                               max_deviation, k%theta + step))
    end subroutine secant_angle

end module ddc_growth_corrector
