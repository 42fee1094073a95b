/* A downsampled map of a distributed field, gathered on rank 0 (for rendering large grids). */
#include "mpi/mpi_internal.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <stdlib.h>

/* Per surface row, the sums of values over each block's columns: rows x block_columns. */
static void row_block_sums(const im_mpi_solver *s, const double *values, int factor, int block_columns, double *out)
{
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row)
        for (int b = 0; b < block_columns; ++b) {
            int end = (b + 1) * factor < s->nx ? (b + 1) * factor : s->nx;
            double sum = 0;
            for (int ix = b * factor; ix < end; ++ix)
                sum += values[(size_t)row * s->nx + ix];
            out[(size_t)row * block_columns + b] = sum;
        }
}

/* Rank 0: the map from every row's block sums, added over each block's rows in row order. */
static void add_block_rows(const im_mpi_solver *s, const double *all, int factor, im_field *map)
{
#pragma omp parallel for schedule(static)
    for (int by = 0; by < map->ny; ++by)
        for (int bx = 0; bx < map->nx; ++bx) {
            int end = (by + 1) * factor < s->ny ? (by + 1) * factor : s->ny;
            double sum = 0;
            for (int y = by * factor; y < end; ++y)
                sum += all[(size_t)y * map->nx + bx];
            map->data[(size_t)by * map->nx + bx] = sum;
        }
}

int im_mpi_gather_map(const im_mpi_solver *s, const double *values, int factor, im_field **out)
{
    ARG_REQUIRE(s, "solver");
    *out = NULL;
    if (factor < 1)
        return im_fail(IM_EINVAL, "map factor %d: expected >= 1", factor);
    const int block_columns = (s->nx + factor - 1) / factor, block_rows = (s->ny + factor - 1) / factor;
    double *mine = malloc(sizeof(double) * ((size_t)s->rows * block_columns + 1)), *all = NULL;
    im_field *map = NULL;
    int status = mine ? IM_OK : im_fail(IM_ENOMEM, "map of rank %d's rows", s->rank);
    if (status == IM_OK && s->rank == 0) {
        all = malloc(sizeof(double) * (size_t)s->ny * block_columns);
        status = all ? im_field_create(block_columns, block_rows, s->delta * factor, &map)
                     : im_fail(IM_ENOMEM, "map: %d x %d row sums on rank 0", block_columns, s->ny);
    }
    status = mpi_collective_status(s->comm, status);
    if (status == IM_OK) {
        row_block_sums(s, values, factor, block_columns, mine);
        MPI_Datatype row;
        MPI_Type_contiguous(block_columns, MPI_DOUBLE, &row);
        MPI_Type_commit(&row);
        MPI_Gatherv(mine, s->rows, row, all, s->row_counts, s->row_starts, row, 0, s->comm);
        MPI_Type_free(&row);
        if (s->rank == 0)
            add_block_rows(s, all, factor, map);
    }
    free(mine);
    free(all);
    if (status != IM_OK) {
        im_field_free(map);
        return status;
    }
    *out = map;
    return IM_OK;
}
