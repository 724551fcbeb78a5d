!> Sums of the full-plane Crouch & Starfield kernel over many elements weighted by their
!> DDs (superposition) at one point: the fused loops of the field evaluation and of the face
!> displacements at element midpoints.
!>
!> Every source (an element, or one of its symmetry images carrying (sign_s Ds, Dn)) is
!> stored once with its geometry and DDs (source_table), and sorted into cells of about
!> an element's length, so that the sources a point is near or on (point_flag) are found
!> among those of its cell and the neighbouring ones; a sum over the sources is one
!> loop without branches that the compiler vectorizes (with the SIMD logarithm and atan2 of
!> glibc's libmvec where gfortran declares them). Off the element's segment the angle it
!> subtends is one atan2, atan2(y, x - a) - atan2(y, x + a) = atan2(2 a y, (x - a)(x + a)
!> + y^2), and F2 one logarithm of r1^2 / r2^2. The values equal the general kernel's
!> (ddc_influence_kernel, summed by kernel_with_images) within round-off: suites `fields`
!> and `kernel` compare the two paths. Full plane only: the half-plane takes the general
!> path. The atan2 is written out (Cephes' rational approximation, branch-free) so that
!> the loop vectorizes; CMake compiles this file with -fno-trapping-math, without which
!> gfortran keeps the selections of that loop as branches.
module ddc_influence_superposition
    use ddc_kinds, only: wp
    use ddc_constants, only: pi
    use ddc_model_types, only: element_set
    use ddc_model_results, only: point_clear, point_near, point_on_element
    use ddc_influence_assembly, only: image_transform, image_of
    use ddc_sorting, only: sorted_order, first_at_least
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: source_table, build_sources, point_flag, flag_at, superpose

    !> A point closer to an element's line than this fraction of its half-length, within
    !> its extent, is on the element (the field is discontinuous or singular there).
    real(wp), parameter, public :: on_element_tolerance = 1.0e-10_wp

    !> Cephes' atan (S. L. Moshier): atan(t) = t + t z P(z) / Q(z), z = t^2, for
    !> |t| <= 0.66 (relative error below 2e-16), after the reductions t -> -1/t (above
    !> tan(3 pi / 8), plus pi / 2) and t -> (t - 1) / (t + 1) (above 0.66, plus pi / 4);
    !> more_bits is the part of pi / 2 below double precision.
    real(wp), parameter :: atan_p(5) = [-8.750608600031904122785e-1_wp, &
        -1.615753718733365076637e1_wp, -7.500855792314704667340e1_wp, &
        -1.228866684490136173410e2_wp, -6.485021904942025371773e1_wp]
    real(wp), parameter :: atan_q(5) = [2.485846490142306297962e1_wp, &
        1.650270098316988542046e2_wp, 4.328810604912902668951e2_wp, &
        4.853903996359136964868e2_wp, 1.945506571482613964425e2_wp]
    real(wp), parameter :: tan_3pi_8 = 2.41421356237309504880_wp, half_pi = 0.5_wp * pi, &
        quarter_pi = 0.25_wp * pi, more_bits = 6.123233995736765886130e-17_wp

    !> The sources of a sum: every element, then its images under each transform.
    type :: source_table
        !> Number of sources: elements times (1 + images)
        integer :: n = 0
        !> Midpoint and half-length [length unit], direction cosines and cos, sin of twice
        !> the angle, shape (n)
        real(wp), allocatable :: xm(:), ym(:), a(:), c(:), s(:), c2(:), s2(:)
        !> Shear and normal DD [length unit] (the image's Ds carries the sign of its
        !> reflection), shape (n)
        real(wp), allocatable :: ds(:), dn(:)
        !> Cells of side h (the largest element length, a little more) over the midpoints,
        !> from (x0, y0), nx by ny of them [length unit]: a point is near or on a source
        !> only if the source's midpoint lies in the point's cell or a neighbouring one
        real(wp) :: x0 = 0.0_wp, y0 = 0.0_wp, h = 1.0_wp
        integer(int64) :: nx = 0, ny = 0
        !> Cell number of each source (ix ny + iy, exact as a real below 2^53) in ascending
        !> order, and the sources in that order, shape (n)
        real(wp), allocatable :: cell(:)
        integer, allocatable :: by_cell(:)
    end type source_table

contains

    !> The sources of elements with DDs ds, dn and their images: source k <= n is element
    !> k, source t n + k its image under images(t).
    pure subroutine build_sources(elements, images, ds, dn, src)
        !> Elements with geometry computed
        type(element_set), intent(in) :: elements
        !> Image transforms (empty without symmetry)
        type(image_transform), intent(in) :: images(:)
        !> DDs of the elements [length unit], shape (n)
        real(wp), intent(in) :: ds(:), dn(:)
        !> The sources
        type(source_table), intent(out) :: src
        integer :: n, t, j, k

        n = elements%n
        src%n = n * (1 + size(images))
        allocate (src%xm(src%n), src%ym(src%n), src%a(src%n), src%c(src%n), src%s(src%n), &
                  src%c2(src%n), src%s2(src%n), src%ds(src%n), src%dn(src%n))
        src%xm(1:n) = elements%x_mid
        src%ym(1:n) = elements%y_mid
        src%c(1:n) = elements%cos_beta
        src%s(1:n) = elements%sin_beta
        src%ds(1:n) = ds
        do t = 1, size(images)
            do j = 1, n
                k = t * n + j
                call image_of(elements, j, images(t), src%xm(k), src%ym(k), src%c(k), src%s(k))
                src%ds(k) = images(t)%sign_s * ds(j)
            end do
        end do
        do t = 0, size(images)
            src%a(t * n + 1:(t + 1) * n) = elements%half_length
            src%dn(t * n + 1:(t + 1) * n) = dn
        end do
        src%c2 = src%c**2 - src%s**2
        src%s2 = 2.0_wp * src%c * src%s
        call index_cells(src)
    end subroutine build_sources

    !> Sort the sources into cells of side h = 2 (1 + 1e-6) max a: every point within 2a
    !> of a source's midpoint (where it can be near or on the source) lies in the source's
    !> cell or one of its eight neighbours.
    pure subroutine index_cells(src)
        type(source_table), intent(inout) :: src
        real(wp), allocatable :: cell(:)

        if (src%n == 0) return
        src%h = 2.0_wp * (1.0_wp + 1.0e-6_wp) * maxval(src%a)
        src%x0 = minval(src%xm)
        src%y0 = minval(src%ym)
        src%nx = int((maxval(src%xm) - src%x0) / src%h, int64) + 1
        src%ny = int((maxval(src%ym) - src%y0) / src%h, int64) + 1
        ! Cell numbers are below 2^53 for any mesh that fits in memory: exact as reals.
        cell = real(int((src%xm - src%x0) / src%h, int64) * src%ny + &
                    int((src%ym - src%y0) / src%h, int64), wp)
        src%by_cell = sorted_order(cell)
        src%cell = cell(src%by_cell)
    end subroutine index_cells

    !> Where a point lies relative to one element (midpoint xm, ym, half-length a, direction
    !> cosb, sinb): clear, near (within one element length of its centre, where TWODD skips
    !> points) or on it (including its ends).
    elemental integer function point_flag(x, y, xm, ym, a, cosb, sinb) result(flag)
        !> Point, element midpoint and half-length [length unit], element direction cosines
        real(wp), intent(in) :: x, y, xm, ym, a, cosb, sinb
        real(wp) :: xl, yl

        xl = (x - xm) * cosb + (y - ym) * sinb
        yl = -(x - xm) * sinb + (y - ym) * cosb
        if (abs(yl) <= on_element_tolerance * a .and. &
            abs(xl) <= a * (1.0_wp + on_element_tolerance)) then
            flag = point_on_element
        else if (xl**2 + yl**2 < (2.0_wp * a)**2) then
            flag = point_near
        else
            flag = point_clear
        end if
    end function point_flag

    !> The worst flag of a point over all sources: point_flag on the sources of its cell
    !> and the eight around it (every other source is clear of it).
    pure integer function flag_at(src, x, y) result(flag)
        !> The sources
        type(source_table), intent(in) :: src
        !> The point [length unit]
        real(wp), intent(in) :: x, y
        real(wp) :: fx, fy, key
        integer(int64) :: ix, iy
        integer :: i, k, j

        flag = point_clear
        fx = (x - src%x0) / src%h
        fy = (y - src%y0) / src%h
        if (.not. (fx > -2.0_wp .and. fx < real(src%nx + 1, wp) .and. fy > -2.0_wp .and. &
                   fy < real(src%ny + 1, wp))) return
        do ix = int(floor(fx), int64) - 1, int(floor(fx), int64) + 1
            if (ix < 0 .or. ix >= src%nx) cycle
            do iy = int(floor(fy), int64) - 1, int(floor(fy), int64) + 1
                if (iy < 0 .or. iy >= src%ny) cycle
                key = real(ix * src%ny + iy, wp)
                do k = first_at_least(src%cell, key), size(src%cell)
                    if (src%cell(k) /= key) exit
                    j = src%by_cell(k)
                    i = point_flag(x, y, src%xm(j), src%ym(j), src%a(j), src%c(j), src%s(j))
                    flag = max(flag, i)
                end do
            end do
        end do
    end function flag_at

    !> Displacement and stress at (x, y) caused by every source but source `skip`, in the
    !> global frame. The point must not be on a source (flag_at), except on the skipped one.
    pure subroutine superpose(src, shear_modulus, nu, x, y, skip, u, stress)
        !> The sources
        type(source_table), intent(in) :: src
        !> Shear modulus [stress unit] and Poisson's ratio [-]
        real(wp), intent(in) :: shear_modulus, nu
        !> The point [length unit]
        real(wp), intent(in) :: x, y
        !> Source left out (0: none)
        integer, intent(in) :: skip
        !> Displacement ux, uy [length unit]
        real(wp), intent(out) :: u(2)
        !> Stress sxx, syy, sxy [stress unit]
        real(wp), intent(out) :: stress(3)

        call sum_sources(src%n, src%xm, src%ym, src%a, src%c, src%s, src%c2, src%s2, src%ds, &
                         src%dn, shear_modulus, nu, x, y, skip, u, stress)
    end subroutine superpose

    !> superpose on the source arrays (explicit shapes: the loop vectorizes). The
    !> factors 1 / (4 pi (1 - nu)) of F2..F7 and 2 G of the stress are taken out of the
    !> sums; the stress is summed as its mean and the two rotated deviatoric parts.
    pure subroutine sum_sources(n, xm, ym, a, c, s, c2, s2, ds, dn, shear_modulus, nu, x, y, &
                                skip, u, stress)
        integer, intent(in) :: n
        real(wp), intent(in) :: xm(n), ym(n), a(n), c(n), s(n), c2(n), s2(n), ds(n), dn(n)
        real(wp), intent(in) :: shear_modulus, nu, x, y
        integer, intent(in) :: skip
        real(wp), intent(out) :: u(2), stress(3)
        real(wp) :: con, k1, k2, dx, dy, xl, yl, xa, xb, r1, r2, inv, i1, i2, f2, f3, f4, f5
        real(wp) :: f6, f7, w, bs, bn, uxl, uyl, mean, dev, sxy, ux, uy, sm, sp, sq
        real(wp) :: num, den, ax, ay, diff, total, t, z, phi, rest
        logical :: steep, mid
        integer :: j

        con = 1.0_wp / (4.0_wp * pi * (1.0_wp - nu))
        k1 = 2.0_wp * (1.0_wp - nu)
        k2 = 1.0_wp - 2.0_wp * nu
        ux = 0.0_wp
        uy = 0.0_wp
        sm = 0.0_wp
        sp = 0.0_wp
        sq = 0.0_wp
        !$omp simd reduction(+:ux, uy, sm, sp, sq) private(dx, dy, xl, yl, xa, xb, r1, r2, &
        !$omp     inv, i1, i2, f2, f3, f4, f5, f6, f7, w, bs, bn, uxl, uyl, mean, dev, sxy, num, &
        !$omp     den, ax, ay, diff, total, t, z, phi, rest, steep, mid)
        do j = 1, n
            dx = x - xm(j)
            dy = y - ym(j)
            xl = dx * c(j) + dy * s(j)
            yl = -dx * s(j) + dy * c(j)
            xa = xl - a(j)
            xb = xl + a(j)
            r1 = xa**2 + yl**2
            r2 = xb**2 + yl**2
            inv = 1.0_wp / (r1 * r2)
            i1 = r2 * inv
            i2 = r1 * inv
            f2 = 0.5_wp * log(r1 * i2)
            ! f3 = -atan2(num, den), the angle subtended, by Cephes' atan (Moshier) on the
            ! first octant; both branches of every merge are computed (the loop has no
            ! branch).
            num = 2.0_wp * a(j) * yl
            den = xa * xb + yl**2
            ax = abs(den)
            ay = abs(num)
            steep = ay > tan_3pi_8 * ax
            mid = ay > 0.66_wp * ax
            diff = ay - ax
            total = ay + ax
            t = merge(-ax, merge(diff, ay, mid), steep) / merge(ay, merge(total, ax, mid), steep)
            z = t**2
            phi = merge(half_pi + more_bits, merge(quarter_pi + 0.5_wp * more_bits, 0.0_wp, mid), &
                        steep) + (t + t * (z * ((((atan_p(1) * z + atan_p(2)) * z + atan_p(3)) &
                        * z + atan_p(4)) * z + atan_p(5)) / (((((z + atan_q(1)) * z + atan_q(2)) &
                        * z + atan_q(3)) * z + atan_q(4)) * z + atan_q(5))))
            rest = pi - phi
            f3 = -sign(merge(rest, phi, den < 0.0_wp), num)
            f4 = yl * i1 - yl * i2
            f5 = xa * i1 - xb * i2
            f6 = (xa**2 - yl**2) * i1**2 - (xb**2 - yl**2) * i2**2
            f7 = 2.0_wp * yl * (xa * i1**2 - xb * i2**2)
            w = merge(0.0_wp, 1.0_wp, j == skip)
            bs = w * ds(j)
            bn = w * dn(j)
            ! Local displacement and stress (C&S eq. 5.2.5), then the global frame.
            uxl = bs * (k1 * f3 - yl * f5) + bn * (-k2 * f2 - yl * f4)
            uyl = bs * (k2 * f2 - yl * f4) + bn * (k1 * f3 + yl * f5)
            mean = bs * f4 - bn * f5
            dev = bs * (f4 + yl * f6) + bn * yl * f7
            sxy = bs * (-f5 + yl * f7) - bn * yl * f6
            ux = ux + (uxl * c(j) - uyl * s(j))
            uy = uy + (uxl * s(j) + uyl * c(j))
            sm = sm + mean
            sp = sp + (dev * c2(j) - sxy * s2(j))
            sq = sq + (dev * s2(j) + sxy * c2(j))
        end do
        u = con * [ux, uy]
        stress = 2.0_wp * shear_modulus * con * [sm + sp, sm - sp, sq]
    end subroutine sum_sources

end module ddc_influence_superposition
