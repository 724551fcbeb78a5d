!> Placeholder, being written.
module ddc_contact_lemke
    implicit none
    private
end module ddc_contact_lemke
