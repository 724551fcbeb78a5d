!> Where the Fortran suites write the files of their cases: `temporary_path(name)` is `name`
!> in `temporary_folder()`, the folder $TMPDIR names. CTest sets it to a folder of the test's
!> own in the build tree and fails the run when something is left there
!> (tests/CMakeLists.txt); by hand, without TMPDIR, it is /tmp. A case removes every file it
!> writes.
module ddc_test_temporary
    implicit none
    private

    public :: temporary_folder, temporary_path

contains

    !> The temporary folder: $TMPDIR, else /tmp.
    function temporary_folder() result(folder)
        character(len=:), allocatable :: folder
        integer :: length, stat

        call get_environment_variable('TMPDIR', length=length, status=stat)
        if (stat /= 0 .or. length == 0) then
            folder = '/tmp'
            return
        end if
        allocate (character(len=length) :: folder)
        call get_environment_variable('TMPDIR', folder)
    end function temporary_folder

    !> `name` in the temporary folder.
    function temporary_path(name) result(path)
        !> A file or folder name, unique within the suite
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: path

        path = temporary_folder()//'/'//name
    end function temporary_path

end module ddc_test_temporary
