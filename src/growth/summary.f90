!> What became of each tip of a growth run: its path length, the steps it grew in (a link
!> and a break-through of the free surface count), its last record (why it stopped) from
!> the growth record, and the fracture a linked tip ends on from the final geometry.
module ddc_growth_summary
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, element_end
    use ddc_model_results, only: growth_record, growth_grew, growth_corrector_failed
    use ddc_growth_clearance, only: ends_on_link
    use ddc_growth_extension, only: tip_element, tip_end_begin
    implicit none
    private

    public :: tip_summary, summarize_tips, linked_fracture

    !> One tip of a growth run.
    type :: tip_summary
        !> Fracture (1-based) and end (0 begin, 1 end)
        integer :: fracture_id = 0, end = 0
        !> Length grown over the run [length unit]
        real(wp) :: path_length = 0.0_wp
        !> Steps in which it grew
        integer :: steps_grown = 0
        !> Reason of its last record (growth_grew ... growth_waiting)
        integer :: last_reason = 0
        !> K_eq of its last record [stress unit * length unit**0.5]
        real(wp) :: last_k_eq = 0.0_wp
    end type tip_summary

contains

    !> One summary per tip with a record, in the order of their first records (the order
    !> of fractures, begin before end: every tip has a record in the first step).
    pure subroutine summarize_tips(record, tips)
        !> The growth record of a run
        type(growth_record), intent(in) :: record
        !> One summary per tip
        type(tip_summary), allocatable, intent(out) :: tips(:)
        integer :: r, t, k, key(size(record%step))
        integer, allocatable :: keys(:)

        key = 2 * record%fracture_id + record%end
        allocate (keys(0))
        do r = 1, size(key)
            if (.not. any(keys == key(r))) keys = [keys, key(r)]
        end do
        allocate (tips(size(keys)))
        do t = 1, size(keys)
            tips(t)%fracture_id = keys(t) / 2
            tips(t)%end = mod(keys(t), 2)
            do r = 1, size(key)
                if (key(r) /= keys(t)) cycle
                k = record%reason(r)
                tips(t)%last_reason = k
                tips(t)%last_k_eq = record%k_eq(r)
                if (k == growth_grew .or. k == growth_corrector_failed .or. &
                    ends_on_link(k)) then
                    tips(t)%steps_grown = tips(t)%steps_grown + 1
                    tips(t)%path_length = tips(t)%path_length + record%length(r)
                end if
            end do
        end do
    end subroutine summarize_tips

    !> The fracture that end `end` (0 begin, 1 end) of a fracture ends on in the final
    !> geometry: the first other fracture with an element end there (bit for bit, as a link
    !> makes it); 0 when there is none.
    pure integer function linked_fracture(model, fracture, end)
        !> The final geometry
        type(model_type), intent(in) :: model
        !> Fracture (1-based) and end
        integer, intent(in) :: fracture, end
        real(wp) :: x, y
        integer :: k

        call element_end(model%elements, tip_element(model, fracture, end), &
                         merge(1, 2, end == tip_end_begin), x, y)
        associate (e => model%elements)
            linked_fracture = 0
            do k = 1, e%n
                if (e%fracture_id(k) == fracture) cycle
                if ((e%x_begin(k) == x .and. e%y_begin(k) == y) .or. &
                    (e%x_end(k) == x .and. e%y_end(k) == y)) then
                    linked_fracture = e%fracture_id(k)
                    return
                end if
            end do
        end associate
    end function linked_fracture

end module ddc_growth_summary
