!> The paper's LCP (Ritz, Mutlu & Pollard 2012;
!> docs/theory/contact.md#the-linear-complementarity-problem) of a set of contact elements: with A
!> the 2N x 2N influence matrix ordered [s; n] (traction t = S_r + A D), C = A^-1 from the checked
!> LU, D0 = C S_r' (normal rows shifted by the fluid pressure p) and dMU = diag(mu),
!>
!>     z = [ -S_n' ; S_R ; D_L ]      w = [ -Dn ; D_R ; S_L ]      Ds = D_L - D_R
!>     M = [ CNN - CNS dMU , CNS , 0 ;  CSN - CSS dMU , CSS , I ;  2 dMU , -I , 0 ]
!>     q = [ D0_n - CNS Sf ; D0_s - CSS Sf ; 2 Sf ]
!>
!> solved by Lemke's method (ddc_contact_lemke) after scaling stresses by a stress scale
!> sigma0 (largest resolved remote stress, strength or pressure) and displacements by
!> delta0 = sigma0 / max_i A_ii, so that every entry is O(1). The solution is certified
!> (ddc_contact_certificate) against the unfactored M and checked (ddc_contact_result).
!>
!> Loading history (docs/theory/earth.md#loading-histories; build_contact_lcp once, then
!> solve_paper_lcp per step with the previous total slip and basis): the same M, q with the previous
!> total slip, Ds = Ds_previous + dD_L - dD_R, warm-started from the previous basis. DDs that are
!> exactly zero in the LCP (its nonbasic variables) are exactly zero here.
module ddc_contact_paper_lcp
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, set_internal_error, exit_solver_failure
    use ddc_contact_lemke, only: solve_lcp_lemke
    use ddc_contact_certificate, only: certify_lcp
    use ddc_contact_result, only: contact_result, block_scales, check_solution
    use ddc_linalg_lapack, only: dgemv
    use ddc_linalg_lu, only: lu_invert, influence_hint
    use ddc_text, only: seconds_text, itoa
    use ddc_allocation, only: allocation_failed, real_bytes
    use ddc_progress, only: report_progress, reports_phases
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: contact_lcp, build_contact_lcp, solve_paper_lcp, set_lcp_friction

    !> The paper's LCP matrix of a set of contact elements, built once for a sequence of
    !> loads (a loading history, docs/theory/earth.md#loading-histories): only q changes from step
    !> to step.
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

    !> Build the LCP matrix M of n contact elements once
    !> (docs/theory/contact.md#the-linear-complementarity-problem): C = A^-1 by LAPACK, M from C and
    !> mu, and M scaled for Lemke. The time and flops of the inverse are added to res.
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
        integer :: n, n2, n3, i, stat

        n = size(mu)
        n2 = 2 * n
        n3 = 3 * n
        if (size(a, 1) /= n2 .or. size(a, 2) /= n2) then
            call set_internal_error(error, 'build_contact_lcp', 'array sizes do not match')
            return
        end if
        call invert_influence(a, lcp%c, res, error)
        if (allocated(error)) return
        allocate (lcp%a(n2, n2), stat=stat)
        if (stat == 0) allocate (lcp%m(n3, n3), stat=stat)
        if (stat == 0) allocate (lcp%m_scaled(n3, n3), stat=stat)
        if (stat /= 0) then
            call allocation_failed(error, 'the LCP matrices of '//itoa(n)// &
                                   ' contact elements (Lemke)', &
                                   real_bytes * 22.0_wp * real(n, wp)**2)
            return
        end if
        lcp%a = a
        lcp%a_max = 0.0_wp
        do i = 1, n2
            lcp%a_max = max(lcp%a_max, abs(a(i, i)))
        end do
        if (.not. lcp%a_max > 0.0_wp) lcp%a_max = maxval(abs(a))
        if (.not. lcp%a_max > 0.0_wp) lcp%a_max = 1.0_wp
        call set_lcp_friction(lcp, mu)
    end subroutine build_contact_lcp

    !> M (and its scaled copy) for the friction coefficients mu, from the inverse C kept in
    !> lcp (slip weakening changes mu between solves: no new inverse).
    subroutine set_lcp_friction(lcp, mu)
        !> The LCP, built by build_contact_lcp
        type(contact_lcp), intent(inout) :: lcp
        !> Friction coefficient of each element, shape (n) [-]
        real(wp), intent(in) :: mu(:)
        real(wp), allocatable :: zs(:), ws(:)
        integer :: n, n2, n3, j

        n = size(mu)
        n2 = 2 * n
        n3 = 3 * n
        lcp%mu = mu

        ! M exactly as docs/theory/contact.md#the-linear-complementarity-problem writes it; C blocks
        ! are CSS = c(1:n, 1:n), CSN = c(1:n, n+1:2n), CNS = c(n+1:2n, 1:n), CNN = c(n+1:, n+1:).
        associate (c => lcp%c)
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
        do j = 1, n3
            lcp%m_scaled(:, j) = lcp%m(:, j) * (zs(j) / ws)
        end do
    end subroutine set_lcp_friction

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
        res%counts%seconds = res%counts%seconds + &
            real(t1 - t0, wp) / real(max(rate, 1_int64), wp)
        res%counts%flops = res%counts%flops + 2.0_wp * real(size(a, 1), wp)**3
        if (reports_phases(size(a, 1) / 2)) call report_progress('inverse of A for '// &
            "Lemke's LCP done in "//seconds_text(real(t1 - t0, wp) / real(max(rate, 1_int64), wp)))
    end subroutine invert_influence

    !> One LCP solve with frictional strength sf on a built LCP: q for the load (and the
    !> previous total slip ds_previous, docs/theory/earth.md#loading-histories; zero for a one-shot
    !> solve), scale, solve, certify, recover total DDs.
    subroutine solve_paper_lcp(lcp, s_r_s, s_r_n, sf, p, ds_previous, sigma0, res, error, rule, &
                          basis, max_pivots)
        type(contact_lcp), intent(in) :: lcp
        real(wp), intent(in) :: s_r_s(:), s_r_n(:), sf(:), p(:), ds_previous(:), sigma0
        type(contact_result), intent(inout) :: res
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: rule, max_pivots
        integer, intent(inout), optional :: basis(:)

        real(wp), allocatable :: q(:), z(:), w(:), zt(:), wt(:), d0(:), srp(:), zs(:), ws(:)
        real(wp), allocatable :: snp(:), ad(:)
        real(wp) :: delta0, dscale
        integer, allocatable :: warm(:)
        integer :: n, n2, n3, pivots
        character(len=300) :: line
        character(len=:), allocatable :: problem

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

        ! q as docs/theory/contact.md#the-linear-complementarity-problem writes it, with the
        ! previous slip (docs/theory/earth.md#loading-histories).
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

        ! Certificate against the unfactored M, with the block magnitudes: sigma0 for
        ! stresses and the larger of delta0 and the largest DD for displacements.
        dscale = max(delta0, maxval(abs(res%ds)), maxval(abs(res%dn)))
        call block_scales(n, sigma0, dscale, zs, ws)
        res%certificate = certify_lcp(lcp%m, q, z, w, z_scale=zs, w_scale=ws)
        allocate (ad(n2))
        call dgemv('N', n2, n2, 1.0_wp, lcp%a, n2, [res%ds, res%dn], 1, 0.0_wp, ad, 1)
        call check_solution(ad, s_r_s, s_r_n, lcp%mu, sf, snp, dscale, res, problem, &
                            ds_previous)
        if (len(problem) > 0) call set_error(error, exit_solver_failure, problem)
    end subroutine solve_paper_lcp

end module ddc_contact_paper_lcp
