!> The solves of a growth run (docs/theory/growth.md#solving-a-grown-model-cheaply): the input
!> geometry, then grown geometries (trials: the corrector's, and a step's final one). The geometry
!> of a step's last trial becomes the base of the next step (accept_trial).
!>
!> A model whose elements are all contact elements and which the Newton method solves
!> (lcp_method 'newton', or 'auto' from auto_newton_min_elements on) keeps for its base the
!> influence matrix, the element states and the factors of the Newton method's last
!> reduced system. A trial then
!> - builds its influence matrix from the base's (ddc_growth_influence): only the new
!>   elements' rows and columns are computed; the base block is moved once per step, and
!>   the corrector's later trials of the step replace only the new rows and columns;
!> - starts the Newton method from the base's states (a new element takes the state of the
!>   element it grows from) and from the base's factors renumbered to the grown model, so
!>   that the new elements' unknowns enter by bordering (Schur complement,
!>   ddc_contact_reduced_factors) instead of a new factorization;
!> - is solved, certified and checked by solve_contact_with exactly as a one-shot solve,
!>   with the same fallbacks (an update that lost accuracy factorizes anew, a Newton
!>   failure falls back to Lemke).
!> The trials share one contact_session (each on its own matrix: new_matrix), whose states
!> carry over from one trial to the next; when a step is accepted, an update of its factors
!> that leaves the next step's trials no room is factorized anew (refactor_full_update).
!> A trial that splits base elements (a linking step, docs/theory/growth.md#linking-and-stops) is
!> assembled and factorized whole, from no states.
!> Every other model (Lemke, TWODD-style elements, no contact) is solved from scratch by
!> run_model, as before growth had a solver.
!> Under a loading history (docs/theory/growth.md#growth-along-a-loading-history) the solver keeps
!> the friction memory: every solve starts from the total slip of the base, an element that is
!> there, or was split, keeps its slip and a new element starts from none (it joins the memory from
!> the step that made it); so does the strength state (ddc_contact_fault_law: the slip path and the
!> strengths in force: a new element starts intact, with its given strengths); a new load step
!> is a solve of the base geometry at the new load (solve_loaded), on the kept path with the
!> base's matrix and factors. Tractions, face displacements and fields are computed once, for
!> the final geometry (final_results). Every solve's K at tips of unequal elements is calibrated
!> (ddc_growth_tip_zone, docs/theory/tips.md#tips-of-grown-fractures).
module ddc_growth_solver
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_allocation, only: allocation_failed, real_bytes
    use ddc_text, only: itoa
    use ddc_model_types, only: model_type, condition_contact, rigid_joint
    use ddc_model_results, only: model_results, solver_record
    use ddc_influence_assembly, only: assemble_influence
    use ddc_influence_body, only: body_matrix_correction
    use ddc_solve_elastic, only: row_kinds
    use ddc_model_element_laws, only: fault_law_of
    use ddc_contact_options, only: lcp_auto, lcp_newton
    use ddc_contact_formulation, only: auto_newton_min_elements
    use ddc_contact_counts, only: factor_counts
    use ddc_contact_fault_law, only: fault_law
    use ddc_contact_stiffness, only: dense_stiffness
    use ddc_contact_reduced_factors, only: reduced_factors, renumber_factors, copy_factors, &
        refactor_full_update, counts_of
    use ddc_growth_tip_zone, only: calibrate_tips
    use ddc_run_model, only: run_model, finish_model, evaluate_fields, model_load, find_tips_and_k
    use ddc_run_contact_run, only: contact_run, contact_step
    use ddc_model_medium, only: medium_of
    use ddc_solve_operator, only: elastic_load
    use ddc_solve_dense_operator, only: dense_operator
    use ddc_growth_influence, only: grow_influence, unknown_map
    implicit none
    private

    public :: growth_solver, solve_input, solve_grown, solve_loaded, accept_trial, final_results
    public :: restore_memory
    public :: keeps_solves, solves_done

    !> What the solves of one growth run keep. Arrays of n elements of the base or trial.
    type :: growth_solver
        private
        !> The base (the last accepted geometry) was solved on the kept path
        logical :: kept = .false.
        !> The base's influence matrix [s; n], shape (2n, 2n) [stress / length], its states
        !> (open; shear: stick 0, slip +-1 as the Newton method codes them) and factors
        real(wp), allocatable :: base_matrix(:, :)
        logical, allocatable :: base_open(:)
        integer, allocatable :: base_shear(:)
        type(reduced_factors) :: base_factors
        !> A trial was solved since the last accept_trial, and on the kept path
        logical :: pending = .false., trial_kept = .false.
        !> The last trial: its matrix, where the base block sits in it (moved_to; not
        !> allocated when the matrix was assembled whole), and the contact run of its solves
        !> (ddc_run_contact_run), whose session holds its states (the next trial's start)
        !> and whose dense stiffness its factors
        real(wp), allocatable :: matrix(:, :)
        integer, allocatable :: layout(:)
        type(contact_run) :: run
        !> The LU factors of the run's factors are a copy of base_factors' (or these of
        !> those), neither factorized anew nor bordered since: factorizations and borderings
        !> counted by both then
        logical :: lu_shared = .false.
        integer :: shared_factorizations = 0
        !> Sums over every solve of the run: phase times and counts
        type(solver_record) :: totals
        !> Solves done
        integer :: solves = 0
        !> The friction memory is kept (a loading history): the total slip of the base and of
        !> the last trial [length unit], shape (n)
        logical :: memory = .false.
        real(wp), allocatable :: base_ds(:), trial_ds(:)
        !> With the friction memory: the fault law of every element of the base and of the
        !> last trial, for its strength state (values in force and slip path)
        type(fault_law) :: base_law, trial_law
    end type growth_solver

contains

    !> Whether a model is solved on the kept path: every element a rigid contact element (an
    !> elastic joint's system is run_model's), and the Newton method in use.
    pure logical function keeps_solves(model)
        !> The model
        type(model_type), intent(in) :: model

        keeps_solves = all(model%elements%condition == condition_contact) .and. &
            (model%solver%lcp_method == lcp_newton .or. (model%solver%lcp_method == &
             lcp_auto .and. model%elements%n >= auto_newton_min_elements))
        if (keeps_solves) keeps_solves = .not. (any(model%elements%shear_stiffness < &
            rigid_joint) .or. any(model%elements%normal_stiffness < rigid_joint))
    end function keeps_solves

    !> Number of solves done so far.
    pure integer function solves_done(solver)
        !> The solver
        type(growth_solver), intent(in) :: solver

        solves_done = solver%solves
    end function solves_done

    !> Solve the input geometry; it is the base of the first step.
    subroutine solve_input(solver, model, results, error, friction_memory)
        !> The solver (fresh)
        type(growth_solver), intent(inout), target :: solver
        !> The input model (without observations)
        type(model_type), intent(in) :: model
        !> Its DDs, states, tips, tractions and solver record
        type(model_results), intent(out) :: results
        !> Set when the solve fails
        type(error_type), allocatable, intent(out) :: error
        !> Keep the friction memory from this solve on (a loading history; default no)
        logical, intent(in), optional :: friction_memory

        if (present(friction_memory)) solver%memory = friction_memory
        call solve_grown(solver, model, [integer ::], results, error)
        if (allocated(error)) return
        call accept_trial(solver)
    end subroutine solve_input

    !> A fresh solver for a resumed run (--resume): no kept base (the first solve assembles
    !> and factorizes whole), the friction memory of the earlier run's final geometry.
    pure subroutine restore_memory(solver, ds, law)
        !> The solver (fresh)
        type(growth_solver), intent(inout) :: solver
        !> Total slip of every element of the base [length unit], shape (n)
        real(wp), intent(in) :: ds(:)
        !> The fault law of every element of the base with its strength state
        type(fault_law), intent(in) :: law

        solver%memory = .true.
        solver%base_ds = ds
        solver%base_law = law
    end subroutine restore_memory

    !> Solve the base geometry at a new load (model: the base at that load), from the
    !> friction memory of the base; it stays the base.
    subroutine solve_loaded(solver, model, results, error)
        !> The solver
        type(growth_solver), intent(inout), target :: solver
        !> The base geometry at the new load (without observations)
        type(model_type), intent(in) :: model
        !> Its DDs, states, tips, tractions and solver record
        type(model_results), intent(out) :: results
        !> Set when the solve fails
        type(error_type), allocatable, intent(out) :: error
        integer :: i

        call solve_grown(solver, model, [(i, i = 1, model%elements%n)], results, error)
        if (allocated(error)) return
        call accept_trial(solver)
    end subroutine solve_loaded

    !> Solve a grown model (a trial): from the base when both are on the kept path,
    !> else from scratch.
    subroutine solve_grown(solver, model, moved_to, results, error, origin)
        !> The solver
        type(growth_solver), intent(inout), target :: solver
        !> The grown model (without observations)
        type(model_type), intent(in) :: model
        !> The index in model of each element of the base, shape (n_base); empty: no base
        integer, intent(in) :: moved_to(:)
        !> Its DDs, states, tips, tractions and solver record
        type(model_results), intent(out) :: results
        !> Set when the solve fails
        type(error_type), allocatable, intent(out) :: error
        !> The element of the base each element of model comes from (moved, or split in
        !> two), 0 for a new one, shape (n) (default: from moved_to); the friction memory
        !> follows it
        integer, intent(in), optional :: origin(:)
        real(wp), allocatable :: held(:)
        integer, allocatable :: from(:)
        type(fault_law) :: law
        integer :: i

        solver%pending = .true.
        solver%solves = solver%solves + 1
        solver%trial_kept = keeps_solves(model)
        allocate (held(model%elements%n), source=0.0_wp)
        allocate (from(model%elements%n), source=0)
        if (present(origin)) then
            from = origin
        else if (size(moved_to) > 0) then
            from(moved_to) = [(i, i = 1, size(moved_to))]
        end if
        law = fault_law_of(model%elements)
        if (solver%memory .and. allocated(solver%base_ds)) then
            where (from > 0) held = solver%base_ds(max(from, 1))
            if (allocated(solver%base_law%slip_path)) then
                call law%take_in_force(solver%base_law, from)
            end if
        end if
        if (solver%trial_kept) then
            call solve_kept(solver, model, moved_to, held, law, results, error)
        else if (solver%memory) then
            call run_model(model, results, error, ds_previous=held, strengths=law)
        else
            call run_model(model, results, error, ds_previous=held)
        end if
        if (allocated(error)) return
        if (solver%memory) then
            ! The memory of an elastic joint is its plastic slip, as in a loading history.
            solver%trial_ds = results%elements%ds
            if (allocated(results%elements%ds_elastic)) solver%trial_ds = results%elements%ds &
                - results%elements%ds_elastic
            solver%trial_law = law
        end if
        call calibrate_tips(model, results%tips, error)
        if (allocated(error)) return
        call add_record(solver%totals, results%solver)
    end subroutine solve_grown

    !> The last trial becomes the base of the next step (nothing happens without a trial).
    subroutine accept_trial(solver)
        !> The solver
        type(growth_solver), intent(inout), target :: solver
        type(dense_stiffness), pointer :: stiffness

        if (.not. solver%pending) return
        solver%pending = .false.
        solver%kept = solver%trial_kept
        if (solver%memory) then
            call move_alloc(solver%trial_ds, solver%base_ds)
            solver%base_law = solver%trial_law
        end if
        if (allocated(solver%base_matrix)) deallocate (solver%base_matrix)
        if (allocated(solver%layout)) deallocate (solver%layout)
        if (.not. solver%kept) then
            if (allocated(solver%matrix)) deallocate (solver%matrix)
            solver%lu_shared = .false.
            return
        end if
        call move_alloc(solver%matrix, solver%base_matrix)
        call move_alloc(solver%run%session%open, solver%base_open)
        call move_alloc(solver%run%session%shear_state, solver%base_shear)
        ! A full update would leave the next step's trials no room: factorize it anew.
        call kept_stiffness(solver, stiffness)
        call refactor_full_update(stiffness%factors, solver%base_matrix, solver%totals%counts)
        call share_factors(solver, solver%base_factors, stiffness%factors)
    end subroutine accept_trial

    !> to = from for the kept factors of the base and of the trial (one of each), without
    !> copying their LU factors again where to's are a copy of from's already (the
    !> trials of a step all start from the base's).
    subroutine share_factors(solver, to, from)
        type(growth_solver), intent(inout), target :: solver
        type(reduced_factors), intent(inout) :: to, from
        type(dense_stiffness), pointer :: stiffness
        type(factor_counts) :: made

        ! Every new factorization of the trial's factors is counted there.
        call kept_stiffness(solver, stiffness)
        made = counts_of(stiffness%factors)
        call copy_factors(to, from, same_lu=solver%lu_shared .and. &
                          made%factorizations + made%borderings == solver%shared_factorizations)
        made = counts_of(stiffness%factors)
        solver%lu_shared = .true.
        solver%shared_factorizations = made%factorizations + made%borderings
    end subroutine share_factors

    !> The results of the final geometry (the last accepted one): tractions, face
    !> displacements and tips from the kept matrix when kept, and the fields; the solver
    !> record's phase times and counts are the sums over every solve of the run.
    subroutine final_results(solver, model, current, results)
        !> The solver
        type(growth_solver), intent(in) :: solver
        !> The final model, with its observations
        type(model_type), intent(in) :: model
        !> The results of its solve
        type(model_results), intent(in) :: current
        !> Its complete results
        type(model_results), intent(out) :: results
        type(solver_record) :: last

        results = current
        last = results%solver
        if (solver%kept) then
            ! finish_model computes the tractions anew, with the face displacements.
            deallocate (results%elements%shear_traction, results%elements%normal_traction)
            call finish_model(model, model_load(model), results, matrix=solver%base_matrix, &
                              tips_found=.true.)
        else
            call evaluate_fields(model, results)
        end if
        ! The tips as the solve calibrated them (ddc_growth_tip_zone).
        results%tips = current%tips
        associate (s => results%solver, t => solver%totals)
            s%seconds_assembly = t%seconds_assembly
            s%counts = t%counts
            s%seconds_lcp = t%seconds_lcp
            s%seconds_fields = t%seconds_fields - last%seconds_fields + s%seconds_fields
            s%newton_iterations = t%newton_iterations
            s%pivots = t%pivots
            s%lcp_solves = t%lcp_solves
        end associate
    end subroutine final_results

    !> Add one solve's phase times and counts to the totals.
    pure subroutine add_record(totals, one)
        type(solver_record), intent(inout) :: totals
        type(solver_record), intent(in) :: one

        totals%seconds_assembly = totals%seconds_assembly + one%seconds_assembly
        call totals%counts%add(one%counts)
        totals%seconds_lcp = totals%seconds_lcp + one%seconds_lcp
        totals%seconds_fields = totals%seconds_fields + one%seconds_fields
        totals%newton_iterations = totals%newton_iterations + one%newton_iterations
        totals%pivots = totals%pivots + one%pivots
        totals%lcp_solves = totals%lcp_solves + one%lcp_solves
    end subroutine add_record

    !> A solve on the kept path: the influence matrix grown from the base's (or assembled
    !> whole without a kept base), the Newton method started from the base's states and
    !> factors.
    subroutine solve_kept(solver, model, moved_to, held, law, results, error)
        type(growth_solver), intent(inout), target :: solver
        type(model_type), intent(in) :: model
        integer, intent(in) :: moved_to(:)
        real(wp), intent(in) :: held(:)
        !> The fault law: the strength state before the solve, after it on return
        type(fault_law), intent(inout) :: law
        type(model_results), intent(out) :: results
        type(error_type), allocatable, intent(out) :: error
        type(reduced_factors) :: no_factors
        type(dense_stiffness), pointer :: stiffness
        integer, allocatable :: shear_row(:), normal_row(:)
        logical :: grow, placed, finite
        integer :: n, stat
        integer(int64) :: t0, t1, rate

        call system_clock(t0, rate)
        n = model%elements%n
        ! A linking step splits base elements (moved_to 0): its trials are assembled whole
        ! and factorized anew.
        grow = solver%kept .and. size(moved_to) > 0 .and. allocated(solver%base_open)
        if (grow) grow = all(moved_to > 0)
        placed = .false.
        if (grow .and. allocated(solver%layout) .and. allocated(solver%matrix)) then
            placed = size(solver%matrix, 1) == 2 * n .and. size(solver%layout) == &
                size(moved_to)
            if (placed) placed = all(solver%layout == moved_to)
        end if
        if (.not. placed) then
            if (allocated(solver%matrix)) deallocate (solver%matrix)
            allocate (solver%matrix(2 * n, 2 * n), stat=stat)
            if (stat /= 0) then
                call allocation_failed(error, 'the influence matrix of '//itoa(n)// &
                                       ' elements', real_bytes * (2.0_wp * real(n, wp))**2)
                return
            end if
        end if
        if (grow) then
            call grow_influence(solver%base_matrix, moved_to, medium_of(model), placed, &
                                solver%matrix, finite)
            solver%layout = moved_to
            call kept_stiffness(solver, stiffness)
            call share_factors(solver, stiffness%factors, solver%base_factors)
            call renumber_factors(stiffness%factors, unknown_map(moved_to, n))
            ! A later trial of the step starts from the states of the one before (its new
            ! elements lie close to these), the first one from the base's.
            if (.not. (placed .and. allocated(solver%run%session%open))) then
                call inherit_states(solver, model, moved_to)
            end if
        else
            allocate (shear_row(n), normal_row(n))
            call row_kinds(model%elements%condition, shear_row, normal_row)
            call assemble_influence(medium_of(model), shear_row, normal_row, solver%matrix)
            if (allocated(model%body)) call body_matrix_correction(medium_of(model), shear_row, &
                                                                   normal_row, solver%matrix)
            if (allocated(solver%layout)) deallocate (solver%layout)
            call kept_stiffness(solver, stiffness)
            stiffness%factors = no_factors
            solver%lu_shared = .false.
            if (allocated(solver%run%session%open)) deallocate (solver%run%session%open, &
                                                                solver%run%session%shear_state)
            ! solve_contact_with checks the whole matrix.
            finite = .false.
        end if
        call system_clock(t1)
        results%solver%seconds_assembly = real(t1 - t0, wp) / real(rate, wp)
        ! The counts of this solve only (the factors carry those of the base's solves).
        call kept_stiffness(solver, stiffness)
        stiffness%counts = factor_counts()
        call solve_contact_on(solver, model, finite, held, law, results, error)
    end subroutine solve_kept

    !> The Newton method's start for a grown model: the base's states at the old elements'
    !> new places; a new element takes the state of the element it grows from (the next
    !> one of its fracture that is older, in index order, else the one before).
    subroutine inherit_states(solver, model, moved_to)
        type(growth_solver), intent(inout) :: solver
        type(model_type), intent(in) :: model
        integer, intent(in) :: moved_to(:)
        logical :: known(model%elements%n)
        logical, allocatable :: open_state(:)
        integer, allocatable :: shear_state(:)
        integer :: n, i

        n = model%elements%n
        allocate (open_state(n), shear_state(n))
        open_state = .false.
        shear_state = 0
        known = .false.
        open_state(moved_to) = solver%base_open
        shear_state(moved_to) = solver%base_shear
        known(moved_to) = .true.
        ! Elements grown at a begin tip come before their fracture's old ones ...
        do i = n - 1, 1, -1
            if (.not. known(i)) call take_from(i, i + 1)
        end do
        ! ... and those grown at an end tip after them.
        do i = 2, n
            if (.not. known(i)) call take_from(i, i - 1)
        end do
        call move_alloc(open_state, solver%run%session%open)
        call move_alloc(shear_state, solver%run%session%shear_state)

    contains

        subroutine take_from(to, from)
            integer, intent(in) :: to, from

            if (.not. known(from)) return
            if (model%elements%fracture_id(from) /= model%elements%fracture_id(to)) return
            open_state(to) = open_state(from)
            shear_state(to) = shear_state(from)
            known(to) = .true.
        end subroutine take_from

    end subroutine inherit_states

    !> The dense stiffness of the trials' contact run, in which their factors live (made
    !> on first use).
    subroutine kept_stiffness(solver, stiffness)
        type(growth_solver), intent(inout), target :: solver
        type(dense_stiffness), pointer, intent(out) :: stiffness

        associate (run => solver%run)
            if (.not. allocated(run%operator)) allocate (dense_operator :: run%operator)
            if (.not. allocated(run%operator%stiffness)) then
                allocate (dense_stiffness :: run%operator%stiffness)
            end if
            select type (s => run%operator%stiffness)
            type is (dense_stiffness)
                stiffness => s
            end select
        end associate
    end subroutine kept_stiffness

    !> The contact solve of a model whose elements are all contact elements: a step of the
    !> trials' contact run on the solver's matrix, from the session's states (when
    !> allocated) and the run's factors, which keep the solution's for the next trial;
    !> DDs, states, tractions, tips and the record set.
    subroutine solve_contact_on(solver, model, checked, held, law, results, error)
        type(growth_solver), intent(inout), target :: solver
        type(model_type), intent(in) :: model
        !> Every entry of the solver's matrix is known to be finite
        logical, intent(in) :: checked
        !> Total slip before this solve (friction memory), shape (n) [length]
        real(wp), intent(in) :: held(:)
        !> The fault law: the strength state before the solve, after it on return
        type(fault_law), intent(inout) :: law
        type(model_results), intent(inout) :: results
        type(error_type), allocatable, intent(out) :: error
        type(contact_step) :: solution
        type(elastic_load) :: load
        real(wp) :: seconds_assembly

        call solver%run%border(medium_of(model), model%solver, solver%matrix, checked)
        call solver%run%hold(held, law)
        load = model_load(model)
        call solver%run%step(load, solution, error)
        if (allocated(error)) return
        law = solver%run%law_in_force()
        seconds_assembly = results%solver%seconds_assembly
        results%solver = solution%record
        results%solver%seconds_assembly = seconds_assembly
        associate (res => solution%contact)
            results%elements%ds = res%ds
            results%elements%dn = res%dn
            results%elements%state = res%state
            results%elements%shear_traction = res%shear_traction
            results%elements%normal_traction = res%normal_traction
        end associate
        ! The strengths in force are results where they can change (as a one-shot solve's).
        if (law%beyond_coulomb()) then
            results%elements%sf_in_force = law%sf_in_force
            results%elements%tensile_in_force = law%tensile_in_force
            results%elements%mu_in_force = law%mu_in_force
        end if
        call find_tips_and_k(solver%run, solver%run%medium, model, load, results)
    end subroutine solve_contact_on

end module ddc_growth_solver
