!> Tests of the Crouch & Starfield kernel and the influence assembly.
module test_kernel
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_influence_kernel, only: kernel_functions, face_positive, face_negative, dd_kernel, &
        dd_kernel_at
    use ddc_constants, only: pi
    use ddc_influence_assembly, only: assemble_influence, row_traction, row_displacement, &
        row_identity
    use ddc_influence_response, only: midpoint_response
    use ddc_model_types, only: model_type, condition_traction, symmetry_none, symmetry_both
    use ddc_test_builders, only: straight_crack, kinked_network
    implicit none
    private

    public :: collect_kernel

    real(wp), parameter :: nu = 0.25_wp, half = 0.3_wp

contains

    !> Cases of the kernel suite.
    subroutine collect_kernel(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('self_influence', test_self_influence), &
                 new_test('derivatives_of_f1', test_derivatives_of_f1), &
                 new_test('face_jump', test_face_jump), &
                 new_test('hooke_law', test_hooke_law), &
                 new_test('collinear_symmetry', test_collinear_symmetry), &
                 new_test('fast_assembly_equals_general', test_fast_assembly), &
                 new_test('fast_responses_equal_general', test_fast_responses)]
    end subroutine collect_kernel

    !> The potential F1 = f(x, y) of Crouch & Starfield eq. 5.2.x, atan2 branch as F3.
    pure real(wp) function f1(x, y)
        real(wp), intent(in) :: x, y
        real(wp) :: con

        con = 1.0_wp / (4.0_wp * pi * (1.0_wp - nu))
        f1 = -con * (y * (atan2(y, x - half) - atan2(y, x + half)) &
                     - (x - half) * 0.5_wp * log((x - half)**2 + y**2) &
                     + (x + half) * 0.5_wp * log((x + half)**2 + y**2))
    end function f1

    !> F(index) at (x, y) off the element.
    real(wp) function fk(index, x, y)
        integer, intent(in) :: index
        real(wp), intent(in) :: x, y
        real(wp) :: f(2:7)

        call kernel_functions(x, y, half, nu, face_positive, f)
        fk = f(index)
    end function fk

    !> A_ss(i,i) = A_nn(i,i) = G / (pi (1 - nu) a) and A_sn(i,i) = A_ns(i,i) = 0.
    subroutine test_self_influence(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        real(wp) :: a(2, 2), g, expected
        integer :: rows(1)

        model = straight_crack(1, 0.7_wp, 0.4_wp, condition_traction, 0.0_wp, 0.0_wp, &
                               3.0_wp, nu)
        g = 3.0_wp / (2.0_wp * (1.0_wp + nu))
        rows = row_traction
        call assemble_influence(model%elements, g, nu, rows, rows, a)
        expected = g / (pi * (1.0_wp - nu) * 0.7_wp)
        call check(error, a(1, 1), expected, 'A_ss(1,1)', rel_tol=1.0e-14_wp)
        call check(error, a(2, 2), expected, 'A_nn(1,1)', rel_tol=1.0e-14_wp)
        call check(error, a(1, 2), 0.0_wp, 'A_sn(1,1)', abs_tol=1.0e-14_wp * expected)
        call check(error, a(2, 1), 0.0_wp, 'A_ns(1,1)', abs_tol=1.0e-14_wp * expected)
    end subroutine test_self_influence

    !> F2 = f,x  F3 = f,y  F4 = f,xy  F5 = f,xx = -f,yy  F6 = f,xyy  F7 = f,yyy,
    !> each against a central difference of the function below it, at points off the element.
    subroutine test_derivatives_of_f1(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: points(2, 5) = reshape([0.1_wp, 0.2_wp, -0.5_wp, 0.05_wp, &
            0.9_wp, -0.4_wp, 0.31_wp, 0.7_wp, -1.3_wp, -1.1_wp], [2, 5])
        real(wp), parameter :: h = 1.0e-5_wp, tol = 1.0e-6_wp
        real(wp) :: x, y, scale
        integer :: k

        do k = 1, size(points, 2)
            x = points(1, k)
            y = points(2, k)
            ! Central differences are accurate to O(h^2) relative to the function's scale.
            scale = 1.0_wp / (x**2 + y**2)
            call check(error, fk(2, x, y), (f1(x + h, y) - f1(x - h, y)) / (2 * h), &
                       'F2 = dF1/dx', abs_tol=tol)
            call check(error, fk(3, x, y), (f1(x, y + h) - f1(x, y - h)) / (2 * h), &
                       'F3 = dF1/dy', abs_tol=tol)
            call check(error, fk(4, x, y), (fk(3, x + h, y) - fk(3, x - h, y)) / (2 * h), &
                       'F4 = dF3/dx', abs_tol=tol * scale)
            call check(error, fk(5, x, y), (fk(2, x + h, y) - fk(2, x - h, y)) / (2 * h), &
                       'F5 = dF2/dx', abs_tol=tol * scale)
            call check(error, fk(5, x, y), -(fk(3, x, y + h) - fk(3, x, y - h)) / (2 * h), &
                       'F5 = -dF3/dy', abs_tol=tol * scale)
            call check(error, fk(6, x, y), (fk(4, x, y + h) - fk(4, x, y - h)) / (2 * h), &
                       'F6 = dF4/dy', abs_tol=tol * scale**2)
            call check(error, fk(7, x, y), -(fk(5, x, y + h) - fk(5, x, y - h)) / (2 * h), &
                       'F7 = -dF5/dy', abs_tol=tol * scale**2)
            if (allocated(error)) return
        end do
    end subroutine test_derivatives_of_f1

    !> On the element F3 jumps by -1/(2(1-nu)): u_s(-) - u_s(+) = Ds for unit Ds.
    subroutine test_face_jump(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: fm(2:7), fp(2:7), fa(2:7), fb(2:7)

        call kernel_functions(0.1_wp, 0.0_wp, half, nu, face_negative, fm)
        call kernel_functions(0.1_wp, 0.0_wp, half, nu, face_positive, fp)
        call check(error, 2.0_wp * (1.0_wp - nu) * (fm(3) - fp(3)), 1.0_wp, &
                   'jump of 2(1-nu)F3 across the element', rel_tol=1.0e-14_wp)
        ! The one-sided values are the limits from below and above.
        call kernel_functions(0.1_wp, -1.0e-9_wp, half, nu, face_positive, fa)
        call kernel_functions(0.1_wp, 1.0e-9_wp, half, nu, face_positive, fb)
        call check(error, fm(3), fa(3), 'F3 negative face = limit from below', rel_tol=1.0e-8_wp)
        call check(error, fp(3), fb(3), 'F3 positive face = limit from above', rel_tol=1.0e-8_wp)
    end subroutine test_face_jump

    !> The kernel's stresses follow from its displacements by plane-strain Hooke's law
    !> (central differences), for unit Ds and unit Dn.
    subroutine test_hooke_law(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: g = 1.3_wp, h = 1.0e-6_wp
        real(wp), parameter :: points(2, 3) = reshape([0.1_wp, 0.7_wp, -0.5_wp, -0.2_wp, &
                                                       0.9_wp, 0.35_wp], [2, 3])
        type(dd_kernel) :: k, kxp, kxm, kyp, kym
        real(wp) :: exx, eyy, exy, lambda, x, y
        integer :: p, d

        lambda = 2.0_wp * g * nu / (1.0_wp - 2.0_wp * nu)
        do p = 1, size(points, 2)
            x = points(1, p)
            y = points(2, p)
            k = dd_kernel_at(x, y, half, g, nu, face_positive)
            kxp = dd_kernel_at(x + h, y, half, g, nu, face_positive)
            kxm = dd_kernel_at(x - h, y, half, g, nu, face_positive)
            kyp = dd_kernel_at(x, y + h, half, g, nu, face_positive)
            kym = dd_kernel_at(x, y - h, half, g, nu, face_positive)
            do d = 1, 2
                exx = (kxp%ux(d) - kxm%ux(d)) / (2 * h)
                eyy = (kyp%uy(d) - kym%uy(d)) / (2 * h)
                exy = 0.5_wp * ((kyp%ux(d) - kym%ux(d)) + (kxp%uy(d) - kxm%uy(d))) / (2 * h)
                call check(error, k%sxx(d), lambda * (exx + eyy) + 2 * g * exx, 'sxx from u', &
                           abs_tol=1.0e-7_wp)
                call check(error, k%syy(d), lambda * (exx + eyy) + 2 * g * eyy, 'syy from u', &
                           abs_tol=1.0e-7_wp)
                call check(error, k%sxy(d), 2 * g * exy, 'sxy from u', abs_tol=1.0e-7_wp)
            end do
        end do
    end subroutine test_hooke_law

    !> Equal collinear elements influence each other symmetrically (traction and
    !> displacement rows).
    subroutine test_collinear_symmetry(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        real(wp) :: a(12, 12)
        integer :: rows(6), i, j, kind

        model = straight_crack(6, 1.0_wp, 0.3_wp, condition_traction, 0.0_wp, 0.0_wp, &
                               1.0_wp, nu)
        do kind = row_traction, row_displacement
            rows = kind
            call assemble_influence(model%elements, 0.4_wp, nu, rows, rows, a)
            do j = 1, 6
                do i = 1, 6
                    if (i == j) cycle
                    call check(error, a(i, j), a(j, i), 'A_ss symmetry', abs_tol=1.0e-13_wp)
                    call check(error, a(6 + i, 6 + j), a(6 + j, 6 + i), 'A_nn symmetry', &
                               abs_tol=1.0e-13_wp)
                end do
            end do
        end do
    end subroutine test_collinear_symmetry

    !> Row kinds of the kinked network (18 elements): mostly traction rows, some
    !> displacement and identity rows.
    subroutine network_rows(shear_row, normal_row)
        integer, intent(out) :: shear_row(18), normal_row(18)

        shear_row = row_traction
        normal_row = row_traction
        shear_row([3, 14]) = row_displacement
        normal_row([4, 14, 16]) = row_displacement
        shear_row(9) = row_identity
        normal_row(9) = row_identity
    end subroutine network_rows

    !> Largest |a - b| over the rows of one kind, relative to the largest |b| there.
    pure real(wp) function rows_difference(a, b, kinds, kind) result(d)
        real(wp), intent(in) :: a(:, :), b(:, :)
        integer, intent(in) :: kinds(:), kind
        integer, allocatable :: rows(:)
        integer :: i

        rows = pack([(i, i = 1, size(kinds))], kinds == kind)
        d = maxval(abs(a(rows, :) - b(rows, :))) / max(maxval(abs(b(rows, :))), tiny(1.0_wp))
    end function rows_difference

    !> The full-plane assembly (traction rows from the stress part alone, vectorized) gives
    !> the general kernel's matrix within 1e-12 of each row kind's largest entry, with
    !> every symmetry; identity rows exactly.
    subroutine test_fast_assembly(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        real(wp) :: fast(36, 36), general(36, 36), d
        integer :: shear_row(18), normal_row(18), kind, sym
        character(len=40) :: label

        call network_rows(shear_row, normal_row)
        do sym = symmetry_none, symmetry_both
            model = kinked_network(sym)
            call assemble_influence(model%elements, 400.0_wp, nu, shear_row, normal_row, fast)
            call assemble_influence(model%elements, 400.0_wp, nu, shear_row, normal_row, &
                                    general, general=.true.)
            do kind = row_traction, row_identity
                d = rows_difference(fast, general, [shear_row, normal_row], kind)
                write (label, '(a,i0,a,i0)') 'symmetry ', sym, ', row kind ', kind
                if (kind == row_traction) write (*, '(a,es10.3)') '    '//trim(label)//': ', d
                call check(error, d, 0.0_wp, trim(label), abs_tol=merge(0.0_wp, 1.0e-12_wp, &
                           kind == row_identity))
                ! Two computations (the fast path is taken): round-off differs somewhere.
                if (kind == row_traction) call check(error, d > 0.0_wp, trim(label)// &
                    ': the full-plane path is its own')
            end do
            if (allocated(error)) return
        end do
    end subroutine test_fast_assembly

    !> Tractions and face displacements at the midpoints from the assembled matrix and the
    !> fused full-plane sum equal the general kernel's sums over every pair within 1e-12
    !> (of the largest value), with every symmetry and mixed row kinds.
    subroutine test_fast_responses(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        real(wp) :: matrix(36, 36), ds(18), dn(18), fast(18, 4), general(18, 4), d
        integer :: shear_row(18), normal_row(18), sym, q, i
        character(len=40) :: label

        call network_rows(shear_row, normal_row)
        ds = [(1.0e-3_wp * sin(real(i, wp)), i = 1, 18)]
        dn = [(-5.0e-4_wp * cos(2.0_wp * i), i = 1, 18)]
        do sym = symmetry_none, symmetry_both
            model = kinked_network(sym)
            call assemble_influence(model%elements, 400.0_wp, nu, shear_row, normal_row, matrix)
            call midpoint_response(model%elements, 400.0_wp, nu, matrix, shear_row, &
                normal_row, ds, dn, fast(:, 1), fast(:, 2), fast(:, 3), fast(:, 4))
            call midpoint_response(model%elements, 400.0_wp, nu, matrix, shear_row, &
                normal_row, ds, dn, general(:, 1), general(:, 2), general(:, 3), &
                general(:, 4), general=.true.)
            do q = 1, 3, 2
                d = maxval(abs(fast(:, q:q + 1) - general(:, q:q + 1))) / &
                    maxval(abs(general(:, q:q + 1)))
                write (label, '(a,i0,a)') 'symmetry ', sym, merge(': tractions    ', &
                                                                   ': displacements', q == 1)
                write (*, '(a,es10.3)') '    '//trim(label)//' ', d
                call check(error, d, 0.0_wp, trim(label), abs_tol=1.0e-12_wp)
                call check(error, d > 0.0_wp, trim(label)//': the matrix and the fused sum')
            end do
            if (allocated(error)) return
        end do
    end subroutine test_fast_responses

end module test_kernel
