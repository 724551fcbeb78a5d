!> Placeholder, being written.
module ddc_solve_lapack
    implicit none
    private
end module ddc_solve_lapack
