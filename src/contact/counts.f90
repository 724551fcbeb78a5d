!> What the factorizations of a solve cost (docs/theory/contact.md#the-newton-active-set-method):
!> the counts of the Newton method's reduced systems (new LU factorizations, low-rank updates of
!> kept factors, reuses of unchanged factors, bases extended by bordering), the wall time of
!> the factorizations and updates and their nominal flops (2/3 m^3 per LU of size m; 2 m^3
!> for the inverse of A of Lemke's method).
!> One type, held by the factors (ddc_contact_reduced_factors), the stiffness operator, the
!> contact result and the solver record (ddc_model_results), so that a new counter is
!> added here only: every copy assigns the whole type, every sum calls add and every
!> difference (what one solve did to counts kept over many) calls since.
module ddc_contact_counts
    use ddc_kinds, only: wp
    implicit none
    private

    public :: factor_counts, since

    !> Counts, time and flops of factorizations; a sum over solves by add.
    type :: factor_counts
        !> New LU factorizations, low-rank updates, reuses of unchanged factors, bases
        !> extended by bordering their factors (a growth run's accepted geometry)
        integer :: factorizations = 0, updates = 0, reuses = 0, borderings = 0
        !> Wall time of the factorizations and updates [s]
        real(wp) :: seconds = 0.0_wp
        !> Nominal flops of the factorizations [-]
        real(wp) :: flops = 0.0_wp
    contains
        !> this = this + other, counter by counter
        procedure :: add
    end type factor_counts

contains

    !> this = this + other, counter by counter.
    elemental subroutine add(this, other)
        !> The sum
        class(factor_counts), intent(inout) :: this
        !> What is added
        type(factor_counts), intent(in) :: other

        this%factorizations = this%factorizations + other%factorizations
        this%updates = this%updates + other%updates
        this%reuses = this%reuses + other%reuses
        this%borderings = this%borderings + other%borderings
        this%seconds = this%seconds + other%seconds
        this%flops = this%flops + other%flops
    end subroutine add

    !> now - before, counter by counter: what was counted in between.
    elemental type(factor_counts) function since(now, before)
        !> The counts now, and as they were before
        type(factor_counts), intent(in) :: now, before

        since%factorizations = now%factorizations - before%factorizations
        since%updates = now%updates - before%updates
        since%reuses = now%reuses - before%reuses
        since%borderings = now%borderings - before%borderings
        since%seconds = now%seconds - before%seconds
        since%flops = now%flops - before%flops
    end function since

end module ddc_contact_counts
