!> Read a whole text file into one string (lines separated by newline characters), and the
!> paths written inside input files.
module ddc_input_text_file
    use ddc_kinds, only: wp
    use ddc_error, only: error_type, set_error, exit_bad_input
    use ddc_allocation, only: allocation_failed
    implicit none
    private

    public :: read_text_file, open_namelist, base_name, folder_of, resolve

contains

    !> Read the whole file at path into text. A missing, unreadable, empty or binary file
    !> (one that contains a NUL byte) is an error with code exit_bad_input naming the path.
    subroutine read_text_file(path, text, error)
        !> Path of the file, as given by the user
        character(len=*), intent(in) :: path
        !> Content of the file, newlines included
        character(len=:), allocatable, intent(out) :: text
        !> Allocated when the file cannot be used
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, stat, file_size
        logical :: exists
        character(len=512) :: message

        if (len_trim(path) == 0) then
            call set_error(error, exit_bad_input, 'empty file name')
            return
        end if
        inquire (file=path, exist=exists)
        if (.not. exists) then
            call set_error(error, exit_bad_input, path//': file not found')
            return
        end if
        open (newunit=unit, file=path, access='stream', form='unformatted', &
              action='read', status='old', iostat=stat, iomsg=message)
        if (stat /= 0) then
            call set_error(error, exit_bad_input, path//': cannot open: '//trim(message))
            return
        end if
        inquire (unit=unit, size=file_size)
        if (file_size < 0) then
            close (unit)
            call set_error(error, exit_bad_input, path//': cannot tell the file size')
            return
        end if
        allocate (character(len=file_size) :: text, stat=stat)
        if (stat /= 0) then
            close (unit)
            call allocation_failed(error, 'the text of '//path, real(file_size, wp))
            return
        end if
        if (file_size > 0) then
            read (unit, iostat=stat, iomsg=message) text
            if (stat /= 0) then
                close (unit)
                call set_error(error, exit_bad_input, path//': cannot read: '//trim(message))
                return
            end if
        end if
        close (unit)
        if (verify(text, ' '//achar(9)//achar(10)//achar(13)) == 0) then
            call set_error(error, exit_bad_input, path//': the file is empty')
        else if (index(text, achar(0)) > 0) then
            call set_error(error, exit_bad_input, path//': not a text file (contains NUL bytes)')
        end if
    end subroutine read_text_file

    !> Open a namelist file for the reads of its groups: the file itself, or, when its last
    !> line has no final newline (as some editors and scripts write it), a scratch copy that
    !> has one: gfortran reports the end of the file in a group that ends there, though it
    !> read the group.
    subroutine open_namelist(path, text, unit, error)
        !> Path of the file, as given by the user
        character(len=*), intent(in) :: path
        !> Its content (read_text_file: not empty)
        character(len=*), intent(in) :: text
        !> The unit to read the groups from
        integer, intent(out) :: unit
        !> Allocated (exit_bad_input) when it cannot be opened
        type(error_type), allocatable, intent(out) :: error
        integer :: stat
        character(len=512) :: message

        if (text(len(text):) == achar(10)) then
            open (newunit=unit, file=path, status='old', action='read', form='formatted', &
                  iostat=stat, iomsg=message)
        else
            open (newunit=unit, status='scratch', action='readwrite', form='formatted', &
                  iostat=stat, iomsg=message)
            ! A record of its own: the text's lines, then the newline the file lacks.
            if (stat == 0) write (unit, '(a)', iostat=stat, iomsg=message) text
            if (stat == 0) rewind (unit, iostat=stat, iomsg=message)
        end if
        if (stat /= 0) call set_error(error, exit_bad_input, path//': cannot open: '// &
                                      trim(message))
    end subroutine open_namelist

    !> The file name of a path, with or without its extension.
    pure function base_name(path, keep_extension) result(name)
        !> A file path
        character(len=*), intent(in) :: path
        !> Keep the part after the last dot
        logical, intent(in) :: keep_extension
        character(len=:), allocatable :: name
        integer :: dot

        name = path(index(path, '/', back=.true.) + 1:)
        if (.not. keep_extension) then
            dot = index(name, '.', back=.true.)
            if (dot > 1) name = name(1:dot - 1)
        end if
    end function base_name

    !> Folder of a path including its trailing '/', or '' when there is none.
    pure function folder_of(path) result(dir)
        !> A file path
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: dir
        integer :: slash

        slash = index(path, '/', back=.true.)
        dir = path(1:slash)
    end function folder_of

    !> A path written in the input file, relative to the input file's folder.
    pure function resolve(dir, file) result(path)
        !> Folder of the input file (folder_of), and the path written in it
        character(len=*), intent(in) :: dir, file
        character(len=:), allocatable :: path

        if (len(file) > 0) then
            if (file(1:1) == '/') then
                path = file
                return
            end if
        end if
        path = dir//file
    end function resolve

end module ddc_input_text_file
