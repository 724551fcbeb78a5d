!> The boundary of a finite body, solved so that the rock outside it stays at rest
!> (docs/theory/finite-bodies.md).
!>
!> The body's boundary carries a quadratic DD equal to the rock's displacement there (the
!> DD u(-) - u(+) is -u where the interior is on the side of the element's normal, +u on
!> the other) and a quadratic line load equal to the traction on the body: the field of
!> both and of the fractures inside is then the body's own field inside and zero outside
!> (Somigliana's identity). At each node one of the DD and the line load of each component
!> is given (the side's condition) and the other is unknown; the equations ask for zero
!> traction on the outer face at every node. Rigid motions the conditions leave free are
!> fixed by bordering (their weighted sum of boundary displacements is zero), once the
!> tractions given are checked in equilibrium along them.
!>
!> The fractures see the body as a change of their medium: with the body's unknowns z,
!>     S z = r - C d,
!> (S the body's equations, r from its given values, C the traction of the fractures' DDs
!> d at its nodes), the fractures' rows take E z: their influence matrix loses E S^-1 C,
!> their load gains E S^-1 r plus the field of the given values.
module ddc_influence_body
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_text, only: rtoa
    use ddc_model_types, only: condition_displacement, condition_mixed_us_sn, &
        condition_mixed_ss_un
    use ddc_model_body, only: finite_body, body_nodes
    use ddc_model_medium, only: elastic_medium
    use ddc_model_results, only: boundary_results
    use ddc_influence_kernel, only: dd_kernel, dd_kernel_global, face_positive
    use ddc_influence_kernel_polynomial, only: nodal_sources, node_fields, &
        local_node_fields, node_weights, body_node_xi
    use ddc_influence_assembly, only: row_traction, row_displacement
    use ddc_linalg_lu, only: lu_factor, lu_solve
    use ddc_linalg_lapack, only: dgemm, dsyev, dgetrs, dgetrf
    implicit none
    private

    public :: prepare_body, body_matrix_correction, body_block_correction, body_load, body_state
    public :: body_field_at
    public :: body_induced_at, body_unknowns, boundary_values

    !> Kinds of a node's source component
    integer, parameter :: source_dd = 1, source_load = 2

contains

    !> The number of unknowns of the body (two per node).
    pure integer function body_unknowns(body)
        type(finite_body), intent(in) :: body

        body_unknowns = 2 * body_nodes * size(body%xm)
    end function body_unknowns

    !> Which source carries the unknown of component c (1: s, 2: n) of node i, and its factor
    !> per unit unknown (the unknown is the displacement or the traction along the side's s
    !> and outward n; docs/theory/finite-bodies.md#the-rock-outside-at-rest).
    pure subroutine unknown_source(body, i, c, kind, factor)
        type(finite_body), intent(in) :: body
        integer, intent(in) :: i, c
        integer, intent(out) :: kind
        real(wp), intent(out) :: factor

        if (displacement_given(body, i, c)) then
            kind = source_load
        else
            kind = source_dd
        end if
        factor = source_factor(body, kind, c)
    end subroutine unknown_source

    !> The source amplitude per unit displacement (source_dd) or traction (source_load) along
    !> s (c = 1) or the outward n (c = 2): D_s = -o u_s, D_n = u_n, P_s = t_s, P_n = -o t_n
    !> with o the orientation (+1 counter-clockwise).
    pure real(wp) function source_factor(body, kind, c)
        type(finite_body), intent(in) :: body
        integer, intent(in) :: kind, c

        if ((kind == source_dd) .eqv. (c == 1)) then
            source_factor = -real(body%orientation, wp)
        else
            source_factor = 1.0_wp
        end if
    end function source_factor

    !> Whether the side of node i gives the displacement of component c (else the traction).
    pure logical function displacement_given(body, i, c)
        type(finite_body), intent(in) :: body
        integer, intent(in) :: i, c

        associate (condition => body%condition(body%side((i - 1) / body_nodes + 1)))
            if (c == 1) then
                displacement_given = condition == condition_displacement .or. &
                                     condition == condition_mixed_us_sn
            else
                displacement_given = condition == condition_displacement .or. &
                                     condition == condition_mixed_ss_un
            end if
        end associate
    end function displacement_given

    !> The given value of component c of node i.
    pure real(wp) function given_value(body, i, c)
        type(finite_body), intent(in) :: body
        integer, intent(in) :: i, c

        if (c == 1) then
            given_value = body%given_s(i)
        else
            given_value = body%given_n(i)
        end if
    end function given_value

    !> The nodal fields of element e at (x, y); at the node `own_node` of e itself (0: the
    !> point is off e) on the outer face.
    pure function element_fields(body, shear_modulus, nu, x, y, e, own_node) result(f)
        type(finite_body), intent(in) :: body
        real(wp), intent(in) :: shear_modulus, nu, x, y
        integer, intent(in) :: e, own_node
        type(nodal_sources) :: f

        if (own_node > 0) then
            f = local_node_fields(body_node_xi(own_node) * body%a(e), 0.0_wp, body%a(e), &
                                  body%cosb(e), body%sinb(e), shear_modulus, nu, &
                                  -body%orientation)
        else
            f = node_fields(x, y, body%xm(e), body%ym(e), body%a(e), body%cosb(e), &
                            body%sinb(e), shear_modulus, nu, face_positive)
        end if
    end function element_fields

    !> Displacement and stress (ux, uy, sxx, syy, sxy) at (x, y) per unit of each unknown
    !> (columns), and of the given values (`given`); the point is node `node` of the body
    !> (0: a point off the boundary).
    pure subroutine unit_fields(body, shear_modulus, nu, x, y, node, columns, given)
        type(finite_body), intent(in) :: body
        real(wp), intent(in) :: shear_modulus, nu, x, y
        integer, intent(in) :: node
        real(wp), intent(out) :: columns(:, :), given(5)
        type(nodal_sources) :: f
        real(wp) :: factor, values(5)
        integer :: e, k, j, c, kind, own

        given = 0.0_wp
        do e = 1, size(body%xm)
            own = 0
            if (node > 0) then
                if ((node - 1) / body_nodes + 1 == e) own = node - body_nodes * (e - 1)
            end if
            f = element_fields(body, shear_modulus, nu, x, y, e, own)
            do k = 1, body_nodes
                j = body_nodes * (e - 1) + k
                do c = 1, 2
                    call unknown_source(body, j, c, kind, factor)
                    if (kind == source_dd) then
                        columns(:, 2 * (j - 1) + c) = factor * kernel_values(f%dd(k), unit(c))
                        values = kernel_values(f%load(k), unit(c))
                    else
                        columns(:, 2 * (j - 1) + c) = factor * kernel_values(f%load(k), unit(c))
                        values = kernel_values(f%dd(k), unit(c))
                    end if
                    given = given + source_factor(body, 3 - kind, c) * given_value(body, j, c) * &
                            values
                end do
            end do
        end do
    end subroutine unit_fields

    !> ux, uy, sxx, syy, sxy of a kernel's two columns weighted by w.
    pure function kernel_values(k, w) result(values)
        type(dd_kernel), intent(in) :: k
        real(wp), intent(in) :: w(2)
        real(wp) :: values(5)

        values = [dot_product(k%ux, w), dot_product(k%uy, w), dot_product(k%sxx, w), &
                  dot_product(k%syy, w), dot_product(k%sxy, w)]
    end function kernel_values

    !> The unit vector c of two.
    pure function unit(c) result(w)
        integer, intent(in) :: c
        real(wp) :: w(2)

        w = 0.0_wp
        w(c) = 1.0_wp
    end function unit

    !> Shear and normal traction of stress (sxx, syy, sxy) on a plane of direction (c, s)
    !> (normal (-s, c)).
    pure function on_plane(stress, c, s) result(t)
        real(wp), intent(in) :: stress(3), c, s
        real(wp) :: t(2)

        t(1) = -(stress(1) - stress(2)) * s * c + stress(3) * (c**2 - s**2)
        t(2) = stress(1) * s**2 - 2.0_wp * stress(3) * s * c + stress(2) * c**2
    end function on_plane

    !> The body's equations, bordered by its free rigid motions, factorized, and the unknowns
    !> under the given values with every fracture closed. Refuses tractions out of
    !> equilibrium along a free rigid motion.
    subroutine prepare_body(body, shear_modulus, nu, error)
        type(finite_body), intent(inout) :: body
        real(wp), intent(in) :: shear_modulus, nu
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: matrix(:, :), rhs(:, :), motions(:, :), constraint(:, :)
        real(wp), allocatable :: columns(:, :)
        real(wp) :: given(5)
        integer :: nz, nm, row, e

        nz = body_unknowns(body)
        call free_motions(body, motions)
        nm = size(motions, 2)
        body%free_motions = nm
        call check_equilibrium(body, motions, error)
        if (allocated(error)) return
        allocate (matrix(nz + nm, nz + nm), rhs(nz + nm, 1), columns(5, nz))
        matrix = 0.0_wp
        rhs = 0.0_wp
        ! Row pair of each node: the traction on its element's outer face
        !$omp parallel do default(none) schedule(dynamic, 4) private(row, e, columns, given) &
        !$omp shared(body, shear_modulus, nu, nz, matrix, rhs)
        do row = 1, nz / 2
            e = (row - 1) / body_nodes + 1
            call unit_fields(body, shear_modulus, nu, body%node_x(row), body%node_y(row), row, &
                             columns, given)
            matrix(2 * row - 1, 1:nz) = plane_rows(columns(3:5, :), body%cosb(e), &
                                                   body%sinb(e), 1)
            matrix(2 * row, 1:nz) = plane_rows(columns(3:5, :), body%cosb(e), body%sinb(e), 2)
            rhs(2 * row - 1:2 * row, 1) = -on_plane(given(3:5), body%cosb(e), body%sinb(e))
        end do
        !$omp end parallel do
        if (nm > 0) then
            call motion_rows(body, motions, constraint)
            matrix(nz + 1:, 1:nz) = constraint
            matrix(1:nz, nz + 1:) = transpose(constraint)
        end if
        allocate (body%pivots(nz + nm))
        call lu_factor(matrix, body%pivots, 'the equations of the finite body (&body)', error)
        if (allocated(error)) return
        call move_alloc(matrix, body%factors)
        if (nm > 0) call find_left_null(body, nz, nm)
        call solve_body(body, rhs)
        body%loaded = rhs(:, 1)
    end subroutine prepare_body

    !> The left null vectors y of the equations S (free motions N: S N = 0): the bordered
    !> transpose [S' N; N' 0] [y; m] = [0; e_k] gives S' y = 0 (N' S' y = 0 forces m = 0).
    subroutine find_left_null(body, nz, nm)
        type(finite_body), intent(inout) :: body
        integer, intent(in) :: nz, nm
        real(wp) :: vectors(nz + nm, nm), gram(nm, nm)
        integer :: k, info, pivots(nm)

        vectors = 0.0_wp
        do k = 1, nm
            vectors(nz + k, k) = 1.0_wp
        end do
        call dgetrs('T', nz + nm, nm, body%factors, nz + nm, body%pivots, vectors, nz + nm, info)
        body%left_null = vectors(1:nz, :)
        gram = matmul(transpose(body%left_null), body%left_null)
        allocate (body%left_null_gram(nm, nm))
        body%left_null_gram = 0.0_wp
        do k = 1, nm
            body%left_null_gram(k, k) = 1.0_wp
        end do
        call dgetrf(nm, nm, gram, nm, pivots, info)
        call dgetrs('N', nm, nm, gram, nm, pivots, body%left_null_gram, nm, info)
    end subroutine find_left_null

    !> Solves the body's equations for right-hand sides rhs (columns; the free motions'
    !> rows 0), their parts along the left null vectors removed first: the solution in
    !> least squares of a system that discretization leaves slightly inconsistent.
    subroutine solve_body(body, rhs)
        type(finite_body), intent(in) :: body
        real(wp), intent(inout) :: rhs(:, :)
        integer :: nz

        if (body%free_motions > 0) then
            nz = size(body%left_null, 1)
            rhs(1:nz, :) = rhs(1:nz, :) - matmul(body%left_null, matmul(body%left_null_gram, &
                matmul(transpose(body%left_null), rhs(1:nz, :))))
        end if
        call lu_solve(body%factors, body%pivots, rhs)
    end subroutine solve_body

    !> Component `which` (1: shear, 2: normal) of the traction on a plane of direction
    !> (c, s) of every column of stresses (sxx, syy, sxy), shape (m).
    pure function plane_rows(stress, c, s, which) result(t)
        real(wp), intent(in) :: stress(:, :), c, s
        integer, intent(in) :: which
        real(wp) :: t(size(stress, 2))

        if (which == 1) then
            t = -(stress(1, :) - stress(2, :)) * s * c + stress(3, :) * (c**2 - s**2)
        else
            t = stress(1, :) * s**2 - 2.0_wp * stress(3, :) * s * c + stress(2, :) * c**2
        end if
    end function plane_rows

    !> The rigid motions the given displacements leave free: columns of coefficients on
    !> translation x, translation y and rotation about the centroid (per unit of the body's
    !> size), shape (3, free).
    subroutine free_motions(body, motions)
        type(finite_body), intent(in) :: body
        real(wp), allocatable, intent(out) :: motions(:, :)
        real(wp) :: gram(3, 3), values(3), work(64), row(3)
        integer :: i, c, info, count

        gram = 0.0_wp
        count = 0
        do i = 1, size(body%node_x)
            do c = 1, 2
                if (.not. displacement_given(body, i, c)) cycle
                row = motion_components(body, i, c)
                gram = gram + spread(row, 2, 3) * spread(row, 1, 3)
                count = count + 1
            end do
        end do
        call dsyev('V', 'U', 3, gram, 3, values, work, size(work), info)
        ! Eigenvalues ascending: those near zero (relative to the count of displacement
        ! components, each of which adds at most 2) are the free motions.
        motions = gram(:, pack([1, 2, 3], values <= 1.0e-10_wp * max(real(count, wp), 1.0_wp)))
    end subroutine free_motions

    !> The global direction of component c (1: along the side, 2: the outward normal) at
    !> node i.
    pure function direction_of(body, i, c) result(d)
        type(finite_body), intent(in) :: body
        integer, intent(in) :: i, c
        real(wp) :: d(2)
        integer :: e

        e = (i - 1) / body_nodes + 1
        if (c == 1) then
            d = [body%cosb(e), body%sinb(e)]
        else
            d = -real(body%orientation, wp) * [-body%sinb(e), body%cosb(e)]
        end if
    end function direction_of

    !> The displacement along component c of node i of a unit translation x, of one y and
    !> of a rotation about the centroid of unit displacement at the body's size.
    pure function motion_components(body, i, c) result(row)
        type(finite_body), intent(in) :: body
        integer, intent(in) :: i, c
        real(wp) :: row(3)
        real(wp) :: xc, yc, size_of, u(2, 3)

        xc = sum(body%x) / size(body%x)
        yc = sum(body%y) / size(body%y)
        size_of = max(maxval(body%x) - minval(body%x), maxval(body%y) - minval(body%y))
        u(:, 1) = [1.0_wp, 0.0_wp]
        u(:, 2) = [0.0_wp, 1.0_wp]
        u(:, 3) = [-(body%node_y(i) - yc), body%node_x(i) - xc] / size_of
        row = matmul(direction_of(body, i, c), u)
    end function motion_components

    !> The weight of node i in integrals along the boundary [length unit].
    pure real(wp) function node_weight(body, i)
        type(finite_body), intent(in) :: body
        integer, intent(in) :: i
        integer :: e

        e = (i - 1) / body_nodes + 1
        node_weight = body%a(e) * node_weights(i - body_nodes * (e - 1))
    end function node_weight

    !> The weighted boundary displacement of each free motion per unit unknown, shape
    !> (free, nz): zero on traction unknowns.
    pure subroutine motion_rows(body, motions, rows)
        type(finite_body), intent(in) :: body
        real(wp), intent(in) :: motions(:, :)
        real(wp), allocatable, intent(out) :: rows(:, :)
        integer :: i, c

        allocate (rows(size(motions, 2), body_unknowns(body)))
        rows = 0.0_wp
        do i = 1, size(body%node_x)
            do c = 1, 2
                if (displacement_given(body, i, c)) cycle
                rows(:, 2 * (i - 1) + c) = node_weight(body, i) * &
                                           matmul(motion_components(body, i, c), motions)
            end do
        end do
    end subroutine motion_rows

    !> The work of the given tractions along each free motion must vanish (within 1e-3 of
    !> the work of their magnitudes): else the body has no equilibrium. Below that (tractions
    !> linear along each element that sample a smooth load, for one) the solve removes the
    !> part out of balance in least squares (solve_body).
    subroutine check_equilibrium(body, motions, error)
        type(finite_body), intent(in) :: body
        real(wp), intent(in) :: motions(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: work(size(motions, 2)), scale, force(2), along(size(motions, 2))
        integer :: i, c

        work = 0.0_wp
        scale = 0.0_wp
        force = 0.0_wp
        do i = 1, size(body%node_x)
            do c = 1, 2
                if (displacement_given(body, i, c)) cycle
                along = matmul(motion_components(body, i, c), motions)
                associate (t => given_value(body, i, c), w => node_weight(body, i))
                    work = work + w * t * along
                    scale = scale + w * abs(t) * sum(abs(along))
                    force = force + w * t * direction_of(body, i, c)
                end associate
            end do
        end do
        if (any(abs(work) > 1.0e-3_wp * scale)) then
            call set_error(error, exit_bad_input, '&body: the tractions given are not in '// &
                           'equilibrium along a rigid motion that no displacement given holds '// &
                           '(their net force is ('//rtoa(force(1))//', '//rtoa(force(2))// &
                           '), '//rtoa(maxval(abs(work)) / scale)//' of their magnitude, '// &
                           'more than 1e-3): balance them, or give a displacement that holds '// &
                           'the body')
        end if
    end subroutine check_equilibrium

    !> The traction on every node's equations per unit DD of the listed fracture elements
    !> (columns 1:m their Ds, m+1:2m their Dn), shape (nz + free, 2m): C.
    subroutine fracture_columns(medium, list, c)
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: list(:)
        real(wp), allocatable, intent(out) :: c(:, :)
        type(dd_kernel) :: k
        integer :: row, l, j, e, m

        m = size(list)
        allocate (c(size(medium%body%loaded), 2 * m))
        c = 0.0_wp
        !$omp parallel do default(none) schedule(dynamic, 8) private(row, l, j, e, k) &
        !$omp shared(medium, c, m, list)
        do row = 1, size(medium%body%node_x)
            e = (row - 1) / body_nodes + 1
            do l = 1, m
                j = list(l)
                k = dd_kernel_global(medium%body%node_x(row), medium%body%node_y(row), &
                                     medium%elements%x_mid(j), medium%elements%y_mid(j), &
                                     medium%elements%half_length(j), &
                                     medium%elements%cos_beta(j), medium%elements%sin_beta(j), &
                                     medium%shear_modulus, medium%poissons_ratio, face_positive)
                c(2 * row - 1:2 * row, l) = on_plane([k%sxx(1), k%syy(1), k%sxy(1)], &
                                                     medium%body%cosb(e), medium%body%sinb(e))
                c(2 * row - 1:2 * row, m + l) = on_plane([k%sxx(2), k%syy(2), k%sxy(2)], &
                                                         medium%body%cosb(e), &
                                                         medium%body%sinb(e))
            end do
        end do
        !$omp end parallel do
    end subroutine fracture_columns

    !> Every element's index, 1 to n.
    pure function every_element(medium) result(list)
        type(elastic_medium), intent(in) :: medium
        integer :: list(medium%elements%n)
        integer :: i

        list = [(i, i = 1, medium%elements%n)]
    end function every_element

    !> The body's unknowns (and its free motions' multipliers) with the fractures' DDs ds, dn:
    !> z = loaded - S^-1 C d.
    function body_state(medium, ds, dn) result(z)
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: ds(:), dn(:)
        real(wp) :: z(size(medium%body%loaded))
        real(wp), allocatable :: rhs(:, :), c(:, :)

        call fracture_columns(medium, every_element(medium), c)
        rhs = matmul(c, reshape([ds, dn], [2 * size(ds), 1]))
        call solve_body(medium%body, rhs)
        z = medium%body%loaded - rhs(:, 1)
    end function body_state

    !> Displacement and stress (ux, uy, sxx, syy, sxy) at (x, y) of the body's sources for
    !> its unknowns z (body_state), with the given values or (given false) without; the
    !> point off the boundary.
    pure function body_field_at(medium, z, x, y, given) result(values)
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: z(:), x, y
        logical, intent(in) :: given
        real(wp) :: values(5)
        real(wp) :: columns(5, body_unknowns(medium%body))

        call unit_fields(medium%body, medium%shear_modulus, medium%poissons_ratio, x, y, 0, &
                         columns, values)
        if (.not. given) values = 0.0_wp
        values = values + matmul(columns, z(1:size(columns, 2)))
    end function body_field_at

    !> The body's rows of the listed fracture elements per unit body unknown, rows 1:m and
    !> m+1:2m by the elements' row kinds (the traction along s, n at the midpoint, or the
    !> displacement; 0 for an identity row), shape (2m, nz): E.
    subroutine fracture_rows(medium, shear_row, normal_row, list, rows)
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: shear_row(:), normal_row(:), list(:)
        real(wp), allocatable, intent(out) :: rows(:, :)
        real(wp), allocatable :: columns(:, :)
        real(wp) :: given(5)
        integer :: m, l, i

        m = size(list)
        allocate (rows(2 * m, body_unknowns(medium%body)))
        allocate (columns(5, body_unknowns(medium%body)))
        !$omp parallel do default(none) schedule(dynamic, 4) private(l, i, columns, given) &
        !$omp shared(m, medium, rows, shear_row, normal_row, list)
        do l = 1, m
            i = list(l)
            call unit_fields(medium%body, medium%shear_modulus, medium%poissons_ratio, &
                             medium%elements%x_mid(i), medium%elements%y_mid(i), 0, columns, &
                             given)
            call kind_rows(columns, medium%elements%cos_beta(i), medium%elements%sin_beta(i), &
                           shear_row(i), normal_row(i), rows(l, :), rows(m + l, :))
        end do
        !$omp end parallel do
    end subroutine fracture_rows

    !> The shear and normal rows of an element of direction (c, s) and row kinds from
    !> columns of displacement and stress.
    pure subroutine kind_rows(columns, c, s, shear_row, normal_row, shear, normal)
        real(wp), intent(in) :: columns(:, :), c, s
        integer, intent(in) :: shear_row, normal_row
        real(wp), intent(out) :: shear(:), normal(:)

        select case (shear_row)
        case (row_traction)
            shear = plane_rows(columns(3:5, :), c, s, 1)
        case (row_displacement)
            shear = columns(1, :) * c + columns(2, :) * s
        case default
            shear = 0.0_wp
        end select
        select case (normal_row)
        case (row_traction)
            normal = plane_rows(columns(3:5, :), c, s, 2)
        case (row_displacement)
            normal = -columns(1, :) * s + columns(2, :) * c
        case default
            normal = 0.0_wp
        end select
    end subroutine kind_rows

    !> The fractures' influence matrix in the body: minus E S^-1 C, E the body's rows of the
    !> fractures (fracture_rows) and C the fractures' traction at the body's nodes.
    subroutine body_matrix_correction(medium, shear_row, normal_row, matrix)
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: shear_row(:), normal_row(:)
        real(wp), intent(inout) :: matrix(:, :)
        real(wp), allocatable :: rows(:, :), solved(:, :)
        integer :: n

        n = medium%elements%n
        call fracture_rows(medium, shear_row, normal_row, every_element(medium), rows)
        call fracture_columns(medium, every_element(medium), solved)
        call solve_body(medium%body, solved)
        call dgemm('N', 'N', 2 * n, 2 * n, body_unknowns(medium%body), -1.0_wp, rows, 2 * n, &
                   solved, size(solved, 1), 1.0_wp, matrix, size(matrix, 1))
    end subroutine body_matrix_correction

    !> body_matrix_correction on the rows of the elements `row_list` and the columns of the
    !> elements `column_list` only ([s; n] indices of the whole matrix): the new rows and
    !> columns of a grown model.
    subroutine body_block_correction(medium, shear_row, normal_row, row_list, column_list, &
                                     matrix)
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: shear_row(:), normal_row(:), row_list(:), column_list(:)
        real(wp), intent(inout) :: matrix(:, :)
        real(wp), allocatable :: rows(:, :), solved(:, :), block(:, :)
        integer :: n

        if (size(row_list) == 0 .or. size(column_list) == 0) return
        n = medium%elements%n
        call fracture_rows(medium, shear_row, normal_row, row_list, rows)
        call fracture_columns(medium, column_list, solved)
        call solve_body(medium%body, solved)
        allocate (block(2 * size(row_list), 2 * size(column_list)))
        call dgemm('N', 'N', size(block, 1), size(block, 2), body_unknowns(medium%body), &
                   1.0_wp, rows, size(rows, 1), solved, size(solved, 1), 0.0_wp, block, &
                   size(block, 1))
        associate (r => [row_list, n + row_list], c => [column_list, n + column_list])
            matrix(r, c) = matrix(r, c) - block
        end associate
    end subroutine body_block_correction

    !> The traction along s and n and the displacement at the fractures' midpoints of the body
    !> under its given values, every fracture closed: what the body adds to their load.
    pure subroutine body_load(medium, shear, normal, us, un)
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(out) :: shear(:), normal(:), us(:), un(:)
        real(wp) :: values(5)
        integer :: i

        associate (el => medium%elements)
            do i = 1, el%n
                values = body_field_at(medium, medium%body%loaded, el%x_mid(i), el%y_mid(i), .true.)
                associate (t => on_plane(values(3:5), el%cos_beta(i), el%sin_beta(i)))
                    shear(i) = t(1)
                    normal(i) = t(2)
                end associate
                us(i) = values(1) * el%cos_beta(i) + values(2) * el%sin_beta(i)
                un(i) = -values(1) * el%sin_beta(i) + values(2) * el%cos_beta(i)
            end do
        end associate
    end subroutine body_load

    !> Adds the traction and displacement the body's answer to the fractures' DDs gives the
    !> listed fracture elements (the change of the medium: -E S^-1 C d).
    subroutine body_induced_at(medium, ds, dn, list, ts, tn, us, un)
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: ds(:), dn(:)
        integer, intent(in) :: list(:)
        real(wp), intent(inout) :: ts(:), tn(:), us(:), un(:)
        real(wp) :: z(size(medium%body%loaded))
        real(wp) :: values(5)
        integer :: k, i

        z = body_state(medium, ds, dn)
        z = z - medium%body%loaded
        associate (el => medium%elements)
            do k = 1, size(list)
                i = list(k)
                values = body_field_at(medium, z, el%x_mid(i), el%y_mid(i), .false.)
                associate (t => on_plane(values(3:5), el%cos_beta(i), el%sin_beta(i)))
                    ts(i) = ts(i) + t(1)
                    tn(i) = tn(i) + t(2)
                end associate
                us(i) = us(i) + values(1) * el%cos_beta(i) + values(2) * el%sin_beta(i)
                un(i) = un(i) - values(1) * el%sin_beta(i) + values(2) * el%cos_beta(i)
            end do
        end associate
    end subroutine body_induced_at
    !> The boundary after a solve with the fractures' DDs ds, dn: each node's displacement
    !> and traction along s and the outward n (given or solved) and each side's net force.
    subroutine boundary_values(medium, ds, dn, boundary)
        type(elastic_medium), intent(in) :: medium
        real(wp), intent(in) :: ds(:), dn(:)
        type(boundary_results), intent(out) :: boundary
        real(wp) :: z(size(medium%body%loaded)), value
        real(wp), allocatable :: u(:, :), t(:, :)
        integer :: i, c, e

        z = body_state(medium, ds, dn)
        associate (body => medium%body)
            allocate (u(2, size(body%node_x)), t(2, size(body%node_x)))
            do i = 1, size(body%node_x)
                do c = 1, 2
                    value = z(2 * (i - 1) + c)
                    if (displacement_given(body, i, c)) then
                        u(c, i) = given_value(body, i, c)
                        t(c, i) = value
                    else
                        u(c, i) = value
                        t(c, i) = given_value(body, i, c)
                    end if
                end do
            end do
            boundary%x = body%node_x
            boundary%y = body%node_y
            boundary%side = [((body%side((i - 1) / body_nodes + 1)), i = 1, size(body%node_x))]
            boundary%us = u(1, :)
            boundary%un = u(2, :)
            boundary%ts = t(1, :)
            boundary%tn = t(2, :)
            allocate (boundary%force_x(size(body%x)), boundary%force_y(size(body%x)))
            boundary%force_x = 0.0_wp
            boundary%force_y = 0.0_wp
            do i = 1, size(body%node_x)
                e = boundary%side(i)
                associate (f => node_weight(body, i) * (t(1, i) * direction_of(body, i, 1) + &
                                                        t(2, i) * direction_of(body, i, 2)))
                    boundary%force_x(e) = boundary%force_x(e) + f(1)
                    boundary%force_y(e) = boundary%force_y(e) + f(2)
                end associate
            end do
        end associate
    end subroutine boundary_values

end module ddc_influence_body
