!> Anderson acceleration of a fixed-point iteration x = G(x) (Walker & Ni 2011, the
!> "type II" form): the next iterate is G's last value less the combination of its last
!> few changes whose residual changes best cancel the last residual G(x) - x (least
!> squares). Where plain iteration converges slowly or alternates, this converges in far
!> fewer evaluations of G.
module ddc_linalg_anderson
    use ddc_kinds, only: wp
    implicit none
    private

    public :: anderson_mixer

    !> A column of changes smaller than this fraction of the residual's scale adds nothing
    !> but round-off to the least-squares problem and is left out
    real(wp), parameter :: dependence_tolerance = 1.0e-10_wp

    !> The history of one iteration.
    type :: anderson_mixer
        private
        !> Changes kept (the depth of the history)
        integer :: depth = 4
        !> Changes held now
        integer :: count = 0
        !> The last G(x) and residual G(x) - x
        real(wp), allocatable :: last_g(:), last_r(:)
        !> Changes of G and of the residual between successive iterates, newest last,
        !> shape (size of x, depth)
        real(wp), allocatable :: dg(:, :), dr(:, :)
    contains
        procedure :: next
    end type anderson_mixer

contains

    !> The next iterate from the current one x and G(x).
    pure subroutine next(this, x, g)
        !> The iteration's history
        class(anderson_mixer), intent(inout) :: this
        !> The current iterate on entry, the next on exit
        real(wp), intent(inout) :: x(:)
        !> G(x)
        real(wp), intent(in) :: g(:)
        real(wp) :: r(size(x)), q(size(x), this%depth), rr(this%depth, this%depth)
        real(wp) :: gamma(this%depth), rhs(this%depth), scale
        integer :: used(this%depth), n, k, l

        r = g - x
        if (.not. allocated(this%dg)) then
            allocate (this%dg(size(x), this%depth), this%dr(size(x), this%depth))
        else
            if (this%count == this%depth) then
                this%dg(:, :this%depth - 1) = this%dg(:, 2:)
                this%dr(:, :this%depth - 1) = this%dr(:, 2:)
                this%count = this%count - 1
            end if
            this%count = this%count + 1
            this%dg(:, this%count) = g - this%last_g
            this%dr(:, this%count) = r - this%last_r
        end if
        this%last_g = g
        this%last_r = r
        x = g
        if (this%count == 0) return
        ! Least squares min |r - dr gamma| by modified Gram-Schmidt on the columns of dr,
        ! a column (nearly) in the span of those before it left out.
        scale = max(norm2(r), tiny(1.0_wp))
        n = 0
        do k = 1, this%count
            q(:, n + 1) = this%dr(:, k)
            do l = 1, n
                rr(l, n + 1) = dot_product(q(:, l), q(:, n + 1))
                q(:, n + 1) = q(:, n + 1) - rr(l, n + 1) * q(:, l)
            end do
            rr(n + 1, n + 1) = norm2(q(:, n + 1))
            if (rr(n + 1, n + 1) <= dependence_tolerance * scale) cycle
            q(:, n + 1) = q(:, n + 1) / rr(n + 1, n + 1)
            n = n + 1
            used(n) = k
        end do
        if (n == 0) return
        rhs(:n) = matmul(r, q(:, :n))
        do k = n, 1, -1
            gamma(k) = (rhs(k) - dot_product(rr(k, k + 1:n), gamma(k + 1:n))) / rr(k, k)
        end do
        do k = 1, n
            x = x - gamma(k) * this%dg(:, used(k))
        end do
    end subroutine next

end module ddc_linalg_anderson
