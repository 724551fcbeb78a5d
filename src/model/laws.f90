!> The strength laws beyond Coulomb's friction and cohesion (docs/theory/strength.md): the
!> given values of each contact element that the fault law (ddc_contact_fault_law) takes
!> besides mu and sf, each a per-element array of element_set.
!>
!> for_each_law is the one list of them, each with what the places that handle the laws
!> need: its name (of the element array, the fault_law component, the &fracture variable and
!> elements_file column and the /elements dataset; new_<name> in &growth and &sweep), the
!> default that leaves Coulomb's law as it is, its range, its units, whether a value other
!> than the default takes the law beyond Coulomb's, and the Coulomb value it may not exceed.
!> The defaults (default_strength_laws: the elements read, a flaw's new fracture), the
!> &fracture and &growth readers, what new elements of a growth run take (set_law), the
!> &sweep parameters, the fault law of a model's elements (law_values), /elements and the
!> echo go through it. A new law is an array of element_set and a component of
!> fault_law, listed here (docs/ARCHITECTURE.md, "A new strength law"); the CTest
!> architecture fails when the list disagrees with the element arrays, the fault law or the
!> namelists.
module ddc_model_laws
    use ddc_kinds, only: wp
    use ddc_model_types, only: element_set, growth_options, no_residual_drop, rigid_joint, &
        strength_law_count
    use ddc_model_limits, only: quantity_non_negative, quantity_positive
    use ddc_model_records, only: units_stress, units_length, units_one, units_stiffness
    implicit none
    private

    public :: strength_law, law_action, for_each_law, strength_laws, law_index
    public :: law_values, set_law, default_strength_laws, laws_allocated
    public :: acting_values, at_most_rule, new_law_bound

    !> One strength law: what the places that handle it need.
    type :: strength_law
        !> Its name: the element_set array and the fault_law component, the &fracture variable
        !> and elements_file column, the /elements dataset; new_<name> in &growth and &sweep
        character(len=:), allocatable :: name
        !> The value that leaves Coulomb's law as it is, which an element takes where the
        !> input gives none
        real(wp) :: default = 0.0_wp
        !> Its range: quantity_non_negative or quantity_positive (ddc_model_limits)
        integer :: quantity = quantity_non_negative
        !> What it measures: units_stress, units_one, units_length or units_stiffness
        !> (ddc_model_records)
        integer :: units = units_one
        !> A value other than the default takes the law beyond Coulomb's (fault_law's
        !> beyond_coulomb); not so the distances, which say how gradually a drop comes
        logical :: beyond_coulomb = .false.
        !> The Coulomb value ('sf', 'mu') that this value after slip may not exceed: the
        !> smaller of the two acts (acting_values); '' for none
        character(len=:), allocatable :: at_most
    end type strength_law

    !> What a routine does with every strength law: it extends this type with its data and is
    !> handed each law by for_each_law.
    type, abstract :: law_action
    contains
        !> Act on one law and its per-element array
        procedure(act_on_law), deferred :: on_law
    end type law_action

    abstract interface
        !> Act on one law and its per-element array, shape (n) or unallocated
        pure subroutine act_on_law(action, law, values)
            import :: law_action, strength_law, wp
            implicit none
            !> The action and its data
            class(law_action), intent(inout) :: action
            !> The law
            type(strength_law), intent(in) :: law
            !> Its array
            real(wp), allocatable, intent(inout) :: values(:)
        end subroutine act_on_law
    end interface

    !> Collects the laws in the order of the list, whether each one's array is allocated and,
    !> when asked, their values (strength_laws, law_values, laws_allocated).
    type, extends(law_action) :: law_listing
        !> The laws listed so far
        type(strength_law) :: laws(strength_law_count)
        !> Whether each one's array is allocated
        logical :: has_array(strength_law_count) = .false.
        !> Their values, column k law k, shape (n, strength_law_count); unallocated: not asked
        real(wp), allocatable :: values(:, :)
        !> How many
        integer :: listed = 0
    contains
        procedure :: on_law => list_law
    end type law_listing

    !> Sets the elements `rows` of the law `name` (set_law).
    type, extends(law_action) :: law_setting
        !> The law set
        character(len=:), allocatable :: name
        !> The elements set, shape (m)
        integer, allocatable :: rows(:)
        !> Their values, shape (m)
        real(wp), allocatable :: values(:)
    contains
        procedure :: on_law => set_rows
    end type law_setting

contains

    !> The one list of the strength laws: the action gets each law with its per-element array
    !> of element_set, once, in this order: that of growth_options' new_law, which the model
    !> fingerprint hashes, so a new law goes at the end. A new law is declared in element_set
    !> (and listed in for_each_element_array) and in fault_law, and listed here; the CTest
    !> architecture fails when they disagree.
    pure subroutine for_each_law(elements, action)
        !> The set whose arrays the action gets
        type(element_set), intent(inout) :: elements
        !> What to do with each law
        class(law_action), intent(inout) :: action

        call action%on_law(law('tensile_strength', 0.0_wp, quantity_non_negative, &
                               units_stress, beyond_coulomb=.true.), elements%tensile_strength)
        call action%on_law(law('sf_residual', no_residual_drop, quantity_non_negative, &
                               units_stress, beyond_coulomb=.true., at_most='sf'), &
                           elements%sf_residual)
        call action%on_law(law('mu_dynamic', no_residual_drop, quantity_non_negative, &
                               units_one, beyond_coulomb=.true., at_most='mu'), &
                           elements%mu_dynamic)
        call action%on_law(law('slip_weakening_distance', 0.0_wp, quantity_non_negative, &
                               units_length, beyond_coulomb=.false.), &
                           elements%slip_weakening_distance)
        call action%on_law(law('opening_weakening_distance', 0.0_wp, quantity_non_negative, &
                               units_length, beyond_coulomb=.false.), &
                           elements%opening_weakening_distance)
        call action%on_law(law('shear_stiffness', rigid_joint, quantity_positive, &
                               units_stiffness, beyond_coulomb=.true.), elements%shear_stiffness)
        call action%on_law(law('normal_stiffness', rigid_joint, quantity_positive, &
                               units_stiffness, beyond_coulomb=.true.), elements%normal_stiffness)
    end subroutine for_each_law

    !> One law of the list.
    pure function law(name, default, quantity, units, beyond_coulomb, at_most) result(described)
        !> Its name
        character(len=*), intent(in) :: name
        !> Its default
        real(wp), intent(in) :: default
        !> Its range and units
        integer, intent(in) :: quantity, units
        !> Whether a value other than the default goes beyond Coulomb's law
        logical, intent(in) :: beyond_coulomb
        !> The Coulomb value it may not exceed (default none)
        character(len=*), intent(in), optional :: at_most
        type(strength_law) :: described

        described%name = name
        described%default = default
        described%quantity = quantity
        described%units = units
        described%beyond_coulomb = beyond_coulomb
        described%at_most = ''
        if (present(at_most)) described%at_most = at_most
    end function law

    !> The laws in the order of the list.
    pure function strength_laws() result(laws)
        type(strength_law) :: laws(strength_law_count)
        type(element_set) :: none
        type(law_listing) :: listing

        call for_each_law(none, listing)
        laws = listing%laws
    end function strength_laws

    !> The place in the list of the law `name`, 0 when there is none.
    pure integer function law_index(name)
        !> The law's name
        character(len=*), intent(in) :: name
        type(strength_law) :: laws(strength_law_count)
        integer :: k

        laws = strength_laws()
        law_index = 0
        do k = 1, size(laws)
            if (laws(k)%name == name) law_index = k
        end do
    end function law_index

    !> The given values of every law, column k law k, shape (n, strength_law_count).
    pure function law_values(elements) result(values)
        !> The elements, every law's array allocated
        type(element_set), intent(in) :: elements
        real(wp), allocatable :: values(:, :)
        type(element_set) :: copy
        type(law_listing) :: listing

        copy = elements
        allocate (listing%values(elements%n, strength_law_count))
        call for_each_law(copy, listing)
        call move_alloc(listing%values, values)
    end function law_values

    !> The elements `rows` of the law `name` (one of the list) take values.
    pure subroutine set_law(elements, name, rows, values)
        !> The elements, the law's array allocated
        type(element_set), intent(inout) :: elements
        !> The law's name
        character(len=*), intent(in) :: name
        !> The elements set, shape (m)
        integer, intent(in) :: rows(:)
        !> Their values, shape (m)
        real(wp), intent(in) :: values(:)
        type(law_setting) :: setting

        setting%name = name
        setting%rows = rows
        setting%values = values
        call for_each_law(elements, setting)
    end subroutine set_law

    !> The strength laws at their defaults (no tensile strength, no drops, rigid contact) on
    !> the elements where `which` holds: every element before the input gives its values, the
    !> elements of a flaw's new fracture.
    pure subroutine default_strength_laws(elements, which)
        !> The set (every law's array allocated)
        type(element_set), intent(inout) :: elements
        !> The elements to set, shape (n)
        logical, intent(in) :: which(:)
        type(strength_law) :: laws(strength_law_count)
        integer, allocatable :: rows(:)
        integer :: k, i

        laws = strength_laws()
        rows = pack([(i, i = 1, size(which))], which)
        do k = 1, size(laws)
            call set_law(elements, laws(k)%name, rows, spread(laws(k)%default, 1, size(rows)))
        end do
    end subroutine default_strength_laws

    !> Whether every law's array is allocated (a model built in part, as tests do, may lack
    !> them).
    pure logical function laws_allocated(elements)
        !> The elements
        type(element_set), intent(in) :: elements
        type(element_set) :: copy
        type(law_listing) :: listing

        copy = elements
        call for_each_law(copy, listing)
        laws_allocated = all(listing%has_array)
    end function laws_allocated

    !> The values of a law as they act: a value after slip capped by the Coulomb value it falls
    !> from (law%at_most), the given values otherwise; shape (n).
    pure function acting_values(elements, law, values) result(acting)
        !> The elements (mu and sf)
        type(element_set), intent(in) :: elements
        !> The law
        type(strength_law), intent(in) :: law
        !> Its given values, shape (n)
        real(wp), intent(in) :: values(:)
        real(wp) :: acting(size(values))

        select case (law%at_most)
        case ('sf')
            acting = min(elements%sf, values)
        case ('mu')
            acting = min(elements%mu, values)
        case default
            acting = values
        end select
    end function acting_values

    !> Why a value of the law above the Coulomb value it falls from (law%at_most) is refused;
    !> '' for a law without one.
    pure function at_most_rule(law) result(rule)
        !> The law
        type(strength_law), intent(in) :: law
        character(len=:), allocatable :: rule

        select case (law%at_most)
        case ('sf')
            rule = 'the cohesion after slip must not exceed the intact one'
        case ('mu')
            rule = 'the friction after slip must not exceed the static one'
        case default
            rule = ''
        end select
    end function at_most_rule

    !> The Coulomb value (new_sf, new_mu) that the law's value for new elements of a growth
    !> run may not exceed, and whether &growth gives one (not for a law without law%at_most).
    pure subroutine new_law_bound(growth, law, bounded, bound)
        !> The growth options
        type(growth_options), intent(in) :: growth
        !> The law
        type(strength_law), intent(in) :: law
        !> Whether the options give the Coulomb value
        logical, intent(out) :: bounded
        !> That value (0 when not bounded)
        real(wp), intent(out) :: bound

        bounded = .false.
        bound = 0.0_wp
        select case (law%at_most)
        case ('sf')
            bounded = growth%override_sf
            bound = growth%new_sf
        case ('mu')
            bounded = growth%override_mu
            bound = growth%new_mu
        case default
            ! none
        end select
    end subroutine new_law_bound

    !> Keep the law, whether its array is allocated, and its values when asked.
    pure subroutine list_law(action, law, values)
        class(law_listing), intent(inout) :: action
        type(strength_law), intent(in) :: law
        real(wp), allocatable, intent(inout) :: values(:)

        action%listed = action%listed + 1
        action%laws(action%listed) = law
        action%has_array(action%listed) = allocated(values)
        if (allocated(action%values)) action%values(:, action%listed) = values
    end subroutine list_law

    !> Set the rows of the law named.
    pure subroutine set_rows(action, law, values)
        class(law_setting), intent(inout) :: action
        type(strength_law), intent(in) :: law
        real(wp), allocatable, intent(inout) :: values(:)

        if (law%name == action%name) values(action%rows) = action%values
    end subroutine set_rows

end module ddc_model_laws
