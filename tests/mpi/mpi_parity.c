/* MPI parity over every solve kind (issue 33), run under mpirun with 1, 2, 3 and 4 ranks
 * (tests/mpi/mpi_parity.sh): each kind is a history of warm-started steps on one rough surface, its first
 * step cold (the cascade start where the serial plan has one), solved over the ranks and, on rank 0, by the
 * serial solver a user runs for it. Every step must take the serial step's fine and coarse iterations,
 * reach its load and approach to 1e-10 relative and its contact set patch by patch, and, with a hardness,
 * its plastic depth: the cap's memory (the depth kept across steps, the unloading step solved on the
 * flattened surface).
 *
 * Kinds: the half-space cone, sphere and flat punch under displacement and load control, without and with
 * the hardness cap (loading, deeper, unloading); the periodic cell under a mean pressure and a mean gap,
 * without and with the cap; the adhesive periodic cell under a mean gap. The serial reference is
 * im_indentation_step (crop off), except for the half-space under load control with a cap: over ranks that
 * is Polonsky-Keer's load control with the cap (docs/mpi.md), serially im_solver_solve, each with the
 * plastic memory a distributed caller keeps (mpi.h: g0 plus the plastic depth). Not here: adhesive
 * half-space indentation and the adhesive cell under load control (not distributed yet).
 *
 * Prints one line per step on rank 0, the values in hexadecimal: the script requires the same bytes for
 * every rank count. Usage: mpi_parity_check [SIDE] (the grid is SIDE x SIDE, 64 by default; the punches,
 * targets and surface scale with it). A failed check aborts all ranks. */
#include "mpi_check.h"

#include "indentmap/mpi.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_STEPS = 4 };

enum kind { HALF_SPACE, PERIODIC, ADHESIVE };

typedef struct history {
    const char *name;
    enum kind kind;
    im_indenter punch; /* the half-space's */
    enum im_control control;
    double hardness; /* the pressure cap H_p (0: none) */
    int steps;
    /* half-space: approaches in units of the grid side / 32, or the smooth loads there; periodic: mean
     * pressures p_m, or mean gaps as fractions of the undeformed cell's */
    double targets[MAX_STEPS];
} history;

static int side = 64;

static im_field *rough_surface(void)
{
    im_surface_params params = im_surface_params_default();
    params.nx = params.ny = side;
    params.lambda_r = side;
    params.seed = 33;
    im_field *surface;
    check_status(im_surface_generate(&params, &surface), "serial synthesis");
    return surface;
}

static im_solver_options options(const history *h)
{
    im_solver_options o = im_solver_options_default();
    o.crop = 0;
    o.tol = 1e-10;
    o.periodic = h->kind != HALF_SPACE;
    o.hardness = h->hardness;
    return o;
}

static im_solver_options adhesive_options(const history *h)
{
    im_solver_options o = options(h);
    o.adhesion_work = 0.004;
    o.adhesion_range = 0.1;
    return o;
}

static double undeformed_mean_gap(const im_field *surface)
{
    double highest = -INFINITY, sum = 0;
    for (size_t i = 0; i < im_field_count(surface); ++i)
        highest = fmax(highest, surface->data[i]);
    for (size_t i = 0; i < im_field_count(surface); ++i)
        sum += highest - surface->data[i];
    return sum / (double)im_field_count(surface);
}

/* Step k's target in the units of the solvers. */
static double target_of(const history *h, const im_field *surface, int k)
{
    const double t = h->targets[k];
    if (h->kind == HALF_SPACE) {
        const double w = t * side / 32.0;
        return h->control == IM_CONTROL_LOAD ? im_indenter_load(&h->punch, 1, w) : w;
    }
    return h->control == IM_CONTROL_LOAD ? t * side * side : t * undeformed_mean_gap(surface);
}

static double largest_target(const history *h, const im_field *surface)
{
    double largest = 0;
    for (int k = 0; k < h->steps; ++k)
        largest = fmax(largest, target_of(h, surface, k));
    return largest;
}

/* What one step gave, over ranks or serially; force (rank 0 only) the whole field of forces. */
typedef struct step_answer {
    im_step_result result;
    im_field *force;
} step_answer;

/* ---- the plastic memory a distributed half-space caller keeps (mpi.h: it passes g0 + depth) ----
 * Every patch at the cap flows down by its overlap -(g0 - w + u): the depth and g0 grow by it. */
static void keep_plastic_flow(size_t n, double cap, double approach, const double *p, const double *u, double *gap0,
                              double *depth, long *yielding)
{
    *yielding = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!(p[i] >= cap))
            continue;
        ++*yielding;
        const double flow = -(gap0[i] - approach + u[i]);
        if (flow > 0) {
            depth[i] += flow;
            gap0[i] += flow;
        }
    }
}

static double largest_of(const double *values, size_t n)
{
    double largest = 0;
    for (size_t i = 0; i < n; ++i)
        largest = fmax(largest, values[i]);
    return largest;
}

/* The half-space's step fields from a solve and the memory kept beside it. */
static void solve_to_step(const im_solve_result *s, long yielding, double deepest, im_step_result *out)
{
    memset(out, 0, sizeof *out);
    out->approach = s->approach;
    out->load = s->load;
    out->contact_patches = s->contact_patches;
    out->iterations = s->iterations;
    out->coarse_iterations = s->coarse_iterations;
    out->yielding_patches = yielding;
    out->plastic_depth = deepest;
}

/* ---- serial references, on rank 0 ---- */

/* im_indentation_step, the serial history `indent` takes. */
static void serial_indentation(const history *h, const im_field *surface, step_answer *answers)
{
    im_solver_options o = h->kind == ADHESIVE ? adhesive_options(h) : options(h);
    /* a periodic cell's flat covers it whole (corners side / sqrt 2 from the centre) */
    const im_indenter punch = h->kind == HALF_SPACE ? h->punch : im_indenter_flat(side);
    im_indentation *run;
    check_status(im_indentation_create(surface, &punch, h->control, largest_target(h, surface), &o, &run),
                 "serial indentation");
    for (int k = 0; k < h->steps; ++k) {
        check_status(im_indentation_step(run, target_of(h, surface, k), &answers[k].result), "serial step");
        check_status(im_indentation_fields(run, &answers[k].force, NULL, NULL), "serial force");
    }
    im_indentation_free(run);
}

/* im_solver_solve with the caller's memory: the serial form of the distributed half-space under load control
 * with a cap (gap0: the undeformed gap the ranks made, gathered). */
static void serial_capped_loads(const history *h, const im_field *surface, im_field *gap0, step_answer *answers)
{
    im_solver_options o = options(h);
    im_solver_plan *plan;
    check_status(im_solver_plan_create(side, side, 1.0, &o, &plan), "serial plan");
    const size_t n = im_field_count(gap0);
    double *pressure = calloc(n, sizeof(double)), *u = malloc(sizeof(double) * n), *depth = calloc(n, sizeof(double));
    for (int k = 0; k < h->steps; ++k) {
        im_solve_result s;
        check_status(im_solver_solve(plan, gap0->data, h->control, target_of(h, surface, k), pressure, u, &s),
                     "serial capped solve");
        long yielding;
        keep_plastic_flow(n, h->hardness, s.approach, pressure, u, gap0->data, depth, &yielding);
        solve_to_step(&s, yielding, largest_of(depth, n), &answers[k].result);
        check_status(im_field_create(side, side, 1.0, &answers[k].force), "serial force");
        memcpy(answers[k].force->data, pressure, sizeof(double) * n);
    }
    im_solver_plan_free(plan);
    free(pressure);
    free(u);
    free(depth);
}

/* ---- over ranks ---- */

/* The half-space history on the ranks' rows: im_mpi_solver_solve warm-started, with the caller's memory
 * under a cap. The undeformed gap the ranks made is gathered into *gathered_gap0 (rank 0). */
static void distributed_half_space(const history *h, const im_field *surface, step_answer *answers,
                                   im_field **gathered_gap0)
{
    im_solver_options o = options(h);
    im_mpi_solver *solver;
    int y0, rows;
    check_status(im_mpi_solver_create(MPI_COMM_WORLD, side, side, 1.0, &o, &solver), "distributed plan");
    im_mpi_solver_rows(solver, &y0, &rows);
    const size_t n = (size_t)rows * side;
    double *gap0 = malloc(sizeof(double) * (n + 1)), *pressure = calloc(n + 1, sizeof(double)),
           *u = malloc(sizeof(double) * (n + 1)), *depth = calloc(n + 1, sizeof(double));
    check_status(im_mpi_undeformed_gap(solver, surface->data + (size_t)y0 * side, &h->punch, gap0),
                 "distributed gap");
    check_status(im_mpi_gather_map(solver, gap0, 1, gathered_gap0), "gathered gap");
    for (int k = 0; k < h->steps; ++k) {
        im_solve_result s;
        check_status(im_mpi_solver_solve(solver, gap0, h->control, target_of(h, surface, k), pressure, u, &s),
                     "distributed solve");
        long yielding = 0;
        if (h->hardness > 0)
            keep_plastic_flow(n, h->hardness, s.approach, pressure, u, gap0, depth, &yielding);
        double deepest = largest_of(depth, n);
        MPI_Allreduce(MPI_IN_PLACE, &yielding, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
        MPI_Allreduce(MPI_IN_PLACE, &deepest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        solve_to_step(&s, yielding, deepest, &answers[k].result);
        check_status(im_mpi_gather_map(solver, pressure, 1, &answers[k].force), "gathered force");
    }
    im_mpi_solver_free(solver);
    free(gap0);
    free(pressure);
    free(u);
    free(depth);
}

/* The periodic cell's history over ranks: im_mpi_flat_contact_step (with adhesion for ADHESIVE). */
static void distributed_cell(const history *h, const im_field *surface, step_answer *answers)
{
    im_solver_options o = options(h), adhesive = adhesive_options(h);
    im_mpi_solver *solver;
    int y0, rows;
    check_status(im_mpi_solver_create(MPI_COMM_WORLD, side, side, 1.0, &o, &solver), "periodic distributed plan");
    im_mpi_solver_rows(solver, &y0, &rows);
    im_mpi_flat_contact *run;
    check_status(im_mpi_flat_contact_create(solver, surface->data + (size_t)y0 * side, &run), "distributed cell");
    if (h->kind == ADHESIVE)
        check_status(im_mpi_flat_contact_adhesion(run, &adhesive), "adhesion over ranks");
    for (int k = 0; k < h->steps; ++k) {
        check_status(im_mpi_flat_contact_step(run, h->control, target_of(h, surface, k), &answers[k].result),
                     "distributed step");
        check_status(im_mpi_gather_map(solver, im_mpi_flat_contact_pressure(run), 1, &answers[k].force),
                     "gathered force");
    }
    im_mpi_flat_contact_free(run);
    im_mpi_solver_free(solver);
}

/* ---- comparison, on rank 0 ---- */

static void check_close(const history *h, int k, const char *what, double value, double serial)
{
    char detail[256];
    const double difference = fabs(value - serial);
    snprintf(detail, sizeof detail, "%s step %d: %s %.17g (serial %.17g), difference %.3g", h->name, k + 1, what,
             value, serial, difference);
    check(difference <= 1e-10 * fmax(fabs(serial), fabs(value)), what, detail);
}

/* Patches whose force's sign (pressed, pulled or free) differs. */
static long sign_differences(const im_field *a, const im_field *b)
{
    long differ = 0;
    for (size_t i = 0; i < im_field_count(a); ++i)
        differ += (a->data[i] > 0) != (b->data[i] > 0) || (a->data[i] < 0) != (b->data[i] < 0);
    return differ;
}

static void compare_step(const history *h, int k, const step_answer *mpi, const step_answer *serial)
{
    const im_step_result *m = &mpi->result, *s = &serial->result;
    char detail[320];
    snprintf(detail, sizeof detail,
             "%s step %d: %d fine and %d coarse iterations (serial %d, %d), %ld in contact (%ld), %ld yielding "
             "(%ld), %ld patches differ",
             h->name, k + 1, m->iterations, m->coarse_iterations, s->iterations, s->coarse_iterations,
             m->contact_patches, s->contact_patches, m->yielding_patches, s->yielding_patches,
             sign_differences(mpi->force, serial->force));
    /* A load under a cap on the half-space is searched: a dozen displacement-controlled solves (pk.c), any
     * of which may end one iteration apart from the serial one where its residual meets the tolerance within
     * the engines' different orders of summation; the ranks still agree to the bit (the script), and the
     * answer and contact set with the serial one (below). */
    const int searched = h->kind == HALF_SPACE && h->control == IM_CONTROL_LOAD && h->hardness > 0;
    const int slack = searched ? s->iterations / 100 + 1 : 0;
    check(abs(m->iterations - s->iterations) <= slack && m->coarse_iterations == s->coarse_iterations,
          searched ? "iterations as the serial step's, to 1%" : "iterations as the serial step's", detail);
    check(m->contact_patches == s->contact_patches && m->yielding_patches == s->yielding_patches &&
              sign_differences(mpi->force, serial->force) == 0,
          "contact as the serial step's", detail);
    /* (with a cap the serial plan has no cascade either: plain PK steps) */
    check(k > 0 || h->hardness > 0 || m->coarse_iterations > 0, "a cold first step from the cascade", detail);
    check(s->contact_patches > 20, "a contact of many patches", detail);
    check_close(h, k, "load", m->load, s->load);
    check_close(h, k, "approach", m->approach, s->approach);
    /* a plastic depth is an overlap, a gap: as exact as the stopping rule makes gaps, tol times the approach */
    snprintf(detail, sizeof detail, "%s step %d: plastic depth %.17g (serial %.17g)", h->name, k + 1,
             m->plastic_depth, s->plastic_depth);
    check(fabs(m->plastic_depth - s->plastic_depth) <= 1e-10 * s->approach, "plastic depth", detail);
    if (h->kind != HALF_SPACE)
        check_close(h, k, "mean gap", m->mean_gap, s->mean_gap);
    if (h->kind == ADHESIVE)
        check_close(h, k, "tensile force", m->tensile_force, s->tensile_force);
}

/* With a cap: it binds on loading, and the unloading step (the last) keeps the depth of the deepest one. */
static void check_memory(const history *h, const step_answer *serial)
{
    if (!(h->hardness > 0))
        return;
    const im_step_result *first = &serial[0].result, *last = &serial[h->steps - 1].result;
    char detail[256];
    snprintf(detail, sizeof detail, "%s: %ld patches yielding at step 1, plastic depth %.3g then %.3g", h->name,
             first->yielding_patches, first->plastic_depth, last->plastic_depth);
    check(first->yielding_patches > 0 && last->plastic_depth >= first->plastic_depth && first->plastic_depth > 0,
          "a cap that binds and is remembered", detail);
}

static void print_step(const history *h, int k, const step_answer *mpi, const step_answer *serial)
{
    const im_step_result *m = &mpi->result;
    printf("%s-step%d load %a approach %a contact %ld iterations %d coarse %d yielding %ld depth %a | serial "
           "iterations %d coarse %d\n",
           h->name, k + 1, m->load, m->approach, m->contact_patches, m->iterations, m->coarse_iterations,
           m->yielding_patches, m->plastic_depth, serial->result.iterations, serial->result.coarse_iterations);
}

static void run_history(const history *h)
{
    im_field *surface = rough_surface(), *gap0 = NULL;
    step_answer mpi[MAX_STEPS], serial[MAX_STEPS];
    memset(mpi, 0, sizeof mpi);
    memset(serial, 0, sizeof serial);
    if (h->kind == HALF_SPACE)
        distributed_half_space(h, surface, mpi, &gap0);
    else
        distributed_cell(h, surface, mpi);
    if (rank == 0) {
        if (h->kind == HALF_SPACE && h->control == IM_CONTROL_LOAD && h->hardness > 0)
            serial_capped_loads(h, surface, gap0, serial);
        else
            serial_indentation(h, surface, serial);
        for (int k = 0; k < h->steps; ++k) {
            compare_step(h, k, &mpi[k], &serial[k]);
            print_step(h, k, &mpi[k], &serial[k]);
        }
        check_memory(h, serial);
        fflush(stdout);
    }
    for (int k = 0; k < h->steps; ++k) {
        im_field_free(mpi[k].force);
        im_field_free(serial[k].force);
    }
    im_field_free(gap0);
    im_field_free(surface);
}

int main(int argc, char **argv)
{
    mpi_test_start(&argc, &argv);
    if (argc > 1)
        side = atoi(argv[1]);
    check(side >= 64, "grid side", "expected a side of at least 64 (the cascade's coarse grid is 32)");
    const im_indenter cone = im_indenter_cone(80), sphere = im_indenter_sphere(1.5 * side),
                      flat = im_indenter_flat(side / 5.0);
    const enum im_control w = IM_CONTROL_DISPLACEMENT, n = IM_CONTROL_LOAD, g = IM_CONTROL_MEAN_GAP;
    /* loading, deeper, unloading; the cap is the cone's and sphere's mean pressure or above */
    const history histories[] = {
        {"cone-displacement", HALF_SPACE, cone, w, 0, 3, {1, 1.5, 0.6}},
        {"cone-load", HALF_SPACE, cone, n, 0, 3, {1, 1.5, 0.6}},
        {"cone-hardness-displacement", HALF_SPACE, cone, w, 0.12, 3, {1, 1.5, 0.6}},
        {"cone-hardness-load", HALF_SPACE, cone, n, 0.12, 1, {1}},
        {"sphere-displacement", HALF_SPACE, sphere, w, 0, 3, {1, 1.5, 0.6}},
        {"sphere-load", HALF_SPACE, sphere, n, 0, 3, {1, 1.5, 0.6}},
        {"sphere-hardness-displacement", HALF_SPACE, sphere, w, 0.1, 3, {1, 1.5, 0.6}},
        {"sphere-hardness-load", HALF_SPACE, sphere, n, 0.1, 1, {1}},
        {"flat-displacement", HALF_SPACE, flat, w, 0, 3, {0.5, 0.75, 0.3}},
        {"flat-load", HALF_SPACE, flat, n, 0, 3, {0.5, 0.75, 0.3}},
        {"flat-hardness-displacement", HALF_SPACE, flat, w, 0.12, 3, {0.5, 0.75, 0.3}},
        {"flat-hardness-load", HALF_SPACE, flat, n, 0.12, 1, {0.5}},
        {"periodic-pressure", PERIODIC, cone, n, 0, 3, {0.01, 0.02, 0.005}},
        {"periodic-hardness-pressure", PERIODIC, cone, n, 0.1, 4, {0.01, 0.02, 0.005, 0.015}},
        {"periodic-mean-gap", PERIODIC, cone, g, 0, 3, {0.6, 0.4, 0.8}},
        {"periodic-hardness-mean-gap", PERIODIC, cone, g, 0.1, 4, {0.6, 0.4, 0.8, 0.5}},
        {"periodic-adhesion-mean-gap", ADHESIVE, cone, g, 0, 3, {0.6, 0.3, 0.8}},
    };
    for (size_t k = 0; k < sizeof histories / sizeof histories[0]; ++k)
        run_history(&histories[k]);
    im_mpi_cleanup();
    MPI_Finalize();
    return 0;
}
