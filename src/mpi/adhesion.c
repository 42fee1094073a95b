/* The adhesive passes over ranks (solver/adhesion.h: adhesion_ranks): the repulsive solve on the ranks, sums
 * in row order, reductions over the communicator, the rows just outside each rank's and the edge check (also
 * an indentation's steps over ranks, indentation.c); and the state of a periodic cell's adhesive steps (flat.c). */
#include "mpi/mpi_internal.h"

#include "indentmap/status.h"

#include <stdlib.h>

static int solve_over_ranks(void *context, const double *gap0, enum im_control control, double target,
                            double *pressure, double *displacement, im_solve_result *result)
{
    return im_mpi_solver_solve(context, gap0, control, target, pressure, displacement, result);
}

static void convolve_over_ranks(void *context, const double *in, double *out) { mpi_convolve(context, in, out); }

static double sum_over_ranks(void *context, const double *field)
{
    const im_mpi_solver *s = context;
    return mpi_surface_mean(s, field) * ((double)s->nx * s->ny);
}

static void combine_over_ranks(void *context, double *values, int count, enum adhesion_combine how)
{
    const im_mpi_solver *s = context;
    MPI_Op op = how == ADHESION_MIN ? MPI_MIN : how == ADHESION_MAX ? MPI_MAX : MPI_SUM;
    MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, op, s->comm);
}

/* The rank holding surface row y (wrapped around a periodic cell), MPI_PROC_NULL off the grid. */
static int holder_of(const im_mpi_solver *s, int y)
{
    if (s->plan.options.periodic)
        y = (y + s->ny) % s->ny;
    for (int r = 0; r < s->ranks; ++r)
        if (y >= s->row_starts[r] && y < s->row_starts[r] + s->row_counts[r])
            return r;
    return MPI_PROC_NULL;
}

enum { TAG_ABOVE = 271, TAG_BELOW };

/* A rank's first row is the row below the rank holding the row above it, and its last row the row above the
 * one holding the row below: each rank sends both and receives both (nothing from off the grid: NaN stays). */
static void outer_rows_over_ranks(void *context, const double *field, double *above, double *below)
{
    const im_mpi_solver *s = context;
    for (int x = 0; x < s->nx; ++x)
        above[x] = below[x] = NAN;
    if (s->rows == 0)
        return;
    const int up = holder_of(s, s->y0 - 1), down = holder_of(s, s->y0 + s->rows);
    const double *last = field + (size_t)(s->rows - 1) * s->nx;
    MPI_Sendrecv(field, s->nx, MPI_DOUBLE, up, TAG_BELOW, below, s->nx, MPI_DOUBLE, down, TAG_BELOW, s->comm,
                 MPI_STATUS_IGNORE);
    MPI_Sendrecv(last, s->nx, MPI_DOUBLE, down, TAG_ABOVE, above, s->nx, MPI_DOUBLE, up, TAG_ABOVE, s->comm,
                 MPI_STATUS_IGNORE);
}

static long first_on_edge_over_ranks(void *context, const double *values)
{
    return mpi_first_on_edge(context, values);
}

void mpi_adhesion_ranks(im_mpi_solver *s, adhesion_ranks *out)
{
    *out = (adhesion_ranks){.context = s,
                            .solve = solve_over_ranks,
                            .convolve = convolve_over_ranks,
                            .sum = sum_over_ranks,
                            .combine = combine_over_ranks,
                            .outer_rows = outer_rows_over_ranks,
                            .first_on_edge = first_on_edge_over_ranks};
}

/* IM_EINVAL for invalid options, no work, or the solver's hardness. */
static int check_adhesion(const im_mpi_solver *s, const im_solver_options *options)
{
    int status = im_solver_options_check(options);
    if (status != IM_OK)
        return status;
    if (!(options->adhesion_work > 0))
        return im_fail(IM_EINVAL, "adhesion work = %g: expected a work of adhesion > 0", options->adhesion_work);
    if (s->plan.options.hardness > 0)
        return im_fail(IM_EINVAL,
                       "adhesion work = %g with the solver's hardness %g: adhesion with plasticity is not "
                       "available over ranks",
                       options->adhesion_work, s->plan.options.hardness);
    return IM_OK;
}

int mpi_adhesion_create(im_mpi_solver *s, const im_solver_options *options, mpi_adhesion *out)
{
    *out = (mpi_adhesion){0};
    int status = check_adhesion(s, options);
    if (status != IM_OK)
        return status;
    im_solver_options solved; /* a widened zone's law (solver.h: im_adhesion_solved_law) */
    status = im_adhesion_solved_law(options, s->delta, &solved, NULL);
    const size_t n = (size_t)s->rows * s->nx;
    if (status == IM_OK)
        status = adhesion_create(s->nx, s->rows, s->plan.options.periodic, &solved, &out->state);
    if (status == IM_OK && !(out->net_pressure = calloc(n + 1, sizeof(double))))
        status = im_fail(IM_ENOMEM, "adhesion over ranks %d x %d: rank %d's net pressure", s->nx, s->ny, s->rank);
    status = mpi_collective_status(s->comm, status);
    if (status != IM_OK) {
        mpi_adhesion_free(out);
        return status;
    }
    mpi_adhesion_ranks(s, &out->ranks);
    adhesion_over_ranks(out->state, &out->ranks);
    return IM_OK;
}

void mpi_adhesion_free(mpi_adhesion *a)
{
    adhesion_free(a->state);
    free(a->net_pressure);
    *a = (mpi_adhesion){0};
}

void mpi_adhesion_values(mpi_adhesion *a, const im_mpi_solver *s, const double *pressure, im_step_result *out)
{
    const size_t n = (size_t)s->rows * s->nx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        a->net_pressure[i] = adhesion_net_pressure(a->state, i, pressure[i]);
    adhesion_split(a->state, pressure, s->delta, &out->tensile_force, &out->adhesive_patches,
                   &out->repulsive_patches);
}
