# `cmake --install BUILD --prefix P` (docs/install.md): the programs, the library with its
# Fortran modules, the CMake package (find_package(ddc2d) gives ddc2d::ddc2d), a pkg-config
# file, the example inputs and an Lmod module file. Every installed file that points at the
# prefix finds it relative to its own place, so a --prefix given at install time works.
include(CMakePackageConfigHelpers)

set(programs ddc2d)
if(DDC2D_MPI)
    list(APPEND programs ddc2d_serial)
endif()
install(TARGETS ${programs} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(TARGETS ddc2d_lib EXPORT ddc2d-targets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${DDC2D_LIBRARY_MODULE_DIR}/ DESTINATION ${DDC2D_INSTALL_MODULEDIR}
        FILES_MATCHING PATTERN "*.mod")

# The CMake package: the exported target, its dependencies found again for the user
# (cmake/ddc2d-config.cmake.in) and the version (0.x: a minor version may break the API).
install(EXPORT ddc2d-targets NAMESPACE ddc2d:: DESTINATION ${DDC2D_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ddc2d-config.cmake.in
    ${PROJECT_BINARY_DIR}/package/ddc2d-config.cmake
    INSTALL_DESTINATION ${DDC2D_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/ddc2d-config-version.cmake
    COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/ddc2d-config.cmake
              ${PROJECT_BINARY_DIR}/package/ddc2d-config-version.cmake
        DESTINATION ${DDC2D_INSTALL_CMAKEDIR})

# The libraries and flags of a list as a linker sees them on a command line: paths and
# flags as they are, bare names as -l<name>.
function(ddc2d_link_words out)
    set(words "")
    foreach(item IN LISTS ARGN)
        if(item MATCHES "^(-|/)")
            list(APPEND words "${item}")
        elseif(NOT item STREQUAL "")
            list(APPEND words "-l${item}")
        endif()
    endforeach()
    list(REMOVE_DUPLICATES words)
    string(JOIN " " joined ${words})
    set(${out} "${joined}" PARENT_SCOPE)
endfunction()

# pkg-config: the library is static, so Libs names what it needs (LAPACK, HDF5 Fortran,
# hmat-oss unless DDC2D_HMATRIX is off, OpenMP) for a plain
# `gfortran main.f90 $(pkg-config --cflags --libs ddc2d)`.
file(RELATIVE_PATH pc_to_prefix /root/${CMAKE_INSTALL_LIBDIR}/pkgconfig /root)
string(REGEX REPLACE "/$" "" pc_to_prefix "${pc_to_prefix}")
set(hmat_library "")
if(DDC2D_HMATRIX)
    get_target_property(hmat_library HMAT::hmat LOCATION)
endif()
ddc2d_link_words(pc_dependencies ${LAPACK_LIBRARIES} ${LAPACK_LINKER_FLAGS}
                 ${HDF5_Fortran_LIBRARIES} ${hmat_library} ${OpenMP_Fortran_FLAGS})
list(TRANSFORM HDF5_Fortran_INCLUDE_DIRS PREPEND "-I" OUTPUT_VARIABLE pc_includes)
string(JOIN " " pc_includes ${pc_includes})
configure_file(${PROJECT_SOURCE_DIR}/packaging/ddc2d.pc.in
               ${PROJECT_BINARY_DIR}/package/ddc2d.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/package/ddc2d.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# The example inputs of input/, with the files they name (input/seas: the surface stations).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/input/ DESTINATION ${CMAKE_INSTALL_DATADIR}/ddc2d/examples
        FILES_MATCHING PATTERN "*.nml" PATTERN "*.csv")

# Lmod: share/modulefiles/ddc2d/<version>.lua (`module use P/share/modulefiles; module load
# ddc2d`), which finds the prefix as many folders up from itself as it lies below it.
set(DDC2D_INSTALL_MODULEFILEDIR ${CMAKE_INSTALL_DATADIR}/modulefiles/ddc2d)
string(REGEX MATCHALL "[^/]+" module_folders ${DDC2D_INSTALL_MODULEFILEDIR})
list(LENGTH module_folders module_depth)
configure_file(${PROJECT_SOURCE_DIR}/packaging/lmod/ddc2d.lua.in
               ${PROJECT_BINARY_DIR}/package/${PROJECT_VERSION}.lua @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/package/${PROJECT_VERSION}.lua
        DESTINATION ${DDC2D_INSTALL_MODULEFILEDIR})
