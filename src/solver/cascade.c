/* Cascade multi-resolution cold starts (Bemporad & Paggi 2015, arXiv 1506.00532; see solver.h):
 * the problem is restricted to a grid of 2 delta patches, solved there (itself started the same way
 * from a coarser grid), and its pressure, prolonged piecewise constant, starts the fine solve. The
 * fine solve then has the contact set nearly right, so it needs far fewer iterations than from the
 * local guess; the coarse solves cost a quarter per level. */
#include "solver/engine.h"

#include "core/summation.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The coarsest level has at least this many patches a side: below it a level's solve costs more in
 * its own fixed overheads than it saves. */
enum { CASCADE_MIN_SIDE = 32 };

/* The coarse solves stop at this tolerance (or the fine one, if looser): the coarse answer differs
 * from the fine one by the discretisation error anyway, far more than 1e-4. */
static const double CASCADE_TOL = 1e-4;

int solver_cascade_sides(int nx, int ny, int periodic, int *cx, int *cy)
{
    *cx = (nx + 1) / 2;
    *cy = (ny + 1) / 2;
    /* a periodic cell halves only into whole blocks: the coarse cell must have the same period */
    const int whole = !periodic || (nx % 2 == 0 && ny % 2 == 0);
    return whole && *cx >= CASCADE_MIN_SIDE && *cy >= CASCADE_MIN_SIDE;
}

int solver_cascade_create(im_solver_plan *p)
{
    int cx, cy;
    if (!p->options.cascade || !solver_cascade_sides(p->nx, p->ny, p->options.periodic, &cx, &cy))
        return IM_OK;
    size_t n = (size_t)cx * cy;
    p->coarse_gap0 = malloc(sizeof(double) * n);
    p->coarse_pressure = malloc(sizeof(double) * n);
    p->coarse_displacement = malloc(sizeof(double) * n);
    if (!p->coarse_gap0 || !p->coarse_pressure || !p->coarse_displacement)
        return im_fail(IM_ENOMEM, "solver plan %d x %d: cascade level %d x %d", p->nx, p->ny, cx, cy);
    im_solver_options o = solver_cascade_options(&p->options);
    return solver_plan_create_level(cx, cy, 2 * p->delta, &o, p, &p->coarse);
}

im_solver_options solver_cascade_options(const im_solver_options *fine)
{
    im_solver_options o = *fine;
    o.tol = fmax(o.tol, CASCADE_TOL);
    return o;
}

void solver_cascade_free(im_solver_plan *p)
{
    im_solver_plan_free(p->coarse);
    free(p->coarse_gap0);
    free(p->coarse_pressure);
    free(p->coarse_displacement);
}

void solver_cascade_pair_sum(const double *row, int nx, int cx, double *sum, int *count)
{
    *sum = 0;
    *count = 0;
    for (int ix = 2 * cx; ix < 2 * cx + 2 && ix < nx; ++ix)
        if (isfinite(row[ix])) {
            *sum += row[ix];
            ++*count;
        }
}

double solver_cascade_block_mean(double upper, double lower, int count)
{
    return count ? (upper + lower) / count : INFINITY;
}

/* A restriction's fine plan and gap, and whether the coarse gaps are summed. */
typedef struct restriction {
    const im_solver_plan *fine;
    const double *gap0;
    int summed;
} restriction;

/* The coarse gaps [first, last) of coarse row cy. A coarse gap is the mean over its 2 x 2 block of the fine
 * gaps that are finite (+inf if none is: a flat punch cannot touch there); blocks cut by an odd side hold
 * fewer patches. */
static void restrict_row(const im_solver_plan *p, const double *gap0, int cy, int first, int last)
{
    const im_solver_plan *c = p->coarse;
    for (int cx = first; cx < last; ++cx) {
        double upper, lower = 0;
        int upper_count, lower_count = 0;
        solver_cascade_pair_sum(gap0 + (size_t)2 * cy * p->nx, p->nx, cx, &upper, &upper_count);
        if (2 * cy + 1 < p->ny)
            solver_cascade_pair_sum(gap0 + (size_t)(2 * cy + 1) * p->nx, p->nx, cx, &lower, &lower_count);
        p->coarse_gap0[(size_t)cy * c->nx + cx] = solver_cascade_block_mean(upper, lower, upper_count + lower_count);
    }
}

/* The coarse gaps of the coarse patches [lo, hi) (row-major), and when summed their sum, taken while they
 * are in cache (summation.h: sum_ranges; else 0). */
static double restrict_range(size_t lo, size_t hi, const void *context)
{
    const restriction *r = context;
    const int nx = r->fine->coarse->nx;
    for (size_t k = lo; k < hi;) {
        const int cy = (int)(k / (size_t)nx), first = (int)(k % (size_t)nx);
        const int last = hi - k < (size_t)(nx - first) ? first + (int)(hi - k) : nx;
        restrict_row(r->fine, r->gap0, cy, first, last);
        k += (size_t)(last - first);
    }
    return r->summed ? sum_doubles_range(r->fine->coarse_gap0, lo, hi) : 0;
}

/* The coarse gap, and its mean where the coarse level's periodic approach is checked (else NaN): summed
 * as the pass makes it, to sum_doubles' bits over the coarse gap, with no second pass over it. */
static double restrict_gap(const im_solver_plan *p, const double *gap0, enum im_control control)
{
    const restriction r = {p, gap0, solver_periodic_approach_checked(p->coarse, control)};
    const size_t n = (size_t)p->coarse->nx * p->coarse->ny;
    const double sum = sum_ranges(n, restrict_range, &r);
    return r.summed ? sum / (double)n : NAN;
}

int solver_cascade_prolong_row(const double *coarse_row, const double *gap_row, int nx, double *pressure_row)
{
    int loaded = 0;
    for (int ix = 0; ix < nx; ++ix) {
        double v = isfinite(gap_row[ix]) ? coarse_row[ix / 2] : 0;
        pressure_row[ix] = v;
        loaded |= v > 0;
    }
    return loaded;
}

/* Fine pressure = the coarse pressure of its block, except where the fine gap is infinite. Returns
 * whether any patch is loaded. */
static int prolong_pressure(const im_solver_plan *p, const double *gap0, double *pressure)
{
    const im_solver_plan *c = p->coarse;
    int loaded = 0;
#pragma omp parallel for schedule(static) reduction(| : loaded)
    for (int iy = 0; iy < p->ny; ++iy)
        loaded |= solver_cascade_prolong_row(p->coarse_pressure + (size_t)(iy / 2) * c->nx, gap0 + (size_t)iy * p->nx,
                                             p->nx, pressure + (size_t)iy * p->nx);
    return loaded;
}

/* The coarse solve from zero pressure; keep: its answer may stay on the engine (*kept when it did). */
static int solve_level(im_solver_plan *coarse, const double *coarse_gap0, double mean_gap0, enum im_control control,
                       double target, double *coarse_pressure, double *coarse_displacement, int keep, int *usable,
                       int *kept)
{
    memset(coarse_pressure, 0, sizeof(double) * (size_t)coarse->nx * coarse->ny);
    im_solve_result result = {0};
    /* Only a start: a coarse solve that stops at its cap still gives one (p >= 0 whatever happens),
     * and one that breaks down leaves the fine solve the local guess. */
    int status = solver_solve_coarse(coarse, coarse_gap0, mean_gap0, control, target, coarse_pressure,
                                     coarse_displacement, keep, &result, kept);
    *usable = status != IM_ENUMERIC;
    return result.iterations + result.coarse_iterations;
}

int solver_cascade_solve(im_solver_plan *coarse, const double *coarse_gap0, double mean_gap0, enum im_control control,
                         double target, double *coarse_pressure, double *coarse_displacement, int *usable)
{
    int kept;
    return solve_level(coarse, coarse_gap0, mean_gap0, control, target, coarse_pressure, coarse_displacement, 0,
                       usable, &kept);
}

int solver_cascade_start(im_solver_plan *p, const double *gap0, enum im_control control, double target,
                         double *pressure, int *prolonged)
{
    const double mean_gap0 = restrict_gap(p, gap0, control);
    /* both levels on one engine that keeps answers: the coarse answer is prolonged there (engine.h) */
    const int keep = p->engine->keeps_answers && p->coarse->engine == p->engine;
    int usable, kept;
    int iterations = solve_level(p->coarse, p->coarse_gap0, mean_gap0, control, target, p->coarse_pressure,
                                 p->coarse_displacement, keep, &usable, &kept);
    *prolonged = usable && kept;
    if (!usable || (!kept && !prolong_pressure(p, gap0, pressure)))
        memset(pressure, 0, sizeof(double) * (size_t)p->nx * p->ny);
    return iterations;
}
