!> How a result was computed, so that a figure can be traced to it: the BLAS
!> library and its kernel (and who chose it), the compiler and its options, the CPU model and
!> the thread counts. Written as root attributes of the result file (blas, blas_core,
!> blas_core_chosen_by, compiler, compiler_options, cpu, threads, blas_threads), the BLAS
!> pair also in /solver, and as one line of the run's summary.
module ddc_output_provenance
    use, intrinsic :: iso_fortran_env, only: compiler_version, compiler_options
    !$ use omp_lib, only: omp_get_max_threads
    use ddc_text, only: itoa
    use ddc_linalg_blas_library, only: blas_description, describe_blas
    use ddc_linalg_blas_kernel, only: cpu_description, describe_cpu, kernel_choice, &
        environment_value, coretype_variable, chosen_variable
    implicit none
    private

    public :: run_provenance, describe_run, provenance_line

    !> Where a result came from; every text non-empty ('unknown' when not known).
    type :: run_provenance
        !> The BLAS library as it describes itself, and its kernel
        character(len=:), allocatable :: blas, blas_core
        !> Who chose the kernel: 'the BLAS', 'the user (OPENBLAS_CORETYPE=...)' or 'ddc2d
        !> (OPENBLAS_CORETYPE=...; OpenBLAS had chosen ...)'
        character(len=:), allocatable :: blas_core_chosen_by
        !> compiler_version() and compiler_options() of iso_fortran_env
        character(len=:), allocatable :: compiler, options
        !> The CPU's model name
        character(len=:), allocatable :: cpu
        !> OpenMP threads and the BLAS's own threads (0: unknown)
        integer :: threads = 1, blas_threads = 0
    end type run_provenance

contains

    !> This run's provenance.
    function describe_run() result(p)
        !> The provenance
        type(run_provenance) :: p
        type(blas_description) :: blas
        type(cpu_description) :: cpu

        blas = describe_blas()
        cpu = describe_cpu()
        p%blas = blas%library
        p%blas_core = blas%core
        p%blas_core_chosen_by = kernel_choice(environment_value(coretype_variable), &
                                              environment_value(chosen_variable))
        if (len(p%blas_core_chosen_by) == 0) p%blas_core_chosen_by = 'the BLAS'
        p%compiler = compiler_version()
        p%options = compiler_options()
        p%cpu = cpu%model
        p%blas_threads = blas%threads
        p%threads = 1
        !$ p%threads = omp_get_max_threads()
    end function describe_run

    !> The summary's line: 'computed with BLAS ... (kernel ..., chosen by ...), compiler
    !> ... (options ...), CPU ..., T OpenMP thread(s), B BLAS thread(s)'.
    pure function provenance_line(p) result(line)
        !> The provenance
        type(run_provenance), intent(in) :: p
        character(len=:), allocatable :: line
        character(len=:), allocatable :: blas_threads

        blas_threads = 'unknown'
        if (p%blas_threads > 0) blas_threads = itoa(p%blas_threads)
        line = 'computed with BLAS '//p%blas//' (kernel '//p%blas_core//', chosen by '// &
            p%blas_core_chosen_by//'), compiler '//p%compiler//' ('//p%options//'), CPU '// &
            p%cpu//', '//itoa(p%threads)//' OpenMP thread(s), '//blas_threads// &
            ' BLAS thread(s)'
    end function provenance_line

end module ddc_output_provenance
