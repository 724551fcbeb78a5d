!> The elastic operator a contact run solves on (docs/ARCHITECTURE.md#the-contact-run): the
!> response of a medium on its contact elements, with the elements of TWODD-style
!> conditions (the free elements) condensed out
!> (docs/theory/contact.md#models-that-mix-contact-and-other-conditions).
!>
!> With the system K x = b split into free unknowns F and contact unknowns C, the contact
!> elements see t_C = S_r,C + K_CF K_FF^-1 b_F + A x_C with A = K_CC - K_CF K_FF^-1 K_FC
!> (load_contact gives the first two terms, stiffness is A), and the free DDs follow as
!> x_F = K_FF^-1 (b_F - K_FC x_C) (complete). How A is held is the operator's: a dense
!> matrix in this process (ddc_solve_dense_operator), a hierarchical matrix
!> (ddc_solve_hierarchical_operator), a matrix distributed over MPI processes
!> (src/parallel/). Every procedure is called by every process of a distributed run with
!> the same arguments.
module ddc_solve_operator
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_internal_error
    use ddc_text, only: itoa
    use ddc_model_medium, only: elastic_medium
    use ddc_model_results, only: solver_record
    use ddc_contact_stiffness, only: stiffness_operator
    implicit none
    private

    public :: elastic_operator, elastic_load, free_part

    !> One load of a medium: the remote stress, resolved on each element, and the fluid
    !> pressure in each contact element.
    type :: elastic_load
        !> Remote stress sxx, syy, sxy at y = 0 [stress unit] and its gradient d/dy [stress
        !> unit / length unit]
        real(wp) :: remote(3) = 0.0_wp, gradient(3) = 0.0_wp
        !> Remote shear and normal traction on each element (tension positive) [stress
        !> unit], shape (n)
        real(wp), allocatable :: shear(:), normal(:)
        !> Total fluid pressure in each element (compression positive; read on contact
        !> elements) [stress unit], shape (n)
        real(wp), allocatable :: pressure(:)
    end type elastic_load

    !> What load_contact keeps of a load for complete: the free DDs with the contact DDs
    !> at zero (or the operator's own record of them).
    type :: free_part
        !> K_FF^-1 b_F, shape (2 nf) [length unit]
        real(wp), allocatable :: dd(:)
    end type free_part

    !> The response of a medium on its contact elements, the free elements condensed out.
    type, abstract :: elastic_operator
        !> Number of contact and of free elements
        integer :: nc = 0, nf = 0
        !> Indices of the contact and of the free elements in the medium, shape (nc), (nf)
        integer, allocatable :: contact(:), free(:)
        !> A, ordered [s; n] over the contact elements, as the contact methods see it
        class(stiffness_operator), allocatable :: stiffness
        !> A in memory, shape (2 nc, 2 nc), where the operator holds it densely (Lemke's
        !> method and elastic joints need it; not associated otherwise)
        real(wp), pointer, contiguous :: matrix(:, :) => null()
        !> The influence matrix of every element, rows as their conditions, shape (2n, 2n),
        !> where the operator holds it in memory (the midpoint responses use it)
        real(wp), pointer, contiguous :: whole(:, :) => null()
        !> Elastic joints: the map of the contact elements' fluid pressure onto the load of
        !> the plastic DDs' problem (ddc_solve_joints), shape (nc, nc)
        real(wp), allocatable :: load_map(:, :)
        !> What a failed contact solve's message adds (what the numbers count, what to try)
        character(len=:), allocatable :: hint
        !> Nominal flops of the condensation (recorded with the contact solve's) [-]
        real(wp) :: flops = 0.0_wp
        !> What making the operator took: seconds_assembly, counts%seconds (factorization),
        !> and for a compressed one hierarchical, hmatrix_tolerance, compression_ratio
        type(solver_record) :: record
        !> multiply_shear has the shear columns of A apart (prepare_shear_products)
        logical :: shear_columns_apart = .false.
    contains
        !> The remote traction on the contact elements for a load, free elements included
        procedure(load_interface), deferred :: load_contact
        !> The DDs of every element from those of the contact elements
        procedure(complete_interface), deferred :: complete
        !> Induced tractions at the free elements' midpoints (a loading history's record)
        procedure :: free_tractions => no_free_tractions
        !> t = t + A(rows, columns) dd: the product on a subset of the contact elements
        procedure :: multiply_elements
        !> t = t + A [ds; 0]: the tractions of every contact element from shear DDs alone
        procedure :: multiply_shear
        !> Ready the operator for many products multiply_shear (a compressed operator
        !> compresses those columns of A alone)
        procedure :: prepare_shear_products => shear_columns_of_stiffness
        !> Elastic joints: the contact problem of the plastic DDs (ddc_solve_joints)
        procedure :: add_joints => no_joints
        !> Free what the operator holds
        procedure(release_interface), deferred :: release
    end type elastic_operator

    abstract interface
        !> shift = [S_r,C shear; S_r,C normal] + K_CF K_FF^-1 b_F for one load.
        subroutine load_interface(this, medium, load, shift, kept, error)
            import :: elastic_operator, elastic_medium, elastic_load, free_part, error_type, wp
            implicit none
            !> The operator
            class(elastic_operator), intent(inout) :: this
            !> Its medium
            type(elastic_medium), intent(in) :: medium
            !> The load
            type(elastic_load), intent(in) :: load
            !> Remote shear then normal traction on the contact elements, shape (2 nc)
            !> [stress unit]
            real(wp), intent(out) :: shift(:)
            !> What complete needs of this load
            type(free_part), intent(out) :: kept
            !> Set when the free elements' system has no solution
            type(error_type), allocatable, intent(out) :: error
        end subroutine load_interface

        !> DDs of every element from the contact elements' (x_C = [ds; dn]).
        subroutine complete_interface(this, medium, load, x_contact, kept, ds, dn, record, &
                                      error)
            import :: elastic_operator, elastic_medium, elastic_load, free_part, &
                solver_record, error_type, wp
            implicit none
            !> The operator
            class(elastic_operator), intent(inout) :: this
            !> Its medium
            type(elastic_medium), intent(in) :: medium
            !> The load of load_contact
            type(elastic_load), intent(in) :: load
            !> The contact elements' DDs [Ds; Dn] [length unit], shape (2 nc)
            real(wp), intent(in) :: x_contact(:)
            !> What load_contact kept of the load
            type(free_part), intent(in) :: kept
            !> DDs of every element [length unit], shape (n)
            real(wp), intent(out) :: ds(:), dn(:)
            !> equilibrium_residual is raised to the free rows' relative residual where
            !> larger; an operator that solves the free elements only now records that solve
            type(solver_record), intent(inout) :: record
            !> Set when the free elements' system has no solution
            type(error_type), allocatable, intent(out) :: error
        end subroutine complete_interface

        !> Free what the operator holds.
        subroutine release_interface(this)
            import :: elastic_operator
            implicit none
            !> The operator
            class(elastic_operator), intent(inout) :: this
        end subroutine release_interface
    end interface

contains

    !> Operators that do not keep the free elements' rows have no free tractions.
    subroutine no_free_tractions(this, medium, ds, dn, shear_traction, normal_traction, error)
        !> The operator
        class(elastic_operator), intent(in) :: this
        !> Its medium
        type(elastic_medium), intent(in) :: medium
        !> DDs of every element [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Induced shear and normal traction of the free elements [stress unit], shape (nf)
        real(wp), intent(out) :: shear_traction(:), normal_traction(:)
        !> Set: the operator cannot
        type(error_type), allocatable, intent(out) :: error

        shear_traction = 0.0_wp
        normal_traction = 0.0_wp
        call set_internal_error(error, 'free_tractions', 'an operator that keeps no rows '// &
                                'of the '//itoa(this%nf)//' free elements (of '// &
                                itoa(medium%elements%n)//', with DDs of '//itoa(size(ds))// &
                                ' and '//itoa(size(dn))//')')
    end subroutine no_free_tractions

    !> Operators other than dense ones take no elastic joints (the run's capabilities
    !> refuse them before).
    subroutine no_joints(this, compliance, error)
        !> The operator
        class(elastic_operator), intent(inout) :: this
        !> Joint compliance of each contact element [length / stress], shape (2 nc)
        real(wp), intent(in) :: compliance(:)
        !> Set: the operator cannot
        type(error_type), allocatable, intent(out) :: error

        call set_internal_error(error, 'add_joints', 'elastic joints ('// &
            itoa(size(compliance))//' compliances) on an operator of '//itoa(this%nc)// &
            ' contact elements that does not hold its matrix')
    end subroutine no_joints

    !> t = t + A(rows, columns) dd, rows and columns listed as contact elements (1..nc):
    !> the product of the whole operator with dd placed on the listed columns.
    subroutine multiply_elements(this, rows, columns, dd, t)
        !> The operator
        class(elastic_operator), intent(in) :: this
        !> The contact elements whose tractions are wanted and those whose DDs are given,
        !> shape (mr), (mc)
        integer, intent(in) :: rows(:), columns(:)
        !> DDs [Ds; Dn] of the listed columns [length unit], shape (2 mc)
        real(wp), intent(in) :: dd(:)
        !> Tractions [shear; normal] of the listed rows [stress unit], shape (2 mr)
        real(wp), intent(inout) :: t(:)
        real(wp) :: whole(2 * this%nc), product(2 * this%nc)

        whole = 0.0_wp
        whole(columns) = dd(1:size(columns))
        whole(this%nc + columns) = dd(size(columns) + 1:)
        product = 0.0_wp
        call this%stiffness%multiply(whole, product)
        t(1:size(rows)) = t(1:size(rows)) + product(rows)
        t(size(rows) + 1:) = t(size(rows) + 1:) + product(this%nc + rows)
    end subroutine multiply_elements

    !> Operators whose multiply_shear takes the shear columns from A as it is.
    subroutine shear_columns_of_stiffness(this)
        !> The operator
        class(elastic_operator), intent(inout) :: this

        this%shear_columns_apart = .false.
    end subroutine shear_columns_of_stiffness

    !> t = t + A [ds; 0]: the shear and normal tractions of every contact element from shear
    !> DDs of every contact element and no normal DDs (a fault that does not open: the
    !> products of an earthquake-cycle run, docs/theory/cycles.md#the-elastic-product).
    subroutine multiply_shear(this, ds, t)
        !> The operator
        class(elastic_operator), intent(in) :: this
        !> Shear DDs of the contact elements [length unit], shape (nc)
        real(wp), intent(in) :: ds(:)
        !> Tractions [shear; normal] of the contact elements [stress unit], shape (2 nc)
        real(wp), intent(inout) :: t(:)
        real(wp) :: product(2 * this%nc)

        product = 0.0_wp
        call this%stiffness%multiply([ds, spread(0.0_wp, 1, this%nc)], product)
        t = t + product
    end subroutine multiply_shear

end module ddc_solve_operator
