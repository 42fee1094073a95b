/* An indentation history of the half-space over ranks (mpi.h): im_indentation_step's displacement-controlled
 * steps on the whole surface, each rank holding its rows, the adhesive ones by solver/adhesion.c's passes over
 * the ranks (adhesion.c: mpi_adhesion). */
#include "mpi/mpi_internal.h"
#include "core/args.h"
#include "solver/flat.h"

#include "indentmap/status.h"

#include <limits.h>
#include <stdlib.h>

struct im_mpi_indentation {
    im_mpi_solver *solver; /* the caller's */
    im_indenter punch;
    double *gap0, *pressure, *displacement; /* this rank's rows: pressure and displacement the repulsive parts */
    double approach;                        /* the last step's */
    mpi_adhesion adhesion;                  /* state NULL: a repulsive history */
};

void im_mpi_indentation_free(im_mpi_indentation *run)
{
    if (!run)
        return;
    free(run->gap0);
    free(run->pressure);
    free(run->displacement);
    mpi_adhesion_free(&run->adhesion);
    free(run);
}

static int allocate(const im_mpi_solver *s, im_mpi_indentation *run)
{
    const size_t n = (size_t)s->rows * s->nx + 1; /* + 1: ranks without surface rows */
    run->gap0 = malloc(sizeof(double) * n);
    run->pressure = calloc(n, sizeof(double));
    run->displacement = calloc(n, sizeof(double));
    const int ok = run->gap0 && run->pressure && run->displacement;
    return ok ? IM_OK : im_fail(IM_ENOMEM, "distributed indentation %d x %d: rank %d's rows", s->nx, s->ny, s->rank);
}

int im_mpi_indentation_create(im_mpi_solver *s, const double *heights, const im_indenter *punch,
                              const im_solver_options *adhesion, im_mpi_indentation **out)
{
    ARG_REQUIRE(out, "out");
    *out = NULL;
    ARG_REQUIRE(s, "solver");
    ARG_REQUIRE(heights, "heights");
    ARG_REQUIRE(punch, "punch");
    if (s->plan.options.periodic) /* the same options on every rank: the same answer */
        return im_fail(IM_EINVAL, "distributed indentation: the solver solves a periodic cell; expected one made "
                                  "with periodic = 0 (the half-space; a cell's steps: im_mpi_flat_contact_step)");
    im_mpi_indentation *run = calloc(1, sizeof *run);
    int status = run ? allocate(s, run) : im_fail(IM_ENOMEM, "distributed indentation");
    status = mpi_collective_status(s->comm, status);
    if (status == IM_OK)
        status = im_mpi_undeformed_gap(s, heights, punch, run->gap0);
    if (status == IM_OK && adhesion && adhesion->adhesion_work != 0)
        status = mpi_adhesion_create(s, adhesion, &run->adhesion);
    if (status != IM_OK) {
        im_mpi_indentation_free(run);
        return status;
    }
    run->solver = s;
    run->punch = *punch;
    *out = run;
    return IM_OK;
}

/* IM_EEDGE when the adhesive zone reaches the surface's outer row or column (indentation.c: check_zone). */
static int check_zone(const im_mpi_indentation *run)
{
    const im_mpi_solver *s = run->solver;
    const long first = mpi_first_on_edge(s, run->adhesion.state->share);
    if (first == LONG_MAX)
        return IM_OK;
    return im_fail(IM_EEDGE,
                   "the adhesive zone reached the edge of the surface at patch (%ld, %ld) (approach %g): the "
                   "surface is too small for this step",
                   first % s->nx, first / s->nx, run->approach);
}

static int solve_step(im_mpi_indentation *run, double approach, im_solve_result *solve)
{
    im_mpi_solver *s = run->solver;
    if (run->adhesion.state)
        return adhesion_solve(run->adhesion.state, &s->plan, run->gap0, approach, run->pressure, run->displacement,
                              solve);
    return im_mpi_solver_solve(s, run->gap0, IM_CONTROL_DISPLACEMENT, approach, run->pressure, run->displacement,
                               solve);
}

/* *out from the step's solve, as indentation.c's fill_step on the half-space without plastic memory. */
static void fill_step(im_mpi_indentation *run, const im_solve_result *solve, im_step_result *out)
{
    const im_mpi_solver *s = run->solver;
    const double d2 = s->delta * s->delta;
    const double area = im_indenter_area_for_load(&run->punch, s->plan.options.e_star, solve->load);
    step_result_from_solve(solve, area, d2, 0, out);
    out->mean_gap = NAN;
    if (run->adhesion.state)
        mpi_adhesion_values(&run->adhesion, s, run->pressure, out);
}

int im_mpi_indentation_step(im_mpi_indentation *run, double approach, im_step_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    const int adhesive = run->adhesion.state != NULL;
    if (!(isfinite(approach) && (adhesive || approach >= 0)))
        return im_fail(IM_EINVAL, "approach = %g: expected a finite value%s", approach,
                       adhesive ? "" : " >= 0 (a negative one only with adhesion)");
    im_solve_result solve = {0};
    int status = solve_step(run, approach, &solve);
    run->approach = solve.approach;
    if (status == IM_OK)
        status = im_mpi_check_edge(run->solver, run->pressure);
    if (status == IM_OK && adhesive)
        status = check_zone(run);
    fill_step(run, &solve, out);
    return status;
}

const double *im_mpi_indentation_pressure(const im_mpi_indentation *run)
{
    ARG_REQUIRE_OR(run, "run", NULL);
    return run->adhesion.state ? run->adhesion.net_pressure : run->pressure;
}

int im_mpi_indentation_gap(const im_mpi_indentation *run, double *gap)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(gap, "gap");
    const size_t n = (size_t)run->solver->rows * run->solver->nx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        gap[i] = run->gap0[i] - run->approach +
                 adhesion_net_displacement(run->adhesion.state, i, run->displacement[i]);
    return IM_OK;
}
