!> The trials of the work criterion's searches (docs/fracture-growth.md#output): one row per
!> trial, for a tip's kinks (/growth/trials) and a flaw's first cracks
!> (/growth/initiations/flaw_trials).
module ddc_model_trial_records
    use ddc_kinds, only: wp
    implicit none
    private

    public :: trial_records, add_trial

    !> The trials of the work criterion's searches, one row per trial (t trials), shape (t)
    !> for every array: a tip's kinks (/growth/trials) or a flaw's first cracks
    !> (/growth/initiations/flaw_trials). Its columns are listed in ddc_model_records'
    !> for_each_trial_column.
    type :: trial_records
        !> Growth step of the trial
        integer, allocatable :: step(:)
        !> Whose trial it is: in a growth step the tip (index of the run's tips), in
        !> /growth/trials the tip's record (1-based row of /growth), in flaw_trials the flaw
        integer, allocatable :: owner(:)
        !> Direction [degree] (a kink: from the tip's outward direction; a flaw's crack: from
        !> the x axis, -90 .. 90) and efficiency (NaN when not solved or blocked) [stress unit
        !> * length unit]
        real(wp), allocatable :: angle(:), efficiency(:)
        !> The state of its new elements (trial_stuck ... trial_blocked)
        integer, allocatable :: state(:)
    end type trial_records

contains

    !> Append one trial (allocating the columns on the first).
    pure subroutine add_trial(trials, step, owner, angle, efficiency, state)
        !> The trials
        type(trial_records), intent(inout) :: trials
        !> Growth step and owner (see trial_records)
        integer, intent(in) :: step, owner
        !> Direction [degree] and efficiency [stress unit * length unit]
        real(wp), intent(in) :: angle, efficiency
        !> The state of its new elements (trial_stuck ... trial_blocked)
        integer, intent(in) :: state

        if (.not. allocated(trials%step)) then
            allocate (trials%step(0), trials%owner(0), trials%angle(0), trials%efficiency(0), &
                      trials%state(0))
        end if
        trials%step = [trials%step, step]
        trials%owner = [trials%owner, owner]
        trials%angle = [trials%angle, angle]
        trials%efficiency = [trials%efficiency, efficiency]
        trials%state = [trials%state, state]
    end subroutine add_trial

end module ddc_model_trial_records
