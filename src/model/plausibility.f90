!> Notes (not errors) on input that is valid but implausible, for the model echo:
!> - in a half-plane, a remote sxx or syy that turns tensile with depth (a gradient of the
!>   wrong sign: with y negative downward, compression grows with depth for ds_dy > 0);
!> - a pore pressure p0 + dp_dy y that is negative somewhere in the model (hydrostatic is
!>   dp_dy < 0);
!> - a tensile strength above the Coulomb apex sf/mu, which the law caps there (with the
!>   default sf = 0 a fracture then has no tensile strength at all), of a fracture or of the
!>   new contact elements of growth (&growth new_tensile_strength against new_sf, new_mu or
!>   the values of the tip elements they grow from);
!> - a slip_weakening_distance on a fracture none of whose elements with it has a friction
!>   or cohesion that drops (mu_dynamic not below mu, sf_residual not below sf): it does
!>   nothing (where some elements weaken, the others, say a weak centre without cohesion,
!>   are no mistake);
!> - a fluid pressure that makes the effective normal stress tensile beyond the tensile
!>   strength on every contact element of a model without a loading history: all of them
!>   open;
!> - stresses whose strain |stress| / E lies outside about strain_min .. strain_max, the
!>   mark of a stress_unit that differs from the unit of youngs_modulus.
!> The model's depth range is that of its element ends and observation points.
module ddc_model_plausibility
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, domain_half_plane, condition_contact, tensile_cap, &
        condition_traction, condition_mixed_us_sn, condition_mixed_ss_un
    use ddc_model_loads, only: resolve_remote_stress, total_pressure
    use ddc_model_laws, only: law_index
    use ddc_text, only: short_real, newline, itoa
    implicit none
    private

    public :: plausibility_notes, depth_range, strain_min, strain_max

    !> Strains |stress| / E outside this range get a note [-]
    real(wp), parameter :: strain_min = 1.0e-6_wp, strain_max = 0.1_wp

contains

    !> Lowest and highest y of the model: element ends and observation points.
    pure subroutine depth_range(model, deepest, highest)
        !> The model
        type(model_type), intent(in) :: model
        !> Lowest and highest y [length unit]
        real(wp), intent(out) :: deepest, highest
        integer :: k

        associate (e => model%elements)
            deepest = min(minval(e%y_begin), minval(e%y_end))
            highest = max(maxval(e%y_begin), maxval(e%y_end))
        end associate
        if (.not. allocated(model%observations)) return
        do k = 1, size(model%observations)
            if (size(model%observations(k)%y) == 0) cycle
            deepest = min(deepest, minval(model%observations(k)%y))
            highest = max(highest, maxval(model%observations(k)%y))
        end do
    end subroutine depth_range

    !> The notes on a model, one per line ('' when there are none).
    function plausibility_notes(model, units_given) result(notes)
        !> The model, with at least one element
        type(model_type), intent(in) :: model
        !> The stress unit was chosen by the user (false for a TWODD deck, which has none:
        !> no strain note then)
        logical, intent(in) :: units_given
        !> The notes, newline-separated
        character(len=:), allocatable :: notes
        real(wp) :: deepest, highest
        integer :: k

        notes = ''
        call depth_range(model, deepest, highest)
        if (model%elements%domain == domain_half_plane) then
            call tensile_with_depth('sxx', model%sxx, model%stress_gradient(1))
            call tensile_with_depth('syy', model%syy, model%stress_gradient(2))
        end if
        if (any(model%elements%condition == condition_contact)) then
            call negative_pore_pressure()
            if (.not. allocated(model%load_path%vertex)) call tension_on_every_contact()
        end if
        do k = 1, size(model%fractures)
            call capped_tensile_strength(k)
            call idle_weakening_distance(k)
        end do
        if (model%growth%active) call capped_new_tensile_strength()
        if (units_given) call strain_range()

    contains

        subroutine add(note)
            character(len=*), intent(in) :: note

            if (len(notes) > 0) notes = notes//newline
            notes = notes//note
        end subroutine add

        !> value + gradient y > 0 at the deepest point while the gradient is negative.
        subroutine tensile_with_depth(name, value, gradient)
            character(len=*), intent(in) :: name
            real(wp), intent(in) :: value, gradient
            real(wp) :: deep

            deep = value + gradient * deepest
            if (.not. (gradient < 0.0_wp .and. deep > 0.0_wp)) return
            call add('the remote '//name//' = '//short_real(value)//' + '//short_real(gradient) &
                     //' y turns tensile with depth: '//short_real(deep)//' '// &
                     model%stress_unit//' at y = '//short_real(deepest)//' '// &
                     model%length_unit//' (the deepest point of the model); with y negative '// &
                     'downward, compression that grows with depth needs d'//name//'_dy > 0')
        end subroutine tensile_with_depth

        !> p0 + dp_dy y < 0 at the top or the bottom of the model.
        subroutine negative_pore_pressure()
            real(wp) :: p_deep, p_high, y

            p_deep = model%pore_fluid(1) + model%pore_fluid(2) * deepest
            p_high = model%pore_fluid(1) + model%pore_fluid(2) * highest
            if (.not. min(p_deep, p_high) < 0.0_wp) return
            y = merge(deepest, highest, p_deep < p_high)
            call add('the pore pressure p0 + dp_dy y = '//short_real(model%pore_fluid(1))// &
                     ' + '//short_real(model%pore_fluid(2))//' y is negative: '// &
                     short_real(min(p_deep, p_high))//' '//model%stress_unit//' at y = '// &
                     short_real(y)//' '//model%length_unit//' (the fluid would pull the '// &
                     'crack faces together); hydrostatic pressure with y negative downward '// &
                     'has dp_dy < 0 (-0.0098 MPa/m for water)')
        end subroutine negative_pore_pressure

        !> Fracture k's tensile strength where the cap at the apex sf/mu lowers it.
        subroutine capped_tensile_strength(k)
            integer, intent(in) :: k
            integer :: capped

            associate (first => model%fractures(k)%first_element, &
                       last => model%fractures(k)%last_element)
                associate (t => model%elements%tensile_strength(first:last), &
                           t_in => tensile_cap(model%elements%tensile_strength(first:last), &
                                               model%elements%sf(first:last), &
                                               model%elements%mu(first:last)))
                    capped = count(t_in < t)
                    if (capped == 0) return
                    call add('fracture '//itoa(k)//' '//model%fractures(k)%name// &
                             ': tensile_strength '//short_real(maxval(t, mask=t_in < t))// &
                             ' '//model%stress_unit//' is above the Coulomb apex sf/mu on '// &
                             itoa(capped)//' of '//itoa(size(t))//' elements and is capped '// &
                             'there to '//short_real(minval(t_in, mask=t_in < t))//' .. '// &
                             short_real(maxval(t_in, mask=t_in < t))//' '// &
                             model%stress_unit//' (where the shear strength sf - mu T '// &
                             'vanishes); a tensile strength T needs sf >= mu T')
                end associate
            end associate
        end subroutine capped_tensile_strength

        !> &growth new_tensile_strength where the cap at the apex sf/mu of the new contact
        !> elements lowers it: their sf and mu are new_sf, new_mu where given, else those of
        !> the tip elements they grow from.
        subroutine capped_new_tensile_strength()
            real(wp) :: t, t_in, low, high
            character(len=:), allocatable :: names
            integer :: law, f, end, tip, named

            law = law_index('tensile_strength')
            if (.not. model%growth%override_law(law)) return
            t = model%growth%new_law(law)
            low = huge(1.0_wp)
            high = -huge(1.0_wp)
            names = ''
            named = 0
            do f = 1, size(model%fractures)
                if (.not. model%growth%fracture_grows(f)) cycle
                do end = 1, 2
                    tip = merge(model%fractures(f)%first_element, &
                                model%fractures(f)%last_element, end == 1)
                    if (model%elements%condition(tip) /= condition_contact) cycle
                    t_in = tensile_cap(t, merge(model%growth%new_sf, model%elements%sf(tip), &
                                                model%growth%override_sf), &
                                       merge(model%growth%new_mu, model%elements%mu(tip), &
                                             model%growth%override_mu))
                    if (.not. t_in < t) cycle
                    low = min(low, t_in)
                    high = max(high, t_in)
                    if (named /= f) then
                        if (named > 0) names = names//', '
                        names = names//model%fractures(f)%name
                        named = f
                    end if
                end do
            end do
            if (len(names) == 0) return
            call add('&growth: new_tensile_strength '//short_real(t)//' '// &
                     model%stress_unit//' is above the Coulomb apex sf/mu of the new '// &
                     'contact elements of '//names//' (new_sf, new_mu, or the values of '// &
                     'their tip element) and is capped there to '//short_real(low)//' .. '// &
                     short_real(high)//' '//model%stress_unit//' (where the shear strength '// &
                     'sf - mu T vanishes); a tensile strength T needs sf >= mu T (give new_sf)')
        end subroutine capped_new_tensile_strength

        !> Fracture k's slip_weakening_distance where no element that has it weakens:
        !> neither mu_dynamic is below mu nor sf_residual below sf on any of them.
        subroutine idle_weakening_distance(k)
            integer, intent(in) :: k
            integer :: given

            associate (first => model%fractures(k)%first_element, &
                       last => model%fractures(k)%last_element)
                associate (dc => model%elements%slip_weakening_distance(first:last), &
                           mu => model%elements%mu(first:last), &
                           mud => model%elements%mu_dynamic(first:last), &
                           sf => model%elements%sf(first:last), &
                           sfr => model%elements%sf_residual(first:last))
                    given = count(dc > 0.0_wp)
                    if (given == 0 .or. any(dc > 0.0_wp .and. (mud < mu .or. sfr < sf))) return
                    call add('fracture '//itoa(k)//' '//model%fractures(k)%name// &
                             ': slip_weakening_distance is given, but neither friction nor '// &
                             'cohesion weakens on any of the '//itoa(given)//' elements '// &
                             'that have it (mu_dynamic is not below mu, sf_residual not '// &
                             'below sf): it does nothing (give mu_dynamic < mu or '// &
                             'sf_residual < sf)')
                end associate
            end associate
        end subroutine idle_weakening_distance

        !> The fluid pressure turns the effective normal traction (remote normal traction
        !> plus fluid pressure) above the tensile strength in force on every contact
        !> element. Remote tension alone (a crack pulled open) is a model of its own.
        subroutine tension_on_every_contact()
            real(wp), allocatable :: shear(:), normal(:), effective(:), strength(:)
            logical, allocatable :: contact(:)

            associate (e => model%elements)
                allocate (shear(e%n), normal(e%n))
                call resolve_remote_stress(e, model%sxx, model%syy, model%sxy, shear, normal, &
                                           model%stress_gradient)
                effective = normal + total_pressure(e, model%pore_fluid)
                strength = tensile_cap(e%tensile_strength, e%sf, e%mu)
                contact = e%condition == condition_contact
                if (all(normal > strength .or. .not. contact)) return
                if (.not. all(effective > strength .or. .not. contact)) return
                call add('the fluid pressure makes the effective normal stress tensile on '// &
                         'every contact element ('//short_real(minval(effective, contact))// &
                         ' .. '//short_real(maxval(effective, contact))//' '// &
                         model%stress_unit//', remote normal stress plus fluid pressure, '// &
                         'above the tensile strength): every one opens whole')
            end associate
        end subroutine tension_on_every_contact

        !> The largest stress given (remote stress at the top and bottom of the model,
        !> pressures, given tractions) against Young's modulus.
        subroutine strain_range()
            real(wp) :: stress, strain

            stress = max(maxval(abs([model%sxx, model%syy, model%sxy] + &
                                    model%stress_gradient * deepest)), &
                         maxval(abs([model%sxx, model%syy, model%sxy] + &
                                    model%stress_gradient * highest)))
            associate (e => model%elements)
                stress = max(stress, maxval(abs(e%pressure)), &
                             abs(model%pore_fluid(1) + model%pore_fluid(2) * deepest), &
                             abs(model%pore_fluid(1) + model%pore_fluid(2) * highest), &
                             maxval(abs(e%bc_s), mask=e%condition == condition_traction .or. &
                                    e%condition == condition_mixed_ss_un), &
                             maxval(abs(e%bc_n), mask=e%condition == condition_traction .or. &
                                    e%condition == condition_mixed_us_sn))
            end associate
            if (.not. stress > 0.0_wp) return
            strain = stress / model%youngs_modulus
            if (strain >= strain_min .and. strain <= strain_max) return
            call add('the largest stress given, '//short_real(stress)//' '// &
                     model%stress_unit//', is '//short_real(strain)//' times '// &
                     'youngs_modulus = '//short_real(model%youngs_modulus)//' (a strain '// &
                     'outside about '//short_real(strain_min)//' .. '//short_real(strain_max)// &
                     '): check stress_unit; youngs_modulus and every stress are in one unit, '// &
                     'here '//model%stress_unit)
        end subroutine strain_range

    end function plausibility_notes

end module ddc_model_plausibility
