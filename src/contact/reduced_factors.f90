!> The factors of the reduced systems of the active-set method (ddc_contact_active_set) on a
!> dense influence matrix (ddc_contact_stiffness' dense_stiffness): one system factorized
!> and then reused while the element states change little.
!>
!> Its unknowns are the DDs not fixed by the states, each named by its index g in the [s; n]
!> ordering of the influence matrix A (Ds of a slipping element, Dn of an open one); the
!> row of unknown g is A(g, :) + coef A(p, :) on the unknowns' columns, p the normal row
!> of g's element. The LU factors of one such system (the base) are kept:
!> - the same unknowns and coefficients: the factors as they are (two triangular solves);
!> - a few changes (unknowns added or removed, coefficients changed): a low-rank update
!>   of the base. In the order base unknowns, then added ones, the system is
!>   [K B; C D]: K is the base matrix with the rows r of the changed base unknowns
!>   replaced (a new coefficient; a removed unknown's row by d e_r, d its old diagonal, so
!>   that its value is 0), solved through the base factors by the Sherman-Morrison-Woodbury
!>   formula K^-1 = J^-1 - Z (I + Delta Z)^-1 Delta J^-1 (Z = J^-1 on the changed rows'
!>   unit vectors, Delta their new rows minus the old); the added unknowns are eliminated
!>   by the Schur complement S = D - C K^-1 B (bordering), which keeps the scale of A.
!>   The columns of Z and of J^-1 B0 (B with the base coefficients) are kept for as long
!>   as their rows and unknowns stay in the update: when the changed rows change between
!>   Newton iterations, K^-1 B follows from them in O(mb nr na), without solving the
!>   bordered columns through J again;
!> - more than max(16, m / 8) changed plus added unknowns, or a numerically singular
!>   I + Delta Z or S: a new factorization, which becomes the base.
!> The caller checks every solution against the unfactored A (ddc_contact_active_set) and
!> drops the factors (forget_factors) when an update has lost accuracy. A growth run
!> factorizes an accepted update anew when it is more than half full (refactor_full_update).
module ddc_contact_reduced_factors
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_linalg_lapack, only: dgemm, dtrmm, dtrsm, dlaswp
    use ddc_linalg_lu, only: lu_factor, lu_solve
    use ddc_contact_counts, only: factor_counts
    implicit none
    private

    public :: reduced_factors, set_system, solve_system, forget_factors, renumber_factors
    public :: copy_factors, refactor_full_update
    public :: last_action, counts_of, border_unknowns
    public :: action_factorized, action_updated, action_reused

    !> What set_system did: a new factorization, a low-rank update of the base, or nothing
    integer, parameter :: action_factorized = 1, action_updated = 2, action_reused = 3

    !> Most changes handled by an update: max(min_update_rank, m / update_fraction)
    integer, parameter :: min_update_rank = 16, update_fraction = 8
    !> Base rows gathered together from the columns of A (C^T, Delta^T)
    integer, parameter :: gather_block = 64

    !> The reduced system of the current states and the factors it is solved with. Its
    !> components are private: the procedures below keep them consistent.
    type :: reduced_factors
        private
        !> The current unknowns ([s; n] indices of A), the partner row of each and its
        !> coefficient, shape (m)
        integer, allocatable :: unknown(:), partner(:)
        real(wp), allocatable :: coef(:)
        !> The base: unknowns, partners, coefficients and the diagonal of its matrix, shape
        !> (mb); its LU factors and pivots, shape (mb, mb) and (mb); mb < 0 before the first
        integer :: mb = -1
        integer, allocatable :: base_unknown(:), base_partner(:), ipiv(:)
        real(wp), allocatable :: base_coef(:), base_diag(:), factors(:, :)
        !> Position of each current unknown in the order base, then added, shape (m);
        !> numbers of changed base rows and of added unknowns (both 0: the base itself)
        integer, allocatable :: position(:)
        integer :: nr = 0, na = 0
        !> The changed base rows and their new coefficients (huge: removed), shape (nr);
        !> Z = J^-1 on their unit vectors, shape (mb, nr); Delta^T, shape (mb, nr); LU
        !> factors and pivots of I + Delta Z, shape (nr, nr)
        integer, allocatable :: changed_rows(:)
        real(wp), allocatable :: changed_coef(:), z(:, :), delta_t(:, :), capacitance(:, :)
        integer, allocatable :: capacitance_ipiv(:)
        !> Y0 = J^-1 B0 and W = K^-1 B, shape (mb, na), and the unknown of each column,
        !> shape (na) (border); C^T, shape (mb, na); LU factors and pivots of the Schur
        !> complement S = D - C W, shape (na, na)
        real(wp), allocatable :: y0(:, :), w(:, :), c_t(:, :), schur(:, :)
        integer, allocatable :: y0_of(:), schur_ipiv(:)
        !> The coefficient of each column of C^T, shape (na) (its unknown is y0_of's), and
        !> S before its factorization, shape (na, na)
        real(wp), allocatable :: c_t_coef(:), schur_plain(:, :)
        !> What the last set_system did (action_*)
        integer :: action = 0
        !> The base's factors were bordered (extend_base) since its last factorization: a
        !> system solved with them as they are is reported as updated, so that its caller
        !> checks the solution against the unfactored matrix
        logical :: bordered = .false.
        !> New factorizations, low-rank updates and reuses of unchanged factors, the wall
        !> time of the factorizations and updates and the flops of the factorizations
        type(factor_counts) :: counts
    end type reduced_factors

contains

    !> Make (unknown, partner, coef) the current system: reuse the factors, update them or
    !> factorize anew. error is allocated when a new factorization is (numerically)
    !> singular; it names the iteration's subject and the element.
    subroutine set_system(sys, a, unknown, partner, coef, subject, error)
        !> The system and its factors
        type(reduced_factors), intent(inout) :: sys
        !> Influence matrix ordered [s; n], shape (2n, 2n) [stress / length]
        real(wp), intent(in) :: a(:, :)
        !> Unknowns ([s; n] indices), partner rows and coefficients, shape (m)
        integer, intent(in) :: unknown(:), partner(:)
        real(wp), intent(in) :: coef(:)
        !> What the system is, for the message of a singular factorization
        character(len=*), intent(in) :: subject
        !> Allocated when the system is (numerically) singular
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: base_at(:), current_at(:), changed(:), added(:)
        logical, allocatable :: differs(:)
        integer :: n2, m, r, rank
        integer(int64) :: t0, t1, rate

        call system_clock(t0, rate)
        if (sys%mb >= 0 .and. same_system(sys, unknown, coef)) then
            ! The current system again (unchanged states): its factors or update as they are.
            sys%action = merge(action_updated, action_reused, sys%bordered)
            sys%counts%reuses = sys%counts%reuses + 1
            return
        end if
        sys%unknown = unknown
        sys%partner = partner
        sys%coef = coef
        m = size(unknown)
        n2 = size(a, 1)
        if (sys%mb >= 0) then
            allocate (base_at(n2), current_at(n2))
            base_at = 0
            current_at = 0
            base_at(sys%base_unknown) = [(r, r = 1, sys%mb)]
            current_at(unknown) = [(r, r = 1, m)]
            ! Base rows whose unknown left or whose coefficient changed; added unknowns.
            allocate (differs(sys%mb))
            do r = 1, sys%mb
                differs(r) = current_at(sys%base_unknown(r)) == 0
                if (.not. differs(r)) differs(r) = &
                    coef(current_at(sys%base_unknown(r))) /= sys%base_coef(r)
            end do
            changed = pack([(r, r = 1, sys%mb)], differs)
            added = pack([(r, r = 1, m)], base_at(unknown) == 0)
            rank = size(changed) + size(added)
            if (rank == 0) then
                sys%position = base_at(unknown)
                sys%nr = 0
                sys%na = 0
                sys%action = merge(action_updated, action_reused, sys%bordered)
                sys%counts%reuses = sys%counts%reuses + 1
                return
            end if
            if (sys%mb > 0 .and. rank <= update_limit(sys)) then
                call update_base(sys, a, changed, added, current_at, base_at)
                if (sys%action == action_updated) then
                    call system_clock(t1)
                    sys%counts%seconds = sys%counts%seconds + &
                        real(t1 - t0, wp) / real(max(rate, 1_int64), wp)
                    return
                end if
            end if
        end if
        call refactor(sys, a, subject, error)
    end subroutine set_system

    !> Most changed plus added unknowns an update of the current system may hold.
    pure integer function update_limit(sys)
        !> The system (set_system done)
        type(reduced_factors), intent(in) :: sys

        update_limit = max(min_update_rank, size(sys%unknown) / update_fraction)
    end function update_limit

    !> Make an update more than half full (2 (nr + na) > update_limit) the base: its added
    !> unknowns join the base's factors by bordering (extend_base), or, where that cannot be
    !> done, the system is factorized anew; a smaller update is carried on, leaving half for
    !> the unknowns the next systems add (a growth run: the accepted geometry's). A singular
    !> system is left to the next set_system.
    subroutine refactor_full_update(sys, a, counts)
        !> The factors (set_system done); extended or refactored, or forgotten when singular
        type(reduced_factors), intent(inout) :: sys
        !> Influence matrix of the current system [s; n], shape (2n, 2n) [stress / length]
        real(wp), intent(in) :: a(:, :)
        !> The caller's counts: the factorization, its time and flops are added
        type(factor_counts), intent(inout) :: counts
        type(error_type), allocatable :: singular
        integer, allocatable :: unknown(:), partner(:)
        real(wp), allocatable :: coef(:)
        real(wp) :: seconds, flops
        integer :: factorizations, borderings
        logical :: extended

        if (sys%mb < 0) return
        if (2 * (sys%nr + sys%na) <= update_limit(sys)) return
        unknown = sys%unknown
        partner = sys%partner
        coef = sys%coef
        seconds = sys%counts%seconds
        flops = sys%counts%flops
        factorizations = sys%counts%factorizations
        borderings = sys%counts%borderings
        ! Extended, the changed rows (if any) form the update of the new base; else the
        ! system is factorized anew.
        call extend_base(sys, a, extended)
        if (.not. extended) call forget_factors(sys)
        call set_system(sys, a, unknown, partner, coef, &
                        'the reduced system of the accepted geometry', singular)
        if (allocated(singular)) call forget_factors(sys)
        counts%factorizations = counts%factorizations + sys%counts%factorizations - &
            factorizations
        counts%borderings = counts%borderings + sys%counts%borderings - borderings
        counts%seconds = counts%seconds + sys%counts%seconds - seconds
        counts%flops = counts%flops + sys%counts%flops - flops
    end subroutine refactor_full_update

    !> The base extended by the added unknowns of the current update, without a new
    !> factorization: with P L U = J (the base) and the added unknowns' columns B and rows C
    !> on the base (base coefficients) and block D,
    !>     [J B; C D] = diag(P, P_S) [L 0; X L_S] [U Y; 0 U_S],
    !> Y = L^-1 P^T B = U Y0 (Y0 = J^-1 B, kept by border), X = P_S^T C U^-1 and
    !> P_S L_S U_S = S0 = D - C Y0: O(mb^2 na) instead of O((mb + na)^3). The current
    !> unknowns become the extended base's (the changed rows are the caller's to update).
    !> ok is false, and the factors are as they were, when there is nothing to extend or S0
    !> is numerically singular.
    subroutine extend_base(sys, a, ok)
        type(reduced_factors), intent(inout) :: sys
        real(wp), intent(in) :: a(:, :)
        logical, intent(out) :: ok
        type(error_type), allocatable :: singular, ill_conditioned
        real(wp), allocatable :: lu(:, :), s0(:, :), t(:, :), ca(:), d_diag(:)
        integer, allocatable :: at(:), ga(:), pa(:), ipiv_s(:)
        integer :: mb, na, m, q, k, l
        integer(int64) :: t0, t1, rate

        ok = .false.
        mb = sys%mb
        na = sys%na
        if (mb <= 0 .or. na == 0 .or. .not. allocated(sys%y0) .or. &
            .not. allocated(sys%c_t)) return
        call system_clock(t0, rate)
        m = mb + na
        ! The added unknowns in the order of their columns (positions mb + 1 .. mb + na).
        allocate (at(m))
        at(sys%position) = [(k, k = 1, size(sys%position))]
        ga = sys%unknown(at(mb + 1:))
        pa = sys%partner(at(mb + 1:))
        ca = sys%coef(at(mb + 1:))
        ! S0 = D - C Y0, factorized; D's diagonal joins the base's
        allocate (s0(na, na), ipiv_s(na))
        do q = 1, na
            s0(:, q) = a(ga, ga(q)) + ca * a(pa, ga(q))
        end do
        d_diag = [(s0(q, q), q = 1, na)]
        call dgemm('T', 'N', na, na, mb, -1.0_wp, sys%c_t, mb, sys%y0, mb, 1.0_wp, s0, na)
        call lu_factor(s0, ipiv_s, 'the bordered base', singular, &
                       ill_conditioned=ill_conditioned)
        if (allocated(singular) .or. allocated(ill_conditioned)) return
        allocate (lu(m, m))
        !$omp parallel do default(none) schedule(static) private(l) shared(lu, sys, mb)
        do l = 1, mb
            lu(1:mb, l) = sys%factors(:, l)
        end do
        !$omp end parallel do
        ! Y = U Y0
        lu(1:mb, mb + 1:) = sys%y0
        call dtrmm('L', 'U', 'N', 'N', mb, na, 1.0_wp, sys%factors, mb, lu(1, mb + 1), m)
        ! X = P_S^T (U^-T C^T)^T
        t = sys%c_t
        call dtrsm('L', 'U', 'T', 'N', mb, na, 1.0_wp, sys%factors, mb, t, mb)
        lu(mb + 1:, 1:mb) = transpose(t)
        call dlaswp(mb, lu(mb + 1, 1), m, 1, na, ipiv_s, 1)
        lu(mb + 1:, mb + 1:) = s0
        sys%base_diag = [sys%base_diag, d_diag]
        call move_alloc(lu, sys%factors)
        sys%ipiv = [sys%ipiv, mb + ipiv_s]
        sys%base_unknown = [sys%base_unknown, ga]
        sys%base_partner = [sys%base_partner, pa]
        sys%base_coef = [sys%base_coef, ca]
        sys%mb = m
        sys%unknown = sys%base_unknown
        sys%partner = sys%base_partner
        sys%coef = sys%base_coef
        sys%position = [(k, k = 1, m)]
        sys%nr = 0
        sys%na = 0
        call drop_update(sys)
        sys%bordered = .true.
        sys%counts%borderings = sys%counts%borderings + 1
        ok = .true.
        call system_clock(t1)
        sys%counts%seconds = sys%counts%seconds + &
            real(t1 - t0, wp) / real(max(rate, 1_int64), wp)
        sys%counts%flops = sys%counts%flops + 2.0_wp * real(mb, wp)**2 * real(na, wp) + &
            2.0_wp * real(na, wp)**2 * real(mb, wp) + 2.0_wp / 3.0_wp * real(na, wp)**3
    end subroutine extend_base

    !> What the last set_system did: action_factorized, action_updated, action_reused (or 0).
    pure integer function last_action(sys)
        !> The factors
        type(reduced_factors), intent(in) :: sys

        last_action = sys%action
    end function last_action

    !> Factorizations, updates and reuses so far, their time and flops (a copy carries them).
    pure type(factor_counts) function counts_of(sys)
        !> The factors
        type(reduced_factors), intent(in) :: sys

        counts_of = sys%counts
    end function counts_of

    !> The unknowns ([s; n] indices) whose columns J^-1 B0 the last update keeps, shape (na).
    pure function border_unknowns(sys) result(unknown)
        !> The factors
        type(reduced_factors), intent(in) :: sys
        integer, allocatable :: unknown(:)

        unknown = [integer ::]
        if (allocated(sys%y0_of)) unknown = sys%y0_of
    end function border_unknowns

    !> to = from, with to's storage of the LU factors reused when it has their shape: a
    !> growth run copies its base's factors for every trial, and a fresh matrix of that
    !> size costs its page faults on top of the copy. With same_lu, to holds a copy of
    !> from's LU factors already (neither was factorized anew since one was copied from the
    !> other): they are not copied again (O(m^2) bytes a trial of the work criterion
    !> saves), the rest is.
    subroutine copy_factors(to, from, same_lu)
        !> The copy
        type(reduced_factors), intent(inout) :: to
        !> The factors copied (left as they were)
        type(reduced_factors), intent(inout) :: from
        !> to's LU factors are a copy of from's (default no)
        logical, intent(in), optional :: same_lu
        real(wp), allocatable :: storage(:, :), lu(:, :)
        logical :: keep
        integer :: l

        call move_alloc(to%factors, storage)
        call move_alloc(from%factors, lu)
        to = from
        keep = .false.
        if (present(same_lu)) keep = same_lu
        if (keep) keep = allocated(lu) .and. allocated(storage)
        if (keep) keep = all(shape(storage) == shape(lu))
        if (keep) then
            call move_alloc(storage, to%factors)
        else if (allocated(lu)) then
            if (allocated(storage)) then
                if (any(shape(storage) /= shape(lu))) deallocate (storage)
            end if
            if (.not. allocated(storage)) allocate (storage, mold=lu)
            !$omp parallel do default(none) schedule(static) private(l) shared(storage, lu)
            do l = 1, size(lu, 2)
                storage(:, l) = lu(:, l)
            end do
            !$omp end parallel do
            call move_alloc(storage, to%factors)
        end if
        call move_alloc(lu, from%factors)
    end subroutine copy_factors

    !> Forget the factors and free their memory: the next set_system factorizes anew.
    subroutine forget_factors(sys)
        !> The factors
        type(reduced_factors), intent(inout) :: sys

        sys%mb = -1
        call drop_update(sys)
        if (allocated(sys%factors)) deallocate (sys%factors)
        if (allocated(sys%ipiv)) deallocate (sys%ipiv)
    end subroutine forget_factors

    !> Give the unknowns new numbers when the influence matrix is rebuilt with more
    !> elements (fracture growth): the [s; n] index of every unknown moves, its row and
    !> column keep their values, so the factors stay valid; the new elements' unknowns
    !> then enter as added unknowns (bordering).
    pure subroutine renumber_factors(sys, new_index)
        !> The factors
        type(reduced_factors), intent(inout) :: sys
        !> The new index of every old [s; n] index, shape (2 n_old)
        integer, intent(in) :: new_index(:)

        if (allocated(sys%unknown)) sys%unknown = new_index(sys%unknown)
        if (allocated(sys%partner)) sys%partner = new_index(sys%partner)
        if (allocated(sys%base_unknown)) sys%base_unknown = new_index(sys%base_unknown)
        if (allocated(sys%base_partner)) sys%base_partner = new_index(sys%base_partner)
        if (allocated(sys%y0_of)) sys%y0_of = new_index(sys%y0_of)
    end subroutine renumber_factors

    !> Free the arrays of the last low-rank update.
    subroutine drop_update(sys)
        type(reduced_factors), intent(inout) :: sys

        if (allocated(sys%changed_rows)) deallocate (sys%changed_rows)
        if (allocated(sys%y0_of)) deallocate (sys%y0_of, sys%y0)
        if (allocated(sys%z)) deallocate (sys%z)
        if (allocated(sys%delta_t)) deallocate (sys%delta_t, sys%capacitance, &
                                                sys%capacitance_ipiv)
        if (allocated(sys%w)) deallocate (sys%w)
        if (allocated(sys%c_t)) deallocate (sys%c_t, sys%c_t_coef, sys%schur, sys%schur_ipiv, &
                                            sys%schur_plain)
    end subroutine drop_update

    !> Whether the unknowns and coefficients are those of the current system (exactly:
    !> the same states give the same numbers).
    pure logical function same_system(sys, unknown, coef)
        type(reduced_factors), intent(in) :: sys
        integer, intent(in) :: unknown(:)
        real(wp), intent(in) :: coef(:)

        same_system = .false.
        if (.not. allocated(sys%unknown)) return
        if (size(sys%unknown) /= size(unknown)) return
        same_system = all(sys%unknown == unknown) .and. all(sys%coef == coef)
    end function same_system

    !> Factorize the current system anew; it becomes the base.
    subroutine refactor(sys, a, subject, error)
        !> The system: the current unknowns are set (set_system)
        type(reduced_factors), intent(inout) :: sys
        !> Influence matrix ordered [s; n], shape (2n, 2n) [stress / length]
        real(wp), intent(in) :: a(:, :)
        !> What the system is, for the message of a singular factorization
        character(len=*), intent(in) :: subject
        !> Allocated when the system is (numerically) singular
        type(error_type), allocatable, intent(out) :: error
        integer :: m, k, l, n
        integer(int64) :: t0, t1, rate

        call system_clock(t0, rate)
        m = size(sys%unknown)
        n = size(a, 1) / 2
        sys%mb = m
        sys%base_unknown = sys%unknown
        sys%base_partner = sys%partner
        sys%base_coef = sys%coef
        sys%position = [(k, k = 1, m)]
        sys%nr = 0
        sys%na = 0
        call drop_update(sys)
        sys%action = action_factorized
        sys%bordered = .false.
        sys%counts%factorizations = sys%counts%factorizations + 1
        if (allocated(sys%factors)) deallocate (sys%factors)
        allocate (sys%factors(m, m))
        !$omp parallel do default(none) schedule(static) private(k, l) shared(a, sys, m)
        do l = 1, m
            do k = 1, m
                sys%factors(k, l) = a(sys%unknown(k), sys%unknown(l)) + &
                    sys%coef(k) * a(sys%partner(k), sys%unknown(l))
            end do
        end do
        !$omp end parallel do
        sys%base_diag = [(sys%factors(k, k), k = 1, m)]
        if (allocated(sys%ipiv)) deallocate (sys%ipiv)
        allocate (sys%ipiv(m))
        call lu_factor(sys%factors, sys%ipiv, subject, error, &
                       element=modulo(sys%unknown - 1, n) + 1, shear=sys%unknown <= n)
        if (allocated(error)) sys%mb = -1
        call system_clock(t1)
        sys%counts%seconds = sys%counts%seconds + &
            real(t1 - t0, wp) / real(max(rate, 1_int64), wp)
        sys%counts%flops = sys%counts%flops + 2.0_wp / 3.0_wp * real(m, wp)**3
    end subroutine refactor

    !> The low-rank update of the base for the changed base rows and the added unknowns
    !> (positions in the current system); sys%action is action_updated unless I + Delta Z
    !> or the Schur complement is numerically singular. When the changed rows and their
    !> coefficients are those of the last update (the usual case between Newton iterations:
    !> only unknowns added), its Z, Delta and I + Delta Z serve as they are.
    subroutine update_base(sys, a, changed, added, current_at, base_at)
        type(reduced_factors), intent(inout) :: sys
        real(wp), intent(in) :: a(:, :)
        integer, intent(in) :: changed(:), added(:), current_at(:), base_at(:)
        real(wp), allocatable :: row_coef(:)
        integer :: nr, q, c
        logical :: same_rows, ok

        sys%action = 0
        nr = size(changed)
        sys%position = base_at(sys%unknown)
        do q = 1, size(added)
            sys%position(added(q)) = sys%mb + q
        end do
        ! The new coefficient of each changed base row (huge: its unknown was removed).
        allocate (row_coef(nr))
        do q = 1, nr
            c = current_at(sys%base_unknown(changed(q)))
            row_coef(q) = huge(1.0_wp)
            if (c > 0) row_coef(q) = sys%coef(c)
        end do
        ! Exact comparison: the same rows with the same coefficients give the same K.
        same_rows = allocated(sys%changed_rows)
        if (same_rows) same_rows = size(sys%changed_rows) == nr
        if (same_rows) same_rows = all(sys%changed_rows == changed) .and. &
            all(sys%changed_coef == row_coef)
        sys%nr = nr
        if (.not. same_rows) then
            call change_rows(sys, a, changed, row_coef, ok)
            if (.not. ok) return
        end if
        call border(sys, a, added, same_rows, ok)
        if (.not. ok) return
        sys%action = action_updated
        sys%counts%updates = sys%counts%updates + 1
    end subroutine update_base

    !> The changed base rows: Z = J^-1 E_R (the columns of rows changed in the last update
    !> kept: Z depends on the rows only), Delta^T (new rows - old rows, by columns of A),
    !> and the factors of I + Delta Z; ok is false when I + Delta Z is numerically singular.
    subroutine change_rows(sys, a, changed, row_coef, ok)
        type(reduced_factors), intent(inout) :: sys
        real(wp), intent(in) :: a(:, :)
        integer, intent(in) :: changed(:)
        real(wp), intent(in) :: row_coef(:)
        logical, intent(out) :: ok
        type(error_type), allocatable :: singular, ill_conditioned
        integer, allocatable :: kept_rows(:), fresh(:)
        real(wp), allocatable :: z(:, :), zf(:, :)
        real(wp) :: d, scale
        integer :: mb, nr, q, r, p, g, l, k, l0

        ok = .true.
        mb = sys%mb
        nr = size(changed)
        scale = maxval(abs(sys%base_diag))
        if (.not. scale > 0.0_wp) scale = 1.0_wp
        allocate (z(mb, nr), kept_rows(nr))
        kept_rows = 0
        if (allocated(sys%changed_rows)) then
            do q = 1, nr
                k = findloc(sys%changed_rows, changed(q), 1)
                kept_rows(q) = k
                if (k > 0) z(:, q) = sys%z(:, k)
            end do
        end if
        fresh = pack([(q, q = 1, nr)], kept_rows == 0)
        if (size(fresh) > 0) then
            allocate (zf(mb, size(fresh)))
            zf = 0.0_wp
            do q = 1, size(fresh)
                zf(changed(fresh(q)), q) = 1.0_wp
            end do
            call lu_solve(sys%factors, sys%ipiv, zf)
            z(:, fresh) = zf
        end if
        sys%changed_rows = changed
        sys%changed_coef = row_coef
        call move_alloc(z, sys%z)
        if (allocated(sys%delta_t)) deallocate (sys%delta_t, sys%capacitance, &
                                                sys%capacitance_ipiv)
        allocate (sys%delta_t(mb, nr), sys%capacitance(nr, nr), sys%capacitance_ipiv(nr))
        ! In blocks of base rows, as C^T in border.
        do l0 = 1, mb, gather_block
            do q = 1, nr
                r = changed(q)
                p = sys%base_partner(r)
                do l = l0, min(mb, l0 + gather_block - 1)
                    g = sys%base_unknown(l)
                    if (row_coef(q) < huge(1.0_wp)) then
                        sys%delta_t(l, q) = (row_coef(q) - sys%base_coef(r)) * a(p, g)
                    else
                        sys%delta_t(l, q) = -(a(sys%base_unknown(r), g) + &
                                              sys%base_coef(r) * a(p, g))
                    end if
                end do
            end do
        end do
        do q = 1, nr
            r = changed(q)
            if (row_coef(q) == huge(1.0_wp)) then
                d = sys%base_diag(r)
                if (d == 0.0_wp) d = scale
                ! The removed unknown's row becomes d e_r: its value is 0.
                sys%delta_t(r, q) = sys%delta_t(r, q) + d
            end if
        end do
        if (nr == 0) return
        sys%capacitance = 0.0_wp
        do q = 1, nr
            sys%capacitance(q, q) = 1.0_wp
        end do
        call dgemm('T', 'N', nr, nr, mb, 1.0_wp, sys%delta_t, mb, sys%z, mb, 1.0_wp, &
                   sys%capacitance, nr)
        call lu_factor(sys%capacitance, sys%capacitance_ipiv, 'the update', singular, &
                       ill_conditioned=ill_conditioned)
        ok = .not. (allocated(singular) .or. allocated(ill_conditioned))
        if (.not. ok) deallocate (sys%changed_rows)
    end subroutine change_rows

    !> The added unknowns: W = K^-1 B (B their columns on the current base rows, 0 in
    !> removed rows), C^T and D (their rows, by columns of A) and the factors of the Schur
    !> complement S = D - C W; ok is false when S is numerically singular.
    !> W is not solved through K: with Y0 = J^-1 B0 (B0 the columns on the base rows with
    !> the base coefficients, kept for as long as the unknown stays added) and dB = B - B0
    !> (non-zero on the changed rows only), W = Y0 + Z (I + Delta Z)^-1 (dB - Delta Y0),
    !> O(mb nr na) when the changed rows change instead of O(mb^2 na).
    subroutine border(sys, a, added, same_rows, ok)
        type(reduced_factors), intent(inout) :: sys
        real(wp), intent(in) :: a(:, :)
        integer, intent(in) :: added(:)
        !> The changed rows are the last update's: W keeps the columns it had
        logical, intent(in) :: same_rows
        logical, intent(out) :: ok
        type(error_type), allocatable :: singular, ill_conditioned
        integer, allocatable :: ga(:), pa(:), fresh(:), column_of(:)
        real(wp), allocatable :: ca(:), y0(:, :), yf(:, :), t(:, :), c_t_before(:, :), &
            coef_before(:), s_before(:, :)
        integer, allocatable :: of_before(:), new(:), old(:)
        integer :: mb, nr, na, q, r, p, g, l, l0, k

        ok = .true.
        mb = sys%mb
        nr = sys%nr
        na = size(added)
        ! W is formed anew: free it before the new Y0 is. C^T keeps the columns of the
        ! unknowns added before with the same coefficients (their rows of A on the base).
        if (allocated(sys%w)) deallocate (sys%w)
        if (allocated(sys%c_t)) then
            call move_alloc(sys%c_t, c_t_before)
            call move_alloc(sys%c_t_coef, coef_before)
            call move_alloc(sys%schur_plain, s_before)
            deallocate (sys%schur, sys%schur_ipiv)
        end if
        if (allocated(sys%y0_of)) of_before = sys%y0_of
        ga = sys%unknown(added)
        pa = sys%partner(added)
        ca = sys%coef(added)
        allocate (y0(mb, na), column_of(na))
        column_of = 0
        if (allocated(sys%y0_of)) then
            do q = 1, na
                column_of(q) = findloc(sys%y0_of, ga(q), 1)
                if (column_of(q) > 0) y0(:, q) = sys%y0(:, column_of(q))
            end do
        end if
        fresh = pack([(q, q = 1, na)], column_of == 0)
        if (size(fresh) > 0) then
            allocate (yf(mb, size(fresh)))
            do q = 1, size(fresh)
                g = ga(fresh(q))
                yf(:, q) = a(sys%base_unknown, g) + sys%base_coef * a(sys%base_partner, g)
            end do
            call lu_solve(sys%factors, sys%ipiv, yf)
            y0(:, fresh) = yf
        end if
        call move_alloc(y0, sys%y0)
        sys%y0_of = ga
        sys%w = sys%y0
        if (nr > 0 .and. na > 0) then
            allocate (t(nr, na))
            do q = 1, nr
                r = sys%changed_rows(q)
                p = sys%base_partner(r)
                if (sys%changed_coef(q) < huge(1.0_wp)) then
                    t(q, :) = (sys%changed_coef(q) - sys%base_coef(r)) * a(p, ga)
                else
                    t(q, :) = -(a(sys%base_unknown(r), ga) + sys%base_coef(r) * a(p, ga))
                end if
            end do
            call dgemm('T', 'N', nr, na, mb, -1.0_wp, sys%delta_t, mb, sys%y0, mb, 1.0_wp, &
                       t, nr)
            call lu_solve(sys%capacitance, sys%capacitance_ipiv, t)
            call dgemm('N', 'N', mb, na, nr, 1.0_wp, sys%z, mb, t, nr, 1.0_wp, sys%w, mb)
        end if
        sys%na = na
        allocate (sys%c_t(mb, na), sys%schur(na, na), sys%schur_ipiv(na))
        sys%c_t_coef = ca
        column_of = 0
        if (allocated(c_t_before) .and. allocated(of_before)) then
            do q = 1, na
                k = findloc(of_before, ga(q), 1)
                if (k > 0) then
                    if (coef_before(k) == ca(q)) column_of(q) = k
                end if
                if (column_of(q) > 0) sys%c_t(:, q) = c_t_before(:, column_of(q))
            end do
        end if
        fresh = pack([(q, q = 1, na)], column_of == 0)
        ! In blocks of base rows: C^T is written by columns while the block's columns of A
        ! stay in cache (row by row, each row of C^T would touch na cache lines).
        do l0 = 1, mb, gather_block
            do k = 1, size(fresh)
                q = fresh(k)
                do l = l0, min(mb, l0 + gather_block - 1)
                    g = sys%base_unknown(l)
                    sys%c_t(l, q) = a(ga(q), g) + ca(q) * a(pa(q), g)
                end do
            end do
        end do
        do q = 1, na
            sys%schur(:, q) = a(ga, ga(q)) + ca * a(pa, ga(q))
        end do
        if (na == 0) then
            allocate (sys%schur_plain(0, 0))
            return
        end if
        ! S = D - C W. With the same changed rows W keeps its columns: the entries of two
        ! unknowns added before (with their coefficients) are the last S's, and only the
        ! rows and columns of the others are formed, O(na nn mb) instead of O(na^2 mb).
        if (.not. (same_rows .and. allocated(s_before))) column_of = 0
        new = pack([(q, q = 1, na)], column_of == 0)
        old = pack([(q, q = 1, na)], column_of > 0)
        if (size(old) > 0) then
            sys%schur(old, old) = s_before(column_of(old), column_of(old))
            call subtract_products(sys%c_t(:, new), sys%w(:, old), new, old)
        end if
        call subtract_products(sys%c_t, sys%w(:, new), [(q, q = 1, na)], new)
        sys%schur_plain = sys%schur
        call lu_factor(sys%schur, sys%schur_ipiv, 'the update', singular, &
                       ill_conditioned=ill_conditioned)
        ok = .not. (allocated(singular) .or. allocated(ill_conditioned))

    contains

        !> S(rows, columns) = S(rows, columns) - c^T w (c the columns of C^T of the rows, w
        !> the columns of W).
        subroutine subtract_products(c, w, rows, columns)
            real(wp), intent(in) :: c(:, :), w(:, :)
            integer, intent(in) :: rows(:), columns(:)
            real(wp) :: block(size(rows), size(columns))

            if (size(rows) == 0 .or. size(columns) == 0) return
            block = sys%schur(rows, columns)
            call dgemm('T', 'N', size(rows), size(columns), mb, -1.0_wp, c, mb, w, mb, &
                       1.0_wp, block, size(rows))
            sys%schur(rows, columns) = block
        end subroutine subtract_products
    end subroutine border

    !> Y = K^-1 Y: the base factors corrected for the changed rows (Woodbury).
    subroutine solve_k(sys, y)
        type(reduced_factors), intent(in) :: sys
        real(wp), intent(inout) :: y(:, :)
        real(wp), allocatable :: t(:, :)
        integer :: k

        k = size(y, 2)
        if (sys%mb > 0) call lu_solve(sys%factors, sys%ipiv, y)
        if (sys%nr == 0 .or. k == 0) return
        allocate (t(sys%nr, k))
        call dgemm('T', 'N', sys%nr, k, sys%mb, 1.0_wp, sys%delta_t, sys%mb, y, sys%mb, &
                   0.0_wp, t, sys%nr)
        call lu_solve(sys%capacitance, sys%capacitance_ipiv, t)
        call dgemm('N', 'N', sys%mb, k, sys%nr, -1.0_wp, sys%z, sys%mb, t, sys%nr, 1.0_wp, y, &
                   sys%mb)
    end subroutine solve_k

    !> Solve the current system: rhs (current order) in, solution out.
    subroutine solve_system(sys, rhs)
        !> The system (set_system done)
        type(reduced_factors), intent(in) :: sys
        !> Right-hand side on entry, solution on exit, shape (m)
        real(wp), intent(inout) :: rhs(:)
        real(wp), allocatable :: x(:), xb(:, :), xa(:, :)
        integer :: mb

        mb = sys%mb
        if (size(rhs) == 0) return
        allocate (x(mb + sys%na))
        x = 0.0_wp
        x(sys%position) = rhs
        xb = reshape(x(1:mb), [mb, 1])
        call solve_k(sys, xb)
        if (sys%na > 0) then
            xa = reshape(x(mb + 1:), [sys%na, 1])
            call dgemm('T', 'N', sys%na, 1, mb, -1.0_wp, sys%c_t, mb, xb, mb, 1.0_wp, xa, &
                       sys%na)
            call lu_solve(sys%schur, sys%schur_ipiv, xa)
            call dgemm('N', 'N', mb, 1, sys%na, -1.0_wp, sys%w, mb, xa, sys%na, 1.0_wp, xb, mb)
            x(mb + 1:) = xa(:, 1)
        end if
        x(1:mb) = xb(:, 1)
        rhs = x(sys%position)
    end subroutine solve_system

end module ddc_contact_reduced_factors
