!> The tester: `ddc2d_tester SUITE` runs one suite and exits non-zero on any failure.
program ddc2d_tester
    use ddc_testing, only: test_case, run_suite
    use test_kernel, only: collect_kernel
    implicit none
    type(test_case), allocatable :: tests(:)
    character(len=64) :: suite
    integer :: failures

    if (command_argument_count() /= 1) then
        write (*, '(a)') 'usage: ddc2d_tester SUITE'
        error stop 2
    end if
    call get_command_argument(1, suite)
    select case (trim(suite))
    case ('kernel')
        call collect_kernel(tests)
    case default
        write (*, '(a)') 'unknown suite: '//trim(suite)
        error stop 2
    end select

    failures = 0
    call run_suite(trim(suite), tests, failures)
    write (*, '(i0,a,i0,a)') size(tests) - failures, ' passed, ', failures, ' failed'
    if (failures > 0) error stop 1
end program ddc2d_tester
