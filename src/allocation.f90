!> The one message of a failed allocation: what could not be allocated and how much memory
!> it needed, with the exit code exit_out_of_memory. Every allocate of a matrix, a history
!> or the input's own data (file text, observation points) passes stat= and turns a failure
!> into this error; the vectors of one value per element or point are covered by the
!> memory estimate checked before the solve (ddc_run_memory), which counts them.
module ddc_allocation
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_out_of_memory
    use ddc_text, only: bytes_text
    implicit none
    private

    public :: allocation_failed, real_bytes, integer_bytes

    !> Bytes of one real(wp) and of one default integer
    real(wp), parameter :: real_bytes = real(storage_size(1.0_wp) / 8, wp)
    real(wp), parameter :: integer_bytes = real(storage_size(1) / 8, wp)

contains

    !> The error of a failed allocation: "not enough memory for <what> (<size>)".
    subroutine allocation_failed(error, what, bytes)
        !> The error to create (exit_out_of_memory)
        type(error_type), allocatable, intent(out) :: error
        !> What was being allocated, e.g. 'the influence matrix of 20000 elements'
        character(len=*), intent(in) :: what
        !> Its size [bytes]
        real(wp), intent(in) :: bytes

        call set_error(error, exit_out_of_memory, 'not enough memory for '//what//' ('// &
                       bytes_text(bytes)//'); see the size guide in docs/performance.md#size-guide')
    end subroutine allocation_failed

end module ddc_allocation
