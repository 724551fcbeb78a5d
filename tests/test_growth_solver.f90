!> The solves of a growth run (ddc_growth_solver, ddc_growth_influence): the grown influence
!> matrix against a whole assembly (full plane and half-plane, a later trial replacing only
!> the new rows and columns), a solve through renumbered and bordered factors against a
!> fresh factorization, a growth run on the kept path against the final geometry solved from
!> scratch and against the same run with Lemke (solved from scratch at every solve), and
!> 1 and 2 threads.
module test_growth_solver
    use omp_lib, only: omp_set_num_threads, omp_get_max_threads
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_model_types, only: model_type, growth_options, condition_contact, &
        domain_half_plane
    use ddc_model_results, only: model_results
    use ddc_contact_options, only: lcp_newton, lcp_lemke
    use ddc_influence_assembly, only: assemble_influence, row_traction
    use ddc_linalg_lu, only: lu_factor, lu_solve
    use ddc_contact_reduced_factors, only: reduced_factors, set_system, solve_system, &
        renumber_factors, last_action, border_unknowns, action_updated
    use ddc_growth_extension, only: tip_path, make_path, extend_model, tip_end_begin, &
        tip_end_end
    use ddc_growth_influence, only: grow_influence, unknown_map, new_elements
    use ddc_growth_solver, only: keeps_solves
    use ddc_growth_driver, only: grow_fractures
    use ddc_run_model, only: run_model
    use ddc_test_builders, only: polyline_model
    implicit none
    private

    public :: collect_growth_solver

    real(wp), parameter :: e_modulus = 50000.0_wp, nu = 0.25_wp
    real(wp), parameter :: g_modulus = e_modulus / (2.0_wp * (1.0_wp + nu))

contains

    !> Cases of the growth_solver suite.
    subroutine collect_growth_solver(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('grown_influence_matches_assembly', test_grown_influence), &
                 new_test('grown_influence_half_plane', test_grown_influence_half_plane), &
                 new_test('bordered_solve_matches_fresh_lu', test_bordered_solve), &
                 new_test('kept_path_matches_final_solve', test_kept_against_final), &
                 new_test('kept_path_matches_lemke_growth', test_kept_against_lemke), &
                 new_test('kept_path_one_and_two_threads', test_kept_threads)]
    end subroutine collect_growth_solver

    ! ---- helpers ------------------------------------------------------------------------

    !> A frictional flaw at 45 degrees under compression (SPEC-GROWTH 4: it slides, its
    !> wings open), n elements, growing `steps` steps by the Newton method (the kept path).
    function sliding_flaw(n, steps) result(model)
        integer, intent(in) :: n, steps
        type(model_type) :: model
        real(wp), parameter :: c = 0.70710678118654752_wp

        model = polyline_model([-c, c], [-c, c], [n], condition_contact, 0.0_wp, 0.0_wp, &
                               e_modulus, nu)
        model%elements%mu = 0.6_wp
        model%elements%sf = 1.0_wp
        model%sxx = -2.0_wp
        model%syy = -100.0_wp
        model%solver%lcp_method = lcp_newton
        model%growth%active = .true.
        model%growth%steps = steps
        model%growth%toughness = 2.0_wp
        model%growth%override_sf = .true.
        model%growth%new_sf = 0.0_wp
        allocate (model%growth%fracture_grows(1))
        model%growth%fracture_grows = .true.
    end function sliding_flaw

    !> The model grown by three elements at each tip, at angles theta_b, theta_e [rad];
    !> where the old elements went.
    subroutine grow_both_tips(model, theta_b, theta_e, grown, moved_to)
        type(model_type), intent(in) :: model
        real(wp), intent(in) :: theta_b, theta_e
        type(model_type), intent(out) :: grown
        integer, allocatable, intent(out) :: moved_to(:)
        type(tip_path) :: paths(2)
        integer, allocatable :: created(:), grown_created(:)

        paths(1) = make_path(model, 1, tip_end_begin, theta_b, 0.1_wp, 3)
        paths(2) = make_path(model, 1, tip_end_end, theta_e, 0.1_wp, 3)
        allocate (created(model%elements%n), source=0)
        call extend_model(model, created, paths, 1, growth_options(), grown, grown_created, &
                          moved_to)
    end subroutine grow_both_tips

    !> The whole influence matrix of a model, traction rows.
    subroutine assemble_whole(model, a)
        type(model_type), intent(in) :: model
        real(wp), allocatable, intent(out) :: a(:, :)
        integer :: rows(model%elements%n)

        rows = row_traction
        allocate (a(2 * model%elements%n, 2 * model%elements%n))
        call assemble_influence(model%elements, g_modulus, nu, rows, rows, a)
    end subroutine assemble_whole

    !> Largest |a - b| over the largest |b|.
    pure real(wp) function relative_difference(a, b)
        real(wp), intent(in) :: a(:), b(:)

        relative_difference = maxval(abs(a - b)) / max(maxval(abs(b)), tiny(1.0_wp))
    end function relative_difference

    !> Grow a model twice (two trials of one step: the second replaces only the new rows
    !> and columns) and compare each grown matrix with the whole assembly.
    subroutine check_grown_influence(error, model)
        type(error_type), allocatable, intent(inout) :: error
        type(model_type), intent(in) :: model
        type(model_type) :: grown
        real(wp), allocatable :: old(:, :), a(:, :), whole(:, :)
        integer, allocatable :: moved_to(:)
        logical :: finite

        call assemble_whole(model, old)
        call grow_both_tips(model, 0.3_wp, -0.5_wp, grown, moved_to)
        call check(error, size(new_elements(moved_to, grown%elements%n)), 6, 'new elements')
        call check(error, moved_to(1), 4, 'the begin tip moves the old elements')
        allocate (a(2 * grown%elements%n, 2 * grown%elements%n), source=huge(1.0_wp))
        call grow_influence(old, moved_to, grown%elements, g_modulus, nu, .false., a, finite)
        call assemble_whole(grown, whole)
        call check(error, finite, 'finite')
        call check(error, relative_difference(reshape(a, [size(a)]), &
                   reshape(whole, [size(whole)])), 0.0_wp, 'first trial', abs_tol=1.0e-13_wp)
        ! The second trial at other angles: the old block stays where the first put it.
        call grow_both_tips(model, -0.4_wp, 0.2_wp, grown, moved_to)
        call grow_influence(old, moved_to, grown%elements, g_modulus, nu, .true., a, finite)
        call assemble_whole(grown, whole)
        call check(error, relative_difference(reshape(a, [size(a)]), &
                   reshape(whole, [size(whole)])), 0.0_wp, 'second trial, border replaced', &
                   abs_tol=1.0e-13_wp)
    end subroutine check_grown_influence

    ! ---- the grown influence matrix -----------------------------------------------------

    !> Full plane: the grown matrix equals the whole assembly (to 1e-13 of its largest
    !> entry; the same kernel evaluations, so in practice bit for bit).
    subroutine test_grown_influence(error)
        type(error_type), allocatable, intent(out) :: error

        call check_grown_influence(error, sliding_flaw(20, 1))
    end subroutine test_grown_influence

    !> Half-plane (the general kernel path): the same, for a buried flaw.
    subroutine test_grown_influence_half_plane(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model

        model = sliding_flaw(20, 1)
        model%elements%y_begin = model%elements%y_begin - 3.0_wp
        model%elements%y_end = model%elements%y_end - 3.0_wp
        model%elements%y_mid = model%elements%y_mid - 3.0_wp
        model%elements%domain = domain_half_plane
        call check_grown_influence(error, model)
    end subroutine test_grown_influence_half_plane

    ! ---- bordered factors ---------------------------------------------------------------

    !> Factors of a reduced system of the model before growing (every Ds, and a few Dn with
    !> friction rows) and an update of them, renumbered to the grown model and bordered by
    !> the new elements' unknowns: the solve agrees with a fresh LU of the grown system
    !> (1e-10 relative) and was an update, not a new factorization.
    subroutine test_bordered_solve(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, grown
        type(reduced_factors) :: factors
        type(error_type), allocatable :: singular
        real(wp), allocatable :: old(:, :), a(:, :), j(:, :), x(:), rhs(:, :), coef(:)
        integer, allocatable :: moved_to(:), unknown(:), partner(:), fresh(:), ipiv(:), kept(:)
        integer :: n0, n, k, l
        logical :: finite

        model = sliding_flaw(30, 1)
        n0 = model%elements%n
        call assemble_whole(model, old)
        ! Ds of every element (slip rows with friction), Dn of the last five (open).
        unknown = [[(k, k = 1, n0)], [(n0 + k, k = n0 - 4, n0)]]
        partner = [[(n0 + k, k = 1, n0)], [(n0 + k, k = n0 - 4, n0)]]
        coef = [spread(0.6_wp, 1, n0), spread(0.0_wp, 1, 5)]
        call set_system(factors, old, unknown, partner, coef, 'test', singular)
        call check(error, .not. allocated(singular), 'base factorized')
        if (allocated(error)) return
        ! An update before growing (Ds of element 2 turns, Dn of element n0 - 5 opens): what
        ! it keeps for the added Dn (J^-1 B0) has to follow the renumbering.
        coef(2) = -0.6_wp
        call set_system(factors, old, [unknown, 2 * n0 - 5], [partner, 2 * n0 - 5], &
                        [coef, 0.0_wp], 'test', singular)
        call check(error, last_action(factors), action_updated, 'an update before growing')
        if (allocated(error)) return

        call grow_both_tips(model, 0.3_wp, -0.5_wp, grown, moved_to)
        n = grown%elements%n
        allocate (a(2 * n, 2 * n))
        call grow_influence(old, moved_to, grown%elements, g_modulus, nu, .false., a, finite)
        call renumber_factors(factors, unknown_map(moved_to, n))
        call check(error, size(border_unknowns(factors)) == 1, 'J^-1 B0 kept for the added Dn')
        if (allocated(error)) return
        kept = border_unknowns(factors)
        call check(error, kept(1), n + moved_to(n0 - 5), 'kept J^-1 B0 renumbered')
        if (allocated(error)) return
        fresh = new_elements(moved_to, n)
        ! The grown system: the old unknowns at their new places, then Ds and Dn of the new
        ! elements (open: no friction).
        unknown = [moved_to, n + moved_to(n0 - 4:n0), n + moved_to(n0 - 5), fresh, n + fresh]
        partner = [n + moved_to, n + moved_to(n0 - 4:n0), n + moved_to(n0 - 5), n + fresh, &
                   n + fresh]
        coef = [spread(0.6_wp, 1, n0), spread(0.0_wp, 1, 6 + 2 * size(fresh))]
        coef(2) = -0.6_wp
        call set_system(factors, a, unknown, partner, coef, 'test', singular)
        call check(error, .not. allocated(singular), 'bordered')
        call check(error, last_action(factors), action_updated, 'an update, not a new LU')
        if (allocated(error)) return
        x = [(sin(real(k, wp)), k = 1, size(unknown))]
        rhs = reshape(x, [size(x), 1])
        call solve_system(factors, x)

        allocate (j(size(unknown), size(unknown)), ipiv(size(unknown)))
        do l = 1, size(unknown)
            do k = 1, size(unknown)
                j(k, l) = a(unknown(k), unknown(l)) + coef(k) * a(partner(k), unknown(l))
            end do
        end do
        call lu_factor(j, ipiv, 'test', singular)
        call check(error, .not. allocated(singular), 'fresh LU')
        if (allocated(error)) return
        call lu_solve(j, ipiv, rhs)
        call check(error, relative_difference(x, rhs(:, 1)), 0.0_wp, &
                   'bordered solve against a fresh LU', abs_tol=1.0e-10_wp)
    end subroutine test_bordered_solve

    ! ---- growth runs on the kept path ---------------------------------------------------

    !> Five steps of the wings on the kept path (the Newton method's factors bordered, not
    !> factorized anew at every solve): the final results equal those of run_model on the
    !> final geometry, solved from scratch (states equal, DDs and K within 1e-9 relative).
    subroutine test_kept_against_final(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(model_results) :: r, fresh
        integer :: solves

        model = sliding_flaw(40, 5)
        call check(error, keeps_solves(model), 'the Newton method keeps its solves')
        if (allocated(error)) return
        call grow_fractures(model, r, error)
        if (allocated(error)) return
        solves = 1 + sum(r%growth%corrections)
        call check(error, r%solver%counts%updates > 0, 'the factors are updated')
        call check(error, r%solver%counts%factorizations < solves, &
                   'fewer factorizations than solves')
        if (allocated(error)) return
        call run_model(model, fresh, error)
        if (allocated(error)) return
        call check(error, all(r%elements%state == fresh%elements%state), 'states')
        call check(error, relative_difference(r%elements%ds, fresh%elements%ds), 0.0_wp, 'ds', &
                   abs_tol=1.0e-9_wp)
        call check(error, relative_difference(r%elements%dn, fresh%elements%dn), 0.0_wp, 'dn', &
                   abs_tol=1.0e-9_wp)
        call check(error, relative_difference(r%elements%normal_traction, &
                   fresh%elements%normal_traction), 0.0_wp, 'normal traction', abs_tol=1.0e-9_wp)
        call check(error, relative_difference(r%tips%k1, fresh%tips%k1), 0.0_wp, 'K_I', &
                   abs_tol=1.0e-9_wp)
        call check(error, relative_difference(r%tips%k2, fresh%tips%k2), 0.0_wp, 'K_II', &
                   abs_tol=1.0e-9_wp)
    end subroutine test_kept_against_final

    !> The same run with Lemke (every solve from scratch): the same steps, reasons and
    !> corrector solves, angles within 1e-6 degrees, the final DDs within 1e-8 relative.
    subroutine test_kept_against_lemke(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: newton_model, lemke_model
        type(model_results) :: newton, lemke

        newton_model = sliding_flaw(40, 5)
        lemke_model = newton_model
        lemke_model%solver%lcp_method = lcp_lemke
        call check(error, .not. keeps_solves(lemke_model), 'Lemke solves from scratch')
        if (allocated(error)) return
        call grow_fractures(newton_model, newton, error)
        if (allocated(error)) return
        call grow_fractures(lemke_model, lemke, error)
        if (allocated(error)) return
        call check(error, size(newton%growth%step), size(lemke%growth%step), 'records')
        call check(error, newton_model%elements%n, lemke_model%elements%n, 'elements')
        if (allocated(error)) return
        call check(error, all(newton%growth%reason == lemke%growth%reason), 'reasons')
        call check(error, all(newton%growth%corrections == lemke%growth%corrections), &
                   'corrector solves')
        ! Tips that did not grow have NaN angles in both.
        call check(error, maxval(abs(newton%growth%angle - lemke%growth%angle), &
                   mask=newton%growth%angle == newton%growth%angle), 0.0_wp, &
                   'angles [degree]', abs_tol=1.0e-6_wp)
        call check(error, all(newton%elements%state == lemke%elements%state), 'final states')
        call check(error, relative_difference(newton%elements%ds, lemke%elements%ds), 0.0_wp, &
                   'final ds', abs_tol=1.0e-8_wp)
        call check(error, relative_difference(newton%elements%dn, lemke%elements%dn), 0.0_wp, &
                   'final dn', abs_tol=1.0e-8_wp)
    end subroutine test_kept_against_lemke

    !> 1 and 2 threads on the kept path: the same geometry and DDs (1e-12 relative).
    subroutine test_kept_threads(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: one_model, two_model
        type(model_results) :: one, two
        integer :: saved

        one_model = sliding_flaw(40, 3)
        two_model = one_model
        saved = omp_get_max_threads()
        call omp_set_num_threads(1)
        call grow_fractures(one_model, one, error)
        if (.not. allocated(error)) then
            call omp_set_num_threads(2)
            call grow_fractures(two_model, two, error)
        end if
        call omp_set_num_threads(saved)
        if (allocated(error)) return
        call check(error, one_model%elements%n, two_model%elements%n, 'elements')
        if (allocated(error)) return
        call check(error, relative_difference(one_model%elements%x_end, &
                   two_model%elements%x_end), 0.0_wp, 'x_end', abs_tol=1.0e-12_wp)
        call check(error, relative_difference(one%elements%ds, two%elements%ds), 0.0_wp, &
                   'ds', abs_tol=1.0e-12_wp)
        call check(error, relative_difference(one%elements%dn, two%elements%dn), 0.0_wp, &
                   'dn', abs_tol=1.0e-12_wp)
    end subroutine test_kept_threads

end module test_growth_solver
