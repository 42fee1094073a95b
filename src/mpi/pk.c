/* Polonsky-Keer constrained conjugate gradients over ranks (solver.h's algorithm and stopping
 * rule; sums in row order, see mpi.h). */
#include "mpi/mpi_internal.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <limits.h>
#include <string.h>

typedef struct gap_stats {
    double approach;     /* w used for these gaps */
    long contact;        /* |I_c| */
    double sum_squares;  /* sum over I_c of g^2 */
    double penetration;  /* max over p = 0 of -g (0 if none) */
} gap_stats;

typedef struct pk_run {
    im_mpi_solver *s;
    const double *gap0;
    enum im_control control;
    double target;
    double *p, *u;
    int convolutions;
} pk_run;

static size_t local_count(const im_mpi_solver *s) { return (size_t)s->rows * s->nx; }

static long global_count(const im_mpi_solver *s, long mine)
{
    long all;
    MPI_Allreduce(&mine, &all, 1, MPI_LONG, MPI_SUM, s->comm);
    return all;
}

static double global_max(const im_mpi_solver *s, double mine)
{
    double all;
    MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_MAX, s->comm);
    return all;
}

/* The caller's stop flag as any rank saw it (mpirun forwards a signal to every rank, not at the same
 * instant), so that every rank stops at the same iteration: the signal's number, 0 to go on. The
 * options are the same on every rank, so either all ranks have a flag to read or none has. */
static int stop_signal(const im_mpi_solver *s)
{
    const volatile sig_atomic_t *stop = s->options.stop;
    return stop ? (int)global_max(s, (double)*stop) : 0;
}

/* Row-ordered total of v over I_c = {p > 0} (over all patches when p is NULL); *count: |I_c|. */
static double contact_total(const pk_run *r, const double *a, const double *b, long *count)
{
    const im_mpi_solver *s = r->s;
    const int nx = s->nx;
    long c = 0;
#pragma omp parallel for schedule(static) reduction(+ : c)
    for (int row = 0; row < s->rows; ++row) {
        compensated sum = {0, 0};
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)row * nx + ix;
            if (r->p[i] > 0) {
                compensated_add(&sum, b ? a[i] + b[i] : a[i]);
                ++c;
            }
        }
        s->row_sums[row] = compensated_total(&sum);
    }
    double total;
    mpi_ordered_totals(s, 1, &total);
    *count = global_count(s, c);
    return total;
}

/* g = u + g0 - w, with w imposed or (load control) the mean of u + g0 over I_c. */
static gap_stats compute_gaps(const pk_run *r)
{
    const im_mpi_solver *s = r->s;
    const int nx = s->nx;
    gap_stats st = {.approach = r->target};
    if (r->control == IM_CONTROL_LOAD) {
        double sum = contact_total(r, r->u, r->gap0, &st.contact);
        st.approach = st.contact ? sum / st.contact : 0;
    }
    const double w = st.approach;
    double penetration = 0;
    long contact = 0;
#pragma omp parallel for schedule(static) reduction(+ : contact) reduction(max : penetration)
    for (int row = 0; row < s->rows; ++row) {
        compensated squares = {0, 0};
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)row * nx + ix;
            double gi = r->u[i] + r->gap0[i] - w;
            s->gap[i] = gi;
            if (r->p[i] > 0) {
                compensated_add(&squares, gi * gi);
                ++contact;
            } else if (-gi > penetration)
                penetration = -gi;
        }
        s->row_sums[row] = compensated_total(&squares);
    }
    mpi_ordered_totals(s, 1, &st.sum_squares);
    st.contact = global_count(s, contact);
    st.penetration = global_max(s, penetration);
    return st;
}

static double relative_residual(const gap_stats *st)
{
    double rms = st->contact ? sqrt(st->sum_squares / st->contact) : 0;
    return fmax(rms, st->penetration) / st->approach;
}

static void convolve(pk_run *r, const double *in, double *out)
{
    im_mpi_convolve(r->s, in, out);
    ++r->convolutions;
}

/* Winkler guess p = max(w - g0, 0) / K(0); returns its load delta^2 sum p. */
static double winkler_load(const pk_run *r, double w, int store)
{
    const im_mpi_solver *s = r->s;
    const int nx = s->nx;
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        compensated sum = {0, 0};
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)row * nx + ix;
            double pi = r->gap0[i] < w ? (w - r->gap0[i]) / s->k0 : 0;
            if (store)
                r->p[i] = pi;
            compensated_add(&sum, pi);
        }
        s->row_sums[row] = compensated_total(&sum);
    }
    double total;
    mpi_ordered_totals(s, 1, &total);
    return total * s->delta * s->delta;
}

/* Cold start: the Winkler guess at the imposed approach, or (load control) at the approach where
 * it carries the load, by bisection (at w = K(0) N / delta^2 the first-touch patch alone does). */
static void cold_start(pk_run *r)
{
    double w = r->target;
    if (r->control == IM_CONTROL_LOAD) {
        double lo = 0, hi = r->s->k0 * r->target / (r->s->delta * r->s->delta);
        for (int k = 0; k < 60; ++k) {
            double mid = 0.5 * (lo + hi);
            if (winkler_load(r, mid, 0) < r->target)
                lo = mid;
            else
                hi = mid;
        }
        w = hi;
    }
    winkler_load(r, w, 1);
}

/* Under load control, rescales p (and u, by linearity) so that delta^2 sum p = N. */
static void impose_load(pk_run *r)
{
    long contact;
    const double load = contact_total(r, r->p, NULL, &contact) * r->s->delta * r->s->delta;
    if (!(load > 0))
        return;
    const double scale = r->target / load;
    const size_t n = local_count(r->s);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        r->p[i] *= scale;
        r->u[i] *= scale;
    }
}

/* New search direction t = g + beta t on I_c, 0 elsewhere. */
static void update_direction(const pk_run *r, double beta)
{
    const size_t n = local_count(r->s);
    double *t = r->s->direction;
    const double *g = r->s->gap;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        t[i] = r->p[i] > 0 ? g[i] + beta * t[i] : 0;
}

/* Step length tau = <g, t> / <K t, t> over I_c; under load control K t is centred over I_c:
 * <K t - mean, t> = <K t, t> - mean <1, t>. */
static double step_length(const pk_run *r)
{
    const im_mpi_solver *s = r->s;
    const int nx = s->nx;
    const double *t = s->direction, *g = s->gap, *q = s->response;
    long count = 0;
#pragma omp parallel for schedule(static) reduction(+ : count)
    for (int row = 0; row < s->rows; ++row) {
        compensated sums[4] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}}; /* <g,t>, <q,t>, sum q, sum t */
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)row * nx + ix;
            if (r->p[i] > 0) {
                compensated_add(&sums[0], g[i] * t[i]);
                compensated_add(&sums[1], q[i] * t[i]);
                compensated_add(&sums[2], q[i]);
                compensated_add(&sums[3], t[i]);
                ++count;
            }
        }
        for (int j = 0; j < 4; ++j)
            s->row_sums[(size_t)row * 4 + j] = compensated_total(&sums[j]);
    }
    double totals[4];
    mpi_ordered_totals(s, 4, totals);
    count = global_count(s, count);
    double den = totals[1];
    if (r->control == IM_CONTROL_LOAD && count > 0)
        den -= totals[2] / count * totals[3];
    return totals[0] / den;
}

/* u -= tau K t; p -= tau t on I_c, clipped at zero; patches outside I_c that penetrate (g < 0)
 * join with p = -tau g. Returns how many patches (all ranks) differ from the plain CG step;
 * *joined is set when any joined. */
static long update_pressure(pk_run *r, double tau, int *joined)
{
    const im_mpi_solver *s = r->s;
    const size_t n = local_count(s);
    const double *t = s->direction, *g = s->gap, *q = s->response;
    double *p = r->p, *u = r->u;
    long changes = 0;
    int any_joined = 0;
#pragma omp parallel for schedule(static) reduction(+ : changes) reduction(| : any_joined)
    for (size_t i = 0; i < n; ++i) {
        u[i] -= tau * q[i];
        if (p[i] > 0) {
            double next = p[i] - tau * t[i];
            changes += next < 0;
            p[i] = next < 0 ? 0 : next;
        } else if (g[i] < 0) {
            p[i] = -tau * g[i];
            any_joined = 1;
            ++changes;
        }
    }
    MPI_Allreduce(MPI_IN_PLACE, &any_joined, 1, MPI_INT, MPI_LOR, s->comm);
    *joined = any_joined;
    return global_count(s, changes);
}

static int check_inputs(const im_mpi_solver *s, const double *gap0, enum im_control control, double target,
                        const double *p)
{
    if (control != IM_CONTROL_DISPLACEMENT && control != IM_CONTROL_LOAD)
        return im_fail(IM_EINVAL, "control %d: expected displacement or load", (int)control);
    if (!(isfinite(target) && target >= 0))
        return im_fail(IM_EINVAL, "%s = %g: expected a finite value >= 0",
                       control == IM_CONTROL_LOAD ? "load" : "approach", target);
    const size_t n = local_count(s);
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
        return im_fail(IM_EINVAL, "warm-start pressure at patch (%ld, %ld): expected finite and >= 0",
                       bad[1] % s->nx, bad[1] / s->nx);
    return IM_OK;
}

static void summarise(const pk_run *r, const gap_stats *st, im_solve_result *out)
{
    const im_mpi_solver *s = r->s;
    const size_t n = local_count(s);
    double peak = 0;
#pragma omp parallel for schedule(static) reduction(max : peak)
    for (size_t i = 0; i < n; ++i)
        peak = r->p[i] > peak ? r->p[i] : peak;
    long contact;
    const double sum = contact_total(r, r->p, NULL, &contact);
    out->approach = st->approach;
    out->load = sum * s->delta * s->delta;
    out->contact_patches = contact;
    out->mean_pressure = contact ? sum / contact : 0;
    out->max_pressure = global_max(s, peak);
}

/* The CG loop proper (as src/solver/pk.c, with every changed patch added back by an exact
 * convolution); returns IM_OK, IM_ENOCONV, IM_ENUMERIC or IM_EINTERRUPTED, the same on every rank. */
static int iterate(pk_run *r, im_solve_result *res, gap_stats *last)
{
    const im_solver_options *o = &r->s->options;
    int exact = 1, restart = 1;
    double previous_squares = 1;
    for (;;) {
        gap_stats st = compute_gaps(r);
        *last = st;
        res->residual = relative_residual(&st);
        if (!isfinite(res->residual))
            return im_fail(IM_ENUMERIC, "contact iteration %d: residual is %g", res->iterations, res->residual);
        if (res->residual <= o->tol) {
            if (exact)
                return IM_OK;
            convolve(r, r->p, r->u); /* confirm on the exact displacement */
            exact = 1;
            continue;
        }
        if (res->iterations >= o->max_iterations)
            return im_fail(IM_ENOCONV, "contact solve: residual %.3g > tol %.3g after %d iterations (cap)",
                           res->residual, o->tol, res->iterations);
        const int stopped_by = stop_signal(r->s);
        if (stopped_by) /* p is still a valid (warm) start on every rank */
            return im_fail(IM_EINTERRUPTED, "contact solve: interrupted by signal %d after %d iterations",
                           stopped_by, res->iterations);
        if (st.contact == 0) { /* everything was clipped: start again from the local guess */
            cold_start(r);
            convolve(r, r->p, r->u);
            restart = exact = 1;
            continue;
        }
        ++res->iterations;
        update_direction(r, restart ? 0 : st.sum_squares / previous_squares);
        previous_squares = st.sum_squares;
        convolve(r, r->s->direction, r->s->response);
        double tau = step_length(r);
        if (!(tau > 0) && !restart) { /* the conjugate direction no longer descends */
            restart = 1;
            continue;
        }
        if (isnan(tau) && restart) /* the direction vanishes on I_c: the local (Winkler) step */
            tau = 1.0 / r->s->k0;
        if (!isfinite(tau) || tau <= 0)
            return im_fail(IM_ENUMERIC, "contact iteration %d: step length %g", res->iterations, tau);
        if (update_pressure(r, tau, &restart) > 0) {
            convolve(r, r->p, r->u);
            exact = 1;
        } else
            exact = 0;
        if (r->control == IM_CONTROL_LOAD)
            impose_load(r);
    }
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
    const size_t n = local_count(s);
    pk_run r = {.s = s, .gap0 = gap0, .control = control, .target = target, .p = pressure, .u = displacement};
    gap_stats last = {0};
    if (target == 0) { /* no approach or no load: no contact */
        memset(pressure, 0, sizeof(double) * n);
        memset(displacement, 0, sizeof(double) * n);
    } else {
        long positive = 0;
        for (size_t i = 0; i < n && !positive; ++i)
            positive = pressure[i] > 0;
        if (global_count(s, positive) == 0)
            cold_start(&r);
        convolve(&r, pressure, displacement);
        if (control == IM_CONTROL_LOAD)
            impose_load(&r);
        status = iterate(&r, &res, &last);
    }
    summarise(&r, &last, &res);
    res.convolutions = r.convolutions;
    res.seconds = MPI_Wtime() - start;
    if (result)
        *result = res;
    return status;
}
