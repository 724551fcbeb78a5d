!> Models built in code for the physics tests (no input files involved).
module ddc_test_builders
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, fracture_type, symmetry_options, condition_traction, &
                               condition_contact, element_array_action, for_each_element_array
    use ddc_contact_options, only: solver_options
    use ddc_mesh_geometry, only: allocate_elements, compute_geometry
    use ddc_mesh_polyline, only: polyline_elements
    use ddc_constants, only: pi
    implicit none
    private

    public :: polyline_model, straight_crack, circular_hole, join_fractures, kinked_network
    public :: kinked_contact_fault

    !> One per-element array, held.
    type :: held_reals
        real(wp), allocatable :: values(:)
    end type held_reals
    type :: held_integers
        integer, allocatable :: values(:)
    end type held_integers

    !> Takes the per-element arrays of one set, then appends each to the same array of
    !> another (join_fractures): both passes go through for_each_element_array, in its order.
    type, extends(element_array_action) :: element_append
        !> The arrays taken
        type(held_reals), allocatable :: reals(:)
        type(held_integers), allocatable :: integers(:)
        !> Arrays appended so far; appending (the second pass) once taken
        integer :: real_count = 0, integer_count = 0
        logical :: appending = .false.
    contains
        procedure :: on_reals => append_reals
        procedure :: on_integers => append_integers
    end type element_append

contains

    !> One fracture along a polyline with counts(k) equal elements on segment k, every
    !> element with the same condition and given values; contact values mu = sf = p = 0.
    function polyline_model(x, y, counts, condition, bc_s, bc_n, youngs_modulus, nu) &
        result(model)
        real(wp), intent(in) :: x(:), y(:)
        integer, intent(in) :: counts(:), condition
        real(wp), intent(in) :: bc_s, bc_n, youngs_modulus, nu
        type(model_type) :: model

        model%title = 'test model'
        model%youngs_modulus = youngs_modulus
        model%poissons_ratio = nu
        model%length_unit = 'm'
        model%stress_unit = 'MPa'
        model%time_unit = 's'
        model%solver = solver_options()
        call allocate_elements(model%elements, sum(counts))
        call polyline_elements(x, y, counts, model%elements%x_begin, model%elements%y_begin, &
                               model%elements%x_end, model%elements%y_end)
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
    end function polyline_model

    !> A straight crack of half-length a centred on the origin at angle beta [rad].
    function straight_crack(n, a, beta, condition, bc_s, bc_n, youngs_modulus, nu) result(model)
        integer, intent(in) :: n, condition
        real(wp), intent(in) :: a, beta, bc_s, bc_n, youngs_modulus, nu
        type(model_type) :: model

        model = polyline_model([-a * cos(beta), a * cos(beta)], [-a * sin(beta), a * sin(beta)], &
                               [n], condition, bc_s, bc_n, youngs_modulus, nu)
    end function straight_crack

    !> A circular hole of radius r0 around the origin, n elements ordered counter-clockwise
    !> so that the body (outside) lies on the negative face of every element.
    function circular_hole(n, r0, condition, bc_s, bc_n, youngs_modulus, nu) result(model)
        integer, intent(in) :: n, condition
        real(wp), intent(in) :: r0, bc_s, bc_n, youngs_modulus, nu
        type(model_type) :: model
        real(wp) :: theta(0:n)
        integer :: i

        theta = [(2.0_wp * pi * real(i, wp) / real(n, wp), i = 0, n)]
        ! Closing the loop exactly: the last vertex is the first.
        model = polyline_model([r0 * cos(theta(0:n - 1)), r0], [r0 * sin(theta(0:n - 1)), 0.0_wp], &
                               [(1, i = 1, n)], condition, bc_s, bc_n, youngs_modulus, nu)
    end function circular_hole

    !> Append the fractures of `other` to `model` (same material and loading assumed).
    subroutine join_fractures(model, other)
        type(model_type), intent(inout) :: model
        type(model_type), intent(in) :: other
        type(model_type) :: taken
        type(element_append) :: append
        integer :: n

        n = model%elements%n
        taken = other
        allocate (append%reals(0), append%integers(0))
        call for_each_element_array(taken%elements, append)
        append%appending = .true.
        call for_each_element_array(model%elements, append)
        model%elements%fracture_id(n + 1:) = model%elements%fracture_id(n + 1:) + &
                                             size(model%fractures)
        model%elements%n = n + other%elements%n
        call compute_geometry(model%elements)
        model%fractures = [model%fractures, fracture_type(name='fracture_2', &
            first_element=n + 1, last_element=n + other%elements%n)]
    end subroutine join_fractures

    !> Two fractures of traction elements, one kinked (12 elements of unequal lengths) and
    !> one straight (6), in x > 0 and y > -0.6, with the given symmetry about x = 0 and
    !> y = -0.6; E = 1000, nu = 0.25.
    function kinked_network(symmetry_kind) result(model)
        integer, intent(in) :: symmetry_kind
        type(model_type) :: model
        type(model_type) :: other

        model = polyline_model([0.3_wp, 1.0_wp, 1.5_wp], [0.2_wp, 0.25_wp, 0.7_wp], [7, 5], &
                               condition_traction, 0.0_wp, 0.0_wp, 1000.0_wp, 0.25_wp)
        other = polyline_model([0.4_wp, 1.3_wp], [-0.3_wp, -0.1_wp], [6], condition_traction, &
                               0.0_wp, 0.0_wp, &
                               1000.0_wp, 0.25_wp)
        call join_fractures(model, other)
        model%elements%symmetry = symmetry_options(kind=symmetry_kind, xsym=0.0_wp, &
                                                   ysym=-0.6_wp)
    end function kinked_network

    !> A kinked fault: (-1, 0)-(0, 0) then 35 degrees up, 30 contact elements each, Sf = 0,
    !> mu = 0.6, fluid pressure 17.5 under sxx = -5, syy = -20, sxy = 0.5, E = 50000,
    !> nu = 0.25: the flat part is closed and partly sticks, partly slips; the inclined part
    !> opens.
    function kinked_contact_fault() result(model)
        type(model_type) :: model
        real(wp), parameter :: angle = 35.0_wp * pi / 180.0_wp

        model = polyline_model([-1.0_wp, 0.0_wp, cos(angle)], [0.0_wp, 0.0_wp, sin(angle)], &
                               [30, 30], condition_contact, 0.0_wp, 0.0_wp, 50000.0_wp, &
                               0.25_wp)
        model%elements%mu = 0.6_wp
        model%elements%pressure = 17.5_wp
        model%sxx = -5.0_wp
        model%syy = -20.0_wp
        model%sxy = 0.5_wp
    end function kinked_contact_fault

    !> Take a real array (first pass) or append the one taken in its place (second pass).
    subroutine append_reals(action, values)
        class(element_append), intent(inout) :: action
        real(wp), allocatable, intent(inout) :: values(:)
        type(held_reals), allocatable :: more(:)
        integer :: i

        if (action%appending) then
            action%real_count = action%real_count + 1
            values = [values, action%reals(action%real_count)%values]
            return
        end if
        allocate (more(size(action%reals) + 1))
        do i = 1, size(action%reals)
            call move_alloc(action%reals(i)%values, more(i)%values)
        end do
        more(size(more))%values = values
        call move_alloc(more, action%reals)
    end subroutine append_reals

    !> Take an integer array (first pass) or append the one taken in its place (second pass).
    subroutine append_integers(action, values)
        class(element_append), intent(inout) :: action
        integer, allocatable, intent(inout) :: values(:)
        type(held_integers), allocatable :: more(:)
        integer :: i

        if (action%appending) then
            action%integer_count = action%integer_count + 1
            values = [values, action%integers(action%integer_count)%values]
            return
        end if
        allocate (more(size(action%integers) + 1))
        do i = 1, size(action%integers)
            call move_alloc(action%integers(i)%values, more(i)%values)
        end do
        more(size(more))%values = values
        call move_alloc(more, action%integers)
    end subroutine append_integers

end module ddc_test_builders
