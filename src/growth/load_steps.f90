!> The loading history of a growth run (docs/theory/growth.md#growth-along-a-loading-history): what
!> /history records at the end of every load step while the fractures grow between them.
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
    use ddc_error, only: error_type
    use ddc_allocation, only: allocation_failed, real_bytes
    use ddc_text, only: itoa
    use ddc_model_results, only: model_results, history_record, growth_record, tip_set
    use ddc_model_records, only: lay_out_history
    use ddc_growth_extension, only: tip_element, tip_end_begin, tip_end_end
    use ddc_model_restart, only: restart_state
    use ddc_growth_tips, only: growing_tip, locate_tip
    use ddc_model_loads, only: shear_modulus_of
    use ddc_history_fronts, only: record_fronts
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
        !> The path has a time axis; the model fluid sources (their columns are recorded)
        logical :: time = .false., flow = .false.
    end type load_step_history

contains

    !> Room for the columns of `steps` load steps of the input geometry `work`.
    subroutine start_load_steps(history, work, steps, error, time, flow)
        !> The history (fresh)
        type(load_step_history), intent(out) :: history
        !> The input geometry
        type(model_type), intent(in) :: work
        !> Load steps of the path
        integer, intent(in) :: steps
        !> Set when the history does not fit in memory
        type(error_type), allocatable, intent(out) :: error
        !> The path has a time axis; the model has fluid sources
        logical, intent(in) :: time, flow
        integer :: i

        history%lineage = [(i, i = 1, work%elements%n)]
        history%time = time
        history%flow = flow
        if (flow) then
            call lay_out(history%h, work%elements%n, 2 * size(work%fractures), steps, 0, &
                         error, time=time, fractures=size(work%fractures))
        else
            call lay_out(history%h, work%elements%n, 2 * size(work%fractures), steps, 0, &
                         error, time=time)
        end if
    end subroutine start_load_steps

    !> Room for `steps` load steps and the first `done` columns of an earlier run that ended
    !> with the geometry `work` (--resume).
    subroutine resume_load_steps(history, work, state, loads, steps, done, error)
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
        !> Set when the history does not fit in memory
        type(error_type), allocatable, intent(out) :: error
        integer :: i

        history%lineage = [(i, i = 1, work%elements%n)]
        history%k = done
        associate (h => history%h)
            h = state%results%history
            ! K rows of the fracture ends; the file holds those of its final tips.
            h%k1 = end_rows(state%results%history%k1)
            h%k2 = end_rows(state%results%history%k2)
            call lay_out(h, work%elements%n, 2 * size(work%fractures), steps, done, error)
            if (allocated(error)) return
            h%load(:, 1:done) = loads(:, 1:done)
        end associate

    contains

        !> K of the fracture ends from K of the earlier run's final tips (NaN: no tip).
        function end_rows(k_tips) result(k_ends)
            real(wp), intent(in) :: k_tips(:, :)
            real(wp) :: k_ends(2 * size(work%fractures), size(k_tips, 2))
            integer :: f, end, t

            k_ends = ieee_value(1.0_wp, ieee_quiet_nan)
            do f = 1, size(work%fractures)
                do end = tip_end_begin, tip_end_end
                    t = locate_tip(state%results%tips, tip_element(work, f, end), end)
                    if (t == 0) cycle
                    k_ends(2 * (f - 1) + end - tip_end_begin + 1, :) = k_tips(t, :)
                end do
            end do
        end function end_rows

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
    subroutine record_load_step(history, work, current, load, error, time, volume)
        !> The history
        type(load_step_history), intent(inout) :: history
        !> The current geometry and its solution at the step's load
        type(model_type), intent(in) :: work
        type(model_results), intent(in) :: current
        !> The load, rows as load_path_names, shape (7)
        real(wp), intent(in) :: load(:)
        !> Set when the history does not fit in memory
        type(error_type), allocatable, intent(out) :: error
        !> The step's time [time unit] (a path with a time axis) and the volume the fluid
        !> sources let in by then [length^2] (a model with sources)
        real(wp), intent(in), optional :: time, volume
        integer :: k, f, end, i, t

        call follow_rows(history, 2 * size(work%fractures), error)
        if (allocated(error)) return
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
            if (present(time)) h%time(k) = time
            if (present(volume)) then
                h%pressure(:, k) = work%elements%flow_pressure
                h%injected_volume(k) = volume
                call record_fronts(work, shear_modulus_of(work), k, h)
            end if
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
    subroutine finish_load_steps(history, work, tips, growing, growth, h, error)
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
        !> Set when the history does not fit in memory
        type(error_type), allocatable, intent(out) :: error
        integer :: k, f, end, t, i, j

        k = history%k
        h = history%h
        call lay_out(h, size(h%ds, 1), size(h%k1, 1), k, k, error)
        if (allocated(error)) return
        ! K rows of the final tips instead of the fracture ends
        deallocate (h%k1, h%k2)
        allocate (h%k1(tips%n, k), h%k2(tips%n, k))
        h%k1 = ieee_value(1.0_wp, ieee_quiet_nan)
        h%k2 = h%k1
        associate (c => history%h)
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

    !> Move the rows of the columns so far to the elements of the current geometry, and make
    !> room for the K rows of its fracture ends (`ends`: new fractures add theirs).
    subroutine follow_rows(history, ends, error)
        type(load_step_history), intent(inout) :: history
        integer, intent(in) :: ends
        type(error_type), allocatable, intent(out) :: error
        integer :: i

        associate (h => history%h, lineage => history%lineage)
            if (size(lineage) == size(h%ds, 1) .and. ends == size(h%k1, 1)) then
                if (all(lineage == [(i, i = 1, size(lineage))])) return
            end if
            if (history%flow) then
                call lay_out(h, size(lineage), ends, size(h%ds, 2), history%k, error, lineage, &
                             fractures=ends / 2)
            else
                call lay_out(h, size(lineage), ends, size(h%ds, 2), history%k, error, lineage)
            end if
            lineage = [(i, i = 1, size(lineage))]
        end associate
    end subroutine follow_rows

    !> Lay the columns out anew (ddc_model_records' lay_out_history, with the columns of
    !> growth along a load path); error: they do not fit.
    subroutine lay_out(h, rows, ends, steps, kept, error, origin, time, fractures)
        !> The columns
        type(history_record), intent(inout) :: h
        !> Element rows, fracture ends, steps, steps kept
        integer, intent(in) :: rows, ends, steps, kept
        !> Set when they do not fit in memory
        type(error_type), allocatable, intent(inout) :: error
        !> The row each element row takes (0: none; default its own), shape (rows)
        integer, intent(in), optional :: origin(:)
        !> Lay out the column of a time axis too (default: when there)
        logical, intent(in), optional :: time
        !> Lay out the columns of fluid sources, for this many fractures (default: when
        !> there, for as many as before)
        integer, intent(in), optional :: fractures
        integer :: stat

        call lay_out_history(h, rows, ends, steps, kept, stat, origin, growth=.true., &
                             time=time, fractures=fractures)
        if (stat /= 0) call allocation_failed(error, 'the history of '//itoa(rows)// &
                                              ' elements at '//itoa(steps)//' load steps', &
                                              real_bytes * 5.0_wp * real(rows, wp) * &
                                              real(steps, wp))
    end subroutine lay_out

end module ddc_growth_load_steps
