!> Tests of the memory guard: the estimate of each method, the number of elements that
!> fit, the refusal message, the memory found in /proc/meminfo and the cgroups (fake files
!> under /tmp), sizes as text and the message of a failed allocation.
module test_memory
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_error, only: exit_out_of_memory
    use ddc_model_types, only: model_type, condition_contact, condition_traction, rigid_joint
    use ddc_contact_options, only: lcp_auto, lcp_lemke, lcp_newton
    use ddc_run_memory, only: memory_need, estimate_memory, check_memory, elements_that_fit
    use ddc_run_available_memory, only: available_memory, no_limit
    use ddc_text, only: bytes_text
    use ddc_allocation, only: allocation_failed
    use ddc_test_builders, only: polyline_model
    implicit none
    private
    public :: collect_memory

    !> Bytes of the program itself and of one real, as the estimate counts them
    real(wp), parameter :: program = 20.0e6_wp, r = 8.0_wp

contains

    !> Cases of the memory suite.
    subroutine collect_memory(tests)
        !> The cases
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('estimate_of_each_method', test_estimates), &
                 new_test('estimate_with_condensation_and_points', test_condensation), &
                 new_test('estimate_from_starting_states', test_starting_states), &
                 new_test('estimate_of_a_loading_history', test_history), &
                 new_test('estimate_of_a_growth_run', test_growth), &
                 new_test('estimate_with_elastic_joints', test_joints), &
                 new_test('elements_that_fit', test_fit), &
                 new_test('refusal_message', test_refusal), &
                 new_test('meminfo_and_cgroup_v1', test_cgroup_v1), &
                 new_test('cgroup_v2_and_no_limit', test_cgroup_v2), &
                 new_test('nothing_readable_is_no_limit', test_no_files), &
                 new_test('sizes_as_text', test_bytes_text), &
                 new_test('allocation_failed_message', test_allocation_failed)]
    end subroutine collect_memory

    !> A model of n elements, the first nc of them contact elements; no geometry needed.
    function counted_model(n, nc) result(model)
        integer, intent(in) :: n, nc
        type(model_type) :: model

        model%elements%n = n
        allocate (model%elements%condition(n))
        model%elements%condition = condition_traction
        model%elements%condition(:nc) = condition_contact
        allocate (model%observations(0))
    end function counted_model

    !> Elastic joints hold A_j, (2N)^2 reals, beside A while the contact method works, and
    !> build it with two more.
    subroutine test_joints(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(memory_need) :: rigid, joints
        real(wp) :: n

        n = 1000.0_wp
        model = counted_model(1000, 1000)
        allocate (model%elements%shear_stiffness(1000), model%elements%normal_stiffness(1000))
        model%elements%shear_stiffness = rigid_joint
        model%elements%normal_stiffness = rigid_joint
        rigid = estimate_memory(model)
        model%elements%normal_stiffness(7) = 1.0e5_wp
        joints = estimate_memory(model)
        call check(error, joints%held_bytes - rigid%held_bytes, r * 4.0_wp * n**2, &
                   'A_j held', rel_tol=1.0e-12_wp)
        ! The peak: building A_j (three such matrices beside A), or the method beside A_j.
        call check(error, joints%bytes, max(rigid%held_bytes + r * 12.0_wp * n**2, &
                   joints%held_bytes + rigid%bytes - rigid%held_bytes), &
                   'peak with joints', rel_tol=1.0e-12_wp)
    end subroutine test_joints

    !> Every contact method and the elastic solve against the formulas of ddc_run_memory:
    !> (2N)^2 reals per matrix; Lemke 45 N^2 beyond A, Newton 4 N^2; 50 reals per element.
    subroutine test_estimates(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(memory_need) :: need
        real(wp) :: n, fixed

        n = 1000.0_wp
        fixed = program + r * 50.0_wp * n
        model = counted_model(1000, 0)
        need = estimate_memory(model)
        call check(error, need%method == 'lu', 'method of a model without contact')
        call check(error, need%bytes, fixed + r * 8.0_wp * n**2, 'LU: matrix and factors', &
                   rel_tol=1.0e-14_wp)
        model = counted_model(1000, 1000)
        need = estimate_memory(model)
        call check(error, need%method == 'newton', "auto from 300 contact elements: newton")
        call check(error, need%bytes, fixed + r * (9.5_wp * n**2 + 60.0_wp * n), &
                   'newton: A, the reduced system and an update at their largest', &
                   rel_tol=1.0e-14_wp)
        call check(error, need%fallback_bytes, fixed + r * (49.0_wp * n**2 + 60.0_wp * n), &
                   'the fallback to Lemke: A and 45 N^2', rel_tol=1.0e-14_wp)
        model%solver%lcp_method = lcp_lemke
        need = estimate_memory(model)
        call check(error, need%method == 'lemke', 'lcp_method = lemke')
        call check(error, need%bytes, fixed + r * (49.0_wp * n**2 + 60.0_wp * n), 'lemke', &
                   rel_tol=1.0e-14_wp)
        call check(error, need%fallback_bytes, 0.0_wp, 'lemke has no fallback', &
                   abs_tol=0.0_wp)
        model = counted_model(200, 200)
        need = estimate_memory(model)
        call check(error, need%method == 'lemke', 'auto below 300 contact elements: lemke')
        model%solver%lcp_method = lcp_newton
        need = estimate_memory(model)
        call check(error, need%method == 'newton', 'lcp_method = newton')
    end subroutine test_estimates

    !> The paper's fault (every element slips from the start: n unknowns) and the same
    !> fault sticking (mu = 0.8: none): the Newton method from its starting states, 1.375 m^2
    !> reals for m unknowns, beside the largest (m = 2n: 5.5 n^2).
    subroutine test_starting_states(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(memory_need) :: need
        real(wp) :: n, fixed, worst

        model = polyline_model([-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [1000], condition_contact, &
                               0.0_wp, 0.0_wp, 50000.0_wp, 0.25_wp)
        model%elements%mu = 0.6_wp
        model%elements%sf = 1.0_wp
        model%sxx = -143.75_wp
        model%syy = -81.25_wp
        model%sxy = 54.13_wp
        n = 1000.0_wp
        fixed = program + r * 50.0_wp * n
        worst = fixed + r * (9.5_wp * n**2 + 60.0_wp * n)
        need = estimate_memory(model)
        call check(error, need%start_unknowns, 1000, 'every element slips from the start')
        call check(error, need%bytes, fixed + r * (4.0_wp * n**2 + 1.375_wp * n**2 + &
                   60.0_wp * n), 'A and the reduced system of n unknowns', rel_tol=1.0e-14_wp)
        call check(error, need%worst_bytes, worst, 'at the largest', rel_tol=1.0e-14_wp)
        model%elements%mu = 0.8_wp
        need = estimate_memory(model)
        call check(error, need%start_unknowns, 0, 'every element sticks from the start')
        call check(error, need%bytes, fixed + r * (4.0_wp * n**2 + 60.0_wp * n), 'A alone', &
                   rel_tol=1.0e-14_wp)
        ! Refused only when the smaller need does not fit; what fits scales with it.
        call check(error, elements_that_fit(model, need%bytes), 1000, 'the start fits')
        model%load_path%steps = [4]
        allocate (model%load_path%vertex(7, 2), source=0.0_wp)
        need = estimate_memory(model)
        call check(error, need%start_unknowns, -1, 'a loading history: counted at the largest')
    end subroutine test_starting_states

    !> TWODD-style elements beside contact elements: the whole matrix, K_FF, K_FF^-1 K_FC
    !> and A are held while Newton works; observation points count 13 reals each.
    subroutine test_condensation(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(memory_need) :: need
        real(wp) :: nc, nf, held

        model = counted_model(1000, 600)
        model%solver%lcp_method = lcp_newton
        deallocate (model%observations)
        allocate (model%observations(2))
        allocate (model%observations(1)%x(5000), model%observations(2)%x(3000))
        nc = 600.0_wp
        nf = 400.0_wp
        held = r * (4.0_wp * nc**2 + 4.0_wp * (nc + nf)**2 + 4.0_wp * (nf**2 + nf * nc))
        need = estimate_memory(model)
        call check(error, need%held_bytes, program + r * (50.0_wp * 1000.0_wp + &
                   13.0_wp * 8000.0_wp) + held, 'held while the contact method works', &
                   rel_tol=1.0e-14_wp)
        call check(error, need%bytes, need%held_bytes + r * (5.5_wp * nc**2 + 60.0_wp * nc), &
                   'newton on the condensed system', rel_tol=1.0e-14_wp)
    end subroutine test_condensation

    !> A loading history is solved by the method asked for and stores 12 reals per element
    !> and step.
    subroutine test_history(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, without
        type(memory_need) :: need, need_without

        without = counted_model(500, 500)
        without%solver%lcp_method = lcp_lemke
        model = without
        allocate (model%load_path%vertex(7, 3))
        model%load_path%steps = [40, 59]
        need = estimate_memory(model)
        need_without = estimate_memory(without)
        call check(error, need%method == 'lemke (loading history)', 'method: '//need%method)
        call check(error, need%bytes - need_without%bytes, &
                   r * 12.0_wp * 500.0_wp * 100.0_wp, '100 steps of 500 elements', &
                   rel_tol=1.0e-9_wp)
        model%solver%lcp_method = lcp_auto
        without%solver%lcp_method = lcp_auto
        need = estimate_memory(model)
        need_without = estimate_memory(without)
        call check(error, need%method == 'newton (loading history)', 'auto: '//need%method)
        call check(error, need%bytes - need_without%bytes, &
                   r * 12.0_wp * 500.0_wp * 100.0_wp, 'newton: 100 steps of 500 elements', &
                   rel_tol=1.0e-9_wp)
    end subroutine test_history

    !> A growth run solved by Newton keeps the base geometry's matrix and factors: 9 N^2
    !> reals more; with Lemke (solved from scratch every time) nothing more.
    subroutine test_growth(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, without
        type(memory_need) :: need, need_without

        without = counted_model(500, 500)
        without%solver%lcp_method = lcp_auto
        model = without
        model%growth%active = .true.
        need = estimate_memory(model)
        need_without = estimate_memory(without)
        call check(error, need%method == 'newton (growth)', 'method: '//need%method)
        call check(error, need%bytes - need_without%bytes, r * 9.0_wp * 500.0_wp**2, &
                   'the base geometry of 500 elements', rel_tol=1.0e-9_wp)
        model%solver%lcp_method = lcp_lemke
        without%solver%lcp_method = lcp_lemke
        need = estimate_memory(model)
        need_without = estimate_memory(without)
        call check(error, need%bytes, need_without%bytes, 'lemke: as without growth', &
                   rel_tol=1.0e-15_wp)
    end subroutine test_growth

    !> The largest number of elements whose estimate fits: it fits, one more does not.
    subroutine test_fit(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model, smaller
        type(memory_need) :: need
        real(wp) :: available
        integer :: fit

        model = counted_model(200000, 200000)
        available = 24.0e9_wp
        fit = elements_that_fit(model, available)
        smaller = counted_model(fit, fit)
        need = estimate_memory(smaller)
        call check(error, need%bytes <= available, 'the fit fits')
        smaller = counted_model(fit + 1, fit + 1)
        need = estimate_memory(smaller)
        call check(error, need%bytes > available, 'one more does not')
        ! Newton: about 76 N^2 bytes, so about sqrt(24e9 / 76) = 17770 elements.
        call check(error, real(fit, wp), 17770.0_wp, 'elements that fit in 24 GB', &
                   rel_tol=1.0e-3_wp)
        call check(error, elements_that_fit(model, 1.0_wp), 0, 'nothing fits in one byte')
    end subroutine test_fit

    !> The message names the elements, the need, the method, what is available and where
    !> that comes from, and how many elements fit; a model that fits passes.
    subroutine test_refusal(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(error_type), allocatable :: refused

        model = counted_model(200000, 200000)
        call check_memory(model, estimate_memory(model), 24.0e9_wp, 'MemAvailable', refused)
        call check(error, allocated(refused), '200000 elements in 24 GB must be refused')
        if (allocated(error)) return
        call check(error, refused%code, exit_out_of_memory, 'exit code')
        call check(error, index(refused%message, '200000 elements need about 3 TB of '// &
            'memory with the newton method, but about 24 GB is available here '// &
            '(MemAvailable); about 17757 elements fit.') == 1, 'message: '//refused%message)
        model = counted_model(1000, 1000)
        call check_memory(model, estimate_memory(model), 24.0e9_wp, 'MemAvailable', refused)
        call check(error, .not. allocated(refused), '1000 elements fit in 24 GB')
    end subroutine test_refusal

    !> Write a text file.
    subroutine write_file(path, text)
        character(len=*), intent(in) :: path, text
        integer :: unit

        call execute_command_line('mkdir -p '//path(:index(path, '/', back=.true.) - 1))
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') text
        close (unit)
    end subroutine write_file

    !> cgroup v1: the process's own cgroup and its parent both have limits; the smallest of
    !> them and MemAvailable counts.
    subroutine test_cgroup_v1(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: base = '/tmp/ddc2d_test_memory_v1'
        real(wp) :: bytes
        character(len=:), allocatable :: source

        call write_file(base//'/meminfo', 'MemTotal:       24684084 kB'//new_line('a')// &
                        'MemAvailable:   24179608 kB'//new_line('a')//'Cached: 1 kB')
        call write_file(base//'/cgroup', '9:name=systemd:/'//new_line('a')// &
                        '4:cpu,memory:/jobs/job_7/step_0'//new_line('a')//'0::/')
        call write_file(base//'/root/memory/memory.limit_in_bytes', '9223372036854771712')
        call write_file(base//'/root/memory/jobs/job_7/memory.limit_in_bytes', '4294967296')
        call write_file(base//'/root/memory/jobs/job_7/step_0/memory.limit_in_bytes', &
                        '8589934592')
        call available_memory(bytes, source, base//'/meminfo', base//'/cgroup', base//'/root')
        call check(error, bytes, 4294967296.0_wp, 'the job limit, smaller than the step''s', &
                   rel_tol=0.0_wp)
        call check(error, source == 'the memory cgroup limit in '//base// &
                   '/root/memory/jobs/job_7/memory.limit_in_bytes', 'source: '//source)
        call write_file(base//'/root/memory/jobs/job_7/memory.limit_in_bytes', &
                        '9223372036854771712')
        call write_file(base//'/root/memory/jobs/job_7/step_0/memory.limit_in_bytes', &
                        '9223372036854771712')
        call available_memory(bytes, source, base//'/meminfo', base//'/cgroup', base//'/root')
        call check(error, bytes, 24179608.0_wp * 1024.0_wp, 'no cgroup limit: MemAvailable', &
                   rel_tol=0.0_wp)
        call check(error, source == 'MemAvailable in '//base//'/meminfo', 'source: '//source)
    end subroutine test_cgroup_v1

    !> cgroup v2: memory.max of the process's cgroup ("max" above it); a path that is not
    !> visible (a container) falls back to the root's memory.max.
    subroutine test_cgroup_v2(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: base = '/tmp/ddc2d_test_memory_v2'
        real(wp) :: bytes
        character(len=:), allocatable :: source

        call write_file(base//'/meminfo', 'MemAvailable:   1000000 kB')
        call write_file(base//'/cgroup', '0::/slurm/job_3')
        call write_file(base//'/root/slurm/memory.max', 'max')
        call write_file(base//'/root/slurm/job_3/memory.max', '536870912')
        call available_memory(bytes, source, base//'/meminfo', base//'/cgroup', base//'/root')
        call check(error, bytes, 536870912.0_wp, 'the job cgroup', rel_tol=0.0_wp)
        call write_file(base//'/cgroup', '0::/not/visible/here')
        call write_file(base//'/root/memory.max', '268435456')
        call available_memory(bytes, source, base//'/meminfo', base//'/cgroup', base//'/root')
        call check(error, bytes, 268435456.0_wp, 'the root of the mounted hierarchy', &
                   rel_tol=0.0_wp)
        call write_file(base//'/root/memory.max', 'max')
        call available_memory(bytes, source, base//'/meminfo', base//'/cgroup', base//'/root')
        call check(error, bytes, 1.024e9_wp, 'no limit: MemAvailable', rel_tol=0.0_wp)
    end subroutine test_cgroup_v2

    !> Without any readable file there is no limit, and nothing is refused.
    subroutine test_no_files(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: bytes
        character(len=:), allocatable :: source

        call available_memory(bytes, source, '/tmp/ddc2d_no_such_meminfo', &
                              '/tmp/ddc2d_no_such_cgroup', '/tmp/ddc2d_no_such_root')
        call check(error, bytes == no_limit, 'no limit')
        call check(error, source == 'no limit found', 'source: '//source)
    end subroutine test_no_files

    subroutine test_bytes_text(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, bytes_text(640.0_wp) == '640 bytes', bytes_text(640.0_wp))
        call check(error, bytes_text(1.28e12_wp) == '1.3 TB', bytes_text(1.28e12_wp))
        call check(error, bytes_text(2.56e12_wp) == '2.6 TB', bytes_text(2.56e12_wp))
        call check(error, bytes_text(24.7e9_wp) == '25 GB', bytes_text(24.7e9_wp))
        call check(error, bytes_text(999.7e6_wp) == '1 GB', bytes_text(999.7e6_wp))
        call check(error, bytes_text(1.5e18_wp) == '1500000 TB', bytes_text(1.5e18_wp))
    end subroutine test_bytes_text

    subroutine test_allocation_failed(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failed

        call allocation_failed(failed, 'the influence matrix of 200000 elements', 1.28e12_wp)
        call check(error, failed%code, exit_out_of_memory, 'exit code')
        call check(error, failed%message == 'not enough memory for the influence matrix of '// &
                   '200000 elements (1.3 TB); see the size guide in the README', failed%message)
    end subroutine test_allocation_failed

end module test_memory
