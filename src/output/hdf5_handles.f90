!> The handle layer of ddc2d's HDF5 files, shared by the writer (ddc_output_hdf5) and the
!> reader (ddc_output_hdf5_read): the library session, files, groups, datasets, attributes
!> and string types, each created or opened with its status turned into an error that names
!> the object and the file, and each closed on every path (chained status: a routine does
!> nothing when the error is already set, but closing always runs). The plain HDF5 Fortran
!> API is used (no HL library).
module ddc_output_hdf5_handles
    use, intrinsic :: iso_c_binding, only: c_char, c_null_char
    use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5close_f, h5eset_auto_f, &
        h5dont_atexit_f, h5fcreate_f, h5fopen_f, h5fclose_f, H5F_ACC_TRUNC_F, &
        H5F_ACC_RDONLY_F, h5gcreate_f, h5gclose_f, h5screate_f, h5screate_simple_f, &
        h5sclose_f, H5S_SCALAR_F, h5dcreate_f, &
        h5dclose_f, h5acreate_f, h5aclose_f, h5tcopy_f, h5tset_size_f, h5tset_strpad_f, &
        h5tset_cset_f, h5tget_size_f, h5tget_class_f, h5tis_variable_str_f, H5T_FORTRAN_S1, &
        H5T_STR_NULLPAD_F, H5T_CSET_UTF8_F, H5T_STRING_F
    use ddc_error, only: error_type, set_error, exit_io_failure
    implicit none
    private

    public :: h5_object, open_session, close_session, create_file, open_file, close_file
    public :: create_group, close_group, create_dataset, close_dataset
    public :: create_attribute, close_attribute, create_string_type, string_width
    public :: fail, child_path, c_chars

    !> An open HDF5 object (file, group or dataset) with its path, for messages.
    type :: h5_object
        !> HDF5 identifier
        integer(hid_t) :: id = -1
        !> Path of the object inside the file ('/' for the root)
        character(len=:), allocatable :: path
        !> Name of the file, for messages
        character(len=:), allocatable :: file
    end type h5_object

    !> "HDF5 could not <action> <object path> in <file>", or "... <action> in <file>"
    interface fail
        module procedure fail_on_object, fail_in_file
    end interface fail

contains

    !> Start the HDF5 library; its errors become messages here, not stack dumps.
    subroutine open_session(error)
        !> Allocated with exit_io_failure when the library cannot be initialised
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        ! HDF5 1.10's exit handler crashes on a file whose close failed (a full disk, a
        ! file-size limit); every file is closed here before the program ends.
        call h5dont_atexit_f(status)
        call h5open_f(status)
        if (status /= 0) then
            call set_error(error, exit_io_failure, 'HDF5 library could not be initialised')
            return
        end if
        call h5eset_auto_f(0, status)
    end subroutine open_session

    !> Stop the HDF5 library (after every handle is closed).
    subroutine close_session()
        integer :: status

        call h5close_f(status)
    end subroutine close_session

    !> Create (truncate) the file at path; its root group is the returned object.
    subroutine create_file(path, file, error)
        !> Path of the file
        character(len=*), intent(in) :: path
        !> The file's root, path '/'
        type(h5_object), intent(out) :: file
        !> Allocated with exit_io_failure when the file cannot be created
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        file%path = '/'
        file%file = path
        if (allocated(error)) return
        call h5fcreate_f(path, H5F_ACC_TRUNC_F, file%id, status)
        if (status /= 0) then
            file%id = -1
            call set_error(error, exit_io_failure, 'HDF5 could not create file '//path)
        end if
    end subroutine create_file

    !> Open the file at path read-only; its root group is the returned object.
    subroutine open_file(path, file, error)
        !> Path of the file
        character(len=*), intent(in) :: path
        !> The file's root, path '/'
        type(h5_object), intent(out) :: file
        !> Allocated with exit_io_failure when the file cannot be opened
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        file%path = '/'
        file%file = path
        if (allocated(error)) return
        call h5fopen_f(path, H5F_ACC_RDONLY_F, file%id, status)
        if (status /= 0) then
            file%id = -1
            call fail(error, 'open file', path)
        end if
    end subroutine open_file

    !> Close a file (always attempted; reports only when no error is set yet).
    subroutine close_file(file, error)
        !> The file from create_file or open_file
        type(h5_object), intent(inout) :: file
        !> Set when closing fails (a full disk shows here)
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        if (file%id < 0) return
        call h5fclose_f(file%id, status)
        if (status /= 0 .and. .not. allocated(error)) then
            call set_error(error, exit_io_failure, 'HDF5 could not close file '//file%file// &
                           ' (disk full?)')
        end if
        file%id = -1
    end subroutine close_file

    !> Create a group below parent.
    subroutine create_group(parent, name, group, error)
        type(h5_object), intent(in) :: parent
        character(len=*), intent(in) :: name
        type(h5_object), intent(out) :: group
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        group%path = child_path(parent, name)
        group%file = parent%file
        if (allocated(error)) return
        call h5gcreate_f(parent%id, name, group%id, status)
        if (status /= 0) then
            group%id = -1
            call fail(error, 'create group', group)
        end if
    end subroutine create_group

    !> Close a group (always attempted; reports only when no error is set yet).
    subroutine close_group(group, error)
        type(h5_object), intent(inout) :: group
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        if (group%id < 0) return
        call h5gclose_f(group%id, status)
        if (status /= 0) call fail(error, 'close group', group)
        group%id = -1
    end subroutine close_group

    !> Create a dataset of Fortran dims `dims` (scalar when empty) below parent.
    subroutine create_dataset(parent, name, data_type, dims, dataset, error)
        type(h5_object), intent(in) :: parent
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in) :: data_type
        integer, intent(in) :: dims(:)
        type(h5_object), intent(out) :: dataset
        type(error_type), allocatable, intent(inout) :: error
        integer :: space_status, status

        dataset%path = child_path(parent, name)
        dataset%file = parent%file
        if (allocated(error)) return
        call create_with_space(parent%id, name, data_type, dims, .false., dataset%id, &
                               space_status, status)
        if (space_status /= 0) then
            call fail(error, 'create the dataspace of dataset', dataset)
        else if (status /= 0) then
            call fail(error, 'create dataset', dataset)
        end if
    end subroutine create_dataset

    !> Close a dataset (always attempted; reports only when no error is set yet).
    subroutine close_dataset(dataset, error)
        type(h5_object), intent(inout) :: dataset
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        if (dataset%id < 0) return
        call h5dclose_f(dataset%id, status)
        if (status /= 0) call fail(error, 'close dataset', dataset)
        dataset%id = -1
    end subroutine close_dataset

    !> Create an attribute of dims `dims` (scalar when empty) on an object.
    subroutine create_attribute(object, name, data_type, dims, attribute, error)
        type(h5_object), intent(in) :: object
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in) :: data_type
        integer, intent(in) :: dims(:)
        integer(hid_t), intent(out) :: attribute
        type(error_type), allocatable, intent(inout) :: error
        integer :: space_status, status

        attribute = -1
        if (allocated(error)) return
        call create_with_space(object%id, name, data_type, dims, .true., attribute, &
                               space_status, status)
        if (space_status /= 0) then
            call fail(error, 'create the dataspace of attribute '//name//' of', object)
        else if (status /= 0) then
            call fail(error, 'create attribute '//name//' of', object)
        end if
    end subroutine create_attribute

    !> Close an attribute (always attempted; reports only when no error is set yet).
    subroutine close_attribute(object, name, attribute, error)
        type(h5_object), intent(in) :: object
        character(len=*), intent(in) :: name
        integer(hid_t), intent(inout) :: attribute
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        if (attribute < 0) return
        call h5aclose_f(attribute, status)
        if (status /= 0) call fail(error, 'close attribute '//name//' of', object)
        attribute = -1
    end subroutine close_attribute

    !> Create a dataset, or an attribute when is_attribute, of Fortran dims `dims` (scalar
    !> when empty) named name on the object loc. space_status /= 0 when the dataspace could
    !> not be made; status /= 0 when the object could not be created. id is -1 unless made.
    subroutine create_with_space(loc, name, data_type, dims, is_attribute, id, space_status, &
                                 status)
        integer(hid_t), intent(in) :: loc
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in) :: data_type
        integer, intent(in) :: dims(:)
        logical, intent(in) :: is_attribute
        integer(hid_t), intent(out) :: id
        integer, intent(out) :: space_status, status
        integer(hid_t) :: space
        integer :: close_status

        id = -1
        status = 0
        call create_space(dims, space, space_status)
        if (space_status /= 0) return
        if (is_attribute) then
            call h5acreate_f(loc, name, data_type, space, id, status)
        else
            call h5dcreate_f(loc, name, data_type, space, id, status)
        end if
        if (status /= 0) id = -1
        call h5sclose_f(space, close_status)
    end subroutine create_with_space

    !> A simple dataspace of Fortran dims `dims`, or a scalar one when dims is empty.
    subroutine create_space(dims, space, status)
        integer, intent(in) :: dims(:)
        integer(hid_t), intent(out) :: space
        integer, intent(out) :: status

        if (size(dims) == 0) then
            call h5screate_f(H5S_SCALAR_F, space, status)
        else
            call h5screate_simple_f(size(dims), int(dims, hsize_t), space, status)
        end if
    end subroutine create_space

    !> A fixed-length, NUL-padded UTF-8 string type of `width` bytes.
    subroutine create_string_type(width, string_type, status)
        integer, intent(in) :: width
        integer(hid_t), intent(out) :: string_type
        integer, intent(out) :: status

        call h5tcopy_f(H5T_FORTRAN_S1, string_type, status)
        if (status /= 0) return
        call h5tset_size_f(string_type, int(width, size_t), status)
        if (status == 0) call h5tset_strpad_f(string_type, H5T_STR_NULLPAD_F, status)
        if (status == 0) call h5tset_cset_f(string_type, H5T_CSET_UTF8_F, status)
    end subroutine create_string_type

    !> Width in bytes of a fixed-length string type; status /= 0 for other types.
    subroutine string_width(data_type, width, status)
        integer(hid_t), intent(in) :: data_type
        integer, intent(out) :: width, status
        integer(size_t) :: bytes
        integer :: type_class
        logical :: variable

        width = 0
        call h5tget_class_f(data_type, type_class, status)
        if (status /= 0) return
        if (type_class /= H5T_STRING_F) then
            status = -1
            return
        end if
        call h5tis_variable_str_f(data_type, variable, status)
        if (status /= 0) return
        if (variable) then
            status = -1
            return
        end if
        call h5tget_size_f(data_type, bytes, status)
        width = int(bytes)
    end subroutine string_width

    !> Set an I/O error "HDF5 could not <action> <path> in <file>" unless one is set.
    subroutine fail_on_object(error, action, object, name)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: action
        type(h5_object), intent(in) :: object
        !> Name of a child of object the action was about
        character(len=*), intent(in), optional :: name

        if (allocated(error)) return
        if (present(name)) then
            call set_error(error, exit_io_failure, 'HDF5 could not '//action//' ' &
                //child_path(object, name)//' in '//object%file)
        else
            call set_error(error, exit_io_failure, 'HDF5 could not '//action//' ' &
                //object%path//' in '//object%file)
        end if
    end subroutine fail_on_object

    !> Set an I/O error "HDF5 could not <action> in <file>" unless one is set.
    subroutine fail_in_file(error, action, path)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: action, path

        if (allocated(error)) return
        call set_error(error, exit_io_failure, 'HDF5 could not '//action//' in '//path)
    end subroutine fail_in_file

    !> Path of a child object: parent path / name.
    pure function child_path(parent, name) result(path)
        type(h5_object), intent(in) :: parent
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: path

        if (parent%path == '/') then
            path = '/'//name
        else
            path = parent%path//'/'//name
        end if
    end function child_path

    !> The characters of text, NUL-padded to width, for C.
    pure function c_chars(text, width) result(chars)
        character(len=*), intent(in) :: text
        integer, intent(in) :: width
        character(kind=c_char) :: chars(width)
        integer :: i

        chars = c_null_char
        do i = 1, min(len(text), width)
            chars(i) = text(i:i)
        end do
    end function c_chars

end module ddc_output_hdf5_handles
