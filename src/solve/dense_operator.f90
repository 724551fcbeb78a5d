!> The elastic operator of a medium as dense matrices in this process (ddc_solve_operator):
!> the influence matrix assembled once, the free elements condensed out by one LU of K_FF,
!> and A = K_CC - K_CF K_FF^-1 K_FC in memory, on which both contact methods work; elastic
!> joints replace A by the matrix of their plastic DDs (ddc_solve_joints).
!>
!> The condensation depends on the geometry only (new_dense_operator, once); the remote
!> traction on the contact elements and the free DDs depend on the load (load_contact and
!> complete, once per load): a loading history condenses once.
module ddc_solve_dense_operator
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_solver_failure
    use ddc_model_types, only: condition_contact
    use ddc_model_medium, only: elastic_medium
    use ddc_model_results, only: solver_record
    use ddc_influence_body, only: body_matrix_correction
    use ddc_influence_assembly, only: assemble_influence
    use ddc_influence_response, only: listed_tractions
    use ddc_solve_elastic, only: row_kinds, given_values
    use ddc_solve_joints, only: joint_system
    use ddc_solve_operator, only: elastic_operator, elastic_load, free_part
    use ddc_linalg_lapack, only: dgemm, dgemv
    use ddc_linalg_lu, only: lu_factor, lu_solve, influence_hint, residual_tol
    use ddc_contact_stiffness, only: dense_stiffness
    use ddc_text, only: rtoa, itoa, seconds_text
    use ddc_progress, only: report_progress, reports_phases
    use ddc_allocation, only: allocation_failed, real_bytes
    implicit none
    private

    public :: dense_operator, new_dense_operator

    !> A medium's operator held densely.
    type, extends(elastic_operator) :: dense_operator
        !> Row kinds of every element (ddc_solve_elastic), shape (n)
        integer, allocatable :: shear_row(:), normal_row(:)
        !> A of the contact elements, shape (2 nc, 2 nc) (matrix points at it, or at the
        !> joints' matrix)
        real(wp), pointer, contiguous :: a(:, :) => null()
        !> The joints' matrix of the plastic DDs and its load map (elastic joints only),
        !> shape (2 nc, 2 nc)
        real(wp), pointer, contiguous :: a_joint(:, :) => null()
        !> The whole system (kept only when nf > 0), shape (2n, 2n)
        real(wp), pointer, contiguous :: system(:, :) => null()
        !> The matrix is the caller's, viewed (a growth run's grown matrix): not freed here
        logical :: viewed = .false.
        !> Why K_FF is ill-conditioned where no contact element is left to judge it (the
        !> solve's residual does: complete)
        character(len=:), allocatable :: ill_conditioned
        !> LU factors of K_FF and their pivots, shape (2 nf, 2 nf), (2 nf)
        real(wp), allocatable :: kff(:, :)
        integer, allocatable :: ipiv(:)
        !> K_FF^-1 K_FC, shape (2 nf, 2 nc)
        real(wp), allocatable :: y(:, :)
    contains
        procedure :: load_contact => dense_load_contact
        procedure :: complete => dense_complete
        procedure :: free_tractions => dense_free_tractions
        procedure :: multiply_elements => dense_multiply_elements
        procedure :: multiply_shear => dense_multiply_shear
        procedure :: add_joints
        procedure :: view_matrix
        procedure :: release => dense_release
    end type dense_operator

contains

    !> Assemble the influence matrix of the medium and condense the free elements out
    !> (timed into record: assembly and factorization).
    subroutine new_dense_operator(medium, operator, error)
        !> The medium, geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The operator
        type(dense_operator), intent(out) :: operator
        !> Set when K_FF is singular (exit_solver_failure) or the matrices do not fit in
        !> memory (exit_out_of_memory)
        type(error_type), allocatable, intent(out) :: error
        real(wp), pointer, contiguous :: matrix(:, :)
        real(wp), allocatable :: kcf(:, :)
        integer :: n, i, stat
        integer(int64) :: t0, t1, t2, rate

        associate (op => operator, elements => medium%elements, record => operator%record)
            n = elements%n
            call system_clock(t0, rate)
            op%contact = pack([(i, i = 1, n)], elements%condition == condition_contact)
            op%free = pack([(i, i = 1, n)], elements%condition /= condition_contact)
            op%nc = size(op%contact)
            op%nf = size(op%free)
            allocate (dense_stiffness :: op%stiffness)
            allocate (op%shear_row(n), op%normal_row(n))
            allocate (matrix(2 * n, 2 * n), stat=stat)
            if (stat /= 0) then
                call allocation_failed(error, 'the influence matrix of '//itoa(n)// &
                                       ' elements', real_bytes * (2.0_wp * real(n, wp))**2)
                return
            end if
            call row_kinds(elements%condition, op%shear_row, op%normal_row)
            call assemble_influence(medium, op%shear_row, op%normal_row, matrix)
            if (allocated(medium%body)) call body_matrix_correction(medium, op%shear_row, &
                                                                    op%normal_row, matrix)
            call system_clock(t1)
            record%seconds_assembly = real(t1 - t0, wp) / real(rate, wp)
            if (reports_phases(n)) call report_progress('assembly done in '// &
                seconds_text(record%seconds_assembly)//' ('//itoa(2 * n)//' x '// &
                itoa(2 * n)//' influence matrix)')
            if (op%nf == 0) then
                ! Every element is a contact element: A is the whole matrix (no copy).
                op%a => matrix
                op%whole => matrix
            else
                op%system => matrix
                op%whole => matrix
                call condense(op, kcf, error)
                if (allocated(error)) return
                if (op%nc > 0) op%hint = ' (element numbers count the contact elements only)'
            end if
            op%matrix => op%a
            ! LU of K_FF, its solve for 2 nc + 1 right-hand sides and the product.
            associate (nc => real(op%nc, wp), nf => real(op%nf, wp))
                op%flops = 2.0_wp / 3.0_wp * (2.0_wp * nf)**3 + 2.0_wp * (2.0_wp * nf)**2 * &
                    (2.0_wp * nc + 1.0_wp) + 2.0_wp * (2.0_wp * nc)**2 * (2.0_wp * nf)
            end associate
            call system_clock(t2)
            record%counts%seconds = real(t2 - t1, wp) / real(rate, wp)
            if (reports_phases(n) .and. op%nf > 0 .and. op%nc > 0) call report_progress( &
                'condensation of '//itoa(op%nf)//' elements done in '// &
                seconds_text(record%counts%seconds))
            if (reports_phases(n) .and. op%nc == 0) call report_progress('LU '// &
                'factorization done in '//seconds_text(record%counts%seconds))
        end associate
        call bind_stiffness(operator)
    end subroutine new_dense_operator

    !> A of the contact elements, the LU of K_FF and y = K_FF^-1 K_FC from the whole
    !> system (op%system).
    subroutine condense(op, kcf, error)
        type(dense_operator), intent(inout) :: op
        !> Work array for K_CF
        real(wp), allocatable, intent(inout) :: kcf(:, :)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: ill_conditioned
        integer :: cu(2 * op%nc), fu(2 * op%nf)
        real(wp) :: residual
        integer :: n, nc, nf, stat
        character(len=*), parameter :: among_free = &
            ' (among the elements with TWODD-style conditions)'

        nc = op%nc
        nf = op%nf
        n = nc + nf
        ! Unknown indices in the full system, ordered [s; n] within each set.
        cu = [op%contact, n + op%contact]
        fu = [op%free, n + op%free]
        allocate (op%ipiv(2 * nf))
        allocate (op%a(2 * nc, 2 * nc), stat=stat)
        if (stat == 0) allocate (op%kff(2 * nf, 2 * nf), stat=stat)
        if (stat == 0) allocate (op%y(2 * nf, 2 * nc), stat=stat)
        if (stat == 0) allocate (kcf(2 * nc, 2 * nf), stat=stat)
        if (stat /= 0) then
            call allocation_failed(error, 'the condensation of '//itoa(nf)// &
                ' elements with TWODD-style conditions out of '//itoa(n), real_bytes * &
                4.0_wp * (real(nc, wp) + real(nf, wp))**2)
            return
        end if
        if (nc == 0) then
            ! No contact element: K_FF is the whole system (a copy, no gather).
            op%kff(:, :) = op%system
            call lu_factor(op%kff, op%ipiv, 'influence matrix', error, &
                           ill_conditioned=ill_conditioned)
            if (allocated(error)) then
                error%message = error%message//influence_hint
                return
            end if
            ! A singular K_FF is judged by the residual of the solve (complete).
            if (allocated(ill_conditioned)) then
                call move_alloc(ill_conditioned%message, op%ill_conditioned)
            end if
            return
        end if
        op%a(:, :) = op%system(cu, cu)
        op%kff(:, :) = op%system(fu, fu)
        op%y(:, :) = op%system(fu, cu)
        kcf(:, :) = op%system(cu, fu)
        call lu_factor(op%kff, op%ipiv, 'influence matrix', error, &
                       element=[op%free, op%free], ill_conditioned=ill_conditioned)
        if (allocated(error)) then
            error%message = error%message//influence_hint//among_free
            return
        end if
        call lu_solve(op%kff, op%ipiv, op%y)
        ! A hole (closed contour) is numerically singular but consistent: K_FF y = K_FC.
        if (allocated(ill_conditioned)) then
            residual = norm2(matmul(op%system(fu, fu), op%y) - op%system(fu, cu)) / &
                max(norm2(op%system(fu, cu)), tiny(1.0_wp))
            if (.not. residual <= residual_tol) then
                call set_error(error, exit_solver_failure, ill_conditioned%message// &
                               influence_hint//among_free//' (relative residual '// &
                               rtoa(residual)//')')
                return
            end if
        end if
        call dgemm('N', 'N', 2 * nc, 2 * nc, 2 * nf, -1.0_wp, kcf, 2 * nc, op%y, 2 * nf, &
                   1.0_wp, op%a, 2 * nc)
        deallocate (kcf)
    end subroutine condense

    !> The operator of a medium of contact elements alone on a matrix the caller holds (a
    !> growth run's matrix, bordered from the base's: ddc_growth_influence), which must
    !> live as long as the operator uses it; the stiffness keeps the factors it had.
    subroutine view_matrix(this, medium, matrix)
        !> The operator
        class(dense_operator), intent(inout) :: this
        !> The medium, every element a contact element
        type(elastic_medium), intent(in) :: medium
        !> Its influence matrix [s; n], shape (2n, 2n) [stress / length]
        real(wp), intent(in), target, contiguous :: matrix(:, :)
        integer :: i, n

        n = medium%elements%n
        this%contact = [(i, i = 1, n)]
        this%free = [integer ::]
        this%nc = n
        this%nf = 0
        if (.not. allocated(this%stiffness)) allocate (dense_stiffness :: this%stiffness)
        this%a => matrix
        this%matrix => matrix
        this%whole => matrix
        this%viewed = .true.
        call bind_stiffness(this)
    end subroutine view_matrix

    !> The Newton method's operator works on the matrix of the contact problem.
    subroutine bind_stiffness(op)
        class(dense_operator), intent(inout) :: op

        select type (s => op%stiffness)
        type is (dense_stiffness)
            s%a => op%matrix
        end select
    end subroutine bind_stiffness

    !> Elastic joints (ddc_solve_joints): the contact problem becomes that of the plastic
    !> DDs, on its own matrix and with a load map of the fluid pressure (load_map).
    subroutine add_joints(this, compliance, error)
        !> The operator
        class(dense_operator), intent(inout) :: this
        !> Joint compliance of each contact element [length / stress], shape (2 nc)
        real(wp), intent(in) :: compliance(:)
        !> Set when a matrix is singular
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a_joint(:, :)

        call joint_system(this%a, compliance, a_joint, this%load_map, error)
        if (allocated(error)) return
        allocate (this%a_joint, source=a_joint)
        this%matrix => this%a_joint
        call bind_stiffness(this)
    end subroutine add_joints

    !> shift = [S_r,C shear; S_r,C normal] + K_CF K_FF^-1 b_F.
    subroutine dense_load_contact(this, medium, load, shift, kept, error)
        class(dense_operator), intent(inout) :: this
        type(elastic_medium), intent(in) :: medium
        type(elastic_load), intent(in) :: load
        real(wp), intent(out) :: shift(:)
        type(free_part), intent(out) :: kept
        !> Not set: K_FF was factorized when the operator was made
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: b(:, :)
        integer :: n

        n = medium%elements%n
        shift = [load%shear(this%contact), load%normal(this%contact)]
        allocate (b(2 * this%nf, 1))
        if (this%nf > 0) then
            b(:, 1) = given_values(medium%elements, this%shear_row, this%normal_row, &
                                   load%shear, load%normal, this%free)
            call lu_solve(this%kff, this%ipiv, b)
            if (this%nc > 0) shift = shift + matmul(this%system([this%contact, &
                n + this%contact], [this%free, n + this%free]), b(:, 1))
        end if
        kept%dd = b(:, 1)
    end subroutine dense_load_contact

    !> Free DDs x_F = K_FF^-1 b_F - K_FF^-1 K_FC x_C, checked against the unfactored free
    !> rows.
    subroutine dense_complete(this, medium, load, x_contact, kept, ds, dn, record, error)
        class(dense_operator), intent(inout) :: this
        type(elastic_medium), intent(in) :: medium
        type(elastic_load), intent(in) :: load
        real(wp), intent(in) :: x_contact(:)
        type(free_part), intent(in) :: kept
        real(wp), intent(out) :: ds(:), dn(:)
        type(solver_record), intent(inout) :: record
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: x_free(:), residual_free(:), b_free(:)
        integer, allocatable :: cu(:), fu(:)
        integer :: n

        n = size(ds)
        ds(this%contact) = x_contact(1:this%nc)
        dn(this%contact) = x_contact(this%nc + 1:)
        if (this%nf == 0) return
        b_free = given_values(medium%elements, this%shear_row, this%normal_row, load%shear, &
                              load%normal, this%free)
        if (this%nc == 0) then
            ! The free rows are the whole system (no gather).
            x_free = kept%dd
            residual_free = matmul(this%system, x_free) - b_free
        else
            cu = [this%contact, n + this%contact]
            fu = [this%free, n + this%free]
            x_free = kept%dd - matmul(this%y, x_contact)
            ! The free rows against the unfactored system: K_FF x_F + K_FC x_C = b_F.
            residual_free = matmul(this%system(fu, fu), x_free) + &
                matmul(this%system(fu, cu), x_contact) - b_free
        end if
        ds(this%free) = x_free(1:this%nf)
        dn(this%free) = x_free(this%nf + 1:)
        associate (residual => record%equilibrium_residual)
            residual = max(residual, norm2(residual_free) / max(norm2(b_free), tiny(1.0_wp)))
            ! A hole (closed contour) is numerically singular but consistent: its residual
            ! is small.
            if (allocated(this%ill_conditioned) .and. .not. residual <= residual_tol) then
                call set_error(error, exit_solver_failure, this%ill_conditioned// &
                               influence_hint//' (relative residual '//rtoa(residual)//')')
            end if
        end associate
    end subroutine dense_complete

    !> Induced tractions of the free elements from their rows of the system.
    subroutine dense_free_tractions(this, medium, ds, dn, shear_traction, normal_traction, &
                                    error)
        class(dense_operator), intent(in) :: this
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: ds(:), dn(:)
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        type(error_type), allocatable, intent(out) :: error

        if (this%nf == 0) return
        call listed_tractions(medium, this%system, this%shear_row, this%normal_row, this%free, &
                              ds, dn, shear_traction, normal_traction)
    end subroutine dense_free_tractions

    !> t = t + A(rows, columns) dd from the rows and columns of A in memory.
    subroutine dense_multiply_elements(this, rows, columns, dd, t)
        class(dense_operator), intent(in) :: this
        integer, intent(in) :: rows(:), columns(:)
        real(wp), intent(in) :: dd(:)
        real(wp), intent(inout) :: t(:)
        real(wp), allocatable :: block(:, :)
        integer :: mr, mc

        mr = size(rows)
        mc = size(columns)
        associate (nc => this%nc)
            block = this%matrix([rows, nc + rows], [columns, nc + columns])
        end associate
        call dgemv('N', 2 * mr, 2 * mc, 1.0_wp, block, 2 * mr, dd, 1, 1.0_wp, t, 1)
    end subroutine dense_multiply_elements

    !> t = t + A [ds; 0]: the first nc columns of A alone (no copy: they are contiguous).
    subroutine dense_multiply_shear(this, ds, t)
        class(dense_operator), intent(in) :: this
        real(wp), intent(in) :: ds(:)
        real(wp), intent(inout) :: t(:)

        call dgemv('N', 2 * this%nc, this%nc, 1.0_wp, this%matrix, 2 * this%nc, ds, 1, &
                   1.0_wp, t, 1)
    end subroutine dense_multiply_shear

    !> Free the matrices and factors.
    subroutine dense_release(this)
        class(dense_operator), intent(inout) :: this

        select type (s => this%stiffness)
        type is (dense_stiffness)
            nullify (s%a)
            call s%discard_factors()
        end select
        nullify (this%matrix, this%whole)
        if (associated(this%a_joint)) deallocate (this%a_joint)
        if (this%viewed) nullify (this%a)
        if (associated(this%a)) deallocate (this%a)
        if (associated(this%system)) deallocate (this%system)
    end subroutine dense_release

end module ddc_solve_dense_operator
