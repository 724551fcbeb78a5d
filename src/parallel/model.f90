!> The model on every process of a distributed run: the root read and checked it; the others
!> get from it what the solve and the post-processing use (collective).
module ddc_parallel_model
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, element_set, element_array_action, &
        for_each_element_array
    use ddc_parallel_context, only: parallel_context, root
    use ddc_parallel_collective, only: share
    implicit none
    private

    public :: share_model

    !> Broadcasts every per-element array from the root (share_elements).
    type, extends(element_array_action) :: element_broadcast
        !> The processes
        type(parallel_context) :: context
    contains
        procedure :: on_reals => share_element_reals
        procedure :: on_integers => share_element_integers
    end type element_broadcast

contains

    !> Broadcast the root's model: elastic constants, remote stress and its gradient, pore
    !> fluid, elements with their geometry, symmetry and domain, observation points, solver
    !> options and block size. The title, units, fractures, input text, output file and
    !> sweep task stay on the root, which alone writes.
    subroutine share_model(context, model)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> The root's model on entry; on exit every process has its solve's part
        type(model_type), intent(inout) :: model
        integer :: count, i

        call share(context, model%youngs_modulus)
        call share(context, model%poissons_ratio)
        call share(context, model%interface_y)
        call share(context, model%upper_youngs_modulus)
        call share(context, model%upper_poissons_ratio)
        call share(context, model%sxx)
        call share(context, model%syy)
        call share(context, model%sxy)
        do i = 1, 3
            call share(context, model%stress_gradient(i))
        end do
        do i = 1, 2
            call share(context, model%pore_fluid(i))
        end do
        call share(context, model%solver%lcp_method)
        call share(context, model%solver%open_cohesion)
        call share(context, model%solver%k_method)
        call share(context, model%solver%k_zone_elements)
        ! Root only: model%solver%work_bytes (the root's memory check sets it for the
        ! fallback from Newton to Lemke, which a distributed solve does not have).
        ! Root only: model%solver%matrix (hierarchical is refused with more than one
        ! process, ddc_parallel_plan; the others are dense), and so its settings:
        ! Root only: model%solver%hmatrix_tolerance (as matrix)
        ! Root only: model%solver%hmatrix_leaf_size (as matrix)
        ! Root only: model%solver%hmatrix_eta (as matrix)
        ! Root only: model%solver%k_extrapolation (a loading history's, which a
        ! distributed solve does not have).
        call share(context, model%block_size)
        call share_elements(context, model%elements)

        count = -1
        if (allocated(model%observations)) count = size(model%observations)
        call share(context, count)
        if (count < 0) return
        if (context%rank /= root) then
            if (allocated(model%observations)) deallocate (model%observations)
            allocate (model%observations(count))
        end if
        do i = 1, count
            associate (o => model%observations(i))
                call share(context, o%kind)
                call share(context, o%nx)
                call share(context, o%ny)
                call share(context, o%x)
                call share(context, o%y)
            end associate
        end do
    end subroutine share_model

    !> Broadcast the root's elements: their number, every per-element array, symmetry and
    !> domain.
    subroutine share_elements(context, elements)
        !> The processes
        type(parallel_context), intent(in) :: context
        !> The root's elements on entry; on exit every process has them
        type(element_set), intent(inout) :: elements
        type(element_broadcast) :: broadcast

        call share(context, elements%n)
        broadcast%context = context
        call for_each_element_array(elements, broadcast)
        call share(context, elements%symmetry%kind)
        call share(context, elements%symmetry%xsym)
        call share(context, elements%symmetry%ysym)
        call share(context, elements%domain)
    end subroutine share_elements

    !> Broadcast one real per-element array from the root.
    subroutine share_element_reals(action, values)
        !> The broadcast
        class(element_broadcast), intent(inout) :: action
        !> The root's array on exit
        real(wp), allocatable, intent(inout) :: values(:)

        call share(action%context, values)
    end subroutine share_element_reals

    !> Broadcast one integer per-element array from the root.
    subroutine share_element_integers(action, values)
        !> The broadcast
        class(element_broadcast), intent(inout) :: action
        !> The root's array on exit
        integer, allocatable, intent(inout) :: values(:)

        call share(action%context, values)
    end subroutine share_element_integers

end module ddc_parallel_model
