!> The loads of a model: elastic constants, the remote stress resolved on elements and the
!> fluid pressure inside them (docs/theory/kernels.md#remote-stress-on-an-element,
!> docs/theory/earth.md#pore-fluid-and-effective-stress). Used by the solvers, the post
!> processing and the output alike.
module ddc_model_loads
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, element_set, condition_contact, growth_options
    implicit none
    private

    public :: shear_modulus_of, resolve_remote_stress, total_pressure, static_pressure, &
        work_threshold_of

contains

    !> Shear modulus G = E / (2 (1 + nu)) of a model [stress unit].
    pure real(wp) function shear_modulus_of(model)
        !> The model (its Young's modulus and Poisson's ratio)
        type(model_type), intent(in) :: model

        shear_modulus_of = model%youngs_modulus / (2.0_wp * (1.0_wp + model%poissons_ratio))
    end function shear_modulus_of

    !> The efficiency a tip must reach to grow [stress unit * length unit]: work_threshold,
    !> or 2 G_c with G_c = K_Ic^2 (1 - nu^2) / E when it is not given.
    pure real(wp) function work_threshold_of(options, youngs_modulus, nu) result(threshold)
        !> The growth options (work_threshold, toughness)
        type(growth_options), intent(in) :: options
        !> Young's modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: youngs_modulus, nu

        threshold = options%work_threshold
        if (threshold > 0.0_wp) return
        threshold = 2.0_wp * options%toughness**2 * (1.0_wp - nu**2) / youngs_modulus
    end function work_threshold_of

    !> Remote stress resolved on every element
    !> (docs/theory/kernels.md#remote-stress-on-an-element), tension positive; with a
    !> gradient, the stress at each midpoint (exact element average of a linear field,
    !> docs/theory/earth.md#stress-that-varies-with-depth).
    pure subroutine resolve_remote_stress(elements, sxx, syy, sxy, shear, normal, gradient)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Remote stress [stress unit] (at y = 0 when a gradient is given)
        real(wp), intent(in) :: sxx, syy, sxy
        !> Resolved shear and normal traction [stress unit], shape (n)
        real(wp), intent(out) :: shear(:), normal(:)
        !> d(sxx, syy, sxy)/dy [stress unit / length unit]; zero when absent
        real(wp), intent(in), optional :: gradient(3)
        real(wp) :: g(3)

        g = 0.0_wp
        if (present(gradient)) g = gradient
        associate (c => elements%cos_beta, s => elements%sin_beta, y => elements%y_mid)
            shear = -((sxx + g(1) * y) - (syy + g(2) * y)) * s * c &
                    + (sxy + g(3) * y) * (c**2 - s**2)
            normal = (sxx + g(1) * y) * s**2 - 2.0_wp * (sxy + g(3) * y) * s * c &
                     + (syy + g(2) * y) * c**2
        end associate
    end subroutine resolve_remote_stress

    !> Fluid pressure inside every contact element: its own pressure, the pore fluid's and
    !> the pressure the fluid sources diffused into it (docs/injection.md); other elements
    !> keep their value.
    pure function total_pressure(elements, pore_fluid) result(pressure)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Pore fluid (p0 [stress unit], dp_dy [stress unit / length unit])
        real(wp), intent(in) :: pore_fluid(2)
        !> Total pressure, compression positive [stress unit], shape (n)
        real(wp) :: pressure(elements%n)

        pressure = static_pressure(elements, pore_fluid)
        where (elements%condition == condition_contact) &
            pressure = pressure + elements%flow_pressure
    end function total_pressure

    !> The pressure that does not change in time: every contact element's own pressure plus
    !> the pore fluid p0 + dp_dy * y at its midpoint
    !> (docs/theory/earth.md#pore-fluid-and-effective-stress); other elements keep their value.
    pure function static_pressure(elements, pore_fluid) result(pressure)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Pore fluid (p0 [stress unit], dp_dy [stress unit / length unit])
        real(wp), intent(in) :: pore_fluid(2)
        !> Pressure, compression positive [stress unit], shape (n)
        real(wp) :: pressure(elements%n)

        pressure = elements%pressure
        where (elements%condition == condition_contact) &
            pressure = pressure + pore_fluid(1) + pore_fluid(2) * elements%y_mid
    end function static_pressure

end module ddc_model_loads
