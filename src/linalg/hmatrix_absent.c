/* The C side of ddc_linalg_hmatrix (hmatrix.f90) in a build without hmat-oss
 * (DDC2D_HMATRIX=OFF, README.md#licence): no hierarchical matrix can be made. The input
 * refuses &solver matrix = 'hierarchical' and 'auto' takes the dense matrix there, so these
 * run only when a program of the library asks for one itself: the assembly fails (NULL),
 * which the Fortran side reports as an error, and nothing after it is reached. */
#include <stddef.h>

typedef void (*ddc_fill_block)(void *context, int row_count, const int *rows, int col_count,
                               const int *cols, double *block);

void *ddc2d_hmatrix_assemble(int rows, const double *row_coordinates, int cols,
                             const double *col_coordinates, int leaf_size, double eta,
                             double epsilon, ddc_fill_block fill, void *context) {
    (void)rows, (void)row_coordinates, (void)cols, (void)col_coordinates, (void)leaf_size;
    (void)eta, (void)epsilon, (void)fill, (void)context;
    return NULL;
}

void *ddc2d_hmatrix_copy(void *handle) {
    (void)handle;
    return NULL;
}

int ddc2d_hmatrix_factor(void *handle) {
    (void)handle;
    return -1;
}

int ddc2d_hmatrix_solve(void *handle, double *b, int nrhs) {
    (void)handle, (void)b, (void)nrhs;
    return -1;
}

int ddc2d_hmatrix_multiply(void *handle, double *x, double *y) {
    (void)handle, (void)x, (void)y;
    return -1;
}

void ddc2d_hmatrix_sizes(void *handle, double *stored, double *dense) {
    (void)handle;
    *stored = 0.0;
    *dense = 0.0;
}

void ddc2d_hmatrix_free(void *handle) {
    (void)handle;
}
