!> The elastic operator of a medium on hierarchical matrices (ddc_solve_operator,
!> docs/theory/hierarchical.md): a medium of contact elements alone as the compressed A of
!> ddc_solve_hierarchical_stiffness (the Newton method; no dense matrix, so no Lemke and no
!> elastic joints), or a medium without contact elements, solved per load by H-LU with
!> refinement (ddc_solve_hierarchical). Contact elements beside free ones are not condensed
!> on hierarchical matrices: the run's capabilities refuse such a medium.
module ddc_solve_hierarchical_operator
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_internal_error
    use ddc_model_types, only: condition_contact
    use ddc_model_medium, only: elastic_medium
    use ddc_model_results, only: solver_record
    use ddc_contact_options, only: solver_options
    use ddc_solve_operator, only: elastic_operator, elastic_load, free_part
    use ddc_solve_hierarchical, only: solve_hierarchical, report_assembly, unknown_points, &
        settings_of
    use ddc_linalg_hmatrix, only: hmatrix
    use ddc_solve_hierarchical_stiffness, only: hierarchical_stiffness, &
        new_hierarchical_stiffness
    implicit none
    private

    public :: hierarchical_operator, new_hierarchical_operator

    !> A medium's operator on hierarchical matrices.
    type, extends(elastic_operator) :: hierarchical_operator
        !> The medium the compressed A points at: a copy that lives as long as it does
        type(elastic_medium), pointer :: kept => null()
        !> The hmatrix_ settings of &solver (the solves without contact elements)
        type(solver_options) :: options
        !> The shear columns of A alone, compressed (prepare_shear_products)
        type(hmatrix), pointer :: shear => null()
    contains
        procedure :: load_contact => hierarchical_load_contact
        procedure :: complete => hierarchical_complete
        procedure :: prepare_shear_products => hierarchical_prepare_shear
        procedure :: multiply_shear => hierarchical_multiply_shear
        procedure :: release => hierarchical_release
    end type hierarchical_operator

contains

    !> The operator of a medium whose elements are all contact elements (A compressed, timed
    !> into record) or all free elements (nothing done before a load).
    subroutine new_hierarchical_operator(medium, options, operator, error)
        !> The medium, geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The hmatrix_ settings of &solver
        type(solver_options), intent(in) :: options
        !> The operator
        type(hierarchical_operator), intent(out) :: operator
        !> Set when hmat-oss fails, or (internal) for contact elements beside free ones
        type(error_type), allocatable, intent(out) :: error
        integer :: n, i
        integer(int64) :: t0, t1, rate

        associate (op => operator, elements => medium%elements, record => operator%record)
            n = elements%n
            op%options = options
            op%contact = pack([(i, i = 1, n)], elements%condition == condition_contact)
            op%free = pack([(i, i = 1, n)], elements%condition /= condition_contact)
            op%nc = size(op%contact)
            op%nf = size(op%free)
            record%hierarchical = .true.
            record%hmatrix_tolerance = options%hmatrix_tolerance
            if (op%nc == 0) return
            if (op%nf > 0) then
                call set_internal_error(error, 'new_hierarchical_operator', 'contact '// &
                                        'elements beside elements of other conditions')
                return
            end if
            call system_clock(t0, rate)
            allocate (op%kept, source=medium)
            allocate (hierarchical_stiffness :: op%stiffness)
            select type (s => op%stiffness)
            type is (hierarchical_stiffness)
                call new_hierarchical_stiffness(op%kept, options, s, error)
                call system_clock(t1)
                record%seconds_assembly = real(t1 - t0, wp) / real(rate, wp)
                record%counts%seconds = 0.0_wp
                if (allocated(error)) return
                record%compression_ratio = s%a%stored_fraction()
                call report_assembly(n, record%seconds_assembly, record%compression_ratio)
            end select
        end associate
    end subroutine new_hierarchical_operator

    !> The remote traction on the contact elements (no free elements to add).
    subroutine hierarchical_load_contact(this, medium, load, shift, kept, error)
        class(hierarchical_operator), intent(inout) :: this
        type(elastic_medium), intent(in) :: medium
        type(elastic_load), intent(in) :: load
        real(wp), intent(out) :: shift(:)
        type(free_part), intent(out) :: kept
        !> Not set: the free elements are solved in complete
        type(error_type), allocatable, intent(out) :: error

        shift = [load%shear(this%contact), load%normal(this%contact)]
        allocate (kept%dd(2 * min(this%nf, medium%elements%n)), source=0.0_wp)
    end subroutine hierarchical_load_contact

    !> The DDs of every element: the contact elements' as solved, or, without contact
    !> elements, the free elements' by H-LU with refinement (assembly and solve recorded).
    subroutine hierarchical_complete(this, medium, load, x_contact, kept, ds, dn, record, &
                                     error)
        class(hierarchical_operator), intent(inout) :: this
        type(elastic_medium), intent(in) :: medium
        type(elastic_load), intent(in) :: load
        real(wp), intent(in) :: x_contact(:)
        type(free_part), intent(in) :: kept
        real(wp), intent(out) :: ds(:), dn(:)
        type(solver_record), intent(inout) :: record
        type(error_type), allocatable, intent(out) :: error

        if (this%nf == 0) then
            ds = x_contact(1:this%nc)
            dn = x_contact(this%nc + 1:)
            return
        end if
        if (size(kept%dd) /= 2 * this%nf) then
            call set_internal_error(error, 'hierarchical_complete', 'a load of another medium')
            return
        end if
        call solve_hierarchical(medium, load%shear, load%normal, this%options, ds, dn, &
                                record%equilibrium_residual, record%compression_ratio, &
                                record%seconds_assembly, record%counts%seconds, error)
    end subroutine hierarchical_complete

    !> The shear columns of A (every row against the contact elements' Ds) compressed alone:
    !> half of A, for the many products of an earthquake-cycle run. Where hmat-oss cannot,
    !> the products stay those of the whole A.
    subroutine hierarchical_prepare_shear(this)
        class(hierarchical_operator), intent(inout) :: this
        type(error_type), allocatable :: failed
        real(wp), allocatable :: rows(:, :), columns(:, :)

        if (this%nc == 0 .or. this%nf > 0 .or. associated(this%shear)) return
        select type (s => this%stiffness)
        type is (hierarchical_stiffness)
            allocate (this%shear)
            ! The entries of A: its column u <= nc is the Ds of contact element u.
            rows = unknown_points(this%kept%elements)
            columns = rows(:, :this%nc)
            call this%shear%assemble_rectangular(rows, columns, s%source, &
                                                 settings_of(this%options), failed)
        end select
        this%shear_columns_apart = associated(this%shear) .and. .not. allocated(failed)
        if (associated(this%shear) .and. .not. this%shear_columns_apart) then
            call this%shear%release()
            deallocate (this%shear)
        end if
    end subroutine hierarchical_prepare_shear

    !> t = t + A [ds; 0] by the compressed shear columns (else by the whole A).
    subroutine hierarchical_multiply_shear(this, ds, t)
        class(hierarchical_operator), intent(in) :: this
        real(wp), intent(in) :: ds(:)
        real(wp), intent(inout) :: t(:)
        real(wp) :: product(size(t))
        type(error_type), allocatable :: failed

        if (.not. this%shear_columns_apart) then
            product = 0.0_wp
            call this%stiffness%multiply([ds, spread(0.0_wp, 1, this%nc)], product)
        else
            call this%shear%multiply(ds, product, failed)
            ! hmat-oss fails a product only on a broken matrix: poison the result.
            if (allocated(failed)) product = huge(1.0_wp)
        end if
        t = t + product
    end subroutine hierarchical_multiply_shear

    !> Free the compressed A and its elements.
    subroutine hierarchical_release(this)
        class(hierarchical_operator), intent(inout) :: this

        if (allocated(this%stiffness)) then
            select type (s => this%stiffness)
            type is (hierarchical_stiffness)
                call s%release()
            end select
        end if
        if (associated(this%shear)) then
            call this%shear%release()
            deallocate (this%shear)
        end if
        if (associated(this%kept)) deallocate (this%kept)
    end subroutine hierarchical_release

end module ddc_solve_hierarchical_operator
