!> At start-up: is the BLAS kernel the best the BLAS has for this CPU
!> (docs/performance.md#the-blas-kernel)? The advice is ddc_linalg_blas_kernel's; here it is
!> carried out. The serial program runs itself again, once, with OPENBLAS_CORETYPE set (before
!> anything is printed or read; the new process is told so by DDC2D_OPENBLAS_CHOSE and does not
!> run itself again); the MPI program, whose processes the launcher started, warns with the
!> variable to set. A kernel the user chose is respected (a note in the echo), a run that cannot
!> be fixed warns on standard error. And its threads: one for a model of fewer than 4000
!> unknowns, unless the user set them (docs/performance.md#threads).
module ddc_app_blas
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use ddc_version, only: program_name
    use ddc_linalg_blas_library, only: blas_description, describe_blas, run_again_with, &
        set_blas_threads
    use ddc_text, only: itoa
    use ddc_linalg_blas_kernel, only: cpu_description, describe_cpu, kernel_advice, &
        advise_kernel, kernel_choice, environment_value, isa_name, coretype_variable, &
        chosen_variable, advice_note, advice_rerun, advice_warn
    implicit none
    private

    public :: check_blas_kernel, choose_blas_threads

    !> Unknowns of a model below which OpenBLAS runs one thread (docs/performance.md#threads):
    !> its solves are too short to share, and the second thread, waiting for a core (on a
    !> loaded machine, or beside the OpenMP threads), slowed every one of them
    integer, parameter :: shared_blas_min_unknowns = 4000

contains

    !> Check the kernel; run again with a better one when allowed (does not return then).
    subroutine check_blas_kernel(can_rerun, echo)
        !> This program may run itself again (the serial program)
        logical, intent(in) :: can_rerun
        !> The echo's lines about the BLAS, for the model echo
        character(len=:), allocatable, intent(out) :: echo
        type(blas_description) :: blas
        type(cpu_description) :: cpu
        type(kernel_advice) :: advice
        character(len=:), allocatable :: user_core, chosen, choice

        blas = describe_blas()
        cpu = describe_cpu()
        user_core = environment_value(coretype_variable)
        chosen = environment_value(chosen_variable)
        if (len(user_core) == 0) chosen = ''
        advice = advise_kernel(cpu%level, blas%core, blas%dynamic, user_core, chosen, &
                               can_rerun)
        if (advice%action == advice_rerun) then
            flush (output_unit)
            flush (error_unit)
            call run_again_with(coretype_variable, advice%core, chosen_variable, blas%core)
            advice = advise_kernel(cpu%level, blas%core, blas%dynamic, user_core, chosen, &
                                   .false.)
        end if
        choice = kernel_choice(user_core, chosen)
        if (len(choice) == 0) choice = 'the BLAS'
        echo = '  blas: '//blas%library//'; kernel '//blas%core//' (chosen by '//choice// &
            ') on '//cpu%model//' ('//isa_name(cpu%level)//')'
        if (advice%action == advice_note) echo = echo//new_line('a')//'    ('// &
            advice%message//')'
        if (advice%action == advice_warn) write (error_unit, '(a)') program_name// &
            ': warning: '//advice%message
    end subroutine check_blas_kernel

    !> One BLAS thread for a model of fewer than shared_blas_min_unknowns unknowns, unless
    !> the user set the BLAS's threads (OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS).
    subroutine choose_blas_threads(unknowns, echo)
        !> Unknowns of the model (two per element)
        integer, intent(in) :: unknowns
        !> The echo's line about the BLAS threads
        character(len=:), allocatable, intent(out) :: echo
        type(blas_description) :: blas

        blas = describe_blas()
        if (blas%threads == 0) then
            echo = '  blas threads: unknown (not OpenBLAS)'
            return
        end if
        echo = '  blas threads: '//itoa(blas%threads)
        if (len(environment_value('OPENBLAS_NUM_THREADS')) > 0 .or. &
            len(environment_value('GOTO_NUM_THREADS')) > 0) then
            echo = echo//' (OPENBLAS_NUM_THREADS)'
        else if (blas%threads > 1 .and. unknowns < shared_blas_min_unknowns) then
            if (set_blas_threads(1)) echo = '  blas threads: 1 ('//itoa(unknowns)// &
                ' unknowns, below '//itoa(shared_blas_min_unknowns)// &
                ': OPENBLAS_NUM_THREADS sets more)'
        end if
    end subroutine choose_blas_threads

end module ddc_app_blas
