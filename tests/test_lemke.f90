!> Tests of the Lemke LCP solver and the LCP certificate (suite `lemke`).
module test_lemke
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: exit_solver_failure
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_contact_lemke, only: solve_lcp_lemke, lemke_rule_first_index, &
        lemke_rule_lexicographic
    use ddc_contact_certificate, only: lcp_certificate, certify_lcp
    implicit none
    private
    public :: collect_lemke

    interface
        subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            implicit none
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgesv
    end interface

contains

    !> Cases of the lemke suite.
    subroutine collect_lemke(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [ &
            new_test('trivial_q_nonnegative', test_trivial), &
            new_test('hand_n1', test_hand_n1), &
            new_test('hand_n2', test_hand_n2), &
            new_test('hand_n3', test_hand_n3), &
            new_test('random_p_matrix_spd', test_random_spd), &
            new_test('random_p_matrix_diagonally_dominant', test_random_dominant), &
            new_test('covering_vector', test_cover), &
            new_test('degenerate_ties_naive_cycles', test_degenerate_cycling), &
            new_test('degenerate_zero_q_naive_ray', test_degenerate_zero_q), &
            new_test('infeasible_ray_termination', test_infeasible), &
            new_test('pivot_limit', test_pivot_limit), &
            new_test('certificate', test_certificate) &
            ]
    end subroutine collect_lemke

    !> Solve with the default rule and check z, w against expected values and the
    !> certificate.
    subroutine solve_and_check(error, m, q, z_expected, label)
        type(error_type), allocatable, intent(inout) :: error
        real(wp), intent(in) :: m(:, :), q(:), z_expected(:)
        character(len=*), intent(in) :: label
        real(wp) :: z(size(q)), w(size(q))
        integer :: pivots, i
        type(lcp_certificate) :: cert

        call solve_lcp_lemke(m, q, z, w, pivots, error)
        if (allocated(error)) then
            error%message = label//': '//error%message
            return
        end if
        do i = 1, size(q)
            call check(error, z(i), z_expected(i), label//' z', abs_tol=1.0e-12_wp)
            call check(error, w(i), dot_product(m(i, :), z_expected) + q(i), label//' w', &
                abs_tol=1.0e-12_wp)
        end do
        if (allocated(error)) return
        cert = certify_lcp(m, q, z, w)
        call check(error, cert%passed, label//': certificate fails')
    end subroutine solve_and_check

    subroutine test_trivial(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: m(2, 2), z(2), w(2)
        integer :: pivots

        m = reshape([1.0_wp, -3.0_wp, 2.0_wp, -5.0_wp], [2, 2])
        call solve_lcp_lemke(m, [0.0_wp, 2.0_wp], z, w, pivots, error)
        if (allocated(error)) return
        call check(error, pivots, 0, 'pivots')
        call check(error, z(1), 0.0_wp, 'z1', abs_tol=0.0_wp)
        call check(error, z(2), 0.0_wp, 'z2', abs_tol=0.0_wp)
        call check(error, w(2), 2.0_wp, 'w2', abs_tol=0.0_wp)
    end subroutine test_trivial

    !> 2 z - 4 = w: z = 2, w = 0; with q = 3 the trivial solution.
    subroutine test_hand_n1(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: z(1), w(1)
        integer :: pivots

        call solve_and_check(error, reshape([2.0_wp], [1, 1]), [-4.0_wp], [2.0_wp], 'n1')
        if (allocated(error)) return
        call solve_lcp_lemke(reshape([2.0_wp], [1, 1]), [-4.0_wp], z, w, pivots, error)
        if (allocated(error)) return
        ! z0 enters, then z1 enters and z0 leaves.
        call check(error, pivots, 2, 'pivots')
    end subroutine test_hand_n1

    !> M = [2 1; 1 2]: q = (-5, -6) gives z = M^-1 (5, 6) = (4/3, 7/3), w = 0;
    !> q = (-1, 2) gives z = (1/2, 0), w = (0, 5/2).
    subroutine test_hand_n2(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: m(2, 2)

        m = reshape([2.0_wp, 1.0_wp, 1.0_wp, 2.0_wp], [2, 2])
        call solve_and_check(error, m, [-5.0_wp, -6.0_wp], [4.0_wp / 3, 7.0_wp / 3], 'both')
        call solve_and_check(error, m, [-1.0_wp, 2.0_wp], [0.5_wp, 0.0_wp], 'one')
    end subroutine test_hand_n2

    !> M = [4 1 0; 1 4 1; 0 1 4], q = (-4, 2, -4): z1 = z3 = 1 (4 z = 4, M13 = 0),
    !> w2 = z1 + z3 + 2 = 4.
    subroutine test_hand_n3(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: m(3, 3)

        m = reshape([4.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 4.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, &
            4.0_wp], [3, 3])
        call solve_and_check(error, m, [-4.0_wp, 2.0_wp, -4.0_wp], &
            [1.0_wp, 0.0_wp, 1.0_wp], 'n3')
    end subroutine test_hand_n3

    !> Random P-matrices M = B B' + 0.1 I (symmetric positive definite), n = 1..8.
    subroutine test_random_spd(error)
        type(error_type), allocatable, intent(out) :: error
        call random_p_matrix_cases(error, 1)
    end subroutine test_random_spd

    !> Random non-symmetric P-matrices: strictly row diagonally dominant, positive diagonal.
    subroutine test_random_dominant(error)
        type(error_type), allocatable, intent(out) :: error
        call random_p_matrix_cases(error, 2)
    end subroutine test_random_dominant

    !> For each n = 1..8, 10 seeded problems: Lemke against brute-force enumeration of all
    !> 2^n complementary bases (a P-matrix LCP has exactly one solution).
    subroutine random_p_matrix_cases(error, kind)
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in) :: kind
        integer(int64) :: seed
        real(wp), allocatable :: m(:, :), b(:, :), q(:), z(:), w(:), zb(:)
        integer :: n, trial, pivots, nsol, i
        character(len=40) :: label

        seed = 20120304_int64 + kind
        do n = 1, 8
            do trial = 1, 10
                allocate (m(n, n), b(n, n), q(n), z(n), w(n), zb(n))
                call random_matrix(seed, b)
                if (kind == 1) then
                    m = matmul(b, transpose(b))
                    do i = 1, n
                        m(i, i) = m(i, i) + 0.1_wp
                    end do
                else
                    m = b
                    do i = 1, n
                        m(i, i) = sum(abs(b(i, :))) - abs(b(i, i)) + 0.2_wp
                    end do
                end if
                call random_matrix(seed, b)
                q = b(:, 1)
                write (label, '(a,i0,a,i0)') 'n = ', n, ', trial ', trial
                call brute_force(m, q, zb, nsol)
                call check(error, nsol, 1, trim(label)//': brute-force solutions')
                if (allocated(error)) return
                call solve_lcp_lemke(m, q, z, w, pivots, error)
                if (allocated(error)) then
                    error%message = trim(label)//': '//error%message
                    return
                end if
                do i = 1, n
                    call check(error, z(i), zb(i), trim(label)//' z', abs_tol=1.0e-10_wp)
                end do
                call check(error, pivots <= 10 * n, trim(label)//': too many pivots')
                if (allocated(error)) return
                deallocate (m, b, q, z, w, zb)
            end do
        end do
    end subroutine random_p_matrix_cases

    !> A non-default covering vector reaches the same (unique) solution.
    subroutine test_cover(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: m(3, 3), z(3), w(3)
        integer :: pivots

        m = reshape([4.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 4.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, &
            4.0_wp], [3, 3])
        call solve_lcp_lemke(m, [-4.0_wp, 2.0_wp, -4.0_wp], z, w, pivots, error, &
            cover=[1.0_wp, 2.0_wp, 3.0_wp])
        if (allocated(error)) return
        call check(error, z(1), 1.0_wp, 'z1', abs_tol=1.0e-12_wp)
        call check(error, z(2), 0.0_wp, 'z2', abs_tol=1.0e-12_wp)
        call check(error, z(3), 1.0_wp, 'z3', abs_tol=1.0e-12_wp)
        call check(error, w(2), 4.0_wp, 'w2', abs_tol=1.0e-12_wp)
    end subroutine test_cover

    !> Degenerate LCP with a P-matrix and q = (-1, -1, -1): every ratio test ties.
    !>
    !> M is a P-matrix (principal minors 1, 1, 1, 4, 5, 5 and det 20), so the LCP has
    !> exactly one solution for every q and Lemke with the lexicographic rule must reach
    !> it. With the naive rule (smallest row index among ties) the method is deterministic
    !> and never terminates: it runs 100 pivots, more than the number of distinct bases of
    !> [I, -M, -d] (at most C(7, 3) = 35), so a basis repeats - it cycles. Found by a
    !> seeded search over small integer P-matrices.
    subroutine test_degenerate_cycling(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        real(wp) :: m(3, 3), q(3), z(3), w(3), zb(3)
        integer :: pivots, nsol

        m = transpose(reshape([1.0_wp, 3.0_wp, -2.0_wp, -1.0_wp, 1.0_wp, 2.0_wp, &
            2.0_wp, -2.0_wp, 1.0_wp], [3, 3]))
        q = -1.0_wp
        call brute_force(m, q, zb, nsol)
        call check(error, nsol, 1, 'brute-force solutions')
        if (allocated(error)) return
        call solve_and_check(error, m, q, zb, 'lexicographic')
        if (allocated(error)) return
        call solve_lcp_lemke(m, q, z, w, pivots, error, rule=lemke_rule_lexicographic)
        if (allocated(error)) return
        call check(error, pivots, 4, 'lexicographic pivots')
        call solve_lcp_lemke(m, q, z, w, pivots, failure, max_pivots=100, &
            rule=lemke_rule_first_index)
        call check(error, allocated(failure), 'the naive rule should cycle on this problem')
        if (allocated(error)) return
        call check(error, index(failure%message, 'pivot limit') > 0, &
            'the naive rule should stop at the pivot limit: '//failure%message)
        call check(error, pivots, 100, 'naive pivots')
    end subroutine test_degenerate_cycling

    !> Degenerate LCP with a zero in q and a tie in the first ratio test (q1/d1 = q3/d3).
    !>
    !> A solution exists (brute force finds it), and the lexicographic rule finds it in 3
    !> pivots. The naive rule lets z0 replace w_1 (first index of the tie); w_3 stays basic
    !> at zero and z_1 then enters with no positive entry in its column: a ray after one
    !> pivot, so naive Lemke reports "no solution" for a solvable problem.
    subroutine test_degenerate_zero_q(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        real(wp) :: m(3, 3), q(3), z(3), w(3), zb(3)
        integer :: pivots, nsol

        m = transpose(reshape([-1.0_wp, -1.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, -1.0_wp, &
            -1.0_wp, 1.0_wp, 0.0_wp], [3, 3]))
        q = [-1.0_wp, 0.0_wp, -1.0_wp]
        call brute_force(m, q, zb, nsol)
        call check(error, nsol >= 1, 'brute force finds no solution')
        if (allocated(error)) return
        call solve_lcp_lemke(m, q, z, w, pivots, error)
        if (allocated(error)) return
        call check(error, pivots, 3, 'lexicographic pivots')
        call check(error, is_solution(m, q, z), 'lexicographic z is not a solution')
        if (allocated(error)) return
        call solve_lcp_lemke(m, q, z, w, pivots, failure, rule=lemke_rule_first_index)
        call check(error, allocated(failure), 'the naive rule should end on a ray')
        if (allocated(error)) return
        call check(error, index(failure%message, 'ray') > 0, 'expected a ray: '//failure%message)
        call check(error, pivots, 1, 'naive pivots')
    end subroutine test_degenerate_zero_q

    !> w = -z - 1 >= 0 has no solution with z >= 0: ray termination, reported.
    subroutine test_infeasible(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        real(wp) :: z(1), w(1)
        integer :: pivots

        call solve_lcp_lemke(reshape([-1.0_wp], [1, 1]), [-1.0_wp], z, w, pivots, failure)
        call check(error, allocated(failure), 'an infeasible LCP must be an error')
        if (allocated(error)) return
        call check(error, failure%code == exit_solver_failure, 'wrong code: '//failure%message)
        call check(error, index(failure%message, 'ray') > 0, 'not a ray: '//failure%message)
        call check(error, pivots, 1, 'pivots')
    end subroutine test_infeasible

    !> A solvable problem stopped by a pivot limit of 1 is an error, not a result.
    subroutine test_pivot_limit(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        real(wp) :: m(2, 2), z(2), w(2)
        integer :: pivots

        m = reshape([2.0_wp, 1.0_wp, 1.0_wp, 2.0_wp], [2, 2])
        call solve_lcp_lemke(m, [-5.0_wp, -6.0_wp], z, w, pivots, failure, max_pivots=1)
        call check(error, allocated(failure), 'the pivot limit must be an error')
        if (allocated(error)) return
        call check(error, failure%code == exit_solver_failure, 'wrong code: '//failure%message)
        call check(error, index(failure%message, 'pivot limit') > 0, &
                   'not the pivot limit: '//failure%message)
        call check(error, pivots, 1, 'pivots')
    end subroutine test_pivot_limit

    !> The certificate recomputes w from M and q, applies the scales, and fails bad answers.
    subroutine test_certificate(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: m(2, 2), q(2), z(2), w(2)
        type(lcp_certificate) :: cert

        m = reshape([2.0_wp, 1.0_wp, 1.0_wp, 2.0_wp], [2, 2])
        q = [-1.0_wp, 2.0_wp]
        z = [0.5_wp, 0.0_wp]
        w = [0.0_wp, 2.5_wp]
        cert = certify_lcp(m, q, z, w)
        call check(error, cert%passed, 'exact solution fails')
        call check(error, cert%min_w, 0.0_wp, 'min_w', abs_tol=1.0e-15_wp)
        ! The solver's w is not trusted: a wrong w fails through the mismatch.
        cert = certify_lcp(m, q, z, [0.0_wp, 1.0_wp])
        call check(error, .not. cert%passed, 'a wrong w passes')
        ! Row 2: M z + q = 2.5, scale max(|q_2|, |M_21 z_1|) = 2: |1 - 2.5| / 2 = 0.75.
        call check(error, cert%max_w_mismatch, 0.75_wp, 'mismatch', rel_tol=1.0e-12_wp)
        ! z = (0.5 + 1e-6, 0): w1 = 2e-6 > 0 so z1 w1 = 1e-6 violates complementarity.
        z(1) = 0.5_wp + 1.0e-6_wp
        w = matmul(m, z) + q
        cert = certify_lcp(m, q, z, w)
        call check(error, .not. cert%passed, 'a non-complementary z passes')
        ! Scales: w_1 is in units 1e-3 here, so the same z violates more, scaled.
        cert = certify_lcp(m, q, z, w, z_scale=[1.0_wp, 1.0_wp], w_scale=[1.0e-3_wp, 1.0_wp], &
            tolerance=1.0e-2_wp)
        call check(error, cert%max_complementarity, (0.5_wp + 1.0e-6_wp) * 2.0e-3_wp, &
            'scaled complementarity', rel_tol=1.0e-6_wp)
        call check(error, cert%passed, 'tolerance 1e-2 should pass')
        ! A negative z fails.
        cert = certify_lcp(m, q, [-1.0e-3_wp, 0.0_wp], matmul(m, [-1.0e-3_wp, 0.0_wp]) + q)
        call check(error, .not. cert%passed, 'a negative z passes')
        ! Inconsistent sizes fail.
        cert = certify_lcp(m, q, [0.5_wp], w)
        call check(error, .not. cert%passed, 'inconsistent sizes pass')
    end subroutine test_certificate

    !> All solutions among the 2^n complementary bases: z_S = -M_SS^-1 q_S, feasible
    !> when z >= 0 and w = M z + q >= 0 (to 1e-12). Returns the last one found.
    subroutine brute_force(m, q, z, nsol)
        real(wp), intent(in) :: m(:, :), q(:)
        real(wp), intent(out) :: z(:)
        integer, intent(out) :: nsol
        real(wp), allocatable :: a(:, :), b(:, :), zt(:)
        integer, allocatable :: idx(:), ipiv(:)
        integer :: n, s, i, k, info

        n = size(q)
        nsol = 0
        z = 0.0_wp
        allocate (zt(n))
        do s = 0, 2**n - 1
            idx = pack([(i, i=1, n)], [(btest(s, i - 1), i=1, n)])
            k = size(idx)
            zt = 0.0_wp
            if (k > 0) then
                a = m(idx, idx)
                allocate (b(k, 1), ipiv(k))
                b(:, 1) = -q(idx)
                call dgesv(k, 1, a, k, ipiv, b, k, info)
                if (info /= 0) then
                    deallocate (b, ipiv)
                    cycle
                end if
                zt(idx) = b(:, 1)
                deallocate (b, ipiv)
            end if
            if (is_solution(m, q, zt)) then
                nsol = nsol + 1
                z = zt
            end if
        end do
    end subroutine brute_force

    !> z >= 0, w = M z + q >= 0, z'w = 0, each to 1e-10.
    pure logical function is_solution(m, q, z)
        real(wp), intent(in) :: m(:, :), q(:), z(:)
        real(wp) :: w(size(q))

        w = matmul(m, z) + q
        is_solution = all(z >= -1.0e-10_wp) .and. all(w >= -1.0e-10_wp) .and. &
            all(abs(z * w) <= 1.0e-10_wp)
    end function is_solution

    !> Fill a matrix with uniform values in [-1, 1) from a Park-Miller generator.
    subroutine random_matrix(seed, b)
        integer(int64), intent(inout) :: seed
        real(wp), intent(out) :: b(:, :)
        integer :: i, j

        do j = 1, size(b, 2)
            do i = 1, size(b, 1)
                seed = mod(16807_int64 * seed, 2147483647_int64)
                b(i, j) = 2.0_wp * real(seed, wp) / 2147483647.0_wp - 1.0_wp
            end do
        end do
    end subroutine random_matrix

end module test_lemke
