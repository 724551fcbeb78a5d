!> The maximum tangential stress criterion (Erdogan & Sih 1963;
!> docs/theory/growth.md#the-maximum-tangential-stress-criterion): the kink angle and K_eq of a
!> tip from its K, and the first slope of the local-symmetry corrector
!> (ddc_growth_corrector), which turns the MTS kinks.
!>
!> Angles are measured counter-clockwise from the tip's outward direction, K in the tip's
!> own frame (K_II > 0 for a crack along +x under sxy > 0 at either tip:
!> docs/theory/tips.md#k-from-the-tip-element). K_I is taken as max(K_I, 0): a closed tip has
!> no opening mode.
module ddc_growth_mts
    use ddc_kinds, only: wp
    implicit none
    private

    public :: mts_angle, equivalent_k, kink_slope

contains

    !> The kink angle of the maximum tangential stress [rad], in (-pi/2, pi/2):
    !> 2 atan((K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II)), 0 when K_II = 0, written as
    !> -2 atan(2 K_II / (K_I + sqrt(K_I^2 + 8 K_II^2))) (the same value without the
    !> cancellation when K_II is small). Pure mode II: -70.53 degrees where K_II > 0.
    elemental real(wp) function mts_angle(k1, k2)
        !> Stress intensity factors [stress unit * length unit**0.5]
        real(wp), intent(in) :: k1, k2
        real(wp) :: opening, denominator

        opening = max(k1, 0.0_wp)
        denominator = opening + sqrt(opening**2 + 8.0_wp * k2**2)
        if (denominator > 0.0_wp) then
            ! + 0 turns the -0 of K_II = 0 into 0 for printing.
            mts_angle = -2.0_wp * atan(2.0_wp * k2 / denominator) + 0.0_wp
        else
            ! K_I <= 0 and K_II = 0: no tangential stress singularity, no preferred kink.
            mts_angle = 0.0_wp
        end if
    end function mts_angle

    !> The equivalent mode-I factor (the tangential stress factor at angle theta):
    !> cos(theta/2) (K_I cos^2(theta/2) - 1.5 K_II sin(theta)) [stress unit * length^0.5].
    elemental real(wp) function equivalent_k(k1, k2, theta)
        !> Stress intensity factors [stress unit * length unit**0.5]
        real(wp), intent(in) :: k1, k2
        !> Kink angle [rad]
        real(wp), intent(in) :: theta

        equivalent_k = cos(0.5_wp * theta) * (max(k1, 0.0_wp) * cos(0.5_wp * theta)**2 - &
                                               1.5_wp * k2 * sin(theta))
    end function equivalent_k

    !> d K_II / d theta of an infinitesimal kink at angle theta (first-order kink theory,
    !> Cotterell & Rice 1980: K_II of the kink is the shear stress factor k_rtheta, whose
    !> derivative is k_thetatheta - k_rr / 2 by equilibrium) [stress unit * length^0.5 / rad].
    !> The corrector's first slope; pure mode II gives K_eq, pure mode I K_I / 2.
    elemental real(wp) function kink_slope(k1, k2, theta)
        !> Stress intensity factors [stress unit * length unit**0.5]
        real(wp), intent(in) :: k1, k2
        !> Kink angle [rad]
        real(wp), intent(in) :: theta
        real(wp) :: opening, k_rr

        opening = max(k1, 0.0_wp)
        k_rr = 0.25_wp * (opening * (5.0_wp * cos(0.5_wp * theta) - cos(1.5_wp * theta)) + &
                          k2 * (-5.0_wp * sin(0.5_wp * theta) + 3.0_wp * sin(1.5_wp * theta)))
        kink_slope = equivalent_k(k1, k2, theta) - 0.5_wp * k_rr
    end function kink_slope

end module ddc_growth_mts
