!> The fingerprint of a model: a 64-bit FNV-1a hash (Fowler, Noll, Vo) of everything in the
!> validated model that determines the result, written as 16 hex digits. Two inputs with
!> the same fingerprint solve the same problem; a run resumed from an earlier result file
!> (--resume) must have the fingerprint that file records.
!>
!>     h_0 = 14695981039346656037,   h_k = (h_{k-1} xor byte_k) * (2**40 + 435)  mod 2**64
!>
!> over the bytes of each value (reals and integers as stored), each array preceded by its
!> size and each text by its length. Not hashed, so that a resumed run may go further: the
!> growth steps, the load path (its steps and vertices; whether there is one is hashed), and
!> what does not change the solution (title, file names, input text, the sweep record, the
!> memory limit of this machine). The per-element arrays go through for_each_element_array,
!> so a new one is hashed without a change here; the CTest architecture fails when another
!> component is neither hashed in hash_model nor marked there as not hashed.
module ddc_model_fingerprint
    use, intrinsic :: iso_fortran_env, only: int8, int64
    use ddc_kinds, only: wp
    use ddc_contact_options, only: k_auto, default_k_zone_elements
    use ddc_model_types, only: model_type, growth_criterion_work, element_set, &
        element_array_action, for_each_element_array, domain_bimaterial
    implicit none
    private

    public :: model_fingerprint, recorded_fingerprint, fingerprint_length

    !> Length of a fingerprint's text (hex digits)
    integer, parameter :: fingerprint_length = 16

    !> The hash state: the low and high 32 bits of h, each in [0, 2**32), so that every
    !> product fits an int64 (no signed overflow).
    type, extends(element_array_action) :: fnv_hash
        integer(int64) :: low = int(z'84222325', int64), high = int(z'CBF29CE4', int64)
    contains
        procedure :: on_reals => hash_element_reals
        procedure :: on_integers => hash_element_integers
        procedure :: on_later_law => hash_later_law
    end type fnv_hash

    integer(int64), parameter :: mask32 = int(z'FFFFFFFF', int64)

contains

    !> The fingerprint of a model, 16 hex digits (upper case).
    function model_fingerprint(model) result(text)
        !> A validated model, before any run changed it
        type(model_type), intent(in) :: model
        !> The hash as text
        character(len=fingerprint_length) :: text
        type(fnv_hash) :: hash

        call hash_model(model, hash)
        write (text, '(z8.8, z8.8)') hash%high, hash%low
    end function model_fingerprint

    !> The fingerprint app recorded in the model before the run (model%fingerprint), or the
    !> model's own when none was recorded (a model that no run has changed).
    function recorded_fingerprint(model) result(text)
        !> The model
        type(model_type), intent(in) :: model
        !> The fingerprint, 16 hex digits
        character(len=fingerprint_length) :: text

        if (allocated(model%fingerprint)) then
            text = model%fingerprint
        else
            text = model_fingerprint(model)
        end if
    end function recorded_fingerprint

    !> Every component of the model that determines the result, in a fixed order.
    subroutine hash_model(model, hash)
        type(model_type), intent(in) :: model
        type(fnv_hash), intent(inout) :: hash
        type(element_set) :: elements
        integer :: i

        ! Not hashed: model%title, model%output_file, model%input_file (names only)
        ! Not hashed: model%input_text (holds steps and the path; its parsed values count)
        ! Not hashed: model%solver%k_extrapolation (not an input: the same K to the
        ! coupling's tolerance either way)
        ! Not hashed: model%sweep (a record; --resume is refused for sweep tasks)
        ! Not hashed: model%fingerprint (this hash)
        ! Not hashed: model%resumed_from, model%resumed_from_created (a record of the run)
        ! Not hashed: model%growth%steps, model%load_path%steps, model%load_path%vertex
        ! Not hashed: model%load_path%varies (a resumed run may go further)
        ! Not hashed: model%cycle%active (the options below are hashed when it holds)
        ! Not hashed: model%load_path%time (as the vertices: a resumed run may go further)
        ! Not hashed: model%solver%work_bytes (this machine's memory, not the model)
        ! Not hashed: model%solver%matrix (it changes a result within hmatrix_tolerance
        ! only: a loading history may go on from its file on either matrix), and so its
        ! settings:
        ! Not hashed: model%solver%hmatrix_tolerance (as matrix)
        ! Not hashed: model%solver%hmatrix_leaf_size (as matrix)
        ! Not hashed: model%solver%hmatrix_eta (as matrix)
        call add_reals(hash, [model%youngs_modulus, model%poissons_ratio])
        call add_text(hash, model%length_unit)
        call add_text(hash, model%stress_unit)
        ! Only where not the default: the fingerprints of earlier models stay as they were.
        if (allocated(model%time_unit)) then
            if (model%time_unit /= 's') call add_text(hash, model%time_unit)
        end if
        if (allocated(model%injections)) then
            do i = 1, size(model%injections)
                call add_text(hash, model%injections(i)%name)
                call add_integers(hash, [model%injections(i)%fracture_id, &
                                         model%injections(i)%kind])
                call add_reals(hash, [model%injections(i)%x, model%injections(i)%y, &
                                      model%injections(i)%value, model%injections(i)%start, &
                                      model%injections(i)%stop])
            end do
        end if
        ! Only with coupled flow: the other models keep their fingerprints.
        if (model%fluid%active) then
            call add_reals(hash, [model%fluid%viscosity, model%fluid%compressibility, &
                                  model%fluid%leak_off_coefficient])
        end if
        ! Only with a finite body: the other models keep their fingerprints.
        if (allocated(model%body)) then
            call add_reals(hash, [model%body%x, model%body%y, model%body%bc_s, model%body%bc_n, &
                                  model%body%bc_s_end, model%body%bc_n_end])
            call add_integers(hash, [model%body%elements, model%body%condition])
        end if
        ! Not hashed: model%body%orientation, model%body%xm, model%body%ym, model%body%a
        ! Not hashed: model%body%cosb, model%body%sinb, model%body%side, model%body%node_x
        ! Not hashed: model%body%node_y, model%body%given_s, model%body%given_n (the
        ! geometry and values at the nodes follow from the sides hashed above)
        ! Not hashed: model%body%factors, model%body%pivots, model%body%loaded
        ! Not hashed: model%body%free_motions, model%body%left_null, model%body%left_null_gram
        ! (the solved system, made before a solve)
        call add_reals(hash, [model%sxx, model%syy, model%sxy])
        call add_reals(hash, model%stress_gradient)
        call add_reals(hash, model%pore_fluid)
        call add_integers(hash, [model%elements%n, model%elements%domain, &
                                 model%elements%symmetry%kind])
        ! Only in two bonded half-planes: the other models keep their fingerprints.
        if (model%elements%domain == domain_bimaterial) then
            call add_reals(hash, [model%interface_y, model%upper_youngs_modulus, &
                                  model%upper_poissons_ratio])
        end if
        call add_reals(hash, [model%elements%symmetry%xsym, model%elements%symmetry%ysym])
        elements = model%elements
        call for_each_element_array(elements, hash)
        call add_integers(hash, [size(model%fractures)])
        do i = 1, size(model%fractures)
            call add_text(hash, model%fractures(i)%name)
            call add_integers(hash, [model%fractures(i)%first_element, &
                                     model%fractures(i)%last_element])
        end do
        call add_integers(hash, [size(model%observations)])
        do i = 1, size(model%observations)
            call add_text(hash, model%observations(i)%name)
            call add_integers(hash, [model%observations(i)%kind, model%observations(i)%nx, &
                                     model%observations(i)%ny])
            call add_allocated_reals(hash, model%observations(i)%x)
            call add_allocated_reals(hash, model%observations(i)%y)
        end do
        call add_integers(hash, [model%solver%lcp_method, model%solver%open_cohesion, &
                                 model%block_size])
        ! The K method where it is given (the default leaves earlier fingerprints as they were).
        if (model%solver%k_method /= k_auto) call add_integers(hash, [model%solver%k_method])
        if (model%solver%k_zone_elements /= default_k_zone_elements) then
            call add_integers(hash, [model%solver%k_zone_elements])
        end if
        call add_integers(hash, merge(1, 0, [allocated(model%load_path%vertex), &
                                             model%growth%active]))
        call add_reals(hash, [model%growth%toughness, model%growth%increment, &
                              model%growth%element_length, model%growth%new_mu, &
                              model%growth%new_sf])
        call add_integers(hash, [model%growth%tips, model%growth%criterion, &
                                 model%growth%max_corrections])
        call add_integers(hash, merge(1, 0, [model%growth%override_mu, &
                                             model%growth%override_sf]))
        ! Only the work criterion reads them: other models keep their fingerprints.
        if (model%growth%criterion == growth_criterion_work) then
            call add_reals(hash, [model%growth%angle_range, model%growth%angle_step, &
                                  model%growth%work_threshold])
            ! Always: a result of the search before angle_search (every angle of the range)
            ! is not resumed by the seeded search.
            call add_integers(hash, [model%growth%work_mode, model%growth%angle_search])
        end if
        ! Only when given: the fingerprints of models without them stay as they were.
        if (any(model%growth%override_law)) then
            call add_integers(hash, merge(1, 0, model%growth%override_law))
            call add_reals(hash, model%growth%new_law)
        end if
        if (allocated(model%growth%fracture_grows)) then
            call add_integers(hash, merge(1, 0, model%growth%fracture_grows))
        else
            call add_integers(hash, [-1])
        end if
        ! Only a model with &initiation hashes its options: every other model's fingerprint
        ! stays as it was.
        if (model%initiation%active) then
            call add_reals(hash, [model%initiation%tensile_strength, &
                                  model%initiation%probe_distance, model%initiation%flaw_length])
            call add_allocated_reals(hash, model%initiation%flaw_x)
            call add_allocated_reals(hash, model%initiation%flaw_y)
        end if
        ! Only a cycle model hashes its options and time unit: every other model's
        ! fingerprint stays as it was.
        ! Not hashed: model%cycle%end_time (a resumed run may go further)
        ! Not hashed: model%cycle%checkpoint_interval (when the file is written, not what)
        if (model%cycle%active) then
            call add_text(hash, model%time_unit)
            call add_integers(hash, [model%cycle%state_law])
            call add_reals(hash, [model%cycle%tolerance, model%cycle%radiation_damping, &
                                  model%cycle%shear_wave_speed, model%cycle%plate_rate, &
                                  model%cycle%seismic_threshold, model%cycle%output_interval, &
                                  model%cycle%event_output_interval, &
                                  model%cycle%profile_spacing])
        end if
    end subroutine hash_model

    !> Hash one real per-element array.
    subroutine hash_element_reals(action, values)
        class(fnv_hash), intent(inout) :: action
        real(wp), allocatable, intent(inout) :: values(:)

        call add_allocated_reals(action, values)
    end subroutine hash_element_reals

    !> Hash a per-element array of a law added later only where it is not all 0 (its
    !> default, which leaves the law as it was): models that do not use the law keep the
    !> fingerprint that earlier versions recorded, so their result files can be resumed.
    subroutine hash_later_law(action, values)
        class(fnv_hash), intent(inout) :: action
        real(wp), allocatable, intent(inout) :: values(:)

        if (.not. allocated(values)) return
        if (any(values /= 0.0_wp)) call add_allocated_reals(action, values)
    end subroutine hash_later_law

    !> Hash a real array (its size first; -1 when unallocated).
    subroutine add_allocated_reals(hash, values)
        class(fnv_hash), intent(inout) :: hash
        real(wp), allocatable, intent(in) :: values(:)

        if (allocated(values)) then
            call add_reals(hash, values)
        else
            call add_integers(hash, [-1])
        end if
    end subroutine add_allocated_reals

    !> Hash one integer per-element array (its size first; -1 when unallocated).
    subroutine hash_element_integers(action, values)
        class(fnv_hash), intent(inout) :: action
        integer, allocatable, intent(inout) :: values(:)

        if (allocated(values)) then
            call add_integers(action, values)
        else
            call add_integers(action, [-1])
        end if
    end subroutine hash_element_integers

    !> Hash reals: their number, then their bytes.
    subroutine add_reals(hash, values)
        class(fnv_hash), intent(inout) :: hash
        real(wp), intent(in) :: values(:)

        call add_bytes(hash, transfer(size(values), [0_int8]))
        if (size(values) > 0) call add_bytes(hash, transfer(values, [0_int8]))
    end subroutine add_reals

    !> Hash integers: their number, then their bytes.
    subroutine add_integers(hash, values)
        class(fnv_hash), intent(inout) :: hash
        integer, intent(in) :: values(:)

        call add_bytes(hash, transfer(size(values), [0_int8]))
        if (size(values) > 0) call add_bytes(hash, transfer(values, [0_int8]))
    end subroutine add_integers

    !> Hash a text: its length (-1 when unallocated), then its characters.
    subroutine add_text(hash, text)
        class(fnv_hash), intent(inout) :: hash
        character(len=:), allocatable, intent(in) :: text

        if (.not. allocated(text)) then
            call add_integers(hash, [-1])
            return
        end if
        call add_integers(hash, [len(text)])
        if (len(text) > 0) call add_bytes(hash, transfer(text, [0_int8], len(text)))
    end subroutine add_text

    !> FNV-1a over bytes: h = (h xor byte) * (2**40 + 435) mod 2**64, on 32-bit halves.
    subroutine add_bytes(hash, bytes)
        class(fnv_hash), intent(inout) :: hash
        integer(int8), intent(in) :: bytes(:)
        integer(int64) :: low, high, product
        integer :: i

        low = hash%low
        high = hash%high
        do i = 1, size(bytes)
            low = ieor(low, iand(int(bytes(i), int64), 255_int64))
            ! h * 435 on both halves, plus h * 2**40: the low 24 bits of low moved up 8.
            product = low * 435_int64
            high = iand(high * 435_int64 + shiftr(product, 32) + &
                        shiftl(iand(low, int(z'FFFFFF', int64)), 8), mask32)
            low = iand(product, mask32)
        end do
        hash%low = low
        hash%high = high
    end subroutine add_bytes

end module ddc_model_fingerprint
