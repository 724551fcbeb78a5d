# Compiler flags for our own targets only, per configuration.
# -Wno-compare-reals: the input readers compare with deliberate sentinels (unset_real) and
# exact zeros; every other warning of -Wall -Wextra is fixed, and DDC2D_WERROR (on in the
# debug preset, which scripts/test.sh and CI build) makes a new one an error.
option(DDC2D_WERROR "Treat compiler warnings as errors" OFF)

function(ddc2d_set_flags target)
    if(CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
        target_compile_options(${target} PRIVATE
            "$<$<COMPILE_LANGUAGE:Fortran>:-std=f2008;-fimplicit-none;-ffree-line-length-132>"
            "$<$<AND:$<COMPILE_LANGUAGE:Fortran>,$<CONFIG:Debug>>:-Og;-g;-Wall;-Wextra;-Wno-compare-reals;-Wno-maybe-uninitialized;-fcheck=all;-fbacktrace;-ffpe-trap=invalid,zero>"
            $<$<CONFIG:Release>:-O3>
            $<$<CONFIG:RelWithDebInfo>:-O2 -g>
            $<$<BOOL:${DDC2D_NATIVE}>:-march=native>
            $<$<BOOL:${DDC2D_WERROR}>:-Werror>)
    endif()
    # The one C file (src/linalg/blas_library.c: weak BLAS queries, re-execution).
    if(CMAKE_C_COMPILER_ID STREQUAL "GNU")
        target_compile_options(${target} PRIVATE
            "$<$<COMPILE_LANGUAGE:C>:-std=c11;-Wall;-Wextra>"
            "$<$<AND:$<COMPILE_LANGUAGE:C>,$<CONFIG:Debug>>:-Og;-g>")
    endif()
endfunction()
