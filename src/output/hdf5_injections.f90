!> /injection (docs/injection.md#output): the model's fluid sources, one row each
!> (name, fracture, point, overpressure or rate, start and stop), for the tools that plot what
!> they did; with coupled flow (&fluid) its attributes viscosity, compressibility and
!> leak_off_coefficient, and with fluid-driven growth toughness.
module ddc_output_hdf5_injections
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_text, only: allocated_text
    use ddc_model_types, only: model_type, source_overpressure
    use ddc_output_hdf5_handles, only: h5_object, create_group, close_group
    use ddc_output_hdf5_write, only: write_real_1d, write_int_1d, write_string_1d, &
        write_attribute
    implicit none
    private

    public :: write_injections

contains

    !> /injection, when the model has fluid sources.
    subroutine write_injections(root, model, error)
        !> The file
        type(h5_object), intent(in) :: root
        !> The model that was solved
        type(model_type), intent(in) :: model
        !> Set when a write fails (nothing is written when it is set already)
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: group
        character(len=:), allocatable :: length, time
        integer, allocatable :: fracture_id(:)
        real(wp), allocatable :: x(:), y(:)
        integer :: k, n, width

        if (.not. allocated(model%injections)) return
        n = size(model%injections)
        if (n == 0) return
        length = allocated_text(model%length_unit)
        time = allocated_text(model%time_unit)
        width = maxval([(len(model%injections(k)%name), k = 1, n)])
        call create_group(root, 'injection', group, error)
        if (allocated(error)) return
        block
            character(len=width) :: names(n)

            do k = 1, n
                names(k) = model%injections(k)%name
            end do
            call write_string_1d(group, 'name', names, error)
        end block
        associate (s => model%injections)
            ! Contiguous copies: a component of an array of sources is strided.
            fracture_id = s%fracture_id
            x = s%x
            y = s%y
            call write_int_1d(group, 'fracture_id', fracture_id, error)
            call write_real_1d(group, 'x', x, length, error)
            call write_real_1d(group, 'y', y, length, error)
            ! Each source is one of the two: NaN in the other's column.
            call write_real_1d(group, 'overpressure', merge(s%value, ieee_nan(), &
                               s%kind == source_overpressure), &
                               allocated_text(model%stress_unit), error)
            call write_real_1d(group, 'rate', merge(ieee_nan(), s%value, &
                               s%kind == source_overpressure), length//'^2/'//time, error)
            call write_real_1d(group, 'start', merge(s%start, ieee_nan(), &
                               s%start /= -huge(1.0_wp)), time, error)
            call write_real_1d(group, 'stop', merge(s%stop, ieee_nan(), &
                               s%stop /= huge(1.0_wp)), time, error)
        end associate
        if (model%fluid%active) then
            call write_attribute(group, 'viscosity', model%fluid%viscosity, error)
            call write_attribute(group, 'compressibility', model%fluid%compressibility, error)
            call write_attribute(group, 'leak_off_coefficient', &
                                 model%fluid%leak_off_coefficient, error)
            ! A hydraulic fracture: the toughness its tips grow at (its closed forms).
            if (model%growth%active) call write_attribute(group, 'toughness', &
                                                          model%growth%toughness, error)
        end if
        call close_group(group, error)

    contains

        pure real(wp) function ieee_nan()
            ieee_nan = ieee_value(1.0_wp, ieee_quiet_nan)
        end function ieee_nan
    end subroutine write_injections

end module ddc_output_hdf5_injections
