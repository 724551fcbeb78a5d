!> Command-line parsing of the ddc2d executable (docs/getting-started.md#the-command-line).
module ddc_app_command_line
    use ddc_error, only: error_type, set_error, exit_bad_input
    implicit none
    private

    public :: command_line_options, parse_command_line, usage_text
    public :: action_run, action_version, action_help, task_number

    !> What the program was asked to do
    integer, parameter :: action_run = 1, action_version = 2, action_help = 3

    !> The parsed command line.
    type :: command_line_options
        !> action_run, action_version or action_help
        integer :: action = action_run
        !> Input file: a namelist file, or a classic TWODD deck when twodd is true
        character(len=:), allocatable :: input_file
        !> The input file is a TWODD deck (--twodd DECK)
        logical :: twodd = .false.
        !> Output file from -o (overrides &output file); unallocated when absent
        character(len=:), allocatable :: output_file
        !> TWODD-style result tables from --res; unallocated when absent
        character(len=:), allocatable :: res_file
        !> List the tasks of a sweep (--list) instead of running
        logical :: list = .false.
        !> Sweep task from --task K; -1 when absent
        integer :: task = -1
        !> Value of SLURM_ARRAY_TASK_ID when --task is absent and the variable is set
        character(len=:), allocatable :: environment_task
        !> Result file of an earlier run to continue (--resume FILE); unallocated when absent
        character(len=:), allocatable :: resume_file
    end type command_line_options

contains

    !> The help text.
    function usage_text() result(text)
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line('a')

        text = 'usage: ddc2d INPUT.nml [-o OUT.h5] [--res RES.txt] [--resume OLD.h5]'//nl// &
               '       ddc2d SWEEP.nml --list | --task K [-o OUT.h5]'//nl// &
               '       ddc2d --twodd DECK [-o OUT.h5] [--res RES.txt]'//nl// &
               '       ddc2d --version | --help'//nl//nl// &
               'Solves a 2D displacement discontinuity model of faults and fractures given'//nl// &
               'as a namelist file and writes the results to an HDF5 file (default: the'//nl// &
               'input file name with extension .h5 in the current folder, or &output'//nl// &
               'file).'//nl//nl// &
               '  --twodd DECK    read a classic TWODD deck (Crouch & Starfield 1983, ch. 5:'// &
               nl// &
               '                  KODE 1-4, symmetry KSYM 1-4) instead of a namelist file'//nl// &
               '  -o OUT.h5       the HDF5 result file'//nl// &
               '  --res RES.txt   also write the result tables in the layout of the TWODD'//nl// &
               '                  print, at full precision (es24.15); observation points'//nl// &
               '                  that TWODD would skip (within one element length of an'//nl// &
               '                  element centre) are computed and marked * (** on an'//nl// &
               '                  element: NaN)'//nl// &
               '  --list          print the tasks of the &sweep group: "tasks: N", then one'//nl// &
               '                  line per task with its parameters and output file'//nl// &
               '  --task K        run task K (0 to N-1) of the &sweep group (without'//nl// &
               '                  --task: $SLURM_ARRAY_TASK_ID when set); the output is'//nl// &
               '                  OUT.h5 with _task<K> (zero-padded) before .h5; a task'//nl// &
               '                  with a complete output is skipped (exit status 0)'//nl// &
               '  --resume OLD.h5 continue the growth run or loading history of OLD.h5, the'// &
               nl// &
               '                  complete result of an earlier run of the same input by'//nl// &
               '                  the same ddc2d version (only &growth steps may differ, and'// &
               nl// &
               '                  the load path may be longer); OUT.h5 may be OLD.h5'//nl//nl// &
               'Exit status: 0 success; 1 no solution or solver failure; 2 bad input or'//nl// &
               'usage; 3 a file could not be read or written (an output path that cannot'//nl// &
               'be written too: ddc2d creates no folders); 4 internal error (a bug in'//nl// &
               'ddc2d); 5 the model is too large for the memory here (the machine or its'//nl// &
               'cgroup, e.g. Slurm --mem): the message gives the estimate, what is'//nl// &
               'available and how many elements fit; 6 a growth run stopped at a step'//nl// &
               'whose solve failed: the steps before it are written (end_reason failed)'//nl// &
               'and --resume goes on from them. A failed run leaves no other output file.'
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
            case ('--res')
                if (i == n) then
                    call set_error(error, exit_bad_input, 'option '//arg//' needs a file name')
                    return
                end if
                i = i + 1
                options%res_file = argument(i)
                if (len(options%res_file) == 0) then
                    call set_error(error, exit_bad_input, 'the --res file name is empty')
                    return
                end if
            case ('--list')
                options%list = .true.
            case ('--task')
                if (i == n) then
                    call set_error(error, exit_bad_input, 'option '//arg//' needs a task number')
                    return
                end if
                i = i + 1
                arg = argument(i)
                options%task = task_number(arg, '--task '//arg, error)
                if (allocated(error)) return
            case ('--resume')
                ! An option after --resume means its file was forgotten: not a file '-o'.
                if (i < n) arg = argument(i + 1)
                if (i == n .or. arg(1:min(1, len(arg))) == '-') then
                    call set_error(error, exit_bad_input, 'option --resume needs the result '// &
                                   'file of the run to continue')
                    return
                end if
                i = i + 1
                options%resume_file = argument(i)
                if (len(options%resume_file) == 0) then
                    call set_error(error, exit_bad_input, 'the --resume file name is empty')
                    return
                end if
            case ('--twodd')
                if (i == n) then
                    call set_error(error, exit_bad_input, 'option '//arg//' needs a deck file')
                    return
                end if
                if (options%twodd .or. allocated(options%input_file)) then
                    call set_error(error, exit_bad_input, 'more than one input file given')
                    return
                end if
                i = i + 1
                options%input_file = argument(i)
                options%twodd = .true.
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
        if (options%twodd .and. (options%list .or. options%task >= 0)) then
            call set_error(error, exit_bad_input, '--list and --task need a namelist file '// &
                           'with a &sweep group, not a TWODD deck')
            return
        end if
        if (allocated(options%resume_file) .and. (options%twodd .or. options%list .or. &
                                                  options%task >= 0)) then
            call set_error(error, exit_bad_input, '--resume continues a growth run or a '// &
                           'loading history of a namelist model, not a TWODD deck (--twodd) '// &
                           'or a sweep (--list, --task)')
            return
        end if
        if (options%list .and. options%task >= 0) then
            call set_error(error, exit_bad_input, 'give --list or --task, not both')
            return
        end if
        if (options%task < 0) then
            call get_environment_variable('SLURM_ARRAY_TASK_ID', length=n, status=i)
            if (i == 0) then
                allocate (character(len=n) :: options%environment_task)
                call get_environment_variable('SLURM_ARRAY_TASK_ID', options%environment_task)
            end if
        end if
        if (.not. allocated(options%input_file)) then
            call set_error(error, exit_bad_input, 'no input file given')
        else if (len(options%input_file) == 0) then
            call set_error(error, exit_bad_input, 'the input file name is empty')
        end if
    end subroutine parse_command_line

    !> A task number (a non-negative integer) from text; source names it in the message.
    function task_number(text, source, error) result(task)
        !> The text, e.g. '7'
        character(len=*), intent(in) :: text
        !> Where it came from, e.g. '--task 7' or 'SLURM_ARRAY_TASK_ID=7'
        character(len=*), intent(in) :: source
        !> Allocated with exit_bad_input when text is not a non-negative integer
        type(error_type), allocatable, intent(out) :: error
        !> The task number
        integer :: task
        integer :: stat

        task = -1
        stat = 1
        if (len(text) > 0 .and. len(text) < 10 .and. verify(text, '0123456789') == 0) then
            read (text, *, iostat=stat) task
        end if
        if (stat /= 0) then
            call set_error(error, exit_bad_input, source//': the task must be a number '// &
                           '0, 1, 2, ...')
        end if
    end function task_number

end module ddc_app_command_line
