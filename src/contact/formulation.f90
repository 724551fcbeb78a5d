!> Frictional contact on displacement discontinuity elements as an LCP (SPEC section 4).
!>
!> The paper's formulation (Ritz, Mutlu & Pollard 2012): with A the 2N x 2N influence
!> matrix of the contact elements ordered [s; n] (traction t = S_r + A D), C = A^-1 from
!> LAPACK, D0 = C S_r' (normal rows shifted by the fluid pressure p) and dMU = diag(mu),
!>
!>     z = [ -S_n' ; S_R ; D_L ]      w = [ -Dn ; D_R ; S_L ]      Ds = D_L - D_R
!>     M = [ CNN - CNS dMU , CNS , 0 ;  CSN - CSS dMU , CSS , I ;  2 dMU , -I , 0 ]
!>     q = [ D0_n - CNS Sf ; D0_s - CSS Sf ; 2 Sf ]
!>
!> solved by Lemke's method (ddc_contact_lemke) after scaling stresses by a stress scale
!> sigma0 (largest resolved remote stress, strength or pressure) and displacements by
!> delta0 = sigma0 / max_i A_ii, so that every entry is O(1). The solution is certified
!> (ddc_contact_certificate) against the unfactored M, and the recovered DDs are checked
!> against the unfactored A (equilibrium residual per block). A failed LAPACK call, an
!> LCP that Lemke cannot solve, a failed certificate or a large residual is an error
!> (exit_solver_failure), never a result.
!>
!> States (codes of ddc_model_results): open when the opening -Dn exceeds
!> state_dd_tol * dd_scale; otherwise slip when |Ds| (in a loading history the slip
!> increment of the step) exceeds that tolerance or the element is on its friction limit
!> (tau_s - |s_s| <= state_stress_tol * sigma0); otherwise stick.
!>
!> Loading history (SPEC-EARTH section 3; build_contact_lcp once, then
!> solve_contact_increment per step): the same M, q with the previous total slip,
!> Ds = Ds_previous + dD_L - dD_R; always Lemke, warm-started from the previous basis.
!> dd_scale = max(max |Ds|, max |Dn|, delta0): DDs that are exactly zero in the LCP (its
!> nonbasic variables) are exactly zero here; basic variables that are zero in exact
!> arithmetic come out at round-off level, far below the tolerance.
!>
!> Methods (options%lcp_method of solve_contact, &solver lcp_method):
!> - 'lemke': the paper's LCP above, solved by the lexicographic Lemke method (reference);
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
!>
!> open_cohesion: 'kept' (the paper) lets an open element carry shear up to Sf;
!> 'lost' sets Sf = 0 on every element that opens and solves again until no open
!> element has cohesion left (the set of such elements only grows, so this terminates).
module ddc_contact_formulation
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, set_internal_error, exit_solver_failure, &
        exit_bad_input
    use ddc_contact_states, only: state_stick, state_slip, state_open
    use ddc_contact_options, only: solver_options, lcp_auto, lcp_newton, cohesion_lost
    use ddc_contact_lemke, only: solve_lcp_lemke
    use ddc_contact_certificate, only: lcp_certificate, certify_lcp, &
        certify_complementarity, default_certificate_tolerance
    use ddc_contact_active_set, only: active_set_result, solve_contact_active_set
    use ddc_linalg_lapack, only: dgemv
    use ddc_linalg_lu, only: lu_invert, influence_hint, residual_tol
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: contact_result, solve_contact
    public :: contact_lcp, build_contact_lcp, solve_contact_increment, contact_stress_scale
    public :: state_dd_tol, state_stress_tol, residual_tol
    public :: auto_newton_min_elements, newton_max_iterations

    !> Relative tolerance on DDs for the state rule (times dd_scale) [-]
    real(wp), parameter :: state_dd_tol = 1.0e-9_wp
    !> Relative tolerance on the friction limit for the state rule (times sigma0) [-]
    real(wp), parameter :: state_stress_tol = 1.0e-9_wp
    !> lcp_method = 'auto' uses 'newton' from this many contact elements on, else 'lemke'
    integer, parameter :: auto_newton_min_elements = 300
    !> Default iteration limit of the 'newton' method
    integer, parameter :: newton_max_iterations = 100

    !> Solution of a contact problem on n elements; arrays shape (n).
    type :: contact_result
        !> Shear and normal displacement discontinuity, C&S signs (opening = -dn) [length]
        real(wp), allocatable :: ds(:), dn(:)
        !> Total shear and normal traction, tension positive, not shifted by p [stress]
        real(wp), allocatable :: shear_traction(:), normal_traction(:)
        !> state_stick, state_slip or state_open
        integer, allocatable :: state(:)
        !> Frictional strength in force at the end (0 where cohesion was lost) [stress]
        real(wp), allocatable :: sf_effective(:)
        !> Method that produced the result: 'lemke' or 'newton'
        character(len=:), allocatable :: method
        !> Why the first method failed and the other one produced the result: Newton falling
        !> back to Lemke, or (lcp_method 'auto') Lemke to Newton; empty when neither did
        character(len=:), allocatable :: fallback
        !> Newton (active-set) iterations, summed over solves
        integer :: iterations = 0
        !> Lemke pivots, summed over all LCP solves
        integer :: pivots = 0
        !> Number of LCP solves (1 unless open_cohesion = 'lost' re-solved)
        integer :: solves = 0
        !> Certificate of the last LCP solve
        type(lcp_certificate) :: certificate
        !> Relative equilibrium residual ||A D + S_r - t|| / scale, shear and normal block
        real(wp) :: equilibrium_residual(2) = 0.0_wp
        !> Stress scale sigma0 [stress] and displacement scale delta0 [length] used
        real(wp) :: stress_scale = 1.0_wp, dd_scale = 1.0_wp
        !> Wall time of the factorizations (the inverse of A for Lemke, the LU of the reduced
        !> systems for newton) and of the rest of the contact solves (building M, Lemke or
        !> the active-set iteration, certificate and recovery, summed over solves) [s]
        real(wp) :: seconds_factorization = 0.0_wp, seconds_lcp = 0.0_wp
        !> Nominal flop count of those factorizations (2/3 m^3 per LU of size m; 2 m^3 for
        !> the inverse of A) [-]
        real(wp) :: factorization_flops = 0.0_wp
    end type contact_result


    !> The paper's LCP matrix of a set of contact elements, built once for a sequence of
    !> loads (a loading history, SPEC-EARTH section 3): only q changes from step to step.
    type :: contact_lcp
        !> Influence matrix ordered [s; n], shape (2n, 2n) [stress / length]
        real(wp), allocatable :: a(:, :)
        !> Its inverse C = A^-1, shape (2n, 2n) [length / stress]
        real(wp), allocatable :: c(:, :)
        !> M of the LCP (unscaled, for the certificate) and M scaled for Lemke (stresses by
        !> sigma0, displacements by sigma0 / max A_ii: independent of sigma0), shape (3n, 3n)
        real(wp), allocatable :: m(:, :), m_scaled(:, :)
        !> Friction coefficient, shape (n) [-]
        real(wp), allocatable :: mu(:)
        !> max_i A_ii [stress / length]
        real(wp) :: a_max = 1.0_wp
    end type contact_lcp

contains

    !> Solve the frictional contact problem of n elements (SPEC section 4).
    subroutine solve_contact(a, s_r_s, s_r_n, mu, sf, pressure, options, res, error, rule, &
                             max_iterations)
        !> Influence matrix ordered [s; n]: traction = s_r + a [Ds; Dn], shape (2n, 2n)
        !> [stress / length]
        real(wp), intent(in) :: a(:, :)
        !> Remote shear traction resolved on each element (plus any traction from
        !> non-contact elements), shape (n) [stress]
        real(wp), intent(in) :: s_r_s(:)
        !> Remote normal traction resolved on each element, tension positive, shape (n)
        !> [stress]
        real(wp), intent(in) :: s_r_n(:)
        !> Friction coefficient, shape (n) [-]
        real(wp), intent(in) :: mu(:)
        !> Frictional strength (cohesion), shape (n) [stress]
        real(wp), intent(in) :: sf(:)
        !> Fluid pressure inside the crack, compression positive, shape (n) [stress]
        real(wp), intent(in) :: pressure(:)
        !> LCP method and cohesion of open elements
        type(solver_options), intent(in) :: options
        !> The solution
        type(contact_result), intent(out) :: res
        !> Allocated on failure (exit_solver_failure; exit_bad_input for NaN or Inf data,
        !> exit_internal_error for inconsistent arguments)
        type(error_type), allocatable, intent(out) :: error
        !> Tie-breaking rule of Lemke (tests only; default lexicographic)
        integer, intent(in), optional :: rule
        !> Iteration limit of 'newton' (default newton_max_iterations)
        integer, intent(in), optional :: max_iterations

        real(wp), allocatable :: sf_eff(:), no_slip(:)
        type(contact_lcp) :: lcp
        type(active_set_result) :: states
        integer :: n, limit
        integer(int64) :: t0, t1, rate
        logical :: lost, newton, automatic
        integer :: rounds
        character(len=:), allocatable :: reason
        character(len=200) :: line

        n = size(mu)
        if (size(a, 1) /= 2 * n .or. size(a, 2) /= 2 * n .or. size(s_r_s) /= n &
            .or. size(s_r_n) /= n .or. size(sf) /= n .or. size(pressure) /= n) then
            call set_internal_error(error, 'solve_contact', 'array sizes do not match')
            return
        end if
        lost = options%open_cohesion == cohesion_lost
        if (.not. (all(ieee_is_finite(a)) .and. all(ieee_is_finite(s_r_s)) .and. &
            all(ieee_is_finite(s_r_n)) .and. all(ieee_is_finite(mu)) .and. &
            all(ieee_is_finite(sf)) .and. all(ieee_is_finite(pressure)))) then
            call set_error(error, exit_bad_input, 'contact: NaN or Inf in the input arrays')
            return
        end if
        automatic = options%lcp_method == lcp_auto
        newton = options%lcp_method == lcp_newton .or. &
            (automatic .and. n >= auto_newton_min_elements)
        limit = newton_max_iterations
        if (present(max_iterations)) limit = max_iterations
        if (any(mu < 0.0_wp) .or. any(sf < 0.0_wp)) then
            call set_internal_error(error, 'solve_contact', 'mu and sf must not be negative')
            return
        end if
        if (n == 0) then
            allocate (res%ds(0), res%dn(0), res%shear_traction(0), res%normal_traction(0), &
                res%state(0), res%sf_effective(0))
            res%certificate%passed = .true.
            return
        end if

        if (newton) then
            res%method = 'newton'
        else
            res%method = 'lemke'
        end if
        res%fallback = ''
        rounds = 0
        call system_clock(t0, rate)
        sf_eff = sf
        do
            rounds = rounds + 1
            if (newton) then
                call solve_once_newton(a, s_r_s, s_r_n, mu, sf_eff, pressure, limit, res, &
                    states, reason)
                if (len(reason) > 0) then
                    newton = .false.
                    res%method = 'lemke'
                    res%fallback = reason
                end if
            end if
            if (.not. newton) then
                if (.not. allocated(lcp%m)) then
                    call build_contact_lcp(a, mu, lcp, res, error)
                    if (allocated(error)) return
                    allocate (no_slip(n), source=0.0_wp)
                end if
                call solve_once(lcp, s_r_s, s_r_n, sf_eff, pressure, no_slip, &
                    contact_stress_scale(s_r_s, s_r_n, sf, pressure), res, error, rule=rule)
                if (allocated(error) .and. automatic .and. len(res%fallback) == 0) then
                    ! M is not copositive-plus: Lemke can end on a ray where the contact
                    ! problem has a solution (seen at acute fault branches). 'auto' then
                    ! asks the Newton method, whose answer is checked the same way, and
                    ! keeps it for the rounds after cohesion is lost.
                    call solve_once_newton(a, s_r_s, s_r_n, mu, sf_eff, pressure, limit, res, &
                        states, reason)
                    if (len(reason) == 0) then
                        newton = .true.
                        res%method = 'newton'
                        res%fallback = 'lemke failed: '//error%message
                        deallocate (error)
                    else
                        error%message = error%message//' (the Newton method failed too: '// &
                            reason//')'
                    end if
                end if
            end if
            if (allocated(error)) then
                if (rounds > 1) then
                    write (line, '(a,i0,a)') ' (solve ', rounds, &
                        ", after cohesion was lost on opening elements)"
                    error%message = error%message//trim(line)
                end if
                if (len(res%fallback) > 0) error%message = error%message// &
                    ' (after the first method failed: '//res%fallback//')'
                return
            end if
            if (.not. lost) exit
            if (.not. drop_open_cohesion(res%state, sf_eff)) exit
        end do
        call system_clock(t1)
        res%seconds_lcp = real(t1 - t0, wp) / real(max(rate, 1_int64), wp) - &
            res%seconds_factorization
    end subroutine solve_contact

    !> Zero the cohesion of every open element that still has some; true when any did.
    function drop_open_cohesion(state, sf_eff) result(changed)
        integer, intent(in) :: state(:)
        real(wp), intent(inout) :: sf_eff(:)
        logical :: changed
        logical :: lose(size(state))

        lose = state == state_open .and. sf_eff > 0.0_wp
        changed = any(lose)
        where (lose) sf_eff = 0.0_wp
    end function drop_open_cohesion

    !> Build the LCP matrix M of n contact elements once (SPEC section 4): C = A^-1 by
    !> LAPACK, M from C and mu, and M scaled for Lemke. The time and flops of the inverse
    !> are added to res.
    subroutine build_contact_lcp(a, mu, lcp, res, error)
        !> Influence matrix ordered [s; n], shape (2n, 2n) [stress / length]
        real(wp), intent(in) :: a(:, :)
        !> Friction coefficient, shape (n) [-]
        real(wp), intent(in) :: mu(:)
        !> The LCP matrix and what it was built from
        type(contact_lcp), intent(out) :: lcp
        !> Factorization time and flops are added
        type(contact_result), intent(inout) :: res
        !> Allocated when A is singular (exit_solver_failure) or sizes differ
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: zs(:), ws(:)
        integer :: n, n2, n3, i, j

        n = size(mu)
        n2 = 2 * n
        n3 = 3 * n
        if (size(a, 1) /= n2 .or. size(a, 2) /= n2) then
            call set_internal_error(error, 'build_contact_lcp', 'array sizes do not match')
            return
        end if
        call invert_influence(a, lcp%c, res, error)
        if (allocated(error)) return
        lcp%a = a
        lcp%mu = mu
        lcp%a_max = 0.0_wp
        do i = 1, n2
            lcp%a_max = max(lcp%a_max, abs(a(i, i)))
        end do
        if (.not. lcp%a_max > 0.0_wp) lcp%a_max = maxval(abs(a))
        if (.not. lcp%a_max > 0.0_wp) lcp%a_max = 1.0_wp

        ! M exactly as SPEC section 4 writes it; C blocks are CSS = c(1:n, 1:n),
        ! CSN = c(1:n, n+1:2n), CNS = c(n+1:2n, 1:n), CNN = c(n+1:, n+1:).
        associate (c => lcp%c)
            allocate (lcp%m(n3, n3))
            lcp%m = 0.0_wp
            do j = 1, n
                lcp%m(1:n, j) = c(n + 1:n2, n + j) - c(n + 1:n2, j) * mu(j)
                lcp%m(1:n, n + j) = c(n + 1:n2, j)
                lcp%m(n + 1:n2, j) = c(1:n, n + j) - c(1:n, j) * mu(j)
                lcp%m(n + 1:n2, n + j) = c(1:n, j)
                lcp%m(n + j, n2 + j) = 1.0_wp
                lcp%m(n2 + j, j) = 2.0_wp * mu(j)
                lcp%m(n2 + j, n + j) = -1.0_wp
            end do
        end associate
        ! Scaled problem: z = zs * zt, w = ws * wt with z = [stress; stress; length] and
        ! w = [length; length; stress]; with sigma0 = 1 (the ratios do not depend on it).
        call block_scales(n, 1.0_wp, 1.0_wp / lcp%a_max, zs, ws)
        allocate (lcp%m_scaled(n3, n3))
        do j = 1, n3
            lcp%m_scaled(:, j) = lcp%m(:, j) * (zs(j) / ws)
        end do
    end subroutine build_contact_lcp

    !> Magnitude of each row of z = [stress; stress; length] and w = [length; length;
    !> stress] of an LCP on n elements, for a stress scale and a displacement scale.
    pure subroutine block_scales(n, stress, length, zs, ws)
        integer, intent(in) :: n
        real(wp), intent(in) :: stress, length
        real(wp), allocatable, intent(out) :: zs(:), ws(:)

        zs = [spread(stress, 1, 2 * n), spread(length, 1, n)]
        ws = [spread(length, 1, 2 * n), spread(stress, 1, n)]
    end subroutine block_scales

    !> One step of a loading history (SPEC-EARTH section 3) on an LCP built once: q for
    !> the step's load with the previous total slip, solved by Lemke (warm-started from
    !> the previous step's basis when that basis is still feasible), certified and
    !> recovered; total DDs in res. open_cohesion 'lost' re-solves the step until no open
    !> element keeps cohesion; sf_effective carries the lost cohesion to later steps.
    subroutine solve_contact_increment(lcp, s_r_s, s_r_n, sf_effective, pressure, &
                                       open_cohesion, ds_previous, stress_scale, basis, res, &
                                       error, max_pivots)
        !> The LCP matrix (build_contact_lcp)
        type(contact_lcp), intent(in) :: lcp
        !> Remote shear and normal traction on each element at this step, shape (n) [stress]
        real(wp), intent(in) :: s_r_s(:), s_r_n(:)
        !> Frictional strength in force, shape (n) [stress]; set to 0 where cohesion is lost
        real(wp), intent(inout) :: sf_effective(:)
        !> Fluid pressure inside each element at this step, shape (n) [stress]
        real(wp), intent(in) :: pressure(:)
        !> cohesion_kept or cohesion_lost
        integer, intent(in) :: open_cohesion
        !> Total shear DD at the end of the previous step, shape (n) [length]
        real(wp), intent(in) :: ds_previous(:)
        !> Stress scale sigma0 of the whole history (contact_stress_scale, largest over
        !> the steps) [stress]
        real(wp), intent(in) :: stress_scale
        !> LCP basis of the previous step on entry (0 entries: none), this step's on exit,
        !> shape (3n)
        integer, intent(inout) :: basis(:)
        !> This step's solution (total DDs, tractions, states, certificate, pivots)
        type(contact_result), intent(out) :: res
        !> Allocated when the step has no certified solution (exit_solver_failure)
        type(error_type), allocatable, intent(out) :: error
        !> Pivot limit of each Lemke solve (default that of solve_lcp_lemke)
        integer, intent(in), optional :: max_pivots

        res%method = 'lemke'
        res%fallback = ''
        do
            call solve_once(lcp, s_r_s, s_r_n, sf_effective, pressure, ds_previous, &
                            stress_scale, res, error, basis=basis, max_pivots=max_pivots)
            if (allocated(error)) return
            if (open_cohesion /= cohesion_lost) exit
            if (.not. drop_open_cohesion(res%state, sf_effective)) exit
        end do
    end subroutine solve_contact_increment

    !> Stress scale sigma0 of a contact problem: the largest resolved remote stress,
    !> strength or pressure (1 when all vanish) [stress].
    pure function contact_stress_scale(s_r_s, s_r_n, sf, p) result(sigma0)
        !> Remote shear and normal traction, strength and pressure, shape (n) [stress]
        real(wp), intent(in) :: s_r_s(:), s_r_n(:), sf(:), p(:)
        !> The scale [stress]
        real(wp) :: sigma0

        sigma0 = max(maxval(abs(s_r_s)), maxval(abs(s_r_n)), maxval(abs(s_r_n + p)), &
            maxval(abs(sf)), maxval(abs(p)))
        if (.not. sigma0 > 0.0_wp) sigma0 = 1.0_wp
    end function contact_stress_scale

    !> C = A^-1 by the checked LU (ddc_linalg_lu); singular or numerically singular A is an
    !> error. Its time and nominal flops (2 (2n)^3) are added to res.
    subroutine invert_influence(a, c, res, error)
        real(wp), intent(in) :: a(:, :)
        real(wp), allocatable, intent(out) :: c(:, :)
        type(contact_result), intent(inout) :: res
        type(error_type), allocatable, intent(out) :: error
        integer(int64) :: t0, t1, rate

        call system_clock(t0, rate)
        call lu_invert(a, c, 'contact: influence matrix', error)
        if (allocated(error)) then
            error%message = error%message//influence_hint
            return
        end if
        call system_clock(t1)
        res%seconds_factorization = res%seconds_factorization + &
            real(t1 - t0, wp) / real(max(rate, 1_int64), wp)
        res%factorization_flops = res%factorization_flops + 2.0_wp * real(size(a, 1), wp)**3
    end subroutine invert_influence

    !> Stress scale sigma0 (contact_stress_scale) and displacement scale delta0 =
    !> sigma0 / max_i A_ii of a problem; both stored in res.
    subroutine problem_scales(a, s_r_s, s_r_n, sf, p, res)
        real(wp), intent(in) :: a(:, :), s_r_s(:), s_r_n(:), sf(:), p(:)
        type(contact_result), intent(inout) :: res
        real(wp) :: amax
        integer :: i

        amax = 0.0_wp
        do i = 1, size(a, 1)
            amax = max(amax, abs(a(i, i)))
        end do
        if (.not. amax > 0.0_wp) amax = maxval(abs(a))
        res%stress_scale = contact_stress_scale(s_r_s, s_r_n, sf, p)
        res%dd_scale = res%stress_scale / amax
    end subroutine problem_scales

    !> One LCP solve with frictional strength sf on a built LCP: q for the load (and the
    !> previous total slip ds_previous, SPEC-EARTH section 3; zero for a one-shot solve),
    !> scale, solve, certify, recover total DDs.
    subroutine solve_once(lcp, s_r_s, s_r_n, sf, p, ds_previous, sigma0, res, error, rule, &
                          basis, max_pivots)
        type(contact_lcp), intent(in) :: lcp
        real(wp), intent(in) :: s_r_s(:), s_r_n(:), sf(:), p(:), ds_previous(:), sigma0
        type(contact_result), intent(inout) :: res
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: rule, max_pivots
        integer, intent(inout), optional :: basis(:)

        real(wp), allocatable :: q(:), z(:), w(:), zt(:), wt(:), d0(:), srp(:), zs(:), ws(:)
        real(wp), allocatable :: snp(:)
        real(wp) :: delta0, dscale
        integer, allocatable :: warm(:)
        integer :: n, n2, n3, pivots
        character(len=300) :: line

        n = size(lcp%mu)
        n2 = 2 * n
        n3 = 3 * n

        ! Scales: stresses by sigma0, displacements by delta0 = sigma0 / max A_ii.
        delta0 = sigma0 / lcp%a_max
        res%stress_scale = sigma0
        res%dd_scale = delta0

        ! D0 = C S_r' with S_r' = [s_r_s; s_r_n + p].
        srp = [s_r_s, s_r_n + p]
        allocate (d0(n2))
        call dgemv('N', n2, n2, 1.0_wp, lcp%c, n2, srp, 1, 0.0_wp, d0, 1)

        ! q as SPEC section 4 writes it, with the previous slip (SPEC-EARTH section 3).
        allocate (q(n3))
        q(1:n) = d0(n + 1:n2) - matmul(lcp%c(n + 1:n2, 1:n), sf)
        q(n + 1:n2) = d0(1:n) - matmul(lcp%c(1:n, 1:n), sf) + ds_previous
        q(n2 + 1:n3) = 2.0_wp * sf

        call block_scales(n, sigma0, delta0, zs, ws)
        allocate (zt(n3), wt(n3))
        if (present(basis)) then
            warm = basis
            call solve_lcp_lemke(lcp%m_scaled, q / ws, zt, wt, pivots, error, rule=rule, &
                max_pivots=max_pivots, warm_basis=warm, basis=basis)
        else
            call solve_lcp_lemke(lcp%m_scaled, q / ws, zt, wt, pivots, error, rule=rule, &
                max_pivots=max_pivots)
        end if
        res%pivots = res%pivots + pivots
        res%solves = res%solves + 1
        if (allocated(error)) then
            write (line, '(a,i0,a)') '; LCP rows k, N + k and 2N + k belong to contact &
                &element k (N = ', n, ')'
            error%code = exit_solver_failure
            error%message = 'contact: '//error%message//trim(line)
            return
        end if
        z = zt * zs
        w = wt * ws

        ! Recovery: Ds = Ds_previous + dD_L - dD_R.
        res%dn = -w(1:n)
        res%ds = ds_previous + z(n2 + 1:n3) - w(n + 1:n2)
        snp = -z(1:n)
        res%shear_traction = -z(n + 1:n2) - lcp%mu * snp + sf
        res%normal_traction = snp - p
        res%sf_effective = sf

        ! Certificate against the unfactored M, with the block magnitudes: sigma0 for
        ! stresses and the larger of delta0 and the largest DD for displacements.
        dscale = max(delta0, maxval(abs(res%ds)), maxval(abs(res%dn)))
        call block_scales(n, sigma0, dscale, zs, ws)
        res%certificate = certify_lcp(lcp%m, q, z, w, z_scale=zs, w_scale=ws)
        call check_solution(lcp%a, s_r_s, s_r_n, lcp%mu, sf, snp, dscale, res, line, &
                            ds_previous)
        if (len_trim(line) > 0) call set_error(error, exit_solver_failure, trim(line))
    end subroutine solve_once

    !> One solve by the active-set Newton method (no inverse of A), certified as the
    !> equivalent LCP. reason is empty on success, else why Lemke must take over.
    subroutine solve_once_newton(a, s_r_s, s_r_n, mu, sf, p, limit, res, states, reason)
        real(wp), intent(in) :: a(:, :), s_r_s(:), s_r_n(:), mu(:), sf(:), p(:)
        integer, intent(in) :: limit
        type(contact_result), intent(inout) :: res
        !> States of the previous solve on entry (warm start when allocated); this solve's
        !> on exit
        type(active_set_result), intent(inout) :: states
        character(len=:), allocatable, intent(out) :: reason
        type(active_set_result) :: next
        real(wp), allocatable :: tau(:), z(:), w(:), zs(:), ws(:), snp(:)
        real(wp) :: dscale
        integer :: n, n2, i
        character(len=300) :: line

        n = size(mu)
        n2 = 2 * n
        call problem_scales(a, s_r_s, s_r_n, sf, p, res)
        if (allocated(states%open)) then
            call solve_contact_active_set(a, s_r_s, s_r_n + p, mu, sf, res%stress_scale, &
                next, limit, states%open, states%shear_state)
        else
            call solve_contact_active_set(a, s_r_s, s_r_n + p, mu, sf, res%stress_scale, &
                next, limit)
        end if
        res%iterations = res%iterations + next%iterations
        res%solves = res%solves + 1
        res%seconds_factorization = res%seconds_factorization + next%seconds_factorization
        res%factorization_flops = res%factorization_flops + next%factorization_flops
        if (.not. next%converged) then
            reason = 'newton: '//next%reason
            return
        end if
        states = next

        ! z and w of the paper's LCP from the DDs and the tractions A D + S_r of the
        ! unfactored A; Ds split as D_L - D_R with the smaller part zero.
        associate (ss => next%shear, snf => next%normal_effective)
            tau = sf - mu * snf
            z = [-snf, tau - ss, max(next%ds, 0.0_wp)]
            w = [-next%dn, max(-next%ds, 0.0_wp), tau + ss]
        end associate
        dscale = max(res%dd_scale, maxval(abs(next%ds)), maxval(abs(next%dn)))
        call block_scales(n, res%stress_scale, dscale, zs, ws)
        res%certificate = certify_complementarity(z, w, zs, ws, default_certificate_tolerance)

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
        res%sf_effective = sf
        call check_solution(a, s_r_s, s_r_n, mu, sf, snp, dscale, res, line)
        reason = 'newton: '//trim(line)
        if (len_trim(line) == 0) reason = ''
    end subroutine solve_once_newton

    !> Checks common to both methods on a recovered solution (res%ds, dn, tractions):
    !> the certificate passed and the DDs are in equilibrium with the tractions against the
    !> unfactored A; then the states (slip: a slip increment over ds_previous, when given, or
    !> on the friction limit). message is blank on success, else says what failed.
    subroutine check_solution(a, s_r_s, s_r_n, mu, sf, snp, dscale, res, message, ds_previous)
        real(wp), intent(in) :: a(:, :), s_r_s(:), s_r_n(:), mu(:), sf(:), snp(:), dscale
        type(contact_result), intent(inout) :: res
        character(len=*), intent(out) :: message
        real(wp), intent(in), optional :: ds_previous(:)
        real(wp), allocatable :: dd(:), ad(:), tau(:), slip(:)
        real(wp) :: tol_d, tol_s, scale
        integer :: n, n2, i

        message = ''
        n = size(mu)
        n2 = 2 * n
        if (.not. res%certificate%passed) then
            write (message, '(a,4(es10.3,a))') 'contact: the LCP solution fails its &
                &certificate (scaled min z ', res%certificate%min_z, ', min w ', &
                res%certificate%min_w, ', max |z w| ', res%certificate%max_complementarity, &
                ', w mismatch ', res%certificate%max_w_mismatch, ')'
            return
        end if

        ! Equilibrium of the recovered DDs against the unfactored A.
        dd = [res%ds, res%dn]
        allocate (ad(n2))
        call dgemv('N', n2, n2, 1.0_wp, a, n2, dd, 1, 0.0_wp, ad, 1)
        ! Both blocks are tractions: one scale for both, so that a block that vanishes (no
        ! resolved shear at all) is not measured against its own round-off.
        scale = max(norm2(ad), norm2([s_r_s, s_r_n]), &
                    norm2([res%shear_traction, res%normal_traction]))
        res%equilibrium_residual(1) = block_residual(ad(1:n), s_r_s, res%shear_traction, scale)
        res%equilibrium_residual(2) = block_residual(ad(n + 1:n2), s_r_n, &
            res%normal_traction, scale)
        if (.not. maxval(res%equilibrium_residual) <= residual_tol) then
            write (message, '(a,2(es10.3,a))') 'contact: the recovered DDs are not in &
                &equilibrium (relative residual ', res%equilibrium_residual(1), &
                ' shear, ', res%equilibrium_residual(2), ' normal)'
            return
        end if

        ! States.
        tol_d = state_dd_tol * dscale
        tol_s = state_stress_tol * res%stress_scale
        tau = sf - mu * snp
        slip = res%ds
        if (present(ds_previous)) slip = res%ds - ds_previous
        if (allocated(res%state)) deallocate (res%state)
        allocate (res%state(n))
        do i = 1, n
            if (-res%dn(i) > tol_d) then
                res%state(i) = state_open
            else if (abs(slip(i)) > tol_d .or. tau(i) - abs(res%shear_traction(i)) <= tol_s) &
                then
                res%state(i) = state_slip
            else
                res%state(i) = state_stick
            end if
        end do
    end subroutine check_solution

    !> ||ad + s_r - t|| / scale, 0 when the scale vanishes.
    pure function block_residual(ad, s_r, t, scale) result(r)
        real(wp), intent(in) :: ad(:), s_r(:), t(:), scale
        real(wp) :: r

        if (scale > 0.0_wp) then
            r = norm2(ad + s_r - t) / scale
        else
            r = 0.0_wp
        end if
    end function block_residual

end module ddc_contact_formulation
