!> The range of real input values ddc2d accepts.
module ddc_model_limits
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use ddc_kinds, only: wp
    implicit none
    private

    public :: max_input_magnitude, within_limits, limits_text

    !> Largest and smallest accepted magnitude of a non-zero input real. The kernels raise
    !> coordinate differences to the sixth power and the solvers divide by moduli: outside
    !> this range they would overflow or underflow double precision.
    real(wp), parameter :: max_input_magnitude = 1.0e50_wp, min_input_magnitude = 1.0e-50_wp

    !> What a value outside the limits is told, after "x = value".
    character(len=*), parameter :: limits_text = &
        ' is not a finite number of magnitude 0 or 1e-50 .. 1e50'

contains

    !> True for zero and for finite values of magnitude between the limits.
    elemental logical function within_limits(x)
        !> The value
        real(wp), intent(in) :: x

        within_limits = ieee_is_finite(x)
        if (within_limits) within_limits = x == 0.0_wp .or. &
            (abs(x) <= max_input_magnitude .and. abs(x) >= min_input_magnitude)
    end function within_limits

end module ddc_model_limits
