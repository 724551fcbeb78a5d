# Where `cmake --install` puts the library's Fortran module files and the CMake package.
# .mod files are read only by the compiler that wrote them (and often only by the same
# version), so their folder names the compiler: include/ddc2d/GNU-12.2.0 for gfortran 12.2.
set(DDC2D_INSTALL_MODULEDIR
    ${CMAKE_INSTALL_INCLUDEDIR}/ddc2d/${CMAKE_Fortran_COMPILER_ID}-${CMAKE_Fortran_COMPILER_VERSION}
    CACHE STRING "Install folder of the Fortran .mod files, relative to the prefix")
set(DDC2D_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/ddc2d
    CACHE STRING "Install folder of the CMake package (ddc2d-config.cmake), relative to the prefix")
