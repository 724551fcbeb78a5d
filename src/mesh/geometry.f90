!> Geometry derived from element end points: midpoint, half-length, orientation.
module ddc_mesh_geometry
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, element_array_action, for_each_element_array
    use ddc_model_laws, only: default_strength_laws
    use ddc_model_rate_state, only: clear_rate_state
    implicit none
    private

    public :: compute_geometry, allocate_elements

    !> Allocates every per-element array for n elements (allocate_elements).
    type, extends(element_array_action) :: element_allocation
        !> Number of elements
        integer :: n = 0
    contains
        procedure :: on_reals => allocate_reals
        procedure :: on_integers => allocate_integers
    end type element_allocation

contains

    !> Allocate every per-element array of an element set (those of the geometry too) for
    !> n elements; values unset, but the strength laws beyond Coulomb at their defaults (no
    !> tensile strength, no drops, rigid contact), no flow (diffusivity, transmissivity and
    !> residual aperture 0) and no rate-and-state values (0).
    subroutine allocate_elements(elements, n)
        !> The set to allocate (its arrays unallocated)
        type(element_set), intent(inout) :: elements
        !> Number of elements
        integer, intent(in) :: n
        type(element_allocation) :: allocation

        elements%n = n
        allocation%n = n
        call for_each_element_array(elements, allocation)
        call default_strength_laws(elements, spread(.true., 1, n))
        call clear_rate_state(elements)
        elements%diffusivity = 0.0_wp
        elements%transmissivity = 0.0_wp
        elements%flow_pressure = 0.0_wp
        elements%residual_aperture = 0.0_wp
    end subroutine allocate_elements

    !> Allocate one real array for the set's elements.
    subroutine allocate_reals(action, values)
        !> The allocation
        class(element_allocation), intent(inout) :: action
        !> The array, unallocated on entry
        real(wp), allocatable, intent(inout) :: values(:)

        allocate (values(action%n))
    end subroutine allocate_reals

    !> Allocate one integer array for the set's elements.
    subroutine allocate_integers(action, values)
        !> The allocation
        class(element_allocation), intent(inout) :: action
        !> The array, unallocated on entry
        integer, allocatable, intent(inout) :: values(:)

        allocate (values(action%n))
    end subroutine allocate_integers

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
