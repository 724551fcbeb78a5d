!> Placeholder, being written.
module ddc_output_hdf5
    implicit none
    private
end module ddc_output_hdf5
