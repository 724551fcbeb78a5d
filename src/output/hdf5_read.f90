!> A small reader for ddc2d result files: datasets, their dims and attributes.
!>
!> Meant for tests and tools (regression comparisons) and for the question whether a
!> sweep task's result file is complete (output_is_complete: app/ skips such a task), not
!> for the solver. Every routine opens the file read-only, reads one thing and closes
!> every handle on every path. Each routine calls h5open_f/h5close_f itself: do not call
!> it while another part of the program holds HDF5 handles open.
module ddc_output_hdf5_read
    use, intrinsic :: iso_c_binding, only: c_char, c_loc, c_ptr
    use hdf5, only: hid_t, hsize_t, h5dopen_f, h5dclose_f, h5dread_f, h5dget_space_f, &
        h5dget_type_f, h5aopen_by_name_f, h5aclose_f, h5aread_f, h5aget_space_f, &
        h5aget_type_f, h5sget_simple_extent_ndims_f, h5sget_simple_extent_dims_f, &
        h5sget_simple_extent_npoints_f, h5sclose_f, h5tclose_f, h5fis_hdf5_f, &
        H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_output_hdf5_handles, only: h5_object, open_session, close_session, &
        handle_open_file => open_file, handle_close_file => close_file, string_width, fail
    use ddc_text, only: from_c_chars
    implicit none
    private

    public :: read_real_dataset, read_int_dataset, read_string_dataset, read_dataset_dims
    public :: read_string_attribute, read_real_attribute, read_int_attribute
    public :: output_is_complete, is_hdf5_file, has_dataset

contains

    !> Values of a real dataset in array element order (any rank, flattened).
    subroutine read_real_dataset(path, dataset, values, error)
        !> Path of the HDF5 file
        character(len=*), intent(in) :: path
        !> Path of the dataset inside the file, e.g. '/elements/ds'
        character(len=*), intent(in) :: dataset
        !> The values, shape (number of elements of the dataset)
        real(wp), allocatable, target, intent(out) :: values(:)
        !> Allocated with exit_io_failure when the dataset cannot be read
        type(error_type), allocatable, intent(out) :: error
        type(h5_object) :: file
        integer(hid_t) :: dset

        call open_dataset(path, dataset, file, dset, error)
        if (allocated(error)) return
        allocate (values(dataset_size(dset)))
        call read_and_close(file, dset, H5T_NATIVE_DOUBLE, c_loc(values), &
                            dataset//' as reals', path, error)
    end subroutine read_real_dataset

    !> Values of an integer dataset in array element order (any rank, flattened).
    subroutine read_int_dataset(path, dataset, values, error)
        !> Path of the HDF5 file
        character(len=*), intent(in) :: path
        !> Path of the dataset inside the file, e.g. '/elements/state'
        character(len=*), intent(in) :: dataset
        !> The values, shape (number of elements of the dataset)
        integer, allocatable, target, intent(out) :: values(:)
        !> Allocated with exit_io_failure when the dataset cannot be read
        type(error_type), allocatable, intent(out) :: error
        type(h5_object) :: file
        integer(hid_t) :: dset

        call open_dataset(path, dataset, file, dset, error)
        if (allocated(error)) return
        allocate (values(dataset_size(dset)))
        call read_and_close(file, dset, H5T_NATIVE_INTEGER, c_loc(values), &
                            dataset//' as integers', path, error)
    end subroutine read_int_dataset

    !> Values of a 1-D dataset of fixed-length strings, trailing NULs and blanks removed.
    ! allow(C072): the caller chooses the length of the strings
    subroutine read_string_dataset(path, dataset, values, error)
        !> Path of the HDF5 file
        character(len=*), intent(in) :: path
        !> Path of the dataset inside the file, e.g. '/fractures/name'
        character(len=*), intent(in) :: dataset
        !> The strings, blank-padded, shape (number of strings); the caller chooses the
        !> length, a longer stored string is an error
        character(len=*), allocatable, intent(out) :: values(:)
        !> Allocated with exit_io_failure when the dataset cannot be read
        type(error_type), allocatable, intent(out) :: error
        character(kind=c_char), allocatable, target :: buffer(:)
        character(len=:), allocatable :: text
        type(h5_object) :: file
        integer(hid_t) :: dset, data_type
        type(c_ptr) :: pointer
        integer :: status, width, n, i

        call open_dataset(path, dataset, file, dset, error)
        if (allocated(error)) return
        call h5dget_type_f(dset, data_type, status)
        if (status /= 0) then
            call fail(error, 'get the type of dataset '//dataset, path)
        else
            call string_width(data_type, width, status)
            if (status /= 0) then
                call fail(error, 'read dataset '//dataset//' as fixed-length strings', path)
            else
                n = dataset_size(dset)
                allocate (buffer(max(1, width * n)))
                allocate (values(n))
                status = 0
                if (n > 0) then
                    pointer = c_loc(buffer)
                    call h5dread_f(dset, data_type, pointer, status)
                end if
                if (status /= 0) then
                    call fail(error, 'read dataset '//dataset, path)
                else
                    do i = 1, n
                        text = from_c_chars(buffer((i - 1) * width + 1:i * width))
                        if (len(text) > len(values)) then
                            call fail(error, 'fit a string of dataset '//dataset &
                                //' into the length the caller gave', path)
                            exit
                        end if
                        values(i) = text
                    end do
                end if
            end if
            call h5tclose_f(data_type, status)
        end if
        call close_dataset(file, dset, path, error)
    end subroutine read_string_dataset

    !> Dims of a dataset in Fortran order (h5py shows them reversed); empty for a scalar.
    subroutine read_dataset_dims(path, dataset, dims, error)
        !> Path of the HDF5 file
        character(len=*), intent(in) :: path
        !> Path of the dataset inside the file
        character(len=*), intent(in) :: dataset
        !> Extent of each dimension, Fortran order, shape (rank)
        integer, allocatable, intent(out) :: dims(:)
        !> Allocated with exit_io_failure when the dataset cannot be read
        type(error_type), allocatable, intent(out) :: error
        type(h5_object) :: file
        integer(hid_t) :: dset, space
        integer(hsize_t), allocatable :: extent(:), max_extent(:)
        integer :: status, rank

        call open_dataset(path, dataset, file, dset, error)
        if (allocated(error)) return
        call h5dget_space_f(dset, space, status)
        if (status /= 0) then
            call fail(error, 'get the dataspace of dataset '//dataset, path)
        else
            call h5sget_simple_extent_ndims_f(space, rank, status)
            if (status == 0) then
                allocate (extent(max(rank, 1)), max_extent(max(rank, 1)))
                if (rank > 0) call h5sget_simple_extent_dims_f(space, extent, max_extent, &
                    status)
            end if
            if (status < 0) then
                call fail(error, 'get the dims of dataset '//dataset, path)
            else
                dims = int(extent(:rank))
            end if
            call h5sclose_f(space, status)
        end if
        call close_dataset(file, dset, path, error)
    end subroutine read_dataset_dims

    !> A fixed-length string attribute, trailing NULs removed.
    subroutine read_string_attribute(path, object, name, value, error)
        !> Path of the HDF5 file
        character(len=*), intent(in) :: path
        !> Path of the object carrying the attribute, e.g. '/' or '/elements/ds'
        character(len=*), intent(in) :: object
        !> Name of the attribute
        character(len=*), intent(in) :: name
        !> Its value
        character(len=:), allocatable, intent(out) :: value
        !> Allocated with exit_io_failure when the attribute cannot be read
        type(error_type), allocatable, intent(out) :: error
        character(kind=c_char), allocatable, target :: buffer(:)
        type(h5_object) :: file
        integer(hid_t) :: attribute, data_type
        type(c_ptr) :: pointer
        integer :: status, width

        call open_attribute(path, object, name, file, attribute, error)
        if (allocated(error)) return
        call h5aget_type_f(attribute, data_type, status)
        if (status /= 0) then
            call fail(error, 'get the type of attribute '//name//' of '//object, path)
        else
            call string_width(data_type, width, status)
            if (status /= 0) then
                call fail(error, 'read attribute '//name//' of '//object &
                    //' as a fixed-length string', path)
            else
                allocate (buffer(width))
                pointer = c_loc(buffer)
                call h5aread_f(attribute, data_type, pointer, status)
                if (status /= 0) then
                    call fail(error, 'read attribute '//name//' of '//object, path)
                else
                    value = from_c_chars(buffer)
                end if
            end if
            call h5tclose_f(data_type, status)
        end if
        call close_attribute(file, attribute, path, error)
    end subroutine read_string_attribute

    !> A real attribute, scalar or 1-D, as an array.
    subroutine read_real_attribute(path, object, name, values, error)
        !> Path of the HDF5 file
        character(len=*), intent(in) :: path
        !> Path of the object carrying the attribute
        character(len=*), intent(in) :: object
        !> Name of the attribute
        character(len=*), intent(in) :: name
        !> Its values, shape (1) for a scalar
        real(wp), allocatable, target, intent(out) :: values(:)
        !> Allocated with exit_io_failure when the attribute cannot be read
        type(error_type), allocatable, intent(out) :: error
        type(h5_object) :: file
        integer(hid_t) :: attribute
        type(c_ptr) :: pointer
        integer :: status

        call open_attribute(path, object, name, file, attribute, error)
        if (allocated(error)) return
        allocate (values(attribute_size(attribute)))
        pointer = c_loc(values)
        call h5aread_f(attribute, H5T_NATIVE_DOUBLE, pointer, status)
        if (status /= 0) call fail(error, 'read attribute '//name//' of '//object, path)
        call close_attribute(file, attribute, path, error)
    end subroutine read_real_attribute

    !> A scalar integer attribute.
    subroutine read_int_attribute(path, object, name, value, error)
        !> Path of the HDF5 file
        character(len=*), intent(in) :: path
        !> Path of the object carrying the attribute
        character(len=*), intent(in) :: object
        !> Name of the attribute
        character(len=*), intent(in) :: name
        !> Its value
        integer, intent(out) :: value
        !> Allocated with exit_io_failure when the attribute cannot be read
        type(error_type), allocatable, intent(out) :: error
        integer, target :: buffer(1)
        type(h5_object) :: file
        integer(hid_t) :: attribute
        type(c_ptr) :: pointer
        integer :: status

        value = 0
        call open_attribute(path, object, name, file, attribute, error)
        if (allocated(error)) return
        if (attribute_size(attribute) /= 1) then
            call fail(error, 'read attribute '//name//' of '//object//' as a scalar', path)
        else
            pointer = c_loc(buffer)
            call h5aread_f(attribute, H5T_NATIVE_INTEGER, pointer, status)
            if (status /= 0) then
                call fail(error, 'read attribute '//name//' of '//object, path)
            else
                value = buffer(1)
            end if
        end if
        call close_attribute(file, attribute, path, error)
    end subroutine read_int_attribute

    !> True when path holds a readable ddc2d result with the root attribute complete = 1, and
    !> for a cycle run one that did not stop at a checkpoint (/cycle end_reason 'running').
    function output_is_complete(path) result(complete)
        !> Path of the result file
        character(len=*), intent(in) :: path
        !> The file exists, is readable HDF5 and is complete
        logical :: complete
        type(error_type), allocatable :: error
        character(len=:), allocatable :: reason
        integer :: flag

        inquire (file=path, exist=complete)
        if (.not. complete) return
        call read_int_attribute(path, '/', 'complete', flag, error)
        complete = .not. allocated(error)
        if (complete) complete = flag == 1
        if (.not. (complete .and. has_dataset(path, '/cycle/time'))) return
        call read_string_attribute(path, '/cycle', 'end_reason', reason, error)
        complete = .not. allocated(error)
        if (complete) complete = reason /= 'running'
    end function output_is_complete

    !> Whether a result file holds a dataset (false too when it cannot be read).
    function has_dataset(path, dataset) result(found)
        !> Path of the file
        character(len=*), intent(in) :: path
        !> Path of the dataset inside the file
        character(len=*), intent(in) :: dataset
        !> The dataset is there
        logical :: found
        type(error_type), allocatable :: error
        integer, allocatable :: dims(:)

        call read_dataset_dims(path, dataset, dims, error)
        found = .not. allocated(error)
    end function has_dataset

    !> True when path is a readable HDF5 file (its signature; nothing else is read).
    function is_hdf5_file(path) result(hdf5_file)
        !> Path of the file
        character(len=*), intent(in) :: path
        !> The file carries the HDF5 signature
        logical :: hdf5_file
        type(error_type), allocatable :: error
        integer :: status

        hdf5_file = .false.
        call open_session(error)
        if (allocated(error)) return
        call h5fis_hdf5_f(path, hdf5_file, status)
        if (status /= 0) hdf5_file = .false.
        call close_session()
    end function is_hdf5_file

    ! ------------------------------------------------------ handles, always closed

    !> Start HDF5 and open the file read-only; on failure HDF5 is stopped again.
    subroutine open_file(path, file, error)
        character(len=*), intent(in) :: path
        type(h5_object), intent(out) :: file
        type(error_type), allocatable, intent(inout) :: error

        call open_session(error)
        if (allocated(error)) return
        call handle_open_file(path, file, error)
        if (allocated(error)) call close_session()
    end subroutine open_file

    !> Close the file and HDF5.
    subroutine close_file(file, error)
        type(h5_object), intent(inout) :: file
        type(error_type), allocatable, intent(inout) :: error

        call handle_close_file(file, error)
        call close_session()
    end subroutine close_file

    !> Open the file and one of its datasets; on failure everything is closed again.
    subroutine open_dataset(path, dataset, file, dset, error)
        character(len=*), intent(in) :: path, dataset
        type(h5_object), intent(out) :: file
        integer(hid_t), intent(out) :: dset
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        dset = -1
        call open_file(path, file, error)
        if (allocated(error)) return
        call h5dopen_f(file%id, dataset, dset, status)
        call check_opened(status, 'dataset '//dataset, path, file, dset, error)
    end subroutine open_dataset

    !> Close a dataset and its file.
    subroutine close_dataset(file, dset, path, error)
        type(h5_object), intent(inout) :: file
        integer(hid_t), intent(inout) :: dset
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        call h5dclose_f(dset, status)
        if (status /= 0) call fail(error, 'close a dataset', path)
        call close_file(file, error)
    end subroutine close_dataset

    !> Read a whole open dataset into memory of the given type, then close it and its file.
    subroutine read_and_close(file, dset, mem_type, pointer, what, path, error)
        type(h5_object), intent(inout) :: file
        integer(hid_t), intent(inout) :: dset
        integer(hid_t), intent(in) :: mem_type
        type(c_ptr), intent(in) :: pointer
        character(len=*), intent(in) :: what, path
        type(error_type), allocatable, intent(inout) :: error
        type(c_ptr) :: buffer
        integer :: status

        buffer = pointer
        call h5dread_f(dset, mem_type, buffer, status)
        if (status /= 0) call fail(error, 'read dataset '//what, path)
        call close_dataset(file, dset, path, error)
    end subroutine read_and_close

    !> Open the file and an attribute of one of its objects; closes all on failure.
    subroutine open_attribute(path, object, name, file, attribute, error)
        character(len=*), intent(in) :: path, object, name
        type(h5_object), intent(out) :: file
        integer(hid_t), intent(out) :: attribute
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        attribute = -1
        call open_file(path, file, error)
        if (allocated(error)) return
        call h5aopen_by_name_f(file%id, object, name, attribute, status)
        call check_opened(status, 'attribute '//name//' of '//object, path, file, attribute, &
                          error)
    end subroutine open_attribute

    !> After opening an object of the file: on failure (status /= 0) mark the handle
    !> closed, set the error "could not open <what>" and close the file again.
    subroutine check_opened(status, what, path, file, handle, error)
        integer, intent(in) :: status
        character(len=*), intent(in) :: what, path
        type(h5_object), intent(inout) :: file
        integer(hid_t), intent(inout) :: handle
        type(error_type), allocatable, intent(inout) :: error

        if (status == 0) return
        handle = -1
        call fail(error, 'open '//what, path)
        call close_file(file, error)
    end subroutine check_opened

    !> Close an attribute and its file.
    subroutine close_attribute(file, attribute, path, error)
        type(h5_object), intent(inout) :: file
        integer(hid_t), intent(inout) :: attribute
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(inout) :: error
        integer :: status

        call h5aclose_f(attribute, status)
        if (status /= 0) call fail(error, 'close an attribute', path)
        call close_file(file, error)
    end subroutine close_attribute

    !> Number of elements of a dataset (0 when it cannot be told).
    function dataset_size(dset) result(n)
        integer(hid_t), intent(in) :: dset
        integer :: n
        integer(hid_t) :: space
        integer :: status

        call h5dget_space_f(dset, space, status)
        n = space_points(space, status)
    end function dataset_size

    !> Number of elements of an attribute (1 for a scalar; 0 when it cannot be told).
    function attribute_size(attribute) result(n)
        integer(hid_t), intent(in) :: attribute
        integer :: n
        integer(hid_t) :: space
        integer :: status

        call h5aget_space_f(attribute, space, status)
        n = space_points(space, status)
    end function attribute_size

    !> Number of points of a dataspace, which is then closed; got is the status of getting
    !> the space (0 when the space could not be had or its size told).
    function space_points(space, got) result(n)
        integer(hid_t), intent(in) :: space
        integer, intent(in) :: got
        integer :: n
        integer(hsize_t) :: points
        integer :: status

        n = 0
        if (got /= 0) return
        call h5sget_simple_extent_npoints_f(space, points, status)
        if (status == 0) n = int(points)
        call h5sclose_f(space, status)
    end function space_points

end module ddc_output_hdf5_read
