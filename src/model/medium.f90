!> The elastic medium of a model: its elements (geometry, conditions, given values) in one
!> elastic material, in the full plane or in the half-plane below a free surface
!> (elements%domain), with the symmetry images of elements%symmetry. The solve layers take a
!> medium where they took the elements with the shear modulus and Poisson's ratio; a medium
!> of two bonded materials would add the second material and the interface here.
module ddc_model_medium
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, element_set
    use ddc_model_loads, only: shear_modulus_of
    implicit none
    private

    public :: elastic_medium, medium_of

    !> Elements in one elastic material.
    type :: elastic_medium
        !> The elements, geometry computed
        type(element_set) :: elements
        !> Shear modulus [stress unit]
        real(wp) :: shear_modulus = 0.0_wp
        !> Poisson's ratio [-]
        real(wp) :: poissons_ratio = 0.0_wp
    end type elastic_medium

contains

    !> The medium of a model.
    pure function medium_of(model) result(medium)
        !> A model with element geometry computed
        type(model_type), intent(in) :: model
        type(elastic_medium) :: medium

        medium%elements = model%elements
        medium%shear_modulus = shear_modulus_of(model)
        medium%poissons_ratio = model%poissons_ratio
    end function medium_of

end module ddc_model_medium
