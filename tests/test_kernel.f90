!> Tests of the Crouch & Starfield kernel.
module test_kernel
    use ddc_testing, only: test_case, new_test, check, error_type
    implicit none
    private
    public :: collect_kernel
contains
    !> Cases of the kernel suite.
    subroutine collect_kernel(tests)
        type(test_case), allocatable, intent(out) :: tests(:)
        allocate (tests(0))
    end subroutine collect_kernel
end module test_kernel
