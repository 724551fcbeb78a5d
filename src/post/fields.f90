!> Placeholder, being written.
module ddc_post_fields
    implicit none
    private
end module ddc_post_fields
