!> Typed writes into ddc2d's HDF5 files: real and integer datasets (with their `units` or
!> `coding` attribute), string datasets, and scalar or 1-D attributes. Strings are stored
!> fixed-length, NUL-padded, UTF-8. Each routine does nothing when the error is already set
!> and closes what it opened on every path.
module ddc_output_hdf5_write
    use, intrinsic :: iso_c_binding, only: c_char, c_loc
    use hdf5, only: hid_t, hsize_t, h5dwrite_f, h5awrite_f, h5tclose_f, H5T_NATIVE_DOUBLE, &
        H5T_NATIVE_INTEGER
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use ddc_output_hdf5_handles, only: h5_object, create_dataset, close_dataset, &
        create_attribute, close_attribute, create_string_type, fail, c_chars
    implicit none
    private

    public :: write_real_1d, write_int_1d, write_real_dataset, write_int_dataset
    public :: write_string_1d, write_attribute

    !> Attributes of any object: strings, reals (scalar or 1-D) and integers.
    interface write_attribute
        module procedure write_string_attribute, write_real_attribute, &
            write_real_array_attribute, write_int_attribute, write_int_array_attribute
    end interface write_attribute

contains

    !> A 1-D real dataset with a `units` attribute.
    subroutine write_real_1d(parent, name, values, units, error)
        type(h5_object), intent(in) :: parent
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: values(:)
        character(len=*), intent(in) :: units
        type(error_type), allocatable, intent(inout) :: error

        call write_real_dataset(parent, name, values, [size(values)], units, error)
    end subroutine write_real_1d

    !> A 1-D integer dataset, with an optional `coding` attribute.
    subroutine write_int_1d(parent, name, values, error, coding)
        type(h5_object), intent(in) :: parent
        character(len=*), intent(in) :: name
        integer, intent(in) :: values(:)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in), optional :: coding

        call write_int_dataset(parent, name, values, [size(values)], error, coding)
    end subroutine write_int_1d

    !> A real dataset of Fortran dims `dims` (scalar when dims is empty) from values in
    !> array element order, with a `units` attribute.
    subroutine write_real_dataset(parent, name, values, dims, units, error)
        type(h5_object), intent(in) :: parent
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: values(:)
        integer, intent(in) :: dims(:)
        character(len=*), intent(in) :: units
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: dataset
        integer :: status

        call create_dataset(parent, name, H5T_NATIVE_DOUBLE, dims, dataset, error)
        if (allocated(error)) return
        if (size(values) > 0) then
            call h5dwrite_f(dataset%id, H5T_NATIVE_DOUBLE, values, &
                int(max(dims, 1), hsize_t), status)
            if (status /= 0) call fail(error, 'write dataset', dataset)
        end if
        call write_attribute(dataset, 'units', units, error)
        call close_dataset(dataset, error)
    end subroutine write_real_dataset

    !> An integer dataset of Fortran dims `dims`, with an optional `coding` attribute.
    subroutine write_int_dataset(parent, name, values, dims, error, coding)
        type(h5_object), intent(in) :: parent
        character(len=*), intent(in) :: name
        integer, intent(in) :: values(:)
        integer, intent(in) :: dims(:)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in), optional :: coding
        type(h5_object) :: dataset
        integer :: status

        call create_dataset(parent, name, H5T_NATIVE_INTEGER, dims, dataset, error)
        if (allocated(error)) return
        if (size(values) > 0) then
            call h5dwrite_f(dataset%id, H5T_NATIVE_INTEGER, values, &
                int(max(dims, 1), hsize_t), status)
            if (status /= 0) call fail(error, 'write dataset', dataset)
        end if
        if (present(coding)) call write_attribute(dataset, 'coding', coding, error)
        call close_dataset(dataset, error)
    end subroutine write_int_dataset

    !> A 1-D dataset of fixed-length, NUL-padded UTF-8 strings (trailing blanks dropped).
    subroutine write_string_1d(parent, name, values, error)
        type(h5_object), intent(in) :: parent
        character(len=*), intent(in) :: name
        character(len=*), intent(in) :: values(:)
        type(error_type), allocatable, intent(inout) :: error
        type(h5_object) :: dataset
        character(kind=c_char), allocatable, target :: buffer(:)
        integer(hid_t) :: string_type
        integer :: i, width, status

        if (allocated(error)) return
        width = max(1, len(values))
        allocate (buffer(width * size(values)))
        do i = 1, size(values)
            buffer((i - 1) * width + 1:i * width) = c_chars(trim(values(i)), width)
        end do
        call create_string_type(width, string_type, status)
        if (status /= 0) then
            call fail(error, 'create a string type for', parent, name)
        else
            call create_dataset(parent, name, string_type, [size(values)], dataset, error)
            if (.not. allocated(error)) then
                if (size(values) > 0) then
                    call h5dwrite_f(dataset%id, string_type, c_loc(buffer), status)
                    if (status /= 0) call fail(error, 'write dataset', dataset)
                end if
                call close_dataset(dataset, error)
            end if
        end if
        call h5tclose_f(string_type, status)
    end subroutine write_string_1d

    !> A scalar string attribute (fixed length, NUL-padded, UTF-8).
    subroutine write_string_attribute(object, name, value, error)
        type(h5_object), intent(in) :: object
        character(len=*), intent(in) :: name
        character(len=*), intent(in) :: value
        type(error_type), allocatable, intent(inout) :: error
        character(kind=c_char), allocatable, target :: buffer(:)
        integer(hid_t) :: string_type, attribute
        integer :: width, status

        if (allocated(error)) return
        width = max(1, len(value))
        buffer = c_chars(value, width)
        call create_string_type(width, string_type, status)
        if (status /= 0) then
            call fail(error, 'create a string type for attribute '//name//' of', object)
        else
            call create_attribute(object, name, string_type, [integer ::], attribute, error)
            if (.not. allocated(error)) then
                call h5awrite_f(attribute, string_type, c_loc(buffer), status)
                if (status /= 0) call fail(error, 'write attribute '//name//' of', object)
                call close_attribute(object, name, attribute, error)
            end if
        end if
        call h5tclose_f(string_type, status)
    end subroutine write_string_attribute

    !> A scalar real attribute.
    subroutine write_real_attribute(object, name, value, error)
        type(h5_object), intent(in) :: object
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: value
        type(error_type), allocatable, intent(inout) :: error

        call put_real_attribute(object, name, [value], [integer ::], error)
    end subroutine write_real_attribute

    !> A 1-D real attribute.
    subroutine write_real_array_attribute(object, name, values, error)
        type(h5_object), intent(in) :: object
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: values(:)
        type(error_type), allocatable, intent(inout) :: error

        call put_real_attribute(object, name, values, [size(values)], error)
    end subroutine write_real_array_attribute

    !> A real attribute of dims `dims` (scalar when empty).
    subroutine put_real_attribute(object, name, values, dims, error)
        type(h5_object), intent(in) :: object
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: values(:)
        integer, intent(in) :: dims(:)
        type(error_type), allocatable, intent(inout) :: error
        integer(hid_t) :: attribute
        integer :: status

        call create_attribute(object, name, H5T_NATIVE_DOUBLE, dims, attribute, error)
        if (allocated(error)) return
        call h5awrite_f(attribute, H5T_NATIVE_DOUBLE, values, int([size(values)], hsize_t), &
            status)
        if (status /= 0) call fail(error, 'write attribute '//name//' of', object)
        call close_attribute(object, name, attribute, error)
    end subroutine put_real_attribute

    !> A scalar integer attribute.
    subroutine write_int_attribute(object, name, value, error)
        type(h5_object), intent(in) :: object
        character(len=*), intent(in) :: name
        integer, intent(in) :: value
        type(error_type), allocatable, intent(inout) :: error

        call put_int_attribute(object, name, [value], [integer ::], error)
    end subroutine write_int_attribute

    !> A 1-D integer attribute.
    subroutine write_int_array_attribute(object, name, values, error)
        type(h5_object), intent(in) :: object
        character(len=*), intent(in) :: name
        integer, intent(in) :: values(:)
        type(error_type), allocatable, intent(inout) :: error

        call put_int_attribute(object, name, values, [size(values)], error)
    end subroutine write_int_array_attribute

    !> An integer attribute of dims `dims` (scalar when empty).
    subroutine put_int_attribute(object, name, values, dims, error)
        type(h5_object), intent(in) :: object
        character(len=*), intent(in) :: name
        integer, intent(in) :: values(:)
        integer, intent(in) :: dims(:)
        type(error_type), allocatable, intent(inout) :: error
        integer(hid_t) :: attribute
        integer :: status

        call create_attribute(object, name, H5T_NATIVE_INTEGER, dims, attribute, error)
        if (allocated(error)) return
        call h5awrite_f(attribute, H5T_NATIVE_INTEGER, values, int([size(values)], hsize_t), &
            status)
        if (status /= 0) call fail(error, 'write attribute '//name//' of', object)
        call close_attribute(object, name, attribute, error)
    end subroutine put_int_attribute

end module ddc_output_hdf5_write
