!> An engine that does the heavy work of one model run in its own way: the elastic
!> operator of the contact run, the midpoint responses and the fields. run_model
!> (ddc_run_model) holds the steps around them once and does the work in this process when
!> given no engine; a distributed engine (src/parallel/, MPI build) spreads it over
!> processes.
module ddc_run_engine
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_medium, only: elastic_medium
    use ddc_model_results, only: field_result
    use ddc_solve_operator, only: elastic_operator
    implicit none
    private

    public :: model_engine

    !> What a model run needs done; every procedure is called by every process of a
    !> distributed run with the same arguments.
    type, abstract :: model_engine
    contains
        !> The operator the contact run solves on
        procedure(operator_interface), deferred :: make_operator
        !> Induced tractions and face displacements at every element midpoint
        procedure(response_interface), deferred :: midpoint_response
        !> Displacement and stress at observation points
        procedure(field_interface), deferred :: evaluate_field
    end type model_engine

    abstract interface
        !> The elastic operator of a medium that the contact run of the model solves on
        !> (ddc_solve_operator), timed into its record.
        subroutine operator_interface(this, medium, operator, error)
            import :: model_engine, elastic_medium, elastic_operator, error_type
            implicit none
            !> The engine
            class(model_engine), intent(inout) :: this
            !> The medium, geometry computed
            type(elastic_medium), intent(in) :: medium
            !> The operator
            class(elastic_operator), allocatable, intent(out) :: operator
            !> Set when the operator cannot be made
            type(error_type), allocatable, intent(out) :: error
        end subroutine operator_interface

        !> Induced tractions and negative-face displacements at every element midpoint.
        subroutine response_interface(this, medium, ds, dn, shear_traction, normal_traction, &
                                      us_minus, un_minus)
            import :: model_engine, elastic_medium, wp
            implicit none
            !> The engine
            class(model_engine), intent(inout) :: this
            !> The medium, element geometry computed
            type(elastic_medium), intent(in) :: medium
            !> Displacement discontinuities [length unit], shape (n)
            real(wp), intent(in) :: ds(:), dn(:)
            !> Induced shear and normal traction [stress unit], shape (n)
            real(wp), intent(out) :: shear_traction(:), normal_traction(:)
            !> Negative-face displacement along s and n [length unit], shape (n)
            real(wp), intent(out) :: us_minus(:), un_minus(:)
        end subroutine response_interface

        !> Fields at observation points (ddc_post_fields' evaluate_field).
        subroutine field_interface(this, medium, remote, ds, dn, x, y, field, gradient)
            import :: model_engine, elastic_medium, field_result, wp
            implicit none
            !> The engine
            class(model_engine), intent(inout) :: this
            !> The medium, element geometry computed
            type(elastic_medium), intent(in) :: medium
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
