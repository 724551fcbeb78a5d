!> The tester: `ddc2d_tester SUITE` runs one suite and exits non-zero on any failure.
program ddc2d_tester
    use ddc_testing, only: test_case, run_suite
    use test_output, only: collect_output
    use test_kernel, only: collect_kernel
    use test_half_plane_kernel, only: collect_half_plane_kernel
    use test_half_plane, only: collect_half_plane
    use test_input, only: collect_input
    use test_mesh, only: collect_mesh
    use test_lemke, only: collect_lemke
    use test_contact, only: collect_contact
    use test_crack, only: collect_crack
    use test_fields, only: collect_fields
    use test_twodd_reference, only: collect_twodd_reference
    use test_hole, only: collect_hole
    use test_threads, only: collect_threads
    use test_frictional, only: collect_frictional
    use test_twodd_deck, only: collect_twodd_deck
    use test_fast_contact, only: collect_fast_contact
    use test_sweep, only: collect_sweep
    use test_history, only: collect_history
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
    case ('half_plane_kernel')
        call collect_half_plane_kernel(tests)
    case ('half_plane')
        call collect_half_plane(tests)
    case ('input')
        call collect_input(tests)
    case ('mesh')
        call collect_mesh(tests)
    case ('crack')
        call collect_crack(tests)
    case ('fields')
        call collect_fields(tests)
    case ('output')
        call collect_output(tests)
    case ('lemke')
        call collect_lemke(tests)
    case ('twodd_reference')
        call collect_twodd_reference(tests)
    case ('hole')
        call collect_hole(tests)
    case ('threads')
        call collect_threads(tests)
    case ('contact')
        call collect_contact(tests)
    case ('frictional')
        call collect_frictional(tests)
    case ('twodd_deck')
        call collect_twodd_deck(tests)
    case ('fast_contact')
        call collect_fast_contact(tests)
    case ('sweep')
        call collect_sweep(tests)
    case ('history')
        call collect_history(tests)
    case default
        write (*, '(a)') 'unknown suite: '//trim(suite)
        error stop 2
    end select

    failures = 0
    call run_suite(trim(suite), tests, failures)
    write (*, '(i0,a,i0,a)') size(tests) - failures, ' passed, ', failures, ' failed'
    if (failures > 0) error stop 1
end program ddc2d_tester
