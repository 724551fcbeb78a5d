!> The record of the new fractures a growth run started inside the rock (&initiation,
!> docs/fracture-growth.md#new-fractures-inside-the-rock): one row per new fracture, in the order
!> they started; /growth/initiations in the result file.
module ddc_model_initiations
    use ddc_kinds, only: wp
    implicit none
    private

    public :: initiation_record, initiation_tail, initiation_flaw, append_initiation, &
        empty_initiation_record, append_flaw_trial

    !> Kinds of new fracture: a tail beside a contact element's end, a crack at a flaw point
    integer, parameter :: initiation_tail = 1, initiation_flaw = 2

    !> The new fractures, shape (k) for every array.
    type :: initiation_record
        !> initiation_tail or initiation_flaw
        integer, allocatable :: kind(:)
        !> Growth step whose check started it, and load step (1 without a load path)
        integer, allocatable :: step(:), load_step(:)
        !> The new fracture (1-based), and the fracture it starts from (0 for a flaw)
        integer, allocatable :: fracture_id(:), parent(:)
        !> The parent's element whose end it starts at (its index when it started; 0 for a
        !> flaw), and the flaw point (0 for a tail)
        integer, allocatable :: element(:), flaw(:)
        !> Side of the parent it starts on: +1 the side of the element normal
        !> (-sin beta, cos beta), -1 the other; 0 for a flaw
        integer, allocatable :: side(:)
        !> Where it starts: the parent's vertex, or the flaw point [length unit]
        real(wp), allocatable :: x(:), y(:)
        !> The probe point [length unit] (the flaw point for a flaw)
        real(wp), allocatable :: probe_x(:), probe_y(:)
        !> The maximum principal stress at the probe point before the fracture existed,
        !> tension positive, effective where there is pore fluid [stress unit]
        real(wp), allocatable :: tension(:)
        !> Direction of the new crack, counter-clockwise from the x axis [degree]
        real(wp), allocatable :: angle(:)
        !> Criterion 'work': a flaw's efficiency when it started (NaN for a tail, and under
        !> 'mts') [stress unit * length unit]
        real(wp), allocatable :: efficiency(:)
        !> Criterion 'work' with flaws, every trial of a flaw's first crack (t trials;
        !> allocated by the first): the growth step of the check, the flaw, the crack's
        !> direction [degree, -90 .. 90], its efficiency (NaN when blocked) and the state of
        !> its elements (the trial states of the tips' searches), shape (t)
        integer, allocatable :: trial_step(:), trial_flaw(:), trial_state(:)
        real(wp), allocatable :: trial_angle(:), trial_efficiency(:)
        !> The last check that started nothing: its growth step (0: none, or no probe), the
        !> largest tension probed in it [stress unit] and that probe point [length unit]
        integer :: largest_step = 0
        real(wp) :: largest_tension = 0.0_wp, largest_x = 0.0_wp, largest_y = 0.0_wp
    end type initiation_record

contains

    !> Append one row to the record (allocating it on the first).
    pure subroutine append_initiation(record, kind, step, load_step, fracture_id, parent, &
                                      element, flaw, side, point, probe, tension, angle, &
                                      efficiency)
        !> The record
        type(initiation_record), intent(inout) :: record
        !> The row's integer values (see initiation_record)
        integer, intent(in) :: kind, step, load_step, fracture_id, parent, element, flaw, side
        !> Start point and probe point (x, y) [length unit]
        real(wp), intent(in) :: point(2), probe(2)
        !> Probed tension [stress unit], direction [degree] and efficiency (NaN but for a
        !> flaw under 'work') [stress unit * length unit]
        real(wp), intent(in) :: tension, angle, efficiency

        if (.not. allocated(record%kind)) call empty_initiation_record(record)
        record%kind = [record%kind, kind]
        record%step = [record%step, step]
        record%load_step = [record%load_step, load_step]
        record%fracture_id = [record%fracture_id, fracture_id]
        record%parent = [record%parent, parent]
        record%element = [record%element, element]
        record%flaw = [record%flaw, flaw]
        record%side = [record%side, side]
        record%x = [record%x, point(1)]
        record%y = [record%y, point(2)]
        record%probe_x = [record%probe_x, probe(1)]
        record%probe_y = [record%probe_y, probe(2)]
        record%tension = [record%tension, tension]
        record%angle = [record%angle, angle]
        record%efficiency = [record%efficiency, efficiency]
    end subroutine append_initiation

    !> Append one trial of a flaw's first crack (allocating the trial columns on the first).
    pure subroutine append_flaw_trial(record, step, flaw, angle, efficiency, state)
        !> The record
        type(initiation_record), intent(inout) :: record
        !> Growth step of the check, and the flaw
        integer, intent(in) :: step, flaw
        !> The crack's direction [degree] and efficiency [stress unit * length unit]
        real(wp), intent(in) :: angle, efficiency
        !> The state of its elements (trial_stuck ... trial_blocked)
        integer, intent(in) :: state

        if (.not. allocated(record%trial_step)) then
            allocate (record%trial_step(0), record%trial_flaw(0), record%trial_state(0), &
                      record%trial_angle(0), record%trial_efficiency(0))
        end if
        record%trial_step = [record%trial_step, step]
        record%trial_flaw = [record%trial_flaw, flaw]
        record%trial_state = [record%trial_state, state]
        record%trial_angle = [record%trial_angle, angle]
        record%trial_efficiency = [record%trial_efficiency, efficiency]
    end subroutine append_flaw_trial

    !> A record without rows.
    pure subroutine empty_initiation_record(record)
        !> The record
        type(initiation_record), intent(out) :: record

        allocate (record%kind(0), record%step(0), record%load_step(0), record%fracture_id(0), &
                  record%parent(0), record%element(0), record%flaw(0), record%side(0), &
                  record%x(0), record%y(0), record%probe_x(0), record%probe_y(0), &
                  record%tension(0), record%angle(0), record%efficiency(0))
    end subroutine empty_initiation_record

end module ddc_model_initiations
