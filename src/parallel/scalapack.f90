!> Explicit interfaces for the BLACS and ScaLAPACK routines ddc2d calls (MPI build), like
!> ddc_linalg_lapack for LAPACK: every module that calls them takes the interface from here,
!> so argument mismatches are compile-time errors. Descriptors are the 9-integer arrays of
!> ScaLAPACK (dtype, context, m, n, mb, nb, rsrc, csrc, lld).
module ddc_parallel_scalapack
    use ddc_kinds, only: wp
    implicit none
    private

    public :: blacs_get, blacs_gridinit, blacs_gridinfo, blacs_gridexit, blacs_exit
    public :: numroc, indxg2p, indxg2l, indxl2g, descinit
    public :: pdgetrf, pdgetrs, pdgecon, pdlange

    interface
        !> A BLACS internal value, e.g. the default system context (BLACS)
        subroutine blacs_get(icontxt, what, val)
            implicit none
            integer, intent(in) :: icontxt, what
            integer, intent(out) :: val
        end subroutine blacs_get
        !> Map the processes of a context onto a process grid (BLACS)
        subroutine blacs_gridinit(icontxt, layout, nprow, npcol)
            implicit none
            integer, intent(inout) :: icontxt
            character, intent(in) :: layout
            integer, intent(in) :: nprow, npcol
        end subroutine blacs_gridinit
        !> Shape of the process grid and this process's row and column (BLACS)
        subroutine blacs_gridinfo(icontxt, nprow, npcol, myrow, mycol)
            implicit none
            integer, intent(in) :: icontxt
            integer, intent(out) :: nprow, npcol, myrow, mycol
        end subroutine blacs_gridinfo
        !> Release a process grid (BLACS)
        subroutine blacs_gridexit(icontxt)
            implicit none
            integer, intent(in) :: icontxt
        end subroutine blacs_gridexit
        !> Free the resources of BLACS when done (BLACS)
        subroutine blacs_exit(notdone)
            implicit none
            integer, intent(in) :: notdone
        end subroutine blacs_exit
        !> Rows or columns of a block-cyclic matrix that one process holds (ScaLAPACK)
        function numroc(n, nb, iproc, isrcproc, nprocs) result(count)
            implicit none
            integer, intent(in) :: n, nb, iproc, isrcproc, nprocs
            integer :: count
        end function numroc
        !> The process that holds a global row or column index (ScaLAPACK)
        function indxg2p(indxglob, nb, iproc, isrcproc, nprocs) result(proc)
            implicit none
            integer, intent(in) :: indxglob, nb, iproc, isrcproc, nprocs
            integer :: proc
        end function indxg2p
        !> The local index of a global row or column index (ScaLAPACK)
        function indxg2l(indxglob, nb, iproc, isrcproc, nprocs) result(indx)
            implicit none
            integer, intent(in) :: indxglob, nb, iproc, isrcproc, nprocs
            integer :: indx
        end function indxg2l
        !> The global index of a local row or column index (ScaLAPACK)
        function indxl2g(indxloc, nb, iproc, isrcproc, nprocs) result(indx)
            implicit none
            integer, intent(in) :: indxloc, nb, iproc, isrcproc, nprocs
            integer :: indx
        end function indxl2g
        !> Fill the array descriptor of a block-cyclic matrix (ScaLAPACK)
        subroutine descinit(desc, m, n, mb, nb, irsrc, icsrc, ictxt, lld, info)
            implicit none
            integer, intent(out) :: desc(9), info
            integer, intent(in) :: m, n, mb, nb, irsrc, icsrc, ictxt, lld
        end subroutine descinit
        !> LU factorization of a distributed matrix (ScaLAPACK)
        subroutine pdgetrf(m, n, a, ia, ja, desca, ipiv, info)
            import :: wp
            implicit none
            integer, intent(in) :: m, n, ia, ja, desca(9)
            real(wp), intent(inout) :: a(*)
            integer, intent(out) :: ipiv(*), info
        end subroutine pdgetrf
        !> Solve with the LU factors of pdgetrf (ScaLAPACK)
        subroutine pdgetrs(trans, n, nrhs, a, ia, ja, desca, ipiv, b, ib, jb, descb, info)
            import :: wp
            implicit none
            character, intent(in) :: trans
            integer, intent(in) :: n, nrhs, ia, ja, desca(9), ib, jb, descb(9)
            real(wp), intent(in) :: a(*)
            integer, intent(in) :: ipiv(*)
            real(wp), intent(inout) :: b(*)
            integer, intent(out) :: info
        end subroutine pdgetrs
        !> Reciprocal condition number of a distributed matrix from its LU factors (ScaLAPACK)
        subroutine pdgecon(norm, n, a, ia, ja, desca, anorm, rcond, work, lwork, iwork, &
                           liwork, info)
            import :: wp
            implicit none
            character, intent(in) :: norm
            integer, intent(in) :: n, ia, ja, desca(9), lwork, liwork
            real(wp), intent(in) :: a(*), anorm
            real(wp), intent(out) :: rcond
            real(wp), intent(inout) :: work(*)
            integer, intent(inout) :: iwork(*)
            integer, intent(out) :: info
        end subroutine pdgecon
        !> Norm of a distributed matrix (ScaLAPACK)
        function pdlange(norm, m, n, a, ia, ja, desca, work) result(val)
            import :: wp
            implicit none
            character, intent(in) :: norm
            integer, intent(in) :: m, n, ia, ja, desca(9)
            real(wp), intent(in) :: a(*)
            real(wp), intent(inout) :: work(*)
            real(wp) :: val
        end function pdlange
    end interface

end module ddc_parallel_scalapack
