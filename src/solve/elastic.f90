!> Placeholder, being written.
module ddc_solve_elastic
    implicit none
    private
end module ddc_solve_elastic
