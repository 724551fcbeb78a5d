!> Models with contact elements: TWODD-style elements are eliminated (static condensation)
!> so that the LCP covers the contact elements only
!> (docs/theory/contact.md#models-that-mix-contact-and-other-conditions).
!>
!> With the system K x = b split into free unknowns F (elements with TWODD conditions, rows
!> as their conditions say) and contact unknowns C (traction rows t_C = S_r,C + K_CC x_C +
!> K_CF x_F):  x_F = K_FF^-1 (b_F - K_FC x_C), so the contact elements see
!> A = K_CC - K_CF K_FF^-1 K_FC and the remote traction S_r,C + K_CF K_FF^-1 b_F.
!>
!> The condensation depends on the geometry only (condense_contact, once); the remote
!> traction on the contact elements and the free DDs depend on the load (contact_load and
!> complete_dds, once per load): a loading history condenses once.
!>
!> The fault law of the contact elements (fault_law_of) is read from the model's
!> per-element arrays here, for every solve of the solve layer (this one, a loading
!> history, growth and the MPI build).
module ddc_solve_frictional
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, set_internal_error, exit_solver_failure
    use ddc_model_types, only: element_set, condition_contact, strength_law_count
    use ddc_model_laws, only: strength_law, strength_laws, law_values
    use ddc_model_results, only: solver_record, state_free
    use ddc_influence_assembly, only: assemble_influence
    use ddc_solve_elastic, only: row_kinds, given_values
    use ddc_linalg_lapack, only: dgemm
    use ddc_linalg_lu, only: lu_factor, lu_solve, influence_hint, residual_tol
    use ddc_text, only: rtoa, itoa, seconds_text
    use ddc_progress, only: report_progress, reports_phases
    use ddc_allocation, only: allocation_failed, real_bytes
    use ddc_contact_result, only: contact_result
    use ddc_contact_formulation, only: solve_contact, solve_contact_with
    use ddc_contact_options, only: solver_options, cohesion_lost, matrix_hierarchical
    use ddc_solve_hierarchical_stiffness, only: hierarchical_stiffness, &
        new_hierarchical_stiffness
    use ddc_solve_hierarchical, only: report_assembly
    use ddc_contact_fault_law, only: fault_law, new_fault_law
    use ddc_solve_joints, only: joint_system, joint_load, joint_dds
    implicit none
    private

    public :: solve_frictional
    public :: condensed_contact, condense_contact, contact_load, complete_dds, record_contact
    public :: release_matrix, fault_law_of, strengths_change, contact_only_system

    !> The contact elements' view of a model with TWODD-style elements condensed out.
    type :: condensed_contact
        !> Number of contact and of free (TWODD-style) elements
        integer :: nc = 0, nf = 0
        !> Indices of the contact and of the free elements in the model, shape (nc), (nf)
        integer, allocatable :: contact(:), free(:)
        !> Row kinds of every element (ddc_solve_elastic), shape (n)
        integer, allocatable :: shear_row(:), normal_row(:)
        !> Influence matrix of the contact elements with the free ones condensed out,
        !> ordered [s; n], shape (2 nc, 2 nc) [stress / length]
        real(wp), allocatable :: a(:, :)
        !> The whole system (kept only when nf > 0), shape (2n, 2n)
        real(wp), allocatable :: matrix(:, :)
        !> LU factors of K_FF and their pivots, shape (2 nf, 2 nf), (2 nf)
        real(wp), allocatable :: kff(:, :)
        integer, allocatable :: ipiv(:)
        !> K_FF^-1 K_FC, shape (2 nf, 2 nc)
        real(wp), allocatable :: y(:, :)
        !> Nominal flops of the condensation [-]
        real(wp) :: flops = 0.0_wp
    end type condensed_contact

contains

    !> Solve a model with at least one contact element.
    subroutine solve_frictional(elements, shear_modulus, nu, remote_shear, remote_normal, &
                                options, ds, dn, state, record, matrix, error, law, &
                                ds_previous, law_start)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> Remote stress resolved on each element [stress unit], shape (n)
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        !> LCP method and cohesion of open elements (docs/theory/contact.md#choosing-the-method)
        type(solver_options), intent(in) :: options
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(out) :: ds(:), dn(:)
        !> Element states (state_free for TWODD-style elements), shape (n)
        integer, intent(out) :: state(:)
        !> Method, pivots, certificate, residual and timings are filled in
        type(solver_record), intent(inout) :: record
        !> The influence matrix of every element, rows as row_kinds (unfactored), shape
        !> (2n, 2n)
        real(wp), allocatable, intent(out) :: matrix(:, :)
        !> Set when the model has no solution or the solver failed
        type(error_type), allocatable, intent(out) :: error
        !> The fault law of every element with the values in force at the end (0 for
        !> TWODD-style elements)
        type(fault_law), intent(out), optional :: law
        !> Total slip of every element before this solve (friction memory of a growth run
        !> under a loading history; default 0), shape (n) [length]
        real(wp), intent(in), optional :: ds_previous(:)
        !> The fault law of every element with the values in force and slip path before this
        !> solve (a growth run under a loading history; default: the given values, no slip)
        type(fault_law), intent(in), optional :: law_start
        type(condensed_contact) :: sys
        type(contact_result) :: res
        type(fault_law) :: contact_law
        real(wp), allocatable :: shift(:), y_load(:), compliance(:), a_joint(:, :), &
            load_map(:, :), ss(:), sn(:), held(:)

        if (options%matrix == matrix_hierarchical) then
            call solve_on_hierarchical(elements, shear_modulus, nu, remote_shear, &
                                       remote_normal, options, ds, dn, state, record, error, &
                                       law, ds_previous, law_start)
            return
        end if
        call condense_contact(elements, shear_modulus, nu, sys, record, error)
        if (allocated(error)) return
        allocate (shift(2 * sys%nc), y_load(2 * sys%nf))
        call contact_load(sys, elements, remote_shear, remote_normal, shift, y_load)
        contact_law = fault_law_of(elements, sys%contact)
        if (present(law_start)) call contact_law%take_in_force(law_start, sys%contact)
        compliance = contact_law%joint_compliance()
        ss = shift(1:sys%nc)
        sn = shift(sys%nc + 1:)
        if (any(compliance > 0.0_wp)) then
            ! Elastic joints: the contact problem of the plastic DDs (ddc_solve_joints).
            call joint_system(sys%a, compliance, a_joint, load_map, error)
            if (allocated(error)) return
            call joint_load(load_map, elements%pressure(sys%contact), ss, sn)
            deallocate (load_map)
        else
            call move_alloc(sys%a, a_joint)
        end if
        allocate (held(sys%nc), source=0.0_wp)
        if (present(ds_previous)) held = ds_previous(sys%contact)
        call solve_contact(a_joint, ss, sn, contact_law, elements%pressure(sys%contact), &
                           options, res, error, ds_previous=held)
        if (.not. allocated(sys%a)) call move_alloc(a_joint, sys%a)
        if (allocated(error)) then
            if (sys%nf > 0) error%message = error%message// &
                ' (element numbers count the contact elements only)'
            return
        end if
        if (any(compliance > 0.0_wp)) call joint_dds(compliance, &
            elements%pressure(sys%contact), res%shear_traction, res%normal_traction, &
            res%ds, res%dn)
        call record_contact(res, sys%flops, record)
        call complete_dds(sys, elements, remote_shear, remote_normal, res, y_load, ds, dn, &
                          state, record%equilibrium_residual)
        call release_matrix(sys, matrix)
        if (present(law)) then
            law = fault_law_of(elements)
            call law%place_in_force(contact_law, sys%contact)
        end if
    end subroutine solve_frictional

    !> solve_frictional on a hierarchical matrix (docs/theory/hierarchical.md): every
    !> element a contact element, no elastic joints (the input's rules), the Newton method
    !> on ddc_solve_hierarchical_stiffness; no dense matrix is handed back.
    subroutine solve_on_hierarchical(elements, shear_modulus, nu, remote_shear, remote_normal, &
                                     options, ds, dn, state, record, error, law, &
                                     ds_previous, law_start)
        type(element_set), intent(in) :: elements
        real(wp), intent(in) :: shear_modulus, nu
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        type(solver_options), intent(in) :: options
        real(wp), intent(out) :: ds(:), dn(:)
        integer, intent(out) :: state(:)
        type(solver_record), intent(inout) :: record
        type(error_type), allocatable, intent(out) :: error
        type(fault_law), intent(out), optional :: law
        real(wp), intent(in), optional :: ds_previous(:)
        type(fault_law), intent(in), optional :: law_start
        ! The operator points at the elements: a copy that lives as long as it does
        type(element_set), target :: kept
        type(hierarchical_stiffness) :: stiffness
        type(contact_result) :: res
        type(fault_law) :: contact_law
        real(wp), allocatable :: held(:)
        integer :: n, i
        integer(int64) :: t0, t1, rate

        n = elements%n
        if (any(elements%condition /= condition_contact)) then
            call set_internal_error(error, 'solve_on_hierarchical', &
                                    'called with elements that are not contact elements')
            return
        end if
        call system_clock(t0, rate)
        kept = elements
        call new_hierarchical_stiffness(kept, shear_modulus, nu, options, stiffness, error)
        call system_clock(t1)
        record%seconds_assembly = real(t1 - t0, wp) / real(rate, wp)
        record%counts%seconds = 0.0_wp
        if (.not. allocated(error)) then
            record%hierarchical = .true.
            record%compression_ratio = stiffness%a%stored_fraction()
            record%hmatrix_tolerance = options%hmatrix_tolerance
            call report_assembly(n, record%seconds_assembly, record%compression_ratio)
            contact_law = fault_law_of(elements)
            if (present(law_start)) call contact_law%take_in_force(law_start, [(i, i = 1, n)])
            allocate (held(n), source=0.0_wp)
            if (present(ds_previous)) held = ds_previous
            call solve_contact_with(stiffness, remote_shear, remote_normal, contact_law, &
                                    elements%pressure, options, res, error, ds_previous=held)
        end if
        call stiffness%release()
        if (allocated(error)) return
        call record_contact(res, 0.0_wp, record)
        ds = res%ds
        dn = res%dn
        state = res%state
        if (present(law)) law = contact_law
    end subroutine solve_on_hierarchical

    !> The fault law of the elements `subset` (default: every element), from the model's
    !> per-element arrays: mu, sf and each strength law of the list (ddc_model_laws).
    pure function fault_law_of(elements, subset) result(law)
        !> The model's elements
        type(element_set), intent(in) :: elements
        !> Indices of the elements, shape (m)
        integer, intent(in), optional :: subset(:)
        type(fault_law) :: law
        type(strength_law) :: laws(strength_law_count)
        real(wp), allocatable :: given(:, :)
        integer, allocatable :: pick(:)
        integer :: i, k

        if (present(subset)) then
            pick = subset
        else
            pick = [(i, i = 1, elements%n)]
        end if
        laws = strength_laws()
        given = law_values(elements)
        law = new_fault_law(elements%mu(pick), elements%sf(pick))
        do k = 1, size(laws)
            call law%set_given(laws(k)%name, given(pick, k))
        end do
    end function fault_law_of

    !> Whether a strength in force can change in a solve of the model: its law goes beyond
    !> Coulomb's, or open elements lose their cohesion (open_cohesion = 'lost'). A loading
    !> history records the strengths of each step only then.
    pure logical function strengths_change(elements, options)
        !> The model's elements
        type(element_set), intent(in) :: elements
        !> Its solver options
        type(solver_options), intent(in) :: options
        type(fault_law) :: law

        law = fault_law_of(elements)
        strengths_change = law%beyond_coulomb() .or. options%open_cohesion == cohesion_lost
    end function strengths_change

    !> Hand over the influence matrix of every element (no copy): the contact block itself
    !> when every element is a contact element, else the whole system.
    subroutine release_matrix(sys, matrix)
        !> The condensed system; its matrix is moved out
        type(condensed_contact), intent(inout) :: sys
        !> The influence matrix of every element, shape (2n, 2n)
        real(wp), allocatable, intent(out) :: matrix(:, :)

        if (sys%nf == 0) then
            call move_alloc(sys%a, matrix)
        else
            call move_alloc(sys%matrix, matrix)
        end if
    end subroutine release_matrix

    !> Assemble the influence matrix and condense the TWODD-style elements out (timed into
    !> record: assembly and factorization).
    subroutine condense_contact(elements, shear_modulus, nu, sys, record, error)
        !> Elements with geometry computed, at least one contact element
        type(element_set), intent(in) :: elements
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> The condensed system
        type(condensed_contact), intent(out) :: sys
        !> seconds_assembly and counts%seconds (factorization) are set
        type(solver_record), intent(inout) :: record
        !> Set when K_FF is singular (exit_solver_failure) or the matrices do not fit in
        !> memory (exit_out_of_memory)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: matrix(:, :), kcf(:, :)
        integer, allocatable :: cu(:), fu(:)
        type(error_type), allocatable :: ill_conditioned
        real(wp) :: residual
        integer :: n, nc, nf, i, stat
        character(len=*), parameter :: among_free = &
            ' (among the elements with TWODD-style conditions)'
        integer(int64) :: t0, t1, t2, rate

        n = elements%n
        call system_clock(t0, rate)
        sys%contact = pack([(i, i = 1, n)], elements%condition == condition_contact)
        sys%free = pack([(i, i = 1, n)], elements%condition /= condition_contact)
        nc = size(sys%contact)
        nf = size(sys%free)
        sys%nc = nc
        sys%nf = nf
        ! Unknown indices in the full system, ordered [s; n] within each set.
        cu = [sys%contact, n + sys%contact]
        fu = [sys%free, n + sys%free]

        allocate (sys%shear_row(n), sys%normal_row(n))
        allocate (matrix(2 * n, 2 * n), stat=stat)
        if (stat /= 0) then
            call allocation_failed(error, 'the influence matrix of '//itoa(n)//' elements', &
                                   real_bytes * (2.0_wp * real(n, wp))**2)
            return
        end if
        call row_kinds(elements%condition, sys%shear_row, sys%normal_row)
        call assemble_influence(elements, shear_modulus, nu, sys%shear_row, sys%normal_row, &
                                matrix)
        call system_clock(t1)
        record%seconds_assembly = real(t1 - t0, wp) / real(rate, wp)
        if (reports_phases(n)) call report_progress('assembly done in '// &
            seconds_text(record%seconds_assembly)//' ('//itoa(2 * n)//' x '//itoa(2 * n)// &
            ' influence matrix)')

        if (nf == 0) then
            ! Every element is a contact element: A is the whole matrix (no copy).
            call move_alloc(matrix, sys%a)
        else
            ! A of the contact elements, K_FF, y = K_FF^-1 K_FC and K_CF, copied out
            allocate (sys%ipiv(2 * nf))
            allocate (sys%a(2 * nc, 2 * nc), stat=stat)
            if (stat == 0) allocate (sys%kff(2 * nf, 2 * nf), stat=stat)
            if (stat == 0) allocate (sys%y(2 * nf, 2 * nc), stat=stat)
            if (stat == 0) allocate (kcf(2 * nc, 2 * nf), stat=stat)
            if (stat /= 0) then
                call allocation_failed(error, 'the condensation of '//itoa(nf)// &
                    ' elements with TWODD-style conditions out of '//itoa(n), real_bytes * &
                    4.0_wp * (real(nc, wp) + real(nf, wp))**2)
                return
            end if
            sys%a(:, :) = matrix(cu, cu)
            sys%kff(:, :) = matrix(fu, fu)
            sys%y(:, :) = matrix(fu, cu)
            kcf(:, :) = matrix(cu, fu)
            call lu_factor(sys%kff, sys%ipiv, 'influence matrix', error, &
                           element=[sys%free, sys%free], ill_conditioned=ill_conditioned)
            if (allocated(error)) then
                error%message = error%message//influence_hint//among_free
                return
            end if
            call lu_solve(sys%kff, sys%ipiv, sys%y)
            ! A hole (closed contour) is numerically singular but consistent: K_FF y = K_FC.
            if (allocated(ill_conditioned)) then
                residual = norm2(matmul(matrix(fu, fu), sys%y) - matrix(fu, cu)) / &
                    max(norm2(matrix(fu, cu)), tiny(1.0_wp))
                if (.not. residual <= residual_tol) then
                    call set_error(error, exit_solver_failure, ill_conditioned%message// &
                                   influence_hint//among_free//' (relative residual '// &
                                   rtoa(residual)//')')
                    return
                end if
            end if
            call dgemm('N', 'N', 2 * nc, 2 * nc, 2 * nf, -1.0_wp, kcf, 2 * nc, &
                       sys%y, 2 * nf, 1.0_wp, sys%a, 2 * nc)
            deallocate (kcf)
            call move_alloc(matrix, sys%matrix)
        end if
        ! LU of K_FF, its solve for 2 nc + 1 right-hand sides and the product.
        sys%flops = 2.0_wp / 3.0_wp * real(2 * nf, wp)**3 + 2.0_wp * real(2 * nf, wp)**2 * &
            real(2 * nc + 1, wp) + 2.0_wp * real(2 * nc, wp)**2 * real(2 * nf, wp)
        call system_clock(t2)
        record%counts%seconds = real(t2 - t1, wp) / real(rate, wp)
        if (reports_phases(n) .and. nf > 0) call report_progress('condensation of '// &
            itoa(nf)//' elements done in '//seconds_text(record%counts%seconds))
    end subroutine condense_contact

    !> The condensed system of a model whose elements are all contact elements, without its
    !> matrix (a hierarchical operator holds A: ddc_solve_hierarchical_stiffness).
    pure subroutine contact_only_system(elements, sys)
        type(element_set), intent(in) :: elements
        type(condensed_contact), intent(out) :: sys
        integer :: i

        sys%nc = elements%n
        sys%nf = 0
        sys%contact = [(i, i = 1, elements%n)]
        allocate (sys%free(0), sys%shear_row(elements%n), sys%normal_row(elements%n))
        call row_kinds(elements%condition, sys%shear_row, sys%normal_row)
    end subroutine contact_only_system

    !> Remote traction on the contact elements for one load, free elements condensed out:
    !> shift = [S_r,C shear; S_r,C normal] + K_CF K_FF^-1 b_F.
    subroutine contact_load(sys, elements, remote_shear, remote_normal, shift, y_load)
        !> The condensed system
        type(condensed_contact), intent(in) :: sys
        !> The model's elements (their given values b_F)
        type(element_set), intent(in) :: elements
        !> Remote stress resolved on each element [stress unit], shape (n)
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        !> Remote shear then normal traction on the contact elements, shape (2 nc) [stress]
        real(wp), intent(out) :: shift(:)
        !> K_FF^-1 b_F, shape (2 nf) (complete_dds needs it)
        real(wp), intent(out) :: y_load(:)
        real(wp), allocatable :: b(:, :)
        integer :: n

        n = elements%n
        shift = [remote_shear(sys%contact), remote_normal(sys%contact)]
        allocate (b(2 * sys%nf, 1))
        if (sys%nf > 0) then
            b(:, 1) = given_values(elements, sys%shear_row, sys%normal_row, remote_shear, &
                                   remote_normal, sys%free)
            call lu_solve(sys%kff, sys%ipiv, b)
            shift = shift + matmul(sys%matrix([sys%contact, n + sys%contact], &
                                              [sys%free, n + sys%free]), b(:, 1))
        end if
        y_load = b(:, 1)
    end subroutine contact_load

    !> DDs and states of every element from a contact solution: contact elements from res,
    !> free ones from x_F = K_FF^-1 b_F - K_FF^-1 K_FC x_C, checked against the unfactored
    !> free rows.
    subroutine complete_dds(sys, elements, remote_shear, remote_normal, res, y_load, ds, dn, &
                            state, residual)
        !> The condensed system
        type(condensed_contact), intent(in) :: sys
        !> The model's elements (their given values b_F)
        type(element_set), intent(in) :: elements
        !> Remote stress resolved on each element of the same load [stress unit], shape (n)
        real(wp), intent(in) :: remote_shear(:), remote_normal(:)
        !> The contact solution
        type(contact_result), intent(in) :: res
        !> K_FF^-1 b_F of the same load (contact_load), shape (2 nf)
        real(wp), intent(in) :: y_load(:)
        !> Displacement discontinuities [length unit], shape (n)
        real(wp), intent(out) :: ds(:), dn(:)
        !> Element states (state_free for TWODD-style elements), shape (n)
        integer, intent(out) :: state(:)
        !> Relative equilibrium residual: raised to that of the free rows when larger [-]
        real(wp), intent(inout) :: residual
        real(wp), allocatable :: x_contact(:), x_free(:), residual_free(:), b_free(:)
        integer, allocatable :: cu(:), fu(:)
        integer :: n

        n = size(ds)
        state = state_free
        state(sys%contact) = res%state
        ds(sys%contact) = res%ds
        dn(sys%contact) = res%dn
        if (sys%nf == 0) return
        cu = [sys%contact, n + sys%contact]
        fu = [sys%free, n + sys%free]
        x_contact = [res%ds, res%dn]
        x_free = y_load - matmul(sys%y, x_contact)
        ds(sys%free) = x_free(1:sys%nf)
        dn(sys%free) = x_free(sys%nf + 1:)
        ! The free rows against the unfactored system: K_FF x_F + K_FC x_C = b_F.
        b_free = given_values(elements, sys%shear_row, sys%normal_row, remote_shear, &
                              remote_normal, sys%free)
        residual_free = matmul(sys%matrix(fu, fu), x_free) + &
            matmul(sys%matrix(fu, cu), x_contact) - b_free
        residual = max(residual, norm2(residual_free) / max(norm2(b_free), tiny(1.0_wp)))
    end subroutine complete_dds

    !> Fill the solver record from a contact solution.
    subroutine record_contact(res, flops, record)
        !> The contact solution
        type(contact_result), intent(in) :: res
        !> Nominal flops of the factorizations outside the contact solve (the condensation)
        real(wp), intent(in) :: flops
        !> Method, pivots, counts, certificate, residual, flops and LCP time are set; the
        !> factorization time is added to
        type(solver_record), intent(inout) :: record
        real(wp) :: seconds

        record%method = res%method
        record%fallback = res%fallback
        record%newton_iterations = res%iterations
        seconds = record%counts%seconds
        record%counts = res%counts
        record%counts%flops = res%counts%flops + flops
        record%counts%seconds = seconds + res%counts%seconds
        record%pivots = res%pivots
        record%lcp_solves = res%solves
        record%certificate_min_z = res%certificate%min_z
        record%certificate_min_w = res%certificate%min_w
        record%certificate_max_complementarity = res%certificate%max_complementarity
        record%certificate_tolerance = res%certificate%tolerance
        record%seconds_lcp = res%seconds_lcp
        record%equilibrium_residual = maxval(res%equilibrium_residual)
    end subroutine record_contact
end module ddc_solve_frictional
