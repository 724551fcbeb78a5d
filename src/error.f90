!> Error type that travels up to the program, and the exit codes
!> (docs/troubleshooting.md#exit-status).
module ddc_error
    implicit none
    private

    public :: error_type, set_error, set_internal_error
    public :: exit_success, exit_solver_failure, exit_bad_input, exit_io_failure
    public :: exit_internal_error, exit_out_of_memory, exit_stopped_early

    !> The run succeeded.
    integer, parameter :: exit_success = 0
    !> The model has no solution or the solver failed.
    integer, parameter :: exit_solver_failure = 1
    !> Bad input or bad usage.
    integer, parameter :: exit_bad_input = 2
    !> Reading or writing a file failed.
    integer, parameter :: exit_io_failure = 3
    !> A contract between two parts of ddc2d was broken: a bug, not the user's input
    integer, parameter :: exit_internal_error = 4
    !> The model is too large for the memory of this machine (or its cgroup): it would run
    !> with more memory, unchanged
    integer, parameter :: exit_out_of_memory = 5
    !> A run of steps (fracture growth) stopped at a step whose solve failed: the steps it
    !> completed are written, the failure recorded, and --resume can go on from them
    integer, parameter :: exit_stopped_early = 6

    !> An error: the exit code it maps to and one sentence for the user.
    type :: error_type
        !> Exit code (exit_solver_failure, exit_bad_input, exit_io_failure,
        !> exit_internal_error, exit_out_of_memory or exit_stopped_early)
        integer :: code = exit_bad_input
        !> Message for the user, naming file, group and variable where it applies
        character(len=:), allocatable :: message
    end type error_type

contains

    !> Allocate an error with its exit code and message.
    subroutine set_error(error, code, message)
        !> The error to create
        type(error_type), allocatable, intent(out) :: error
        !> Exit code the program will return
        integer, intent(in) :: code
        !> One sentence for the user
        character(len=*), intent(in) :: message

        allocate (error)
        error%code = code
        error%message = message
    end subroutine set_error

    !> Allocate an internal error (exit_internal_error): a broken contract between two parts
    !> of ddc2d, reported with where it was found.
    subroutine set_internal_error(error, where, what)
        !> The error to create
        type(error_type), allocatable, intent(out) :: error
        !> The procedure that found it
        character(len=*), intent(in) :: where
        !> What was wrong
        character(len=*), intent(in) :: what

        call set_error(error, exit_internal_error, 'internal error in '//where//': '//what// &
                       ' (a bug in ddc2d: please report it with the input file)')
    end subroutine set_internal_error

end module ddc_error
