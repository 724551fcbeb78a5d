!> The contact elements' influence matrix A as a hierarchical matrix, for the active-set
!> Newton method (docs/theory/hierarchical.md#contact-on-the-compressed-operator): products
!> A D by the compressed A (kept unfactorized: the certificate and the method's checks use
!> it), and every reduced system J (rows unknown(k) + coef(k) partner(k), columns
!> unknown(l) of A: ddc_contact_stiffness) assembled as a hierarchical matrix of its own
!> from the kernel, H-LU factorized, and solved with refinement against the compressed
!> A, so that the tractions the method imposes hold for the operator that checks them. A
!> system of the same unknowns, partners and coefficients as the last reuses its factors;
!> hmat-oss offers no low-rank update, so any change factorizes anew.
module ddc_solve_hierarchical_stiffness
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_model_medium, only: elastic_medium
    use ddc_linalg_hmatrix, only: hmatrix, block_source, hmatrix_settings
    use ddc_contact_options, only: solver_options
    use ddc_contact_stiffness, only: stiffness_operator, reduced_system, action_solved, &
        action_factorized, action_reused
    use ddc_solve_hierarchical, only: influence_source, new_influence_source, unknown_points, &
        max_refinements, refined_residual, settings_of
    implicit none
    private

    public :: hierarchical_stiffness, new_hierarchical_stiffness

    !> Rows unknown(k) + coef(k) partner(k) and columns unknown(l) of A, from the kernel.
    type, extends(block_source) :: reduced_source
        type(influence_source), pointer :: full => null()
        integer, allocatable :: unknown(:), partner(:)
        real(wp), allocatable :: coef(:)
    contains
        procedure :: fill => fill_reduced
    end type reduced_source

    !> A of n contact elements, compressed, and the factors of its last reduced system.
    type, extends(stiffness_operator) :: hierarchical_stiffness
        type(influence_source), pointer :: source => null()
        type(hmatrix_settings) :: settings
        !> A, compressed (unfactorized)
        type(hmatrix), pointer :: a => null()
        !> H-LU factors of the last reduced system and what it was
        type(hmatrix), pointer :: factors => null()
        integer, allocatable :: unknown(:), partner(:)
        real(wp), allocatable :: coef(:)
        !> Largest |A_ii| (from the elements' own 2 x 2 blocks)
        real(wp) :: diagonal = 0.0_wp
        logical :: finite = .true.
    contains
        procedure :: max_diagonal => hierarchical_max_diagonal
        procedure :: max_entry => hierarchical_max_diagonal
        procedure :: all_finite => hierarchical_all_finite
        procedure :: multiply => hierarchical_multiply
        procedure :: solve_reduced => hierarchical_solve_reduced
        procedure :: discard_factors => hierarchical_discard_factors
        procedure :: release => hierarchical_release
    end type hierarchical_stiffness

contains

    !> The operator of the elements (all contact elements: traction rows), A assembled with
    !> the hmatrix_ settings of &solver.
    subroutine new_hierarchical_stiffness(medium, options, stiffness, error)
        type(elastic_medium), intent(in), target :: medium
        type(solver_options), intent(in) :: options
        type(hierarchical_stiffness), intent(out) :: stiffness
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: own(2, 2)
        integer :: i, n

        allocate (stiffness%source, stiffness%a, stiffness%factors)
        stiffness%source = new_influence_source(medium)
        stiffness%settings = settings_of(options)
        call stiffness%a%assemble(unknown_points(medium%elements), stiffness%source, &
                                  stiffness%settings, error)
        if (allocated(error)) return
        n = medium%elements%n
        do i = 1, n
            call stiffness%source%fill([i, n + i], [i, n + i], own)
            stiffness%diagonal = max(stiffness%diagonal, abs(own(1, 1)), abs(own(2, 2)))
            stiffness%finite = stiffness%finite .and. all(ieee_is_finite(own))
        end do
    end subroutine new_hierarchical_stiffness

    !> Largest |A_ii| (also the largest |A_ij| the method asks for: with constant elements
    !> an element's own influence is the largest in its row and column).
    function hierarchical_max_diagonal(this) result(value)
        class(hierarchical_stiffness), intent(in) :: this
        real(wp) :: value

        value = this%diagonal
    end function hierarchical_max_diagonal

    !> The elements' own blocks finite (every other entry comes from the same kernel).
    function hierarchical_all_finite(this) result(value)
        class(hierarchical_stiffness), intent(in) :: this
        logical :: value

        value = this%finite
    end function hierarchical_all_finite

    !> t = t + A dd by the compressed A.
    subroutine hierarchical_multiply(this, dd, t)
        class(hierarchical_stiffness), intent(in) :: this
        real(wp), intent(in) :: dd(:)
        real(wp), intent(inout) :: t(:)
        real(wp) :: product(size(t))
        type(error_type), allocatable :: error

        call this%a%multiply(dd, product, error)
        ! hmat-oss fails a product only on a broken matrix: poison the result, which the
        ! method's checks then refuse.
        if (allocated(error)) product = huge(1.0_wp)
        t = t + product
    end subroutine hierarchical_multiply

    !> Solve J x = rhs: the kept factors when the system is the last one, else J
    !> assembled and H-LU factorized; refined against the compressed A.
    subroutine hierarchical_solve_reduced(this, system, x, subject, singular, seconds, flops)
        class(hierarchical_stiffness), intent(inout) :: this
        type(reduced_system), intent(in) :: system
        real(wp), intent(out) :: x(:)
        character(len=*), intent(in) :: subject
        type(error_type), allocatable, intent(out) :: singular
        !> Wall time of the assembly and factorization is added; flops are not counted
        !> (hmat-oss gives none)
        real(wp), intent(inout) :: seconds, flops
        type(reduced_source), target :: source
        real(wp), allocatable :: rhs(:, :), points(:, :), full(:), t(:)
        integer :: m, step
        integer(int64) :: t0, t1, rate

        this%action = action_solved
        m = size(system%unknown)
        if (m == 0) return
        if (.not. same_system(this, system)) then
            call system_clock(t0, rate)
            source%full => this%source
            source%unknown = system%unknown
            source%partner = system%partner
            source%coef = system%coef
            points = unknown_points(this%source%medium%elements)
            points = points(:, system%unknown)
            call this%factors%assemble(points, source, this%settings, singular)
            if (.not. allocated(singular)) call this%factors%factor(singular)
            if (allocated(singular)) then
                singular%message = subject//': '//singular%message
                call this%factors%release()
                if (allocated(this%unknown)) deallocate (this%unknown)
                return
            end if
            this%unknown = system%unknown
            this%partner = system%partner
            this%coef = system%coef
            call system_clock(t1)
            seconds = seconds + real(t1 - t0, wp) / real(rate, wp)
            this%counts%factorizations = this%counts%factorizations + 1
            this%counts%seconds = this%counts%seconds + real(t1 - t0, wp) / real(rate, wp)
            this%action = action_factorized
            ! hmat-oss counts no flops: the record's flops leave H-LU out.
            flops = flops + 0.0_wp
        else
            this%counts%reuses = this%counts%reuses + 1
            this%action = action_reused
        end if
        allocate (rhs(m, 1), full(2 * this%source%medium%elements%n), &
                  t(2 * this%source%medium%elements%n))
        rhs(:, 1) = system%rhs
        call this%factors%solve(rhs, singular)
        if (allocated(singular)) return
        x = rhs(:, 1)
        ! Refinement: r = rhs - J x with J x from the compressed A, until r is at round-off
        ! of the right-hand side.
        do step = 1, max_refinements
            full = 0.0_wp
            full(system%unknown) = x
            t = 0.0_wp
            call this%multiply(full, t)
            rhs(:, 1) = system%rhs - (t(system%unknown) + system%coef * t(system%partner))
            if (norm2(rhs(:, 1)) <= refined_residual * norm2(system%rhs)) exit
            call this%factors%solve(rhs, singular)
            if (allocated(singular)) return
            x = x + rhs(:, 1)
        end do
    end subroutine hierarchical_solve_reduced

    !> The system is the one whose factors are kept.
    pure logical function same_system(this, system)
        class(hierarchical_stiffness), intent(in) :: this
        type(reduced_system), intent(in) :: system

        same_system = .false.
        if (.not. allocated(this%unknown)) return
        if (size(this%unknown) /= size(system%unknown)) return
        same_system = all(this%unknown == system%unknown) .and. &
                      all(this%partner == system%partner) .and. all(this%coef == system%coef)
    end function same_system

    !> Drop the kept factors.
    subroutine hierarchical_discard_factors(this)
        class(hierarchical_stiffness), intent(inout) :: this

        if (associated(this%factors)) call this%factors%release()
        if (allocated(this%unknown)) deallocate (this%unknown)
        this%action = action_solved
    end subroutine hierarchical_discard_factors

    !> Free the compressed A, the kept factors and the source (their hmat-oss matrices by
    !> the hmatrix finalizer).
    subroutine hierarchical_release(this)
        class(hierarchical_stiffness), intent(inout) :: this

        if (associated(this%factors)) deallocate (this%factors)
        if (associated(this%a)) deallocate (this%a)
        if (associated(this%source)) deallocate (this%source)
    end subroutine hierarchical_release

    !> block(k, l) = J(rows(k), cols(l)).
    subroutine fill_reduced(source, rows, cols, block)
        class(reduced_source), intent(in) :: source
        integer, intent(in) :: rows(:), cols(:)
        real(wp), intent(out) :: block(:, :)
        real(wp) :: partner_rows(size(rows), size(cols))
        integer :: k

        call source%full%fill(source%unknown(rows), source%unknown(cols), block)
        call source%full%fill(source%partner(rows), source%unknown(cols), partner_rows)
        do k = 1, size(rows)
            block(k, :) = block(k, :) + source%coef(rows(k)) * partner_rows(k, :)
        end do
    end subroutine fill_reduced

end module ddc_solve_hierarchical_stiffness
