!> Progress of long runs: the solvers report where they are (a line per step of a loading
!> history, per phase of a large model) to a handler that the program installs; without
!> one (the library in tests) nothing happens. Only app/ prints.
module ddc_progress
    implicit none
    private

    public :: progress_handler, set_progress_handler, report_progress, reports_phases
    public :: phase_min_elements

    !> Phases are reported for models of at least this many elements
    integer, parameter :: phase_min_elements = 1000

    abstract interface
        !> Receives one line of progress.
        subroutine progress_handler(line)
            implicit none
            !> The line, without a newline
            character(len=*), intent(in) :: line
        end subroutine progress_handler
    end interface

    !> The installed handler; none by default
    procedure(progress_handler), pointer :: handler => null()

contains

    !> Install the handler that receives progress lines (app/).
    subroutine set_progress_handler(new_handler)
        !> The handler
        procedure(progress_handler) :: new_handler

        handler => new_handler
    end subroutine set_progress_handler

    !> Send one line to the handler, if one is installed.
    subroutine report_progress(line)
        !> The line
        character(len=*), intent(in) :: line

        if (associated(handler)) call handler(line)
    end subroutine report_progress

    !> Whether the phases of a model of n elements are reported.
    pure logical function reports_phases(n)
        !> Number of elements
        integer, intent(in) :: n

        reports_phases = n >= phase_min_elements
    end function reports_phases

end module ddc_progress
