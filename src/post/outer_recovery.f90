!> The elements outside the zones of the local K re-solve, recovered to higher order
!> (docs/theory/tips.md#the-local-re-solve).
!>
!> Each such traction or contact element keeps the two DDs of the solve at its midpoint,
!> but acts with a DD that varies along it: the quadratic through its midpoint value and
!> those of its neighbours along the fracture (one-sided beside a tip zone's far end, a
!> junction or a kink; linear or constant where fewer neighbours qualify). A constant
!> element's DD steps at its ends; those steps stress the points near them, a re-solved
!> zone's nodes and the neighbours' midpoints, at first order in the element length. The
!> recovered DD has no such steps: what is left is of the order of the quadratic's error.
!> A straight source farther than near_lengths of its lengths from a receiver acts as two
!> constant halves with the DD's mean and first moment (the two leading terms of its field
!> there; a curved one's first moment has parts two halves do not hold: the turn of its
!> frame and its bow).
module ddc_post_outer_recovery
    use ddc_kinds, only: wp
    use ddc_model_medium, only: elastic_medium
    use ddc_influence_kernel, only: dd_kernel, face_negative
    use ddc_influence_assembly, only: kernel_function, image_transform, &
        segment_kernel_with_images, resolved_tractions
    use ddc_influence_higher_order, only: weighted_element, arc_element, node_xi, &
        element_tractions, point_at
    use ddc_post_tips, only: end_neighbours, end_turn
    implicit none
    private

    public :: outer_recovery, recover_outer, recovered_block, stencil_blocks, halves_kernels
    public :: halves_block, near_lengths, next_recovered, far_recovered_blocks

    !> A source nearer than this many of its lengths acts with its recovered DD, a farther
    !> one as two constant halves with the recovered DD's means over them
    real(wp), parameter :: near_lengths = 8.0_wp
    !> Recovered neighbours along the fracture on each side of a receiver whose recovered DD
    !> at its arc is compared with their constant DD at its chord in the correction of its
    !> row: on a straight receiver (the rest differ by their DDs' first moments' difference,
    !> falling as the cube of the distance), and on a curved one (whose arc and chord
    !> midpoints see the whole fracture's constant DDs differently)
    integer, parameter, public :: straight_reach = 64, curved_reach = 4096
    !> The mean of a quadratic through nodes at -2/3, 0, 2/3 of the half-length, as the
    !> weights of the nodal values, and its first moment about the midpoint per length**2
    real(wp), parameter :: quadratic_mean(3) = [0.375_wp, 0.25_wp, 0.375_wp]
    real(wp), parameter :: quadratic_moment(3) = [-0.125_wp, 0.0_wp, 0.125_wp]

    !> The recovered elements of one geometry.
    type :: outer_recovery
        !> Elements recovered (model numbering), shape (m), and each element's place among
        !> them (0: not recovered), shape (n)
        integer, allocatable :: element(:), place(:)
        !> Their arcs (the model's sampled curvature), shape (m)
        type(weighted_element), allocatable :: arc(:)
        !> The elements whose midpoint values the DD of each passes through (0: unused),
        !> shape (3, m), and the weight of each value at the three nodes, shape (3, 3, m)
        integer, allocatable :: stencil(:, :)
        real(wp), allocatable :: weight(:, :, :)
        !> The neighbour of every element at each end where one alone shares it (0: none),
        !> and that neighbour's end there, shape (2, n) (ddc_post_tips end_neighbours)
        integer, allocatable :: neighbour(:, :), neighbour_side(:, :)
    end type outer_recovery

contains

    !> The recovery of the elements that serve (traction and contact elements) outside the
    !> zones.
    pure function recover_outer(medium, curvature, serves, in_zone, max_turn) result(outer)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The sampled curvature of every element [1 / length unit], shape (n)
        real(wp), intent(in) :: curvature(:)
        !> Whether each element is a traction or contact element, and whether it is
        !> re-solved in a zone, shape (n)
        logical, intent(in) :: serves(:), in_zone(:)
        !> A neighbour that turns by more than this [rad] does not continue the DD
        real(wp), intent(in) :: max_turn
        type(outer_recovery) :: outer
        integer :: m, k, i

        associate (e => medium%elements)
            m = count(serves .and. .not. in_zone)
            allocate (outer%element(m))
            outer%element = pack([(i, i = 1, e%n)], serves .and. .not. in_zone)
            allocate (outer%place(e%n), source=0)
            outer%place(outer%element) = [(k, k = 1, m)]
            allocate (outer%arc(m), outer%stencil(3, m), outer%weight(3, 3, m), &
                      outer%neighbour(2, e%n), outer%neighbour_side(2, e%n))
            call end_neighbours(e, outer%neighbour, outer%neighbour_side)
            do k = 1, m
                i = outer%element(k)
                outer%arc(k) = arc_element(e%x_begin(i), e%y_begin(i), e%x_end(i), e%y_end(i), &
                                           curvature(i))
                call stencil_of(i, 0.5_wp * outer%arc(k)%length, outer%stencil(:, k), &
                                outer%weight(:, :, k))
            end do
        end associate

    contains

        !> The neighbour beyond end `side` of element i that continues its DD (0: none), its
        !> end there, and the distance between their midpoints along the fracture.
        pure subroutine next_along(i, side, j, j_side, distance)
            integer, intent(in) :: i, side
            integer, intent(out) :: j, j_side
            real(wp), intent(out) :: distance

            associate (e => medium%elements)
                j = outer%neighbour(side, i)
                j_side = 0
                distance = 0.0_wp
                if (j == 0) return
                j_side = outer%neighbour_side(side, i)
                if (.not. serves(j) .or. abs(end_turn(e, i, side, j, j_side)) > max_turn) then
                    j = 0
                    return
                end if
                distance = e%half_length(i) + e%half_length(j)
            end associate
        end subroutine next_along

        !> The midpoints the DD of element i passes through and their weights at its nodes:
        !> both neighbours where they continue it, else two on one side, else fewer.
        pure subroutine stencil_of(i, h, stencil, weight)
            integer, intent(in) :: i
            !> Half the arc length of element i
            real(wp), intent(in) :: h
            integer, intent(out) :: stencil(3)
            real(wp), intent(out) :: weight(3, 3)
            integer :: near(2), near_side(2), far(2), far_side(2), side, count
            real(wp) :: d_near(2), d_far(2), position(3), at
            integer :: node, p, q

            do side = 1, 2
                call next_along(i, side, near(side), near_side(side), d_near(side))
                far(side) = 0
                d_far(side) = 0.0_wp
                if (near(side) > 0) call next_along(near(side), 3 - near_side(side), &
                                                    far(side), far_side(side), d_far(side))
            end do
            ! Positions along the fracture from i's midpoint, positive toward its end.
            stencil = 0
            position = 0.0_wp
            stencil(1) = i
            count = 1
            if (near(1) > 0 .and. near(2) > 0) then
                stencil(2:3) = near
                position(2:3) = [-d_near(1), d_near(2)]
                count = 3
            else
                do side = 1, 2
                    if (near(side) == 0) cycle
                    stencil(2) = near(side)
                    position(2) = merge(-1.0_wp, 1.0_wp, side == 1) * d_near(side)
                    count = 2
                    if (far(side) > 0) then
                        stencil(3) = far(side)
                        position(3) = merge(-1.0_wp, 1.0_wp, side == 1) * &
                                      (d_near(side) + d_far(side))
                        count = 3
                    end if
                end do
            end if
            weight = 0.0_wp
            do node = 1, 3
                at = node_xi(node) * h
                do p = 1, count
                    weight(node, p) = 1.0_wp
                    do q = 1, count
                        if (q /= p) weight(node, p) = weight(node, p) * (at - position(q)) / &
                                                      (position(p) - position(q))
                    end do
                end do
            end do
        end subroutine stencil_of


    end function recover_outer

    !> Shear and normal traction at a receiver per unit nodal DD of recovered element k,
    !> shape (2, 6) (rows t_s, t_n; columns Ds, Dn at each node): of its recovered DD where
    !> the receiver is near it (or always, where asked), else of its two halves.
    pure function recovered_block(outer, kernel, images, medium, k, x, y, c, s, s_self, &
                                  exact) result(block)
        !> The recovery
        type(outer_recovery), intent(in) :: outer
        !> The model's kernel and image transforms (ddc_influence_assembly)
        procedure(kernel_function) :: kernel
        type(image_transform), intent(in) :: images(:)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The recovered element
        integer, intent(in) :: k
        !> Receiver [length unit] and its plane's direction cosines
        real(wp), intent(in) :: x, y, c, s
        !> The receiver's arc length from the element's begin where it lies on the element,
        !> negative elsewhere [length unit]
        real(wp), intent(in) :: s_self
        !> Use the recovered DD at any distance
        logical, intent(in) :: exact
        real(wp) :: block(2, 6)
        real(wp) :: constant(2, 2)
        logical :: far

        if (.not. exact .and. s_self < 0.0_wp) then
            call far_recovered_blocks(outer, kernel, images, medium, k, x, y, c, s, block, &
                                      constant, far)
            if (far) return
        end if
        call element_tractions(kernel, images, medium, outer%arc(k), s_self, x, y, c, s, block)
    end function recovered_block

    !> Where the receiver is far from straight recovered element k (beyond near_lengths of
    !> its lengths from its midpoint): its block per unit nodal DD from its two halves
    !> (recovered_block), and its constant DD's block at the same receiver (the two halves
    !> together), shape (2, 2); else far = .false. and neither is set.
    pure subroutine far_recovered_blocks(outer, kernel, images, medium, k, x, y, c, s, block, &
                                         constant, far)
        type(outer_recovery), intent(in) :: outer
        procedure(kernel_function) :: kernel
        type(image_transform), intent(in) :: images(:)
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: k
        !> Receiver [length unit] and its plane's direction cosines
        real(wp), intent(in) :: x, y, c, s
        real(wp), intent(out) :: block(2, 6), constant(2, 2)
        logical, intent(out) :: far
        real(wp) :: halves(2, 2, 2)
        integer :: i

        i = outer%element(k)
        associate (e => medium%elements, arc => outer%arc(k))
            far = arc%curvature == 0.0_wp .and. &
                  hypot(x - e%x_mid(i), y - e%y_mid(i)) > near_lengths * arc%length
            if (.not. far) return
            halves = halves_kernels(kernel, images, medium, arc, x, y, c, s)
            block = halves_block(halves, arc%length, quadratic_mean, &
                                 quadratic_moment * arc%length**2)
            constant = halves(:, :, 1) + halves(:, :, 2)
        end associate
    end subroutine far_recovered_blocks

    !> A recovered element's block per unit nodal DD (recovered_block) as blocks per unit
    !> midpoint DD of the elements of its stencil, shape (2, 2, 3) (rows t_s, t_n; columns
    !> Ds, Dn; zero where the stencil has no element).
    pure function stencil_blocks(outer, k, nodal_block) result(blocks)
        type(outer_recovery), intent(in) :: outer
        integer, intent(in) :: k
        real(wp), intent(in) :: nodal_block(2, 6)
        real(wp) :: blocks(2, 2, 3)
        integer :: p, node

        ! A DD's components in its element's frame are those in any neighbour's, whichever
        ! way the neighbour runs (both the frame and the faces turn).
        blocks = 0.0_wp
        do p = 1, 3
            if (outer%stencil(p, k) == 0) cycle
            do node = 1, 3
                blocks(:, :, p) = blocks(:, :, p) + outer%weight(node, p, k) * &
                                  nodal_block(:, 2 * node - 1:2 * node)
            end do
        end do
    end function stencil_blocks

    !> Shear and normal traction at a receiver far from an element per unit DD of each of two
    !> constant segments on the chords of its halves, shape (2, 2, 2) (rows t_s, t_n;
    !> columns Ds, Dn; the half).
    pure function halves_kernels(kernel, images, medium, element, x, y, c, s) result(blocks)
        procedure(kernel_function) :: kernel
        type(image_transform), intent(in) :: images(:)
        type(elastic_medium), intent(in) :: medium
        type(weighted_element), intent(in) :: element
        !> Receiver [length unit] and its plane's direction cosines
        real(wp), intent(in) :: x, y, c, s
        real(wp) :: blocks(2, 2, 2)
        type(dd_kernel) :: kh
        real(wp) :: p(2, 3), cs(2), half, ts(2), tn(2)
        integer :: h

        p(:, 1) = [element%xb, element%yb]
        call point_at(element, 0.5_wp * element%length, p(1, 2), p(2, 2), cs(1), cs(2))
        call point_at(element, element%length, p(1, 3), p(2, 3), cs(1), cs(2))
        do h = 1, 2
            half = 0.5_wp * norm2(p(:, h + 1) - p(:, h))
            kh = segment_kernel_with_images(kernel, x, y, 0.5_wp * (p(1, h) + p(1, h + 1)), &
                                            0.5_wp * (p(2, h) + p(2, h + 1)), half, &
                                            (p(1, h + 1) - p(1, h)) / (2.0_wp * half), &
                                            (p(2, h + 1) - p(2, h)) / (2.0_wp * half), images, &
                                            medium, face_negative)
            call resolved_tractions(kh, c, s, ts, tn)
            blocks(1, :, h) = ts
            blocks(2, :, h) = tn
        end do
    end function halves_kernels

    !> The block per unit nodal DD, shape (2, 6), of an element acting as two constant halves
    !> (halves_kernels) whose DDs have its mean and first moment about the midpoint, given
    !> as the weights of the three nodal values in them [-] and [length unit**2].
    pure function halves_block(halves, length, mean_weight, moment_weight) result(block)
        real(wp), intent(in) :: halves(2, 2, 2), length, mean_weight(3), moment_weight(3)
        real(wp) :: block(2, 6)
        real(wp) :: share(3, 2)
        integer :: node

        ! Halves of length L / 2 at -L/4 and L/4: m2 - m1 = 8 moment / L^2.
        share(:, 1) = mean_weight - 4.0_wp * moment_weight / length**2
        share(:, 2) = mean_weight + 4.0_wp * moment_weight / length**2
        do node = 1, 3
            block(:, 2 * node - 1:2 * node) = share(node, 1) * halves(:, :, 1) + &
                                              share(node, 2) * halves(:, :, 2)
        end do
    end function halves_block

    !> The next recovered element along the fracture from element j, leaving it by its end
    !> `side` (0 where none: a junction, a zone, a tip or back at `first`), and the end
    !> by which to leave that one.
    pure subroutine next_recovered(outer, j, side, first, next, next_side)
        type(outer_recovery), intent(in) :: outer
        integer, intent(in) :: j, side, first
        integer, intent(out) :: next, next_side

        next = outer%neighbour(side, j)
        next_side = 0
        if (next == 0) return
        if (outer%place(next) == 0 .or. next == first) then
            next = 0
            return
        end if
        next_side = 3 - outer%neighbour_side(side, j)
    end subroutine next_recovered

end module ddc_post_outer_recovery
