!> Atomic publication of result files (SPEC section 6): write under a temporary name,
!> rename to the final name at the end, remove the temporary file on failure.
!>
!> Knows nothing of HDF5 or physics. The temporary file lives in the same folder as the
!> final file, so the rename never crosses a file system and is atomic (POSIX rename(2)).
module ddc_output_atomic
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
    use ddc_error, only: error_type, set_error, exit_bad_input, exit_io_failure
    implicit none
    private

    public :: partial_name, publish_file, remove_file, check_writable

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
    subroutine publish_file(temporary_path, final_path, error)
        !> Path of the finished temporary file
        character(len=*), intent(in) :: temporary_path
        !> Path the file gets; an existing file there is replaced
        character(len=*), intent(in) :: final_path
        !> Allocated with exit_io_failure if the rename fails
        type(error_type), allocatable, intent(out) :: error

        if (c_rename(c_string(temporary_path), c_string(final_path)) == 0_c_int) return
        call set_error(error, exit_io_failure, 'could not rename '//temporary_path//' to ' &
            //final_path//': '//rename_diagnosis(temporary_path, final_path))
    end subroutine publish_file

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

    !> Prove before any solve that the result file can be written: create and delete its
    !> temporary file. An empty name or a path that is an existing folder is bad usage
    !> (exit_bad_input); a path that cannot be written (missing folder, no permission, a
    !> read-only file system) is an I/O failure (exit_io_failure). Folders are not created.
    subroutine check_writable(path, error)
        !> Path of the final result file
        character(len=*), intent(in) :: path
        !> Allocated with exit_bad_input for an empty name or a folder, exit_io_failure when
        !> the path is not writable
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: temporary
        character(len=256) :: message
        integer :: unit, status

        if (len_trim(path) == 0) then
            call set_error(error, exit_bad_input, 'the output file name is empty')
            return
        end if
        if (is_folder(path)) then
            call set_error(error, exit_bad_input, 'output path '//path &
                //' is a folder, not a file name')
            return
        end if
        temporary = partial_name(path)
        open (newunit=unit, file=temporary, status='replace', action='write', &
            iostat=status, iomsg=message)
        if (status /= 0) then
            call set_error(error, exit_io_failure, 'output path '//path &
                //' is not writable (could not create '//temporary//': '//trim(message) &
                //'); '//missing_folder_hint(path))
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

    !> A NUL-terminated copy of a Fortran string for C.
    pure function c_string(text) result(c_text)
        character(len=*), intent(in) :: text
        character(kind=c_char) :: c_text(len(text) + 1)
        integer :: i

        do i = 1, len(text)
            c_text(i) = text(i:i)
        end do
        c_text(len(text) + 1) = c_null_char
    end function c_string

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
