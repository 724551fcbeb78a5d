!> Placeholder, being written.
module ddc_mesh_polyline
    implicit none
    private
end module ddc_mesh_polyline
