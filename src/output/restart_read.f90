!> Read the end of an earlier run from its complete result file (--resume, SPEC-GROWTH 8):
!> the final geometry's end points and fracture ranges, its element results and tips, the
!> growth record and the loading history, bit for bit as written (ddc_output_hdf5). The
!> file was checked before (app/resume_check: complete, same version and model), so a
!> dataset that is missing here is an error of the file.
module ddc_output_restart_read
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_io_failure
    use ddc_model_results, only: growth_end_names
    use ddc_model_restart, only: restart_state
    use ddc_output_hdf5_read, only: read_real_dataset, read_int_dataset, read_string_dataset, &
        read_string_attribute, read_int_attribute, read_real_attribute, has_dataset
    implicit none
    private

    public :: read_restart

contains

    !> The restart state of the result file `path`.
    subroutine read_restart(path, state, error)
        !> The earlier run's result file
        character(len=*), intent(in) :: path
        !> Its end
        type(restart_state), intent(out) :: state
        !> Set (exit_io_failure, naming the file) when a dataset cannot be read
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: end_name
        integer :: n, i, e

        call reals('/elements/x_begin', state%x_begin)
        call reals('/elements/y_begin', state%y_begin)
        call reals('/elements/x_end', state%x_end)
        call reals('/elements/y_end', state%y_end)
        call integers('/elements/fracture_id', state%fracture_id)
        call integers('/fractures/first_element', state%first_element)
        call integers('/fractures/last_element', state%last_element)
        associate (r => state%results%elements)
            call reals('/elements/ds', r%ds)
            call reals('/elements/dn', r%dn)
            call integers('/elements/state', r%state)
            call reals('/elements/shear_traction', r%shear_traction)
            call reals('/elements/normal_traction', r%normal_traction)
            call reals('/elements/us_minus', r%us_minus)
            call reals('/elements/un_minus', r%un_minus)
            call reals('/elements/us_plus', r%us_plus)
            call reals('/elements/un_plus', r%un_plus)
            if (has_dataset(path, '/elements/sf_in_force')) then
                call reals('/elements/sf_in_force', r%sf_in_force)
                call reals('/elements/tensile_strength_in_force', r%tensile_in_force)
            end if
            if (has_dataset(path, '/elements/mu_in_force')) call reals('/elements/mu_in_force', &
                                                                r%mu_in_force)
        end associate
        associate (t => state%results%tips)
            call reals('/tips/x', t%x)
            call reals('/tips/y', t%y)
            call integers('/tips/fracture_id', t%fracture_id)
            call integers('/tips/element', t%element)
            call reals('/tips/k1', t%k1)
            call reals('/tips/k2', t%k2)
            call integers('/tips/graded', t%graded)
            if (allocated(error)) return
            ! tip_set%side: 2 at the element's end point, 1 at its begin
            t%n = size(t%x)
            allocate (t%side(t%n))
            do i = 1, t%n
                e = t%element(i)
                t%side(i) = merge(2, 1, t%x(i) == state%x_end(e) .and. &
                                  t%y(i) == state%y_end(e))
            end do
        end associate
        call read_last_solve()
        if (has_dataset(path, '/growth/step')) call read_growth()
        if (allocated(error)) return
        if (has_dataset(path, '/history/pivots')) call read_history()

    contains

        !> How the last solve went (/solver: method, fallback, certificate, residual): the
        !> record of the final solution, should the resumed run not solve again.
        subroutine read_last_solve()
            associate (r => state%results%solver)
                if (allocated(error)) return
                call read_string_attribute(path, '/solver', 'method', r%method, error)
                if (.not. allocated(error)) call read_string_attribute(path, '/solver', &
                    'fallback', r%fallback, error)
                if (allocated(error)) then
                    call reading_failed('/solver attributes')
                    return
                end if
                call real_attribute('certificate_min_z', r%certificate_min_z)
                call real_attribute('certificate_min_w', r%certificate_min_w)
                call real_attribute('certificate_max_complementarity', &
                                    r%certificate_max_complementarity)
                call real_attribute('certificate_tolerance', r%certificate_tolerance)
                call real_attribute('equilibrium_residual', r%equilibrium_residual)
            end associate
        end subroutine read_last_solve

        !> A real attribute of /solver.
        subroutine real_attribute(name, target_value)
            character(len=*), intent(in) :: name
            real(wp), intent(inout) :: target_value
            real(wp), allocatable :: value(:)

            if (allocated(error)) return
            call read_real_attribute(path, '/solver', name, value, error)
            if (allocated(error)) then
                call reading_failed('/solver attribute '//name)
            else
                target_value = value(1)
            end if
        end subroutine real_attribute

        !> The growth record.
        subroutine read_growth()
            associate (g => state%results%growth)
                call integers('/growth/step', g%step)
                if (has_dataset(path, '/growth/load_step')) then
                    call integers('/growth/load_step', g%load_step)
                else if (allocated(g%step)) then
                    allocate (g%load_step(size(g%step)), source=1)
                end if
                call integers('/growth/fracture_id', g%fracture_id)
                call integers('/growth/end', g%end)
                call reals('/growth/x', g%x)
                call reals('/growth/y', g%y)
                call reals('/growth/k1', g%k1)
                call reals('/growth/k2', g%k2)
                call reals('/growth/k_eq', g%k_eq)
                call reals('/growth/mts_angle', g%mts_angle)
                call reals('/growth/angle', g%angle)
                call integers('/growth/corrections', g%corrections)
                call reals('/growth/k2_after', g%k2_after)
                call reals('/growth/length', g%length)
                call integers('/growth/reason', g%reason)
                call integers('/elements/created_step', g%created_step)
                if (allocated(error)) return
                call read_int_attribute(path, '/growth', 'steps_taken', g%steps_taken, error)
                if (allocated(error)) return
                call read_string_attribute(path, '/growth', 'end_reason', end_name, error)
                if (allocated(error)) return
                g%end_reason = findloc([(trim(growth_end_names(i)) == trim(end_name), &
                                         i = 1, size(growth_end_names))], .true., 1)
                if (g%end_reason == 0) call set_error(error, exit_io_failure, path// &
                    ': /growth end_reason '''//end_name//''' is not known')
            end associate
        end subroutine read_growth

        !> The loading history's columns (the loads follow from the model's path).
        subroutine read_history()
            integer, allocatable :: flat_state(:)
            integer :: k, tips

            associate (h => state%results%history)
                call integers('/history/pivots', h%pivots)
                if (allocated(error)) return
                k = size(h%pivots)
                n = size(state%x_begin)
                tips = state%results%tips%n
                call columns('/history/ds', n, k, h%ds)
                call columns('/history/dn', n, k, h%dn)
                call columns('/history/shear_traction', n, k, h%shear_traction)
                call columns('/history/normal_traction', n, k, h%normal_traction)
                call columns('/history/k1', tips, k, h%k1)
                call columns('/history/k2', tips, k, h%k2)
                call integers('/history/state', flat_state)
                if (allocated(flat_state)) h%state = reshape(flat_state, [n, k])
                call integers('/history/newton_iterations', h%newton_iterations)
                call strings('/history/method', h%method)
                call strings('/history/fallback', h%fallback)
                call reals('/history/certificate_min_z', h%certificate_min_z)
                call reals('/history/certificate_min_w', h%certificate_min_w)
                call reals('/history/certificate_max_complementarity', &
                           h%certificate_max_complementarity)
                call reals('/history/equilibrium_residual', h%equilibrium_residual)
                if (has_dataset(path, '/history/element_count')) call integers( &
                    '/history/element_count', h%element_count)
            end associate
        end subroutine read_history

        !> A real dataset of the history shaped (rows, steps) in Fortran.
        subroutine columns(dataset, rows, steps, values)
            character(len=*), intent(in) :: dataset
            integer, intent(in) :: rows, steps
            real(wp), allocatable, intent(out) :: values(:, :)
            real(wp), allocatable :: flat(:)

            call reals(dataset, flat)
            if (allocated(flat)) values = reshape(flat, [rows, steps])
        end subroutine columns

        subroutine reals(dataset, values)
            character(len=*), intent(in) :: dataset
            real(wp), allocatable, intent(inout) :: values(:)

            if (allocated(error)) return
            if (allocated(values)) deallocate (values)
            call read_real_dataset(path, dataset, values, error)
            if (allocated(error)) call reading_failed(dataset)
        end subroutine reals

        subroutine integers(dataset, values)
            character(len=*), intent(in) :: dataset
            integer, allocatable, intent(inout) :: values(:)

            if (allocated(error)) return
            if (allocated(values)) deallocate (values)
            call read_int_dataset(path, dataset, values, error)
            if (allocated(error)) call reading_failed(dataset)
        end subroutine integers

        ! allow(C072): the history's strings have the lengths of history_record
        subroutine strings(dataset, values)
            character(len=*), intent(in) :: dataset
            character(len=*), allocatable, intent(inout) :: values(:)

            if (allocated(error)) return
            if (allocated(values)) deallocate (values)
            call read_string_dataset(path, dataset, values, error)
            if (allocated(error)) call reading_failed(dataset)
        end subroutine strings

        subroutine reading_failed(dataset)
            character(len=*), intent(in) :: dataset

            error%code = exit_io_failure
            error%message = '--resume '//path//': reading '//dataset//': '//error%message
        end subroutine reading_failed

    end subroutine read_restart

end module ddc_output_restart_read
