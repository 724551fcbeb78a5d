!> Options of the contact solver (&solver; docs/theory/contact.md#choosing-the-method): the LCP
!> method and what open elements do with their cohesion. Their input names are parsed here, once;
!> everything downstream holds the integer codes.
module ddc_contact_options
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_text, only: lower, newline
    implicit none
    private

    public :: solver_options, parse_solver_options, option_code
    public :: lcp_auto, lcp_lemke, lcp_newton, lcp_method_names
    public :: cohesion_kept, cohesion_lost, open_cohesion_names
    public :: matrix_auto, matrix_dense, matrix_hierarchical, matrix_names
    public :: k_auto, k_higher_order, k_tip_element, k_method_names, default_k_zone_elements

    !> LCP methods: 'auto' (Newton from auto_newton_min_elements contact elements on, else
    !> Lemke), 'lemke' (the paper's LCP, the reference), 'newton' (active set)
    integer, parameter :: lcp_auto = 1, lcp_lemke = 2, lcp_newton = 3
    !> Input names of the LCP methods, indexed by code
    character(len=*), parameter :: lcp_method_names(3) = [character(len=6) :: &
        'auto', 'lemke', 'newton']

    !> Cohesion of open elements: 'kept' (the paper: an open element carries shear up to
    !> Sf) or 'lost' (open faces carry no shear)
    integer, parameter :: cohesion_kept = 1, cohesion_lost = 2
    !> Input names of the cohesion modes, indexed by code
    character(len=*), parameter :: open_cohesion_names(2) = [character(len=4) :: &
        'kept', 'lost']

    !> Influence matrices (docs/theory/hierarchical.md): 'auto' (dense where it fits in
    !> memory, else hierarchical where the model allows it), 'dense', 'hierarchical'
    !> (hmat-oss: compressed blocks and H-LU; models without contact elements, one solve)
    integer, parameter :: matrix_auto = 1, matrix_dense = 2, matrix_hierarchical = 3
    !> Input names of the matrix kinds, indexed by code
    character(len=*), parameter :: matrix_names(3) = [character(len=12) :: &
        'auto', 'dense', 'hierarchical']

    !> How the tips' K is computed (docs/theory/tips.md#choosing-the-method): 'auto' (the
    !> higher-order re-solve up to higher_order_max_elements elements re-solved, without
    !> growth; else the tip element), 'higher_order', 'tip_element'
    integer, parameter :: k_auto = 1, k_higher_order = 2, k_tip_element = 3
    !> Elements of a tip's zone in the local re-solve for K (docs/theory/tips.md
    !> #the-size-of-the-zones: K within 1e-5 of the closed forms, at most 2e-6 on straight
    !> and graded cracks)
    integer, parameter :: default_k_zone_elements = 32
    !> Input names of the K methods, indexed by code
    character(len=*), parameter :: k_method_names(3) = [character(len=12) :: &
        'auto', 'higher_order', 'tip_element']

    !> Options of the contact solver, passed as one object.
    type :: solver_options
        !> lcp_auto, lcp_lemke or lcp_newton
        integer :: lcp_method = lcp_auto
        !> cohesion_kept or cohesion_lost
        integer :: open_cohesion = cohesion_kept
        !> Memory the contact method may use beyond the matrix it is given [bytes]: a
        !> fallback from Newton to Lemke that needs more stops with exit_out_of_memory
        !> instead of starting (set from the machine's memory; no limit by default)
        real(wp) :: work_bytes = huge(1.0_wp)
        !> matrix_auto, matrix_dense or matrix_hierarchical as given (run/memory resolves
        !> 'auto' before the solve)
        integer :: matrix = matrix_auto
        !> Hierarchical matrices: relative accuracy of each compressed block, most unknowns
        !> in a leaf of the cluster tree, admissibility parameter eta
        real(wp) :: hmatrix_tolerance = 1.0e-6_wp
        integer :: hmatrix_leaf_size = 64
        real(wp) :: hmatrix_eta = 2.0_wp
        !> k_auto, k_higher_order or k_tip_element
        integer :: k_method = k_auto
        !> Elements of a tip's zone in the local re-solve for K
        integer :: k_zone_elements = default_k_zone_elements
        !> The local re-solve's K of a history step is its last two coupled solutions'
        !> extrapolated to the step's load where they show it holds (tests compare it with
        !> a coupling solved at every step)
        logical :: k_extrapolation = .true.
    end type solver_options

contains

    !> Code of a name in a list of input names (case-insensitive, blanks ignored); 0 when
    !> it is not there.
    pure integer function option_code(name, names)
        !> The name as given
        character(len=*), intent(in) :: name
        !> The input names, indexed by code
        character(len=*), intent(in) :: names(:)
        integer :: i

        option_code = 0
        do i = 1, size(names)
            if (trim(names(i)) == lower(trim(adjustl(name)))) then
                option_code = i
                return
            end if
        end do
    end function option_code

    !> Solver options from their input names; a bad name is an error (exit_bad_input) with
    !> one line per bad name: "lcp_method = 'x' is not one of 'auto', 'lemke', 'newton'".
    subroutine parse_solver_options(lcp_method, open_cohesion, matrix, options, error)
        !> Input names of the LCP method, of the cohesion mode and of the matrix kind
        character(len=*), intent(in) :: lcp_method, open_cohesion, matrix
        !> The options (the defaults where a name is bad)
        type(solver_options), intent(out) :: options
        !> Allocated when a name is bad
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: problems
        integer :: code

        problems = ''
        code = option_code(lcp_method, lcp_method_names)
        if (code == 0) then
            call add_problem('lcp_method', lcp_method, lcp_method_names)
        else
            options%lcp_method = code
        end if
        code = option_code(open_cohesion, open_cohesion_names)
        if (code == 0) then
            call add_problem('open_cohesion', open_cohesion, open_cohesion_names)
        else
            options%open_cohesion = code
        end if
        code = option_code(matrix, matrix_names)
        if (code == 0) then
            call add_problem('matrix', matrix, matrix_names)
        else
            options%matrix = code
        end if
        if (len(problems) > 0) call set_error(error, exit_bad_input, problems)

    contains

        subroutine add_problem(variable, value, names)
            character(len=*), intent(in) :: variable, value, names(:)
            integer :: i

            if (len(problems) > 0) problems = problems//newline
            problems = problems//variable//" = '"//trim(adjustl(value))//"' is not one of "
            do i = 1, size(names)
                if (i > 1) problems = problems//', '
                problems = problems//"'"//trim(names(i))//"'"
            end do
        end subroutine add_problem
    end subroutine parse_solver_options

end module ddc_contact_options
