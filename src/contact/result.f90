!> The solution of a contact problem (docs/theory/contact.md#the-certificate), whichever method
!> produced it, and the checks every solution passes before it is a result: the LCP certificate has
!> passed, the recovered DDs are in equilibrium with the tractions against the unfactored influence
!> matrix (relative residual per block at most residual_tol), and each element gets its
!> state.
!>
!> States (ddc_contact_states): open when the opening -Dn exceeds state_dd_tol * dd_scale;
!> otherwise slip when |Ds| (in a loading history the slip increment of the step) exceeds
!> that tolerance or the element is on its friction limit (tau_s - |s_s| <=
!> state_stress_tol * sigma0); otherwise stick. dd_scale = max(max |Ds|, max |Dn|, delta0).
module ddc_contact_result
    use ddc_kinds, only: wp
    use ddc_contact_states, only: state_stick, state_slip, state_open
    use ddc_contact_certificate, only: lcp_certificate, certify_complementarity, &
        default_certificate_tolerance
    use ddc_contact_counts, only: factor_counts
    use ddc_linalg_lu, only: residual_tol
    implicit none
    private

    public :: contact_result, state_dd_tol, state_stress_tol, residual_tol
    public :: contact_stress_scale, problem_scales, block_scales, check_solution
    public :: frictional_certificate

    !> Relative tolerance on DDs for the state rule (times dd_scale) [-]
    real(wp), parameter :: state_dd_tol = 1.0e-9_wp
    !> Relative tolerance on the friction limit for the state rule (times sigma0) [-]
    real(wp), parameter :: state_stress_tol = 1.0e-9_wp

    !> Solution of a contact problem on n elements; arrays shape (n).
    type :: contact_result
        !> Shear and normal displacement discontinuity, C&S signs (opening = -dn) [length]
        real(wp), allocatable :: ds(:), dn(:)
        !> Total shear and normal traction, tension positive, not shifted by p [stress]
        real(wp), allocatable :: shear_traction(:), normal_traction(:)
        !> state_stick, state_slip or state_open
        integer, allocatable :: state(:)
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
        !> Solves of the Newton method's reduced systems so far (of the session, in a
        !> loading history): new factorizations, low-rank updates, reuses of unchanged
        !> factors; the wall time of the factorizations of this solve (the inverse of A
        !> for Lemke, the LU of the reduced systems for newton) [s] and their nominal flops
        !> (2/3 m^3 per LU of size m; 2 m^3 for the inverse of A) [-]
        type(factor_counts) :: counts
        !> Certificate of the last LCP solve
        type(lcp_certificate) :: certificate
        !> Relative equilibrium residual ||A D + S_r - t|| / scale, shear and normal block
        real(wp) :: equilibrium_residual(2) = 0.0_wp
        !> Least scale of that residual [stress]: a solve of a shifted law (a tensile
        !> strength) sets that of the unshifted load, whose tractions can vanish when
        !> shifted; 0 otherwise
        real(wp) :: residual_scale_floor = 0.0_wp
        !> Stress scale sigma0 [stress] and displacement scale delta0 [length] used
        real(wp) :: stress_scale = 1.0_wp, dd_scale = 1.0_wp
        !> Wall time of the contact solves but their factorizations (building M, Lemke or
        !> the active-set iteration, certificate and recovery, summed over solves) [s]
        real(wp) :: seconds_lcp = 0.0_wp
    end type contact_result

contains

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

    !> Stress scale sigma0 (contact_stress_scale) and displacement scale delta0 =
    !> sigma0 / stiffness of a problem; both stored in res.
    subroutine problem_scales(stiffness, s_r_s, s_r_n, sf, p, res)
        !> Stiffness scale of the influence matrix: max_i |A_ii| (max |A_ij| when the
        !> diagonal vanishes) [stress / length]
        real(wp), intent(in) :: stiffness
        real(wp), intent(in) :: s_r_s(:), s_r_n(:), sf(:), p(:)
        type(contact_result), intent(inout) :: res

        res%stress_scale = contact_stress_scale(s_r_s, s_r_n, sf, p)
        res%dd_scale = res%stress_scale / stiffness
    end subroutine problem_scales

    !> Magnitude of each row of z = [stress; stress; length] and w = [length; length;
    !> stress] of an LCP on n elements, for a stress scale and a displacement scale.
    pure subroutine block_scales(n, stress, length, zs, ws)
        integer, intent(in) :: n
        real(wp), intent(in) :: stress, length
        real(wp), allocatable, intent(out) :: zs(:), ws(:)

        zs = [spread(stress, 1, 2 * n), spread(length, 1, n)]
        ws = [spread(length, 1, 2 * n), spread(stress, 1, n)]
    end subroutine block_scales

    !> The certificate of a frictional contact solution given by its DDs and total tractions:
    !> the paper's LCP's z = [-S_n', tau_s - s_s, slip+] and w = [-Dn, slip-, tau_s + s_s]
    !> (tau_s = Sf - mu S_n', the slip an increment over the slip held, split as D_L - D_R
    !> with the smaller part zero), whose relation w = M z + q holds when the tractions are
    !> those of the DDs: the Newton method's solution, a history's coupled K solution
    !> extrapolated along its load (ddc_run_coupled_k).
    pure function frictional_certificate(ds, dn, held, shear, normal_effective, mu, sf, &
                                         stress_scale, dd_scale) result(cert)
        !> DDs and the slip held before [length], shear and effective normal traction (s_n + p)
        !> [stress], friction [-] and cohesion [stress] of each element, shape (n)
        real(wp), intent(in) :: ds(:), dn(:), held(:), shear(:), normal_effective(:), mu(:), &
            sf(:)
        !> Stress and displacement scale of the rows [stress], [length]
        real(wp), intent(in) :: stress_scale, dd_scale
        type(lcp_certificate) :: cert
        real(wp) :: slip(size(ds)), tau(size(ds))
        real(wp), allocatable :: zs(:), ws(:)

        slip = ds - held
        tau = sf - mu * normal_effective
        call block_scales(size(ds), stress_scale, dd_scale, zs, ws)
        cert = certify_complementarity([-normal_effective, tau - shear, max(slip, 0.0_wp)], &
                                       [-dn, max(-slip, 0.0_wp), tau + shear], zs, ws, &
                                       default_certificate_tolerance)
    end function frictional_certificate

    !> Checks common to both methods on a recovered solution (res%ds, dn, tractions):
    !> the certificate passed and the DDs are in equilibrium with the tractions against the
    !> unfactored A (ad = A [res%ds; res%dn], computed by the caller from the matrix, dense or
    !> distributed); then the states (slip: a slip increment over ds_previous, when given, or
    !> on the friction limit). message is empty on success, else says what failed. On
    !> success the result's tractions become S_r + A D of the unfactored A (those the method
    !> imposed or recovered agree with them within the residual).
    subroutine check_solution(ad, s_r_s, s_r_n, mu, sf, snp, dscale, res, message, ds_previous)
        real(wp), intent(in) :: ad(:), s_r_s(:), s_r_n(:), mu(:), sf(:), snp(:), dscale
        type(contact_result), intent(inout) :: res
        character(len=:), allocatable, intent(out) :: message
        real(wp), intent(in), optional :: ds_previous(:)
        real(wp), allocatable :: tau(:), slip(:)
        real(wp) :: tol_d, tol_s, scale
        integer :: n, n2, i
        character(len=300) :: line

        message = ''
        n = size(mu)
        n2 = 2 * n
        if (.not. res%certificate%passed) then
            write (line, '(a,4(es10.3,a))') 'contact: the LCP solution fails its &
                &certificate (scaled min z ', res%certificate%min_z, ', min w ', &
                res%certificate%min_w, ', max |z w| ', res%certificate%max_complementarity, &
                ', w mismatch ', res%certificate%max_w_mismatch, ')'
            message = trim(line)
            return
        end if

        ! Equilibrium of the recovered DDs against the unfactored A.
        ! Both blocks are tractions: one scale for both, so that a block that vanishes (no
        ! resolved shear at all) is not measured against its own round-off.
        scale = max(norm2(ad), norm2([s_r_s, s_r_n]), &
                    norm2([res%shear_traction, res%normal_traction]), res%residual_scale_floor)
        res%equilibrium_residual(1) = block_residual(ad(1:n), s_r_s, res%shear_traction, scale)
        res%equilibrium_residual(2) = block_residual(ad(n + 1:n2), s_r_n, &
            res%normal_traction, scale)
        if (.not. maxval(res%equilibrium_residual) <= residual_tol) then
            write (line, '(a,2(es10.3,a))') 'contact: the recovered DDs are not in &
                &equilibrium (relative residual ', res%equilibrium_residual(1), &
                ' shear, ', res%equilibrium_residual(2), ' normal)'
            message = trim(line)
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
        res%shear_traction = s_r_s + ad(1:n)
        res%normal_traction = s_r_n + ad(n + 1:n2)
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

end module ddc_contact_result
