!> What a loading history with fluid sources records of each fracture's slipping patch
!> (docs/injection.md#output): its length, where it begins and ends along the fracture and
!> the fracture's seismic moment, and a line where the patch jumped (an instability).
module ddc_history_fronts
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type
    use ddc_model_results, only: history_record, state_slip, state_open
    use ddc_progress, only: report_progress
    use ddc_text, only: itoa, short_real
    implicit none
    private

    public :: record_fronts, report_jumps

contains

    !> Step k's slipping patch of each fracture (elements that slip or open): its length,
    !> where it begins and ends along the fracture, and the fracture's seismic moment.
    pure subroutine record_fronts(model, shear_modulus, k, h)
        !> The model (its fractures and elements: the rows of the history's element columns)
        type(model_type), intent(in) :: model
        !> Shear modulus [stress unit]
        real(wp), intent(in) :: shear_modulus
        !> The step
        integer, intent(in) :: k
        !> The history: the step's DDs and states read, its fracture columns set
        type(history_record), intent(inout) :: h
        real(wp) :: s
        integer :: f, i

        associate (e => model%elements)
            do f = 1, size(model%fractures)
                h%slipping_length(f, k) = 0.0_wp
                h%front_begin(f, k) = ieee_value(1.0_wp, ieee_quiet_nan)
                h%front_end(f, k) = ieee_value(1.0_wp, ieee_quiet_nan)
                h%moment(f, k) = 0.0_wp
                s = 0.0_wp
                do i = model%fractures(f)%first_element, model%fractures(f)%last_element
                    h%moment(f, k) = h%moment(f, k) + shear_modulus * abs(h%ds(i, k)) * &
                        2.0_wp * e%half_length(i)
                    if (h%state(i, k) == state_slip .or. h%state(i, k) == state_open) then
                        h%slipping_length(f, k) = h%slipping_length(f, k) + &
                            2.0_wp * e%half_length(i)
                        if (ieee_is_nan(h%front_begin(f, k))) h%front_begin(f, k) = s
                        h%front_end(f, k) = s + 2.0_wp * e%half_length(i)
                    end if
                    s = s + 2.0_wp * e%half_length(i)
                end do
            end do
        end associate
    end subroutine record_fronts

    !> A progress line for each fracture whose slipping patch jumped in step k: a patch that
    !> slipped before grew by more than jump_elements of its elements, at more than
    !> jump_factor times the rate (per
    !> change of sqrt(t), the rate of a self-similar front) of the step before. That is an
    !> instability: no quasi-static state lies near the step before, and the equilibrium found
    !> is the arrested one (docs/theory/injection.md#instability).
    subroutine report_jumps(model, times, k, h)
        !> The model
        type(model_type), intent(in) :: model
        !> The time of every step [time unit]
        real(wp), intent(in) :: times(:)
        !> The step
        integer, intent(in) :: k
        !> The history, its fracture columns set up to step k
        type(history_record), intent(in) :: h
        integer, parameter :: jump_elements = 5
        real(wp), parameter :: jump_factor = 4.0_wp
        real(wp) :: grown, rate, rate_before, element
        integer :: f

        if (k < 3) return
        do f = 1, size(model%fractures)
            associate (fr => model%fractures(f), length => h%slipping_length(f, :))
                grown = length(k) - length(k - 1)
                rate = grown / (sqrt(times(k) - times(1)) - sqrt(times(k - 1) - times(1)))
                rate_before = (length(k - 1) - length(k - 2)) / &
                    (sqrt(times(k - 1) - times(1)) - sqrt(times(k - 2) - times(1)))
                element = 2.0_wp * sum(model%elements%half_length(fr%first_element: &
                    fr%last_element)) / real(fr%last_element - fr%first_element + 1, wp)
                ! A patch that starts (none the step before) has nothing to jump from.
                if (length(k - 1) > 0.0_wp .and. grown > jump_elements * element .and. &
                    rate > jump_factor * max(rate_before, 0.0_wp)) then
                    call report_progress(fr%name//': the slipping patch jumped from '// &
                        short_real(length(k - 1))//' to '//short_real(length(k))//' '// &
                        model%length_unit//' in step '//itoa(k)//' (an instability: the '// &
                        'equilibrium found is the arrested one)')
                end if
            end associate
        end do
    end subroutine report_jumps

end module ddc_history_fronts
