!> The memory a model needs, estimated before anything large is allocated, against what
!> this machine offers (ddc_run_available_memory): a model that cannot fit is refused with
!> one message (exit_out_of_memory) instead of failing in an allocation.
!>
!> The estimate adds (in reals of 8 bytes, N elements, nc of them contact elements, nf the
!> others):
!> - the solve, at its peak: TWODD-style elements only, the influence matrix and its LU
!>   factors, 2 (2N)^2; with contact elements the assembled matrix (2N)^2 is condensed to
!>   the contact elements' A (2nc)^2 (with nf > 0 the whole matrix, K_FF, K_FF^-1 K_FC and
!>   a temporary K_CF are kept too), then the contact method works on A
!>   (ddc_contact_memory: Lemke 45 nc^2, Newton 1.375 m^2 for a reduced system of m
!>   unknowns, up to 5.5 nc^2 when every element slips and opens); a loading history
!>   solves each step with the same method (Newton keeps its factors between steps, Lemke
!>   its LCP) and stores about 12 reals per element and step (15 with the strengths in
!>   force), held from the start; a growth run whose elements are all contact elements
!>   solved by Newton keeps the influence matrix and the reduced factors of the last
!>   accepted geometry beside those of the trial (ddc_growth_solver), with the arrays of
!>   the update it may carry on (at most 3 m^2 / 16 for m = 2N unknowns): 9 N^2 more,
!>   counted at the input's N (the grown N is not known before the run); elastic joints
!>   (a finite shear_stiffness or normal_stiffness, ddc_solve_joints) hold A_j (2nc)^2
!>   beside A, and build it with two more such matrices, C + K^-1 and the load map;
!> - the model and its results, 50 reals per element and 13 per observation point;
!> - the program itself (libraries, buffers), 20 MB;
!> - K's local re-solve where it serves (add_k_resolve: the zones' matrices and the
!>   coupling's kept rows, ddc_post_higher_order_k), held from the first solve on.
!> The Newton method is estimated twice: from the states its solve starts from (those of
!> the remote stress alone: slip where the shear traction exceeds the strength, open where
!> the effective normal traction is tensile; a one-shot solve without TWODD-style elements,
!> otherwise the largest) and at its largest, every element slipping and open. A model is
!> refused when the first does not fit; should the states later ask for more than is left,
!> the method stops then with exit_out_of_memory (ddc_contact_active_set).
!> Measured (Release, OpenBLAS, 2026-11-24): the peak resident memory of Lemke runs is
!> within 5 % of the estimate; that of the benchmark's straight and mixed faults (Newton,
!> N = 2000-8000) within 10 % of the estimate from the starting states
!> (docs/performance.md#size-guide).
module ddc_run_memory
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_out_of_memory
    use ddc_allocation, only: real_bytes
    use ddc_text, only: bytes_text, itoa
    use ddc_model_types, only: model_type, condition_contact, rigid_joint
    use ddc_model_laws, only: laws_allocated
    use ddc_contact_options, only: lcp_auto, lcp_newton, matrix_hierarchical
    use ddc_contact_formulation, only: auto_newton_min_elements
    use ddc_contact_memory, only: lemke_bytes, newton_bytes
    use ddc_contact_active_set, only: starting_unknowns
    use ddc_contact_result, only: contact_stress_scale
    use ddc_model_element_laws, only: strengths_change
    use ddc_model_loads, only: resolve_remote_stress, total_pressure
    use ddc_model_body, only: body_nodes
    use ddc_model_medium, only: elastic_medium, medium_of
    use ddc_model_results, only: tip_set
    use ddc_post_tips, only: find_tips
    use ddc_post_higher_order_k, only: uses_higher_order, higher_order_bytes
    implicit none
    private

    public :: memory_need, estimate_memory, add_k_resolve, check_memory, elements_that_fit
    public :: hierarchical_min_elements

    !> The program's own memory: libraries, OpenBLAS and HDF5 buffers [bytes]
    real(wp), parameter :: program_bytes = 20.0e6_wp
    !> Reals per element of the model and its results, and per observation point
    real(wp), parameter :: element_reals = 50.0_wp, point_reals = 13.0_wp
    !> Reals per element and step that a loading history stores, and those it stores besides
    !> where it records the strengths in force (records_strengths)
    real(wp), parameter :: history_reals = 12.0_wp, strength_reals = 3.0_wp
    !> Reals per squared element that a growth run keeps for its base geometry (matrix,
    !> reduced factors and a carried update)
    real(wp), parameter :: growth_base_reals = 9.0_wp
    !> A hierarchical matrix of m unknowns stores about hmatrix_reals m log2(m) reals at
    !> the default settings (measured: docs/performance.md#hierarchical-matrices); its
    !> assembly and solve work on hmatrix_work_reals reals per unknown beside it
    real(wp), parameter :: hmatrix_reals = 30.0_wp, hmatrix_work_reals = 20.0_wp
    !> &solver matrix = 'auto' takes a hierarchical matrix from this many elements on (where
    !> the model allows it): measured on a 2-core machine, the benchmark's straight fault
    !> solves faster on it from about 5000 elements, its kinked network (13 Newton
    !> iterations) from about 12000 (docs/performance.md#hierarchical-matrices)
    integer, parameter :: hierarchical_min_elements = 12000

    !> What a model needs, and where it was estimated to peak.
    type :: memory_need
        !> Estimated peak memory of the run [bytes]: the Newton method's from the states its
        !> solve starts from
        real(wp) :: bytes = 0.0_wp
        !> The same with the Newton method's reduced system at its largest (every element
        !> slipping and open) [bytes]; bytes for the other methods
        real(wp) :: worst_bytes = 0.0_wp
        !> Unknowns of the Newton method's first reduced system (-1: counted at the largest)
        integer :: start_unknowns = -1
        !> The method the estimate is for: 'lu', 'newton' or 'lemke', followed by ' (loading
        !> history)' for a history
        character(len=:), allocatable :: method
        !> Peak if the Newton method fails and falls back to Lemke [bytes]; 0 when the run
        !> cannot fall back
        real(wp) :: fallback_bytes = 0.0_wp
        !> Memory held while the contact method works, outside its own work [bytes]
        real(wp) :: held_bytes = 0.0_wp
        !> The share of K's local re-solve in each of the above [bytes] (add_k_resolve)
        real(wp) :: k_bytes = 0.0_wp
    end type memory_need

contains

    !> The estimated peak memory of solving a model with the method it will use.
    pure function estimate_memory(model) result(need)
        !> The model (elements, observation sets, solver options, load path)
        type(model_type), intent(in) :: model
        !> The estimate
        type(memory_need) :: need

        need = need_of(model, model%elements%n, &
                       count(model%elements%condition == condition_contact), &
                       first_unknowns(model))
    end function estimate_memory

    !> Add the memory of K's local re-solve where it will serve: the zones' matrices and the
    !> coupling's kept rows, allocated after the first solve and held from then on (the
    !> tips and zones of the input geometry).
    subroutine add_k_resolve(model, need)
        !> The model, element geometry computed
        type(model_type), intent(in) :: model
        !> The estimate of the solve (estimate_memory); k_bytes set
        type(memory_need), intent(inout) :: need
        type(elastic_medium) :: medium
        type(tip_set) :: tips
        real(wp), allocatable :: zero(:)
        character(len=:), allocatable :: why_not
        logical :: uses

        if (.not. allocated(model%elements%cos_beta) .or. model%elements%n == 0) return
        medium = medium_of(model)
        allocate (zero(model%elements%n), source=0.0_wp)
        call find_tips(medium, zero, zero, tips)
        call uses_higher_order(model%solver%k_method, model%solver%k_zone_elements, &
                               model%growth%active, medium, tips, uses, why_not)
        if (.not. uses) return
        need%k_bytes = higher_order_bytes(medium, tips, model%solver%k_zone_elements)
        need%bytes = need%bytes + need%k_bytes
        need%worst_bytes = need%worst_bytes + need%k_bytes
        need%held_bytes = need%held_bytes + need%k_bytes
        if (need%fallback_bytes > 0.0_wp) need%fallback_bytes = need%fallback_bytes + &
                                                                need%k_bytes
    end subroutine add_k_resolve

    !> The unknowns of the Newton method's first reduced system: states from the remote
    !> stress on the contact elements (ddc_contact_active_set); -1 when the solve starts
    !> elsewhere (loading history, growth, TWODD-style elements condensed into the load,
    !> no geometry).
    pure integer function first_unknowns(model)
        !> The model
        type(model_type), intent(in) :: model
        real(wp), allocatable :: shear(:), normal(:), pressure(:)

        first_unknowns = -1
        if (allocated(model%load_path%vertex) .or. model%growth%active) return
        if (.not. allocated(model%elements%cos_beta) .or. model%elements%n == 0) return
        if (any(model%elements%condition /= condition_contact)) return
        allocate (shear(model%elements%n), normal(model%elements%n))
        call resolve_remote_stress(model%elements, model%sxx, model%syy, model%sxy, shear, &
                                   normal, model%stress_gradient)
        pressure = total_pressure(model%elements, model%pore_fluid)
        first_unknowns = starting_unknowns(shear, normal + pressure, model%elements%mu, &
            model%elements%sf, contact_stress_scale(shear, normal, model%elements%sf, pressure))
    end function first_unknowns

    !> The estimate for n elements, nc of them contact elements, with the model's
    !> observation sets, solver options and load path.
    pure function need_of(model, elements, contact, unknowns) result(need)
        !> The model (observation sets, solver options, load path)
        type(model_type), intent(in) :: model
        !> Number of elements and of contact elements among them
        integer, intent(in) :: elements, contact
        !> Unknowns of the Newton method's first reduced system (-1: the largest, 2 contact)
        integer, intent(in) :: unknowns
        !> The estimate
        type(memory_need) :: need
        real(wp) :: n, nc, nf, matrix, held, condense, points, fixed
        character(len=:), allocatable :: history
        integer :: k

        n = real(elements, wp)
        nc = real(contact, wp)
        nf = n - nc
        points = 0.0_wp
        if (allocated(model%observations)) then
            do k = 1, size(model%observations)
                points = points + real(size(model%observations(k)%x), wp)
            end do
        end if
        fixed = program_bytes + real_bytes * (element_reals * n + point_reals * points) + &
                body_bytes(model, n)
        history = ''
        if (allocated(model%load_path%vertex)) then
            history = ' (loading history)'
            fixed = fixed + real_bytes * (history_reals + merge(strength_reals, 0.0_wp, &
                records_strengths(model))) * n * real(1 + sum(model%load_path%steps), wp)
        end if
        matrix = real_bytes * 4.0_wp * n**2
        if (model%solver%matrix == matrix_hierarchical) then
            need%method = trim(merge('newton', 'lu    ', contact > 0))//', hierarchical matrix'
            need%bytes = fixed + hierarchical_bytes(elements)
            need%worst_bytes = need%bytes
            return
        end if
        if (contact == 0) then
            need%method = 'lu'
            need%bytes = fixed + 2.0_wp * matrix
            need%worst_bytes = need%bytes
            return
        end if
        ! Held while the contact method works: A of the contact elements, and with free
        ! elements the whole matrix, K_FF and K_FF^-1 K_FC; the condensation's peak adds a
        ! temporary K_CF.
        held = real_bytes * 4.0_wp * nc**2
        condense = matrix
        if (nf > 0.0_wp) then
            held = held + matrix + real_bytes * 4.0_wp * (nf**2 + nf * nc)
            condense = held + real_bytes * 4.0_wp * nf * nc
        end if
        if (has_joints(model)) then
            condense = max(condense, held + real_bytes * 12.0_wp * nc**2)
            held = held + real_bytes * 4.0_wp * nc**2
        end if
        need%held_bytes = fixed + held
        if (model%solver%lcp_method == lcp_newton .or. (model%solver%lcp_method == &
            lcp_auto .and. contact >= auto_newton_min_elements)) then
            if (model%growth%active .and. nf == 0.0_wp) then
                held = held + real_bytes * growth_base_reals * n**2
                need%held_bytes = fixed + held
                history = ' (growth)'
            end if
            need%method = 'newton'//history
            need%worst_bytes = fixed + max(condense, held + newton_bytes(contact))
            need%bytes = need%worst_bytes
            if (unknowns >= 0) then
                need%start_unknowns = unknowns
                need%bytes = fixed + max(condense, held + newton_bytes(contact, unknowns))
            end if
            need%fallback_bytes = fixed + max(condense, held + lemke_bytes(contact))
        else
            need%method = 'lemke'//history
            need%bytes = fixed + max(condense, held + lemke_bytes(contact), &
                                     held + newton_bytes(contact))
            need%worst_bytes = need%bytes
        end if
    end function need_of

    !> A finite body's part (ddc_influence_body): its bordered equations, factorized, in
    !> each of the two copies of the medium a solve holds (its own and its run's), and the
    !> fractures' rows of the body beside the body's answer to their DDs while the
    !> influence matrix takes them.
    pure real(wp) function body_bytes(model, n)
        type(model_type), intent(in) :: model
        !> Number of fracture elements
        real(wp), intent(in) :: n
        real(wp) :: nz

        body_bytes = 0.0_wp
        if (.not. allocated(model%body)) return
        nz = 2.0_wp * real(body_nodes * sum(model%body%elements), wp)
        body_bytes = real_bytes * (2.0_wp * (nz + 3.0_wp)**2 + 4.0_wp * n * nz)
    end function body_bytes

    !> The peak of a hierarchical solve of n elements (ddc_solve_hierarchical): the
    !> compressed matrix and its H-LU factors beside it, hmatrix_reals reals per unknown
    !> each, and the assembly's workspace.
    pure real(wp) function hierarchical_bytes(elements)
        integer, intent(in) :: elements
        real(wp) :: m

        m = 2.0_wp * real(elements, wp)
        hierarchical_bytes = real_bytes * (2.0_wp * hmatrix_reals * m * log(m) / log(2.0_wp) + &
                                           hmatrix_work_reals * m)
    end function hierarchical_bytes

    !> Whether a loading history of the model records the strengths in force of each step
    !> (ddc_model_element_laws' strengths_change); not without the per-element laws.
    pure logical function records_strengths(model)
        type(model_type), intent(in) :: model

        associate (e => model%elements)
            records_strengths = allocated(e%mu) .and. allocated(e%sf) .and. laws_allocated(e)
            if (records_strengths) records_strengths = strengths_change(e, model%solver)
        end associate
    end function records_strengths

    !> Whether a contact element has an elastic joint (a finite stiffness).
    pure logical function has_joints(model)
        type(model_type), intent(in) :: model

        has_joints = .false.
        if (allocated(model%elements%shear_stiffness)) has_joints = &
            any(model%elements%shear_stiffness < rigid_joint)
        if (allocated(model%elements%normal_stiffness)) has_joints = has_joints .or. &
            any(model%elements%normal_stiffness < rigid_joint)
    end function has_joints

    !> The largest number of elements, the model's share of contact elements, observation
    !> sets, solver and load path kept, whose estimate fits in `available` bytes (0 when
    !> not even one element does).
    pure integer function elements_that_fit(model, available)
        !> The model
        type(model_type), intent(in) :: model
        !> Memory available [bytes]
        real(wp), intent(in) :: available
        real(wp) :: share, start_share
        type(memory_need) :: need
        integer :: low, high, middle, contact

        contact = count(model%elements%condition == condition_contact)
        share = real(contact, wp) / real(max(model%elements%n, 1), wp)
        ! The starting unknowns per contact element stay as they are (-1: the largest).
        start_share = -1.0_wp
        need = estimate_memory(model)
        if (need%start_unknowns >= 0) start_share = real(need%start_unknowns, wp) / &
            real(max(contact, 1), wp)
        low = 0
        high = model%elements%n
        do while (high - low > 1)
            middle = low + (high - low) / 2
            need = need_of(model, middle, nint(share * middle), &
                           scaled_unknowns(nint(share * middle)))
            if (need%bytes <= available) then
                low = middle
            else
                high = middle
            end if
        end do
        elements_that_fit = low
        need = need_of(model, high, nint(share * high), scaled_unknowns(nint(share * high)))
        if (need%bytes <= available) elements_that_fit = high

    contains

        pure integer function scaled_unknowns(contact_elements)
            integer, intent(in) :: contact_elements

            scaled_unknowns = -1
            if (start_share >= 0.0_wp) scaled_unknowns = nint(start_share * contact_elements)
        end function scaled_unknowns

    end function elements_that_fit

    !> Refuse a model whose estimate exceeds the memory available (exit_out_of_memory),
    !> with one message saying how much it needs, how much there is, where that limit comes
    !> from and how many elements would fit.
    subroutine check_memory(model, need, available, source, error)
        !> The model
        type(model_type), intent(in) :: model
        !> Its estimate (estimate_memory)
        type(memory_need), intent(in) :: need
        !> Memory available here [bytes]
        real(wp), intent(in) :: available
        !> Where that limit comes from, e.g. 'MemAvailable in /proc/meminfo'
        character(len=*), intent(in) :: source
        !> Allocated (exit_out_of_memory) when the model does not fit
        type(error_type), allocatable, intent(out) :: error

        if (need%bytes <= available) return
        call set_error(error, exit_out_of_memory, itoa(model%elements%n)//' elements need '// &
            'about '//bytes_text(need%bytes)//' of memory with the '//need%method// &
            ' method, but about '//bytes_text(available)//' is available here ('//source// &
            '); about '//itoa(elements_that_fit(model, available - need%k_bytes))// &
            ' elements fit. Use a '// &
            'machine with more memory (on Slurm: sbatch --mem), or fewer elements; see '// &
            'the size guide in docs/performance.md#size-guide')
    end subroutine check_memory

end module ddc_run_memory
