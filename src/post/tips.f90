!> Placeholder, being written.
module ddc_post_tips
    implicit none
    private
end module ddc_post_tips
