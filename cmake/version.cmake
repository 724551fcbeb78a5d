# Program version, the git commit of the source and what the build has, compiled into
# ddc_version.
execute_process(COMMAND git rev-parse --short=12 HEAD
                WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                OUTPUT_VARIABLE DDC2D_GIT_COMMIT OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET RESULT_VARIABLE git_status)
if(NOT git_status EQUAL 0 OR DDC2D_GIT_COMMIT STREQUAL "")
    set(DDC2D_GIT_COMMIT "unknown")
endif()
if(DDC2D_HMATRIX)
    set(DDC2D_WITH_HMATRIX .true.)
else()
    set(DDC2D_WITH_HMATRIX .false.)
endif()
configure_file(${PROJECT_SOURCE_DIR}/src/version.f90.in ${PROJECT_BINARY_DIR}/generated/version.f90 @ONLY)
