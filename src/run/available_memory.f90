!> The memory this process may use: the smaller of the machine's MemAvailable
!> (/proc/meminfo) and the limit of every memory cgroup the process is in, from its own
!> cgroup up to the root of the hierarchy (as /proc/self/cgroup names them): cgroup v2
!> memory.max, cgroup v1 memory/memory.limit_in_bytes. A Slurm job's --mem is such a
!> limit. In a container whose /proc/self/cgroup path is not visible under /sys/fs/cgroup,
!> the limits at the root of the mounted hierarchy are read. Files that are missing or
!> unreadable are skipped; "max" and values of 2^60 bytes and more mean no limit.
module ddc_run_available_memory
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    implicit none
    private

    public :: available_memory, no_limit

    !> What is returned when no limit is found [bytes]
    real(wp), parameter :: no_limit = huge(1.0_wp)
    !> Limits at or above this many bytes are no limit (cgroup v1 writes about 2^63)
    real(wp), parameter :: unlimited_from = 2.0_wp**60

contains

    !> The memory available to this process and where that number comes from.
    subroutine available_memory(bytes, source, meminfo, proc_cgroup, cgroup_root)
        !> Memory available [bytes]; no_limit when nothing says
        real(wp), intent(out) :: bytes
        !> Where the limit comes from, e.g. 'MemAvailable in /proc/meminfo'
        character(len=:), allocatable, intent(out) :: source
        !> The files to read, for tests (defaults /proc/meminfo, /proc/self/cgroup and the
        !> mount point /sys/fs/cgroup)
        character(len=*), intent(in), optional :: meminfo, proc_cgroup, cgroup_root
        character(len=:), allocatable :: meminfo_file, cgroup_file, root
        character(len=512) :: line
        real(wp) :: kilobytes
        integer :: unit, stat, colon, second

        meminfo_file = '/proc/meminfo'
        cgroup_file = '/proc/self/cgroup'
        root = '/sys/fs/cgroup'
        if (present(meminfo)) meminfo_file = meminfo
        if (present(proc_cgroup)) cgroup_file = proc_cgroup
        if (present(cgroup_root)) root = cgroup_root
        bytes = no_limit
        source = 'no limit found'
        open (newunit=unit, file=meminfo_file, status='old', action='read', iostat=stat)
        if (stat == 0) then
            do
                read (unit, '(a)', iostat=stat) line
                if (stat /= 0) exit
                if (index(line, 'MemAvailable:') /= 1) cycle
                read (line(len('MemAvailable:') + 1:), *, iostat=stat) kilobytes
                if (stat == 0) call take(1024.0_wp * kilobytes, 'MemAvailable in '// &
                                         meminfo_file)
                exit
            end do
            close (unit)
        end if
        open (newunit=unit, file=cgroup_file, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            ! id:controllers:path; v2 has no controllers, v1 lists memory among them
            colon = index(line, ':')
            second = colon + index(line(colon + 1:), ':')
            if (colon == 0 .or. second == colon) cycle
            if (line(:colon - 1) == '0' .and. second == colon + 1) then
                call walk(root, trim(line(second + 1:)), 'memory.max')
            else if (has_memory(line(colon + 1:second - 1))) then
                call walk(root//'/memory', trim(line(second + 1:)), 'memory.limit_in_bytes')
            end if
        end do
        close (unit)

    contains

        !> Keep the smaller limit.
        subroutine take(value, where)
            real(wp), intent(in) :: value
            character(len=*), intent(in) :: where

            if (value >= unlimited_from .or. .not. value < bytes) return
            bytes = value
            source = where
        end subroutine take

        !> The limits in `file` of the cgroup at path under base and of its parents; the
        !> base's own when the path is not visible there.
        subroutine walk(base, path, file)
            character(len=*), intent(in) :: base, path, file
            character(len=:), allocatable :: folder
            logical :: found
            integer :: slash

            folder = base//path
            if (path == '/') folder = base
            inquire (file=folder//'/.', exist=found)
            if (.not. found) folder = base
            do
                call read_limit(folder//'/'//file)
                if (len(folder) <= len(base)) exit
                slash = index(folder, '/', back=.true.)
                folder = folder(:slash - 1)
            end do
        end subroutine walk

        !> One limit file: a number of bytes, or "max".
        subroutine read_limit(file)
            character(len=*), intent(in) :: file
            character(len=64) :: text
            integer(int64) :: value
            integer :: limit_unit, status

            open (newunit=limit_unit, file=file, status='old', action='read', iostat=status)
            if (status /= 0) return
            read (limit_unit, '(a)', iostat=status) text
            close (limit_unit)
            if (status /= 0 .or. verify(trim(text), '0123456789') /= 0 .or. &
                len_trim(text) == 0 .or. len_trim(text) > 19) return
            read (text, *, iostat=status) value
            if (status == 0) call take(real(value, wp), 'the memory cgroup limit in '//file)
        end subroutine read_limit

    end subroutine available_memory

    !> True when a comma-separated list of cgroup v1 controllers holds 'memory'.
    pure logical function has_memory(controllers)
        character(len=*), intent(in) :: controllers

        has_memory = index(','//trim(controllers)//',', ',memory,') > 0
    end function has_memory

end module ddc_run_available_memory
