!> The tips that may grow: the begin and end of every fracture allowed to grow, when the
!> solved model reports them as crack tips (an end shared with another element, a crack
!> mouth on the free surface, or an end inside a fracture given as a CSV with gaps does
!> not grow), and where such a tip is in a tip set.
module ddc_growth_tips
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_internal_error
    use ddc_text, only: itoa
    use ddc_model_types, only: model_type, growth_options
    use ddc_model_results, only: tip_set
    use ddc_growth_extension, only: tip_element, tip_end_begin, tip_end_end
    implicit none
    private

    !> Relative tolerance of a kink counted as shorter than its increment
    real(wp), parameter :: short_tolerance = 1.0e-6_wp

    public :: growing_tip, find_growing_tips, fracture_tip, locate_tip, increment_for, &
        resumed_element_length

    !> A fracture end that may grow.
    type :: growing_tip
        !> Fracture (1-based) and end (tip_end_begin, tip_end_end)
        integer :: fracture = 0, end = tip_end_end
        !> Stopped for good (at another element or the free surface)
        logical :: stopped = .false.
        !> Length of the elements it grows by after a kink shorter than the increment (whose
        !> element may be shorter) [length unit]; 0: its tip element's length
        real(wp) :: element_length = 0.0_wp
        !> Length of the kink it last grew by [length unit]; 0: none yet. Its next length
        !> search starts from twice that (docs/theory/growth.md#shorter-kinks)
        real(wp) :: kink_length = 0.0_wp
    end type growing_tip

contains

    !> The fracture ends that may grow, in the order of fractures, begin before end.
    function find_growing_tips(model, tips, grows) result(found)
        !> The model, fractures in element order
        type(model_type), intent(in) :: model
        !> Its tips (find_tips)
        type(tip_set), intent(in) :: tips
        !> Whether each fracture may grow, shape (fractures)
        logical, intent(in) :: grows(:)
        type(growing_tip), allocatable :: found(:)
        integer :: f, end

        allocate (found(0))
        do f = 1, size(model%fractures)
            if (.not. grows(f)) cycle
            do end = tip_end_begin, tip_end_end
                if (locate_tip(tips, tip_element(model, f, end), end) > 0) then
                    found = [found, growing_tip(fracture=f, end=end)]
                end if
            end do
        end do
    end function find_growing_tips

    !> Index in the tip set of end `end` (tip_end_begin, tip_end_end) of an element; 0 when
    !> that end is not a tip.
    pure integer function locate_tip(tips, element, end)
        !> The tips of a solved model
        type(tip_set), intent(in) :: tips
        !> The element, and which of its ends
        integer, intent(in) :: element, end
        integer :: k

        locate_tip = 0
        do k = 1, tips%n
            ! tip_set%side: 1 begin, 2 end
            if (tips%element(k) == element .and. tips%side(k) == end + 1) then
                locate_tip = k
                return
            end if
        end do
    end function locate_tip

    !> Index in the tip set of end `end` of a fracture of a solved model, which must be a
    !> tip (growth never closes one: an internal error otherwise).
    subroutine fracture_tip(model, tips, fracture, end, index, error)
        !> The solved model
        type(model_type), intent(in) :: model
        !> Its tips
        type(tip_set), intent(in) :: tips
        !> Fracture (1-based) and end (tip_end_begin, tip_end_end)
        integer, intent(in) :: fracture, end
        !> Index of the tip in tips
        integer, intent(out) :: index
        !> Set (internal error) when that end is not a tip
        type(error_type), allocatable, intent(out) :: error

        index = locate_tip(tips, tip_element(model, fracture, end), end)
        if (index == 0) call set_internal_error(error, 'fracture growth', 'end '//itoa(end)// &
                                                ' of fracture '//itoa(fracture)//' is not a tip')
    end subroutine fracture_tip

    !> Length and number of elements of an increment from a tip element of length tip_length:
    !> `increment` (default 2 tip_length) in n = nint(increment / element_length) >= 1 equal
    !> elements (element_length default: tip_length).
    pure subroutine increment_for(options, tip_length, length, pieces, element_length)
        !> The growth options (increment, element_length)
        type(growth_options), intent(in) :: options
        !> Length of the tip element (or of the elements before a short kink) [length unit]
        real(wp), intent(in) :: tip_length
        !> Length of the increment [length unit]
        real(wp), intent(out) :: length
        !> Number of its elements
        integer, intent(out) :: pieces
        !> Length of the elements the tip grows by [length unit]
        real(wp), intent(out) :: element_length

        length = options%increment
        if (length <= 0.0_wp) length = 2.0_wp * tip_length
        element_length = options%element_length
        if (element_length <= 0.0_wp) element_length = tip_length
        pieces = max(1, nint(length / element_length))
    end subroutine increment_for

    !> growing_tip%element_length of a tip after the kinks it grew by (lengths, in order) from
    !> an input tip element of length first_length: the element length of its increments
    !> after a kink shorter than the increment, 0 after a whole increment.
    pure real(wp) function resumed_element_length(options, first_length, lengths) &
        result(kept)
        !> The growth options (increment, element_length)
        type(growth_options), intent(in) :: options
        !> Length of the input tip element [length unit]
        real(wp), intent(in) :: first_length
        !> Lengths of the tip's kinks, in order [length unit]
        real(wp), intent(in) :: lengths(:)
        real(wp) :: tip_length, full, element_length
        integer :: j, pieces

        kept = 0.0_wp
        tip_length = first_length
        do j = 1, size(lengths)
            if (kept > 0.0_wp) tip_length = kept
            call increment_for(options, tip_length, full, pieces, element_length)
            if (lengths(j) < (1.0_wp - short_tolerance) * full) then
                kept = element_length
            else
                kept = 0.0_wp
                tip_length = full / real(pieces, wp)
            end if
        end do
    end function resumed_element_length

end module ddc_growth_tips
