!> Frictional contact solved on the stiffness system by a semismooth Newton method in its
!> primal-dual active-set form (Hintermueller, Ito & Kunisch 2002; Hueeber & Wohlmuth 2005
!> for friction), without the inverse of the influence matrix.
!>
!> Every contact element has a normal state (closed: Dn = 0; open: S_n' = 0) and a shear
!> state (stick: Ds = 0; slip with s_s = +tau_s or s_s = -tau_s, tau_s = Sf - mu S_n').
!> For given states the DDs that are not fixed at zero (Ds on slipping elements, Dn on open
!> ones) solve one dense linear system made of rows of A (a slip row is the shear row plus
!> +-mu times the normal row of the same element), factorized by LAPACK. The states are
!> then updated from the complementarity conditions: a closed element opens when S_n' > 0,
!> an open one closes when its opening would be negative; a sticking element slips towards
!> the sign of s_s when |s_s| > tau_s; a slipping element sticks when its slip runs against
!> the sense its traction imposes (from there it may slip the other way in the next
!> iteration: the direct reversal of the complementarity function s_s - c Ds, with c one
!> element's stiffness, overshoots when many elements unload together, and made the states
!> cycle). Unchanged states end the iteration. Round-off cannot make states flip back and
!> forth: a state is kept while its condition is violated by less than the state tolerances
!> (relative 1e-9 of the stress scale and of the largest diagonal entry of A times it),
!> which the certificate of the caller accepts.
!>
!> The method is not guaranteed to converge with Coulomb friction: it stops when the states
!> repeat with period two (a cycle), when the iteration limit is reached or when a reduced
!> system is numerically singular, and says why; the caller then falls back to Lemke.
!>
!> Where it is the last resort (escape), a cycle is not the end yet. The two states of the
!> cycle differ on a few elements whose conditions no state of theirs meets while the others
!> keep theirs: the way out needs other elements to change, ones that no condition of their
!> own tells to (seen at tails branching off a fault at 30 degrees: the fault element beside
!> each must close where the cycle keeps it open). They are among those whose DDs change most
!> between the two states of the cycle (the response to the cycling elements): every set of
!> the escape_candidates elements of largest response (in binary order: the first, the
!> second, both, the third, ...) is switched between open and closed (closed sticking) in
!> each of the two states of the cycle in turn, and the iteration goes on from there (each
!> try with the iteration limit of its own) until one converges or every try has failed
!> (at most 14).
!>
!> Loading history (docs/theory/earth.md#loading-histories): given the total slip ds_previous of the
!> step before, a sticking element keeps it (stick = no slip increment: Ds = ds_previous), the
!> slip increment Ds - ds_previous opposes the shear traction and Signorini acts on the
!> total Dn; the unknowns stay the total DDs, the fixed slips enter the right-hand side
!> (A times them, kept while they do not change). One-shot solves have ds_previous = 0.
!>
!> One iteration costs one product with A (8 N^2 flops) and one solve of the reduced
!> system: with the dense operator a new LU (2/3 m^3 flops for m unknowns, at most 2N)
!> only when the states changed much; unchanged states reuse the factors (two triangular
!> solves) and a few changes update them (low rank). A solve through an update is
!> checked: the imposed tractions of the unknowns' rows must hold against A D from the
!> unfactored A (to update_tol of the stress scale), else the factors are dropped and the
!> system is factorized anew.
!> How A is stored, multiplied and factorized is the business of the stiffness operator
!> (ddc_contact_stiffness): a dense matrix in memory, whose factors are kept between
!> iterations and between solves (the steps of a loading history), or one distributed over
!> MPI processes (one-shot solves only: no slip is held there).
module ddc_contact_active_set
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_contact_stiffness, only: stiffness_operator, reduced_system, action_updated, &
        action_name
    use ddc_text, only: itoa, seconds_text, bytes_text
    use ddc_contact_memory, only: newton_bytes
    use ddc_progress, only: report_progress, reports_phases
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: active_set_result, active_set_workspace, solve_contact_active_set
    public :: starting_unknowns
    public :: shear_stick, shear_slip_plus, shear_slip_minus

    !> Shear states: stick (Ds = 0), slip with s_s = +tau_s (Ds <= 0), slip with
    !> s_s = -tau_s (Ds >= 0)
    integer, parameter :: shear_stick = 0, shear_slip_plus = 1, shear_slip_minus = -1

    !> Relative tolerance of the state updates (stress scale and stiffness times it) [-]
    real(wp), parameter :: state_tol = 1.0e-9_wp
    !> Largest residual of the unknowns' rows, relative to the stress scale, accepted from a
    !> solve through a low-rank update [-]
    real(wp), parameter :: update_tol = 1.0e-11_wp
    !> Elements of largest response tried by the escape from a cycle (module header)
    integer, parameter :: escape_candidates = 3

    !> What the method keeps between solves on the same A (the steps of a loading history):
    !> the DDs held at non-zero values by the states (the previous slip of sticking
    !> elements), shape (2n), and A times them, shape (2n) [length], [stress].
    type :: active_set_workspace
        real(wp), allocatable :: fixed(:), fixed_traction(:)
    end type active_set_workspace

    !> Outcome of the active-set iteration on n contact elements; arrays shape (n).
    type :: active_set_result
        !> States unchanged by the last update (a candidate solution for the caller to
        !> certify); when false, reason says why the iteration stopped
        logical :: converged = .false.
        !> Why the iteration did not converge (empty when it did)
        character(len=:), allocatable :: reason
        !> Iterations done (linear solves)
        integer :: iterations = 0
        !> DDs [length] and total tractions from the unfactored A: shear s_s and effective
        !> normal S_n' = s_n + p [stress]
        real(wp), allocatable :: ds(:), dn(:), shear(:), normal_effective(:)
        !> A [Ds; Dn] from the unfactored A, shape (2n) [stress]
        real(wp), allocatable :: ad(:)
        !> Final states: open (normal) and shear_stick / shear_slip_plus / shear_slip_minus
        logical, allocatable :: open(:)
        integer, allocatable :: shear_state(:)
        !> Wall time of the LU factorizations and updates [s] and the nominal flop count of
        !> the factorizations (2/3 m^3 each)
        real(wp) :: seconds_factorization = 0.0_wp, factorization_flops = 0.0_wp
        !> Stopped because the states asked for a reduced system larger than the memory
        !> left (reason says how large)
        logical :: memory_exceeded = .false.
    end type active_set_result

contains

    !> Solve the contact conditions on the stiffness system, t = S_r + A D.
    subroutine solve_contact_active_set(a, s_r_s, s_r_np, mu, sf, sigma0, res, &
                                        max_iterations, work, start_open, start_shear, &
                                        ds_previous, work_bytes, escape)
        !> Influence matrix ordered [s; n], 2n x 2n [stress / length]
        class(stiffness_operator), intent(inout) :: a
        !> Remote shear traction and effective normal traction (s_n + p) on each element,
        !> shape (n) [stress]
        real(wp), intent(in) :: s_r_s(:), s_r_np(:)
        !> Friction coefficient [-] and frictional strength [stress], shape (n)
        real(wp), intent(in) :: mu(:), sf(:)
        !> Stress scale of the problem (> 0) [stress]
        real(wp), intent(in) :: sigma0
        !> The outcome; converged tells whether res holds a candidate solution
        type(active_set_result), intent(out) :: res
        !> Iteration limit
        integer, intent(in) :: max_iterations
        !> Fixed tractions kept from earlier solves on the same A (empty at first)
        type(active_set_workspace), intent(inout) :: work
        !> Initial states (default: from the remote stress alone), shape (n)
        logical, intent(in), optional :: start_open(:)
        integer, intent(in), optional :: start_shear(:)
        !> Total slip of the previous step of a loading history (default 0), shape (n)
        !> [length]
        real(wp), intent(in), optional :: ds_previous(:)
        !> Memory left for the reduced system and its updates (default: no limit) [bytes]
        real(wp), intent(in), optional :: work_bytes
        !> The method is the last resort: a cycle is left by the tries of the module header
        !> before it gives up (default .false.)
        logical, intent(in), optional :: escape

        real(wp), allocatable :: t(:), dd(:), held(:), dd_before(:)
        logical, allocatable :: open_old(:), cycle_open(:, :)
        integer, allocatable :: shear_old(:), cycle_shear(:, :), candidates(:)
        real(wp) :: c, tol_s, tol_d, limit
        integer :: n, n2, i, unknowns, iterations, tries
        integer(int64) :: t0, t1, rate
        logical :: changed, cycling, escaping, complete, unchecked
        type(error_type), allocatable :: singular

        n = size(mu)
        n2 = 2 * n
        complete = .false.
        unchecked = .false.
        c = a%max_diagonal()
        if (.not. c > 0.0_wp) c = 1.0_wp
        tol_s = state_tol * sigma0
        tol_d = state_tol * sigma0 / c
        allocate (res%ds(n), res%dn(n), dd(n2), t(n2), res%ad(n2))
        allocate (held(n), source=0.0_wp)
        if (present(ds_previous)) held = ds_previous

        ! Initial states from the remote stress (D = 0), unless given.
        call initial_states(s_r_s, s_r_np, mu, sf, tol_s, res%open, res%shear_state)
        if (present(start_open)) res%open = start_open
        if (present(start_shear)) res%shear_state = start_shear
        limit = huge(1.0_wp)
        if (present(work_bytes)) limit = work_bytes
        allocate (open_old(n), shear_old(n))
        open_old = .not. res%open
        shear_old = shear_stick
        escaping = .false.
        if (present(escape)) escaping = escape
        dd = 0.0_wp
        allocate (dd_before(n2), source=0.0_wp)
        tries = 0
        iterations = 0

        do
            if (iterations >= max_iterations .and. .not. complete) then
                if (next_try()) cycle
                res%reason = 'no convergence within '//itoa(max_iterations)//' iterations'// &
                    tries_text()
                return
            end if
            ! The pass that completes a converged iteration's tractions is not one more.
            if (.not. complete) then
                res%iterations = res%iterations + 1
                iterations = iterations + 1
                if (escaping) dd_before = dd
            end if
            call system_clock(t0, rate)
            call solve_states(a, s_r_s, s_r_np, mu, sf, held, sigma0, limit, complete, res, &
                              work, dd, t, unknowns, unchecked, singular)
            if (allocated(singular)) then
                res%reason = singular%message
                return
            end if
            call system_clock(t1)
            if (reports_phases(n) .and. .not. complete) call report_progress('newton iteration '// &
                itoa(res%iterations)//': '//itoa(unknowns)//' unknowns, '// &
                action_name(a%action)//', '// &
                seconds_text(real(t1 - t0, wp) / real(max(rate, 1_int64), wp)))
            res%ds = dd(1:n)
            res%dn = dd(n + 1:n2)
            res%shear = t(1:n)
            res%normal_effective = t(n + 1:n2)

            ! cycling: the new states equal those before the last update.
            cycling = .true.
            changed = .false.
            do i = 1, n
                call update_states(res%open(i), res%shear_state(i), res%ds(i) - held(i), &
                    res%dn(i), res%shear(i), res%normal_effective(i), mu(i), sf(i), tol_s, &
                    tol_d, open_old(i), shear_old(i), changed, cycling)
            end do
            if (.not. changed) then
                ! Decided from the rows that decide the states: the same states once more,
                ! with t on every row (and a solve through an update checked).
                if (.not. complete) then
                    complete = .true.
                    cycle
                end if
                res%converged = .true.
                res%reason = ''
                return
            end if
            complete = .false.
            if (cycling) then
                if (escaping .and. .not. allocated(candidates)) call keep_cycle()
                if (next_try()) cycle
                res%reason = 'the element states cycle (period 2) after '// &
                    itoa(res%iterations)//' iterations'//tries_text()
                return
            end if
        end do

    contains

        !> The first cycle's two states (the new ones and those just solved) and the elements
        !> outside it whose DDs changed most between their solutions, largest first (ties to
        !> the lower index; none that did not change).
        subroutine keep_cycle()
            real(wp), allocatable :: response(:)
            integer :: k, best

            cycle_open = reshape([res%open, open_old], [n, 2])
            cycle_shear = reshape([res%shear_state, shear_old], [n, 2])
            response = abs(dd(1:n) - dd_before(1:n)) + abs(dd(n + 1:n2) - dd_before(n + 1:n2))
            where ((res%open .neqv. open_old) .or. res%shear_state /= shear_old) response = 0.0_wp
            allocate (candidates(0))
            do k = 1, escape_candidates
                best = maxloc(response, 1)
                if (.not. response(best) > 0.0_wp) exit
                candidates = [candidates, best]
                response(best) = 0.0_wp
            end do
        end subroutine keep_cycle

        !> Start the next try out of the kept cycle: the candidates of set (tries + 1) / 2 (its
        !> bits) switched between open and closed in the cycle's first state (odd tries) or
        !> second (even); .false. when no try is left.
        logical function next_try()
            integer :: k, b, j

            next_try = .false.
            if (.not. allocated(candidates)) return
            if (tries >= 2 * (2**size(candidates) - 1)) return
            tries = tries + 1
            next_try = .true.
            k = 2 - mod(tries, 2)
            res%open = cycle_open(:, k)
            res%shear_state = cycle_shear(:, k)
            do b = 1, size(candidates)
                if (.not. btest((tries + 1) / 2, b - 1)) cycle
                j = candidates(b)
                res%open(j) = .not. res%open(j)
                if (.not. res%open(j)) res%shear_state(j) = shear_stick
            end do
            open_old = .not. res%open
            shear_old = shear_stick
            iterations = 0
        end function next_try

        !> ' (2 tries out of a cycle failed too)' after failed tries, else ''.
        function tries_text() result(text)
            character(len=:), allocatable :: text

            text = ''
            if (tries > 0) text = ' ('//itoa(tries)//' tries out of a cycle failed too)'
        end function tries_text

    end subroutine solve_contact_active_set

    !> New states of one element from its DDs and tractions; changed is set when the
    !> linear system changes, cycling is cleared when the new states differ from the old.
    pure subroutine update_states(open, shear_state, ds, dn, ss, snp, mu, sf, tol_s, tol_d, &
                                  open_old, shear_old, changed, cycling)
        logical, intent(inout) :: open, changed, cycling
        integer, intent(inout) :: shear_state
        real(wp), intent(in) :: ds, dn, ss, snp, mu, sf, tol_s, tol_d
        logical, intent(inout) :: open_old
        integer, intent(inout) :: shear_old
        logical :: open_new
        integer :: shear_new
        real(wp) :: tau

        ! Normal: closed while -S_n' + c Dn > 0.
        if (open) then
            open_new = .not. dn > tol_d
        else
            open_new = snp > tol_s
        end if
        ! Shear: tau_s of the current iterate (S_n' = 0 on open elements).
        tau = sf - mu * min(snp, 0.0_wp)
        if (open) tau = sf
        select case (shear_state)
        case (shear_stick)
            shear_new = shear_stick
            if (abs(ss) > tau + tol_s) shear_new = int(sign(1.0_wp, ss))
        case default
            ! Slip against the imposed traction's sense: the element sticks (it may slip the
            ! other way from there, by the stick rule above, in the next iteration).
            shear_new = shear_state
            if (real(shear_state, wp) * ds > tol_d) shear_new = shear_stick
        end select

        if (open_new .neqv. open) changed = .true.
        ! On an open element without cohesion slip +tau_s and -tau_s are the same equation.
        if (shear_new /= shear_state .and. .not. (open .and. open_new .and. .not. sf > 0.0_wp &
            .and. shear_new /= shear_stick .and. shear_state /= shear_stick)) changed = .true.
        if ((open_new .neqv. open_old) .or. shear_new /= shear_old) cycling = .false.
        open_old = open
        shear_old = shear_state
        open = open_new
        shear_state = shear_new
    end subroutine update_states

    !> Solve for the DDs of the current states: dd = [Ds; Dn] (Ds = held on sticking
    !> elements, Dn = 0 on closed ones), and t = S + A dd with A dd in res%ad; unknowns is
    !> the size of the reduced system. singular is allocated when the reduced system is
    !> (numerically) singular.
    subroutine solve_states(a, s_r_s, s_r_np, mu, sf, held, sigma0, work_bytes, complete, &
                            res, work, dd, t, unknowns, unchecked, singular)
        class(stiffness_operator), intent(inout) :: a
        real(wp), intent(in) :: s_r_s(:), s_r_np(:), mu(:), sf(:), held(:), sigma0
        !> Memory left for the reduced system and its updates [bytes]
        real(wp), intent(in) :: work_bytes
        !> Complete the last pass: dd is the solution of these states already, t is wanted on
        !> every row from A dd (else the states are solved for, and A dd is formed on the rows
        !> the states are decided from only, the unknowns' rows being what they impose)
        logical, intent(in) :: complete
        type(active_set_result), intent(inout) :: res
        type(active_set_workspace), intent(inout) :: work
        !> DDs [Ds; Dn]: the solution (in: the last one, read to complete it)
        real(wp), intent(inout) :: dd(:)
        real(wp), intent(out) :: t(:)
        integer, intent(out) :: unknowns
        !> A solve through an update not yet checked against A (set here by an incomplete
        !> one, cleared by the check of a complete one)
        logical, intent(inout) :: unchecked
        type(error_type), allocatable, intent(out) :: singular
        type(reduced_system) :: system
        real(wp), allocatable :: x(:), fixed(:), s(:)
        integer :: n, m
        logical :: known
        character(len=:), allocatable :: subject

        n = size(mu)
        ! The DDs the states fix: the held slip of sticking elements; S with A times them.
        allocate (fixed(2 * n), source=0.0_wp)
        where (res%shear_state == shear_stick) fixed(1:n) = held
        s = [s_r_s, s_r_np]
        if (any(fixed /= 0.0_wp)) then
            ! Exact comparison: the kept product serves exactly the same fixed DDs.
            known = allocated(work%fixed)
            if (known) known = size(work%fixed) == size(fixed)
            if (known) known = all(work%fixed == fixed)
            if (.not. known) then
                work%fixed = fixed
                if (allocated(work%fixed_traction)) deallocate (work%fixed_traction)
                allocate (work%fixed_traction(2 * n), source=0.0_wp)
                call a%multiply(fixed, work%fixed_traction)
            end if
            s = s + work%fixed_traction
        end if
        call reduced_unknowns(res%open, res%shear_state, s(1:n), s(n + 1:), mu, sf, system)
        m = size(system%unknown)
        unknowns = m
        ! Before its factors are allocated: a system the memory cannot hold stops the run
        ! cleanly (the estimate before the solve counted the starting states).
        if (newton_bytes(n, m) > work_bytes) then
            res%memory_exceeded = .true.
            allocate (singular)
            singular%message = 'the states of iteration '//itoa(res%iterations)// &
                ' ask for a reduced system of '//itoa(m)//' unknowns, which needs about '// &
                bytes_text(newton_bytes(n, m))//' with its updates, but about '// &
                bytes_text(work_bytes)//' is left here'
            return
        end if
        allocate (x(m))
        subject = 'the reduced system of iteration '//itoa(res%iterations)
        if (complete) then
            ! The states' solution is dd already: its tractions on every row.
            x = dd(system%unknown)
        else
            ! Asked even without unknowns: an operator with unknowns of its own updates them.
            call a%solve_reduced(system, x, subject, singular, res%seconds_factorization, &
                                 res%factorization_flops)
            if (allocated(singular)) return
        end if
        call tractions(x, complete, .false.)
        if (.not. complete .and. a%action == action_updated .and. m > 0) unchecked = .true.
        ! A solve through a low-rank update must meet the unknowns' equations against the
        ! unfactored A (complete tractions); else factorize anew and solve again.
        if (complete .and. unchecked .and. m > 0) then
            if (.not. maxval(abs(t(system%unknown) + system%coef * t(system%partner) - &
                                 target())) <= update_tol * sigma0) then
                call a%discard_factors()
                call a%solve_reduced(system, x, subject, singular, &
                                     res%seconds_factorization, res%factorization_flops)
                if (allocated(singular)) return
                call tractions(x, .false., .true.)
            end if
        end if
        if (complete) unchecked = .false.

    contains

        !> dd from the fixed DDs and the solution, A dd and t = S_r + A dd: on the rows the
        !> states are decided from (those of no unknown, and the partner rows of friction), the
        !> unknowns' rows then what they impose; with `rest`, the other rows of that same dd
        !> added (the product complete); with `whole`, every row anew.
        subroutine tractions(solution, rest, whole)
            real(wp), intent(in) :: solution(:)
            logical, intent(in) :: rest, whole
            logical, allocatable :: needed(:)
            real(wp), allocatable :: imposed(:), sr(:)
            integer :: k, g, p

            dd = fixed
            dd(system%unknown) = solution
            sr = [s_r_s, s_r_np]
            if (whole) then
                res%ad = 0.0_wp
                call a%multiply(dd, res%ad)
                t = sr + res%ad
                return
            end if
            allocate (needed(2 * n), source=.true.)
            needed(system%unknown) = .false.
            needed(pack(system%partner, system%partner /= system%unknown .and. &
                        system%coef /= 0.0_wp)) = .true.
            if (rest) then
                where (.not. needed) res%ad = 0.0_wp
                call a%multiply_rows(dd, .not. needed, res%ad)
                t = sr + res%ad
                return
            end if
            res%ad = 0.0_wp
            call a%multiply_rows(dd, needed, res%ad)
            t = sr + res%ad
            imposed = target()
            do k = 1, m
                g = system%unknown(k)
                p = system%partner(k)
                if (p == g) then
                    t(g) = imposed(k) / (1.0_wp + system%coef(k))
                else
                    t(g) = imposed(k) - system%coef(k) * t(p)
                end if
            end do
            res%ad(system%unknown) = t(system%unknown) - sr(system%unknown)
        end subroutine tractions

        !> What each unknown's row imposes: sign Sf on a slip row (the friction part is
        !> in its coefficient), 0 on an open element's normal row.
        function target() result(values)
            real(wp) :: values(m)
            integer :: k, i

            do k = 1, m
                i = system%unknown(k)
                values(k) = 0.0_wp
                if (i <= n) values(k) = real(res%shear_state(i), wp) * sf(i)
            end do
        end function target

    end subroutine solve_states

    !> The reduced system of given states: the unknowns not fixed at zero, Ds of slipping
    !> elements (row: the shear row + coef * the normal row, s_s - sign tau_s = 0) then Dn of
    !> open elements (row: the normal row, S_n' = 0).
    pure subroutine reduced_unknowns(open, shear_state, s_r_s, s_r_np, mu, sf, system)
        logical, intent(in) :: open(:)
        integer, intent(in) :: shear_state(:)
        real(wp), intent(in) :: s_r_s(:), s_r_np(:), mu(:), sf(:)
        type(reduced_system), intent(out) :: system
        integer :: n, m, i

        n = size(mu)
        m = count(shear_state /= shear_stick) + count(open)
        allocate (system%unknown(m), system%partner(m), system%coef(m), system%rhs(m))
        m = 0
        do i = 1, n
            if (shear_state(i) /= shear_stick) then
                m = m + 1
                system%unknown(m) = i
                system%partner(m) = n + i
                system%coef(m) = 0.0_wp
                ! s_s - sign tau_s = 0 with tau_s = Sf - mu S_n' (closed) or Sf (open).
                system%rhs(m) = real(shear_state(i), wp) * sf(i) - s_r_s(i)
                if (.not. open(i)) then
                    system%coef(m) = real(shear_state(i), wp) * mu(i)
                    system%rhs(m) = system%rhs(m) - system%coef(m) * s_r_np(i)
                end if
            end if
        end do
        do i = 1, n
            if (open(i)) then
                m = m + 1
                system%unknown(m) = n + i
                system%partner(m) = n + i
                system%coef(m) = 0.0_wp
                system%rhs(m) = -s_r_np(i)
            end if
        end do
    end subroutine reduced_unknowns

    !> States from the remote stress alone (D = 0): open where the effective normal
    !> traction is tensile, slipping towards the shear traction where it exceeds tau_s.
    pure subroutine initial_states(s_r_s, s_r_np, mu, sf, tol_s, open, shear_state)
        !> Remote shear and effective normal traction, shape (n) [stress]
        real(wp), intent(in) :: s_r_s(:), s_r_np(:)
        !> Friction coefficient [-] and frictional strength [stress], shape (n)
        real(wp), intent(in) :: mu(:), sf(:)
        !> State tolerance [stress]
        real(wp), intent(in) :: tol_s
        !> Normal and shear states, shape (n)
        logical, allocatable, intent(out) :: open(:)
        integer, allocatable, intent(out) :: shear_state(:)
        real(wp), allocatable :: tau(:)
        integer :: i

        open = s_r_np > tol_s
        tau = merge(sf, sf - mu * min(s_r_np, 0.0_wp), open)
        allocate (shear_state(size(mu)))
        do i = 1, size(mu)
            shear_state(i) = shear_stick
            if (abs(s_r_s(i)) > tau(i) + tol_s) shear_state(i) = int(sign(1.0_wp, s_r_s(i)))
        end do
    end subroutine initial_states

    !> Unknowns of the first reduced system of a one-shot solve (the states from the remote
    !> stress), for the memory estimate before the solve.
    pure integer function starting_unknowns(s_r_s, s_r_np, mu, sf, sigma0)
        !> Remote shear and effective normal traction, shape (n) [stress]
        real(wp), intent(in) :: s_r_s(:), s_r_np(:)
        !> Friction coefficient [-] and frictional strength [stress], shape (n)
        real(wp), intent(in) :: mu(:), sf(:)
        !> Stress scale of the problem [stress]
        real(wp), intent(in) :: sigma0
        logical, allocatable :: open(:)
        integer, allocatable :: shear_state(:)

        call initial_states(s_r_s, s_r_np, mu, sf, state_tol * sigma0, open, shear_state)
        starting_unknowns = count(shear_state /= shear_stick) + count(open)
    end function starting_unknowns

end module ddc_contact_active_set
