/* What Fortran cannot say: which BLAS this process runs, its threads, and a re-execution of
 * the program.
 *
 * The queries of OpenBLAS (openblas_get_config, openblas_get_corename,
 * openblas_get_num_threads) and of BLIS (bli_info_get_version_str, bli_arch_query_id,
 * bli_arch_string) are weak references: ddc2d links and runs with any BLAS, and a query
 * the BLAS in use does not have is a null pointer (the library is then "unknown").
 * ddc_linalg_blas_library (blas_library.f90) is the Fortran side.
 */
#define _POSIX_C_SOURCE 200809L /* setenv */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern char *openblas_get_config(void) __attribute__((weak));
extern char *openblas_get_corename(void) __attribute__((weak));
extern int openblas_get_num_threads(void) __attribute__((weak));
extern void openblas_set_num_threads(int threads) __attribute__((weak));
extern const char *bli_info_get_version_str(void) __attribute__((weak));
extern int bli_arch_query_id(void) __attribute__((weak));
extern const char *bli_arch_string(int id) __attribute__((weak));

static void copy_text(char *to, int size, const char *from)
{
    if (size <= 0) return;
    snprintf(to, (size_t)size, "%s", from ? from : "");
}

/* The BLAS library (its configuration string), its kernel and its threads (0: unknown);
 * returns 1 for OpenBLAS, 2 for BLIS, 0 for another BLAS. */
int ddc2d_blas_query(char *library, int library_size, char *core, int core_size,
                     int *threads)
{
    *threads = 0;
    if (openblas_get_config && openblas_get_corename) {
        copy_text(library, library_size, openblas_get_config());
        copy_text(core, core_size, openblas_get_corename());
        if (openblas_get_num_threads) *threads = openblas_get_num_threads();
        return 1;
    }
    if (bli_info_get_version_str) {
        char version[200];
        snprintf(version, sizeof version, "BLIS %s", bli_info_get_version_str());
        copy_text(library, library_size, version);
        copy_text(core, core_size,
                  bli_arch_query_id && bli_arch_string ? bli_arch_string(bli_arch_query_id())
                                                      : "");
        return 2;
    }
    copy_text(library, library_size, "");
    copy_text(core, core_size, "");
    return 0;
}

/* Tell the BLAS how many threads to run (OpenBLAS); returns 0 where it cannot be told. */
int ddc2d_blas_set_threads(int threads)
{
    if (!openblas_set_num_threads) return 0;
    openblas_set_num_threads(threads);
    return 1;
}

/* Run this program again from the start with the same arguments (/proc/self/cmdline) and
 * name=value added to its environment (marker=marker_value too, so that the new process
 * knows it was started this way). Returns only when that fails (-1). */
int ddc2d_reexec_with(const char *name, const char *value, const char *marker,
                      const char *marker_value)
{
    static char arguments[65536];
    char *argv[1024];
    FILE *file = fopen("/proc/self/cmdline", "rb");
    size_t length, k = 0;
    int argc = 0;

    if (!file) return -1;
    length = fread(arguments, 1, sizeof arguments - 1, file);
    fclose(file);
    if (length == 0 || length >= sizeof arguments - 1) return -1;
    arguments[length] = '\0';
    for (; k < length && argc < 1023; k += strlen(arguments + k) + 1)
        argv[argc++] = arguments + k;
    if (k < length) return -1; /* more arguments than argv holds */
    argv[argc] = NULL;
    if (setenv(name, value, 1) != 0 || setenv(marker, marker_value, 1) != 0) return -1;
    fflush(stdout);
    fflush(stderr);
    execv("/proc/self/exe", argv);
    unsetenv(name);
    unsetenv(marker);
    return -1;
}
