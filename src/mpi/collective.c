/* Collective helpers of the distributed solver: ordered sums, shared statuses, row moves. */
#include "mpi/mpi_internal.h"

#include "indentmap/status.h"

#include <stdlib.h>
#include <string.h>

void mpi_ordered_totals(const im_mpi_solver *s, int k, double *totals)
{
    /* counts and displacements in rows of k doubles: a derived type keeps them in rows */
    MPI_Datatype sums;
    MPI_Type_contiguous(k, MPI_DOUBLE, &sums);
    MPI_Type_commit(&sums);
    MPI_Allgatherv(s->row_sums, s->rows, sums, s->all_row_sums, s->row_counts, s->row_starts, sums, s->comm);
    MPI_Type_free(&sums);
    for (int j = 0; j < k; ++j) {
        compensated c = {0, 0};
        for (int r = 0; r < s->ny; ++r)
            compensated_add(&c, s->all_row_sums[(size_t)r * k + j]);
        totals[j] = compensated_total(&c);
    }
}

double mpi_surface_mean(const im_mpi_solver *s, const double *values)
{
    const int nx = s->nx;
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        compensated sum = {0, 0};
        for (int ix = 0; ix < nx; ++ix)
            compensated_add(&sum, values[(size_t)row * nx + ix]);
        s->row_sums[row] = compensated_total(&sum);
    }
    double total;
    mpi_ordered_totals(s, 1, &total);
    return total / ((double)nx * s->ny);
}

int mpi_exit_code(MPI_Comm comm, int code)
{
    int rank, worst;
    MPI_Comm_rank(comm, &rank);
    MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MAX, comm);
    return rank == 0 ? worst : 0;
}

int mpi_collective_status(MPI_Comm comm, int status)
{
    int rank, ranks;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks);
    int mine = status != 0 ? rank : ranks, first;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
    if (first == ranks)
        return 0;
    char message[512] = "";
    if (rank == first)
        snprintf(message, sizeof message, "%s", im_last_error());
    int shared = status;
    MPI_Bcast(&shared, 1, MPI_INT, first, comm);
    MPI_Bcast(message, sizeof message, MPI_CHAR, first, comm);
    if (rank == first)
        return status;
    return im_fail(shared, "rank %d: %s", first, message);
}

/* Rows [a0, a0 + an) and [b0, b0 + bn) overlap in [*start, *start + return value). */
static int overlap(int a0, int an, int b0, int bn, int *start)
{
    int lo = a0 > b0 ? a0 : b0, hi = a0 + an < b0 + bn ? a0 + an : b0 + bn;
    *start = lo;
    return hi > lo ? hi - lo : 0;
}

int mpi_redistribute_rows(MPI_Comm comm, int nx, int have_y0, int have_rows, const double *have, size_t have_stride,
                          int want_y0, int want_rows, double *want)
{
    int ranks;
    MPI_Comm_size(comm, &ranks);
    int mine[4] = {have_y0, have_rows, want_y0, want_rows};
    int *all = malloc(sizeof(int) * 4 * (size_t)ranks), *counts = malloc(sizeof(int) * 4 * (size_t)ranks);
    double *packed = malloc(sizeof(double) * ((size_t)have_rows * nx + 1));
    int status = all && counts && packed ? 0 : im_fail(IM_ENOMEM, "moving %d rows between ranks", have_rows);
    status = mpi_collective_status(comm, status);
    if (status == 0) {
        MPI_Allgather(mine, 4, MPI_INT, all, 4, MPI_INT, comm);
        int *send_n = counts, *send_at = counts + ranks, *recv_n = counts + 2 * ranks, *recv_at = counts + 3 * ranks;
        for (int r = 0; r < ranks; ++r) {
            int start;
            send_n[r] = overlap(have_y0, have_rows, all[4 * r + 2], all[4 * r + 3], &start);
            send_at[r] = start - have_y0;
            recv_n[r] = overlap(all[4 * r], all[4 * r + 1], want_y0, want_rows, &start);
            recv_at[r] = start - want_y0;
        }
        for (int r = 0; r < have_rows; ++r)
            memcpy(packed + (size_t)r * nx, have + (size_t)r * have_stride, sizeof(double) * nx);
        MPI_Datatype row;
        MPI_Type_contiguous(nx, MPI_DOUBLE, &row);
        MPI_Type_commit(&row);
        MPI_Alltoallv(packed, send_n, send_at, row, want, recv_n, recv_at, row, comm);
        MPI_Type_free(&row);
    }
    free(all);
    free(counts);
    free(packed);
    return status;
}
