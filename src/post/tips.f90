!> Crack tips and their stress intensity factors (SPEC section 5).
module ddc_post_tips
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, symmetry_x, symmetry_y, symmetry_both, &
        domain_half_plane
    use ddc_model_results, only: tip_set
    implicit none
    private

    public :: find_tips

    !> End points closer than this fraction of the shorter element's length are shared.
    real(wp), parameter :: shared_end_tolerance = 1.0e-8_wp
    !> A tip element longer or shorter than its neighbour by more than this fraction makes
    !> the tip graded
    real(wp), parameter :: graded_tolerance = 1.0e-2_wp

contains

    !> True when end `side` (1 begin, 2 end) of element i coincides with an end of another
    !> element, lies on a symmetry line (where it meets its own image) or, in a half-plane,
    !> on the free surface y = 0 (a crack mouth, SPEC-EARTH 1).
    pure logical function end_is_shared(elements, i, side)
        type(element_set), intent(in) :: elements
        integer, intent(in) :: i, side
        real(wp) :: x, y, tol

        if (side == 1) then
            x = elements%x_begin(i)
            y = elements%y_begin(i)
        else
            x = elements%x_end(i)
            y = elements%y_end(i)
        end if
        end_is_shared = .true.
        tol = shared_end_tolerance * 2.0_wp * elements%half_length(i)
        associate (sym => elements%symmetry)
            if ((sym%kind == symmetry_x .or. sym%kind == symmetry_both) .and. &
                abs(x - sym%xsym) <= tol) return
            if ((sym%kind == symmetry_y .or. sym%kind == symmetry_both) .and. &
                abs(y - sym%ysym) <= tol) return
        end associate
        if (elements%domain == domain_half_plane .and. abs(y) <= tol) return
        end_is_shared = element_at_end(elements, i, side) > 0
    end function end_is_shared

    !> Another element with an end at end `side` (1 begin, 2 end) of element i; 0 if none.
    pure integer function element_at_end(elements, i, side)
        type(element_set), intent(in) :: elements
        integer, intent(in) :: i, side
        real(wp) :: x, y, tol
        integer :: j

        x = merge(elements%x_begin(i), elements%x_end(i), side == 1)
        y = merge(elements%y_begin(i), elements%y_end(i), side == 1)
        do j = 1, elements%n
            if (j == i) cycle
            tol = shared_end_tolerance * 2.0_wp * &
                  min(elements%half_length(i), elements%half_length(j))
            if (hypot(elements%x_begin(j) - x, elements%y_begin(j) - y) <= tol .or. &
                hypot(elements%x_end(j) - x, elements%y_end(j) - y) <= tol) then
                element_at_end = j
                return
            end if
        end do
        element_at_end = 0
    end function element_at_end

    !> Tips (element ends shared with no other element) with K_I and K_II from the tip
    !> element's DDs: K = -G D / (2 (1 - nu) sqrt(h)), h the tip element's half-length.
    subroutine find_tips(elements, shear_modulus, nu, ds, dn, tips)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> The tips found, in element order (begin before end)
        type(tip_set), intent(out) :: tips
        logical :: is_tip(2, elements%n)
        integer :: i, side, k, neighbour
        real(wp) :: factor

        !$omp parallel do default(none) private(i, side) shared(elements, is_tip)
        do i = 1, elements%n
            do side = 1, 2
                is_tip(side, i) = .not. end_is_shared(elements, i, side)
            end do
        end do
        !$omp end parallel do

        tips%n = count(is_tip)
        allocate (tips%x(tips%n), tips%y(tips%n), tips%fracture_id(tips%n), &
                  tips%element(tips%n), tips%k1(tips%n), tips%k2(tips%n), tips%graded(tips%n), &
                  tips%side(tips%n))
        k = 0
        do i = 1, elements%n
            do side = 1, 2
                if (.not. is_tip(side, i)) cycle
                k = k + 1
                if (side == 1) then
                    tips%x(k) = elements%x_begin(i)
                    tips%y(k) = elements%y_begin(i)
                else
                    tips%x(k) = elements%x_end(i)
                    tips%y(k) = elements%y_end(i)
                end if
                tips%fracture_id(k) = elements%fracture_id(i)
                tips%element(k) = i
                tips%side(k) = side
                factor = -shear_modulus / (2.0_wp * (1.0_wp - nu) * sqrt(elements%half_length(i)))
                ! + 0 turns the -0 of an unloaded mode into 0 for printing.
                tips%k1(k) = factor * dn(i) + 0.0_wp
                tips%k2(k) = factor * ds(i) + 0.0_wp
                ! The neighbour shares the tip element's other end.
                neighbour = element_at_end(elements, i, 3 - side)
                tips%graded(k) = 0
                if (neighbour > 0) then
                    if (abs(elements%half_length(neighbour) - elements%half_length(i)) > &
                        graded_tolerance * elements%half_length(i)) tips%graded(k) = 1
                end if
            end do
        end do
    end subroutine find_tips

end module ddc_post_tips
