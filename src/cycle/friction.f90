!> Regularized rate-and-state friction (docs/theory/cycles.md#the-fault), pure: the friction
!> coefficient, the state evolution of the aging and the slip law, the state of an initial
!> stress, and the slip rate of the stress balance by a safeguarded Newton iteration.
!>
!> The state is held as psi = ln(V0 theta / L) (theta the state [time], L = dc), so that
!>
!>     f(V, psi) = a asinh( V / (2 V0) exp((f0 + b psi) / a) ),
!>     aging:  dpsi/dt = (V0 / L) exp(-psi) - |V| / L,
!>     slip:   dpsi/dt = -(|V| / L) (psi + ln(|V| / V0)).
!>
!> The balance of an element under the driving shear stress tau (the shear traction that
!> drives positive slip), effective normal stress sigma > 0 and radiation damping eta,
!>
!>     sigma f(V, psi) + eta V = tau,
!>
!> has one root V of the sign of tau (its left side is odd and increasing in V); it is
!> solved for x = ln|V| between closed-form bounds (slip_rate).
module ddc_cycle_friction
    use ddc_kinds, only: wp
    use ddc_model_cycles, only: state_law_aging
    implicit none
    private

    public :: friction, state_rate, initial_state, slip_rate, log_sinh

    !> ln(1e8): beyond the argument 1e8, asinh(z) = ln(2 z) in double precision
    real(wp), parameter :: log_asinh_log_from = 18.420680743952367_wp
    !> Newton's last step on x = ln|V| (after it the relative error of V is below its square)
    !> and the bracket that ends a bisection (a relative error of V) [-]; iteration limit
    real(wp), parameter :: newton_tolerance = 1.0e-8_wp, bracket_tolerance = 1.0e-13_wp
    integer, parameter :: newton_limit = 100

contains

    !> asinh(r exp(q)) for r >= 0 without overflow: ln(2 r) + q where the argument is large.
    elemental real(wp) function asinh_scaled(r, q) result(value)
        !> The factor r >= 0 and the exponent q of the argument
        real(wp), intent(in) :: r, q
        real(wp) :: log_argument

        if (r <= 0.0_wp) then
            value = 0.0_wp
            return
        end if
        log_argument = log(r) + q
        if (log_argument > log_asinh_log_from) then
            value = log_argument + log(2.0_wp)
        else
            value = asinh(exp(log_argument))
        end if
    end function asinh_scaled

    !> ln(sinh(y)) for y > 0 without overflow.
    elemental real(wp) function log_sinh(y)
        !> The argument, positive
        real(wp), intent(in) :: y

        if (y > 20.0_wp) then
            log_sinh = y - log(2.0_wp) + log(1.0_wp - exp(-2.0_wp * y))
        else
            log_sinh = log(sinh(y))
        end if
    end function log_sinh

    !> The friction coefficient f(V, psi) [-], odd in V.
    elemental real(wp) function friction(v, psi, a, b, f0, v0)
        !> Slip rate [length / time] and state psi = ln(V0 theta / L) [-]
        real(wp), intent(in) :: v, psi
        !> a, b, f0 [-] and the reference slip rate V0 [length / time]
        real(wp), intent(in) :: a, b, f0, v0

        friction = sign(a * asinh_scaled(abs(v) / (2.0_wp * v0), (f0 + b * psi) / a), v)
    end function friction

    !> dpsi/dt of the aging law or the slip law [1 / time].
    elemental real(wp) function state_rate(law, v, psi, dc, v0)
        !> state_law_aging or state_law_slip (ddc_model_cycles)
        integer, intent(in) :: law
        !> Slip rate [length / time], state psi [-]
        real(wp), intent(in) :: v, psi
        !> L [length] and V0 [length / time]
        real(wp), intent(in) :: dc, v0

        if (law == state_law_aging) then
            state_rate = (v0 * exp(-psi) - abs(v)) / dc
        else if (v == 0.0_wp) then
            state_rate = 0.0_wp
        else
            state_rate = -(abs(v) / dc) * (psi + log(abs(v) / v0))
        end if
    end function state_rate

    !> The state psi at which an element slips at v under the driving shear stress tau:
    !> f(v, psi) = (tau - eta v) / sigma (tau - eta v of the sign of v; the input's check).
    elemental real(wp) function initial_state(v, tau, sigma, eta, a, b, f0, v0) result(psi)
        !> Slip rate [length / time], driving shear stress [stress]
        real(wp), intent(in) :: v, tau
        !> Effective normal stress [stress], radiation damping [stress time / length]
        real(wp), intent(in) :: sigma, eta
        !> a, b, f0 [-] and V0 [length / time]
        real(wp), intent(in) :: a, b, f0, v0
        real(wp) :: q

        ! a asinh(|v| / (2 V0) e^q) = |tau - eta v| / sigma with q = (f0 + b psi) / a
        q = log(2.0_wp * v0 / abs(v)) + log_sinh(abs(tau - eta * v) / (a * sigma))
        psi = (a * q - f0) / b
    end function initial_state

    !> The slip rate V of sigma f(V, psi) + eta V = tau [length / time], by Newton's method
    !> on x = ln|V| kept within bounds that always hold the root (bisection where a Newton
    !> step would leave them): above, the root without damping; below, the smaller of the
    !> rates at which friction alone and damping alone carry tau / 2. Newton converges
    !> quadratically: a step below newton_tolerance leaves an error far below it.
    elemental subroutine slip_rate(tau, sigma, eta, psi, a, b, f0, v0, guess, v, iterations)
        !> Driving shear stress [stress], effective normal stress [stress] (> 0)
        real(wp), intent(in) :: tau, sigma
        !> Radiation damping [stress time / length] (>= 0), state psi [-]
        real(wp), intent(in) :: eta, psi
        !> a, b, f0 [-] and V0 [length / time]
        real(wp), intent(in) :: a, b, f0, v0
        !> A guess of V (the last one) [length / time]
        real(wp), intent(in) :: guess
        !> The slip rate [length / time]
        real(wp), intent(out) :: v
        !> Newton iterations taken
        integer, intent(out) :: iterations
        real(wp) :: drive, shift, lo, hi, x, step, h, dh, rate, log_z, z, f, slope
        logical :: newton

        iterations = 0
        drive = abs(tau)
        if (drive == 0.0_wp) then
            v = 0.0_wp
            return
        end if
        ! f = a asinh(Z), Z = |V| / (2 V0) exp((f0 + b psi) / a) = exp(x + shift)
        shift = (f0 + b * psi) / a - log(2.0_wp * v0)
        ! sigma f(V) = drive at Z = sinh(drive / (a sigma)): the root without damping
        hi = log_sinh(drive / (a * sigma)) - shift
        lo = log_sinh(0.5_wp * drive / (a * sigma)) - shift
        if (eta > 0.0_wp) then
            hi = min(hi, log(drive / eta))
            lo = min(lo, log(0.5_wp * drive / eta))
        end if
        x = hi
        if (guess /= 0.0_wp) x = min(hi, max(lo, log(abs(guess))))
        do iterations = 1, newton_limit
            rate = exp(x)
            log_z = x + shift
            if (log_z > log_asinh_log_from) then
                ! asinh(Z) = ln(2 Z) and d asinh(Z) / dx = 1 in double precision
                f = log_z + log(2.0_wp)
                slope = 1.0_wp
            else
                z = exp(log_z)
                f = asinh(z)
                slope = z / sqrt(1.0_wp + z * z)
            end if
            ! h(x) = sigma f(e^x) + eta e^x - drive and its derivative in x
            h = sigma * a * f + eta * rate - drive
            dh = sigma * a * slope + eta * rate
            if (h > 0.0_wp) then
                hi = x
            else
                lo = x
            end if
            step = -h / dh
            newton = x + step >= lo .and. x + step <= hi
            if (.not. newton) step = 0.5_wp * (lo + hi) - x
            x = x + step
            if ((newton .and. abs(step) <= newton_tolerance) .or. &
                hi - lo <= bracket_tolerance) exit
        end do
        v = sign(exp(x), tau)
    end subroutine slip_rate

end module ddc_cycle_friction
