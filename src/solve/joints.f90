!> Elastic joints (Goodman): the faces of a closed contact element deform before they slip
!> or open, traction = -stiffness x (elastic DD) (shear: s_s = -k_s Ds_e; normal:
!> S_n' = -k_n Dn_e, so a compressed joint overlaps by -S_n'/k_n), and the contact law acts
!> on the rest, the plastic DD D_p = D - D_e.
!>
!> With C = A^-1 and the compliance K^-1 = diag(1/k_s; 1/k_n) (0 for rigid contact), the
!> DDs D = C (t - S_r) split into D_p = (C + K^-1) t' - C S_r' in the effective tractions
!> t' = t + [0; p] (S_r' likewise). So the joint problem is the rigid contact problem for
!> D_p with the influence matrix A_j = (C + K^-1)^-1 (a diagonal compliance added to C,
!> the stick and closed block of the paper's LCP) and the resolved load
!> S_r,j' = A_j C S_r' = T S_r': both methods (Lemke, Newton) solve it as they are, and
!> D = D_p - K^-1 t' afterwards. It costs two inverses of a 2n x 2n matrix, once per
!> model (and loading history), and a second copy of the matrix. The compliance comes
!> from the fault law (ddc_contact_fault_law's joint_compliance).
module ddc_solve_joints
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_linalg_lu, only: lu_invert
    implicit none
    private

    public :: joint_system, joint_load, joint_dds, elastic_dds

contains

    !> The influence matrix A_j of the plastic DDs and the load map T = A_j A^-1.
    subroutine joint_system(a, compliance, a_joint, load_map, error)
        !> Influence matrix of the contact elements ordered [s; n], shape (2n, 2n)
        !> [stress / length]
        real(wp), intent(in) :: a(:, :)
        !> Compliance [1/k_s; 1/k_n] of every element (0: rigid), shape (2n)
        !> [length / stress]
        real(wp), intent(in) :: compliance(:)
        !> A_j, shape (2n, 2n) [stress / length], and T, shape (2n, 2n) [-]
        real(wp), allocatable, intent(out) :: a_joint(:, :), load_map(:, :)
        !> Allocated when A or C + K^-1 is singular
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: c(:, :)
        integer :: i

        call lu_invert(a, c, 'contact: influence matrix', error)
        if (allocated(error)) return
        do i = 1, size(compliance)
            c(i, i) = c(i, i) + compliance(i)
        end do
        call lu_invert(c, a_joint, 'contact: joint compliance matrix', error)
        if (allocated(error)) return
        ! T = A_j C = A_j (C + K^-1 - K^-1) = I - A_j K^-1
        load_map = -a_joint
        do i = 1, size(compliance)
            load_map(:, i) = load_map(:, i) * compliance(i)
            load_map(i, i) = load_map(i, i) + 1.0_wp
        end do
    end subroutine joint_system

    !> The resolved load of the joint problem: [s_s; s_n + p] <- T [s_s; s_n + p].
    pure subroutine joint_load(load_map, p, s_s, s_n)
        !> T of joint_system, shape (2n, 2n)
        real(wp), intent(in) :: load_map(:, :)
        !> Fluid pressure, shape (n) [stress]
        real(wp), intent(in) :: p(:)
        !> Resolved shear and normal traction (normal without p), shape (n) [stress]
        real(wp), intent(inout) :: s_s(:), s_n(:)
        real(wp) :: shifted(2 * size(p))
        integer :: n

        n = size(p)
        shifted = matmul(load_map, [s_s, s_n + p])
        s_s = shifted(1:n)
        s_n = shifted(n + 1:) - p
    end subroutine joint_load

    !> Total DDs from the plastic ones and the tractions: D = D_p - K^-1 t'.
    pure subroutine joint_dds(compliance, p, shear, normal, ds, dn)
        !> Compliance [1/k_s; 1/k_n], shape (2n) [length / stress]
        real(wp), intent(in) :: compliance(:)
        !> Fluid pressure, total shear and normal traction, shape (n) [stress]
        real(wp), intent(in) :: p(:), shear(:), normal(:)
        !> Plastic DDs in, total DDs out, shape (n) [length]
        real(wp), intent(inout) :: ds(:), dn(:)
        real(wp) :: ds_elastic(size(p)), dn_elastic(size(p))

        call elastic_dds(compliance, p, shear, normal, ds_elastic, dn_elastic)
        ds = ds + ds_elastic
        dn = dn + dn_elastic
    end subroutine joint_dds

    !> The elastic DDs of the joints from their tractions: D_e = -K^-1 t' (0 for rigid
    !> contact); the plastic DDs are the total ones less these.
    pure subroutine elastic_dds(compliance, p, shear, normal, ds_elastic, dn_elastic)
        !> Compliance [1/k_s; 1/k_n], shape (2n) [length / stress]
        real(wp), intent(in) :: compliance(:)
        !> Fluid pressure, total shear and normal traction, shape (n) [stress]
        real(wp), intent(in) :: p(:), shear(:), normal(:)
        !> Elastic shear and normal DDs, shape (n) [length]
        real(wp), intent(out) :: ds_elastic(:), dn_elastic(:)
        integer :: n

        n = size(p)
        ds_elastic = -compliance(1:n) * shear
        dn_elastic = -compliance(n + 1:) * (normal + p)
    end subroutine elastic_dds

end module ddc_solve_joints
