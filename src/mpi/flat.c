/* Nominally flat contact of a periodic cell over ranks: solver/flat.h's cell on a periodic
 * distributed solver, each rank holding its rows; and its history steps with plastic memory or with
 * adhesion (solver/adhesion.c's passes over the ranks), as im_indentation_step takes them on a periodic
 * cell under a rigid flat (indentation.c). */
#include "mpi/mpi_internal.h"
#include "core/args.h"
#include "solver/flat.h"
#include "solver/search.h"

#include "indentmap/status.h"

#include <limits.h>
#include <stdlib.h>

struct im_mpi_flat_contact {
    im_mpi_solver *solver; /* the caller's */
    flat_cell cell;        /* its gap0 includes the plastic depth */
    double *plastic;       /* this rank's rows: the plastic depth accumulated over the steps */
    double *terms;         /* this rank's rows: the per-patch terms of an ordered sum */
    double plastic_work;   /* H_p delta^2 times the sum of the depth increments */
    int steps;             /* taken so far */
    mpi_adhesion adhesion; /* with im_mpi_flat_contact_adhesion: its state over the ranks, the net pressure */
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
    free(run->plastic);
    free(run->terms);
    mpi_adhesion_free(&run->adhesion);
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
    int status = run && flat_cell_allocate(&run->cell, n) == IM_OK &&
                         (run->plastic = calloc(n + 1, sizeof(double))) &&
                         (run->terms = malloc(sizeof(double) * (n + 1)))
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

/* IM_EINVAL for a single (repulsive) solve of an adhesive cell. */
static int check_repulsive(const im_mpi_flat_contact *run)
{
    return run->adhesion.state
               ? im_fail(IM_EINVAL, "an adhesive cell is solved in steps (im_mpi_flat_contact_step): a "
                                    "single solve is the repulsive problem")
               : IM_OK;
}

int im_mpi_flat_contact_solve(im_mpi_flat_contact *run, double mean_pressure, im_flat_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    int status = check_repulsive(run);
    return status == IM_OK ? flat_solve_pressure(&run->cell, mean_pressure, out) : status;
}

int im_mpi_flat_contact_solve_gap(im_mpi_flat_contact *run, double mean_gap, im_flat_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    int status = check_repulsive(run);
    return status == IM_OK ? flat_solve_gap(&run->cell, mean_gap, out) : status;
}

int im_mpi_flat_contact_adhesion(im_mpi_flat_contact *run, const im_solver_options *options)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(options, "options");
    if (run->adhesion.state || run->steps > 0)
        return im_fail(IM_EINVAL, "adhesion: expected once, before the cell's first step (%d taken)", run->steps);
    return mpi_adhesion_create(run->solver, options, &run->adhesion);
}

const double *im_mpi_flat_contact_pressure(const im_mpi_flat_contact *run)
{
    ARG_REQUIRE_OR(run, "run", NULL);
    return run->adhesion.state ? run->adhesion.net_pressure : run->cell.pressure;
}

int im_mpi_flat_contact_gap(const im_mpi_flat_contact *run, double *gap)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(gap, "gap");
    const flat_cell *c = &run->cell;
    const size_t n = (size_t)run->solver->rows * run->solver->nx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        gap[i] = c->gap0[i] - c->approach + adhesion_net_displacement(run->adhesion.state, i, c->displacement[i]);
    return IM_OK;
}

/* The sum over the cell of run->terms, in row order: the same bits for any rank count. */
static double ordered_sum(const im_mpi_flat_contact *run)
{
    const im_mpi_solver *s = run->solver;
    return mpi_surface_mean(s, run->terms) * ((double)s->nx * s->ny);
}

/* Plastic memory (indentation.c: accumulate_plastic_flow): the overlap of every patch at the cap is
 * added to its plastic depth and its undeformed gap; returns the patches at the cap. */
static long plastic_flow(im_mpi_flat_contact *run)
{
    flat_cell *c = &run->cell;
    const double cap = run->solver->plan.options.hardness;
    const size_t n = (size_t)run->solver->rows * run->solver->nx;
    long yielding = 0;
#pragma omp parallel for schedule(static) reduction(+ : yielding)
    for (size_t i = 0; i < n; ++i) {
        const double flow = c->pressure[i] >= cap ? -(c->gap0[i] - c->approach + c->displacement[i]) : 0.0;
        yielding += c->pressure[i] >= cap;
        run->terms[i] = flow > 0 ? flow : 0.0;
        run->plastic[i] += run->terms[i];
        c->gap0[i] += run->terms[i];
    }
    MPI_Allreduce(MPI_IN_PLACE, &yielding, 1, MPI_LONG, MPI_SUM, run->solver->comm);
    const double d = run->solver->delta;
    run->plastic_work += cap * d * d * ordered_sum(run);
    c->mean_gap0 = mpi_surface_mean(run->solver, c->gap0);
    return yielding;
}

/* The largest plastic depth and the least undeformed gap over the cell (where the flat, withdrawn, touches). */
static void plastic_extremes(const im_mpi_flat_contact *run, double *deepest, double *touch)
{
    const size_t n = (size_t)run->solver->rows * run->solver->nx;
    double extremes[2] = {0, INFINITY};
    for (size_t i = 0; i < n; ++i) {
        extremes[0] = fmax(extremes[0], run->plastic[i]);
        extremes[1] = fmin(extremes[1], run->cell.gap0[i]);
    }
    MPI_Allreduce(MPI_IN_PLACE, &extremes[0], 1, MPI_DOUBLE, MPI_MAX, run->solver->comm);
    MPI_Allreduce(MPI_IN_PLACE, &extremes[1], 1, MPI_DOUBLE, MPI_MIN, run->solver->comm);
    *deepest = extremes[0];
    *touch = extremes[1];
}

/* Persson's u-bar: the mean over the cell of max(g0 - w + u, 0). */
static double mean_open_gap(im_mpi_flat_contact *run)
{
    const flat_cell *c = &run->cell;
    const size_t n = (size_t)run->solver->rows * run->solver->nx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        run->terms[i] = fmax(
            c->gap0[i] - c->approach + adhesion_net_displacement(run->adhesion.state, i, c->displacement[i]), 0.0);
    return mpi_surface_mean(run->solver, run->terms);
}

/* IM_EINVAL, as im_indentation_step, for a target this cell's steps do not take. */
static int check_step(const im_mpi_flat_contact *run, enum im_control control, double target)
{
    const im_mpi_solver *s = run->solver;
    const double cap = s->plan.options.hardness;
    if (control != IM_CONTROL_LOAD && control != IM_CONTROL_MEAN_GAP)
        return im_fail(IM_EINVAL, "periodic step: control %d: expected IM_CONTROL_LOAD or IM_CONTROL_MEAN_GAP",
                       (int)control);
    if (run->adhesion.state && control != IM_CONTROL_MEAN_GAP)
        return im_fail(IM_EINVAL,
                       "load %g on an adhesive cell: expected IM_CONTROL_MEAN_GAP (adhesion under load "
                       "control is not available over ranks: im_indentation_step's, serial)",
                       target);
    if (!(isfinite(target) && (control == IM_CONTROL_LOAD ? target >= 0 : target > 0)))
        return im_fail(IM_EINVAL, "%s = %g: expected a finite value %s",
                       control == IM_CONTROL_LOAD ? "load" : "mean gap", target,
                       control == IM_CONTROL_LOAD ? ">= 0" : "> 0 (at 0 the cell is in full contact)");
    const double capacity = cap * s->nx * s->ny * s->delta * s->delta;
    if (cap > 0 && target >= capacity)
        return im_fail(IM_EINVAL,
                       "load %g: a periodic cell at hardness %g carries less than H_p A0 = %g (at that "
                       "load every patch would have yielded: full contact, no approach to find)",
                       target, cap, capacity);
    return IM_OK;
}

static int displacement_solve(void *context, double w, im_solve_result *s)
{
    flat_cell *c = &((im_mpi_flat_contact *)context)->cell;
    return c->solve(c->solver, c->gap0, IM_CONTROL_DISPLACEMENT, w, c->pressure, c->displacement, s);
}

static double negative_mean_gap(void *context, const im_solve_result *s)
{
    im_mpi_flat_contact *run = context;
    run->cell.approach = s->approach;
    return -mean_open_gap(run);
}

/* The approach of mean gap target, searched under a hardness as im_indentation_step searches it (search.h). */
static int solve_at_mean_gap(im_mpi_flat_contact *run, double target, im_solve_result *out)
{
    approach_search search = {.context = run,
                              .target = -target,
                              .tol = run->solver->plan.options.tol,
                              .measure = negative_mean_gap,
                              .solve = displacement_solve};
    /* mean u = 0: the approach mean g0 - target gives the mean gap; above mean g0 the flat is clear */
    return search_mean_gap(&search, run->cell.mean_gap0 - target, run->solver->plan.options.hardness, out);
}

int im_mpi_flat_contact_step(im_mpi_flat_contact *run, enum im_control control, double target, im_step_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    int status = check_step(run, control, target);
    if (status != IM_OK)
        return status;
    flat_cell *c = &run->cell;
    im_solve_result solve = {0};
    ++run->steps;
    if (run->adhesion.state) /* mean u = 0 with the zone's lift too: the approach gives the mean gap */
        status = adhesion_solve(run->adhesion.state, &run->solver->plan, c->gap0, c->mean_gap0 - target, c->pressure,
                                c->displacement, &solve);
    else if (control == IM_CONTROL_MEAN_GAP)
        status = solve_at_mean_gap(run, target, &solve);
    else
        status = c->solve(c->solver, c->gap0, IM_CONTROL_LOAD, target, c->pressure, c->displacement, &solve);
    double deepest;
    if (control == IM_CONTROL_LOAD && status == IM_OK && target == 0) /* N = 0 up to where the flat touches */
        plastic_extremes(run, &deepest, &solve.approach);
    c->approach = solve.approach;
    const im_mpi_solver *s = run->solver;
    long yielding = status == IM_OK && s->plan.options.hardness > 0 ? plastic_flow(run) : 0;
    const double d2 = s->delta * s->delta;
    step_result_from_solve(&solve, (double)s->nx * s->ny * d2, d2, 1, out);
    out->plastic_work = run->plastic_work;
    out->mean_gap = mean_open_gap(run);
    plastic_extremes(run, &out->plastic_depth, &out->residual_approach);
    out->yielding_patches = yielding;
    if (run->adhesion.state)
        mpi_adhesion_values(&run->adhesion, s, c->pressure, out);
    return status;
}
