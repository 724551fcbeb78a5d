!> The fault law of contact elements (docs/theory/strength.md): Coulomb friction and cohesion, and
!> the strength beyond Coulomb, element by element, as the given values and the values in
!> force, with the laws' rules. ddc_contact_formulation iterates the rules to a fixed point;
!> the LCP solvers (Lemke, the active-set method) see plain arrays and know nothing of it.
!>
!> - Tensile strength T: an intact element opens only when S_n' reaches T; Coulomb's law
!>   in the shifted traction S_n'' = S_n' - T is the paper's LCP with s_n - T for the
!>   resolved normal traction and Sf - mu T for Sf (shifted). T is capped at the apex
!>   Sf/mu of the Coulomb envelope, where the shear strength vanishes.
!> - Residual cohesion: with d_c = 0 an element that slipped keeps min(Sf, sf_residual)
!>   at once (weaken); with d_c > 0 the cohesion falls linearly with the slip path as the
!>   friction does, Sf(s) = Sf - (Sf - Sf_r) min(s / d_c, 1) (cohesion); with
!>   open_cohesion = 'lost' an element that opens keeps none (lose_open_cohesion).
!> - Opening weakening: with opening_weakening_distance d_o > 0 the tensile strength falls
!>   linearly with the opening w, T(w) = T (1 - min(w / d_o, 1)) (tensile); with d_o = 0 it
!>   is lost at once when the element opens. Both gradual drops regularize the singular
!>   stress at a front, so that failure loads converge with the mesh.
!> - Slip weakening: mu(s) = mu - (mu - mu_d) min(s / d_c, 1) for the slip s (the slip
!>   path, accumulated over the steps of a loading history) and mu_d = min(mu, mu_dynamic);
!>   with d_c = 0, mu_d once the element has slipped at all (friction).
!> - Elastic joint: the faces deform before they slip or open, with a shear and a normal
!>   stiffness (rigid_joint: rigid contact); ddc_solve_joints solves it with the compliance
!>   (joint_compliance).
!>
!> A new law: its given values (and values in force) here, with new_fault_law's default
!> that leaves Coulomb's law as it is and its case in set_given, its rule as a procedure of
!> fault_law, its part of beyond_coulomb, and its entry in the list of the laws that
!> ddc_model_element_laws' fault_law_of goes through (ddc_model_laws' for_each_law;
!> docs/ARCHITECTURE.md, "A new strength law").
module ddc_contact_fault_law
    use ddc_kinds, only: wp
    use ddc_contact_states, only: state_slip, state_open
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    implicit none
    private

    public :: fault_law, new_fault_law, no_residual_drop, rigid_joint, tensile_cap

    !> sf_residual and mu_dynamic of an element whose cohesion and friction do not drop
    !> after slip (the default: a sweep may change sf or mu after the input was read)
    real(wp), parameter :: no_residual_drop = huge(1.0_wp)
    !> shear_stiffness and normal_stiffness of rigid contact (the default)
    real(wp), parameter :: rigid_joint = huge(1.0_wp)

    !> The fault law of n contact elements; every array has shape (n).
    type :: fault_law
        !> Given: friction coefficient [-] and cohesion (frictional strength) [stress]
        real(wp), allocatable :: mu(:), sf(:)
        !> Given: tensile strength T >= 0 [stress] (lost once the element opens) and the
        !> cohesion after the element first slipped [stress] (no_residual_drop: no drop)
        real(wp), allocatable :: tensile_strength(:), sf_residual(:)
        !> Given: dynamic friction [-] (no_residual_drop: no drop) and slip-weakening
        !> distance d_c >= 0 of friction and cohesion [length]
        real(wp), allocatable :: mu_dynamic(:), slip_weakening_distance(:)
        !> Given: opening over which the tensile strength falls to 0 [length] (0: at once)
        real(wp), allocatable :: opening_weakening_distance(:)
        !> Given: shear and normal stiffness of an elastic joint [stress / length]
        !> (rigid_joint: rigid contact)
        real(wp), allocatable :: shear_stiffness(:), normal_stiffness(:)
        !> In force: cohesion [stress] (0 where it was lost), tensile strength [stress] (0
        !> where it was lost on opening; after a solve capped at the Coulomb apex
        !> sf_in_force/mu), friction [-] (of the last solve) and the slip path [length] (the
        !> sum of the slip increments so far: the friction memory)
        real(wp), allocatable :: sf_in_force(:), tensile_in_force(:), mu_in_force(:)
        real(wp), allocatable :: slip_path(:)
    contains
        procedure :: set_given
        procedure :: sizes_match
        procedure :: all_finite
        procedure :: any_negative
        procedure :: beyond_coulomb
        procedure :: has_joints
        procedure :: joint_compliance
        procedure :: weakens
        procedure :: weakens_gradually
        procedure :: friction
        procedure :: cohesion
        procedure :: tensile
        procedure :: shifted
        procedure :: weaken
        procedure :: lose_open_cohesion
        procedure :: place_in_force
        procedure :: take_in_force
    end type fault_law

contains

    !> The fault law of n elements from its given values: a value not given leaves
    !> Coulomb's law as it is (no tensile strength, no drop of cohesion or friction, rigid
    !> contact); the values in force are the given ones and the slip path is 0.
    pure function new_fault_law(mu, sf, tensile_strength, sf_residual, mu_dynamic, &
                                slip_weakening_distance, shear_stiffness, normal_stiffness, &
                                opening_weakening_distance) result(law)
        !> Friction coefficient [-] and cohesion [stress], shape (n)
        real(wp), intent(in) :: mu(:), sf(:)
        !> Tensile strength (default 0) and cohesion after slip (default no_residual_drop)
        !> [stress], shape (n)
        real(wp), intent(in), optional :: tensile_strength(:), sf_residual(:)
        !> Dynamic friction (default no_residual_drop) [-] and slip-weakening distance
        !> (default 0) [length], shape (n)
        real(wp), intent(in), optional :: mu_dynamic(:), slip_weakening_distance(:)
        !> Shear and normal joint stiffness (default rigid_joint) [stress / length], shape (n)
        real(wp), intent(in), optional :: shear_stiffness(:), normal_stiffness(:)
        !> Opening over which the tensile strength falls to 0 (default 0: at once)
        !> [length], shape (n)
        real(wp), intent(in), optional :: opening_weakening_distance(:)
        type(fault_law) :: law

        allocate (law%mu, source=mu)
        allocate (law%sf, source=sf)
        allocate (law%tensile_strength, source=given_or(tensile_strength, 0.0_wp))
        allocate (law%sf_residual, source=given_or(sf_residual, no_residual_drop))
        allocate (law%mu_dynamic, source=given_or(mu_dynamic, no_residual_drop))
        allocate (law%slip_weakening_distance, source=given_or(slip_weakening_distance, &
                                                               0.0_wp))
        allocate (law%opening_weakening_distance, &
                  source=given_or(opening_weakening_distance, 0.0_wp))
        allocate (law%shear_stiffness, source=given_or(shear_stiffness, rigid_joint))
        allocate (law%normal_stiffness, source=given_or(normal_stiffness, rigid_joint))
        allocate (law%sf_in_force, source=sf)
        allocate (law%tensile_in_force, source=law%tensile_strength)
        allocate (law%mu_in_force, source=mu)
        allocate (law%slip_path(size(mu)), source=0.0_wp)

    contains

        !> The given values, else the default on each of the n elements.
        pure function given_or(values, default) result(out)
            real(wp), intent(in), optional :: values(:)
            real(wp), intent(in) :: default
            real(wp), allocatable :: out(:)

            if (present(values)) then
                out = values
            else
                allocate (out(size(mu)), source=default)
            end if
        end function given_or

    end function new_fault_law

    !> Set the given values of the law beyond Coulomb's named `name`: the component of that
    !> name, as the list of the laws (ddc_model_laws' for_each_law) names it. Before a solve:
    !> the tensile strength in force is the given one, as in new_fault_law. A name that is
    !> none of them sets nothing (the CTest architecture holds the cases here to that list).
    pure subroutine set_given(law, name, values)
        !> The law of n elements
        class(fault_law), intent(inout) :: law
        !> The name of the law
        character(len=*), intent(in) :: name
        !> Its given values, shape (n)
        real(wp), intent(in) :: values(:)

        select case (name)
        case ('tensile_strength')
            law%tensile_strength = values
            law%tensile_in_force = values
        case ('sf_residual')
            law%sf_residual = values
        case ('mu_dynamic')
            law%mu_dynamic = values
        case ('slip_weakening_distance')
            law%slip_weakening_distance = values
        case ('opening_weakening_distance')
            law%opening_weakening_distance = values
        case ('shear_stiffness')
            law%shear_stiffness = values
        case ('normal_stiffness')
            law%normal_stiffness = values
        case default
            ! not a law of this type
        end select
    end subroutine set_given

    !> Whether every value is there for n elements.
    pure logical function sizes_match(law, n)
        !> The law
        class(fault_law), intent(in) :: law
        !> Number of elements
        integer, intent(in) :: n

        sizes_match = allocated(law%mu) .and. allocated(law%sf) .and. &
            allocated(law%tensile_strength) .and. allocated(law%sf_residual) .and. &
            allocated(law%mu_dynamic) .and. allocated(law%slip_weakening_distance) .and. &
            allocated(law%opening_weakening_distance) .and. allocated(law%shear_stiffness) &
            .and. allocated(law%normal_stiffness) .and. &
            allocated(law%sf_in_force) .and. allocated(law%tensile_in_force) .and. &
            allocated(law%mu_in_force) .and. allocated(law%slip_path)
        if (sizes_match) sizes_match = all([size(law%mu), size(law%sf), &
            size(law%tensile_strength), size(law%sf_residual), size(law%mu_dynamic), &
            size(law%slip_weakening_distance), size(law%opening_weakening_distance), &
            size(law%shear_stiffness), &
            size(law%normal_stiffness), size(law%sf_in_force), size(law%tensile_in_force), &
            size(law%mu_in_force), size(law%slip_path)] == n)
    end function sizes_match

    !> Whether the friction and the cohesion and tensile strength in force are finite.
    pure logical function all_finite(law)
        !> The law
        class(fault_law), intent(in) :: law

        all_finite = all(ieee_is_finite(law%mu)) .and. all(ieee_is_finite(law%sf_in_force)) &
            .and. all(ieee_is_finite(law%tensile_in_force))
    end function all_finite

    !> Whether a value the contact solve reads is negative (none may be).
    pure logical function any_negative(law)
        !> The law
        class(fault_law), intent(in) :: law

        any_negative = any(law%mu < 0.0_wp) .or. any(law%sf_in_force < 0.0_wp) .or. &
            any(law%tensile_in_force < 0.0_wp) .or. any(law%sf_residual < 0.0_wp) .or. &
            any(law%mu_dynamic < 0.0_wp) .or. any(law%slip_weakening_distance < 0.0_wp) .or. &
            any(law%opening_weakening_distance < 0.0_wp) .or. any(law%slip_path < 0.0_wp)
    end function any_negative

    !> Whether any element's law goes beyond Coulomb's: a tensile strength, a drop of
    !> cohesion or friction after slip, or an elastic joint.
    pure logical function beyond_coulomb(law)
        !> The law
        class(fault_law), intent(in) :: law

        beyond_coulomb = any(law%tensile_strength > 0.0_wp) .or. &
            any(law%sf_residual < law%sf) .or. law%weakens() .or. law%has_joints()
    end function beyond_coulomb

    !> Whether any element has an elastic joint (a finite stiffness).
    pure logical function has_joints(law)
        !> The law
        class(fault_law), intent(in) :: law

        has_joints = any(law%shear_stiffness < rigid_joint) .or. &
            any(law%normal_stiffness < rigid_joint)
    end function has_joints

    !> [1/k_s; 1/k_n] of the joints (0 for rigid_joint), shape (2n) [length / stress].
    pure function joint_compliance(law) result(compliance)
        !> The law
        class(fault_law), intent(in) :: law
        real(wp), allocatable :: compliance(:)

        compliance = [law%shear_stiffness, law%normal_stiffness]
        where (compliance >= rigid_joint)
            compliance = 0.0_wp
        elsewhere
            compliance = 1.0_wp / compliance
        end where
    end function joint_compliance

    !> Whether the friction of any element drops with slip (slip weakening).
    pure logical function weakens(law)
        !> The law
        class(fault_law), intent(in) :: law

        weakens = any(law%mu_dynamic < law%mu)
    end function weakens

    !> Whether any element's cohesion falls with slip over d_c > 0 or its tensile strength
    !> with opening over d_o > 0: strengths that the iteration must bring to a fixed point
    !> (weaken).
    pure logical function weakens_gradually(law)
        !> The law
        class(fault_law), intent(in) :: law

        weakens_gradually = any(law%slip_weakening_distance > 0.0_wp .and. &
                                law%sf_residual < law%sf) .or. &
            any(law%opening_weakening_distance > 0.0_wp .and. law%tensile_strength > 0.0_wp)
    end function weakens_gradually

    !> Cohesion after a slip path s: Sf - (Sf - Sf_r) min(s / d_c, 1) with Sf_r =
    !> min(Sf, sf_residual), where d_c > 0; Sf elsewhere (there weaken drops it at once);
    !> shape (n) [stress].
    pure function cohesion(law, s) result(sf_s)
        !> The law
        class(fault_law), intent(in) :: law
        !> Slip path of each element [length], shape (n)
        real(wp), intent(in) :: s(:)
        real(wp) :: sf_s(size(s))
        real(wp) :: ratio(size(s))

        ratio = 0.0_wp
        where (law%slip_weakening_distance > 0.0_wp) &
            ratio = min(s / law%slip_weakening_distance, 1.0_wp)
        sf_s = law%sf - (law%sf - min(law%sf, law%sf_residual)) * ratio
    end function cohesion

    !> Tensile strength after an opening w: T (1 - min(w / d_o, 1)) where d_o > 0; T
    !> elsewhere (there weaken drops it at once); shape (n) [stress].
    pure function tensile(law, w) result(t_w)
        !> The law
        class(fault_law), intent(in) :: law
        !> Opening of each element (-Dn, 0 where closed) [length], shape (n)
        real(wp), intent(in) :: w(:)
        real(wp) :: t_w(size(w))
        real(wp) :: ratio(size(w))

        ratio = 0.0_wp
        where (law%opening_weakening_distance > 0.0_wp) &
            ratio = min(max(w, 0.0_wp) / law%opening_weakening_distance, 1.0_wp)
        t_w = law%tensile_strength * (1.0_wp - ratio)
    end function tensile

    !> Friction after a slip path s: mu - (mu - mu_d) min(s / d_c, 1) with mu_d =
    !> min(mu, mu_dynamic); with d_c = 0, mu_d where the element has slipped (s > 0 or
    !> state slip); shape (n) [-].
    pure function friction(law, s, state) result(mu_f)
        !> The law
        class(fault_law), intent(in) :: law
        !> Slip path of each element [length], shape (n)
        real(wp), intent(in) :: s(:)
        !> States of the last solve (ddc_contact_states), shape (n)
        integer, intent(in) :: state(:)
        real(wp) :: mu_f(size(s))
        real(wp) :: ratio(size(s)), mu_d(size(s))

        mu_d = min(law%mu, law%mu_dynamic)
        ratio = 0.0_wp
        where (law%slip_weakening_distance > 0.0_wp)
            ratio = min(s / law%slip_weakening_distance, 1.0_wp)
        elsewhere (s > 0.0_wp .or. state == state_slip)
            ratio = 1.0_wp
        end where
        mu_f = law%mu - (law%mu - mu_d) * ratio
        where (.not. mu_d < law%mu) mu_f = law%mu
    end function friction

    !> The shifted Coulomb law of the values in force: sf_in = sf - mu T, s_n_in = s_n - T
    !> with T the tensile strength capped at the apex sf/mu. With T = 0 these are sf and
    !> s_n, bit for bit.
    pure subroutine shifted(law, s_n, sf_in, s_n_in, cap)
        !> The law (friction, cohesion and tensile strength in force)
        class(fault_law), intent(in) :: law
        !> Resolved normal traction [stress], shape (n)
        real(wp), intent(in) :: s_n(:)
        !> Cohesion and resolved normal traction of the shifted law [stress], shape (n)
        real(wp), allocatable, intent(out) :: sf_in(:), s_n_in(:)
        !> T in force [stress], shape (n)
        real(wp), allocatable, intent(out) :: cap(:)

        associate (mu => law%mu_in_force, sf => law%sf_in_force)
            cap = tensile_cap(law%tensile_in_force, sf, mu)
            sf_in = max(sf - mu * cap, 0.0_wp)
            s_n_in = s_n - cap
        end associate
    end subroutine shifted

    !> The tensile strength T capped at the Coulomb apex sf/mu, where the shear strength
    !> sf - mu T of the shifted law would turn negative; T where it is below the apex.
    elemental function tensile_cap(tensile_strength, sf, mu) result(cap)
        !> Tensile strength T >= 0, cohesion sf >= 0 [stress]
        real(wp), intent(in) :: tensile_strength, sf
        !> Friction coefficient [-]
        real(wp), intent(in) :: mu
        !> min(T, sf/mu) [stress]
        real(wp) :: cap

        cap = tensile_strength
        if (mu * tensile_strength > sf) cap = sf / mu
    end function tensile_cap

    !> After a solve: with d_o = 0, elements that opened lose their tensile strength, and
    !> with d_c = 0 elements that slipped drop their cohesion to min(sf_in_force,
    !> sf_residual), at once; with d_o > 0 or d_c > 0 the strength in force falls to that of
    !> the law at the opening or slip path (tensile, cohesion; never upwards), when that
    !> lowers some strength by more than tol. True when any strength in force changed.
    function weaken(law, state, s, w, tol, moving) result(changed)
        !> The law; its tensile strength and cohesion in force change
        class(fault_law), intent(inout) :: law
        !> States of the solve (ddc_contact_states), shape (n)
        integer, intent(in) :: state(:)
        !> Slip path after the solve [length], shape (n)
        real(wp), intent(in) :: s(:)
        !> Opening after the solve (-Dn) [length], shape (n)
        real(wp), intent(in) :: w(:)
        !> Smallest drop of a gradual strength that counts as a change [stress]
        real(wp), intent(in) :: tol
        !> The element whose gradual strength fell most, by more than tol; 0 if none did
        integer, intent(out) :: moving
        logical :: changed
        logical :: opened(size(state)), slipped(size(state))
        real(wp) :: sf_after(size(state)), t_after(size(state)), drop(size(state))

        sf_after = min(law%sf_in_force, law%sf_residual)
        opened = state == state_open .and. law%tensile_in_force > 0.0_wp .and. &
            .not. law%opening_weakening_distance > 0.0_wp
        slipped = state == state_slip .and. law%sf_in_force > sf_after .and. &
            .not. law%slip_weakening_distance > 0.0_wp
        changed = any(opened) .or. any(slipped)
        where (opened) law%tensile_in_force = 0.0_wp
        where (slipped) law%sf_in_force = sf_after
        moving = 0
        if (.not. law%weakens_gradually()) return
        sf_after = min(law%sf_in_force, law%cohesion(s))
        t_after = min(law%tensile_in_force, law%tensile(w))
        drop = max(law%sf_in_force - sf_after, law%tensile_in_force - t_after)
        if (.not. maxval(drop) > tol) return
        moving = maxloc(drop, 1)
        changed = .true.
        law%sf_in_force = sf_after
        law%tensile_in_force = t_after
    end function weaken

    !> open_cohesion = 'lost': zero the cohesion in force of every open element that still
    !> has some; true when any did.
    function lose_open_cohesion(law, state) result(changed)
        !> The law; its cohesion in force changes
        class(fault_law), intent(inout) :: law
        !> States of the solve (ddc_contact_states), shape (n)
        integer, intent(in) :: state(:)
        logical :: changed
        logical :: lose(size(state))

        lose = state == state_open .and. law%sf_in_force > 0.0_wp
        changed = any(lose)
        where (lose) law%sf_in_force = 0.0_wp
    end function lose_open_cohesion

    !> The values in force of the elements `subset` from the law of those elements (part),
    !> 0 on the others (elements without contact).
    pure subroutine place_in_force(law, part, subset)
        !> The law of every element; its values in force are set
        class(fault_law), intent(inout) :: law
        !> The law of the elements `subset`, shape (m)
        type(fault_law), intent(in) :: part
        !> Indices of those elements in law, shape (m)
        integer, intent(in) :: subset(:)

        law%sf_in_force = 0.0_wp
        law%tensile_in_force = 0.0_wp
        law%mu_in_force = 0.0_wp
        law%slip_path = 0.0_wp
        law%sf_in_force(subset) = part%sf_in_force
        law%tensile_in_force(subset) = part%tensile_in_force
        law%mu_in_force(subset) = part%mu_in_force
        law%slip_path(subset) = part%slip_path
    end subroutine place_in_force

    !> The values in force and slip path of some elements from those of another law's
    !> elements (an element carried over from an earlier solve keeps its state); the others
    !> keep theirs.
    pure subroutine take_in_force(law, other, source)
        !> The law of n elements; values in force set where source > 0
        class(fault_law), intent(inout) :: law
        !> The law the states come from
        type(fault_law), intent(in) :: other
        !> The element of other each element of law takes its state from, 0: none, shape (n)
        integer, intent(in) :: source(:)

        where (source > 0)
            law%sf_in_force = other%sf_in_force(max(source, 1))
            law%tensile_in_force = other%tensile_in_force(max(source, 1))
            law%mu_in_force = other%mu_in_force(max(source, 1))
            law%slip_path = other%slip_path(max(source, 1))
        end where
    end subroutine take_in_force

end module ddc_contact_fault_law
