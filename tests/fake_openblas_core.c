/* A stand-in for OpenBLAS's kernel name, preloaded (LD_PRELOAD) by
 * tests/python/test_blas_kernel.py so that the start-up check of ddc2d sees an OpenBLAS
 * that chose an old kernel on this CPU: openblas_get_corename returns
 * DDC2D_TEST_CORENAME when set (a kernel OpenBLAS keeps whatever OPENBLAS_CORETYPE says),
 * else OPENBLAS_CORETYPE when set (OpenBLAS took it), else "Prescott". The real OpenBLAS
 * still does the arithmetic with its own kernel. */
#include <stdlib.h>

char *openblas_get_corename(void)
{
    char *forced = getenv("DDC2D_TEST_CORENAME");
    char *coretype = getenv("OPENBLAS_CORETYPE");

    if (forced) return forced;
    if (coretype) return coretype;
    return "Prescott";
}
