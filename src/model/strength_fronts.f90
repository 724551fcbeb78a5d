!> Notes and warnings of the model echo on strength that drops at a slip or opening front
!> (docs/theory/strength.md#failure-loads-that-converge-with-the-mesh). The stress at a front
!> is singular, so a strength that drops at once has no failure load that converges with the
!> mesh; a drop over a slip_weakening_distance d_c (cohesion and friction) or an
!> opening_weakening_distance d_o (tensile strength) has, once its cohesive zone spans a few
!> elements. The zone is about (Palmer & Rice 1973)
!>
!>     Lambda = (9 pi / 32) G d / ((1 - nu) (tau_p - tau_r))
!>
!> with G the shear modulus, d = d_c and tau_p - tau_r = (sf - sf_r) + (mu - mu_d) |S_n'|
!> (the drop of cohesion and friction at the effective normal stress S_n' of the remote
!> stress, tension positive, compression only), or d = d_o and tau_p - tau_r the tensile
!> strength in force (capped at the Coulomb apex).
module ddc_model_strength_fronts
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_model_types, only: model_type, tensile_cap, condition_contact
    use ddc_model_loads, only: resolve_remote_stress, total_pressure, shear_modulus_of
    use ddc_text, only: short_real, newline, itoa
    implicit none
    private

    public :: instant_drop_notes, cohesive_zone_warnings, cohesive_zone_length
    public :: min_zone_elements

    !> A cohesive zone shorter than this many elements gets a warning [-]
    real(wp), parameter :: min_zone_elements = 3.0_wp

contains

    !> Cohesive zone length (9 pi / 32) G d / ((1 - nu) drop) [length]; 0 where there is no
    !> drop or no distance.
    elemental real(wp) function cohesive_zone_length(shear_modulus, poissons_ratio, &
                                                      distance, drop) result(zone)
        !> Shear modulus G [stress] and Poisson's ratio nu [-]
        real(wp), intent(in) :: shear_modulus, poissons_ratio
        !> Weakening distance d [length] and strength drop tau_p - tau_r [stress]
        real(wp), intent(in) :: distance, drop

        zone = 0.0_wp
        if (drop > 0.0_wp .and. distance > 0.0_wp) zone = 9.0_wp * pi / 32.0_wp * &
            shear_modulus * distance / ((1.0_wp - poissons_ratio) * drop)
    end function cohesive_zone_length

    !> A note per fracture whose strength drops at once at a front: d_c = 0 with sf_residual
    !> below sf or mu_dynamic below mu, or a tensile strength in force with d_o = 0
    !> (newline-separated; '' when there is none).
    function instant_drop_notes(model) result(notes)
        !> The model, with at least one element
        type(model_type), intent(in) :: model
        !> The notes
        character(len=:), allocatable :: notes
        character(len=:), allocatable :: what, names
        integer :: k, slipping, opening

        notes = ''
        do k = 1, size(model%fractures)
            associate (first => model%fractures(k)%first_element, &
                       last => model%fractures(k)%last_element, e => model%elements)
                associate (contact => e%condition(first:last) == condition_contact, &
                           dc => e%slip_weakening_distance(first:last), &
                           drop_sf => min(e%sf(first:last), e%sf_residual(first:last)) < &
                               e%sf(first:last), &
                           drop_mu => min(e%mu(first:last), e%mu_dynamic(first:last)) < &
                               e%mu(first:last), &
                           t_in => tensile_cap(e%tensile_strength(first:last), &
                                               e%sf(first:last), e%mu(first:last)), &
                           d_o => e%opening_weakening_distance(first:last))
                    slipping = count(contact .and. .not. dc > 0.0_wp .and. (drop_sf .or. drop_mu))
                    opening = count(contact .and. t_in > 0.0_wp .and. .not. d_o > 0.0_wp)
                end associate
            end associate
            if (slipping + opening == 0) cycle
            what = ''
            names = ''
            if (slipping > 0) then
                what = 'cohesion or friction drops at once on slip (slip_weakening_distance'// &
                       ' = 0) on '//itoa(slipping)
                names = 'slip_weakening_distance'
            end if
            if (opening > 0) then
                if (slipping > 0) then
                    what = what//' and the tensile strength on opening '// &
                           '(opening_weakening_distance = 0) on '//itoa(opening)
                    names = names//' and opening_weakening_distance'
                else
                    what = 'the tensile strength drops at once on opening '// &
                           '(opening_weakening_distance = 0) on '//itoa(opening)
                    names = 'opening_weakening_distance'
                end if
            end if
            if (len(notes) > 0) notes = notes//newline
            notes = notes//'fracture '//itoa(k)//' '//model%fractures(k)%name//': '//what// &
                ' of '//itoa(model%fractures(k)%last_element - &
                model%fractures(k)%first_element + 1)//' elements: the stress at a slip '// &
                'or opening front is singular, so the loads at which such strength fails '// &
                'depend on the element length; give '//names//' (a cohesive zone of at '// &
                'least 3 elements) for failure loads that converge with the mesh'
        end do
    end function instant_drop_notes

    !> A warning per fracture and law whose cohesive zone spans fewer than
    !> min_zone_elements elements somewhere (newline-separated; '' when there is none).
    function cohesive_zone_warnings(model) result(warnings)
        !> The model, with at least one element
        type(model_type), intent(in) :: model
        !> The warnings
        character(len=:), allocatable :: warnings
        real(wp), allocatable :: shear(:), normal(:), compression(:), slip_drop(:), &
            slip_zone(:), open_zone(:), spans(:)
        real(wp) :: g
        integer :: k

        warnings = ''
        g = shear_modulus_of(model)
        associate (e => model%elements)
            allocate (shear(e%n), normal(e%n))
            call resolve_remote_stress(e, model%sxx, model%syy, model%sxy, shear, normal, &
                                       model%stress_gradient)
            compression = max(-(normal + total_pressure(e, model%pore_fluid)), 0.0_wp)
            slip_drop = (e%sf - min(e%sf, e%sf_residual)) + &
                (e%mu - min(e%mu, e%mu_dynamic)) * compression
            slip_zone = cohesive_zone_length(g, model%poissons_ratio, &
                                             e%slip_weakening_distance, slip_drop)
            open_zone = cohesive_zone_length(g, model%poissons_ratio, &
                                             e%opening_weakening_distance, &
                                             tensile_cap(e%tensile_strength, e%sf, e%mu))
            where (e%condition /= condition_contact)
                slip_zone = 0.0_wp
                open_zone = 0.0_wp
            end where
        end associate
        do k = 1, size(model%fractures)
            call warn(k, slip_zone, 'slip_weakening_distance', 'the drop of cohesion and '// &
                      'friction at the remote normal stress')
            call warn(k, open_zone, 'opening_weakening_distance', 'the tensile strength')
        end do

    contains

        !> The warning of fracture k for the zones of one law (0: none there).
        subroutine warn(k, zone, name, drop)
            integer, intent(in) :: k
            real(wp), intent(in) :: zone(:)
            character(len=*), intent(in) :: name, drop
            integer :: short

            associate (first => model%fractures(k)%first_element, &
                       last => model%fractures(k)%last_element)
                spans = zone(first:last) / (2.0_wp * model%elements%half_length(first:last))
                short = count(zone(first:last) > 0.0_wp .and. spans < min_zone_elements)
                if (short == 0) return
                if (len(warnings) > 0) warnings = warnings//newline
                warnings = warnings//'fracture '//itoa(k)//' '//model%fractures(k)% &
                    name//': the cohesive zone of '//name//', about (9 pi / 32) G d / '// &
                    '((1 - nu)(tau_p - tau_r)) with tau_p - tau_r '//drop//', spans only '// &
                    short_real(three_digits(minval(spans, mask=zone(first:last) > 0.0_wp)))// &
                    ' element lengths (fewer than 3 on '//itoa(short)//' of '// &
                    itoa(last - first + 1)//' elements; zone '// &
                    short_real(three_digits(minval(zone(first:last), &
                                                   mask=zone(first:last) > 0.0_wp)))// &
                    ' '//model%length_unit//'): its failure loads still depend on the '// &
                    'element length; give a larger '//name//' or shorter elements'
            end associate
        end subroutine warn

    end function cohesive_zone_warnings

    !> x rounded to three significant digits (an estimate needs no more).
    pure real(wp) function three_digits(x)
        !> The value
        real(wp), intent(in) :: x
        character(len=24) :: text

        write (text, '(es24.2)') x
        read (text, *) three_digits
    end function three_digits

end module ddc_model_strength_fronts
