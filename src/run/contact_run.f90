!> The contact run (docs/ARCHITECTURE.md#the-contact-run): what every driver steps. It owns
!> the medium's elastic operator (dense, hierarchical or distributed: ddc_solve_operator),
!> the fault law of the contact elements with its values in force and the slip they hold,
!> elastic joints, the contact session the steps share (ddc_contact_formulation: the
!> Newton method's states and factors, Lemke's LCP and basis) and the K method.
!>
!> - prepare: once per geometry (assembly, condensation of the TWODD-style elements,
!>   compression or distribution of A, the joints' system);
!> - step: one equilibrium under a load (remote stress and fluid pressure), from the
!>   friction memory and strengths in force the steps before left;
!> - tip_k: the stress intensity factors of a step's DDs by the run's K method;
!> - finish: free what the run holds.
!> A one-shot solve is prepare + step; a loading history a loop of steps; growth solves
!> each grown geometry on a run of its own, with the memory carried over (hold). What a run
!> cannot do with a model is answered once, by run_refusal (ddc_model_capabilities).
!>
!> A run is not copied: its operator points into memory the run owns.
module ddc_run_contact_run
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure
    use ddc_model_types, only: domain_bimaterial
    use ddc_model_medium, only: elastic_medium, upper_remote_stress
    use ddc_model_results, only: solver_record, state_free, tip_set, element_results
    use ddc_model_loads, only: resolve_remote_stress, total_pressure
    use ddc_contact_options, only: solver_options, matrix_hierarchical, lcp_newton
    use ddc_contact_result, only: contact_result, contact_stress_scale
    use ddc_contact_formulation, only: solve_contact_with, contact_session, contact_problem, &
        new_matrix
    use ddc_contact_fault_law, only: fault_law
    use ddc_solve_operator, only: elastic_operator, elastic_load, free_part
    use ddc_influence_body, only: body_load
    use ddc_solve_dense_operator, only: dense_operator, new_dense_operator
    use ddc_solve_hierarchical_operator, only: hierarchical_operator, &
        new_hierarchical_operator
    use ddc_model_element_laws, only: fault_law_of
    use ddc_solve_joints, only: joint_load, joint_dds
    use ddc_post_tips, only: stress_intensity
    use ddc_post_higher_order_k, only: higher_order_solver, prepare_higher_order, &
        higher_order_k, uses_higher_order, outer_correction
    use ddc_text, only: itoa, rtoa
    use ddc_linalg_anderson, only: anderson_mixer
    use ddc_contact_counts, only: factor_counts
    use ddc_contact_result, only: frictional_certificate
    use ddc_contact_certificate, only: lcp_certificate
    use ddc_run_coupled_k, only: coupled_solution, coupled_path
    implicit none
    private

    public :: contact_run, contact_step, load_of, record_contact

    !> The local re-solve's coupling to the elements outside its zones stops when K moves by
    !> less than this fraction of the largest |K| from one solve to the next, or when the
    !> traction it added gives itself back within this fraction of its largest value (the
    !> fixed point: a stuck fault's DDs do not answer it at all), or fails after
    !> max_coupling_solves solves
    real(wp), parameter :: coupling_tolerance = 1.0e-8_wp
    integer, parameter :: max_coupling_solves = 60

    !> The solution of one step.
    type :: contact_step
        !> Displacement discontinuities of every element [length unit], shape (n)
        real(wp), allocatable :: ds(:), dn(:)
        !> Element states (state_free for TWODD-style elements), shape (n)
        integer, allocatable :: state(:)
        !> The contact elements' solution: method, counts, certificate, tractions
        type(contact_result) :: contact
        !> Method, pivots, certificate, counts and equilibrium residual of this step (the
        !> preparation's times and counts not included)
        type(solver_record) :: record
    end type contact_step

    !> What the steps of one geometry share.
    type :: contact_run
        private
        !> The medium
        type(elastic_medium), public :: medium
        !> Options of the contact solver
        type(solver_options) :: options
        !> The elastic operator
        class(elastic_operator), allocatable, public :: operator
        !> The fault law of the contact elements, with the values in force
        type(fault_law) :: law
        !> Total (plastic) slip of the contact elements before the next step [length unit],
        !> shape (nc)
        real(wp), allocatable :: held(:)
        !> The slip and fault law in force before the last step, and those of the model with
        !> the K re-solve's higher-order zones after its last coupled solution (its own
        !> friction memory: in a history, the slip it kept when the step's elements stick)
        real(wp), allocatable :: held_before(:), k_held(:)
        type(fault_law) :: law_before, k_law
        !> Joint compliance of the contact elements (elastic joints), shape (2 nc)
        real(wp), allocatable :: compliance(:)
        !> What the steps share: states, factors, Lemke's LCP and basis (growth's kept path
        !> seeds the Newton method's states of a grown geometry)
        type(contact_session), public :: session
        !> Stress scale of every step's certificate (a history's, over all its loads)
        real(wp), allocatable :: stress_scale
        !> The K method: the higher-order re-solve when it serves (decided on the first
        !> tip_k), and why the tip element serves where it does ('' before the decision)
        logical :: higher_order = .false., k_decided = .false.
        type(higher_order_solver) :: k_solver
        character(len=:), allocatable :: tip_element_reason
        !> A step was solved on this run (the local re-solve solves the model again)
        logical :: stepped = .false.
        !> Solutions whose K the local re-solve gave, those where its coupling to the elements
        !> outside the zones stopped early (K its last iterate), and why the last one did
        integer :: k_evaluations = 0, k_unsettled = 0
        character(len=:), allocatable :: unsettled_reason
        !> The local re-solve's last two coupled solutions: the next step of a history starts
        !> from their extrapolation to its load, and takes it where it holds
        type(coupled_path) :: k_path
    contains
        procedure :: start
        procedure :: prepare
        procedure :: border
        procedure :: record_of
        procedure :: hold
        procedure :: take_steps
        procedure :: set_stress_scale
        procedure :: stress_scale_of
        procedure :: step
        procedure :: law_in_force
        procedure :: free_tractions
        procedure :: tip_k
        procedure :: extrapolate_k
        procedure :: k_memory
        procedure :: hold_k_memory
        procedure :: couple_outer
        procedure :: finish
    end type contact_run

contains

    !> The load of a medium's elements at a remote stress and pore fluid: the stress resolved
    !> on each element (in two bonded half-planes, the stress of its material:
    !> upper_remote_stress), the contact elements' own pressure plus the pore fluid's.
    pure function load_of(medium, remote, gradient, pore_fluid) result(load)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Remote stress sxx, syy, sxy at y = 0 [stress unit] and d/dy of it [stress unit /
        !> length unit] (the lower material's)
        real(wp), intent(in) :: remote(3), gradient(3)
        !> Pore pressure p0 at y = 0 [stress unit] and its gradient d/dy [stress / length]
        real(wp), intent(in) :: pore_fluid(2)
        type(elastic_load) :: load
        real(wp) :: upper(3), upper_gradient(3)
        real(wp), allocatable :: shear(:), normal(:), us(:), un(:)

        associate (elements => medium%elements)
            allocate (load%shear(elements%n), load%normal(elements%n))
            call resolve_remote_stress(elements, remote(1), remote(2), remote(3), load%shear, &
                                       load%normal, gradient)
            if (elements%domain == domain_bimaterial) then
                upper = upper_remote_stress(medium, remote)
                upper_gradient = upper_remote_stress(medium, gradient)
                allocate (shear(elements%n), normal(elements%n))
                call resolve_remote_stress(elements, upper(1), upper(2), upper(3), shear, &
                                           normal, upper_gradient)
                where (elements%y_mid > medium%interface_y)
                    load%shear = shear
                    load%normal = normal
                end where
            end if
            load%pressure = total_pressure(elements, pore_fluid)
            if (allocated(medium%body)) then
                allocate (shear(elements%n), normal(elements%n), us(elements%n), &
                          un(elements%n))
                call body_load(medium, shear, normal, us, un)
                load%shear = load%shear + shear
                load%normal = load%normal + normal
            end if
        end associate
        load%remote = remote
        load%gradient = gradient
    end function load_of

    !> A run of a medium without an operator yet: enough for tip_k (the K of DDs solved
    !> elsewhere); prepare makes the operator.
    pure subroutine start(this, medium, options)
        !> The run (fresh)
        class(contact_run), intent(inout) :: this
        !> The medium, geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Options of the contact solver
        type(solver_options), intent(in) :: options

        this%medium = medium
        this%options = options
    end subroutine start

    !> The solver record of a step with the preparation's times, counts and compression.
    pure function record_of(this, solution) result(record)
        !> The run
        class(contact_run), intent(in) :: this
        !> The step
        type(contact_step), intent(in) :: solution
        type(solver_record) :: record

        record = solution%record
        associate (p => this%operator%record)
            record%seconds_assembly = p%seconds_assembly + record%seconds_assembly
            record%counts%seconds = p%counts%seconds + record%counts%seconds
            record%hierarchical = p%hierarchical
            record%hmatrix_tolerance = p%hmatrix_tolerance
            ! The compression is the operator's, but that of the step's solve without
            ! contact elements
            if (this%operator%nc > 0) record%compression_ratio = p%compression_ratio
        end associate
    end function record_of

    !> Prepare the run of a medium: its operator (given: a distributed one; else dense or
    !> hierarchical as options%matrix says), the fault law of its contact elements and,
    !> for elastic joints, the system of their plastic DDs.
    subroutine prepare(this, medium, options, error, operator)
        !> The run (fresh)
        class(contact_run), intent(inout) :: this
        !> The medium, geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Options of the contact solver
        type(solver_options), intent(in) :: options
        !> Set when the operator cannot be made (singular, out of memory)
        type(error_type), allocatable, intent(out) :: error
        !> An operator made elsewhere (the MPI build's), moved in
        class(elastic_operator), allocatable, intent(inout), optional :: operator
        type(dense_operator), allocatable :: dense
        type(hierarchical_operator), allocatable :: compressed

        call this%start(medium, options)
        if (present(operator)) then
            call move_alloc(operator, this%operator)
        else if (options%matrix == matrix_hierarchical) then
            allocate (compressed)
            call new_hierarchical_operator(medium, options, compressed, error)
            call move_alloc(compressed, this%operator)
        else
            allocate (dense)
            call new_dense_operator(medium, dense, error)
            call move_alloc(dense, this%operator)
        end if
        if (allocated(error)) return
        associate (op => this%operator)
            this%law = fault_law_of(medium%elements, op%contact)
            allocate (this%held(op%nc), source=0.0_wp)
            this%compliance = this%law%joint_compliance()
            if (any(this%compliance > 0.0_wp)) then
                call op%add_joints(this%compliance, error)
            else
                deallocate (this%compliance)
            end if
        end associate
    end subroutine prepare

    !> Prepare the run of a grown geometry of contact elements alone on the matrix the
    !> caller bordered from the base's (growth's kept path, ddc_growth_solver; the matrix
    !> lives as long as the run uses it): the dense operator views it and keeps the factors
    !> of the geometry before (the caller renumbers them), the session its states (the
    !> Newton method's start) and forgets what depended on the old matrix.
    subroutine border(this, medium, options, matrix, checked)
        !> The run (fresh, or the previous geometry's)
        class(contact_run), intent(inout) :: this
        !> The grown medium, every element a rigid contact element
        type(elastic_medium), intent(in) :: medium
        !> Options of the contact solver
        type(solver_options), intent(in) :: options
        !> Its influence matrix [s; n], shape (2n, 2n) [stress / length]
        real(wp), intent(in), target, contiguous :: matrix(:, :)
        !> Every entry of the matrix is known to be finite
        logical, intent(in) :: checked

        call this%start(medium, options)
        if (.not. allocated(this%operator)) allocate (dense_operator :: this%operator)
        select type (op => this%operator)
        type is (dense_operator)
            call op%view_matrix(medium, matrix)
        end select
        this%session%warm = .true.
        call new_matrix(this%session, checked)
        this%law = fault_law_of(medium%elements, this%operator%contact)
        this%held = spread(0.0_wp, 1, this%operator%nc)
        call forget_k(this)
    end subroutine border

    !> K's re-solve of the geometry before (its zones, coupled solutions and memory) does
    !> not serve a new one: the next tip_k decides and prepares anew.
    pure subroutine forget_k(this)
        class(contact_run), intent(inout) :: this
        type(higher_order_solver) :: no_solver
        type(coupled_path) :: no_path

        this%k_decided = .false.
        this%higher_order = .false.
        this%stepped = .false.
        this%k_solver = no_solver
        this%k_path = no_path
        if (allocated(this%k_held)) deallocate (this%k_held)
    end subroutine forget_k

    !> The friction memory and strength state the next step starts from (a growth run's
    !> solves, a resumed history): the total slip of every element and, when given, the
    !> fault law of every element with its values in force and slip path.
    pure subroutine hold(this, ds, law)
        !> The run (prepared)
        class(contact_run), intent(inout) :: this
        !> Total (plastic) slip of every element [length unit], shape (n)
        real(wp), intent(in) :: ds(:)
        !> The fault law of every element with its strength state
        type(fault_law), intent(in), optional :: law

        this%held = ds(this%operator%contact)
        if (present(law)) call this%law%take_in_force(law, this%operator%contact)
    end subroutine hold

    !> A run of many steps (a loading history): Lemke starts each solve from its last
    !> basis; and the limits of the methods (tests): Lemke's pivots and Newton's
    !> iterations per solve.
    pure subroutine take_steps(this, max_pivots, max_iterations)
        !> The run
        class(contact_run), intent(inout) :: this
        !> Pivot limit of each Lemke solve and iteration limit of each Newton solve
        integer, intent(in), optional :: max_pivots, max_iterations

        this%session%warm = .true.
        if (present(max_pivots)) this%session%limits%max_pivots = max_pivots
        if (present(max_iterations)) this%session%limits%max_iterations = max_iterations
    end subroutine take_steps

    !> One stress scale for the certificate and Lemke's scaling of every step (a history's:
    !> the largest stress_scale_of its loads).
    pure subroutine set_stress_scale(this, scale)
        !> The run
        class(contact_run), intent(inout) :: this
        !> The stress scale [stress unit]
        real(wp), intent(in) :: scale

        this%stress_scale = scale
    end subroutine set_stress_scale

    !> The stress scale of a load on the contact elements (ddc_contact_result).
    subroutine stress_scale_of(this, load, scale, error)
        !> The run (prepared)
        class(contact_run), intent(inout) :: this
        !> The load
        type(elastic_load), intent(in) :: load
        !> The stress scale [stress unit]
        real(wp), intent(out) :: scale
        !> Set when the free elements' system has no solution
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: shift(:)
        type(free_part) :: kept

        associate (op => this%operator)
            allocate (shift(2 * op%nc))
            call op%load_contact(this%medium, load, shift, kept, error)
            scale = contact_stress_scale(shift(1:op%nc), shift(op%nc + 1:), &
                                         this%medium%elements%sf(op%contact), &
                                         load%pressure(op%contact))
        end associate
    end subroutine stress_scale_of

    !> One equilibrium under a load: the contact problem of the contact elements (with the
    !> method and fallbacks of ddc_contact_formulation, from the session's states and the
    !> memory), then the free elements' DDs. The memory and strengths in force move on.
    subroutine step(this, load, solution, error)
        !> The run (prepared)
        class(contact_run), intent(inout), target :: this
        !> The load
        type(elastic_load), intent(in) :: load
        !> DDs, states and the record of this step
        type(contact_step), intent(out) :: solution
        !> Set when the contact problem or the free elements' system has no solution
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: shift(:)
        type(contact_problem) :: problem
        type(free_part) :: kept
        integer :: n, nc

        n = this%medium%elements%n
        associate (op => this%operator, res => solution%contact, rec => solution%record)
            nc = op%nc
            allocate (solution%ds(n), solution%dn(n), solution%state(n), shift(2 * nc))
            call op%load_contact(this%medium, load, shift, kept, error)
            if (allocated(error)) return
            solution%state = state_free
            if (nc == 0) then
                rec%method = 'lu'
                allocate (res%ds(0), res%dn(0))
            else
                problem%pressure = load%pressure(op%contact)
                if (allocated(op%load_map)) call joint_load(op%load_map, problem%pressure, &
                                                            shift(1:nc), shift(nc + 1:))
                problem%shear = shift(1:nc)
                problem%normal = shift(nc + 1:)
                this%held_before = this%held
                this%law_before = this%law
                problem%ds_previous = this%held
                if (allocated(this%stress_scale)) problem%stress_scale = this%stress_scale
                call solve_contact_with(op%stiffness, problem, this%law, this%options, res, &
                                        error, op%matrix, this%session)
                if (allocated(error)) then
                    if (allocated(op%hint)) error%message = error%message//op%hint
                    return
                end if
                ! The memory of an elastic joint is its plastic slip.
                this%held = res%ds
                if (allocated(this%compliance)) call joint_dds(this%compliance, &
                    problem%pressure, res%shear_traction, res%normal_traction, res%ds, res%dn)
                call record_contact(res, op%flops, rec)
                solution%state(op%contact) = res%state
            end if
            call op%complete(this%medium, load, [res%ds, res%dn], kept, solution%ds, &
                             solution%dn, rec, error)
        end associate
        this%stepped = .not. allocated(error)
    end subroutine step

    !> The fault law of every element with the values in force the steps left on the
    !> contact elements (the given values on the others).
    pure function law_in_force(this) result(law)
        !> The run
        class(contact_run), intent(in) :: this
        type(fault_law) :: law

        law = fault_law_of(this%medium%elements)
        call law%place_in_force(this%law, this%operator%contact)
    end function law_in_force

    !> The total midpoint tractions of a step: the contact elements' as solved, the free
    !> elements' from their rows (operators that keep them), both with the remote stress.
    subroutine free_tractions(this, load, solution, shear_traction, normal_traction, error)
        !> The run
        class(contact_run), intent(in) :: this
        !> The step's load
        type(elastic_load), intent(in) :: load
        !> The step's solution
        type(contact_step), intent(in) :: solution
        !> Total shear and normal traction of every element [stress unit], shape (n)
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        !> Set when the operator keeps no rows of the free elements
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: ts(this%operator%nf), tn(this%operator%nf)

        associate (op => this%operator)
            shear_traction(op%contact) = solution%contact%shear_traction
            normal_traction(op%contact) = solution%contact%normal_traction
            if (op%nf == 0) return
            call op%free_tractions(this%medium, solution%ds, solution%dn, ts, tn, error)
            if (allocated(error)) return
            shear_traction(op%free) = ts + load%shear(op%free)
            normal_traction(op%free) = tn + load%normal(op%free)
        end associate
    end subroutine free_tractions

    !> K_I and K_II at tips of solved DDs: the tip element's, replaced by the higher-order
    !> re-solve's where the run's K method (&solver k_method, decided on the first call)
    !> has it serve; tips%k_method says which, and why.
    subroutine tip_k(this, load, solved, growth, tips, k1, k2)
        !> The run (started)
        class(contact_run), intent(inout) :: this
        !> The load the DDs were solved for
        type(elastic_load), intent(in) :: load
        !> DDs, states, total midpoint tractions and (where recorded) friction in force of
        !> every element
        type(element_results), intent(in) :: solved
        !> Whether the model grows its fractures (growth calibrates the tip element)
        logical, intent(in) :: growth
        !> The tips (ddc_post_tips); k_method set, graded cleared where the re-solve serves
        type(tip_set), intent(inout) :: tips
        !> K_I and K_II of each tip [stress unit * length unit**0.5], shape (tips)
        real(wp), intent(out) :: k1(:), k2(:)
        type(error_type), allocatable :: failed
        real(wp), allocatable :: k1_high(:), k2_high(:), mu(:)
        logical :: extrapolated

        associate (m => this%medium)
            call stress_intensity(m, tips%element, solved%ds, solved%dn, k1, k2)
            if (.not. this%k_decided) then
                this%k_decided = .true.
                call uses_higher_order(this%options%k_method, this%options%k_zone_elements, &
                                       growth, m, tips, this%higher_order, &
                                       this%tip_element_reason)
                if (this%higher_order) then
                    call prepare_higher_order(m, tips, this%options%k_zone_elements, &
                                              this%k_solver, failed)
                    call note_failure()
                end if
                if (coupled() .and. .not. this%stepped) then
                    this%higher_order = .false.
                    this%tip_element_reason = 'the elements outside the zones of the '// &
                        're-solve were not solved by this run'
                end if
            end if
            extrapolated = .false.
            if (coupled()) call this%extrapolate_k(load, k1_high, k2_high, extrapolated)
            if (extrapolated) then
                ! A tip outside the zones keeps the tip element's K of the step's own DDs.
                where (this%k_solver%local(tips%element) == 0)
                    k1_high = k1
                    k2_high = k2
                end where
            end if
            if (this%higher_order .and. .not. extrapolated) then
                if (allocated(solved%mu_in_force)) then
                    mu = solved%mu_in_force
                else
                    mu = m%elements%mu
                end if
                k1_high = k1
                k2_high = k2
                call higher_order_k(this%k_solver, m, solved%ds, solved%dn, &
                                    solved%shear_traction, solved%normal_traction, mu, &
                                    load%remote, load%gradient, solved%state, tips, k1_high, &
                                    k2_high, failed)
                call note_failure()
            end if
            if (coupled()) this%k_evaluations = this%k_evaluations + 1
            if (coupled() .and. .not. extrapolated) then
                call this%couple_outer(load, solved, mu, tips, k1_high, k2_high, failed)
                if (allocated(failed)) then
                    this%k_unsettled = this%k_unsettled + 1
                    this%unsettled_reason = failed%message
                end if
            end if
            if (this%higher_order) then
                k1 = k1_high
                k2 = k2_high
                where (this%k_solver%local(tips%element) > 0) tips%graded = 0
                tips%k_method = 'higher_order'
                if (this%k_unsettled > 0) tips%k_method = tips%k_method// &
                    ' (the coupling to the elements outside the zones stopped early at '// &
                    itoa(this%k_unsettled)//' of '//itoa(this%k_evaluations)// &
                    ' solutions, K there its last iterate: '//this%unsettled_reason//')'
            else if (len(this%tip_element_reason) > 0) then
                tips%k_method = 'tip_element ('//this%tip_element_reason//')'
            end if
        end associate

    contains

        !> Whether the re-solve serves and has elements outside its zones to couple.
        logical function coupled()
            coupled = this%higher_order
            if (coupled) coupled = size(this%k_solver%outer%element) > 0
        end function coupled

        !> A re-solve that fails leaves the run's K method the tip element's.
        subroutine note_failure()
            if (.not. allocated(failed)) return
            this%higher_order = .false.
            this%tip_element_reason = 'the higher-order re-solve failed: '//failed%message
        end subroutine note_failure
    end subroutine tip_k

    !> K of a history step by the local re-solve's last two coupled solutions extrapolated
    !> to its load (ddc_run_coupled_k), where the fault law is Coulomb's (the equations then
    !> linear while the states hold) and the extrapolated solution meets the contact
    !> conditions to the contact solver's own certificate: no solve. The friction memory of
    !> the model with higher-order zones moves on as a solve's would.
    subroutine extrapolate_k(this, load, k1, k2, done)
        !> The run (its re-solve coupled)
        class(contact_run), intent(inout) :: this
        !> The step's load
        type(elastic_load), intent(in) :: load
        !> K of the tips [stress unit * length unit**0.5], shape (tips), where done
        real(wp), allocatable, intent(out) :: k1(:), k2(:)
        !> Whether K was extrapolated
        logical, intent(out) :: done
        type(coupled_solution) :: candidate
        type(lcp_certificate) :: certificate
        real(wp), allocatable :: values(:)
        real(wp) :: dd_scale

        done = .false.
        if (.not. this%options%k_extrapolation .or. .not. allocated(this%k_held)) return
        if (this%law%beyond_coulomb()) return
        values = load_values(load)
        if (.not. this%k_path%extends(values)) return
        candidate = this%k_path%at(values)
        associate (contact => this%operator%contact, law => this%k_law, c => candidate)
            dd_scale = max(c%dd_scale, maxval(abs([c%ds, c%dn, 0.0_wp])))
            certificate = frictional_certificate(c%ds, c%dn, this%k_held, c%shear, &
                c%normal + load%pressure(contact), law%mu_in_force, law%sf_in_force, &
                c%stress_scale, dd_scale)
        end associate
        if (.not. certificate%passed) return
        done = .true.
        call move_alloc(candidate%k1, k1)
        call move_alloc(candidate%k2, k2)
        call move_alloc(candidate%ds, this%k_held)
    end subroutine extrapolate_k

    !> The friction memory of the model with the re-solve's higher-order zones, for a result
    !> file (--resume): its slip on the contact elements, the steps' elsewhere; not allocated
    !> where the re-solve was never coupled.
    pure subroutine k_memory(this, ds, memory)
        !> The run
        class(contact_run), intent(in) :: this
        !> The last step's slip of every element [length unit], shape (n)
        real(wp), intent(in) :: ds(:)
        !> The memory [length unit], shape (n)
        real(wp), allocatable, intent(out) :: memory(:)

        if (.not. allocated(this%k_held)) return
        memory = ds
        memory(this%operator%contact) = this%k_held
    end subroutine k_memory

    !> A resumed history's memory of the model with higher-order zones (k_memory of the
    !> earlier run); its strengths start from those the steps hold.
    pure subroutine hold_k_memory(this, memory)
        !> The run (held: its law in force restored)
        class(contact_run), intent(inout) :: this
        !> The memory [length unit], shape (n)
        real(wp), intent(in) :: memory(:)

        this%k_held = memory(this%operator%contact)
        this%k_law = this%law
    end subroutine hold_k_memory

    !> The local re-solve coupled to the elements outside its zones: the model solved again
    !> under its load plus the traction the zones' higher-order DDs and the recovered DDs
    !> add at their midpoints (outer_correction), then the zones re-solved, until K stops
    !> moving (docs/theory/tips.md#the-local-re-solve). The run's friction memory and
    !> strengths are left as the step left them.
    subroutine couple_outer(this, load, solved, mu, tips, k1, k2, error)
        !> The run (stepped)
        class(contact_run), intent(inout) :: this
        !> The load the DDs were solved for
        type(elastic_load), intent(in) :: load
        !> The step's DDs, states and total midpoint tractions
        type(element_results), intent(in) :: solved
        !> Friction in force [-], shape (n)
        real(wp), intent(in) :: mu(:)
        !> The tips
        type(tip_set), intent(in) :: tips
        !> K of the re-solve with the step's DDs outside the zones on entry, coupled on exit
        !> [stress unit * length unit**0.5], shape (tips)
        real(wp), intent(inout) :: k1(:), k2(:)
        !> Set when a solve fails or K does not settle
        type(error_type), allocatable, intent(out) :: error
        type(elastic_load) :: shifted
        type(contact_step) :: trial
        type(fault_law) :: law, coupled_law
        type(anderson_mixer) :: mixer
        type(factor_counts) :: counts
        real(wp), allocatable :: held(:), coupled_held(:), shear_traction(:), &
            normal_traction(:), shift(:)
        real(wp), allocatable :: k1_next(:), k2_next(:), correction(:)
        real(wp) :: scale, change
        integer :: n, solves, method

        n = this%medium%elements%n
        allocate (shear_traction, source=solved%shear_traction)
        allocate (normal_traction, source=solved%normal_traction)
        scale = maxval(hypot(k1, k2))
        allocate (correction(2 * n))
        call this%k_path%start(load_values(load), solved%state(this%operator%contact), shift)
        if (.not. allocated(shift)) then
            allocate (shift(2 * n))
            call outer_correction(this%k_solver, this%medium, solved%ds, solved%dn, shift(:n), &
                                  shift(n + 1:))
        end if
        shifted = load
        do solves = 1, max_coupling_solves
            shifted%shear = load%shear + shift(:n)
            shifted%normal = load%normal + shift(n + 1:)
            ! Solved again from the memory and strengths of the model with higher-order zones
            ! (at the first solution, those the step started from); the run's are then left
            ! as the step left them, and the counts of the solver's work are the steps' alone.
            held = this%held
            law = this%law
            if (allocated(this%operator%stiffness)) counts = this%operator%stiffness%counts
            if (allocated(this%k_held)) then
                this%held = this%k_held
                this%law = this%k_law
            else if (allocated(this%held_before)) then
                this%held = this%held_before
                this%law = this%law_before
            end if
            this%session%limits%fall_back = .false.
            ! By the Newton method from the step's states: Lemke would start afresh at every
            ! solve of the coupling.
            method = this%options%lcp_method
            this%options%lcp_method = lcp_newton
            call this%step(shifted, trial, error)
            this%options%lcp_method = method
            this%session%limits%fall_back = .true.
            if (allocated(this%operator%stiffness)) this%operator%stiffness%counts = counts
            coupled_held = this%held
            coupled_law = this%law
            this%held = held
            this%law = law
            if (allocated(error)) return
            associate (op => this%operator)
                if (op%nc > 0) then
                    shear_traction(op%contact) = trial%contact%shear_traction
                    normal_traction(op%contact) = trial%contact%normal_traction
                end if
            end associate
            k1_next = k1
            k2_next = k2
            call higher_order_k(this%k_solver, this%medium, trial%ds, trial%dn, shear_traction, &
                                normal_traction, mu, load%remote, load%gradient, trial%state, &
                                tips, k1_next, k2_next, error)
            if (allocated(error)) return
            change = maxval(abs([k1_next - k1, k2_next - k2]))
            k1 = k1_next
            k2 = k2_next
            ! K of the step's own DDs is no iterate: two solves at least, unless the solve's
            ! traction gives itself back.
            if (solves > 1 .and. change <= coupling_tolerance * scale) then
                call keep_coupled()
                return
            end if
            call outer_correction(this%k_solver, this%medium, trial%ds, trial%dn, &
                                  correction(:n), correction(n + 1:))
            if (maxval(abs(correction - shift)) <= coupling_tolerance * maxval(abs(shift))) then
                call keep_coupled()
                return
            end if
            call mixer%next(shift, correction)
        end do
        call set_error(error, exit_solver_failure, 'K still moved by '//rtoa(change)// &
                       ' (its largest value '//rtoa(scale)//') after '// &
                       itoa(max_coupling_solves)//' solves')

    contains

        !> The next step's coupling starts from this one's solution, memory and strengths.
        subroutine keep_coupled()
            type(coupled_solution), allocatable :: solution

            allocate (solution)
            solution%load = load_values(load)
            solution%shift = shift
            associate (contact => this%operator%contact)
                solution%ds = trial%ds(contact)
                solution%dn = trial%dn(contact)
                solution%state = trial%state(contact)
                solution%shear = shear_traction(contact)
                solution%normal = normal_traction(contact)
            end associate
            solution%k1 = k1
            solution%k2 = k2
            solution%stress_scale = trial%contact%stress_scale
            solution%dd_scale = trial%contact%dd_scale
            call this%k_path%keep(solution)
            call move_alloc(coupled_held, this%k_held)
            this%k_law = coupled_law
        end subroutine keep_coupled
    end subroutine couple_outer

    !> A load's values as one vector: the tractions and pressures on the elements, the
    !> remote stress and its gradient.
    pure function load_values(load) result(values)
        type(elastic_load), intent(in) :: load
        real(wp), allocatable :: values(:)

        values = [load%shear, load%normal, load%remote, load%gradient]
        if (allocated(load%pressure)) values = [values, load%pressure]
    end function load_values

    !> Free what the run holds.
    subroutine finish(this)
        !> The run
        class(contact_run), intent(inout) :: this

        if (allocated(this%operator)) call this%operator%release()
    end subroutine finish


    !> Fill the solver record from a contact solution.
    subroutine record_contact(res, flops, record)
        !> The contact solution
        type(contact_result), intent(in) :: res
        !> Nominal flops of the factorizations outside the contact solve (the condensation)
        real(wp), intent(in) :: flops
        !> Method, pivots, counts, certificate, residual, flops and LCP time are set; the
        !> factorization time is added to
        type(solver_record), intent(inout) :: record
        real(wp) :: seconds

        record%method = res%method
        record%fallback = res%fallback
        record%newton_iterations = res%iterations
        seconds = record%counts%seconds
        record%counts = res%counts
        record%counts%flops = res%counts%flops + flops
        record%counts%seconds = seconds + res%counts%seconds
        record%pivots = res%pivots
        record%lcp_solves = res%solves
        record%certificate_min_z = res%certificate%min_z
        record%certificate_min_w = res%certificate%min_w
        record%certificate_max_complementarity = res%certificate%max_complementarity
        record%certificate_tolerance = res%certificate%tolerance
        record%seconds_lcp = res%seconds_lcp
        record%equilibrium_residual = maxval(res%equilibrium_residual)
    end subroutine record_contact

end module ddc_run_contact_run
