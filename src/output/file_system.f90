!> What the operating system says about a path: its kind (regular file, folder, link,
!> device, FIFO, socket), where a link points, the free space of a file system and the
!> file-size limit of the process (ulimit -f). Thin ISO_C_BINDING wrappers of POSIX/Linux
!> calls whose structures have one layout on every 64-bit Linux:
!>   statx(2)     stx_mode is the 16-bit field at byte 28 of struct statx (fixed by the kernel ABI);
!>   statvfs(3)   f_frsize and f_bavail are the 2nd and 5th unsigned longs (LP64 glibc);
!>   getrlimit(2) struct rlimit is {rlim_cur, rlim_max}, two 64-bit values;
!>   signal(2)    SIGXFSZ (25 on x86-64 and AArch64) ignored, so that a write beyond the
!>                file-size limit fails with EFBIG (an I/O error we report) instead of
!>                killing the process.
!> Knows nothing of HDF5 or of results.
module ddc_output_file_system
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_int16_t, c_int64_t, c_long, &
        c_size_t, c_null_char, c_funptr, c_intptr_t, c_null_funptr
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: path_kind, link_target, free_bytes, file_size_limit, ignore_file_size_signal
    public :: c_string
    public :: kind_missing, kind_regular, kind_folder, kind_link, kind_other

    !> Kinds of path returned by path_kind
    integer, parameter :: kind_missing = 0, kind_regular = 1, kind_folder = 2, &
        kind_link = 3, kind_other = 4

    ! statx(2): the current folder, do not follow a final link, ask for the file type
    integer(c_int), parameter :: at_fdcwd = -100_c_int, at_symlink_nofollow = 256_c_int, &
        statx_type = 1_c_int
    ! st_mode file-type bits (S_IFMT and its values)
    integer, parameter :: s_ifmt = 61440, s_ifsock = 49152, s_iflnk = 40960, &
        s_ifreg = 32768, s_ifblk = 24576, s_ifdir = 16384, s_ifchr = 8192, s_ififo = 4096
    integer(c_int), parameter :: rlimit_fsize = 1_c_int, sigxfsz = 25_c_int
    ! PATH_MAX of Linux: the longest link target readlink(2) can return
    integer, parameter :: path_max = 4096

    interface
        function c_statx(dirfd, path, flags, mask, buffer) result(status) bind(C, name='statx')
            import :: c_char, c_int, c_int16_t
            implicit none
            integer(c_int), value, intent(in) :: dirfd, flags, mask
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int16_t), intent(out) :: buffer(128)
            integer(c_int) :: status
        end function c_statx

        function c_readlink(path, buffer, size) result(length) bind(C, name='readlink')
            import :: c_char, c_long, c_size_t
            implicit none
            character(kind=c_char), intent(in) :: path(*)
            character(kind=c_char), intent(out) :: buffer(*)
            integer(c_size_t), value, intent(in) :: size
            integer(c_long) :: length
        end function c_readlink

        function c_statvfs(path, buffer) result(status) bind(C, name='statvfs')
            import :: c_char, c_int, c_long
            implicit none
            character(kind=c_char), intent(in) :: path(*)
            integer(c_long), intent(out) :: buffer(32)
            integer(c_int) :: status
        end function c_statvfs

        function c_getrlimit(resource, limits) result(status) bind(C, name='getrlimit')
            import :: c_int, c_int64_t
            implicit none
            integer(c_int), value, intent(in) :: resource
            integer(c_int64_t), intent(out) :: limits(2)
            integer(c_int) :: status
        end function c_getrlimit

        function c_signal(signal, handler) result(previous) bind(C, name='signal')
            import :: c_int, c_funptr
            implicit none
            integer(c_int), value, intent(in) :: signal
            type(c_funptr), value, intent(in) :: handler
            type(c_funptr) :: previous
        end function c_signal
    end interface

contains

    !> The kind of what path names, without following a final link: kind_missing (nothing
    !> there, or it cannot be examined), kind_regular, kind_folder, kind_link or kind_other;
    !> description says it in words ('character device', 'FIFO', ...).
    subroutine path_kind(path, kind, description)
        !> The path to examine
        character(len=*), intent(in) :: path
        !> One of the kind_* constants
        integer, intent(out) :: kind
        !> The kind in words, for messages
        character(len=:), allocatable, intent(out) :: description
        integer(c_int16_t) :: buffer(128)
        integer :: mode

        buffer = 0_c_int16_t
        kind = kind_missing
        description = 'missing'
        if (c_statx(at_fdcwd, c_string(path), at_symlink_nofollow, statx_type, buffer) &
            /= 0_c_int) return
        ! stx_mode: bytes 28-29, the 15th 16-bit word; unsigned.
        mode = iand(int(buffer(15)), 65535)
        select case (iand(mode, s_ifmt))
        case (s_ifreg)
            kind = kind_regular
            description = 'regular file'
        case (s_ifdir)
            kind = kind_folder
            description = 'folder'
        case (s_iflnk)
            kind = kind_link
            description = 'symbolic link'
        case (s_ifchr)
            kind = kind_other
            description = 'character device'
        case (s_ifblk)
            kind = kind_other
            description = 'block device'
        case (s_ififo)
            kind = kind_other
            description = 'FIFO (named pipe)'
        case (s_ifsock)
            kind = kind_other
            description = 'socket'
        case default
            kind = kind_other
            description = 'special file'
        end select
    end subroutine path_kind

    !> Where the symbolic link at path points (as stored in the link); empty when path is no
    !> readable link.
    function link_target(path) result(target)
        !> Path of the link
        character(len=*), intent(in) :: path
        !> The stored target, relative to the link's folder unless it starts with '/'
        character(len=:), allocatable :: target
        character(kind=c_char) :: buffer(path_max)
        integer(c_long) :: length
        integer :: i

        length = c_readlink(c_string(path), buffer, int(path_max, c_size_t))
        allocate (character(len=max(int(length), 0)) :: target)
        do i = 1, len(target)
            target(i:i) = buffer(i)
        end do
    end function link_target

    !> Bytes an unprivileged process may still write on the file system holding folder.
    subroutine free_bytes(folder, bytes, known)
        !> An existing folder on that file system
        character(len=*), intent(in) :: folder
        !> f_bavail * f_frsize [bytes]; 0 when unknown
        integer(int64), intent(out) :: bytes
        !> False when statvfs failed
        logical, intent(out) :: known
        integer(c_long) :: buffer(32)

        buffer = 0_c_long
        bytes = 0_int64
        known = c_statvfs(c_string(folder), buffer) == 0_c_int
        if (known) bytes = int(buffer(5), int64) * int(buffer(2), int64)
    end subroutine free_bytes

    !> The process's file-size limit (ulimit -f, RLIMIT_FSIZE).
    subroutine file_size_limit(bytes, limited)
        !> The soft limit [bytes]; huge when there is none
        integer(int64), intent(out) :: bytes
        !> False when there is no limit (RLIM_INFINITY) or it cannot be read
        logical, intent(out) :: limited
        integer(c_int64_t) :: limits(2)

        limits = -1_c_int64_t
        bytes = huge(bytes)
        limited = .false.
        if (c_getrlimit(rlimit_fsize, limits) /= 0_c_int) return
        ! RLIM_INFINITY is all bits set: -1 as a signed 64-bit integer.
        limited = limits(1) >= 0_c_int64_t
        if (limited) bytes = int(limits(1), int64)
    end subroutine file_size_limit

    !> Let a write beyond the file-size limit fail with an error instead of SIGXFSZ killing
    !> the process, so that the partial file is removed and the cause reported.
    subroutine ignore_file_size_signal()
        type(c_funptr) :: previous

        ! SIG_IGN is the handler address 1.
        previous = c_signal(sigxfsz, transfer(1_c_intptr_t, c_null_funptr))
    end subroutine ignore_file_size_signal

    !> A NUL-terminated copy of a Fortran string for C.
    pure function c_string(text) result(c_text)
        !> The Fortran string
        character(len=*), intent(in) :: text
        !> text followed by NUL
        character(kind=c_char) :: c_text(len(text) + 1)
        integer :: i

        do i = 1, len(text)
            c_text(i) = text(i:i)
        end do
        c_text(len(text) + 1) = c_null_char
    end function c_string

end module ddc_output_file_system
