!> The elastic medium of a model: its elements (geometry, conditions, given values) in the
!> rock around them: one elastic material in the full plane or in the half-plane below a
!> free surface, or two materials in two half-planes bonded at y = interface_y
!> (elements%domain; docs/theory/bimaterial.md), with the symmetry images of
!> elements%symmetry. The solve layers and the kernels take a medium where they took the
!> elements with the shear modulus and Poisson's ratio.
module ddc_model_medium
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, element_set, domain_bimaterial
    use ddc_model_loads, only: shear_modulus_of
    use ddc_model_body, only: finite_body
    implicit none
    private

    public :: elastic_medium, elastic_material, medium_of, with_elements
    public :: material_at, element_material, upper_remote_stress, remote_stress_at

    !> An isotropic elastic material (plane strain).
    type :: elastic_material
        !> Shear modulus [stress unit]
        real(wp) :: shear_modulus = 0.0_wp
        !> Poisson's ratio [-]
        real(wp) :: poissons_ratio = 0.0_wp
    end type elastic_material

    !> Elements in the rock.
    type :: elastic_medium
        !> The elements, geometry computed
        type(element_set) :: elements
        !> Shear modulus [stress unit] of the rock (of the lower material of two bonded
        !> half-planes)
        real(wp) :: shear_modulus = 0.0_wp
        !> Poisson's ratio [-] of the rock (of the lower material)
        real(wp) :: poissons_ratio = 0.0_wp
        !> Two bonded half-planes: the material above the interface
        type(elastic_material) :: upper
        !> Two bonded half-planes: the height of the interface [length unit]
        real(wp) :: interface_y = 0.0_wp
        !> The finite body the elements lie in, its system solved
        !> (ddc_influence_body%prepare_body); unallocated in an infinite medium
        type(finite_body), allocatable :: body
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
        if (model%elements%domain == domain_bimaterial) then
            medium%upper = elastic_material(model%upper_youngs_modulus / &
                                            (2.0_wp * (1.0_wp + model%upper_poissons_ratio)), &
                                            model%upper_poissons_ratio)
            medium%interface_y = model%interface_y
        end if
        if (allocated(model%body)) medium%body = model%body
    end function medium_of

    !> The medium of other elements in the same rock.
    pure function with_elements(medium, elements) result(other)
        !> A medium
        type(elastic_medium), intent(in) :: medium
        !> The elements, geometry computed
        type(element_set), intent(in) :: elements
        type(elastic_medium) :: other

        other%elements = elements
        other%shear_modulus = medium%shear_modulus
        other%poissons_ratio = medium%poissons_ratio
        other%upper = medium%upper
        other%interface_y = medium%interface_y
        if (allocated(medium%body)) other%body = medium%body
    end function with_elements

    !> The material at height y: the upper one above the interface of two bonded
    !> half-planes; the lower one (the rock's) on it, below it and in any other domain.
    pure function material_at(medium, y) result(material)
        !> The medium
        type(elastic_medium), intent(in) :: medium
        !> Height of the point [length unit]
        real(wp), intent(in) :: y
        type(elastic_material) :: material

        if (medium%elements%domain == domain_bimaterial .and. y > medium%interface_y) then
            material = medium%upper
        else
            material = elastic_material(medium%shear_modulus, medium%poissons_ratio)
        end if
    end function material_at

    !> The material of element j: the material at its midpoint (elements lying on the
    !> interface count as the lower material's).
    pure function element_material(medium, j) result(material)
        !> The medium, geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Element index
        integer, intent(in) :: j
        type(elastic_material) :: material

        material = material_at(medium, medium%elements%y_mid(j))
    end function element_material

    !> The remote stress of the upper material of two bonded half-planes from the lower
    !> one's (docs/theory/bimaterial.md#remote-stress): syy and sxy carry over, sxx follows
    !> from the continuity of the strain exx in plane strain. Linear, so it serves the
    !> stress and its gradient alike.
    pure function upper_remote_stress(medium, lower) result(upper)
        !> The medium (two bonded half-planes)
        type(elastic_medium), intent(in) :: medium
        !> sxx, syy, sxy of the lower material (or their gradients d/dy)
        real(wp), intent(in) :: lower(3)
        real(wp) :: upper(3)

        associate (gl => medium%shear_modulus, nl => medium%poissons_ratio, &
                   gu => medium%upper%shear_modulus, nu => medium%upper%poissons_ratio)
            upper = lower
            upper(1) = (gu / gl * ((1.0_wp - nl) * lower(1) - nl * lower(2)) + nu * lower(2)) / &
                       (1.0_wp - nu)
        end associate
    end function upper_remote_stress

    !> The remote stress at height y [stress unit]: remote + gradient y, in the upper
    !> material of two bonded half-planes its own (upper_remote_stress).
    pure function remote_stress_at(medium, remote, gradient, y) result(stress)
        !> The medium
        type(elastic_medium), intent(in) :: medium
        !> Remote stress sxx, syy, sxy at y = 0 [stress unit] (the lower material's) and its
        !> gradient d/dy [stress unit / length unit]
        real(wp), intent(in) :: remote(3), gradient(3)
        !> Height [length unit]
        real(wp), intent(in) :: y
        real(wp) :: stress(3)

        if (medium%elements%domain == domain_bimaterial .and. y > medium%interface_y) then
            stress = upper_remote_stress(medium, remote) + upper_remote_stress(medium, gradient) * y
        else
            stress = remote + gradient * y
        end if
    end function remote_stress_at

end module ddc_model_medium
