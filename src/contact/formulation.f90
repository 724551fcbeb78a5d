!> Frictional contact on displacement discontinuity elements (docs/theory/contact.md): the methods
!> and how they back each other up.
!>
!> Methods (options%lcp_method of solve_contact, &solver lcp_method):
!> - 'lemke': the paper's LCP solved by the lexicographic Lemke method (the reference,
!>   ddc_contact_paper_lcp);
!> - 'newton': a semismooth Newton / primal-dual active-set method on the stiffness system
!>   t = S_r + A D (ddc_contact_active_set): no inverse of A, one LU of a reduced system
!>   per iteration. Its result is certified as the equivalent LCP: z and w of the
!>   paper's formulation are computed from the DDs and the tractions A D + S_r of the
!>   unfactored A (so w = M z + q holds by construction) and must pass the same sign and
!>   complementarity tolerances; the tractions the iteration imposed (s_s = +-tau_s on
!>   slipping elements, S_n' = 0 on open ones) must match A D + S_r within residual_tol.
!>   When the iteration does not converge, a reduced system is singular or a check
!>   fails, the solve falls back to Lemke and the reason is kept (contact_result%fallback);
!> - 'auto': 'newton' above auto_newton_min_elements contact elements, else 'lemke'; when
!>   that Lemke solve fails (a ray: M is not copositive-plus, seen at acute branches), the
!>   Newton method is tried before the solve is reported as failed.
!> The Newton method that is the last resort (after Lemke failed under 'newton' or 'auto', or
!> without the dense matrix) tries to leave a cycle of its states before it gives up
!> (ddc_contact_active_set's escape); where Lemke follows it does not, so that a problem
!> Lemke solves keeps Lemke's solution.
!>
!> A failed LAPACK call, an LCP that no method solves, a failed certificate or a large
!> residual is an error (exit_solver_failure), never a result.
!>
!> solve_contact takes the dense influence matrix; solve_contact_with takes any stiffness
!> operator (ddc_contact_stiffness), e.g. a matrix distributed over MPI processes, and
!> without the dense matrix (Lemke's tableau needs it) solves by the Newton method alone: a
!> Newton failure is then an error (exit_solver_failure) that says why.
!>
!> A loading history (docs/theory/earth.md#loading-histories) solves one step after the other with
!> the same methods and fallbacks: each step gives the total slip of the step before
!> (ds_previous), keeps its dense stiffness operator (whose factors the Newton method
!> reuses and updates from step to step) and a contact_session with what else the steps
!> share: the paper's LCP once Lemke needed it and Lemke's last basis (warm start), the
!> Newton method's states (warm start) and its fixed tractions. A growth run keeps one
!> session for its solves: each has a new matrix (new_matrix), so only the states carry
!> over.
!>
!> open_cohesion: 'kept' (the paper) lets an open element carry shear up to Sf;
!> 'lost' sets Sf = 0 on every element that opens and solves again until no open
!> element has cohesion left (the set of such elements only grows, so this terminates).
!>
!> The fault law (ddc_contact_fault_law: given values, values in force and the rules) goes
!> in and comes out with the values in force at the end, so that the next step of a
!> loading history starts from them; the LCP solvers get plain arrays from it.
!>
!> Strength beyond Coulomb (tensile strength and sf_residual): an intact element opens
!> only when S_n' reaches its tensile strength T. With T in force the contact law is
!> Coulomb's in the shifted traction S_n'' = S_n' - T: S_n'' <= 0, opening S_n'' = 0, and
!> tau_s = (Sf - mu T) - mu S_n''. That is the paper's LCP with s_n - T for the resolved
!> normal traction and Sf - mu T for Sf, so each solve is the same certified LCP (T is capped at the
!> Coulomb apex Sf/mu, where the shear strength vanishes, so that Sf - mu T >= 0). After
!> each solve, elements that opened lose T (T = 0) and elements that slipped drop their
!> cohesion to min(Sf, sf_residual); the problem is solved again until no element
!> changes. Strengths only decrease and take finitely many values, so this fixed point
!> is reached in at most 2n + 1 solves; the last solve is certified with the strengths
!> in force, which the law keeps.
!>
!> Slip weakening (mu_dynamic, slip_weakening_distance): each solve holds every
!> element's friction fixed at mu(s) of its slip path s before the solve; after it the
!> frictions are updated from the new slip and the problem solved again until they change
!> by less than weakening_tol (friction only decreases along the iteration: no healing,
!> so the iteration is monotone). When they
!> still change after max_weakening_solves solves, the load has no quasi-static solution
!> this iteration can reach: an error (exit_solver_failure) naming the element whose
!> friction changed most.
!>
!> Gradual strength drops (slip_weakening_distance with sf_residual, and
!> opening_weakening_distance): the cohesion and tensile strength in force are brought to
!> those of the law at the new slip path and opening after each solve, never upwards, in
!> the same iteration, until none falls by more than weakening_tol times the stress scale;
!> beyond max_weakening_solves solves that is the same error, naming the element.
module ddc_contact_formulation
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, set_internal_error, exit_bad_input, &
        exit_out_of_memory, exit_solver_failure
    use ddc_text, only: bytes_text, itoa, rtoa
    use ddc_contact_memory, only: lemke_bytes
    use ddc_contact_options, only: solver_options, lcp_auto, lcp_newton, lcp_lemke, cohesion_lost
    use ddc_contact_fault_law, only: fault_law
    use ddc_contact_states, only: state_stick, state_open
    use ddc_contact_active_set, only: active_set_result, active_set_workspace, &
        solve_contact_active_set
    use ddc_contact_stiffness, only: stiffness_operator, dense_stiffness
    use ddc_contact_counts, only: factor_counts
    use ddc_contact_result, only: contact_result, contact_stress_scale, problem_scales, &
        check_solution, frictional_certificate
    use ddc_contact_paper_lcp, only: contact_lcp, build_contact_lcp, solve_paper_lcp, &
        set_lcp_friction
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: solve_contact, solve_contact_with, contact_session, auto_newton_min_elements
    public :: contact_problem, contact_limits
    public :: new_matrix
    public :: newton_max_iterations

    !> lcp_method = 'auto' uses 'newton' from this many contact elements on, else 'lemke'
    integer, parameter :: auto_newton_min_elements = 300
    !> Default iteration limit of the 'newton' method
    integer, parameter :: newton_max_iterations = 100
    !> Slip weakening: largest change of a friction coefficient between the last two solves
    !> of a converged fixed point [-], and the solves allowed beyond those of the other
    !> laws (2n + 1)
    real(wp), parameter :: weakening_tol = 1.0e-12_wp
    integer, parameter :: max_weakening_solves = 200

    !> One contact problem of n elements: the load on them and the slip they hold.
    type :: contact_problem
        !> Remote shear and normal traction (tension positive) resolved on each element,
        !> plus any traction from non-contact elements, shape (n) [stress]
        real(wp), allocatable :: shear(:), normal(:)
        !> Fluid pressure inside each element, compression positive, shape (n) [stress]
        real(wp), allocatable :: pressure(:)
        !> Total slip before this solve (friction memory; default 0), shape (n) [length]
        real(wp), allocatable :: ds_previous(:)
        !> Stress scale of the certificate and of Lemke's scaling (default: from this load,
        !> contact_stress_scale) [stress]
        real(wp), allocatable :: stress_scale
    end type contact_problem

    !> Limits of the methods (tests; each default where not allocated).
    type :: contact_limits
        !> Tie-breaking rule of Lemke (default lexicographic)
        integer, allocatable :: rule
        !> Iteration limit of 'newton' (default newton_max_iterations)
        integer, allocatable :: max_iterations
        !> Pivot limit of each Lemke solve (default that of solve_lcp_lemke)
        integer, allocatable :: max_pivots
        !> Largest number of solves of the strength fixed point (default
        !> 2n + 1 + max_weakening_solves)
        integer, allocatable :: max_solves
        !> A Newton failure falls back to Lemke (else it is the solve's failure: a solve
        !> whose failure its caller can take, as the K re-solve's)
        logical :: fall_back = .true.
    end type contact_limits

    !> What successive solves on the same contact elements (the steps of a loading history)
    !> keep besides their stiffness operator: the paper's LCP once built and Lemke's last
    !> basis, the Newton method's states and fixed tractions; and the methods' limits.
    type :: contact_session
        !> Limits of the methods (tests)
        type(contact_limits) :: limits
        !> Lemke starts each solve from its last basis (the steps of a loading history, the
        !> trials of a growth run); else each solve of the strength fixed point afresh
        logical :: warm = .false.
        !> The paper's LCP (built on the first Lemke solve)
        type(contact_lcp) :: lcp
        !> Lemke's last basis, shape (3n); 0 entries: none yet
        integer, allocatable :: basis(:)
        !> The Newton method's fixed tractions
        type(active_set_workspace) :: newton
        !> States of the last solve (warm start of the Newton method), shape (n)
        logical, allocatable :: open(:)
        integer, allocatable :: shear_state(:)
        !> Whether A was found finite (it is checked once)
        logical :: a_checked = .false.
    end type contact_session

contains

    !> The session's next solve is on another matrix (a grown model): forget what depends on
    !> the matrix (the paper's LCP, Lemke's basis, the Newton method's fixed tractions) and
    !> keep the states, from which the Newton method starts.
    subroutine new_matrix(session, checked)
        !> The session
        type(contact_session), intent(inout) :: session
        !> Every entry of the new matrix is known to be finite
        logical, intent(in) :: checked
        type(contact_session) :: fresh

        call move_alloc(session%open, fresh%open)
        call move_alloc(session%shear_state, fresh%shear_state)
        fresh%limits = session%limits
        fresh%warm = session%warm
        fresh%a_checked = checked
        session = fresh
    end subroutine new_matrix

    !> Solve the frictional contact problem of n elements
    !> (docs/theory/contact.md#the-contact-law-of-one-element) on a dense matrix.
    subroutine solve_contact(a, problem, law, options, res, error, limits)
        !> Influence matrix ordered [s; n]: traction = s_r + a [Ds; Dn], shape (2n, 2n)
        !> [stress / length]
        real(wp), intent(in), target, contiguous :: a(:, :)
        !> The load on the n elements and the slip they hold
        type(contact_problem), intent(in) :: problem
        !> The fault law of the n elements: the values in force at the start, those at the
        !> end on return (see solve_contact_with)
        type(fault_law), intent(inout) :: law
        !> LCP method and cohesion of open elements
        type(solver_options), intent(in) :: options
        !> The solution
        type(contact_result), intent(out) :: res
        !> Allocated on failure (exit_solver_failure; exit_bad_input for NaN or Inf data,
        !> exit_internal_error for inconsistent arguments)
        type(error_type), allocatable, intent(out) :: error
        !> Limits of the methods (tests)
        type(contact_limits), intent(in), optional :: limits
        type(dense_stiffness) :: stiffness
        type(contact_session) :: session
        integer(int64) :: t0, t1, rate

        if (size(a, 1) /= 2 * size(problem%shear) .or. size(a, 2) /= 2 * size(problem%shear)) &
            then
            call set_internal_error(error, 'solve_contact', 'array sizes do not match')
            return
        end if
        stiffness%a => a
        if (present(limits)) session%limits = limits
        call solve_contact_with(stiffness, problem, law, options, res, error, a, session)
        ! Freeing the factors (up to (2n)^2 reals) is part of the contact solve's time.
        call system_clock(t0, rate)
        call stiffness%discard_factors()
        call system_clock(t1)
        res%seconds_lcp = res%seconds_lcp + real(t1 - t0, wp) / real(max(rate, 1_int64), wp)
    end subroutine solve_contact

    !> Solve the frictional contact problem of n elements
    !> (docs/theory/contact.md#the-contact-law-of-one-element) on any stiffness operator, or one
    !> step of a loading history (ds_previous, session); without the dense matrix a, by the Newton
    !> method alone.
    subroutine solve_contact_with(stiffness, problem, law, options, res, error, a, session)
        !> The influence matrix A ordered [s; n]: traction = s_r + A [Ds; Dn], 2n x 2n
        !> [stress / length]
        class(stiffness_operator), intent(inout) :: stiffness
        !> The load on the n elements and the slip they hold (a step of a loading history:
        !> the total slip at the end of the previous step)
        type(contact_problem), intent(in) :: problem
        !> The fault law of the n elements: its given values, and the values in force at
        !> the start (cohesion and tensile strength; the slip path, from which the friction
        !> in force follows); on return those at the end, with which the last solve was
        !> certified (undefined after an error)
        type(fault_law), intent(inout) :: law
        !> LCP method and cohesion of open elements (the method is 'newton' without a)
        type(solver_options), intent(in) :: options
        !> The solution
        type(contact_result), intent(out) :: res
        !> Allocated on failure (exit_solver_failure; exit_bad_input for NaN or Inf data,
        !> exit_internal_error for inconsistent arguments)
        type(error_type), allocatable, intent(out) :: error
        !> The same matrix in memory, shape (2n, 2n): Lemke's method needs it
        real(wp), intent(in), optional :: a(:, :)
        !> What the steps of a loading history share, with the methods' limits (default: a
        !> fresh one); with it, Lemke starts from its last basis
        type(contact_session), intent(inout), optional :: session
        type(contact_session), allocatable :: fresh
        logical :: weakening
        real(wp), allocatable :: held(:)
        real(wp) :: sigma0
        integer :: n, limit, solves_limit
        logical :: checked
        integer(int64) :: t_start, t_end, rate

        ! The lcp phase: everything from here on (the checks of A included, 4 n^2 reads)
        ! but the factorizations, so that no part of the solve is in no phase.
        call system_clock(t_start, rate)
        n = size(problem%shear)
        if (size(problem%normal) /= n .or. size(problem%pressure) /= n .or. &
            .not. law%sizes_match(n)) then
            call set_internal_error(error, 'solve_contact', 'array sizes do not match')
            return
        end if
        allocate (held(n), source=0.0_wp)
        weakening = law%weakens()
        solves_limit = 2 * n + 1 + max_weakening_solves
        if (present(session)) then
            if (allocated(session%limits%max_solves)) solves_limit = session%limits%max_solves
        end if
        if (allocated(problem%ds_previous)) then
            if (size(problem%ds_previous) /= n) then
                call set_internal_error(error, 'solve_contact', 'array sizes do not match')
                return
            end if
            held = problem%ds_previous
        end if
        ! A is checked once per session (the steps of a history share it).
        checked = .false.
        if (present(session)) checked = session%a_checked
        if (.not. checked) checked = stiffness%all_finite()
        if (.not. (checked .and. all(ieee_is_finite(problem%shear)) .and. &
            all(ieee_is_finite(problem%normal)) .and. law%all_finite() .and. &
            all(ieee_is_finite(problem%pressure)) .and. all(ieee_is_finite(held)))) then
            call set_error(error, exit_bad_input, 'contact: NaN or Inf in the input arrays')
            return
        end if
        if (present(session)) session%a_checked = .true.
        limit = newton_max_iterations
        if (present(session)) then
            if (allocated(session%limits%max_iterations)) limit = &
                session%limits%max_iterations
        end if
        if (law%any_negative()) then
            call set_internal_error(error, 'solve_contact', &
                                    'the strength laws must not be negative')
            return
        end if
        if (n == 0) then
            allocate (res%ds(0), res%dn(0), res%shear_traction(0), res%normal_traction(0), &
                res%state(0))
            res%certificate%passed = .true.
            return
        end if
        sigma0 = contact_stress_scale(problem%shear, problem%normal, law%sf_in_force, &
                                      problem%pressure)
        if (allocated(problem%stress_scale)) sigma0 = problem%stress_scale
        if (present(session)) then
            call strength_fixed_point(session, session%warm)
        else
            allocate (fresh)
            call strength_fixed_point(fresh, .false.)
            deallocate (fresh)
        end if
        call system_clock(t_end)
        res%seconds_lcp = real(t_end - t_start, wp) / real(max(rate, 1_int64), wp) - &
            res%counts%seconds

    contains

        !> The strength fixed point (docs/theory/strength.md): solves under the strengths in
        !> force (solve_by_method), each followed by the laws' rules, until no strength in
        !> force changes; warm: Lemke starts from the session's basis.
        subroutine strength_fixed_point(s, warm)
            type(contact_session), intent(inout) :: s
            logical, intent(in) :: warm
            real(wp), allocatable :: sf_in(:), srn_in(:), t_cap(:), mu_next(:), path(:)
            logical :: newton, changed
            integer :: rounds, moving
            character(len=200) :: line
            type(factor_counts) :: this_solve

            newton = options%lcp_method == lcp_newton .or. .not. present(a) .or. &
                (options%lcp_method == lcp_auto .and. n >= auto_newton_min_elements)
            if (newton) then
                res%method = 'newton'
            else
                res%method = 'lemke'
            end if
            res%fallback = ''
            rounds = 0
            law%mu_in_force = law%friction(law%slip_path, spread(0, 1, n))
            do
                rounds = rounds + 1
                call law%shifted(problem%normal, sf_in, srn_in, t_cap)
                res%residual_scale_floor = 0.0_wp
                if (any(t_cap > 0.0_wp)) res%residual_scale_floor = &
                    max(norm2([problem%shear, problem%normal]), norm2(t_cap))
                call solve_by_method(s, warm, sf_in, srn_in, newton)
                if (allocated(error)) then
                    if (rounds > 1) then
                        write (line, '(a,i0,a)') ' (solve ', rounds, &
                            ", after strength was lost on elements that opened or slipped)"
                        error%message = error%message//trim(line)
                    end if
                    if (len(res%fallback) > 0) error%message = error%message// &
                        ' (after the first method failed: '//res%fallback//')'
                    return
                end if
                if (.not. newton) call keep_states(res, s)
                res%normal_traction = res%normal_traction + t_cap
                path = law%slip_path + abs(res%ds - held)
                changed = law%weaken(res%state, path, -res%dn, weakening_tol * sigma0, moving)
                if (moving > 0 .and. rounds >= solves_limit) then
                    call set_error(error, exit_solver_failure, 'contact: strength '// &
                        'weakening found no quasi-static solution: after '//itoa(rounds)// &
                        ' solves the cohesion or tensile strength of element '// &
                        itoa(moving)//' still falls (its slip or opening runs away)')
                    return
                end if
                if (options%open_cohesion == cohesion_lost) then
                    if (law%lose_open_cohesion(res%state)) changed = .true.
                end if
                if (weakening) then
                    ! No healing: friction only decreases along the iteration.
                    associate (mu_in => law%mu_in_force)
                        mu_next = min(mu_in, law%friction(path, res%state))
                        if (maxval(abs(mu_next - mu_in)) > weakening_tol) then
                            if (rounds >= solves_limit) then
                                call set_error(error, exit_solver_failure, 'contact: slip '// &
                                    'weakening found no quasi-static solution: after '// &
                                    itoa(rounds)//' solves the friction of element '// &
                                    itoa(maxloc(abs(mu_next - mu_in), 1))//' still changes '// &
                                    'by '//rtoa(maxval(abs(mu_next - mu_in)))// &
                                    ' (its slip runs away)')
                                return
                            end if
                            changed = .true.
                            mu_in = mu_next
                        end if
                    end associate
                end if
                if (.not. changed) exit
            end do
            ! The last solve changed no strength in force: it was certified with them (T
            ! capped at the apex), and its slip path is the memory.
            law%tensile_in_force = t_cap
            law%slip_path = path
            ! The operator's counts (of the session), with this solve's time and flops.
            this_solve = res%counts
            res%counts = stiffness%counts
            res%counts%seconds = this_solve%seconds
            res%counts%flops = this_solve%flops
        end subroutine strength_fixed_point

        !> One solve under the strengths in force by the method in use (newton), and the
        !> one place of its fallbacks: a Newton failure falls back to Lemke where the dense
        !> matrix is at hand (for the rest of the fixed point), a Lemke failure under 'auto'
        !> asks the Newton method; error is set when no method solves it.
        subroutine solve_by_method(s, warm, sf_in, srn_in, newton)
            type(contact_session), intent(inout) :: s
            logical, intent(in) :: warm
            !> Cohesion and resolved normal traction of the shifted law [stress], shape (n)
            real(wp), intent(in) :: sf_in(:), srn_in(:)
            !> The Newton method is in use (else Lemke's); changed by a fallback
            logical, intent(inout) :: newton
            character(len=:), allocatable :: reason
            logical :: exceeded

            if (newton) then
                call solve_once_newton(s, srn_in, sf_in, .not. present(a), reason, exceeded)
                if (exceeded) then
                    call set_error(error, exit_out_of_memory, 'contact: '//reason)
                else if (len(reason) > 0 .and. &
                         (.not. present(a) .or. .not. s%limits%fall_back)) then
                    call set_error(error, exit_solver_failure, 'contact: '//reason)
                else if (len(reason) > 0) then
                    ! Lemke's memory, not the Newton factors beside it.
                    call stiffness%discard_factors()
                    newton = .false.
                    res%method = 'lemke'
                    res%fallback = reason
                end if
            end if
            if (newton .or. allocated(error)) return
            call solve_once_lemke(s, warm, sf_in, srn_in, law%mu_in_force)
            if (.not. allocated(error) .or. options%lcp_method == lcp_lemke) return
            ! M is not copositive-plus: Lemke can end on a ray where the contact problem has
            ! a solution (seen at acute fault branches). The Newton method is then asked
            ! again, as the last resort (it leaves cycles), its answer checked the same way,
            ! and kept for the rounds after cohesion is lost.
            call solve_once_newton(s, srn_in, sf_in, .true., reason, exceeded)
            if (exceeded) then
                reason = error%message//' (the Newton method then stopped: '//reason//')'
                deallocate (error)
                call set_error(error, exit_out_of_memory, reason)
            else if (len(reason) == 0) then
                newton = .true.
                res%method = 'newton'
                res%fallback = 'lemke failed: '//error%message
                deallocate (error)
            else
                error%message = error%message//' (the Newton method failed too: '//reason// &
                    '); frictional contact may have no solution here, as at a branch at a '// &
                    'small angle (docs/contact-and-strength.md#junctions)'
            end if
        end subroutine solve_by_method

        !> One Lemke solve of the paper's LCP (built once per session, when memory allows),
        !> from the session's last basis when warm.
        subroutine solve_once_lemke(s, warm, sf_eff, srn, mu_now)
            type(contact_session), intent(inout) :: s
            logical, intent(in) :: warm
            !> Cohesion and resolved normal traction of the shifted law [stress]
            real(wp), intent(in) :: sf_eff(:), srn(:)
            !> Friction in force [-]
            real(wp), intent(in) :: mu_now(:)

            if (.not. allocated(s%lcp%m) .and. len(res%fallback) > 0 .and. &
                lemke_bytes(n) > options%work_bytes) then
                call set_error(error, exit_out_of_memory, 'contact: the Newton method '// &
                    'failed ('//res%fallback//') and the fallback to Lemke would need '// &
                    'about '//bytes_text(lemke_bytes(n))//' more memory, but about '// &
                    bytes_text(options%work_bytes)//' is left here')
                return
            end if
            if (.not. allocated(s%lcp%m)) then
                call build_contact_lcp(a, mu_now, s%lcp, res, error)
                if (allocated(error)) return
                allocate (s%basis(3 * n), source=0)
            else if (any(s%lcp%mu /= mu_now)) then
                ! Slip weakening changed mu: a new M, and no basis of the old one.
                call set_lcp_friction(s%lcp, mu_now)
                s%basis = 0
            end if
            if (warm) then
                call solve_paper_lcp(s%lcp, problem%shear, srn, sf_eff, problem%pressure, held, &
                                     sigma0, res, error, rule=s%limits%rule, basis=s%basis, &
                                     max_pivots=s%limits%max_pivots)
            else
                call solve_paper_lcp(s%lcp, problem%shear, srn, sf_eff, problem%pressure, held, &
                                     sigma0, res, error, rule=s%limits%rule, &
                                     max_pivots=s%limits%max_pivots)
            end if
        end subroutine solve_once_lemke

        !> One solve by the active-set Newton method (no inverse of A), certified as the
        !> equivalent LCP. reason is empty on success, else why Lemke must take over.
        subroutine solve_once_newton(s, s_r_n, sf, last_resort, reason, exceeded)
            !> The session: its states are the warm start and take this solve's
            type(contact_session), intent(inout) :: s
            !> Resolved normal traction and cohesion of the shifted law [stress], shape (n)
            real(wp), intent(in) :: s_r_n(:), sf(:)
            !> No method follows: a cycle of the states is not the end yet
            logical, intent(in) :: last_resort
            character(len=:), allocatable, intent(out) :: reason
            !> The states asked for a reduced system larger than the memory left (reason says
            !> so): no other method can take over (Lemke needs more)
            logical, intent(out) :: exceeded
            type(active_set_result) :: next
            real(wp), allocatable :: snp(:)
            real(wp) :: dscale, stiffness_scale
            integer :: n, i
            character(len=:), allocatable :: failure

            associate (s_r_s => problem%shear, p => problem%pressure, mu => law%mu_in_force)
                n = size(sf)
                stiffness_scale = stiffness%max_diagonal()
                if (.not. stiffness_scale > 0.0_wp) stiffness_scale = stiffness%max_entry()
                call problem_scales(stiffness_scale, s_r_s, s_r_n, sf, p, res)
                if (allocated(problem%stress_scale)) then
                    res%dd_scale = res%dd_scale * sigma0 / res%stress_scale
                    res%stress_scale = sigma0
                end if
                if (allocated(s%open)) then
                    call solve_contact_active_set(stiffness, s_r_s, s_r_n + p, mu, sf, &
                        res%stress_scale, next, limit, s%newton, s%open, s%shear_state, &
                        ds_previous=held, work_bytes=options%work_bytes, escape=last_resort)
                else
                    call solve_contact_active_set(stiffness, s_r_s, s_r_n + p, mu, sf, &
                        res%stress_scale, next, limit, s%newton, ds_previous=held, &
                        work_bytes=options%work_bytes, escape=last_resort)
                end if
                exceeded = next%memory_exceeded
                res%iterations = res%iterations + next%iterations
                res%solves = res%solves + 1
                res%counts%seconds = res%counts%seconds + next%seconds_factorization
                res%counts%flops = res%counts%flops + next%factorization_flops
                if (.not. next%converged) then
                    reason = 'newton: '//next%reason
                    return
                end if
                s%open = next%open
                s%shear_state = next%shear_state

                ! Certified as the paper's LCP, from the DDs and the tractions A D + S_r of the
                ! unfactored A.
                dscale = max(res%dd_scale, maxval(abs(next%ds)), maxval(abs(next%dn)))
                res%certificate = frictional_certificate(next%ds, next%dn, held, next%shear, &
                    next%normal_effective, mu, sf, res%stress_scale, dscale)

                ! The tractions the iteration imposed: S_n' = 0 on open elements, s_s = +-tau_s
                ! on slipping ones; elsewhere those of A D + S_r.
                snp = merge(0.0_wp, next%normal_effective, next%open)
                res%shear_traction = next%shear
                do i = 1, n
                    if (next%shear_state(i) /= 0) res%shear_traction(i) = &
                        real(next%shear_state(i), wp) * (sf(i) - mu(i) * snp(i))
                end do
                res%normal_traction = snp - p
                res%ds = next%ds
                res%dn = next%dn
                ! A D of the last iteration (the product the states were updated from).
                call check_solution(next%ad, s_r_s, s_r_n, mu, sf, snp, dscale, res, failure, held)
                reason = ''
                if (len(failure) > 0) reason = 'newton: '//failure
            end associate
        end subroutine solve_once_newton

    end subroutine solve_contact_with

    !> Newton states from a Lemke solution, for the next solve's warm start: open elements
    !> open; shear stick where the element sticks, else slip towards its shear traction.
    subroutine keep_states(res, s)
        type(contact_result), intent(in) :: res
        type(contact_session), intent(inout) :: s

        s%open = res%state == state_open
        s%shear_state = merge(0, int(sign(1.0_wp, res%shear_traction)), &
                              res%state == state_stick)
    end subroutine keep_states

end module ddc_contact_formulation
