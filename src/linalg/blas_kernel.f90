!> Does the BLAS kernel fit the CPU? OpenBLAS picks its kernel from the CPU's model number
!> and falls back to an old one for a model it does not know: Debian 12's OpenBLAS runs
!> "Prescott" (SSE3) on recent Xeons with AVX-512, and LU(16000) takes 24.9 s there against
!> 4.13 s with OPENBLAS_CORETYPE=SkylakeX (docs/performance.md#the-blas-kernel). The instruction set
!> the CPU offers comes from the flags of /proc/cpuinfo, that of a kernel from its name:
!>
!>   level 0 SSE:     Katmai ... Prescott, Core2, Penryn, Dunnington, Nehalem, Atom, Athlon,
!>                    Opteron, Barcelona, Nano, Bobcat
!>   level 1 AVX:     Sandybridge, Bulldozer, Piledriver, Steamroller
!>   level 2 AVX2:    Haswell, Zen, Excavator
!>   level 3 AVX-512: SkylakeX, Cooperlake, SapphireRapids
!>
!> A kernel below level 2 on a CPU of level 2 or more is older than the CPU: the advice is
!> SkylakeX on AVX-512 (avx512f, bw, vl and dq), else Haswell. A kernel the user chose
!> (OPENBLAS_CORETYPE) is respected with a note; otherwise ddc2d runs itself again with
!> OPENBLAS_CORETYPE set (an OpenBLAS built with DYNAMIC_ARCH, a program that may), or warns
!> with the variable to set. Unknown names (other BLAS libraries, future kernels) get no
!> advice.
module ddc_linalg_blas_kernel
    use ddc_text, only: lower
    implicit none
    private

    public :: cpu_description, describe_cpu, cpu_level_of_flags, kernel_level, isa_name
    public :: kernel_advice, advise_kernel, kernel_choice, environment_value
    public :: isa_unknown, isa_sse, isa_avx, isa_avx2, isa_avx512
    public :: advice_none, advice_note, advice_rerun, advice_warn
    public :: coretype_variable, chosen_variable

    !> Instruction-set levels of CPUs and kernels
    integer, parameter :: isa_unknown = -1, isa_sse = 0, isa_avx = 1, isa_avx2 = 2, &
        isa_avx512 = 3
    !> What to do about the kernel: nothing; a note in the echo (the user's choice);
    !> run again with OPENBLAS_CORETYPE = advice%core; warn on standard error
    integer, parameter :: advice_none = 0, advice_note = 1, advice_rerun = 2, advice_warn = 3
    !> The variable OpenBLAS reads its kernel from, and the one ddc2d sets beside it when it
    !> runs itself again (its value: the kernel OpenBLAS had chosen)
    character(len=*), parameter :: coretype_variable = 'OPENBLAS_CORETYPE'
    character(len=*), parameter :: chosen_variable = 'DDC2D_OPENBLAS_CHOSE'

    !> The CPU this process runs on.
    type :: cpu_description
        !> Model name of /proc/cpuinfo ('unknown' when there is none)
        character(len=:), allocatable :: model
        !> Its instruction-set level (isa_*)
        integer :: level = isa_unknown
    end type cpu_description

    !> The advice on a kernel.
    type :: kernel_advice
        !> advice_none, advice_note, advice_rerun or advice_warn
        integer :: action = advice_none
        !> The kernel to use ('' with advice_none)
        character(len=:), allocatable :: core
        !> What to tell the user ('' with advice_none)
        character(len=:), allocatable :: message
    end type kernel_advice

contains

    !> The CPU's model name and instruction-set level, from the first processor of a
    !> cpuinfo file (default /proc/cpuinfo; level isa_unknown when it cannot be read).
    function describe_cpu(file) result(cpu)
        !> The file to read (tests)
        character(len=*), intent(in), optional :: file
        !> The CPU
        type(cpu_description) :: cpu
        character(len=8192) :: line
        character(len=:), allocatable :: path
        integer :: unit, stat, colon, k
        logical :: flags_found

        path = '/proc/cpuinfo'
        if (present(file)) path = file
        cpu%model = 'unknown'
        flags_found = .false.
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            ! 'model name<TAB>: ...'
            do k = 1, len_trim(line)
                if (line(k:k) == achar(9)) line(k:k) = ' '
            end do
            colon = index(line, ':')
            if (colon == 0) cycle
            if (trim(line(:colon - 1)) == 'model name' .and. cpu%model == 'unknown') then
                cpu%model = trim(adjustl(line(colon + 1:)))
            else if (trim(line(:colon - 1)) == 'flags' .and. .not. flags_found) then
                cpu%level = cpu_level_of_flags(line(colon + 1:))
                flags_found = .true.
            end if
            if (flags_found .and. cpu%model /= 'unknown') exit
        end do
        close (unit)
    end function describe_cpu

    !> The instruction-set level of a CPU from its flags (space-separated, as cpuinfo).
    pure integer function cpu_level_of_flags(flags)
        !> The flags, e.g. 'fpu sse sse2 avx avx2 fma'
        character(len=*), intent(in) :: flags

        cpu_level_of_flags = isa_sse
        if (has('avx')) cpu_level_of_flags = isa_avx
        if (has('avx2') .and. has('fma')) cpu_level_of_flags = isa_avx2
        if (cpu_level_of_flags == isa_avx2 .and. has('avx512f') .and. has('avx512bw') .and. &
            has('avx512vl') .and. has('avx512dq')) cpu_level_of_flags = isa_avx512

    contains

        pure logical function has(flag)
            character(len=*), intent(in) :: flag

            has = index(' '//flags//' ', ' '//flag//' ') > 0
        end function has

    end function cpu_level_of_flags

    !> The instruction-set level of an OpenBLAS kernel (isa_unknown for a name not known).
    pure integer function kernel_level(core)
        !> The kernel's name, as openblas_get_corename gives it (any case)
        character(len=*), intent(in) :: core

        select case (lower(trim(core)))
        case ('katmai', 'coppermine', 'northwood', 'prescott', 'banias', 'atom', 'core2', &
              'penryn', 'dunnington', 'nehalem', 'athlon', 'opteron', 'opteron_sse3', &
              'barcelona', 'nano', 'bobcat')
            kernel_level = isa_sse
        case ('sandybridge', 'bulldozer', 'piledriver', 'steamroller')
            kernel_level = isa_avx
        case ('haswell', 'zen', 'excavator')
            kernel_level = isa_avx2
        case ('skylakex', 'cooperlake', 'sapphirerapids')
            kernel_level = isa_avx512
        case default
            kernel_level = isa_unknown
        end select
    end function kernel_level

    !> The name of an instruction-set level.
    pure function isa_name(level) result(name)
        !> isa_*
        integer, intent(in) :: level
        character(len=:), allocatable :: name

        select case (level)
        case (isa_sse)
            name = 'SSE'
        case (isa_avx)
            name = 'AVX'
        case (isa_avx2)
            name = 'AVX2'
        case (isa_avx512)
            name = 'AVX-512'
        case default
            name = 'unknown'
        end select
    end function isa_name

    !> What to do about the kernel `core` on a CPU of level `cpu_level`.
    pure function advise_kernel(cpu_level, core, dynamic, user_core, chosen, can_rerun) &
        result(advice)
        !> The CPU's instruction-set level (isa_*)
        integer, intent(in) :: cpu_level
        !> The kernel in use
        character(len=*), intent(in) :: core
        !> The BLAS takes OPENBLAS_CORETYPE (OpenBLAS built with DYNAMIC_ARCH)
        logical, intent(in) :: dynamic
        !> OPENBLAS_CORETYPE as found ('' when not set)
        character(len=*), intent(in) :: user_core
        !> The kernel OpenBLAS had chosen when ddc2d ran itself again with
        !> OPENBLAS_CORETYPE set ('' when it did not)
        character(len=*), intent(in) :: chosen
        !> This program may run itself again (not under MPI)
        logical, intent(in) :: can_rerun
        !> The advice
        type(kernel_advice) :: advice
        character(len=:), allocatable :: best, what

        advice%core = ''
        advice%message = ''
        if (kernel_level(core) == isa_unknown .or. kernel_level(core) >= isa_avx2 .or. &
            cpu_level < isa_avx2) return
        best = 'Haswell'
        if (cpu_level >= isa_avx512) best = 'SkylakeX'
        advice%core = best
        what = 'OpenBLAS runs its '//trim(core)//' kernel ('//isa_name(kernel_level(core))// &
            ') on this '//isa_name(cpu_level)//' CPU'
        if (len(chosen) > 0) then
            advice%action = advice_warn
            advice%message = what//' although ddc2d set '//coretype_variable//'='// &
                trim(user_core)//' (OpenBLAS had chosen '//trim(chosen)//'): dense linear '// &
                'algebra runs up to 3x slower; use an OpenBLAS that knows this CPU'
        else if (len(user_core) > 0) then
            advice%action = advice_note
            advice%message = coretype_variable//'='//trim(user_core)//' is the user''s '// &
                'choice; this CPU could run '//best
        else if (.not. dynamic) then
            advice%action = advice_warn
            advice%message = what//', the only one this OpenBLAS was built for: dense '// &
                'linear algebra runs up to 3x slower; use an OpenBLAS built with '// &
                'DYNAMIC_ARCH (Debian: libopenblas0-pthread) or for this CPU'
        else if (can_rerun) then
            advice%action = advice_rerun
            advice%message = what//': running again with '//coretype_variable//'='//best
        else
            advice%action = advice_warn
            advice%message = what//': dense linear algebra runs up to 3x slower; set '// &
                coretype_variable//'='//best//' (export '//coretype_variable//'='//best// &
                '; with Open MPI: mpiexec -x '//coretype_variable//'='//best//')'
        end if
    end function advise_kernel

    !> Who chose the kernel: '' (the BLAS itself), 'the user (OPENBLAS_CORETYPE=...)' or
    !> 'ddc2d (OPENBLAS_CORETYPE=...; OpenBLAS had chosen ...)'.
    pure function kernel_choice(user_core, chosen) result(choice)
        !> OPENBLAS_CORETYPE and the kernel OpenBLAS had chosen before ddc2d set it ('' each
        !> when not set)
        character(len=*), intent(in) :: user_core, chosen
        character(len=:), allocatable :: choice

        choice = ''
        if (len(user_core) == 0) return
        if (len(chosen) > 0) then
            choice = 'ddc2d ('//coretype_variable//'='//user_core//'; OpenBLAS had chosen '// &
                chosen//')'
        else
            choice = 'the user ('//coretype_variable//'='//user_core//')'
        end if
    end function kernel_choice

    !> The value of an environment variable ('' when it is not set).
    function environment_value(name) result(value)
        !> The variable
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: value
        integer :: length, stat

        call get_environment_variable(name, length=length, status=stat)
        allocate (character(len=max(length, 0)) :: value)
        if (stat /= 0 .or. length == 0) then
            value = ''
            return
        end if
        call get_environment_variable(name, value)
        value = trim(value)
    end function environment_value

end module ddc_linalg_blas_kernel
