!> Earthquake cycles on rate-and-state faults (docs/earthquake-cycles.md,
!> docs/theory/cycles.md): the options of a cycle run (&cycle) and its record, the /cycle
!> group of the result file. The elements' own values (a, b, dc, ...) are per-element arrays
!> of element_set (ddc_model_rate_state lists them).
module ddc_model_cycles
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    implicit none
    private

    public :: cycle_options, cycle_record, cycle_resume, radiation_damping_of
    public :: state_law_aging, state_law_slip, state_law_names
    public :: cycle_running, cycle_end_time, cycle_normal_stress, cycle_step_size, &
        cycle_end_names

    !> State evolution laws: aging (dtheta/dt = 1 - V theta / L) and slip (dtheta/dt =
    !> -(V theta / L) ln(V theta / L)) (docs/theory/cycles.md#the-fault)
    integer, parameter :: state_law_aging = 1, state_law_slip = 2
    !> Input names of the state laws, indexed by law
    character(len=*), parameter :: state_law_names(2) = [character(len=5) :: 'aging', 'slip']

    !> How a cycle run ended: not yet (a checkpoint), at end_time, stopped where an effective
    !> normal stress reached zero, stopped where the time step fell below what the time can
    !> resolve
    integer, parameter :: cycle_running = 0, cycle_end_time = 1, cycle_normal_stress = 2, &
                          cycle_step_size = 3
    !> Names of the end reasons, indexed by reason
    character(len=*), parameter :: cycle_end_names(0:3) = [character(len=13) :: &
        'running', 'end_time', 'normal_stress', 'step_size']

    !> A cycle run (&cycle; docs/input-reference.md#cycle). Times in the model's time unit,
    !> lengths and stresses in its length and stress units.
    type :: cycle_options
        !> The model runs earthquake cycles (a &cycle group was given)
        logical :: active = .false.
        !> Time at which the run ends [time unit]
        real(wp) :: end_time = 0.0_wp
        !> Tolerance of the time integration: the largest accepted local error of a step,
        !> relative (docs/theory/cycles.md#error-control) [-]
        real(wp) :: tolerance = 1.0e-7_wp
        !> Radiation damping eta [stress unit * time unit / length unit] as given, or the shear
        !> wave speed c_s [length unit / time unit] it is G / (2 c_s) of (0 where the other is
        !> given: radiation_damping_of)
        real(wp) :: radiation_damping = 0.0_wp, shear_wave_speed = 0.0_wp
        !> Plate rate of the back-slip loading, in the sign of ds [length unit / time unit]
        real(wp) :: plate_rate = 0.0_wp
        !> A time is seismic while the largest slip rate is at least this [length unit / time
        !> unit]
        real(wp) :: seismic_threshold = 1.0e-3_wp
        !> state_law_aging or state_law_slip
        integer :: state_law = state_law_aging
        !> Least time between two recorded rows outside events and inside them [time unit]
        !> (0: every step)
        real(wp) :: output_interval = 0.0_wp, event_output_interval = 0.0_wp
        !> Spacing of the recorded elements along each fault [length unit] (0: every element)
        real(wp) :: profile_spacing = 0.0_wp
        !> Wall-clock seconds between two checkpoints of the result file (0: none) [s]
        real(wp) :: checkpoint_interval = 600.0_wp
    end type cycle_options

    !> Where a run stands, for a checkpoint and --resume: the time, the step, slip and state
    !> of every rate-and-state element and the event in progress.
    type :: cycle_resume
        !> Time [time unit] and the next step size [time unit]
        real(wp) :: time = 0.0_wp, step = 0.0_wp
        !> Slip (total ds) [length unit], state psi = ln(V0 theta / L) [-] and slip rate
        !> [length unit / time unit] of every rate-and-state element, shape (m)
        real(wp), allocatable :: slip(:), state(:), slip_rate(:)
        !> An event is in progress: its start [time unit], the element where it started,
        !> its largest slip rate so far [length unit / time unit] and the slip at its start
        !> [length unit], shape (m)
        logical :: in_event = .false.
        real(wp) :: event_start = 0.0_wp, event_peak_rate = 0.0_wp
        integer :: event_element = 0
        real(wp), allocatable :: event_start_slip(:)
        !> Time of the last recorded row [time unit]
        real(wp) :: last_row = 0.0_wp
    end type cycle_resume

    !> The record of a cycle run (docs/output-reference.md#cycle): k rows (recorded times),
    !> r recorded elements (the profile), p observation points, e events. The arrays of rows
    !> and events hold room for more: their first `rows` and `events` entries are the record.
    type :: cycle_record
        !> Rows and events recorded
        integer :: rows = 0, events = 0
        !> The rate-and-state elements (indices into /elements), shape (m)
        integer, allocatable :: elements(:)
        !> The recorded elements (indices into /elements) and their distance along their
        !> fault from its first vertex [length unit], shape (r)
        integer, allocatable :: profile(:)
        real(wp), allocatable :: distance(:)
        !> Time [time unit], largest |slip rate| [length unit / time unit] and the element it
        !> is on, of each row, shape (k)
        real(wp), allocatable :: time(:), max_slip_rate(:)
        integer, allocatable :: max_rate_element(:)
        !> Slip (total ds) [length unit], slip rate [length unit / time unit], shear and
        !> normal traction (tension positive) [stress unit], state log10(theta) [log10 time
        !> unit] of the recorded elements at each row, shape (r, k)
        real(wp), allocatable :: slip(:, :), slip_rate(:, :), shear_traction(:, :), &
            normal_traction(:, :), state(:, :)
        !> Displacement and velocity at the observation points, back-slip's rigid
        !> translation included [length unit, length unit / time unit], shape (p, k)
        real(wp), allocatable :: ux(:, :), uy(:, :), vx(:, :), vy(:, :)
        !> Events: start and end time [time unit], the element where the slip rate first
        !> reached the threshold and its midpoint [length unit], the largest slip rate
        !> [length unit / time unit], the largest slip [length unit] and the moment per unit
        !> length of fault (G times the integral of |slip| along the faults) [stress unit *
        !> length unit], shape (e); the slip of each recorded element, shape (r, e)
        real(wp), allocatable :: event_start(:), event_end(:), event_x(:), event_y(:), &
            event_peak_rate(:), event_max_slip(:), event_moment(:)
        integer, allocatable :: event_element(:)
        real(wp), allocatable :: event_slip(:, :)
        !> How the run ended (cycle_running ... cycle_step_size) and where: the element and
        !> time of a lost normal stress (0 otherwise)
        integer :: end_reason = cycle_running
        integer :: end_element = 0
        !> Seconds of wall-clock time, accepted and rejected steps, products of the elastic
        !> operator, Newton iterations
        real(wp) :: seconds = 0.0_wp
        integer :: steps = 0, rejected = 0, products = 0
        integer(int64) :: newton_iterations = 0
        !> Where the run stands, for --resume
        type(cycle_resume) :: now
    end type cycle_record

contains

    !> The radiation damping of a cycle run [stress unit * time unit / length unit]: as given,
    !> or G / (2 c_s) (docs/theory/cycles.md#the-fault).
    pure real(wp) function radiation_damping_of(options, shear_modulus)
        !> The run's options
        type(cycle_options), intent(in) :: options
        !> The shear modulus G [stress unit]
        real(wp), intent(in) :: shear_modulus

        if (options%shear_wave_speed > 0.0_wp) then
            radiation_damping_of = shear_modulus / (2.0_wp * options%shear_wave_speed)
        else
            radiation_damping_of = options%radiation_damping
        end if
    end function radiation_damping_of

end module ddc_model_cycles
