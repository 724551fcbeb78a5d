!> Frictional contact on displacement discontinuity elements (SPEC section 4): the methods
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
!>
!> A failed LAPACK call, an LCP that no method solves, a failed certificate or a large
!> residual is an error (exit_solver_failure), never a result.
!>
!> solve_contact takes the dense influence matrix; solve_contact_with takes any stiffness
!> operator (ddc_contact_stiffness), e.g. a matrix distributed over MPI processes, and
!> without the dense matrix (Lemke's tableau needs it) solves by the Newton method alone: a
!> Newton failure is then an error (exit_solver_failure) that says why.
!>
!> open_cohesion: 'kept' (the paper) lets an open element carry shear up to Sf;
!> 'lost' sets Sf = 0 on every element that opens and solves again until no open
!> element has cohesion left (the set of such elements only grows, so this terminates).
module ddc_contact_formulation
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, set_internal_error, exit_bad_input, &
        exit_out_of_memory, exit_solver_failure
    use ddc_text, only: bytes_text
    use ddc_contact_memory, only: lemke_bytes
    use ddc_contact_options, only: solver_options, lcp_auto, lcp_newton, cohesion_lost
    use ddc_contact_certificate, only: certify_complementarity, default_certificate_tolerance
    use ddc_contact_active_set, only: active_set_result, solve_contact_active_set
    use ddc_contact_stiffness, only: stiffness_operator, dense_stiffness
    use ddc_contact_result, only: contact_result, contact_stress_scale, problem_scales, &
        block_scales, check_solution, drop_open_cohesion
    use ddc_contact_paper_lcp, only: contact_lcp, build_contact_lcp, solve_paper_lcp
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: solve_contact, solve_contact_with, auto_newton_min_elements, newton_max_iterations

    !> lcp_method = 'auto' uses 'newton' from this many contact elements on, else 'lemke'
    integer, parameter :: auto_newton_min_elements = 300
    !> Default iteration limit of the 'newton' method
    integer, parameter :: newton_max_iterations = 100

contains

    !> Solve the frictional contact problem of n elements (SPEC section 4).
    subroutine solve_contact(a, s_r_s, s_r_n, mu, sf, pressure, options, res, error, rule, &
                             max_iterations)
        !> Influence matrix ordered [s; n]: traction = s_r + a [Ds; Dn], shape (2n, 2n)
        !> [stress / length]
        real(wp), intent(in), target, contiguous :: a(:, :)
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
        type(dense_stiffness) :: stiffness

        if (size(a, 1) /= 2 * size(mu) .or. size(a, 2) /= 2 * size(mu)) then
            call set_internal_error(error, 'solve_contact', 'array sizes do not match')
            return
        end if
        stiffness%a => a
        call solve_contact_with(stiffness, s_r_s, s_r_n, mu, sf, pressure, options, res, error, &
                                a, rule, max_iterations)
    end subroutine solve_contact

    !> Solve the frictional contact problem of n elements (SPEC section 4) on any stiffness
    !> operator; without the dense matrix a, by the Newton method alone.
    subroutine solve_contact_with(stiffness, s_r_s, s_r_n, mu, sf, pressure, options, res, &
                                  error, a, rule, max_iterations)
        !> The influence matrix A ordered [s; n]: traction = s_r + A [Ds; Dn], 2n x 2n
        !> [stress / length]
        class(stiffness_operator), intent(inout) :: stiffness
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
        !> LCP method and cohesion of open elements (the method is 'newton' without a)
        type(solver_options), intent(in) :: options
        !> The solution
        type(contact_result), intent(out) :: res
        !> Allocated on failure (exit_solver_failure; exit_bad_input for NaN or Inf data,
        !> exit_internal_error for inconsistent arguments)
        type(error_type), allocatable, intent(out) :: error
        !> The same matrix in memory, shape (2n, 2n): Lemke's method needs it
        real(wp), intent(in), optional :: a(:, :)
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
        if (size(s_r_s) /= n .or. size(s_r_n) /= n .or. size(sf) /= n .or. &
            size(pressure) /= n) then
            call set_internal_error(error, 'solve_contact', 'array sizes do not match')
            return
        end if
        lost = options%open_cohesion == cohesion_lost
        if (.not. (stiffness%all_finite() .and. all(ieee_is_finite(s_r_s)) .and. &
            all(ieee_is_finite(s_r_n)) .and. all(ieee_is_finite(mu)) .and. &
            all(ieee_is_finite(sf)) .and. all(ieee_is_finite(pressure)))) then
            call set_error(error, exit_bad_input, 'contact: NaN or Inf in the input arrays')
            return
        end if
        automatic = options%lcp_method == lcp_auto
        newton = options%lcp_method == lcp_newton .or. .not. present(a) .or. &
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
                call solve_once_newton(stiffness, s_r_s, s_r_n, mu, sf_eff, pressure, limit, &
                    res, states, reason)
                if (len(reason) > 0 .and. .not. present(a)) then
                    call set_error(error, exit_solver_failure, 'contact: '//reason)
                else if (len(reason) > 0) then
                    newton = .false.
                    res%method = 'lemke'
                    res%fallback = reason
                end if
            end if
            if (.not. newton) then
                if (.not. allocated(lcp%m) .and. len(res%fallback) > 0 .and. &
                    lemke_bytes(n) > options%work_bytes) then
                    call set_error(error, exit_out_of_memory, 'contact: the Newton method '// &
                        'failed ('//res%fallback//') and the fallback to Lemke would need '// &
                        'about '//bytes_text(lemke_bytes(n))//' more memory, but about '// &
                        bytes_text(options%work_bytes)//' is left here')
                    return
                end if
                if (.not. allocated(lcp%m)) then
                    call build_contact_lcp(a, mu, lcp, res, error)
                    if (allocated(error)) return
                    allocate (no_slip(n), source=0.0_wp)
                end if
                call solve_paper_lcp(lcp, s_r_s, s_r_n, sf_eff, pressure, no_slip, &
                    contact_stress_scale(s_r_s, s_r_n, sf, pressure), res, error, rule=rule)
                if (allocated(error) .and. automatic .and. len(res%fallback) == 0) then
                    ! M is not copositive-plus: Lemke can end on a ray where the contact
                    ! problem has a solution (seen at acute fault branches). 'auto' then
                    ! asks the Newton method, whose answer is checked the same way, and
                    ! keeps it for the rounds after cohesion is lost.
                    call solve_once_newton(stiffness, s_r_s, s_r_n, mu, sf_eff, pressure, &
                        limit, res, states, reason)
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
    end subroutine solve_contact_with

    !> One solve by the active-set Newton method (no inverse of A), certified as the
    !> equivalent LCP. reason is empty on success, else why Lemke must take over.
    subroutine solve_once_newton(stiffness, s_r_s, s_r_n, mu, sf, p, limit, res, states, reason)
        class(stiffness_operator), intent(inout) :: stiffness
        real(wp), intent(in) :: s_r_s(:), s_r_n(:), mu(:), sf(:), p(:)
        integer, intent(in) :: limit
        type(contact_result), intent(inout) :: res
        !> States of the previous solve on entry (warm start when allocated); this solve's
        !> on exit
        type(active_set_result), intent(inout) :: states
        character(len=:), allocatable, intent(out) :: reason
        type(active_set_result) :: next
        real(wp), allocatable :: tau(:), z(:), w(:), zs(:), ws(:), snp(:), ad(:)
        real(wp) :: dscale, stiffness_scale
        integer :: n, n2, i
        character(len=:), allocatable :: problem

        n = size(mu)
        n2 = 2 * n
        stiffness_scale = stiffness%max_diagonal()
        if (.not. stiffness_scale > 0.0_wp) stiffness_scale = stiffness%max_entry()
        call problem_scales(stiffness_scale, s_r_s, s_r_n, sf, p, res)
        if (allocated(states%open)) then
            call solve_contact_active_set(stiffness, s_r_s, s_r_n + p, mu, sf, &
                res%stress_scale, next, limit, states%open, states%shear_state)
        else
            call solve_contact_active_set(stiffness, s_r_s, s_r_n + p, mu, sf, &
                res%stress_scale, next, limit)
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
        allocate (ad(n2), source=0.0_wp)
        call stiffness%multiply([res%ds, res%dn], ad)
        call check_solution(ad, s_r_s, s_r_n, mu, sf, snp, dscale, res, problem)
        reason = ''
        if (len(problem) > 0) reason = 'newton: '//problem
    end subroutine solve_once_newton

end module ddc_contact_formulation
