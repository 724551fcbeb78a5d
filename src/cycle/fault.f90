!> The rate-and-state faults of a cycle run as the system its integrator advances
!> (docs/theory/cycles.md#the-equations): the state y = [slip; psi] of the m rate-and-state
!> elements and its rate. At time t each element's tractions are
!>
!>     shear  t_s = tau0 + (A [ds; 0])_s,     ds = slip - V_p t   (back-slip),
!>     sigma     = sigma0 - (A [ds; 0])_n     (effective normal stress, compression positive),
!>
!> the product by the elastic operator of the contact run (its contact elements are the
!> rate-and-state elements); the slip rate balances the driving stress -t_s against friction
!> and radiation damping (ddc_cycle_friction), and psi evolves by the state law. Where some
!> sigma is not positive the rate is undefined (failure: the element).
module ddc_cycle_fault
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set
    use ddc_model_cycles, only: cycle_options, radiation_damping_of
    use ddc_model_rate_state, only: rate_state_table, rate_state_count, rs_a, rs_b, rs_dc, &
        rs_f0, rs_v0, rs_v_init, rs_sigma0, rs_tau0
    use ddc_solve_operator, only: elastic_operator
    use ddc_cycle_friction, only: slip_rate, state_rate, initial_state
    use ddc_cycle_runge_kutta, only: ode_system
    implicit none
    private

    public :: rate_state_fault, new_fault

    !> The rate-and-state elements, their law and the operator of their products.
    type, extends(ode_system) :: rate_state_fault
        !> Number of rate-and-state elements
        integer :: m = 0
        !> Their values (ddc_model_rate_state): a, b, f0 [-], L [length], V0 [length / time],
        !> sigma0, tau0 [stress], shape (m)
        real(wp), allocatable :: a(:), b(:), f0(:), dc(:), v0(:), sigma0(:), tau0(:)
        !> Radiation damping [stress time / length], plate rate [length / time]
        real(wp) :: eta = 0.0_wp, plate_rate = 0.0_wp
        !> state_law_aging or state_law_slip
        integer :: law = 0
        !> The operator of the run (its contact elements are these elements, in order)
        class(elastic_operator), pointer :: operator => null()
        !> Of the last evaluation: slip rate [length / time], shear traction and effective
        !> normal stress [stress], shape (m) (the slip rates are the next Newton guesses)
        real(wp), allocatable :: v(:), shear(:), sigma(:)
        !> Products and Newton iterations so far
        integer :: products = 0
        integer(int64) :: newton_iterations = 0
    contains
        procedure :: rates => fault_rates
        procedure :: initial
    end type rate_state_fault

contains

    !> The fault of the rate-and-state elements `rows` of a set of elements, for a cycle
    !> run's options, on an operator whose contact elements they are.
    function new_fault(elements, rows, options, shear_modulus, operator) result(fault)
        !> The elements with their rate-and-state values
        type(element_set), intent(in) :: elements
        !> The rate-and-state elements, in the order of the operator's contact elements,
        !> shape (m)
        integer, intent(in) :: rows(:)
        !> The cycle run's options
        type(cycle_options), intent(in) :: options
        !> Shear modulus [stress unit] (the radiation damping of a shear wave speed)
        real(wp), intent(in) :: shear_modulus
        !> The operator (it must outlive the fault)
        class(elastic_operator), intent(in), target :: operator
        type(rate_state_fault) :: fault
        real(wp), allocatable :: table(:, :)

        ! Allocated first: gfortran -Og warns of the descriptor of a bare assignment here.
        allocate (table(size(rows), rate_state_count))
        table = rate_state_table(elements, rows)
        fault%m = size(rows)
        fault%a = table(:, rs_a)
        fault%b = table(:, rs_b)
        fault%dc = table(:, rs_dc)
        fault%f0 = table(:, rs_f0)
        fault%v0 = table(:, rs_v0)
        fault%sigma0 = table(:, rs_sigma0)
        fault%tau0 = table(:, rs_tau0)
        fault%eta = radiation_damping_of(options, shear_modulus)
        fault%plate_rate = options%plate_rate
        fault%law = options%state_law
        fault%operator => operator
        fault%v = table(:, rs_v_init)
        fault%shear = fault%tau0
        fault%sigma = fault%sigma0
    end function new_fault

    !> The state at time 0: no slip, and each element's psi from its v_init and tau0
    !> (docs/theory/cycles.md#initial-state), shape (2 m).
    pure function initial(fault, v_init) result(y)
        !> The fault
        class(rate_state_fault), intent(in) :: fault
        !> The initial slip rate of each element [length / time], shape (m)
        real(wp), intent(in) :: v_init(:)
        real(wp) :: y(2 * fault%m)

        y(:fault%m) = 0.0_wp
        y(fault%m + 1:) = initial_state(v_init, -fault%tau0, fault%sigma0, fault%eta, &
                                        fault%a, fault%b, fault%f0, fault%v0)
    end function initial

    !> [dslip/dt; dpsi/dt] at (t, y); failure is the first element whose effective normal
    !> stress is not positive.
    subroutine fault_rates(system, t, y, dydt, failure)
        class(rate_state_fault), intent(inout) :: system
        real(wp), intent(in) :: t
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: dydt(:)
        integer, intent(out) :: failure
        real(wp) :: traction(2 * system%m), guess(system%m)
        integer :: iterations(system%m)

        associate (m => system%m, f => system)
            traction = 0.0_wp
            call f%operator%multiply_shear(y(:m) - f%plate_rate * t, traction)
            f%products = f%products + 1
            f%sigma = f%sigma0 - traction(m + 1:)
            failure = findloc(f%sigma > 0.0_wp, .false., 1)
            if (failure > 0) return
            f%shear = f%tau0 + traction(:m)
            ! The driving stress is -t_s: a shear traction (tension positive) drives a slip
            ! ds of the opposite sign. The last slip rates are the guesses. (Serial: a
            ! thread team's barrier at every stage costs more than these few iterations.)
            guess = f%v
            call slip_rate(-f%shear, f%sigma, f%eta, y(m + 1:), f%a, f%b, f%f0, f%v0, guess, &
                           f%v, iterations)
            f%newton_iterations = f%newton_iterations + sum(iterations)
            dydt(:m) = f%v
            dydt(m + 1:) = state_rate(f%law, f%v, y(m + 1:), f%dc, f%v0)
        end associate
    end subroutine fault_rates

end module ddc_cycle_fault
