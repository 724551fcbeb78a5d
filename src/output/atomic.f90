!> Placeholder, being written.
module ddc_output_atomic
    implicit none
    private
end module ddc_output_atomic
