!> An engine that does the heavy work of one model run in its own way: the solve, the
!> midpoint responses and the fields. run_model (ddc_run_model) holds the steps around them
!> once and does the work in this process when given no engine; a distributed engine
!> (src/parallel/, MPI build) spreads it over processes.
module ddc_run_engine
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_types, only: element_set
    use ddc_model_results, only: solver_record, field_result
    use ddc_contact_options, only: solver_options
    use ddc_contact_fault_law, only: fault_law
    implicit none
    private

    public :: model_engine

    !> What a model run needs done; every procedure is called by every process of a
    !> distributed run with the same arguments.
    type, abstract :: model_engine
    contains
        !> Displacement discontinuities, states and the solver record
        procedure(solve_interface), deferred :: solve
        !> Induced tractions and face displacements at every element midpoint
        procedure(response_interface), deferred :: midpoint_response
        !> Displacement and stress at observation points
        procedure(field_interface), deferred :: evaluate_field
    end type model_engine

    abstract interface
        !> Solve for the DDs of every element (contact elements with the contact solver,
        !> TWODD-style ones by their conditions).
        subroutine solve_interface(this, elements, shear_modulus, nu, remote_shear, &
                                   remote_normal, options, ds, dn, state, record, error, &
                                   law)
            import :: model_engine, element_set, solver_options, solver_record, error_type, &
                fault_law, wp
            implicit none
            !> The engine
            class(model_engine), intent(inout) :: this
            !> Elements with geometry computed; contact elements carry their total pressure
            type(element_set), intent(in) :: elements
            !> Shear modulus [stress unit] and Poisson's ratio [-]
            real(wp), intent(in) :: shear_modulus, nu
            !> Remote stress resolved on each element [stress unit], shape (n)
            real(wp), intent(in) :: remote_shear(:), remote_normal(:)
            !> Options of the contact solver
            type(solver_options), intent(in) :: options
            !> Displacement discontinuities [length unit], shape (n)
            real(wp), intent(out) :: ds(:), dn(:)
            !> Element states (state_free for TWODD-style elements), shape (n)
            integer, intent(out) :: state(:)
            !> Method, residual, certificate and timings are filled in
            type(solver_record), intent(inout) :: record
            !> Set when the model has no solution or the solver failed
            type(error_type), allocatable, intent(out) :: error
            !> The fault law of every element with the values in force at the end (contact
            !> models; see ddc_solve_frictional)
            type(fault_law), intent(out), optional :: law
        end subroutine solve_interface

        !> Induced tractions and negative-face displacements at every element midpoint.
        subroutine response_interface(this, elements, shear_modulus, nu, ds, dn, &
                                      shear_traction, normal_traction, us_minus, un_minus)
            import :: model_engine, element_set, wp
            implicit none
            !> The engine
            class(model_engine), intent(inout) :: this
            !> Elements with geometry computed
            type(element_set), intent(in) :: elements
            !> Shear modulus [stress unit] and Poisson's ratio [-]
            real(wp), intent(in) :: shear_modulus, nu
            !> Displacement discontinuities [length unit], shape (n)
            real(wp), intent(in) :: ds(:), dn(:)
            !> Induced shear and normal traction [stress unit], shape (n)
            real(wp), intent(out) :: shear_traction(:), normal_traction(:)
            !> Negative-face displacement along s and n [length unit], shape (n)
            real(wp), intent(out) :: us_minus(:), un_minus(:)
        end subroutine response_interface

        !> Fields at observation points (ddc_post_fields' evaluate_field).
        subroutine field_interface(this, elements, shear_modulus, nu, remote, ds, dn, x, y, &
                                   field, gradient)
            import :: model_engine, element_set, field_result, wp
            implicit none
            !> The engine
            class(model_engine), intent(inout) :: this
            !> Elements with geometry computed
            type(element_set), intent(in) :: elements
            !> Shear modulus [stress unit] and Poisson's ratio [-]
            real(wp), intent(in) :: shear_modulus, nu
            !> Remote stress (sxx, syy, sxy) at y = 0 [stress unit]
            real(wp), intent(in) :: remote(3)
            !> Displacement discontinuities [length unit], shape (n)
            real(wp), intent(in) :: ds(:), dn(:)
            !> Observation points [length unit], shape (npoints)
            real(wp), intent(in) :: x(:), y(:)
            !> Fields at the points (a distributed engine completes them on the first
            !> process only)
            type(field_result), intent(out) :: field
            !> d(sxx, syy, sxy)/dy of the remote stress [stress unit / length unit]
            real(wp), intent(in) :: gradient(3)
        end subroutine field_interface
    end interface

end module ddc_run_engine
