/* An indentation history of the half-space over ranks (mpi.h): im_indentation_step's steps on the whole surface,
 * each rank holding its rows, by the serial step logic itself (solver/indentation_rows.h: plastic memory, load
 * control and its searches, adhesion), its solves and reductions over the ranks (adhesion.c: mpi_adhesion_ranks). */
#include "mpi/mpi_internal.h"
#include "core/args.h"
#include "core/team_size.h"
#include "solver/indentation_rows.h"

#include "indentmap/status.h"

#include <stdlib.h>

struct im_mpi_indentation {
    im_mpi_solver *solver;  /* the caller's */
    double solver_hardness; /* its own cap, restored when the run is freed (the steps set theirs) */
    adhesion_ranks ranks;   /* the steps' solves and reductions over the solver's ranks */
    im_indentation *steps;  /* the serial steps on this rank's rows */
    double *net_pressure;   /* this rank's rows: the last step's net pressure (tensile where negative) */
};

void im_mpi_indentation_free(im_mpi_indentation *run)
{
    if (!run)
        return;
    if (run->solver)
        run->solver->plan.options.hardness = run->solver_hardness;
    im_indentation_free(run->steps);
    free(run->net_pressure);
    free(run);
}

/* max h - min h over the whole surface (the bound of a load-controlled approach, as serially). */
static double height_range(const im_mpi_solver *s, const double *heights)
{
    const size_t n = (size_t)s->rows * s->nx;
    double extremes[2] = {-INFINITY, -INFINITY}; /* the largest height and minus the least */
    for (size_t i = 0; i < n; ++i) {
        extremes[0] = fmax(extremes[0], heights[i]);
        extremes[1] = fmax(extremes[1], -heights[i]);
    }
    MPI_Allreduce(MPI_IN_PLACE, extremes, 2, MPI_DOUBLE, MPI_MAX, s->comm);
    return extremes[0] + extremes[1];
}

/* The run's options: the solver's (tol, E*, hardness) with the adhesion's work, range, law and zone. */
static im_solver_options run_options(const im_mpi_solver *s, const im_solver_options *adhesion)
{
    im_solver_options o = s->plan.options;
    if (adhesion && adhesion->adhesion_work != 0) {
        o.adhesion_work = adhesion->adhesion_work;
        o.adhesion_range = adhesion->adhesion_range;
        o.adhesion_law = adhesion->adhesion_law;
        o.adhesion_zone = adhesion->adhesion_zone;
    }
    return o;
}

/* The serial steps on this rank's rows of g0. Collective. */
static int create_steps(im_mpi_indentation *run, const double *heights, const im_indenter *punch,
                        enum im_control control, double largest_target, const im_solver_options *adhesion)
{
    im_mpi_solver *s = run->solver;
    const size_t n = (size_t)s->rows * s->nx + 1; /* + 1: ranks without surface rows */
    double *gap0 = malloc(sizeof(double) * n);
    run->net_pressure = calloc(n, sizeof(double));
    int status = mpi_collective_status(s->comm, gap0 && run->net_pressure
                                                    ? IM_OK
                                                    : im_fail(IM_ENOMEM,
                                                              "distributed indentation %d x %d: rank "
                                                              "%d's rows",
                                                              s->nx, s->ny, s->rank));
    if (status == IM_OK)
        status = im_mpi_undeformed_gap(s, heights, punch, gap0);
    if (status == IM_OK) {
        mpi_adhesion_ranks(s, &run->ranks);
        const indentation_rows grid = {.nx = s->nx,
                                       .ny = s->ny,
                                       .rows = s->rows,
                                       .delta = s->delta,
                                       .gap0 = gap0,
                                       .height_range = height_range(s, heights),
                                       .plan = &s->plan,
                                       .ranks = &run->ranks};
        const im_solver_options options = run_options(s, adhesion);
        status = mpi_collective_status(s->comm, indentation_create_on_rows(&grid, punch, control, largest_target,
                                                                           &options, &run->steps));
    }
    free(gap0);
    return status;
}

int im_mpi_indentation_create(im_mpi_solver *s, const double *heights, const im_indenter *punch,
                              enum im_control control, double largest_target, const im_solver_options *adhesion,
                              im_mpi_indentation **out)
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
    int status = mpi_collective_status(s->comm, run ? IM_OK : im_fail(IM_ENOMEM, "distributed indentation"));
    if (status != IM_OK) {
        free(run);
        return status;
    }
    run->solver = s;
    run->solver_hardness = s->plan.options.hardness;
    status = create_steps(run, heights, punch, control, largest_target, adhesion);
    if (status != IM_OK) {
        im_mpi_indentation_free(run);
        return status;
    }
    *out = run;
    return IM_OK;
}

int im_mpi_indentation_step(im_mpi_indentation *run, double target, im_step_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    team_choose(); /* this rank's threads, for the step and the net pressures alike (core/team_size.c) */
    /* the steps' decisions are global (every rank the same); their allocations are made at creation */
    int status = mpi_collective_status(run->solver->comm, im_indentation_step(run->steps, target, out));
    const indentation_rows_state state = indentation_rows_state_of(run->steps);
    const size_t n = (size_t)run->solver->rows * run->solver->nx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        run->net_pressure[i] = adhesion_net_pressure(state.adhesion, i, state.pressure[i]);
    team_restore();
    return status;
}

const double *im_mpi_indentation_pressure(const im_mpi_indentation *run)
{
    ARG_REQUIRE_OR(run, "run", NULL);
    return run->net_pressure;
}

int im_mpi_indentation_gap(const im_mpi_indentation *run, double *gap)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(gap, "gap");
    const indentation_rows_state state = indentation_rows_state_of(run->steps);
    const size_t n = (size_t)run->solver->rows * run->solver->nx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        gap[i] = state.gap0[i] - state.approach + adhesion_net_displacement(state.adhesion, i, state.displacement[i]);
    return IM_OK;
}
