!> Solve one model: a contact run prepared and stepped once (ddc_run_contact_run), then
!> element results, tips and fields. The heavy work of a distributed run goes to an engine
!> (ddc_run_engine): its operator, midpoint responses and fields.
module ddc_run_model
    !$ use omp_lib, only: omp_get_max_threads
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, domain_half_plane
    use ddc_model_results, only: model_results
    use ddc_model_medium, only: elastic_medium, medium_of
    use ddc_model_loads, only: shear_modulus_of
    use ddc_contact_fault_law, only: fault_law
    use ddc_influence_response, only: midpoint_response, kernel_response
    use ddc_influence_body, only: prepare_body, body_load, boundary_values
    use ddc_solve_elastic, only: row_kinds
    use ddc_solve_hierarchical, only: hierarchical_response, hierarchical_field
    use ddc_solve_joints, only: elastic_dds
    use ddc_solve_operator, only: elastic_operator, elastic_load
    use ddc_post_fields, only: evaluate_field
    use ddc_run_engine, only: model_engine
    use ddc_run_contact_run, only: contact_run, contact_step, load_of
    use ddc_post_tips, only: find_tips
    use ddc_progress, only: report_progress, reports_phases
    use ddc_text, only: itoa, seconds_text
    implicit none
    private

    public :: run_model, finish_model, evaluate_fields, model_load, wall_seconds
    public :: prepare_model_body, find_tips_and_k

    !> A field of at least this many point-element pairs reports its end (progress)
    real(wp), parameter :: field_report_pairs = 1.0e8_wp

contains

    !> Wall-clock seconds since an arbitrary origin.
    real(wp) function wall_seconds()
        integer(int64) :: count, rate

        call system_clock(count, rate)
        wall_seconds = real(count, wp) / real(rate, wp)
    end function wall_seconds

    !> Solve a validated model and compute every result the output needs: a contact run
    !> prepared and stepped once (ddc_run_contact_run), then finish_model.
    subroutine run_model(model, results, error, engine, ds_previous, strengths)
        !> A validated model with element geometry computed
        type(model_type), intent(in) :: model
        !> Element results, tips, fields and the solver record
        type(model_results), intent(out) :: results
        !> Set when the model has no solution or the solver failed
        type(error_type), allocatable, intent(out) :: error
        !> The engine of a distributed run (default: the work is done in this process)
        class(model_engine), intent(inout), optional :: engine
        !> Total slip of every element before this solve (friction memory of a growth run
        !> under a loading history; default 0; not with an engine), shape (n) [length]
        real(wp), intent(in), optional :: ds_previous(:)
        !> The fault law of every element: on entry the values in force and slip path before
        !> this solve (with ds_previous; not with an engine), on return those after it
        !> (contact models)
        type(fault_law), intent(inout), optional :: strengths
        type(contact_run), target :: run
        type(contact_step) :: solution
        type(elastic_load) :: load
        class(elastic_operator), allocatable :: operator
        type(fault_law) :: law
        type(elastic_medium) :: medium
        real(wp) :: t_start, t_free
        integer :: n

        t_start = wall_seconds()
        ! The input readers check this too; a sweep may change the remote stress after them.
        if (model%elements%domain == domain_half_plane .and. (model%syy /= 0.0_wp .or. &
            model%sxy /= 0.0_wp .or. model%stress_gradient(3) /= 0.0_wp)) then
            call set_error(error, exit_bad_input, 'half-plane: the remote syy, sxy and '// &
                           'dsxy_dy must be 0 (traction-free surface y = 0)')
            return
        end if
        n = model%elements%n
        medium = medium_of(model)
        if (allocated(medium%body)) then
            if (.not. allocated(medium%body%factors)) call prepare_body(medium%body, &
                medium%shear_modulus, medium%poissons_ratio, error)
            if (allocated(error)) return
        end if
        if (present(engine)) then
            call engine%make_operator(medium, operator, error)
            if (.not. allocated(error)) call run%prepare(medium, model%solver, error, operator)
        else
            call run%prepare(medium, model%solver, error)
        end if
        if (allocated(error)) then
            call run%finish()
            return
        end if
        load = model_load(model, medium)
        if (present(ds_previous)) call run%hold(ds_previous, strengths)
        call run%step(load, solution, error)
        if (allocated(error)) then
            call run%finish()
            return
        end if
        results%solver = run%record_of(solution)
        associate (e => results%elements, rec => results%solver)
            call move_alloc(solution%ds, e%ds)
            call move_alloc(solution%dn, e%dn)
            call move_alloc(solution%state, e%state)
            if (run%operator%nc > 0) then
                law = run%law_in_force()
                if (present(strengths)) strengths = law
                e%sf_in_force = law%sf_in_force
                e%tensile_in_force = law%tensile_in_force
                e%mu_in_force = law%mu_in_force
            end if
            if (reports_phases(n)) call report_progress('solved ('//rec%method//') in '// &
                seconds_text(wall_seconds() - t_start))
        end associate
        if (frees_before_responses(run, present(engine))) then
            ! The midpoint responses of a hierarchical solve assemble matrices of their own:
            ! the run's are freed first, so that the peak holds one set; K (whose local
            ! re-solve solves the model again) comes first, from the run's tractions.
            t_free = wall_seconds()
            allocate (results%elements%shear_traction(n), results%elements%normal_traction(n))
            call run%free_tractions(load, solution, results%elements%shear_traction, &
                                    results%elements%normal_traction, error)
            if (allocated(error)) then
                call run%finish()
                return
            end if
            call find_tips_and_k(run, medium, model, load, results)
            deallocate (results%elements%shear_traction, results%elements%normal_traction)
            call run%finish()
            t_free = wall_seconds() - t_free
            call finish_model(model, load, results, engine=engine, tips_found=.true., &
                              prepared=medium)
            results%solver%seconds_fields = results%solver%seconds_fields + t_free
        else
            call finish_model(model, load, results, run=run, engine=engine, prepared=medium)
            ! Freeing the influence matrix (32 n^2 bytes) ends the phase of its last use.
            t_free = wall_seconds()
            call run%finish()
            results%solver%seconds_fields = results%solver%seconds_fields + wall_seconds() - &
                                            t_free
        end if
        if (.not. allocated(law%shear_stiffness)) then
            continue
        else if (law%has_joints()) then
            associate (e => results%elements)
                allocate (e%ds_elastic(n), e%dn_elastic(n))
                call elastic_dds(law%joint_compliance(), load%pressure, e%shear_traction, &
                                 e%normal_traction, e%ds_elastic, e%dn_elastic)
            end associate
        end if
        results%solver%seconds_total = wall_seconds() - t_start
    end subroutine run_model

    !> A finite body's equations solved once for the whole run (a growth run's geometries
    !> share them: the body does not change); nothing without a body.
    subroutine prepare_model_body(model, error)
        !> The model; model%body's system is set
        type(model_type), intent(inout) :: model
        !> Set when the body's equations cannot be solved or its tractions do not balance
        type(error_type), allocatable, intent(out) :: error

        if (.not. allocated(model%body)) return
        call prepare_body(model%body, shear_modulus_of(model), model%poissons_ratio, error)
    end subroutine prepare_model_body

    !> Whether the run's operator is freed before the midpoint responses: a hierarchical
    !> operator of contact elements alone (its own tractions are those of its solution), in
    !> this process.
    logical function frees_before_responses(run, with_engine)
        type(contact_run), intent(in) :: run
        logical, intent(in) :: with_engine

        frees_before_responses = .false.
        if (with_engine .or. .not. allocated(run%operator)) return
        frees_before_responses = .not. associated(run%operator%whole) .and. &
                                 run%operator%nf == 0 .and. run%operator%nc > 0
    end function frees_before_responses

    !> The tips of solved DDs and their K by the run's K method (the run at the load the DDs
    !> were solved for; the elements' DDs, states, tractions and friction in force set).
    subroutine find_tips_and_k(run, medium, model, load, results)
        type(contact_run), intent(inout) :: run
        type(elastic_medium), intent(in) :: medium
        type(model_type), intent(in) :: model
        type(elastic_load), intent(in) :: load
        type(model_results), intent(inout) :: results
        real(wp), allocatable :: k1(:), k2(:)

        call find_tips(medium, results%elements%ds, results%elements%dn, results%tips)
        allocate (k1(results%tips%n), k2(results%tips%n))
        call run%tip_k(load, results%elements, model%growth%active, results%tips, k1, k2)
        results%tips%k1 = k1
        results%tips%k2 = k2
    end subroutine find_tips_and_k

    !> The load of a model at its remote stress and pore fluid (and its finite body's given
    !> values: the medium prepared for it).
    pure function model_load(model, prepared) result(load)
        !> The model
        type(model_type), intent(in) :: model
        !> Its medium, a finite body's system solved (default: medium_of the model)
        type(elastic_medium), intent(in), optional :: prepared
        type(elastic_load) :: load

        if (present(prepared)) then
            load = load_of(prepared, [model%sxx, model%syy, model%sxy], &
                           model%stress_gradient, model%pore_fluid)
        else
            load = load_of(medium_of(model), [model%sxx, model%syy, model%sxy], &
                           model%stress_gradient, model%pore_fluid)
        end if
    end function model_load

    !> The results that follow from the DDs of a solved model (results%elements%ds, dn,
    !> state): tractions and face displacements at the midpoints (from the influence matrix
    !> in memory: the run's or the given one, ddc_influence_response; from the engine; or
    !> from hierarchical matrices), tips with K by the run's K method, and the fields; the
    !> time goes to results%solver%seconds_fields, and the number of threads is recorded.
    subroutine finish_model(model, load, results, matrix, engine, run, tips_found, prepared)
        !> The model at the load the DDs were solved for
        type(model_type), intent(in) :: model
        !> That load
        type(elastic_load), intent(in) :: load
        !> ds, dn and state set on entry; tractions, face displacements, tips and fields added
        type(model_results), intent(inout) :: results
        !> The influence matrix of the solve, rows as row_kinds of the elements' conditions,
        !> shape (2n, 2n) (a growth run's kept matrix)
        real(wp), intent(in), optional :: matrix(:, :)
        !> The engine of a distributed run
        class(model_engine), intent(inout), optional :: engine
        !> The contact run of the solve: its matrix and its K method
        type(contact_run), intent(inout), optional, target :: run
        !> results%tips are found and have their K (find_tips_and_k; default: not yet)
        logical, intent(in), optional :: tips_found
        !> The model's medium, a finite body's system solved (default: medium_of the model)
        type(elastic_medium), intent(in), optional :: prepared
        type(contact_run), target :: k_only
        type(contact_run), pointer :: k_run
        type(elastic_medium) :: medium
        integer, allocatable :: shear_row(:), normal_row(:)
        type(error_type), allocatable :: failed
        real(wp), pointer, contiguous :: whole(:, :)
        real(wp) :: t0
        logical :: found
        integer :: n

        t0 = wall_seconds()
        n = model%elements%n
        if (present(prepared)) then
            call finish_in(prepared)
        else
            medium = medium_of(model)
            call finish_in(medium)
        end if

    contains

        !> The work, in the medium m (the prepared one, not copied: a finite body's
        !> factors are large).
        subroutine finish_in(m)
            type(elastic_medium), intent(in) :: m

            results%solver%threads = 1
            !$ results%solver%threads = omp_get_max_threads()
            whole => null()
            if (present(run) .and. .not. present(matrix)) then
                if (allocated(run%operator)) whole => run%operator%whole
            end if
            associate (e => results%elements)
                allocate (e%shear_traction(n), e%normal_traction(n), e%us_minus(n), e%un_minus(n))
                if (present(engine)) then
                    call engine%midpoint_response(m, e%ds, e%dn, e%shear_traction, &
                                                  e%normal_traction, e%us_minus, e%un_minus)
                else if (present(matrix) .or. associated(whole)) then
                    allocate (shear_row(n), normal_row(n))
                    call row_kinds(model%elements%condition, shear_row, normal_row)
                    if (present(matrix)) then
                        call midpoint_response(m, matrix, shear_row, normal_row, e%ds, e%dn, &
                                               e%shear_traction, e%normal_traction, e%us_minus, &
                                               e%un_minus)
                    else
                        call midpoint_response(m, whole, shear_row, normal_row, e%ds, e%dn, &
                                               e%shear_traction, e%normal_traction, e%us_minus, &
                                               e%un_minus)
                    end if
                else
                    ! A hierarchical solve keeps no dense matrix: products with hierarchical
                    ! ones, or the kernel sums where hmat-oss fails.
                    call hierarchical_response(m, e%ds, e%dn, model%solver, e%shear_traction, &
                                               e%normal_traction, e%us_minus, e%un_minus, failed)
                    if (allocated(failed)) call kernel_response(m, e%ds, e%dn, &
                        e%shear_traction, e%normal_traction, e%us_minus, e%un_minus)
                end if
                e%shear_traction = e%shear_traction + load%shear
                e%normal_traction = e%normal_traction + load%normal
                if (allocated(m%body)) then
                    call add_body_displacement(m, e%us_minus, e%un_minus)
                    call boundary_values(m, e%ds, e%dn, results%boundary)
                end if
                ! ds = us(-) - us(+), dn = un(-) - un(+)
                e%us_plus = e%us_minus - e%ds
                e%un_plus = e%un_minus - e%dn
                found = .false.
                if (present(tips_found)) found = tips_found
                if (.not. found) then
                    if (present(run)) then
                        k_run => run
                    else
                        call k_only%start(m, model%solver)
                        k_run => k_only
                    end if
                    call find_tips_and_k(k_run, m, model, load, results)
                end if
                if (reports_phases(n)) call report_progress('tractions, face displacements '// &
                    'and tips done in '//seconds_text(wall_seconds() - t0))
            end associate
            call evaluate_fields(model, results, engine, m)
            results%solver%seconds_fields = wall_seconds() - t0
        end subroutine finish_in
    end subroutine finish_model

    !> Adds the displacement of a finite body's given values (every fracture closed) to the
    !> face displacements along s and n of the elements.
    pure subroutine add_body_displacement(medium, us, un)
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(inout) :: us(:), un(:)
        real(wp), dimension(size(us)) :: shear, normal, us_body, un_body

        call body_load(medium, shear, normal, us_body, un_body)
        us = us + us_body
        un = un + un_body
    end subroutine add_body_displacement

    !> The fields at every observation set of the model for the DDs in results (allocates
    !> results%fields, one per observation set).
    subroutine evaluate_fields(model, results, engine, prepared)
        !> The solved model
        type(model_type), intent(in) :: model
        !> Its element results; the fields are set
        type(model_results), intent(inout) :: results
        !> The engine of a distributed run (default: the work is done in this process)
        class(model_engine), intent(inout), optional :: engine
        !> The model's medium, a finite body's system solved (default: medium_of the model)
        type(elastic_medium), intent(in), optional :: prepared
        type(error_type), allocatable :: failed
        type(elastic_medium) :: medium
        real(wp) :: t0
        integer :: i

        t0 = wall_seconds()
        if (present(prepared)) then
            call fields_in(prepared)
        else
            medium = medium_of(model)
            call fields_in(medium)
        end if

    contains

        !> The work, in the medium m (the prepared one, not copied).
        subroutine fields_in(m)
            type(elastic_medium), intent(in) :: m

            if (allocated(results%fields)) deallocate (results%fields)
            if (allocated(model%observations)) then
                allocate (results%fields(size(model%observations)))
            else
                allocate (results%fields(0))
            end if
            do i = 1, size(results%fields)
                associate (remote => [model%sxx, model%syy, model%sxy], &
                           o => model%observations(i), e => results%elements)
                    if (present(engine)) then
                        call engine%evaluate_field(m, remote, e%ds, e%dn, o%x, o%y, &
                                                   results%fields(i), model%stress_gradient)
                    else if (results%solver%hierarchical) then
                        ! Products with a compressed field matrix, or the sums where hmat-oss
                        ! fails.
                        call hierarchical_field(m, remote, model%stress_gradient, e%ds, e%dn, &
                                                o%x, o%y, model%solver, results%fields(i), failed)
                        if (allocated(failed)) call evaluate_field(m, remote, e%ds, e%dn, &
                            o%x, o%y, results%fields(i), model%stress_gradient)
                    else
                        call evaluate_field(m, remote, e%ds, e%dn, o%x, o%y, &
                                            results%fields(i), model%stress_gradient)
                    end if
                    if (reports_phases(model%elements%n) .or. real(model%elements%n, wp) * &
                        real(size(o%x), wp) >= field_report_pairs) call report_progress('field '// &
                        o%name//' ('//itoa(size(o%x))//' points) done after '// &
                        seconds_text(wall_seconds() - t0))
                end associate
            end do
        end subroutine fields_in
    end subroutine evaluate_fields

end module ddc_run_model
