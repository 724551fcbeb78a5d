!> The loading history of a growth run (SPEC-GROWTH 6): what /history records at the end of
!> every load step while the fractures grow between them.
!>
!> Each load step adds a column: the load, the DDs, states and tractions of every element,
!> K at every fracture end that is a tip, the number of elements and the solve's record.
!> The geometry grows between columns, so the rows follow the elements: after each growth
!> step the driver tells where each element came from (follow_growth), and the next column
!> first moves the rows of the earlier ones to the elements' new places (a split element's
!> halves both take its rows; a new element has NaN, state_not_grown, before it was made).
!> At the end the rows are the final geometry's elements, the K rows its tips, and the grown
!> length of every tip that may grow is summed from the growth record per load step.
module ddc_growth_load_steps
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type
    use ddc_model_results, only: model_results, history_record, growth_record, tip_set, &
        state_not_grown, copy_steps
    use ddc_growth_extension, only: tip_element, tip_end_begin, tip_end_end
    use ddc_model_restart, only: restart_state
    use ddc_growth_tips, only: growing_tip, locate_tip
    implicit none
    private

    public :: load_step_history, start_load_steps, follow_growth, record_load_step, &
        finish_load_steps, resume_load_steps

    !> The columns recorded so far and how the current geometry's elements relate to them.
    type :: load_step_history
        private
        !> The columns so far (rows: the elements at the last column; K rows: ends)
        type(history_record) :: h
        !> Columns recorded
        integer :: k = 0
        !> The row of each element of the current geometry (0: made since), shape (n)
        integer, allocatable :: lineage(:)
    end type load_step_history

contains

    !> Room for the columns of `steps` load steps of the input geometry `work`.
    subroutine start_load_steps(history, work, steps)
        !> The history (fresh)
        type(load_step_history), intent(out) :: history
        !> The input geometry
        type(model_type), intent(in) :: work
        !> Load steps of the path
        integer, intent(in) :: steps
        integer :: n, ends, i

        n = work%elements%n
        ends = 2 * size(work%fractures)
        history%lineage = [(i, i = 1, n)]
        associate (h => history%h)
            allocate (h%load(7, steps), h%pivots(steps), h%newton_iterations(steps), &
                      h%method(steps), h%fallback(steps), h%certificate_min_z(steps), &
                      h%certificate_min_w(steps), h%certificate_max_complementarity(steps), &
                      h%equilibrium_residual(steps), h%element_count(steps))
            allocate (h%ds(n, steps), h%dn(n, steps), h%shear_traction(n, steps), &
                      h%normal_traction(n, steps), h%k1(ends, steps), h%k2(ends, steps))
            allocate (h%state(n, steps), source=state_not_grown)
        end associate
    end subroutine start_load_steps

    !> Room for `steps` load steps and the first `done` columns of an earlier run that ended
    !> with the geometry `work` (--resume).
    subroutine resume_load_steps(history, work, state, loads, steps, done)
        !> The history (fresh)
        type(load_step_history), intent(out) :: history
        !> The earlier run's final geometry
        type(model_type), intent(in) :: work
        !> The earlier run's end (its /history, K of its final tips)
        type(restart_state), intent(in) :: state
        !> The load at every step of the path, shape (7, steps)
        real(wp), intent(in) :: loads(:, :)
        !> Load steps of the path
        integer, intent(in) :: steps
        !> Columns of the earlier run kept (the others are recorded again)
        integer, intent(in) :: done
        integer :: f, end, i, t

        call start_load_steps(history, work, steps)
        associate (h => history%h, old => state%results%history)
            history%k = done
            h%load(:, 1:done) = loads(:, 1:done)
            call copy_steps(old, h, done)
            h%element_count(1:done) = old%element_count(1:done)
            ! K rows of the fracture ends; the file holds those of its final tips.
            h%k1(:, 1:done) = ieee_value(1.0_wp, ieee_quiet_nan)
            h%k2(:, 1:done) = h%k1(:, 1:done)
            do f = 1, size(work%fractures)
                do end = tip_end_begin, tip_end_end
                    t = locate_tip(state%results%tips, tip_element(work, f, end), end)
                    if (t == 0) cycle
                    i = 2 * (f - 1) + end - tip_end_begin + 1
                    h%k1(i, 1:done) = old%k1(t, 1:done)
                    h%k2(i, 1:done) = old%k2(t, 1:done)
                end do
            end do
        end associate
    end subroutine resume_load_steps

    !> A growth step was accepted: origin is the element of the geometry before it that each
    !> element of the grown one comes from (0: new).
    pure subroutine follow_growth(history, origin)
        !> The history
        type(load_step_history), intent(inout) :: history
        !> Shape (grown n)
        integer, intent(in) :: origin(:)
        integer, allocatable :: grown(:)

        if (.not. allocated(history%lineage)) return
        allocate (grown(size(origin)), source=0)
        where (origin > 0) grown = history%lineage(max(origin, 1))
        call move_alloc(grown, history%lineage)
    end subroutine follow_growth

    !> The column of the load step that just ended: the current geometry `work` at `load`,
    !> solved in `current`.
    subroutine record_load_step(history, work, current, load)
        !> The history
        type(load_step_history), intent(inout) :: history
        !> The current geometry and its solution at the step's load
        type(model_type), intent(in) :: work
        type(model_results), intent(in) :: current
        !> The load, rows as load_path_names, shape (7)
        real(wp), intent(in) :: load(:)
        integer :: k, f, end, i, t

        call follow_rows(history)
        history%k = history%k + 1
        k = history%k
        associate (h => history%h, e => current%elements, s => current%solver)
            h%load(:, k) = load
            h%ds(:, k) = e%ds
            h%dn(:, k) = e%dn
            h%state(:, k) = e%state
            h%shear_traction(:, k) = e%shear_traction
            h%normal_traction(:, k) = e%normal_traction
            h%element_count(k) = work%elements%n
            h%pivots(k) = s%pivots
            h%newton_iterations(k) = s%newton_iterations
            h%method(k) = s%method
            h%fallback(k) = s%fallback
            h%certificate_min_z(k) = s%certificate_min_z
            h%certificate_min_w(k) = s%certificate_min_w
            h%certificate_max_complementarity(k) = s%certificate_max_complementarity
            h%equilibrium_residual(k) = s%equilibrium_residual
            ! K of every fracture end that is a tip now (NaN for one that is not)
            h%k1(:, k) = ieee_value(1.0_wp, ieee_quiet_nan)
            h%k2(:, k) = h%k1(:, k)
            do f = 1, size(work%fractures)
                do end = tip_end_begin, tip_end_end
                    i = 2 * (f - 1) + end - tip_end_begin + 1
                    t = locate_tip(current%tips, tip_element(work, f, end), end)
                    if (t == 0) cycle
                    h%k1(i, k) = current%tips%k1(t)
                    h%k2(i, k) = current%tips%k2(t)
                end do
            end do
        end associate
    end subroutine record_load_step

    !> The history of the run: its columns, rows of the final geometry `work` (the geometry
    !> of the last column), K rows of its tips, and the grown length of every tip that may
    !> grow at the end of each load step.
    subroutine finish_load_steps(history, work, tips, growing, growth, h)
        !> The history
        type(load_step_history), intent(inout) :: history
        !> The final geometry and its tips
        type(model_type), intent(in) :: work
        type(tip_set), intent(in) :: tips
        !> The fracture ends that may grow
        type(growing_tip), intent(in) :: growing(:)
        !> The growth record of the run
        type(growth_record), intent(in) :: growth
        !> The history as /history writes it
        type(history_record), intent(out) :: h
        integer :: k, f, end, t, i, j

        k = history%k
        associate (c => history%h)
            h%load = c%load(:, 1:k)
            h%ds = c%ds(:, 1:k)
            h%dn = c%dn(:, 1:k)
            h%state = c%state(:, 1:k)
            h%shear_traction = c%shear_traction(:, 1:k)
            h%normal_traction = c%normal_traction(:, 1:k)
            h%element_count = c%element_count(1:k)
            h%pivots = c%pivots(1:k)
            h%newton_iterations = c%newton_iterations(1:k)
            h%method = c%method(1:k)
            h%fallback = c%fallback(1:k)
            h%certificate_min_z = c%certificate_min_z(1:k)
            h%certificate_min_w = c%certificate_min_w(1:k)
            h%certificate_max_complementarity = c%certificate_max_complementarity(1:k)
            h%equilibrium_residual = c%equilibrium_residual(1:k)
            allocate (h%k1(tips%n, k), h%k2(tips%n, k))
            h%k1 = ieee_value(1.0_wp, ieee_quiet_nan)
            h%k2 = h%k1
            do f = 1, size(work%fractures)
                do end = tip_end_begin, tip_end_end
                    t = locate_tip(tips, tip_element(work, f, end), end)
                    if (t == 0) cycle
                    i = 2 * (f - 1) + end - tip_end_begin + 1
                    h%k1(t, :) = c%k1(i, 1:k)
                    h%k2(t, :) = c%k2(i, 1:k)
                end do
            end do
        end associate
        allocate (h%tip_fracture_id(size(growing)), h%tip_end(size(growing)), &
                  h%grown_length(size(growing), k))
        do i = 1, size(growing)
            h%tip_fracture_id(i) = growing(i)%fracture
            h%tip_end(i) = growing(i)%end
            do j = 1, k
                h%grown_length(i, j) = sum(growth%length, growth%fracture_id == &
                    growing(i)%fracture .and. growth%end == growing(i)%end .and. &
                    growth%load_step <= j)
            end do
        end do
    end subroutine finish_load_steps

    !> Move the rows of the columns so far to the elements of the current geometry.
    subroutine follow_rows(history)
        type(load_step_history), intent(inout) :: history
        integer :: i

        associate (h => history%h, lineage => history%lineage)
            if (size(lineage) == size(h%ds, 1)) then
                if (all(lineage == [(i, i = 1, size(lineage))])) return
            end if
            call follow_real(h%ds)
            call follow_real(h%dn)
            call follow_real(h%shear_traction)
            call follow_real(h%normal_traction)
            call follow_state(h%state)
            lineage = [(i, i = 1, size(lineage))]
        end associate

    contains

        subroutine follow_real(a)
            real(wp), allocatable, intent(inout) :: a(:, :)
            real(wp), allocatable :: moved(:, :)

            allocate (moved(size(history%lineage), size(a, 2)))
            moved = ieee_value(1.0_wp, ieee_quiet_nan)
            do i = 1, size(history%lineage)
                if (history%lineage(i) > 0) moved(i, :) = a(history%lineage(i), :)
            end do
            call move_alloc(moved, a)
        end subroutine follow_real

        subroutine follow_state(a)
            integer, allocatable, intent(inout) :: a(:, :)
            integer, allocatable :: moved(:, :)

            allocate (moved(size(history%lineage), size(a, 2)), source=state_not_grown)
            do i = 1, size(history%lineage)
                if (history%lineage(i) > 0) moved(i, :) = a(history%lineage(i), :)
            end do
            call move_alloc(moved, a)
        end subroutine follow_state

    end subroutine follow_rows

end module ddc_growth_load_steps
