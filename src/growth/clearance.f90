!> Where growth must stop or link (docs/theory/growth.md#linking-and-stops): new elements that would
!> cross or touch another element or come closer than half an element length to one, and in a
!> half-plane new elements that would come that close to the free surface y = 0 (or reach it).
!> Nothing is ever meshed across another fracture.
!>
!> Breaking through: in a half-plane a path that would reach the surface, or come that close
!> to it, ends on it instead (reason surface): a link whose target is the surface (target 0),
!> to where the path crosses y = 0 or, where it only comes close, to the point of the surface
!> above the path's highest point; its last point has y = 0 bit for bit and is a crack mouth,
!> no tip. It is refused (the tip stops: intersection) when it would not keep clear of the
!> other elements.
!>
!> Linking: a path that meets an element j of another fracture ends on it instead. The link
!> point P is the crossing with j, or the point of j nearest to the path where it only comes
!> close; P within a quarter of j's length of a vertex of j snaps to that vertex (no tiny
!> element), else j is split at P. The link path runs straight from the tip to P in
!> n = max(1, nint(|P - tip| / h)) equal elements (h: the path's element length), its last
!> point P bit for bit. A link is refused (the tip stops: intersection) when P is within
!> clearance of the other fracture's end (tips meeting); when the link would come within
!> clearance of an element of a third fracture or of its own, touch the other fracture
!> before P (it may approach it at a shallow angle: a hook), or come within clearance of
!> another path or link of the step (head-on); when two links would split the same
!> element. When the two fractures are connected already (by a shared vertex, an earlier
!> link, or in a half-plane both by the free surface; of the step's tips the first in order
!> links) the link is refused as enclosing: it would close a contour around a block of rock
!> (or a wedge under the surface) whose rigid motion leaves the system singular (with contact
!> elements the block slides freely between open and slipping faces) and its DDs
!> undetermined.
module ddc_growth_clearance
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, domain_half_plane, domain_bimaterial
    use ddc_model_body, only: inside_body
    use ddc_model_results, only: growth_intersection, growth_surface, growth_linked, &
        growth_enclosing, growth_interface
    use ddc_growth_extension, only: tip_path, tip_element, tip_end_begin, path_element_length, &
        element_split, outward_direction
    use ddc_mesh_segments, only: segment_distance, point_segment_distance, crossing_fraction, &
        far_apart
    implicit none
    private

    public :: check_paths, path_clear, tip_link, link_parts, ends_on_link

    !> A tip's link to another fracture, or through the free surface
    !> (docs/theory/growth.md#linking-and-stops).
    type :: tip_link
        !> The link path from the tip to the link point (its last point)
        type(tip_path) :: path
        !> The element of the other fracture it ends on (index in the model before growing;
        !> surface_target for the free surface) and whether that element is split at the link
        !> point (else the point is its vertex)
        integer :: target = 0
        logical :: split = .false.
        !> Applied angle, counter-clockwise from the tip's outward direction [rad], and
        !> length of the link [length unit]
        real(wp) :: theta = 0.0_wp, length = 0.0_wp
    end type tip_link

    !> A link point within this fraction of the element's length of a vertex snaps to it
    real(wp), parameter :: snap_fraction = 0.25_wp
    !> Relative margin below the clearance of the tip elements' reach (at_tip)
    real(wp), parameter :: near_tolerance = 1.0e-6_wp

    !> New elements keep at least this fraction of their length from every other element
    !> and from the free surface
    real(wp), parameter :: clearance_fraction = 0.5_wp

    !> check_paths' code of a path that keeps clear (else a growth reason: growth_intersection,
    !> growth_surface, growth_linked or growth_enclosing)
    integer, parameter :: path_clear = 0

    !> The target of a link through the free surface (no element)
    integer, parameter :: surface_target = 0

contains

    !> For every active path: path_clear when its new elements keep clear of every element of the
    !> model (and of a finite body's boundary) and of every other active path,
    !> growth_intersection when they do not,
    !> growth_surface when (in a half-plane) they keep clear of every element but not of
    !> the surface, growth_interface when (with two materials) they keep clear of every
    !> element but not of the interface. The first new element may meet the tip element only
    !> at the tip: its far end must keep clear of the tip element. With `links`, a path that
    !> meets an element of another fracture links (growth_linked, its link in links) unless
    !> the link is
    !> refused (growth_enclosing when the fractures are connected already, else
    !> growth_intersection), and one that does not keep clear of the surface breaks through
    !> it (growth_surface, its link in links) unless that link is refused
    !> (growth_intersection); `fixed` are the links of the step made before, which the new
    !> paths and links must keep clear of.
    pure subroutine check_paths(model, paths, active, problem, links, fixed)
        !> The model before growing, geometry computed
        type(model_type), intent(in) :: model
        !> The candidate paths, one per growing tip
        type(tip_path), intent(in) :: paths(:)
        !> Which paths are candidates, shape (size(paths))
        logical, intent(in) :: active(:)
        !> path_clear or a growth reason for each path (path_clear when not active)
        integer, intent(out) :: problem(:)
        !> The links of the paths that link, shape (size(paths))
        type(tip_link), intent(out), optional :: links(:)
        !> Links made before in the step
        type(tip_link), intent(in), optional :: fixed(:)
        real(wp) :: clearance(size(paths))
        type(tip_path) :: used(size(paths))
        integer :: p, q, hit
        logical :: clash, made

        problem = path_clear
        do p = 1, size(paths)
            if (.not. active(p)) cycle
            clearance(p) = clearance_fraction * path_element_length(paths(p))
            used(p) = paths(p)
            call hits_model(model, paths(p), clearance(p), hit)
            if (hit == 0) then
                ! Clear of the elements: in a finite body, maybe not of its boundary (the
                ! tip stops there).
                if (allocated(model%body)) then
                    if (.not. clear_of_body(model, paths(p), clearance(p))) then
                        problem(p) = growth_intersection
                    end if
                    cycle
                end if
                ! Clear of the elements: with two materials, maybe not of the interface.
                if (model%elements%domain == domain_bimaterial) then
                    if (.not. clear_of_interface(paths(p), model%interface_y, &
                                                 clearance(p))) problem(p) = growth_interface
                    cycle
                end if
                ! In a half-plane, maybe not of the surface.
                if (model%elements%domain /= domain_half_plane) cycle
                if (all(paths(p)%y(1:) <= -clearance(p))) cycle
                problem(p) = growth_surface
                if (.not. present(links)) cycle
                call surface_link(model, paths(p), clearance(p), links(p), made)
                if (made) then
                    used(p) = links(p)%path
                else
                    problem(p) = growth_intersection
                end if
                cycle
            end if
            problem(p) = growth_intersection
            if (.not. present(links)) cycle
            call make_link(model, paths(p), clearance(p), hit, links(p), made)
            if (.not. made) cycle
            if (connected(model, paths(p)%fracture, model%elements%fracture_id(hit), &
                          earlier())) then
                problem(p) = growth_enclosing
            else
                problem(p) = growth_linked
                used(p) = links(p)%path
            end if
        end do
        do p = 1, size(paths)
            if (.not. active(p)) cycle
            do q = p + 1, size(paths)
                if (.not. active(q)) cycle
                clash = path_distance(used(p), used(q)) < max(clearance(p), clearance(q))
                if (problem(p) == growth_linked .and. problem(q) == growth_linked) then
                    clash = clash .or. links(p)%target == links(q)%target
                end if
                if (clash) then
                    problem(p) = growth_intersection
                    problem(q) = growth_intersection
                end if
            end do
            if (.not. present(fixed)) cycle
            do q = 1, size(fixed)
                clash = path_distance(used(p), fixed(q)%path) < clearance(p)
                if (problem(p) == growth_linked) then
                    clash = clash .or. links(p)%target == fixed(q)%target
                end if
                if (clash) problem(p) = growth_intersection
            end do
        end do

    contains

        !> The links made before path p: the fixed ones, then those of paths 1 .. p - 1.
        pure function earlier() result(made_links)
            type(tip_link), allocatable :: made_links(:)
            integer :: q

            allocate (made_links(0))
            if (present(fixed)) made_links = fixed
            do q = 1, p - 1
                if (ends_on_link(problem(q))) made_links = [made_links, links(q)]
            end do
        end function earlier

    end subroutine check_paths

    !> Whether a path keeps at least `clearance` from the interface y = interface_y of two
    !> bonded half-planes with its new points, on its tip's side: a tip stops before the
    !> interface, as crossing or deflecting into it needs a rule of its own
    !> (docs/theory/bimaterial.md#growth). A tip on the interface keeps clear of it in no
    !> direction.
    pure logical function clear_of_interface(path, interface_y, clearance)
        !> The path
        type(tip_path), intent(in) :: path
        !> Height of the interface [length unit]
        real(wp), intent(in) :: interface_y
        !> The clearance of its new elements [length unit]
        real(wp), intent(in) :: clearance
        real(wp) :: side

        side = sign(1.0_wp, path%y(0) - interface_y)
        clear_of_interface = abs(path%y(0) - interface_y) > near_tolerance * clearance .and. &
                             all(side * (path%y(1:path%n) - interface_y) >= clearance)
    end function clear_of_interface

    !> Whether fractures a and b are connected: by chains of fractures that share an element
    !> end (within 1e-8 of the shorter element's length, as the tips are found) or that
    !> the links join; in a half-plane the free surface (node surface_target) joins the
    !> fractures with an element end on it and those the step's links take through it.
    pure logical function connected(model, a, b, links)
        type(model_type), intent(in) :: model
        integer, intent(in) :: a, b
        type(tip_link), intent(in) :: links(:)
        integer :: root(surface_target:size(model%fractures)), i, j, k
        real(wp) :: tol

        root = [(i, i = surface_target, size(model%fractures))]
        do k = 1, size(links)
            associate (l => links(k))
                if (l%target == surface_target) then
                    call join(root, l%path%fracture, surface_target)
                else
                    call join(root, l%path%fracture, model%elements%fracture_id(l%target))
                end if
            end associate
        end do
        associate (e => model%elements)
            if (e%domain == domain_half_plane) then
                do i = 1, e%n
                    tol = 2.0e-8_wp * e%half_length(i)
                    if (min(abs(e%y_begin(i)), abs(e%y_end(i))) <= tol) then
                        call join(root, e%fracture_id(i), surface_target)
                    end if
                end do
            end if
            do i = 1, e%n
                do j = i + 1, e%n
                    if (e%fracture_id(i) == e%fracture_id(j)) cycle
                    tol = 2.0e-8_wp * min(e%half_length(i), e%half_length(j))
                    if (min(hypot(e%x_begin(i) - e%x_begin(j), e%y_begin(i) - e%y_begin(j)), &
                            hypot(e%x_begin(i) - e%x_end(j), e%y_begin(i) - e%y_end(j)), &
                            hypot(e%x_end(i) - e%x_begin(j), e%y_end(i) - e%y_begin(j)), &
                            hypot(e%x_end(i) - e%x_end(j), e%y_end(i) - e%y_end(j))) <= tol) then
                        call join(root, e%fracture_id(i), e%fracture_id(j))
                    end if
                end do
            end do
        end associate
        connected = find(root, a) == find(root, b)
    end function connected

    !> The set of fracture f (union-find over fractures and the surface: root(f) == f at a
    !> set's root).
    pure integer function find(root, f)
        integer, intent(in) :: root(surface_target:), f

        find = f
        do while (root(find) /= find)
            find = root(find)
        end do
    end function find

    !> Join the sets of fractures (or the surface) f and g.
    pure subroutine join(root, f, g)
        integer, intent(inout) :: root(surface_target:)
        integer, intent(in) :: f, g

        root(find(root, f)) = find(root, g)
    end subroutine join

    !> The element of the model that a path's new elements come closer than `clearance` to
    !> first (its tip elements excepted at the tip itself: at_tip), 0 when none does: of
    !> those within clearance of the first new element that meets any, the one crossed
    !> nearest to the element's start, else the nearest one (ties: the lowest index).
    pure subroutine hits_model(model, path, clearance, hit)
        type(model_type), intent(in) :: model
        type(tip_path), intent(in) :: path
        real(wp), intent(in) :: clearance
        integer, intent(out) :: hit
        integer :: k, j
        real(wp) :: d, best, t
        logical :: near(model%elements%n)

        near = at_tip(model, path, clearance)
        hit = 0
        associate (e => model%elements)
            do k = 1, path%n
                ! Crossings rank by where they cross (-1 .. 0), others by distance.
                best = huge(1.0_wp)
                do j = 1, e%n
                    if (far_apart(path%x(k - 1), path%y(k - 1), path%x(k), path%y(k), &
                                  e%x_begin(j), e%y_begin(j), e%x_end(j), e%y_end(j), &
                                  clearance)) cycle
                    if (k == 1 .and. near(j)) then
                        d = point_segment_distance(path%x(1), path%y(1), e%x_begin(j), &
                                                   e%y_begin(j), e%x_end(j), e%y_end(j))
                    else
                        d = segment_distance(path%x(k - 1), path%y(k - 1), path%x(k), &
                                             path%y(k), e%x_begin(j), e%y_begin(j), &
                                             e%x_end(j), e%y_end(j))
                    end if
                    if (d >= clearance) cycle
                    if (d <= 0.0_wp .and. .not. (k == 1 .and. near(j))) then
                        t = crossing_fraction(path%x(k - 1), path%y(k - 1), path%x(k), &
                            path%y(k), e%x_begin(j), e%y_begin(j), e%x_end(j), e%y_end(j))
                        d = t - 1.0_wp
                    end if
                    if (d < best) then
                        best = d
                        hit = j
                    end if
                end do
                if (hit > 0) return
            end do
        end associate
    end subroutine hits_model

    !> The elements a path's first new element touches at its tip, whose distance from it is
    !> taken from that element's far end: the tip element, and behind it those of the tip's
    !> fracture that begin (counted along the fracture from the tip) within twice the
    !> clearance (a new element's length) of the tip, as after a kink shorter than that.
    pure function at_tip(model, path, clearance) result(near)
        type(model_type), intent(in) :: model
        type(tip_path), intent(in) :: path
        real(wp), intent(in) :: clearance
        logical :: near(model%elements%n)
        integer :: j, step, last
        real(wp) :: along

        near = .false.
        associate (f => model%fractures(path%fracture))
            j = tip_element(model, path%fracture, path%end)
            step = merge(1, -1, path%end == tip_end_begin)
            last = merge(f%last_element, f%first_element, step == 1)
            along = 0.0_wp
            do
                near(j) = .true.
                along = along + 2.0_wp * model%elements%half_length(j)
                if (j == last .or. along >= (1.0_wp - near_tolerance) * 2.0_wp * clearance) exit
                j = j + step
            end do
        end associate
    end function at_tip

    !> The link of a path that meets element `hit` (hits_model); made false when it may not
    !> link.
    pure subroutine make_link(model, path, clearance, hit, link, made)
        type(model_type), intent(in) :: model
        type(tip_path), intent(in) :: path
        real(wp), intent(in) :: clearance
        integer, intent(in) :: hit
        type(tip_link), intent(out) :: link
        logical, intent(out) :: made
        real(wp) :: px, py, t, length
        integer :: k, f

        made = .false.
        associate (e => model%elements)
            f = e%fracture_id(hit)
            if (f == path%fracture) return
            call link_point(model, path, hit, px, py, t)
            length = 2.0_wp * e%half_length(hit)
            link%target = hit
            if (t <= snap_fraction) then
                px = e%x_begin(hit)
                py = e%y_begin(hit)
                if (hit == model%fractures(f)%first_element) return
            else if (t >= 1.0_wp - snap_fraction) then
                px = e%x_end(hit)
                py = e%y_end(hit)
                if (hit == model%fractures(f)%last_element) return
            else
                link%split = .true.
            end if
            ! Not at (or next to) the other fracture's ends: tips that meet do not link.
            k = model%fractures(f)%first_element
            if (hypot(px - e%x_begin(k), py - e%y_begin(k)) < clearance) return
            k = model%fractures(f)%last_element
            if (hypot(px - e%x_end(k), py - e%y_end(k)) < clearance) return
        end associate
        call straight_link(model, path, px, py, link, made)
        if (made) made = link_clear(model, link, clearance)
    end subroutine make_link

    !> The link of a path (clear of every element) that does not keep clear of the free
    !> surface: to where its first new element that reaches y = 0 crosses it, else to the
    !> point of the surface above its highest point; made false when it may not break through
    !> (the link would not keep clear of the other elements).
    pure subroutine surface_link(model, path, clearance, link, made)
        type(model_type), intent(in) :: model
        type(tip_path), intent(in) :: path
        real(wp), intent(in) :: clearance
        type(tip_link), intent(out) :: link
        logical, intent(out) :: made
        real(wp) :: px, t
        integer :: k

        link%target = surface_target
        px = path%x(maxloc(path%y, 1) - 1)
        do k = 1, path%n
            if (path%y(k) < 0.0_wp) cycle
            t = -path%y(k - 1) / (path%y(k) - path%y(k - 1))
            px = path%x(k - 1) + t * (path%x(k) - path%x(k - 1))
            exit
        end do
        call straight_link(model, path, px, 0.0_wp, link, made)
        if (made) made = link_clear(model, link, clearance)
    end subroutine surface_link

    !> The path, length and angle of a link running straight from a path's tip to the link
    !> point (px, py) in n = max(1, nint(length / h)) equal elements, its last point (px, py)
    !> bit for bit; made false when the link point is the tip.
    pure subroutine straight_link(model, path, px, py, link, made)
        type(model_type), intent(in) :: model
        type(tip_path), intent(in) :: path
        real(wp), intent(in) :: px, py
        type(tip_link), intent(inout) :: link
        logical, intent(out) :: made
        real(wp) :: dx, dy, outward(2)
        integer :: k, n, parent

        dx = px - path%x(0)
        dy = py - path%y(0)
        link%length = hypot(dx, dy)
        made = link%length > 0.0_wp
        if (.not. made) return
        n = max(1, nint(link%length / path_element_length(path)))
        link%path%fracture = path%fracture
        link%path%end = path%end
        link%path%n = n
        allocate (link%path%x(0:n), link%path%y(0:n))
        link%path%x(0) = path%x(0)
        link%path%y(0) = path%y(0)
        do k = 1, n - 1
            link%path%x(k) = path%x(0) + dx * real(k, wp) / real(n, wp)
            link%path%y(k) = path%y(0) + dy * real(k, wp) / real(n, wp)
        end do
        link%path%x(n) = px
        link%path%y(n) = py
        parent = tip_element(model, path%fracture, path%end)
        outward = outward_direction(model%elements, parent, path%end)
        link%theta = atan2(outward(1) * dy - outward(2) * dx, outward(1) * dx + outward(2) * dy)
    end subroutine straight_link

    !> Where a path meets element j: the crossing of its first new element that meets j, or
    !> where it only comes close, the point of j nearest to that element's end nearer to j;
    !> (px, py) and the fraction t of j's length from its begin.
    pure subroutine link_point(model, path, j, px, py, t)
        type(model_type), intent(in) :: model
        type(tip_path), intent(in) :: path
        integer, intent(in) :: j
        real(wp), intent(out) :: px, py, t
        real(wp) :: ax, ay, bx, by, qx, qy, length2
        integer :: k

        associate (e => model%elements)
            ax = e%x_begin(j)
            ay = e%y_begin(j)
            bx = e%x_end(j)
            by = e%y_end(j)
        end associate
        length2 = (bx - ax)**2 + (by - ay)**2
        do k = 1, path%n
            if (segment_distance(path%x(k - 1), path%y(k - 1), path%x(k), path%y(k), ax, ay, &
                                 bx, by) > 0.0_wp) cycle
            ! Crossing: where it crosses, as a fraction of j.
            t = crossing_fraction(ax, ay, bx, by, path%x(k - 1), path%y(k - 1), path%x(k), &
                                  path%y(k))
            px = ax + t * (bx - ax)
            py = ay + t * (by - ay)
            return
        end do
        ! No crossing: the path point nearest to j.
        qx = path%x(path%n)
        qy = path%y(path%n)
        do k = 0, path%n
            if (point_segment_distance(path%x(k), path%y(k), ax, ay, bx, by) < &
                point_segment_distance(qx, qy, ax, ay, bx, by)) then
                qx = path%x(k)
                qy = path%y(k)
            end if
        end do
        t = max(0.0_wp, min(1.0_wp, ((qx - ax) * (bx - ax) + (qy - ay) * (by - ay)) / length2))
        px = ax + t * (bx - ax)
        py = ay + t * (by - ay)
    end subroutine link_point

    !> Whether a link keeps clear: every element of the link keeps `clearance` from every
    !> element of the model, except from the target's fracture (which it must only not touch
    !> before the link point), the last one from those that hold the link point, and the
    !> first one from the tip elements (at_tip: only its far end must keep clear of them); in a
    !> half-plane, every point of a link to another fracture keeps clear of the surface.
    pure logical function link_clear(model, link, clearance)
        type(model_type), intent(in) :: model
        type(tip_link), intent(in) :: link
        real(wp), intent(in) :: clearance
        real(wp) :: px, py, d
        integer :: k, j, target_fracture
        logical :: near(model%elements%n)

        link_clear = .false.
        target_fracture = 0
        associate (e => model%elements, p => link%path)
            if (link%target /= surface_target) then
                target_fracture = e%fracture_id(link%target)
                if (e%domain == domain_half_plane) then
                    if (any(p%y(1:) > -clearance)) return
                end if
            end if
            near = at_tip(model, p, clearance)
            px = p%x(p%n)
            py = p%y(p%n)
            do k = 1, p%n
                do j = 1, e%n
                    if (far_apart(p%x(k - 1), p%y(k - 1), p%x(k), p%y(k), e%x_begin(j), &
                                  e%y_begin(j), e%x_end(j), e%y_end(j), clearance)) cycle
                    if (k == p%n .and. holds_point(j)) cycle
                    if (k == 1 .and. near(j)) then
                        d = point_segment_distance(p%x(1), p%y(1), e%x_begin(j), &
                                                   e%y_begin(j), e%x_end(j), e%y_end(j))
                    else
                        d = segment_distance(p%x(k - 1), p%y(k - 1), p%x(k), p%y(k), &
                                             e%x_begin(j), e%y_begin(j), e%x_end(j), e%y_end(j))
                    end if
                    ! The link may meet its target's fracture at a shallow angle (a hook):
                    ! there it must not touch it before P, nor the last element the target's
                    ! neighbours (a quarter of the target's length from P at least).
                    if (e%fracture_id(j) == target_fracture .and. &
                        (k < p%n .or. next_to_target(j))) then
                        if (d <= 0.0_wp) return
                    else if (d < clearance) then
                        return
                    end if
                end do
            end do
        end associate
        link_clear = .true.

    contains

        !> Element j holds the link point: it is the target, or (snapped) has it as a vertex.
        pure logical function holds_point(j)
            integer, intent(in) :: j

            associate (e => model%elements)
                holds_point = j == link%target .or. (e%x_begin(j) == px .and. &
                    e%y_begin(j) == py) .or. (e%x_end(j) == px .and. e%y_end(j) == py)
            end associate
        end function holds_point

        !> Element j shares an end with the target (bit for bit: the same fracture's
        !> neighbours); never for a link through the surface.
        pure logical function next_to_target(j)
            integer, intent(in) :: j
            integer :: t

            next_to_target = .false.
            t = link%target
            if (t == surface_target) return
            associate (e => model%elements)
                next_to_target = (e%x_begin(j) == e%x_end(t) .and. e%y_begin(j) == e%y_end(t)) &
                    .or. (e%x_end(j) == e%x_begin(t) .and. e%y_end(j) == e%y_begin(t))
            end associate
        end function next_to_target

    end function link_clear

    !> The paths and splits the links add to the model.
    pure subroutine link_parts(links, paths, splits)
        !> The links of a step
        type(tip_link), intent(in) :: links(:)
        !> Their paths, shape (size(links))
        type(tip_path), allocatable, intent(out) :: paths(:)
        !> The splits of those that split their target
        type(element_split), allocatable, intent(out) :: splits(:)
        integer :: i

        allocate (paths(size(links)), splits(0))
        do i = 1, size(links)
            paths(i) = links(i)%path
            if (links(i)%split) splits = [splits, element_split(element=links(i)%target, &
                x=links(i)%path%x(links(i)%path%n), y=links(i)%path%y(links(i)%path%n))]
        end do
    end subroutine link_parts

    !> Smallest distance between the new elements of two paths.
    pure real(wp) function path_distance(a, b)
        type(tip_path), intent(in) :: a, b
        integer :: i, j

        path_distance = huge(1.0_wp)
        do i = 1, a%n
            do j = 1, b%n
                path_distance = min(path_distance, segment_distance(a%x(i - 1), a%y(i - 1), &
                    a%x(i), a%y(i), b%x(j - 1), b%y(j - 1), b%x(j), b%y(j)))
            end do
        end do
    end function path_distance

    !> Whether a tip with this reason ends on a link: to another fracture (growth_linked) or
    !> through the free surface (growth_surface with a link).
    elemental logical function ends_on_link(reason)
        !> A growth reason
        integer, intent(in) :: reason

        ends_on_link = reason == growth_linked .or. reason == growth_surface
    end function ends_on_link

    !> Whether every new vertex of a path lies inside the model's finite body, farther than
    !> the clearance from its boundary.
    pure logical function clear_of_body(model, path, clearance)
        type(model_type), intent(in) :: model
        type(tip_path), intent(in) :: path
        real(wp), intent(in) :: clearance
        integer :: k

        clear_of_body = .true.
        do k = 1, ubound(path%x, 1)
            if (.not. inside_body(model%body, path%x(k), path%y(k), clearance)) then
                clear_of_body = .false.
                return
            end if
        end do
    end function clear_of_body

end module ddc_growth_clearance
