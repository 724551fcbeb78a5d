!> A small assertion module: test cases, suites and checks with explicit tolerances.
!>
!> Shaped like pFUnit / test-drive so tests port mechanically: one suite per module, a
!> collect_<suite> routine returning its cases, one procedure per case. A check that fails
!> allocates the error with a message; the case returns at once.
module ddc_testing
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    implicit none
    private

    public :: test_case, new_test, test_procedure, run_suite, check, error_type
    public :: relative_error

    abstract interface
        !> One test case: allocates error when it fails.
        subroutine test_procedure(error)
            import :: error_type
            implicit none
            !> Allocated on failure, with the reason
            type(error_type), allocatable, intent(out) :: error
        end subroutine test_procedure
    end interface

    !> A named test case.
    type :: test_case
        character(len=:), allocatable :: name
        procedure(test_procedure), pointer, nopass :: run => null()
    end type test_case

    !> Compare reals (with tolerances), integers or a logical condition.
    interface check
        module procedure check_real, check_integer, check_logical
    end interface check

contains

    !> Make a test case from a name and a procedure.
    function new_test(name, run) result(test)
        !> Name of the case, printed in the report
        character(len=*), intent(in) :: name
        !> The procedure to run
        procedure(test_procedure) :: run
        type(test_case) :: test

        test%name = name
        test%run => run
    end function new_test

    !> Run every case of a suite, print one line each; count the failures.
    subroutine run_suite(suite_name, tests, failures)
        !> Name of the suite
        character(len=*), intent(in) :: suite_name
        !> The cases
        type(test_case), intent(in) :: tests(:)
        !> Number of failed cases (added to)
        integer, intent(inout) :: failures
        type(error_type), allocatable :: error
        integer :: i

        do i = 1, size(tests)
            call tests(i)%run(error)
            if (allocated(error)) then
                failures = failures + 1
                write (*, '(a)') 'FAIL '//suite_name//'/'//tests(i)%name//': '//error%message
                deallocate (error)
            else
                write (*, '(a)') 'PASS '//suite_name//'/'//tests(i)%name
            end if
        end do
    end subroutine run_suite

    !> |actual - expected| / |expected|, or the absolute difference when expected is 0.
    elemental function relative_error(actual, expected) result(err)
        real(wp), intent(in) :: actual, expected
        real(wp) :: err

        if (expected == 0.0_wp) then
            err = abs(actual - expected)
        else
            err = abs(actual - expected) / abs(expected)
        end if
    end function relative_error

    !> Pass when |actual - expected| <= max(abs_tol, rel_tol * |expected|).
    subroutine check_real(error, actual, expected, label, rel_tol, abs_tol)
        type(error_type), allocatable, intent(inout) :: error
        real(wp), intent(in) :: actual, expected
        !> What is compared, for the message
        character(len=*), intent(in) :: label
        !> Relative and absolute tolerance (at least one must be given)
        real(wp), intent(in), optional :: rel_tol, abs_tol
        real(wp) :: tol
        character(len=200) :: line

        if (allocated(error)) return
        if (.not. present(rel_tol) .and. .not. present(abs_tol)) then
            call set_error(error, 1, label//': no tolerance given')
            return
        end if
        tol = 0.0_wp
        if (present(abs_tol)) tol = abs_tol
        if (present(rel_tol)) tol = max(tol, rel_tol * abs(expected))
        if (.not. ieee_is_finite(actual) .or. abs(actual - expected) > tol) then
            write (line, '(3(a,es24.16))') ' = ', actual, ', expected ', expected, &
                ', relative error ', relative_error(actual, expected)
            call set_error(error, 1, label//trim(line))
        end if
    end subroutine check_real

    !> Pass when the integers are equal.
    subroutine check_integer(error, actual, expected, label)
        type(error_type), allocatable, intent(inout) :: error
        integer, intent(in) :: actual, expected
        character(len=*), intent(in) :: label
        character(len=100) :: line

        if (allocated(error)) return
        if (actual /= expected) then
            write (line, '(a,i0,a,i0)') ' = ', actual, ', expected ', expected
            call set_error(error, 1, label//trim(line))
        end if
    end subroutine check_integer

    !> Pass when the condition holds.
    subroutine check_logical(error, condition, label)
        type(error_type), allocatable, intent(inout) :: error
        logical, intent(in) :: condition
        character(len=*), intent(in) :: label

        if (allocated(error)) return
        if (.not. condition) call set_error(error, 1, label)
    end subroutine check_logical

end module ddc_testing
