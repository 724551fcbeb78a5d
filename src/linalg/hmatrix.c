/* The C side of ddc_linalg_hmatrix (hmatrix.f90): a hierarchical matrix of hmat-oss
 * (header hmat/hmat.h, Debian libhmat-oss-dev) built from a Fortran block filler. hmat-oss
 * calls its functions through a table (hmat_interface_t) that Fortran cannot call
 * directly; this file keeps that table and hands Fortran plain functions.
 *
 * The blocks are assembled by hmat-oss's "block compute" scenario: prepare_block maps a
 * block's rows and columns from hmat's numbering (the cluster tree's order) to the
 * caller's 1-based unknowns once; compute_block then asks the filler for the whole block,
 * one row or one column of it (ACA+ asks for single rows and columns). */
#include <stdlib.h>
#include <string.h>
#include <hmat/hmat.h>

/* Fill block(row_count, col_count), column-major, with the entries of the caller's rows
 * rows[0..row_count) and columns cols[0..col_count) (1-based). */
typedef void (*ddc_fill_block)(void *context, int row_count, const int *rows, int col_count,
                               const int *cols, double *block);

typedef struct {
    hmat_interface_t api;
    hmat_cluster_tree_t *tree, *col_tree; /* col_tree: a rectangular matrix's columns */
    hmat_matrix_t *matrix;
    int owns_tree; /* a copy shares its original's cluster tree */
    ddc_fill_block fill;
    void *context;
} ddc_hmatrix;

typedef struct {
    ddc_hmatrix *owner;
    int *rows, *cols;
} block_map;

static void release_block(void *data) {
    block_map *map = data;
    free(map->rows);
    free(map->cols);
    free(map);
}

static void compute_block(void *data, int row_start, int row_count, int col_start,
                          int col_count, void *block) {
    block_map *map = data;
    map->owner->fill(map->owner->context, row_count, map->rows + row_start, col_count,
                     map->cols + col_start, block);
}

static void prepare_block(int row_start, int row_count, int col_start, int col_count,
                          int *row_hmat2client, int *row_client2hmat, int *col_hmat2client,
                          int *col_client2hmat, void *context, hmat_block_info_t *info) {
    (void)row_client2hmat;
    (void)col_client2hmat;
    block_map *map = malloc(sizeof *map);
    int *rows = malloc(sizeof(int) * (size_t)row_count);
    int *cols = malloc(sizeof(int) * (size_t)col_count);
    if (!map || !rows || !cols) abort(); /* a few ints per block: no recovery from this */
    for (int i = 0; i < row_count; ++i) rows[i] = row_hmat2client[row_start + i] + 1;
    for (int j = 0; j < col_count; ++j) cols[j] = col_hmat2client[col_start + j] + 1;
    map->owner = context;
    map->rows = rows;
    map->cols = cols;
    info->block_type = hmat_block_full;
    info->user_data = map;
    info->release_user_data = release_block;
}

static hmat_cluster_tree_t *cluster_tree(int count, const double *coordinates,
                                         int leaf_size) {
    hmat_clustering_algorithm_t *median = hmat_create_clustering_median();
    hmat_clustering_algorithm_t *leaves = hmat_create_clustering_max_dof(median, leaf_size);
    hmat_cluster_tree_t *tree = hmat_create_cluster_tree((double *)coordinates, 2, count,
                                                         leaves);
    hmat_delete_clustering(leaves);
    hmat_delete_clustering(median);
    return tree;
}

static void free_trees(ddc_hmatrix *h) {
    if (h->col_tree) hmat_delete_cluster_tree(h->col_tree);
    if (h->tree) hmat_delete_cluster_tree(h->tree);
}

/* The matrix of rows rows and cols columns whose unknowns sit at row_coordinates[2 k],
 * [2 k + 1] and col_coordinates (NULL: the rows' points, a square matrix of one cluster
 * tree), each tree split at medians into leaves of at most leaf_size unknowns, blocks
 * admissible by Hackbusch's condition with eta, compressed by ACA+ to the relative
 * accuracy epsilon (also that of the recompressions of H-LU). NULL when hmat-oss fails. */
void *ddc2d_hmatrix_assemble(int rows, const double *row_coordinates, int cols,
                             const double *col_coordinates, int leaf_size, double eta,
                             double epsilon, ddc_fill_block fill, void *context) {
    ddc_hmatrix *h = calloc(1, sizeof *h);
    if (!h) return NULL;
    hmat_init_default_interface(&h->api, HMAT_DOUBLE_PRECISION);
    h->tree = cluster_tree(rows, row_coordinates, leaf_size);
    if (col_coordinates) h->col_tree = cluster_tree(cols, col_coordinates, leaf_size);
    hmat_admissibility_t *admissibility = hmat_create_admissibility_standard(eta);
    h->matrix = h->api.create_empty_hmatrix_admissibility(
        h->tree, h->col_tree ? h->col_tree : h->tree, 0, admissibility);
    hmat_delete_admissibility(admissibility);
    if (!h->matrix) {
        free_trees(h);
        free(h);
        return NULL;
    }
    h->api.set_low_rank_epsilon(h->matrix, epsilon);
    h->owns_tree = 1;
    h->fill = fill;
    h->context = context;
    hmat_assemble_context_t assembly;
    hmat_assemble_context_init(&assembly);
    hmat_compression_algorithm_t *compression = hmat_create_compression_aca_plus(epsilon);
    assembly.compression = compression;
    assembly.prepare = prepare_block;
    assembly.block_compute = compute_block;
    assembly.user_context = h;
    assembly.progress = NULL;
    assembly.factorization = hmat_factorization_none;
    int status = h->api.assemble_generic(h->matrix, &assembly);
    hmat_delete_compression(compression);
    h->context = NULL; /* the filler's context lives only for the assembly */
    if (status != 0) {
        h->api.destroy(h->matrix);
        free_trees(h);
        free(h);
        return NULL;
    }
    return h;
}

/* A copy of an assembled (unfactorized) matrix that shares its cluster tree: free it before
 * the original. NULL when hmat-oss fails. */
void *ddc2d_hmatrix_copy(void *handle) {
    ddc_hmatrix *h = handle;
    ddc_hmatrix *copy = calloc(1, sizeof *copy);
    if (!copy) return NULL;
    *copy = *h;
    copy->owns_tree = 0;
    copy->matrix = h->api.copy(h->matrix);
    if (!copy->matrix) {
        free(copy);
        return NULL;
    }
    return copy;
}

/* H-LU factorization in place; 0 on success. */
int ddc2d_hmatrix_factor(void *handle) {
    ddc_hmatrix *h = handle;
    hmat_factorization_context_t factorization;
    hmat_factorization_context_init(&factorization);
    factorization.factorization = hmat_factorization_lu;
    factorization.progress = NULL;
    return h->api.factorize_generic(h->matrix, &factorization);
}

/* b(order, nrhs) := A^-1 b with the factors (caller's numbering); 0 on success. */
int ddc2d_hmatrix_solve(void *handle, double *b, int nrhs) {
    ddc_hmatrix *h = handle;
    return h->api.solve_systems(h->matrix, b, nrhs);
}

/* y := A x (caller's numbering; x is reordered and restored in place; a rectangular
 * matrix: x of its columns, y of its rows); 0 on success. */
int ddc2d_hmatrix_multiply(void *handle, double *x, double *y) {
    ddc_hmatrix *h = handle;
    double one = 1.0, zero = 0.0;
    return h->api.gemv('N', &one, h->matrix, x, &zero, y, 1);
}

/* Reals stored, and reals a dense matrix of the same order would store. */
void ddc2d_hmatrix_sizes(void *handle, double *stored, double *dense) {
    ddc_hmatrix *h = handle;
    hmat_info_t info;
    memset(&info, 0, sizeof info);
    h->api.get_info(h->matrix, &info);
    *stored = (double)info.compressed_size;
    *dense = (double)info.uncompressed_size;
}

void ddc2d_hmatrix_free(void *handle) {
    ddc_hmatrix *h = handle;
    if (!h) return;
    h->api.destroy(h->matrix);
    if (h->owns_tree) free_trees(h);
    free(h);
}
