!> Working precision for every real in ddc2d.
module ddc_kinds
    use, intrinsic :: iso_fortran_env, only: real64
    implicit none
    private

    !> Kind of all reals: IEEE double precision.
    integer, parameter, public :: wp = real64

end module ddc_kinds
