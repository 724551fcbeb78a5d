!> A posteriori certificate of an LCP solution w = M z + q, w >= 0, z >= 0, z'w = 0.
!>
!> The certificate recomputes w from the unfactored M and q (it never trusts the solver's
!> own w) and measures, each scaled by the magnitude of its row: the most negative z, the
!> most negative w, the largest |z_i w_i| and the largest mismatch between the solver's w
!> and M z + q. Rows of a physical LCP mix units (displacements and stresses); the caller
!> passes the magnitude of each row's z and w (block magnitudes).
!>
!> certify_complementarity measures a pair (z, w) whose relation w = M z + q holds by
!> construction (a contact solver on the stiffness system computes both from the DDs and
!> the tractions of the unfactored influence matrix): signs and complementarity only.
module ddc_contact_certificate
    use ddc_kinds, only: wp
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    implicit none
    private

    public :: lcp_certificate, certify_lcp, certify_complementarity
    public :: default_certificate_tolerance

    !> Default tolerance on every scaled measure
    real(wp), parameter :: default_certificate_tolerance = 1.0e-8_wp

    !> Scaled measures of how well (z, w) solves the LCP; passed when each is within tolerance.
    type :: lcp_certificate
        !> min_i z_i / z_scale_i (>= -tolerance to pass) [-]
        real(wp) :: min_z = 0.0_wp
        !> min_i (M z + q)_i / w_scale_i (>= -tolerance to pass) [-]
        real(wp) :: min_w = 0.0_wp
        !> max_i |z_i (M z + q)_i| / (z_scale_i w_scale_i) (<= tolerance to pass) [-]
        real(wp) :: max_complementarity = 0.0_wp
        !> max_i |w_i - (M z + q)_i| / w_scale_i for the solver's w (<= tolerance) [-]
        real(wp) :: max_w_mismatch = 0.0_wp
        !> Tolerance applied to each measure [-]
        real(wp) :: tolerance = default_certificate_tolerance
        !> All measures finite and within tolerance
        logical :: passed = .false.
    end type lcp_certificate

contains

    !> Certify (z, w) as a solution of w = M z + q, w >= 0, z >= 0, z'w = 0.
    !>
    !> Default scales: z_scale_i = max |z| (the same for every row) and w_scale_i =
    !> max(|q_i|, max_j |M_ij z_j|), the size of the terms summed into w_i. Scales that are
    !> zero are replaced by 1. Inconsistent sizes give a certificate that fails with every
    !> measure set to huge().
    pure function certify_lcp(m, q, z, w, z_scale, w_scale, tolerance) result(cert)
        !> The LCP matrix, unfactored, shape (n, n)
        real(wp), intent(in) :: m(:, :)
        !> The LCP vector, shape (n)
        real(wp), intent(in) :: q(:)
        !> Candidate solution z, shape (n)
        real(wp), intent(in) :: z(:)
        !> The solver's w, shape (n) (compared with M z + q, not used otherwise)
        real(wp), intent(in) :: w(:)
        !> Magnitude of z in each row (units of z_i), shape (n)
        real(wp), intent(in), optional :: z_scale(:)
        !> Magnitude of w in each row (units of w_i), shape (n)
        real(wp), intent(in), optional :: w_scale(:)
        !> Tolerance on each measure (default default_certificate_tolerance)
        real(wp), intent(in), optional :: tolerance
        !> The certificate
        type(lcp_certificate) :: cert

        real(wp), allocatable :: wz(:), zs(:), ws(:)
        logical :: sizes_ok
        integer :: n, i, j

        n = size(q)
        if (present(tolerance)) cert%tolerance = tolerance
        sizes_ok = size(m, 1) == n .and. size(m, 2) == n .and. size(z) == n .and. size(w) == n
        if (present(z_scale)) sizes_ok = sizes_ok .and. size(z_scale) == n
        if (present(w_scale)) sizes_ok = sizes_ok .and. size(w_scale) == n
        if (.not. sizes_ok) then
            cert%min_z = -huge(1.0_wp)
            cert%min_w = -huge(1.0_wp)
            cert%max_complementarity = huge(1.0_wp)
            cert%max_w_mismatch = huge(1.0_wp)
            cert%passed = .false.
            return
        end if
        if (n == 0) then
            cert%passed = .true.
            return
        end if

        ! w recomputed from the unfactored matrix.
        wz = q
        allocate (zs(n), ws(n))
        ws = abs(q)
        do j = 1, n
            wz = wz + m(:, j) * z(j)
            ws = max(ws, abs(m(:, j) * z(j)))
        end do
        if (present(w_scale)) ws = abs(w_scale)
        if (present(z_scale)) then
            zs = abs(z_scale)
        else
            zs = maxval(abs(z))
        end if
        do i = 1, n
            if (.not. zs(i) > 0.0_wp) zs(i) = 1.0_wp
            if (.not. ws(i) > 0.0_wp) ws(i) = 1.0_wp
        end do

        cert = certify_complementarity(z, wz, zs, ws, cert%tolerance)
        cert%max_w_mismatch = maxval(abs(w - wz) / ws)
        cert%passed = cert%passed .and. ieee_is_finite(cert%max_w_mismatch) &
            .and. cert%max_w_mismatch <= cert%tolerance
    end function certify_lcp

    !> Certify z >= 0, w >= 0, z'w = 0 for a pair whose relation w = M z + q holds by
    !> construction (max_w_mismatch is 0). Scales that are zero are replaced by 1.
    pure function certify_complementarity(z, w, z_scale, w_scale, tolerance) result(cert)
        !> Candidate solution z and its complement w, shape (n)
        real(wp), intent(in) :: z(:), w(:)
        !> Magnitude of z and of w in each row, shape (n)
        real(wp), intent(in) :: z_scale(:), w_scale(:)
        !> Tolerance on each measure
        real(wp), intent(in) :: tolerance
        !> The certificate
        type(lcp_certificate) :: cert
        real(wp), allocatable :: zs(:), ws(:)

        cert%tolerance = tolerance
        if (size(z) == 0) then
            cert%passed = .true.
            return
        end if
        zs = merge(abs(z_scale), 1.0_wp, abs(z_scale) > 0.0_wp)
        ws = merge(abs(w_scale), 1.0_wp, abs(w_scale) > 0.0_wp)
        cert%min_z = minval(z / zs)
        cert%min_w = minval(w / ws)
        cert%max_complementarity = maxval(abs((z / zs) * (w / ws)))
        cert%max_w_mismatch = 0.0_wp
        cert%passed = ieee_is_finite(cert%min_z) .and. ieee_is_finite(cert%min_w) &
            .and. ieee_is_finite(cert%max_complementarity) &
            .and. cert%min_z >= -cert%tolerance .and. cert%min_w >= -cert%tolerance &
            .and. cert%max_complementarity <= cert%tolerance
    end function certify_complementarity

end module ddc_contact_certificate
