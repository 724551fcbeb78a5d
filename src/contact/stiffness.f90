!> The influence matrix A of a contact problem as the active-set Newton method sees it
!> (ddc_contact_active_set): its stiffness scale, products A D, and solves of reduced systems
!> made of its rows and columns. A dense matrix in memory (dense_stiffness) is one; a matrix
!> distributed over MPI processes (src/parallel/) is another, so that the state logic of the
!> method, its certificate and its checks are one code for both.
!>
!> A has 2n rows and columns for n contact elements, ordered [s; n]: traction = s_r + A D
!> with D = [Ds; Dn]. A reduced system keeps m of the unknowns (ddc_contact_active_set says
!> which) and one row for each: J(k, l) = A(unknown(k), unknown(l)) + coef(k) A(partner(k),
!> unknown(l)).
!>
!> The dense operator keeps the factors of its reduced systems between solves
!> (ddc_contact_reduced_factors): a system of the same unknowns and rows reuses them, a few
!> changes update them, and only many changes factorize anew; every operator records what
!> its last solve did (action) and counts its solves (ddc_contact_counts).
module ddc_contact_stiffness
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_linalg_lapack, only: dgemv
    use ddc_contact_counts, only: factor_counts, since
    use ddc_contact_reduced_factors, only: reduced_factors, set_system, solve_system, &
        forget_factors, last_action, counts_of, action_factorized, action_updated, &
        action_reused
    implicit none
    private

    public :: stiffness_operator, reduced_system, dense_stiffness
    public :: action_solved, action_factorized, action_updated, action_reused, action_name

    !> What a reduced solve did beyond the codes of ddc_contact_reduced_factors: solved
    !> without saying how (an operator that factorizes every system)
    integer, parameter :: action_solved = 0

    !> The unknowns and rows of a reduced system of m unknowns, shape (m) each.
    type :: reduced_system
        !> Unknown k is unknown(k) of A ([s; n] ordering, 1 to 2n)
        integer, allocatable :: unknown(:)
        !> Row k is row unknown(k) plus coef(k) times row partner(k) of A
        integer, allocatable :: partner(:)
        real(wp), allocatable :: coef(:)
        !> Right-hand side [stress]
        real(wp), allocatable :: rhs(:)
    end type reduced_system

    !> The influence matrix of n contact elements, however it is stored. Every procedure is
    !> called by every process of a distributed run with the same arguments.
    type, abstract :: stiffness_operator
        !> What the last solve_reduced did (action_*)
        integer :: action = action_solved
        !> What its reduced solves did so far: new LU factorizations, low-rank updates of
        !> kept factors, reuses of unchanged factors, their time and flops
        type(factor_counts) :: counts
    contains
        !> Largest |A_ii| [stress / length]
        procedure(real_query), deferred :: max_diagonal
        !> Largest |A_ij| [stress / length]
        procedure(real_query), deferred :: max_entry
        !> Every entry finite
        procedure(logical_query), deferred :: all_finite
        !> t = t + A dd
        procedure(multiply_interface), deferred :: multiply
        !> t = t + A dd on the rows needed, the others left as they are (default: from the
        !> whole product)
        procedure :: multiply_rows => multiply_every_row
        !> Solve a reduced system
        procedure(solve_interface), deferred :: solve_reduced
        !> Drop kept factors: the next reduced solve factorizes anew (default: nothing kept)
        procedure :: discard_factors => keep_nothing
    end type stiffness_operator

    abstract interface
        !> A number describing the matrix.
        function real_query(this) result(value)
            import :: stiffness_operator, wp
            implicit none
            !> The matrix
            class(stiffness_operator), intent(in) :: this
            !> The number
            real(wp) :: value
        end function real_query

        !> A property of the matrix.
        function logical_query(this) result(value)
            import :: stiffness_operator
            implicit none
            !> The matrix
            class(stiffness_operator), intent(in) :: this
            !> Whether it holds
            logical :: value
        end function logical_query

        !> t = t + A dd. An operator may keep unknowns of its own (condensed out of A) from
        !> its last solve_reduced; dd is then the solution of that solve.
        subroutine multiply_interface(this, dd, t)
            import :: stiffness_operator, wp
            implicit none
            !> The matrix
            class(stiffness_operator), intent(in) :: this
            !> DDs [Ds; Dn] [length], shape (2n)
            real(wp), intent(in) :: dd(:)
            !> Tractions [stress], shape (2n): A dd is added
            real(wp), intent(inout) :: t(:)
        end subroutine multiply_interface

        !> Solve the reduced system J x = system%rhs with a checked LU factorization.
        subroutine solve_interface(this, system, x, subject, singular, seconds, flops)
            import :: stiffness_operator, reduced_system, error_type, wp
            implicit none
            !> The matrix (an operator with unknowns of its own keeps their solution)
            class(stiffness_operator), intent(inout) :: this
            !> The reduced system (possibly without unknowns: every DD fixed at zero)
            type(reduced_system), intent(in) :: system
            !> The solution, shape (m)
            real(wp), intent(out) :: x(:)
            !> What the system is, for the message
            character(len=*), intent(in) :: subject
            !> Allocated when J is (numerically) singular, naming the element and unknown
            type(error_type), allocatable, intent(out) :: singular
            !> Wall time [s] and nominal flops of the factorization are added
            real(wp), intent(inout) :: seconds, flops
        end subroutine solve_interface
    end interface

    !> A dense influence matrix in memory (not copied: a pointer to the caller's), and the
    !> factors of its last reduced systems.
    type, extends(stiffness_operator) :: dense_stiffness
        !> The matrix, shape (2n, 2n) [stress / length]
        real(wp), pointer, contiguous :: a(:, :) => null()
        !> The kept factors
        type(reduced_factors) :: factors
    contains
        procedure :: max_diagonal => dense_max_diagonal
        procedure :: max_entry => dense_max_entry
        procedure :: all_finite => dense_all_finite
        procedure :: multiply => dense_multiply
        procedure :: multiply_rows => dense_multiply_rows
        procedure :: solve_reduced => dense_solve_reduced
        procedure :: discard_factors => dense_discard_factors
    end type dense_stiffness

contains

    !> Nothing is kept: nothing to drop.
    subroutine keep_nothing(this)
        class(stiffness_operator), intent(inout) :: this

        this%action = action_solved
    end subroutine keep_nothing

    !> t = t + A dd on the rows needed, from the whole product (an operator that has no
    !> cheaper way to them).
    subroutine multiply_every_row(this, dd, needed, t)
        !> The matrix
        class(stiffness_operator), intent(in) :: this
        !> DDs [Ds; Dn] [length], shape (2n)
        real(wp), intent(in) :: dd(:)
        !> The rows needed, shape (2n)
        logical, intent(in) :: needed(:)
        !> Tractions [stress], shape (2n): A dd is added on the rows needed
        real(wp), intent(inout) :: t(:)
        real(wp), allocatable :: product(:)

        allocate (product(size(t)), source=0.0_wp)
        call this%multiply(dd, product)
        where (needed) t = t + product
    end subroutine multiply_every_row

    !> The name of a reduced solve's action, for progress lines.
    pure function action_name(action) result(name)
        !> action_solved, action_factorized, action_updated or action_reused
        integer, intent(in) :: action
        character(len=:), allocatable :: name

        select case (action)
        case (action_factorized)
            name = 'new factorization'
        case (action_updated)
            name = 'low-rank update'
        case (action_reused)
            name = 'factorization reused'
        case default
            name = 'solved'
        end select
    end function action_name

    !> Largest |A_ii|.
    function dense_max_diagonal(this) result(value)
        class(dense_stiffness), intent(in) :: this
        real(wp) :: value
        integer :: i

        value = 0.0_wp
        do i = 1, size(this%a, 1)
            value = max(value, abs(this%a(i, i)))
        end do
    end function dense_max_diagonal

    !> Largest |A_ij|.
    function dense_max_entry(this) result(value)
        class(dense_stiffness), intent(in) :: this
        real(wp) :: value

        value = maxval(abs(this%a))
    end function dense_max_entry

    !> Every entry finite (a pass over 4 n^2 entries: parallel over the columns).
    function dense_all_finite(this) result(value)
        class(dense_stiffness), intent(in) :: this
        logical :: value
        real(wp), pointer, contiguous :: a(:, :)
        integer :: j

        a => this%a
        value = .true.
        !$omp parallel do default(none) shared(a) reduction(.and.:value) schedule(static)
        do j = 1, size(a, 2)
            value = value .and. all(ieee_is_finite(a(:, j)))
        end do
        !$omp end parallel do
    end function dense_all_finite

    !> t = t + A dd (dgemv).
    subroutine dense_multiply(this, dd, t)
        class(dense_stiffness), intent(in) :: this
        real(wp), intent(in) :: dd(:)
        real(wp), intent(inout) :: t(:)
        integer :: n2

        n2 = size(this%a, 1)
        call dgemv('N', n2, n2, 1.0_wp, this%a, n2, dd, 1, 1.0_wp, t, 1)
    end subroutine dense_multiply

    !> t = t + A dd on the runs of rows needed (a run is a block of A's rows: its columns'
    !> pieces are contiguous), runs closer than run_gap rows joined, the rows between them
    !> left as they are; from the whole product when most rows are needed.
    subroutine dense_multiply_rows(this, dd, needed, t)
        class(dense_stiffness), intent(in) :: this
        real(wp), intent(in) :: dd(:)
        logical, intent(in) :: needed(:)
        real(wp), intent(inout) :: t(:)
        integer, parameter :: run_gap = 16
        real(wp), pointer, contiguous :: entries(:)
        real(wp), allocatable :: product(:)
        integer :: n2, first, last, next

        n2 = size(this%a, 1)
        if (4 * count(needed) > 3 * n2) then
            call multiply_every_row(this, dd, needed, t)
            return
        end if
        ! A as one vector: a run's block starts at its first row of column 1.
        entries(1:size(this%a)) => this%a
        allocate (product(n2), source=0.0_wp)
        first = findloc(needed, .true., 1)
        do while (first > 0)
            ! The run ends where no row is needed for run_gap rows.
            last = first
            do
                next = findloc(needed(last + 1:min(n2, last + run_gap)), .true., 1)
                if (next == 0) exit
                last = last + next
            end do
            call dgemv('N', last - first + 1, n2, 1.0_wp, entries(first:), n2, dd, 1, 0.0_wp, &
                       product(first:last), 1)
            first = 0
            if (last < n2) then
                first = findloc(needed(last + 1:), .true., 1)
                if (first > 0) first = first + last
            end if
        end do
        where (needed) t = t + product
    end subroutine dense_multiply_rows

    !> Solve J x = rhs with the kept factors: reused, updated or new (set_system).
    subroutine dense_solve_reduced(this, system, x, subject, singular, seconds, flops)
        class(dense_stiffness), intent(inout) :: this
        type(reduced_system), intent(in) :: system
        real(wp), intent(out) :: x(:)
        character(len=*), intent(in) :: subject
        type(error_type), allocatable, intent(out) :: singular
        real(wp), intent(inout) :: seconds, flops
        type(factor_counts) :: before, now

        this%action = action_solved
        if (size(system%unknown) == 0) return
        before = counts_of(this%factors)
        call set_system(this%factors, this%a, system%unknown, system%partner, system%coef, &
                        subject, singular)
        now = counts_of(this%factors)
        seconds = seconds + now%seconds - before%seconds
        flops = flops + now%flops - before%flops
        ! The factors may carry counts of solves before this operator's (a copy).
        call this%counts%add(since(now, before))
        if (allocated(singular)) return
        this%action = last_action(this%factors)
        x = system%rhs
        call solve_system(this%factors, x)
    end subroutine dense_solve_reduced

    !> Drop the kept factors.
    subroutine dense_discard_factors(this)
        class(dense_stiffness), intent(inout) :: this

        call forget_factors(this%factors)
        this%action = action_solved
    end subroutine dense_discard_factors

end module ddc_contact_stiffness
