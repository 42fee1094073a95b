/* The adhesive passes over ranks (solver/adhesion.h: adhesion_ranks): the repulsive solve on the ranks, sums
 * in row order, reductions over the communicator and the rows just outside each rank's. */
#include "mpi/mpi_internal.h"

#include "indentmap/status.h"

static int solve_over_ranks(void *context, const double *gap0, double w, double *pressure, double *displacement,
                            im_solve_result *result)
{
    return im_mpi_solver_solve(context, gap0, IM_CONTROL_DISPLACEMENT, w, pressure, displacement, result);
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

void mpi_adhesion_ranks(im_mpi_solver *s, adhesion_ranks *out)
{
    *out = (adhesion_ranks){.context = s,
                            .solve = solve_over_ranks,
                            .convolve = convolve_over_ranks,
                            .sum = sum_over_ranks,
                            .combine = combine_over_ranks,
                            .outer_rows = outer_rows_over_ranks};
}
