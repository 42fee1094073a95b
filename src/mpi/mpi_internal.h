/* Internal: the distributed solver's layout and the collective helpers of src/mpi/ (see mpi.h). */
#ifndef INDENTMAP_MPI_INTERNAL_H
#define INDENTMAP_MPI_INTERNAL_H

#include "core/summation.h"
#include "indentmap/mpi.h"

#include <fftw3-mpi.h>
#include <math.h>
#include <stddef.h>

struct im_mpi_solver {
    MPI_Comm comm;
    int rank, ranks;
    int nx, ny, px, py;           /* surface grid; padded grid 2nx x 2ny */
    double delta, k0;             /* patch side; K(0), the local (Winkler) stiffness */
    im_solver_options options;
    ptrdiff_t local_n0, local_0_start; /* this rank's padded rows */
    ptrdiff_t local_n1, local_1_start; /* its columns of the transposed spectrum */
    int y0, rows;                 /* its surface rows: the padded rows that lie on the surface */
    int *row_counts, *row_starts; /* every rank's rows and y0, for the ordered sums */
    double *buffer;               /* local_n0 padded rows of stride px + 2 (in-place r2c/c2r) */
    double *spectrum;             /* local_n1 x py: K's real spectrum divided by px py, transposed */
    fftw_plan forward, backward;
    double *direction, *gap, *response; /* rows * nx work arrays of the iteration (t, g, K t) */
    double *row_sums, *all_row_sums;    /* rows * MPI_SUMS_MAX and ny * MPI_SUMS_MAX */
};

#define MPI_SUMS_MAX 5

/* totals[j] = sum over the surface rows, in row order and compensated, of the per-row sums this
 * rank left in solver->row_sums[r * k + j] (k <= MPI_SUMS_MAX quantities, r its local rows). */
void mpi_ordered_totals(const im_mpi_solver *solver, int k, double *totals);

/* The same status on every rank: the lowest failing rank's, with its message carried to the
 * others as "rank K: ...". */
int mpi_collective_status(MPI_Comm comm, int status);

/* Moves rows between decompositions: this rank has rows [have_y0, have_y0 + have_rows) of an
 * nx-wide grid (stride have_stride) and wants rows [want_y0, want_y0 + want_rows) (stride nx). */
int mpi_redistribute_rows(MPI_Comm comm, int nx, int have_y0, int have_rows, const double *have, size_t have_stride,
                          int want_y0, int want_rows, double *want);

#endif
