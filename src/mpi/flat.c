/* Nominally flat contact of a periodic cell over ranks: solver/flat.h's cell on a periodic
 * distributed solver, each rank holding its rows. */
#include "mpi/mpi_internal.h"
#include "core/args.h"
#include "solver/flat.h"

#include "indentmap/status.h"

#include <limits.h>
#include <stdlib.h>

struct im_mpi_flat_contact {
    im_mpi_solver *solver; /* the caller's */
    flat_cell cell;
};

static int solve_over_ranks(void *solver, const double *gap0, enum im_control control, double target,
                            double *pressure, double *displacement, im_solve_result *result)
{
    return im_mpi_solver_solve(solver, gap0, control, target, pressure, displacement, result);
}

/* IM_ENUMERIC naming the first non-finite height of the surface, on every rank; else the largest. */
static int highest_height(const im_mpi_solver *s, const double *heights, double *highest)
{
    const size_t n = (size_t)s->rows * s->nx;
    long bad = LONG_MAX;
    double largest = -INFINITY;
    for (size_t i = 0; i < n && bad == LONG_MAX; ++i) {
        if (!isfinite(heights[i]))
            bad = (long)((size_t)s->y0 * s->nx + i);
        largest = fmax(largest, heights[i]);
    }
    MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_LONG, MPI_MIN, s->comm);
    MPI_Allreduce(&largest, highest, 1, MPI_DOUBLE, MPI_MAX, s->comm);
    if (bad < LONG_MAX)
        return im_fail(IM_ENUMERIC, "surface height at patch (%ld, %ld) is not finite: expected finite heights",
                       bad % s->nx, bad / s->nx);
    return IM_OK;
}

void im_mpi_flat_contact_free(im_mpi_flat_contact *run)
{
    if (!run)
        return;
    flat_cell_free(&run->cell);
    free(run);
}

int im_mpi_flat_contact_create(im_mpi_solver *s, const double *heights, im_mpi_flat_contact **out)
{
    ARG_REQUIRE(out, "out");
    *out = NULL;
    ARG_REQUIRE(s, "solver");
    ARG_REQUIRE(heights, "heights");
    if (!s->plan.options.periodic) /* the same options on every rank: the same answer */
        return im_fail(IM_EINVAL, "distributed flat contact: the solver solves the half-space; expected one made "
                       "with periodic = 1 (a periodic cell)");
    im_mpi_flat_contact *run = calloc(1, sizeof *run);
    const size_t n = (size_t)s->rows * s->nx;
    int status = run && flat_cell_allocate(&run->cell, n) == IM_OK
                     ? IM_OK
                     : im_fail(IM_ENOMEM, "distributed flat contact %d x %d: rank %d's rows", s->nx, s->ny, s->rank);
    double highest;
    status = mpi_collective_status(s->comm, status);
    if (status == IM_OK)
        status = highest_height(s, heights, &highest);
    if (status != IM_OK) {
        im_mpi_flat_contact_free(run);
        return status;
    }
    run->solver = s;
    run->cell.solve = solve_over_ranks;
    run->cell.solver = s;
    run->cell.patches = (double)s->nx * s->ny;
    run->cell.cell_area = run->cell.patches * s->delta * s->delta;
    flat_gap(heights, n, highest, run->cell.gap0);
    run->cell.mean_gap0 = mpi_surface_mean(s, run->cell.gap0);
    *out = run;
    return IM_OK;
}

int im_mpi_flat_contact_solve(im_mpi_flat_contact *run, double mean_pressure, im_flat_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    return flat_solve_pressure(&run->cell, mean_pressure, out);
}

int im_mpi_flat_contact_solve_gap(im_mpi_flat_contact *run, double mean_gap, im_flat_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    return flat_solve_gap(&run->cell, mean_gap, out);
}

const double *im_mpi_flat_contact_pressure(const im_mpi_flat_contact *run)
{
    ARG_REQUIRE_OR(run, "run", NULL);
    return run->cell.pressure;
}
