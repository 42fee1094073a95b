/* The undeformed gap and the edge check over ranks (solver.h's definitions). */
#include "mpi/mpi_internal.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <limits.h>

int im_mpi_undeformed_gap(const im_mpi_solver *s, const double *heights, const im_indenter *punch, double *gap0)
{
    ARG_REQUIRE(s, "solver");
    int status = im_indenter_check(punch);
    if (status != IM_OK)
        return status; /* the same punch on every rank: the same answer */
    const int nx = s->nx;
    const double d = s->delta;
    double ax, ay;
    im_indenter_axis(punch, nx, s->ny, d, &ax, &ay);
    long bad = LONG_MAX;
    double lowest = INFINITY;
#pragma omp parallel for schedule(static) reduction(min : lowest, bad)
    for (int row = 0; row < s->rows; ++row)
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)row * nx + ix;
            if (!isfinite(heights[i]) && (long)((size_t)s->y0 * nx + i) < bad)
                bad = (long)((size_t)s->y0 * nx + i);
            gap0[i] = im_indenter_height(punch, (ix + 0.5) * d - ax, (s->y0 + row + 0.5) * d - ay) - heights[i];
            lowest = gap0[i] < lowest ? gap0[i] : lowest;
        }
    MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_LONG, MPI_MIN, s->comm);
    MPI_Allreduce(MPI_IN_PLACE, &lowest, 1, MPI_DOUBLE, MPI_MIN, s->comm);
    if (bad < LONG_MAX)
        return im_fail(IM_ENUMERIC, "surface height at patch (%ld, %ld) is not finite", bad % nx, bad / nx);
    if (!isfinite(lowest))
        return im_fail(IM_EINVAL, "the %s punch at (%g, %g) covers no patch of the %d x %d surface",
                       im_punch_name(punch->kind), ax, ay, nx, s->ny);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < (size_t)s->rows * nx; ++i)
        gap0[i] -= lowest;
    return IM_OK;
}

/* The first patch (row-major over the surface) with p > 0 on the outer row or column, or LONG_MAX. */
static long first_edge_contact(const im_mpi_solver *s, const double *p)
{
    const int nx = s->nx;
    for (int row = 0; row < s->rows; ++row) {
        int y = s->y0 + row, outer_row = y == 0 || y == s->ny - 1;
        for (int ix = 0; ix < nx; ++ix)
            if ((outer_row || ix == 0 || ix == nx - 1) && p[(size_t)row * nx + ix] > 0)
                return (long)y * nx + ix;
    }
    return LONG_MAX;
}

long mpi_first_on_edge(const im_mpi_solver *s, const double *values)
{
    long first = first_edge_contact(s, values);
    MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_LONG, MPI_MIN, s->comm);
    return first;
}

int im_mpi_check_edge(const im_mpi_solver *s, const double *pressure)
{
    ARG_REQUIRE(s, "solver");
    const long first = mpi_first_on_edge(s, pressure);
    if (first == LONG_MAX)
        return IM_OK;
    return im_fail(IM_EEDGE,
                   "contact reached the edge of the %d x %d surface at patch (%ld, %ld): the surface is too "
                   "small for this step",
                   s->nx, s->ny, first % s->nx, first / s->nx);
}
