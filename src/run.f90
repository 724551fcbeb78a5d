!> Placeholder, being written.
module ddc_run
    implicit none
    private
end module ddc_run
