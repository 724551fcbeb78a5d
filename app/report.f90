!> What the program tells the user on standard output: the effective model and a summary.
module ddc_app_report
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, condition_names, observation_kind_names, &
        symmetry_none, symmetry_names
    use ddc_model_results, only: model_results, state_names
    use ddc_contact_options, only: lcp_method_names, open_cohesion_names, lcp_lemke
    implicit none
    private

    public :: print_model_summary, print_results_summary

contains

    !> Echo the effective model: material, remote stress, fractures, observations, output.
    subroutine print_model_summary(unit, model)
        !> Unit to write to
        integer, intent(in) :: unit
        !> The model as read
        type(model_type), intent(in) :: model
        integer :: i, first

        write (unit, '(a)') 'ddc2d model: '//model%title
        write (unit, '(a,g0,1x,a,a,g0)') '  youngs_modulus = ', model%youngs_modulus, &
            model%stress_unit, ', poissons_ratio = ', model%poissons_ratio
        if (model%elements%symmetry%kind /= symmetry_none) write (unit, '(a,a,a,g0,a,g0,a)') &
            '  symmetry ', trim(symmetry_names(model%elements%symmetry%kind)), ' (xsym = ', &
            model%elements%symmetry%xsym, ', ysym = ', model%elements%symmetry%ysym, &
            '): image elements implicit'
        write (unit, '(a,3(g0,1x),a)') '  remote stress sxx, syy, sxy = ', model%sxx, model%syy, &
            model%sxy, model%stress_unit
        do i = 1, size(model%fractures)
            first = model%fractures(i)%first_element
            write (unit, '(a,i0,a,a,a,i0,a,a)') '  fracture ', i, ' ', model%fractures(i)%name, &
                ': ', model%fractures(i)%last_element - first + 1, ' elements, condition ', &
                trim(condition_names(model%elements%condition(first)))
        end do
        if (allocated(model%observations)) then
            do i = 1, size(model%observations)
                write (unit, '(a,a,a,a,a,i0,a)') '  ', trim(observation_kind_names( &
                    model%observations(i)%kind)), ' ', model%observations(i)%name, ': ', &
                    size(model%observations(i)%x), ' points'
            end do
        end if
        write (unit, '(a,a,a,a)') '  solver: lcp_method = ', &
            trim(lcp_method_names(model%solver%lcp_method)), ', open_cohesion = ', &
            trim(open_cohesion_names(model%solver%open_cohesion))
        if (allocated(model%load_path%steps) .and. model%solver%lcp_method /= lcp_lemke) then
            write (unit, '(a)') '  (the loading history is solved step by step with '// &
            "Lemke's method, whatever lcp_method says)"
        end if
        write (unit, '(a)') '  output: '//model%output_file
    end subroutine print_model_summary

    !> Summary of the results: states, peak DDs, tips with K, timings.
    subroutine print_results_summary(unit, model, results)
        !> Unit to write to
        integer, intent(in) :: unit
        !> The model solved
        type(model_type), intent(in) :: model
        !> Its results
        type(model_results), intent(in) :: results
        integer :: i, state

        associate (e => results%elements, s => results%solver)
            if (s%processes > 0) then
                write (unit, '(a,a,3(a,i0),a,i0,a,i0,a,es10.3)') 'solved with ', s%method, &
                    ' on ', s%processes, ' process(es) (grid ', s%process_grid(1), ' x ', &
                    s%process_grid(2), ', block size ', s%block_size, '), ', s%threads, &
                    ' thread(s) each; equilibrium residual ', s%equilibrium_residual
            else
                write (unit, '(a,a,a,i0,a,es10.3)') 'solved with ', s%method, ' on ', &
                    s%threads, ' thread(s); equilibrium residual ', s%equilibrium_residual
            end if
            do state = 0, 3
                if (count(e%state == state) > 0) write (unit, '(2x,a,a,i0)') &
                    trim(state_names(state)), ' elements: ', count(e%state == state)
            end do
            write (unit, '(a,es12.5,1x,a)') '  peak |ds| = ', maxval(abs(e%ds)), model%length_unit
            write (unit, '(a,es12.5,1x,a)') '  peak opening = ', max(0.0_wp, maxval(-e%dn)), &
                model%length_unit
            do i = 1, results%tips%n
                write (unit, '(a,i0,a,2(es12.5,1x),a,es12.5,a,es12.5)') '  tip ', i, ' at ', &
                    results%tips%x(i), results%tips%y(i), ' K_I = ', results%tips%k1(i), &
                    ', K_II = ', results%tips%k2(i)
                if (results%tips%graded(i) == 1) write (unit, '(a)') '    (graded mesh at '// &
                    'this tip: the tip element differs from its neighbour, K is less accurate)'
            end do
            write (unit, '(a,6(f0.3,a))') '  seconds: assembly ', s%seconds_assembly, &
                ', factorization ', s%seconds_factorization, ', lcp ', s%seconds_lcp, &
                ', fields ', s%seconds_fields, ', output ', s%seconds_output, ', total ', &
                s%seconds_total + s%seconds_output, ''
        end associate
        write (unit, '(a)') 'wrote '//model%output_file
    end subroutine print_results_summary

end module ddc_app_report
