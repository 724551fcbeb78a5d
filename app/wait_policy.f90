!> How the OpenMP threads wait for work (docs/performance.md#threads). OpenBLAS runs threads
!> of its own beside OpenMP's; under libgomp's default an OpenMP thread spins for a while
!> after each parallel region, on the core an OpenBLAS thread needs for the factorization or
!> solve that follows. Growth runs, which alternate short parallel loops and small solves,
!> ran 4 times slower on 2 threads than on 1 that way, and tens of times slower on a loaded
!> machine (the other half of the remedy: ddc_app_blas's one BLAS thread for a small model).
!> libgomp reads OMP_WAIT_POLICY once, when the program is loaded: the serial program with
!> more than one thread runs itself again, once, with OMP_WAIT_POLICY=PASSIVE, before
!> anything is printed or read (the new process is told so by DDC2D_SET_WAIT_POLICY). Not where the
!> user chose (OMP_WAIT_POLICY or GOMP_SPINCOUNT set), in the MPI program (its launcher
!> started its processes) or under valgrind (whose tool would be run again instead).
module ddc_app_wait_policy
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use omp_lib, only: omp_get_max_threads
    use ddc_text, only: itoa
    use ddc_linalg_blas_library, only: run_again_with
    use ddc_linalg_blas_kernel, only: environment_value
    implicit none
    private

    public :: check_wait_policy

    !> The variables libgomp reads, and the one ddc2d sets beside the first when it runs
    !> itself again
    character(len=*), parameter :: policy_variable = 'OMP_WAIT_POLICY', &
        spin_variable = 'GOMP_SPINCOUNT', set_variable = 'DDC2D_SET_WAIT_POLICY'

contains

    !> Run again with the threads waiting asleep where allowed (does not return then).
    subroutine check_wait_policy(can_rerun, echo)
        !> This program may run itself again (the serial program)
        logical, intent(in) :: can_rerun
        !> The echo's line about the OpenMP threads, for the model echo
        character(len=:), allocatable, intent(out) :: echo
        character(len=:), allocatable :: policy, spin
        integer :: threads

        threads = omp_get_max_threads()
        policy = environment_value(policy_variable)
        spin = environment_value(spin_variable)
        if (can_rerun .and. threads > 1 .and. len(policy) == 0 .and. len(spin) == 0 .and. &
            .not. under_valgrind()) then
            flush (output_unit)
            flush (error_unit)
            call run_again_with(policy_variable, 'PASSIVE', set_variable, 'yes')
        end if
        echo = '  openmp: '//itoa(threads)//' thread(s)'
        if (threads == 1) return
        if (len(environment_value(set_variable)) > 0 .and. policy == 'PASSIVE') then
            echo = echo//', waiting asleep (OMP_WAIT_POLICY=PASSIVE, set by ddc2d)'
        else if (len(policy) > 0 .or. len(spin) > 0) then
            echo = echo//', waiting as the user chose ('// &
                trim(adjustl(setting(policy_variable, policy)//' '// &
                             setting(spin_variable, spin)))//')'
        else
            echo = echo//', spinning after each parallel region (libgomp''s default; '// &
                policy_variable//'=PASSIVE leaves the cores to the BLAS threads)'
        end if
    end subroutine check_wait_policy

    !> name=value where the value is set, else ''.
    pure function setting(name, value) result(text)
        character(len=*), intent(in) :: name, value
        character(len=:), allocatable :: text

        text = ''
        if (len(value) > 0) text = name//'='//value
    end function setting

    !> Whether this process runs under valgrind (its preloaded core library).
    logical function under_valgrind()
        under_valgrind = index(environment_value('LD_PRELOAD'), 'vgpreload') > 0
    end function under_valgrind

end module ddc_app_wait_policy
