!> The local K re-solve's coupled solutions along a loading history
!> (docs/theory/tips.md#k-along-a-loading-history). The coupled solution (the model solved
!> under its load plus the traction its zones add, the zones re-solved) is linear in the
!> load while its contact states hold, so along a straight stretch of the load path a
!> step's is the last two coupled solutions' extrapolated to its load. The extrapolation
!> solves the same equations (equilibrium is linear whatever the states); whether it is
!> the step's solution is what the contact conditions say, checked by the caller with the
!> contact solver's own certificate. K is then extrapolated too: no solve.
module ddc_run_coupled_k
    use ddc_kinds, only: wp
    use ddc_contact_states, only: state_slip
    implicit none
    private

    public :: coupled_solution, coupled_path

    !> How far beyond the last two coupled solutions, in units of the load between them, a
    !> solution is extrapolated: the coupling's error (its tolerance) grows as 1 + 2 times
    !> this. The next coupled solution is then that far from the last, so the solves along a
    !> straight stretch of N steps are about log_(1 + this) N.
    real(wp), parameter :: max_reach = 16.0_wp
    !> How far a load may lie off the line of the last two, relative to the load between
    !> them (rounding of the loads' resolution on the elements) [-]
    real(wp), parameter :: line_tolerance = 1.0e-10_wp

    !> One coupled solution of the local re-solve.
    type :: coupled_solution
        !> The load's values: tractions and pressures on the elements, remote stress and
        !> gradient (ddc_run_contact_run's load_values)
        real(wp), allocatable :: load(:)
        !> The traction the zones and recovered DDs add outside the zones, [shear; normal],
        !> shape (2 n) [stress]
        real(wp), allocatable :: shift(:)
        !> The contact elements' DDs [length], states and total shear and normal traction
        !> [stress], shape (nc)
        real(wp), allocatable :: ds(:), dn(:)
        integer, allocatable :: state(:)
        real(wp), allocatable :: shear(:), normal(:)
        !> K_I and K_II of each tip [stress * length**0.5], shape (tips)
        real(wp), allocatable :: k1(:), k2(:)
        !> Stress and displacement scale of the solve's certificate [stress], [length]
        real(wp) :: stress_scale = 1.0_wp, dd_scale = 1.0_wp
    end type coupled_solution

    !> The last two coupled solutions of a history.
    type :: coupled_path
        type(coupled_solution), allocatable :: last, before
    contains
        procedure :: keep
        procedure :: reach
        procedure :: extends
        procedure :: at
        procedure :: start
    end type coupled_path

contains

    !> A new coupled solution: the last becomes the one before.
    subroutine keep(this, solution)
        !> The path
        class(coupled_path), intent(inout) :: this
        !> The solution (moved in)
        type(coupled_solution), intent(inout), allocatable :: solution

        if (allocated(this%last)) call move_alloc(this%last, this%before)
        call move_alloc(solution, this%last)
    end subroutine keep

    !> How far a load is along the change of load from the solution before to the last one,
    !> from the last (its projection, in units of that change; 0 where the load did not
    !> change or before two solutions).
    pure real(wp) function reach(this, load)
        !> The path
        class(coupled_path), intent(in) :: this
        !> The load's values
        real(wp), intent(in) :: load(:)
        real(wp) :: step

        reach = 0.0_wp
        if (.not. allocated(this%before)) return
        if (size(load) /= size(this%last%load)) return
        step = sum((this%last%load - this%before%load)**2)
        if (step > 0.0_wp) reach = sum((load - this%last%load) * &
                                       (this%last%load - this%before%load)) / step
    end function reach

    !> Whether a load's coupled solution may be extrapolated from the last two: they have
    !> the same states (and slip senses), and the load lies on their line, not farther
    !> than max_reach from the last.
    pure logical function extends(this, load)
        !> The path
        class(coupled_path), intent(in) :: this
        !> The load's values
        real(wp), intent(in) :: load(:)
        real(wp) :: along, change

        extends = .false.
        if (.not. allocated(this%before)) return
        associate (a => this%before, b => this%last)
            if (size(load) /= size(b%load) .or. size(a%load) /= size(b%load)) return
            if (any(a%state /= b%state)) return
            if (any(a%state == state_slip .and. b%state == state_slip .and. &
                    sign(1.0_wp, a%shear) /= sign(1.0_wp, b%shear))) return
            change = norm2(b%load - a%load)
            if (.not. change > 0.0_wp) return
            along = this%reach(load)
            if (abs(along) > max_reach) return
            extends = norm2(load - b%load - along * (b%load - a%load)) <= &
                line_tolerance * change * max(1.0_wp, abs(along))
        end associate
    end function extends

    !> The coupled solution of a load extrapolated from the last two (its certificate's
    !> scales the larger of theirs).
    pure function at(this, load) result(solution)
        !> The path (extends the load)
        class(coupled_path), intent(in) :: this
        !> The load's values
        real(wp), intent(in) :: load(:)
        type(coupled_solution) :: solution
        real(wp) :: along

        along = this%reach(load)
        associate (a => this%before, b => this%last)
            solution%load = load
            solution%shift = b%shift + along * (b%shift - a%shift)
            solution%ds = b%ds + along * (b%ds - a%ds)
            solution%dn = b%dn + along * (b%dn - a%dn)
            solution%state = b%state
            solution%shear = b%shear + along * (b%shear - a%shear)
            solution%normal = b%normal + along * (b%normal - a%normal)
            solution%k1 = b%k1 + along * (b%k1 - a%k1)
            solution%k2 = b%k2 + along * (b%k2 - a%k2)
            solution%stress_scale = max(a%stress_scale, b%stress_scale)
            solution%dd_scale = max(a%dd_scale, b%dd_scale)
        end associate
    end function at

    !> The traction a step's coupling starts from: where the step's contact states are those
    !> of the last coupled solution, its traction, extrapolated to the step's load where the
    !> solution before has them too; else none (the step's own DDs give it: a traction of
    !> other states would start the solves far from theirs).
    pure subroutine start(this, load, state, shift)
        !> The path
        class(coupled_path), intent(in) :: this
        !> The step's load values and its contact elements' states, shape (nc)
        real(wp), intent(in) :: load(:)
        integer, intent(in) :: state(:)
        !> The traction, [shear; normal], shape (2 n) [stress]; unallocated where none
        real(wp), allocatable, intent(out) :: shift(:)

        if (.not. allocated(this%last)) return
        if (any(state /= this%last%state)) return
        shift = this%last%shift
        if (.not. allocated(this%before)) return
        if (all(this%before%state == this%last%state)) shift = shift + this%reach(load) * &
            (this%last%shift - this%before%shift)
    end subroutine start

end module ddc_run_coupled_k
