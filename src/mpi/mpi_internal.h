/* Internal: the distributed solver's layout and the collective helpers of src/mpi/ (see mpi.h). */
#ifndef INDENTMAP_MPI_INTERNAL_H
#define INDENTMAP_MPI_INTERNAL_H

#include "core/summation.h"
#include "mpi/agree.h"
#include "indentmap/mpi.h"
#include "solver/engine.h"

#include <fftw3-mpi.h>
#include <math.h>
#include <stddef.h>

/* The distributed solver is solver/pk.c's iteration over the MPI engine (engine_mpi.c): plan is
 * what pk.c reads (options, delta, K(0), no direct sums), and its engine's passes work on the fields
 * below. */
struct im_mpi_solver {
    im_solver_plan plan;          /* engine = &solver_engine_mpi, mpi = this solver */
    MPI_Comm comm;
    int rank, ranks;
    int nx, ny, px, py;           /* surface grid; padded grid 2nx x 2ny */
    double delta, k0;             /* patch side; K(0), the local (Winkler) stiffness (plan.kernel) */
    ptrdiff_t local_n0, local_0_start; /* this rank's padded rows */
    ptrdiff_t local_n1, local_1_start; /* its columns of the transposed spectrum */
    int y0, rows;                 /* its surface rows: the padded rows that lie on the surface */
    int *row_counts, *row_starts; /* every rank's rows and y0, for the ordered sums */
    double *buffer;               /* local_n0 padded rows of stride px + 2 (in-place r2c/c2r) */
    double *spectrum;             /* local_n1 x py: K's real spectrum divided by px py, transposed */
    fftw_plan forward, backward;
    double *direction, *gap, *response; /* rows * nx work arrays of the iteration (t, g, K t) */
    double *row_sums, *all_row_sums;    /* rows * MPI_SUMS_MAX and ny * MPI_SUMS_MAX */
    /* The preconditioner (pk.c; off with a hardness): M = 1 / the spectrum of K wrapped on the unpadded
     * nx x ny grid, by FFTW-MPI's r2c / c2r pair of that grid, its rows cut in blocks of the padded
     * slabs' size so that each rank transforms its own surface rows (no moves). */
    double *precondition_buffer;  /* rows padded rows of stride 2 (nx / 2 + 1) (in place) */
    double *inverse_spectrum;     /* precondition_columns x ny, transposed, divided by nx ny */
    ptrdiff_t precondition_columns;
    fftw_plan precondition_forward, precondition_backward;
    double *preconditioned;       /* rows * nx: z = M g */
};

#define MPI_SUMS_MAX 5

extern const solver_engine solver_engine_mpi;

/* u = K p on this rank's rows (the engine's convolution; im_mpi_convolve). */
void mpi_convolve(im_mpi_solver *solver, const double *pressure, double *displacement);

/* totals[j] = sum over the surface rows, in row order and compensated, of the per-row sums this
 * rank left in solver->row_sums[r * k + j] (k <= MPI_SUMS_MAX quantities, r its local rows). */
void mpi_ordered_totals(const im_mpi_solver *solver, int k, double *totals);

/* Moves rows between decompositions: this rank has rows [have_y0, have_y0 + have_rows) of an
 * nx-wide grid (stride have_stride) and wants rows [want_y0, want_y0 + want_rows) (stride nx). */
int mpi_redistribute_rows(MPI_Comm comm, int nx, int have_y0, int have_rows, const double *have, size_t have_stride,
                          int want_y0, int want_rows, double *want);

#endif
