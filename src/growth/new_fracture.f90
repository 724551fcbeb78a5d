!> A new fracture inside the rock (docs/fracture-growth.md#new-fractures-inside-the-rock): the
!> vertices of a flaw's first crack, and the model with a new fracture appended. The start
!> rules (ddc_growth_initiation) and a flaw's angle search (ddc_growth_flaw_search) build their
!> fractures here.
module ddc_growth_new_fracture
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, growth_options, initiation_options, &
        condition_contact
    use ddc_model_laws, only: default_strength_laws
    use ddc_model_initiations, only: initiation_flaw
    use ddc_mesh_geometry, only: compute_geometry
    use ddc_growth_extension, only: inherit_values, take_new_element_laws
    implicit none
    private

    public :: flaw_path, add_fracture

contains

    !> A flaw's vertices: flaw_length (default the increment) centred on the point along
    !> `along`, in elements of the growth's element_length (default: two elements).
    pure subroutine flaw_path(growth, initiation, point, along, xs, ys)
        !> The growth options (increment, element_length)
        type(growth_options), intent(in) :: growth
        !> The initiation options (flaw_length)
        type(initiation_options), intent(in) :: initiation
        !> The flaw point [length unit] and the crack's unit direction
        real(wp), intent(in) :: point(2), along(2)
        !> The vertices [length unit]
        real(wp), allocatable, intent(out) :: xs(:), ys(:)
        real(wp) :: length
        integer :: pieces, j

        length = initiation%flaw_length
        if (length <= 0.0_wp) length = growth%increment
        pieces = 2
        if (growth%element_length > 0.0_wp) pieces = max(2, nint(length / growth%element_length))
        xs = [(point(1) + along(1) * length * (real(j, wp) / pieces - 0.5_wp), j = 0, pieces)]
        ys = [(point(2) + along(2) * length * (real(j, wp) / pieces - 0.5_wp), j = 0, pieces)]
    end subroutine flaw_path

    !> The model with a new fracture of the polyline (xs, ys) appended after every element.
    !> A tail's elements take its parent element's values (as elements grown at a tip do);
    !> a flaw's are frictionless, cohesionless contact elements of intact rock (no strength
    !> law) without pressure, but for the new-element values &growth gives.
    subroutine add_fracture(work, kind, parent_element, xs, ys, name, growth, grown)
        !> The current geometry
        type(model_type), intent(in) :: work
        !> initiation_tail or initiation_flaw
        integer, intent(in) :: kind
        !> A tail's parent element (0 for a flaw)
        integer, intent(in) :: parent_element
        !> The new fracture's vertices [length unit]
        real(wp), intent(in) :: xs(:), ys(:)
        !> Its name
        character(len=*), intent(in) :: name
        !> The growth options (new-element values)
        type(growth_options), intent(in) :: growth
        !> The geometry with the new fracture
        type(model_type), intent(out) :: grown
        integer :: n, m, i, parent, nf

        n = work%elements%n
        m = size(xs) - 1
        ! A flaw (element 0) takes element 1's values, overwritten below.
        parent = max(parent_element, 1)
        grown = work
        call inherit_values(work%elements, [(i, i = 1, n), spread(parent, 1, m)], &
                            [spread(.false., 1, n), spread(.true., 1, m)], growth, &
                            grown%elements)
        associate (e => grown%elements, new => [(i, i = n + 1, n + m)])
            e%x_begin(new) = xs(:m)
            e%y_begin(new) = ys(:m)
            e%x_end(new) = xs(2:)
            e%y_end(new) = ys(2:)
            e%fracture_id(new) = size(work%fractures) + 1
            if (kind == initiation_flaw) then
                ! Intact rock: no friction, cohesion or strength law but what &growth gives.
                e%condition(new) = condition_contact
                e%mu(new) = 0.0_wp
                e%sf(new) = 0.0_wp
                e%pressure(new) = 0.0_wp
                e%bc_s(new) = 0.0_wp
                e%bc_n(new) = 0.0_wp
            end if
        end associate
        if (kind == initiation_flaw) then
            call default_strength_laws(grown%elements, [(i > n, i = 1, n + m)])
            call take_new_element_laws(grown%elements, [(i > n, i = 1, n + m)], growth)
        end if
        call compute_geometry(grown%elements)
        ! Element by element: an array constructor of a type with an allocatable name
        ! leaks its temporaries with gfortran (valgrind).
        nf = size(work%fractures)
        deallocate (grown%fractures)
        allocate (grown%fractures(nf + 1))
        grown%fractures(:nf) = work%fractures
        grown%fractures(nf + 1)%name = name
        grown%fractures(nf + 1)%first_element = n + 1
        grown%fractures(nf + 1)%last_element = n + m
    end subroutine add_fracture

end module ddc_growth_new_fracture
