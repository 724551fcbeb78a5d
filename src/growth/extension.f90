!> New elements at growing tips (docs/theory/growth.md#new-elements): the straight path of one
!> increment at a kink angle, and the model with those paths added so that every fracture stays one
!> ordered polyline (appended after the last element at an end tip, put before the first
!> element at a begin tip).
module ddc_growth_extension
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, element_set, growth_options, condition_contact, &
        select_elements, strength_law_count
    use ddc_model_laws, only: strength_law, strength_laws, set_law
    use ddc_mesh_geometry, only: compute_geometry
    implicit none
    private

    public :: tip_path, tip_end_begin, tip_end_end, tip_element, element_split
    public :: make_path, extend_model, path_element_length, outward_direction, inherit_values
    public :: take_new_element_laws

    !> Ends of a fracture (the coding of /growth/end): its begin tip, its end tip
    integer, parameter :: tip_end_begin = 0, tip_end_end = 1

    !> The straight path of one tip's increment: n equal elements from the tip.
    type :: tip_path
        !> Fracture (1-based) and end (tip_end_begin or tip_end_end) of the tip
        integer :: fracture = 0, end = tip_end_end
        !> Number of new elements
        integer :: n = 0
        !> Path points from the tip (index 0) to the new tip (index n) [length unit],
        !> shape (0:n)
        real(wp), allocatable :: x(:), y(:)
    end type tip_path

    !> An element split in two at a point where a linking tip ends
    !> (docs/theory/growth.md#linking-and-stops).
    type :: element_split
        !> The element (index in the model before growing)
        integer :: element = 0
        !> The point, shared bit for bit by both halves and the link [length unit]
        real(wp) :: x = 0.0_wp, y = 0.0_wp
    end type element_split

contains

    !> The element at end `end` (tip_end_begin, tip_end_end) of a fracture.
    pure integer function tip_element(model, fracture, end)
        !> The model
        type(model_type), intent(in) :: model
        !> Fracture (1-based) and its end
        integer, intent(in) :: fracture, end

        if (end == tip_end_begin) then
            tip_element = model%fractures(fracture)%first_element
        else
            tip_element = model%fractures(fracture)%last_element
        end if
    end function tip_element

    !> Unit vector from the tip element's other end towards the tip.
    pure function outward_direction(elements, element, end) result(direction)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> The tip element, and which of its ends is the tip (tip_end_begin, tip_end_end)
        integer, intent(in) :: element, end
        !> (cos, sin) of the outward direction
        real(wp) :: direction(2)

        direction = [elements%cos_beta(element), elements%sin_beta(element)]
        if (end == tip_end_begin) direction = -direction
    end function outward_direction

    !> The path of an increment of `length` in n equal elements from a tip, at angle theta
    !> counter-clockwise from the tip's outward direction.
    pure function make_path(model, fracture, end, theta, length, n) result(path)
        !> The model whose fracture grows
        type(model_type), intent(in) :: model
        !> Fracture (1-based) and end (tip_end_begin, tip_end_end)
        integer, intent(in) :: fracture, end
        !> Kink angle [rad]
        real(wp), intent(in) :: theta
        !> Length of the increment [length unit]
        real(wp), intent(in) :: length
        !> Number of new elements (>= 1)
        integer, intent(in) :: n
        type(tip_path) :: path
        real(wp) :: outward(2), along(2), x0, y0, t
        integer :: e, k

        e = tip_element(model, fracture, end)
        outward = outward_direction(model%elements, e, end)
        along = [outward(1) * cos(theta) - outward(2) * sin(theta), &
                 outward(2) * cos(theta) + outward(1) * sin(theta)]
        if (end == tip_end_begin) then
            x0 = model%elements%x_begin(e)
            y0 = model%elements%y_begin(e)
        else
            x0 = model%elements%x_end(e)
            y0 = model%elements%y_end(e)
        end if
        path%fracture = fracture
        path%end = end
        path%n = n
        allocate (path%x(0:n), path%y(0:n))
        ! The first point is the tip itself, bit for bit, so that the new element shares it.
        path%x(0) = x0
        path%y(0) = y0
        do k = 1, n
            t = length * real(k, wp) / real(n, wp)
            path%x(k) = x0 + t * along(1)
            path%y(k) = y0 + t * along(2)
        end do
    end function make_path

    !> Length of each element of a path [length unit].
    pure real(wp) function path_element_length(path)
        !> The path (n >= 1)
        type(tip_path), intent(in) :: path

        path_element_length = hypot(path%x(path%n) - path%x(0), path%y(path%n) - path%y(0)) / &
                              real(path%n, wp)
    end function path_element_length

    !> The model with the paths' elements added to their fractures, and the step that
    !> created each element. New elements take the tip element's condition and values;
    !> new contact elements take new_mu, new_sf when the growth options override them.
    !> Every element of model keeps its geometry and values bit for bit; only its index
    !> changes (moved_to), so the influences among them do not change; a split element is
    !> replaced by its two halves (moved_to 0), which keep its values and created step.
    subroutine extend_model(model, created, paths, step, options, grown, grown_created, &
                            moved_to, splits, origin)
        !> The model before growing, geometry computed
        type(model_type), intent(in) :: model
        !> Growth step that created each element of model, shape (n)
        integer, intent(in) :: created(:)
        !> One path per growing tip (at most one per fracture end)
        type(tip_path), intent(in) :: paths(:)
        !> The step the new elements belong to
        integer, intent(in) :: step
        !> new_mu, new_sf
        type(growth_options), intent(in) :: options
        !> The model with the new elements (observations as in model)
        type(model_type), intent(out) :: grown
        !> Growth step that created each element of grown, shape (grown n)
        integer, allocatable, intent(out) :: grown_created(:)
        !> The index in grown of each element of model, shape (model n)
        integer, allocatable, intent(out), optional :: moved_to(:)
        !> Elements of model split in two (each at most once)
        type(element_split), intent(in), optional :: splits(:)
        !> The element of model each element of grown comes from (moved, or split in two),
        !> 0 for a new one, shape (grown n)
        integer, allocatable, intent(out), optional :: origin(:)
        real(wp), allocatable :: x_begin(:), y_begin(:), x_end(:), y_end(:)
        logical, allocatable :: is_new(:), is_half(:)
        integer, allocatable :: pick(:)
        integer :: added, f, p, pb, pe, k, next, n, s

        added = 0
        do p = 1, size(paths)
            added = added + paths(p)%n
        end do
        if (present(splits)) added = added + size(splits)
        n = model%elements%n + added
        allocate (pick(n), grown_created(n))
        allocate (is_new(n), is_half(n), source=.false.)
        allocate (x_begin(n), y_begin(n), x_end(n), y_end(n), source=0.0_wp)
        grown = model
        if (present(moved_to)) allocate (moved_to(model%elements%n))
        next = 0
        do f = 1, size(model%fractures)
            pb = find_path(paths, f, tip_end_begin)
            pe = find_path(paths, f, tip_end_end)
            grown%fractures(f)%first_element = next + 1
            if (pb > 0) then
                ! Elements run from the new tip towards the old one, into the fracture.
                do k = paths(pb)%n, 1, -1
                    call new_element(paths(pb)%x(k), paths(pb)%y(k), paths(pb)%x(k - 1), &
                                     paths(pb)%y(k - 1), model%fractures(f)%first_element)
                end do
            end if
            do k = model%fractures(f)%first_element, model%fractures(f)%last_element
                s = 0
                if (present(splits)) s = find_split(splits, k)
                if (s > 0) then
                    associate (e => model%elements)
                        call half(e%x_begin(k), e%y_begin(k), splits(s)%x, splits(s)%y, k)
                        call half(splits(s)%x, splits(s)%y, e%x_end(k), e%y_end(k), k)
                    end associate
                    if (present(moved_to)) moved_to(k) = 0
                    cycle
                end if
                next = next + 1
                pick(next) = k
                grown_created(next) = created(k)
                if (present(moved_to)) moved_to(k) = next
            end do
            if (pe > 0) then
                do k = 1, paths(pe)%n
                    call new_element(paths(pe)%x(k - 1), paths(pe)%y(k - 1), paths(pe)%x(k), &
                                     paths(pe)%y(k), model%fractures(f)%last_element)
                end do
            end if
            grown%fractures(f)%last_element = next
        end do
        call inherit_values(model%elements, pick, is_new, options, grown%elements)
        associate (a => grown%elements)
            where (is_new .or. is_half)
                a%x_begin = x_begin
                a%y_begin = y_begin
                a%x_end = x_end
                a%y_end = y_end
            end where
        end associate
        call compute_geometry(grown%elements)
        if (present(origin)) origin = merge(0, pick, is_new)

    contains

        !> The next element of grown: from (xb, yb) to (xe, ye), with the values of the
        !> tip element `parent` of model.
        subroutine new_element(xb, yb, xe, ye, parent)
            real(wp), intent(in) :: xb, yb, xe, ye
            integer, intent(in) :: parent

            next = next + 1
            pick(next) = parent
            grown_created(next) = step
            is_new(next) = .true.
            x_begin(next) = xb
            y_begin(next) = yb
            x_end(next) = xe
            y_end(next) = ye
        end subroutine new_element

        !> The next element of grown: half of the split element k of model, from (xb, yb)
        !> to (xe, ye), with all its values.
        subroutine half(xb, yb, xe, ye, k)
            real(wp), intent(in) :: xb, yb, xe, ye
            integer, intent(in) :: k

            next = next + 1
            pick(next) = k
            grown_created(next) = created(k)
            is_half(next) = .true.
            x_begin(next) = xb
            y_begin(next) = yb
            x_end(next) = xe
            y_end(next) = ye
        end subroutine half

    end subroutine extend_model

    !> The values of the elements of a grown geometry (docs/theory/growth.md#new-elements), the one
    !> rule for growth and for a resumed run: each takes those of the element it comes from (a
    !> new one, grown at a tip, the tip element's given values: the element arrays hold no
    !> weakening) and, a new contact element, new_mu, new_sf and the strength laws new_law
    !> where the growth options override them. End points and geometry are the caller's to
    !> set.
    subroutine inherit_values(elements, pick, is_new, options, grown)
        !> The elements the grown ones come from
        type(element_set), intent(in) :: elements
        !> The element of `elements` each grown element comes from, shape (grown n)
        integer, intent(in) :: pick(:)
        !> Whether each grown element is new, shape (grown n)
        logical, intent(in) :: is_new(:)
        !> The growth options (override_mu, new_mu, override_sf, new_sf, override_law, new_law)
        type(growth_options), intent(in) :: options
        !> The grown elements
        type(element_set), intent(out) :: grown

        call select_elements(elements, pick, grown)
        call take_new_element_laws(grown, is_new .and. grown%condition == condition_contact, &
                                   options)
    end subroutine inherit_values

    !> The elements marked `takes` take new_mu, new_sf and the strength laws new_law where
    !> the growth options give them.
    subroutine take_new_element_laws(elements, takes, options)
        !> The elements
        type(element_set), intent(inout) :: elements
        !> Which elements take the options' values, shape (elements%n)
        logical, intent(in) :: takes(:)
        !> The growth options (override_mu, new_mu, override_sf, new_sf, override_law, new_law)
        type(growth_options), intent(in) :: options
        type(strength_law) :: laws(strength_law_count)
        integer, allocatable :: rows(:)
        integer :: k, i

        laws = strength_laws()
        rows = pack([(i, i = 1, elements%n)], takes)
        do k = 1, size(laws)
            if (options%override_law(k)) call set_law(elements, laws(k)%name, rows, &
                                                      spread(options%new_law(k), 1, size(rows)))
        end do
        if (options%override_mu) where (takes) elements%mu = options%new_mu
        if (options%override_sf) where (takes) elements%sf = options%new_sf
    end subroutine take_new_element_laws

    !> Index of the path at end `end` of fracture f; 0 when there is none.
    pure integer function find_path(paths, f, end)
        type(tip_path), intent(in) :: paths(:)
        integer, intent(in) :: f, end
        integer :: p

        find_path = 0
        do p = 1, size(paths)
            if (paths(p)%fracture == f .and. paths(p)%end == end) find_path = p
        end do
    end function find_path

    !> Index of the split of element k; 0 when it is not split.
    pure integer function find_split(splits, k)
        type(element_split), intent(in) :: splits(:)
        integer, intent(in) :: k
        integer :: s

        find_split = 0
        do s = 1, size(splits)
            if (splits(s)%element == k) find_split = s
        end do
    end function find_split

end module ddc_growth_extension
