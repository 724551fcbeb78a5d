!> Fault strength beyond Coulomb (issue 26), element by element: the laws the contact
!> solve iterates to a fixed point (ddc_contact_formulation), without elasticity.
!>
!> - Tensile strength T: an intact element opens only when S_n' reaches T; Coulomb's law
!>   in the shifted traction S_n'' = S_n' - T is the paper's LCP with s_n - T for the
!>   resolved normal traction and Sf - mu T for Sf (shifted_law). T is capped at the apex
!>   Sf/mu of the Coulomb envelope, where the shear strength vanishes.
!> - Residual cohesion: an element that slipped keeps min(Sf, sf_residual) (weaken).
!> - Slip weakening: mu(s) = mu - (mu - mu_d) min(s / d_c, 1) for the slip s (the slip
!>   path, accumulated over the steps of a loading history); with d_c = 0, mu_d once the
!>   element has slipped at all (friction_in_force).
module ddc_contact_strength
    use ddc_kinds, only: wp
    use ddc_contact_states, only: state_slip, state_open
    implicit none
    private

    public :: shifted_law, weaken, friction_in_force

contains

    !> The shifted Coulomb law of a tensile strength t: sf_in = sf - mu T, s_n_in = s_n - T
    !> with T = t capped at the apex sf/mu. With t = 0 these are sf and s_n, bit for bit.
    pure subroutine shifted_law(mu, sf, s_n, t, sf_in, s_n_in, cap)
        !> Friction [-], cohesion [stress], resolved normal traction [stress] and tensile
        !> strength [stress] of each element, shape (n)
        real(wp), intent(in) :: mu(:), sf(:), s_n(:), t(:)
        !> Cohesion and resolved normal traction of the shifted law [stress], shape (n)
        real(wp), allocatable, intent(out) :: sf_in(:), s_n_in(:)
        !> T in force [stress], shape (n)
        real(wp), allocatable, intent(out) :: cap(:)

        cap = t
        where (mu * t > sf) cap = sf / mu
        sf_in = max(sf - mu * cap, 0.0_wp)
        s_n_in = s_n - cap
    end subroutine shifted_law

    !> After a solve: elements that opened lose their tensile strength, elements that
    !> slipped drop their cohesion to sf_after; true when any strength changed.
    function weaken(state, sf_after, t, sf) result(changed)
        !> States of the solve (ddc_contact_states), shape (n)
        integer, intent(in) :: state(:)
        !> Cohesion after slip [stress], shape (n)
        real(wp), intent(in) :: sf_after(:)
        !> Tensile strength and cohesion in force [stress], shape (n)
        real(wp), intent(inout) :: t(:), sf(:)
        logical :: changed
        logical :: opened(size(state)), slipped(size(state))

        opened = state == state_open .and. t > 0.0_wp
        slipped = state == state_slip .and. sf > sf_after
        changed = any(opened) .or. any(slipped)
        where (opened) t = 0.0_wp
        where (slipped) sf = sf_after
    end function weaken

    !> Friction in force after a slip path s: mu - (mu - mu_d) min(s / d_c, 1); with
    !> d_c = 0, mu_d where the element has slipped (s > 0 or state slip).
    pure function friction_in_force(mu, mu_d, d_c, s, state) result(mu_f)
        !> Static and dynamic friction [-], slip-weakening distance [length], slip path
        !> [length] of each element, shape (n)
        real(wp), intent(in) :: mu(:), mu_d(:), d_c(:), s(:)
        !> States of the last solve, shape (n)
        integer, intent(in) :: state(:)
        real(wp) :: mu_f(size(mu))
        real(wp) :: ratio(size(mu))

        ratio = 0.0_wp
        where (d_c > 0.0_wp)
            ratio = min(s / d_c, 1.0_wp)
        elsewhere (s > 0.0_wp .or. state == state_slip)
            ratio = 1.0_wp
        end where
        mu_f = mu - (mu - mu_d) * ratio
        where (.not. mu_d < mu) mu_f = mu
    end function friction_in_force

end module ddc_contact_strength
