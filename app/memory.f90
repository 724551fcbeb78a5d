!> Before the solve: the memory the model needs (ddc_run_memory) against what this
!> machine or its cgroup offers (ddc_run_available_memory), echoed (for the Newton method
!> from its starting states, and at its largest beside it); a model that cannot fit even
!> from its starting states is refused with one message (exit_out_of_memory); the contact
!> solver is told what is left, so that a reduced system that outgrows it, or a fallback
!> from Newton to Lemke that cannot fit, stops cleanly too.
module ddc_app_memory
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_text, only: bytes_text, itoa
    use ddc_version, only: with_hmatrix
    use ddc_model_types, only: model_type
    use ddc_model_capabilities, only: run_refusal, operator_hierarchical
    use ddc_run_memory, only: memory_need, estimate_memory, add_k_resolve, check_memory, &
        hierarchical_min_elements
    use ddc_contact_options, only: matrix_dense, matrix_hierarchical
    use ddc_run_available_memory, only: available_memory, no_limit
    implicit none
    private

    public :: check_model_memory, result_file_bytes, table_file_bytes

contains

    !> Estimate, echo, compare; set the contact solver's work memory.
    subroutine check_model_memory(unit, model, error)
        !> Unit of the echo
        integer, intent(in) :: unit
        !> The model; model%solver%work_bytes is set
        type(model_type), intent(inout) :: model
        !> Allocated (exit_out_of_memory) when the model does not fit
        type(error_type), allocatable, intent(out) :: error
        type(memory_need) :: need
        real(wp) :: available
        character(len=:), allocatable :: source, there

        need = estimate_memory(model)
        call available_memory(available, source)
        there = 'no limit found'
        if (available < no_limit) there = bytes_text(available)//' available ('//source//')'
        call choose_matrix(unit, model, need, available)
        call add_k_resolve(model, need)
        if (need%k_bytes > 0.0_wp) there = bytes_text(need%k_bytes)//' of it for K''s '// &
            'local re-solve; '//there
        if (need%worst_bytes > need%bytes) then
            ! The Newton method from its starting states, and at its largest beside it.
            write (unit, '(a)') '  memory: about '//bytes_text(need%bytes)//' needed ('// &
                need%method//', from the starting states: '//itoa(need%start_unknowns)// &
                ' unknowns), up to '//bytes_text(need%worst_bytes)//' should every element '// &
                'slip and open; '//there
        else
            write (unit, '(a)') '  memory: about '//bytes_text(need%bytes)//' needed ('// &
                need%method//'), '//there
        end if
        if (need%fallback_bytes > available .and. need%bytes <= available) write (unit, &
            '(a)') '    (should the Newton '// &
            'method fail, the fallback to Lemke would need about '// &
            bytes_text(need%fallback_bytes)//': it would stop with exit status 5)'
        call check_memory(model, need, available, source, error)
        if (allocated(error)) return
        model%solver%work_bytes = max(available - need%held_bytes, 0.0_wp)
        ! The Newton method's own limit counts dense reduced systems.
        if (model%solver%matrix == matrix_hierarchical) model%solver%work_bytes = huge(1.0_wp)
    end subroutine check_model_memory

    !> Resolve &solver matrix = 'auto' (docs/theory/hierarchical.md#choosing-the-matrix):
    !> dense in a build without hmat-oss; else, where the model allows a hierarchical
    !> matrix, it from hierarchical_min_elements elements on or where the dense need does not
    !> fit (then `need` is re-estimated), else dense; echo the matrix and why (every run).
    subroutine choose_matrix(unit, model, need, available)
        integer, intent(in) :: unit
        type(model_type), intent(inout) :: model
        type(memory_need), intent(inout) :: need
        real(wp), intent(in) :: available
        character(len=:), allocatable :: why
        integer :: n

        select case (model%solver%matrix)
        case (matrix_hierarchical)
            write (unit, '(a)') "  matrix: hierarchical (&solver matrix = 'hierarchical')"
        case (matrix_dense)
            write (unit, '(a)') "  matrix: dense (&solver matrix = 'dense')"
        case default
            model%solver%matrix = matrix_dense
            n = model%elements%n
            if (.not. with_hmatrix) then
                write (unit, '(a)') '  matrix: dense (built without hmat-oss: CMake option '// &
                    'DDC2D_HMATRIX=OFF)'
                return
            else if (len(run_refusal(model, operator_hierarchical)) > 0) then
                write (unit, '(a)') '  matrix: dense (a hierarchical matrix does not solve '// &
                    'this model: docs/theory/hierarchical.md#what-it-solves)'
                return
            else if (n >= hierarchical_min_elements) then
                why = itoa(n)//' elements, from '//itoa(hierarchical_min_elements)// &
                    ' on a hierarchical matrix is faster'
            else if (need%bytes > available) then
                why = 'the dense matrix would need about '//bytes_text(need%bytes)
            else
                write (unit, '(a)') '  matrix: dense ('//itoa(n)//' elements: below '// &
                    itoa(hierarchical_min_elements)//' a dense matrix is faster)'
                return
            end if
            model%solver%matrix = matrix_hierarchical
            need = estimate_memory(model)
            write (unit, '(a)') '  matrix: hierarchical ('//why//')'
        end select
    end subroutine choose_matrix

    !> The least size of the HDF5 result file: the field datasets alone, known before the
    !> solve (x, y, ux, uy, sxx, syy, sxy as 8-byte reals and near_element as a 4-byte
    !> integer per point, uncompressed), so that a grid of 10^8 points is refused before
    !> hours of solving when its 6 GB cannot be written.
    pure function result_file_bytes(model) result(bytes)
        !> The model to be solved
        type(model_type), intent(in) :: model
        !> Bytes [bytes]
        real(wp) :: bytes
        integer :: i

        bytes = 0.0_wp
        if (.not. allocated(model%observations)) return
        do i = 1, size(model%observations)
            if (allocated(model%observations(i)%x)) bytes = bytes + &
                60.0_wp * real(size(model%observations(i)%x), wp)
        end do
    end function result_file_bytes

    !> The least size of the TWODD tables of --res: one row of 178 bytes or more per field
    !> point (i9, 7 es24.15, a newline) and per element (i10, 12 es24.15, a newline).
    pure function table_file_bytes(model) result(bytes)
        !> The model to be solved
        type(model_type), intent(in) :: model
        !> Bytes [bytes]
        real(wp) :: bytes

        bytes = 178.0_wp * result_file_bytes(model) / 60.0_wp + 299.0_wp * &
            real(model%elements%n, wp)
    end function table_file_bytes

end module ddc_app_memory
