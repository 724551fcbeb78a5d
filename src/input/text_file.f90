!> Placeholder, being written.
module ddc_input_text_file
    implicit none
    private
end module ddc_input_text_file
