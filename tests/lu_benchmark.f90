!> `ddc2d_lu_benchmark N [REPEATS]`: the reference LU of docs/performance.md#the-benchmark.
!> Times one LAPACK DGETRF (partial pivoting, with row interchanges) of an N x N uniform random
!> matrix, linked to the same LAPACK as ddc2d, and prints `seconds <s> gflops <rate>` (the
!> fastest of REPEATS runs, default 1). scripts/benchmark.py calls it with N = 2 x elements. A
!> copy of the matrix is kept only for repeats (one N = 32000 matrix is 8 GB).
program ddc2d_lu_benchmark
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_linalg_lapack, only: dgetrf
    implicit none
    real(wp), allocatable :: a(:, :), a0(:, :)
    integer, allocatable :: ipiv(:)
    character(len=32) :: arg
    integer :: n, repeats, r, info
    integer(int64) :: t0, t1, rate
    real(wp) :: best

    if (command_argument_count() < 1) then
        write (*, '(a)') 'usage: ddc2d_lu_benchmark N [REPEATS]'
        error stop 2
    end if
    call get_command_argument(1, arg)
    read (arg, *) n
    repeats = 1
    if (command_argument_count() >= 2) then
        call get_command_argument(2, arg)
        read (arg, *) repeats
    end if
    allocate (a(n, n), ipiv(n))
    call random_number(a)
    a = a - 0.5_wp
    if (repeats > 1) a0 = a
    best = huge(1.0_wp)
    do r = 1, max(repeats, 1)
        if (r > 1) a = a0
        call system_clock(t0, rate)
        call dgetrf(n, n, a, n, ipiv, info)
        call system_clock(t1)
        best = min(best, real(t1 - t0, wp) / real(rate, wp))
    end do
    if (info /= 0) error stop 1
    write (*, '(a,es12.5,a,f10.3)') 'seconds ', best, ' gflops ', &
        2.0_wp / 3.0_wp * real(n, wp)**3 / best * 1.0e-9_wp
end program ddc2d_lu_benchmark
