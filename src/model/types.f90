!> The model as every input format produces it and every solver consumes it.
!>
!> Elements are stored as arrays (structure of arrays), ordered fracture by fracture,
!> vertex to vertex. Geometry derived from the end points (midpoint, half-length,
!> orientation) is filled by ddc_mesh_geometry. for_each_element_array is the one list of
!> the per-element arrays: allocating them (ddc_mesh_geometry), selecting elements
!> (select_elements, for growth), broadcasting them (ddc_parallel_model) and hashing them
!> (ddc_model_fingerprint) go through it.
module ddc_model_types
    use ddc_kinds, only: wp
    use ddc_contact_options, only: solver_options
    ! The defaults of the fault law, for the per-element arrays that hold its given values,
    ! and its cap on the tensile strength, for what the echo reports in force.
    use ddc_contact_fault_law, only: no_residual_drop, rigid_joint, tensile_cap
    use ddc_model_cycles, only: cycle_options
    use ddc_model_body, only: finite_body
    implicit none
    private

    public :: model_type, element_set, fracture_type, observation_set
    public :: symmetry_options, symmetry_none, symmetry_x, symmetry_y, symmetry_both
    public :: symmetry_names, sweep_task_record, load_path_type, load_path_names
    public :: injection_source, source_overpressure, source_rate, has_sources, fluid_options
    public :: condition_traction, condition_displacement, condition_mixed_us_sn
    public :: condition_mixed_ss_un, condition_contact, condition_prescribed_dd, condition_names
    public :: condition_rate_state
    public :: domain_full_plane, domain_half_plane, domain_bimaterial, domain_names
    public :: observation_grid, observation_line, observation_points, observation_kind_names
    public :: growth_options, growth_tips_all, growth_tips_most_critical, growth_tips_names
    public :: growth_criterion_mts, growth_criterion_work, growth_criterion_names
    public :: work_mode_any, work_mode_opening, work_mode_names
    public :: angle_search_seeded, angle_search_grid, angle_search_names
    public :: initiation_options
    public :: strength_law_count
    public :: default_block_size, no_residual_drop, rigid_joint, tensile_cap
    public :: element_array_action, for_each_element_array, select_elements, element_end

    !> Boundary conditions; 1-4 are the TWODD KODE values.
    integer, parameter :: condition_traction = 1
    integer, parameter :: condition_displacement = 2
    integer, parameter :: condition_mixed_us_sn = 3
    integer, parameter :: condition_mixed_ss_un = 4
    integer, parameter :: condition_contact = 5
    !> Kinematic DDs: bc_s, bc_n are Ds, Dn themselves (docs/theory/kernels.md#element-conditions)
    integer, parameter :: condition_prescribed_dd = 6
    !> A rate-and-state fault element of an earthquake-cycle run (docs/theory/cycles.md)
    integer, parameter :: condition_rate_state = 7
    !> Input names of the conditions, indexed by condition code
    character(len=*), parameter :: condition_names(7) = [character(len=13) :: &
        'traction', 'displacement', 'mixed_us_sn', 'mixed_ss_un', 'contact', 'prescribed_dd', &
        'rate_state']

    !> Elastic domain: the full plane, the half-plane y < 0 with a free surface y = 0, or two
    !> bonded half-planes of different materials (docs/theory/bimaterial.md)
    integer, parameter :: domain_full_plane = 1, domain_half_plane = 2, domain_bimaterial = 3
    !> Input names of the domains, indexed by domain
    character(len=*), parameter :: domain_names(3) = [character(len=10) :: &
        'full_plane', 'half_plane', 'bimaterial']

    !> Block size of the distributed matrices of the MPI build (&solver block_size)
    integer, parameter :: default_block_size = 64

    !> Kinds of observation sets
    integer, parameter :: observation_grid = 1
    integer, parameter :: observation_line = 2
    integer, parameter :: observation_points = 3
    !> Names of the observation kinds, indexed by kind
    character(len=*), parameter :: observation_kind_names(3) = [character(len=6) :: &
        'grid', 'line', 'points']

    !> TWODD's symmetry conditions (KSYM 1-4): the model is mirrored about the line
    !> x = xsym (symmetry_x), y = ysym (symmetry_y) or both; image elements are implicit.
    integer, parameter :: symmetry_none = 1, symmetry_x = 2, symmetry_y = 3, symmetry_both = 4
    !> Input names of the symmetry kinds, indexed by kind
    character(len=*), parameter :: symmetry_names(4) = [character(len=4) :: &
        'none', 'x', 'y', 'both']

    !> Symmetry of the model (TWODD KSYM and its lines).
    type :: symmetry_options
        !> symmetry_none, symmetry_x (about x = xsym), symmetry_y (about y = ysym), both
        integer :: kind = symmetry_none
        !> Position of the symmetry lines [length unit]
        real(wp) :: xsym = 0.0_wp, ysym = 0.0_wp
    end type symmetry_options

    !> All boundary elements of the model, shape (n) for every array.
    type :: element_set
        !> Number of elements
        integer :: n = 0
        !> End points [length unit]
        real(wp), allocatable :: x_begin(:), y_begin(:), x_end(:), y_end(:)
        !> Index of the fracture each element belongs to (1-based)
        integer, allocatable :: fracture_id(:)
        !> Boundary condition code (condition_traction ... condition_contact)
        integer, allocatable :: condition(:)
        !> Given shear and normal value for TWODD-style conditions
        !> [stress unit for tractions, length unit for displacements]
        real(wp), allocatable :: bc_s(:), bc_n(:)
        !> Friction coefficient [-], cohesion (frictional strength) [stress unit],
        !> internal fluid pressure [stress unit], for contact elements
        real(wp), allocatable :: mu(:), sf(:), pressure(:)
        !> Fault strength beyond Coulomb, for contact elements: tensile strength T >= 0
        !> [stress unit] (lost once the element opens) and the cohesion after the element
        !> first slipped [stress unit]; the cohesion in force after slip is
        !> min(sf, sf_residual) (no_residual_drop: no drop)
        real(wp), allocatable :: tensile_strength(:), sf_residual(:)
        !> Slip weakening, for contact elements: friction falls linearly from mu to
        !> min(mu, mu_dynamic) [-] as the slip grows from 0 to slip_weakening_distance d_c
        !> >= 0 [length unit] (no_residual_drop: no drop; d_c = 0: at once)
        real(wp), allocatable :: mu_dynamic(:), slip_weakening_distance(:)
        !> Opening weakening, for contact elements: the tensile strength falls linearly to 0
        !> as the opening grows from 0 to opening_weakening_distance d_o >= 0 [length unit]
        !> (0: lost at once when the element opens)
        real(wp), allocatable :: opening_weakening_distance(:)
        !> Elastic joint, for contact elements: shear and normal stiffness [stress unit /
        !> length unit] of the faces before they slip or open (rigid_joint: rigid contact)
        real(wp), allocatable :: shear_stiffness(:), normal_stiffness(:)
        !> Rate-and-state elements (ddc_model_rate_state; 0 on other elements): a, b [-], the
        !> characteristic slip dc [length unit], f0 [-], v0 and the initial slip rate v_init
        !> [length unit / time unit], the initial effective normal stress sigma0 (compression
        !> positive) and shear traction tau0 [stress unit]
        real(wp), allocatable :: rs_a(:), rs_b(:), rs_dc(:), rs_f0(:), rs_v0(:), rs_v_init(:), &
            rs_sigma0(:), rs_tau0(:)
        !> Flow along the fractures (docs/injection.md): hydraulic diffusivity alpha [length^2 /
        !> time unit] and transmissivity T [length^3 / (stress unit time unit)]; 0: the
        !> element does not conduct
        real(wp), allocatable :: diffusivity(:), transmissivity(:)
        !> Flow coupled to opening (&fluid; docs/fluid-driven-fractures.md): the aperture of
        !> the closed faces, through which fluid flows and where it is stored [length unit];
        !> 0: the element does not conduct
        real(wp), allocatable :: residual_aperture(:)
        !> The pressure change that diffused into the element from the fluid sources by the
        !> current time [stress unit] (0 without sources; a contact element's pore pressure
        !> rises by it); a new element of a growth run takes its tip element's
        real(wp), allocatable :: flow_pressure(:)
        !> Derived geometry: midpoint, half-length [length unit], cos and sin of the
        !> element angle beta (counter-clockwise from +x)
        real(wp), allocatable :: x_mid(:), y_mid(:), half_length(:)
        real(wp), allocatable :: cos_beta(:), sin_beta(:)
        !> Symmetry lines whose implicit image elements every influence sum includes (set by
        !> the input readers; none by default)
        type(symmetry_options) :: symmetry
        !> domain_full_plane, domain_half_plane or domain_bimaterial: the kernel of every
        !> influence sum
        integer :: domain = domain_full_plane
    end type element_set

    !> What a routine does with every per-element array of an element_set: it extends
    !> this type with its data and is handed each array by for_each_element_array.
    type, abstract :: element_array_action
    contains
        !> Act on one real per-element array
        procedure(act_on_reals), deferred :: on_reals
        !> Act on one integer per-element array
        procedure(act_on_integers), deferred :: on_integers
        !> Act on one real per-element array added later whose default 0 leaves the model as
        !> it was (a strength law, the hydraulic properties, the rate-and-state values;
        !> on_reals unless the action says otherwise)
        procedure :: on_later_law => act_on_later_law
    end type element_array_action

    abstract interface
        !> Act on one real per-element array, shape (n) or unallocated
        subroutine act_on_reals(action, values)
            import :: element_array_action, wp
            implicit none
            !> The action and its data
            class(element_array_action), intent(inout) :: action
            !> The array
            real(wp), allocatable, intent(inout) :: values(:)
        end subroutine act_on_reals

        !> Act on one integer per-element array, shape (n) or unallocated
        subroutine act_on_integers(action, values)
            import :: element_array_action
            implicit none
            !> The action and its data
            class(element_array_action), intent(inout) :: action
            !> The array
            integer, allocatable, intent(inout) :: values(:)
        end subroutine act_on_integers
    end interface

    !> Element j of the selected set is element pick(j) of the source (select_elements).
    type, extends(element_array_action) :: element_selection
        !> The source element of each selected element, shape (selected n)
        integer, allocatable :: pick(:)
    contains
        procedure :: on_reals => select_reals
        procedure :: on_integers => select_integers
    end type element_selection

    !> One fracture: a name and its contiguous range of elements.
    type :: fracture_type
        !> Name given by the user (or fracture_<k>)
        character(len=:), allocatable :: name
        !> First and last element index of this fracture
        integer :: first_element = 0, last_element = -1
    end type fracture_type

    !> A set of observation points: a regular grid, a line or a list.
    type :: observation_set
        !> Name given by the user; the HDF5 group under /fields
        character(len=:), allocatable :: name
        !> observation_grid, observation_line or observation_points
        integer :: kind = observation_points
        !> Grid shape (nx, ny); a line or list has ny = 1
        integer :: nx = 0, ny = 1
        !> Point coordinates [length unit], shape (nx*ny), x varying fastest on a grid
        real(wp), allocatable :: x(:), y(:)
    end type observation_set

    !> The task of a parameter sweep a model is (docs/sweeps-and-slurm.md), stored in its output.
    type :: sweep_task_record
        !> Task number, 0-based; -1 when the model is not a sweep task
        integer :: task = -1
        !> Number of tasks of the sweep; 0 when the model is not a sweep task
        integer :: tasks = 0
        !> Parameter names as written in &sweep, shape (number of parameters)
        character(len=64), allocatable :: names(:)
        !> The task's value of each parameter, shape (number of parameters)
        real(wp), allocatable :: values(:)
    end type sweep_task_record

    !> Names of the quantities a loading history varies (docs/theory/earth.md#loading-histories), in
    !> the order of load_path_type%vertex: remote stress, its gradients d/dy, pore pressure p0
    character(len=*), parameter :: load_path_names(7) = [character(len=7) :: &
        'sxx', 'syy', 'sxy', 'dsxx_dy', 'dsyy_dy', 'dsxy_dy', 'p0']

    !> Kinds of fluid source (&injection): a pressure change held at a point, a volume rate
    !> into the network at a point
    integer, parameter :: source_overpressure = 1, source_rate = 2

    !> A fluid source at a point of a fracture (&injection; docs/injection.md).
    type :: injection_source
        !> Name given by the user, or injection_<k>
        character(len=:), allocatable :: name
        !> The fracture (1-based) and the point on it [length unit]
        integer :: fracture_id = 0
        real(wp) :: x = 0.0_wp, y = 0.0_wp
        !> source_overpressure or source_rate
        integer :: kind = source_rate
        !> The pressure change held [stress unit], or the rate per unit length out of the
        !> plane [length^2 / time unit] (negative: production)
        real(wp) :: value = 0.0_wp
        !> When it acts [time unit]: from start (default: the path's first time) until stop
        !> (default: never stops; a stopped source is shut in: no flux at its point)
        real(wp) :: start = -huge(1.0_wp), stop = huge(1.0_wp)
    end type injection_source

    !> The fluid that flows through the fractures it opens (&fluid;
    !> docs/fluid-driven-fractures.md): with it the sources' pressure follows lubrication
    !> flow coupled to the opening instead of diffusing on fixed fractures.
    type :: fluid_options
        !> The model has &fluid
        logical :: active = .false.
        !> Dynamic viscosity [stress unit time unit], compressibility [1 / stress unit] and
        !> Carter's leak-off coefficient [length unit / time unit^(1/2)] (0: no leak-off)
        real(wp) :: viscosity = 0.0_wp, compressibility = 0.0_wp, leak_off_coefficient = 0.0_wp
    end type fluid_options

    !> A loading history (&load_path; docs/theory/earth.md#loading-histories): the load at the
    !> path's vertices (the first is the starting state) and the increments on each leg.
    type :: load_path_type
        !> The load at each vertex, rows in the order of load_path_names (quantities not
        !> given in &load_path hold the model's fixed value), shape (7, vertices)
        !> [stress unit; stress unit / length unit for the gradients]
        real(wp), allocatable :: vertex(:, :)
        !> Number of increments on each leg, shape (vertices - 1)
        integer, allocatable :: steps(:)
        !> The time of each vertex, strictly increasing [time unit], shape (vertices); not
        !> allocated when the path has no time axis (its steps spaced evenly on each leg)
        real(wp), allocatable :: time(:)
        !> Which quantities were given per vertex, shape (7)
        logical :: varies(7) = .false.
    end type load_path_type

    !> Which critical tips grow in a step (&growth tips): every one, or only the most
    !> critical
    integer, parameter :: growth_tips_all = 1, growth_tips_most_critical = 2
    !> Input names of the tip choices, indexed by choice
    character(len=*), parameter :: growth_tips_names(2) = [character(len=13) :: &
        'all', 'most_critical']
    !> Growth criteria: maximum tangential stress (Erdogan & Sih 1963); the largest external
    !> work per unit of new fracture (docs/theory/growth.md#the-work-criterion)
    integer, parameter :: growth_criterion_mts = 1, growth_criterion_work = 2
    !> Input names of the criteria, indexed by criterion
    character(len=*), parameter :: growth_criterion_names(2) = [character(len=4) :: 'mts', &
        'work']
    !> Which trials of the work criterion are candidates (&growth work_mode): those whose new
    !> elements open or slip, or only those whose new elements open
    integer, parameter :: work_mode_any = 1, work_mode_opening = 2
    character(len=*), parameter :: work_mode_names(2) = [character(len=7) :: 'any', 'opening']
    !> How the work criterion searches a tip's angles (&growth angle_search): from the
    !> kinked-crack estimate of the best angle (docs/theory/growth.md#the-work-criterion), or
    !> every trial angle of the range
    integer, parameter :: angle_search_seeded = 1, angle_search_grid = 2
    character(len=*), parameter :: angle_search_names(2) = [character(len=6) :: 'seeded', &
        'grid']
    !> Number of the strength laws beyond Coulomb, the per-element arrays of element_set that
    !> for_each_law (ddc_model_laws) lists; the CTest architecture holds the two equal
    integer, parameter :: strength_law_count = 7

    !> Fracture growth (&growth; docs/theory/growth.md#the-growth-step): quasi-static, one increment
    !> per step.
    type :: growth_options
        !> The model grows its fractures (a &growth group was given)
        logical :: active = .false.
        !> Largest number of growth steps
        integer :: steps = 0
        !> Fracture toughness K_Ic [stress unit * length unit**0.5]
        real(wp) :: toughness = 0.0_wp
        !> Growth length per step [length unit]; 0: twice the tip element's length
        real(wp) :: increment = 0.0_wp
        !> Length of new elements [length unit]; 0: the tip element's length
        real(wp) :: element_length = 0.0_wp
        !> growth_tips_all or growth_tips_most_critical
        integer :: tips = growth_tips_all
        !> growth_criterion_mts or growth_criterion_work
        integer :: criterion = growth_criterion_mts
        !> The work criterion: trial kinks from -angle_range to +angle_range about the tip's
        !> direction every angle_step [degree]; a tip grows when its efficiency reaches
        !> work_threshold [stress unit * length unit] (default 2 K_Ic^2 (1 - nu^2) / E)
        real(wp) :: angle_range = 90.0_wp, angle_step = 5.0_wp, work_threshold = 0.0_wp
        !> work_mode_any or work_mode_opening; angle_search_seeded or angle_search_grid
        integer :: work_mode = work_mode_any, angle_search = angle_search_seeded
        !> Largest number of solves of the local-symmetry corrector per step (0: no
        !> corrector, tips grow at the MTS angle)
        integer :: max_corrections = 8
        !> Whether the tips of each fracture may grow, shape (fractures)
        logical, allocatable :: fracture_grows(:)
        !> New contact elements take new_mu, new_sf instead of the tip element's values
        logical :: override_mu = .false., override_sf = .false.
        !> Friction [-] and cohesion [stress unit] of new contact elements, when overridden
        real(wp) :: new_mu = 0.0_wp, new_sf = 0.0_wp
        !> New contact elements take new_law(k) for strength law k of for_each_law
        !> (ddc_model_laws; the &growth variable new_<name>) where override_law(k), instead of
        !> the tip element's given value
        logical :: override_law(strength_law_count) = .false.
        real(wp) :: new_law(strength_law_count) = 0.0_wp
    end type growth_options

    !> New fractures inside the rock (&initiation;
    !> docs/fracture-growth.md#new-fractures-inside-the-rock): tails beside contact elements
    !> and cracks at flaw points, where the maximum tension reaches the rock's tensile
    !> strength.
    type :: initiation_options
        !> The model starts new fractures (an &initiation group was given)
        logical :: active = .false.
        !> Tensile strength T0 of the rock [stress unit]
        real(wp) :: tensile_strength = 0.0_wp
        !> Distance of the probe points from the elements' ends [length unit]
        real(wp) :: probe_distance = 0.0_wp
        !> Length of a flaw's first crack [length unit]; 0: the growth increment
        real(wp) :: flaw_length = 0.0_wp
        !> Flaw points [length unit], shape (flaws)
        real(wp), allocatable :: flaw_x(:), flaw_y(:)
    end type initiation_options

    !> A complete model, independent of the input format it came from.
    type :: model_type
        !> Title of the model
        character(len=:), allocatable :: title
        !> Young's modulus [stress unit] and Poisson's ratio [-] (of the lower material in two
        !> bonded half-planes)
        real(wp) :: youngs_modulus = 0.0_wp, poissons_ratio = 0.0_wp
        !> Two bonded half-planes (elements%domain == domain_bimaterial): the material above
        !> the interface y = interface_y [length unit], its Young's modulus [stress unit]
        !> and Poisson's ratio [-]
        real(wp) :: interface_y = 0.0_wp
        real(wp) :: upper_youngs_modulus = 0.0_wp, upper_poissons_ratio = 0.0_wp
        !> Unit names, stored in the output (labels only: ddc2d converts nothing)
        character(len=:), allocatable :: length_unit, stress_unit, time_unit
        !> Remote stress, tension positive [stress unit]
        real(wp) :: sxx = 0.0_wp, syy = 0.0_wp, sxy = 0.0_wp
        !> Remote stress gradients d(sxx, syy, sxy)/dy [stress unit / length unit]:
        !> the remote stress at depth y is (sxx, syy, sxy) + y * stress_gradient
        real(wp) :: stress_gradient(3) = 0.0_wp
        !> Pore fluid pressure p0 [stress unit] and dp/dy [stress unit / length unit],
        !> compression positive; already added to elements%pressure of contact elements
        real(wp) :: pore_fluid(2) = 0.0_wp
        !> The boundary elements
        type(element_set) :: elements
        !> The fractures, in element order
        type(fracture_type), allocatable :: fractures(:)
        !> The finite body the fractures lie in (&body); unallocated for an infinite plane
        type(finite_body), allocatable :: body
        !> Observation sets for field output
        type(observation_set), allocatable :: observations(:)
        !> Solver options
        type(solver_options) :: solver
        !> Rows and columns of the blocks of the block-cyclic distributed matrices (MPI
        !> build; &solver block_size)
        integer :: block_size = default_block_size
        !> Output file (after -o and &output are applied)
        character(len=:), allocatable :: output_file
        !> Input file path and its full text, kept for self-description
        character(len=:), allocatable :: input_file, input_text
        !> The sweep task this model is, when it is one
        type(sweep_task_record) :: sweep
        !> Loading history; vertex not allocated when the model has none (one state)
        type(load_path_type) :: load_path
        !> Fluid sources on the fractures (&injection; none: allocated with size 0 or not
        !> allocated)
        type(injection_source), allocatable :: injections(:)
        !> The fluid of coupled flow (&fluid); inactive without the group
        type(fluid_options) :: fluid
        !> Fracture growth; inactive unless the input has &growth
        type(growth_options) :: growth
        !> New fractures inside the rock, when it grows
        type(initiation_options) :: initiation
        !> Earthquake cycles on its rate-and-state elements; inactive unless the input has
        !> &cycle
        type(cycle_options) :: cycle
        !> Fingerprint of the model as read (ddc_model_fingerprint), recorded by app before
        !> a run changes the model (growth adds elements); unallocated until then
        character(len=:), allocatable :: fingerprint
        !> The result file a resumed run (--resume) continues, and when that file was
        !> written; unallocated for a run that continues none
        character(len=:), allocatable :: resumed_from, resumed_from_created
    end type model_type

contains

    !> x and y of end `side` (1 begin, 2 end) of element i.
    pure subroutine element_end(elements, i, side, x, y)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Element and end (1 begin, 2 end)
        integer, intent(in) :: i, side
        !> The end point [length unit]
        real(wp), intent(out) :: x, y

        if (side == 1) then
            x = elements%x_begin(i)
            y = elements%y_begin(i)
        else
            x = elements%x_end(i)
            y = elements%y_end(i)
        end if
    end subroutine element_end

    !> Whether a model has fluid sources (&injection).
    pure logical function has_sources(model)
        !> The model
        type(model_type), intent(in) :: model

        has_sources = .false.
        if (allocated(model%injections)) has_sources = size(model%injections) > 0
    end function has_sources

    !> A real per-element array of a law added later: by default like any other.
    subroutine act_on_later_law(action, values)
        !> The action and its data
        class(element_array_action), intent(inout) :: action
        !> The array, shape (n) or unallocated
        real(wp), allocatable, intent(inout) :: values(:)

        call action%on_reals(values)
    end subroutine act_on_later_law

    !> The one list of the per-element arrays of an element_set: the action gets each
    !> array once, in this order (the MPI broadcast relies on the order being the same on
    !> every process). A new per-element array is declared in the type and listed here;
    !> the CTest architecture fails when an array component is missing.
    subroutine for_each_element_array(elements, action)
        !> The set whose arrays the action gets
        type(element_set), intent(inout) :: elements
        !> What to do with each array
        class(element_array_action), intent(inout) :: action

        call action%on_reals(elements%x_begin)
        call action%on_reals(elements%y_begin)
        call action%on_reals(elements%x_end)
        call action%on_reals(elements%y_end)
        call action%on_integers(elements%fracture_id)
        call action%on_integers(elements%condition)
        call action%on_reals(elements%bc_s)
        call action%on_reals(elements%bc_n)
        call action%on_reals(elements%mu)
        call action%on_reals(elements%sf)
        call action%on_reals(elements%pressure)
        call action%on_reals(elements%tensile_strength)
        call action%on_reals(elements%sf_residual)
        call action%on_reals(elements%mu_dynamic)
        call action%on_reals(elements%slip_weakening_distance)
        call action%on_later_law(elements%opening_weakening_distance)
        call action%on_reals(elements%shear_stiffness)
        call action%on_reals(elements%normal_stiffness)
        call action%on_later_law(elements%rs_a)
        call action%on_later_law(elements%rs_b)
        call action%on_later_law(elements%rs_dc)
        call action%on_later_law(elements%rs_f0)
        call action%on_later_law(elements%rs_v0)
        call action%on_later_law(elements%rs_v_init)
        call action%on_later_law(elements%rs_sigma0)
        call action%on_later_law(elements%rs_tau0)
        call action%on_later_law(elements%diffusivity)
        call action%on_later_law(elements%transmissivity)
        call action%on_later_law(elements%flow_pressure)
        call action%on_later_law(elements%residual_aperture)
        call action%on_reals(elements%x_mid)
        call action%on_reals(elements%y_mid)
        call action%on_reals(elements%half_length)
        call action%on_reals(elements%cos_beta)
        call action%on_reals(elements%sin_beta)
    end subroutine for_each_element_array

    !> The set whose element j is element pick(j) of source: every per-element value, and
    !> the source's symmetry and domain. Values are copied, never recomputed.
    subroutine select_elements(source, pick, selected)
        !> The elements to select from
        type(element_set), intent(in) :: source
        !> Index in source of each selected element (repeats allowed), shape (selected n)
        integer, intent(in) :: pick(:)
        !> The selected elements
        type(element_set), intent(out) :: selected
        type(element_selection) :: selection

        selected = source
        selected%n = size(pick)
        selection%pick = pick
        call for_each_element_array(selected, selection)
    end subroutine select_elements

    !> Replace a real array (when allocated) by its picked elements.
    subroutine select_reals(action, values)
        !> The selection
        class(element_selection), intent(inout) :: action
        !> The array
        real(wp), allocatable, intent(inout) :: values(:)

        if (allocated(values)) values = values(action%pick)
    end subroutine select_reals

    !> Replace an integer array (when allocated) by its picked elements.
    subroutine select_integers(action, values)
        !> The selection
        class(element_selection), intent(inout) :: action
        !> The array
        integer, allocatable, intent(inout) :: values(:)

        if (allocated(values)) values = values(action%pick)
    end subroutine select_integers

end module ddc_model_types
