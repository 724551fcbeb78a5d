!> Lemke's complementary pivoting method for the linear complementarity problem (LCP)
!>
!>     w = M z + q,  w >= 0,  z >= 0,  z'w = 0
!>
!> with a covering vector d (default all ones) and the lexicographic minimum-ratio rule
!> (ties in the ratio test broken by the rows of [q, B^-1], Cottle, Pang & Stone 1992,
!> section 4.4), which makes the method finite on degenerate problems.
!>
!> The tableau is kept dense in revised form: the explicit basis inverse B^-1 (n x n) and
!> the basic values B^-1 q. A pivot costs one matrix-vector product (the entering column,
!> BLAS dgemv) and one rank-1 update (BLAS dger): O(n^2). On termination the basic values
!> are recomputed from the final basis with one checked LU solve when that makes the
!> solution more accurate than the accumulated tableau.
!>
!> Tolerances are relative to the data, so the problem should be scaled so that its
!> entries are commensurate (the contact formulation scales stresses and displacements
!> to O(1) before calling). Knows nothing of elasticity.
module ddc_contact_lemke
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, set_internal_error, exit_solver_failure
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use ddc_linalg_lapack, only: dgemv, dger
    use ddc_linalg_lu, only: lu_factor, lu_solve
    use ddc_allocation, only: allocation_failed, real_bytes
    use ddc_text, only: itoa
    implicit none
    private

    public :: solve_lcp_lemke
    public :: lemke_rule_lexicographic, lemke_rule_first_index

    !> Ties in the ratio test broken by the rows of [q, B^-1] (the default; finite)
    integer, parameter :: lemke_rule_lexicographic = 1
    !> Ties broken by the smallest row index (textbook naive rule: can cycle or end on a
    !> ray on degenerate problems; kept only to test and demonstrate the default)
    integer, parameter :: lemke_rule_first_index = 2

    !> Relative size below which an entry of the entering column is not a pivot candidate
    real(wp), parameter :: pivot_tol = 1.0e-11_wp
    !> Relative size below which two rows tie in the ratio test
    real(wp), parameter :: tie_tol = 1.0e-11_wp
    !> Relative size below which two entries of B^-1 tie in the lexicographic test
    real(wp), parameter :: lex_tol = 1.0e-9_wp

contains

    !> Solve the LCP w = M z + q, w >= 0, z >= 0, z'w = 0 by Lemke's method.
    !>
    !> Returns z = 0, w = q with 0 pivots when q >= 0. Ray termination (no blocking row
    !> for the entering variable: the LCP has no solution or Lemke cannot find one) and
    !> exceeding max_pivots are errors with code exit_solver_failure; pivots is set in
    !> every case. Nonbasic variables are exactly zero in z and w.
    !>
    !> Warm start (a sequence of LCPs with the same M, e.g. a loading history): when
    !> warm_basis names a complementary basis whose basic values B^-1 q are all
    !> non-negative, that basis is the solution (0 pivots, one LAPACK solve); otherwise the
    !> method starts from scratch. basis returns the final complementary basis.
    subroutine solve_lcp_lemke(m, q, z, w, pivots, error, max_pivots, cover, rule, &
                               warm_basis, basis)
        !> The LCP matrix, shape (n, n)
        real(wp), intent(in) :: m(:, :)
        !> The LCP vector, shape (n)
        real(wp), intent(in) :: q(:)
        !> Solution z >= 0, shape (n)
        real(wp), intent(out) :: z(:)
        !> Solution w = M z + q >= 0, shape (n)
        real(wp), intent(out) :: w(:)
        !> Number of pivots done (including the first one, on the covering variable)
        integer, intent(out) :: pivots
        !> Allocated on ray termination, pivot limit or bad arguments
        type(error_type), allocatable, intent(out) :: error
        !> Pivot limit (default 10 n)
        integer, intent(in), optional :: max_pivots
        !> Covering vector d > 0, shape (n) (default all ones)
        real(wp), intent(in), optional :: cover(:)
        !> Tie-breaking rule (default lemke_rule_lexicographic)
        integer, intent(in), optional :: rule
        !> A complementary basis to try first: variable indices, 1..n for w_i and n+1..2n
        !> for z_i, shape (n)
        integer, intent(in), optional :: warm_basis(:)
        !> The final complementary basis, same coding, shape (n) (all w when q >= 0;
        !> meaningless after an error)
        integer, intent(out), optional :: basis(:)

        real(wp), allocatable :: binv(:, :), bbar(:), col(:), d(:), x(:)
        integer, allocatable :: rows(:)
        integer :: n, limit, tie_rule, entering, leaving, r, i, z0, stat
        real(wp) :: qscale
        logical :: ok
        character(len=200) :: line

        n = size(q)
        pivots = 0
        z = 0.0_wp
        w = 0.0_wp
        if (size(m, 1) /= n .or. size(m, 2) /= n .or. size(z) /= n .or. size(w) /= n) then
            call set_internal_error(error, 'solve_lcp_lemke', 'matrix and vector sizes differ')
            return
        end if
        if (.not. all(ieee_is_finite(q)) .or. .not. all(ieee_is_finite(m))) then
            call set_internal_error(error, 'solve_lcp_lemke', 'M or q holds NaN or Inf')
            return
        end if
        allocate (d(n))
        d = 1.0_wp
        if (present(cover)) then
            if (size(cover) /= n) then
                call set_internal_error(error, 'solve_lcp_lemke', &
                                        'covering vector has the wrong size')
                return
            end if
            if (any(.not. (cover > 0.0_wp))) then
                call set_internal_error(error, 'solve_lcp_lemke', &
                                        'covering vector must be positive')
                return
            end if
            d = cover
        end if
        limit = 10 * n
        if (present(max_pivots)) limit = max_pivots
        tie_rule = lemke_rule_lexicographic
        if (present(rule)) tie_rule = rule

        ! Trivial solution.
        w = q
        if (present(basis)) basis = [(i, i = 1, n)]
        if (all(q >= 0.0_wp)) return
        w = 0.0_wp

        ! Warm start: the given basis when it is complementary and feasible for this q.
        if (present(warm_basis)) then
            if (size(warm_basis) == n) then
                ok = all(warm_basis >= 1 .and. warm_basis <= 2 * n)
                ! One of w_i, z_i for every i, in any row order.
                if (ok) ok = all([(count(modulo(warm_basis - 1, n) + 1 == i) == 1, &
                                   i = 1, n)])
                if (ok) call basis_values(m, q, warm_basis, x, ok, error)
                if (allocated(error)) return
                if (ok) ok = minval(x) >= -tie_tol * maxval(abs(q))
                if (ok) then
                    call current_solution(warm_basis, x, n, z, w)
                    if (present(basis)) basis = warm_basis
                    return
                end if
            end if
        end if

        ! Variables: 1..n are w_i, n+1..2n are z_i, 2n+1 is the covering variable z0.
        z0 = 2 * n + 1
        allocate (bbar(n), col(n), rows(n))
        allocate (binv(n, n), stat=stat)
        if (stat /= 0) then
            call allocation_failed(error, "the basis inverse of Lemke's method (LCP of "// &
                                   'size '//itoa(n)//')', real_bytes * real(n, wp)**2)
            return
        end if
        binv = 0.0_wp
        do i = 1, n
            binv(i, i) = 1.0_wp
            rows(i) = i
        end do
        bbar = q
        qscale = maxval(abs(q))

        ! First pivot: z0 enters (column -d); the leaving row is the lexicographic
        ! minimum of (q_i, e_i') / d_i, which makes every row lexico-positive.
        col = -d
        r = select_row(bbar, binv, d, qscale, tie_rule, rows, 0)
        call pivot(binv, bbar, col, r)
        leaving = rows(r)
        rows(r) = z0
        pivots = 1

        do
            entering = complement(leaving, n)
            if (pivots >= limit) then
                write (line, '(a,i0,a,i0,a)') 'LCP: Lemke reached its pivot limit (', &
                    limit, ') without a solution (n = ', n, ')'
                call set_error(error, exit_solver_failure, trim(line))
                call current_solution(rows, bbar, n, z, w)
                return
            end if
            call entering_column(entering, n, m, binv, col)
            r = select_row(bbar, binv, col, qscale, tie_rule, rows, z0)
            if (r == 0) then
                write (line, '(a,i0,a,a,a,a,i0,a)') 'LCP: Lemke ended on a ray after ', &
                    pivots, trim(merge(' pivot ', ' pivots', pivots == 1)), ' (entering ', &
                    trim(variable_name(entering, n)), &
                    ', n = ', n, '): the problem has no solution that Lemke can reach'
                call set_error(error, exit_solver_failure, trim(line))
                call current_solution(rows, bbar, n, z, w)
                return
            end if
            call pivot(binv, bbar, col, r)
            leaving = rows(r)
            rows(r) = entering
            pivots = pivots + 1
            if (leaving == z0) exit
        end do

        call current_solution(rows, bbar, n, z, w)
        call refine_solution(m, q, rows, n, z, w, error)
        if (present(basis)) basis = rows
    end subroutine solve_lcp_lemke

    !> The complement of a variable: w_i <-> z_i.
    pure function complement(var, n) result(c)
        integer, intent(in) :: var, n
        integer :: c

        if (var <= n) then
            c = var + n
        else
            c = var - n
        end if
    end function complement

    !> Name of a variable for messages: w_i, z_i or z0.
    function variable_name(var, n) result(name)
        integer, intent(in) :: var, n
        character(len=24) :: name

        if (var <= n) then
            write (name, '(a,i0)') 'w_', var
        else if (var <= 2 * n) then
            write (name, '(a,i0)') 'z_', var - n
        else
            name = 'z0'
        end if
    end function variable_name

    !> Entering column B^-1 a_j: a_j = e_j for w_j, -M(:, j) for z_j.
    subroutine entering_column(var, n, m, binv, col)
        integer, intent(in) :: var, n
        real(wp), intent(in) :: m(:, :), binv(:, :)
        real(wp), intent(out) :: col(:)

        if (var <= n) then
            col = binv(:, var)
        else
            call dgemv('N', n, n, -1.0_wp, binv, n, m(:, var - n), 1, 0.0_wp, col, 1)
        end if
    end subroutine entering_column

    !> Pivot on row r of column col: update B^-1 and the basic values (rank-1, dger).
    subroutine pivot(binv, bbar, col, r)
        real(wp), intent(inout) :: binv(:, :), bbar(:)
        real(wp), intent(inout) :: col(:)
        integer, intent(in) :: r
        real(wp), allocatable :: row(:)
        real(wp) :: p
        integer :: n

        n = size(bbar)
        p = col(r)
        row = binv(r, :) / p
        binv(r, :) = row
        bbar(r) = bbar(r) / p
        col(r) = 0.0_wp
        call dger(n, n, -1.0_wp, col, 1, row, 1, binv, n)
        bbar = bbar - col * bbar(r)
    end subroutine pivot

    !> Row that leaves the basis, 0 when no entry of col is positive (a ray).
    !>
    !> Candidates are rows with col_i > 0 (relative to max |col|). The primary ratio is
    !> bbar_i / col_i; rows tie when stepping to the minimum ratio theta would bring them
    !> to zero as well (bbar_i - theta col_i <= tie_tol * qscale). The covering variable
    !> leaves whenever it ties (the method then ends). Other ties are broken by the
    !> lexicographic minimum of B^-1(i, :) / col_i, column by column, or by the smallest
    !> index under the naive rule.
    function select_row(bbar, binv, col, qscale, tie_rule, basis, z0) result(r)
        real(wp), intent(in) :: bbar(:), binv(:, :), col(:), qscale
        integer, intent(in) :: tie_rule, basis(:), z0
        integer :: r
        logical, allocatable :: cand(:)
        real(wp), allocatable :: ratio(:)
        real(wp) :: theta, cmax, vmin, vmax, tol
        integer :: n, i, k

        n = size(bbar)
        r = 0
        cmax = maxval(abs(col))
        if (.not. cmax > 0.0_wp) return
        cand = col > pivot_tol * cmax
        if (.not. any(cand)) return
        allocate (ratio(n))
        ratio = huge(1.0_wp)
        where (cand) ratio = bbar / merge(col, 1.0_wp, cand)
        theta = minval(ratio, mask=cand)
        tol = tie_tol * max(qscale, tiny(1.0_wp))
        do i = 1, n
            if (cand(i)) cand(i) = bbar(i) - theta * col(i) <= tol
        end do
        ! The covering variable leaves when it can: the method then ends on a solution.
        if (z0 > 0) then
            do i = 1, n
                if (cand(i) .and. basis(i) == z0) then
                    r = i
                    return
                end if
            end do
        end if
        if (count(cand) > 1) then
            if (tie_rule == lemke_rule_lexicographic) then
                do k = 1, n
                    where (cand) ratio = binv(:, k) / merge(col, 1.0_wp, cand)
                    vmin = minval(ratio, mask=cand)
                    vmax = maxval(abs(ratio), mask=cand)
                    do i = 1, n
                        if (cand(i)) cand(i) = ratio(i) - vmin <= lex_tol * vmax
                    end do
                    if (count(cand) == 1) exit
                end do
            end if
        end if
        ! First remaining candidate: the unique lexicographic minimum, or the naive choice.
        do i = 1, n
            if (cand(i)) then
                r = i
                return
            end if
        end do
    end function select_row

    !> Read z and w off the basis: basic values from bbar, nonbasic exactly zero.
    pure subroutine current_solution(basis, bbar, n, z, w)
        integer, intent(in) :: basis(:), n
        real(wp), intent(in) :: bbar(:)
        real(wp), intent(out) :: z(:), w(:)
        integer :: i

        z = 0.0_wp
        w = 0.0_wp
        do i = 1, n
            if (basis(i) <= n) then
                w(basis(i)) = bbar(i)
            else if (basis(i) <= 2 * n) then
                z(basis(i) - n) = bbar(i)
            end if
        end do
    end subroutine current_solution

    !> Recompute the basic values from the final basis with one LAPACK solve, and keep
    !> them when their complementarity violation (against M z + q) is smaller.
    subroutine refine_solution(m, q, basis, n, z, w, error)
        real(wp), intent(in) :: m(:, :), q(:)
        integer, intent(in) :: basis(:), n
        real(wp), intent(inout) :: z(:), w(:)
        !> Allocated (exit_out_of_memory) when the basis matrix does not fit in memory
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: x(:), z2(:), w2(:)
        logical :: ok

        call basis_values(m, q, basis, x, ok, error)
        if (.not. ok) return
        allocate (z2(n), w2(n))
        call current_solution(basis, x, n, z2, w2)
        if (violation(m, q, z2, w2) < violation(m, q, z, w)) then
            z = z2
            w = w2
        end if
    end subroutine refine_solution

    !> Basic values x = B^-1 q of a basis (columns e_i for w_i, -M(:, j) for z_j) by one
    !> checked LU solve; ok is false when B is (numerically) singular or x is not finite.
    subroutine basis_values(m, q, basis, x, ok, error)
        real(wp), intent(in) :: m(:, :), q(:)
        integer, intent(in) :: basis(:)
        real(wp), allocatable, intent(out) :: x(:)
        logical, intent(out) :: ok
        !> Allocated (exit_out_of_memory) when the basis matrix does not fit in memory
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: b(:, :), rhs(:, :)
        integer, allocatable :: ipiv(:)
        type(error_type), allocatable :: singular, ill_conditioned
        integer :: i, n, stat

        n = size(q)
        ok = .false.
        allocate (rhs(n, 1), ipiv(n))
        allocate (b(n, n), stat=stat)
        if (stat /= 0) then
            call allocation_failed(error, "the basis matrix of Lemke's method (LCP of "// &
                                   'size '//itoa(n)//')', real_bytes * real(n, wp)**2)
            return
        end if
        b = 0.0_wp
        do i = 1, n
            if (basis(i) <= n) then
                b(basis(i), i) = 1.0_wp
            else
                b(:, i) = -m(:, basis(i) - n)
            end if
        end do
        rhs(:, 1) = q
        ! An ill-conditioned basis is still tried: the caller compares the violations.
        call lu_factor(b, ipiv, 'LCP basis', singular, ill_conditioned=ill_conditioned)
        ok = .not. allocated(singular)
        if (ok) call lu_solve(b, ipiv, rhs)
        x = rhs(:, 1)
        if (ok) ok = all(ieee_is_finite(x))
    end subroutine basis_values

    !> Largest violation of the LCP by (z, w), relative to the size of the terms of M z + q.
    pure function violation(m, q, z, w) result(v)
        real(wp), intent(in) :: m(:, :), q(:), z(:), w(:)
        real(wp) :: v
        real(wp) :: scale

        scale = max(maxval(abs(q)), maxval(abs(w)), tiny(1.0_wp))
        v = max(0.0_wp, -minval(z) / max(maxval(abs(z)), tiny(1.0_wp)), -minval(w) / scale, &
            maxval(abs(matmul(m, z) + q - w)) / scale)
    end function violation

end module ddc_contact_lemke
