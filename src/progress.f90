!> Progress of long runs: the solvers report where they are (a line per step of a loading
!> history, per phase of a large model) to a handler that the program installs; without
!> one (the library in tests) nothing happens. Only app/ prints.
!>
!> A caller that runs many short solves (the growth steps' corrector solves) holds the
!> lines: while held, a line reaches the handler only once the hold has lasted a given time,
!> so the phases of a slow solve are still shown and those of quick ones are not.
module ddc_progress
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    implicit none
    private

    public :: progress_handler, set_progress_handler, report_progress, reports_phases
    public :: phase_min_elements, hold_progress, release_progress

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

    !> system_clock when the hold began (-1: not held), and its length in clock ticks
    integer(int64) :: held_since = -1, hold_ticks = 0

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

        integer(int64) :: now

        if (.not. associated(handler)) return
        if (held_since >= 0) then
            call system_clock(now)
            if (now - held_since < hold_ticks) return
        end if
        call handler(line)
    end subroutine report_progress

    !> Drop the lines of the next `seconds` (until release_progress).
    subroutine hold_progress(seconds)
        !> How long lines are dropped [s]
        real(wp), intent(in) :: seconds
        integer(int64) :: rate

        call system_clock(held_since, rate)
        hold_ticks = int(seconds * real(rate, wp), int64)
    end subroutine hold_progress

    !> Let every line through again.
    subroutine release_progress()
        held_since = -1
    end subroutine release_progress

    !> Whether the phases of a model of n elements are reported.
    pure logical function reports_phases(n)
        !> Number of elements
        integer, intent(in) :: n

        reports_phases = n >= phase_min_elements
    end function reports_phases

end module ddc_progress
