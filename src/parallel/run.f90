!> The engine of a distributed run (ddc_run_engine): run_model's heavy work spread over the
!> processes. The contact run's operator is ddc_parallel_solve's; the midpoint responses
!> are split by elements and every process gets them all (O(n)); the fields are split by
!> points and gathered on the root, which alone writes them.
module ddc_parallel_run
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_medium, only: elastic_medium
    use ddc_model_results, only: field_result
    use ddc_solve_operator, only: elastic_operator
    use ddc_influence_response, only: kernel_response
    use ddc_post_fields, only: evaluate_field
    use ddc_run_engine, only: model_engine
    use ddc_parallel_context, only: parallel_context
    use ddc_parallel_collective, only: split_range, gather_on_root, gather_on_all
    use ddc_parallel_solve, only: distributed_operator, new_distributed_operator
    implicit none
    private

    public :: distributed_engine

    !> The processes doing one model's work.
    type, extends(model_engine) :: distributed_engine
        !> The processes and their grid (open)
        type(parallel_context) :: context
    contains
        procedure :: make_operator => distributed_make_operator
        procedure :: midpoint_response => distributed_response
        procedure :: evaluate_field => distributed_field
    end type distributed_engine

contains

    !> The medium's operator distributed over the engine's processes.
    subroutine distributed_make_operator(this, medium, operator, error)
        class(distributed_engine), intent(inout) :: this
        type(elastic_medium), intent(in) :: medium
        class(elastic_operator), allocatable, intent(out) :: operator
        type(error_type), allocatable, intent(out) :: error
        type(distributed_operator), allocatable :: distributed

        allocate (distributed)
        call new_distributed_operator(this%context, medium, distributed, error)
        if (.not. allocated(error)) call move_alloc(distributed, operator)
    end subroutine distributed_make_operator

    !> Each process computes the responses of its share of the elements; all get them all.
    subroutine distributed_response(this, medium, ds, dn, shear_traction, normal_traction, &
                                    us_minus, un_minus)
        class(distributed_engine), intent(inout) :: this
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: ds(:), dn(:)
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        real(wp), intent(out) :: us_minus(:), un_minus(:)
        real(wp), allocatable :: ts(:), tn(:), us(:), un(:)
        integer :: first, last

        call split_range(medium%elements%n, this%context%processes, this%context%rank, first, &
                         last)
        allocate (ts(first:last), tn(first:last), us(first:last), un(first:last))
        call kernel_response(medium, ds, dn, ts, tn, us, un, first)
        call gather_on_all(this%context, ts, shear_traction)
        call gather_on_all(this%context, tn, normal_traction)
        call gather_on_all(this%context, us, us_minus)
        call gather_on_all(this%context, un, un_minus)
    end subroutine distributed_response

    !> Each process evaluates its share of the points; the root gets them all.
    subroutine distributed_field(this, medium, remote, ds, dn, x, y, field, gradient)
        class(distributed_engine), intent(inout) :: this
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: remote(3)
        real(wp), intent(in) :: ds(:), dn(:)
        real(wp), intent(in) :: x(:), y(:)
        type(field_result), intent(out) :: field
        real(wp), intent(in) :: gradient(3)
        type(field_result) :: part
        integer :: first, last

        call split_range(size(x), this%context%processes, this%context%rank, first, last)
        call evaluate_field(medium, remote, ds, dn, x(first:last), y(first:last), part, &
                            gradient)
        call gather_on_root(this%context, part%ux, field%ux)
        call gather_on_root(this%context, part%uy, field%uy)
        call gather_on_root(this%context, part%sxx, field%sxx)
        call gather_on_root(this%context, part%syy, field%syy)
        call gather_on_root(this%context, part%sxy, field%sxy)
        call gather_on_root(this%context, part%flag, field%flag)
    end subroutine distributed_field

end module ddc_parallel_run
