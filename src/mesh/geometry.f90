!> Geometry derived from element end points: midpoint, half-length, orientation.
module ddc_mesh_geometry
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, no_residual_drop, rigid_joint
    implicit none
    private

    public :: compute_geometry, allocate_elements

contains

    !> Allocate every array of an element set for n elements (values unset, but the
    !> strength laws beyond Coulomb at their defaults: no tensile strength, no drops, rigid
    !> contact).
    subroutine allocate_elements(elements, n)
        !> The set to allocate
        type(element_set), intent(inout) :: elements
        !> Number of elements
        integer, intent(in) :: n

        elements%n = n
        allocate (elements%x_begin(n), elements%y_begin(n), elements%x_end(n), &
                  elements%y_end(n), elements%fracture_id(n), elements%condition(n), &
                  elements%bc_s(n), elements%bc_n(n), elements%mu(n), elements%sf(n), &
                  elements%pressure(n), elements%tensile_strength(n), elements%sf_residual(n), &
                  elements%mu_dynamic(n), elements%slip_weakening_distance(n), &
                  elements%shear_stiffness(n), elements%normal_stiffness(n))
        elements%tensile_strength = 0.0_wp
        elements%sf_residual = no_residual_drop
        elements%mu_dynamic = no_residual_drop
        elements%slip_weakening_distance = 0.0_wp
        elements%shear_stiffness = rigid_joint
        elements%normal_stiffness = rigid_joint
    end subroutine allocate_elements

    !> Fill midpoint, half-length and direction cosines from the end points.
    subroutine compute_geometry(elements)
        !> Elements whose end points are set
        type(element_set), intent(inout) :: elements
        real(wp) :: dx(elements%n), dy(elements%n), length(elements%n)

        dx = elements%x_end - elements%x_begin
        dy = elements%y_end - elements%y_begin
        length = hypot(dx, dy)
        elements%x_mid = 0.5_wp * (elements%x_begin + elements%x_end)
        elements%y_mid = 0.5_wp * (elements%y_begin + elements%y_end)
        elements%half_length = 0.5_wp * length
        ! Zero-length elements are rejected by the mesh checks; avoid 0/0 before that.
        elements%cos_beta = merge(dx, 1.0_wp, length > 0.0_wp) / &
                            merge(length, 1.0_wp, length > 0.0_wp)
        elements%sin_beta = merge(dy, 0.0_wp, length > 0.0_wp) / &
                            merge(length, 1.0_wp, length > 0.0_wp)
    end subroutine compute_geometry

end module ddc_mesh_geometry
