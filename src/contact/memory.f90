!> Working memory of the contact methods on n contact elements, beyond the influence
!> matrix A they are given (2n x 2n), counted from what they allocate at once:
!> - Lemke (the paper's LCP): build_contact_lcp keeps C = A^-1 and a copy of A (2n x 2n
!>   each) and M, M scaled (3n x 3n each); solve_lcp_lemke adds its basis inverse and, to
!>   refine the solution, the basis matrix (3n x 3n each); with one n x n temporary, 45 n^2
!>   reals. (What a built LCP keeps between the steps of a loading history, 26 n^2, and
!>   the Newton factors beside it stay below that.)
!> - Newton (active set): the LU factors of the reduced system, m x m with m at most 2n
!>   (every element slipping and open; an all-slip fault needs n x n), and the arrays of a
!>   low-rank update of them (ddc_contact_reduced_factors: at most 3 m x m / 8 while one is
!>   formed), 1.375 m^2 reals: 5.5 n^2 at the largest. The method stops with
!>   exit_out_of_memory when its states ask for a reduced system larger than the memory
!>   left (ddc_contact_active_set).
!> Vectors of length n are counted as 60 n reals for either.
module ddc_contact_memory
    use ddc_kinds, only: wp
    use ddc_allocation, only: real_size => real_bytes
    implicit none
    private

    public :: lemke_bytes, newton_bytes

    !> Reals of the vectors of either method, per element
    real(wp), parameter :: vector_reals = 60.0_wp

contains

    !> Peak working memory of Lemke's method on the paper's LCP [bytes].
    pure real(wp) function lemke_bytes(n)
        !> Number of contact elements
        integer, intent(in) :: n

        lemke_bytes = real_size * (45.0_wp * real(n, wp)**2 + vector_reals * real(n, wp))
    end function lemke_bytes

    !> Peak working memory of the active-set Newton method: its reduced system of m
    !> unknowns and a low-rank update of it [bytes].
    pure real(wp) function newton_bytes(n, unknowns)
        !> Number of contact elements
        integer, intent(in) :: n
        !> Unknowns m of the reduced system (default 2n, the largest: every element slipping
        !> and open)
        integer, intent(in), optional :: unknowns
        real(wp) :: m

        m = 2.0_wp * real(n, wp)
        if (present(unknowns)) m = real(unknowns, wp)
        newton_bytes = real_size * (1.375_wp * m**2 + vector_reals * real(n, wp))
    end function newton_bytes

end module ddc_contact_memory
