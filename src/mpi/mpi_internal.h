/* Internal: the distributed solver's layout and the collective helpers of src/mpi/ (see mpi.h). */
#ifndef INDENTMAP_MPI_INTERNAL_H
#define INDENTMAP_MPI_INTERNAL_H

#include "core/summation.h"
#include "mpi/agree.h"
#include "indentmap/mpi.h"
#include "solver/adhesion.h"
#include "solver/engine.h"

#include <fftw3-mpi.h>
#include <math.h>
#include <stddef.h>

/* One FFTW-MPI r2c / c2r pair of an n1 x n0 real grid, in place, transposed between them: this rank
 * has `rows` of its real rows (stride 2 (n1 / 2 + 1)) and `columns` x n0 of its spectrum. */
typedef struct mpi_transform {
    double *buffer;
    fftw_plan forward, backward;
    ptrdiff_t rows, columns, column_length;
    size_t stride;
} mpi_transform;

/* The distributed solver is solver/pk.c's iteration over the MPI engine (engine_mpi.c): plan is
 * what pk.c reads (options, delta, K(0), no direct sums), and its engine's passes work on the fields
 * below. */
struct im_mpi_solver {
    im_solver_plan plan; /* engine = &solver_engine_mpi, mpi = this solver */
    MPI_Comm comm;
    int rank, ranks;
    int nx, ny, px, py;                 /* surface grid; transform grid 2nx x 2ny (periodic: nx x ny) */
    double delta, k0;                   /* patch side; K(0), the local (Winkler) stiffness (plan.kernel) */
    ptrdiff_t local_0_start;            /* this rank's first transform row */
    ptrdiff_t local_1_start;            /* its first column of the transposed spectrum */
    int y0, rows;                       /* its surface rows: the transform rows that lie on the surface */
    int *row_counts, *row_starts;       /* every rank's rows and y0, for the ordered sums */
    mpi_transform convolution;          /* of the transform grid: u = K p */
    double *spectrum;                   /* its columns x py: K's real spectrum divided by px py, transposed */
    double *direction, *gap, *response; /* rows * nx work arrays of the iteration (t, g, K t) */
    double *row_sums, *all_row_sums;    /* rows * MPI_SUMS_MAX and ny * MPI_SUMS_MAX */
    /* The preconditioner (pk.c; off with a hardness): M = 1 / the spectrum of K wrapped on the unpadded
     * nx x ny grid. On the half-space, by its own pair of that grid (unpadded), its rows cut in blocks
     * of the padded slabs' size so that each rank transforms its own surface rows (no moves); in the
     * periodic mode that grid is the convolution's and its pair serves (precondition_with). */
    mpi_transform unpadded;
    const mpi_transform *precondition_with;
    double *inverse_spectrum; /* precondition_with's columns x ny, transposed, divided by nx ny */
    double *preconditioned;   /* rows * nx: z = M g */
    /* The cascade (cascade.c): its first coarse level, a serial CPU plan (with its own coarser levels)
     * that every rank holds whole and solves alike (NULL: none), and that level's fields. */
    im_solver_plan *coarse;
    double *coarse_gap0, *coarse_pressure, *coarse_displacement;
    double *coarse_sums; /* 4 cx cy: the blocks' pair sums and counts, upper and lower rows */
};

#define MPI_SUMS_MAX 5

extern const solver_engine solver_engine_mpi;

/* u = K p on this rank's rows (the engine's convolution; im_mpi_convolve). */
void mpi_convolve(im_mpi_solver *solver, const double *pressure, double *displacement);

/* out = the inverse transform of (spectrum x the transform of in) by the pair t, in and out this
 * rank's surface rows (rows * nx; may alias); the transform's other rows and columns are zeros. */
void mpi_transform_apply(const im_mpi_solver *solver, const mpi_transform *t, const double *spectrum,
                         const double *in, double *out);

/* The cascade start over ranks (cascade.c): the coarse level when the options and the grid have one,
 * its start (as solver_cascade_start: the coarse iterations; pressure, this rank's rows, all zero when
 * the coarse grids found no contact), and its release. */
int mpi_cascade_create(im_mpi_solver *solver);
int mpi_cascade_start(im_mpi_solver *solver, const double *gap0, enum im_control control, double target,
                      double *pressure);
void mpi_cascade_free(im_mpi_solver *solver);

/* The adhesive passes of a state over this solver's ranks (adhesion.c): out refers to s. */
void mpi_adhesion_ranks(im_mpi_solver *s, adhesion_ranks *out);

/* The adhesion of a periodic cell's steps over the ranks (adhesion.c): its state on this rank's rows, whose passes
 * run over the solver's ranks, and the net pressure of the last step. Kept where it was made (the state refers
 * to ranks). */
typedef struct mpi_adhesion {
    adhesion_state *state; /* NULL: no adhesion */
    adhesion_ranks ranks;
    double *net_pressure;
} mpi_adhesion;

/* *out for options' law over s's ranks (a periodic cell's when s is periodic): IM_EINVAL for invalid options,
 * no work of adhesion, or the solver's hardness (adhesion with plasticity over ranks is not available; the same
 * options on every rank: the same answer); IM_ENOMEM on every rank when some rank's allocation failed. */
int mpi_adhesion_create(im_mpi_solver *s, const im_solver_options *options, mpi_adhesion *out);
void mpi_adhesion_free(mpi_adhesion *a);
/* The net pressure of a step whose repulsive pressure is pressure (this rank's rows), and its tensile force and
 * adhesive and repulsive patches into *out. Collective. */
void mpi_adhesion_values(mpi_adhesion *a, const im_mpi_solver *s, const double *pressure, im_step_result *out);

/* The global index (y nx + x) of the first patch, row-major, on the surface's outer row or column where
 * values (this rank's rows) is > 0, or LONG_MAX: the same on every rank. Collective. */
long mpi_first_on_edge(const im_mpi_solver *solver, const double *values);

/* The mean over the surface of values (this rank's rows), summed in row order: the same bits on every
 * rank for any rank count. */
double mpi_surface_mean(const im_mpi_solver *solver, const double *values);

/* totals[j] = sum over the surface rows, in row order and compensated, of the per-row sums this
 * rank left in solver->row_sums[r * k + j] (k <= MPI_SUMS_MAX quantities, r its local rows). */
void mpi_ordered_totals(const im_mpi_solver *solver, int k, double *totals);

/* Moves rows between decompositions: this rank has rows [have_y0, have_y0 + have_rows) of an
 * nx-wide grid (stride have_stride) and wants rows [want_y0, want_y0 + want_rows) (stride nx). */
int mpi_redistribute_rows(MPI_Comm comm, int nx, int have_y0, int have_rows, const double *have, size_t have_stride,
                          int want_y0, int want_rows, double *want);

#endif
