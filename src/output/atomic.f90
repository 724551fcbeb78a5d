!> Atomic publication of result files (docs/output-reference.md#how-the-file-is-written): write
!> under a temporary name, rename to the final name at the end, remove the temporary file on
!> failure.
!>
!> Knows nothing of HDF5 or physics. Only regular files are ever replaced: the final target
!> is the path with its symbolic links followed (the link stays, the file it points to is
!> replaced); a folder, device, FIFO or socket there is refused (exit_io_failure). The
!> temporary file lives in the folder of that target, so the rename never crosses a file
!> system and is atomic (POSIX rename(2)).
module ddc_output_atomic
    use, intrinsic :: iso_c_binding, only: c_char, c_int
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input, exit_io_failure
    use ddc_text, only: bytes_text
    use ddc_output_file_system, only: path_kind, link_target, free_bytes, file_size_limit, &
        c_string, kind_missing, kind_regular, kind_folder, kind_link
    implicit none
    private

    public :: partial_name, publish_file, remove_file, check_writable, resolve_target
    public :: check_free_space, explain_write_failure

    !> Most symbolic links followed in a row (Linux's MAXSYMLINKS)
    integer, parameter :: max_links = 40

    !> Suffix of the temporary file written before publication
    character(len=*), parameter :: partial_suffix = '.partial'

    interface
        !> POSIX rename(2): atomically replace new_path by old_path; 0 on success.
        function c_rename(old_path, new_path) result(status) bind(C, name='rename')
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: old_path(*)
            character(kind=c_char), intent(in) :: new_path(*)
            integer(c_int) :: status
        end function c_rename
    end interface

contains

    !> The temporary name under which a result file is written before publication.
    pure function partial_name(final_path) result(name)
        !> Path of the final result file
        character(len=*), intent(in) :: final_path
        !> final_path with '.partial' appended
        character(len=:), allocatable :: name

        name = final_path//partial_suffix
    end function partial_name

    !> Rename the finished temporary file to its final name (atomic, replaces the target).
    !> final_path is a target from resolve_target; should a folder, device, FIFO, socket or
    !> link have appeared there since, nothing is replaced.
    subroutine publish_file(temporary_path, final_path, error)
        !> Path of the finished temporary file
        character(len=*), intent(in) :: temporary_path
        !> Path the file gets; an existing regular file there is replaced
        character(len=*), intent(in) :: final_path
        !> Allocated with exit_io_failure if the rename fails or is refused
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: description
        integer :: kind

        call path_kind(final_path, kind, description)
        if (kind /= kind_missing .and. kind /= kind_regular) then
            call set_error(error, exit_io_failure, 'did not rename '//temporary_path//' to ' &
                //final_path//': that is now a '//description//', not a regular file')
            return
        end if
        if (c_rename(c_string(temporary_path), c_string(final_path)) == 0_c_int) return
        call set_error(error, exit_io_failure, 'could not rename '//temporary_path//' to ' &
            //final_path//': '//rename_diagnosis(temporary_path, final_path))
    end subroutine publish_file

    !> The file a result written to path replaces: path with its symbolic links followed
    !> (relative targets from the link's folder). Refused (exit_io_failure) when that is a
    !> folder, a device, a FIFO or a socket: ddc2d only ever replaces regular files.
    subroutine resolve_target(path, final_path, error)
        !> The output path as given
        character(len=*), intent(in) :: path
        !> The regular file (existing or not) to write
        character(len=:), allocatable, intent(out) :: final_path
        !> Allocated with exit_io_failure for a target that is not a regular file
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: description, target, shown
        integer :: kind, hop

        final_path = path
        do hop = 1, max_links
            call path_kind(final_path, kind, description)
            if (kind /= kind_link) exit
            target = link_target(final_path)
            if (len(target) == 0) exit
            if (target(1:1) == '/' .or. index(final_path, '/') == 0) then
                final_path = target
            else
                final_path = folder_of(final_path)//'/'//target
            end if
        end do
        if (kind == kind_missing .or. kind == kind_regular) return
        shown = 'output path '//path
        if (final_path /= path) shown = shown//' (a link to '//final_path//')'
        if (kind == kind_link) then
            call set_error(error, exit_io_failure, shown//' is a chain of more than '// &
                'forty symbolic links or an unreadable link')
        else if (kind == kind_folder) then
            call set_error(error, exit_io_failure, shown//' is a folder, not a file name')
        else
            call set_error(error, exit_io_failure, shown//' is a '//description// &
                ', not a regular file: ddc2d writes its results only to regular files '// &
                'and never replaces anything else')
        end if
    end subroutine resolve_target

    !> Refuse, before the solve, a result of a known size that cannot fit on the file
    !> system of its target (free space for unprivileged users, statvfs).
    subroutine check_free_space(path, bytes, error)
        !> Path of the final result file
        character(len=*), intent(in) :: path
        !> Least size of the result [bytes]
        real(wp), intent(in) :: bytes
        !> Allocated with exit_io_failure when the result cannot fit
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: final_path
        integer(int64) :: free
        logical :: known

        call resolve_target(path, final_path, error)
        if (allocated(error)) return
        call free_bytes(folder_of(final_path), free, known)
        if (.not. known .or. bytes <= real(free, wp)) return
        call set_error(error, exit_io_failure, 'output '//path//' needs at least '// &
            bytes_text(bytes)//' but its file system ('//folder_of(final_path)//') has only '// &
            bytes_text(real(free, wp))//' free: free space, or write it elsewhere '// &
            '(-o), or ask for fewer field points')
    end subroutine check_free_space

    !> Add to the error of a failed write its likely cause: the file-size limit
    !> (ulimit -f) or a full file system. Call it before removing the temporary file.
    subroutine explain_write_failure(final_path, temporary_path, error)
        !> Path of the final result file
        character(len=*), intent(in) :: final_path
        !> Path of the temporary file that was being written
        character(len=*), intent(in) :: temporary_path
        !> The write's error; its message gets the final path and the cause
        type(error_type), intent(inout) :: error
        integer(int64) :: size, limit, free
        logical :: limited, known
        integer :: status
        ! Below this a file system counts as full: HDF5 writes in blocks of this order.
        integer(int64), parameter :: nearly_full = 1048576_int64

        size = -1_int64
        inquire (file=temporary_path, size=size, iostat=status)
        if (status /= 0) size = -1_int64
        call file_size_limit(limit, limited)
        call free_bytes(folder_of(final_path), free, known)
        error%message = 'writing '//final_path//' failed: '//error%message
        if (limited .and. size >= limit - nearly_full) then
            error%message = error%message//'; cause: the file-size limit (ulimit -f) of '// &
                bytes_text(real(limit, wp))
        else if (known .and. free < nearly_full) then
            error%message = error%message//'; cause: its file system is full ('// &
                bytes_text(real(free, wp))//' free)'
        end if
    end subroutine explain_write_failure

    !> Delete a file if it exists; silent when it does not or cannot be deleted.
    subroutine remove_file(path)
        !> Path of the file to delete
        character(len=*), intent(in) :: path
        logical :: exists
        integer :: unit, status

        inquire (file=path, exist=exists, iostat=status)
        if (status /= 0 .or. .not. exists) return
        open (newunit=unit, file=path, status='old', action='read', iostat=status)
        if (status /= 0) return
        close (unit, status='delete', iostat=status)
        ! Best effort: the caller reports the failure that made it remove the file.
        if (status /= 0) return
    end subroutine remove_file

    !> Prove before any solve that the result file can be written: follow its links, refuse
    !> what is not a regular file, create and delete its temporary file. An empty name is
    !> bad usage (exit_bad_input); a folder, device, FIFO or socket as target or a path that
    !> cannot be written (missing folder, no permission, a read-only file system) is an I/O
    !> failure (exit_io_failure). Folders are not created.
    subroutine check_writable(path, error)
        !> Path of the final result file
        character(len=*), intent(in) :: path
        !> Allocated with exit_bad_input for an empty name, exit_io_failure when the path is
        !> not a writable regular file
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: temporary, final_path
        character(len=256) :: message
        integer :: unit, status

        if (len_trim(path) == 0) then
            call set_error(error, exit_bad_input, 'the output file name is empty')
            return
        end if
        call resolve_target(path, final_path, error)
        if (allocated(error)) return
        temporary = partial_name(final_path)
        open (newunit=unit, file=temporary, status='replace', action='write', &
            iostat=status, iomsg=message)
        if (status /= 0) then
            call set_error(error, exit_io_failure, 'output path '//path &
                //' is not writable (could not create '//temporary//': '//trim(message) &
                //'); '//missing_folder_hint(final_path))
            return
        end if
        close (unit, status='delete', iostat=status, iomsg=message)
        if (status /= 0) then
            call set_error(error, exit_io_failure, 'output path '//path &
                //' is not usable (could not delete the test file '//temporary//': ' &
                //trim(message)//')')
        end if
    end subroutine check_writable

    !> Why a path cannot be created: its folder is missing (create it first), or else
    !> permissions or the file system.
    function missing_folder_hint(path) result(hint)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: hint

        if (folder_exists(folder_of(path))) then
            hint = 'check the permissions of its folder '//folder_of(path)
        else
            hint = 'its folder '//folder_of(path)//' does not exist (ddc2d does not '// &
                'create folders: mkdir -p '//folder_of(path)//')'
        end if
    end function missing_folder_hint

    !> The likely reason a rename failed, found without errno.
    function rename_diagnosis(temporary_path, final_path) result(reason)
        character(len=*), intent(in) :: temporary_path, final_path
        character(len=:), allocatable :: reason
        logical :: exists
        integer :: status

        inquire (file=temporary_path, exist=exists, iostat=status)
        if (status == 0 .and. .not. exists) then
            reason = 'the temporary file does not exist'
        else if (.not. folder_exists(folder_of(final_path))) then
            reason = 'the folder '//folder_of(final_path)//' does not exist'
        else if (is_folder(final_path)) then
            reason = 'the target is a folder'
        else
            reason = 'permission denied or the file system refused it'
        end if
    end function rename_diagnosis

    !> The folder part of a path ('.' when there is none).
    pure function folder_of(path) result(folder)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: folder
        integer :: slash

        slash = index(path, '/', back=.true.)
        if (slash == 0) then
            folder = '.'
        else if (slash == 1) then
            folder = '/'
        else
            folder = path(:slash - 1)
        end if
    end function folder_of

    !> True when the folder exists (a file named folder/. exists).
    function folder_exists(folder) result(exists)
        character(len=*), intent(in) :: folder
        logical :: exists
        integer :: status

        inquire (file=folder//'/.', exist=exists, iostat=status)
        if (status /= 0) exists = .false.
    end function folder_exists

    !> True when the path names an existing folder.
    function is_folder(path) result(folder)
        character(len=*), intent(in) :: path
        logical :: folder

        folder = folder_exists(path)
    end function is_folder

end module ddc_output_atomic
