# Compiler flags for our own targets only, per configuration.
function(ddc2d_set_flags target)
    if(CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
        target_compile_options(${target} PRIVATE
            -std=f2008 -fimplicit-none -ffree-line-length-132
            $<$<CONFIG:Debug>:-Og -g -Wall -Wextra -Wno-maybe-uninitialized -fcheck=all
                -fbacktrace -ffpe-trap=invalid,zero>
            $<$<CONFIG:Release>:-O3>
            $<$<CONFIG:RelWithDebInfo>:-O2 -g>
            $<$<BOOL:${DDC2D_NATIVE}>:-march=native>)
    endif()
endfunction()
