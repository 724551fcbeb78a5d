!> Placeholder, being written.
module ddc_input_namelist
    implicit none
    private
end module ddc_input_namelist
