!> An embedded explicit Runge-Kutta pair with the first stage of a step the last of the one
!> before (FSAL) and the error control of a cycle run (docs/theory/cycles.md#the-integrator):
!> Dormand-Prince 5(4) (7 stages, 6 new per step).
!>
!> A step of size h from (t, y) with y' = F(t, y) takes the stages k_i = F(t + c_i h, y + h
!> sum_j a_ij k_j), advances y_new = y + h sum_i b_i k_i (the higher order) and estimates its
!> local error by e = h sum_i (b_i - bhat_i) k_i; the last stage is F(t + h, y_new). Its
!> error norm is max_i |e_i| / (tolerance scale_i): the step is accepted when it is at most
!> 1, and the next step is h min(5, max(0.2, 0.9 norm^(-1/(q+1)))) with q the lower order
!> (at most h after a rejection).
module ddc_cycle_runge_kutta
    use ddc_kinds, only: wp
    implicit none
    private

    public :: ode_system, embedded_pair, dormand_prince, attempt_step, next_step

    !> Most stages of a pair
    integer, parameter :: max_stages = 7

    !> A system y' = F(t, y) whose evaluation may fail (outside the domain of F).
    type, abstract :: ode_system
    contains
        !> F(t, y)
        procedure(rates_interface), deferred :: rates
    end type ode_system

    abstract interface
        !> dydt = F(t, y); failure > 0 where F is not defined at y (then dydt is not set).
        subroutine rates_interface(system, t, y, dydt, failure)
            import :: ode_system, wp
            implicit none
            !> The system
            class(ode_system), intent(inout) :: system
            !> Time
            real(wp), intent(in) :: t
            !> State, shape (n)
            real(wp), intent(in) :: y(:)
            !> Its rate, shape (n)
            real(wp), intent(out) :: dydt(:)
            !> 0, or a positive code of why F is not defined at y
            integer, intent(out) :: failure
        end subroutine rates_interface
    end interface

    !> An embedded pair: its tableau, with the last stage at (t + h, y_new).
    type :: embedded_pair
        !> Name, number of stages, lower order q
        character(len=16) :: name = ''
        integer :: stages = 0, lower_order = 0
        !> Nodes c; coefficients a; weights b of the higher order and the error weights b -
        !> bhat; the first `stages` of each dimension
        real(wp) :: c(max_stages) = 0.0_wp, a(max_stages, max_stages) = 0.0_wp, &
            b(max_stages) = 0.0_wp, e(max_stages) = 0.0_wp
    end type embedded_pair

contains

    !> Dormand & Prince (1980), RK5(4)7M.
    pure function dormand_prince() result(pair)
        type(embedded_pair) :: pair

        pair%name = 'dormand_prince'
        pair%stages = 7
        pair%lower_order = 4
        pair%c = [0.0_wp, 1.0_wp / 5.0_wp, 3.0_wp / 10.0_wp, 4.0_wp / 5.0_wp, 8.0_wp / 9.0_wp, &
                  1.0_wp, 1.0_wp]
        pair%a(2, 1) = 1.0_wp / 5.0_wp
        pair%a(3, 1:2) = [3.0_wp / 40.0_wp, 9.0_wp / 40.0_wp]
        pair%a(4, 1:3) = [44.0_wp / 45.0_wp, -56.0_wp / 15.0_wp, 32.0_wp / 9.0_wp]
        pair%a(5, 1:4) = [19372.0_wp / 6561.0_wp, -25360.0_wp / 2187.0_wp, &
                          64448.0_wp / 6561.0_wp, -212.0_wp / 729.0_wp]
        pair%a(6, 1:5) = [9017.0_wp / 3168.0_wp, -355.0_wp / 33.0_wp, 46732.0_wp / 5247.0_wp, &
                          49.0_wp / 176.0_wp, -5103.0_wp / 18656.0_wp]
        pair%b = [35.0_wp / 384.0_wp, 0.0_wp, 500.0_wp / 1113.0_wp, 125.0_wp / 192.0_wp, &
                  -2187.0_wp / 6784.0_wp, 11.0_wp / 84.0_wp, 0.0_wp]
        pair%a(7, 1:6) = pair%b(1:6)
        pair%e = pair%b - [5179.0_wp / 57600.0_wp, 0.0_wp, 7571.0_wp / 16695.0_wp, &
                           393.0_wp / 640.0_wp, -92097.0_wp / 339200.0_wp, 187.0_wp / 2100.0_wp, &
                           1.0_wp / 40.0_wp]
    end function dormand_prince

    !> One attempted step of size h from (t, y), whose rate first is F(t, y): the new state,
    !> its rate (the last stage) and the error norm; failure > 0 when a stage left the
    !> domain of F (then the step is to be rejected).
    subroutine attempt_step(pair, system, t, y, first, h, scale, tolerance, y_new, last, &
                            norm, failure, stages)
        !> The pair
        type(embedded_pair), intent(in) :: pair
        !> The system
        class(ode_system), intent(inout) :: system
        !> Time and step size
        real(wp), intent(in) :: t, h
        !> State and its rate at t, shape (n)
        real(wp), intent(in) :: y(:), first(:)
        !> The error scale of each component, shape (n), and the tolerance (relative to it)
        real(wp), intent(in) :: scale(:), tolerance
        !> State at t + h and its rate, shape (n)
        real(wp), intent(out) :: y_new(:), last(:)
        !> Error norm (at most 1: accept)
        real(wp), intent(out) :: norm
        !> 0, or the failure of the stage that left the domain
        integer, intent(out) :: failure
        !> Work space of the stages, shape (n, pair%stages)
        real(wp), intent(inout) :: stages(:, :)
        real(wp), allocatable :: trial(:)
        integer :: i, j

        norm = huge(1.0_wp)
        stages(:, 1) = first
        allocate (trial(size(y)))
        do i = 2, pair%stages
            trial = y
            do j = 1, i - 1
                if (pair%a(i, j) /= 0.0_wp) trial = trial + h * pair%a(i, j) * stages(:, j)
            end do
            call system%rates(t + pair%c(i) * h, trial, stages(:, i), failure)
            if (failure > 0) return
        end do
        ! The last stage is taken at y + h sum b_i k_i: the new state itself.
        y_new = trial
        last = stages(:, pair%stages)
        trial = 0.0_wp
        do j = 1, pair%stages
            if (pair%e(j) /= 0.0_wp) trial = trial + h * pair%e(j) * stages(:, j)
        end do
        norm = maxval(abs(trial) / scale) / tolerance
    end subroutine attempt_step

    !> The size of the next step after one of size h with the given error norm.
    pure real(wp) function next_step(pair, h, norm)
        !> The pair
        type(embedded_pair), intent(in) :: pair
        !> The step size taken and its error norm
        real(wp), intent(in) :: h, norm
        real(wp) :: factor

        if (norm <= 0.0_wp) then
            factor = 5.0_wp
        else
            factor = min(5.0_wp, max(0.2_wp, 0.9_wp * norm**(-1.0_wp / &
                                                         real(pair%lower_order + 1, wp))))
        end if
        if (norm > 1.0_wp) factor = min(factor, 1.0_wp)
        next_step = h * factor
    end function next_step

end module ddc_cycle_runge_kutta
