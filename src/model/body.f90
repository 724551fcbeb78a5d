!> A finite body: the rock inside one closed polygon, loaded through its boundary
!> (docs/finite-bodies.md, docs/theory/finite-bodies.md).
!>
!> The boundary is cut into straight elements, each with three nodes; at every node one
!> displacement or traction component is given along the side (s, from the side's first
!> vertex to its next) and one along the outward normal (n), by the side's condition, and
!> the other two are unknowns. The given values vary linearly along a side, from its value
!> at the first vertex to the one at the next. This module holds the definition and its
!> geometry; the solve of the boundary is in ddc_influence_body.
module ddc_model_body
    use ddc_kinds, only: wp
    implicit none
    private

    public :: finite_body, set_body_geometry, inside_body, body_nodes

    !> Nodes per element
    integer, parameter :: body_nodes = 3

    type :: finite_body
        !> Vertices of the closed polygon, the first not repeated [length unit], shape (m)
        real(wp), allocatable :: x(:), y(:)
        !> Elements, condition (ddc_model_types: condition_traction ...
        !> condition_mixed_ss_un) and given
        !> values along s and n at the side's first vertex and at its next of each side
        integer, allocatable :: elements(:), condition(:)
        real(wp), allocatable :: bc_s(:), bc_n(:), bc_s_end(:), bc_n_end(:)
        !> +1 when the vertices run counter-clockwise (the interior on the left of each
        !> element, on the side of its normal), -1 clockwise
        integer :: orientation = 1
        !> Per element: midpoint, half-length, direction, side [length unit]
        real(wp), allocatable :: xm(:), ym(:), a(:), cosb(:), sinb(:)
        integer, allocatable :: side(:)
        !> Per node (element by element, three each): position [length unit], the given
        !> values along s and n [length unit or stress unit]
        real(wp), allocatable :: node_x(:), node_y(:), given_s(:), given_n(:)
        !> The solved system (ddc_influence_body%prepare_body): LU factors and pivots of the
        !> boundary's equations, bordered by its free rigid motions, and the unknowns under
        !> the given values with every fracture closed
        real(wp), allocatable :: factors(:, :)
        integer, allocatable :: pivots(:)
        real(wp), allocatable :: loaded(:)
        !> Number of rigid motions the conditions leave free (0 to 3); the left null vectors
        !> of the equations they leave (columns, shape (nz, free)) and the inverse of their
        !> Gram matrix: a right-hand side loses its part along them before a solve
        integer :: free_motions = 0
        real(wp), allocatable :: left_null(:, :), left_null_gram(:, :)
    end type finite_body

contains

    !> The elements and nodes of a body whose sides, conditions and values are set.
    pure subroutine set_body_geometry(body)
        type(finite_body), intent(inout) :: body
        real(wp) :: xb, yb, xe, ye, length, t0, t1, t
        integer :: m, n, side, k, e, node, next

        m = size(body%x)
        n = sum(body%elements)
        ! Twice the signed area: positive when counter-clockwise
        body%orientation = merge(1, -1, sum(body%x * cshift(body%y, 1) - cshift(body%x, 1) * &
                                           body%y) > 0.0_wp)
        allocate (body%xm(n), body%ym(n), body%a(n), body%cosb(n), body%sinb(n), body%side(n))
        allocate (body%node_x(body_nodes * n), body%node_y(body_nodes * n))
        allocate (body%given_s(body_nodes * n), body%given_n(body_nodes * n))
        e = 0
        do side = 1, m
            next = merge(1, side + 1, side == m)
            length = hypot(body%x(next) - body%x(side), body%y(next) - body%y(side))
            do k = 1, body%elements(side)
                e = e + 1
                t0 = real(k - 1, wp) / real(body%elements(side), wp)
                t1 = real(k, wp) / real(body%elements(side), wp)
                xb = body%x(side) + t0 * (body%x(next) - body%x(side))
                yb = body%y(side) + t0 * (body%y(next) - body%y(side))
                xe = body%x(side) + t1 * (body%x(next) - body%x(side))
                ye = body%y(side) + t1 * (body%y(next) - body%y(side))
                body%xm(e) = 0.5_wp * (xb + xe)
                body%ym(e) = 0.5_wp * (yb + ye)
                body%a(e) = 0.5_wp * hypot(xe - xb, ye - yb)
                body%cosb(e) = (body%x(next) - body%x(side)) / length
                body%sinb(e) = (body%y(next) - body%y(side)) / length
                body%side(e) = side
                do node = 1, body_nodes
                    associate (i => body_nodes * (e - 1) + node, &
                               xi => real(2 * node - 4, wp) / 3.0_wp)
                        body%node_x(i) = body%xm(e) + xi * body%a(e) * body%cosb(e)
                        body%node_y(i) = body%ym(e) + xi * body%a(e) * body%sinb(e)
                        t = hypot(body%node_x(i) - body%x(side), body%node_y(i) - body%y(side)) &
                            / length
                        body%given_s(i) = (1.0_wp - t) * body%bc_s(side) + t * body%bc_s_end(side)
                        body%given_n(i) = (1.0_wp - t) * body%bc_n(side) + t * body%bc_n_end(side)
                    end associate
                end do
            end do
        end do
    end subroutine set_body_geometry

    !> Whether (x, y) lies strictly inside the body's polygon (even-odd rule), farther than
    !> tolerance from its boundary [length unit].
    pure logical function inside_body(body, x, y, tolerance)
        type(finite_body), intent(in) :: body
        real(wp), intent(in) :: x, y, tolerance
        integer :: i, j, m
        real(wp) :: dx, dy, t, d

        m = size(body%x)
        inside_body = .false.
        j = m
        do i = 1, m
            associate (xi => body%x(i), yi => body%y(i), xj => body%x(j), yj => body%y(j))
                if ((yi > y) .neqv. (yj > y)) then
                    if (x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside_body = .not. inside_body
                end if
                dx = xi - xj
                dy = yi - yj
                t = max(0.0_wp, min(1.0_wp, ((x - xj) * dx + (y - yj) * dy) / (dx**2 + dy**2)))
                d = hypot(x - xj - t * dx, y - yj - t * dy)
            end associate
            if (d <= tolerance) then
                inside_body = .false.
                return
            end if
            j = i
        end do
    end function inside_body

end module ddc_model_body
