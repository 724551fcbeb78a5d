!> The record of the new fractures a growth run started inside the rock (&initiation,
!> docs/fracture-growth.md#new-fractures-inside-the-rock): one row per new fracture, in the order
!> they started; /growth/initiations in the result file.
module ddc_model_initiations
    use ddc_kinds, only: wp
    use ddc_model_trial_records, only: trial_records
    implicit none
    private

    public :: initiation_record, initiation_tail, initiation_flaw

    !> Kinds of new fracture: a tail beside a contact element's end, a crack at a flaw point
    integer, parameter :: initiation_tail = 1, initiation_flaw = 2

    !> The new fractures, shape (k) for every array. Its columns are listed in
    !> ddc_model_records' for_each_initiation_column, which lays out, appends and writes them.
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
        !> Criterion 'work' with flaws, every trial of a flaw's first crack (allocated by the
        !> first); owner: the flaw
        type(trial_records) :: trials
        !> The last check that started nothing: its growth step (0: none, or no probe), the
        !> largest tension probed in it [stress unit] and that probe point [length unit]
        integer :: largest_step = 0
        real(wp) :: largest_tension = 0.0_wp, largest_x = 0.0_wp, largest_y = 0.0_wp
    end type initiation_record

end module ddc_model_initiations
