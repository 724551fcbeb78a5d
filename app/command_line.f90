!> Command-line parsing of the ddc2d executable (SPEC section 6).
module ddc_app_command_line
    use ddc_error, only: error_type, set_error, exit_bad_input
    implicit none
    private

    public :: command_line_options, parse_command_line, usage_text
    public :: action_run, action_version, action_help

    !> What the program was asked to do
    integer, parameter :: action_run = 1, action_version = 2, action_help = 3

    !> The parsed command line.
    type :: command_line_options
        !> action_run, action_version or action_help
        integer :: action = action_run
        !> Namelist input file
        character(len=:), allocatable :: input_file
        !> Output file from -o (overrides &output file); unallocated when absent
        character(len=:), allocatable :: output_file
    end type command_line_options

contains

    !> The help text.
    function usage_text() result(text)
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line('a')

        text = 'usage: ddc2d INPUT.nml [-o OUT.h5]'//nl// &
               '       ddc2d --version | --help'//nl//nl// &
               'Solves a 2D displacement discontinuity model of faults and fractures given as'//nl// &
               'a namelist file and writes the results to an HDF5 file (default: the input'//nl// &
               'file name with extension .h5 in the current folder, or &output file).'//nl//nl// &
               'Exit status: 0 success; 1 no solution or solver failure; 2 bad input or'//nl// &
               'usage; 3 I/O failure. A failed run leaves no output file.'
    end function usage_text

    !> The i-th argument as a deferred-length string.
    function argument(i) result(arg)
        integer, intent(in) :: i
        character(len=:), allocatable :: arg
        integer :: length

        call get_command_argument(i, length=length)
        allocate (character(len=length) :: arg)
        call get_command_argument(i, arg)
    end function argument

    !> Parse the program's arguments; bad usage is an error with exit_bad_input.
    subroutine parse_command_line(options, error)
        !> The parsed options
        type(command_line_options), intent(out) :: options
        !> Set on bad usage
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: arg
        integer :: i, n

        n = command_argument_count()
        i = 0
        do while (i < n)
            i = i + 1
            arg = argument(i)
            select case (arg)
            case ('--version', '-V')
                options%action = action_version
                return
            case ('--help', '-h')
                options%action = action_help
                return
            case ('-o', '--output')
                if (i == n) then
                    call set_error(error, exit_bad_input, 'option '//arg//' needs a file name')
                    return
                end if
                i = i + 1
                options%output_file = argument(i)
            case default
                if (arg(1:min(1, len(arg))) == '-') then
                    call set_error(error, exit_bad_input, 'unknown option '//arg)
                    return
                end if
                if (allocated(options%input_file)) then
                    call set_error(error, exit_bad_input, 'more than one input file: '// &
                                   options%input_file//' and '//arg)
                    return
                end if
                options%input_file = arg
            end select
        end do
        if (.not. allocated(options%input_file)) then
            call set_error(error, exit_bad_input, 'no input file given')
        else if (len(options%input_file) == 0) then
            call set_error(error, exit_bad_input, 'the input file name is empty')
        end if
    end subroutine parse_command_line

end module ddc_app_command_line
