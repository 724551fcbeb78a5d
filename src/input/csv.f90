!> Placeholder, being written.
module ddc_input_csv
    implicit none
    private
end module ddc_input_csv
