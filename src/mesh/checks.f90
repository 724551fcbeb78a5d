!> Placeholder, being written.
module ddc_mesh_checks
    implicit none
    private
end module ddc_mesh_checks
