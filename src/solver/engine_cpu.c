/* The CPU engine of the Polonsky-Keer iteration (engine.h): the plan's own arrays, OpenMP loops,
 * FFTW transforms (plan.c). Sums of doubles are taken over fixed parts of the grid, then in part order
 * (the load compensated, core/summation.h), so that a solve gives the same bits whatever the team size
 * (core/team_size.c picks it per solve); counts and extremes are OpenMP reductions, exact in any order. */
#include "solver/engine.h"

#include "core/summation.h"
#include "indentmap/status.h"

#include <math.h>
#include <omp.h>
#include <string.h>

static size_t patches(const pk_run *r) { return (size_t)r->plan->nx * r->plan->ny; }

enum { PARTS = 64, MOST_SUMS = 4 };

typedef struct part_sums {
    double s[MOST_SUMS];
} part_sums;

/* The first index of part k of [0, n). */
static size_t part_start(size_t n, int k) { return n * (size_t)k / PARTS; }

/* The parts' sums added in part order. */
static part_sums parts_total(const part_sums *parts)
{
    part_sums total = {{0}};
    for (int k = 0; k < PARTS; ++k)
        for (int j = 0; j < MOST_SUMS; ++j)
            total.s[j] += parts[k].s[j];
    return total;
}

static int cpu_nothing(pk_run *r)
{
    (void)r;
    return IM_OK;
}

static void cpu_convolve_pressure(pk_run *r) { im_solver_convolve(r->plan, r->p, r->u); }

static void cpu_convolve_direction(pk_run *r) { solver_convolve_rows(r->plan); }

static double cpu_contact_mean(pk_run *r, double p_factor, double u_factor, double cap, long *count)
{
    const size_t n = patches(r);
    const int rescale = p_factor != 1 || u_factor != 1;
    double *p = r->p, *u = r->u;
    const double *g0 = r->gap0;
    part_sums parts[PARTS];
    long c = 0;
#pragma omp parallel for schedule(static) reduction(+ : c)
    for (int k = 0; k < PARTS; ++k) {
        double sum = 0;
        for (size_t i = part_start(n, k); i < part_start(n, k + 1); ++i) {
            if (rescale) {
                p[i] *= p_factor;
                u[i] *= u_factor;
            }
            if (solver_elastic(p[i], cap)) {
                sum += u[i] + g0[i];
                ++c;
            }
        }
        parts[k] = (part_sums){{sum}};
    }
    *count = c;
    return c ? parts_total(parts).s[0] / c : 0;
}

static gap_stats cpu_gaps(pk_run *r, double w, double cap)
{
    const size_t n = patches(r);
    const double *p = r->p, *u = r->u, *g0 = r->gap0;
    double *g = r->plan->gap, *z = r->plan->preconditioned;
    const int mask = r->plan->options.precondition;
    part_sums parts[PARTS];
    double penetration = 0;
    long contact = 0;
#pragma omp parallel for schedule(static) reduction(+ : contact) reduction(max : penetration)
    for (int k = 0; k < PARTS; ++k) {
        double squares = 0, moving_squares = 0, penetration_squares = 0;
        for (size_t i = part_start(n, k); i < part_start(n, k + 1); ++i) {
            double gi = u[i] + g0[i] - w;
            g[i] = gi;
            if (mask)
                z[i] = solver_in_step(p[i], gi, INFINITY, SOLVER_JOIN_NONE) ? gi : 0;
            if (solver_elastic(p[i], cap)) {
                squares += gi * gi;
                ++contact;
            } else {
                if (solver_bound_violation(p[i], gi) > penetration)
                    penetration = solver_bound_violation(p[i], gi);
                if (p[i] == 0 && gi < 0) /* would join */
                    penetration_squares += gi * gi;
            }
            if (solver_moving(p[i], gi, cap))
                moving_squares += gi * gi;
        }
        parts[k] = (part_sums){{squares, moving_squares, penetration_squares}};
    }
    const part_sums total = parts_total(parts);
    return (gap_stats){.contact = contact,
                       .sum_squares = total.s[0],
                       .moving_squares = total.s[1],
                       .penetration = penetration,
                       .penetration_squares = total.s[2]};
}

static double cpu_winkler(pk_run *r, double w, double k0, int store)
{
    const size_t n = patches(r);
    const double d2 = r->plan->delta * r->plan->delta;
    part_sums parts[PARTS];
#pragma omp parallel for schedule(static)
    for (int k = 0; k < PARTS; ++k) {
        double sum = 0;
        for (size_t i = part_start(n, k); i < part_start(n, k + 1); ++i) {
            double pi = r->gap0[i] < w ? (w - r->gap0[i]) / k0 : 0;
            if (store)
                r->p[i] = pi;
            sum += pi;
        }
        parts[k] = (part_sums){{sum}};
    }
    return parts_total(parts).s[0] * d2;
}

static void cpu_clip(pk_run *r, double cap)
{
    const size_t n = patches(r);
    for (size_t i = 0; i < n; ++i)
        r->p[i] = solver_project(r->p[i], cap);
}

static int cpu_any_positive(pk_run *r) { return solver_any_positive(r->p, patches(r)); }

static void cpu_load_split(pk_run *r, double cap, double *elastic, double *capped)
{
    const size_t n = patches(r);
    const double d2 = r->plan->delta * r->plan->delta;
    part_sums parts[PARTS];
#pragma omp parallel for schedule(static)
    for (int k = 0; k < PARTS; ++k) {
        double elastic_load = 0, capped_load = 0;
        for (size_t i = part_start(n, k); i < part_start(n, k + 1); ++i) {
            if (solver_elastic(r->p[i], cap))
                elastic_load += r->p[i] * d2;
            else
                capped_load += r->p[i] * d2;
        }
        parts[k] = (part_sums){{elastic_load, capped_load}};
    }
    const part_sums total = parts_total(parts);
    *elastic = total.s[0];
    *capped = total.s[1];
}

int solver_scale_elastic_patches(double *p, size_t n, double scale, double cap)
{
    int clipped = 0;
#pragma omp parallel for schedule(static) reduction(| : clipped)
    for (size_t i = 0; i < n; ++i)
        if (solver_elastic(p[i], cap)) {
            p[i] = solver_project(p[i] * scale, cap);
            clipped |= p[i] == cap;
        }
    return clipped;
}

static int cpu_scale_elastic(pk_run *r, double scale, double cap)
{
    return solver_scale_elastic_patches(r->p, patches(r), scale, cap);
}

static double cpu_pressure_sum(pk_run *r) { return sum_doubles(r->p, patches(r)); }

static void cpu_scale(pk_run *r, double p_factor, double u_factor)
{
    const size_t n = patches(r);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        r->p[i] *= p_factor;
        r->u[i] *= u_factor;
    }
}

/* Writes t also into the padded rows that the convolution transforms (one pass instead of two). */
static void cpu_direction(pk_run *r, int preconditioned, double beta, double cap)
{
    const im_solver_plan *plan = r->plan;
    const int nx = plan->nx, ny = plan->ny, px = plan->px;
    double *t = plan->direction;
    const double *g = plan->gap, *p = r->p, *source = preconditioned ? plan->preconditioned : plan->gap;
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < ny; ++iy) {
        double *padded = plan->rows_in + (size_t)iy * px;
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)iy * nx + ix;
            t[i] = solver_in_step(p[i], g[i], cap, r->join) ? source[i] + beta * t[i] : 0;
            padded[ix] = t[i];
        }
    }
}

/* An unpadded transform pair, a quarter of a convolution's size (plan.c). */
static double cpu_precondition(pk_run *r, long *count)
{
    im_solver_plan *plan = r->plan;
    const size_t n = patches(r), modes = (size_t)plan->ny * (plan->nx / 2 + 1);
    const double *g = plan->gap, *p = r->p;
    double *z = plan->preconditioned;
    if (r->join != SOLVER_JOIN_NONE) { /* without a join the gaps pass left this mask */
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; ++i)
            z[i] = solver_in_step(p[i], g[i], INFINITY, r->join) ? g[i] : 0;
    }
    solver_count_pair(plan, SOLVER_PAIR_M);
    fftw_execute(plan->precondition_forward);
    solver_multiply_modes(plan->precondition_modes, plan->inverse_spectrum, modes);
    fftw_execute(plan->precondition_backward);
    part_sums parts[PARTS];
    long c = 0;
#pragma omp parallel for schedule(static) reduction(+ : c)
    for (int k = 0; k < PARTS; ++k) {
        double z_sum = 0, gz = 0;
        for (size_t i = part_start(n, k); i < part_start(n, k + 1); ++i) {
            if (solver_in_step(p[i], g[i], INFINITY, r->join)) {
                z_sum += z[i];
                gz += g[i] * z[i];
                ++c;
            }
        }
        parts[k] = (part_sums){{z_sum, gz}};
    }
    *count = c;
    const part_sums total = parts_total(parts);
    plan->uncentred_gz = total.s[1];
    return total.s[0];
}

/* Centring by 0 (displacement control) changes no z: <g, z> is then the one the precondition pass
 * summed, the same parts in the same order, and the pass over p, g and z is saved. */
static double cpu_precondition_centre(pk_run *r, double mean)
{
    if (mean == 0)
        return r->plan->uncentred_gz;
    const size_t n = patches(r);
    const double *g = r->plan->gap, *p = r->p;
    double *z = r->plan->preconditioned;
    part_sums parts[PARTS];
#pragma omp parallel for schedule(static)
    for (int k = 0; k < PARTS; ++k) {
        double gz = 0;
        for (size_t i = part_start(n, k); i < part_start(n, k + 1); ++i)
            if (solver_in_step(p[i], g[i], INFINITY, r->join)) {
                z[i] -= mean;
                gz += g[i] * z[i];
            }
        parts[k] = (part_sums){{gz}};
    }
    return parts_total(parts).s[0];
}

/* K t is read in place from the convolution's rows. */
static step_terms cpu_step(pk_run *r, double cap)
{
    const im_solver_plan *plan = r->plan;
    const int nx = plan->nx, ny = plan->ny, px = plan->px;
    const double *t = plan->direction, *g = plan->gap, *p = r->p;
    part_sums parts[PARTS];
    long count = 0;
#pragma omp parallel for schedule(static) reduction(+ : count)
    for (int k = 0; k < PARTS; ++k) {
        double num = 0, qt = 0, q_sum = 0, t_sum = 0;
        for (size_t iy = part_start(ny, k); iy < part_start(ny, k + 1); ++iy) {
            const double *q = plan->rows_out + iy * px;
            for (int ix = 0; ix < nx; ++ix) {
                size_t i = iy * nx + ix;
                if (solver_in_step(p[i], g[i], cap, r->join)) {
                    num += g[i] * t[i];
                    qt += q[ix] * t[i];
                    q_sum += q[ix];
                    t_sum += t[i];
                    ++count;
                }
            }
        }
        parts[k] = (part_sums){{num, qt, q_sum, t_sum}};
    }
    const part_sums total = parts_total(parts);
    return (
        step_terms){.gt = total.s[0], .kt_t = total.s[1], .kt_sum = total.s[2], .t_sum = total.s[3], .count = count};
}

/* The changes of part k's rows, at the front of the part's own stretch of plan->changed and
 * changed_value (a part holds no more changes than patches); compact_changes moves them together. */
static long update_part(pk_run *r, int k, double tau, double cap, int *joined)
{
    const im_solver_plan *plan = r->plan;
    const int nx = plan->nx, px = plan->px;
    const double *t = plan->direction, *g = plan->gap;
    double *p = r->p, *u = r->u;
    const size_t first = part_start(plan->ny, k) * nx;
    long changes = 0;
    for (size_t iy = part_start(plan->ny, k); iy < part_start(plan->ny, k + 1); ++iy) {
        const double *q = plan->rows_out + iy * px;
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = iy * nx + ix;
            double c = 0;
            u[i] -= tau * q[ix];
            if (solver_in_step(p[i], g[i], cap, r->join)) {
                const double next = p[i] - tau * t[i];
                *joined |= p[i] == 0 && next > 0;
                p[i] = solver_project(next, cap);
                c = p[i] - next;
            } else if (solver_joins_by_gap(p[i], g[i], r->join)) {
                p[i] = c = solver_project(-tau * g[i], cap);
                *joined = 1;
            }
            if (c != 0) {
                plan->changed[first + changes] = (long)i;
                plan->changed_value[first + changes++] = c;
            }
        }
    }
    return changes;
}

/* The parts' changes moved to the front of plan->changed, in index order (as the parts are). */
static void compact_changes(const im_solver_plan *plan, const long *part_changes)
{
    long total = 0;
    for (int k = 0; k < PARTS; ++k) {
        const size_t first = part_start(plan->ny, k) * plan->nx;
        memmove(plan->changed + total, plan->changed + first, sizeof(long) * part_changes[k]);
        memmove(plan->changed_value + total, plan->changed_value + first, sizeof(double) * part_changes[k]);
        total += part_changes[k];
    }
}

/* Records how p differs from the plain CG step p - tau t in plan->changed and changed_value, listed
 * as they arise (no pass over a grid of changes); listed together only when the direct sums will
 * take them (direct_limit; more are never read: pk.c convolves). */
static long cpu_update_pressure(pk_run *r, double tau, double cap, int *joined)
{
    long part_changes[PARTS], changes = 0;
    int any_joined = 0;
#pragma omp parallel for schedule(static) reduction(+ : changes) reduction(| : any_joined)
    for (int k = 0; k < PARTS; ++k) {
        part_changes[k] = update_part(r, k, tau, cap, &any_joined);
        changes += part_changes[k];
    }
    *joined = any_joined;
    if (changes > 0 && changes <= r->plan->direct_limit)
        compact_changes(r->plan, part_changes);
    return changes;
}

static void cpu_add_point_loads(pk_run *r, long changes)
{
    im_solver_plan *plan = r->plan;
    solver_add_point_loads(plan, plan->changed, plan->changed_value, changes, r->u);
}

static void cpu_summary(pk_run *r, double *sum, long *contact, double *peak)
{
    const size_t n = patches(r);
    double largest = 0;
    long c = 0;
#pragma omp parallel for schedule(static) reduction(+ : c) reduction(max : largest)
    for (size_t i = 0; i < n; ++i)
        if (r->p[i] > 0) {
            ++c;
            if (r->p[i] > largest)
                largest = r->p[i];
        }
    *sum = sum_doubles(r->p, n); /* p >= 0: the sum over the contact set */
    *contact = c;
    *peak = largest;
}

static int cpu_convolve_arrays(im_solver_plan *plan, const double *pressure, double *displacement)
{
    const int nx = plan->nx, ny = plan->ny, px = plan->px;
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < ny; ++iy) { /* the right halves zeroed again: a convolution's plan wrote its result there */
        memcpy(plan->rows_in + (size_t)iy * px, pressure + (size_t)iy * nx, sizeof(double) * nx);
        memset(plan->rows_in + (size_t)iy * px + nx, 0, sizeof(double) * (px - nx));
    }
    solver_convolve_rows(plan);
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < ny; ++iy)
        memcpy(displacement + (size_t)iy * nx, plan->rows_out + (size_t)iy * px, sizeof(double) * nx);
    return IM_OK;
}

static void cpu_free(im_solver_plan *plan) { (void)plan; }

const solver_engine solver_engine_cpu = {
    .name = "cpu",
    .begin = cpu_nothing,
    .finish = cpu_nothing,
    .convolve_pressure = cpu_convolve_pressure,
    .convolve_direction = cpu_convolve_direction,
    .contact_mean = cpu_contact_mean,
    .gaps = cpu_gaps,
    .winkler = cpu_winkler,
    .clip = cpu_clip,
    .any_positive = cpu_any_positive,
    .load_split = cpu_load_split,
    .scale_elastic = cpu_scale_elastic,
    .pressure_sum = cpu_pressure_sum,
    .scale = cpu_scale,
    .direction = cpu_direction,
    .precondition = cpu_precondition,
    .precondition_centre = cpu_precondition_centre,
    .step = cpu_step,
    .update_pressure = cpu_update_pressure,
    .add_point_loads = cpu_add_point_loads,
    .summary = cpu_summary,
    .convolve_arrays = cpu_convolve_arrays,
    .free = cpu_free,
};
