!> Placeholder, being written.
module ddc_influence_assembly
    implicit none
    private
end module ddc_influence_assembly
