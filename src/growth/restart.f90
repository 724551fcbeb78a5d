!> A growth run resumed from the end of an earlier one (--resume;
!> docs/theory/earth.md#what-a-step-hands-on): the geometry it ended with, rebuilt from the input
!> model as growth builds it, and the tips that may still grow.
!>
!> The file holds the final end points, fractures and created steps, not every element
!> value as given. So each element of the final geometry takes the values of the input
!> element it comes from, as ddc_growth_extension gave them: an input element (created
!> step 0) its own (a split one: both halves, found as the consecutive elements that span
!> it), a grown element those of its fracture's input tip element at that end, with what
!> a new element takes (inherit_values); then its end points from the file (bit for bit)
!> and the geometry computed.
!>
!> Under a loading history the strength state goes on too (resumed_strengths): the strengths in
!> force as the file holds them, and the slip path summed over its load steps.
module ddc_growth_restart
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_model_types, only: model_type, rigid_joint
    use ddc_model_laws, only: law_index
    use ddc_model_results, only: growth_intersection, growth_surface, growth_linked, &
        growth_enclosing, growth_interface, growth_grew, growth_corrector_failed
    use ddc_model_restart, only: restart_state
    use ddc_mesh_geometry, only: compute_geometry
    use ddc_growth_extension, only: inherit_values, tip_element
    use ddc_growth_tips, only: growing_tip, resumed_element_length
    use ddc_contact_fault_law, only: fault_law
    use ddc_model_element_laws, only: fault_law_of
    implicit none
    private

    public :: resumed_geometry, resumed_tips, resumed_strengths

contains

    !> The final geometry of the earlier run (observations as in model) and the growth
    !> step that created each of its elements.
    subroutine resumed_geometry(model, state, work, created, error)
        !> The input model (validated)
        type(model_type), intent(in) :: model
        !> The earlier run's end
        type(restart_state), intent(in) :: state
        !> Its final geometry
        type(model_type), intent(out) :: work
        !> Growth step that created each element, shape (n)
        integer, allocatable, intent(out) :: created(:)
        !> Set (exit_bad_input) when the file's geometry does not follow from the model
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: pick(:)
        integer :: f, i, j, n, joint_laws(2)

        n = size(state%x_begin)
        created = state%results%growth%created_step
        ! The laws of new elements that make joints of them
        joint_laws = [law_index('shear_stiffness'), law_index('normal_stiffness')]
        if (allocated(model%load_path%vertex) .and. (any(model%elements%shear_stiffness < &
            rigid_joint) .or. any(model%elements%normal_stiffness < rigid_joint) .or. &
            any(model%growth%override_law(joint_laws)))) then
            ! The memory of elastic joints is their plastic slip, which the file does not hold.
            call set_error(error, exit_bad_input, '--resume: growth along a load path with '// &
                           'elastic joints (shear_stiffness, normal_stiffness) cannot be resumed')
            return
        end if
        if (size(state%first_element) /= size(model%fractures) .or. size(created) /= n) then
            call mismatch('its fractures or elements do not match the model')
            return
        end if
        allocate (pick(n), source=0)
        do f = 1, size(model%fractures)
            associate (input => model%fractures(f), e => model%elements)
                j = input%first_element
                do i = state%first_element(f), state%last_element(f)
                    if (created(i) > 0) then
                        ! Grown before the input's elements: at the begin tip.
                        pick(i) = merge(input%first_element, input%last_element, &
                                        j == input%first_element)
                        cycle
                    end if
                    if (j > input%last_element) exit
                    pick(i) = j
                    ! The element (or a split one's second half) ends where input j ends.
                    if (state%x_end(i) == e%x_end(j) .and. state%y_end(i) == e%y_end(j)) then
                        j = j + 1
                    end if
                end do
                if (j /= input%last_element + 1) then
                    call mismatch('fracture '//input%name//' does not hold the model''s '// &
                                  'elements')
                    return
                end if
            end associate
        end do
        if (any(pick == 0)) then
            call mismatch('an element comes from no element of the model')
            return
        end if
        work = model
        call inherit_values(model%elements, pick, created > 0, model%growth, work%elements)
        associate (a => work%elements)
            a%x_begin = state%x_begin
            a%y_begin = state%y_begin
            a%x_end = state%x_end
            a%y_end = state%y_end
            a%fracture_id = state%fracture_id
        end associate
        work%fractures%first_element = state%first_element
        work%fractures%last_element = state%last_element
        call compute_geometry(work%elements)

    contains

        subroutine mismatch(why)
            character(len=*), intent(in) :: why

            call set_error(error, exit_bad_input, '--resume: the earlier result does not '// &
                           'follow from the model: '//why)
        end subroutine mismatch

    end subroutine resumed_geometry

    !> The fracture ends that may grow, as the earlier run found them (those of its first
    !> check's records), each stopped for good when its last record says so, and with the
    !> element length its increments keep after a kink shorter than the increment.
    function resumed_tips(model, state) result(tips)
        !> The input model (its tip elements as given)
        type(model_type), intent(in) :: model
        !> The earlier run's end
        type(restart_state), intent(in) :: state
        type(growing_tip), allocatable :: tips(:)
        integer :: i, k, last
        logical, allocatable :: grew(:)

        associate (g => state%results%growth)
            allocate (tips(0))
            ! The first check's records: one per tip (the checks of load steps in which
            ! nothing grew share the step number of the next growth step).
            do k = 1, size(g%step)
                if (g%step(k) /= g%step(1)) exit
                if (any(tips%fracture == g%fracture_id(k) .and. tips%end == g%end(k))) exit
                tips = [tips, growing_tip(fracture=g%fracture_id(k), end=g%end(k))]
            end do
            do i = 1, size(tips)
                last = findloc(g%fracture_id == tips(i)%fracture .and. g%end == tips(i)%end, &
                               .true., 1, back=.true.)
                tips(i)%stopped = any(g%reason(last) == [growth_intersection, &
                                                         growth_surface, growth_linked, &
                                                         growth_enclosing, growth_interface])
                grew = g%fracture_id == tips(i)%fracture .and. g%end == tips(i)%end .and. &
                       (g%reason == growth_grew .or. g%reason == growth_corrector_failed)
                tips(i)%element_length = resumed_element_length(model%growth, 2.0_wp * &
                    model%elements%half_length(tip_element(model, tips(i)%fracture, &
                                                           tips(i)%end)), pack(g%length, grew))
                if (any(grew)) tips(i)%kink_length = g%length(findloc(grew, .true., 1, &
                                                                      back=.true.))
            end do
        end associate
    end function resumed_tips

    !> The fault law of the earlier run's final geometry with its strength state: the
    !> strengths in force of the file (the given ones where the file holds none) and the
    !> slip path, which the file does not hold: the sum of the slip increments between the
    !> load steps of /history (an element not made yet slips none), else the slip itself.
    !> It is the path of the uninterrupted run where slip does not reverse within a load
    !> step (the friction in force follows from it at the next solve).
    function resumed_strengths(work, state) result(law)
        !> The final geometry (resumed_geometry)
        type(model_type), intent(in) :: work
        !> The earlier run's end
        type(restart_state), intent(in) :: state
        type(fault_law) :: law
        real(wp), allocatable :: before(:), now(:)
        integer :: k

        law = fault_law_of(work%elements)
        associate (e => state%results%elements, h => state%results%history)
            if (allocated(e%sf_in_force)) then
                law%sf_in_force = e%sf_in_force
                law%tensile_in_force = e%tensile_in_force
            end if
            if (allocated(e%mu_in_force)) law%mu_in_force = e%mu_in_force
            if (.not. allocated(h%ds)) then
                law%slip_path = abs(e%ds)
                return
            end if
            allocate (before(work%elements%n), source=0.0_wp)
            law%slip_path = 0.0_wp
            do k = 1, size(h%ds, 2)
                now = merge(h%ds(:, k), 0.0_wp, ieee_is_finite(h%ds(:, k)))
                law%slip_path = law%slip_path + abs(now - before)
                before = now
            end do
        end associate
    end function resumed_strengths

end module ddc_growth_restart
