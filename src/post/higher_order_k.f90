!> K_I and K_II by a local higher-order re-solve (docs/theory/tips.md#the-local-re-solve).
!>
!> A zone of the first zone_elements traction or contact elements from each tip is solved
!> again with higher-order elements (ddc_influence_higher_order: quadratic, square-root
!> weighted over the first half of each tip's zone, circular arcs where the polyline
!> samples a curve); the traction and contact elements outside the zones act with their
!> recovered DDs (ddc_post_outer_recovery), the other elements with their constant DDs.
!> Each re-solved element keeps its condition in the solve (row_conditions) at each of its
!> three nodes, with the solve's values on the element: a traction element its tractions, a
!> closed contact element its DD or joint law and the Coulomb law where it slips. K comes
!> from the limit of D / sqrt(r) at each tip, in the frame of the fracture's tangent there.
!> The zones' traction rows depend on the geometry alone and are assembled once
!> (prepare_higher_order); the system is factorized again only when the conditions change.
!>
!> The elements outside the zones are the solve's: outer_correction gives the traction the
!> higher-order zones and the recovered DDs add at their midpoints to the constant elements'
!> (the caller solves the model again with it, ddc_run_contact_run, until K stops moving).
module ddc_post_higher_order_k
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_error, only: error_type
    use ddc_model_types, only: element_set, condition_contact, condition_traction, rigid_joint, &
        domain_bimaterial
    use ddc_model_results, only: tip_set
    use ddc_model_medium, only: elastic_medium, elastic_material, element_material, &
        remote_stress_at
    use ddc_contact_states, only: state_stick, state_slip
    use ddc_allocation, only: allocation_failed, real_bytes
    use ddc_influence_kernel, only: dd_kernel, face_negative
    use ddc_influence_assembly, only: kernel_function, select_kernel, image_transform, &
        image_transforms, kernel_with_images, resolved_tractions
    use ddc_influence_higher_order, only: weighted_element, arc_element, node_xi, &
        nodal_basis, element_tractions, weight_at, point_at, gauss_x => gauss_8_x, &
        gauss_w => gauss_8_w
    use ddc_post_tips, only: tip_chain, end_neighbours, end_on_mirror, end_turn
    use ddc_post_outer_recovery, only: outer_recovery, recover_outer, recovered_block, &
        stencil_blocks, halves_kernels, halves_block, near_lengths, next_recovered, &
        straight_reach, curved_reach, far_recovered_blocks
    use ddc_linalg_lu, only: lu_factor, lu_solve
    use ddc_linalg_block_rows, only: block_row, row_builder, row_times
    use ddc_linalg_low_rank, only: low_rank_block, add_low_rank_times, pair_entries, &
        approximate_entries
    use ddc_post_far_rows, only: zone_cluster, zone_clusters, far_from, beyond_band, far_block, &
        drop_far, append_near, far_tolerance
    use ddc_contact_options, only: k_higher_order, k_tip_element
    use ddc_text, only: itoa
    implicit none
    private

    public :: higher_order_solver, prepare_higher_order, higher_order_k, uses_higher_order
    public :: tips_re_solved
    public :: higher_order_bytes
    public :: outer_correction
    public :: on_demand_rows

    !> k_method = 'auto' re-solves at most this many elements in all the zones (two dense
    !> matrices of 6 unknowns per element, the traction rows and the factors: 576 MB here)
    integer, parameter :: higher_order_max_elements = 1000
    !> Unknowns per element: three nodes, two DDs
    integer, parameter :: per_element = 6
    !> A vertex that turns by more than this [rad] off a sampled curve is a corner of the
    !> fracture, where a zone of the re-solve is centred
    real(wp), parameter :: kink_turn = 1.0e-6_wp
    !> A kink that turns by this much or more [rad] has a zone of half a tip's zone a side,
    !> a smaller one in proportion, at least min_kink_zone elements (kink_zone; 20 degrees)
    real(wp), parameter :: full_kink_turn = 0.35_wp
    integer, parameter :: min_kink_zone = 2
    !> A vertex that turns by more than this [rad] is a kink, not a sample of a curve
    real(wp), parameter :: max_curve_turn = 0.35_wp
    !> The curvatures at two vertices of a sampled curve agree within this fraction
    real(wp), parameter :: curvature_agreement = 0.5_wp
    !> The rows of the zones' load and of the outer correction are kept where they take at
    !> most this many bytes, else gathered again at each product [bytes]
    real(wp), parameter :: kept_rows_max_bytes = 256.0_wp * 1024.0_wp**2
    !> Receivers of the outer correction gathered at once (its rows whole at once while they
    !> are kept): a sixteenth of them, from 128 to 1024 (a block's columns, the zone's, are
    !> then repeated in fewer blocks); and columns of a zone's load in one low-rank block
    !> (the size of its dense form)
    integer, parameter :: min_receivers = 128, max_receivers = 1024, zone_columns = 4096
    !> A cluster with at least this many rows of the zones' load (two a node: 16 zone
    !> elements) has its far blocks, of the zones' load and of the outer correction,
    !> approximated from the entries they ask for (zone_load_entries, correction_entries); a
    !> smaller one's rank is near its rows' or columns', and its rows are gathered whole
    integer, parameter :: on_demand_rows = 96
    !> Receivers of the outer correction in one block from entries on demand (its members'
    !> columns are kept while it is approximated: 128 bytes a receiver and member)
    integer, parameter :: on_demand_receivers = 8192
    !> The parts of a row of the outer correction: the whole row, the band of recovered
    !> neighbours alone, the zones' part alone
    integer, parameter :: whole_row = 0, band_part = 1, zones_part = 2
    !> The two linear maps of the coupling: the tractions at the zones' nodes from the DDs
    !> outside them, and the outer correction
    integer, parameter :: zone_load = 1, correction = 2

    !> The clusters of zone elements of one geometry and what is far from each, shape (n,
    !> clusters): the elements (the zones' load's far columns) and the receivers of the
    !> outer correction, also beyond their bands' reach of it (its far rows).
    type :: zone_far_field
        type(zone_cluster), allocatable :: clusters(:)
        logical, allocatable :: far_elements(:, :), far_receivers(:, :)
    end type zone_far_field

    !> The rows of one low-rank block of a map being kept, and its columns, shape (columns).
    type :: far_task
        integer, allocatable :: which(:)
        logical, allocatable :: far(:)
    end type far_task

    !> The zones' load at one cluster's nodes from the elements far from it, computed on
    !> demand: a pair of rows a node's two tractions (zone_load_row at the far columns alone),
    !> a pair of columns a far element's two DDs (its constant DD's block, or its share in
    !> the recovered DDs whose stencils hold it).
    type, extends(pair_entries) :: zone_load_entries
        type(higher_order_solver), pointer :: solver => null()
        type(elastic_medium), pointer :: medium => null()
        procedure(kernel_function), pointer, nopass :: kernel => null()
        type(image_transform), allocatable :: images(:)
        !> The rows of the zones' load (the cluster's nodes) and the far elements (the
        !> columns)
        integer, allocatable :: node_row(:), element(:)
        !> Whether each element is a column, and its place among them, shape (n)
        logical, allocatable :: far(:)
        integer, allocatable :: place(:)
        !> The recovered elements whose stencils hold element j (their places in the
        !> recovery): holder(first(j):first(j + 1) - 1), shape (n + 1) and (:)
        integer, allocatable :: first(:), holder(:)
    contains
        procedure :: row_pair => zone_load_row_pair
        procedure :: column_pair => zone_load_column_pair
    end type zone_load_entries

    !> One zone element's columns of a correction block (correction_entries).
    type :: member_columns
        real(wp), allocatable :: values(:, :)
    end type member_columns

    !> The outer correction at the far receivers of one cluster from its zone elements,
    !> computed on demand: a pair of rows a receiver's two tractions from every member (four
    !> pairs of columns each: its three nodes' DDs and its constant DD), a pair of columns one
    !> of a member's at every receiver; a member's four are computed together and kept.
    type, extends(pair_entries) :: correction_entries
        type(higher_order_solver), pointer :: solver => null()
        type(elastic_medium), pointer :: medium => null()
        procedure(kernel_function), pointer, nopass :: kernel => null()
        type(image_transform), allocatable :: images(:)
        !> The rows of the correction (receivers) and the cluster's zone elements
        integer, allocatable :: receiver(:), member(:)
        !> Each member's four pairs of columns, shape (2 receivers, 8) where computed
        type(member_columns), allocatable :: computed(:)
    contains
        procedure :: row_pair => correction_row_pair
        procedure :: column_pair => correction_column_pair
    end type correction_entries

    !> The re-solve of one geometry and its tips.
    type :: higher_order_solver
        !> Elements re-solved (model numbering), and each element's place among them (0: not
        !> re-solved), shape (re-solved) and (n)
        integer, allocatable :: solved(:), local(:)
        !> Their geometry and weights
        type(weighted_element), allocatable :: weighted(:)
        !> Traction rows: the tractions at the nodes per unit nodal value, shape (6 re-solved,
        !> 6 re-solved)
        real(wp), allocatable :: traction(:, :)
        !> The system of the row conditions `rows` (row_conditions), factorized (LU and
        !> pivots); rows unallocated before the first
        real(wp), allocatable :: lu(:, :), rows(:, :)
        integer, allocatable :: ipiv(:)
        !> The traction and contact elements outside the zones, recovered
        type(outer_recovery) :: outer
        !> The weights of each re-solved element's three nodal values in its mean DD [-] and
        !> in its first moment about the midpoint [length unit**2], shape (3, re-solved)
        real(wp), allocatable :: mean_weight(:, :), moment_weight(:, :)
        !> The rows of the zones' load (one per node of the zones, in the order of the
        !> unknowns; columns the model's elements) and of the outer correction (one per
        !> recovered element; columns the model's elements, then the zones' nodes), each
        !> block per unit pair of DDs (Ds, Dn); kept where they fit (kept_rows_max_bytes),
        !> their entries far from a zone as low-rank blocks (ddc_post_far_rows). rows_kept:
        !> the zones' load and the zones' part of the correction are kept; bands_kept: the
        !> correction's bands too (else gathered again at each product)
        logical :: rows_kept = .false., bands_kept = .false.
        !> The estimates of their bytes (rows_bytes): the zones' parts and the bands
        real(wp) :: zones_bytes = 0.0_wp, bands_bytes = 0.0_wp
        type(block_row), allocatable :: zone_rows(:), correction_rows(:)
        type(low_rank_block), allocatable :: zone_far(:), correction_far(:)
        !> The clusters whose far blocks of the zones' load and of the outer correction came
        !> from entries on demand (zone_load_entries, correction_entries; the others' from
        !> their gathered rows)
        integer :: far_loads_on_demand = 0, far_corrections_on_demand = 0
        !> The nodal DDs of the last re-solve [length unit], shape (6 re-solved)
        real(wp), allocatable :: nodal(:)
    end type higher_order_solver

contains

    !> Whether K comes from the higher-order re-solve, and why not where it does not.
    pure subroutine uses_higher_order(k_method, zone, growth, medium, tips, uses, why_not)
        !> &solver k_method (k_auto, k_higher_order or k_tip_element)
        integer, intent(in) :: k_method
        !> Elements of a tip's zone
        integer, intent(in) :: zone
        !> Whether the model grows its fractures
        logical, intent(in) :: growth
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The tips (ddc_post_tips)
        type(tip_set), intent(in) :: tips
        !> Whether the re-solve serves
        logical, intent(out) :: uses
        !> Why the tip element serves instead ('' where the re-solve serves or there are
        !> no tips)
        character(len=:), allocatable, intent(out) :: why_not
        integer :: n

        uses = .false.
        why_not = ''
        if (tips%n == 0) return
        if (k_method == k_tip_element) then
            why_not = "&solver k_method = 'tip_element'"
        else if (growth .and. k_method /= k_higher_order) then
            ! Every trial of a growth step would prepare its zones anew: asked for only.
            why_not = 'growth calibrates the tip element'
        else if (allocated(medium%body)) then
            ! The zones' loads sum the kernel of the infinite plane.
            why_not = 'the fractures lie in a finite body'
        else
            n = count(re_solved(medium, tips, zone))
            uses = n > 0 .and. (k_method == k_higher_order .or. n <= higher_order_max_elements)
            if (n == 0) then
                why_not = 'no tip on a traction or contact element'
            else if (.not. uses) then
                why_not = itoa(n)//' elements in the zones, above '// &
                    itoa(higher_order_max_elements)//" (k_method = 'higher_order' asks for it)"
            end if
        end if
    end subroutine uses_higher_order

    !> Assemble the traction rows of the zones' re-solve and recover the elements outside
    !> them.
    subroutine prepare_higher_order(medium, tips, zone, solver, error, max_kept_bytes)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The tips (ddc_post_tips)
        type(tip_set), intent(in) :: tips
        !> Elements of a tip's zone
        integer, intent(in) :: zone
        !> The re-solve, its traction rows assembled (factorized by higher_order_k)
        type(higher_order_solver), intent(out) :: solver
        !> Allocated when the matrices do not fit in memory
        type(error_type), allocatable, intent(out) :: error
        !> Keep the rows of the coupling where they take at most this many bytes [bytes]
        !> (default kept_rows_max_bytes)
        real(wp), intent(in), optional :: max_kept_bytes
        real(wp), allocatable :: curvature(:)
        type(zone_far_field) :: field
        real(wp) :: limit
        integer :: k, m, stat

        associate (s => solver, elements => medium%elements)
            s%solved = pack([(k, k = 1, elements%n)], re_solved(medium, tips, zone))
            allocate (s%local(elements%n), source=0)
            s%local(s%solved) = [(k, k = 1, size(s%solved))]
            curvature = sampled_curvature(elements)
            s%weighted = tip_weighted_elements(elements, tips, curvature, s%solved, s%local)
            s%outer = recover_outer(medium, curvature, serves(elements), s%local > 0, &
                                    max_curve_turn)
            m = per_element * size(s%solved)
            allocate (s%traction(m, m), stat=stat)
            if (stat == 0) allocate (s%lu(m, m), stat=stat)
            if (stat == 0) allocate (s%ipiv(m), stat=stat)
            if (stat /= 0) then
                call allocation_failed(error, 'the higher-order re-solve for K of '// &
                    itoa(size(s%solved))//' elements', 2.0_wp * real_bytes * real(m, wp)**2)
                return
            end if
            call assemble(medium, s%solved, s%weighted, s%traction)
            call add_recovered_neighbours(medium, s)
            call moment_weights(s%weighted, s%mean_weight, s%moment_weight)
            limit = kept_rows_max_bytes
            if (present(max_kept_bytes)) limit = max_kept_bytes
            field = far_field(medium, s%solved, s%outer%neighbour, curvature)
            call rows_bytes(medium, s%local > 0, curvature, field, s%zones_bytes, s%bands_bytes)
            s%rows_kept = s%zones_bytes <= limit
            s%bands_kept = s%rows_kept .and. s%zones_bytes + s%bands_bytes <= limit
            if (s%rows_kept) call keep_rows(medium, s, field)
        end associate
    end subroutine prepare_higher_order

    !> K_I and K_II of the re-solved tips for one solution of the model; the other tips'
    !> values are left as given.
    subroutine higher_order_k(solver, medium, ds, dn, shear_traction, normal_traction, mu, &
                              remote, gradient, state, tips, k1, k2, error)
        !> The re-solve (prepare_higher_order); factorized again where the conditions changed
        type(higher_order_solver), intent(inout) :: solver
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The solve's DDs [length unit] and total midpoint tractions [stress unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:), shear_traction(:), normal_traction(:)
        !> Friction in force [-], shape (n)
        real(wp), intent(in) :: mu(:)
        !> Remote stress sxx, syy, sxy (at y = 0) [stress unit] and its gradient d/dy
        !> [stress unit / length unit]
        real(wp), intent(in) :: remote(3), gradient(3)
        !> Element states, shape (n)
        integer, intent(in) :: state(:)
        !> The tips
        type(tip_set), intent(in) :: tips
        !> Stress intensity factors [stress unit * length unit**0.5], shape (tips)
        real(wp), intent(inout) :: k1(:), k2(:)
        !> Allocated when the re-solve's matrix is singular (K left as given)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: q(:, :), r(:), rows(:, :)
        integer :: k, l, i, node, row

        allocate (rows(5, size(solver%solved)))
        rows = row_conditions(medium%elements, ds, shear_traction, mu, state, solver%solved)
        if (.not. allocated(solver%rows)) then
            call factorize(solver, rows, error)
        else if (any(rows /= solver%rows)) then
            call factorize(solver, rows, error)
        end if
        if (allocated(error)) return
        allocate (r(size(solver%lu, 1)), q(size(solver%lu, 1), 1))
        call load_of(medium, solver, ds, dn, shear_traction, normal_traction, remote, gradient, r)
        ! Each row's condition holds for the solve's values on its element.
        do l = 1, size(solver%solved)
            i = solver%solved(l)
            do node = 1, 3
                row = per_element * (l - 1) + 2 * (node - 1)
                q(row + 1, 1) = rows(1, l) * r(row + 1) + rows(2, l) * r(row + 2) + &
                                rows(3, l) * ds(i)
                q(row + 2, 1) = rows(4, l) * r(row + 2) + rows(5, l) * dn(i)
            end do
        end do
        call lu_solve(solver%lu, solver%ipiv, q)
        solver%nodal = q(:, 1)
        do k = 1, tips%n
            l = solver%local(tips%element(k))
            if (l == 0) cycle
            call tip_k(element_material(medium, tips%element(k)), solver, q(:, 1), tips, k, &
                       k1(k), k2(k))
            ! A DD held at zero on the tip element has no K (exactly: the factorization's
            ! pivots may leave rounding in it).
            if (rows(1, l) == 0.0_wp) k2(k) = 0.0_wp
            if (rows(4, l) == 0.0_wp) k1(k) = 0.0_wp
        end do
    end subroutine higher_order_k

    !> The condition of each re-solved element, as the coefficients (a_ss, a_sn, b_s, a_nn,
    !> b_n) of its rows a_ss t_s + a_sn t_n + b_s D_s = const and a_nn t_n + b_n D_n = const
    !> at each node, the constants those of the solve's values on the element. A traction
    !> element and an open contact element: t_s, t_n. A closed contact element: D_n (rigid:
    !> the solve holds it at zero) or t_n + k_n D_n (an elastic joint); slipping, the
    !> Coulomb law t_s + sign(t_s) mu t_n; sticking, D_s where it never slipped (rigid),
    !> t_s + k_s D_s (an elastic joint), else t_s (the shape of a slip it kept is unknown).
    pure function row_conditions(elements, ds, shear_traction, mu, state, solved) result(rows)
        type(element_set), intent(in) :: elements
        real(wp), intent(in) :: ds(:), shear_traction(:), mu(:)
        integer, intent(in) :: state(:), solved(:)
        real(wp) :: rows(5, size(solved))
        real(wp) :: ks, kn
        integer :: l, i

        do l = 1, size(solved)
            i = solved(l)
            rows(:, l) = [1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp]
            if (elements%condition(i) /= condition_contact) cycle
            if (state(i) /= state_stick .and. state(i) /= state_slip) cycle
            ks = rigid_joint
            kn = rigid_joint
            if (allocated(elements%shear_stiffness)) ks = elements%shear_stiffness(i)
            if (allocated(elements%normal_stiffness)) kn = elements%normal_stiffness(i)
            if (kn < rigid_joint) then
                rows(4:5, l) = [1.0_wp, kn]
            else
                rows(4:5, l) = [0.0_wp, 1.0_wp]
            end if
            if (state(i) == state_slip) then
                rows(2, l) = sign(mu(i), shear_traction(i))
            else if (ks < rigid_joint) then
                rows(3, l) = ks
            else if (ds(i) == 0.0_wp) then
                rows(1:3, l) = [0.0_wp, 0.0_wp, 1.0_wp]
            end if
        end do
    end function row_conditions

    !> The system of the given row conditions from the traction rows, factorized.
    subroutine factorize(solver, rows, error)
        type(higher_order_solver), intent(inout) :: solver
        real(wp), intent(in) :: rows(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: w(3), dw
        integer :: l, node, row, m, u

        m = size(solver%traction, 1)
        do l = 1, size(solver%solved)
            ! The DD at a node is its weight times the nodal value.
            do node = 1, 3
                call weight_at(solver%weighted(l), 0.5_wp * solver%weighted(l)%length * &
                               (1.0_wp + node_xi(node)), w(node), dw)
            end do
            do node = 1, 3
                row = per_element * (l - 1) + 2 * (node - 1)
                solver%lu(row + 1, :) = rows(1, l) * solver%traction(row + 1, :) + &
                                        rows(2, l) * solver%traction(row + 2, :)
                solver%lu(row + 1, row + 1) = solver%lu(row + 1, row + 1) + rows(3, l) * w(node)
                solver%lu(row + 2, :) = rows(4, l) * solver%traction(row + 2, :)
                solver%lu(row + 2, row + 2) = solver%lu(row + 2, row + 2) + rows(5, l) * w(node)
            end do
        end do
        solver%rows = rows
        call lu_factor(solver%lu, solver%ipiv, 'matrix of the higher-order re-solve for K', &
                       error, [(solver%solved((u - 1) / per_element + 1), u = 1, m)], &
                       [(mod(u - 1, 2) == 0, u = 1, m)])
        if (allocated(error)) deallocate (solver%rows)
    end subroutine factorize

    !> The zones: the first `zone` traction or contact elements of the chain from each tip on
    !> such an element, and the first zone / 2 from each corner of a fracture with tips
    !> (where its DD is not smooth: a kink, a junction, a crack mouth at a free surface, a
    !> crossing of the interface of two materials).
    pure function re_solved(medium, tips, zone) result(mask)
        type(elastic_medium), intent(in) :: medium
        type(tip_set), intent(in) :: tips
        integer, intent(in) :: zone
        logical :: mask(medium%elements%n)
        logical :: kind_serves(medium%elements%n), with_tips(medium%elements%n)
        logical :: is_tip(2, medium%elements%n)
        integer :: neighbour(2, medium%elements%n), neighbour_side(2, medium%elements%n)
        integer :: k, i, side
        real(wp) :: curvature(medium%elements%n)

        associate (elements => medium%elements)
        kind_serves = serves(elements)
        curvature = sampled_curvature(elements)
        mask = .false.
        is_tip = .false.
        call end_neighbours(elements, neighbour, neighbour_side)
        do k = 1, tips%n
            is_tip(tips%side(k), tips%element(k)) = .true.
            if (kind_serves(tips%element(k))) call mark(tips%element(k), tips%side(k), zone)
        end do
        do i = 1, elements%n
            with_tips(i) = any(kind_serves(tips%element) .and. &
                               tips%fracture_id == elements%fracture_id(i))
        end do
        do i = 1, elements%n
            if (.not. (kind_serves(i) .and. with_tips(i))) cycle
            do side = 1, 2
                if (is_tip(side, i)) cycle
                if (neighbour(side, i) > 0) then
                    call mark(i, side, corner_zone(i, side))
                else
                    call mark(i, side, max(zone / 2, 1))
                end if
            end do
        end do
        end associate

    contains

        !> Mark the first `count` elements of the chain from end `side` of element i (each
        !> on through its other end to the neighbour that alone shares it, as tip_chain, but
        !> no farther than asked: a walk per corner).
        pure subroutine mark(i, side, count)
            integer, intent(in) :: i, side, count
            integer :: c, j, j_side, next

            j = i
            j_side = side
            do c = 1, min(count, medium%elements%n)
                if (.not. kind_serves(j)) exit
                mask(j) = .true.
                next = neighbour(3 - j_side, j)
                if (next == 0) exit
                j_side = neighbour_side(3 - j_side, j)
                j = next
            end do
        end subroutine mark

        !> Elements a side of the zone at end `side` of element i (which has a neighbour
        !> there): kink_zone where the polyline turns other than on a sampled curve (whose
        !> elements both have a curvature: sampled_curvature), half a tip's zone where two
        !> materials meet, else 0.
        pure integer function corner_zone(i, side)
            integer, intent(in) :: i, side
            integer :: j
            real(wp) :: turn

            j = neighbour(side, i)
            corner_zone = 0
            associate (e => medium%elements)
                turn = end_turn(e, i, side, j, neighbour_side(side, i))
                if (abs(turn) > kink_turn .and. (curvature(i) == 0.0_wp .or. &
                                                 curvature(j) == 0.0_wp)) then
                    corner_zone = kink_zone(zone, turn)
                end if
                ! Two materials meet there: the DD is not smooth, whatever the turn.
                if (e%domain == domain_bimaterial) then
                    if (e%y_mid(i) > medium%interface_y .neqv. e%y_mid(j) > medium%interface_y) then
                        corner_zone = max(zone / 2, 1)
                    end if
                end if
            end associate
        end function corner_zone
    end function re_solved

    !> Elements a side of a kink's zone: half a tip's zone where the polyline turns by
    !> full_kink_turn or more, in proportion to the turn below it, at least min_kink_zone
    !> (and at most half a tip's zone).
    !> The DD's departure from a smooth one at a kink grows with the turn; a growth path's
    !> small kinks (a few degrees at every step) would otherwise put the whole path in zones.
    pure integer function kink_zone(zone, turn)
        !> Elements of a tip's zone
        integer, intent(in) :: zone
        !> The polyline's turn there [rad]
        real(wp), intent(in) :: turn

        kink_zone = max(min_kink_zone, nint(real(zone / 2, wp) * &
                                            min(1.0_wp, abs(turn) / full_kink_turn)))
        kink_zone = max(1, min(zone / 2, kink_zone))
    end function kink_zone

    !> The tips whose K the re-solve gave: where it served the solve (tips%k_method), those on
    !> elements of a kind it re-solves; the others keep the tip element's K.
    pure function tips_re_solved(elements, tips) result(mask)
        type(element_set), intent(in) :: elements
        type(tip_set), intent(in) :: tips
        logical :: mask(tips%n)
        logical :: kind_serves(elements%n)

        mask = .false.
        if (.not. allocated(tips%k_method)) return
        if (index(tips%k_method, 'higher_order') /= 1) return
        kind_serves = serves(elements)
        mask = kind_serves(tips%element(1:tips%n))
    end function tips_re_solved

    !> Whether each element is of a kind the re-solve serves: traction and contact elements.
    pure function serves(elements)
        type(element_set), intent(in) :: elements
        logical :: serves(elements%n)

        serves = elements%condition == condition_traction .or. &
                 elements%condition == condition_contact
    end function serves

    !> The re-solved elements as arcs (sampled_curvature), with a square-root weight on the
    !> first half of each tip's chain (a zone of fixed size, so the DD over the weight is
    !> smooth).
    pure function tip_weighted_elements(elements, tips, curvature, solved, local) &
        result(weighted)
        type(element_set), intent(in) :: elements
        type(tip_set), intent(in) :: tips
        real(wp), intent(in) :: curvature(:)
        integer, intent(in) :: solved(:), local(:)
        type(weighted_element) :: weighted(size(solved))
        integer, allocatable :: chain(:), near_side(:)
        real(wp) :: reach, r_near, length
        integer :: k, c, i, l

        do l = 1, size(solved)
            i = solved(l)
            weighted(l) = arc_element(elements%x_begin(i), elements%y_begin(i), &
                                      elements%x_end(i), elements%y_end(i), curvature(i))
        end do
        do k = 1, tips%n
            if (local(tips%element(k)) == 0) cycle
            call tip_chain(elements, tips%element(k), tips%side(k), chain, near_side)
            ! The chain as far as it is re-solved.
            c = findloc(local(chain) == 0, .true., dim=1)
            if (c > 0) chain = chain(:c - 1)
            ! Half the chain; all of it where it ends on a symmetry line (its image is the
            ! other half), so that a symmetric model is weighted as its full counterpart.
            reach = 0.5_wp * sum(weighted(local(chain))%length)
            if (end_on_mirror(elements, chain(size(chain)), 3 - near_side(size(chain)))) then
                reach = 2.0_wp * reach
            end if
            r_near = 0.0_wp
            do c = 1, size(chain)
                associate (e => weighted(local(chain(c))))
                    length = e%length
                    if (r_near + 0.5_wp * length > reach * (1.0_wp + 1.0e-9_wp)) exit
                    if (e%factors < 2) then
                        e%factors = e%factors + 1
                        if (near_side(c) == 1) then
                            e%r0(e%factors) = r_near
                            e%dr(e%factors) = 1.0_wp
                        else
                            e%r0(e%factors) = r_near + length
                            e%dr(e%factors) = -1.0_wp
                        end if
                    end if
                end associate
                r_near = r_near + length
            end do
        end do
    end function tip_weighted_elements

    !> The curvature of each element [1 / length unit] where the polyline samples a smooth
    !> curve, in the element's direction (positive turning counter-clockwise); 0 elsewhere.
    !> At a vertex shared by two elements alone, the circle through it and its two
    !> neighbouring vertices has curvature 2 sin(turn) / |next - previous|. A vertex samples
    !> a curve where it turns by at most max_curve_turn and its curvature agrees (within
    !> curvature_agreement) with that of the element's other end, or, at an element with
    !> one such vertex (beside a tip, junction or kink), with that of the neighbour's far
    !> end. An element takes the mean of its ends' curvatures that sample a curve.
    pure function sampled_curvature(elements) result(curvature)
        type(element_set), intent(in) :: elements
        real(wp) :: curvature(elements%n)
        integer :: neighbour(2, elements%n), neighbour_side(2, elements%n)
        real(wp) :: at_end(2, elements%n), other
        logical :: known(2, elements%n)
        integer :: i, side, j

        call end_neighbours(elements, neighbour, neighbour_side)
        do i = 1, elements%n
            do side = 1, 2
                call vertex_curvature(i, side, at_end(side, i), known(side, i))
            end do
        end do
        do i = 1, elements%n
            curvature(i) = 0.0_wp
            if (known(1, i) .and. known(2, i)) then
                if (agree(at_end(1, i), at_end(2, i))) curvature(i) = 0.5_wp * sum(at_end(:, i))
            else if (known(1, i) .or. known(2, i)) then
                side = merge(1, 2, known(1, i))
                j = neighbour(side, i)
                ! The neighbour's far end, in this element's direction.
                if (.not. known(3 - neighbour_side(side, i), j)) cycle
                other = at_end(3 - neighbour_side(side, i), j)
                if (neighbour_side(side, i) == side) other = -other
                if (agree(at_end(side, i), other)) curvature(i) = at_end(side, i)
            end if
        end do

    contains

        !> The curvature at end `side` of element i in its direction, where that end is
        !> shared with one other element and turns by at most max_curve_turn.
        pure subroutine vertex_curvature(i, side, kappa, is_known)
            integer, intent(in) :: i, side
            real(wp), intent(out) :: kappa
            logical, intent(out) :: is_known
            real(wp) :: p(2), v(2), q(2), a(2), b(2), turn

            kappa = 0.0_wp
            is_known = neighbour(side, i) > 0
            if (.not. is_known) return
            ! previous p, vertex v, next q along the element's direction
            if (side == 2) then
                p = [elements%x_begin(i), elements%y_begin(i)]
                v = [elements%x_end(i), elements%y_end(i)]
                q = far_point(neighbour(2, i), neighbour_side(2, i))
            else
                p = far_point(neighbour(1, i), neighbour_side(1, i))
                v = [elements%x_begin(i), elements%y_begin(i)]
                q = [elements%x_end(i), elements%y_end(i)]
            end if
            a = v - p
            b = q - v
            turn = atan2(a(1) * b(2) - a(2) * b(1), dot_product(a, b))
            is_known = abs(turn) <= max_curve_turn
            if (is_known) kappa = 2.0_wp * sin(turn) / norm2(q - p)
        end subroutine vertex_curvature

        !> The end of element j other than `near` (1 begin, 2 end).
        pure function far_point(j, near) result(p)
            integer, intent(in) :: j, near
            real(wp) :: p(2)

            if (near == 1) then
                p = [elements%x_end(j), elements%y_end(j)]
            else
                p = [elements%x_begin(j), elements%y_begin(j)]
            end if
        end function far_point

        pure logical function agree(a, b)
            real(wp), intent(in) :: a, b

            agree = abs(a - b) <= curvature_agreement * max(abs(a), abs(b))
        end function agree
    end function sampled_curvature

    !> The re-solve's matrix: tractions at the nodes per unit nodal DD.
    subroutine assemble(medium, solved, weighted, matrix)
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: solved(:)
        type(weighted_element), intent(in) :: weighted(:)
        real(wp), intent(out) :: matrix(:, :)
        procedure(kernel_function), pointer :: kernel
        type(image_transform), allocatable :: images(:)
        logical :: use_general
        real(wp) :: x, y, c, s, s_self, block(2, per_element)
        integer :: l, node, row, m

        call select_kernel(medium, .true., use_general, kernel, stress_only=.true.)
        images = image_transforms(medium%elements%symmetry)
        ! Each thread owns the rows of its receiving elements.
        !$omp parallel do default(none) schedule(dynamic) private(l, node, row, m, x, y, c, s, &
        !$omp     s_self, block) shared(medium, solved, weighted, matrix, &
        !$omp     kernel, images)
        do l = 1, size(solved)
            do node = 1, 3
                row = per_element * (l - 1) + 2 * (node - 1)
                call node_point(weighted(l), node, x, y, c, s)
                do m = 1, size(solved)
                    s_self = merge(0.5_wp * weighted(l)%length * (1.0_wp + node_xi(node)), &
                                   -1.0_wp, m == l)
                    call element_tractions(kernel, images, medium, weighted(m), s_self, x, y, c, &
                                           s, block)
                    matrix(row + 1:row + 2, per_element * (m - 1) + 1:per_element * m) = block
                end do
            end do
        end do
        !$omp end parallel do
    end subroutine assemble

    !> Add to the zones' traction rows the share of the re-solved elements' midpoint DDs
    !> (their middle nodal values) in the recovered DDs of the elements beside the zones.
    subroutine add_recovered_neighbours(medium, solver)
        type(elastic_medium), intent(in) :: medium
        type(higher_order_solver), intent(inout) :: solver
        procedure(kernel_function), pointer :: kernel
        type(image_transform), allocatable :: images(:)
        logical :: use_general
        real(wp) :: x, y, c, s, blocks(2, 2, 3)
        integer :: k, p, j, l, node, row, col

        call select_kernel(medium, .true., use_general, kernel, stress_only=.true.)
        images = image_transforms(medium%elements%symmetry)
        do k = 1, size(solver%outer%element)
            if (all(solver%local(pack(solver%outer%stencil(:, k), &
                                      solver%outer%stencil(:, k) > 0)) == 0)) cycle
            do l = 1, size(solver%solved)
                do node = 1, 3
                    row = per_element * (l - 1) + 2 * (node - 1)
                    call node_point(solver%weighted(l), node, x, y, c, s)
                    blocks = stencil_blocks(solver%outer, k, recovered_block(solver%outer, &
                        kernel, images, medium, k, x, y, c, s, -1.0_wp, .false.))
                    do p = 1, 3
                        j = solver%outer%stencil(p, k)
                        if (j == 0) cycle
                        if (solver%local(j) == 0) cycle
                        ! The middle node's columns of zone element j.
                        col = per_element * (solver%local(j) - 1) + 2
                        solver%traction(row + 1:row + 2, col + 1:col + 2) = &
                            solver%traction(row + 1:row + 2, col + 1:col + 2) + blocks(:, :, p)
                    end do
                end do
            end do
        end do
    end subroutine add_recovered_neighbours

    !> The re-solve's right-hand side: at each node the solve's traction on its element,
    !> less the remote stress there and the share of the elements not re-solved (the
    !> recovered ones with their recovered DDs: the zones' load rows).
    subroutine load_of(medium, solver, ds, dn, shear_traction, normal_traction, remote, &
                       gradient, rhs)
        type(elastic_medium), intent(in) :: medium
        type(higher_order_solver), intent(in) :: solver
        !> The solve's DDs and total tractions, shape (n)
        real(wp), intent(in) :: ds(:), dn(:), shear_traction(:), normal_traction(:)
        real(wp), intent(in) :: remote(3), gradient(3)
        real(wp), intent(out) :: rhs(:)
        real(wp) :: x, y, c, s, stress(3), outside(2, 3 * size(solver%solved))
        integer :: l, i, node, row

        call rows_times(solver, medium, zone_load, pairs(ds, dn), outside)
        do l = 1, size(solver%solved)
            i = solver%solved(l)
            do node = 1, 3
                row = per_element * (l - 1) + 2 * (node - 1)
                call node_point(solver%weighted(l), node, x, y, c, s)
                stress = remote_stress_at(medium, remote, gradient, y)
                rhs(row + 1) = shear_traction(i) - outside(1, 3 * (l - 1) + node) - &
                               (-(stress(1) - stress(2)) * s * c + stress(3) * (c**2 - s**2))
                rhs(row + 2) = normal_traction(i) - outside(2, 3 * (l - 1) + node) - &
                               (stress(1) * s**2 - 2.0_wp * stress(3) * s * c + stress(2) * c**2)
            end do
        end do
    end subroutine load_of

    !> The DDs (Ds, Dn) of every element as pairs, shape (2, n), and after them the zones'
    !> nodal values where given, shape (2, n + 3 re-solved).
    pure function pairs(ds, dn, nodal) result(x)
        real(wp), intent(in) :: ds(:), dn(:)
        real(wp), intent(in), optional :: nodal(:)
        real(wp), allocatable :: x(:, :)
        integer :: n

        n = size(ds)
        if (present(nodal)) then
            allocate (x(2, n + size(nodal) / 2))
            x(:, n + 1:) = reshape(nodal, [2, size(nodal) / 2])
        else
            allocate (x(2, n))
        end if
        x(1, :n) = ds
        x(2, :n) = dn
    end function pairs

    !> The traction the zones' higher-order DDs (of the last re-solve) and the recovered DDs
    !> add at the midpoints of the recovered elements to that of the constant elements of the
    !> solve (the correction rows, correction_row). Solving the model again under its load
    !> plus this traction gives the elements outside the zones the higher-order response of
    !> the zones and of their own recovered DDs.
    subroutine outer_correction(solver, medium, ds, dn, shear, normal)
        !> The re-solve, after higher_order_k
        type(higher_order_solver), intent(in) :: solver
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The solve's DDs [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> Shear and normal traction to add to the load [stress unit], shape (n)
        real(wp), intent(out) :: shear(:), normal(:)
        real(wp) :: t(2, size(solver%outer%element))

        call rows_times(solver, medium, correction, pairs(ds, dn, solver%nodal), t)
        shear = 0.0_wp
        normal = 0.0_wp
        shear(solver%outer%element) = t(1, :)
        normal(solver%outer%element) = t(2, :)
    end subroutine outer_correction

    !> Row r of the zones' load: the tractions at node r of the zones (in the order of the
    !> unknowns) per unit DD of the elements outside the zones, the recovered ones through
    !> their stencils (less the re-solved elements' share in them, which is in the zones'
    !> matrix: add_recovered_neighbours).
    subroutine zone_load_row(solver, medium, kernel, images, r, sources, builder, only)
        type(higher_order_solver), intent(in) :: solver
        type(elastic_medium), intent(in) :: medium
        procedure(kernel_function) :: kernel
        type(image_transform), intent(in) :: images(:)
        integer, intent(in) :: r
        !> The first and last source elements (a recovered one's blocks fall on its
        !> stencil's columns)
        integer, intent(in) :: sources(2)
        type(row_builder), intent(inout) :: builder
        !> The columns to gather, shape (n) (default all)
        logical, intent(in), optional :: only(:)
        real(wp) :: x, y, c, s, blocks(2, 2, 3)
        integer :: j, k, p
        logical :: takes(3)

        call node_point(solver%weighted((r - 1) / 3 + 1), r - 3 * ((r - 1) / 3), x, y, c, s)
        do j = sources(1), sources(2)
            if (solver%local(j) > 0) cycle
            k = solver%outer%place(j)
            if (k == 0) then
                if (wanted(j)) then
                    call builder%add(j, constant_block(kernel, images, medium, j, [x, y, c, s]))
                end if
                cycle
            end if
            do p = 1, 3
                takes(p) = solver%outer%stencil(p, k) /= 0
                if (takes(p)) takes(p) = solver%local(solver%outer%stencil(p, k)) == 0 .and. &
                                         wanted(solver%outer%stencil(p, k))
            end do
            if (.not. any(takes)) cycle
            blocks = stencil_blocks(solver%outer, k, recovered_block(solver%outer, kernel, &
                                    images, medium, k, x, y, c, s, -1.0_wp, .false.))
            do p = 1, 3
                if (takes(p)) call builder%add(solver%outer%stencil(p, k), blocks(:, :, p))
            end do
        end do

    contains

        pure logical function wanted(column)
            integer, intent(in) :: column

            wanted = .true.
            if (present(only)) wanted = only(column)
        end function wanted
    end subroutine zone_load_row

    !> Rows 2 i - 1 and 2 i of a cluster's far block of the zones' load: node_row(i)'s
    !> tractions at the far columns, shape (2, 2 columns).
    subroutine zone_load_row_pair(this, i, values)
        class(zone_load_entries), intent(inout) :: this
        integer, intent(in) :: i
        real(wp), intent(out) :: values(:, :)
        type(row_builder) :: builder
        type(block_row) :: row
        integer :: k, at

        call builder%start(row_columns(this%medium, this%solver))
        call zone_load_row(this%solver, this%medium, this%kernel, this%images, this%node_row(i), &
                           [1, this%medium%elements%n], builder, this%far)
        call builder%take(row)
        values = 0.0_wp
        do k = 1, size(row%column)
            at = this%place(row%column(k))
            values(:, 2 * at - 1:2 * at) = row%block(:, :, k)
        end do
    end subroutine zone_load_row_pair

    !> Columns 2 i - 1 and 2 i of a cluster's far block of the zones' load: the tractions at
    !> its nodes per unit DD of far element(i), shape (2 rows, 2): as zone_load_row gathers
    !> them, by the sources whose blocks fall on it.
    subroutine zone_load_column_pair(this, i, values)
        class(zone_load_entries), intent(inout) :: this
        integer, intent(in) :: i
        real(wp), intent(out) :: values(:, :)
        real(wp) :: x, y, c, s, block(2, 2), blocks(2, 2, 3)
        integer :: e, row, r, h, k

        e = this%element(i)
        associate (solver => this%solver, outer => this%solver%outer)
            do row = 1, size(this%node_row)
                r = this%node_row(row)
                call node_point(solver%weighted((r - 1) / 3 + 1), r - 3 * ((r - 1) / 3), x, y, &
                                c, s)
                block = 0.0_wp
                if (outer%place(e) == 0) then
                    block = constant_block(this%kernel, this%images, this%medium, e, [x, y, c, s])
                end if
                do h = this%first(e), this%first(e + 1) - 1
                    k = this%holder(h)
                    blocks = stencil_blocks(outer, k, recovered_block(outer, this%kernel, &
                                            this%images, this%medium, k, x, y, c, s, -1.0_wp, &
                                            .false.))
                    block = block + blocks(:, :, findloc(outer%stencil(:, k), e, 1))
                end do
                values(2 * row - 1:2 * row, :) = block
            end do
        end associate
    end subroutine zone_load_column_pair

    !> Rows 2 i - 1 and 2 i of a cluster's far block of the outer correction: receiver(i)'s
    !> tractions from each member's nodal DDs and (less) its constant DD, shape (2, 8 members).
    subroutine correction_row_pair(this, i, values)
        class(correction_entries), intent(inout) :: this
        integer, intent(in) :: i
        real(wp), intent(out) :: values(:, :)
        real(wp) :: arc_point(4), chord(4), block(2, per_element), constant(2, 2)
        integer :: q

        call receiver_points(this%solver, this%medium, this%receiver(i), arc_point, chord)
        do q = 1, size(this%member)
            call zone_element_blocks(this%solver, this%medium, this%kernel, this%images, &
                                     this%receiver(i), this%member(q), arc_point, chord, block, &
                                     constant)
            values(:, 8 * q - 7:8 * q - 2) = block
            values(:, 8 * q - 1:8 * q) = -constant
        end do
    end subroutine correction_row_pair

    !> Columns 2 i - 1 and 2 i of a cluster's far block of the outer correction, shape (2
    !> receivers, 2): from its member's four pairs, computed at every receiver where they are
    !> not yet.
    subroutine correction_column_pair(this, i, values)
        class(correction_entries), intent(inout) :: this
        integer, intent(in) :: i
        real(wp), intent(out) :: values(:, :)
        real(wp) :: arc_point(4), chord(4), block(2, per_element), constant(2, 2)
        integer :: q, r, p

        q = (i - 1) / 4 + 1
        p = i - 4 * (q - 1)
        associate (columns => this%computed(q))
            if (.not. allocated(columns%values)) then
                allocate (columns%values(2 * size(this%receiver), 8))
                do r = 1, size(this%receiver)
                    call receiver_points(this%solver, this%medium, this%receiver(r), arc_point, &
                                         chord)
                    call zone_element_blocks(this%solver, this%medium, this%kernel, this%images, &
                                             this%receiver(r), this%member(q), arc_point, chord, &
                                             block, constant)
                    columns%values(2 * r - 1:2 * r, :6) = block
                    columns%values(2 * r - 1:2 * r, 7:) = -constant
                end do
            end if
            values = columns%values(:, 2 * p - 1:2 * p)
        end associate
    end subroutine correction_column_pair

    !> Row k of the outer correction, at recovered element k: the traction its recovered
    !> neighbours along the fracture and every re-solved element add at the midpoint of its
    !> arc, less their constant DDs' at the midpoint of its chord (where its rows are);
    !> columns the model's elements, then the zones' nodes (a recovered DD passes through
    !> the middle node of a re-solved neighbour). Far from a straight re-solved element, its
    !> two halves with its mean DD and first moment serve.
    subroutine correction_row(solver, medium, kernel, images, k, part, builder, omit)
        type(higher_order_solver), intent(in) :: solver
        type(elastic_medium), intent(in) :: medium
        procedure(kernel_function) :: kernel
        type(image_transform), intent(in) :: images(:)
        integer, intent(in) :: k
        !> whole_row, band_part (the element itself and its neighbours) or zones_part
        integer, intent(in) :: part
        type(row_builder), intent(inout) :: builder
        !> The zone elements to leave out (their share in a low-rank block), shape
        !> (re-solved) (default none)
        logical, intent(in), optional :: omit(:)
        real(wp) :: arc_point(4), chord(4), block(2, per_element), constant(2, 2)
        integer :: i, j, l, node, side, leave, step, reach, next, next_leave, n

        n = medium%elements%n
        i = solver%outer%element(k)
        call receiver_points(solver, medium, k, arc_point, chord)
        reach = merge(straight_reach, curved_reach, solver%outer%arc(k)%curvature == 0.0_wp)
        if (part /= zones_part) call add_band()
        if (part /= band_part) call add_zones()

    contains

        !> The element itself and its recovered neighbours: recovered less constant.
        subroutine add_band()
            call add_recovered(i, 0.5_wp * solver%outer%arc(k)%length, .true.)
            do side = 1, 2
                j = i
                leave = side
                do step = 1, reach
                    call next_recovered(solver%outer, j, leave, i, next, next_leave)
                    if (next == 0) exit
                    j = next
                    leave = next_leave
                    call add_recovered(j, -1.0_wp, .false.)
                end do
            end do
        end subroutine add_band

        !> The zones: higher-order less constant.
        subroutine add_zones()
            do l = 1, size(solver%solved)
                if (present(omit)) then
                    if (omit(l)) cycle
                end if
                call zone_element_blocks(solver, medium, kernel, images, k, l, arc_point, chord, &
                                         block, constant)
                do node = 1, 3
                    call builder%add(n + 3 * (l - 1) + node, block(:, 2 * node - 1:2 * node))
                end do
                call builder%add(solver%solved(l), -constant)
            end do
        end subroutine add_zones

        !> Add recovered element j's traction at the arc's midpoint less its constant DD's at
        !> the chord's; `at` is j's arc length at the receiver where it is i itself (else
        !> negative).
        subroutine add_recovered(j, at, exact)
            integer, intent(in) :: j
            real(wp), intent(in) :: at
            logical, intent(in) :: exact
            real(wp) :: blocks(2, 2, 3), nodal(2, 6), constant(2, 2)
            integer :: p, jp, kj
            logical :: far

            kj = solver%outer%place(j)
            far = .false.
            if (.not. exact .and. at < 0.0_wp) then
                call far_recovered_blocks(solver%outer, kernel, images, medium, kj, arc_point(1), &
                                          arc_point(2), arc_point(3), arc_point(4), nodal, &
                                          constant, far)
            end if
            if (.not. far) then
                nodal = recovered_block(solver%outer, kernel, images, medium, kj, arc_point(1), &
                                        arc_point(2), arc_point(3), arc_point(4), at, exact)
            end if
            ! A straight receiver's chord midpoint is its arc's: a far neighbour's constant
            ! DD acts there as its two halves together.
            if (.not. far .or. solver%outer%arc(k)%curvature /= 0.0_wp) then
                constant = constant_block(kernel, images, medium, j, chord)
            end if
            blocks = stencil_blocks(solver%outer, kj, nodal)
            do p = 1, 3
                jp = solver%outer%stencil(p, kj)
                if (jp == 0) cycle
                ! A re-solved element's midpoint value is its middle node's.
                if (solver%local(jp) > 0) jp = n + 3 * (solver%local(jp) - 1) + 2
                call builder%add(jp, blocks(:, :, p))
            end do
            call builder%add(j, -constant)
        end subroutine add_recovered
    end subroutine correction_row

    !> The receiver of row k of the outer correction: the midpoint of its arc and of its
    !> chord, each with its plane's direction cosines.
    pure subroutine receiver_points(solver, medium, k, arc_point, chord)
        type(higher_order_solver), intent(in) :: solver
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: k
        real(wp), intent(out) :: arc_point(4), chord(4)
        integer :: i

        i = solver%outer%element(k)
        associate (arc => solver%outer%arc(k), el => medium%elements)
            call point_at(arc, 0.5_wp * arc%length, arc_point(1), arc_point(2), arc_point(3), &
                          arc_point(4))
            chord = [el%x_mid(i), el%y_mid(i), el%cos_beta(i), el%sin_beta(i)]
        end associate
    end subroutine receiver_points

    !> Zone element l's share in row k of the outer correction: its higher-order block at
    !> the arc's midpoint per unit nodal DD, shape (2, 6), and its constant DD's at the
    !> chord's, shape (2, 2). Far from a straight zone element, its two halves with its mean
    !> DD and first moment serve.
    pure subroutine zone_element_blocks(solver, medium, kernel, images, k, l, arc_point, &
                                        chord, block, constant)
        type(higher_order_solver), intent(in) :: solver
        type(elastic_medium), intent(in) :: medium
        procedure(kernel_function) :: kernel
        type(image_transform), intent(in) :: images(:)
        integer, intent(in) :: k, l
        real(wp), intent(in) :: arc_point(4), chord(4)
        real(wp), intent(out) :: block(2, per_element), constant(2, 2)
        real(wp) :: halves(2, 2, 2)
        integer :: j

        j = solver%solved(l)
        associate (zone_element => solver%weighted(l))
            if (zone_element%curvature == 0.0_wp .and. midpoint_distance(medium, &
                solver%outer%element(k), j) > near_lengths * zone_element%length) then
                halves = halves_kernels(kernel, images, medium, zone_element, arc_point(1), &
                                        arc_point(2), arc_point(3), arc_point(4))
                block = halves_block(halves, zone_element%length, solver%mean_weight(:, l), &
                                     solver%moment_weight(:, l))
                ! A straight receiver's chord midpoint is its arc's: the constant DD acts
                ! there as its two halves together.
                if (solver%outer%arc(k)%curvature == 0.0_wp) then
                    constant = halves(:, :, 1) + halves(:, :, 2)
                else
                    constant = constant_block(kernel, images, medium, j, chord)
                end if
            else
                call element_tractions(kernel, images, medium, zone_element, -1.0_wp, &
                                       arc_point(1), arc_point(2), arc_point(3), arc_point(4), &
                                       block)
                constant = constant_block(kernel, images, medium, j, chord)
            end if
        end associate
    end subroutine zone_element_blocks

    !> Shear and normal traction at the point receiver(1:2) on the plane of direction
    !> cosines receiver(3:4) per unit constant DD of element j, shape (2, 2) (rows t_s, t_n;
    !> columns Ds, Dn).
    pure function constant_block(kernel, images, medium, j, receiver) result(block)
        procedure(kernel_function) :: kernel
        type(image_transform), intent(in) :: images(:)
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: j
        real(wp), intent(in) :: receiver(4)
        real(wp) :: block(2, 2)
        type(dd_kernel) :: kj
        real(wp) :: ts(2), tn(2)

        kj = kernel_with_images(kernel, receiver(1), receiver(2), medium, j, images, &
                                face_negative)
        call resolved_tractions(kj, receiver(3), receiver(4), ts, tn)
        block(1, :) = ts
        block(2, :) = tn
    end function constant_block

    !> Row r of the zones' load (which = zone_load) or of the outer correction, whole or the
    !> part given: of the zones' load, from the source elements part(1) to part(2) (default
    !> all); of the correction, part(1) (whole_row, band_part or zones_part).
    subroutine gather_row(solver, medium, kernel, images, which, r, builder, part, only, omit)
        type(higher_order_solver), intent(in) :: solver
        type(elastic_medium), intent(in) :: medium
        procedure(kernel_function) :: kernel
        type(image_transform), intent(in) :: images(:)
        integer, intent(in) :: which, r
        type(row_builder), intent(inout) :: builder
        integer, intent(in), optional :: part(2)
        !> Of the zones' load: the columns to gather, shape (n) (default all)
        logical, intent(in), optional :: only(:)
        !> Of the correction: the zone elements to leave out, shape (re-solved) (default none)
        logical, intent(in), optional :: omit(:)

        if (which == zone_load) then
            if (present(part)) then
                call zone_load_row(solver, medium, kernel, images, r, part, builder, only)
            else
                call zone_load_row(solver, medium, kernel, images, r, [1, medium%elements%n], &
                                   builder)
            end if
        else if (present(part)) then
            call correction_row(solver, medium, kernel, images, r, part(1), builder, omit)
        else
            call correction_row(solver, medium, kernel, images, r, whole_row, builder)
        end if
    end subroutine gather_row

    !> The rows of the zones' load (which = zone_load) or of the outer correction times the
    !> pairs x (pairs): from the kept rows, else each row gathered again.
    subroutine rows_times(solver, medium, which, x, y)
        type(higher_order_solver), intent(in) :: solver
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: which
        real(wp), intent(in) :: x(:, :)
        !> shape (2, rows)
        real(wp), intent(out) :: y(:, :)
        procedure(kernel_function), pointer :: kernel
        type(image_transform), allocatable :: images(:)
        type(row_builder) :: builder
        logical :: use_general
        integer :: r

        ! Kept rows: a product too short for threads (whose wait after a parallel region
        ! would slow the BLAS threads of the solves between the products).
        if (solver%rows_kept) then
            if (which == zone_load) then
                call kept_times(solver%zone_rows, solver%zone_far)
            else
                call kept_times(solver%correction_rows, solver%correction_far)
                if (.not. solver%bands_kept) call gathered_times([band_part, 0], y)
            end if
            return
        end if
        y = 0.0_wp
        call gathered_times([whole_row, 0], y)

    contains

        !> y = the kept rows and low-rank blocks times x.
        subroutine kept_times(rows, far)
            type(block_row), intent(in) :: rows(:)
            type(low_rank_block), intent(in) :: far(:)
            integer :: b

            do b = 1, size(y, 2)
                y(:, b) = row_times(rows(b), x)
            end do
            do b = 1, size(far)
                call add_low_rank_times(far(b), x, y)
            end do
        end subroutine kept_times

        !> y += the rows gathered again (their part given, gather_row), one at a time.
        subroutine gathered_times(part, y)
            integer, intent(in) :: part(2)
            real(wp), intent(inout) :: y(:, :)
            real(wp) :: product(2)

            call select_kernel(medium, .true., use_general, kernel, stress_only=.true.)
            images = image_transforms(medium%elements%symmetry)
            !$omp parallel default(none) private(r, builder, product) &
            !$omp     shared(solver, medium, kernel, images, which, x, y, part)
            call builder%start(row_columns(medium, solver))
            !$omp do schedule(dynamic)
            do r = 1, size(y, 2)
                if (which == zone_load) then
                    call gather_row(solver, medium, kernel, images, which, r, builder)
                else
                    call gather_row(solver, medium, kernel, images, which, r, builder, part)
                end if
                call builder%apply(x, product)
                y(:, r) = y(:, r) + product
            end do
            !$omp end do
            !$omp end parallel
        end subroutine gathered_times
    end subroutine rows_times

    !> Gather and keep the rows of the zones' load and of the outer correction (without the
    !> bands where those are not kept), their entries far from a zone in low rank: the
    !> zones' load a cluster's nodes' rows and zone_columns source elements at a time, the
    !> correction a chunk of receivers at a time (whose rows hold a block per zone element),
    !> so that only those pieces are whole at once.
    subroutine keep_rows(medium, solver, field)
        type(elastic_medium), intent(in), target :: medium
        type(higher_order_solver), intent(inout), target :: solver
        !> The zones' clusters and what is far from each (far_field)
        type(zone_far_field), intent(in) :: field
        type(far_task), allocatable :: tasks(:)
        type(block_row), allocatable :: piece(:)
        type(low_rank_block) :: block
        !> A cluster's far blocks of the zones' load (one per zone_columns far elements) or
        !> of the correction (one per on_demand_receivers receivers)
        type :: cluster_blocks
            type(low_rank_block), allocatable :: block(:)
        end type cluster_blocks
        type(cluster_blocks), allocatable :: loads(:), corrections(:)
        logical, allocatable :: far_columns(:), taken(:), approximated(:), corrected(:)
        integer, allocatable :: which(:), first_holder(:), holder(:), cluster_of(:)
        integer :: c, first, n, l, chunk, t
        logical :: found

        n = medium%elements%n
        allocate (solver%zone_rows(3 * size(solver%solved)), &
                  solver%correction_rows(size(solver%outer%element)), solver%zone_far(0), &
                  solver%correction_far(0), piece(3 * size(solver%solved)))
        allocate (far_columns(row_columns(medium, solver)), source=.false.)
        call stencil_holders(first_holder, holder)
        allocate (loads(size(field%clusters)), approximated(size(field%clusters)), &
                  corrections(size(field%clusters)), corrected(size(field%clusters)), &
                  cluster_of(size(solver%solved)))
        approximated = .false.
        corrected = .false.
        !$omp parallel do default(shared) schedule(dynamic) private(c)
        do c = 1, size(field%clusters)
            if (6 * size(field%clusters(c)%member) >= on_demand_rows) then
                call approximate_far_load(c, loads(c)%block, approximated(c))
                call approximate_far_correction(c, corrections(c)%block, corrected(c))
            end if
        end do
        !$omp end parallel do
        solver%far_loads_on_demand = count(approximated)
        solver%far_corrections_on_demand = count(corrected)
        do c = 1, size(field%clusters)
            which = cluster_rows(c)
            if (approximated(c)) then
                ! The far blocks approximated: the rows gathered at the other columns alone.
                solver%zone_far = [solver%zone_far, loads(c)%block]
                far_columns = .false.
                do l = 1, size(loads(c)%block)
                    far_columns(loads(c)%block(l)%column) = .true.
                end do
                call gather(zone_load, solver%zone_rows, which, [1, n], .not. far_columns(:n))
                cycle
            end if
            do l = 1, size(which)
                allocate (solver%zone_rows(which(l))%column(0), &
                          solver%zone_rows(which(l))%block(2, 2, 0))
            end do
            far_columns(:n) = field%far_elements(:, c)
            do first = 1, n, zone_columns
                call gather(zone_load, piece, which, [first, min(n, first + zone_columns - 1)])
                call far_block(piece, which, far_columns, block, found)
                ! A recovered source's stencil may put a column in two pieces: the row then
                ! holds it twice, and its product sums both.
                taken = far_columns .and. found
                do l = 1, size(which)
                    call append_near(solver%zone_rows(which(l)), piece(which(l)), taken)
                    deallocate (piece(which(l))%column, piece(which(l))%block)
                end do
                if (found) solver%zone_far = [solver%zone_far, block]
            end do
        end do
        do c = 1, size(field%clusters)
            cluster_of(field%clusters(c)%member) = c
        end do
        chunk = receivers(size(solver%correction_rows))
        do first = 1, size(solver%correction_rows), chunk
            which = [(l, l = first, min(size(solver%correction_rows), first + chunk - 1))]
            call gather(correction, solver%correction_rows, which, &
                        [merge(whole_row, zones_part, solver%bands_kept), 0], omit_far_of=corrected)
            allocate (tasks(count(.not. corrected)))
            t = 0
            do c = 1, size(field%clusters)
                if (corrected(c)) cycle
                t = t + 1
                call correction_task(field%clusters(c)%member, field%far_receivers(:, c), &
                                     tasks(t))
            end do
            call compress(solver%correction_rows(which(1):which(size(which))), which(1), tasks, &
                          solver%correction_far)
            deallocate (tasks)
        end do
        do c = 1, size(field%clusters)
            if (corrected(c)) solver%correction_far = [solver%correction_far, corrections(c)%block]
        end do

    contains

        !> The rows of the zones' load of cluster c: its nodes'.
        pure function cluster_rows(c) result(rows)
            integer, intent(in) :: c
            integer, allocatable :: rows(:)
            integer :: k

            associate (member => field%clusters(c)%member)
                rows = [(3 * (member(k) - 1) + [1, 2, 3], k = 1, size(member))]
            end associate
        end function cluster_rows

        !> The recovered elements whose stencils hold each element: holder(first(j):first(j +
        !> 1) - 1) those of element j (their places in the recovery).
        subroutine stencil_holders(first, holder)
            integer, allocatable, intent(out) :: first(:), holder(:)
            integer :: filled(n), k, p, j

            allocate (first(n + 1), source=0)
            associate (stencil => solver%outer%stencil)
                do k = 1, size(stencil, 2)
                    do p = 1, 3
                        j = stencil(p, k)
                        if (j > 0) first(j + 1) = first(j + 1) + 1
                    end do
                end do
                first(1) = 1
                do j = 1, n
                    first(j + 1) = first(j + 1) + first(j)
                end do
                allocate (holder(first(n + 1) - 1))
                filled = 0
                do k = 1, size(stencil, 2)
                    do p = 1, 3
                        j = stencil(p, k)
                        if (j == 0) cycle
                        holder(first(j) + filled(j)) = k
                        filled(j) = filled(j) + 1
                    end do
                end do
            end associate
        end subroutine stencil_holders

        !> The far blocks of the zones' load of cluster c (a block per zone_columns of its far
        !> elements) from the entries they ask for (zone_load_entries); found where each
        !> one's low rank is smaller than its entries.
        subroutine approximate_far_load(c, blocks, found)
            integer, intent(in) :: c
            type(low_rank_block), allocatable, intent(out) :: blocks(:)
            logical, intent(out) :: found
            type(zone_load_entries) :: entries
            type(low_rank_block) :: block
            real(wp), allocatable :: u(:, :), v(:, :)
            integer, allocatable :: far(:)
            logical :: use_general
            integer :: k, start, piece

            entries%solver => solver
            entries%medium => medium
            call select_kernel(medium, .true., use_general, entries%kernel, stress_only=.true.)
            entries%images = image_transforms(medium%elements%symmetry)
            entries%node_row = cluster_rows(c)
            entries%first = first_holder
            entries%holder = holder
            far = pack([(k, k = 1, n)], field%far_elements(:, c) .and. solver%local == 0)
            allocate (blocks(0), entries%place(n), entries%far(n))
            found = .false.
            if (size(far) == 0) return
            piece = even_piece(size(far), zone_columns)
            do start = 1, size(far), piece
                entries%element = far(start:min(size(far), start + piece - 1))
                entries%far = .false.
                entries%far(entries%element) = .true.
                entries%place = 0
                entries%place(entries%element) = [(k, k = 1, size(entries%element))]
                call approximate_entries(entries, 2 * size(entries%node_row), &
                                         2 * size(entries%element), far_tolerance, u, v)
                if (.not. allocated(u)) return
                block%row = entries%node_row
                block%column = entries%element
                call move_alloc(u, block%u)
                call move_alloc(v, block%v)
                blocks = [blocks, block]
            end do
            found = .true.
        end subroutine approximate_far_load

        !> The far blocks of the outer correction of cluster c (a block per
        !> on_demand_receivers of its far receivers) from the entries they ask for
        !> (correction_entries); found where each one's low rank is smaller than its entries.
        subroutine approximate_far_correction(c, blocks, found)
            integer, intent(in) :: c
            type(low_rank_block), allocatable, intent(out) :: blocks(:)
            logical, intent(out) :: found
            type(correction_entries) :: entries
            type(low_rank_block) :: block
            real(wp), allocatable :: u(:, :), v(:, :)
            integer, allocatable :: far(:), columns(:)
            logical :: use_general
            integer :: k, l, start, piece

            entries%solver => solver
            entries%medium => medium
            call select_kernel(medium, .true., use_general, entries%kernel, stress_only=.true.)
            entries%images = image_transforms(medium%elements%symmetry)
            entries%member = field%clusters(c)%member
            columns = [(n + 3 * (entries%member(l) - 1) + [1, 2, 3], &
                        solver%solved(entries%member(l)), l = 1, size(entries%member))]
            far = pack([(k, k = 1, size(solver%outer%element))], &
                       field%far_receivers(solver%outer%element, c))
            allocate (blocks(0))
            found = .false.
            if (size(far) == 0) return
            piece = even_piece(size(far), on_demand_receivers)
            do start = 1, size(far), piece
                entries%receiver = far(start:min(size(far), start + piece - 1))
                if (allocated(entries%computed)) deallocate (entries%computed)
                allocate (entries%computed(size(entries%member)))
                call approximate_entries(entries, 2 * size(entries%receiver), &
                                         2 * size(columns), far_tolerance, u, v)
                if (.not. allocated(u)) return
                block%row = entries%receiver
                block%column = columns
                call move_alloc(u, block%u)
                call move_alloc(v, block%v)
                blocks = [blocks, block]
            end do
            found = .true.
        end subroutine approximate_far_correction

        !> The receivers gathered (which) that are far from a cluster at its elements'
        !> columns: their constant DDs' and their nodes'.
        subroutine correction_task(member, far, task)
            !> The cluster's zone elements
            integer, intent(in) :: member(:)
            !> Whether each element is far from the cluster, shape (n)
            logical, intent(in) :: far(:)
            type(far_task), intent(out) :: task
            integer :: k

            task%which = pack(which, far(solver%outer%element(which)))
            allocate (task%far(row_columns(medium, solver)), source=.false.)
            task%far(solver%solved(member)) = .true.
            task%far([(n + 3 * (member(k) - 1) + [1, 2, 3], k = 1, size(member))]) = .true.
        end subroutine correction_task

        !> Gather rows `rows_of` of map `map`, their part given (gather_row), of the zones'
        !> load at the columns `only` (default all), of the correction without the zone
        !> elements of the clusters marked in omit_far_of where the receiver is far from them
        !> (default none).
        subroutine gather(map, rows, rows_of, part, only, omit_far_of)
            integer, intent(in) :: map
            type(block_row), intent(inout) :: rows(:)
            integer, intent(in) :: rows_of(:), part(2)
            logical, intent(in), optional :: only(:), omit_far_of(:)
            procedure(kernel_function), pointer :: kernel
            type(image_transform), allocatable :: images(:)
            type(row_builder) :: builder
            logical :: use_general, omit(size(solver%solved))
            integer :: k

            call select_kernel(medium, .true., use_general, kernel, stress_only=.true.)
            images = image_transforms(medium%elements%symmetry)
            omit = .false.
            !$omp parallel default(none) private(k, builder) firstprivate(omit) &
            !$omp     shared(solver, medium, kernel, images, map, rows, rows_of, part, only, &
            !$omp            omit_far_of, field, cluster_of)
            call builder%start(row_columns(medium, solver))
            !$omp do schedule(dynamic)
            do k = 1, size(rows_of)
                if (present(omit_far_of)) then
                    omit = omit_far_of(cluster_of) .and. &
                           field%far_receivers(solver%outer%element(rows_of(k)), cluster_of)
                end if
                call gather_row(solver, medium, kernel, images, map, rows_of(k), builder, part, &
                                only, omit)
                call builder%take(rows(rows_of(k)))
            end do
            !$omp end do
            !$omp end parallel
        end subroutine gather

        !> The tasks' low-rank blocks (one thread a task), taken out of the rows (those of the
        !> chunk from row `first` on) and kept.
        subroutine compress(rows, first, tasks, kept)
            type(block_row), intent(inout) :: rows(:)
            integer, intent(in) :: first
            type(far_task), intent(in) :: tasks(:)
            type(low_rank_block), allocatable, intent(inout) :: kept(:)
            type(low_rank_block), allocatable :: blocks(:)
            logical :: found(size(tasks))
            integer :: t

            allocate (blocks(size(tasks)))
            !$omp parallel do default(none) schedule(dynamic) private(t) &
            !$omp     shared(rows, first, tasks, blocks, found)
            do t = 1, size(tasks)
                call far_block(rows, tasks(t)%which - first + 1, tasks(t)%far, blocks(t), &
                               found(t))
            end do
            !$omp end parallel do
            blocks = pack(blocks, found)
            call drop_far(rows, blocks, row_columns(medium, solver))
            do t = 1, size(blocks)
                blocks(t)%row = blocks(t)%row + first - 1
            end do
            kept = [kept, blocks]
        end subroutine compress
    end subroutine keep_rows

    !> The length of each of the fewest equal pieces of `total` items with at most `most`
    !> in each (the last may be shorter).
    pure integer function even_piece(total, most)
        integer, intent(in) :: total, most

        even_piece = (total + (total + most - 1) / most - 1) / ((total + most - 1) / most)
    end function even_piece

    !> The clusters of the zone elements `solved` and what is far from each.
    pure function far_field(medium, solved, neighbour, curvature) result(field)
        type(elastic_medium), intent(in) :: medium
        !> The zone elements (model numbering)
        integer, intent(in) :: solved(:)
        !> The neighbour of every element at each end, shape (2, n)
        integer, intent(in) :: neighbour(:, :)
        !> The sampled curvature of every element [1 / length unit], shape (n)
        real(wp), intent(in) :: curvature(:)
        type(zone_far_field) :: field
        integer :: reach(size(curvature)), c

        reach = merge(straight_reach, curved_reach, curvature == 0.0_wp)
        field%clusters = zone_clusters(medium%elements, solved)
        allocate (field%far_elements(size(curvature), size(field%clusters)), &
                  field%far_receivers(size(curvature), size(field%clusters)))
        do c = 1, size(field%clusters)
            field%far_elements(:, c) = far_from(field%clusters(c), medium%elements)
            field%far_receivers(:, c) = field%far_elements(:, c) .and. &
                beyond_band(field%clusters(c), neighbour, reach, solved)
        end do
    end function far_field

    !> The receivers of the outer correction gathered at once, of `recovered`.
    pure integer function receivers(recovered)
        integer, intent(in) :: recovered

        receivers = min(max_receivers, max(min_receivers, recovered / 16))
    end function receivers

    !> The columns of the rows: the model's elements, then the zones' nodes.
    pure integer function row_columns(medium, solver)
        type(elastic_medium), intent(in) :: medium
        type(higher_order_solver), intent(in) :: solver

        row_columns = medium%elements%n + 3 * size(solver%solved)
    end function row_columns

    !> The memory the re-solve of the given zones takes [bytes]: the zones' traction rows
    !> and their factorized system, and the coupling's rows where they are kept.
    pure real(wp) function higher_order_bytes(medium, tips, zone) result(bytes)
        !> The medium, element geometry computed
        type(elastic_medium), intent(in) :: medium
        !> The tips (ddc_post_tips)
        type(tip_set), intent(in) :: tips
        !> Elements of a tip's zone
        integer, intent(in) :: zone
        logical :: in_zone(medium%elements%n)
        integer :: neighbour(2, medium%elements%n), neighbour_side(2, medium%elements%n)
        real(wp), allocatable :: curvature(:)
        real(wp) :: zones, bands
        integer :: nz, k

        in_zone = re_solved(medium, tips, zone)
        nz = count(in_zone)
        bytes = 2.0_wp * real_bytes * real(per_element * nz, wp)**2
        curvature = sampled_curvature(medium%elements)
        call end_neighbours(medium%elements, neighbour, neighbour_side)
        call rows_bytes(medium, in_zone, curvature, far_field(medium, pack([(k, k = 1, &
                        medium%elements%n)], in_zone), neighbour, curvature), zones, bands)
        if (zones <= kept_rows_max_bytes) bytes = bytes + zones
        if (zones + bands <= kept_rows_max_bytes) bytes = bytes + bands
    end function higher_order_bytes

    !> Upper estimates of the bytes of the kept rows and of the rows whole at once while they
    !> are gathered (keep_rows): of the zones' parts and of the correction's bands. A zone
    !> node's row keeps a block per element outside the zones not far from its cluster; a
    !> recovered element's, four per zone element of each cluster it is not far from, and
    !> its band one per neighbour within reach on each side, its own and its stencil's ends;
    !> the far entries' low-rank blocks are counted at rank assumed_rank.
    pure subroutine rows_bytes(medium, in_zone, curvature, field, zones, bands)
        type(elastic_medium), intent(in) :: medium
        !> Whether each element is re-solved, and its sampled curvature, shape (n)
        logical, intent(in) :: in_zone(:)
        real(wp), intent(in) :: curvature(:)
        !> The zones' clusters and what is far from each (far_field)
        type(zone_far_field), intent(in) :: field
        !> The zones' parts and the bands [bytes]
        real(wp), intent(out) :: zones, bands
        real(wp), parameter :: per_block = 4.0_wp * real_bytes + 4.0_wp
        !> (measured 8 to 16 at 16000 elements, 8 to 35 on the benchmark's models)
        integer, parameter :: assumed_rank = 12
        logical :: recovered(size(in_zone))
        real(wp) :: blocks, low_rank, whole, band_blocks
        integer :: n, nz, c, members, k, widest_band, chunk

        n = size(in_zone)
        nz = count(in_zone)
        recovered = serves(medium%elements) .and. .not. in_zone
        chunk = receivers(count(recovered))
        blocks = 0.0_wp
        low_rank = 0.0_wp
        whole = 0.0_wp
        do c = 1, size(field%clusters)
            members = size(field%clusters(c)%member)
            associate (far => field%far_elements(:, c), far_rows => field%far_receivers(:, c))
                blocks = blocks + 3.0_wp * members * count(.not. (far .or. in_zone)) + &
                         4.0_wp * members * count(recovered .and. .not. far_rows)
                low_rank = low_rank + assumed_rank * ( &
                    ceiling(real(count(far), wp) / zone_columns) * (6.0_wp * members + &
                            2.0_wp * zone_columns) + &
                    ceiling(real(count(far_rows .and. recovered), wp) / chunk) * &
                            (2.0_wp * chunk + 8.0_wp * members))
            end associate
            whole = max(whole, 3.0_wp * members * min(zone_columns + 2, n - nz))
        end do
        widest_band = 0
        band_blocks = 0.0_wp
        do k = 1, n
            if (.not. recovered(k)) cycle
            widest_band = max(widest_band, min(n, 2 * reach(k) + 3))
            band_blocks = band_blocks + min(n, 2 * reach(k) + 3)
        end do
        whole = max(whole, min(chunk, count(recovered)) * (widest_band + 4.0_wp * nz))
        zones = per_block * (blocks + whole) + real_bytes * low_rank
        bands = per_block * band_blocks

    contains

        pure integer function reach(k)
            integer, intent(in) :: k

            reach = merge(straight_reach, curved_reach, curvature(k) == 0.0_wp)
        end function reach
    end subroutine rows_bytes

    !> The weights of each re-solved element's nodal values in its mean DD and first moment
    !> (dd_moments of a unit value at each node; the same for both components).
    pure subroutine moment_weights(weighted, mean_weight, moment_weight)
        type(weighted_element), intent(in) :: weighted(:)
        real(wp), allocatable, intent(out) :: mean_weight(:, :), moment_weight(:, :)
        real(wp) :: unit(per_element), moments(2, 2)
        integer :: l, node

        allocate (mean_weight(3, size(weighted)), moment_weight(3, size(weighted)))
        do l = 1, size(weighted)
            do node = 1, 3
                unit = 0.0_wp
                unit(2 * node - 1) = 1.0_wp
                moments = dd_moments(weighted(l), unit)
                mean_weight(node, l) = moments(1, 1)
                moment_weight(node, l) = moments(1, 2)
            end do
        end do
    end subroutine moment_weights

    !> The distance between the midpoints of elements i and j [length unit].
    pure real(wp) function midpoint_distance(medium, i, j)
        type(elastic_medium), intent(in) :: medium
        integer, intent(in) :: i, j

        associate (e => medium%elements)
            midpoint_distance = hypot(e%x_mid(i) - e%x_mid(j), e%y_mid(i) - e%y_mid(j))
        end associate
    end function midpoint_distance

    !> The mean DD (Ds, Dn) of a re-solved element with nodal values q [length unit], and its
    !> first moment about the midpoint along the element [length unit**3]: Gauss-Legendre on
    !> each half in t^2 from its outer end, where a square-root weight is smooth.
    pure function dd_moments(element, q) result(moments)
        type(weighted_element), intent(in) :: element
        real(wp), intent(in) :: q(:)
        !> (:, 1) the mean, (:, 2) the moment
        real(wp) :: moments(2, 2)
        real(wp) :: h, t, at, w, dw, n(3), dn(3), f(2)
        integer :: half, g

        h = 0.5_wp * element%length
        moments = 0.0_wp
        do half = 1, 2
            do g = 1, size(gauss_x)
                t = 0.5_wp * (gauss_x(g) + 1.0_wp)
                ! arc length from the element's begin; d(at)/dt = 2 h t
                at = h * t**2
                if (half == 2) at = element%length - at
                call weight_at(element, at, w, dw)
                call nodal_basis(at / h - 1.0_wp, n, dn)
                f = gauss_w(g) * h * t * w * [sum(n * q(1:per_element:2)), &
                                              sum(n * q(2:per_element:2))]
                moments(:, 1) = moments(:, 1) + f / element%length
                moments(:, 2) = moments(:, 2) + f * (at - h)
            end do
        end do
    end function dd_moments

    !> Node `node` of a re-solved element [length unit] and the tangent there.
    pure subroutine node_point(element, node, x, y, c, s)
        type(weighted_element), intent(in) :: element
        integer, intent(in) :: node
        real(wp), intent(out) :: x, y, c, s

        call point_at(element, 0.5_wp * element%length * (1.0_wp + node_xi(node)), x, y, c, s)
    end subroutine node_point

    !> K of tip k from the re-solve's nodal DDs q (in the frame of the fracture's tangent at
    !> the tip).
    pure subroutine tip_k(material, solver, q, tips, k, k1, k2)
        !> The material of the tip element
        type(elastic_material), intent(in) :: material
        type(higher_order_solver), intent(in) :: solver
        real(wp), intent(in) :: q(:)
        type(tip_set), intent(in) :: tips
        integer, intent(in) :: k
        real(wp), intent(out) :: k1, k2
        real(wp) :: n(3), dn(3), limit(2), s_tip, h, factor
        integer :: l, col, f, c

        l = solver%local(tips%element(k))
        associate (e => solver%weighted(l))
            h = 0.5_wp * e%length
            s_tip = merge(0.0_wp, e%length, tips%side(k) == 1)
            call nodal_basis(merge(-1.0_wp, 1.0_wp, tips%side(k) == 1), n, dn)
            col = per_element * (l - 1)
            do c = 1, 2
                limit(c) = sum(n * q(col + c:col + per_element:2))
            end do
            ! D = limit sqrt(r / h) near the tip: the tip's own factor is sqrt(r / h);
            ! another (a one-element crack's other tip) is at its value there.
            do f = 1, e%factors
                if (abs(e%r0(f) + e%dr(f) * s_tip) > 1.0e-9_wp * e%length) then
                    limit = limit * sqrt((e%r0(f) + e%dr(f) * s_tip) / (e%r0(f) + e%dr(f) * h))
                end if
            end do
        end associate
        ! The opening 4 (1 - nu) / G K sqrt(r / (2 pi)) behind a tip, with D = -opening;
        ! + 0 turns -0 into 0.
        factor = -material%shear_modulus * sqrt(2.0_wp * pi / h) / &
                 (4.0_wp * (1.0_wp - material%poissons_ratio))
        k1 = factor * limit(2) + 0.0_wp
        k2 = factor * limit(1) + 0.0_wp
    end subroutine tip_k

end module ddc_post_higher_order_k
