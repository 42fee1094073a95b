/* The MPI engine of the Polonsky-Keer iteration (solver/engine.h): each rank's passes run over its
 * surface rows with OpenMP, the convolutions through FFTW-MPI (plan.c). What a pass returns is
 * global and the same bits on every rank: each row's sums are compensated in x order, the row sums
 * gathered and added in row order (mpi_ordered_totals); counts travel in the same gather (whole
 * numbers, exact as doubles), maxima and flags by MPI_Allreduce. So every rank takes pk.c's
 * decisions alike, and the answer does not depend on the rank or thread count.
 *
 * No direct sums (the plan's direct_limit is 0): pk.c recomputes u = K p by FFT whenever clipping or
 * joining changed a patch, as the distributed solver always did; direct sums would need every
 * rank's changes and K over the whole grid on each rank. */
#include "mpi/mpi_internal.h"

#include "indentmap/status.h"

#include <math.h>
#include <string.h>

static im_mpi_solver *ranks_of(const pk_run *r) { return r->plan->mpi; }

static size_t local_patches(const im_mpi_solver *s) { return (size_t)s->rows * s->nx; }

/* Row `row`'s k per-row values, summed by mpi_ordered_totals. */
static void store_row(const im_mpi_solver *s, int row, int k, const compensated *sums)
{
    for (int j = 0; j < k; ++j)
        s->row_sums[(size_t)row * k + j] = compensated_total(&sums[j]);
}

static double global_max(const im_mpi_solver *s, double mine)
{
    MPI_Allreduce(MPI_IN_PLACE, &mine, 1, MPI_DOUBLE, MPI_MAX, s->comm);
    return mine;
}

static int global_any(const im_mpi_solver *s, int mine)
{
    MPI_Allreduce(MPI_IN_PLACE, &mine, 1, MPI_INT, MPI_LOR, s->comm);
    return mine;
}

static int mpi_nothing(pk_run *r)
{
    (void)r;
    return IM_OK;
}

static void mpi_convolve_pressure(pk_run *r) { mpi_convolve(ranks_of(r), r->p, r->u); }

static void mpi_convolve_direction(pk_run *r)
{
    im_mpi_solver *s = ranks_of(r);
    mpi_convolve(s, s->direction, s->response);
}

static double mpi_contact_mean(pk_run *r, double p_factor, double u_factor, double cap, long *count)
{
    const im_mpi_solver *s = ranks_of(r);
    const int nx = s->nx;
    const int rescale = p_factor != 1 || u_factor != 1;
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        compensated sums[2] = {{0, 0}, {0, 0}}; /* u + g0, count */
        for (size_t i = (size_t)row * nx; i < (size_t)(row + 1) * nx; ++i) {
            if (rescale) {
                r->p[i] *= p_factor;
                r->u[i] *= u_factor;
            }
            if (solver_elastic(r->p[i], cap)) {
                compensated_add(&sums[0], r->u[i] + r->gap0[i]);
                compensated_add(&sums[1], 1);
            }
        }
        store_row(s, row, 2, sums);
    }
    double totals[2];
    mpi_ordered_totals(s, 2, totals);
    *count = (long)totals[1];
    return *count ? totals[0] / totals[1] : 0;
}

static gap_stats mpi_gaps(pk_run *r, double w, double cap)
{
    const im_mpi_solver *s = ranks_of(r);
    const int nx = s->nx;
    const double *p = r->p, *u = r->u, *g0 = r->gap0;
    const int mask = r->plan->options.precondition;
    double penetration = 0;
#pragma omp parallel for schedule(static) reduction(max : penetration)
    for (int row = 0; row < s->rows; ++row) {
        compensated sums[4] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}}; /* squares, moving, penetrating, contact */
        for (size_t i = (size_t)row * nx; i < (size_t)(row + 1) * nx; ++i) {
            const double gi = u[i] + g0[i] - w;
            s->gap[i] = gi;
            if (mask)
                s->preconditioned[i] = solver_in_step(p[i], gi, INFINITY, SOLVER_JOIN_NONE) ? gi : 0;
            if (solver_elastic(p[i], cap)) {
                compensated_add(&sums[0], gi * gi);
                compensated_add(&sums[3], 1);
            } else {
                if (solver_bound_violation(p[i], gi) > penetration)
                    penetration = solver_bound_violation(p[i], gi);
                if (p[i] == 0 && gi < 0) /* would join */
                    compensated_add(&sums[2], gi * gi);
            }
            if (solver_moving(p[i], gi, cap))
                compensated_add(&sums[1], gi * gi);
        }
        store_row(s, row, 4, sums);
    }
    double totals[4];
    mpi_ordered_totals(s, 4, totals);
    return (gap_stats){.contact = (long)totals[3],
                       .sum_squares = totals[0],
                       .moving_squares = totals[1],
                       .penetration = global_max(s, penetration),
                       .penetration_squares = totals[2]};
}

static double mpi_winkler(pk_run *r, double w, double k0, int store)
{
    const im_mpi_solver *s = ranks_of(r);
    const int nx = s->nx;
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        compensated sum = {0, 0};
        for (size_t i = (size_t)row * nx; i < (size_t)(row + 1) * nx; ++i) {
            const double pi = r->gap0[i] < w ? (w - r->gap0[i]) / k0 : 0;
            if (store)
                r->p[i] = pi;
            compensated_add(&sum, pi);
        }
        store_row(s, row, 1, &sum);
    }
    double total;
    mpi_ordered_totals(s, 1, &total);
    return total * s->delta * s->delta;
}

static void mpi_clip(pk_run *r, double cap)
{
    const size_t n = local_patches(ranks_of(r));
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        r->p[i] = solver_project(r->p[i], cap);
}

static int mpi_any_positive(pk_run *r)
{
    const im_mpi_solver *s = ranks_of(r);
    return global_any(s, solver_any_positive(r->p, local_patches(s)));
}

static void mpi_load_split(pk_run *r, double cap, double *elastic, double *capped)
{
    const im_mpi_solver *s = ranks_of(r);
    const int nx = s->nx;
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        compensated sums[2] = {{0, 0}, {0, 0}}; /* elastic, the others */
        for (size_t i = (size_t)row * nx; i < (size_t)(row + 1) * nx; ++i)
            compensated_add(&sums[solver_elastic(r->p[i], cap) ? 0 : 1], r->p[i]);
        store_row(s, row, 2, sums);
    }
    double totals[2];
    mpi_ordered_totals(s, 2, totals);
    *elastic = totals[0] * s->delta * s->delta;
    *capped = totals[1] * s->delta * s->delta;
}

static int mpi_scale_elastic(pk_run *r, double scale, double cap)
{
    const im_mpi_solver *s = ranks_of(r);
    return global_any(s, solver_scale_elastic_patches(r->p, local_patches(s), scale, cap));
}

static double mpi_pressure_sum(pk_run *r)
{
    const im_mpi_solver *s = ranks_of(r);
    const int nx = s->nx;
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        compensated sum = {0, 0};
        for (size_t i = (size_t)row * nx; i < (size_t)(row + 1) * nx; ++i)
            compensated_add(&sum, r->p[i]);
        store_row(s, row, 1, &sum);
    }
    double total;
    mpi_ordered_totals(s, 1, &total);
    return total;
}

static void mpi_scale(pk_run *r, double p_factor, double u_factor)
{
    const size_t n = local_patches(ranks_of(r));
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        r->p[i] *= p_factor;
        r->u[i] *= u_factor;
    }
}

static void mpi_direction(pk_run *r, int preconditioned, double beta, double cap)
{
    const im_mpi_solver *s = ranks_of(r);
    const size_t n = local_patches(s);
    double *t = s->direction;
    const double *g = s->gap, *p = r->p, *source = preconditioned ? s->preconditioned : s->gap;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        t[i] = solver_in_step(p[i], g[i], cap, r->join) ? source[i] + beta * t[i] : 0;
}

/* z = M g on the step's set through the preconditioner's pair (plan.c); without a join the gaps pass
 * left z = g on the set. */
static void apply_preconditioner(im_mpi_solver *s, const pk_run *r)
{
    const size_t n = local_patches(s);
    if (r->join != SOLVER_JOIN_NONE) {
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; ++i)
            s->preconditioned[i] = solver_in_step(r->p[i], s->gap[i], INFINITY, r->join) ? s->gap[i] : 0;
    }
    mpi_transform_apply(s, s->precondition_with, s->inverse_spectrum, s->preconditioned, s->preconditioned);
}

static double mpi_precondition(pk_run *r, long *count)
{
    im_mpi_solver *s = ranks_of(r);
    const int nx = s->nx;
    apply_preconditioner(s, r);
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        compensated sums[2] = {{0, 0}, {0, 0}}; /* z, count */
        for (size_t i = (size_t)row * nx; i < (size_t)(row + 1) * nx; ++i) {
            if (solver_in_step(r->p[i], s->gap[i], INFINITY, r->join)) {
                compensated_add(&sums[0], s->preconditioned[i]);
                compensated_add(&sums[1], 1);
            }
        }
        store_row(s, row, 2, sums);
    }
    double totals[2];
    mpi_ordered_totals(s, 2, totals);
    *count = (long)totals[1];
    return totals[0];
}

static double mpi_precondition_centre(pk_run *r, double mean)
{
    const im_mpi_solver *s = ranks_of(r);
    const int nx = s->nx;
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        compensated gz = {0, 0};
        for (size_t i = (size_t)row * nx; i < (size_t)(row + 1) * nx; ++i)
            if (solver_in_step(r->p[i], s->gap[i], INFINITY, r->join)) {
                s->preconditioned[i] -= mean;
                compensated_add(&gz, s->gap[i] * s->preconditioned[i]);
            }
        store_row(s, row, 1, &gz);
    }
    double total;
    mpi_ordered_totals(s, 1, &total);
    return total;
}

static step_terms mpi_step(pk_run *r, double cap)
{
    const im_mpi_solver *s = ranks_of(r);
    const int nx = s->nx;
    const double *t = s->direction, *g = s->gap, *q = s->response, *p = r->p;
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        compensated sums[5] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0}}; /* <g,t>, <q,t>, sum q, sum t, count */
        for (size_t i = (size_t)row * nx; i < (size_t)(row + 1) * nx; ++i)
            if (solver_in_step(p[i], g[i], cap, r->join)) {
                compensated_add(&sums[0], g[i] * t[i]);
                compensated_add(&sums[1], q[i] * t[i]);
                compensated_add(&sums[2], q[i]);
                compensated_add(&sums[3], t[i]);
                compensated_add(&sums[4], 1);
            }
        store_row(s, row, 5, sums);
    }
    double totals[5];
    mpi_ordered_totals(s, 5, totals);
    return (step_terms){.gt = totals[0],
                        .kt_t = totals[1],
                        .kt_sum = totals[2],
                        .t_sum = totals[3],
                        .count = (long)totals[4]};
}

static long mpi_update_pressure(pk_run *r, double tau, double cap, int *joined)
{
    const im_mpi_solver *s = ranks_of(r);
    const size_t n = local_patches(s);
    const double *t = s->direction, *g = s->gap, *q = s->response;
    double *p = r->p, *u = r->u;
    long changes = 0, joins = 0; /* patches that differ from the plain step, patches that joined */
#pragma omp parallel for schedule(static) reduction(+ : changes, joins)
    for (size_t i = 0; i < n; ++i) {
        u[i] -= tau * q[i];
        if (solver_in_step(p[i], g[i], cap, r->join)) {
            const double next = p[i] - tau * t[i];
            joins += p[i] == 0 && next > 0;
            p[i] = solver_project(next, cap);
            changes += p[i] != next;
        } else if (solver_joins_by_gap(p[i], g[i], r->join)) {
            p[i] = solver_project(-tau * g[i], cap);
            changes += p[i] != 0;
            ++joins;
        }
    }
    long counts[2] = {changes, joins};
    MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_LONG, MPI_SUM, s->comm);
    *joined = counts[1] > 0;
    return counts[0];
}

static void mpi_summary(pk_run *r, double *sum, long *contact, double *peak)
{
    const im_mpi_solver *s = ranks_of(r);
    const int nx = s->nx;
    double largest = 0;
#pragma omp parallel for schedule(static) reduction(max : largest)
    for (int row = 0; row < s->rows; ++row) {
        compensated sums[2] = {{0, 0}, {0, 0}}; /* p, count */
        for (size_t i = (size_t)row * nx; i < (size_t)(row + 1) * nx; ++i)
            if (r->p[i] > 0) {
                compensated_add(&sums[0], r->p[i]);
                compensated_add(&sums[1], 1);
                largest = r->p[i] > largest ? r->p[i] : largest;
            }
        store_row(s, row, 2, sums);
    }
    double totals[2];
    mpi_ordered_totals(s, 2, totals);
    *sum = totals[0];
    *contact = (long)totals[1];
    *peak = global_max(s, largest);
}

/* Every rank's flag, so that every rank stops at the same iteration (mpirun forwards a signal to
 * every rank, not at the same instant). The options are the same on every rank: all have a flag to
 * read or none has. */
static int mpi_stop_signal(pk_run *r)
{
    const volatile sig_atomic_t *stop = r->plan->options.stop;
    return stop ? (int)global_max(ranks_of(r), (double)*stop) : 0;
}

const solver_engine solver_engine_mpi = {
    .name = "mpi",
    .begin = mpi_nothing,
    .finish = mpi_nothing,
    .convolve_pressure = mpi_convolve_pressure,
    .convolve_direction = mpi_convolve_direction,
    .contact_mean = mpi_contact_mean,
    .gaps = mpi_gaps,
    .winkler = mpi_winkler,
    .clip = mpi_clip,
    .any_positive = mpi_any_positive,
    .load_split = mpi_load_split,
    .scale_elastic = mpi_scale_elastic,
    .pressure_sum = mpi_pressure_sum,
    .scale = mpi_scale,
    .direction = mpi_direction,
    .precondition = mpi_precondition,
    .precondition_centre = mpi_precondition_centre,
    .step = mpi_step,
    .update_pressure = mpi_update_pressure,
    .add_point_loads = NULL, /* never called: direct_limit 0 */
    .summary = mpi_summary,
    .stop_signal = mpi_stop_signal,
    /* An MPI plan is part of its im_mpi_solver, never a caller's plan: no im_solver_convolve (that is
     * im_mpi_convolve) and no im_solver_plan_free (im_mpi_solver_free frees it). */
    .convolve_arrays = NULL,
    .free = NULL,
};
