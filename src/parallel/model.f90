!> The model on every process of a distributed run: the root read and checked it; the others
!> get from it what the solve and the post-processing use (collective).
module ddc_parallel_model
    use ddc_model_types, only: model_type, element_set
    use ddc_parallel_context, only: parallel_context, root
    use ddc_parallel_collective, only: share
    implicit none
    private

    public :: share_model

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

    !> Broadcast the root's elements.
    subroutine share_elements(context, elements)
        type(parallel_context), intent(in) :: context
        type(element_set), intent(inout) :: elements

        call share(context, elements%n)
        call share(context, elements%x_begin)
        call share(context, elements%y_begin)
        call share(context, elements%x_end)
        call share(context, elements%y_end)
        call share(context, elements%fracture_id)
        call share(context, elements%condition)
        call share(context, elements%bc_s)
        call share(context, elements%bc_n)
        call share(context, elements%mu)
        call share(context, elements%sf)
        call share(context, elements%pressure)
        call share(context, elements%tensile_strength)
        call share(context, elements%sf_residual)
        call share(context, elements%mu_dynamic)
        call share(context, elements%slip_weakening_distance)
        call share(context, elements%shear_stiffness)
        call share(context, elements%normal_stiffness)
        call share(context, elements%x_mid)
        call share(context, elements%y_mid)
        call share(context, elements%half_length)
        call share(context, elements%cos_beta)
        call share(context, elements%sin_beta)
        call share(context, elements%symmetry%kind)
        call share(context, elements%symmetry%xsym)
        call share(context, elements%symmetry%ysym)
        call share(context, elements%domain)
    end subroutine share_elements

end module ddc_parallel_model
