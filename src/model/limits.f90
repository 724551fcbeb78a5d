!> The values ddc2d accepts: the magnitude of every input real, and the physical range of
!> the quantities that have one (docs/troubleshooting.md#bad-input-what-the-user-sees). The namelist
!> reader, the TWODD deck reader and the parameter sweep all check their values here, so they accept
!> the same values.
module ddc_model_limits
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use ddc_kinds, only: wp
    implicit none
    private

    public :: max_input_magnitude, within_limits, limits_text, range_problem
    public :: quantity_any, quantity_youngs_modulus, quantity_poissons_ratio
    public :: quantity_non_negative, quantity_positive

    !> Largest and smallest accepted magnitude of a non-zero input real. The kernels raise
    !> coordinate differences to the sixth power and the solvers divide by moduli: outside
    !> this range they would overflow or underflow double precision.
    real(wp), parameter :: max_input_magnitude = 1.0e50_wp, min_input_magnitude = 1.0e-50_wp

    !> What a value outside the limits is told, after "x = value".
    character(len=*), parameter :: limits_text = &
        ' is not a finite number of magnitude 0 or 1e-50 .. 1e50'

    !> Quantities with a physical range: any value within the limits; Young's modulus
    !> (positive); Poisson's ratio (-1, 0.5); friction, cohesion (not negative); lengths and
    !> the fracture toughness (positive)
    integer, parameter :: quantity_any = 0, quantity_youngs_modulus = 1, &
                          quantity_poissons_ratio = 2, quantity_non_negative = 3, &
                          quantity_positive = 4

contains

    !> True for zero and for finite values of magnitude between the limits.
    elemental logical function within_limits(x)
        !> The value
        real(wp), intent(in) :: x

        within_limits = ieee_is_finite(x)
        if (within_limits) within_limits = x == 0.0_wp .or. &
            (abs(x) <= max_input_magnitude .and. abs(x) >= min_input_magnitude)
    end function within_limits

    !> Why a value is not acceptable for its quantity, to follow "name = value "; '' when
    !> it is.
    pure function range_problem(quantity, value) result(problem)
        !> quantity_any, quantity_youngs_modulus, quantity_poissons_ratio,
        !> quantity_non_negative or quantity_positive
        integer, intent(in) :: quantity
        !> The value
        real(wp), intent(in) :: value
        character(len=:), allocatable :: problem

        problem = ''
        if (.not. within_limits(value)) then
            problem = limits_text(2:)
            return
        end if
        select case (quantity)
        case (quantity_youngs_modulus, quantity_positive)
            if (.not. value > 0.0_wp) problem = 'must be positive'
        case (quantity_poissons_ratio)
            if (.not. (value > -1.0_wp .and. value < 0.5_wp)) problem = 'must lie in (-1, 0.5)'
        case (quantity_non_negative)
            if (value < 0.0_wp) problem = 'must be >= 0'
        case default
        end select
    end function range_problem

end module ddc_model_limits
