/* The distributed solve: solver/pk.c's Polonsky-Keer iteration on the MPI engine (engine_mpi.c),
 * after this rank's inputs are checked (the first bad patch over all ranks named on every rank). */
#include "mpi/mpi_internal.h"
#include "core/args.h"
#include "core/team_size.h"

#include "indentmap/status.h"

#include <limits.h>
#include <string.h>

static int check_inputs(const im_mpi_solver *s, const double *gap0, enum im_control control, double target,
                        const double *p)
{
    if (control != IM_CONTROL_DISPLACEMENT && control != IM_CONTROL_LOAD)
        return im_fail(IM_EINVAL,
                       "im_mpi_solver_solve: control = %d: expected IM_CONTROL_DISPLACEMENT or IM_CONTROL_LOAD "
                       "(mean-gap control is im_mpi_flat_contact_solve_gap's, periodic)",
                       (int)control);
    if (!(isfinite(target) && target >= 0))
        return im_fail(IM_EINVAL, "%s = %g: expected a finite value >= 0",
                       control == IM_CONTROL_LOAD ? "load" : "approach", target);
    const size_t n = (size_t)s->rows * s->nx;
    long bad[2] = {LONG_MAX, LONG_MAX}; /* the first offending global index of gap0 and of p */
    for (size_t i = 0; i < n; ++i) {
        if ((isnan(gap0[i]) || gap0[i] < 0) && bad[0] == LONG_MAX)
            bad[0] = (long)((size_t)s->y0 * s->nx + i);
        if (!(isfinite(p[i]) && p[i] >= 0) && bad[1] == LONG_MAX)
            bad[1] = (long)((size_t)s->y0 * s->nx + i);
    }
    MPI_Allreduce(MPI_IN_PLACE, bad, 2, MPI_LONG, MPI_MIN, s->comm);
    if (bad[0] < LONG_MAX)
        return im_fail(IM_ENUMERIC, "undeformed gap at patch (%ld, %ld): expected >= 0 or +inf", bad[0] % s->nx,
                       bad[0] / s->nx);
    if (bad[1] < LONG_MAX)
        return im_fail(IM_EINVAL, "warm-start pressure at patch (%ld, %ld): expected finite and >= 0", bad[1] % s->nx,
                       bad[1] / s->nx);
    if (solver_periodic_approach_checked(&s->plan, control))
        return solver_check_periodic_mean_gap(mpi_surface_mean(s, gap0), target);
    return IM_OK;
}

int im_mpi_solver_solve(im_mpi_solver *s, const double *gap0, enum im_control control, double target,
                        double *pressure, double *displacement, im_solve_result *result)
{
    ARG_REQUIRE(s, "solver");
    im_solve_result res = {0};
    double start = MPI_Wtime();
    int status = check_inputs(s, gap0, control, target, pressure);
    if (status != IM_OK)
        return status;
    pk_run r = solver_pk_run(&s->plan, gap0, control, target, pressure, displacement);
    if (target == 0) { /* no approach or no load: no contact */
        memset(pressure, 0, sizeof(double) * (size_t)s->rows * s->nx);
        memset(displacement, 0, sizeof(double) * (size_t)s->rows * s->nx);
    } else {
        team_choose(); /* this rank's threads: those the other processes leave free, as a serial solve's */
        if (s->coarse && !s->plan.engine->any_positive(&r))
            res.coarse_iterations = mpi_cascade_start(s, gap0, control, target, pressure);
        status = solver_pk_solve(&r, &res);
        team_restore();
    }
    res.convolutions = r.convolutions;
    res.seconds = MPI_Wtime() - start;
    if (result)
        *result = res;
    return status;
}
