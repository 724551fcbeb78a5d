/* ddc2d's BLAS query (src/linalg/blas_library.c) linked without any BLAS: it must link and
 * report another BLAS (family 0, empty strings), as with a BLAS that has none of the
 * OpenBLAS or BLIS queries. Exit status 0 when it does (CTest blas_query_without_blas). */
#include <stdio.h>

int ddc2d_blas_query(char *library, int library_size, char *core, int core_size,
                     int *threads);

int main(void)
{
    char library[64] = "x", core[64] = "x";
    int threads = -1;
    int family = ddc2d_blas_query(library, sizeof library, core, sizeof core, &threads);

    printf("family %d, library '%s', core '%s', threads %d\n", family, library, core,
           threads);
    return !(family == 0 && library[0] == '\0' && core[0] == '\0' && threads == 0);
}
