!> K on grown tips (docs/theory/tips.md#tips-of-grown-fractures): a calibration of the
!> constant-element estimate K = -G D / (2 (1 - nu) sqrt(h))
!> (docs/theory/tips.md#k-from-the-tip-element) for tip zones of unequal elements.
!>
!> That estimate is calibrated (its sqrt(2/pi)) for a tip zone of equal elements. Growth
!> puts elements of another length beside the old tip (an increment of 1/50 of the
!> element length made K 3.6x too large, new elements twice as long -6 %): the error comes
!> from the tip zone's element lengths alone, over several lengths of the largest element
!> there (six missed a change of length 1.2 % low, three increments of two elements of twice
!> the old length: eight). So K is multiplied by
!>
!>     f = K_5(uniform) / K_5(zone),
!>
!> the ratio of the same estimate on two straight collinear auxiliary cracks of
!> half-length A = max(20 max(l), 2 sum(l)) under unit pressure: one whose tips carry the
!> zone's lengths l_1 (tip), l_2, ... padded to A with elements of about l_last, one with
!> those padding elements only. Collinear constant elements, midpoint collocation, the
!> closed-form kernel sigma(x_i) = c0 sum_j D_j (1/(x_i - s1_j) - 1/(x_i - s2_j)) (c0, G and
!> nu cancel in f). On a straight line the shear kernel equals the normal one, so f serves
!> K_II too. A zone of equal elements gives f = 1 exactly, without a solve.
!>
!> The zone (ddc_post_tips's walk_tip_zone and zone_size): the tip's fracture elements from
!> the tip inward (while they share vertices), at most max_zone of them, up to the last element
!> i whose start s_i = l_1 + ... + l_(i-1) is below 8 times the largest length among
!> l_1 ... l_i.
module ddc_growth_tip_zone
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_types, only: model_type
    use ddc_model_results, only: tip_set
    use ddc_linalg_lu, only: lu_factor, lu_solve
    use ddc_post_tips, only: walk_tip_zone, zone_size, max_zone
    use ddc_post_higher_order_k, only: tips_re_solved
    implicit none
    private

    public :: calibrate_tips, graded_factor

    !> Relative difference of lengths that counts as equal
    real(wp), parameter :: equal_tolerance = 1.0e-9_wp
    !> Relative margin that keeps a padding count at n + 1/2 from depending on round-off, so
    !> that point-symmetric tips get the same factor
    real(wp), parameter :: tie_tolerance = 1.0e-6_wp

contains

    !> Multiply K_I, K_II of every tip by its zone's graded_factor, and set `graded` where
    !> the calibration's assumption fails: a zone of unequal elements that is not straight,
    !> or that reaches the fracture's other end (or a junction) before its reach; else 0.
    !> Tips whose K the higher-order re-solve gave need no calibration and keep theirs.
    subroutine calibrate_tips(model, tips, error)
        !> The solved model
        type(model_type), intent(in) :: model
        !> Its tips (find_tips); K and graded updated
        type(tip_set), intent(inout) :: tips
        !> Set when an auxiliary solve fails
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: lengths(:)
        logical, allocatable :: straight(:)
        logical :: re_solved(tips%n)
        real(wp) :: f
        integer :: k, m
        logical :: truncated

        re_solved = tips_re_solved(model%elements, tips)
        do k = 1, tips%n
            if (re_solved(k)) cycle
            call walk_tip_zone(model%elements, tips%element(k), tips%side(k), lengths, straight)
            m = zone_size(lengths)
            truncated = m == size(lengths) .and. size(lengths) < max_zone
            if (all(abs(lengths(1:m) - lengths(1)) <= equal_tolerance * lengths(1))) cycle
            f = graded_factor(lengths(1:m), error)
            if (allocated(error)) return
            tips%k1(k) = f * tips%k1(k)
            tips%k2(k) = f * tips%k2(k)
            tips%graded(k) = merge(1, 0, truncated .or. .not. all(straight(1:m)))
        end do
    end subroutine calibrate_tips

    !> f = K_5(uniform) / K_5(zone) of the module's header, for the zone's lengths l_1 (tip),
    !> l_2, ...; 1 for equal lengths.
    function graded_factor(lengths, error) result(f)
        real(wp), intent(in) :: lengths(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: f, pad, half, k_zone, k_uniform

        f = 1.0_wp
        if (all(abs(lengths - lengths(1)) <= equal_tolerance * lengths(1))) return
        pad = lengths(size(lengths))
        half = max(20.0_wp * maxval(lengths), 2.0_wp * sum(lengths))
        k_zone = auxiliary_k(lengths, half, pad, error)
        if (allocated(error)) return
        k_uniform = auxiliary_k([pad], half, pad, error)
        if (allocated(error)) return
        f = k_uniform / k_zone
    end function graded_factor

    !> The estimate D / sqrt(h) (docs/theory/tips.md#k-from-the-tip-element) at the tip of a
    !> straight crack of half-length `half` under unit pressure (in units of
    !> c0 = G / (2 pi (1 - nu))), whose two halves carry `zone` from each tip inward, padded with
    !> elements of about `pad`.
    function auxiliary_k(zone, half, pad, error) result(k)
        real(wp), intent(in) :: zone(:), half, pad
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: k
        real(wp), allocatable :: side(:), nodes(:), mid(:), a(:, :), b(:, :)
        integer, allocatable :: ipiv(:)
        integer :: n_pad, n, i, j

        ! The count rounded on a grid of tie_tolerance first: a tie goes the same way for
        ! every tip whatever its round-off.
        n_pad = max(1, nint(anint((half - sum(zone)) / pad / tie_tolerance) * tie_tolerance))
        side = [zone, spread((half - sum(zone)) / real(n_pad, wp), 1, n_pad)]
        ! Left tip to right tip: one half, then the other reversed (both tips carry zone).
        side = [side, side(size(side):1:-1)]
        n = size(side)
        allocate (nodes(0:n))
        nodes(0) = -half
        do i = 1, n
            nodes(i) = nodes(i - 1) + side(i)
        end do
        mid = 0.5_wp * (nodes(0:n - 1) + nodes(1:n))
        allocate (a(n, n), b(n, 1), ipiv(n))
        do j = 1, n
            a(:, j) = 1.0_wp / (mid - nodes(j - 1)) - 1.0_wp / (mid - nodes(j))
        end do
        b = 1.0_wp
        call lu_factor(a, ipiv, 'the tip-zone calibration', error)
        if (allocated(error)) return
        call lu_solve(a, ipiv, b)
        k = abs(b(n, 1)) / sqrt(0.5_wp * side(n))
    end function auxiliary_k

end module ddc_growth_tip_zone
