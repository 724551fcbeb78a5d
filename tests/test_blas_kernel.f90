!> Tests of the BLAS kernel advice (ddc_linalg_blas_kernel): CPU flags and kernel names to
!> instruction-set levels, the advice for the cases of issue 28 (Prescott on an AVX-512
!> CPU, Haswell on AVX2, SkylakeX on AVX-512, a kernel the user chose, a re-run that
!> OpenBLAS ignored), and the CPU read from a cpuinfo file (a fake one under /tmp).
module test_blas_kernel
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_linalg_blas_kernel, only: cpu_description, describe_cpu, cpu_level_of_flags, &
        kernel_level, kernel_advice, advise_kernel, kernel_choice, isa_unknown, isa_sse, &
        isa_avx, isa_avx2, isa_avx512, advice_none, advice_note, advice_rerun, advice_warn
    implicit none
    private
    public :: collect_blas_kernel

    !> cpuinfo flags of an AVX-512 Xeon and of an AVX2 EPYC (abridged)
    character(len=*), parameter :: xeon_flags = 'fpu sse sse2 ssse3 fma sse4_1 sse4_2 avx '// &
        'avx2 bmi2 avx512f avx512dq avx512cd avx512bw avx512vl avx512_fp16'
    character(len=*), parameter :: epyc_flags = 'fpu sse sse2 pni ssse3 fma sse4_1 avx f16c '// &
        'avx2 bmi2 sha_ni vaes'

contains

    !> Cases of the blas_kernel suite.
    subroutine collect_blas_kernel(tests)
        !> The cases
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('cpu_levels_from_flags', test_flags), &
                 new_test('kernel_levels_from_names', test_kernels), &
                 new_test('prescott_on_avx512', test_prescott_on_avx512), &
                 new_test('haswell_on_avx2', test_haswell_on_avx2), &
                 new_test('skylakex_on_avx512', test_skylakex_on_avx512), &
                 new_test('user_set_kernel_respected', test_user_set), &
                 new_test('rerun_ignored_warns_once', test_rerun_ignored), &
                 new_test('who_chose_the_kernel', test_choice), &
                 new_test('cpu_from_cpuinfo', test_cpuinfo)]
    end subroutine collect_blas_kernel

    subroutine test_flags(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, cpu_level_of_flags(xeon_flags) == isa_avx512, 'Xeon: AVX-512')
        call check(error, cpu_level_of_flags(epyc_flags) == isa_avx2, 'EPYC: AVX2')
        call check(error, cpu_level_of_flags('fpu sse sse2 avx') == isa_avx, 'AVX only')
        call check(error, cpu_level_of_flags('fpu sse sse2 pni') == isa_sse, 'SSE3')
        ! avx512f alone (Xeon Phi): OpenBLAS runs Haswell there, so AVX2.
        call check(error, cpu_level_of_flags('sse avx avx2 fma avx512f avx512cd') == isa_avx2, &
                   'avx512f without bw, vl, dq')
        ! Whole words only: 'avx2' must not be found in 'avx512f' or 'avx2x'.
        call check(error, cpu_level_of_flags('sse avx avx512f fma avx2x') == isa_avx, &
                   'flags are matched as words')
    end subroutine test_flags

    subroutine test_kernels(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, kernel_level('Prescott') == isa_sse, 'Prescott')
        call check(error, kernel_level('Nehalem') == isa_sse, 'Nehalem')
        call check(error, kernel_level('Sandybridge') == isa_avx, 'Sandybridge')
        call check(error, kernel_level('Haswell') == isa_avx2, 'Haswell')
        call check(error, kernel_level('ZEN') == isa_avx2, 'Zen, any case')
        call check(error, kernel_level('SkylakeX') == isa_avx512, 'SkylakeX')
        call check(error, kernel_level('unknown') == isa_unknown, 'unknown')
        call check(error, kernel_level('skx') == isa_unknown, 'a BLIS architecture')
    end subroutine test_kernels

    !> The node of issue 28: Debian 12's OpenBLAS on a Xeon with AVX-512.
    subroutine test_prescott_on_avx512(error)
        type(error_type), allocatable, intent(out) :: error
        type(kernel_advice) :: advice

        advice = advise_kernel(isa_avx512, 'Prescott', .true., '', '', .true.)
        call check(error, advice%action == advice_rerun, 'serial program: run again')
        call check(error, advice%core == 'SkylakeX', 'with SkylakeX: '//advice%core)
        advice = advise_kernel(isa_avx512, 'Prescott', .true., '', '', .false.)
        call check(error, advice%action == advice_warn, 'MPI program: warn')
        call check(error, index(advice%message, 'OPENBLAS_CORETYPE=SkylakeX') > 0, &
                   'the variable to set: '//advice%message)
        call check(error, index(advice%message, 'mpiexec -x OPENBLAS_CORETYPE=SkylakeX') > 0, &
                   'and how to pass it to MPI processes: '//advice%message)
        advice = advise_kernel(isa_avx512, 'Prescott', .false., '', '', .true.)
        call check(error, advice%action == advice_warn, 'no DYNAMIC_ARCH: warn')
        call check(error, index(advice%message, 'DYNAMIC_ARCH') > 0, 'say what to install')
        advice = advise_kernel(isa_avx2, 'Sandybridge', .true., '', '', .true.)
        call check(error, advice%action == advice_rerun .and. advice%core == 'Haswell', &
                   'AVX kernel on AVX2: Haswell')
    end subroutine test_prescott_on_avx512

    subroutine test_haswell_on_avx2(error)
        type(error_type), allocatable, intent(out) :: error
        type(kernel_advice) :: advice

        advice = advise_kernel(isa_avx2, 'Haswell', .true., '', '', .true.)
        call check(error, advice%action == advice_none, 'Haswell on AVX2: nothing to do')
        call check(error, len(advice%message) == 0, 'no message')
        advice = advise_kernel(isa_avx2, 'Zen', .true., '', '', .true.)
        call check(error, advice%action == advice_none, 'Zen on AVX2: nothing to do')
        advice = advise_kernel(isa_avx, 'Sandybridge', .true., '', '', .true.)
        call check(error, advice%action == advice_none, 'Sandybridge on AVX: nothing to do')
        advice = advise_kernel(isa_unknown, 'Prescott', .true., '', '', .true.)
        call check(error, advice%action == advice_none, 'no cpuinfo: no advice')
    end subroutine test_haswell_on_avx2

    subroutine test_skylakex_on_avx512(error)
        type(error_type), allocatable, intent(out) :: error
        type(kernel_advice) :: advice

        advice = advise_kernel(isa_avx512, 'SkylakeX', .true., '', '', .true.)
        call check(error, advice%action == advice_none, 'SkylakeX on AVX-512')
        advice = advise_kernel(isa_avx512, 'unknown', .true., '', '', .true.)
        call check(error, advice%action == advice_none, 'a kernel not known: no advice')
    end subroutine test_skylakex_on_avx512

    !> OPENBLAS_CORETYPE set by the user (scripts/test-kernels.sh runs the suites so): no
    !> re-run, no warning; a note.
    subroutine test_user_set(error)
        type(error_type), allocatable, intent(out) :: error
        type(kernel_advice) :: advice

        advice = advise_kernel(isa_avx512, 'Nehalem', .true., 'Nehalem', '', .true.)
        call check(error, advice%action == advice_note, 'a note only')
        call check(error, index(advice%message, 'OPENBLAS_CORETYPE=Nehalem') > 0 .and. &
                   index(advice%message, 'SkylakeX') > 0, advice%message)
        advice = advise_kernel(isa_avx2, 'Haswell', .true., 'Haswell', '', .true.)
        call check(error, advice%action == advice_none, 'a good kernel the user chose')
    end subroutine test_user_set

    !> ddc2d ran itself again with OPENBLAS_CORETYPE=SkylakeX and OpenBLAS still runs
    !> Prescott: warn, do not run again.
    subroutine test_rerun_ignored(error)
        type(error_type), allocatable, intent(out) :: error
        type(kernel_advice) :: advice

        advice = advise_kernel(isa_avx512, 'Prescott', .true., 'SkylakeX', 'Prescott', .true.)
        call check(error, advice%action == advice_warn, 'warn instead of a loop')
        call check(error, index(advice%message, 'ddc2d set OPENBLAS_CORETYPE=SkylakeX') > 0, &
                   advice%message)
        advice = advise_kernel(isa_avx512, 'SkylakeX', .true., 'SkylakeX', 'Prescott', .true.)
        call check(error, advice%action == advice_none, 'the re-run took: nothing to do')
    end subroutine test_rerun_ignored

    subroutine test_choice(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, kernel_choice('', '') == '', 'the BLAS chose')
        call check(error, kernel_choice('Nehalem', '') == 'the user (OPENBLAS_CORETYPE=Nehalem)', &
                   'the user chose')
        call check(error, kernel_choice('SkylakeX', 'Prescott') == 'ddc2d (OPENBLAS_CORETYPE='// &
                   'SkylakeX; OpenBLAS had chosen Prescott)', 'ddc2d chose')
    end subroutine test_choice

    !> Model name and flags of the first processor; tabs before the colons, as Linux writes.
    subroutine test_cpuinfo(error)
        type(error_type), allocatable, intent(out) :: error
        type(cpu_description) :: cpu
        character(len=*), parameter :: file = '/tmp/ddc2d_test_cpuinfo.txt'
        integer :: unit

        open (newunit=unit, file=file, status='replace', action='write')
        write (unit, '(a)') 'processor'//achar(9)//': 0'
        write (unit, '(a)') 'model name'//achar(9)//': Intel(R) Xeon(R) Platinum 8480+'
        write (unit, '(a)') 'flags'//achar(9)//achar(9)//': '//xeon_flags
        write (unit, '(a)') 'processor'//achar(9)//': 1'
        write (unit, '(a)') 'model name'//achar(9)//': another'
        write (unit, '(a)') 'flags'//achar(9)//achar(9)//': fpu sse'
        close (unit)
        cpu = describe_cpu(file)
        open (newunit=unit, file=file, status='old')
        close (unit, status='delete')
        call check(error, cpu%model == 'Intel(R) Xeon(R) Platinum 8480+', 'model: '//cpu%model)
        call check(error, cpu%level == isa_avx512, 'AVX-512 from the first processor')
        cpu = describe_cpu('/nonexistent/cpuinfo')
        call check(error, cpu%model == 'unknown' .and. cpu%level == isa_unknown, &
                   'no file: unknown')
    end subroutine test_cpuinfo

end module test_blas_kernel
