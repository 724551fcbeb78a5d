!> The stiffness operator of a distributed run (ddc_contact_stiffness): the whole system of
!> the model (contact rows and the rows of the TWODD-style "free" elements) distributed
!> over the processes, seen by the active-set Newton method as the influence matrix A of
!> the contact elements with the free elements condensed out, without forming A.
!>
!> With the free DDs x_F0 of the contact DDs at zero (solve_free) the contact elements see
!> shift = S_r,C + K_CF x_F0. For contact DDs x_C the free ones are x_F0 + delta with
!> K_FF delta + K_FC x_C = 0, and A x_C = K_CC x_C + K_CF delta. So every reduced system
!> of the method carries the free unknowns along (their rows with right-hand side 0) and
!> keeps their delta for the products with the same x_C; without free elements it is
!> exactly the method's reduced system.
!>
!> Free unknowns are ordered element by element (Ds, Dn of each free element), so that a
!> model without contact elements solves the system in its own order.
module ddc_parallel_stiffness
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_types, only: condition_contact
    use ddc_model_medium, only: elastic_medium
    use ddc_contact_stiffness, only: stiffness_operator, reduced_system
    use ddc_contact_counts, only: factor_counts
    use ddc_parallel_context, only: parallel_context
    use ddc_parallel_collective, only: max_on_all, all_true
    use ddc_parallel_matrix, only: distributed_matrix, owner, local_index, global_rows, &
        global_columns, multiply_whole
    use ddc_parallel_assembly, only: assemble_distributed, shear_unknown, normal_unknown
    use ddc_parallel_redistribute, only: gather_submatrix
    use ddc_parallel_lu, only: distributed_lu, distributed_solve
    implicit none
    private

    public :: distributed_stiffness, assemble_stiffness

    !> The model's system on the processes, and the free DDs of the last solve.
    type, extends(stiffness_operator) :: distributed_stiffness
        !> The processes and their grid
        type(parallel_context) :: context
        !> The 2n x 2n system, rows as the conditions say, interleaved (ddc_parallel_assembly)
        type(distributed_matrix) :: system
        !> Model element of each contact element, shape (nc), and of each free one, (nf)
        integer, allocatable :: contact_elements(:), free_elements(:)
        !> Global index of each contact unknown ([s; n] over the contact elements), (2 nc)
        integer, allocatable :: contact_unknowns(:)
        !> Global index of each free unknown (Ds, Dn of each free element), (2 nf)
        integer, allocatable :: free_unknowns(:)
        !> Global indices that are contact unknowns, shape (2n)
        logical, allocatable :: is_contact(:)
        !> delta of the last reduced solve, ordered as free_unknowns, (2 nf) [length]
        real(wp), allocatable :: free_dd(:)
    contains
        procedure :: max_diagonal => distributed_max_diagonal
        procedure :: max_entry => distributed_max_entry
        procedure :: all_finite => distributed_all_finite
        procedure :: multiply => distributed_multiply
        procedure :: solve_reduced => distributed_solve_reduced
        procedure :: solve_free
        procedure :: solve_gathered
    end type distributed_stiffness

contains

    !> Assemble the model's system on the processes and index its unknowns (collective).
    subroutine assemble_stiffness(context, medium, shear_row, normal_row, stiffness, error)
        !> The processes and their grid
        type(parallel_context), intent(in) :: context
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> Kind of the shear row and of the normal row of each element, shape (n)
        integer, intent(in) :: shear_row(:), normal_row(:)
        !> The operator
        type(distributed_stiffness), intent(out) :: stiffness
        !> Set when the matrix cannot be created (exit_internal_error)
        type(error_type), allocatable, intent(out) :: error
        integer :: i, nf

        stiffness%context = context
        call assemble_distributed(context, medium, shear_row, normal_row, stiffness%system, error)
        if (allocated(error)) return
        associate (every => [(i, i = 1, medium%elements%n)], elements => medium%elements)
            stiffness%contact_elements = pack(every, elements%condition == condition_contact)
            stiffness%free_elements = pack(every, elements%condition /= condition_contact)
        end associate
        stiffness%contact_unknowns = [shear_unknown(stiffness%contact_elements), &
                                      normal_unknown(stiffness%contact_elements)]
        nf = size(stiffness%free_elements)
        allocate (stiffness%free_unknowns(2 * nf))
        stiffness%free_unknowns(1::2) = shear_unknown(stiffness%free_elements)
        stiffness%free_unknowns(2::2) = normal_unknown(stiffness%free_elements)
        allocate (stiffness%is_contact(2 * medium%elements%n), source=.false.)
        stiffness%is_contact(stiffness%contact_unknowns) = .true.
        allocate (stiffness%free_dd(2 * nf), source=0.0_wp)
    end subroutine assemble_stiffness

    !> Largest |A_ii| of the contact unknowns (K_CC's diagonal: the condensed diagonal
    !> would need K_FF^-1 K_FC; both are stiffness scales of the same order).
    function distributed_max_diagonal(this) result(value)
        class(distributed_stiffness), intent(in) :: this
        real(wp) :: value
        integer :: lc, gc

        value = 0.0_wp
        associate (c => this%context, k => this%system, &
                   columns => global_columns(this%context, this%system))
            do lc = 1, k%local_columns
                gc = columns(lc)
                if (.not. this%is_contact(gc) .or. owner(gc, c%block, c%rows) /= c%row) cycle
                value = max(value, abs(k%a(local_index(gc, c%block, c%rows), lc)))
            end do
            value = max_on_all(c, value)
        end associate
    end function distributed_max_diagonal

    !> Largest |A_ij| over the contact unknowns (of K_CC).
    function distributed_max_entry(this) result(value)
        class(distributed_stiffness), intent(in) :: this
        real(wp) :: value
        integer :: lr, lc

        value = 0.0_wp
        associate (c => this%context, k => this%system, &
                   rows => global_rows(this%context, this%system), &
                   columns => global_columns(this%context, this%system))
            do lc = 1, k%local_columns
                if (.not. this%is_contact(columns(lc))) cycle
                do lr = 1, k%local_rows
                    if (this%is_contact(rows(lr))) value = max(value, abs(k%a(lr, lc)))
                end do
            end do
            value = max_on_all(c, value)
        end associate
    end function distributed_max_entry

    !> Every entry of the system finite.
    function distributed_all_finite(this) result(value)
        class(distributed_stiffness), intent(in) :: this
        logical :: value

        associate (k => this%system)
            value = all_true(this%context, all(ieee_is_finite(k%a(1:k%local_rows, :))))
        end associate
    end function distributed_all_finite

    !> t = t + A dd = t + K_CC dd + K_CF delta, delta of the last solve.
    subroutine distributed_multiply(this, dd, t)
        class(distributed_stiffness), intent(in) :: this
        real(wp), intent(in) :: dd(:)
        real(wp), intent(inout) :: t(:)
        real(wp), allocatable :: x(:), y(:)

        allocate (x(this%system%columns), y(this%system%rows), source=0.0_wp)
        x(this%contact_unknowns) = dd
        x(this%free_unknowns) = this%free_dd
        call multiply_whole(this%context, this%system, x, y)
        t = t + y(this%contact_unknowns)
    end subroutine distributed_multiply

    !> The method's reduced system with the free unknowns carried along (right-hand side 0);
    !> keeps their solution delta. Elements are named by their number in the model. Every
    !> reduced system is factorized anew (nothing is kept to update): each is counted as a
    !> factorization.
    subroutine distributed_solve_reduced(this, system, x, subject, singular, seconds, flops)
        class(distributed_stiffness), intent(inout) :: this
        type(reduced_system), intent(in) :: system
        real(wp), intent(out) :: x(:)
        character(len=*), intent(in) :: subject
        type(error_type), allocatable, intent(out) :: singular
        real(wp), intent(inout) :: seconds, flops
        real(wp), allocatable :: solution(:)
        integer, allocatable :: partner(:)
        integer :: m, nc, nf2, f
        real(wp) :: seconds_before, flops_before

        m = size(system%unknown)
        nc = size(this%contact_elements)
        nf2 = size(this%free_unknowns)
        if (m == 0) then
            ! No contact DD moves: delta solves K_FF delta = 0.
            this%free_dd = 0.0_wp
            return
        end if
        partner = merge(this%contact_unknowns(system%partner), 0, system%coef /= 0.0_wp)
        allocate (solution(m + nf2))
        seconds_before = seconds
        flops_before = flops
        call this%solve_gathered([this%contact_unknowns(system%unknown), this%free_unknowns], &
                                 [partner, spread(0, 1, nf2)], &
                                 [system%coef, spread(0.0_wp, 1, nf2)], &
                                 [system%rhs, spread(0.0_wp, 1, nf2)], &
                                 [this%contact_elements(modulo(system%unknown - 1, nc) + 1), &
                                  this%free_elements([((f + 1) / 2, f = 1, nf2)])], &
                                 [system%unknown <= nc, [(mod(f, 2) == 1, f = 1, nf2)]], &
                                 subject, solution, singular, seconds, flops)
        call this%counts%add(factor_counts(factorizations=1, seconds=seconds - seconds_before, &
                                           flops=flops - flops_before))
        if (allocated(singular)) return
        x = solution(1:m)
        this%free_dd = solution(m + 1:)
    end subroutine distributed_solve_reduced

    !> The free DDs with every contact DD at zero: K_FF x = b (collective).
    subroutine solve_free(this, b, x, subject, singular, seconds, flops, ill_conditioned)
        !> The operator
        class(distributed_stiffness), intent(inout) :: this
        !> Given values of the free rows, ordered as free_unknowns, shape (2 nf)
        real(wp), intent(in) :: b(:)
        !> The free DDs, ordered as free_unknowns, shape (2 nf) [length]
        real(wp), intent(out) :: x(:)
        !> What the system is, for the message
        character(len=*), intent(in) :: subject
        !> Allocated when K_FF is (numerically) singular
        type(error_type), allocatable, intent(out) :: singular
        !> Wall time [s] and nominal flops of the factorization are added
        real(wp), intent(inout) :: seconds, flops
        !> A numerically (not exactly) singular K_FF is reported here (x is then usable)
        type(error_type), allocatable, intent(out) :: ill_conditioned
        integer :: nf2, f

        nf2 = size(this%free_unknowns)
        call this%solve_gathered(this%free_unknowns, spread(0, 1, nf2), spread(0.0_wp, 1, nf2), &
                                 b, this%free_elements([((f + 1) / 2, f = 1, nf2)]), &
                                 [(mod(f, 2) == 1, f = 1, nf2)], subject, x, singular, seconds, &
                                 flops, ill_conditioned)
    end subroutine solve_free

    !> Gather J(k, l) = K(rows(k), rows(l)) + coef(k) K(partner(k), rows(l)), factorize it
    !> (checked) and solve J x = rhs (collective).
    subroutine solve_gathered(this, rows, partner, coef, rhs, element, shear, subject, x, &
                              singular, seconds, flops, ill_conditioned)
        !> The operator
        class(distributed_stiffness), intent(in) :: this
        !> Global rows (and columns) of the system, partner rows (0: none), shape (m)
        integer, intent(in) :: rows(:), partner(:)
        !> Factor of each partner row and the right-hand side, shape (m)
        real(wp), intent(in) :: coef(:), rhs(:)
        !> Model element and kind of each unknown, for the messages, shape (m)
        integer, intent(in) :: element(:)
        logical, intent(in) :: shear(:)
        !> What the system is, for the message
        character(len=*), intent(in) :: subject
        !> The solution, shape (m)
        real(wp), intent(out) :: x(:)
        !> Allocated when J is (numerically) singular
        type(error_type), allocatable, intent(out) :: singular
        !> Wall time [s] and nominal flops of the factorization are added
        real(wp), intent(inout) :: seconds, flops
        !> When present, a numerically (not exactly) singular J is reported here
        type(error_type), allocatable, intent(out), optional :: ill_conditioned
        type(distributed_matrix) :: j
        integer, allocatable :: ipiv(:)
        integer(int64) :: t0, t1, rate

        call gather_submatrix(this%context, this%system, rows, partner, coef, rows, j, singular)
        if (allocated(singular)) return
        call system_clock(t0, rate)
        call distributed_lu(this%context, j, ipiv, subject, singular, element, shear, &
                            ill_conditioned)
        call system_clock(t1)
        seconds = seconds + real(t1 - t0, wp) / real(max(rate, 1_int64), wp)
        flops = flops + 2.0_wp / 3.0_wp * real(size(rows), wp)**3
        if (allocated(singular)) return
        call distributed_solve(this%context, j, ipiv, rhs, x)
    end subroutine solve_gathered

end module ddc_parallel_stiffness
