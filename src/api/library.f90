!> The library interface of ddc2d for other programs (docs/install.md#the-library-interface):
!> build a model in code (material, fractures along polylines, remote stress) or read a
!> namelist file, solve it, read the element results and the tips' K, and write the HDF5
!> result file. Every procedure that can fail returns an error value (code and message, as
!> the program's exit status and message); none stops or prints.
!>
!>     type(ddc_model) :: model
!>     type(ddc_result) :: result
!>     type(error_type), allocatable :: error
!>     call new_model(model, 50000.0_wp, 0.25_wp, error)
!>     call add_fracture(model, [-1.0_wp, 1.0_wp], [0.0_wp, 0.0_wp], [100], error, &
!>                       condition='traction', bc_n=-10.0_wp)
!>     call solve(model, result, error)
!>     call get_tips(result, k1=k1)
module ddc_api_library
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_success, exit_solver_failure, &
        exit_bad_input, exit_io_failure, exit_internal_error, exit_out_of_memory, &
        exit_stopped_early
    use ddc_text, only: itoa, rtoa, add_message, messages_error, find_name, quoted_list, lower
    use ddc_model_types, only: model_type, fracture_type, condition_names, condition_contact
    use ddc_model_results, only: model_results, state_free, state_stick, state_slip, &
        state_open, state_names
    use ddc_model_limits, only: range_problem, quantity_any, quantity_youngs_modulus, &
        quantity_poissons_ratio, quantity_non_negative
    use ddc_model_fingerprint, only: model_fingerprint
    use ddc_contact_options, only: solver_options
    use ddc_mesh_geometry, only: allocate_elements, compute_geometry
    use ddc_mesh_polyline, only: polyline_elements
    use ddc_mesh_checks, only: check_elements
    use ddc_input_namelist, only: read_namelist_model
    use ddc_input_sweep, only: read_sweep
    use ddc_sweep_tasks, only: sweep_definition
    use ddc_api_solve, only: solve_model
    use ddc_output_hdf5, only: write_results
    implicit none
    private

    public :: wp, error_type
    public :: exit_success, exit_solver_failure, exit_bad_input, exit_io_failure
    public :: exit_internal_error, exit_out_of_memory, exit_stopped_early
    public :: state_free, state_stick, state_slip, state_open, state_names
    public :: ddc_model, ddc_result
    public :: new_model, add_fracture, set_remote_stress, read_model, solve
    public :: element_count, get_elements, tip_count, get_tips, write_result

    !> The problems found in the values of one call, all reported at once.
    type :: problem_list
        !> Lines so far, joined with newlines
        character(len=:), allocatable :: lines
        !> Number of problems, listed or not
        integer :: count = 0
    end type problem_list

    !> One fracture given in code, kept until the solve makes its elements.
    type :: fracture_input
        !> Its name, and the vertices of its polyline [length unit], shape (segments + 1)
        character(len=:), allocatable :: name
        real(wp), allocatable :: x(:), y(:)
        !> Elements on each segment, shape (segments)
        integer, allocatable :: counts(:)
        !> Condition code (ddc_model_types' condition_names)
        integer :: condition = condition_contact
        !> Friction [-], cohesion and fluid pressure [stress unit] (contact); the given
        !> shear and normal value of the TWODD-style conditions
        real(wp) :: mu = 0.0_wp, sf = 0.0_wp, pressure = 0.0_wp, bc_s = 0.0_wp, bc_n = 0.0_wp
    end type fracture_input

    !> A model to solve: made by new_model (then add_fracture, set_remote_stress) or by
    !> read_model.
    type :: ddc_model
        private
        !> The model: material, remote stress and solver settings; the elements too when read
        type(model_type) :: model
        !> The fractures given in code (none when read from a file)
        type(fracture_input), allocatable :: fractures(:)
        !> new_model or read_model made it; read_model: it holds its elements
        logical :: made = .false., read = .false.
    end type ddc_model

    !> The results of a solve, with the geometry they belong to (a growth run's grown one).
    type :: ddc_result
        private
        !> The model solved, its elements as at the end of the solve
        type(model_type) :: model
        !> Element results, tips, fields, history and growth records
        type(model_results) :: results
    end type ddc_result

contains

    !> Start a model of an elastic body: Young's modulus and Poisson's ratio, no fracture,
    !> no remote stress, the default solver settings. Error (exit_bad_input): a modulus not
    !> positive, a ratio outside (-1, 0.5).
    subroutine new_model(model, youngs_modulus, poissons_ratio, error, title, length_unit, &
                         stress_unit)
        !> The model made
        type(ddc_model), intent(out) :: model
        !> Young's modulus [stress unit]
        real(wp), intent(in) :: youngs_modulus
        !> Poisson's ratio [-]
        real(wp), intent(in) :: poissons_ratio
        !> Allocated when a value is out of range
        type(error_type), allocatable, intent(out) :: error
        !> Title stored in the result file (default 'library model')
        character(len=*), intent(in), optional :: title
        !> Names of the length and stress units, stored in the result file (default 'm'
        !> and 'MPa'; the values are not converted)
        character(len=*), intent(in), optional :: length_unit, stress_unit
        type(problem_list) :: problems

        call check_value(problems, 'youngs_modulus', youngs_modulus, quantity_youngs_modulus)
        call check_value(problems, 'poissons_ratio', poissons_ratio, quantity_poissons_ratio)
        if (report(problems, error)) return
        model%model%title = text_or(title, 'library model')
        model%model%length_unit = text_or(length_unit, 'm')
        model%model%stress_unit = text_or(stress_unit, 'MPa')
        model%model%time_unit = 's'
        model%model%youngs_modulus = youngs_modulus
        model%model%poissons_ratio = poissons_ratio
        model%model%solver = solver_options()
        allocate (model%fractures(0), model%model%observations(0))
        model%made = .true.
    end subroutine new_model

    !> Add a fracture along the polyline (x(k), y(k)) with counts(k) equal elements on its
    !> segment k, every element with the same condition and values. A 'contact' fracture
    !> (the default) takes mu (required), sf and pressure; the TWODD-style conditions
    !> ('traction', 'displacement', 'mixed_us_sn', 'mixed_ss_un', 'prescribed_dd') take
    !> bc_s and bc_n (docs/input-reference.md#fracture). Error (exit_bad_input): no
    !> new_model before, sizes that do not match, a value out of range, a value the
    !> condition does not take; every problem in one message.
    subroutine add_fracture(model, x, y, counts, error, condition, mu, sf, pressure, bc_s, &
                            bc_n, name)
        !> The model (from new_model)
        type(ddc_model), intent(inout) :: model
        !> Vertices of the polyline [length unit], shape (segments + 1)
        real(wp), intent(in) :: x(:), y(:)
        !> Number of elements on each segment, shape (segments)
        integer, intent(in) :: counts(:)
        !> Allocated when the fracture is refused (the model is unchanged)
        type(error_type), allocatable, intent(out) :: error
        !> Element condition (default 'contact')
        character(len=*), intent(in), optional :: condition
        !> Friction coefficient [-] and cohesion [stress unit] ('contact')
        real(wp), intent(in), optional :: mu, sf
        !> Fluid pressure in the fracture, compression positive [stress unit] ('contact')
        real(wp), intent(in), optional :: pressure
        !> Shear and normal value of a TWODD-style condition (traction [stress unit] or
        !> displacement discontinuity [length unit])
        real(wp), intent(in), optional :: bc_s, bc_n
        !> Name of the fracture (default fracture_<k>)
        character(len=*), intent(in), optional :: name
        type(fracture_input) :: fracture
        type(problem_list) :: problems
        character(len=:), allocatable :: prefix
        integer :: k

        if (.not. model%made .or. model%read) then
            call set_error(error, exit_bad_input, 'add_fracture: start the model with '// &
                           'new_model (a model read from a file is complete)')
            return
        end if
        fracture%name = text_or(name, 'fracture_'//itoa(size(model%fractures) + 1))
        prefix = 'fracture '//fracture%name//': '
        if (size(x) /= size(y) .or. size(x) /= size(counts) + 1 .or. size(counts) < 1) then
            call add(problems, prefix//'x and y need one vertex more than counts has '// &
                     'segments (x: '//itoa(size(x))//', y: '//itoa(size(y))//', counts: '// &
                     itoa(size(counts))//')')
        end if
        if (any(counts < 1)) call add(problems, prefix//'every segment needs an element')
        do k = 1, size(x)
            call check_value(problems, prefix//'x('//itoa(k)//')', x(k), quantity_any)
        end do
        do k = 1, size(y)
            call check_value(problems, prefix//'y('//itoa(k)//')', y(k), quantity_any)
        end do
        fracture%condition = find_name(lower(text_or(condition, 'contact')), condition_names)
        if (fracture%condition == 0) then
            call add(problems, prefix//"condition = '"//text_or(condition, '')// &
                     "' is not one of "//quoted_list(condition_names))
        else if (fracture%condition == condition_contact) then
            if (.not. present(mu)) call add(problems, prefix//"mu is required for "// &
                                            "condition 'contact'")
            if (present(bc_s) .or. present(bc_n)) call add(problems, prefix//'bc_s and '// &
                "bc_n are for the TWODD-style conditions, not for 'contact'")
        else if (present(mu) .or. present(sf) .or. present(pressure)) then
            call add(problems, prefix//"mu, sf and pressure are for condition 'contact'")
        end if
        fracture%mu = given_value(problems, prefix//'mu', mu, quantity_non_negative)
        fracture%sf = given_value(problems, prefix//'sf', sf, quantity_non_negative)
        fracture%pressure = given_value(problems, prefix//'pressure', pressure, quantity_any)
        fracture%bc_s = given_value(problems, prefix//'bc_s', bc_s, quantity_any)
        fracture%bc_n = given_value(problems, prefix//'bc_n', bc_n, quantity_any)
        if (report(problems, error)) return
        fracture%x = x
        fracture%y = y
        fracture%counts = counts
        model%fractures = [model%fractures, fracture]
    end subroutine add_fracture

    !> Set the remote (far-field) stress, tension positive [stress unit]. Error
    !> (exit_bad_input): a value that is not a finite number within the input limits.
    subroutine set_remote_stress(model, sxx, syy, sxy, error)
        !> The model
        type(ddc_model), intent(inout) :: model
        !> Remote stress components [stress unit]
        real(wp), intent(in) :: sxx, syy, sxy
        !> Allocated when a value is refused (the model is unchanged)
        type(error_type), allocatable, intent(out) :: error
        type(problem_list) :: problems

        call check_value(problems, 'sxx', sxx, quantity_any)
        call check_value(problems, 'syy', syy, quantity_any)
        call check_value(problems, 'sxy', sxy, quantity_any)
        if (report(problems, error)) return
        model%model%sxx = sxx
        model%model%syy = syy
        model%model%sxy = sxy
    end subroutine set_remote_stress

    !> Read a model from a namelist input file (docs/input-reference.md), with the checks
    !> and messages of the program. Its &load_path and &growth are honoured by solve; a file
    !> with &sweep is refused (its tasks are the program's: ddc2d FILE --task K).
    subroutine read_model(path, model, error)
        !> Path of the namelist file
        character(len=*), intent(in) :: path
        !> The model read
        type(ddc_model), intent(out) :: model
        !> Allocated (exit_bad_input, exit_io_failure) when the file cannot be read or is bad
        type(error_type), allocatable, intent(out) :: error
        type(sweep_definition) :: sweep
        logical :: found

        call read_namelist_model(path, model%model, error)
        if (allocated(error)) return
        call read_sweep(path, model%model, sweep, found, error)
        if (allocated(error)) return
        if (found) then
            call set_error(error, exit_bad_input, path//' is a parameter sweep (&sweep): '// &
                           'run its tasks with the program (ddc2d '//path//' --task K)')
            return
        end if
        allocate (model%fractures(0))
        model%made = .true.
        model%read = .true.
    end subroutine read_model

    !> Solve the model as the program does: by growing its fractures (&growth), along its
    !> loading history (&load_path), or in one solve. The model is not changed. Errors:
    !> exit_bad_input (no fracture, elements that overlap or cross, no model),
    !> exit_solver_failure, exit_out_of_memory, exit_stopped_early (a growth step failed:
    !> result holds the steps before it, as the program writes them).
    subroutine solve(model, result, error)
        !> The model
        type(ddc_model), intent(in) :: model
        !> The results and the geometry solved
        type(ddc_result), intent(out) :: result
        !> Allocated when the model is refused or the solve fails
        type(error_type), allocatable, intent(out) :: error

        if (.not. model%made) then
            call set_error(error, exit_bad_input, 'solve: no model (new_model or read_model '// &
                           'makes one)')
            return
        end if
        result%model = model%model
        if (.not. model%read) then
            call make_elements(model%fractures, result%model, error)
            if (allocated(error)) return
        end if
        result%model%fingerprint = model_fingerprint(result%model)
        call solve_model(result%model, result%results, error)
    end subroutine solve

    !> Number of elements of the solved geometry.
    integer function element_count(result)
        !> The result of solve
        type(ddc_result), intent(in) :: result

        element_count = result%model%elements%n
    end function element_count

    !> The element results of the solved geometry, each of shape (element_count).
    subroutine get_elements(result, ds, dn, state, x_mid, y_mid, fracture, shear_traction, &
                            normal_traction)
        !> The result of solve
        type(ddc_result), intent(in) :: result
        !> Shear and normal displacement discontinuity [length unit] (Crouch and
        !> Starfield's signs: dn < 0 is opening; docs/output-reference.md)
        real(wp), allocatable, intent(out), optional :: ds(:), dn(:)
        !> Element state: state_free (a TWODD-style element), state_stick, state_slip,
        !> state_open (state_names(state) names it)
        integer, allocatable, intent(out), optional :: state(:)
        !> Element midpoints [length unit]
        real(wp), allocatable, intent(out), optional :: x_mid(:), y_mid(:)
        !> The fracture of each element (1-based, in the order they were added or read)
        integer, allocatable, intent(out), optional :: fracture(:)
        !> Total shear and normal traction, tension positive [stress unit]
        real(wp), allocatable, intent(out), optional :: shear_traction(:), normal_traction(:)

        associate (e => result%results%elements, m => result%model%elements)
            if (present(ds)) ds = e%ds
            if (present(dn)) dn = e%dn
            if (present(state)) state = e%state
            if (present(x_mid)) x_mid = m%x_mid
            if (present(y_mid)) y_mid = m%y_mid
            if (present(fracture)) fracture = m%fracture_id
            if (present(shear_traction)) shear_traction = e%shear_traction
            if (present(normal_traction)) normal_traction = e%normal_traction
        end associate
    end subroutine get_elements

    !> Number of crack tips (element ends shared with no other element).
    integer function tip_count(result)
        !> The result of solve
        type(ddc_result), intent(in) :: result

        tip_count = result%results%tips%n
    end function tip_count

    !> The crack tips of the solved geometry, each of shape (tip_count).
    subroutine get_tips(result, k1, k2, x, y, fracture)
        !> The result of solve
        type(ddc_result), intent(in) :: result
        !> Mode I and mode II stress intensity factors [stress unit * length unit**0.5]
        real(wp), allocatable, intent(out), optional :: k1(:), k2(:)
        !> Tip position [length unit]
        real(wp), allocatable, intent(out), optional :: x(:), y(:)
        !> The fracture of each tip (1-based)
        integer, allocatable, intent(out), optional :: fracture(:)

        associate (t => result%results%tips)
            if (present(k1)) k1 = t%k1
            if (present(k2)) k2 = t%k2
            if (present(x)) x = t%x
            if (present(y)) y = t%y
            if (present(fracture)) fracture = t%fracture_id
        end associate
    end subroutine get_tips

    !> Write the HDF5 result file of a solve (docs/output-reference.md), as the program
    !> does. Error (exit_io_failure): the file cannot be written.
    subroutine write_result(result, path, error)
        !> The result of solve
        type(ddc_result), intent(in) :: result
        !> Path of the file (replaced when it exists)
        character(len=*), intent(in) :: path
        !> Allocated when the file cannot be written
        type(error_type), allocatable, intent(out) :: error

        call write_results(path, result%model, result%results, error)
    end subroutine write_result

    ! ---------------------------------------------------------------- private helpers

    !> The elements of the fractures given in code, put into the model and checked as the
    !> namelist reader checks them.
    subroutine make_elements(fractures, model, error)
        type(fracture_input), intent(in) :: fractures(:)
        type(model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: x_begin(:), y_begin(:), x_end(:), y_end(:)
        integer :: k, first, last

        if (size(fractures) == 0) then
            call set_error(error, exit_bad_input, 'solve: the model has no fracture '// &
                           '(add_fracture adds one)')
            return
        end if
        call allocate_elements(model%elements, sum([(sum(fractures(k)%counts), &
                                                     k = 1, size(fractures))]))
        allocate (model%fractures(size(fractures)))
        last = 0
        do k = 1, size(fractures)
            associate (f => fractures(k), e => model%elements)
                first = last + 1
                last = last + sum(f%counts)
                model%fractures(k) = fracture_type(name=f%name, first_element=first, &
                                                   last_element=last)
                call polyline_elements(f%x, f%y, f%counts, x_begin, y_begin, x_end, y_end)
                e%x_begin(first:last) = x_begin
                e%y_begin(first:last) = y_begin
                e%x_end(first:last) = x_end
                e%y_end(first:last) = y_end
                e%fracture_id(first:last) = k
                e%condition(first:last) = f%condition
                e%mu(first:last) = f%mu
                e%sf(first:last) = f%sf
                e%pressure(first:last) = f%pressure
                e%bc_s(first:last) = f%bc_s
                e%bc_n(first:last) = f%bc_n
            end associate
        end do
        call compute_geometry(model%elements)
        call check_elements(model%elements, model%fractures, error)
    end subroutine make_elements

    !> The value given (checked for its quantity), else 0.
    real(wp) function given_value(problems, name, value, quantity)
        type(problem_list), intent(inout) :: problems
        character(len=*), intent(in) :: name
        real(wp), intent(in), optional :: value
        integer, intent(in) :: quantity

        given_value = 0.0_wp
        if (.not. present(value)) return
        call check_value(problems, name, value, quantity)
        given_value = value
    end function given_value

    !> Add a problem when the value is out of its quantity's range.
    subroutine check_value(problems, name, value, quantity)
        type(problem_list), intent(inout) :: problems
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: value
        integer, intent(in) :: quantity
        character(len=:), allocatable :: problem

        problem = range_problem(quantity, value)
        if (len(problem) > 0) call add(problems, name//' = '//rtoa(value)//' '//problem)
    end subroutine check_value

    !> Add a problem to the list.
    subroutine add(problems, line)
        type(problem_list), intent(inout) :: problems
        character(len=*), intent(in) :: line

        if (.not. allocated(problems%lines)) problems%lines = ''
        call add_message(problems%lines, problems%count, line)
    end subroutine add

    !> True, with an error (exit_bad_input) listing the problems, when there are any.
    logical function report(problems, error)
        type(problem_list), intent(in) :: problems
        type(error_type), allocatable, intent(out) :: error

        report = problems%count > 0
        if (report) call messages_error(problems%lines, problems%count, 'problems', error)
    end function report

    !> The optional text when present, else the default.
    function text_or(text, default) result(chosen)
        character(len=*), intent(in), optional :: text
        character(len=*), intent(in) :: default
        character(len=:), allocatable :: chosen

        if (present(text)) then
            chosen = text
        else
            chosen = default
        end if
    end function text_or

end module ddc_api_library
