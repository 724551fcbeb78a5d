!> Tests of the half-plane kernel (SPEC-EARTH section 1).
module test_half_plane_kernel
    use ddc_kinds, only: wp
    use ddc_testing, only: test_case, new_test, check, error_type
    use ddc_influence_kernel, only: dd_kernel, dd_kernel_global, face_positive
    use ddc_influence_kernel_half_plane, only: dd_kernel_half_plane
    implicit none
    private

    public :: collect_half_plane_kernel

    real(wp), parameter :: nu = 0.25_wp

contains

    !> Cases of the half_plane_kernel suite.
    subroutine collect_half_plane_kernel(tests)
        type(test_case), allocatable, intent(out) :: tests(:)

        tests = [new_test('reference_table', test_reference_table), &
                 new_test('traction_free_surface', test_traction_free), &
                 new_test('zero_surface_displacement_on_element_line', test_line_meets_surface), &
                 new_test('deep_element_tends_to_full_plane', test_deep)]
    end subroutine collect_half_plane_kernel

    !> Kernel of an element from (xb, yb) to (xe, ye) at (x, y).
    function kernel(x, y, xb, yb, xe, ye, g, half_plane) result(k)
        real(wp), intent(in) :: x, y, xb, yb, xe, ye, g
        logical, intent(in) :: half_plane
        type(dd_kernel) :: k
        real(wp) :: length

        length = hypot(xe - xb, ye - yb)
        associate (xm => 0.5_wp * (xb + xe), ym => 0.5_wp * (yb + ye), a => 0.5_wp * length, &
                   c => (xe - xb) / length, s => (ye - yb) / length)
            if (half_plane) then
                k = dd_kernel_half_plane(x, y, xm, ym, a, c, s, g, nu, face_positive)
            else
                k = dd_kernel_global(x, y, xm, ym, a, c, s, g, nu, face_positive)
            end if
        end associate
    end function kernel

    !> The table of SPEC-EARTH 1: element (1, -2)-(0, -1), G = 1, nu = 0.25, to 1e-9.
    subroutine test_reference_table(error)
        type(error_type), allocatable, intent(out) :: error
        ! Columns: Ds, Dn, x, y, ux, uy, sxx, syy, sxy
        real(wp), parameter :: table(9, 7) = reshape([ &
            1.0_wp, 0.0_wp, -2.0_wp, 0.0_wp, 6.608001333e-02_wp, -3.837797283e-02_wp, &
            -7.500860196e-02_wp, 0.0_wp, 0.0_wp, &
            1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -5.934156102e-02_wp, 2.394048243e-01_wp, &
            2.881012212e-01_wp, 0.0_wp, 0.0_wp, &
            1.0_wp, 0.0_wp, 0.5_wp, -0.5_wp, -7.954279859e-03_wp, 2.848933485e-01_wp, &
            -1.185319498e-01_wp, -1.064938560e-01_wp, -1.228899671e-01_wp, &
            1.0_wp, 0.0_wp, 1.5_wp, -1.0_wp, -1.205610247e-01_wp, 4.333111612e-02_wp, &
            3.586704176e-02_wp, 1.355224363e-01_wp, 1.504916200e-02_wp, &
            0.0_wp, -1.0_wp, 0.5_wp, 0.0_wp, 4.828140378e-02_wp, 3.342642336e-01_wp, &
            6.758914462e-01_wp, 0.0_wp, 0.0_wp, &
            0.0_wp, -1.0_wp, 0.5_wp, -0.5_wp, 1.648511730e-01_wp, 3.819318266e-01_wp, &
            3.621088342e-01_wp, -2.609608710e-01_wp, 2.107759200e-02_wp, &
            0.0_wp, -1.0_wp, 0.2_wp, -2.5_wp, -1.161530034e-01_wp, -9.277732104e-02_wp, &
            7.172580899e-02_wp, -3.276833064e-01_wp, -1.423193018e-01_wp], [9, 7])
        character(len=3), parameter :: names(5) = ['ux ', 'uy ', 'sxx', 'syy', 'sxy']
        type(dd_kernel) :: k
        real(wp) :: values(5)
        integer :: row, c

        do row = 1, 7
            associate (t => table(:, row))
                k = kernel(t(3), t(4), 1.0_wp, -2.0_wp, 0.0_wp, -1.0_wp, 1.0_wp, .true.)
                values = t(1) * [k%ux(1), k%uy(1), k%sxx(1), k%syy(1), k%sxy(1)] &
                         + t(2) * [k%ux(2), k%uy(2), k%sxx(2), k%syy(2), k%sxy(2)]
                do c = 1, 5
                    call check(error, values(c), t(4 + c), trim(names(c))//' in the table', &
                               rel_tol=1.0e-9_wp, abs_tol=1.0e-9_wp * maxval(abs(t(5:9))))
                end do
            end associate
            if (allocated(error)) return
        end do
    end subroutine test_reference_table

    !> syy and sxy vanish at y = 0 (below 1e-12 of the full-plane values) for random
    !> elements and surface points.
    subroutine test_traction_free(error)
        type(error_type), allocatable, intent(out) :: error
        type(dd_kernel) :: half, full
        real(wp) :: r(6), scale
        integer :: trial, seed_size, d
        integer, allocatable :: seed(:)

        call random_seed(size=seed_size)
        seed = [(1234 + 17 * d, d = 1, seed_size)]
        call random_seed(put=seed)
        do trial = 1, 50
            call random_number(r)
            ! Element below the surface, surface point anywhere in [-3, 3].
            associate (xb => 4 * r(1) - 2, yb => -0.1_wp - 2 * r(2), &
                       xe => 4 * r(3) - 2, ye => -0.1_wp - 2 * r(4), x => 6 * r(5) - 3)
                half = kernel(x, 0.0_wp, xb, yb, xe, ye, 1.0_wp, .true.)
                full = kernel(x, 0.0_wp, xb, yb, xe, ye, 1.0_wp, .false.)
            end associate
            do d = 1, 2
                scale = max(abs(full%syy(d)), abs(full%sxy(d)), abs(full%sxx(d)))
                call check(error, abs(half%syy(d)) + abs(half%sxy(d)), 0.0_wp, &
                           '|syy| + |sxy| on the surface', abs_tol=1.0e-12_wp * scale)
            end do
            if (allocated(error)) return
        end do
    end subroutine test_traction_free

    !> The element (1, -2)-(0, -1) lies on the line y = -1 - x, which meets the surface at
    !> (-1, 0): a uniform DD moves that surface point by exactly nothing.
    subroutine test_line_meets_surface(error)
        type(error_type), allocatable, intent(out) :: error
        type(dd_kernel) :: k

        k = kernel(-1.0_wp, 0.0_wp, 1.0_wp, -2.0_wp, 0.0_wp, -1.0_wp, 1.0_wp, .true.)
        call check(error, maxval(abs([k%ux, k%uy])), 0.0_wp, 'surface displacement', &
                   abs_tol=1.0e-14_wp)
    end subroutine test_line_meets_surface

    !> Depth / length = 1e4: the half-plane field near the element is the full-plane one.
    subroutine test_deep(error)
        type(error_type), allocatable, intent(out) :: error
        type(dd_kernel) :: half, full
        real(wp), parameter :: depth = 2.0e4_wp

        half = kernel(0.3_wp, -depth + 0.4_wp, -0.6_wp, -depth - 0.5_wp, 0.8_wp, -depth + 0.3_wp, &
                      1.0_wp, .true.)
        full = kernel(0.3_wp, -depth + 0.4_wp, -0.6_wp, -depth - 0.5_wp, 0.8_wp, -depth + 0.3_wp, &
                      1.0_wp, .false.)
        call check(error, maxval(abs([half%sxx - full%sxx, half%syy - full%syy, &
                                      half%sxy - full%sxy])), 0.0_wp, 'stress', &
                   abs_tol=1.0e-6_wp * maxval(abs([full%sxx, full%syy, full%sxy])))
        call check(error, maxval(abs([half%ux - full%ux, half%uy - full%uy])), 0.0_wp, &
                   'displacement', abs_tol=1.0e-3_wp * maxval(abs([full%ux, full%uy])))
    end subroutine test_deep

end module test_half_plane_kernel
