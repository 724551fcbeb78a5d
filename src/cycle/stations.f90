!> Displacements of a cycle run at the model's observation points
!> (docs/theory/cycles.md#displacements): the kernels' displacement per unit slip of each
!> rate-and-state element, assembled once, and back-slip's rigid translation. With slip
!> delta and plate slip V_p t,
!>
!>     u = G (delta - V_p t) + r V_p t,
!>
!> where r is +s/2 on the negative face's side of the fault line and -s/2 on the positive
!> face's side (s the fault's direction): the two blocks of a planar fault that reaches
!> the free surface move apart by V_p t, half each. For another geometry back-slip has no
!> such blocks, and r is 0.
module ddc_cycle_stations
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, domain_half_plane
    use ddc_model_medium, only: elastic_medium
    use ddc_influence_kernel, only: dd_kernel, face_negative
    use ddc_influence_assembly, only: kernel_function, select_kernel, image_transform, &
        image_transforms, kernel_with_images
    implicit none
    private

    public :: station_set, new_stations, planar_to_surface

    !> Relative tolerance of the fault being planar (of its length)
    real(wp), parameter :: planar_tolerance = 1.0e-9_wp

    !> The observation points of a cycle run.
    type :: station_set
        !> Number of points
        integer :: p = 0
        !> Displacement x and y per unit slip of each rate-and-state element [-], shape (p, m)
        real(wp), allocatable :: gx(:, :), gy(:, :)
        !> Rigid translation x and y per unit plate slip [-], shape (p)
        real(wp), allocatable :: rx(:), ry(:)
    contains
        procedure :: displacement
    end type station_set

contains

    !> Whether the rate-and-state elements `rows` lie on one line that reaches the free
    !> surface of a half-plane (back-slip's blocks are then rigid).
    pure logical function planar_to_surface(elements, rows)
        !> The elements, geometry computed
        type(element_set), intent(in) :: elements
        !> The rate-and-state elements, shape (m)
        integer, intent(in) :: rows(:)
        real(wp) :: nx, ny, reach, length
        integer :: j

        planar_to_surface = .false.
        if (elements%domain /= domain_half_plane .or. size(rows) == 0) return
        nx = -elements%sin_beta(rows(1))
        ny = elements%cos_beta(rows(1))
        length = 2.0_wp * sum(elements%half_length(rows))
        do j = 1, size(rows)
            associate (i => rows(j))
                if (abs(distance_off(elements%x_begin(i), elements%y_begin(i))) > &
                    planar_tolerance * length .or. abs(distance_off(elements%x_end(i), &
                    elements%y_end(i))) > planar_tolerance * length) return
            end associate
        end do
        reach = max(maxval(elements%y_begin(rows)), maxval(elements%y_end(rows)))
        planar_to_surface = abs(reach) <= planar_tolerance * length

    contains

        pure real(wp) function distance_off(x, y)
            real(wp), intent(in) :: x, y

            distance_off = nx * (x - elements%x_mid(rows(1))) + ny * (y - elements%y_mid(rows(1)))
        end function distance_off
    end function planar_to_surface

    !> The points (x, y) of a run on the rate-and-state elements `rows`.
    function new_stations(medium, rows, x, y) result(stations)
        !> The elements in the rock, geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The rate-and-state elements, shape (m)
        integer, intent(in) :: rows(:)
        !> The points [length unit], shape (p)
        real(wp), intent(in) :: x(:), y(:)
        type(station_set) :: stations
        procedure(kernel_function), pointer :: kernel
        type(image_transform), allocatable :: images(:)
        type(dd_kernel) :: k
        logical :: general
        real(wp) :: side
        integer :: i, j

        stations%p = size(x)
        allocate (stations%gx(size(x), size(rows)), stations%gy(size(x), size(rows)))
        allocate (stations%rx(size(x)), stations%ry(size(x)), source=0.0_wp)
        call select_kernel(medium, .true., general, kernel)
        images = image_transforms(medium%elements%symmetry)
        do j = 1, size(rows)
            do i = 1, size(x)
                k = kernel_with_images(kernel, x(i), y(i), medium, rows(j), images, &
                                       face_negative)
                stations%gx(i, j) = k%ux(1)
                stations%gy(i, j) = k%uy(1)
            end do
        end do
        if (.not. planar_to_surface(medium%elements, rows)) return
        associate (first => rows(1), c => medium%elements%cos_beta(rows(1)), &
                   s => medium%elements%sin_beta(rows(1)), elements => medium%elements)
            do i = 1, size(x)
                ! Positive side: n . (p - m) > 0, with n = (-sin, cos)
                side = -s * (x(i) - elements%x_mid(first)) + c * (y(i) - elements%y_mid(first))
                stations%rx(i) = -sign(0.5_wp, side) * c
                stations%ry(i) = -sign(0.5_wp, side) * s
            end do
        end associate
    end function new_stations

    !> Displacement at the points for back-slip DDs ds = delta - V_p t and plate slip V_p t
    !> (or the velocity for ds = V - V_p and the plate rate) [length unit], shape (p).
    pure subroutine displacement(stations, ds, plate, ux, uy)
        !> The points
        class(station_set), intent(in) :: stations
        !> Back-slip DDs of the rate-and-state elements [length unit], shape (m)
        real(wp), intent(in) :: ds(:)
        !> Plate slip [length unit]
        real(wp), intent(in) :: plate
        !> Displacement x and y [length unit], shape (p)
        real(wp), intent(out) :: ux(:), uy(:)

        ux = matmul(stations%gx, ds) + stations%rx * plate
        uy = matmul(stations%gy, ds) + stations%ry * plate
    end subroutine displacement

end module ddc_cycle_stations
