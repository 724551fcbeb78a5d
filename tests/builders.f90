!> Models built in code for the physics tests (no input files involved).
module ddc_test_builders
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, fracture_type
    use ddc_mesh_geometry, only: allocate_elements, compute_geometry
    use ddc_influence_kernel, only: pi
    implicit none
    private

    public :: straight_crack, circular_hole

contains

    !> A straight crack of half-length a centred on the origin at angle beta [rad], n equal
    !> elements, every element with the same condition and given values.
    function straight_crack(n, a, beta, condition, bc_s, bc_n, youngs_modulus, nu) result(model)
        integer, intent(in) :: n, condition
        real(wp), intent(in) :: a, beta, bc_s, bc_n, youngs_modulus, nu
        type(model_type) :: model
        real(wp) :: t(0:n)
        integer :: i

        model%title = 'straight crack'
        model%youngs_modulus = youngs_modulus
        model%poissons_ratio = nu
        call allocate_elements(model%elements, n)
        t = [(-a + 2.0_wp * a * real(i, wp) / real(n, wp), i = 0, n)]
        model%elements%x_begin = t(0:n - 1) * cos(beta)
        model%elements%y_begin = t(0:n - 1) * sin(beta)
        model%elements%x_end = t(1:n) * cos(beta)
        model%elements%y_end = t(1:n) * sin(beta)
        call fill_common(model, condition, bc_s, bc_n)
    end function straight_crack

    !> A circular hole of radius r0 around the origin, n elements ordered counter-clockwise
    !> so that the body (outside) lies on the negative face of every element.
    function circular_hole(n, r0, condition, bc_s, bc_n, youngs_modulus, nu) result(model)
        integer, intent(in) :: n, condition
        real(wp), intent(in) :: r0, bc_s, bc_n, youngs_modulus, nu
        type(model_type) :: model
        real(wp) :: theta(0:n)
        integer :: i

        model%title = 'circular hole'
        model%youngs_modulus = youngs_modulus
        model%poissons_ratio = nu
        call allocate_elements(model%elements, n)
        theta = [(2.0_wp * pi * real(i, wp) / real(n, wp), i = 0, n)]
        model%elements%x_begin = r0 * cos(theta(0:n - 1))
        model%elements%y_begin = r0 * sin(theta(0:n - 1))
        model%elements%x_end = r0 * cos(theta(1:n))
        model%elements%y_end = r0 * sin(theta(1:n))
        ! Close the loop exactly so the last end is the first begin.
        model%elements%x_end(n) = model%elements%x_begin(1)
        model%elements%y_end(n) = model%elements%y_begin(1)
        call fill_common(model, condition, bc_s, bc_n)
    end function circular_hole

    !> Conditions, material values and the single fracture record shared by the builders.
    subroutine fill_common(model, condition, bc_s, bc_n)
        type(model_type), intent(inout) :: model
        integer, intent(in) :: condition
        real(wp), intent(in) :: bc_s, bc_n

        model%elements%fracture_id = 1
        model%elements%condition = condition
        model%elements%bc_s = bc_s
        model%elements%bc_n = bc_n
        model%elements%mu = 0.0_wp
        model%elements%sf = 0.0_wp
        model%elements%pressure = 0.0_wp
        call compute_geometry(model%elements)
        allocate (model%fractures(1))
        model%fractures(1) = fracture_type(name='fracture_1', first_element=1, &
                                           last_element=model%elements%n)
        allocate (model%observations(0))
    end subroutine fill_common

end module ddc_test_builders
