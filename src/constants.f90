!> Mathematical constants.
module ddc_constants
    use ddc_kinds, only: wp
    implicit none
    private

    !> The ratio of a circle's circumference to its diameter
    real(wp), parameter, public :: pi = 3.14159265358979323846264338327950288_wp

end module ddc_constants
