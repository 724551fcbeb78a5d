!> The opening near the front of a fluid-driven fracture
!> (docs/theory/fluid-driven-fractures.md#the-fluid-driven-tip). A front that the fluid
!> drives at velocity V opens as the toughness asymptote w_k = sqrt(32 / pi) (K_Ic / E')
!> sqrt(r) close to it and as the viscosity asymptote w_m = beta_m (12 eta V / E')^(1/3)
!> r^(2/3) farther away (r the distance to the front); the two are joined as
!> w^3 = w_k^3 + w_m^3, which is each of them where the other is small. A constant tip
!> element's K, E' w / (4 sqrt(h)), is the toughness asymptote's at r = pi h / 2 from its
!> midpoint; the joined asymptote at that distance gives the K the tip element must show
!> for the front to move at V: the apparent toughness.
module ddc_flow_tip_asymptote
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    implicit none
    private

    public :: apparent_toughness, front_distance

    !> beta_m = 2^(1/3) 3^(5/6) of the viscosity asymptote (Desroches et al. 1994)
    real(wp), parameter :: beta_m = 3.1473451902649443_wp

contains

    !> The K_I that a tip element of half-length h shows when the joined asymptote runs
    !> through its opening: K_Ic at rest, more as the front moves faster [stress unit
    !> length unit^(1/2)].
    pure real(wp) function apparent_toughness(toughness, e_prime, viscosity, velocity, h)
        !> K_Ic [stress unit length unit^(1/2)], E' [stress unit], eta [stress unit time
        !> unit], front velocity V >= 0 [length unit / time unit], tip element's half-length
        real(wp), intent(in) :: toughness, e_prime, viscosity, velocity, h
        real(wp) :: k_viscous

        k_viscous = e_prime * viscous_opening(e_prime, viscosity, velocity, 0.5_wp * pi * h) / &
                    (4.0_wp * sqrt(h))
        apparent_toughness = (toughness**3 + k_viscous**3)**(1.0_wp / 3.0_wp)
    end function apparent_toughness

    !> The distance from a point of opening w to the front where the joined asymptote
    !> vanishes [length unit]; 0 where w <= 0.
    pure real(wp) function front_distance(opening, toughness, e_prime, viscosity, velocity)
        real(wp), intent(in) :: opening, toughness, e_prime, viscosity, velocity
        real(wp) :: c_k, c_m, s, g, slope
        integer :: iteration

        front_distance = 0.0_wp
        if (.not. opening > 0.0_wp) return
        ! With s = sqrt(r): w^3 = c_k^3 s^3 + c_m^3 s^4, increasing and convex in s; Newton
        ! from the smaller of the two asymptotes' own roots comes down onto the root.
        c_k = sqrt(32.0_wp / pi) * toughness / e_prime
        c_m = viscous_opening(e_prime, viscosity, velocity, 1.0_wp)
        s = huge(1.0_wp)
        if (c_k > 0.0_wp) s = opening / c_k
        if (c_m > 0.0_wp) s = min(s, (opening / c_m)**0.75_wp)
        do iteration = 1, 100
            g = (c_k * s)**3 + c_m**3 * s**4 - opening**3
            slope = 3.0_wp * c_k**3 * s**2 + 4.0_wp * c_m**3 * s**3
            if (.not. g > 4.0_wp * epsilon(1.0_wp) * opening**3) exit
            s = s - g / slope
        end do
        front_distance = s**2
    end function front_distance

    !> The viscosity asymptote at distance r [length unit].
    pure real(wp) function viscous_opening(e_prime, viscosity, velocity, r)
        real(wp), intent(in) :: e_prime, viscosity, velocity, r

        viscous_opening = beta_m * (12.0_wp * viscosity * velocity / e_prime)**(1.0_wp / 3.0_wp) * &
                          r**(2.0_wp / 3.0_wp)
    end function viscous_opening
end module ddc_flow_tip_asymptote
