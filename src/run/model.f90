!> Solve one model: influence, solve, then element results, tips and fields. The heavy
!> work goes to an engine (ddc_run_engine): this process alone by default, or the processes
!> of a distributed run.
module ddc_run_model
    !$ use omp_lib, only: omp_get_max_threads
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, element_set, condition_contact, domain_half_plane
    use ddc_model_results, only: model_results, solver_record, state_free
    use ddc_model_loads, only: resolve_remote_stress, total_pressure, shear_modulus_of
    use ddc_contact_options, only: solver_options, matrix_hierarchical
    use ddc_contact_fault_law, only: fault_law
    use ddc_influence_response, only: midpoint_response, kernel_response
    use ddc_solve_elastic, only: solve_elastic, row_kinds
    use ddc_solve_hierarchical, only: solve_hierarchical, hierarchical_response, &
        hierarchical_field
    use ddc_solve_frictional, only: solve_frictional
    use ddc_solve_joints, only: elastic_dds
    use ddc_post_fields, only: evaluate_field
    use ddc_run_engine, only: model_engine
    use ddc_post_tips, only: find_tips
    use ddc_post_higher_order_k, only: higher_order_solver, prepare_higher_order, &
        higher_order_k, uses_higher_order
    use ddc_progress, only: report_progress, reports_phases
    use ddc_text, only: itoa, seconds_text
    implicit none
    private

    public :: run_model, finish_model, evaluate_fields

    !> A field of at least this many point-element pairs reports its end (progress)
    real(wp), parameter :: field_report_pairs = 1.0e8_wp

contains

    !> Wall-clock seconds since an arbitrary origin.
    real(wp) function wall_seconds()
        integer(int64) :: count, rate

        call system_clock(count, rate)
        wall_seconds = real(count, wp) / real(rate, wp)
    end function wall_seconds

    !> Solve a validated model and compute every result the output needs.
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
        real(wp), allocatable :: remote_shear(:), remote_normal(:), matrix(:, :)
        type(fault_law) :: law
        type(element_set) :: loaded
        real(wp) :: g, nu, t_start, t_free
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
        g = shear_modulus_of(model)
        nu = model%poissons_ratio

        allocate (remote_shear(n), remote_normal(n))
        call resolve_remote_stress(model%elements, model%sxx, model%syy, model%sxy, &
                                   remote_shear, remote_normal, model%stress_gradient)
        associate (e => results%elements, rec => results%solver)
            allocate (e%ds(n), e%dn(n), e%state(n))
            ! The contact elements see their pressure plus the pore fluid.
            loaded = model%elements
            loaded%pressure = total_pressure(model%elements, model%pore_fluid)
            if (present(engine)) then
                call engine%solve(loaded, g, nu, remote_shear, remote_normal, model%solver, &
                                  e%ds, e%dn, e%state, rec, error, law)
            else
                call solve_here(loaded, g, nu, remote_shear, remote_normal, model%solver, e%ds, &
                                e%dn, e%state, rec, matrix, error, law, ds_previous, strengths)
            end if
            if (allocated(error)) return
            if (allocated(law%sf_in_force)) then
                if (present(strengths)) strengths = law
                e%sf_in_force = law%sf_in_force
                e%tensile_in_force = law%tensile_in_force
                e%mu_in_force = law%mu_in_force
            end if
            if (reports_phases(n)) call report_progress('solved ('//rec%method//') in '// &
                seconds_text(wall_seconds() - t_start))
        end associate
        if (present(engine)) then
            call finish_model(model, remote_shear, remote_normal, results, engine=engine)
        else
            call finish_model(model, remote_shear, remote_normal, results, matrix=matrix)
            ! Freeing the influence matrix (32 n^2 bytes) ends the phase of its last use.
            t_free = wall_seconds()
            if (allocated(matrix)) deallocate (matrix)
            results%solver%seconds_fields = results%solver%seconds_fields + wall_seconds() - &
                t_free
        end if
        if (allocated(law%shear_stiffness)) then
            if (law%has_joints()) then
                associate (e => results%elements)
                    allocate (e%ds_elastic(n), e%dn_elastic(n))
                    call elastic_dds(law%joint_compliance(), loaded%pressure, &
                                     e%shear_traction, e%normal_traction, e%ds_elastic, &
                                     e%dn_elastic)
                end associate
            end if
        end if
        results%solver%seconds_total = wall_seconds() - t_start
    end subroutine run_model

    !> The results that follow from the DDs of a solved model (results%elements%ds, dn):
    !> tractions and face displacements at the midpoints (from the matrix of the solve,
    !> ddc_influence_response, or from the engine), tips with K and the fields; the time
    !> goes to results%solver%seconds_fields, and the number of threads is recorded.
    subroutine finish_model(model, remote_shear, remote_normal, results, matrix, engine, &
                            higher_order)
        !> The model at the load the DDs were solved for
        type(model_type), intent(in) :: model
        !> Remote stress resolved on each element [stress unit], shape (n)
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        !> ds and dn set on entry; tractions, face displacements, tips and fields added
        type(model_results), intent(inout) :: results
        !> The influence matrix of the solve in this process, rows as row_kinds of the
        !> elements' conditions, shape (2n, 2n) (without an engine)
        real(wp), intent(in), optional :: matrix(:, :)
        !> The engine of a distributed run
        class(model_engine), intent(inout), optional :: engine
        !> The higher-order re-solve of this geometry where the caller has it (a loading
        !> history)
        type(higher_order_solver), intent(inout), optional :: higher_order
        integer, allocatable :: shear_row(:), normal_row(:)
        type(error_type), allocatable :: failed
        real(wp) :: g, nu, t0
        integer :: n

        t0 = wall_seconds()
        n = model%elements%n
        g = shear_modulus_of(model)
        nu = model%poissons_ratio
        results%solver%threads = 1
        !$ results%solver%threads = omp_get_max_threads()
        associate (e => results%elements)
            allocate (e%shear_traction(n), e%normal_traction(n), e%us_minus(n), e%un_minus(n))
            if (present(engine)) then
                call engine%midpoint_response(model%elements, g, nu, e%ds, e%dn, &
                                              e%shear_traction, e%normal_traction, e%us_minus, &
                                              e%un_minus)
            else if (.not. present(matrix)) then
                ! A hierarchical solve keeps no dense matrix: products with hierarchical
                ! ones, or the kernel sums where hmat-oss fails.
                call hierarchical_response(model%elements, g, nu, e%ds, e%dn, model%solver, &
                                           e%shear_traction, e%normal_traction, e%us_minus, &
                                           e%un_minus, failed)
                if (allocated(failed)) call kernel_response(model%elements, g, nu, e%ds, &
                    e%dn, e%shear_traction, e%normal_traction, e%us_minus, e%un_minus)
            else
                allocate (shear_row(n), normal_row(n))
                call row_kinds(model%elements%condition, shear_row, normal_row)
                call midpoint_response(model%elements, g, nu, matrix, shear_row, normal_row, &
                                       e%ds, e%dn, e%shear_traction, e%normal_traction, &
                                       e%us_minus, e%un_minus)
            end if
            e%shear_traction = e%shear_traction + remote_shear
            e%normal_traction = e%normal_traction + remote_normal
            ! ds = us(-) - us(+), dn = un(-) - un(+)
            e%us_plus = e%us_minus - e%ds
            e%un_plus = e%un_minus - e%dn
            call find_tips(model%elements, g, nu, e%ds, e%dn, results%tips)
            call higher_order_tip_k(model, results, higher_order)
            if (reports_phases(n)) call report_progress('tractions, face displacements '// &
                'and tips done in '//seconds_text(wall_seconds() - t0))
        end associate
        call evaluate_fields(model, results, engine)
        results%solver%seconds_fields = wall_seconds() - t0
    end subroutine finish_model

    !> The tips' K by the higher-order re-solve where &solver k_method asks for it
    !> (docs/theory/tips.md#choosing-the-method); elsewhere, and where the re-solve's matrix
    !> is singular, the tip element's K of find_tips stays, and tips%k_method says why.
    subroutine higher_order_tip_k(model, results, prepared)
        !> The model at the load the DDs were solved for
        type(model_type), intent(in) :: model
        !> Element results and tips (find_tips) on entry; K replaced
        type(model_results), intent(inout) :: results
        !> The re-solve of this geometry where the caller has it
        type(higher_order_solver), intent(inout), optional :: prepared
        type(higher_order_solver) :: solver
        type(error_type), allocatable :: failed
        character(len=:), allocatable :: why_not
        logical :: uses

        call uses_higher_order(model%solver%k_method, model%growth%active, model%elements, &
                               results%tips, uses, why_not)
        if (.not. uses) then
            if (len(why_not) > 0) results%tips%k_method = 'tip_element ('//why_not//')'
            return
        end if
        if (present(prepared)) then
            call tip_k_of(prepared)
        else
            call prepare_higher_order(model%elements, shear_modulus_of(model), &
                                      model%poissons_ratio, results%tips, solver, failed)
            if (.not. allocated(failed)) call tip_k_of(solver)
        end if
        if (allocated(failed)) results%tips%k_method = &
            'tip_element (the higher-order re-solve failed: '//failed%message//')'

    contains

        subroutine tip_k_of(re_solve)
            type(higher_order_solver), intent(inout) :: re_solve
            real(wp), allocatable :: k1(:), k2(:), mu(:)

            associate (e => results%elements, t => results%tips)
                allocate (k1(t%n), k2(t%n), mu(model%elements%n))
                k1 = t%k1
                k2 = t%k2
                if (allocated(e%mu_in_force)) then
                    mu = e%mu_in_force
                else
                    mu = model%elements%mu
                end if
                call higher_order_k(re_solve, model%elements, shear_modulus_of(model), &
                                    model%poissons_ratio, e%ds, e%dn, e%shear_traction, &
                                    e%normal_traction, mu, [model%sxx, model%syy, model%sxy], &
                                    model%stress_gradient, e%state, t, k1, k2, failed)
                if (allocated(failed)) return
                t%k1 = k1
                t%k2 = k2
                where (re_solve%local(t%element) > 0) t%graded = 0
                t%k_method = 'higher_order'
            end associate
        end subroutine tip_k_of
    end subroutine higher_order_tip_k

    !> The fields at every observation set of the model for the DDs in results (allocates
    !> results%fields, one per observation set).
    subroutine evaluate_fields(model, results, engine)
        !> The solved model
        type(model_type), intent(in) :: model
        !> Its element results; the fields are set
        type(model_results), intent(inout) :: results
        !> The engine of a distributed run (default: the work is done in this process)
        class(model_engine), intent(inout), optional :: engine
        type(error_type), allocatable :: failed
        real(wp) :: t0
        integer :: i

        t0 = wall_seconds()
        if (allocated(results%fields)) deallocate (results%fields)
        if (allocated(model%observations)) then
            allocate (results%fields(size(model%observations)))
        else
            allocate (results%fields(0))
        end if
        do i = 1, size(results%fields)
            associate (remote => [model%sxx, model%syy, model%sxy], o => model%observations(i), &
                       e => results%elements)
                if (present(engine)) then
                    call engine%evaluate_field(model%elements, shear_modulus_of(model), &
                                               model%poissons_ratio, remote, e%ds, e%dn, o%x, &
                                               o%y, results%fields(i), model%stress_gradient)
                else if (results%solver%hierarchical) then
                    ! Products with a compressed field matrix, or the sums where hmat-oss
                    ! fails.
                    call hierarchical_field(model%elements, shear_modulus_of(model), &
                                            model%poissons_ratio, remote, &
                                            model%stress_gradient, e%ds, e%dn, o%x, o%y, &
                                            model%solver, results%fields(i), failed)
                    if (allocated(failed)) call evaluate_field(model%elements, &
                        shear_modulus_of(model), model%poissons_ratio, remote, e%ds, e%dn, &
                        o%x, o%y, results%fields(i), model%stress_gradient)
                else
                    call evaluate_field(model%elements, shear_modulus_of(model), &
                                        model%poissons_ratio, remote, e%ds, e%dn, o%x, o%y, &
                                        results%fields(i), model%stress_gradient)
                end if
                if (reports_phases(model%elements%n) .or. real(model%elements%n, wp) * &
                    real(size(o%x), wp) >= field_report_pairs) call report_progress('field '// &
                    o%name//' ('//itoa(size(o%x))//' points) done after '// &
                    seconds_text(wall_seconds() - t0))
            end associate
        end do
    end subroutine evaluate_fields

    !> The solve in this process: contact models by solve_frictional, the others by
    !> solve_elastic (method 'lu'); the influence matrix of the solve is handed back.
    subroutine solve_here(elements, shear_modulus, nu, remote_shear, remote_normal, options, &
                          ds, dn, state, record, matrix, error, law, ds_previous, law_start)
        type(element_set), intent(in) :: elements
        real(wp), intent(in) :: shear_modulus, nu
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        type(solver_options), intent(in) :: options
        real(wp), intent(out) :: ds(:), dn(:)
        integer, intent(out) :: state(:)
        type(solver_record), intent(inout) :: record
        real(wp), allocatable, intent(out) :: matrix(:, :)
        type(error_type), allocatable, intent(out) :: error
        !> The fault law of every element with the values in force at the end (contact
        !> models; not allocated otherwise)
        type(fault_law), intent(out) :: law
        !> Total slip before this solve (default 0), shape (n) [length]
        real(wp), intent(in), optional :: ds_previous(:)
        !> Values in force and slip path before this solve (default: the given values)
        type(fault_law), intent(in), optional :: law_start

        if (any(elements%condition == condition_contact)) then
            call solve_frictional(elements, shear_modulus, nu, remote_shear, remote_normal, &
                                  options, ds, dn, state, record, matrix, error, law, &
                                  ds_previous, law_start)
        else if (options%matrix == matrix_hierarchical) then
            record%method = 'lu'
            record%hierarchical = .true.
            record%hmatrix_tolerance = options%hmatrix_tolerance
            call solve_hierarchical(elements, shear_modulus, nu, remote_shear, remote_normal, &
                                    options, ds, dn, record%equilibrium_residual, &
                                    record%compression_ratio, record%seconds_assembly, &
                                    record%counts%seconds, error)
            state = state_free
        else
            record%method = 'lu'
            call solve_elastic(elements, shear_modulus, nu, remote_shear, remote_normal, ds, dn, &
                               record%equilibrium_residual, record%seconds_assembly, &
                               record%counts%seconds, matrix, error)
            state = state_free
        end if
    end subroutine solve_here

end module ddc_run_model
