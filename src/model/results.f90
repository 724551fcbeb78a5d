!> Results of a solve: element values, tips, fields and the solver record.
module ddc_model_results
    use ddc_kinds, only: wp
    use ddc_contact_states, only: state_stick, state_slip, state_open
    use ddc_contact_counts, only: factor_counts
    use ddc_model_initiations, only: initiation_record
    use ddc_model_trial_records, only: trial_records
    use ddc_model_cycles, only: cycle_record
    implicit none
    private

    public :: element_results, tip_set, field_result, solver_record, model_results
    public :: boundary_results
    public :: history_record, tip_records, growth_record
    public :: growth_grew, growth_subcritical, growth_intersection, growth_surface, &
        growth_corrector_failed, growth_linked, growth_closed, growth_waiting, &
        growth_enclosing, growth_interface, growth_reason_names
    public :: growth_arrested, growth_step_limit, growth_failed, growth_end_names
    public :: trial_stuck, trial_slipping, trial_opening, trial_blocked, trial_state_coding
    public :: state_free, state_stick, state_slip, state_open, state_names, state_not_grown
    public :: point_clear, point_near, point_on_element, point_outside_body

    !> Element states; free = a TWODD-style condition, not a contact element
    !> (stick, slip and open are the contact solvers' codes, ddc_contact_states)
    integer, parameter :: state_free = 0
    !> The state a growth run's history records for an element before it was made
    integer, parameter :: state_not_grown = -1
    !> Names of the states, indexed by state + 1
    character(len=*), parameter :: state_names(0:3) = [character(len=5) :: &
        'free', 'stick', 'slip', 'open']

    !> Observation point flags: clear of every element; within one element length of an
    !> element centre (TWODD skips these; accuracy reduced); on an element or at its end
    !> (field discontinuous or singular there: values are NaN); outside a finite body or on
    !> its boundary (no rock: NaN)
    integer, parameter :: point_clear = 0, point_near = 1, point_on_element = 2
    integer, parameter :: point_outside_body = 3

    !> Why a tip did or did not grow in a growth step
    !> (docs/theory/growth.md#why-a-tip-does-not-grow): it grew (the corrector converged, or is
    !> switched off); it is subcritical (K_eq < toughness); it stopped for good next to another
    !> element; it broke through the free surface and stopped there; it grew at the MTS angle
    !> because the corrector did not converge; it ended on another fracture (linked:
    !> docs/theory/growth.md#linking-and-stops); its kink closes (K_I = 0 on the new tip: it does
    !> not grow in this step); it is critical but waits (tips = 'most_critical' and another tip
    !> is more critical); it stopped for good because linking to the fracture its path meets
    !> would enclose a block (the two are connected already); it stopped for good before the
    !> interface of two bonded half-planes (its path would cross it or come close)
    integer, parameter :: growth_grew = 0, growth_subcritical = 1, growth_intersection = 2, &
                          growth_surface = 3, growth_corrector_failed = 4, growth_linked = 5, &
                          growth_closed = 6, growth_waiting = 7, growth_enclosing = 8, &
                          growth_interface = 9
    !> Names of the reasons, indexed by reason
    character(len=*), parameter :: growth_reason_names(0:9) = [character(len=48) :: &
        'grew', 'subcritical', 'intersection', 'surface', &
        'corrector failed (grew at mts_angle)', 'linked (ends on another fracture)', &
        'closed (the kink closes, K_I = 0)', 'waiting (critical, not the most critical)', &
        'enclosing (a link would enclose a block)', 'interface (stopped before it)']
    !> Why a growth run ended: no tip can grow any more, the step limit was reached, or the
    !> solve of a step failed (the run stopped before it: exit_stopped_early)
    integer, parameter :: growth_arrested = 1, growth_step_limit = 2, growth_failed = 3
    !> State of a work criterion trial's new elements: none opens or slips (no candidate); some
    !> slip, none opens; some open; the trial's path does not keep clear of the other elements
    !> (not solved, no candidate)
    integer, parameter :: trial_stuck = 0, trial_slipping = 1, trial_opening = 2, &
                          trial_blocked = 3
    !> The coding of the trial states, as the result file states it
    character(len=*), parameter :: trial_state_coding = &
        '0 stuck (no candidate), 1 slipping, 2 opening, 3 blocked (the path does not keep '// &
        'clear; not solved)'
    !> Names of the end reasons, indexed by end reason
    character(len=*), parameter :: growth_end_names(3) = [character(len=10) :: &
        'arrested', 'step_limit', 'failed']

    !> Per-element results, shape (n) for every array.
    type :: element_results
        !> Displacement discontinuities, Crouch & Starfield signs [length unit]
        real(wp), allocatable :: ds(:), dn(:)
        !> Total shear and normal traction, tension positive [stress unit]
        real(wp), allocatable :: shear_traction(:), normal_traction(:)
        !> Displacement of the negative and positive face at the midpoint, in the element's
        !> s and n directions [length unit]
        real(wp), allocatable :: us_minus(:), un_minus(:), us_plus(:), un_plus(:)
        !> Element state (state_free ... state_open)
        integer, allocatable :: state(:)
        !> Strength in force at the end: cohesion and tensile strength (after the drops
        !> of slipped and opened elements; 0 for TWODD-style elements) [stress unit];
        !> not allocated for a model without contact elements
        real(wp), allocatable :: sf_in_force(:), tensile_in_force(:)
        !> Friction in force at the end (slip weakening; 0 for TWODD-style elements) [-]
        real(wp), allocatable :: mu_in_force(:)
        !> Elastic part of the DDs of elastic joints, -traction / stiffness (0 for rigid
        !> contact and TWODD-style elements; the plastic part is ds - ds_elastic) [length
        !> unit]; not allocated for a model without joints
        real(wp), allocatable :: ds_elastic(:), dn_elastic(:)
        !> Slip of the model with the K re-solve's higher-order zones at the end of a
        !> history (its own friction memory, which --resume restores: the steps' slip off
        !> the contact elements) [length unit]; allocated where the re-solve was coupled
        real(wp), allocatable :: ds_k_memory(:)
    end type element_results

    !> Crack tips: element ends shared with no other element.
    type :: tip_set
        !> Number of tips
        integer :: n = 0
        !> Tip position [length unit]
        real(wp), allocatable :: x(:), y(:)
        !> Fracture and element of the tip (1-based)
        integer, allocatable :: fracture_id(:), element(:)
        !> Stress intensity factors [stress unit * length unit**0.5]
        real(wp), allocatable :: k1(:), k2(:)
        !> 1 when an element of the tip's zone differs in length from the tip element by more
        !> than 1 % (ddc_post_tips)
        !> (the K formula assumes equal elements: K is less accurate there), else 0
        integer, allocatable :: graded(:)
        !> The end of its element the tip is: 1 begin, 2 end
        integer, allocatable :: side(:)
        !> How K was computed: 'higher_order' or 'tip_element', with the reason where the
        !> tip element serves a model that asked for the other
        character(len=:), allocatable :: k_method
    end type tip_set

    !> Displacement and stress at the points of one observation set, shape (npoints).
    type :: field_result
        !> Displacement relative to the far field [length unit]
        real(wp), allocatable :: ux(:), uy(:)
        !> Total stress (remote plus induced), tension positive [stress unit]
        real(wp), allocatable :: sxx(:), syy(:), sxy(:)
        !> point_clear, point_near, point_on_element or point_outside_body
        integer, allocatable :: flag(:)
    end type field_result

    !> What the solver did and how long it took.
    type :: solver_record
        !> Method used for the elastic or contact solve ('lu', 'lemke' or 'newton')
        character(len=:), allocatable :: method
        !> Why the 'newton' contact method fell back to Lemke ('' when it did not)
        character(len=:), allocatable :: fallback
        !> Newton (active-set) iterations summed over contact solves
        integer :: newton_iterations = 0
        !> The Newton method's reduced systems: new LU factorizations, low-rank updates of a
        !> factorization, and solves with unchanged factors (states unchanged); the wall time
        !> of every factorization of the run (the phase 'factorization') [s] and the nominal
        !> flops of the timed factorizations (2/3 m^3 per LU of size m) [-]
        type(factor_counts) :: counts
        !> Number of OpenMP threads (of each process)
        integer :: threads = 1
        !> MPI build: the processes of the run (0 in the serial build), their grid (rows,
        !> columns) and the block size of the distributed matrices
        integer :: processes = 0, process_grid(2) = 0, block_size = 0
        !> LCP pivots summed over LCP solves, and the number of LCP solves (more than one
        !> when open_cohesion = 'lost' re-solves); 0 without contact elements
        integer :: pivots = 0, lcp_solves = 0
        !> Relative residual of the recovered DDs against the unfactored system
        real(wp) :: equilibrium_residual = 0.0_wp
        !> A hierarchical matrix solved the model (docs/theory/hierarchical.md): its reals
        !> over those of the dense matrix, and the accuracy asked of its compressed blocks
        logical :: hierarchical = .false.
        real(wp) :: compression_ratio = 1.0_wp, hmatrix_tolerance = 0.0_wp
        !> LCP certificate of the last solve, each scaled by its block's magnitude:
        !> min z, min w (>= -tolerance) and max |z_i w_i| (<= tolerance)
        real(wp) :: certificate_min_z = 0.0_wp, certificate_min_w = 0.0_wp
        real(wp) :: certificate_max_complementarity = 0.0_wp, certificate_tolerance = 0.0_wp
        !> Wall time of each phase but the factorization (counts%seconds) [s]
        real(wp) :: seconds_assembly = 0.0_wp
        real(wp) :: seconds_lcp = 0.0_wp, seconds_fields = 0.0_wp
        real(wp) :: seconds_output = 0.0_wp, seconds_total = 0.0_wp
    end type solver_record

    !> Every step of a loading history (docs/loading-histories.md#output); k steps (the starting
    !> state is step 1), n elements. Not allocated when the model has no load path. Its columns are
    !> listed in ddc_model_records' for_each_history_column.
    type :: history_record
        !> The load of each step, rows as ddc_model_types' load_path_names (remote stress,
        !> its gradients d/dy, pore pressure p0), shape (7, k)
        real(wp), allocatable :: load(:, :)
        !> Total DDs at the end of each step [length unit], shape (n, k)
        real(wp), allocatable :: ds(:, :), dn(:, :)
        !> Element state at the end of each step, shape (n, k)
        integer, allocatable :: state(:, :)
        !> Lemke pivots of each step (0: the previous step's basis was still feasible, or
        !> the Newton method solved it) and Newton iterations of each step, shape (k)
        integer, allocatable :: pivots(:), newton_iterations(:)
        !> The method that solved each step ('lemke' or 'newton') and why the other one
        !> failed first (empty when it did not), shape (k)
        character(len=6), allocatable :: method(:)
        character(len=256), allocatable :: fallback(:)
        !> Total shear and normal traction at the end of each step, tension positive
        !> [stress unit], shape (n, k)
        real(wp), allocatable :: shear_traction(:, :), normal_traction(:, :)
        !> Stress intensity factors of each tip (the tips of /tips) at the end of each step
        !> [stress unit * length unit**0.5], shape (tips, k)
        real(wp), allocatable :: k1(:, :), k2(:, :)
        !> Certificate of each step (scaled min z, min w, max |z w|) and the relative
        !> equilibrium residual, shape (k) [-]
        real(wp), allocatable :: certificate_min_z(:), certificate_min_w(:)
        real(wp), allocatable :: certificate_max_complementarity(:), equilibrium_residual(:)
        !> The strengths in force at the end of each step, where they can change (a law
        !> beyond Coulomb's or open_cohesion = 'lost'; not allocated otherwise): friction
        !> [-], cohesion and tensile strength [stress unit] (0 for TWODD-style elements),
        !> shape (n, k)
        real(wp), allocatable :: mu_in_force(:, :), sf_in_force(:, :), &
            tensile_strength_in_force(:, :)
        !> With fracture growth (docs/theory/growth.md#growth-along-a-loading-history; not
        !> allocated otherwise): the rows of the element arrays are the final geometry's
        !> elements (NaN, state_not_grown before an element was made); the number of elements at
        !> the end of each step, shape (k); the fracture and end (0 begin, 1 end) of every tip
        !> that may grow, shape (tips); the length each has grown by the end of each step
        !> [length unit], shape (tips, k)
        integer, allocatable :: element_count(:), tip_fracture_id(:), tip_end(:)
        real(wp), allocatable :: grown_length(:, :)
        !> The time of each step, where the path has a time axis [time unit], shape (k)
        real(wp), allocatable :: time(:)
        !> With fluid sources (docs/injection.md#output; not allocated otherwise): the
        !> pressure change that diffused into each element [stress unit], shape (n, k); the
        !> volume injected by then, per unit length out of the plane [length^2], shape (k);
        !> of each fracture, the length of its slipping elements, where its slipping patch
        !> begins and ends (arc length from its first vertex to the outer ends of its
        !> outermost slipping elements; NaN when none slips) [length unit], and its seismic
        !> moment per unit length out of the plane (G times its slip's integral) [stress unit
        !> length unit], shape (fractures, k)
        real(wp), allocatable :: pressure(:, :), injected_volume(:)
        !> With coupled flow (&fluid; docs/fluid-driven-fractures.md#output; not allocated
        !> otherwise): the hydraulic aperture of each element (0 where it does not conduct)
        !> [length unit] and the flux along it at its midpoint (first vertex to last) [length^2
        !> / time unit], shape (n, k); the fluid stored beyond the start's and the volume
        !> leaked off by then [length^2], their ratio stored / injected, the iterations of
        !> the step's coupled solve and the volume it left unbalanced as a fraction of the
        !> injected volume, shape (k)
        real(wp), allocatable :: aperture(:, :), flux(:, :)
        real(wp), allocatable :: stored_volume(:), leaked_volume(:), fluid_efficiency(:)
        integer, allocatable :: flow_iterations(:)
        real(wp), allocatable :: flow_residual(:)
        real(wp), allocatable :: slipping_length(:, :), front_begin(:, :), front_end(:, :), &
            moment(:, :)
    end type history_record

    !> What each tip did in a growth step (docs/fracture-growth.md#output): one row per tip
    !> that could still grow, shape (k) for every array. A growth step's view of its tips
    !> (ddc_growth_run_state's step_tips) and a run's record (growth_record) are such rows; a
    !> new quantity is one component here and one line of ddc_model_records'
    !> for_each_tip_column, which lays out, appends, writes and reads every column.
    type :: tip_records
        !> Growth step, fracture (1-based) and end (0 begin tip, 1 end tip)
        integer, allocatable :: step(:), fracture_id(:), end(:)
        !> Load step of a loading history (1 without one)
        integer, allocatable :: load_step(:)
        !> Tip position before growing [length unit]
        real(wp), allocatable :: x(:), y(:)
        !> K_I, K_II of the tip and K_eq at the MTS angle (K_I taken as max(K_I, 0))
        !> [stress unit * length unit**0.5]
        real(wp), allocatable :: k1(:), k2(:), k_eq(:)
        !> MTS angle and applied angle, counter-clockwise from the tip's outward direction
        !> [degree] (applied: NaN when the tip did not grow)
        real(wp), allocatable :: mts_angle(:), angle(:)
        !> Solves of the local-symmetry corrector this tip took part in
        integer, allocatable :: corrections(:)
        !> K_II of the new tip on the grown geometry (NaN when the tip did not grow)
        !> [stress unit * length unit**0.5]
        real(wp), allocatable :: k2_after(:)
        !> Length grown [length unit] (0 when the tip did not grow)
        real(wp), allocatable :: length(:)
        !> growth_grew ... growth_waiting
        integer, allocatable :: reason(:)
        !> Criterion 'work' only: the efficiency dW_ext / dA at the applied angle (of the best
        !> trial; NaN when no trial opened or slipped) [stress unit * length unit]
        real(wp), allocatable :: efficiency(:)
        !> Criterion 'work' only: the share of that trial's work change done through the slip
        !> of frictional faces (new and old) [-] (NaN when no trial opened or slipped)
        real(wp), allocatable :: slip_share(:)
    end type tip_records

    !> A fracture growth run (docs/fracture-growth.md#output): one row per tip per step, in step
    !> order and within a step in the order of fractures, begin tip before end tip (k rows); not
    !> allocated when the model does not grow. Its columns are listed in ddc_model_records'
    !> for_each_growth_column.
    type, extends(tip_records) :: growth_record
        !> Criterion 'work' only, every trial (in /growth/trials); owner: the tip's record
        type(trial_records) :: trials
        !> Steps in which at least one tip grew
        integer :: steps_taken = 0
        !> growth_arrested, growth_step_limit or growth_failed
        integer :: end_reason = growth_arrested
        !> Why the step after the last one failed (growth_failed; else unallocated)
        character(len=:), allocatable :: failure
        !> Growth step that created each element of the final geometry (0: the input's),
        !> shape (n)
        integer, allocatable :: created_step(:)
    end type growth_record

    !> Everything a solve produces.
    !> A finite body's boundary after a solve: every node's displacement and traction along
    !> its side (s) and the outward normal (n), given or solved, and each side's net force.
    type :: boundary_results
        !> Node positions [length unit] and sides, shape (nodes)
        real(wp), allocatable :: x(:), y(:)
        integer, allocatable :: side(:)
        !> Displacement [length unit] and traction on the body [stress unit], shape (nodes)
        real(wp), allocatable :: us(:), un(:), ts(:), tn(:)
        !> Net force on each side, x and y [stress unit x length unit], shape (sides)
        real(wp), allocatable :: force_x(:), force_y(:)
    end type boundary_results

    type :: model_results
        type(element_results) :: elements
        type(tip_set) :: tips
        !> One per observation set of the model
        type(field_result), allocatable :: fields(:)
        type(solver_record) :: solver
        !> Every step of the loading history, when the model has one
        type(history_record) :: history
        !> Every step of fracture growth, when the model grows
        type(growth_record) :: growth
        !> The new fractures started inside the rock, when the model has &initiation
        type(initiation_record) :: initiations
        !> Earthquake cycles, when the model has &cycle (cycle%elements allocated)
        type(cycle_record) :: cycle
        !> The boundary of the finite body, when the model has one (x allocated)
        type(boundary_results) :: boundary
        !> Why a run that records its steps in /history alone (a hydraulic fracture) stopped
        !> before its end; not allocated when it ran to its end
        character(len=:), allocatable :: stopped
    end type model_results

end module ddc_model_results
