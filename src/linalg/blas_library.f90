!> The BLAS this process runs and the kernel it chose (OpenBLAS: openblas_get_config and
!> openblas_get_corename; BLIS: its version and the architecture it picked), and the one
!> way to change an OpenBLAS kernel after start-up: running the program again with
!> OPENBLAS_CORETYPE set (OpenBLAS reads it once, when it is loaded).
!>
!> The C side (blas_library.c) refers to those queries weakly, so that ddc2d links and
!> runs with any BLAS; another BLAS is described as family blas_other with empty strings.
module ddc_linalg_blas_library
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
    use ddc_text, only: from_c_chars
    implicit none
    private

    public :: blas_description, describe_blas, run_again_with, set_blas_threads
    public :: blas_other, blas_openblas, blas_blis

    !> BLAS families: another BLAS (no query known), OpenBLAS, BLIS
    integer, parameter :: blas_other = 0, blas_openblas = 1, blas_blis = 2

    !> Longest library description and kernel name kept [characters]
    integer, parameter :: text_size = 512

    !> The BLAS in use.
    type :: blas_description
        !> blas_other, blas_openblas or blas_blis
        integer :: family = blas_other
        !> The library as it describes itself (OpenBLAS: its configuration, e.g. 'OpenBLAS
        !> 0.3.21 DYNAMIC_ARCH NO_AFFINITY Zen MAX_THREADS=64'); 'unknown' for another BLAS
        character(len=:), allocatable :: library
        !> The kernel it runs (OpenBLAS core name, e.g. 'Haswell'; BLIS architecture);
        !> 'unknown' when it does not say
        character(len=:), allocatable :: core
        !> OpenBLAS built with DYNAMIC_ARCH: its kernel can be chosen with OPENBLAS_CORETYPE
        logical :: dynamic = .false.
        !> The BLAS's own threads (0: unknown)
        integer :: threads = 0
    end type blas_description

    interface
        function blas_query(library, library_size, core, core_size, threads) &
            bind(C, name='ddc2d_blas_query') result(family)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(out) :: library(*), core(*)
            integer(c_int), value :: library_size, core_size
            integer(c_int), intent(out) :: threads
            integer(c_int) :: family
        end function blas_query

        function blas_set_threads(threads) bind(C, name='ddc2d_blas_set_threads') &
            result(told)
            import :: c_int
            implicit none
            integer(c_int), value :: threads
            integer(c_int) :: told
        end function blas_set_threads

        function reexec_with(name, value, marker, marker_value) &
            bind(C, name='ddc2d_reexec_with') result(status)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: name(*), value(*), marker(*), &
                marker_value(*)
            integer(c_int) :: status
        end function reexec_with
    end interface

contains

    !> The BLAS this process runs.
    function describe_blas() result(blas)
        !> Its family, self-description, kernel and threads
        type(blas_description) :: blas
        character(kind=c_char) :: library(text_size), core(text_size)
        integer(c_int) :: threads

        blas%family = int(blas_query(library, text_size, core, text_size, threads))
        blas%threads = int(threads)
        blas%library = trim(from_c_chars(library))
        blas%core = trim(from_c_chars(core))
        if (len(blas%library) == 0) blas%library = 'unknown'
        if (len(blas%core) == 0) blas%core = 'unknown'
        blas%dynamic = blas%family == blas_openblas .and. &
            index(' '//blas%library//' ', ' DYNAMIC_ARCH ') > 0
    end function describe_blas

    !> Tell the BLAS how many threads to run; false where it cannot be told (not OpenBLAS).
    logical function set_blas_threads(threads) result(told)
        !> The threads, at least 1
        integer, intent(in) :: threads

        told = blas_set_threads(int(threads, c_int)) == 1
    end function set_blas_threads

    !> Run this program again from the start, with the same arguments and name=value (and
    !> marker=marker_value) in its environment. Returns only when that cannot be done.
    subroutine run_again_with(name, value, marker, marker_value)
        !> The variable to set and its value, e.g. OPENBLAS_CORETYPE, 'Haswell'
        character(len=*), intent(in) :: name, value
        !> A variable that tells the new process it was started this way, and its value
        character(len=*), intent(in) :: marker, marker_value
        integer(c_int) :: status

        status = reexec_with(name//c_null_char, value//c_null_char, marker//c_null_char, &
                             marker_value//c_null_char)
    end subroutine run_again_with

end module ddc_linalg_blas_library
