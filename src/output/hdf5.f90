!> The HDF5 result file (docs/output-reference.md), written atomically.
!>
!> The file is written under partial_name(path) and renamed to path only when every group,
!> dataset and attribute has been written and the file closed; on any failure the partial
!> file is removed. Handles and typed writes are ddc_output_hdf5_handles' and
!> ddc_output_hdf5_write's; this module holds the layout. As seen from h5py:
!>
!> - root attributes: program, version, git_commit, created (UTC), where the result came
!>   from (blas, blas_core, blas_core_chosen_by, compiler, compiler_options, cpu, threads,
!>   blas_threads: ddc_output_provenance), title, input_file, input_text, units, elastic
!>   constants, remote_stress [sxx, syy, sxy], conventions, open_cohesion, lcp_method,
!>   domain, remote_stress_gradient, pore_fluid, model_fingerprint (ddc_model_fingerprint:
!>   what --resume compares), resumed_from and resumed_from_created (a resumed run only: the
!>   file it continued and that file's created), and last complete = 1;
!> - /elements/<quantity> shape (n), every real dataset with a `units` attribute;
!> - /fractures/{name, first_element, last_element};
!> - /tips/{x, y, fracture_id, element, k1, k2, graded} (empty datasets when there are no
!>   tips) and the attribute k_method (how K was computed);
!> - /fields/<name>/{x, y, ux, uy, sxx, syy, sxy, near_element}, grids shaped (ny, nx)
!>   in h5py (Fortran dims (nx, ny)), lines and point lists 1-D;
!> - /solver attributes (blas and blas_core among them) and /solver/seconds/<phase> scalar
!>   datasets;
!> - /sweep attributes task, tasks, parameters and one per parameter (sweep tasks only);
!> - /history (loading history only, docs/loading-histories.md#output; k steps, the first the
!>   starting state) and /growth (fracture growth only, docs/fracture-growth.md#output; k records,
!>   one per tip per step): one dataset per column of the record (ddc_model_records' lists, written
!>   by ddc_output_hdf5_records), a column of rows and steps shaped (k, rows) in h5py (Fortran
!>   dims (rows, k)); /history/leg_steps (increments per leg) and the load quantities the
!>   path varies (the remote stress always); /growth attributes toughness, increment,
!>   element_length, tips, criterion, max_corrections, fractures, steps, steps_taken,
!>   end_reason, reason_coding; /elements/created_step. /elements hold the last step of a
!>   history; /elements, /tips and /fields describe the final geometry of a growth run;
!> - /cycle (earthquake cycles only, docs/output-reference.md#cycle: ddc_output_hdf5_cycle)
!>   and the rate-and-state values in /elements; /elements, /tips and /fields then hold the
!>   run's last state (its back-slip DDs).
module ddc_output_hdf5
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_internal_error
    use ddc_version, only: program_name, program_version, git_commit
    use ddc_model_types, only: model_type, observation_grid, observation_kind_names, &
        symmetry_names, domain_names, strength_law_count, domain_bimaterial
    use ddc_model_laws, only: strength_law, strength_laws, law_values, acting_values
    use ddc_model_loads, only: static_pressure, shear_modulus_of
    use ddc_model_fingerprint, only: recorded_fingerprint
    use ddc_model_results, only: model_results, boundary_results, state_free, state_stick, &
        state_slip, state_open
    use ddc_model_records, only: state_coding, units_text
    use ddc_contact_options, only: lcp_method_names, open_cohesion_names
    use ddc_output_atomic, only: partial_name, publish_file, remove_file, resolve_target, &
        explain_write_failure
    use ddc_output_hdf5_handles, only: h5_object, open_session, close_session, create_file, &
        close_file, create_group, close_group
    use ddc_output_hdf5_injections, only: write_injections
    use ddc_output_hdf5_initiations, only: write_initiations
    use ddc_output_hdf5_records, only: write_history, write_growth, write_growth_elements
    use ddc_output_hdf5_cycle, only: write_cycle, write_rate_state
    use ddc_output_hdf5_write, only: write_real_1d, write_int_1d, write_real_dataset, &
        write_int_dataset, write_string_1d, write_attribute
    use ddc_output_timestamp, only: utc_timestamp
    use ddc_output_provenance, only: run_provenance, describe_run
    use ddc_text, only: itoa, allocated_text
    implicit none
    private

    public :: write_results

    !> Sign and face conventions stored in every file
    !> Longest input text stored as the root attribute input_text [bytes]
    integer, parameter :: max_attribute_text = 60000
    character(len=*), parameter :: conventions = 'stress tension positive; Crouch & ' &
        //'Starfield displacement discontinuities: ds = us(-) - us(+), dn = un(-) - un(+), ' &
        //'opening = -dn; positive face on the left of the element direction'
    !> Codings stored as attributes of the integer datasets
    character(len=*), parameter :: condition_coding = '1 traction, 2 displacement, ' &
        //'3 mixed_us_sn, 4 mixed_ss_un, 5 contact, 6 prescribed_dd'
    !> What a cycle model's coding adds (the files of other models stay as they were)
    character(len=*), parameter :: rate_state_coding = ', 7 rate_state'
    character(len=*), parameter :: graded_coding = '0 the elements near the tip as long '// &
        'as the tip element, 1 graded mesh at the tip (K less accurate)'
    character(len=*), parameter :: near_coding = '0 clear, 1 within one element length ' &
        //'of an element centre (reduced accuracy), 2 on an element or at an element end ' &
        //'(value NaN)'
    !> The same in a finite body, whose outside has no rock
    character(len=*), parameter :: near_coding_body = near_coding//', 3 outside the body '// &
        'or on its boundary (value NaN)'

contains

    !> Write the result file: to partial_name(path) first, published to path on success.
    subroutine write_results(path, model, results, error)
        !> Path of the final result file
        character(len=*), intent(in) :: path
        !> The model that was solved
        type(model_type), intent(in) :: model
        !> Its results; results%fields(i) belongs to model%observations(i)
        type(model_results), intent(in) :: results
        !> Allocated with exit_io_failure when the file cannot be written
        type(error_type), allocatable, intent(out) :: error
        type(h5_object) :: root
        type(run_provenance) :: provenance
        character(len=:), allocatable :: temporary, final_path
        integer(int64) :: start, now, rate

        call check_consistency(model, results, error)
        if (allocated(error)) return
        call system_clock(start, rate)
        provenance = describe_run()
        call resolve_target(path, final_path, error)
        if (allocated(error)) return
        temporary = partial_name(final_path)
        call open_session(error)
        if (allocated(error)) return
        call create_file(temporary, root, error)
        if (.not. allocated(error)) then
            call write_root_attributes(root, model, provenance, error)
            call write_elements(root, model, results, error)
            call write_fractures(root, model, error)
            call write_injections(root, model, error)
            call write_tips(root, model, results, error)
            call write_fields(root, model, results, error)
            if (allocated(results%boundary%x)) call write_boundary(root, model, &
                                                                   results%boundary, error)
            ! The file's own writing time: everything written before the solver record.
            call system_clock(now)
            call write_solver(root, results, provenance, real(now - start, wp) / &
                              real(rate, wp), error)
            if (model%sweep%tasks > 0) call write_sweep(root, model, error)
            if (allocated(results%history%ds)) call write_history(root, model, &
                                                                  results%history, error)
            if (allocated(results%growth%step)) call write_growth(root, model, results%growth, &
                                                                  error)
            if (allocated(results%growth%step)) call write_initiations(root, model, &
                                                                       results%initiations, error)
            if (allocated(results%cycle%elements)) call write_cycle(root, model, results%cycle, &
                                                                    error)
            ! A run that stopped early says so beside its complete record of the steps it made.
            if (allocated(results%stopped)) call write_attribute(root, 'stopped', &
                                                                 results%stopped, error)
            call write_attribute(root, 'complete', 1, error)
            call close_file(root, error)
        end if
        call close_session()

        if (.not. allocated(error)) then
            call publish_file(temporary, final_path, error)
        else
            call explain_write_failure(final_path, temporary, error)
        end if
        if (allocated(error)) call remove_file(temporary)
    end subroutine write_results

    !> Refuse results whose sizes do not match the model (a programming error).
    subroutine check_consistency(model, results, error)
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: results
        type(error_type), allocatable, intent(out) :: error
        integer :: n, n_sets

        n = model%elements%n
        if (.not. allocated(results%elements%ds) .or. .not. allocated(results%elements%state)) &
            then
            call set_internal_error(error, 'write_results', 'no element results to write')
            return
        end if
        if (size(results%elements%ds) /= n .or. size(results%elements%state) /= n) then
            call set_internal_error(error, 'write_results', &
                                    'element results and model differ in size')
            return
        end if
        n_sets = 0
        if (allocated(model%observations)) n_sets = size(model%observations)
        if (n_sets > 0) then
            if (.not. allocated(results%fields)) then
                call set_internal_error(error, 'write_results', 'no field results')
            else if (size(results%fields) /= n_sets) then
                call set_internal_error(error, 'write_results', &
                                        'field results and observation sets differ in number')
            end if
        end if
    end subroutine check_consistency

    !> Self-description: program, version, date, input, units, elasticity, conventions.
    subroutine write_root_attributes(root, model, provenance, error)
        type(h5_object), intent(in) :: root
        type(model_type), intent(in) :: model
        type(run_provenance), intent(in) :: provenance
        type(error_type), allocatable, intent(inout) :: error

        call write_attribute(root, 'program', program_name, error)
        call write_attribute(root, 'version', program_version, error)
        call write_attribute(root, 'git_commit', git_commit, error)
        call write_attribute(root, 'created', utc_timestamp(), error)
        ! Where the result came from (ddc_output_provenance).
        call write_attribute(root, 'blas', provenance%blas, error)
        call write_attribute(root, 'blas_core', provenance%blas_core, error)
        call write_attribute(root, 'blas_core_chosen_by', provenance%blas_core_chosen_by, error)
        call write_attribute(root, 'compiler', provenance%compiler, error)
        call write_attribute(root, 'compiler_options', provenance%options, error)
        call write_attribute(root, 'cpu', provenance%cpu, error)
        call write_attribute(root, 'threads', provenance%threads, error)
        call write_attribute(root, 'blas_threads', provenance%blas_threads, error)
        call write_attribute(root, 'title', allocated_text(model%title), error)
        call write_attribute(root, 'input_file', allocated_text(model%input_file), error)
        ! An attribute holds at most 64 KiB (HDF5's object header); a longer input goes to
        ! the dataset /input_text, and the attribute says so.
        if (len(allocated_text(model%input_text)) <= max_attribute_text) then
            call write_attribute(root, 'input_text', allocated_text(model%input_text), error)
        else
            call write_attribute(root, 'input_text', 'the input ('// &
                itoa(len(allocated_text(model%input_text)))//' bytes) is the dataset '// &
                '/input_text', error)
            call write_string_1d(root, 'input_text', [allocated_text(model%input_text)], error)
        end if
        call write_attribute(root, 'length_unit', allocated_text(model%length_unit), error)
        call write_attribute(root, 'stress_unit', allocated_text(model%stress_unit), error)
        if (allocated(model%load_path%time)) call write_attribute(root, 'time_unit', &
            allocated_text(model%time_unit), error)
        call write_attribute(root, 'youngs_modulus', model%youngs_modulus, error)
        call write_attribute(root, 'poissons_ratio', model%poissons_ratio, error)
        call write_attribute(root, 'shear_modulus', shear_modulus_of(model), error)
        call write_attribute(root, 'remote_stress', [model%sxx, model%syy, model%sxy], error)
        call write_attribute(root, 'conventions', conventions, error)
        call write_attribute(root, 'open_cohesion', &
                             trim(open_cohesion_names(model%solver%open_cohesion)), error)
        call write_attribute(root, 'lcp_method', trim(lcp_method_names(model%solver%lcp_method)), &
                             error)
        ! TWODD's symmetry: 'none', 'x' (about x = xsym), 'y' (about y = ysym) or 'both'
        call write_attribute(root, 'symmetry', &
                             trim(symmetry_names(model%elements%symmetry%kind)), error)
        call write_attribute(root, 'symmetry_lines', [model%elements%symmetry%xsym, &
                                                      model%elements%symmetry%ysym], error)
        ! 'full_plane', 'half_plane' (free surface y = 0) or 'bimaterial' (with the interface
        ! and the upper material; youngs_modulus, poissons_ratio and shear_modulus are then
        ! the lower one's), d(sxx, syy, sxy)/dy and the pore fluid (p0, dp_dy):
        ! docs/output-reference.md#layout
        call write_attribute(root, 'domain', trim(domain_names(model%elements%domain)), error)
        if (model%elements%domain == domain_bimaterial) then
            call write_attribute(root, 'interface_y', model%interface_y, error)
            call write_attribute(root, 'upper_youngs_modulus', model%upper_youngs_modulus, error)
            call write_attribute(root, 'upper_poissons_ratio', model%upper_poissons_ratio, error)
        end if
        call write_attribute(root, 'remote_stress_gradient', model%stress_gradient, error)
        call write_attribute(root, 'pore_fluid', model%pore_fluid, error)
        call write_attribute(root, 'model_fingerprint', recorded_fingerprint(model), error)
        ! A resumed run: the file it continued (as given to --resume) and when that was written
        if (allocated(model%resumed_from)) then
            call write_attribute(root, 'resumed_from', model%resumed_from, error)
            call write_attribute(root, 'resumed_from_created', &
                                 allocated_text(model%resumed_from_created), error)
        end if
    end subroutine write_root_attributes

    !> /elements: geometry, conditions, results and contact properties, shape (n).
    subroutine write_elements(root, model, results, error)
        type(h5_object), intent(in) :: root
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: results
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: group
        character(len=:), allocatable :: length, stress, given, time

        length = allocated_text(model%length_unit)
        stress = allocated_text(model%stress_unit)
        given = stress//' or '//length//' (by condition)'
        call create_group(root, 'elements', group, error)
        if (allocated(error)) return
        associate (e => model%elements, r => results%elements)
            call write_real_1d(group, 'x_begin', e%x_begin, length, error)
            call write_real_1d(group, 'y_begin', e%y_begin, length, error)
            call write_real_1d(group, 'x_end', e%x_end, length, error)
            call write_real_1d(group, 'y_end', e%y_end, length, error)
            call write_real_1d(group, 'x_mid', e%x_mid, length, error)
            call write_real_1d(group, 'y_mid', e%y_mid, length, error)
            call write_real_1d(group, 'half_length', e%half_length, length, error)
            call write_int_1d(group, 'fracture_id', e%fracture_id, error)
            if (model%cycle%active) then
                call write_int_1d(group, 'condition', e%condition, error, &
                                  condition_coding//rate_state_coding)
            else
                call write_int_1d(group, 'condition', e%condition, error, condition_coding)
            end if
            call write_real_1d(group, 'bc_s', e%bc_s, given, error)
            call write_real_1d(group, 'bc_n', e%bc_n, given, error)
            call write_real_1d(group, 'ds', r%ds, length, error)
            call write_real_1d(group, 'dn', r%dn, length, error)
            call write_real_1d(group, 'opening', -r%dn, length, error)
            call write_real_1d(group, 'shear_traction', r%shear_traction, stress, error)
            call write_real_1d(group, 'normal_traction', r%normal_traction, stress, error)
            call write_real_1d(group, 'us_minus', r%us_minus, length, error)
            call write_real_1d(group, 'un_minus', r%un_minus, length, error)
            call write_real_1d(group, 'us_plus', r%us_plus, length, error)
            call write_real_1d(group, 'un_plus', r%un_plus, length, error)
            call write_int_1d(group, 'state', r%state, error, state_coding)
            call write_real_1d(group, 'mu', e%mu, '1', error)
            call write_real_1d(group, 'sf', e%sf, stress, error)
            ! Contact elements: the given pressure plus the pore fluid (what diffused from
            ! fluid sources changes in time: /history/pressure)
            call write_real_1d(group, 'pressure', static_pressure(e, model%pore_fluid), stress, &
                               error)
            ! Strength beyond Coulomb as it acts, and what was left of it at the end.
            call write_strength_laws(group, model, stress, length, error)
            if (allocated(r%sf_in_force)) then
                call write_real_1d(group, 'sf_in_force', r%sf_in_force, stress, error)
                call write_real_1d(group, 'tensile_strength_in_force', r%tensile_in_force, &
                                   stress, error)
            end if
            if (allocated(r%mu_in_force)) call write_real_1d(group, 'mu_in_force', &
                                                             r%mu_in_force, '1', error)
            ! The K re-solve's own friction memory, for --resume.
            if (allocated(r%ds_k_memory)) call write_real_1d(group, 'ds_k_memory', &
                                                             r%ds_k_memory, length, error)
            ! Elastic joints: the elastic part of the DDs (the plastic part is the rest).
            if (allocated(r%ds_elastic)) then
                call write_real_1d(group, 'ds_elastic', r%ds_elastic, length, error)
                call write_real_1d(group, 'dn_elastic', r%dn_elastic, length, error)
            end if
            ! Flow along the fractures: the hydraulic properties, where some element conducts
            ! (the closed forms ddc2d-plot draws need them).
            if (any(e%diffusivity > 0.0_wp)) then
                time = allocated_text(model%time_unit)
                call write_real_1d(group, 'diffusivity', e%diffusivity, length//'^2/'//time, &
                                   error)
                call write_real_1d(group, 'transmissivity', e%transmissivity, &
                                   length//'^3/('//stress//' '//time//')', error)
            end if
            if (model%fluid%active) call write_real_1d(group, 'residual_aperture', &
                                                       e%residual_aperture, length, error)
            call write_growth_elements(group, model, results%growth, error)
            if (model%cycle%active) call write_rate_state(group, model, error)
        end associate
        call close_group(group, error)
    end subroutine write_elements

    !> One dataset per strength law of the list (ddc_model_laws) in /elements: its values as
    !> they act (a value after slip capped by the Coulomb value it falls from), the mark of
    !> none (no_residual_drop, rigid_joint: the largest real) written as +Inf.
    subroutine write_strength_laws(group, model, stress, length, error)
        type(h5_object), intent(in) :: group
        type(model_type), intent(in) :: model
        !> The unit names
        character(len=*), intent(in) :: stress, length
        type(error_type), allocatable, intent(inout) :: error
        type(strength_law) :: laws(strength_law_count)
        real(wp), allocatable :: given(:, :), acting(:)
        integer :: k

        laws = strength_laws()
        given = law_values(model%elements)
        do k = 1, size(laws)
            acting = acting_values(model%elements, laws(k), given(:, k))
            where (acting >= huge(acting)) acting = ieee_value(1.0_wp, ieee_positive_inf)
            call write_real_1d(group, laws(k)%name, acting, &
                               units_text(laws(k)%units, stress, length), error)
        end do
    end subroutine write_strength_laws

    !> /fractures: name, first_element, last_element (1-based), one entry per fracture.
    subroutine write_fractures(root, model, error)
        type(h5_object), intent(in) :: root
        type(model_type), intent(in) :: model
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: group
        integer :: i, n, width

        n = 0
        if (allocated(model%fractures)) n = size(model%fractures)
        width = 1
        do i = 1, n
            width = max(width, len(allocated_text(model%fractures(i)%name)))
        end do
        call create_group(root, 'fractures', group, error)
        if (allocated(error)) return
        block
            character(len=width) :: names(n)
            integer :: first(n), last(n)

            do i = 1, n
                names(i) = allocated_text(model%fractures(i)%name)
                first(i) = model%fractures(i)%first_element
                last(i) = model%fractures(i)%last_element
            end do
            call write_string_1d(group, 'name', names, error)
            call write_int_1d(group, 'first_element', first, error)
            call write_int_1d(group, 'last_element', last, error)
        end block
        call close_group(group, error)
    end subroutine write_fractures

    !> /sweep (sweep tasks only): attributes task, tasks, parameters (the names, comma
    !> separated, in &sweep order) and one real attribute per parameter with its value.
    subroutine write_sweep(root, model, error)
        type(h5_object), intent(in) :: root
        type(model_type), intent(in) :: model
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: group
        character(len=:), allocatable :: names
        integer :: i

        call create_group(root, 'sweep', group, error)
        if (allocated(error)) return
        call write_attribute(group, 'task', model%sweep%task, error)
        call write_attribute(group, 'tasks', model%sweep%tasks, error)
        names = trim(model%sweep%names(1))
        do i = 2, size(model%sweep%names)
            names = names//', '//trim(model%sweep%names(i))
        end do
        call write_attribute(group, 'parameters', names, error)
        do i = 1, size(model%sweep%names)
            call write_attribute(group, trim(model%sweep%names(i)), model%sweep%values(i), &
                                 error)
        end do
        call close_group(group, error)
    end subroutine write_sweep

    !> /tips: position, fracture, element and stress intensity factors; empty if no tips.
    subroutine write_tips(root, model, results, error)
        type(h5_object), intent(in) :: root
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: results
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: group
        character(len=:), allocatable :: length, k_unit
        real(wp), allocatable :: none_real(:)
        integer, allocatable :: none_int(:)

        length = allocated_text(model%length_unit)
        k_unit = allocated_text(model%stress_unit)//' '//length//'^0.5'
        call create_group(root, 'tips', group, error)
        if (allocated(error)) return
        associate (t => results%tips)
            if (allocated(t%k_method)) call write_attribute(group, 'k_method', t%k_method, error)
            if (t%n > 0) then
                call write_real_1d(group, 'x', t%x, length, error)
                call write_real_1d(group, 'y', t%y, length, error)
                call write_int_1d(group, 'fracture_id', t%fracture_id, error)
                call write_int_1d(group, 'element', t%element, error)
                call write_real_1d(group, 'k1', t%k1, k_unit, error)
                call write_real_1d(group, 'k2', t%k2, k_unit, error)
                call write_int_1d(group, 'graded', t%graded, error, graded_coding)
            else
                allocate (none_real(0), none_int(0))
                call write_real_1d(group, 'x', none_real, length, error)
                call write_real_1d(group, 'y', none_real, length, error)
                call write_int_1d(group, 'fracture_id', none_int, error)
                call write_int_1d(group, 'element', none_int, error)
                call write_real_1d(group, 'k1', none_real, k_unit, error)
                call write_real_1d(group, 'k2', none_real, k_unit, error)
                call write_int_1d(group, 'graded', none_int, error, graded_coding)
            end if
        end associate
        call close_group(group, error)
    end subroutine write_tips

    !> /body: a finite body's boundary, node by node and side by side.
    subroutine write_boundary(root, model, boundary, error)
        type(h5_object), intent(in) :: root
        type(model_type), intent(in) :: model
        type(boundary_results), intent(in) :: boundary
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: group
        character(len=:), allocatable :: length, stress

        length = allocated_text(model%length_unit)
        stress = allocated_text(model%stress_unit)
        call create_group(root, 'body', group, error)
        if (allocated(error)) return
        call write_real_1d(group, 'x', boundary%x, length, error)
        call write_real_1d(group, 'y', boundary%y, length, error)
        call write_int_1d(group, 'side', boundary%side, error)
        call write_real_1d(group, 'us', boundary%us, length, error)
        call write_real_1d(group, 'un', boundary%un, length, error)
        call write_real_1d(group, 'ts', boundary%ts, stress, error)
        call write_real_1d(group, 'tn', boundary%tn, stress, error)
        call write_real_1d(group, 'side_force_x', boundary%force_x, stress//' '//length, error)
        call write_real_1d(group, 'side_force_y', boundary%force_y, stress//' '//length, error)
        call write_real_1d(group, 'vertex_x', model%body%x, length, error)
        call write_real_1d(group, 'vertex_y', model%body%y, length, error)
        call close_group(group, error)
    end subroutine write_boundary

    !> /fields/<name> for every observation set; grids as (nx, ny) Fortran arrays.
    subroutine write_fields(root, model, results, error)
        type(h5_object), intent(in) :: root
        type(model_type), intent(in) :: model
        type(model_results), intent(in) :: results
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: fields, set
        character(len=:), allocatable :: length, stress
        integer, allocatable :: dims(:)
        integer :: i

        length = allocated_text(model%length_unit)
        stress = allocated_text(model%stress_unit)
        call create_group(root, 'fields', fields, error)
        if (allocated(error)) return
        if (allocated(model%observations)) then
            do i = 1, size(model%observations)
                associate (o => model%observations(i), f => results%fields(i))
                    if (o%kind == observation_grid) then
                        dims = [o%nx, o%ny]
                    else
                        dims = [size(o%x)]
                    end if
                    call create_group(fields, allocated_text(o%name), set, error)
                    if (allocated(error)) exit
                    call write_attribute(set, 'kind', trim(observation_kind_names(o%kind)), &
                        error)
                    call write_attribute(set, 'nx', o%nx, error)
                    call write_attribute(set, 'ny', o%ny, error)
                    call write_real_dataset(set, 'x', o%x, dims, length, error)
                    call write_real_dataset(set, 'y', o%y, dims, length, error)
                    call write_real_dataset(set, 'ux', f%ux, dims, length, error)
                    call write_real_dataset(set, 'uy', f%uy, dims, length, error)
                    call write_real_dataset(set, 'sxx', f%sxx, dims, stress, error)
                    call write_real_dataset(set, 'syy', f%syy, dims, stress, error)
                    call write_real_dataset(set, 'sxy', f%sxy, dims, stress, error)
                    if (allocated(model%body)) then
                        call write_int_dataset(set, 'near_element', f%flag, dims, error, &
                                               near_coding_body)
                    else
                        call write_int_dataset(set, 'near_element', f%flag, dims, error, &
                                               near_coding)
                    end if
                    call close_group(set, error)
                end associate
                if (allocated(error)) exit
            end do
        end if
        call close_group(fields, error)
    end subroutine write_fields

    !> /solver: method, threads, pivots, residual and state counts as attributes (and the
    !> processes, their grid and the block size in the MPI build);
    !> /solver/seconds/<phase> wall times as scalar datasets (output: the writing of this
    !> file up to the solver record; total includes it).
    subroutine write_solver(root, results, provenance, seconds_output, error)
        type(h5_object), intent(in) :: root
        type(model_results), intent(in) :: results
        type(run_provenance), intent(in) :: provenance
        real(wp), intent(in) :: seconds_output
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: solver, seconds
        integer, parameter :: no_dims(0) = [integer ::]

        call create_group(root, 'solver', solver, error)
        if (allocated(error)) return
        associate (s => results%solver, state => results%elements%state)
            call write_attribute(solver, 'method', allocated_text(s%method), error)
            call write_attribute(solver, 'fallback', allocated_text(s%fallback), error)
            call write_attribute(solver, 'newton_iterations', s%newton_iterations, error)
            call write_attribute(solver, 'factorizations', s%counts%factorizations, error)
            call write_attribute(solver, 'low_rank_updates', s%counts%updates, error)
            call write_attribute(solver, 'factorization_reuses', s%counts%reuses, error)
            call write_attribute(solver, 'factorization_borderings', s%counts%borderings, error)
            call write_attribute(solver, 'factorization_flops', s%counts%flops, error)
            call write_attribute(solver, 'threads', s%threads, error)
            call write_attribute(solver, 'blas', provenance%blas, error)
            call write_attribute(solver, 'blas_core', provenance%blas_core, error)
            call write_attribute(solver, 'pivots', s%pivots, error)
            call write_attribute(solver, 'lcp_solves', s%lcp_solves, error)
            call write_attribute(solver, 'certificate_min_z', s%certificate_min_z, error)
            call write_attribute(solver, 'certificate_min_w', s%certificate_min_w, error)
            call write_attribute(solver, 'certificate_max_complementarity', &
                                 s%certificate_max_complementarity, error)
            call write_attribute(solver, 'certificate_tolerance', s%certificate_tolerance, error)
            call write_attribute(solver, 'equilibrium_residual', s%equilibrium_residual, error)
            call write_attribute(solver, 'elements_free', count(state == state_free), error)
            call write_attribute(solver, 'elements_stick', count(state == state_stick), error)
            call write_attribute(solver, 'elements_slip', count(state == state_slip), error)
            call write_attribute(solver, 'elements_open', count(state == state_open), error)
            ! Only a hierarchical run says which matrix (a file without `matrix`: dense).
            if (s%hierarchical) then
                call write_attribute(solver, 'matrix', 'hierarchical', error)
                call write_attribute(solver, 'compression_ratio', s%compression_ratio, error)
                call write_attribute(solver, 'hmatrix_tolerance', s%hmatrix_tolerance, error)
            end if
            if (s%processes > 0) then
                call write_attribute(solver, 'processes', s%processes, error)
                call write_attribute(solver, 'process_grid', s%process_grid, error)
                call write_attribute(solver, 'block_size', s%block_size, error)
            end if
            call create_group(solver, 'seconds', seconds, error)
            if (.not. allocated(error)) then
                call write_real_dataset(seconds, 'assembly', [s%seconds_assembly], no_dims, &
                    's', error)
                call write_real_dataset(seconds, 'factorization', &
                    [s%counts%seconds], no_dims, 's', error)
                call write_real_dataset(seconds, 'lcp', [s%seconds_lcp], no_dims, 's', error)
                call write_real_dataset(seconds, 'fields', [s%seconds_fields], no_dims, 's', &
                    error)
                call write_real_dataset(seconds, 'output', [seconds_output], no_dims, 's', &
                    error)
                call write_real_dataset(seconds, 'total', [s%seconds_total + seconds_output], &
                    no_dims, 's', error)
                call close_group(seconds, error)
            end if
        end associate
        call close_group(solver, error)
    end subroutine write_solver

end module ddc_output_hdf5
