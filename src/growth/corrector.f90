!> The local-symmetry corrector (SPEC-GROWTH 1.4). The MTS angle from the tip element's K
!> is only the predictor: with constant elements the K_II of a freshly kinked tip element
!> is inaccurate, and kinking by each step's MTS angle over-corrects the last (wings
!> zig-zag and never arrest). The applied angle is corrected until the new tip has
!> |K_II| <= tolerance (principle of local symmetry): secant iterations on K_II(theta), all
!> growing tips corrected together, one solve of the whole model per iteration.
!> A tip grows only as an opening-mode crack (SPEC-GROWTH 1.4): when the kink at its MTS
!> angle is closed (K_I = 0 on the new tip) it does not grow in this step (reason
!> growth_closed); when a corrected trial closes, the angle goes back halfway to the last
!> open trial (the secant may overshoot into a closing kink; giving up there would stop
!> the tip at a corrector artefact). A tip not converged within the solve budget grows at
!> its MTS angle (reason growth_corrector_failed; that trial was open). A corrected path
!> that meets another fracture links (ddc_growth_clearance, reason growth_linked); every
!> later trial of the step holds the step's links, so the other tips are corrected against
!> the linked network.
module ddc_growth_corrector
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_error, only: error_type
    use ddc_model_types, only: model_type, growth_options, condition_contact
    use ddc_model_results, only: model_results, state_open, growth_grew, &
        growth_corrector_failed, growth_closed, growth_linked
    use ddc_growth_solver, only: growth_solver, solve_grown
    use ddc_growth_extension, only: tip_path, make_path, extend_model, element_split
    use ddc_growth_clearance, only: check_paths, path_clear, tip_link, link_parts
    use ddc_growth_tips, only: fracture_tip
    use ddc_text, only: itoa
    implicit none
    private

    public :: kink, correct_kinks, grow_paths

    !> Largest change of the angle in one corrector iteration [rad] (15 degrees), and
    !> largest distance of the corrected angle from the MTS angle [rad] (45 degrees)
    real(wp), parameter :: max_step = pi / 12.0_wp, max_deviation = pi / 4.0_wp
    !> Halvings of the angle towards straight ahead when an open tip's kink at its MTS
    !> angle closes
    integer, parameter :: max_halvings = 4

    !> One growing tip as the corrector sees it.
    type :: kink
        !> Fracture (1-based) and end (tip_end_begin, tip_end_end) of the tip
        integer :: fracture = 0, end = 0
        !> MTS angle [rad], the slope dK_II/dtheta to start the secant with
        !> [stress unit * length unit**0.5 / rad] (positive), and the tolerance on the new
        !> tip's |K_II| [stress unit * length unit**0.5]
        real(wp) :: theta_mts = 0.0_wp, slope = 1.0_wp, tolerance = 0.0_wp
        !> Length of the increment [length unit] and its number of elements
        real(wp) :: length = 0.0_wp
        integer :: pieces = 1
        !> The applied angle [rad] (out)
        real(wp) :: theta = 0.0_wp
        !> Solves this tip took part in (out)
        integer :: solves = 0
        !> growth_grew, growth_corrector_failed, growth_intersection, growth_surface,
        !> growth_linked or growth_closed (out)
        integer :: reason = growth_grew
        !> The link of a tip that linked (out)
        type(tip_link) :: link
        !> The corrector's iteration: the tip still grows (its path keeps clear), its angle
        !> is still corrected; K_II of its new tip at the current angle, and the previous
        !> point of the secant (angle [rad], K_II) once there is one
        !> [stress unit * length unit**0.5]; whether the last trial's new tip was open
        logical :: active = .true., correcting = .true., have_prev = .false., open = .true.
        real(wp) :: k2 = 0.0_wp, theta_prev = 0.0_wp, k2_prev = 0.0_wp
        !> The tip is open before growing (K_I > 0) (in); its kink closed at the MTS angle,
        !> and how often the angle was halved since
        logical :: tip_open = .false., mts_closed = .false.
        integer :: halvings = 0
    end type kink

contains

    !> Correct the kink angles of the growing tips of `model`; their predictor paths (at
    !> the MTS angles) must keep clear (check_paths). On return each kink has its applied
    !> angle and reason (a corrected path that would not keep clear stops the tip). When
    !> `current` is true, `trial` (with `trial_created`) and `solved` are the model grown
    !> at the applied angles and its solution; otherwise the grown model is still to be
    !> built and solved (grow_paths). `fixed` are the links of tips that linked before the
    !> corrector (at their MTS angle): every trial holds them.
    subroutine correct_kinks(solver, model, created, options, step, kinks, fixed, trial, &
                             trial_created, solved, current, error, trial_origin)
        !> The solves of the run (the base: model)
        type(growth_solver), intent(inout) :: solver
        !> The model before growing (without observations)
        type(model_type), intent(in) :: model
        !> Growth step that created each element of model, shape (n)
        integer, intent(in) :: created(:)
        !> Growth options (max_corrections, new_mu, new_sf)
        type(growth_options), intent(in) :: options
        !> The growth step
        integer, intent(in) :: step
        !> The growing tips
        type(kink), intent(inout) :: kinks(:)
        !> The step's links made before
        type(tip_link), intent(in) :: fixed(:)
        !> The last model solved, and the step that created each of its elements
        type(model_type), intent(out) :: trial
        integer, allocatable, intent(out) :: trial_created(:)
        !> Its solution
        type(model_results), intent(out) :: solved
        !> trial and solved are the model grown at the applied angles
        logical, intent(out) :: current
        !> Set when a solve fails
        type(error_type), allocatable, intent(out) :: error
        !> The element of model each element of trial comes from (0: new), shape (trial n)
        integer, allocatable, intent(out) :: trial_origin(:)
        type(tip_path) :: paths(size(kinks))
        type(tip_path), allocatable :: trial_paths(:)
        type(element_split), allocatable :: splits(:)
        type(tip_link) :: links(size(kinks))
        logical :: changed, closed
        integer :: i, solves, problem(size(kinks))
        logical :: active(size(kinks))
        integer, allocatable :: moved_to(:)

        kinks%theta = kinks%theta_mts
        kinks%reason = growth_grew
        kinks%solves = 0
        kinks%active = .true.
        kinks%correcting = .true.
        kinks%have_prev = .false.
        kinks%open = .true.
        kinks%mts_closed = .false.
        kinks%halvings = 0
        current = .false.
        if (options%max_corrections == 0) return
        do i = 1, size(kinks)
            paths(i) = path_of(kinks(i))
        end do
        solves = 0
        changed = .true.
        do while (solves < options%max_corrections)
            call trial_parts()
            call extend_model(model, created, trial_paths, step, options, trial, &
                              trial_created, moved_to, splits, trial_origin)
            call solve_grown(solver, trial, moved_to, solved, error, trial_origin)
            solves = solves + 1
            if (allocated(error)) then
                error%message = 'growth step '//itoa(step)//', corrector solve '// &
                                itoa(solves)//': '//error%message
                return
            end if
            changed = .false.
            do i = 1, size(kinks)
                if (.not. kinks(i)%active) cycle
                kinks(i)%solves = kinks(i)%solves + 1
                if (.not. kinks(i)%correcting) cycle
                call new_tip(trial, solved, kinks(i), closed, error)
                if (allocated(error)) return
                kinks(i)%open = .not. closed
                if (closed .and. kinks(i)%have_prev) then
                    ! A corrected trial closed: halve the way back to the last open trial.
                    kinks(i)%theta = 0.5_wp * (kinks(i)%theta + kinks(i)%theta_prev)
                    changed = .true.
                else if (closed .and. kinks(i)%tip_open .and. kinks(i)%halvings < &
                         max_halvings) then
                    ! An open tip whose kink closes (the remote compression across a finite
                    ! kink beats the tip's tension): search the open angles nearer straight
                    ! ahead for local symmetry.
                    kinks(i)%mts_closed = .true.
                    kinks(i)%halvings = kinks(i)%halvings + 1
                    kinks(i)%theta = 0.5_wp * kinks(i)%theta
                    changed = .true.
                else if (closed) then
                    ! The kink at its MTS angle is closed: it does not grow (SPEC-GROWTH 1.4).
                    kinks(i)%correcting = .false.
                    kinks(i)%active = .false.
                    kinks(i)%reason = growth_closed
                    changed = .true.
                else if (abs(kinks(i)%k2) > kinks(i)%tolerance) then
                    changed = .true.
                    call secant_angle(kinks(i))
                end if
            end do
            if (.not. changed) exit
            ! Every tip closed or stopped: no trial is left to solve.
            if (.not. any(kinks%active)) return
            call update_paths()
        end do
        current = .not. changed
        if (current) return
        ! Out of solves: the tips not converged (or closed at their last trial) grow at their
        ! MTS angle when its trial was open; otherwise local symmetry is not reached with the
        ! kink open, and the tip does not grow (SPEC-GROWTH 1.4).
        do i = 1, size(kinks)
            if (kinks(i)%active .and. kinks(i)%correcting .and. &
                (.not. kinks(i)%open .or. abs(kinks(i)%k2) > kinks(i)%tolerance)) then
                if (kinks(i)%mts_closed) then
                    kinks(i)%active = .false.
                    kinks(i)%reason = growth_closed
                else
                    kinks(i)%reason = growth_corrector_failed
                    kinks(i)%theta = kinks(i)%theta_mts
                end if
            end if
        end do
        call update_paths()

    contains

        !> Paths at the current angles; those that do not keep clear stop their tips, those
        !> that meet another fracture link.
        subroutine update_paths()
            do i = 1, size(kinks)
                if (kinks(i)%active) paths(i) = path_of(kinks(i))
            end do
            active = kinks%active  ! a strided component: copied here, not as a temporary
            call check_paths(model, paths, active, problem, links, step_links())
            do i = 1, size(kinks)
                if (problem(i) /= path_clear) then
                    kinks(i)%active = .false.
                    kinks(i)%reason = problem(i)
                end if
                if (problem(i) == growth_linked) kinks(i)%link = links(i)
            end do
        end subroutine update_paths

        !> The step's links so far: those made before the corrector, then the kinks'.
        function step_links() result(made)
            type(tip_link), allocatable :: made(:)

            integer :: j

            made = fixed
            do j = 1, size(kinks)
                if (kinks(j)%reason == growth_linked) made = [made, kinks(j)%link]
            end do
        end function step_links

        !> The new elements of the next trial: the paths of the tips still growing, then the
        !> links' paths, and the links' splits.
        subroutine trial_parts()
            type(tip_path), allocatable :: link_paths(:)
            integer :: j

            call link_parts(step_links(), link_paths, splits)
            if (allocated(trial_paths)) deallocate (trial_paths)
            allocate (trial_paths(0))
            do j = 1, size(kinks)
                if (kinks(j)%active) trial_paths = [trial_paths, paths(j)]
            end do
            trial_paths = [trial_paths, link_paths]
        end subroutine trial_parts

        !> The path of one kink at its current angle.
        function path_of(k) result(path)
            type(kink), intent(in) :: k
            type(tip_path) :: path

            path = make_path(model, k%fracture, k%end, k%theta, k%length, k%pieces)
        end function path_of

    end subroutine correct_kinks

    !> The model grown at the kinks' applied angles (those that grew or fell back to their
    !> MTS angle) and with the step's links (`fixed`, then the kinks'), the step that created
    !> each element and where each old element went.
    subroutine grow_paths(model, created, options, step, kinks, fixed, grown, grown_created, &
                          moved_to, grown_origin)
        !> The model before growing
        type(model_type), intent(in) :: model
        !> Growth step that created each element of model, shape (n)
        integer, intent(in) :: created(:)
        !> Growth options (new_mu, new_sf)
        type(growth_options), intent(in) :: options
        !> The growth step
        integer, intent(in) :: step
        !> The growing tips, with their applied angles and reasons
        type(kink), intent(in) :: kinks(:)
        !> The links made before the corrector
        type(tip_link), intent(in) :: fixed(:)
        !> The grown model and the step that created each of its elements
        type(model_type), intent(out) :: grown
        integer, allocatable, intent(out) :: grown_created(:)
        !> The index in grown of each element of model, shape (model n)
        integer, allocatable, intent(out) :: moved_to(:)
        !> The element of model each element of grown comes from (0: new), shape (grown n)
        integer, allocatable, intent(out) :: grown_origin(:)
        type(tip_path), allocatable :: paths(:), link_paths(:)
        type(element_split), allocatable :: splits(:)
        type(tip_link), allocatable :: made(:)
        integer :: i

        made = fixed
        do i = 1, size(kinks)
            if (kinks(i)%reason == growth_linked) made = [made, kinks(i)%link]
        end do
        call link_parts(made, link_paths, splits)
        allocate (paths(0))
        do i = 1, size(kinks)
            if (kinks(i)%reason /= growth_grew .and. &
                kinks(i)%reason /= growth_corrector_failed) cycle
            paths = [paths, make_path(model, kinks(i)%fracture, kinks(i)%end, kinks(i)%theta, &
                                      kinks(i)%length, kinks(i)%pieces)]
        end do
        paths = [paths, link_paths]
        call extend_model(model, created, paths, step, options, grown, grown_created, moved_to, &
                          splits, grown_origin)
    end subroutine grow_paths

    !> K_II of a kink's new tip in the grown model (k%k2), and whether that tip is closed (a
    !> contact element that is not open, or another condition with K_I <= 0).
    subroutine new_tip(grown, solved, k, closed, error)
        type(model_type), intent(in) :: grown
        type(model_results), intent(in) :: solved
        type(kink), intent(inout) :: k
        logical, intent(out) :: closed
        type(error_type), allocatable, intent(out) :: error
        integer :: e, t

        k%k2 = 0.0_wp
        closed = .false.
        call fracture_tip(grown, solved%tips, k%fracture, k%end, t, error)
        if (allocated(error)) return
        e = solved%tips%element(t)
        k%k2 = solved%tips%k2(t)
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
    pure subroutine secant_angle(k)
        !> The kink; its angle and previous point are updated
        type(kink), intent(inout) :: k
        real(wp) :: slope, step

        slope = k%slope
        if (k%have_prev) then
            if (k%theta /= k%theta_prev) then
                if ((k%k2 - k%k2_prev) / (k%theta - k%theta_prev) > 0.0_wp) then
                    slope = (k%k2 - k%k2_prev) / (k%theta - k%theta_prev)
                end if
            end if
        end if
        k%have_prev = .true.
        k%theta_prev = k%theta
        k%k2_prev = k%k2
        step = max(-max_step, min(max_step, -k%k2 / slope))
        k%theta = max(k%theta_mts - max_deviation, min(k%theta_mts + max_deviation, &
                                                        k%theta + step))
    end subroutine secant_angle

end module ddc_growth_corrector
